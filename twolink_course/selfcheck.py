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

While grading (``TWOLINK_GRADING=1``, :mod:`twolink_course.runmode`) each check
also gives its score, the number of parts right, as the check cell's result
(``sys.displayhook``), which is what nbgrader's autograde reads as the cell's
partial credit; a learner's run shows no such result.

In a Jupyter kernel, a check cell whose answer was never assigned (the answer
cell above raised, or was not run) shows one sentence saying so, as the
cell's error, instead of a ``NameError`` traceback (:func:`explain_missing_answers`, run when
this module is imported in a kernel).
"""

from __future__ import annotations

import collections
import linecache
import re
import sys
from types import TracebackType
from typing import Any, NamedTuple

from . import exercises, runmode
from .exercises import judging, spec

__all__ = [
    "check",
    "reset_hints",
    "parse_line",
    "explain_missing_answers",
    "NOT_SOLVED",
    "CORRECT",
    "WRONG",
]

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
    >>> report = check("1.1", arms.osake.fk(np.radians([50.0, -30.0])))
    Exercise 1.1 (tip position): correct.
    >>> report = check("1.1", ...)
    Exercise 1.1 (tip position): not solved yet (replace the ... in p_tip_ex1 with your answer).
    >>> reset_hints()          # hints start again from the first tier
    >>> report = check("1.1", arms.osake.fk([50.0, -30.0]))
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
    report = CheckReport(results)
    if runmode.grading() and _kernel() is not None:
        sys.displayhook(report.score)  # the cell's result: nbgrader's partial credit
    return report


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


#: A call of the self-check in a cell's source, with its exercise's number.
_CHECK_CALL = re.compile(r"selfcheck\.check\(\s*[\"'](?P<number>\d+\.\d+)[\"']")


def _kernel() -> Any:
    """The IPython shell this runs in, or None (a plain script, a test)."""
    ipython = sys.modules.get("IPython")
    return None if ipython is None else ipython.get_ipython()


def _cell_source(traceback: TracebackType | None) -> str:
    """The source of the notebook cell an exception was raised in ("" if not found)."""
    while traceback is not None:
        code = traceback.tb_frame.f_code
        if code.co_name == "<module>":
            return "".join(linecache.getlines(code.co_filename))
        traceback = traceback.tb_next
    return ""


def not_checked(number: str, name: str) -> str:
    """The sentence a check cell shows when its answer ``name`` was never assigned.

    >>> print(not_checked("7.2", "q_ex2"))
    Exercise 7.2 is not checked: q_ex2 is not defined. The answer cell above did not assign it: it raised an error (fix it and run it again) or has not been run yet; then run this cell.
    """
    return (
        f"Exercise {number} is not checked: {name} is not defined. The answer cell "
        "above did not assign it: it raised an error (fix it and run it again) or "
        "has not been run yet; then run this cell."
    )


def _name_error(
    shell: Any,
    kind: type[BaseException],
    error: BaseException,
    traceback: TracebackType | None,
    tb_offset: int | None = None,
) -> None:
    """IPython's handler of a ``NameError``: a check cell's sentence, any other cell's traceback."""
    found = _CHECK_CALL.search(_cell_source(traceback))
    name = getattr(error, "name", None)
    if found is None or not isinstance(name, str):
        shell.showtraceback((kind, error, traceback), tb_offset=tb_offset)
        return
    sentence = NameError(not_checked(found["number"], name), name=name)
    show = getattr(shell, "_showtraceback", None)
    if show is None:  # a shell without it: the exception without its traceback
        shell.showtraceback((NameError, sentence, None), exception_only=True)
        return
    # IPython's private _showtraceback (what showtraceback ends with; ipykernel
    # sends it as the cell's error): the only way to show an error whose
    # "traceback" is one sentence, with no header line and no "%tb" advice
    show(NameError, sentence, [f"NameError: {sentence}"])


def explain_missing_answers() -> bool:
    """Make check cells explain an answer never assigned (in a Jupyter kernel; else nothing).

    The shell's handler of ``NameError`` (``set_custom_exc``) shows
    :func:`not_checked`'s sentence, still as the cell's error (nbgrader gives
    such a check no points), when the cell calls ``selfcheck.check``, and the
    usual traceback for any other cell.  A shell that already has a handler
    of its own keeps it.  Returns whether the handler is in place.

    >>> explain_missing_answers()  # not in a kernel
    False
    """
    shell = _kernel()
    if shell is None or not hasattr(shell, "set_custom_exc"):
        return False
    if shell.custom_exceptions not in ((), (NameError,)):
        return False
    shell.set_custom_exc((NameError,), _name_error)
    return True


explain_missing_answers()
