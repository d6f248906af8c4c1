"""Thrust-target design: the reference chord that gives a required thrust, solved per design inside BILDGroup.

BILD's free parameter is the reference chord ``c_ref`` (Algorithm 1): the
thrust of the ideal rotor grows with it, close to ``T ~ c_ref**p`` with
``p`` about 0.8-1 over two decades of ``c_ref``.  ``BILDGroup(thrust_target=True)``
makes ``ref_chord`` the state of :class:`ThrustTargetComp` (for the
Reynolds-aware exact loading lambda instead, option ``state``: there the
reference chord names its design only piecewise, and the thrust jumps by a
factor of 3 where the reference station changes branch, while the thrust of
the stations at a given lambda moves only where one station changes branch;
``ref_chord`` is then the blade's chord at ``r_ref``), whose residual is
``R = T / T* - 1`` (``T = sum(dT/dr dr)``, the thrust of the stations, as the
performance sums it), and solves it with :class:`ReferenceChordSolver`: passes
of the feed-forward chain, after each of which every design takes its own
bracketed quasi-Newton step in ``y = ln c_ref`` on ``g = ln(T / T*)``::

    y <- y - g / s,   s = dg/dy by secant (1 before the first secant: T ~ c_ref),

kept inside the design's bracket ``(lo, hi)`` (``g < 0`` or a design too
lightly loaded at ``lo``; ``g > 0`` or another infeasible design at ``hi``),
with bisection in ``y`` whenever the step leaves it (a factor 4 beyond the
known side while one side is open), and steps of at most a factor 10 in
``c_ref``.  A design is too lightly loaded where every check it fails asks for
a larger ``c_ref`` (:attr:`~bild_mdo.bild.feasibility.FeasibilityLedger.light`:
no station loaded, or, with the Reynolds-aware exact loading, a reference chord
below the lightest ideal load of its station, where the thrust does not grow
with ``c_ref``).  A design is converged when ``|g| <= rtol``; it then keeps its chord, so
the last pass is consistent at every design.  A design whose bracket closes
(to 1e-9 in ``ln c_ref``) on the infeasible side, so that the target is above
the largest thrust the ideal loading can give (Assumption 3: the reference
station overloads; in forward flight the thrust can even peak before that),
or that does not converge in ``maxiter`` passes, is parked at its largest
feasible chord below the target, evaluated once more and recorded in the
group's feasibility ledger (raised or flagged like every infeasible design);
one whose bracket closes on the light side (a target below the lightest
feasible design there) is parked at its smallest feasible chord above it.
The next solve starts a parked design from the default chord, not from where it was parked.
With the local section point the thrust can jump where the section point of
the reference station changes branch.  A bracket that closes on a jump (its
two ends still more than 1e-6 apart in ``ln T``) is not a solution: the
target lies in the gap and the design is reported so ("thrust target in a
jump of the design").  A downward jump (``lo`` above ``hi``) sends the search
on to the piece below ``hi``, where the thrust rises to the target again.

The total derivatives do not depend on the solver: the group's
:class:`openmdao.api.DirectSolver` solves the linear system of the whole
chain with ``dR/dT``, ``dR/dT*`` of this residual (implicit-function theorem).
Under complex step the real parts start converged; the imaginary parts are
linear in each other, so their secant is the exact slope after one step and
the imaginary part of ``c_ref`` is exact after two (three passes per solve).
"""
import numpy as np
import openmdao.api as om
from openmdao.solvers.solver import NonlinearSolver

from bild_mdo.bild.feasibility import declare_feasibility_option
from bild_mdo.utils.options import declare_size_options
from bild_mdo.utils.sparsity import node_wrt_dist, node_wrt_node

_MAX_FACTOR = np.log(10.0)
# Accepted secant slopes d ln T / d ln c_ref (the physical one is about 0.8-1).
_SLOPE_RANGE = (0.05, 1.0e3)
_EPS = np.finfo(float).eps
# A target not reached within this relative chord of the feasibility boundary is reported as out of reach.
_BOUNDARY_WIDTH = 1e-9
# |ln(T/T*)| above which a bracket closed by round-off is a jump of the design, not a converged chord.
_JUMP_GAP = 1e-6
#: The states a thrust-target solve can take: name -> (units, start without a previous solution, description).
#: The reference chord (BILD's free parameter, Algorithm 1), or, for the Reynolds-aware exact loading, lambda itself
#: (:class:`~bild_mdo.bild.variants.reynolds_exact.variant.ReynoldsExactVariant`: the reference chord would jump
#: where the reference station changes branch).
STATES = {"ref_chord": ("m", 0.15, "chord at the reference station c_ref, solved for T = T*"),
          "ideal_loading_constant": ("m/s", 10.0, "ideal-loading constant lambda, solved for T = T*")}


class ThrustTargetComp(om.ImplicitComponent):
    """Reference chord (or lambda) of the ideal rotor that gives the target thrust: ``R = T / T* - 1``.

    Its ``solve_nonlinear`` takes one bracketed quasi-Newton step per design
    on each pass of :class:`ReferenceChordSolver` (module docstring); used on
    its own it does nothing but check the inputs.

    Options
    -------
    num_nodes, num_radial : int
        Designs and stations.
    feasibility : FeasibilityLedger or None
        The group's ledger (the designs whose target is not reached are recorded there).
    rtol : float
        Relative thrust tolerance of the solve, ``|ln(T/T*)| <= rtol`` (default 1e-12).
    maxiter : int
        Passes after which the designs still iterating are recorded as not converged.
    state : str
        ``'ref_chord'`` (default) or ``'ideal_loading_constant'`` (:data:`STATES`): the output solved for.

    Inputs
    ------
    dthrust_dr[nn, nr] (N/m), dr[nn, nr] (m)
        Thrust per unit span of the stations and their widths (the thrust ``T = sum(dT/dr dr)``: summed here,
        so that the passes of the solve need not run the performance).
    thrust_target[nn] (N)
        Target thrust ``T* > 0``.

    Outputs
    -------
    ref_chord[nn] (m), or ideal_loading_constant[nn] (m/s)
        Chord at the reference station, or lambda (option ``state``).
    """

    def initialize(self):
        declare_size_options(self.options)
        declare_feasibility_option(self.options)
        self.options.declare("rtol", types=float, default=1e-12, desc="relative thrust tolerance |ln(T/T*)|")
        self.options.declare("maxiter", types=int, default=60, desc="passes before a design is given up")
        self.options.declare("state", default="ref_chord", values=tuple(STATES),
                             desc="the variable solved for the thrust: the reference chord or lambda")

    def setup(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        self.add_input("dthrust_dr", val=np.ones((nn, nr)), units="N/m", desc="thrust per unit span, all blades")
        self.add_input("dr", val=np.ones((nn, nr)), units="m", desc="radial width of each station")
        self.add_input("thrust_target", val=np.ones(nn), units="N", desc="target thrust T* (> 0)")
        self._state = self.options["state"]
        units, start, desc = STATES[self._state]
        self.add_output(self._state, val=np.full(nn, start), units=units, lower=0.0, desc=desc)
        # d ln T / d ln c_ref of each design, kept across solves (the first step of the next solve uses it).
        self._slope = np.ones(nn)
        self._parked = None  # a new set-up has no parked designs (and no outputs to reset yet)
        self.start()

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        self.declare_partials(self._state, "thrust_target", rows=rows, cols=cols)
        rows, cols = node_wrt_dist(nn, nr)
        self.declare_partials(self._state, ["dthrust_dr", "dr"], rows=rows, cols=cols)

    def forget_history(self, start=None):
        """Start the next solve as a fresh model would: from ``start`` (the state's default if None) with the
        slope 1.

        Without it a solve starts from the last solve's chord and slope: the same target to 1e-12, but not
        bitwise (a caller that must repeat itself exactly, such as an optimiser's start, calls this first).
        """
        self._slope = np.ones(self.options["num_nodes"])
        self._outputs[self._state] = STATES[self._state][1] if start is None else start

    def start(self):
        """Forget the brackets and passes of the last solve (called by the solver before its first pass).

        A design parked by the last solve starts from the default chord with the slope 1 (where it was parked
        says nothing about the next target).
        """
        nn = self.options["num_nodes"]
        parked = self._parked
        if parked is not None and np.any(parked):
            self._outputs[self._state] = np.where(parked, STATES[self._state][1], self._outputs[self._state])
            self._slope = np.where(parked, 1.0, self._slope)
        self._passes = 0
        self._lo = np.full(nn, -np.inf)
        self._hi = np.full(nn, np.inf)
        self._hi_infeasible = np.zeros(nn, dtype=bool)  # whether hi was set by an infeasible design
        self._lo_light = np.zeros(nn, dtype=bool)  # whether lo was set by a design too lightly loaded
        self._parked = np.zeros(nn, dtype=bool)  # given up: at the largest feasible chord, reported at the end
        self._jumped = np.zeros(nn, dtype=bool)  # given up because the target lies in a jump of the thrust
        self._too_light = np.zeros(nn, dtype=bool)  # given up below the lightest feasible design
        self._previous = None  # (y, g, feasible) of the last pass, for the secant
        #: True once every design is converged or given up (the last pass was consistent).
        self.finished = False

    @staticmethod
    def thrust(inputs):
        """``T = sum(dT/dr dr)`` (N) of every design."""
        return np.sum(inputs["dthrust_dr"] * inputs["dr"], axis=1)

    def apply_nonlinear(self, inputs, outputs, residuals):
        residuals[self._state] = self.thrust(inputs) / inputs["thrust_target"] - 1.0

    def linearize(self, inputs, outputs, partials):
        target = inputs["thrust_target"]
        partials[self._state, "dthrust_dr"] = (inputs["dr"] / target[:, None]).ravel()
        partials[self._state, "dr"] = (inputs["dthrust_dr"] / target[:, None]).ravel()
        partials[self._state, "thrust_target"] = -self.thrust(inputs) / target ** 2

    def solve_nonlinear(self, inputs, outputs):
        target = inputs["thrust_target"]
        if not np.all(np.isfinite(np.real(target)) & (np.real(target) > 0.0)):
            node = int(np.flatnonzero(~(np.isfinite(np.real(target)) & (np.real(target) > 0.0)))[0])
            raise om.AnalysisError(f"{self.msginfo}: thrust_target must be positive and finite, got "
                                   f"{float(np.real(target[node]))!r} at node {node}")
        ledger = self.options["feasibility"]
        if ledger is None:
            return
        self._passes += 1
        self._step(inputs, outputs, ledger)

    def _step(self, inputs, outputs, ledger):
        """One pass: update the brackets, take the steps, decide whether this pass is the last."""
        thrust, target = self.thrust(inputs), inputs["thrust_target"]
        key, jump_key, light_key = (f"{self.pathname}:{name}" for name in ("target", "jump", "light"))
        for name in (key, jump_key, light_key):
            ledger.record(name, np.zeros(thrust.shape, dtype=bool), "", {})
        chord = outputs[self._state]
        shown = f"{self._state} [{STATES[self._state][0]}]"
        y = np.log(chord)
        y_real = np.real(y)
        feasible = ~ledger.infeasible & np.isfinite(np.real(thrust)) & (np.real(thrust) > 0.0)
        light = ~feasible & ledger.light
        g = np.log(np.where(feasible, thrust, target) / target)
        g_real = np.real(g)
        self._update_bracket(y_real, g_real, feasible, light)
        slope_imag = self._update_slopes(y, g, feasible)
        step = -g_real / self._slope
        # Converged: |ln(T/T*)| within rtol, or a step below round-off of ln c_ref, or a bracket closed by
        # round-off on a feasible side.  Under complex step the imaginary part must have converged too.
        both = np.isfinite(self._lo) & np.isfinite(self._hi)
        closed = both & ((self._hi - self._lo) <= 4.0 * _EPS * np.maximum(np.abs(self._hi), 1.0))
        narrow = both & ((self._hi - self._lo) <= _BOUNDARY_WIDTH)
        # A bracket narrowed to 1e-9 in y with the thrust still more than 1e-6 off (a slope beyond any the
        # secant accepts) is a jump of the thrust (a branch switch of the section point), not a solution: the
        # target lies in the gap.  It is given up and reported as such.
        jump = feasible & narrow & ~self._hi_infeasible & ~self._lo_light & (np.abs(g_real) > _JUMP_GAP)
        converged = feasible & ((np.abs(g_real) <= self.options["rtol"]) | (np.abs(step) <= 4.0 * _EPS)
                                | (closed & ~self._hi_infeasible & ~jump))
        real_converged = converged
        if np.iscomplexobj(g):
            # The imaginary step below round-off of the imaginary part of ln c_ref (exactly zero where the
            # perturbed input does not reach this design).
            converged = converged & ((np.imag(g) == 0.0)
                                     | (np.abs(np.imag(g) / slope_imag) <= 1e-13 * np.abs(np.imag(y))))
        # Out of reach (the bracket closed on an infeasible side) or out of passes: the design is parked at
        # its largest feasible chord below the target, evaluated once more, and reported.
        at_boundary = narrow & self._hi_infeasible
        # Below the lightest feasible design (the bracket closes on the light side): parked above, at hi.
        at_light = narrow & self._lo_light & ~self._hi_infeasible
        self._jumped |= jump
        self._too_light |= at_light & ~converged & ~self._parked
        give_up = ~converged & ~self._parked & (at_boundary | at_light | jump
                                                | (self._passes >= self.options["maxiter"]))
        park_at = np.where(self._too_light, self._hi, self._lo)
        move = give_up & np.isfinite(park_at) & (park_at != y_real) & ~(self._lo_light & ~self._too_light)
        self._parked |= give_up
        if np.all(converged | self._parked) and not np.any(move):
            self.finished = True
            ledger.deferred = False
            ledger.record(jump_key, self._parked & self._jumped,
                          "thrust target in a jump of the design: the ideal rotor's thrust jumps across it at this "
                          "reference chord (the section point changes branch; see section_branch); ask for a thrust "
                          "outside the gap, or use section_point='reference'",
                          {"T* [N]": target, "T [N]": thrust, shown: chord})
            ledger.record(light_key, self._parked & self._too_light & ~converged,
                          "thrust target not reached: below the smallest thrust of a feasible ideal loading "
                          "here (the lighter designs load no station, or their reference chord is below the "
                          "lightest ideal load); raise it, or lower rpm or radius",
                          {"T* [N]": target, "T [N]": thrust, shown: chord})
            ledger.record(key, self._parked & ~converged & ~self._jumped & ~self._too_light,
                          "thrust target not reached: above the largest thrust of a feasible ideal loading "
                          "(lower it, or raise rpm or radius) or the reference-chord solve did not converge",
                          {"T* [N]": target, "T [N]": thrust, shown: chord})
            return
        ledger.deferred = True
        y_new = y_real + np.where(feasible, np.clip(step, -_MAX_FACTOR, _MAX_FACTOR),
                                  np.where(light, np.log(4.0), -np.log(4.0)))
        outside = ~((y_new > self._lo) & (y_new < self._hi))
        with np.errstate(invalid="ignore"):  # -inf + inf where no side is known yet (g = 0 exactly): not used
            fallback = np.where(both, 0.5 * (self._lo + self._hi),
                                np.where(np.isfinite(self._lo), self._lo + np.log(4.0), self._hi - np.log(4.0)))
        y_new = np.where(real_converged, y_real, np.where(outside, fallback, y_new))
        y_new = np.where(move, park_at, y_new)
        if np.iscomplexobj(y):
            y_new = y_new + 1j * (np.imag(y) - np.imag(g) / slope_imag)
        outputs[self._state] = np.where(converged | (self._parked & ~move), chord, np.exp(y_new))

    def _update_bracket(self, y, g, feasible, light):
        """``lo``: largest ``ln c_ref`` with ``T < T*`` or too light; ``hi``: smallest with ``T > T*`` or
        infeasible otherwise."""
        below = (feasible & (g < 0.0)) | light
        self._lo_light = np.where(below & (y >= self._lo), light, self._lo_light)
        self._lo = np.where(below, np.maximum(self._lo, y), self._lo)
        above = (~feasible & ~light) | (feasible & (g > 0.0))
        self._hi_infeasible = np.where(above & (y <= self._hi), ~feasible, self._hi_infeasible)
        self._hi = np.where(above, np.minimum(self._hi, y), self._hi)
        # The thrust can jump DOWN where the section point changes branch (lo ends up above hi): a solution
        # then lies on the piece left of hi (T rises with c_ref on each piece), so the search goes on there.
        self._lo = np.where(self._lo > self._hi, -np.inf, self._lo)

    def _update_slopes(self, y, g, feasible):
        """Secant slopes ``d ln T / d ln c_ref``: of the real parts (kept), and of the imaginary parts.

        Under complex step the imaginary parts are linear in each other, so their secant is the exact
        slope after one step, and the next step puts the imaginary part of ``c_ref`` on its derivative.
        """
        slope_imag = self._slope
        if self._previous is not None:
            y_old, g_old, was_feasible = self._previous
            dy = np.real(y) - np.real(y_old)
            with np.errstate(divide="ignore", invalid="ignore"):
                secant = (np.real(g) - np.real(g_old)) / dy
                secant_imag = (np.imag(g) - np.imag(g_old)) / (np.imag(y) - np.imag(y_old))
            usable = feasible & was_feasible & (np.abs(dy) > 1e3 * _EPS) & np.isfinite(secant) \
                & (secant > _SLOPE_RANGE[0]) & (secant < _SLOPE_RANGE[1])
            self._slope = np.where(usable, secant, self._slope)
            slope_imag = np.where(np.isfinite(secant_imag) & (secant_imag != 0.0), secant_imag, self._slope)
        self._previous = (y, g, feasible)
        return slope_imag


class ReferenceChordSolver(NonlinearSolver):
    """Passes of the BILD chain until :class:`ThrustTargetComp` has converged or given up every design.

    The group names its balance component in the attribute ``thrust_target_balance``;
    the number of passes is bounded by that component's ``maxiter``.  The first pass runs the
    subsystems before the balance; the later passes only the loop of ``ref_chord`` (the subsystems
    that depend on it and feed the thrust or check the feasibility of a design): the others are upstream of
    ``ref_chord`` and unchanged.
    The subsystems that depend on ``ref_chord`` without feeding the thrust (the local Mach number),
    and those after the balance (the feasibility check), run once, after the last pass.
    """

    SOLVER = "NL: BILD ref chord"

    def _partition(self, system, balance):
        """``(first, loop, tail)`` names of the subsystems (module docstring), from the connections."""
        prefix = system.pathname + "." if system.pathname else ""
        edges, back = {}, {}
        for target, source in system._conn_global_abs_in2out.items():
            if not (target.startswith(prefix) and source.startswith(prefix)):
                continue
            a, b = source[len(prefix):].split(".", 1)[0], target[len(prefix):].split(".", 1)[0]
            if a != b:
                edges.setdefault(a, set()).add(b)
                back.setdefault(b, set()).add(a)

        def reach(start, graph):
            seen, todo = set(), [start]
            while todo:
                for name in graph.get(todo.pop(), ()):
                    if name not in seen:
                        seen.add(name)
                        todo.append(name)
            return seen

        downstream, feeds = reach(balance.name, edges), reach(balance.name, back)
        order = [sub.name for sub in system._subsystems_myproc]
        after = set(order[order.index(balance.name) + 1:])
        # A check that records into the feasibility ledger (the chord's force coefficient) steers the search.
        checks = {sub.name for sub in system._subsystems_myproc
                  if "feasibility" in sub.options and sub.options["feasibility"] is not None}
        loop = (downstream & (feeds | checks)) - after | {balance.name}
        tail = ((downstream - feeds) | after) - loop
        first = set(order) - tail
        return first, loop, tail

    def _run(self, system, names):
        for subsys in system._relevance.filter(system._all_subsystem_iter()):
            if subsys.name in names:
                system._transfer("nonlinear", "fwd", subsys.name)
                if subsys._is_local:
                    subsys._solve_nonlinear()

    def solve(self):
        system = self._system()
        balance = system.thrust_target_balance
        balance.start()
        if not hasattr(self, "_warm"):
            # Components that can start from their last solution (LocalStationComp): each pass after the
            # first starts every station from its state in the pass before (a design on its own, as in a batch).
            self._warm = [sub for sub in system.system_iter(recurse=True) if hasattr(sub, "warm_start")]
            self._parts = self._partition(system, balance)
        first, loop, tail = self._parts
        if balance not in system._relevance.filter([balance]):
            # A run for derivatives of outputs the thrust does not reach (the chord at r_ref of a lambda solve,
            # under complex step in r_ref): the state keeps its solution, the rest runs once.
            self._run(system, first | tail)
            return
        try:
            for self._iter_count in range(balance.options["maxiter"] + 2):
                self._run(system, first if self._iter_count == 0 else loop)
                if balance.finished:
                    break
                for sub in self._warm:
                    sub.warm_start = True
            else:
                raise om.AnalysisError(f"{system.msginfo}: the reference-chord solve did not finish")
        finally:
            balance.options["feasibility"].deferred = False
            for sub in self._warm:
                sub.warm_start = False
        self._run(system, tail)
