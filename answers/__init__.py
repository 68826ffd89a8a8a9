"""The course's exercise references, readable: for teachers, the grader and the store's builder.

Not part of the installed package.  Each chapter module (``ch4`` ...)
defines ``exercises()``, the :class:`twolink_course.exercises.spec.Exercise` objects
of its chapter, computed by the package from each exercise's data, and, for
an exercise that asks for a function, ``hidden_cases(number, part, seed)``:
inputs the student never saw, drawn from a seed only the grader holds.
``python tools/build_answers.py`` encodes them into
``twolink_course/exercises/store/chN.txt``, what the self-checks compare with.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable
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


def all_exercises() -> list[ExerciseSpec]:
    """Every exercise of every chapter module, in order."""
    return [
        exercise for name in chapter_names() for exercise in chapter(name).exercises()
    ]


HiddenCases = Callable[[np.random.Generator, int], list[Case]]


def hidden_generators() -> dict[tuple[str, str], HiddenCases]:
    """Every chapter's hidden-case generators, by ``(exercise number, part name)``."""
    found: dict[tuple[str, str], HiddenCases] = {}
    for name in chapter_names():
        found.update(getattr(chapter(name), "HIDDEN", {}))
    return found


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
