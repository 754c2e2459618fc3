"""Validation at the boundary: turn user input into float64 arrays or raise.

Every public function of fcgrasp calls one of these ``check_*`` helpers on its
arguments.  Errors are :class:`~fcgrasp.errors.ArgumentError` (a :class:`ValueError`:
wrong shape, non-finite, out of range) or :class:`~fcgrasp.errors.ArgumentTypeError` (a
:class:`TypeError`: not numbers at all), carrying the argument as their ``field``; the
message names it and quotes the value received, in the manner of pytransform3d's
``check_matrix``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import ArgumentError, ArgumentTypeError
from .tolerances import MAX_MAGNITUDE

if TYPE_CHECKING:       # numpy.typing costs a plan's start-up; annotations only need it
    from numpy.typing import NDArray

    FloatArray = NDArray[np.float64]
    IntArray = NDArray[np.intp]
    BoolArray = NDArray[np.bool_]
else:
    FloatArray = IntArray = BoolArray = np.ndarray


def _short(value: Any, limit: int = 80) -> str:
    text = repr(value)
    text = " ".join(text.split())
    return text if len(text) <= limit else text[: limit - 3] + "..."


def check_array(value: Any, name: str, *, last: int | tuple[int, ...] | None = None,
                min_ndim: int = 0, finite: bool = True) -> FloatArray:
    """Return ``value`` as a float64 array, checking its trailing shape.

    Parameters
    ----------
    value : array_like
        User input.
    name : str
        Argument name used in error messages.
    last : int or tuple of int, optional
        Required size of the last axis (or sizes of the last axes).
    min_ndim : int
        Minimum number of dimensions.
    finite : bool
        Reject NaN and infinity.
    """
    arr = numeric_array(value, name)
    if arr.ndim < min_ndim:
        raise ArgumentError(f"{name} must have at least {min_ndim} dimension(s), "
                            f"got shape {arr.shape}: {_short(value)}", name)
    if last is not None:
        want = (last,) if isinstance(last, int) else tuple(last)
        if arr.ndim < len(want) or arr.shape[arr.ndim - len(want):] != want:
            shape_txt = "(..., " + ", ".join(str(w) for w in want) + ")"
            raise ArgumentError(f"{name} must have shape {shape_txt}, got shape {arr.shape}: "
                                f"{_short(value)}", name)
    # one pass: NaN and infinity also fail the comparison with the documented range
    if finite and not np.all(np.abs(arr) <= MAX_MAGNITUDE):
        if not np.all(np.isfinite(arr)):
            raise ArgumentError(f"{name} must be finite, got {_short(value)}", name)
        raise ArgumentError(f"{name} must have magnitudes at most {MAX_MAGNITUDE:g} (fcgrasp's "
                            f"documented range), got {_short(value)}", name)
    return arr


def _is_number(x: Any) -> bool:
    return (isinstance(x, (int, float, np.integer, np.floating))
            and not isinstance(x, (bool, np.bool_)))


def _holds_bool(value: Any) -> bool:
    """Does a nested list hold a bool (numpy would silently turn it into 0 or 1)?"""
    stack = [value]
    while stack:
        x = stack.pop()
        if isinstance(x, (bool, np.bool_)):
            return True
        if isinstance(x, (list, tuple)):
            stack.extend(x)
    return False


def numeric_array(value: Any, name: str) -> FloatArray:
    """``value`` as float64, refusing strings and booleans (which numpy would convert)."""
    if isinstance(value, (str, bytes)):
        raise ArgumentTypeError(f"{name} must be numeric, got {_short(value)}", name)
    try:
        raw = np.asarray(value)
    except ValueError as exc:       # ragged nesting
        raise ArgumentError(f"{name} must be a regular array of numbers, got "
                            f"{_short(value)}", name) from exc
    if raw.dtype.kind in "USb" or (raw.dtype.kind == "O" and not all(
            _is_number(x) for x in raw.ravel())) or (isinstance(value, (list, tuple))
                                                     and _holds_bool(value)):
        raise ArgumentTypeError(f"{name} must hold numbers (not strings or booleans), got "
                                f"{_short(value)}", name)
    try:
        return np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ArgumentTypeError(f"{name} must be an array of numbers, got {_short(value)}",
                                name) from exc


def check_point(value: Any, name: str = "point") -> FloatArray:
    """A planar point, shape (2,)."""
    arr = check_array(value, name, last=2)
    if arr.ndim != 1:
        raise ArgumentError(f"{name} must have shape (2,), got shape {arr.shape}: "
                            f"{_short(value)}", name)
    return arr


def check_contact_points(points: Any, normals: Any) -> tuple[FloatArray, FloatArray]:
    """Contacts given as points and normals, both (k, 2) with k >= 1: the points and the
    normals made unit vectors."""
    p = check_array(points, "points", last=2)
    n = check_array(normals, "normals", last=2)
    if p.ndim != 2 or p.shape != n.shape or not len(p):
        raise ArgumentError(f"points and normals must both be (k, 2) arrays, got shapes "
                            f"{p.shape} and {n.shape}", "points")
    norm = np.hypot(n[:, 0], n[:, 1])
    if np.any(norm <= 0) or not np.all(np.isfinite(norm)) or not np.all(np.isfinite(p)):
        raise ArgumentError(f"normals must be non-zero and points finite, got "
                            f"{_short(normals)}", "normals")
    return p, n / norm[:, None]


def check_direction(value: Any, name: str = "normal") -> FloatArray:
    """A non-zero planar direction, returned as a unit vector of shape (2,)."""
    arr = check_point(value, name)
    norm = float(np.hypot(arr[0], arr[1]))
    if norm == 0.0 or not np.isfinite(norm):
        raise ArgumentError(f"{name} must be a non-zero vector, got {_short(value)}", name)
    return arr / norm


def check_directions(value: Any, name: str = "normals") -> FloatArray:
    """An array of non-zero planar directions (..., 2), returned normalised."""
    arr = check_array(value, name, last=2, min_ndim=1)
    norm = np.hypot(arr[..., 0], arr[..., 1])
    if np.any(norm == 0.0):
        bad = np.argwhere(norm == 0.0)[0]
        raise ArgumentError(f"{name} must be non-zero vectors, got a zero vector at index "
                            f"{tuple(int(i) for i in bad)}", name)
    return arr / norm[..., None]


def check_mu(value: Any, name: str = "mu") -> FloatArray:
    """Coulomb friction coefficients: finite and >= 0 (any shape)."""
    if isinstance(value, bool):
        raise ArgumentTypeError(f"{name} must be a number, got {_short(value)}", name)
    arr = check_array(value, name)
    if np.any(arr < 0):
        raise ArgumentError(f"{name} must be >= 0, got {_short(value)}", name)
    return arr


def check_mu_scalar(value: Any, name: str = "mu") -> float:
    """One Coulomb friction coefficient: a finite number >= 0 (a
    :class:`~fcgrasp.core.values.Friction`, checked when made, gives its ``mu``)."""
    if type(value) in (float, int) and 0 <= value < math.inf:   # the common case, quick
        return float(value)
    if getattr(value, "CHECKED", None) == "mu":     # a Friction: checked when made
        return float(value)
    if not _is_number(value) and not (isinstance(value, np.ndarray) and value.ndim == 0
                                      and _is_number(value.item())):
        raise ArgumentTypeError(f"{name} must be a single number, got {_short(value)}", name)
    return float(check_mu(value, name))


def check_int(value: Any, name: str, *, choices: tuple[int, ...] | None = None,
              minimum: int | None = None) -> int:
    """An integer (not a bool, not a float), optionally one of ``choices`` or >= minimum."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ArgumentTypeError(f"{name} must be an integer, got {_short(value)}", name)
    v = int(value)
    if choices is not None and v not in choices:
        raise ArgumentError(f"{name} must be one of {', '.join(map(str, choices))}, got {v}", name)
    if minimum is not None and v < minimum:
        raise ArgumentError(f"{name} must be >= {minimum}, got {v}", name)
    return v


def check_scalar(value: Any, name: str, *, positive: bool = False,
                 nonnegative: bool = False) -> float:
    """A finite real scalar, optionally > 0 or >= 0."""
    if type(value) in (float, int) and -math.inf < value < math.inf:   # quick, as below
        x = float(value)
        if (positive and not x > 0) or (nonnegative and not x >= 0):
            raise ArgumentError(f"{name} must be {'> 0' if positive else '>= 0'}, got "
                                f"{_short(value)}", name)
        return x
    if isinstance(value, (bool, np.bool_, str, bytes)) or (not np.isscalar(value)
                                                            and np.ndim(value) != 0):
        raise ArgumentTypeError(f"{name} must be a real number, got {_short(value)}", name)
    try:
        x = float(value)
    except (TypeError, ValueError) as exc:
        raise ArgumentTypeError(f"{name} must be a real number, got {_short(value)}", name) from exc
    if not np.isfinite(x):
        raise ArgumentError(f"{name} must be finite, got {_short(value)}", name)
    if positive and not x > 0:
        raise ArgumentError(f"{name} must be > 0, got {_short(value)}", name)
    if nonnegative and not x >= 0:
        raise ArgumentError(f"{name} must be >= 0, got {_short(value)}", name)
    return x


def check_tol(value: Any, name: str = "tol") -> float:
    """A tolerance: finite and >= 0."""
    return check_scalar(value, name, nonnegative=True)


def check_margin(value: Any, name: str = "margin") -> float:
    """A safety margin in degrees, in ``[0, 90)``: the one check of every margin (a
    :class:`~fcgrasp.core.values.Margin`, checked when made, gives its degrees)."""
    if getattr(value, "CHECKED", None) == "margin":     # a Margin: checked when made
        return float(value)
    m = check_scalar(value, name, nonnegative=True)
    if m >= 90.0:
        raise ArgumentError(f"{name} is an angle in degrees below 90, got {value!r}", name)
    return m
