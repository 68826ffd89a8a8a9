"""Self-checks for the course's exercises: right or wrong, with a hint.

An exercise cell assigns the learner's answers to named variables; the next
cell calls ``selfcheck.check("2.1", q_elbow_up, up_within_limits)``.  The
expected values, tolerances, comparisons and hints live in
:mod:`twolink.exercises`, out of the learner's sight.  Each part prints one
line: ``correct.``, ``not solved yet`` (an answer left as ``...``, the stub of
the student edition, so a notebook runs top to bottom with unsolved
exercises), or ``wrong:`` with the reason and the hint.

:func:`check_close` and :func:`check_true` are the lower-level helpers for a
check whose reference is at hand (not used by the chapters' exercises).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import NamedTuple, TypeVar

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["check", "check_close", "check_true", "parse_line", "NOT_SOLVED", "CORRECT", "WRONG"]

NOT_SOLVED = "not solved yet"
CORRECT = "correct"
WRONG = "wrong"

_LINE = re.compile(r"^Exercise (?P<number>\d+\.\d+)(?: \((?P<part>[^)]*)\))?: "
                   r"(?P<status>correct|not solved yet|wrong|not right yet)\b")

_Answer = TypeVar("_Answer")


class PartResult(NamedTuple):
    """One part's verdict: ``status`` is ``"correct"``, ``"not solved yet"`` or ``"wrong"``."""

    number: str
    part: str
    status: str
    message: str


class CheckReport(tuple[PartResult, ...]):
    """The verdicts of one :func:`check` call (a tuple of :class:`PartResult`)."""

    @property
    def passed(self) -> bool:
        """True when every part is correct."""
        return all(result.status == CORRECT for result in self)


def check(exercise: str, *answers: object, **named_answers: object) -> CheckReport:
    """Check a learner's answers to an exercise and print one line per part.

    Parameters
    ----------
    exercise : str
        The exercise's number, e.g. ``"2.1"``.
    *answers : object
        The answers in the order of the exercise's parts.
    **named_answers : object
        Or by the parts' variable names (``q_elbow_up=...``).  A part not given,
        or given as ``...`` or ``None``, is "not solved yet".

    Returns
    -------
    CheckReport
        The verdicts (end the check cell with ``;`` so that only the lines show).

    Examples
    --------
    >>> import numpy as np
    >>> from twolink import arms
    >>> report = check("1.1", arms.osake.fk(np.radians([45.0, -30.0])))
    Exercise 1.1 (tip position): correct.
    >>> report = check("1.1", ...)
    Exercise 1.1 (tip position): not solved yet (replace the ... in p_tip_ex1 with your answer).
    >>> report = check("1.1", arms.osake.fk([45.0, -30.0]))
    Exercise 1.1 (tip position): wrong: this is the tip for the angles read as radians (45 rad, -30 rad): \
convert degrees first. Hint: x = l1 cos q1 + l2 cos(q1 + q2), y likewise with sin; angles in radians
    >>> report.passed
    False
    """
    from . import exercises

    entry = exercises.get(exercise)
    names = [part.name for part in entry.parts]
    if len(answers) > len(names):
        raise TypeError(f"exercise {entry.number} has {len(names)} parts ({', '.join(names)}), got {len(answers)} answers")
    unknown = sorted(set(named_answers) - set(names))
    if unknown:
        raise TypeError(f"exercise {entry.number} has no part {unknown[0]!r}; its parts are {', '.join(names)}")
    given: dict[str, object] = dict(zip(names, answers))
    for name, value in named_answers.items():
        if name in given:
            raise TypeError(f"the answer {name!r} of exercise {entry.number} is given twice")
        given[name] = value
    solved = {name: value for name, value in given.items() if not exercises.is_unsolved(value)}
    results = []
    for part in entry.parts:
        label = f"Exercise {entry.number} ({part.label})"
        if part.name not in solved:
            status, line = NOT_SOLVED, f"{label}: {NOT_SOLVED} (replace the ... in {part.name} with your answer)."
        else:
            siblings = {name: value for name, value in solved.items() if name != part.name}
            try:
                reason = part.judge(solved[part.name], siblings)
            except exercises.Wrong as wrong:
                reason = str(wrong)
            except Exception as exc:  # the learner's value may be of any type
                reason = f"could not use your {part.name} ({type(exc).__name__}: {exc})"
            if reason is None:
                status, line = CORRECT, f"{label}: {CORRECT}."
            else:
                status, line = WRONG, f"{label}: {WRONG}: {reason}. Hint: {part.hint}"
        print(line)
        results.append(PartResult(entry.number, part.label, status, line))
    return CheckReport(results)


def parse_line(line: str) -> tuple[str, str, str] | None:
    """``(number, part, status)`` of a line printed by :func:`check`, or ``None``.

    >>> parse_line("Exercise 2.1 (angles): wrong: the tip lands 3 m from the target. Hint: ...")
    ('2.1', 'angles', 'wrong')
    >>> parse_line("Exercise 1.1: not right yet. Hint: ...")
    ('1.1', '', 'wrong')
    """
    match = _LINE.match(line.strip())
    if not match:
        return None
    status = WRONG if match["status"] == "not right yet" else match["status"]  # check_close's word for wrong
    return match["number"], match["part"] or "", status


def _unsolved(answer: object) -> bool:
    return answer is ... or answer is None


def check_close(label: str, answer: object, expected: ArrayLike, atol: float = 1e-6, rtol: float = 0.0,
                hint: str = "") -> bool:
    """Print whether ``answer`` matches ``expected`` (same shape, within tolerance).

    Parameters
    ----------
    label : str
        Which exercise, e.g. ``"Exercise 1.1"``.
    answer : array_like or Ellipsis
        The learner's value; ``...`` or ``None`` means not attempted yet.
    expected : array_like
        The reference value.
    atol, rtol : float
        Tolerances as in :func:`numpy.allclose`.
    hint : str
        Shown when the answer is wrong.

    Returns
    -------
    bool
        True when correct.

    Examples
    --------
    >>> check_close("Exercise 0.1", [1.0, 2.0], [1.0, 2.0 + 1e-9])
    Exercise 0.1: correct.
    True
    >>> check_close("Exercise 0.1", ..., [1.0, 2.0])
    Exercise 0.1: not solved yet (replace the ... with your answer).
    False
    >>> check_close("Exercise 0.1", [2.0, 1.0], [1.0, 2.0], hint="order is (x, y)")
    Exercise 0.1: not right yet. Hint: order is (x, y)
    False
    """
    if _unsolved(answer):
        print(f"{label}: {NOT_SOLVED} (replace the ... with your answer).")
        return False
    try:
        answer_array = np.asarray(answer, dtype=float)
    except (TypeError, ValueError):
        print(f"{label}: expected numbers, got {type(answer).__name__}. Hint: {hint}")
        return False
    expected_array = np.asarray(expected, dtype=float)
    if answer_array.shape != expected_array.shape:
        print(f"{label}: expected shape {expected_array.shape}, got {answer_array.shape}. Hint: {hint}")
        return False
    if np.allclose(answer_array, expected_array, atol=atol, rtol=rtol):
        print(f"{label}: correct.")
        return True
    print(f"{label}: not right yet. Hint: {hint}")
    return False


def check_true(label: str, answer: _Answer, condition: Callable[[_Answer], object], hint: str = "") -> bool:
    """Print whether a learner's answer satisfies ``condition(answer)``.

    Parameters
    ----------
    label : str
        Which exercise, e.g. ``"Exercise 0.2"``.
    answer : object
        The learner's value; ``...`` or ``None`` means not attempted yet.
    condition : callable
        ``condition(answer)``, true when the answer is right (an exception
        it raises counts as wrong, with its message).
    hint : str
        Shown when the answer is wrong.

    Returns
    -------
    bool
        True when correct.

    Examples
    --------
    >>> check_true("Exercise 0.2", 3, lambda n: n > 2)
    Exercise 0.2: correct.
    True
    """
    if _unsolved(answer):
        print(f"{label}: {NOT_SOLVED} (replace the ... with your answer).")
        return False
    try:
        ok = bool(condition(answer))
    except Exception as exc:  # the learner's value may be of any type
        print(f"{label}: the check could not use your answer ({type(exc).__name__}: {exc}). Hint: {hint}")
        return False
    print(f"{label}: correct." if ok else f"{label}: not right yet. Hint: {hint}")
    return ok
