"""Maximum-L/D operating point of the airfoil at the reference station's Reynolds (and Mach) number."""
import numpy as np
import openmdao.api as om

from bild_mdo.airfoil.builtin import resolve_polar
from bild_mdo.airfoil.max_lift_to_drag_table import max_lift_to_drag_tabulated
from bild_mdo.utils.options import VARIABLES, add_inputs, add_outputs, declare_size_options
from bild_mdo.utils.sparsity import dist_wrt_node, node_wrt_node


def default_polar():
    """The built-in NACA 4412 polar, BILD's default airfoil (paper Sec. 5.2)."""
    return resolve_polar("naca4412")


class ReferenceAirfoilComp(om.ExplicitComponent):
    """Angle of attack, lift and drag coefficients of maximum lift-to-drag ratio.

    BILD operates every blade element at the airfoil's maximum ``C_l/C_d``
    (paper Assumption 2).  The point depends on the Reynolds number (and, for
    a polar with ``varies_with_mach``, on the Mach number), which this
    component evaluates at the reference station with the *local speed
    without induction*::

        Re_ref = rho * W0 * c_ref / mu,   M_ref = W0 / a,   W0 = sqrt(V_x**2 + (Omega r_ref)**2).

    Why ``W0`` and not the inflow speed ``W`` with induction: ``W`` follows
    from the reference-station BEM solve, which itself needs ``C_l*, C_d*``;
    using ``W`` would close a loop and need a coupled solver around two
    components.  ``W0`` keeps the BILD chain feed-forward (RunOnce), uses the
    same convention as the BEM analysis of this package, and changes
    ``Re_ref`` by a few percent only, to which the max-L/D point of a smooth
    polar is weakly sensitive.  A polar that does not vary with Mach number
    is queried without it (exactly the Reynolds-only point).

    The point is the exact root of the polar's ``d(C_l/C_d)/d(alpha) = 0``;
    for a polar that varies with Reynolds number only it is found by
    :func:`~bild_mdo.airfoil.max_lift_to_drag_table.max_lift_to_drag_tabulated`
    (the same Newton solve, warm-started from a table built once per polar),
    and ``compute_partials`` reuses the point ``compute`` found at the same
    inputs (its Reynolds derivatives, evaluated there on first use, are
    the only polar call ``compute`` leaves to it).

    A polar that varies along the span
    (:class:`~bild_mdo.airfoil.spanwise.SpanwisePolar`, ``polar.varies_along_span``)
    gives every station its own point, at the reference station's ``Re_ref``
    and ``M_ref`` and the station's ``r/R`` (Assumption 2 per station):
    ``alpha_star, cl_star, cd_star`` are then ``[nn, nr]``, and the reference
    station's own point, at ``r_ref/R``, is ``alpha_star_ref, cl_star_ref,
    cd_star_ref`` ``[nn]``.  At a station placed at ``r_ref`` the two agree, so
    the back-computed chord there is still ``c_ref``.

    Options
    -------
    num_nodes, num_radial : int
        Number of designs / operating points and of radial stations (used
        only by a polar that varies along the span).
    polar : Polar or None
        Airfoil polar (``bild_mdo.airfoil.polar.Polar``); ``None`` selects the
        built-in NACA 4412.

    Inputs
    ------
    v_axial[nn] (m/s)
        Axial free-stream velocity V_x.
    v_theta_ref[nn] (m/s)
        Rotational speed at the reference station, ``Omega r_ref``.
    ref_chord[nn] (m)
        Chord prescribed at the reference station.
    rho[nn] (kg/m**3), mu[nn] (Pa*s), speed_of_sound[nn] (m/s)
        Air density, dynamic viscosity and speed of sound.
    radii[nn, nr] (m), radius[nn] (m), ref_radius_ratio[nn] (-)
        Stations, tip radius and ``r_ref/R`` (only for a polar that varies
        along the span).

    Outputs
    -------
    reynolds_ref[nn] (-), mach_ref[nn] (-)
        Reynolds and Mach numbers of the reference station.
    alpha_star[nn] (rad), cl_star[nn] (-), cd_star[nn] (-)
        Angle of attack, lift and drag coefficients of maximum lift-to-drag
        ratio; ``[nn, nr]`` (per station) for a polar that varies along the span.
    alpha_star_ref[nn] (rad), cl_star_ref[nn] (-), cd_star_ref[nn] (-)
        The point of the reference station (only for a polar that varies along the span).
    """

    def initialize(self):
        declare_size_options(self.options)
        self.options.declare("polar", default=None, allow_none=True, recordable=False,
                             desc="airfoil Polar object; None selects the built-in NACA 4412")

    def setup(self):
        nn = self.options["num_nodes"]
        polar = self.options["polar"]
        self._polar = default_polar() if polar is None else polar
        self._spanwise = bool(self._polar.varies_along_span)
        self._mach = bool(self._polar.varies_with_mach)
        self._last = None
        add_inputs(self, ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu"))
        add_inputs(self, ("speed_of_sound",))
        self.add_output("reynolds_ref", val=np.full(nn, 3e5), units=None,
                        desc="chord Reynolds number at the reference station (speed without induction)")
        self.add_output("mach_ref", val=np.full(nn, 0.2), units=None,
                        desc="Mach number at the reference station (speed without induction)")
        if self._spanwise:
            add_inputs(self, ("radii", "radius"))
            self.add_input("ref_radius_ratio", val=np.full(nn, 0.5), units=None, desc="r_ref / R")
            nr = self.options["num_radial"]
            for name in _POINT.values():
                _, default, units, desc = VARIABLES[name]
                self.add_output(f"{name}_ref", val=np.full(nn, default), units=units,
                                desc=f"{desc}, of the reference station")
                self.add_output(name, val=np.full((nn, nr), default), units=units, desc=f"{desc}, per station")
        else:
            add_outputs(self, tuple(_POINT.values()))

    def setup_partials(self):
        nn, nr = self.options["num_nodes"], self.options["num_radial"]
        rows, cols = node_wrt_node(nn)
        self.declare_partials("reynolds_ref", _REYNOLDS_INPUTS, rows=rows, cols=cols)
        self.declare_partials("mach_ref", _MACH_INPUTS, rows=rows, cols=cols)
        wrt = list(_REYNOLDS_INPUTS) + (["speed_of_sound"] if self._mach else [])
        if not self._spanwise:
            for name in _POINT.values():
                self.declare_partials(name, wrt, rows=rows, cols=cols)
            return
        for name in _POINT.values():
            self.declare_partials(f"{name}_ref", wrt + ["ref_radius_ratio"], rows=rows, cols=cols)
            self.declare_partials(name, "radii", rows=np.arange(nn * nr), cols=np.arange(nn * nr))
            rows_d, cols_d = dist_wrt_node(nn, nr)
            self.declare_partials(name, wrt + ["radius"], rows=rows_d, cols=cols_d)

    def _flow(self, inputs):
        """``W0``, ``Re_ref`` and ``M_ref`` of the reference station, after the domain checks."""
        names = _REYNOLDS_INPUTS + ("speed_of_sound",)
        # One check of all inputs at once (this runs for every design); the messages name the first failure.
        values = np.real(np.stack([inputs[name] for name in names]))
        if not np.isfinite(values).all():
            for row, name in enumerate(names):
                bad = ~np.isfinite(values[row])
                if np.any(bad):
                    node = int(np.flatnonzero(bad)[0])
                    raise om.AnalysisError(f"{self.msginfo}: {name} must be finite for the reference Reynolds "
                                           f"number, got {float(values[row, node])!r} at node {node}")
        v_x = inputs["v_axial"]
        v_t = inputs["v_theta_ref"]
        speed = np.sqrt(v_x ** 2 + v_t ** 2)
        if not (np.real(speed) > 0.0).all():
            raise om.AnalysisError(
                f"{self.msginfo}: the reference station has no inflow (v_axial = 0 and rpm = 0); "
                "give a positive rotor speed")
        if not (values[2:] > 0.0).all():
            for row, name in enumerate(names):
                if row >= 2 and not np.all(values[row] > 0.0):
                    raise om.AnalysisError(f"{self.msginfo}: {name} must be positive, got {values[row]}")
        return speed, inputs["rho"] * speed * inputs["ref_chord"] / inputs["mu"], speed / inputs["speed_of_sound"]

    def _max_lift_to_drag(self, reynolds, mach, inputs):
        """The point at the reference station (and, spanwise, column 0, then one column per station)."""
        kwargs = {}
        if self._mach:
            kwargs["mach"] = mach
        if self._spanwise:
            fractions = np.concatenate([inputs["ref_radius_ratio"][:, None],
                                        inputs["radii"] / inputs["radius"][:, None]], axis=1)
            reynolds = reynolds[:, None]
            kwargs = {name: value[:, None] for name, value in kwargs.items()}
            kwargs["radial_fraction"] = fractions
        # compute_partials reuses the point compute found at the same (real) arguments.
        key = tuple(np.real(x).tobytes() for x in (reynolds, *kwargs.values()))
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        try:
            if kwargs:
                point = self._polar.max_lift_to_drag(reynolds, **kwargs)
            else:
                # Derivatives on first use (compute_partials): a run without them skips one polar call.
                point = max_lift_to_drag_tabulated(self._polar, reynolds, derivatives=False)
        except ValueError as err:
            raise om.AnalysisError(f"{self.msginfo}: no maximum-L/D point at the reference "
                                   f"Reynolds number: {err}") from err
        self._last = (key, point)
        return point

    def compute(self, inputs, outputs):
        _, reynolds, mach = self._flow(inputs)
        self._last = None
        point = self._max_lift_to_drag(reynolds, mach, inputs)
        outputs["reynolds_ref"] = reynolds
        outputs["mach_ref"] = mach
        for field, name in _POINT.items():
            value = getattr(point, field)
            if self._spanwise:
                outputs[f"{name}_ref"] = value[:, 0]
                outputs[name] = value[:, 1:]
            else:
                outputs[name] = value

    def compute_partials(self, inputs, partials):
        speed, reynolds, mach = self._flow(inputs)
        point = self._max_lift_to_drag(reynolds, mach, inputs)
        dre = {
            "v_axial": reynolds * inputs["v_axial"] / speed ** 2,
            "v_theta_ref": reynolds * inputs["v_theta_ref"] / speed ** 2,
            "ref_chord": reynolds / inputs["ref_chord"],
            "rho": reynolds / inputs["rho"],
            "mu": -reynolds / inputs["mu"],
        }
        dmach = {
            "v_axial": inputs["v_axial"] / (speed * inputs["speed_of_sound"]),
            "v_theta_ref": inputs["v_theta_ref"] / (speed * inputs["speed_of_sound"]),
            "speed_of_sound": -mach / inputs["speed_of_sound"],
        }
        for name, d in dre.items():
            partials["reynolds_ref", name] = d
        for name, d in dmach.items():
            partials["mach_ref", name] = d
        if not self._spanwise:
            for field, out in _POINT.items():
                for name, d in dre.items():
                    partials[out, name] = getattr(point, f"d{field}_dre") * d
                if self._mach:
                    for name, d in dmach.items():
                        value = getattr(point, f"d{field}_dmach") * d
                        partials[out, name] = partials[out, name] + value if name in dre else value
            return
        radius = inputs["radius"][:, None]
        for field, out in _POINT.items():
            d_re, d_x = getattr(point, f"d{field}_dre"), getattr(point, f"d{field}_dradial_fraction")
            d_mach = getattr(point, f"d{field}_dmach") if self._mach else None
            for name in set(dre) | (set(dmach) if self._mach else set()):
                d = d_re * dre[name][:, None] if name in dre else 0.0
                if self._mach and name in dmach:
                    d = d + d_mach * dmach[name][:, None]
                partials[f"{out}_ref", name] = d[:, 0]
                partials[out, name] = d[:, 1:].ravel()
            partials[f"{out}_ref", "ref_radius_ratio"] = d_x[:, 0]
            # r/R = radii / R at each station.
            partials[out, "radii"] = (d_x[:, 1:] / radius).ravel()
            partials[out, "radius"] = (-d_x[:, 1:] * inputs["radii"] / radius ** 2).ravel()


#: Fields of the max-L/D point -> output names.
_POINT = {"alpha": "alpha_star", "cl": "cl_star", "cd": "cd_star"}
_REYNOLDS_INPUTS = ("v_axial", "v_theta_ref", "ref_chord", "rho", "mu")
_MACH_INPUTS = ("v_axial", "v_theta_ref", "speed_of_sound")
