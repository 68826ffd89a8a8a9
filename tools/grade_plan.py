"""What every notebook of a grading run is asked, drawn once from the grader's seed.

- each function part: its visible calls, then ``hidden_calls`` hidden ones
  (``answers.hidden_cases``);
- each value exercise with a ``RERUN`` entry: ``draws`` draws of hidden
  inputs (``answers.hidden_draws``), each with its references computed by the
  package, here, outside every student's process (for every value part but
  those worked on paper, ``answers.on_paper``);
- each function part's forbidden calls (``PartSpec.forbidden``).

The inputs travel to the kernel as plain data (:func:`encode_input`), read
back there by ``tools/grading_probe.py``'s ``decode_input``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from twolink import TwoLinkArm
from twolink_course.exercises import judging
from twolink_course.exercises.spec import Case, ExerciseSpec, PartSpec

#: Hidden calls per function part; hidden draws per value exercise graded on hidden inputs;
#: draws looked at to find one that tells a part's visible answer from a computed one.
HIDDEN_CALLS, HIDDEN_DRAWS, MORE_DRAWS = 20, 3, 30


def encode_input(value: Any, where: str = "input") -> dict[str, Any]:
    """An input of an exercise as plain data: an arm, an array, a number, a text, a tuple, list or dict of them.

    >>> encode_input(np.array([0.5, 1.0]))
    {'array': {'values': [0.5, 1.0], 'dtype': 'float64'}}
    >>> encode_input(TwoLinkArm(1.0, 2.0))["arm"]["l2"]
    {'float': 2.0}
    >>> encode_input({1, 2}, "exercise 4.1's q_ex1")
    Traceback (most recent call last):
    ...
    TypeError: exercise 4.1's q_ex1 is a set: the grader passes arms, arrays, numbers, texts, None, and tuples, lists and dicts (by text) of them
    """
    if isinstance(value, TwoLinkArm):
        return {
            "arm": {
                field.name: encode_input(getattr(value, field.name), where)
                for field in dataclasses.fields(value)
                if field.init
            }
        }
    if isinstance(value, np.ndarray) and value.dtype.kind in "biuf":
        if value.dtype.kind == "f" and not np.all(np.isfinite(value)):
            raise ValueError(f"{where} holds nan or inf: a hidden draw must be finite")
        return {"array": {"values": value.tolist(), "dtype": str(value.dtype)}}
    if isinstance(value, (bool, np.bool_)):
        return {"bool": bool(value)}
    if isinstance(value, (int, np.integer)):
        return {"int": int(value)}
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            raise ValueError(f"{where} is {value}: a hidden draw must be finite")
        return {"float": float(value)}
    if isinstance(value, str):
        return {"str": value}
    if value is None:
        return {"none": None}
    if isinstance(value, (tuple, list)):
        kind = "tuple" if isinstance(value, tuple) else "list"
        return {kind: [encode_input(item, where) for item in value]}
    if isinstance(value, dict) and all(isinstance(key, str) for key in value):
        return {
            "dict": [[key, encode_input(item, where)] for key, item in value.items()]
        }
    raise TypeError(
        f"{where} is a {type(value).__name__}: the grader passes arms, arrays, numbers, "
        "texts, None, and tuples, lists and dicts (by text) of them"
    )


def telling(
    hidden_draws: Any,
    rerun: Any,
    number: str,
    seed: int,
    draws: int,
    parts: list[PartSpec],
) -> list[tuple[Mapping[str, Any], Mapping[str, Any]]]:
    """``draws`` hidden draws of exercise ``number``, and more where a part needs them.

    A draw tells a part's visible answer (typed in) from a computed one when the
    visible answer is wrong on it.  A yes/no or a count has few values: three
    draws can all share the visible answer (a chapter's yes/no did in one seed
    in ten).  For each part that no draw tells, the first later draw of the same
    stream that does is added (at most :data:`MORE_DRAWS` draws looked at), so
    a typed-in answer earns nothing on any seed.
    """
    made = list(hidden_draws(rerun, number, seed, draws))

    def untold(chosen: list[Any]) -> list[PartSpec]:
        return [
            part
            for part in parts
            if part.name in chosen[0][1]
            and all(
                judging.judge_value(part, part.expected, references[part.name]).right
                for _, references in chosen
            )
        ]

    if not made or not untold(made):
        return made
    more = list(hidden_draws(rerun, number, seed, MORE_DRAWS))[draws:]
    for part in untold(made):
        found = next(
            (
                draw
                for draw in more
                if not judging.judge_value(
                    part, part.expected, draw[1][part.name]
                ).right
            ),
            None,
        )
        if found is not None and all(found is not d for d in made):
            made.append(found)
    return made


@dataclasses.dataclass(frozen=True)
class Draw:
    """One draw of hidden inputs of a value exercise: the inputs as data, and each part's reference."""

    inputs: Mapping[str, Any]
    references: Mapping[str, Any]


@dataclasses.dataclass(frozen=True)
class Plan:
    """What every notebook is asked, by exercise and part."""

    calls: Mapping[tuple[str, str], tuple[Case, ...]]
    shown: Mapping[
        tuple[str, str], int
    ]  # how many of a part's calls are its visible ones
    draws: Mapping[str, tuple[Draw, ...]]

    @classmethod
    def drawn(
        cls,
        course: Any,
        seed: int,
        count: int = HIDDEN_CALLS,
        draws: int = HIDDEN_DRAWS,
    ) -> Plan:
        """The plan of ``course`` (``grade_release.Course``): its ``hidden_cases(number,
        part, seed, count)`` for each function part, ``draws`` of its ``hidden_draws``
        for each of its ``reruns`` entries (``answers.Rerun``)."""
        exercises: list[ExerciseSpec] = course.exercises
        reruns: Mapping[str, Any] = course.reruns
        hidden_cases = course.hidden_cases
        calls, shown = {}, {}
        for exercise in exercises:
            for part in exercise.parts:
                if part.kind == "function":
                    key = (exercise.number, part.name)
                    hidden = hidden_cases(exercise.number, part.name, seed, count)
                    calls[key] = (*part.cases, *hidden)
                    shown[key] = len(part.cases)
        drawn = {}
        numbers = {exercise.number: exercise for exercise in exercises}
        for number, rerun in reruns.items():
            if number not in numbers:
                continue
            on_paper = getattr(course, "on_paper", frozenset())
            values = [
                p.name
                for p in numbers[number].parts
                if p.kind != "function" and (number, p.name) not in on_paper
            ]
            parts = [p for p in numbers[number].parts if p.name in values]
            made = []
            for inputs, references in telling(
                course.hidden_draws, rerun, number, seed, draws, parts
            ):
                missing = sorted(set(values) - set(references))
                if missing:
                    raise KeyError(
                        f"exercise {number}: RERUN's answers() gives no reference for {missing}"
                    )
                made.append(
                    Draw(
                        {
                            name: encode_input(
                                value, f"exercise {number}'s input {name}"
                            )
                            for name, value in inputs.items()
                        },
                        {name: references[name] for name in values},
                    )
                )
            drawn[number] = tuple(made)
        return cls(calls, shown, drawn)

    def request(self, exercise: ExerciseSpec, solution: str | None) -> dict[str, Any]:
        """What the probe after ``exercise``'s check cell is asked (plain data).

        ``solution``: the source of the notebook's answer cell, re-run on the
        hidden draws (None: none found, or the exercise has no draws).
        """
        request: dict[str, Any] = {
            "exercise": exercise.number,
            "names": [part.name for part in exercise.parts],
            "calls": {
                part.name: [dict(case.arguments) for case in self.calls[key]]
                for part in exercise.parts
                if (key := (exercise.number, part.name)) in self.calls
            },
            "forbidden": {
                part.name: list(part.forbidden)
                for part in exercise.parts
                if part.forbidden
            },
        }
        if solution is not None and self.draws.get(exercise.number):
            request["rerun"] = {
                "source": solution,
                "draws": [dict(draw.inputs) for draw in self.draws[exercise.number]],
            }
        return request
