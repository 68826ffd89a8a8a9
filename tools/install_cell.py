"""Every chapter's first code cell: install twolink where it is missing (Colab, a bare Jupyter).

In a clone (``make lab``, Binder) ``import twolink`` succeeds and the cell does
nothing.  Elsewhere it runs ``%pip install`` of the course package with its
course extras, from the environment variable ``TWOLINK_SOURCE`` when set (any
pip requirement: a fork's ``twolink[course] @ git+https://...`` or a local
``/path/to/twolink[course]``), else from the repository URL written in
``[project.urls]`` of pyproject.toml (by name, ``twolink[course]``, while
that URL is the placeholder).

Usage::

    python tools/install_cell.py notebooks/*.ipynb           # insert or update the cell
    python tools/install_cell.py --check notebooks/*.ipynb   # exit 1 if a notebook's first code cell differs
"""

from __future__ import annotations

import argparse
import pathlib
import sys
from collections.abc import Sequence
from typing import Any

import nbformat

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import links  # noqa: E402

ROOT = links.ROOT
#: The environment variable that overrides where the cell installs twolink from.
SOURCE_VARIABLE = "TWOLINK_SOURCE"
#: The cell's first line, which also marks a cell as the install cell.
MARKER = "# Setup: installs twolink only where `import twolink` fails (Colab, a bare Jupyter)."


def install_cell_source(default_requirement: str | None = None) -> str:
    """The canonical first code cell, installing ``default_requirement`` unless TWOLINK_SOURCE is set.

    Examples
    --------
    >>> print(install_cell_source("twolink[course]"))  # doctest: +ELLIPSIS
    # Setup: installs twolink only where `import twolink` fails (Colab, a bare Jupyter).
    # In a clone it does nothing.
    try:
        import twolink  # noqa: F401
    except ImportError:
        import os
    <BLANKLINE>
        source = os.environ.get("TWOLINK_SOURCE", "twolink[course]")
        print(
            f"twolink is not installed here: installing {source} "
            "(set TWOLINK_SOURCE to install from elsewhere)"
        )
        %pip install --quiet "{source}"
        import twolink  # noqa: F401
    """
    if default_requirement is None:
        default_requirement = links.install_requirement(links.repository_url())
    return "\n".join(
        [
            MARKER,
            "# In a clone it does nothing.",
            "try:",
            "    import twolink  # noqa: F401",
            "except ImportError:",
            "    import os",
            "",
            f"    source = os.environ.get({SOURCE_VARIABLE!r}, {default_requirement!r})".replace(
                "'", '"'
            ),
            "    print(",
            '        f"twolink is not installed here: installing {source} "',
            f'        "(set {SOURCE_VARIABLE} to install from elsewhere)"',
            "    )",
            '    %pip install --quiet "{source}"',
            "    import twolink  # noqa: F401",
        ]
    )


def _first_code_index(notebook: Any) -> int | None:
    for index, cell in enumerate(notebook.cells):
        if cell.cell_type == "code":
            return index
    return None


def is_up_to_date(notebook: Any, source: str | None = None) -> bool:
    """Whether the notebook's first code cell is exactly the install cell."""
    source = install_cell_source() if source is None else source
    index = _first_code_index(notebook)
    return index is not None and notebook.cells[index].source == source


def apply(notebook: Any, source: str | None = None) -> bool:
    """Insert the install cell before the first code cell, or update it if it is already there.

    Returns True if the notebook changed.  Applying twice changes nothing the second time.
    """
    source = install_cell_source() if source is None else source
    index = _first_code_index(notebook)
    if index is not None and notebook.cells[index].source == source:
        return False
    if index is not None and notebook.cells[index].source.startswith(MARKER):
        notebook.cells[index].source = source
        notebook.cells[index].outputs = []
        notebook.cells[index].execution_count = None
        return True
    cell = nbformat.v4.new_code_cell(source)
    if "id" not in next(
        (c for c in notebook.cells), {}
    ):  # notebooks stored without cell ids stay so
        cell.pop("id", None)
    notebook.cells.insert(len(notebook.cells) if index is None else index, cell)
    return True


def main(argv: Sequence[str] | None = None) -> int:
    """Write (or with ``--check``, check) the install cell of the notebooks named; 1 if any is stale."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument(
        "--check",
        action="store_true",
        help="fail if a notebook's first code cell is not the install cell",
    )
    parser.add_argument("notebooks", nargs="*", type=pathlib.Path)
    args = parser.parse_args(argv)
    paths = args.notebooks or sorted((ROOT / "notebooks").glob("*.ipynb"))
    source = install_cell_source()
    stale: list[pathlib.Path] = []
    for path in paths:
        notebook = nbformat.read(path, as_version=4)
        if args.check:
            if not is_up_to_date(notebook, source):
                stale.append(path)
        elif apply(notebook, source):
            nbformat.write(notebook, path)
            print(
                f"{path}: install cell written (re-execute it: make notebooks NOTEBOOKS={path})"
            )
    if stale:
        for path in stale:
            print(
                f"{path}: the first code cell is not the install cell; run `python tools/install_cell.py {path}`",
                file=sys.stderr,
            )
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
