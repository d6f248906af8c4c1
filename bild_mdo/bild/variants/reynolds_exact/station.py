"""ReynoldsStationComp: every station of the Reynolds-aware exact ideal loading, solved on its own given lambda."""
from bild_mdo.bild.variants.local_point.load_path_model import station_jets
from bild_mdo.bild.variants.local_point.options import station_failures
from bild_mdo.bild.variants.local_point.station import LocalStationComp
from bild_mdo.bild.variants.reynolds_exact.solve import LOADED, solve_stations


class ReynoldsStationComp(LocalStationComp):
    """Inflow angle and section point of every station of the Reynolds-aware exact ideal loading.

    Each annulus minimises ``F (e - lambda t)`` with its section point at the
    least ``cd/cl`` of its own path of fixed load, in the model of the polar's
    load-path table (:mod:`~bild_mdo.bild.variants.local_point.load_path_model`);
    the solve is :func:`~bild_mdo.bild.variants.reynolds_exact.solve.solve_stations`,
    every station of every design at once; the states are ``(phi, x0)`` and the
    residuals ``(R1, R2)``.  An unloaded station (no minimum of ``F (e - lambda
    t)`` below its unloaded value 0) gets ``eta2 = 1``, zero chord (``reynolds =
    load_reynolds = 0``), ``section_branch = -1``, a placeholder section point
    and zero partials; an overloaded station, a failed solve or a load Reynolds
    number past :data:`~bild_mdo.airfoil.load_path_table.REYNOLDS_SPAN` times the
    polar's data is infeasible.  Its partials come from the compiled model
    (:mod:`~bild_mdo.bild.variants.local_point.partials_kernel`), its
    complex-step path from the jets.  Outputs, options and the rest:
    :class:`~bild_mdo.bild.variants.local_point.station.LocalStationComp`.
    """

    METHOD = "Reynolds-aware exact ideal loading"
    FAILURES = {code: value for code, value in station_failures(METHOD).items() if code in (3, 4, 5)}
    LOADED = LOADED
    RESIDUALS = ("r1", "r2")

    def solve(self, flow, start):
        if start is None:
            solution = solve_stations(self.table, flow)
        else:
            solution = solve_stations(self.table, flow, start=start[0][0], first_label=start[1])
        return (solution.phi, solution.x0), solution.label, solution.status, solution.values

    def jets(self, flow, states, label):
        jets = station_jets(self.table, flow, states[0], states[1], label)
        outputs = {"eta2": jets.eta2, "alpha_star": jets.alpha, "cl_star": jets.cl, "cd_star": jets.cd,
                   "reynolds": jets.reynolds, "load_reynolds": jets.load_reynolds}
        return (jets.r1, jets.r2), ("phi", "x0"), outputs
