"""The set-up BILD problem behind :func:`~bild_mdo.results.design.design_rotor`, cached by configuration.

Setting up a :class:`~bild_mdo.bild.bild_group.BILDGroup` costs far more than
running it, so the problems are kept by configuration (sizes, blades, polar,
loss model, chord form, root-chord correction, input mode, section point) and reused; the
caller sets the inputs and runs the model.  A 10,000-design model holds a few
hundred MB of vectors and Jacobians, so only a handful are kept.
"""
from __future__ import annotations

import openmdao.api as om

from bild_mdo import validation
from bild_mdo.airfoil.text import sweep_polar
from bild_mdo.bild.bild_group import BILDGroup
from bild_mdo.utils.problem_cache import ProblemCache

# Set-up problems by configuration, least recently used first.
_PROBLEM_CACHE = ProblemCache(size=4)


def clear_model_cache():
    """Forget the set-up BILD problems cached by :func:`bild_problem` (frees their memory)."""
    _PROBLEM_CACHE.clear()


def _bild_problem(num_nodes, num_radial, num_blades, polar, loss_model, chord_form, correction, input_mode,
                  on_infeasible, thrust_target, section_point, ideal_loading, use_atmosphere):
    def make():
        group = BILDGroup(num_nodes=num_nodes, num_radial=num_radial, num_blades=num_blades, polar=polar,
                          loss_model=loss_model, chord_form=chord_form, root_chord_correction=correction,
                          input_mode=input_mode, on_infeasible=on_infeasible, thrust_target=thrust_target,
                          section_point=section_point, ideal_loading=ideal_loading,
                          use_atmosphere=use_atmosphere)
        prob = om.Problem(group, reports=False)
        prob.setup(check=False)
        prob.final_setup()
        return prob

    key = (num_nodes, num_radial, num_blades, loss_model, chord_form, correction, input_mode, on_infeasible,
           thrust_target, section_point, ideal_loading, use_atmosphere)
    return _PROBLEM_CACHE.get(key, polar, make)


def bild_problem(num_nodes=1, num_radial=30, num_blades=3, airfoil="naca4412", loss_model="tip_hub",
                 chord_form="thrust", root_chord_correction=None, input_mode="v_axial", on_infeasible="raise",
                 thrust_target=False, section_point="reference", ideal_loading="paper", use_atmosphere=True):
    """The cached, set-up BILD problem :func:`~bild_mdo.results.design.design_rotor` uses for this configuration.

    For users who want OpenMDAO access (totals, recorders) to the same model;
    inputs are promoted names of :class:`~bild_mdo.bild.BILDGroup`.

    Parameters
    ----------
    num_nodes, num_radial, num_blades : int
        Designs, radial stations and blades (integers >= 1).
    airfoil : Polar or str
        A polar or airfoil text (:func:`bild_mdo.airfoil.text.sweep_polar`: a built-in name, a NACA
        designation, polar files, ``AIRFOIL@re=RE``, a spanwise set ...).
    loss_model, chord_form, root_chord_correction, input_mode, on_infeasible, thrust_target
        Options of :class:`~bild_mdo.bild.BILDGroup` (``thrust_target=True``: set the
        input ``thrust_target`` (N) instead of ``ref_chord``, which becomes an output).  With ``on_infeasible='flag'``
        the run never fails for an infeasible design: read the output ``feasible``
        and ``prob.model.feasibility`` (the reasons) after ``run_model``.
    section_point, ideal_loading, use_atmosphere
        Options of :class:`~bild_mdo.bild.BILDGroup` too: each value has its own cached problem
        (``use_atmosphere=False``: set ``rho``, ``mu``, ``speed_of_sound`` instead of ``altitude``).

    Returns
    -------
    openmdao.api.Problem
        Set up; the same object for the same configuration while it stays in the cache.
    """
    polar = sweep_polar(airfoil)  # one object per airfoil text, so the cache is hit on repeated calls
    return _bild_problem(validation.integer("num_nodes", num_nodes), validation.integer("num_radial", num_radial),
                         validation.integer("num_blades", num_blades), polar, loss_model, chord_form,
                         root_chord_correction, input_mode, on_infeasible,
                         thrust_target, section_point, ideal_loading, bool(use_atmosphere))
