"""What an exercise part expects, as data: the answer's kind, unit, tolerance, typical mistakes and hints.

A part's specification is written by the course in the repository's
``answers/`` folder (readable, for teachers and the grader) and shipped with
the package only in encoded form (``twolink_course/exercises/store/chN.txt``): the
self-check compares with the values stored there, and no function of the
installed package computes an exercise's answer.

Kinds of answers
----------------
``"number"``
    one real number (a Python or numpy number, a size-one array, a sympy number);
``"vector"``, ``"matrix"``
    real numbers of a given ``shape`` (lists, tuples, arrays, sympy matrices);
``"angles"``
    angles in radians, of a given ``shape``: equal up to whole turns;
``"bool"``
    ``True`` or ``False`` (numpy's bools too), nothing else;
``"text"``
    a string, compared after stripping surrounding white space;
``"function"``
    a function of the exercise's arguments, called on the visible cases
    (:class:`Case`); its return value is judged as the part's ``output``.

Examples
--------
>>> part = PartSpec("p_tip", "tip position", "vector", shape=(2,), unit="m",
...             expected=[0.1, 0.2], components=("x", "y"),
...             hints=("Reread section 2.", "x = ..."))
>>> PartSpec.from_json(part.to_json()) == part
True
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

__all__ = ["KINDS", "Tolerance", "Mistake", "Case", "PartSpec", "ExerciseSpec", "plain"]

KINDS = ("number", "vector", "matrix", "angles", "bool", "text", "function")


@dataclasses.dataclass(frozen=True)
class Tolerance:
    """How close a numeric answer must be.

    ``atol`` and ``rtol`` bound a value computed in code: ``|a - e| <= atol +
    rtol |e|``.  ``significant`` (an int), when set, is the precision the
    exercise asks for a value a student may compute by hand ("to 3
    significant figures"): any answer that rounds to the right value at that
    precision is accepted, i.e. ``|a - e|`` up to half a unit in the last
    asked digit of ``e``.
    """

    atol: float = 1e-9
    rtol: float = 1e-9
    significant: int | None = None

    def allowed(self, expected: float) -> float:
        """The largest miss accepted for an expected value ``expected``.

        >>> Tolerance(atol=0.0, rtol=0.0, significant=3).allowed(0.013333)
        5e-05
        >>> Tolerance().allowed(2.0)
        3e-09
        """
        code = self.atol + self.rtol * abs(expected)
        if self.significant is None or expected == 0.0:
            return code
        exponent = math.floor(math.log10(abs(expected))) - self.significant + 1
        return max(code, float(f"{0.5 * 10.0**exponent:.12g}"))


@dataclasses.dataclass(frozen=True)
class Mistake:
    """A typical wrong answer: its value on the exercise's data and the diagnosis in words.

    For a ``"function"`` part, ``value`` is the list of what the mistaken
    function returns on each visible case.
    """

    value: Any
    diagnosis: str


@dataclasses.dataclass(frozen=True)
class Case:
    """One call of a learner's function: its arguments by name and the right return value.

    An argument that is an arm is written as ``{"arm": {"l1": ..., "l2": ...}}``
    (made into a :class:`twolink.TwoLinkArm` when the function is called).
    """

    arguments: Mapping[str, Any]
    expected: Any


@dataclasses.dataclass(frozen=True)
class PartSpec:
    """One answer of an exercise: what it is, what is right, what typical mistakes give.

    Attributes
    ----------
    name : str
        The notebook variable holding the answer (``"q_elbow_up"``).
    label : str
        What it is, in the check's line (``"elbow-up angles"``).
    kind : str
        One of :data:`KINDS`.
    expected : object
        The right value (numbers as nested lists; for ``"function"``: unused,
        the cases hold the values).
    shape : tuple of int
        For ``"vector"``, ``"matrix"`` and ``"angles"``: the answer's shape.
    unit : str
        The unit of the numbers (``"m"``, ``"N m"``, ``"rad"``; ``""`` for none).
    components : tuple of str
        Names of a vector's entries, for the feedback (``("tau1", "tau2")``).
    tolerance : Tolerance
    mistakes : tuple of Mistake
        Typical wrong answers, checked in order.
    hints : tuple of str
        From a nudge (which idea, which section) to a more specific step; the
        first wrong try shows the first, later tries the next ones.  None
        states the whole computation or the value.
    cases : tuple of Case
        For ``"function"``: the visible calls and their right return values.
    output : PartSpec or None
        For ``"function"``: how a return value is judged (kind, shape, unit,
        tolerance).
    forbidden : tuple of str
        For ``"function"``: the package's callables the exercise asks the
        learner not to use, as dotted import paths
        (``"twolink.arm.TwoLinkArm.fk"``); the function is judged with them
        unavailable (:func:`twolink_course.exercises.forbidden.unavailable`).
    """

    name: str
    label: str
    kind: str
    expected: Any = None
    shape: tuple[int, ...] = ()
    unit: str = ""
    components: tuple[str, ...] = ()
    tolerance: Tolerance = Tolerance()
    mistakes: tuple[Mistake, ...] = ()
    hints: tuple[str, ...] = ()
    cases: tuple[Case, ...] = ()
    output: PartSpec | None = None
    forbidden: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(
                f"part {self.name!r}: kind must be one of {KINDS}; got {self.kind!r}"
            )
        if self.kind == "function" and (self.output is None or not self.cases):
            raise ValueError(
                f"part {self.name!r}: a function part needs an output and cases"
            )
        if self.forbidden and self.kind != "function":
            raise ValueError(
                f"part {self.name!r}: only a function part can forbid calls; "
                f"got forbidden={self.forbidden!r} on a {self.kind!r} part"
            )

    def to_json(self) -> dict[str, Any]:
        """The part as JSON-ready data (nested dicts and lists)."""
        data = plain(dataclasses.asdict(self))
        if self.output is not None:
            data["output"] = self.output.to_json()
        if not self.forbidden:
            del data[
                "forbidden"
            ]  # most parts forbid nothing: the store stays as it was
        return data

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> PartSpec:
        """The part from :meth:`to_json`'s data."""
        fields = dict(data)
        fields["shape"] = tuple(fields.get("shape", ()))
        fields["components"] = tuple(fields.get("components", ()))
        fields["tolerance"] = Tolerance(**fields.get("tolerance", {}))
        fields["mistakes"] = tuple(Mistake(**m) for m in fields.get("mistakes", ()))
        fields["hints"] = tuple(fields.get("hints", ()))
        fields["cases"] = tuple(Case(**c) for c in fields.get("cases", ()))
        fields["forbidden"] = tuple(fields.get("forbidden", ()))
        output = fields.get("output")
        fields["output"] = None if output is None else cls.from_json(output)
        return cls(**fields)


@dataclasses.dataclass(frozen=True)
class ExerciseSpec:
    """An exercise: its number (``"4.1"``), its chapter's notebook stem and its parts, in order."""

    number: str
    chapter: str
    parts: tuple[PartSpec, ...]

    def to_json(self) -> dict[str, Any]:
        return {
            "number": self.number,
            "chapter": self.chapter,
            "parts": [part.to_json() for part in self.parts],
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> ExerciseSpec:
        return cls(
            data["number"],
            data["chapter"],
            tuple(PartSpec.from_json(p) for p in data["parts"]),
        )


def plain(value: Any) -> Any:
    """``value`` with numpy arrays and numbers made into lists and floats (JSON-ready).

    >>> import numpy as np
    >>> plain({"q": np.array([1.0, 2.0]), "ok": np.bool_(True)})
    {'q': [1.0, 2.0], 'ok': True}
    """
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)) and not isinstance(value, str):
        return [plain(v) for v in value]
    return value
