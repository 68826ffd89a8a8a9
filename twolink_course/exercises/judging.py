"""Judging one answer against its part's specification: right, a named mistake, or the size of the miss.

:func:`judge` reads the learner's value as the part's kind asks (any
equivalent form: a list, a tuple, an array, numpy or sympy numbers; angles up
to whole turns), compares it with the expected value within the part's
tolerance, then with each typical mistake the part registers (the first that
matches gives its diagnosis in words), and otherwise says which quantity
misses, in which direction and by how much, in the part's unit.  It never
prints a bare tolerance.

Every comparison goes through :func:`agrees`: a nan or an infinity is never
within a tolerance of a finite value (so never right unless the part's
expected value is that nan or infinity), and anything that is not a number is
refused with what was expected.  A value that equals the expected one rounded
(where the part asks for full precision) is told it looks rounded.

Examples
--------
>>> from twolink_course.exercises.spec import Mistake, PartSpec
>>> part = PartSpec("tau", "torques", "vector", expected=[10.0, -4.0], shape=(2,),
...             unit="N m", components=("tau1", "tau2"),
...             mistakes=(Mistake([-10.0, 4.0], "the sign is reversed"),))
>>> judge(part, (10.0, -4.0))
Verdict(right=True, message='')
>>> judge(part, [-10, 4]).message
'the sign is reversed'
>>> judge(part, [12.5, -4.0]).message
'tau1 is 2.5 N m too large'
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import numbers as abstract_numbers
from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from twolink.arm import TwoLinkArm
from twolink.conventions import wrap_angle

from ..display import significant
from . import forbidden
from .spec import Case, PartSpec

__all__ = [
    "Verdict",
    "Unusable",
    "agrees",
    "judge",
    "judge_value",
    "judge_function",
    "read_answer",
]


class Verdict(NamedTuple):
    """Whether an answer is right, and if not, what is wrong with it, in words."""

    right: bool
    message: str


class Unusable(Exception):
    """An answer of the wrong type or shape: the message says what was expected."""


_KIND_WORDS = {
    "number": "one number",
    "vector": "numbers",
    "matrix": "a matrix of numbers",
    "angles": "angles in radians",
}


def _in_unit(part: PartSpec) -> str:
    return f" in {part.unit}" if part.unit else ""


def _float(value: Any, part: PartSpec) -> float:
    """One element as a float: Python, numpy and sympy real numbers; nothing else."""
    if isinstance(value, (bool, np.bool_)):
        raise Unusable(f"expected a number{_in_unit(part)}, got {value!r} (a bool)")
    if isinstance(value, abstract_numbers.Real):
        return float(value)
    if isinstance(value, abstract_numbers.Complex) or np.iscomplexobj(value):
        number = complex(value)
        if abs(number.imag) > 1e-9 * max(1.0, abs(number.real)):
            raise Unusable("expected real numbers, got a complex one")
        return number.real
    if getattr(value, "is_number", False):  # a sympy number: sqrt(2), pi/4, Float
        try:
            number = complex(value)
        except (TypeError, ValueError):
            raise Unusable(f"could not evaluate {value} to a number") from None
        if abs(number.imag) > 1e-9 * max(1.0, abs(number.real)):
            raise Unusable(f"expected real numbers, got {value} (complex)")
        return number.real
    if getattr(value, "free_symbols", None):
        names = ", ".join(sorted(str(s) for s in value.free_symbols))
        raise Unusable(
            f"expected a number{_in_unit(part)}, got an expression in {names}: "
            "substitute the values (.subs) first"
        )
    raise Unusable(
        f"expected {_KIND_WORDS.get(part.kind, 'numbers')}{_in_unit(part)}, "
        f"got a {type(value).__name__}"
    )


def _array(answer: Any, part: PartSpec) -> NDArray[np.float64]:
    """The answer as a float array of the part's shape (size-one axes may differ)."""
    if isinstance(answer, (str, bytes, Mapping, set)) or callable(answer):
        raise Unusable(
            f"expected {_KIND_WORDS.get(part.kind, 'numbers')}{_in_unit(part)}, "
            f"got a {type(answer).__name__}"
        )
    if hasattr(answer, "tolist") and not isinstance(answer, np.ndarray):
        answer = answer.tolist()  # a sympy Matrix
    try:
        raw = np.array(answer, dtype=object)
    except Exception as error:  # ragged lists and the like
        raise Unusable(
            f"could not read your numbers ({type(error).__name__})"
        ) from None
    if any(isinstance(v, (list, tuple, np.ndarray)) for v in raw.ravel()):
        raise Unusable("could not read your numbers: its rows have different lengths")
    values = np.array([_float(v, part) for v in raw.ravel()], dtype=float).reshape(
        raw.shape
    )
    shape = tuple(part.shape)
    if values.shape != shape:
        if values.size == math.prod(shape) and values.squeeze().shape == tuple(
            n for n in shape if n != 1
        ):
            values = values.reshape(shape)
        else:
            count = math.prod(shape)
            raise Unusable(
                f"expected {count} number{'s' if count != 1 else ''} (shape {shape})"
                f"{_in_unit(part)}, got shape {values.shape}"
            )
    return values


def read_answer(part: PartSpec, answer: Any) -> Any:
    """The answer in the form the part compares: a float, a float array, a bool or a str.

    Raises :class:`Unusable` with what was expected.

    >>> from twolink_course.exercises.spec import PartSpec
    >>> read_answer(PartSpec("ok", "reachable", "bool", expected=True), 0)
    Traceback (most recent call last):
    ...
    twolink_course.exercises.judging.Unusable: a yes/no answer is True or False; got 0 (a int)
    """
    if part.kind == "bool":
        if isinstance(answer, (bool, np.bool_)):
            return bool(answer)
        if (
            isinstance(answer, np.ndarray)
            and answer.shape == ()
            and answer.dtype == bool
        ):
            return bool(answer)
        raise Unusable(
            f"a yes/no answer is True or False; got {answer!r} (a {type(answer).__name__})"
        )
    if part.kind == "text":
        if not isinstance(answer, str):
            raise Unusable(f"expected a str, got a {type(answer).__name__}")
        return answer.strip()
    if part.kind == "number":
        if isinstance(answer, (list, tuple, np.ndarray)) or hasattr(answer, "tolist"):
            return float(_array(answer, dataclasses.replace(part, shape=())))
        return _float(answer, part)
    return _array(answer, part)


def agrees(
    value: Any, target: Any, allowed: Any, *, angles: bool = False
) -> NDArray[np.bool_]:
    """Whether each number of ``value`` is within ``allowed`` of ``target`` (elementwise).

    The one comparison of every judged number.  A nan or an infinity agrees
    only with the same nan or infinity (so never with a finite target, however
    large the tolerance); ``angles``: equal up to whole turns.

    >>> agrees([1.0, np.nan, np.inf], [1.0 + 1e-12, 2.0, 3.0], 1e-9).tolist()
    [True, False, False]
    >>> agrees(np.inf, np.inf, 0.0).tolist(), agrees(2 * np.pi, 0.0, 1e-9, angles=True).tolist()
    (True, True)
    """
    value = np.asarray(value, dtype=float)
    target = np.asarray(target, dtype=float)
    finite = np.isfinite(value) & np.isfinite(target)
    difference = np.where(finite, value - np.where(finite, target, 0.0), 0.0)
    if angles:
        difference = np.asarray(wrap_angle(difference))
    close = finite & (np.abs(difference) <= np.asarray(allowed, dtype=float))
    same = ~np.isfinite(target) & (
        (value == target) | (np.isnan(value) & np.isnan(target))
    )
    return np.asarray(close | same)


def _misses(part: PartSpec, value: Any, target: Any) -> NDArray[np.float64] | bool:
    """``value - target`` where they do not agree (0 elsewhere), or whether bool/text differ."""
    if part.kind in ("bool", "text"):
        return bool(value != target)
    expected = np.asarray(target, dtype=float)
    given = np.asarray(value, dtype=float)
    allowed = np.vectorize(part.tolerance.allowed, otypes=[float])(
        np.where(np.isfinite(expected), expected, 0.0)
    )
    agreed = agrees(given, expected, allowed, angles=part.kind == "angles")
    with np.errstate(invalid="ignore"):
        difference = given - expected
    if part.kind == "angles":
        finite = np.isfinite(difference)
        difference = np.where(
            finite, wrap_angle(np.where(finite, difference, 0.0)), difference
        )
    return np.where(agreed, 0.0, difference)


def _matches(part: PartSpec, value: Any, target: Any) -> bool:
    miss = _misses(part, value, target)
    return not miss if isinstance(miss, bool) else not np.any(miss)


def _not_finite(part: PartSpec, value: Any, target: Any) -> str | None:
    """What is wrong with a nan or an infinity where the part expects a finite number, or None."""
    if part.kind not in ("number", "vector", "matrix", "angles"):
        return None
    given = np.asarray(value, dtype=float)
    wrong = ~np.isfinite(given) & np.isfinite(np.asarray(target, dtype=float))
    if not np.any(wrong):
        return None
    what = "nan (not a number)" if np.any(np.isnan(given[wrong])) else "infinite"
    if given.ndim == 0:
        return f"your {part.label} is {what}: compute a finite number"
    return f"your {part.label} contains {'nan (not a number)' if 'nan' in what else 'an infinite number'}: compute finite numbers"


#: The most significant figures a typed number is looked at with (a double holds ~16).
_MOST_FIGURES = 12


def _figures(value: float, expected: float) -> int | None:
    """The fewest significant figures to which ``expected`` rounds to exactly ``value``, or None.

    >>> _figures(1.23, 1.2345678), _figures(1.2345678, 1.2345678), _figures(1.3, 1.2345678)
    (3, 1, None)
    """
    if value == expected:
        return 1
    for figures in range(1, _MOST_FIGURES + 1):
        if float(f"{expected:.{figures}g}") == value:
            return figures
    return None


def _rounding(part: PartSpec, value: Any, target: Any) -> str | None:
    """Why a value that misses looks typed in rounded (every number ``target`` rounded), or None."""
    if part.kind not in ("number", "vector", "matrix"):
        return None
    given = np.ravel(np.asarray(value, dtype=float))
    expected = np.ravel(np.asarray(target, dtype=float))
    if not (np.all(np.isfinite(given)) and np.all(np.isfinite(expected))):
        return None
    figures = [_figures(float(v), float(e)) for v, e in zip(given, expected)]
    if any(found is None for found in figures):
        return None
    most = max(found for found in figures if found is not None)
    asked = part.tolerance.significant
    if asked is None:
        return (
            f"your {part.label} looks rounded (to {most} significant figures): compute "
            "it in code from the exercise's values; this part is compared to full "
            "precision, so a typed number does not do"
        )
    if most < asked:
        return (
            f"your {part.label} is rounded to {most} significant figures; this part "
            f"asks for at least {asked}"
        )
    return None


def _digits(value: float) -> int:
    """Two significant digits, or as many as the integer part has (``120``, not ``1.2e2``)."""
    return max(2, min(6, math.floor(math.log10(value)) + 1)) if value > 0 else 2


def _size(part: PartSpec, amount: float) -> str:
    """A miss's size in the part's unit (angles in degrees), to two significant digits."""
    if part.kind == "angles" or part.unit == "rad":
        degrees = math.degrees(abs(amount))
        return significant(degrees, _digits(degrees), "°")
    if part.unit == "m" and abs(amount) < 0.1:
        return significant(100 * abs(amount), 2, "cm")
    return significant(abs(amount), _digits(abs(amount)), part.unit)


def _name(part: PartSpec, index: tuple[int, ...]) -> str:
    if part.components and len(index) == 1 and index[0] < len(part.components):
        return part.components[index[0]]
    if len(index) == 2:
        return f"entry (row {index[0] + 1}, column {index[1] + 1}) of your {part.label}"
    return (
        f"entry {index[0] + 1} of your {part.label}" if index else f"your {part.label}"
    )


def _describe_miss(part: PartSpec, miss: NDArray[np.float64] | bool) -> str:
    if isinstance(miss, bool):
        return f"this is not the {part.label} asked for"
    if part.components == ("x", "y") and part.unit == "m" and miss.shape == (2,):
        across = (
            ("to the right of" if miss[0] > 0 else "to the left of") if miss[0] else ""
        )
        up = ("above" if miss[1] > 0 else "below") if miss[1] else ""
        parts = [
            f"{_size(part, m)} {where}" for m, where in zip(miss, (across, up)) if m
        ]
        return (
            f"your {part.label} is {_size(part, float(np.hypot(*miss)))} from the right "
            f"point: {' and '.join(parts)} it"
        )
    if miss.ndim == 0:
        return f"your {part.label} is {_size(part, float(miss))} too {'large' if miss > 0 else 'small'}"
    wrong = [index for index in np.ndindex(miss.shape) if miss[index]]
    said = [
        f"{_name(part, index)} is {_size(part, float(miss[index]))} too "
        f"{'large' if miss[index] > 0 else 'small'}"
        for index in wrong[:3]
    ]
    more = f" ({len(wrong) - 3} more entries miss)" if len(wrong) > 3 else ""
    return ", ".join(said[:-1]) + (" and " if len(said) > 1 else "") + said[-1] + more


def judge(part: PartSpec, answer: Any) -> Verdict:
    """Judge ``answer`` for ``part``: right, a typical mistake named, or the miss described.

    For a ``"function"`` part, see :func:`judge_function` (called with the
    part's visible cases).
    """
    if part.kind == "function":
        if not callable(answer):
            return Verdict(
                False, f"expected a function (def ...), got a {type(answer).__name__}"
            )
        return judge_function(part, answer, part.cases)
    try:
        value = read_answer(part, answer)
    except Unusable as error:
        return Verdict(False, str(error))
    return _verdict(part, value, part.expected, part.mistakes)


def _verdict(
    part: PartSpec, value: Any, expected: Any, mistakes: Sequence[Any] = ()
) -> Verdict:
    """``value`` (as read) against ``expected``: right, nan or inf, a mistake, rounded, or the miss."""
    if _matches(part, value, expected):
        return Verdict(True, "")
    message = _not_finite(part, value, expected)
    if message is not None:
        return Verdict(False, message)
    for mistake in mistakes:
        if _matches(part, value, mistake.value):
            return Verdict(False, mistake.diagnosis)
    message = _rounding(part, value, expected)
    if message is not None:
        return Verdict(False, message)
    return Verdict(False, _describe_miss(part, _misses(part, value, expected)))


def judge_value(part: PartSpec, answer: Any, expected: Any) -> Verdict:
    """Judge ``answer`` for ``part`` against another expected value (the part's on other inputs).

    The grader's verdict on inputs the learner never saw: the part's kind,
    shape and tolerance, no typical mistake (they belong to the visible
    inputs), and no value of the inputs in the message.

    >>> from twolink_course.exercises.spec import PartSpec
    >>> part = PartSpec("tau", "torques", "vector", expected=[1.0, 2.0], shape=(2,), unit="N m")
    >>> judge_value(part, [3.0, 4.0], [3.0, 4.0]).right, judge_value(part, [1.0, 2.0], [3.0, 4.0]).right
    (True, False)
    """
    try:
        value = read_answer(part, answer)
    except Unusable as error:
        return Verdict(False, str(error))
    return _verdict(part, value, expected)


def _arguments(case: Case, make_arm: Callable[..., Any]) -> dict[str, Any]:
    arguments = {}
    for name, value in case.arguments.items():
        if isinstance(value, Mapping) and set(value) == {"arm"}:
            arguments[name] = make_arm(**value["arm"])
        elif isinstance(value, list):
            arguments[name] = np.array(value, dtype=float)
        else:
            arguments[name] = value
    return arguments


def _shown(arguments: Mapping[str, Any]) -> str:
    def text(value: Any) -> str:
        if hasattr(value, "l1") and hasattr(value, "l2"):
            return f"TwoLinkArm(l1={value.l1:g}, l2={value.l2:g})"
        if isinstance(value, np.ndarray):
            return "[" + ", ".join(f"{v:.6g}" for v in value.ravel()) + "]"
        return repr(value)

    return ", ".join(f"{name}={text(value)}" for name, value in arguments.items())


def _parameter_problem(
    function: Callable[..., Any], arguments: Mapping[str, Any]
) -> str | None:
    """Why ``function`` cannot be called with ``arguments`` by name (its parameters' names), or None."""
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):  # a builtin without a signature: call it and see
        return None
    try:
        signature.bind(**arguments)
    except TypeError:
        pass
    else:
        return None
    named = [
        parameter.name
        for parameter in signature.parameters.values()
        if parameter.kind
        in (inspect.Parameter.POSITIONAL_OR_KEYWORD, inspect.Parameter.KEYWORD_ONLY)
    ]
    asked = list(arguments)
    said = (
        f"the check calls your function with keyword arguments "
        f"({', '.join(f'{name}=...' for name in asked)})"
    )
    if len(named) == len(asked) and named != asked:
        differing = [
            (mine, theirs) for mine, theirs in zip(named, asked) if mine != theirs
        ]
        renames = " and ".join(f"{mine} to {theirs}" for mine, theirs in differing)
        return f"{said}, but yours names its parameters ({', '.join(named)}): rename {renames}"
    return f"{said}, but yours takes ({', '.join(named) or 'no named parameters'})"


def judge_function(
    part: PartSpec,
    function: Callable[..., Any],
    cases: Sequence[Case],
    *,
    shown: int | None = None,
) -> Verdict:
    """Call ``function`` on each case and judge what it returns as ``part.output``.

    The function is called with the case's arguments by name, with the
    callables of ``part.forbidden`` unavailable
    (:func:`twolink_course.exercises.forbidden.unavailable`): a call of one
    fails the part, saying why.  A typical mistake of a function part is
    recognised when the function returns the mistake's value on the cases it
    was written for (the visible ones, first); otherwise the first case that
    misses is described.  ``shown``: how many cases, from the first, may be
    shown with their arguments (the grader's hidden cases are not: a miss
    there is told without them); all by default.
    """
    if part.output is None:
        raise ValueError(
            f"part {part.name!r} is not a function part (it has no output)"
        )
    shown = len(cases) if shown is None else shown
    returned = []
    first_miss: str | None = None
    for index, case in enumerate(cases):
        arguments = _arguments(case, TwoLinkArm)
        where = (
            f"called with {_shown(arguments)}"
            if index < shown
            else "called with other arguments of the grader's (not shown)"
        )
        problem = _parameter_problem(function, arguments)
        if problem is not None:
            return Verdict(False, problem)
        with forbidden.unavailable(part.forbidden) as called:
            try:
                result = function(**arguments)
            except Exception as error:  # the learner's function may raise anything
                result = error
        if called:
            return Verdict(False, forbidden.reason(called[0]))
        if isinstance(result, Exception):
            detail = f": {result}" if index < shown else ""
            return Verdict(
                False,
                f"your function raised {type(result).__name__}{detail} when {where}",
            )
        try:
            value = read_answer(part.output, result)
        except Unusable as error:
            return Verdict(False, f"{where}, it returned: {error}")
        returned.append(value)
        if first_miss is None:
            verdict = _verdict(part.output, value, case.expected)
            if not verdict.right:
                first_miss = f"{where}, {verdict.message}"
    if first_miss is None:
        return Verdict(True, "")
    for mistake in part.mistakes:
        if len(mistake.value) <= len(returned) and all(
            _matches(part.output, value, target)
            for value, target in zip(returned, mistake.value)
        ):
            return Verdict(False, mistake.diagnosis)
    return Verdict(False, first_miss)
