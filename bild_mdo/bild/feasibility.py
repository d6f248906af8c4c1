"""Infeasible designs of a BILD batch: found by the components in one pass, reported once.

A BILD design is infeasible where the ideal loading does not exist: the
paper's Assumption 3 (positive local thrust, ``u_axial > V_x``, and a
reference station that is not overloaded) fails at some station, or a hover
rotor cannot load any station (zero torque).  Each check is vectorised over
the nodes.  A component used on its own raises one
:class:`openmdao.api.AnalysisError` counting the failing nodes and naming up
to ten of them.  Inside :class:`~bild_mdo.bild.bild_group.BILDGroup` the
components write into the group's :class:`FeasibilityLedger` instead and
give the failing nodes finite placeholder values, so the rest of the batch
runs on; :class:`FeasibilityComp`, last in the group, then raises ONE error
listing every infeasible node with its reason (``on_infeasible='raise'``) or
reports the mask as the output ``feasible`` (``'flag'``).  Every operation is
elementwise over the nodes, so a feasible node's values do not depend on the
other nodes of the batch.
"""
from __future__ import annotations

import numpy as np
import openmdao.api as om

from bild_mdo.utils.options import declare_size_options

#: What BILDGroup does with infeasible nodes: raise one error, or flag them in the output ``feasible``.
ON_INFEASIBLE = ("raise", "flag")

#: Nodes described in full (with their values) in a message.
DETAILED_NODES = 10


def declare_feasibility_option(options):
    """Declare the ``feasibility`` option: the group's ledger, or None for a component used alone."""
    options.declare("feasibility", default=None, allow_none=True, recordable=False,
                    desc="FeasibilityLedger of the enclosing BILDGroup; None raises AnalysisError at once")


def node_ranges(nodes):
    """Node indices as compact text: ``'0-3, 7, 9-10'`` (every index, runs collapsed)."""
    nodes = np.asarray(nodes, dtype=int)
    if nodes.size == 0:
        return ""
    breaks = np.flatnonzero(np.diff(nodes) != 1)
    starts = nodes[np.concatenate(([0], breaks + 1))]
    ends = nodes[np.concatenate((breaks, [nodes.size - 1]))]
    return ", ".join(f"{a}" if a == b else f"{a}-{b}" for a, b in zip(starts, ends))


def _node(noun, details, node):
    """``'node 3, station 5 (a = 1, b = 2)'``: the node, its first failing station if known, and the values."""
    where = f"{noun} {int(node)}"
    if "station" in details:
        where += f", station {int(details['station'][node])}"
    values = ", ".join(f"{label} = {float(values[node]):.6g}" for label, values in details.items()
                       if label != "station")
    return f"{where} ({values})"


def describe_nodes(mask, reason, details, noun="node", limit=DETAILED_NODES):
    """``'<reason> at <count> node(s): node 3, station 5 (a = 1, b = 2); ...'``: the first ``limit`` with values."""
    nodes = np.flatnonzero(mask)
    shown = "; ".join(_node(noun, details, i) for i in nodes[:limit])
    more = f"; and {nodes.size - limit} more" if nodes.size > limit else ""
    return f"{reason} at {nodes.size} {noun}(s): {shown}{more}"


def report_infeasible(component, key, mask, reason, details, light=False):
    """Record (in the group's ledger) or raise (a component used alone) the infeasible nodes of one check.

    Parameters
    ----------
    component : openmdao.api.Component
        The checking component (with the ``feasibility`` option).
    key : str
        Name of the check, unique within the component.
    mask : ndarray of bool, shape (nn,)
        Nodes that fail the check.
    reason : str
        What fails and what to change, the same for every node.
    details : dict
        Label -> array (nn,) of the values shown for each failing node.
    light : bool
        Whether the remedy is a larger reference chord (the design is too lightly loaded): a thrust-target
        solve then searches above it (:attr:`FeasibilityLedger.light`).
    """
    ledger = component.options["feasibility"]
    mask = np.asarray(mask, dtype=bool)
    if ledger is not None:
        ledger.record(f"{component.pathname}:{key}", mask, reason, details, light=light)
    elif np.any(mask):
        raise om.AnalysisError(f"{component.msginfo}: {describe_nodes(mask, reason, details)}")


def report_station_status(component, status, failures, v_axial, v_theta, lam):
    """Report the nodes with a station of each failing ``status`` code (``failures``: code -> (key, reason)).

    ``status`` is ``[nn, nr]``; the details name each node's first failing station with its ``V_x``,
    ``V_theta`` and ``lambda`` (arrays broadcastable to ``status``).  Used by the per-station solves of the
    exact ideal loadings.
    """
    for code, (key, reason) in failures.items():
        bad = status == code
        details = station_details(bad, {"V_x [m/s]": v_axial, "V_theta [m/s]": v_theta, "lambda [m/s]": lam})
        report_infeasible(component, key, np.any(bad, axis=1), reason, details)


def station_details(bad, arrays):
    """Details of a station check: the first failing station of each node, the values there, the count.

    Returns a dict for :func:`report_infeasible`: ``station``, then ``arrays``
    at that station, then ``failing stations``; empty where no station fails (the details are
    shown only for failing nodes, and this runs on every call).
    """
    if not np.any(bad):
        return {}
    station = np.argmax(bad, axis=1)
    values = {label: np.take_along_axis(np.broadcast_to(values, bad.shape), station[:, None], axis=1)[:, 0]
              for label, values in arrays.items()}
    return {"station": station, **values, "failing stations": np.sum(bad, axis=1)}


class FeasibilityLedger:
    """The infeasible nodes found by the checks of one BILDGroup run, in the order the checks ran.

    Each check writes its mask on every run (so a later run replaces it).
    The reason of an infeasible node is that of the first check it fails.
    """

    def __init__(self, num_nodes):
        self.num_nodes = num_nodes
        self._checks = {}
        self._light = set()
        #: True while a solver iterates over the group (thrust target): the nodes are recorded, not raised.
        self.deferred = False

    def record(self, key, mask, reason, details, light=False):
        """Store (or replace) the result of check ``key``: see :func:`report_infeasible`."""
        self._checks[key] = (np.array(mask, dtype=bool), reason,
                             {label: np.real(np.array(values)) for label, values in details.items()})
        if light:
            self._light.add(key)
        else:
            self._light.discard(key)

    @property
    def infeasible(self):
        """ndarray of bool (nn,): True where some check fails."""
        mask = np.zeros(self.num_nodes, dtype=bool)
        for failed, _, _ in self._checks.values():
            mask |= failed
        return mask

    @property
    def light(self):
        """ndarray of bool (nn,): True where some check fails and every failing one asks for a larger ``ref_chord``."""
        light = np.zeros(self.num_nodes, dtype=bool)
        heavy = np.zeros(self.num_nodes, dtype=bool)
        for key, (failed, _, _) in self._checks.items():
            if key in self._light:
                light |= failed
            else:
                heavy |= failed
        return light & ~heavy

    def _first_check(self):
        """Index into the checks of each node's first failing check (-1 where feasible)."""
        first = np.full(self.num_nodes, -1)
        for k, (failed, _, _) in enumerate(self._checks.values()):
            first = np.where((first < 0) & failed, k, first)
        return first

    def status(self):
        """ndarray of str (nn,): ``'ok'`` where feasible, else the reason of the first failing check."""
        reasons = np.array(["ok"] + [reason for _, reason, _ in self._checks.values()], dtype=object)
        return reasons[self._first_check() + 1]

    def message(self, noun="node", limit=None):
        """One text naming the infeasible nodes and their reasons, grouped by reason.

        With ``limit=None`` every infeasible node is named (index runs
        collapsed) and the first :data:`DETAILED_NODES` of each reason come
        with their values; otherwise only the first ``limit`` infeasible nodes
        are named, each with its values.
        """
        first = self._first_check()
        infeasible = np.flatnonzero(first >= 0)
        listed = infeasible if limit is None else infeasible[:limit]
        detailed = DETAILED_NODES if limit is None else limit
        lines = [f"{infeasible.size} of {self.num_nodes} {noun}(s) infeasible"
                 + ("" if listed.size == infeasible.size else f" (the first {listed.size} listed)") + ":"]
        for k, (_, reason, details) in enumerate(self._checks.values()):
            nodes = listed[first[listed] == k]
            if nodes.size == 0:
                continue
            shown = "; ".join(_node(noun, details, i) for i in nodes[:detailed])
            lines.append(f"{reason}: {noun}(s) {node_ranges(nodes)} [{shown}]")
        return "\n  ".join(lines)


class FeasibilityComp(om.ExplicitComponent):
    """Last component of a BILDGroup: reports the infeasible nodes its checks found, all at once.

    Options
    -------
    num_nodes : int
        Designs (axis 0).
    ledger : FeasibilityLedger
        Filled by the checking components of the same group.
    on_infeasible : str
        ``'raise'`` (default): one :class:`openmdao.api.AnalysisError` listing
        every infeasible node and its reason; ``'flag'``: no error, the output
        ``feasible`` marks them.

    Outputs
    -------
    feasible[nn] (-)
        1.0 where the design is feasible, 0.0 where it is not (its other
        outputs are then placeholder values with no meaning).  Not
        differentiable (no partials).
    """

    def initialize(self):
        declare_size_options(self.options, radial=False)
        self.options.declare("ledger", types=FeasibilityLedger, recordable=False)
        self.options.declare("on_infeasible", default="raise", values=ON_INFEASIBLE)

    def setup(self):
        self.add_output("feasible", val=np.ones(self.options["num_nodes"]), units=None,
                        desc="1 where the BILD design is feasible, 0 where it is not (placeholder outputs)")

    def compute(self, inputs, outputs):
        ledger = self.options["ledger"]
        infeasible = ledger.infeasible
        if self.options["on_infeasible"] == "raise" and np.any(infeasible) and not ledger.deferred:
            raise om.AnalysisError(f"BILD: {ledger.message()}")
        outputs["feasible"] = np.where(infeasible, 0.0, 1.0)
