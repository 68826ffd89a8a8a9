"""The exercise registry's building blocks: parts, exercises and fair comparisons.

An :class:`Exercise` is a list of :class:`Part` objects.  Each part names the
notebook variable that holds the learner's answer and a *judge*: a function
``judge(answer, siblings)`` that returns ``None`` when the answer is right and
a one-line reason when it is not.  ``siblings`` holds the other parts' answers
that are solved (never ``...`` or ``None``), so a judge that needs a sibling
checks that it is usable and otherwise falls back on the reference: an
unsolved part never makes its sibling's check fail.

Expected values are computed by the package from the exercise's data (never
typed), once, on first use.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import lru_cache
from typing import ParamSpec, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import wrap_angle

__all__ = [
    "Part",
    "Exercise",
    "Judge",
    "Wrong",
    "REGISTRY",
    "register",
    "is_unsolved",
    "numbers",
    "reference",
    "close",
    "angles_close",
    "scalar",
    "boolean",
    "matches",
    "usable",
]

_T = TypeVar("_T")
_P = ParamSpec("_P")

#: A part's judge: ``judge(answer, siblings)`` returns ``None`` when ``answer`` is
#: right and the one-line reason when it is not (or raises :class:`Wrong` with it).
#: ``siblings`` maps the other solved parts' variable names to their answers.
Judge = Callable[[object, dict[str, object]], str | None]


class Wrong(Exception):
    """Raised by a judge's helpers with the one-line reason an answer is wrong."""


def is_unsolved(answer: object) -> bool:
    """True for the student edition's stub ``...`` and for ``None``.

    >>> is_unsolved(...), is_unsolved(None), is_unsolved(0.0)
    (True, True, False)
    """
    return answer is ... or answer is None


def reference(function: Callable[[], _T]) -> Callable[[], _T]:
    """Decorator: compute an expected value (a function of no arguments) once, on first use."""
    return lru_cache(maxsize=None)(function)


@dataclass(frozen=True)
class Part:
    """One answer of an exercise.

    Attributes
    ----------
    name : str
        The notebook variable holding the answer, e.g. ``"q_elbow_up"``.
    label : str
        What it is, in the check's message, e.g. ``"elbow-up angles"``.
    judge : Judge
        ``judge(answer, siblings) -> None or str``: ``None`` when right, else the reason.
    hint : str
        Shown after the reason when the answer is wrong.
    """

    name: str
    label: str
    judge: Judge
    hint: str


@dataclass(frozen=True)
class Exercise:
    """An exercise: its number (``"2.1"``), its parts in order and its notebook."""

    number: str
    parts: tuple[Part, ...]
    chapter: str = field(default="")

    def part(self, name: str) -> Part:
        """The part whose answer variable is ``name``."""
        for part in self.parts:
            if part.name == name:
                return part
        raise KeyError(
            f"exercise {self.number} has no part {name!r}; its parts are {[p.name for p in self.parts]}"
        )


REGISTRY: dict[str, Exercise] = {}


def register(number: str, *parts: Part, chapter: str = "") -> Exercise:
    """Add an exercise to the registry (each number once)."""
    if number in REGISTRY:
        raise ValueError(f"exercise {number} is registered twice")
    exercise = Exercise(number, tuple(parts), chapter)
    REGISTRY[number] = exercise
    return exercise


# ---------------------------------------------------------------- comparisons


def numbers(
    answer: object, shape: tuple[int, ...], what: str = "your answer"
) -> NDArray[np.float64]:
    """The answer as a float array of ``shape``; lists, tuples, arrays and numpy scalars all do.

    >>> numbers([1, 2], (2,)).tolist()
    [1.0, 2.0]
    >>> numbers(np.array([[3.0]]), ()).item()
    3.0
    >>> numbers([1, 2, 3], (2,))
    Traceback (most recent call last):
    ...
    twolink.exercises.registry.Wrong: expected 2 numbers (shape (2,)), got shape (3,)
    """
    if isinstance(answer, (str, bytes, dict, set)) or callable(answer):
        raise Wrong(f"expected numbers, got a {type(answer).__name__}")
    try:
        values = np.asarray(answer)
    except Exception as exc:  # ragged lists and the like
        raise Wrong(
            f"expected numbers, could not read them ({type(exc).__name__})"
        ) from None
    if values.dtype == object or values.dtype.kind not in "biufc":
        raise Wrong(f"expected numbers, got {type(answer).__name__} of {values.dtype}")
    if values.dtype.kind == "c":
        if np.any(
            np.abs(values.imag)
            > 1e-9 * max(1.0, float(np.max(np.abs(values.real), initial=0.0)))
        ):
            raise Wrong("expected real numbers, got complex ones")
        values = values.real
    values = values.astype(float)
    size = int(np.prod(shape)) if shape else 1
    if values.shape != tuple(shape):
        if values.size == size and (
            shape == () or values.ndim == 0 or values.squeeze().shape == tuple(shape)
        ):
            values = values.reshape(shape)
        else:
            count = f"{size} number" + ("s" if size != 1 else "")
            raise Wrong(
                f"expected {count} (shape {tuple(shape)}), got shape {values.shape}"
            )
    if not np.all(np.isfinite(values)):
        raise Wrong(f"{what} contains nan or inf")
    return values


def scalar(answer: object, what: str = "your answer") -> float:
    """The answer as one float (a size-one array will do)."""
    return float(numbers(answer, (), what))


def boolean(answer: object) -> bool:
    """The answer as a bool: ``True``/``False`` or numpy's bools, nothing else.

    >>> boolean(np.bool_(True))
    True
    >>> boolean("yes")
    Traceback (most recent call last):
    ...
    twolink.exercises.registry.Wrong: expected True or False, got a str
    """
    if isinstance(answer, (bool, np.bool_)):
        return bool(answer)
    if isinstance(answer, np.ndarray) and answer.shape == () and answer.dtype == bool:
        return bool(answer)
    raise Wrong(f"expected True or False, got a {type(answer).__name__}")


def _off_by(error: float, tolerance: float) -> str:
    return f"off by {error:.3g} (allowed {tolerance:.2g})"


def close(
    values: ArrayLike, expected: ArrayLike, atol: float = 0.0, rtol: float = 0.0
) -> None:
    """Raise :class:`Wrong` unless ``|values - expected| <= atol + rtol |expected|`` everywhere.

    ``values`` and ``expected`` are numbers or arrays that broadcast together.

    >>> close(1.0 + 1e-12, 1.0, atol=1e-9)
    >>> close([1.0, 2.0], [1.0, 2.5], atol=0.1)
    Traceback (most recent call last):
    ...
    twolink.exercises.registry.Wrong: off by 0.5 (allowed 0.1)
    """
    expected = np.asarray(expected, dtype=float)
    error = np.abs(np.asarray(values, dtype=float) - expected)
    allowed = atol + rtol * np.abs(expected)
    if np.all(error <= allowed):
        return
    worst = int(np.argmax(error - allowed))
    raise Wrong(_off_by(float(error.flat[worst]), float(np.ravel(allowed)[worst])))


def angles_close(
    values: ArrayLike, expected: ArrayLike, atol: float, period: float = 2 * np.pi
) -> None:
    """Like :func:`close` for angles: the difference is wrapped, so angles ``period`` apart are equal.

    ``values`` and ``expected`` are angles (numbers or arrays that broadcast
    together) in the unit of ``period`` (``2 pi``: radians, ``360.0``: degrees).

    >>> angles_close(np.array([2 * np.pi + 0.1, -0.2]), [0.1, -0.2], atol=1e-12)
    >>> angles_close(np.array([0.1]), [0.3], atol=1e-3)
    Traceback (most recent call last):
    ...
    twolink.exercises.registry.Wrong: off by 0.2 (allowed 0.001)
    """
    scale = 2 * np.pi / period
    difference = (
        np.abs(
            wrap_angle(
                scale
                * (np.asarray(values, dtype=float) - np.asarray(expected, dtype=float))
            )
        )
        / scale
    )
    if np.all(difference <= atol):
        return
    raise Wrong(_off_by(float(np.max(difference)), atol))


def matches(check: Callable[_P, object], *args: _P.args, **kwargs: _P.kwargs) -> bool:
    """True when ``check(*args, **kwargs)`` raises no :class:`Wrong` (to recognise a typical mistake)."""
    try:
        check(*args, **kwargs)
    except Wrong:
        return False
    return True


def usable(
    siblings: dict[str, object], name: str, convert: Callable[[object], _T]
) -> _T | None:
    """A sibling's answer converted by ``convert``, or ``None`` if it is missing or unusable."""
    if name not in siblings:
        return None
    try:
        return convert(siblings[name])
    except Wrong:
        return None
    except Exception:  # the learner's value may be of any type
        return None
