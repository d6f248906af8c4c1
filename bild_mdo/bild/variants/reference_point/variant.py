"""ReferencePointVariant: the paper's section point, the maximum-L/D point at the reference Reynolds number."""
from bild_mdo.bild.variants.reference_point.reference_airfoil import ReferenceAirfoilComp
from bild_mdo.bild.reference_induced_velocity import ReferenceInducedVelocityComp
from bild_mdo.bild.variants.reference_point.reference_station import REFERENCE_INPUTS, ReferenceStationComp
from bild_mdo.bild.variants.base import BILDVariant


class ReferencePointVariant(BILDVariant):
    """The members whose stations run at the reference station's airfoil point (paper Assumption 2).

    ``reference_airfoil`` gives the maximum-L/D point at ``Re_ref`` (and ``M_ref``);
    ``reference_station`` the one BEM solve with ``c_ref`` (Algorithm 1, step 2) and
    ``reference_induced_velocity`` its induced velocities.  With a polar that varies
    along the span every station gets its own airfoil's point (``[nn, nr]``) and the
    reference station reads the point of the airfoil at ``r_ref`` (``*_ref``).
    """

    section_point = "reference"

    @property
    def per_station(self):
        return bool(self.wiring.polar.varies_along_span)

    @property
    def reference_inputs(self):
        """The reference station's inputs, with the point of ``r_ref`` for a spanwise polar."""
        return [(name, f"{name}_ref") if self.per_station and name in ("cl_star", "cd_star") else name
                for name in REFERENCE_INPUTS]

    def add_reference(self):
        w, g = self.wiring, self.wiring.group
        point = ["alpha_star", "cl_star", "cd_star"]
        airfoil_in = ["v_axial", "v_theta_ref", "ref_chord", "rho", "mu", "speed_of_sound"]
        if self.per_station:
            airfoil_in += ["radii", "radius", "ref_radius_ratio"]
            point += [f"{name}_ref" for name in point]
        g.add_subsystem("reference_airfoil", ReferenceAirfoilComp(**w.size, polar=w.polar),
                        promotes_inputs=airfoil_in, promotes_outputs=["reynolds_ref", "mach_ref"] + point)
        g.add_subsystem("reference_station", ReferenceStationComp(**w.node, **w.loss),
                        promotes_inputs=self.reference_inputs, promotes_outputs=["phi_ref"])
        g.add_subsystem("reference_induced_velocity", ReferenceInducedVelocityComp(**w.node, **w.loss),
                        promotes_inputs=["phi_ref"] + self.reference_inputs,
                        promotes_outputs=["u_axial_ref", "u_theta_ref"])
