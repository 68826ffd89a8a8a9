"""Each chapter's outline: its sections, its casebook and the casebook's share.

A chapter reads as a main line (numbered sections, Pitfalls, Exercises,
Summary) followed by one last section, ``## Casebook: the coursework``, whose
``###`` entries reproduce and correct what the source coursework did; each
entry names the item of the course's source record it rests on
(``Source record: H3.2.``).  This module finds those parts in a notebook's
JSON; ``tests/notebooks/test_reading_structure.py`` checks them and this script prints
them.

Usage::

    python tools/outline.py                 # every chapter: cells, casebook share, entries
    python tools/outline.py notebooks/03_jacobian_velocity.ipynb
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import pathlib
import re
import sys
from collections.abc import Sequence

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import course_map  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
NOTEBOOK_DIR = ROOT / "notebooks"
CASEBOOK_HEADING = "Casebook: the coursework"
#: The largest share of a chapter's cells its casebook may take.
MAX_CASEBOOK_SHARE = 0.25
#: One item of the source record, plain (``H3.2``) or linked to its anchor on the
#: record's page (``[H3.2](source_record.ipynb#h3-2)``).
_RECORD_ITEM = r"\[?(?:H\d\.\d+|G)\]?(?:\(source_record\.ipynb#[\w-]+\))?"
SOURCE_RECORD = re.compile(rf"Source record: ({_RECORD_ITEM}(?:, {_RECORD_ITEM})*)")
_RECORD_NAME = re.compile(r"H\d\.\d+|G")
_HEADING = re.compile(r"^(#{1,6})\s+(.+?)\s*#*\s*$")
_MARKUP = re.compile(r"[*_`]")


def chapters() -> list[pathlib.Path]:
    """The chapter notebooks, in order (the start page is not a chapter).

    Examples
    --------
    >>> chapters()[0].name
    '01_dh_forward_kinematics.ipynb'
    """
    return course_map.chapters(NOTEBOOK_DIR)


def heading_id(text: str) -> str:
    """The id JupyterLab and nbconvert give a heading: its text, spaces as ``-``.

    Inline markup (``**``, backticks) is dropped as the rendered text drops it.

    Examples
    --------
    >>> heading_id("Casebook: the coursework")
    'Casebook:-the-coursework'
    >>> heading_id("The `acos` **trap**")
    'The-acos-trap'
    """
    return _MARKUP.sub("", text).strip().replace(" ", "-")


@dataclasses.dataclass(frozen=True)
class Heading:
    """One markdown heading: its level, text, id and the index of its cell."""

    level: int
    text: str
    cell: int

    @property
    def id(self) -> str:
        return heading_id(self.text)


@dataclasses.dataclass(frozen=True)
class Entry:
    """One casebook entry: its heading, its cells and the source-record items it names."""

    heading: Heading
    end: int
    records: tuple[str, ...]


@dataclasses.dataclass(frozen=True)
class Outline:
    """A chapter's parts, by cell index."""

    path: pathlib.Path
    cells: list[dict]
    headings: list[Heading]
    casebook: int | None

    @property
    def main_line(self) -> list[dict]:
        """The cells before the casebook (all of them if there is none)."""
        return self.cells[: self.casebook] if self.casebook is not None else self.cells

    @property
    def casebook_share(self) -> float:
        """Cells from the casebook heading to the end, over all cells."""
        if self.casebook is None:
            return 0.0
        return (len(self.cells) - self.casebook) / len(self.cells)

    def entries(self) -> list[Entry]:
        """The casebook's ``###`` entries, each with the source records its first cells name."""
        if self.casebook is None:
            return []
        inside = [
            h
            for h in self.headings
            if h.cell > self.casebook or (h.cell == self.casebook and h.level == 3)
        ]
        found = []
        for number, heading in enumerate(inside):
            if heading.level != 3:
                continue
            later = [h.cell for h in inside[number + 1 :] if h.level <= 3]
            end = later[0] if later else len(self.cells)
            opening = [self.cells[heading.cell]]
            opening += [
                cell
                for cell in self.cells[heading.cell + 1 : end]
                if cell["cell_type"] == "markdown"
            ][:1]
            text = "\n".join(source(cell) for cell in opening)
            records = tuple(
                name
                for match in SOURCE_RECORD.finditer(text)
                for name in _RECORD_NAME.findall(match.group(1))
            )
            found.append(Entry(heading, end, records))
        return found


def source(cell: dict) -> str:
    """A cell's source as one string."""
    text = cell["source"]
    return text if isinstance(text, str) else "".join(text)


def headings_of(cells: Sequence[dict]) -> list[Heading]:
    """Every markdown heading outside code fences, in order."""
    found = []
    for index, cell in enumerate(cells):
        if cell["cell_type"] != "markdown":
            continue
        fenced = False
        for line in source(cell).splitlines():
            if line.lstrip().startswith("```"):
                fenced = not fenced
            match = None if fenced else _HEADING.match(line)
            if match:
                found.append(Heading(len(match.group(1)), match.group(2), index))
    return found


def outline(path: str | pathlib.Path) -> Outline:
    """Read a chapter and find its parts.

    Examples
    --------
    >>> chapter = outline(chapters()[0])
    >>> chapter.headings[0].text.startswith("Chapter 1")
    True
    """
    path = pathlib.Path(path)
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    headings = headings_of(cells)
    casebook = next(
        (h.cell for h in headings if h.level == 2 and h.text == CASEBOOK_HEADING), None
    )
    return Outline(path, cells, headings, casebook)


def report(paths: Sequence[pathlib.Path]) -> str:
    """A table: per chapter, its cells, casebook cells, share and entries."""
    lines = [
        "| chapter | cells | casebook cells | share | entries (source records) |",
        "|---|---:|---:|---:|---|",
    ]
    for path in paths:
        chapter = outline(path)
        casebook_cells = len(chapter.cells) - len(chapter.main_line)
        entries = "; ".join(
            f"{entry.heading.text} ({', '.join(entry.records) or 'none'})"
            for entry in chapter.entries()
        )
        lines.append(
            f"| {path.stem} | {len(chapter.cells)} | {casebook_cells} | "
            f"{chapter.casebook_share:.0%} | {entries or 'no casebook'} |"
        )
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=pathlib.Path)
    args = parser.parse_args(argv)
    print(report(args.notebooks or chapters()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
