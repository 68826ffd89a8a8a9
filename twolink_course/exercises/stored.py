"""The exercises' specifications as shipped: decoded from the package's ``store/chN.txt`` files.

The store is written by ``tools/build_answers.py`` from the repository's
``answers/`` folder (the readable references, for teachers and the grader),
one file per chapter: JSON, compressed and base64-encoded, so that no module
of the installed package reads as a list of answers and no function computes
one.

>>> exercise = specification("4.1")
>>> exercise.parts[0].name, exercise.parts[0].unit
('tau_ex1', 'N m')
"""

from __future__ import annotations

import base64
import functools
import importlib.resources
import json
import zlib
from typing import Any

from .spec import ExerciseSpec

__all__ = ["encode", "decode", "specification", "exercise_numbers"]


def encode(exercises: list[ExerciseSpec]) -> str:
    """The store's text for ``exercises``: sorted JSON, zlib-compressed, base64."""
    data = {exercise.number: exercise.to_json() for exercise in exercises}
    text = json.dumps(data, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return base64.b64encode(zlib.compress(text.encode("utf-8"), 9)).decode("ascii")


def decode(text: str) -> dict[str, Any]:
    """The JSON data of a store's text (exercise number -> exercise data)."""
    data: dict[str, Any] = json.loads(zlib.decompress(base64.b64decode(text)))
    return data


#: The folder of the encoded chapters, inside the package.
STORE = importlib.resources.files(__package__).joinpath("store")


@functools.cache
def _exercises() -> dict[str, ExerciseSpec]:
    found: dict[str, ExerciseSpec] = {}
    for item in sorted(STORE.iterdir(), key=lambda entry: entry.name):
        if item.name.endswith(".txt"):
            for number, data in decode(item.read_text(encoding="ascii")).items():
                found[number] = ExerciseSpec.from_json(data)
    return found


def exercise_numbers() -> list[str]:
    """The numbers of the stored exercises, in chapter order."""
    return sorted(_exercises(), key=lambda n: tuple(int(x) for x in n.split(".")))


def specification(number: str) -> ExerciseSpec | None:
    """The stored exercise ``number`` (``"4.1"``), or None if it is not in the store."""
    return _exercises().get(number)
