"""ExactVariant: the exact ideal loading (Prandtl's factor differentiated) at the reference airfoil point."""
from bild_mdo.bild.variants.exact.exact_eta2 import ExactEta2Comp
from bild_mdo.bild.variants.exact.exact_ideal_loading import ExactIdealLoadingComp
from bild_mdo.bild.variants.reference_point.variant import ReferencePointVariant


class ExactVariant(ReferencePointVariant):
    """Every annulus makes ``E - lambda T`` stationary with ``F`` differentiated
    (:mod:`~bild_mdo.bild.annulus_stationarity`); lambda from the reference station."""

    ideal_loading = "exact"

    def add_loading(self):
        w = self.wiring
        w.group.add_subsystem("ideal_loading", ExactIdealLoadingComp(**w.node, **w.loss, **w.checked),
                              promotes_inputs=["phi_ref"] + [name for name in self.reference_inputs
                                                             if name != "ref_chord"],
                              promotes_outputs=["ideal_loading_constant"])

    def add_stations(self):
        w = self.wiring
        w.group.add_subsystem("eta2", ExactEta2Comp(**w.size, **w.loss, **w.checked,
                                                    varies_along_span=self.per_station),
                              promotes_inputs=["v_axial", "v_theta", "ideal_loading_constant", "cl_star", "cd_star",
                                               "radii", "radius", "hub_radius"],
                              promotes_outputs=["eta2"])
