"""The one partial-derivative check for every bild-mdo component (the OpenAeroStruct ``run_test`` idea).

Used by the test suite and available to users who write their own components
on top of bild-mdo: set inputs, run, compare every declared partial against
complex step and assert with tight tolerances.
"""
import warnings

import openmdao.api as om
import numpy as np
from openmdao.utils.assert_utils import assert_check_partials
from openmdao.utils.om_warnings import DerivativesWarning


def _problem(system, values):
    prob = om.Problem(reports=False)
    prob.model.add_subsystem("system", system, promotes=["*"])
    prob.setup(force_alloc_complex=True)
    names = {meta["prom_name"] for meta in prob.model.get_io_metadata(iotypes="input").values()}
    for name in names & set(values):
        prob.set_val(name, values[name])
    prob.run_model()
    return prob


def check_component_partials(component, values=None, atol=1e-8, rtol=1e-8):
    """Run ``component`` alone with ``values`` set on its inputs and assert its partials against complex step.

    Parameters
    ----------
    component : openmdao.api.Component
        A fresh component instance (use ``num_nodes != num_radial``, both > 1, so a
        transposed sparsity pattern fails).
    values : dict, optional
        Promoted input name -> value; inputs not named keep their defaults.
    atol, rtol : float
        Tolerances of :func:`openmdao.utils.assert_utils.assert_check_partials`.

    Returns
    -------
    openmdao.api.Problem
        The problem, after the check, for further assertions.
    """
    prob = _problem(component, values or {})
    with warnings.catch_warnings():
        # A partial that is exactly zero at the chosen point (for example d/dV_x in hover) stays declared
        # because it is nonzero elsewhere; OpenMDAO's warning about it is not a failure.
        warnings.filterwarnings("ignore", message="(?s).*has zero derivatives", category=DerivativesWarning)
        data = prob.check_partials(method="cs", out_stream=None)
    assert_check_partials(data, atol=atol, rtol=rtol)
    return prob


def check_group_totals(make_group, of, wrt, values=None, atol=1e-8, rtol=1e-8, modes=("fwd", "rev")):
    """Assert the total derivatives of a group against complex step, in each derivative mode.

    Parameters
    ----------
    make_group : callable
        ``make_group()`` returns a fresh group (a new instance per mode).
    of, wrt : list of str
        Promoted output and input names.
    values : dict, optional
        Promoted input name -> value.
    atol, rtol : float
        Tolerances of :func:`openmdao.utils.assert_utils.assert_check_totals`.
    modes : tuple of str
        Derivative modes to check.
    """
    for mode in modes:
        prob = om.Problem(reports=False)
        prob.model.add_subsystem("system", make_group(), promotes=["*"])
        prob.setup(force_alloc_complex=True, mode=mode)
        names = {meta["prom_name"] for meta in prob.model.get_io_metadata(iotypes="input").values()}
        for name in names & set(values or {}):
            prob.set_val(name, values[name])
        prob.run_model()
        data = prob.check_totals(of=of, wrt=wrt, method="cs", out_stream=None)
        assert_totals_match(data, atol=atol, rtol=rtol)


def assert_totals_match(totals_data, atol=1e-8, rtol=1e-8):
    """Assert every (of, wrt) pair of ``check_totals`` data: analytic (fwd or rev) against complex step.

    OpenMDAO 3.45's ``assert_check_totals`` stops at the first pair it reads, so it is not used here.

    Parameters
    ----------
    totals_data : dict
        The return value of :meth:`openmdao.api.Problem.check_totals`.
    atol, rtol : float
        Elementwise tolerances, ``|J - J_cs| <= atol + rtol |J_cs|``.
    """
    failures = []
    for (of, wrt), entry in totals_data.items():
        reference = entry["J_fd"]
        for name in ("J_fwd", "J_rev"):
            jac = entry.get(name)
            if jac is not None and not np.allclose(jac, reference, atol=atol, rtol=rtol):
                failures.append(f"d{of}/d{wrt} ({name[2:]}): max |diff| {np.max(np.abs(jac - reference)):.3g}, "
                                f"max |cs| {np.max(np.abs(reference)):.3g}")
    assert not failures, f"{len(failures)} total derivative(s) differ from complex step:\n" + "\n".join(failures[:20])
