"""Reading any notebook a student can return: a JupyterLab, Colab or VS Code save, nbformat 3, id-less.

:func:`read_returned` takes from a file only what grading needs, each cell's
kind, source and nbgrader ``grade_id``, and the edition the notebook was
handed out from (``metadata.twolink_edition``, :mod:`editions`):

- a path that is not a regular file (a symbolic link, a FIFO, a device) or
  is larger than ``max_bytes`` is refused unread (:func:`refusal`);
- the JSON is parsed as is; a notebook of nbformat 3 (``worksheets``, code
  cells with ``input``) is converted by nbformat first, its outputs dropped
  before (they are never read: the grader runs the notebook afresh);
- sources may be strings or lists of lines; cell ids, outputs, execution
  counts and any other metadata (Colab's, VS Code's) are ignored, so no
  schema is validated over a notebook's outputs (a 45 MB notebook of
  outputs is read in a fraction of a second).

Anything else (not JSON, no cell list, a cell without a known kind) is
unreadable, with a reason in words (:class:`Unreadable`).
"""

from __future__ import annotations

import dataclasses
import json
import os
import pathlib
import stat
from collections.abc import Mapping
from typing import Any

import nbformat

#: Larger files are refused unread (a chapter with its outputs is 0.4 to 2.5 MB).
MAX_NOTEBOOK_BYTES = 50_000_000
CELL_KINDS = ("code", "markdown", "raw")


class Unreadable(Exception):
    """A file that is no notebook the grader can read: the message says why."""


@dataclasses.dataclass(frozen=True)
class Cell:
    """A returned cell: its kind, its source and its nbgrader ``grade_id`` (or None)."""

    kind: str
    source: str
    grade_id: str | None = None


@dataclasses.dataclass(frozen=True)
class Returned:
    """A returned notebook: its cells, and the edition it says it was handed out from (or None)."""

    cells: tuple[Cell, ...]
    edition: Mapping[str, Any] | None = None


def refusal(path: pathlib.Path, max_bytes: int = MAX_NOTEBOOK_BYTES) -> str | None:
    """Why ``path`` is not opened (not a regular file, too large), or None."""
    try:
        info = os.lstat(path)
    except OSError as error:
        return f"refused: cannot stat it ({error.strerror})"
    if stat.S_ISLNK(info.st_mode):
        return "refused: a symbolic link, not a regular file"
    if not stat.S_ISREG(info.st_mode):
        return "refused: not a regular file (a FIFO, a device or a socket)"
    if info.st_size > max_bytes:
        return f"refused: {info.st_size} bytes, more than {max_bytes} (the limit per notebook)"
    return None


def _text(source: Any) -> str:
    if isinstance(source, str):
        return source
    if isinstance(source, list) and all(isinstance(line, str) for line in source):
        return "".join(source)
    raise Unreadable(f"a cell's source is a {type(source).__name__}, not text")


def _grade_id(metadata: Any) -> str | None:
    if not isinstance(metadata, dict):
        return None
    nbgrader = metadata.get("nbgrader")
    if isinstance(nbgrader, dict) and isinstance(nbgrader.get("grade_id"), str):
        return nbgrader["grade_id"]
    return None


def _from_version_3(data: dict[str, Any]) -> dict[str, Any]:
    """An nbformat 3 notebook converted to 4 by nbformat (outputs dropped first)."""
    for worksheet in data.get("worksheets", []) or []:
        for cell in worksheet.get("cells", []) if isinstance(worksheet, dict) else []:
            if isinstance(cell, dict):
                cell.pop("outputs", None)
                cell["outputs"] = []
    try:
        converted = nbformat.reads(json.dumps(data), as_version=4)
    except Exception as error:  # nbformat's own errors, many kinds
        raise Unreadable(
            f"nbformat {data.get('nbformat')} that nbformat cannot convert ({type(error).__name__})"
        ) from None
    return dict(converted)


def parse(text: str | bytes) -> Returned:
    """The cells and edition of a notebook's JSON text (any nbformat from 3 on)."""
    try:
        data = json.loads(text)
    except (ValueError, UnicodeDecodeError) as error:
        raise Unreadable(
            f"not JSON ({type(error).__name__}: {str(error)[:80]})"
        ) from None
    if not isinstance(data, dict):
        raise Unreadable("not a notebook (its JSON is not an object)")
    version = data.get("nbformat")
    if version == 3 or (version is None and "worksheets" in data):
        data = _from_version_3(data)
    elif not isinstance(version, int) or version < 3 or version > 4:
        raise Unreadable(f"not a notebook of nbformat 3 or 4 (nbformat: {version!r})")
    cells = data.get("cells")
    if not isinstance(cells, list):
        raise Unreadable("not a notebook (no list of cells)")
    read = []
    for number, cell in enumerate(cells, start=1):
        if not isinstance(cell, dict) or cell.get("cell_type") not in CELL_KINDS:
            raise Unreadable(f"cell {number} is no code, Markdown or raw cell")
        if "source" not in cell:
            raise Unreadable(f"cell {number} has no source")
        read.append(
            Cell(
                cell["cell_type"],
                _text(cell["source"]),
                _grade_id(cell.get("metadata")),
            )
        )
    metadata = data.get("metadata")
    edition = metadata.get("twolink_edition") if isinstance(metadata, dict) else None
    return Returned(tuple(read), edition if isinstance(edition, dict) else None)


def read_bytes(path: pathlib.Path, max_bytes: int = MAX_NOTEBOOK_BYTES) -> bytes:
    """At most ``max_bytes + 1`` bytes of the regular file ``path``, never through a symbolic
    link and never waiting on a FIFO (an ``OSError`` for those)."""

    def opener(name: str, flags: int) -> int:
        return os.open(name, flags | os.O_NOFOLLOW | os.O_NONBLOCK)

    with open(path, "rb", opener=opener) as handle:
        if not stat.S_ISREG(os.fstat(handle.fileno()).st_mode):
            raise OSError(0, "not a regular file")
        return handle.read(max_bytes + 1)


def read_returned(path: pathlib.Path, max_bytes: int = MAX_NOTEBOOK_BYTES) -> Returned:
    """The notebook at ``path``, read as :func:`parse` does; :class:`Unreadable` if refused or unreadable."""
    reason = refusal(path, max_bytes)
    if reason is not None:
        raise Unreadable(reason)
    try:
        text = read_bytes(path, max_bytes)
    except OSError as error:
        raise Unreadable(f"refused: cannot read it ({error.strerror})") from None
    if len(text) > max_bytes:
        raise Unreadable(
            f"refused: more than {max_bytes} bytes (the limit per notebook)"
        )
    return parse(text)
