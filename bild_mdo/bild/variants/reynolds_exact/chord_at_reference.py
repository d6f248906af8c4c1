"""ChordAtReferenceComp: the blade's chord at ``r_ref`` and its Reynolds number, where lambda is the state.

With ``BILDGroup(thrust_target=True)`` the Reynolds-aware exact loading solves
lambda for the thrust (:mod:`bild_mdo.bild.thrust_target`), not the reference
chord: there is no reference station to give lambda, and the reference chord
becomes what the design has at ``r_ref``, the back-computed chord (before the
root-chord correction) interpolated linearly between the two stations around
``r_ref`` (the end intervals extended where ``r_ref`` lies outside the
stations).  Where the reference state is the ideal load of a station at
``r_ref`` (the design of that ``c_ref`` with ``thrust_target=False``), this
is that ``c_ref`` to the interpolation error of the stations.  The reference
Reynolds number follows it, ``Re_ref = rho W0 c_ref / mu`` with ``W0 =
sqrt(V_x**2 + V_theta_ref**2)`` (the BEM convention of the other variants).

Inputs: ``chord_raw[nn, nr]`` (m), ``radii[nn, nr]`` (m), ``ref_radius[nn]`` (m),
``v_axial[nn]`` (m/s), ``v_theta_ref[nn]`` (m/s), ``rho[nn]`` (kg/m**3), ``mu[nn]`` (Pa*s).
Outputs: ``ref_chord[nn]`` (m), ``reynolds_ref[nn]``.  Analytic partials.
"""
import numpy as np
import openmdao.api as om

from bild_mdo.bild.variants.local_point.gap import reynolds_partials
from bild_mdo.utils.options import add_inputs, declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

_NODE_INPUTS = ("ref_radius", "v_axial", "v_theta_ref", "rho", "mu")


class ChordAtReferenceComp(om.ExplicitComponent):
    """The chord at ``r_ref`` of the stations' back-computed chord, and its Reynolds number (module docstring)."""

    def initialize(self):
        declare_size_options(self.options)

    def setup(self):
        nn = self.options["num_nodes"]
        add_inputs(self, ("chord_raw", "radii") + _NODE_INPUTS)
        self.add_output("ref_chord", val=np.full(nn, 0.1), units="m",
                        desc="chord of the design at the reference station r_ref (stations interpolated)")
        self.add_output("reynolds_ref", val=np.full(nn, 3e5), units=None,
                        desc="chord Reynolds number at the reference station (speed without induction)")

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_dist(nn, nr)
        for out in ("ref_chord", "reynolds_ref"):
            self.declare_partials(out, ["chord_raw", "radii"], rows=rows, cols=cols)
        rows, cols = node_wrt_node(nn)
        self.declare_partials("ref_chord", "ref_radius", rows=rows, cols=cols)
        self.declare_partials("reynolds_ref", list(_NODE_INPUTS), rows=rows, cols=cols)

    def _interval(self, inputs):
        """Per design: the index ``k`` of the interval ``[r_k, r_k+1]`` used, its ends and chords."""
        radii, r_ref = inputs["radii"], inputs["ref_radius"]
        nr = radii.shape[1]
        k = np.sum(np.real(radii[:, 1:-1]) <= np.real(r_ref)[:, None], axis=1) if nr > 2 else np.zeros(len(r_ref), int)
        rows = np.arange(len(r_ref))
        a, b = radii[rows, k], radii[rows, k + 1]
        ca, cb = inputs["chord_raw"][rows, k], inputs["chord_raw"][rows, k + 1]
        return rows, k, a, b, ca, cb

    def _reynolds(self, inputs, chord):
        """``Re_ref`` at ``chord`` and its partials (:func:`~bild_mdo.bild.variants.local_point.gap.reynolds_partials`)."""
        return reynolds_partials(inputs["v_axial"], inputs["v_theta_ref"], chord, inputs["rho"], inputs["mu"])

    def compute(self, inputs, outputs):
        _, _, a, b, ca, cb = self._interval(inputs)
        weight = (inputs["ref_radius"] - a) / (b - a)
        chord = ca + weight * (cb - ca)
        outputs["ref_chord"] = chord
        outputs["reynolds_ref"] = self._reynolds(inputs, chord)[0]

    def compute_partials(self, inputs, partials):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, k, a, b, ca, cb = self._interval(inputs)
        q = inputs["ref_radius"]
        span = b - a
        weight = (q - a) / span
        rise = cb - ca
        chord = ca + weight * rise
        _, d_re = self._reynolds(inputs, chord)
        factor = d_re["chord"]
        d_chord = np.zeros((nn, nr), dtype=np.result_type(weight, float))
        d_radii = np.zeros_like(d_chord)
        d_chord[rows, k], d_chord[rows, k + 1] = 1.0 - weight, weight
        d_radii[rows, k] = rise * (q - b) / span ** 2
        d_radii[rows, k + 1] = -rise * (q - a) / span ** 2
        partials["ref_chord", "chord_raw"] = d_chord.ravel()
        partials["ref_chord", "radii"] = d_radii.ravel()
        partials["ref_chord", "ref_radius"] = rise / span
        partials["reynolds_ref", "chord_raw"] = (factor[:, None] * d_chord).ravel()
        partials["reynolds_ref", "radii"] = (factor[:, None] * d_radii).ravel()
        partials["reynolds_ref", "ref_radius"] = factor * rise / span
        for name, key in (("v_axial", "v_axial"), ("v_theta_ref", "v_theta"), ("rho", "rho"), ("mu", "mu")):
            partials["reynolds_ref", name] = d_re[key]
