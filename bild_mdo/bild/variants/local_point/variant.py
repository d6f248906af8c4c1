"""LocalPointVariant: each station at the least cd/cl of its own path of fixed load (both local members)."""
from bild_mdo.bild.reference_induced_velocity import ReferenceInducedVelocityComp
from bild_mdo.bild.variants.reference_point.reference_station import REFERENCE_INPUTS
from bild_mdo.bild.variants.base import BILDVariant
from bild_mdo.bild.variants.local_point.reference import LocalReferenceComp

_STATION_INPUTS = ["ideal_loading_constant", "v_axial", "v_theta", "radii", "radius", "hub_radius", "rho", "mu"]
_STATION_OUTPUTS = ["eta2", "alpha_star", "cl_star", "cd_star", "reynolds", "load_reynolds", "section_branch"]


class LocalPointVariant(BILDVariant):
    """The members with the local section point: the reference station at the minimum of ``cd/cl`` along its
    own path with the chord ``c_ref`` (:class:`~bild_mdo.bild.variants.local_point.reference.LocalReferenceComp`),
    and every station at the minimum of its own path, in the model of the polar's load-path table
    (:mod:`bild_mdo.airfoil.load_path_table`)."""

    section_point = "local"
    #: The station component class (a :class:`~bild_mdo.bild.variants.local_point.station.LocalStationComp`).
    station_comp = None

    @property
    def per_station(self):
        return True

    def check_polar(self):
        polar = self.wiring.polar
        if polar.varies_along_span or polar.varies_with_mach:
            raise ValueError("section_point='local' needs a polar that varies with the Reynolds number only; "
                             f"{polar.name!r} varies with Mach number or along the span: use section_point='reference'")

    def _options(self):
        w = self.wiring
        return dict(**w.loss, chord_form=w.chord_form, polar=w.polar, **w.checked)

    def add_reference(self):
        w, g = self.wiring, self.wiring.group
        outputs = ["phi_ref", "alpha_star_ref", "cl_star_ref", "cd_star_ref", "reynolds_ref", "load_reynolds_ref",
                   "section_branch_ref"]
        if self.ideal_loading == "exact":
            outputs += ["ideal_loading_constant", "station_branch_ref"]
        g.add_subsystem("reference_point", LocalReferenceComp(**w.node, **self._options(),
                                                              ideal_loading=self.ideal_loading),
                        promotes_inputs=["v_axial", "v_theta_ref", "ref_radius", "ref_chord", "radius", "hub_radius",
                                         "rho", "mu"],
                        promotes_outputs=outputs)
        reference_in = [(name, f"{name}_ref") if name in ("cl_star", "cd_star") else name
                        for name in REFERENCE_INPUTS]
        g.add_subsystem("reference_induced_velocity", ReferenceInducedVelocityComp(**w.node, **w.loss),
                        promotes_inputs=["phi_ref"] + reference_in, promotes_outputs=["u_axial_ref", "u_theta_ref"])

    def add_stations(self):
        w = self.wiring
        w.group.add_subsystem("station_loading", self.station_comp(**w.size, **self._options()),
                              promotes_inputs=_STATION_INPUTS, promotes_outputs=_STATION_OUTPUTS)
