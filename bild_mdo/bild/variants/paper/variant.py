"""PaperVariant: BILD as published (Algorithm 1: Eq. (22), the quartic (27), the reference airfoil point)."""
from bild_mdo.bild.variants.paper.eta2 import Eta2Comp
from bild_mdo.bild.variants.paper.ideal_loading import IdealLoadingComp
from bild_mdo.bild.variants.reference_point.variant import ReferencePointVariant


def add_paper_loading(wiring):
    """lambda of Eq. (22) from the reference station's induced velocities."""
    wiring.group.add_subsystem("ideal_loading", IdealLoadingComp(**wiring.node, **wiring.checked),
                               promotes_inputs=["u_axial_ref", "u_theta_ref", "v_axial", "v_theta_ref"],
                               promotes_outputs=["ideal_loading_constant"])


class PaperVariant(ReferencePointVariant):
    """The paper's method: lambda of Eq. (22) and every station's eta2 from the quartic (27)."""

    ideal_loading = "paper"

    def add_loading(self):
        add_paper_loading(self.wiring)

    def add_stations(self):
        w = self.wiring
        w.group.add_subsystem("eta2", Eta2Comp(**w.size, **w.checked, varies_along_span=self.per_station),
                              promotes_inputs=["v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star"],
                              promotes_outputs=["eta2"])
