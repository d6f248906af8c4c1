"""LocalPaperStationComp: the paper's ideal loading with each station's own section point, solved per station."""
from bild_mdo.bild.variants.local_paper.solve import LOADED, paper_jets, solve_stations
from bild_mdo.bild.variants.local_point.load_path_model import section_jets
from bild_mdo.bild.variants.local_point.options import station_failures
from bild_mdo.bild.variants.local_point.station import LocalStationComp


class LocalPaperStationComp(LocalStationComp):
    """``eta2`` and section point of every station of the paper's loading with the local section point.

    The quartic (27) at each station's own ``cd/cl``, that of the least
    ``cd/cl`` along the station's own path of fixed load, self-consistent with
    the load it gives (:mod:`~bild_mdo.bild.variants.local_paper.solve`: one
    state ``x0`` and one residual ``R`` per station, in the model of the
    polar's load-path table).  A station that the quartic leaves unloaded
    (hover) gets ``eta2 = 1`` and zero chord, ``section_branch = -1``, a
    placeholder section point and zero partials.  Its partials come from the
    compiled model (:mod:`~bild_mdo.bild.variants.local_point.partials_kernel`),
    its complex-step path from the jets.  Outputs, options and the rest:
    :class:`~bild_mdo.bild.variants.local_point.station.LocalStationComp`.
    """

    METHOD = "local section point"
    FAILURES = {code: value for code, value in station_failures(METHOD).items() if code in (4, 5)}
    LOADED = LOADED
    RESIDUALS = ("r2",)

    def solve(self, flow, start):
        solution = solve_stations(self.table, flow)
        return (solution.x0,), solution.label, solution.status, solution.values

    def jets(self, flow, states, label):
        jets = paper_jets(self.table, flow, states[0], label)
        alpha, cl, cd, reynolds, load = section_jets(self.table, label, jets.x0, jets.s, jets.ring.tau)
        outputs = {"eta2": jets.eta2, "alpha_star": alpha, "cl_star": cl, "cd_star": cd, "reynolds": reynolds,
                   "load_reynolds": jets.ring.p * load}
        return (jets.r,), ("x0",), outputs
