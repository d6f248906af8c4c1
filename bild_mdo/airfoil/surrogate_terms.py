"""Evaluation of :class:`~bild_mdo.airfoil.surrogate.TabulatedPolar`: its bicubic spline, the continuation
past the Reynolds table, and the change of variable from ``L = log10 Re`` to ``Re``.

Every function here is complex-step safe in the angle and the Reynolds number
(cells are chosen from real parts), which the tests use to check the
derivatives by complex step.
"""
from __future__ import annotations

import numpy as np

LN10 = np.log(10.0)
# Value, first and second alpha derivative of the cubics a[..., power] at local angles t.
_ALPHA_HORNER = (lambda a, t: a[..., 0] + t * (a[..., 1] + t * (a[..., 2] + t * a[..., 3])),
                 lambda a, t: a[..., 1] + t * (2.0 * a[..., 2] + 3.0 * t * a[..., 3]),
                 lambda a, t: 2.0 * a[..., 2] + 6.0 * t * a[..., 3])
# Value, first and second log-Re derivative of the cubics c[..., power] at local log-Re coordinates u.
_RE_HORNER = (lambda c, u: c[..., 0] + u * (c[..., 1] + u * (c[..., 2] + u * c[..., 3])),
              lambda c, u: c[..., 1] + u * (2.0 * c[..., 2] + 3.0 * u * c[..., 3]),
              lambda c, u: 2.0 * c[..., 2] + 6.0 * u * c[..., 3])
# Points per block in evaluation: keeps the gathered coefficients (32 floats per
# point) in cache-sized pieces.
_CHUNK = 8192
#: Rows of :func:`spline_terms`: ``f, f_a, f_aa, f_L, f_aL, f_aaL, f_LL`` (``_a``: d/dalpha, ``_L``: d/dlog10 Re).
SPLINE_ROWS = ("f", "f_a", "f_aa", "f_L", "f_aL", "f_aaL", "f_LL")
#: Row of :func:`spline_terms` of each quantity :func:`extrapolate_log_reynolds` returns.
EXTRAPOLATED_ROWS = (0, 1, 2, 3, 4, 6)


def spline_terms(coef, grid, log_re_knots, alpha, log_re, rows):
    """Rows ``rows`` (indices into :data:`SPLINE_ROWS`) of the spline's terms of lift and drag.

    Parameters
    ----------
    coef : ndarray, shape (n_alpha_cells * n_re_cells, 32)
        Cell coefficients ``[q, alpha power, log-Re power]`` (``q`` 0 lift, 1 drag), increasing powers.
    grid : tuple
        ``(alpha0, alpha_step, n_alpha_cells, n_re_cells)`` of the uniform, periodic angle grid.
    log_re_knots : ndarray
        ``log10`` of the tabulated Reynolds numbers.
    alpha, log_re : ndarray, shape (n,)
        Angles (rad) and ``log10 Re``, real or complex; ``log_re`` within the table.
    rows : sequence of int

    Returns
    -------
    ndarray, shape (len(rows), 2, n)
    """
    alpha0, step, n_alpha_cells, n_re_cells = grid
    n = alpha.size
    out = np.empty((len(rows), 2, n), dtype=np.result_type(alpha, log_re, float))
    for start in range(0, n, _CHUNK):
        sl = slice(start, min(start + _CHUNK, n))
        # Cell (i, j) and local coordinates t = alpha - alpha_i (wrapped: periodic), u = log10 Re - log_re[j].
        j = np.searchsorted(log_re_knots, np.real(log_re[sl]), side="right") - 1
        np.clip(j, 0, n_re_cells - 1, out=j)
        u = log_re[sl] - log_re_knots[j]
        x = alpha[sl] - alpha0
        x_real = np.real(x)
        if x_real.min() < 0.0 or x_real.max() >= 2.0 * np.pi:
            x_real = np.mod(x_real, 2.0 * np.pi)
            x = x_real + 1j * np.imag(x) if np.iscomplexobj(x) else x_real
        i = np.minimum((x_real / step).astype(np.intp), n_alpha_cells - 1)
        t = x - i * step
        c = np.take(coef, i * n_re_cells + j, axis=0).reshape(-1, 2, 4, 4)
        # c[point, q, alpha power, log-Re power]; Horner in log Re (value, slope, curvature), then in alpha.
        uu, tt = u[:, None, None], t[:, None]
        in_re = {order: _RE_HORNER[order](c, uu) for order in {row // 3 for row in rows}}
        for k, row in enumerate(rows):
            out[k, :, sl] = _ALPHA_HORNER[row % 3](in_re[row // 3], tt).T
    return out


def _change(slope, slope_a, slope_aa, delta, bound):
    """A change ``g`` with ``g(0) = 0`` and ``dg/dL = slope`` at the edge, and its derivatives
    ``g, g_a, g_aa, g_L, g_aL, g_LL``: ``delta * slope`` without ``bound``, ``bound * tanh(delta * slope / bound)``
    with it (:func:`extrapolate_log_reynolds`)."""
    if bound is None:
        zero = np.zeros_like(slope + delta)
        return delta * slope, delta * slope_a, delta * slope_aa, slope + zero, slope_a + zero, zero
    x = delta * slope / bound
    th = np.tanh(x)
    sech2 = 1.0 - th * th
    # x_a = delta slope_a / bound; d/dalpha of sech2 is -2 th sech2 x_a.
    x_a = delta * slope_a / bound
    return (bound * th,
            delta * slope_a * sech2,
            delta * sech2 * (slope_aa - 2.0 * th * slope_a * x_a),
            slope * sech2,
            sech2 * (slope_a - 2.0 * th * slope * x_a),
            -2.0 * slope * slope / bound * th * sech2)


def extrapolate_log_reynolds(edge, delta, bounds=None):
    """Lift and drag at ``d = L - L_e`` past a table edge ``L_e`` (``L = log10 Re``; :class:`TabulatedPolar`).

    Complex-step safe in ``edge`` and ``delta``.

    Parameters
    ----------
    edge : ndarray, shape (6, 2, n)
        ``f, f_a, f_aa, s, s_a, s_aa`` (``_a``: d/dalpha, rad) of lift
        (``[:, 0]``) and drag (``[:, 1]``, ``f > 0``) at the edge.
    delta : ndarray, shape (n,)
        ``L - L_e``.
    bounds : tuple of float, optional
        ``(C, K)``: the bounded continuation (used below the table), with the change of lift and of ``log cd``
        saturating at ``C`` and ``K``::

            cl = f + C tanh(d s / C),    cd = f exp(K tanh(d m / K)),   m = s / f.

        Without: lift linear in ``L`` and ``log cd`` linear in ``L`` (a power law in Re; used above the table).

    Returns
    -------
    tuple of 6 ndarray, shape (2, n)
        ``c, c_a, c_aa, c_L, c_aL, c_LL`` of lift and drag at ``L``.  Without ``bounds``: lift is linear in
        ``L`` (``c_LL = 0``), drag ``f exp(d m)`` (``c_LL = c m**2``).  Both forms have the edge's value and
        slope ``s`` at ``d = 0`` and a zero second derivative of lift and ``log cd`` there.
    """
    lift_bound, drag_bound = (None, None) if bounds is None else bounds
    f, f_a, f_aa, s, s_a, s_aa = edge[:, 0]
    g, g_a, g_aa, g_l, g_al, g_ll = _change(s, s_a, s_aa, delta, lift_bound)
    lift = (f + g, f_a + g_a, f_aa + g_aa, g_l, g_al, g_ll)
    f, f_a, f_aa, s, s_a, s_aa = edge[:, 1]
    # log cd = log f + G, G the change of log cd with slope m = s / f; p_a = d(log f)/dalpha.
    m, p_a = s / f, f_a / f
    m_a = (s_a - m * f_a) / f
    m_aa = (s_aa - m * f_aa) / f - 2.0 * m_a * p_a
    big, big_a, big_aa, big_l, big_al, big_ll = _change(m, m_a, m_aa, delta, drag_bound)
    log_a, log_aa = p_a + big_a, f_aa / f - p_a * p_a + big_aa
    cd = f * np.exp(big)
    drag = (cd, cd * log_a, cd * (log_aa + log_a * log_a), cd * big_l, cd * (big_l * log_a + big_al),
            cd * big_l * big_l + cd * big_ll)
    return tuple(np.stack([x, y]) for x, y in zip(lift, drag))


def per_reynolds(terms, reynolds):
    """Derivatives with respect to ``Re`` from those with respect to ``L = log10 Re`` (``dL/dRe = 1 / (Re ln 10)``).

    Parameters
    ----------
    terms : dict of str to ndarray
        Some of ``f_L, f_aL, f_LL`` (with ``f_L`` whenever ``f_LL`` is there), any shape broadcasting with ``reynolds``.
    reynolds : ndarray

    Returns
    -------
    dict of str to ndarray
        ``f_Re, f_aRe, f_ReRe`` for the terms given::

            f_Re = f_L / (Re ln 10),   f_ReRe = (f_LL / ln 10 - f_L) / (Re**2 ln 10).
    """
    to_re = 1.0 / (reynolds * LN10)
    names = {"f_L": "f_Re", "f_aL": "f_aRe"}
    out = {names[k]: v * to_re for k, v in terms.items() if k in names}
    if "f_LL" in terms:
        out["f_ReRe"] = (terms["f_LL"] / LN10 - terms["f_L"]) * to_re / reynolds
    return out
