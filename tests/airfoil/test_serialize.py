"""Polars written as JSON-ready dictionaries and read back give the same numbers bit for bit."""
import json

import numpy as np
import pytest

from bild_mdo.airfoil import (AnalyticPolar, CompressiblePolar, SpanwisePolar, TabulatedPolar, naca4412,
                              tabulated_polar)
from bild_mdo.airfoil.serialize import polar_from_dict, polar_to_dict
from bild_mdo.airfoil.sources.readers import load_builtin_polars


def _round_trip(polar):
    return polar_from_dict(json.loads(json.dumps(polar_to_dict(polar))))


def _same(a, b, **kw):
    alpha = np.radians(np.linspace(-25, 30, 23))
    for got, want in zip(a.evaluate(alpha, 6e5, **kw), b.evaluate(alpha, 6e5, **kw)):
        np.testing.assert_array_equal(got, want)


def test_builtin_polar_is_written_by_name():
    assert polar_to_dict(naca4412()) == {"type": "builtin", "name": "naca4412"}
    assert _round_trip(naca4412()) is naca4412()


def test_analytic_tables_compressible_and_spanwise_round_trip():
    analytic = AnalyticPolar(cl0=0.3, reynolds_exponent=0.2)
    _same(_round_trip(analytic), analytic)
    tables = TabulatedPolar.cached([p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)],
                                   name="pair")
    back = _round_trip(tables)
    assert back.name == "pair" and back.settings == tables.settings
    _same(back, tables)
    compressible = CompressiblePolar(analytic, "karman-tsien")
    _same(_round_trip(compressible), compressible, mach=0.5)
    spanwise = SpanwisePolar([analytic, tables], [0.25, 0.9])
    _same(_round_trip(spanwise), spanwise, radial_fraction=0.6)


def test_fresh_surrogate_keeps_its_tables():
    polars = [p for p in load_builtin_polars("naca4412") if p.reynolds in (5e5, 1e6)]
    assert tabulated_polar(polars).data == tuple(polars)


def test_unwritable_and_malformed():
    class Custom(AnalyticPolar.__mro__[1]):
        def _evaluate_real(self, alpha, reynolds):
            raise NotImplementedError

    with pytest.raises(ValueError, match="cannot be written to a file"):
        polar_to_dict(Custom())
    with pytest.raises(ValueError, match="unknown airfoil description type 'foil'"):
        polar_from_dict({"type": "foil"})
    with pytest.raises(ValueError, match="incomplete or malformed"):
        polar_from_dict({"type": "tables"})
