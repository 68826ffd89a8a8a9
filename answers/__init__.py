"""The course's exercise references, readable: for teachers, the grader and the store's builder.

Not part of the installed package.  Each chapter module (``ch4`` ...)
defines ``exercises()``, the :class:`twolink.exercises.spec.Exercise` objects
of its chapter, computed by the package from each exercise's data, and, for
an exercise that asks for a function, ``hidden_cases(number, part, seed)``:
inputs the student never saw, drawn from a seed only the grader holds.
``python tools/build_answers.py`` encodes them into
``twolink/exercises/_store.py``, what the self-checks compare with.
"""

from __future__ import annotations

from twolink.exercises.spec import ExerciseSpec

from . import ch4

CHAPTERS = (ch4,)


def all_exercises() -> list[ExerciseSpec]:
    """Every exercise of every chapter module, in order."""
    return [exercise for chapter in CHAPTERS for exercise in chapter.exercises()]
