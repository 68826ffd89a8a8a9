"""The course's exercises: each part's expected value, tolerance, comparison and hint.

One module per chapter (``ch1`` ... ``ch7``) registers its exercises; the
expected values are computed by the package from each exercise's data, on
first use, so a notebook's check cell holds no reference at all:
``selfcheck.check("2.1", q_elbow_up, up_within_limits)``.

>>> from twolink import exercises
>>> exercises.get("2.1").parts[0].name
'q_elbow_up'
>>> len(exercises.all_exercises())
21
"""

from . import ch1, ch2, ch3, ch4, ch5, ch6, ch7  # noqa: F401  (each registers its chapter's exercises)
from .registry import REGISTRY, Exercise, Part, Wrong, is_unsolved

__all__ = ["Exercise", "Part", "Wrong", "get", "all_exercises", "is_unsolved"]


def get(number: str) -> Exercise:
    """The exercise numbered ``number`` (e.g. ``"2.1"``); a clear error for an unknown number."""
    key = str(number).removeprefix("Exercise").strip()
    if key not in REGISTRY:
        raise KeyError(
            f"no exercise {number!r}; the exercises are {', '.join(REGISTRY)}"
        )
    return REGISTRY[key]


def all_exercises() -> list[Exercise]:
    """Every registered exercise, in chapter order."""
    return [
        REGISTRY[number]
        for number in sorted(
            REGISTRY, key=lambda n: tuple(int(x) for x in n.split("."))
        )
    ]
