"""Off-design performance curves and turbine power curves (matplotlib, extra ``bild-mdo[plot]``).

:func:`plot_performance_curves` draws thrust, power, efficiency (or figure of
merit) and the coefficients of an
:class:`~bild_mdo.results.off_design.OffDesignResult` against J or rpm, as in
the paper's Fig. 9; :func:`plot_power_curve` the power curve of a turbine
(:class:`~bild_mdo.results.power_curve.PowerCurve`).  With a ``path`` the figure is
written as PNG (see :mod:`bild_mdo.plots.figure`).
"""
from __future__ import annotations

import numpy as np

from bild_mdo.plots.figure import finish, new_figure


def plot_performance_curves(off_design_result, path=None):
    """Thrust, power, efficiency (or FM) and coefficients of an off-design sweep.

    Efficiency is drawn only where it means something (positive thrust and
    power, forward speed); the maximum-efficiency point (star) and, when the
    sweep contains it, the design point (circle) are marked, as in the
    paper's Fig. 9.  An rpm sweep in hover shows the figure of merit instead.

    Parameters
    ----------
    off_design_result : OffDesignResult
    path : str or path, optional
        PNG file to write.

    Returns
    -------
    matplotlib.figure.Figure
    """
    res = off_design_result
    if res.sweep == "advance_ratio":
        x, xlabel = res.advance_ratio, "advance ratio J = V/(nD) [-]"
    elif res.sweep == "v_axial":
        x, xlabel = res.v_axial, "airspeed V [m/s]"
    else:
        x, xlabel = res.rpm, "rotor speed [rpm]"
    fig = new_figure(path, figsize=(9.0, 6.6))
    (ax_t, ax_p), (ax_e, ax_c) = fig.subplots(2, 2, sharex=True)
    ax_t.plot(x, res.thrust, color="tab:blue", marker="o", ms=3)
    ax_t.axhline(0.0, color="0.5", lw=0.7)
    ax_t.set_ylabel("thrust T [N]")
    ax_t.set_title("Thrust")
    ax_p.plot(x, res.power / 1e3, color="tab:red", marker="o", ms=3)
    ax_p.axhline(0.0, color="0.5", lw=0.7)
    ax_p.set_ylabel("shaft power P [kW]")
    ax_p.set_title("Power")

    hover = np.all(res.v_axial == 0.0)
    if hover:
        ax_e.plot(x, res.figure_of_merit, color="tab:green", marker="o", ms=3, label="figure of merit")
        design = _design_index(res)
        if design is not None:
            ax_e.plot(x[design], res.figure_of_merit[design], marker="o", ms=9, ls="none", mfc="none",
                      mec="k", mew=1.5, label="design point")
        ax_e.set_ylabel("figure of merit FM [-]")
        ax_e.set_title("Figure of merit (hover)")
    else:
        useful = (res.thrust > 0.0) & (res.power > 0.0) & (res.v_axial > 0.0)
        eta = np.where(useful, res.efficiency, np.nan)
        ax_e.plot(x, eta, color="tab:green", marker="o", ms=3, label=r"efficiency $\eta$")
        best = res.max_efficiency_index
        if best is not None:
            ax_e.plot(x[best], res.efficiency[best], marker="*", ms=14, ls="none", color="tab:orange",
                      label=f"max. efficiency {res.efficiency[best]:.3f}")
        design = _design_index(res)
        if design is not None and useful[design]:
            ax_e.plot(x[design], res.efficiency[design], marker="o", ms=9, ls="none", mfc="none",
                      mec="k", mew=1.5, label="design point")
        ax_e.set_ylabel(r"efficiency $\eta$ [-]")
        ax_e.set_title(r"Propulsive efficiency $\eta = VT/P$ (T > 0, P > 0)")
        ax_e.set_ylim(0.0, 1.05)
    ax_c.plot(x, res.thrust_coefficient, color="tab:blue", marker="o", ms=3, label=r"$C_T$")
    ax_c.plot(x, res.power_coefficient, color="tab:red", marker="s", ms=3, label=r"$C_P$")
    ax_c.axhline(0.0, color="0.5", lw=0.7)
    ax_c.set_ylabel("coefficient [-]")
    ax_c.set_title(r"$C_T = T/(\rho n^2 D^4)$, $C_P = P/(\rho n^3 D^5)$")
    for ax in (ax_t, ax_p, ax_e, ax_c):
        ax.grid(True, lw=0.4, alpha=0.6)
    for ax in (ax_e, ax_c):
        ax.set_xlabel(xlabel)
    handles, names = [], []
    for ax in (ax_e, ax_c):
        h, n = ax.get_legend_handles_labels()
        handles += h
        names += n
    fig.legend(handles, names, loc="outside lower center", ncols=min(5, len(names)), fontsize="small",
               frameon=False)
    geom = res.geometry
    fig.suptitle(f"Off-design BEM analysis: B = {geom.num_blades}, R = {geom.radius:.3g} m, "
                 f"altitude {res.altitude:.4g} m"
                 + (f", {res.rpm[0]:.4g} rpm" if res.sweep in ("advance_ratio", "v_axial") else
                    f", V = {res.v_axial[0]:.3g} m/s"))
    return finish(fig, path)


def _design_index(res):
    """Index of the sweep point at the geometry's design point, if the sweep contains it."""
    point = res.geometry.design_point
    if res.sweep == "advance_ratio" and res.design_advance_ratio is not None:
        hits = np.flatnonzero(np.isclose(res.advance_ratio, res.design_advance_ratio, rtol=1e-9, atol=1e-12)
                              & np.isclose(res.rpm, point.get("rpm", np.nan), rtol=1e-9))
    elif res.sweep == "v_axial" and "rpm" in point:
        hits = np.flatnonzero(np.isclose(res.v_axial, point.get("v_axial", np.nan), rtol=1e-9, atol=1e-12)
                              & np.isclose(res.rpm, point["rpm"], rtol=1e-9))
    elif res.sweep == "rpm" and "rpm" in point:
        hits = np.flatnonzero(np.isclose(res.rpm, point["rpm"], rtol=1e-9)
                              & np.isclose(res.v_axial, point.get("v_axial", np.nan), rtol=1e-9, atol=1e-12))
    else:
        return None
    return int(hits[0]) if hits.size else None


def plot_power_curve(curve, path=None):
    """Power, thrust, rotor speed and pitch, and C_P, C_T of a turbine's power curve (the first rotor of a batch).

    The rated wind speed is marked in every panel (dashed) and, with a tip-speed limit reached below rated, the
    start of region 2.5 (dotted).

    Parameters
    ----------
    curve : PowerCurve
        From :func:`~bild_mdo.results.power_curve.power_curve` or ``TurbineDesign.power_curve``.
    path : str or path, optional
        PNG file to write.

    Returns
    -------
    matplotlib.figure.Figure
    """
    one = curve[0] if curve.is_batch else curve
    v = one.wind_speed
    fig = new_figure(path, figsize=(9.0, 6.6))
    (ax_p, ax_t), (ax_s, ax_c) = fig.subplots(2, 2, sharex=True)
    ax_p.plot(v, one.power / 1e3, color="tab:red", marker="o", ms=3)
    ax_p.set_ylabel("power P [kW]")
    ax_p.set_title(f"Power (AEP {one.annual_energy / 3.6e12:.4g} GWh, capacity factor {one.capacity_factor:.3f})")
    ax_t.plot(v, one.thrust / 1e3, color="tab:blue", marker="o", ms=3)
    ax_t.set_ylabel("thrust T [kN]")
    ax_t.set_title("Thrust")
    ax_s.plot(v, one.rpm, color="tab:green", marker="o", ms=3, label="rotor speed")
    ax_s.set_ylabel("rotor speed [rpm]")
    ax_s.set_title("Rotor speed and collective pitch")
    ax_pitch = ax_s.twinx()
    ax_pitch.plot(v, np.degrees(one.collective_pitch), color="tab:purple", marker="s", ms=3, label="pitch")
    ax_pitch.set_ylabel("collective pitch [deg]")
    ax_c.plot(v, one.power_coefficient, color="tab:red", marker="o", ms=3, label="C_P")
    ax_c.plot(v, one.thrust_coefficient, color="tab:blue", marker="o", ms=3, label="C_T")
    ax_c.set_ylabel("coefficient [-]")
    ax_c.set_title("Power and thrust coefficients")
    ax_c.legend()
    for ax in (ax_p, ax_t, ax_s, ax_c):
        ax.axvline(one.rated_wind_speed, color="0.4", ls="--", lw=0.8)
        if one.tip_speed_limit_wind_speed < one.rated_wind_speed:
            ax.axvline(one.tip_speed_limit_wind_speed, color="0.4", ls=":", lw=0.8)
        ax.grid(True, alpha=0.3)
    for ax in (ax_s, ax_c):
        ax.set_xlabel("wind speed V [m/s]")
    return finish(fig, path)
