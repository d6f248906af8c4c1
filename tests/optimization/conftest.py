"""Fixtures of the optimisation tests.

OpenMDAO writes coloring files and other outputs under ``<cwd>/<problem>_out``;
every test here runs inside its own ``tmp_path`` so nothing lands in the repo.

Two cases of the verification sweep (paper Sec. 5.1: 800 rpm, r_ref = 0.5 R,
hub 0.2 R, B = 3, NACA 4412, 30 stations), at R = 1.5 m, sea level,
c_ref = 0.15 m: hover (J = 0) and cruise (J = 1.5), with their BILD designs.
"""
import pytest

from bild_mdo.verification.case_functions import bild_batch
from bild_mdo.verification.cases import SweepSpec

# levels=3 case ids: (J, R, altitude, c_ref) = (0, 1.5 m, 0 m, 0.15 m) and (1.5, 1.5 m, 0 m, 0.15 m).
CASE_IDS = {"hover": 19, "cruise": 46}


@pytest.fixture(autouse=True)
def _run_in_tmp_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)


@pytest.fixture(scope="session")
def designs():
    """``{'hover' | 'cruise': (Case, BILD result dict)}``."""
    spec = SweepSpec(levels=3)
    cases = spec.cases(CASE_IDS.values())
    return {kind: (case, result) for kind, case, result in zip(CASE_IDS, cases, bild_batch(cases))}


def case_args(case, bild):
    """Positional case arguments of the optimisation functions, with BILD's thrust as T*."""
    i = case.inputs
    return (i["v_axial"], i["rpm"], i["radius"], i["hub_radius"], bild["thrust"], i["altitude"])
