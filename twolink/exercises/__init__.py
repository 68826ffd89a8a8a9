"""The course's exercises: each part's expected value, tolerance, typical mistakes and hints.

Exercises are specified in the repository's ``answers/`` folder and shipped
encoded in the package's ``store/chN.txt`` files (decoded by
:mod:`twolink.exercises.stored`, judged by :mod:`twolink.exercises.judging`).
Chapters not yet moved there register judges in a module of their own
(``ch1`` ... ``ch7``).  Either way a notebook's check cell holds no reference:
``selfcheck.check("2.1", q_elbow_up, up_within_limits)``.

>>> from twolink import exercises
>>> exercises.get("2.1").parts[0].name
'q_elbow_up'
>>> len(exercises.all_exercises())
21
"""

from . import ch1, ch2, ch3, ch5, ch6, ch7, spec, stored  # noqa: F401  (each registers its chapter's exercises)
from .registry import REGISTRY, Exercise, Part, Wrong, is_unsolved

__all__ = ["Exercise", "Part", "Wrong", "get", "all_exercises", "is_unsolved"]


def _key(number: str) -> tuple[int, ...]:
    return tuple(int(x) for x in number.split("."))


def get(number: str) -> Exercise | spec.ExerciseSpec:
    """The exercise numbered ``number`` (e.g. ``"2.1"``); a clear error for an unknown number."""
    key = str(number).removeprefix("Exercise").strip()
    specification = stored.specification(key)
    if specification is not None:
        return specification
    if key not in REGISTRY:
        known = sorted({*REGISTRY, *stored.exercise_numbers()}, key=_key)
        raise KeyError(f"no exercise {number!r}; the exercises are {', '.join(known)}")
    return REGISTRY[key]


def all_exercises() -> list[Exercise | spec.ExerciseSpec]:
    """Every exercise, in chapter order."""
    return [
        get(number)
        for number in sorted({*REGISTRY, *stored.exercise_numbers()}, key=_key)
    ]
