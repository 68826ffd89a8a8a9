"""The course's exercises: each part's expected value, tolerance, typical mistakes and hints.

Exercises are specified in the repository's ``answers/`` folder and shipped
encoded in the package's ``store/chN.txt`` files (decoded by
:mod:`twolink_course.exercises.stored`, described by :mod:`twolink_course.exercises.spec`,
judged by :mod:`twolink_course.exercises.judging`).  A notebook's check cell holds
no reference: ``selfcheck.check("2.1", q_elbow_up, up_within_limits)``.

>>> from twolink_course import exercises
>>> exercises.get("2.1").parts[0].name
'q_elbow_up'
>>> [exercise.number for exercise in exercises.all_exercises()][:5]
['1.1', '1.2', '1.3', '1.4', '1.5']
"""

from . import judging, spec, stored
from .spec import ExerciseSpec, PartSpec

__all__ = [
    "ExerciseSpec",
    "PartSpec",
    "get",
    "all_exercises",
    "is_unsolved",
    "judging",
    "spec",
    "stored",
]


def is_unsolved(answer: object) -> bool:
    """True for the student edition's stub ``...`` and for ``None``.

    >>> is_unsolved(...), is_unsolved(None), is_unsolved(0.0)
    (True, True, False)
    """
    return answer is ... or answer is None


def get(number: str) -> ExerciseSpec:
    """The exercise numbered ``number`` (e.g. ``"2.1"``); a clear error for an unknown number."""
    key = str(number).removeprefix("Exercise").strip()
    specification = stored.specification(key)
    if specification is None:
        raise KeyError(
            f"no exercise {number!r}; the exercises are "
            f"{', '.join(stored.exercise_numbers())}"
        )
    return specification


def all_exercises() -> list[ExerciseSpec]:
    """Every exercise, in chapter order."""
    return [get(number) for number in stored.exercise_numbers()]
