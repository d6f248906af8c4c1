"""LocalPaperVariant: the paper's loading (Eq. (22), (27)) with each station's own section point."""
from bild_mdo.bild.variants.local_paper.station import LocalPaperStationComp
from bild_mdo.bild.variants.local_point.variant import LocalPointVariant
from bild_mdo.bild.variants.paper.variant import add_paper_loading


class LocalPaperVariant(LocalPointVariant):
    """lambda of Eq. (22) at the reference station's own section point; every station's eta2 from the quartic
    at its own ``cd/cl``, self-consistent with its load
    (:class:`~bild_mdo.bild.variants.local_paper.station.LocalPaperStationComp`)."""

    ideal_loading = "paper"
    station_comp = LocalPaperStationComp

    def add_loading(self):
        add_paper_loading(self.wiring)
