"""The course's exercise references, readable: for teachers, the grader and the store's builder.

Not part of the installed package.  Each chapter module (``ch4`` ...)
defines ``exercises()``, the :class:`twolink_course.exercises.spec.ExerciseSpec`
objects of its chapter, computed by the package from each exercise's data,
and may define

- ``HIDDEN = {(number, part): hidden_cases}``: for a function part, calls the
  student never saw, ``hidden_cases(rng, count) -> list[Case]``;
- ``RERUN = {number: Rerun(inputs=..., hidden=..., answers=...)}``: for a value
  exercise whose answer cell computes from the names its *inputs cell* binds
  (``# Inputs of exercise N.M``), those inputs, a draw of inputs the student
  never saw and each part's reference on any inputs (:class:`Rerun`); the
  grader re-runs the student's answer cell on hidden draws;
- ``FORBIDDEN = {(number, part): (dotted path, ...)}``: for a function part,
  the package's callables the exercise asks the student not to use (carried
  into the part's specification, :attr:`PartSpec.forbidden`);
- ``PEN_AND_PAPER = ((number, part), ...)``: value parts worked on paper (a
  choice of reason, a hand-derived value), judged on the notebook's own value
  only, even in an exercise with a ``RERUN`` entry (whose ``answers`` need not
  give them).

``python tools/build_answers.py`` encodes the exercises (forbidden calls
included, no hidden input or reference) into
``twolink_course/exercises/store/chN.txt``, what the self-checks compare with.
"""

from __future__ import annotations

import dataclasses
import importlib
import pkgutil
import zlib
from collections.abc import Callable, Mapping
from types import ModuleType

import numpy as np

from twolink_course.exercises.spec import Case, ExerciseSpec


def chapter_names() -> list[str]:
    """The chapter modules of this folder, in order: ``["ch1", ..., "ch7"]``."""
    return sorted(
        module.name
        for module in pkgutil.iter_modules(__path__)
        if module.name.startswith("ch") and module.name[2:].isdigit()
    )


def chapter(name: str) -> ModuleType:
    """The chapter module ``name`` (``"ch4"``)."""
    if name not in chapter_names():
        raise KeyError(f"no answers/{name}.py; the chapters are {chapter_names()}")
    return importlib.import_module(f"{__name__}.{name}")


def with_forbidden(
    exercises: list[ExerciseSpec],
    forbidden: Mapping[tuple[str, str], tuple[str, ...]],
) -> list[ExerciseSpec]:
    """``exercises`` with each part's forbidden calls taken from ``forbidden``.

    A key that names no function part of them is an error naming it.
    """
    parts = {
        (exercise.number, part.name): part
        for exercise in exercises
        for part in exercise.parts
    }
    for key in forbidden:
        if key not in parts or parts[key].kind != "function":
            raise KeyError(
                f"FORBIDDEN names {key}, which is no function part of the chapter; "
                f"its function parts: {sorted(k for k, p in parts.items() if p.kind == 'function')}"
            )
    return [
        dataclasses.replace(
            exercise,
            parts=tuple(
                dataclasses.replace(
                    part, forbidden=tuple(forbidden[exercise.number, part.name])
                )
                if (exercise.number, part.name) in forbidden
                else part
                for part in exercise.parts
            ),
        )
        for exercise in exercises
    ]


def chapter_exercises(name: str) -> list[ExerciseSpec]:
    """The exercises of chapter module ``name`` as stored: with its ``FORBIDDEN`` calls."""
    module = chapter(name)
    return with_forbidden(module.exercises(), getattr(module, "FORBIDDEN", {}))


def all_exercises() -> list[ExerciseSpec]:
    """Every exercise of every chapter module, in order (forbidden calls included)."""
    return [
        exercise for name in chapter_names() for exercise in chapter_exercises(name)
    ]


HiddenCases = Callable[[np.random.Generator, int], list[Case]]
Inputs = dict[str, object]


@dataclasses.dataclass(frozen=True)
class Rerun:
    """How a value exercise is graded on inputs the student never saw.

    Attributes
    ----------
    inputs : dict
        Exactly what the exercise's inputs cell (first line ``# Inputs of
        exercise N.M``) binds, by name: the arm, the angles, the target...
        (``tests/course/test_exercises_rerun.py`` checks it against the chapter).
    hidden : callable
        ``hidden(rng) -> dict``: one draw of inputs the student never saw, the
        same names, valid for the exercise (reachable targets, non-singular
        poses).
    answers : callable
        ``answers(inputs) -> dict``: each part's reference value, by part
        name, computed by the package from those inputs (outside the
        student's process).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> rerun = Rerun(
    ...     inputs={"arm_ex9": TwoLinkArm(1.0, 1.0), "q_ex9": np.zeros(2)},
    ...     hidden=lambda rng: {"arm_ex9": TwoLinkArm(2.0, 1.0), "q_ex9": rng.uniform(-1, 1, 2)},
    ...     answers=lambda given: {"p_ex9": given["arm_ex9"].fk(given["q_ex9"])},
    ... )
    >>> rerun.answers(rerun.inputs)["p_ex9"].tolist()
    [2.0, 0.0]
    """

    inputs: Inputs
    hidden: Callable[[np.random.Generator], Inputs]
    answers: Callable[[Inputs], dict[str, object]]

    def __post_init__(self) -> None:
        if not isinstance(self.inputs, dict) or not all(
            isinstance(name, str) and name.isidentifier() for name in self.inputs
        ):
            raise TypeError(
                f"Rerun.inputs must be a dict of the inputs cell's names; got {self.inputs!r}"
            )
        for field in ("hidden", "answers"):
            if not callable(getattr(self, field)):
                raise TypeError(
                    f"Rerun.{field} must be a function; got {getattr(self, field)!r}"
                )


def hidden_generators() -> dict[tuple[str, str], HiddenCases]:
    """Every chapter's hidden-case generators, by ``(exercise number, part name)``."""
    found: dict[tuple[str, str], HiddenCases] = {}
    for name in chapter_names():
        found.update(getattr(chapter(name), "HIDDEN", {}))
    return found


def rerun_specs() -> dict[str, Rerun]:
    """Every chapter's :class:`Rerun` entries, by exercise number."""
    found: dict[str, Rerun] = {}
    for name in chapter_names():
        found.update(getattr(chapter(name), "RERUN", {}))
    return found


def on_paper() -> frozenset[tuple[str, str]]:
    """Every chapter's ``PEN_AND_PAPER`` parts, as ``(exercise number, part name)``.

    A value part worked on paper (a choice of reason, a hand-derived value)
    has no reference on hidden inputs: within an exercise graded on hidden
    inputs, it is judged on the notebook's own value only, and ``answers()``
    of its :class:`Rerun` need not give it.
    """
    return frozenset(
        (number, part)
        for name in chapter_names()
        for number, part in getattr(chapter(name), "PEN_AND_PAPER", ())
    )


def hidden_cases(number: str, part: str, seed: int, count: int = 20) -> list[Case]:
    """``count`` hidden cases of a function part, drawn from ``seed`` (the grader's).

    The notebook never holds the seed, so no probing of its self-check (which
    calls the function on the visible cases only) can fit these.
    """
    generators = hidden_generators()
    if (number, part) not in generators:
        raise KeyError(
            f"exercise {number} has no function part {part!r} with hidden cases; "
            f"those with hidden cases: {sorted(generators)}"
        )
    return generators[number, part](np.random.default_rng(seed), count)


def exercise_seed(seed: int, number: str) -> list[int]:
    """The seed of exercise ``number``'s draws: the grader's seed, then the exercise's own.

    Each exercise draws from a stream of its own, so adding an exercise
    changes no other exercise's draws.

    >>> exercise_seed(7, "4.1") == exercise_seed(7, "4.1") != exercise_seed(7, "4.2")
    True
    """
    return [seed, zlib.crc32(number.encode("ascii"))]


def hidden_draws(
    rerun: Rerun, number: str, seed: int, count: int
) -> list[tuple[Inputs, dict[str, object]]]:
    """``count`` draws of hidden inputs of exercise ``number``, each with its references."""
    rng = np.random.default_rng(exercise_seed(seed, number))
    draws = []
    for _ in range(count):
        inputs = rerun.hidden(rng)
        if set(inputs) != set(rerun.inputs):
            raise ValueError(
                f"exercise {number}: a hidden draw binds {sorted(inputs)}, the inputs "
                f"cell {sorted(rerun.inputs)}: they must be the same names"
            )
        draws.append((inputs, rerun.answers(inputs)))
    return draws
