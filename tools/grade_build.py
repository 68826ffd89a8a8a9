"""A returned notebook made ready to grade: released inputs restored, a probe for each check, cut to what the answers need.

:func:`build` takes a returned notebook's code cells in order and

- puts each exercise's released inputs cell in place of the returned one
  (found by :func:`grade_release.locate`: by nbgrader's ``grade_id`` or by
  content; one the student deleted is put back before the answer cell, and
  said so), and the probe in place of its check cell (the check's verdicts
  are the grader's: the check itself is not run; a deleted check cell is
  probed all the same, after the answer cell); an exercise whose answer cell
  cannot be found is not probed (not solved);
- a probe cell (``tools/grading_probe.py``, with the forbidden-call guard of
  ``twolink_course/exercises/forbidden.py``, both from the grader's own
  copies) asks what :class:`grade_plan.Plan` asks;
- drops every cell after the last probe and cuts the others to the
  statements the answers need (:func:`grade_prune.needed`).

Each built cell remembers the returned cell it came from (``positions``), so
an error is reported as "cell N" of the file the teacher has.
"""

from __future__ import annotations

import dataclasses
import pathlib
from typing import Any

import grading_probe  # tools/grading_probe.py
import nbformat
from grade_plan import Plan
from grade_prune import needed
from grade_read import Returned
from grade_release import Chapter, Where, locate

import twolink_course.exercises.forbidden as forbidden_module

#: The tag of the grader's probe cells.
PROBE_TAG = "grader-probe"


def _source(module: Any) -> str:
    return pathlib.Path(module.__file__).read_text(encoding="utf-8")


#: The probe's and the guard's sources, read once from the grader's own copies.
PROBE_SOURCE = _source(grading_probe)
GUARD_SOURCE = _source(forbidden_module)


def probe_source(request: dict[str, Any]) -> str:
    """The source of the cell that publishes the answers of ``request["exercise"]``."""
    return (
        f"# Added by the grader: the answers of exercise {request['exercise']}, as data.\n"
        f"_grader_guard = {{'__name__': 'grader_guard'}}\n"
        f"exec(compile({GUARD_SOURCE!r}, '<grader guard>', 'exec'), _grader_guard)\n"
        f"_grader_probe = {{'__name__': 'grader_probe'}}\n"
        f"exec(compile({PROBE_SOURCE!r}, '<grader probe>', 'exec'), _grader_probe)\n"
        f"_grader_probe['report']({request!r}, _grader_guard['unavailable'])\n"
        "del _grader_probe, _grader_guard\n"
    )


@dataclasses.dataclass
class Built:
    """A graded notebook, the exercises it probes, notes for the teacher, and each cell's origin."""

    notebook: Any
    probed: list[str]
    notes: list[str]
    positions: list[
        int | None
    ]  # the returned cell's number (from 1) of each built cell


def build(
    returned: Returned, chapter: Chapter, plan: Plan, *, prune: bool = True
) -> Built:
    """``returned`` made ready to grade as ``chapter`` (see the module's description)."""
    cells = returned.cells
    where: dict[str, Where] = {e.number: locate(cells, e) for e in chapter.exercises}
    role: dict[int, tuple[str, str]] = {}
    notes: list[str] = []
    for number, found in where.items():
        released = chapter.released[number]
        if found.solution is None:
            if found.check is not None:
                role[found.check] = ("check without answer", number)
            notes.append(f"no answer cell of exercise {number} found")
            continue
        role.setdefault(found.solution, ("solution", number))
        if found.check is None:
            notes.append(f"the check cell of exercise {number} was missing: put back")
        else:
            role[found.check] = ("check", number)
        if released.inputs is not None:
            if found.inputs is None:
                notes.append(
                    f"the inputs cell of exercise {number} was missing: put back"
                )
            else:
                role[found.inputs] = ("inputs", number)
    specs = {exercise.number: exercise for exercise in chapter.exercises}
    sources: list[str] = []
    positions: list[int | None] = []
    roots: set[int] = set()
    probed: list[str] = []
    trusted: set[str] = set(chapter.sources)

    def add(source: str, position: int | None, root: bool = False) -> None:
        if root:
            roots.add(len(sources))
        sources.append(source)
        positions.append(position)

    def check_and_probe(number: str, position: int | None) -> None:
        add("", position)  # the check: its verdicts are the grader's, not run
        if number in probed:
            return
        solution = where[number].solution
        request = plan.request(
            specs[number], cells[solution].source if solution is not None else None
        )
        source = probe_source(request)
        trusted.add(source)
        add(source, None, root=True)
        probed.append(number)

    for index, cell in enumerate(cells):
        if cell.kind != "code":
            continue
        kind, number = role.get(index, ("", ""))
        if kind == "inputs":
            add(chapter.released[number].inputs or "", index + 1, root=True)
        elif kind == "check":
            check_and_probe(number, index + 1)
        elif kind == "check without answer":
            add("", index + 1)
        elif kind == "solution":
            if (
                where[number].inputs is None
                and chapter.released[number].inputs is not None
            ):
                add(chapter.released[number].inputs or "", None, root=True)
            add(cell.source, index + 1, root=True)
            if where[number].check is None:
                check_and_probe(number, None)
        else:
            add(cell.source, index + 1)
    probes = {i: number for i, number in enumerate(_probe_numbers(sources, trusted))}
    last = max((i for i, number in probes.items() if number), default=-1)
    sources, positions = sources[: last + 1], positions[: last + 1]
    if prune:
        sources = needed(
            sources,
            {i for i in roots if i <= last},
            [part.name for exercise in chapter.exercises for part in exercise.parts],
            trusted
            | {c.check for c in chapter.released.values()}
            | {c.inputs for c in chapter.released.values() if c.inputs},
        )
    notebook = nbformat.v4.new_notebook()
    for index, source in enumerate(sources):
        cell = nbformat.v4.new_code_cell(source)
        if probes.get(index):
            cell.metadata["tags"] = [PROBE_TAG]
            cell.metadata["twolink_probe"] = probes[index]
        notebook.cells.append(cell)
    return Built(notebook, probed, notes, positions)


def _probe_numbers(sources: list[str], probes: set[str]) -> list[str]:
    """The exercise each built cell probes ("" for a cell that is no probe of the grader's)."""
    prefix = "# Added by the grader: the answers of exercise "
    return [
        source[len(prefix) :].split(",", 1)[0]
        if source in probes and source.startswith(prefix)
        else ""
        for source in sources
    ]
