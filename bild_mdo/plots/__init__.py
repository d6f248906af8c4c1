"""Figures (matplotlib, extra ``bild-mdo[plot]``; imported only when a figure is made).

:func:`plot_blade`
    Planform and twist of one design or a batch (:mod:`bild_mdo.plots.blade`).
:func:`plot_performance_curves`
    Thrust, power, efficiency and coefficients of an off-design sweep (:mod:`bild_mdo.plots.curves`).
:func:`plot_power_curve`
    A turbine's power curve: power, thrust, rotor speed and pitch, C_P and C_T (:mod:`bild_mdo.plots.curves`).
:func:`plot_noise_spectrum`, :func:`plot_directivity`, :func:`arc_observers`
    Rotor-noise spectra at observers and the directivity on an arc (:mod:`bild_mdo.plots.noise`).
:func:`plot_run_times`, :func:`plot_parity`
    The verification sweep's timing scatter (paper Fig. 4) and parity plots (Fig. 5)
    (:mod:`bild_mdo.plots.verification`).
"""
from bild_mdo.plots.blade import plot_blade
from bild_mdo.plots.curves import plot_performance_curves, plot_power_curve
from bild_mdo.plots.noise import arc_observers, plot_directivity, plot_noise_spectrum
from bild_mdo.plots.verification import plot_parity, plot_run_times

__all__ = ["arc_observers", "plot_blade", "plot_directivity", "plot_noise_spectrum", "plot_parity",
           "plot_performance_curves", "plot_power_curve",
           "plot_run_times"]
