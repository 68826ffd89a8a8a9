"""Self-checks for the course's exercises: right or wrong, what is wrong, and a hint.

An exercise cell assigns the learner's answers to named variables; the next
cell calls ``selfcheck.check("2.1", q_elbow_up, up_within_limits)``.  The
expected values, tolerances, typical mistakes and hints come from
:mod:`twolink_course.exercises` (stored encoded), out of the learner's sight.  Each
part prints one line: ``correct.``, ``not solved yet`` (an answer left as
``...``, the stub of the student edition, so a notebook runs top to bottom
with unsolved exercises), or ``wrong:`` with what is wrong (a typical mistake
named, or the quantity that misses, by how much and which way) and the next
hint (the first wrong try a nudge, later ones more specific).

"""

from __future__ import annotations

import collections
import re
from typing import NamedTuple

from . import exercises
from .exercises import judging, spec

__all__ = ["check", "reset_hints", "parse_line", "NOT_SOLVED", "CORRECT", "WRONG"]

NOT_SOLVED = "not solved yet"
CORRECT = "correct"
WRONG = "wrong"

_LINE = re.compile(
    r"^Exercise (?P<number>\d+\.\d+)(?: \((?P<part>[^)]*)\))?: "
    r"(?P<status>correct|not solved yet|wrong|not right yet)\b"
)


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

    @property
    def score(self) -> int:
        """The number of parts answered correctly (a part not solved yet or wrong counts 0).

        nbgrader gives a check cell this many of its points: the chapters' check
        cells end with ``report.score`` in a hidden-test block, and nbgrader reads
        a grade cell's result as its partial credit.

        >>> import numpy as np
        >>> from twolink import arms
        >>> report = check("1.3", np.radians([60.0, 90.0]), ...)
        Exercise 1.3 (relative angles): correct.
        Exercise 1.3 (tip): not solved yet (replace the ... in p_tip_ex3 with your answer).
        >>> report.score, len(report)
        (1, 2)
        """
        return sum(1 for result in self if result.status == CORRECT)


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
    >>> reset_hints()          # hints start again from the first tier
    >>> report = check("1.1", arms.osake.fk([45.0, -30.0]))
    Exercise 1.1 (tip position): wrong: this is the tip for the angles read as radians: \
cos and sin take radians, so convert the degrees first. Hint 1 of 2: Reread 'A1, A2 and \
T_0^2 = A1 A2 with sympy': the last column of T_0^2 holds the tip's x and y.
    >>> report.passed
    False
    """
    entry = exercises.get(exercise)
    names = [part.name for part in entry.parts]
    if len(answers) > len(names):
        raise TypeError(
            f"exercise {entry.number} has {len(names)} parts ({', '.join(names)}), got {len(answers)} answers"
        )
    unknown = sorted(set(named_answers) - set(names))
    if unknown:
        raise TypeError(
            f"exercise {entry.number} has no part {unknown[0]!r}; its parts are {', '.join(names)}"
        )
    given: dict[str, object] = dict(zip(names, answers))
    for name, value in named_answers.items():
        if name in given:
            raise TypeError(
                f"the answer {name!r} of exercise {entry.number} is given twice"
            )
        given[name] = value
    solved = {
        name: value for name, value in given.items() if not exercises.is_unsolved(value)
    }
    results = []
    for part in entry.parts:
        label = f"Exercise {entry.number} ({part.label})"
        if part.name not in solved:
            status, line = (
                NOT_SOLVED,
                f"{label}: {NOT_SOLVED} (replace the ... in {part.name} with your answer).",
            )
        else:
            verdict = judging.judge(part, solved[part.name])
            if verdict.right:
                status, line = CORRECT, f"{label}: {CORRECT}."
            else:
                status = WRONG
                line = (
                    f"{label}: {WRONG}: {verdict.message}.{_hint(entry.number, part)}"
                )
        print(line)
        results.append(PartResult(entry.number, part.label, status, line))
    return CheckReport(results)


#: Wrong tries so far, per (exercise, part): the hint's tier follows it.
_WRONG_TRIES: collections.Counter[tuple[str, str]] = collections.Counter()


def reset_hints() -> None:
    """Forget the wrong tries so far: every part's next hint is its first again.

    >>> reset_hints()
    """
    _WRONG_TRIES.clear()


def _hint(number: str, part: spec.PartSpec) -> str:
    """The next hint for a wrong try of ``part``: the first try a nudge, later ones more specific."""
    if not part.hints:
        return ""
    _WRONG_TRIES[number, part.name] += 1
    tier = min(_WRONG_TRIES[number, part.name], len(part.hints))
    return f" Hint {tier} of {len(part.hints)}: {part.hints[tier - 1]}"


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
    status = (
        WRONG if match["status"] == "not right yet" else match["status"]
    )  # the word for wrong in older notebooks' outputs
    return match["number"], match["part"] or "", status
