"""ReynoldsExactVariant: the Reynolds-aware exact ideal loading (exact loading with the local section point)."""
from bild_mdo.bild.variants.local_point.variant import LocalPointVariant
from bild_mdo.bild.variants.reynolds_exact.station import ReynoldsStationComp


class ReynoldsExactVariant(LocalPointVariant):
    """Each annulus minimises ``F (e - lambda t)`` with its section point following its own load
    (:class:`~bild_mdo.bild.variants.reynolds_exact.station.ReynoldsStationComp`); lambda is that of the reference
    annulus, given by the reference component."""

    ideal_loading = "exact"
    station_comp = ReynoldsStationComp

    def add_loading(self):
        """lambda comes with the reference state (``LocalReferenceComp(ideal_loading='exact')``)."""
