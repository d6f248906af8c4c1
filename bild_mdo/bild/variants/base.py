"""BILDVariant: the interface every member of the BILD family implements, and the parts they share.

A BILD design is one chain (paper Alg. 1): the reference station with the
reference chord, the ideal-loading constant lambda from it, every station's
loading and section point given lambda, then the back-computed chord and the
performance.  The members of the family differ in two choices, the options of
:class:`~bild_mdo.bild.bild_group.BILDGroup`:

* the ideal loading (``ideal_loading``): the paper's Eq. (22) and quartic (27),
  or the exact condition with Prandtl's factor differentiated;
* the section point (``section_point``): every station at the maximum-L/D point
  of the reference station's Reynolds number (the paper's Assumption 2), or each
  station at the least ``cd/cl`` of its own path of fixed load.

A variant adds three parts to the group, in this order, and promotes the
names below; everything else (atmosphere, stations, rotational speed, the
induced velocities, inflow angle, momentum loads, chord, root-chord
correction, Mach number and performance) is shared:

``add_reference``
    the reference station's section point and BEM state: ``phi_ref``,
    ``u_axial_ref``, ``u_theta_ref``, ``reynolds_ref`` and ``alpha_star_ref``,
    ``cl_star_ref``, ``cd_star_ref`` (or, for the reference-point variants with
    a one-airfoil polar, ``alpha_star, cl_star, cd_star`` of shape ``[nn]``);
``add_loading``
    ``ideal_loading_constant`` (lambda, m/s);
``add_stations``
    every station's ``eta2`` and its section point ``alpha_star, cl_star,
    cd_star`` (shape ``[nn, nr]`` where :attr:`BILDVariant.per_station`);
    the local-point variants add ``reynolds``, ``load_reynolds`` and
    ``section_branch``.
"""
from __future__ import annotations

from typing import NamedTuple

from bild_mdo.bild.chord import ChordComp
from bild_mdo.bild.induced_velocity import InducedVelocityComp
from bild_mdo.bild.inflow_angle import InflowAngleComp
from bild_mdo.bild.momentum_loads import MomentumLoadsComp


class Wiring(NamedTuple):
    """What a variant needs to add its components: the group, its polar and the option dictionaries the
    components take (``node``: ``num_nodes``; ``size``: also ``num_radial``; ``loss``: ``num_blades`` and
    ``loss_model``; ``checked``: the group's feasibility ledger), and the chord form."""

    group: object
    polar: object
    node: dict
    size: dict
    loss: dict
    checked: dict
    chord_form: str


class BILDVariant:
    """One member of the BILD family (module docstring); :class:`~bild_mdo.bild.bild_group.BILDGroup` builds the
    member its options name and calls :meth:`add` in its ``setup``."""

    #: The options of BILDGroup that select the member.
    ideal_loading = None
    section_point = None

    def __init__(self, wiring):
        self.wiring = wiring

    @property
    def per_station(self):
        """Whether every station has its own section point (``cl_star`` etc. of shape ``[nn, nr]``)."""
        raise NotImplementedError

    #: What ``BILDGroup(thrust_target=True)`` solves for the thrust (:data:`bild_mdo.bild.thrust_target.STATES`).
    thrust_target_state = "ref_chord"

    def check_polar(self):
        """Raise ValueError with one line where the member cannot use the group's polar."""

    def add_reference(self):
        raise NotImplementedError

    def add_loading(self):
        raise NotImplementedError

    def add_stations(self):
        raise NotImplementedError

    def add(self):
        """The member's part of the chain, then the shared stations' chain up to the chord."""
        self.check_polar()
        self.add_reference()
        self.add_loading()
        self.add_stations()
        add_station_chain(self.wiring, self.per_station)
        add_chord(self.wiring, self.per_station)


def add_station_chain(w, per_station):
    """eta2 -> induced velocity -> inflow angle -> momentum loads (every member)."""
    along = dict(varies_along_span=per_station)
    g = w.group
    g.add_subsystem("induced_velocity", InducedVelocityComp(**w.size, **w.checked, **along),
                    promotes_inputs=["eta2", "v_axial", "v_theta", "cl_star", "cd_star"],
                    promotes_outputs=["u_axial", "u_theta"])
    g.add_subsystem("inflow_angle", InflowAngleComp(**w.size, **w.checked, **along),
                    promotes_inputs=["u_axial", "u_theta", "v_theta", "alpha_star"],
                    promotes_outputs=["phi", "inflow_speed", "twist"])
    g.add_subsystem("momentum_loads", MomentumLoadsComp(**w.size, **w.loss, **w.checked),
                    promotes_inputs=["u_axial", "u_theta", "phi", "radii", "v_axial", "rho", "rpm", "radius",
                                     "hub_radius"],
                    promotes_outputs=["loss_factor", "dthrust_dr", "dtorque_dr", "denergy_loss_dr"])


def add_chord(w, per_station):
    """The back-computed chord, Eq. (31) or the torque form (every member)."""
    load = ["dthrust_dr"] if w.chord_form == "thrust" else ["dtorque_dr", "radii"]
    w.group.add_subsystem("chord", ChordComp(**w.size, num_blades=w.loss["num_blades"], chord_form=w.chord_form,
                                             **w.checked, varies_along_span=per_station),
                          promotes_inputs=load + ["phi", "inflow_speed", "rho", "cl_star", "cd_star"],
                          promotes_outputs=["chord_raw", "lift_coefficient", "drag_coefficient"])
