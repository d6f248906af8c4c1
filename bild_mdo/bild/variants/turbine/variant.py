"""TurbineVariant: the member for energy extraction (the loading of :mod:`~bild_mdo.bild.variants.turbine.kernel`)."""
from bild_mdo.bild.variants.base import BILDVariant
from bild_mdo.bild.variants.reference_point.reference_airfoil import ReferenceAirfoilComp
from bild_mdo.bild.variants.turbine.thrust_limit import ThrustLimitComp
from bild_mdo.bild.variants.turbine.turbine_chord import TurbineChordComp
from bild_mdo.bild.variants.turbine.turbine_inflow import TurbineInflowComp
from bild_mdo.bild.variants.turbine.turbine_loads import TurbineLoadsComp
from bild_mdo.bild.variants.turbine.turbine_reference import TurbineReferenceStationComp

#: How the member of the turbine family is chosen (TurbineBILDGroup's option ``design_for``).
DESIGN_FOR = ("multiplier", "ref_chord", "thrust")
_MU = "power_thrust_multiplier"
_REFERENCE = ["v_axial", "v_theta_ref", "ref_radius", "radius", "hub_radius", "cl_star", "cd_star"]


class TurbineVariant(BILDVariant):
    """The turbine member: the reference point of the paper (Assumption 2), the turbine loading and chord.

    ``add_reference``: the maximum-L/D point at the reference Reynolds number, with the chord ``ref_chord``
    (``design_for='ref_chord'``) or ``section_chord`` (otherwise: the chord the Reynolds number is taken at).
    ``add_loading``: the multiplier ``mu`` -- an input (``'multiplier'``; 0 is maximum power), from the
    reference chord (``'ref_chord'``) or from the thrust (``'thrust'``); the reference station gives the other
    parameter.  ``add_stations``: every station's ``phi``, then its loads and its chord and twist.  The
    propeller chain's induced velocities and loads do not apply (other signs and the windmill state);
    the stations, geometry and rotational speed are shared.
    """

    ideal_loading = "turbine"
    section_point = "reference"

    @property
    def per_station(self):
        return False

    @property
    def design_for(self):
        return self.wiring.group.options["design_for"]

    def check_polar(self):
        if self.wiring.polar.varies_along_span:
            raise ValueError("the turbine BILD takes one airfoil along the span (a polar that does not vary "
                             "along the span)")

    def add_reference(self):
        w = self.wiring
        chord = "ref_chord" if self.design_for == "ref_chord" else ("ref_chord", "section_chord")
        w.group.add_subsystem("reference_airfoil", ReferenceAirfoilComp(**w.size, polar=w.polar),
                              promotes_inputs=["v_axial", "v_theta_ref", chord, "rho", "mu", "speed_of_sound"],
                              promotes_outputs=["reynolds_ref", "mach_ref", "alpha_star", "cl_star", "cd_star"])

    def add_loading(self):
        w, g = self.wiring, self.wiring.group
        if self.design_for == "thrust":
            g.add_subsystem("thrust_limit", ThrustLimitComp(**w.size, **w.loss),
                            promotes_inputs=["thrust_target", "v_axial", "radius", "hub_radius", "rho", "cl_star",
                                             "cd_star", "v_theta", "radii", "dr"], promotes_outputs=[_MU])
        given = "ref_chord" if self.design_for == "ref_chord" else "multiplier"
        ins, outs = (["ref_chord"], [_MU]) if given == "ref_chord" else ([_MU], ["ref_chord"])
        g.add_subsystem("reference_station", TurbineReferenceStationComp(**w.node, **w.loss, given=given),
                        promotes_inputs=_REFERENCE + ins, promotes_outputs=["phi_ref"] + outs)

    def add_stations(self):
        w, g = self.wiring, self.wiring.group
        g.add_subsystem("inflow", TurbineInflowComp(**w.size, **w.loss),
                        promotes_inputs=[_MU, "v_axial", "radius", "hub_radius", "cd_star", "cl_star", "v_theta",
                                         "radii"], promotes_outputs=["phi"])
        g.add_subsystem("loads", TurbineLoadsComp(**w.size, **w.loss),
                        promotes_inputs=["phi", "v_theta", "radii", "v_axial", "radius", "hub_radius", "rho",
                                         "cl_star", "cd_star"],
                        promotes_outputs=["axial_induction", "tangential_induction", "u_axial", "inflow_speed",
                                          "loss_factor", "dthrust_dr", "dtorque_dr"])
        g.add_subsystem("chord", TurbineChordComp(**w.size, num_blades=w.loss["num_blades"]),
                        promotes_inputs=["dthrust_dr", "phi", "inflow_speed", "rho", "alpha_star", "cl_star",
                                         "cd_star"],
                        promotes_outputs=["chord", "twist", "lift_coefficient", "drag_coefficient"])

    def add(self):
        """The reference point, the multiplier and the stations (no propeller station chain)."""
        self.check_polar()
        self.add_reference()
        self.add_loading()
        self.add_stations()
