"""StationsComp: radial stations (radii and widths) of the blade-element discretisation."""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import add_inputs, declare_size_options

from bild_mdo.utils.sparsity import dist_wrt_node


# Relative round-off allowed where a station or annulus meets the hub or the tip (fractions of R).
_ROUND_OFF = 1e-12


def _fraction_array(value, name, nn, nr):
    arr = np.asarray(value, dtype=float)
    if arr.shape == (nr,):
        arr = np.broadcast_to(arr, (nn, nr))
    if arr.shape != (nn, nr):
        raise ValueError(f"{name} must have shape ({nr},) or ({nn}, {nr}), got {arr.shape}")
    return np.array(arr)


def _first_failure(bad):
    """``(node, station)`` of the first True entry of a (nn, nr) mask."""
    node, station = (int(i) for i in np.argwhere(bad)[0])
    return node, station


def _validate_fractions(rf, wf, centred, where):
    """Check user stations (fractions of R); ValueError naming the option and the first bad entry."""
    checks = [
        (~np.isfinite(rf), "radial_fractions", lambda i: f"r/R = {rf[i]:.6g} is not finite"),
        (~np.isfinite(wf), "width_fractions", lambda i: f"dr/R = {wf[i]:.6g} is not finite"),
        (~(rf > 0.0) | ~(rf <= 1.0 + _ROUND_OFF), "radial_fractions",
         lambda i: f"r/R = {rf[i]:.6g} is not on the blade (0 < r/R <= 1)"),
        (~(wf > 0.0), "width_fractions", lambda i: f"dr/R = {wf[i]:.6g} is not positive"),
    ]
    if centred:
        checks += [
            (~(rf < 1.0), "radial_fractions",
             lambda i: f"r/R = {rf[i]:.6g} is not inside the blade (0 < r/R < 1 for centred annuli)"),
            (~(rf - 0.5 * wf >= -_ROUND_OFF) | ~(rf + 0.5 * wf <= 1.0 + _ROUND_OFF), "width_fractions",
             lambda i: f"the annulus r/R +- dr/(2R) = [{rf[i] - 0.5 * wf[i]:.6g}, {rf[i] + 0.5 * wf[i]:.6g}] "
                       "is not inside [0, 1]"),
        ]
    for bad, name, what in checks:
        if np.any(bad):
            node, station = _first_failure(bad)
            raise ValueError(f"{where}: {name}: {what((node, station))} at node {node}, station {station}")
    total = np.sum(wf, axis=1)
    if np.any(total > 1.0 + _ROUND_OFF):
        node = int(np.flatnonzero(total > 1.0 + _ROUND_OFF)[0])
        raise ValueError(f"{where}: width_fractions: the widths of node {node} add up to "
                         f"{total[node]:.6g} > 1, more than the blade span")


def declare_station_options(options):
    """Declare ``radial_fractions`` and ``width_fractions``, the user stations of :class:`StationsComp` and of
    every group that builds one."""
    options.declare("radial_fractions", default=None, allow_none=True,
                    desc="station radii as fractions of the tip radius, shape (nr,) or (nn, nr); "
                         "None for midpoints of equal annuli")
    options.declare("width_fractions", default=None, allow_none=True,
                    desc="station widths as fractions of the tip radius (with radial_fractions)")


class StationsComp(om.ExplicitComponent):
    """Radii and widths of the radial stations; integrals are ``sum(f * dr)``.

    By default the span from hub to tip is cut into ``num_radial`` equal annuli
    and each station sits at the midpoint of its annulus (midpoint rule):
    ``dr = (R - r_hub)/nr``, ``r_j = r_hub + (j + 1/2) dr``.  Alternatively the
    user gives station radii and widths as fractions of the tip radius
    (options ``radial_fractions`` and ``width_fractions``, shape (nr,) or
    (nn, nr)); then ``r = radial_fractions * R`` and ``dr = width_fractions * R``.

    User stations are validated in ``setup`` (``ValueError`` naming the
    option, node and station): finite, ``0 < r/R <= 1``, ``dr/R > 0`` and
    widths that add up to at most the radius.  A station exactly at the tip,
    and widths that are not centred on their stations, are allowed because
    published quadratures use them (a rectangle rule with the last station at
    the tip, trapezoid or Voronoi-cell widths).  With ``centred_annuli=True``
    every station must be the midpoint of an annulus on the disk:
    ``0 < r/R < 1`` and ``r/R +- dr/(2R)`` inside ``[0, 1]``.  In ``compute``
    every station must lie outside the hub, ``r >= r_hub`` (with
    ``centred_annuli``: its whole annulus, ``r - dr/2 >= r_hub``), to
    round-off; otherwise :class:`openmdao.api.AnalysisError` names the node
    and station.

    Options
    -------
    num_nodes, num_radial : int
        Designs (axis 0) and stations (axis 1).
    radial_fractions : array_like or None
        Station radii r/R; None for equal annuli.
    width_fractions : array_like or None
        Station widths dr/R; required with ``radial_fractions``.
    centred_annuli : bool
        Require every user station to be the midpoint of an annulus that lies
        on the blade (default False).

    Inputs
    ------
    radius[nn] (m), hub_radius[nn] (m)
        Tip and hub radius.

    Outputs
    -------
    radii[nn, nr] (m), dr[nn, nr] (m)
        Station radii and widths.
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_station_options(self.options)
        self.options.declare("centred_annuli", types=bool, default=False,
                             desc="require each user station to be the midpoint of an annulus on the blade "
                                  "(r/R +- dr/(2R) inside [0, 1], r - dr/2 >= hub radius)")

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        add_inputs(self, ("radius", "hub_radius"))
        self.add_output("radii", val=np.tile(np.linspace(0.2, 0.95, nr), (nn, 1)), units="m",
                        desc="radius of each station")
        self.add_output("dr", val=np.full((nn, nr), 0.1), units="m", desc="radial width of each station")
        rf, wf = self.options["radial_fractions"], self.options["width_fractions"]
        if (rf is None) != (wf is None):
            raise ValueError("give both radial_fractions and width_fractions, or neither")
        if rf is None:
            self._user = None
        else:
            self._user = (_fraction_array(rf, "radial_fractions", nn, nr),
                          _fraction_array(wf, "width_fractions", nn, nr))
            _validate_fractions(*self._user, self.options["centred_annuli"], self.msginfo)

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = dist_wrt_node(nn, nr)
        if self._user is None:
            # r_j = r_hub + (j + 1/2)(R - r_hub)/nr, dr = (R - r_hub)/nr: constant partials.
            frac = np.tile((np.arange(nr) + 0.5) / nr, nn)
            self.declare_partials("radii", "radius", rows=rows, cols=cols, val=frac)
            self.declare_partials("radii", "hub_radius", rows=rows, cols=cols, val=1.0 - frac)
            self.declare_partials("dr", "radius", rows=rows, cols=cols, val=np.full(nn * nr, 1.0 / nr))
            self.declare_partials("dr", "hub_radius", rows=rows, cols=cols, val=np.full(nn * nr, -1.0 / nr))
        else:
            rf, wf = self._user
            self.declare_partials("radii", "radius", rows=rows, cols=cols, val=rf.ravel())
            self.declare_partials("dr", "radius", rows=rows, cols=cols, val=wf.ravel())

    def compute(self, inputs, outputs):
        nr = self.options["num_radial"]
        R = inputs["radius"][:, None]
        if self._user is None:
            rh = inputs["hub_radius"][:, None]
            width = (R - rh) / nr
            np.add(rh, (np.arange(nr) + 0.5) * width, out=outputs["radii"])
            outputs["dr"] = width
            # r_j = r_hub + (j + 1/2) width is >= r_hub at every station iff at the first (all fail where
            # width < 0 or is NaN), so the check of station 0 finds the same first failure as the full check.
            check = slice(None) if self.options["centred_annuli"] else slice(0, 1)
        else:
            rf, wf = self._user
            outputs["radii"] = rf * R
            outputs["dr"] = wf * R
            check = slice(None)
        self._check_outside_hub(np.real(outputs["radii"][:, check]), np.real(outputs["dr"][:, check]), np.real(R),
                                np.real(inputs["hub_radius"]))

    def _check_outside_hub(self, radii, dr, R, hub):
        centred = self.options["centred_annuli"]
        inner = radii - 0.5 * dr if centred else radii
        bad = ~(inner >= hub[:, None] - _ROUND_OFF * R)
        if np.any(bad):
            node, station = _first_failure(bad)
            rule = "r - dr/2 >= hub_radius (centred annuli)" if centred else "r >= hub_radius"
            raise om.AnalysisError(
                f"{self.msginfo}: node {node}, station {station} lies inside the hub (r = "
                f"{radii[node, station]:.6g} m, dr = {dr[node, station]:.6g} m, hub_radius = {hub[node]:.6g} m, "
                f"R = {R[node, 0]:.6g} m); the stations need {rule}: move them outboard or reduce the hub radius")
