"""PolarData, the one polar type every source returns, and the row checks the file readers share."""
from pathlib import Path

import numpy as np
import pytest

from bild_mdo.airfoil.sources.polar_data import MIN_POINTS, PolarData, PolarFileError, polar_from_rows


def _rows(n=12):
    alpha = np.arange(n, dtype=float) - 2.0
    return alpha, 0.47 + 0.11 * alpha, 0.006 + 1e-4 * alpha ** 2


def test_polardata_validates_and_is_read_only():
    alpha, cl, cd = _rows()
    data = PolarData(reynolds=1e5, mach=0.0, alpha_deg=alpha, cl=cl, cd=cd, source="t")
    with pytest.raises(ValueError):
        data.cl[0] = 1.0
    np.testing.assert_allclose(data.lift_to_drag, cl / cd)
    with pytest.raises(ValueError, match="strictly increasing"):
        PolarData(reynolds=1e5, mach=0.0, alpha_deg=alpha[::-1], cl=cl, cd=cd, source="t")
    with pytest.raises(ValueError, match="cd must be > 0"):
        PolarData(reynolds=1e5, mach=0.0, alpha_deg=alpha, cl=cl, cd=-cd, source="t")
    with pytest.raises(ValueError, match="Reynolds number must be finite and > 0"):
        PolarData(reynolds=0.0, mach=0.0, alpha_deg=alpha, cl=cl, cd=cd, source="t")
    with pytest.raises(ValueError, match="lengths differ"):
        PolarData(reynolds=1e5, mach=0.0, alpha_deg=alpha, cl=cl[:-1], cd=cd, source="t")


def test_polar_from_rows_builds_the_polar():
    alpha, cl, cd = _rows()
    rows = [(k + 3, a, c, d) for k, (a, c, d) in enumerate(zip(alpha, cl, cd))]
    data = polar_from_rows(Path("p.txt"), rows, 2e5, 0.1, 9.0, "p.txt")
    assert (data.reynolds, data.mach, data.ncrit, data.source) == (2e5, 0.1, 9.0, "p.txt")
    np.testing.assert_array_equal(data.cd, cd)


def test_polar_from_rows_names_the_bad_line():
    alpha, cl, cd = _rows()
    rows = [(k + 3, a, c, d) for k, (a, c, d) in enumerate(zip(alpha, cl, cd))]
    rows[4] = (7, rows[4][1], rows[4][2], 0.0)
    with pytest.raises(PolarFileError, match=r"^p.txt:7: cd = 0.0 must be > 0$"):
        polar_from_rows(Path("p.txt"), rows, 2e5, 0.0, None, "p.txt")
    with pytest.raises(PolarFileError, match=rf"only {MIN_POINTS - 1} data rows \(lines 3-11\)"):
        polar_from_rows(Path("p.txt"), rows[:MIN_POINTS - 1], 2e5, 0.0, None, "p.txt")
