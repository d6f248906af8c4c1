"""The one set of input checks of the Python API and the ``bild-mdo`` command.

:func:`~bild_mdo.results.design.design_rotor`,
:func:`~bild_mdo.bem.analyze.analyze_rotor`,
:func:`~bild_mdo.results.off_design.off_design_sweep` and the command line
check their arguments here, so the same mistake gives the same message
everywhere.  Every check raises :class:`ValueError` with one line that names
the argument, what it must be (with its units) and what was given; in a batch
it also names the first offending design (or station)::

    radius must be a positive finite number in m, got '1.5'
    radius must be a positive finite number in m, got 0 (design 1)
    num_blades must be an integer >= 1, got True

Strings and booleans are rejected where a number is expected (NumPy would
quietly turn ``"1.5"`` into 1.5 and ``True`` into 1).

This module sits at the bottom of the package: it imports only NumPy.
"""
from __future__ import annotations

import numbers
import os

import numpy as np

__all__ = [
    "real_array", "check", "positive", "non_negative", "in_range", "smaller", "integer", "choice",
    "batch_size", "memory_bound", "format_bytes", "BYTES_PER_NODE_STATION",
]

#: Peak memory of one design or operating point per radial station in a vectorised OpenMDAO run (bytes):
#: measured as the growth of the peak resident set of a BEM sweep (10,000 points x 30 stations: 2.5 kB) and
#: of a BILD batch (10,000 designs x 30 stations: 2.7 kB), rounded up.
BYTES_PER_NODE_STATION = 3000

_NOT_NUMBERS = (str, bytes, bool, np.bool_)


def _describe(requirement, units, hint):
    text = requirement + (f" in {units}" if units not in (None, "-", "") else "")
    return text + (f" ({hint})" if hint else "")


def _has_non_number(value):
    """Whether a (nested) list or tuple holds a string or a boolean."""
    if isinstance(value, _NOT_NUMBERS):
        return True
    if isinstance(value, (list, tuple)):
        return any(_has_non_number(item) for item in value)
    return False


def _where(mask, axes):
    """`` (design i)`` / `` (design i, station j)`` naming the first True entry of ``mask``; '' for a scalar."""
    if mask.ndim == 0:
        return ""
    first = np.unravel_index(int(np.flatnonzero(mask)[0]), mask.shape)
    if axes is None:
        axes = ("design", "station")[:mask.ndim] if mask.ndim <= 2 else tuple(f"axis {k}" for k in range(mask.ndim))
    return " (" + ", ".join(f"{axis} {int(i)}" for axis, i in zip(axes, first)) + ")"


def real_array(name, value, *, units=None, requirement="a finite number", hint=None, ndim=(0, 1), axes=None):
    """``value`` as a float array, after checking that it holds only finite real numbers.

    Parameters
    ----------
    name : str
        Argument name used in the message.
    value : float or array_like
        The argument.
    units : str, optional
        Its units, shown in the message (None or '-' for dimensionless).
    requirement : str
        What the value must be, e.g. ``'a positive finite number'``; used in the message.
    hint : str, optional
        Short explanation appended in parentheses.
    ndim : tuple of int
        Accepted numbers of dimensions (default: a scalar or a 1-D list).
    axes : tuple of str, optional
        Names of the array axes for the message (see :func:`check`).

    Returns
    -------
    ndarray
        Float array of ``value`` (0-d for a scalar).

    Raises
    ------
    ValueError
        For strings, booleans, None, non-numeric or complex values, a wrong
        number of dimensions, NaN or infinity.
    """
    described = _describe(requirement, units, hint)
    if value is None or _has_non_number(value):
        raise ValueError(f"{name} must be {described}, got {value!r}")
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be {described}, got {value!r}") from None
    if raw.dtype.kind not in "iuf" and not (raw.dtype.kind == "O" and not _object_non_number(raw)):
        raise ValueError(f"{name} must be {described}, got {value!r}")
    try:
        arr = raw.astype(float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be {described}, got {value!r}") from None
    if arr.ndim not in ndim:
        shapes = {0: "a scalar", 1: "a 1-D list of values", 2: "a 2-D array"}
        allowed = " or ".join(shapes.get(n, f"a {n}-D array") for n in ndim)
        raise ValueError(f"{name} must be {allowed}, got shape {arr.shape}")
    check(name, arr, ~np.isfinite(arr), requirement, units=units, hint=hint, axes=axes)
    return arr


def _object_non_number(raw):
    return any(isinstance(item, _NOT_NUMBERS) or not isinstance(item, numbers.Real) for item in raw.flat)


def check(name, arr, mask, requirement, *, units=None, hint=None, axes=None):
    """Raise ValueError naming the first entry of ``arr`` where ``mask`` is True.

    Parameters
    ----------
    name : str
        Argument name.
    arr : ndarray
        Its values (any shape).
    mask : array_like of bool
        True where a value is not allowed (broadcastable to ``arr``).
    requirement : str
        What each value must be, e.g. ``'a positive finite number'``.
    units, hint : str, optional
        As in :func:`real_array`.
    axes : tuple of str, optional
        Names of the array axes for the message; default ``('design', 'station')``.
    """
    arr = np.asarray(arr)
    mask = np.broadcast_to(np.asarray(mask, dtype=bool), arr.shape)
    if not np.any(mask):
        return
    bad = arr[mask].flat[0] if arr.ndim else arr[()]
    shown = f"{bad:g}" if isinstance(bad, (numbers.Real, np.floating, np.integer)) else repr(bad)
    raise ValueError(f"{name} must be {_describe(requirement, units, hint)}, got {shown}{_where(mask, axes)}")


def positive(name, value, *, units=None, hint=None, ndim=(0, 1), axes=None):
    """``value`` as a float array after checking that every entry is a finite number > 0."""
    requirement = "a positive finite number"
    arr = real_array(name, value, units=units, requirement=requirement, hint=hint, ndim=ndim, axes=axes)
    check(name, arr, arr <= 0.0, requirement, units=units, hint=hint, axes=axes)
    return arr


def non_negative(name, value, *, units=None, hint=None, ndim=(0, 1), axes=None):
    """``value`` as a float array after checking that every entry is a finite number >= 0."""
    requirement = "a finite number >= 0"
    arr = real_array(name, value, units=units, requirement=requirement, hint=hint, ndim=ndim, axes=axes)
    check(name, arr, arr < 0.0, requirement, units=units, hint=hint, axes=axes)
    return arr


def in_range(name, value, low, high, *, open_low=False, open_high=False, units=None, hint=None, ndim=(0, 1),
             axes=None):
    """``value`` as a float array after checking ``low <= value <= high`` (``<`` where open) for every entry."""
    interval = f"{'(' if open_low else '['}{low:g}, {high:g}{')' if open_high else ']'}"
    # The units go before the interval: "a finite number in m within [0, 11000]".
    requirement = _describe("a finite number", units, None) + f" within {interval}"
    arr = real_array(name, value, requirement=requirement, hint=hint, ndim=ndim, axes=axes)
    below = arr <= low if open_low else arr < low
    above = arr >= high if open_high else arr > high
    check(name, arr, below | above, requirement, hint=hint, axes=axes)
    return arr


def smaller(name, value, other_name, other, *, hint=None, axes=None):
    """Check ``value < other`` entrywise (broadcast), naming both arguments and the first failing pair."""
    value, other = np.broadcast_arrays(np.asarray(value, dtype=float), np.asarray(other, dtype=float))
    mask = value >= other
    if np.any(mask):
        i = np.flatnonzero(mask)[0]
        raise ValueError(f"{name} must be smaller than {other_name}" + (f" ({hint})" if hint else "")
                         + f", got {value.flat[i]:g} >= {other.flat[i]:g}{_where(mask, axes)}")


def integer(name, value, minimum=1):
    """``value`` as an int after checking it is a whole number >= ``minimum``.

    Integral floats (``3.0``, as a command line may give) are accepted;
    booleans, strings and non-integral numbers are not.

    Returns
    -------
    int
    """
    requirement = f"an integer >= {minimum}"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be {requirement}, got {value!r}")
    if not isinstance(value, numbers.Integral) and not (np.isfinite(value) and float(value).is_integer()):
        raise ValueError(f"{name} must be {requirement}, got {value!r}")
    if value < minimum:
        raise ValueError(f"{name} must be {requirement}, got {int(value)}")
    return int(value)


def choice(name, value, choices):
    """``value`` after checking it is one of ``choices`` (same type and equal; ``1`` is not ``True``)."""
    for allowed in choices:
        if type(value) is type(allowed) and value == allowed:
            return value
    raise ValueError(f"{name} must be one of {', '.join(map(str, choices))}, got {value!r}")


def batch_size(lengths):
    """The common length of the batched arguments, from ``{name: length}`` of the 1-D ones (1 if none).

    Raises
    ------
    ValueError
        If the lengths differ or are zero.
    """
    sizes = set(lengths.values())
    if len(sizes) > 1:
        raise ValueError("batch sizes disagree: batched arguments need equal lengths (or are scalars), got "
                         + ", ".join(f"{name}: {n}" for name, n in lengths.items()))
    size = sizes.pop() if sizes else 1
    if size == 0:
        raise ValueError("batch arguments are empty: give at least one value")
    return size


def format_bytes(size):
    """``size`` bytes as a short text with a decimal unit (``'4.3 GB'``)."""
    for unit in ("B", "kB", "MB", "GB", "TB", "PB"):
        if size < 1000.0 or unit == "PB":
            return f"{size:.3g} {unit}"
        size /= 1000.0
    return f"{size:.3g} PB"  # pragma: no cover


def _memory_limit():
    """Half of the physical memory (bytes), or 4 GB where the platform does not tell."""
    try:
        return 0.5 * os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return 4e9


def memory_bound(what, num_nodes, num_radial, *, bytes_per_value=BYTES_PER_NODE_STATION, limit=None, hint=None,
                 at_least=False):
    """Check that a vectorised run of ``num_nodes`` designs or points at ``num_radial`` stations fits in memory.

    Called before the run, so a size that cannot fit stops at once with the estimate instead of
    exhausting the memory.

    Parameters
    ----------
    what : str
        The argument that sets the size, e.g. ``'--advance-ratio N'``; used in the message.
    num_nodes, num_radial : int
        Designs (or operating points) and radial stations.
    bytes_per_value : float
        Estimated peak memory per design and station (default :data:`BYTES_PER_NODE_STATION`).
    limit : float, optional
        Largest estimate allowed (bytes); default half of the physical memory.
    hint : str, optional
        What to do instead, appended to the message.
    at_least : bool
        ``num_radial`` is a lower bound (the station count is not known yet); the message says so.

    Raises
    ------
    ValueError
        If the estimate exceeds ``limit``; the message gives the estimate and the limit.
    """
    source = " (half the memory of this machine)" if limit is None else ""
    limit = _memory_limit() if limit is None else float(limit)
    estimate = float(num_nodes) * float(num_radial) * float(bytes_per_value)
    if estimate > limit:
        raise ValueError(f"{what} = {int(num_nodes)} with {'at least ' if at_least else ''}{int(num_radial)} "
                         f"stations would need about "
                         f"{format_bytes(estimate)} of memory (estimated {format_bytes(bytes_per_value)} per "
                         f"point and station); the limit is {format_bytes(limit)}{source}" + (f": {hint}" if hint else ""))
