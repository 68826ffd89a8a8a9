"""Every chapter's first code cell: install twolink where it is missing (Colab, a bare Jupyter, the student edition).

In a clone (``make lab``, Binder) ``import twolink`` succeeds and the cell does
nothing and prints nothing.  Elsewhere it runs ``%pip install`` of the course
package with its course extras (``[course]``) from the first of

1. a twolink wheel beside the notebook (``twolink-*.whl`` in the kernel's
   working directory, which Jupyter sets to the notebook's folder): the student
   edition ships one (``tools/editions.py student``);
2. the environment variable ``TWOLINK_SOURCE`` when set (any pip requirement:
   a fork's ``twolink[course] @ git+https://...`` or a local
   ``/path/to/twolink[course]``);
3. the public index or repository: the URL written in ``[project.urls]`` of
   pyproject.toml (by name, ``twolink[course]``, while that URL is the
   placeholder),

and prints which one it used.

Usage::

    python tools/install_cell.py                             # every chapter: insert or update the cell
    python tools/install_cell.py notebooks/02_inverse_kinematics.ipynb
    python tools/install_cell.py --check                     # exit 1 if a chapter's first code cell differs

Without arguments it treats every chapter (``notebooks/NN_*.ipynb``), never
the start page ``notebooks/00_start_here.ipynb``, which has no code.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
from collections.abc import Sequence
from typing import Any

import nbformat

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import course_map  # noqa: E402
import links  # noqa: E402

ROOT = links.ROOT
#: The environment variable that overrides where the cell installs twolink from.
SOURCE_VARIABLE = "TWOLINK_SOURCE"
#: The wheels the cell looks for beside the notebook.
WHEEL_PATTERN = "twolink-*.whl"
#: The cell's first line, which also marks a cell as the install cell.
MARKER = "# Setup: installs twolink only where `import twolink` fails (Colab, a bare Jupyter)."
#: What the cell prints for each of its three sources, after "installing {source} from ".
FROM_WHEEL = "the wheel beside this notebook"
FROM_VARIABLE = SOURCE_VARIABLE
FROM_INDEX = "the package index"


def install_cell_source(default_requirement: str | None = None) -> str:
    """The canonical first code cell; ``default_requirement`` is what it installs when nothing else is there.

    Examples
    --------
    >>> print(install_cell_source("twolink[course]"))  # doctest: +ELLIPSIS
    # Setup: installs twolink only where `import twolink` fails (Colab, a bare Jupyter).
    # In a clone it does nothing. Elsewhere it installs twolink with the course's
    # packages from a twolink wheel in this folder, else from TWOLINK_SOURCE, else
    # from the package index.
    try:
        import twolink  # noqa: F401
    except ImportError:
        import glob
        import os
    <BLANKLINE>
        wheels = sorted(glob.glob("twolink-*.whl"))
        if wheels:
            source, origin = f"{wheels[-1]}[course]", "the wheel beside this notebook"
        elif os.environ.get("TWOLINK_SOURCE"):
            source, origin = os.environ["TWOLINK_SOURCE"], "TWOLINK_SOURCE"
        else:
            source, origin = "twolink[course]", "the package index"
        print(f"twolink is not installed here: installing {source} from {origin}")
        %pip install --quiet "{source}"
        import twolink  # noqa: F401
    """
    if default_requirement is None:
        default_requirement = links.install_requirement(links.repository_url())
    index_origin = (
        FROM_INDEX if default_requirement == "twolink[course]" else "the repository"
    )

    def quoted(text: str) -> str:
        return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'

    index_choice = f"        source, origin = {quoted(default_requirement)}, {quoted(index_origin)}"
    if (
        len(index_choice) > 88
    ):  # as ruff format writes a long line (a long repository URL)
        index_choice = "\n".join(
            [
                "        source, origin = (",
                f"            {quoted(default_requirement)},",
                f"            {quoted(index_origin)},",
                "        )",
            ]
        )

    return "\n".join(
        [
            MARKER,
            "# In a clone it does nothing. Elsewhere it installs twolink with the course's",
            f"# packages from a twolink wheel in this folder, else from {SOURCE_VARIABLE}, else",
            f"# from {index_origin}.",
            "try:",
            "    import twolink  # noqa: F401",
            "except ImportError:",
            "    import glob",
            "    import os",
            "",
            f"    wheels = sorted(glob.glob({quoted(WHEEL_PATTERN)}))",
            "    if wheels:",
            f'        source, origin = f"{{wheels[-1]}}[course]", {quoted(FROM_WHEEL)}',
            f"    elif os.environ.get({quoted(SOURCE_VARIABLE)}):",
            f"        source, origin = os.environ[{quoted(SOURCE_VARIABLE)}], {quoted(FROM_VARIABLE)}",
            "    else:",
            index_choice,
            '    print(f"twolink is not installed here: installing {source} from {origin}")',
            '    %pip install --quiet "{source}"',
            "    import twolink  # noqa: F401",
        ]
    )


#: The student edition's pins, beside its wheel (tools/editions.py copies constraints.txt).
CONSTRAINTS = "constraints.txt"
#: The one line the student edition's cell prints when it installed the widgets' page
#: code into the running Jupyter: the page loaded before it, so the sliders need a reload.
RELOAD_LINE = (
    "twolink is installed. Reload this page (F5, or Cmd+R on a Mac) and run all cells "
    "again: the sliders appear after the reload."
)


def student_install_cell_source() -> str:
    """The student edition's first code cell: the wheel beside it, at the course's versions.

    Where ``import twolink`` fails it installs the wheel beside the notebook with
    the course's packages, pinned by ``constraints.txt`` beside it (the versions
    the course was made with, not the newest), and, when that installed the
    widgets' page code (``jupyterlab_widgets``) into the running Jupyter,
    prints :data:`RELOAD_LINE`: a page loaded before the install cannot show
    the sliders until it is reloaded.

    Examples
    --------
    >>> source = student_install_cell_source()
    >>> source.startswith(MARKER), '-c "constraints.txt"' in source
    (True, True)
    """

    def quoted(text: str) -> str:
        return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'

    return "\n".join(
        [
            MARKER,
            "# The student edition: it installs twolink with the course's packages from the wheel",
            f"# in this folder, at the versions of {CONSTRAINTS} beside it.",
            "try:",
            "    import twolink  # noqa: F401",
            "except ImportError:",
            "    import glob",
            "    import importlib.util",
            "",
            f"    wheels = sorted(glob.glob({quoted(WHEEL_PATTERN)}))",
            "    if not wheels:",
            "        raise FileNotFoundError(",
            '            "the edition\'s twolink wheel (twolink-*.whl) is not beside this notebook: "',
            '            "unzip the whole edition into one folder and open the notebook there"',
            "        )",
            "    wheel = wheels[-1]",
            '    widgets_here = importlib.util.find_spec("jupyterlab_widgets") is not None',
            f'    print(f"twolink is not installed here: installing {{wheel}}[course] from {FROM_WHEEL}")',
            f'    %pip install --quiet "{{wheel}}[course]" -c {quoted(CONSTRAINTS)}',
            "    import twolink  # noqa: F401",
            "",
            "    if not widgets_here:",
            f"        print({quoted(RELOAD_LINE)})",
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
    paths = args.notebooks or course_map.chapters(ROOT / "notebooks")
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
