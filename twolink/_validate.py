"""Input checks shared by the package (private).

Every public function funnels its array arguments through these helpers so
that bad input fails early with a message that says what was wrong and what
is allowed, instead of propagating NaN.  So their inputs are typed
``object``: they take anything and refuse what is not allowed.
"""

from __future__ import annotations

import math
from itertools import chain
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
from numpy.typing import NDArray

from .errors import InputTypeError

if TYPE_CHECKING:
    from .arm import TwoLinkArm

_Arm = TypeVar("_Arm")

#: Python and numpy scalar types accepted where a real number belongs (bool excluded).
_REAL_TYPES = (int, float, np.integer, np.floating)

#: Scalar types refused although they are among the above: booleans, and numpy's time
#: deltas (a subclass of its integers: ``np.timedelta64(1, "s")`` would pass for 1).
_NOT_NUMBERS = (bool, np.bool_, np.timedelta64)


def is_real_number(value: object) -> bool:
    """Whether ``value`` is one real number: a Python or numpy int or float, not a bool or a time delta.

    Examples
    --------
    >>> is_real_number(2), is_real_number(np.float32(0.5)), is_real_number(True), is_real_number(np.timedelta64(1, "s"))
    (True, True, False, False)
    """
    return isinstance(value, _REAL_TYPES) and not isinstance(value, _NOT_NUMBERS)


__all__ = [
    "finite_result",
    "InputTypeError",
    "real_array",
    "require_arm",
    "as_pairs",
    "pair_floats",
    "state_floats",
    "as_finite_scalar",
    "is_real_number",
    "as_time",
    "as_time_span",
    "TIME_RANGE",
    "as_length",
    "LENGTH_RANGE",
    "require_callable",
    "as_count",
    "as_flag",
    "broadcast_start",
    "broadcast_shape",
    "frozen_array",
    "torque_floats",
]

#: Scalar types the one-input fast path converts itself (``float`` is tested
#: first); anything else (bool, complex, str, None, Fraction, ...) is left to
#: :func:`as_pairs`, whose message then names the argument.
_FAST_SCALARS = frozenset((int, np.float64, np.float32, np.int64, np.int32))
_FLOAT64 = np.dtype(np.float64)


def as_pairs(values: object, name: str) -> NDArray[np.float64]:
    """Return ``values`` as a float array of shape ``(..., 2)``.

    Parameters
    ----------
    values : object
        Anything; accepted when numpy can turn it into real floats with a
        last axis of length 2 (array_like), refused otherwise.
    name : str
        The argument's name, used in error messages.

    Returns
    -------
    numpy.ndarray
        A float64 array (not copied when it already is one).

    Raises
    ------
    ValueError
        If the last axis is not of length 2 or any entry is NaN or infinite.

    Examples
    --------
    >>> as_pairs([1, 2], "q")
    array([1., 2.])
    >>> as_pairs([1, 2, 3], "q")
    Traceback (most recent call last):
    ...
    ValueError: q must have shape (..., 2) (two joint angles or an x, y pair per row); got shape (3,)
    """
    array = real_array(values, name, "real numbers of shape (..., 2)")
    if array.ndim == 0 or array.shape[-1] != 2:
        raise ValueError(
            f"{name} must have shape (..., 2) (two joint angles or an x, y pair per row); "
            f"got shape {array.shape}"
        )
    if not np.isfinite(array).all():
        bad = np.argwhere(~np.isfinite(array))[0]
        raise ValueError(
            f"{name} must be finite numbers; entry {tuple(int(i) for i in bad)} "
            f"is {array[tuple(bad)]}"
        )
    return array


def plain_state(
    q: object, qd: object
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """``(q, qd)`` unchanged when both are float64 arrays of shape ``(2,)`` with finite entries, else ``None``.

    One state as :func:`twolink.simulate` passes it to a torque function:
    such a pair needs no conversion or check, and a function of one state
    may use it as it is.  For anything else the caller converts and checks
    the values with its usual messages.

    Examples
    --------
    >>> plain_state(np.array([0.1, 0.2]), np.zeros(2))
    (array([0.1, 0.2]), array([0., 0.]))
    >>> plain_state([0.1, 0.2], np.zeros(2)), plain_state(np.array([np.nan, 0.0]), np.zeros(2))
    (None, None)
    """
    if not (
        type(q) is np.ndarray
        and type(qd) is np.ndarray
        and q.shape == (2,)
        and qd.shape == (2,)
        and q.dtype == np.float64
        and qd.dtype == np.float64
    ):
        return None
    q1, q2 = q.tolist()
    qd1, qd2 = qd.tolist()
    if (
        math.isfinite(q1)
        and math.isfinite(q2)
        and math.isfinite(qd1)
        and math.isfinite(qd2)
    ):
        return q, qd
    return None


def pair_floats(values: object) -> tuple[float, float] | None:
    """Two finite Python floats when ``values`` is plainly one pair of real numbers, else ``None``.

    The fast path of the public functions for one configuration, target or
    state: a list or tuple of two floats or ints (or numpy float/int
    scalars), or a float64 array of shape ``(2,)``, is read without array
    machinery.  Everything else returns ``None`` (other shapes or types,
    booleans, complex numbers, strings, ``None``, NaN, infinity, an int too
    large for a float) and the caller takes its vectorised path, whose
    :func:`as_pairs` accepts or refuses it with the package's messages.  So
    the fast path accepts a subset of what :func:`as_pairs` accepts, with the
    same values, and refuses nothing itself.

    Examples
    --------
    >>> pair_floats([1, 2.5])
    (1.0, 2.5)
    >>> pair_floats(np.array([0.5, 1.0]))
    (0.5, 1.0)
    >>> pair_floats([True, 1.0]) is None, pair_floats([float("nan"), 1.0]) is None
    (True, True)
    """
    # the exact type tests below (faster than isinstance) decide what ``values`` is;
    # mypy does not narrow on them, so the checked value is read through ``items``
    items: Any = values
    kind = type(items)
    if kind is list or kind is tuple:
        if len(items) != 2:
            return None
        first, second = items
        try:
            if type(first) is not float:
                if type(first) not in _FAST_SCALARS:
                    return None
                first = float(first)
            if type(second) is not float:
                if type(second) not in _FAST_SCALARS:
                    return None
                second = float(second)
        except OverflowError:  # an int beyond the float range
            return None
    elif kind is np.ndarray:
        if items.shape != (2,) or items.dtype is not _FLOAT64:
            return None
        first, second = items.tolist()
    else:
        return None
    if math.isfinite(first) and math.isfinite(second):
        return first, second
    return None


def state_floats(
    first: object, second: object, third: object
) -> tuple[float, float, float, float, float, float] | None:
    """Six finite Python floats when each argument is plainly one pair of real numbers, else ``None``.

    The fast path of the one-state dynamics (``q``, ``qd`` and ``qdd`` or
    ``tau``), in one step for the usual calls: three lists (or tuples) of
    two floats, or three float64 arrays of shape ``(2,)``.  Other mixes go
    through :func:`pair_floats` pair by pair; anything it refuses returns
    ``None``, for the caller's vectorised path and its messages.

    Examples
    --------
    >>> state_floats([0.1, 0.2], [0.0, 1.0], [2.0, 3.0])
    (0.1, 0.2, 0.0, 1.0, 2.0, 3.0)
    >>> state_floats(np.zeros(2), [0.0, 1.0], (2, 3))
    (0.0, 0.0, 0.0, 1.0, 2.0, 3.0)
    >>> state_floats([0.1, True], [0.0, 1.0], [2.0, 3.0]) is None
    True
    """
    kind: Any = type(first)
    items: Any = (first, second, third)
    if kind is type(second) and kind is type(third):
        if kind is list or kind is tuple:
            if len(first) == len(second) == len(third) == 2:  # type: ignore[arg-type]
                (a, b), (c, d), (e, f) = items
                if (
                    type(a) is float
                    and type(b) is float
                    and type(c) is float
                    and type(d) is float
                    and type(e) is float
                    and type(f) is float
                    and math.isfinite(a + b + c + d + e + f)
                ):
                    return a, b, c, d, e, f
        elif kind is np.ndarray:
            arrays: tuple[NDArray[Any], ...] = items
            if all(array.shape == (2,) and array.dtype is _FLOAT64 for array in arrays):
                (a, b), (c, d), (e, f) = (array.tolist() for array in arrays)
                if math.isfinite(a + b + c + d + e + f):
                    return a, b, c, d, e, f
    pairs = [pair_floats(item) for item in items]
    if None in pairs:
        return None
    (a, b), (c, d), (e, f) = pairs  # type: ignore[misc]
    return a, b, c, d, e, f


def as_finite_scalar(
    value: object, name: str, *, minimum: float | None = None, strictly: bool = False
) -> float:
    """Return ``value`` as a finite float, optionally bounded below.

    Parameters
    ----------
    value : float
        The number to check.
    name : str
        The argument's name, used in error messages.
    minimum : float, optional
        Lower bound; ``None`` for no bound.
    strictly : bool
        If true the bound is strict (``value > minimum``).

    Examples
    --------
    >>> as_finite_scalar(2, "l1", minimum=0.0, strictly=True)
    2.0
    >>> as_finite_scalar(0, "l1", minimum=0.0, strictly=True)
    Traceback (most recent call last):
    ...
    ValueError: l1 must be > 0.0; got 0.0
    """
    if is_real_number(value):
        number = float(value)  # type: ignore[arg-type]
    elif type(value) is np.ndarray and value.ndim == 0 and value.dtype.kind in "iuf":
        number = float(value)
    else:
        raise InputTypeError(
            f"{name} must be a real number; got {value!r} ({type(value).__name__})"
        )
    if not math.isfinite(number):
        raise ValueError(f"{name} must be finite; got {number}")
    if minimum is not None:
        if strictly and not number > minimum:
            raise ValueError(f"{name} must be > {minimum}; got {number}")
        if not strictly and not number >= minimum:
            raise ValueError(f"{name} must be >= {minimum}; got {number}")
    return number


#: The durations and end times the package accepts, seconds: within them a time's square,
#: its inverse and the accelerations of a path run over it stay normal float64 numbers
#: (a duration of 1e-308 s would make them overflow; one of 1e300 s has no meaning).
TIME_RANGE = (1e-50, 1e50)


def as_time(t: object, name: str = "t (s)") -> float:
    """A time ``t`` in seconds as a finite float: what a controller or a reference is called with.

    A finite float (Python's or numpy's, as an ODE solver passes it) is
    returned at once (a controller is called thousands of times a run);
    anything else is checked by :func:`as_finite_scalar`, naming ``name``.

    Examples
    --------
    >>> as_time(0.25), as_time(1)
    (0.25, 1.0)
    >>> as_time("now")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: t (s) must be a real number; got 'now' (str)
    """
    if isinstance(t, float) and -math.inf < t < math.inf:
        return float(t)
    return as_finite_scalar(t, name)


def as_time_span(value: object, name: str) -> float:
    """``value`` as a duration in seconds within :data:`TIME_RANGE`, or an error naming ``name``.

    Examples
    --------
    >>> as_time_span(2, "duration (s)")
    2.0
    >>> as_time_span(5e-324, "duration (s)")
    Traceback (most recent call last):
    ...
    ValueError: duration (s) must be in [1e-50, 1e+50]; got 5e-324
    """
    number = as_finite_scalar(value, name)
    if not TIME_RANGE[0] <= number <= TIME_RANGE[1]:
        raise ValueError(
            f"{name} must be in [{TIME_RANGE[0]:g}, {TIME_RANGE[1]:g}]; got {number:g}"
        )
    return number


#: The lengths the package accepts, metres (links, radii): within them every square and product
#: the kinematics and dynamics form stays a normal float64 number.
LENGTH_RANGE = (1e-50, 1e50)


def as_length(value: object, name: str) -> float:
    """``value`` as a length in metres within :data:`LENGTH_RANGE`, or an error naming ``name``.

    Examples
    --------
    >>> as_length(0.5, "radius (m)")
    0.5
    >>> as_length(1e-300, "radius (m)")
    Traceback (most recent call last):
    ...
    ValueError: radius (m) must be in [1e-50, 1e+50]; got 1e-300
    """
    number = as_finite_scalar(value, name)
    if not LENGTH_RANGE[0] <= number <= LENGTH_RANGE[1]:
        raise ValueError(
            f"{name} must be in [{LENGTH_RANGE[0]:g}, {LENGTH_RANGE[1]:g}]; got {number:g}"
        )
    return number


def require_callable(value: object, name: str, what: str) -> Any:
    """``value`` if it is callable, else an :class:`InputTypeError` naming ``name`` and saying ``what`` it must be.

    Examples
    --------
    >>> require_callable(3, "controller", "a callable controller(t, q, qd) -> tau")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: controller must be a callable controller(t, q, qd) -> tau; got 3 (int)
    """
    if not callable(value):
        raise InputTypeError(
            f"{name} must be {what}; got {value!r} ({type(value).__name__})"
        )
    return value


def as_count(
    value: object, name: str, *, minimum: int = 1, maximum: int | None = None
) -> int:
    """Return ``value`` as a Python ``int`` at least ``minimum`` (and at most ``maximum``).

    Integers (Python or numpy) and floats with an integral value (``50.0``)
    are accepted; booleans, fractions, strings, ``None``, NaN and infinity
    are refused with a message naming the argument.

    Examples
    --------
    >>> as_count(50, "n", minimum=2)
    50
    >>> as_count(2.5, "n", minimum=2)
    Traceback (most recent call last):
    ...
    ValueError: n must be an integer >= 2; got 2.5
    >>> as_count(True, "n")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: n must be an integer >= 1; got True (bool)
    """
    if not is_real_number(value):
        raise InputTypeError(
            f"{name} must be an integer >= {minimum}; got {value!r} ({type(value).__name__})"
        )
    if isinstance(value, (float, np.floating)) and not (
        math.isfinite(value) and float(value).is_integer()
    ):
        raise ValueError(f"{name} must be an integer >= {minimum}; got {value!r}")
    count = int(value)  # type: ignore[call-overload]
    if count < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}; got {count}")
    if maximum is not None and count > maximum:
        raise ValueError(f"{name} must be an integer <= {maximum}; got {count}")
    return count


def as_flag(value: object, name: str) -> bool:
    """``value`` as a Python ``bool``: only ``True`` or ``False`` (Python or numpy) are accepted.

    A string such as ``"False"`` is truthy and a number's meaning is a
    guess, so both are refused with a message naming the argument.

    Examples
    --------
    >>> as_flag(np.True_, "constrained")
    True
    >>> as_flag("False", "constrained")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: constrained must be True or False; got 'False' (str)
    """
    if not isinstance(value, (bool, np.bool_)):
        raise InputTypeError(
            f"{name} must be True or False; got {value!r} ({type(value).__name__})"
        )
    return bool(value)


def broadcast_start(
    start: object, shape: tuple[int, ...], name: str, against: str = "target p"
) -> NDArray[np.float64]:
    """``start`` (pairs) broadcast to ``shape``, or a message naming both shapes.

    Examples
    --------
    >>> broadcast_start([0.5, 1.0], (3, 2), "q0").shape
    (3, 2)
    >>> broadcast_start([[0.5, 1.0]] * 3, (2, 2), "q0")
    Traceback (most recent call last):
    ...
    ValueError: q0 of shape (3, 2) does not match target p of shape (2, 2): give one start of shape (2,) or one per target, shape (2, 2)
    """
    start = as_pairs(start, name)
    try:
        return np.broadcast_to(start, shape)
    except ValueError:
        raise ValueError(
            f"{name} of shape {start.shape} does not match {against} of shape {shape}: "
            f"give one start of shape (2,) or one per target, shape {shape}"
        ) from None


def broadcast_shape(**arrays: NDArray[np.float64]) -> tuple[int, ...]:
    """The broadcast shape of named ``(..., 2)`` arrays, or a message naming each and its shape.

    Examples
    --------
    >>> broadcast_shape(q=np.zeros((3, 2)), qd=np.zeros(2))
    (3, 2)
    >>> broadcast_shape(q=np.zeros((3, 2)), qd=np.zeros((4, 2)))
    Traceback (most recent call last):
    ...
    ValueError: q of shape (3, 2) and qd of shape (4, 2) do not broadcast together: leading axes must be equal or 1
    """
    try:
        return np.broadcast_shapes(*(array.shape for array in arrays.values()))
    except ValueError:
        names = [f"{name} of shape {array.shape}" for name, array in arrays.items()]
        listed = ", ".join(names[:-1]) + f" and {names[-1]}"
        raise ValueError(
            f"{listed} do not broadcast together: leading axes must be equal or 1"
        ) from None


_BAD_ELEMENT = (bool, np.bool_, complex, np.complexfloating, str, bytes, type(None))
_PLAIN_NUMBERS = frozenset((float, int))
_SEQUENCES = frozenset((list, tuple))


def _masked_message(name: str, what: str) -> str:
    return (
        f"{name} must be {what}; got a masked array (numpy.ma), whose masked entries would be read as the "
        "values hidden under the mask: decide what they mean first and pass a plain array "
        "(values.filled(...) or values.compressed())"
    )


def _refuse_bad_entries(
    items: Any, values: object, name: str, what: str, where: tuple[int, ...] = ()
) -> None:
    """Raise :class:`InputTypeError` for the first entry of a (nested) list or tuple numpy would coerce silently.

    Booleans (read as 0.0 / 1.0), complex numbers, strings, bytes, ``None``,
    boolean arrays and masked arrays are refused at any depth, naming the
    entry's index; numpy turns a boolean among floats into a float before it
    can be seen in the array.
    """
    for index, element in enumerate(items):
        element_type = type(element)
        if element_type is float or element_type is int:
            continue
        if element_type is list or element_type is tuple:
            _refuse_bad_entries(element, values, name, what, (*where, index))
        elif isinstance(element, np.ma.MaskedArray):
            raise InputTypeError(_masked_message(name, what))
        elif isinstance(element, _BAD_ELEMENT) or (
            element_type is np.ndarray and element.dtype.kind == "b"
        ):
            kind = "bool array" if element_type is np.ndarray else element_type.__name__
            raise InputTypeError(
                f"{name} must be {what}; got {values!r} (entry {(*where, index)} is {kind})"
            )


def real_array(
    values: object, name: str, what: str = "real numbers"
) -> NDArray[np.float64]:
    """``values`` as a float64 array, refusing anything that is not real numbers.

    Booleans, complex numbers (whose imaginary part would be dropped),
    strings, bytes, ``None`` and other objects raise :class:`InputTypeError`
    naming the argument, also inside nested lists (numpy would coerce
    several of them silently: ``[[0.3, True]]`` becomes ``[[0.3, 1.0]]``).
    So do masked arrays (:mod:`numpy.ma`), whose masked entries numpy would
    read as the values hidden under the mask.

    Examples
    --------
    >>> real_array([1, 2.5], "q")
    array([1. , 2.5])
    >>> real_array([1.0, 2j], "q")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: q must be real numbers; got [1.0, 2j] (entry (1,) is complex)
    >>> real_array([[0.3, True]], "q")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: q must be real numbers; got [[0.3, True]] (entry (0, 1) is bool)
    >>> real_array(np.ma.masked_array([0.3, 99.0], mask=[False, True]), "q0")
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: q0 must be real numbers; got a masked array (numpy.ma), whose masked entries would be read as the values hidden under the mask: decide what they mean first and pass a plain array (values.filled(...) or values.compressed())
    """
    # the exact type tests below (faster than isinstance) decide what ``values`` is;
    # mypy does not narrow on them, so the checked value is read through ``items``
    items: Any = values
    kind = type(items)
    array: NDArray[Any]
    if kind is np.ndarray:
        array = items
    else:
        if kind is list or kind is tuple:
            # one or two levels of plain floats and ints (the usual lists) are seen at C speed
            types = set(map(type, items))
            if not types <= _PLAIN_NUMBERS and not (
                types <= _SEQUENCES
                and set(map(type, chain.from_iterable(items))) <= _PLAIN_NUMBERS
            ):
                _refuse_bad_entries(items, values, name, what)
        elif isinstance(values, np.ma.MaskedArray):
            raise InputTypeError(_masked_message(name, what))
        elif isinstance(values, _BAD_ELEMENT):
            raise InputTypeError(
                f"{name} must be {what}; got {values!r} ({type(values).__name__})"
            )
        try:
            array = np.asarray(values)
        except (TypeError, ValueError) as exc:
            raise InputTypeError(f"{name} must be {what}; got {values!r}") from exc
    dtype = array.dtype
    if dtype is _FLOAT64:
        return array
    if dtype.kind not in "iuf":
        raise InputTypeError(f"{name} must be {what}; got {values!r} ({dtype} entries)")
    return array.astype(float)


def require_arm(arm: _Arm, who: str = "arm") -> _Arm:
    """Refuse anything that is not an arm (``None``, numbers, ...) with an error naming ``arm``.

    Examples
    --------
    >>> require_arm(None)
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: arm must be a twolink.TwoLinkArm; got None (NoneType)
    """
    if not (hasattr(arm, "l1") and hasattr(arm, "l2") and hasattr(arm, "inertias")):
        raise InputTypeError(
            f"{who} must be a twolink.TwoLinkArm; got {arm!r} ({type(arm).__name__})"
        )
    return arm


def arm_lengths(arm: TwoLinkArm) -> tuple[float, float]:
    """``(l1, l2)`` of ``arm``, or the :func:`require_arm` error naming it (free when it is an arm).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> arm_lengths(TwoLinkArm(1.0, 2.0))
    (1.0, 2.0)
    """
    try:
        return arm.l1, arm.l2
    except AttributeError:
        require_arm(arm)
        raise


def finite_result(
    array: NDArray[np.float64], what: str, cause: str
) -> NDArray[np.float64]:
    """``array`` if every entry is finite, else an error saying the result overflows float64.

    Examples
    --------
    >>> finite_result(np.array([1.0, np.inf]), "joint rates qd (rad/s)", "v_tip is too large for this pose")
    Traceback (most recent call last):
    ...
    OverflowError: the joint rates qd (rad/s) overflow float64 (|value| > 1.8e308) at index (1,): v_tip is too large for this pose
    """
    if np.all(np.isfinite(array)):
        return array
    index = tuple(int(i) for i in np.argwhere(~np.isfinite(array))[0])
    raise OverflowError(
        f"the {what} overflow float64 (|value| > 1.8e308) at index {index}: {cause}"
    )


def as_configuration(
    q: object, name: str = "q", what: str = "one configuration", unit: str = "radians"
) -> NDArray[np.float64]:
    """``q`` as a float array of shape ``(2,)``, or a ``ValueError`` naming its shape.

    The one check for functions that work on a single configuration (or a
    single point: ``what="one (x, y) point"``, ``unit="metres"``).

    Examples
    --------
    >>> as_configuration([0.5, 1.0])
    array([0.5, 1. ])
    >>> as_configuration([[0.5, 1.0]], "q_eq")
    Traceback (most recent call last):
    ...
    ValueError: q_eq must be one configuration of shape (2,) (radians); got shape (1, 2)
    """
    values = as_pairs(q, name)
    if values.shape != (2,):
        raise ValueError(
            f"{name} must be {what} of shape (2,) ({unit}); got shape {values.shape}"
        )
    return values


def torque_floats(value: object, t: float) -> tuple[float, float]:
    """A torque callable's result ``torque(t, q, qd)`` as two finite floats, or a ``ValueError`` naming the time.

    The one check of what a torque function returns, for
    :func:`twolink.dynamics.state_derivative`, :func:`twolink.simulate` and
    :func:`twolink.engine.simulate_in_mujoco` (which, past the start, report
    a non-finite torque as the motion blowing up).

    Examples
    --------
    >>> torque_floats([1, 2.5], 0.0)
    (1.0, 2.5)
    >>> torque_floats([1.0, float("nan")], 0.25)
    Traceback (most recent call last):
    ...
    ValueError: torque(t, q, qd) returned non-finite torques [ 1. nan] at t = 0.25
    """
    if type(value) is not np.ndarray and isinstance(value, np.ma.MaskedArray):
        raise ValueError(
            f"torque(t, q, qd) must return two numbers (N m), not a masked array; got {value!r} at t = {t}"
        )
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"torque(t, q, qd) must return two numbers (N m); got {value!r} at t = {t}"
        ) from exc
    if array.shape != (2,):
        raise ValueError(
            f"torque(t, q, qd) must return shape (2,) (N m); got shape {array.shape} at t = {t}"
        )
    tau1, tau2 = array.tolist()
    if not (math.isfinite(tau1) and math.isfinite(tau2)):
        raise ValueError(
            f"torque(t, q, qd) returned non-finite torques {array} at t = {t}"
        )
    return tau1, tau2


def frozen_array(array: object) -> NDArray[np.float64]:
    """A read-only float copy of ``array`` (the arrays of a simulation's result).

    >>> a = frozen_array([1, 2])
    >>> a, a.flags.writeable
    (array([1., 2.]), False)
    """
    frozen = np.array(array, dtype=float)
    frozen.setflags(write=False)
    return frozen
