"""Build the course's other editions from the committed notebooks.

- Student edition (``make student`` -> ``build/student/``): every
  ``### BEGIN SOLUTION`` ... ``### END SOLUTION`` block is replaced by stubs
  (``name = ...  # your code here`` for each answer the next self-check
  reads), and the outputs of those cells and of the self-check cells are
  cleared, so nothing says "correct" before the student has written a line.
  Self-checks report "not solved yet" for a ``...`` answer, so the notebook
  still runs top to bottom.  Markdown is edition-aware: a passage between
  ``<!-- BEGIN INSTRUCTOR -->`` and ``<!-- END INSTRUCTOR -->`` is dropped, a
  ``<!-- STUDENT: text -->`` comment becomes visible text, and the chapters'
  "Each exercise cell holds a worked solution ..." paragraph is replaced by
  the student's instructions.
  A ``### BEGIN HIDDEN TESTS`` ... ``### END HIDDEN TESTS`` block (the score
  line nbgrader reads at the end of each check cell, ``tools/nbgrader_cells.py``)
  is removed, as ``nbgrader generate_assignment`` removes it.
  The edition runs on its own, away from the repository: beside the notebooks
  (the chapters and the start page ``00_start_here.ipynb``) it holds a wheel
  of twolink, which each chapter's first cell installs when ``import
  twolink`` fails (``tools/install_cell.py``), and the whole folder is zipped
  beside it (``build/student.zip``) for handing out.
- Static edition (``make site`` -> ``build/site/``): every executed notebook
  (the start page first, then the chapters) rendered to HTML by nbconvert,
  with an index page linking them in order; links between notebooks
  (``02_inverse_kinematics.ipynb``) lead to their pages
  (``02_inverse_kinematics.html``); hidden-test blocks and the score they
  print are left out.
  MathJax is served from the ``jupyter-server-mathjax`` package's copy, so the
  pages load nothing from the network.

Usage: ``python tools/editions.py student|site [--source notebooks] [--out DIR]``
(``student`` writes ``DIR`` and ``DIR.zip``).
"""

from __future__ import annotations

import argparse
import ast
import copy
import hashlib
import html
import json
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile
from collections.abc import Sequence
from typing import Any

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import install_cell  # noqa: E402  (tools/install_cell.py: the chapters' first cell)

BEGIN = "### BEGIN SOLUTION"
END = "### END SOLUTION"
STUB_COMMENT = "# your code here"
ROOT = pathlib.Path(__file__).resolve().parent.parent

SOLUTION_BLOCK = re.compile(
    r"^(?P<indent>[ \t]*)"
    + re.escape(BEGIN)
    + r"[^\n]*\n(?P<body>.*?)^[ \t]*"
    + re.escape(END)
    + r"[^\n]*(\n|$)",
    re.MULTILINE | re.DOTALL,
)


BEGIN_HIDDEN = "### BEGIN HIDDEN TESTS"
END_HIDDEN = "### END HIDDEN TESTS"

#: A hidden-test block: from its BEGIN line to its END line, and the line break after it.
HIDDEN_BLOCK = re.compile(
    r"^[ \t]*"
    + re.escape(BEGIN_HIDDEN)
    + r"[^\n]*\n.*?^[ \t]*"
    + re.escape(END_HIDDEN)
    + r"[^\n]*(\n|$)",
    re.MULTILINE | re.DOTALL,
)


def strip_hidden_tests(source: str) -> str:
    r"""``source`` without its ``### BEGIN HIDDEN TESTS`` ... ``### END HIDDEN TESTS`` blocks.

    The line break before a block that ends the cell goes with it, so a check
    cell reads as it did before the block was added.

    >>> strip_hidden_tests("x = 1\n### BEGIN HIDDEN TESTS\nassert x\n### END HIDDEN TESTS\ny = x\n")
    'x = 1\ny = x\n'

    >>> strip_hidden_tests("r = check()\n### BEGIN HIDDEN TESTS\nr.score\n### END HIDDEN TESTS")
    'r = check()'
    >>> strip_hidden_tests("x = 1\n")
    'x = 1\n'
    """
    if source.count(BEGIN_HIDDEN) != source.count(END_HIDDEN):
        raise ValueError(f"unbalanced hidden-test markers in cell:\n{source[:200]}")
    kept, start = [], 0
    for match in HIDDEN_BLOCK.finditer(source):
        before = source[start : match.start()]
        if match.end() == len(source) and not match[0].endswith("\n"):
            before = before.removesuffix("\n")  # the block ended the cell
        kept.append(before)
        start = match.end()
    return "".join(kept) + source[start:]


def assigned_names(code: str) -> list[str]:
    r"""Names a solution block binds, in order of first appearance.

    Assignments anywhere in the block count (inside ``try``, ``if``, ``for``,
    ``with``), except inside nested functions, classes, lambdas and
    comprehensions, whose own names are local to them.

    >>> assigned_names("x = 1\ny, z = 2, 3\nx += 1\ndef f():\n    w = 0")
    ['x', 'y', 'z', 'f']
    >>> assigned_names("try:\n    pass\nexcept ValueError as error:\n    message = str(error)")
    ['message']
    """
    names: list[str] = []

    class Collector(ast.NodeVisitor):
        def visit_Name(self, node: ast.Name) -> None:
            if isinstance(node.ctx, ast.Store) and node.id not in names:
                names.append(node.id)

        def visit_FunctionDef(
            self, node: ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef
        ) -> None:
            if node.name not in names:
                names.append(node.name)

        visit_AsyncFunctionDef = visit_ClassDef = visit_FunctionDef

        def visit_Lambda(self, node: ast.AST) -> None:
            pass

        visit_ListComp = visit_SetComp = visit_DictComp = visit_GeneratorExp = (
            visit_Lambda
        )

    Collector().visit(ast.parse(code))
    return names


def stub_source(source: str, checked_names: set[str] | None = None) -> str:
    """Replace each solution block of a cell's source by stubs for the names it assigns.

    >>> print(stub_source("# Exercise\\n### BEGIN SOLUTION\\np_tip = [1, 2]\\n### END SOLUTION\\n"))
    # Exercise
    p_tip = ...  # your code here
    <BLANKLINE>
    """

    def replace(match: re.Match[str]) -> str:
        indent = match.group("indent")
        body = "\n".join(
            line[len(indent) :] if line.startswith(indent) else line
            for line in match.group("body").splitlines()
        )
        names = assigned_names(body)
        if checked_names is not None:
            # stub only the answers the self-check reads, not the solution's helper variables
            names = [name for name in names if name in checked_names] or names
        if not names:
            raise ValueError(
                f"a solution block assigns no name, so it cannot be stubbed:\n{match.group('body')}"
            )
        return "".join(f"{indent}{name} = ...  {STUB_COMMENT}\n" for name in names)

    if source.count(BEGIN) != source.count(END):
        raise ValueError(f"unbalanced solution markers in cell:\n{source[:200]}")
    return SOLUTION_BLOCK.sub(replace, source)


def loaded_names(code: str) -> set[str]:
    """Names a piece of code reads.

    >>> sorted(loaded_names("check(p_tip, arm.fk(q))"))
    ['arm', 'check', 'p_tip', 'q']
    """
    return {
        node.id
        for node in ast.walk(ast.parse(code))
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load)
    }


def next_selfcheck_names(
    cells: Sequence[dict[str, Any]], start: int
) -> set[str] | None:
    """Names read by the first self-check cell after ``cells[start]``, before the next solution."""
    for cell in cells[start + 1 :]:
        if cell["cell_type"] != "code":
            continue
        source = "".join(cell["source"])
        if BEGIN in source:
            return None
        if "selfcheck.check" in source:
            return loaded_names(source)
    return None


INSTRUCTOR_PASSAGE = re.compile(
    r"<!-- BEGIN INSTRUCTOR -->.*?<!-- END INSTRUCTOR -->\n?", re.DOTALL
)
STUDENT_PASSAGE = re.compile(r"<!-- STUDENT: (?P<text>.*?) -->", re.DOTALL)
WORKED_SOLUTIONS_PARAGRAPH = re.compile(
    r"Each exercise cell holds a worked solution.*?(?=\n\n|\Z)", re.DOTALL
)
STUDENT_INSTRUCTIONS = (
    "Each exercise cell ends with one `name = ...` line per answer: replace each `...` with your\n"
    "answer (code that computes it) and run the cell after it, which checks your answers and says\n"
    '"not solved yet" for any `...` left.'
)


def student_markdown(source: str) -> str:
    """The student edition of a Markdown cell's text.

    >>> student_markdown("Intro.<!-- BEGIN INSTRUCTOR --> Solutions inside.<!-- END INSTRUCTOR --> <!-- STUDENT: Try. -->")
    'Intro. Try.'
    >>> student_markdown("## Exercises\\n\\nEach exercise cell holds a worked solution.\\n\\nMore.").splitlines()[2][:30]
    'Each exercise cell ends with o'
    """
    source = INSTRUCTOR_PASSAGE.sub("", source)
    source = STUDENT_PASSAGE.sub(lambda match: match.group("text"), source)
    return WORKED_SOLUTIONS_PARAGRAPH.sub(STUDENT_INSTRUCTIONS, source)


def is_selfcheck_cell(cell: dict[str, Any]) -> bool:
    """A code cell that calls the self-checks."""
    return cell["cell_type"] == "code" and "selfcheck.check" in "".join(cell["source"])


def student_notebook(notebook: dict[str, Any]) -> dict[str, Any]:
    """A copy of a notebook (as a JSON dict) with solutions stubbed and their outputs cleared.

    Each solution block becomes ``name = ...`` stubs for the names the next
    self-check reads (all names the block assigns if it reads none of them),
    so the stub asks for the answers, not for the worked solution's steps.
    Hidden-test blocks are removed (:func:`strip_hidden_tests`), the
    self-check cells' outputs are cleared and the Markdown is made
    student-facing (:func:`student_markdown`).
    """
    student = copy.deepcopy(notebook)
    cells = student["cells"]
    for index, cell in enumerate(cells):
        source = "".join(cell["source"])
        if cell["cell_type"] == "markdown":
            cell["source"] = student_markdown(source)
            continue
        if cell["cell_type"] != "code":
            continue
        if BEGIN in source:
            cell["source"] = stub_source(source, next_selfcheck_names(cells, index))
        if BEGIN_HIDDEN in source:
            cell["source"] = strip_hidden_tests(source)
        if BEGIN in source or BEGIN_HIDDEN in source or is_selfcheck_cell(cell):
            cell["outputs"] = []
            cell["execution_count"] = None
    return student


def without_hidden_tests(notebook: dict[str, Any]) -> dict[str, Any]:
    r"""``notebook`` with each hidden-test block removed, and the result it showed.

    For the static site: a check cell shows its verdicts, not the score line
    nbgrader reads (``correct_ex1.score``) nor its value.

    >>> cell = {"cell_type": "code", "source": "r = check()\n### BEGIN HIDDEN TESTS\nr.score\n### END HIDDEN TESTS",
    ...         "outputs": [{"output_type": "stream", "text": "correct."}, {"output_type": "execute_result"}]}
    >>> without_hidden_tests({"cells": [cell]})["cells"][0]
    {'cell_type': 'code', 'source': 'r = check()', 'outputs': [{'output_type': 'stream', 'text': 'correct.'}]}
    """
    shown = copy.deepcopy(notebook)
    for cell in shown["cells"]:
        source = "".join(cell["source"])
        if cell["cell_type"] == "code" and BEGIN_HIDDEN in source:
            cell["source"] = strip_hidden_tests(source)
            cell["outputs"] = [
                output
                for output in cell.get("outputs", [])
                if output["output_type"] != "execute_result"
            ]
    return shown


def with_student_install_cell(notebook: dict[str, Any]) -> dict[str, Any]:
    """``notebook`` whose install cell (``tools/install_cell.py``) is the student edition's.

    The edition's cell installs the wheel beside it at the course's versions
    (``constraints.txt`` beside it) and says when the page must be reloaded
    for the sliders (:func:`install_cell.student_install_cell_source`).

    >>> cell = {"cell_type": "code", "source": install_cell.MARKER + "\\n%pip install x",
    ...         "outputs": [], "execution_count": 1}
    >>> student = with_student_install_cell({"cells": [cell]})["cells"][0]
    >>> student["source"] == install_cell.student_install_cell_source(), student["execution_count"]
    (True, None)
    """
    edition = copy.deepcopy(notebook)
    for cell in edition["cells"]:
        source = cell["source"]
        text = "".join(source) if isinstance(source, list) else source
        if cell["cell_type"] == "code" and text.startswith(install_cell.MARKER):
            cell["source"] = install_cell.student_install_cell_source()
            cell["outputs"] = []
            cell["execution_count"] = None
    return edition


def build_student(
    source_dir: str | pathlib.Path, out_dir: str | pathlib.Path
) -> list[pathlib.Path]:
    """Write the student edition of every notebook in ``source_dir`` to ``out_dir``."""
    source_dir, out_dir = pathlib.Path(source_dir), pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written: list[pathlib.Path] = []
    for path in sorted(source_dir.glob("*.ipynb")):
        notebook = json.loads(path.read_text(encoding="utf-8"))
        target = out_dir / path.name
        target.write_text(
            json.dumps(
                with_student_install_cell(student_notebook(notebook)),
                indent=1,
                ensure_ascii=False,
            )
            + "\n",
            encoding="utf-8",
        )
        written.append(target)
    return written


#: The files of the repository a wheel of twolink (the library and the course kit) is built from.
WHEEL_INPUTS = (
    "pyproject.toml",
    "README.md",
    "LICENSE*",
    "twolink",
    "twolink_course",
    "labextension/twolink_figure_alt/labextension",
)


def _copy_wheel_inputs(destination: pathlib.Path) -> None:
    """Copy what the wheel is built from: the files git tracks, else (no git checkout) the tree."""
    try:
        listed = subprocess.run(
            ["git", "ls-files", "-z", "--", *WHEEL_INPUTS],
            cwd=ROOT,
            capture_output=True,
            check=True,
        )
        names = [name for name in listed.stdout.decode().split("\0") if name]
    except (OSError, subprocess.CalledProcessError):  # no git, or not a checkout
        names = []
    if not names:  # the tree as it is
        names = [
            str(path.relative_to(ROOT))
            for pattern in WHEEL_INPUTS
            for found in ROOT.glob(pattern)
            for path in ([found] if found.is_file() else found.rglob("*"))
            if path.is_file() and "__pycache__" not in path.parts
        ]
    for name in names:
        if (ROOT / name).is_file():
            (destination / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, destination / name)


def build_wheel(out_dir: str | pathlib.Path) -> pathlib.Path:
    """Build a wheel of twolink into ``out_dir`` (``pip wheel --no-deps``) and return its path.

    It is built from a copy of the package files git tracks (as they are in
    the working tree), so nothing untracked (a stray module, ``build/lib``)
    gets in and the checkout is not written to; an older ``twolink-*.whl`` in
    ``out_dir`` is removed first.
    """
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    for old in out_dir.glob("twolink-*.whl"):
        old.unlink()
    with tempfile.TemporaryDirectory() as scratch:
        source = pathlib.Path(scratch, "twolink")
        _copy_wheel_inputs(source)
        built = subprocess.run(
            [
                sys.executable,
                "-m",
                "pip",
                "wheel",
                "--no-deps",
                "--quiet",
                "--disable-pip-version-check",
                "--wheel-dir",
                str(out_dir),
                str(source),
            ],
            capture_output=True,
            text=True,
            check=False,
        )
    wheels = sorted(out_dir.glob("twolink-*.whl"))
    if built.returncode != 0 or len(wheels) != 1:
        raise RuntimeError(
            f"building the twolink wheel failed (pip wheel exit {built.returncode}, "
            f"{len(wheels)} wheels):\n{built.stderr[-2000:]}"
        )
    return wheels[0]


# ------------------------------------------------------------------ the edition's record (grading)


def exercise_digest(notebook: dict[str, Any]) -> str:
    """A digest of what grading a chapter depends on: its check cells (hidden tests left out)
    and inputs cells (``# Inputs of exercise N.M``).  Two editions of a chapter with the same
    digest grade alike.

    >>> cell = {"cell_type": "code", "source": 'r = selfcheck.check("1.1", x)'}
    >>> exercise_digest({"cells": [cell]}) == exercise_digest({"cells": [cell, {"cell_type": "markdown", "source": "x"}]})
    True
    """
    kept = []
    for cell in notebook["cells"]:
        source = (
            "".join(cell["source"])
            if isinstance(cell["source"], list)
            else cell["source"]
        )
        if is_selfcheck_cell(cell):
            kept.append(strip_hidden_tests(source))
        elif cell["cell_type"] == "code" and source.startswith("# Inputs of exercise "):
            kept.append(source)
    return hashlib.sha256(json.dumps(kept).encode("utf-8")).hexdigest()[:12]


def commit_of(folder: pathlib.Path = ROOT) -> str:
    """The commit of the checkout (``+changes`` after it if the notebooks or packages differ from it), or ``unknown``."""
    try:
        commit = subprocess.run(
            ["git", "rev-parse", "HEAD"],
            cwd=folder,
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        changed = subprocess.run(
            ["git", "status", "--porcelain", "--", "notebooks", "twolink", "twolink_course", "answers"],
            cwd=folder, capture_output=True, text=True, check=True,
        ).stdout.strip()  # fmt: skip
    except (OSError, subprocess.CalledProcessError):
        return "unknown"
    return commit + ("+changes" if changed else "")


def record_edition(notebooks: Sequence[pathlib.Path]) -> str:
    """Record in each chapter's metadata (``twolink_edition``: the commit and the chapter's
    :func:`exercise_digest`) what the edition was built from; a returned notebook keeps it, and
    ``make grade`` warns when it differs from the chapters it grades with.  Returns the commit."""
    commit = commit_of()
    for path in notebooks:
        notebook = json.loads(path.read_text(encoding="utf-8"))
        if any(is_selfcheck_cell(cell) for cell in notebook["cells"]):
            notebook["metadata"]["twolink_edition"] = {
                "commit": commit,
                "digest": exercise_digest(notebook),
            }
            path.write_text(
                json.dumps(notebook, indent=1, ensure_ascii=False) + "\n",
                encoding="utf-8",
            )
    return commit


def student_readme(start_page: str = "00_start_here.ipynb") -> str:
    """The student edition's README.md: how to open it, the first run's reload, handing back.

    >>> text = student_readme()
    >>> "00_start_here.ipynb" in text and install_cell.RELOAD_LINE in text
    True
    """
    return f"""# twolink: a course on the two-link robot arm (student edition)

1. Unzip this folder and open it in JupyterLab (or Jupyter Notebook, VS Code, Colab).
2. Open `{start_page}`, the start page: it says what each chapter teaches and how
   long it takes, and links to the chapters.
3. Run all cells of a notebook. Its first code cell installs the course (the
   `twolink` wheel in this folder, at the versions of `constraints.txt`). The first
   time, it installs the sliders' page code into your Jupyter and prints one line:

   > {install_cell.RELOAD_LINE}

   Do what it says once; after that, Run All shows the sliders straight away.
4. Your answers go in the cells that say `...`; the check cell under each exercise
   says whether they are right, and why not.
5. Hand back the notebooks as your teacher asks, saved after your last run.
"""


def build_student_edition(
    source_dir: str | pathlib.Path, out_dir: str | pathlib.Path
) -> list[pathlib.Path]:
    """The student edition that runs on its own: notebooks, a twolink wheel, a README, and a zip of them.

    ``out_dir`` gets the student notebooks (:func:`build_student`, each
    chapter recording the commit it comes from, :func:`record_edition`) and the
    wheel (:func:`build_wheel`); ``out_dir`` with ``.zip`` (``build/student.zip``)
    holds the same files in a folder of ``out_dir``'s name.  Returns the files
    written, the zip last.
    """
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    for stale in out_dir.glob("*.ipynb"):  # a notebook renamed or removed since
        stale.unlink()
    written = build_student(source_dir, out_dir)
    record_edition(written)
    written.append(build_wheel(out_dir))
    # the course's versions, which the install cell installs with the wheel
    constraints = out_dir / install_cell.CONSTRAINTS
    shutil.copyfile(ROOT / "constraints.txt", constraints)
    written.append(constraints)
    readme = out_dir / "README.md"
    readme.write_text(student_readme(), encoding="utf-8")
    written.append(readme)
    archive = out_dir.with_name(out_dir.name + ".zip")
    partial = archive.with_name(archive.name + ".partial")
    with zipfile.ZipFile(partial, "w", compression=zipfile.ZIP_DEFLATED) as bundle:
        for path in written:
            bundle.write(path, f"{out_dir.name}/{path.name}")
    partial.replace(archive)
    return [*written, archive]


#: A Markdown link to a notebook by a relative file name: ``[text](02_x.ipynb#anchor)``.
NOTEBOOK_LINK = re.compile(r"\]\((?P<name>[^()\s:/#]+)\.ipynb(?P<anchor>#[^()\s]*)?\)")


def site_links(markdown: str, pages: set[str]) -> str:
    """``markdown`` with its links to the notebooks of ``pages`` (stems) leading to their HTML pages.

    Links to other notebooks (not on the site) and to other sites are left alone.

    >>> site_links("[Next](02_ik.ipynb), [here](02_ik.ipynb#Setup), [x](other.ipynb)", {"02_ik"})
    '[Next](02_ik.html), [here](02_ik.html#Setup), [x](other.ipynb)'
    """

    def replace(match: re.Match[str]) -> str:
        if match["name"] not in pages:
            return match[0]
        return f"]({match['name']}.html{match['anchor'] or ''})"

    return NOTEBOOK_LINK.sub(replace, markdown)


#: An ATX heading: up to three spaces, 1-6 ``#``, then a space (or nothing), the text
#: and an optional closing run of ``#``.
ATX_HEADING = re.compile(
    r"^ {0,3}(?P<level>#{1,6})(?:[ \t]+(?P<text>.*?))?(?:[ \t]+#+)?[ \t]*$"
)
#: A fenced code block's opening or closing line (a ``# comment`` inside is no heading).
FENCE = re.compile(r"^ {0,3}(```|~~~)")
#: Inline Markdown a page title shows as plain text: images and links (their text),
#: code spans, emphasis markers and HTML tags.
_INLINE_MARKUP = [
    (re.compile(r"!?\[([^\]]*)\]\([^)]*\)"), r"\1"),
    (re.compile(r"`+([^`]*)`+"), r"\1"),
    (re.compile(r"(\*{1,3})(\S(?:.*?\S)?)\1"), r"\2"),
    (re.compile(r"</?[A-Za-z][^>]*>"), ""),
]


def markdown_headings(notebook: dict[str, Any]) -> list[tuple[int, str]]:
    """``(level, text)`` of every ATX heading in the notebook's Markdown cells, in order.

    Lines inside fenced code blocks are skipped.

    >>> markdown_headings({"cells": [
    ...     {"cell_type": "code", "source": "# a comment"},
    ...     {"cell_type": "markdown", "source": ["## Setup\\n", "```\\n# code\\n```\\n# Title #"]},
    ... ]})
    [(2, 'Setup'), (1, 'Title')]
    """
    found = []
    for cell in notebook["cells"]:
        if cell["cell_type"] != "markdown":
            continue
        source = cell["source"]
        fenced = False
        for line in (
            "".join(source) if isinstance(source, list) else source
        ).splitlines():
            if FENCE.match(line):
                fenced = not fenced
                continue
            match = None if fenced else ATX_HEADING.match(line)
            if match and match["text"]:
                found.append((len(match["level"]), match["text"].strip()))
    return found


def plain_text(markdown: str) -> str:
    """A line of Markdown as plain text: link and image text kept, code and emphasis marks dropped.

    >>> plain_text("Chapter 9: **Fast** `ik` with [SciPy](https://scipy.org)")
    'Chapter 9: Fast ik with SciPy'
    """
    for pattern, replacement in _INLINE_MARKUP:
        markdown = pattern.sub(replacement, markdown)
    return " ".join(markdown.split())


def chapter_title(notebook: dict[str, Any], fallback: str) -> str:
    """A notebook's title: its first level-1 heading (``# Title``), as plain text.

    Without a level-1 heading the first heading of any level is taken, and
    without any heading ``fallback`` (the file name, say).

    >>> cells = [
    ...     {"cell_type": "markdown", "source": "## Before the title\\n"},
    ...     {"cell_type": "markdown", "source": "# Chapter 9: *fast* IK\\n\\nText."},
    ... ]
    >>> chapter_title({"cells": cells}, "09_fast_ik")
    'Chapter 9: fast IK'
    >>> chapter_title({"cells": cells[:1]}, "09_fast_ik")
    'Before the title'
    >>> chapter_title({"cells": []}, "09_fast_ik")
    '09_fast_ik'
    """
    headings = markdown_headings(notebook)
    # level-1 headings first (sorted is stable: each level keeps its order)
    for _level, text in sorted(headings, key=lambda heading: heading[0] != 1):
        title = plain_text(text)
        if title:
            return title
    return fallback


#: The jupyter-server-mathjax copy ships only the STIX-Web fonts: tell MathJax
#: to use them instead of looking for its default TeX fonts.
#: Formulas are no Tab stops (MathJax's menu stays on a right click): a chapter
#: has hundreds of them, and each stop said nothing more than the text around it.
MATHJAX_FONT_CONFIG = """MathJax.Hub.Config({
  "HTML-CSS": {availableFonts: [], imageFont: null, preferredFont: null, webFont: "STIX-Web"},
  SVG: {font: "STIX-Web"},
  menuSettings: {inTabOrder: false}
});
MathJax.Ajax.loadComplete("[MathJax]/config/local/twolink.js");
"""


def mathjax_source() -> pathlib.Path:
    """Folder of the MathJax 2.7 copy shipped by the jupyter-server-mathjax package."""
    import jupyter_server_mathjax

    return pathlib.Path(jupyter_server_mathjax.__file__).parent / "static"


#: The site's name, after each page's chapter title.
SITE_TITLE = "twolink"
#: The Pygments style of the site's code (accessible-pygments: WCAG AA contrast).
CODE_STYLE = "a11y-high-contrast-light"


#: The index page's file and the text of the links to it.
INDEX_PAGE = "index.html"
INDEX_LINK_TEXT = f"All chapters of {SITE_TITLE}"


def page_name(notebook: pathlib.Path) -> str:
    """The file name of a notebook's page on the site."""
    return notebook.with_suffix(".html").name


def navigation(pages: Sequence[str], titles: Sequence[str]) -> list[dict[str, Any]]:
    """Each page's links: ``{"index", "previous", "next"}``, each ``{"href", "title"}`` or None.

    ``pages`` are the pages' file names in chapter order, ``titles`` their
    titles; the first page has no previous one and the last no next one.
    (The site template reads this from the notebook's metadata
    ``twolink_site``.)

    >>> links = navigation(["a.html", "b.html"], ["A", "B"])
    >>> links[0]["previous"], links[0]["next"], links[1]["next"]
    (None, {'href': 'b.html', 'title': 'B'}, None)
    >>> links[1]["index"]
    {'href': 'index.html', 'title': 'All chapters of twolink'}
    """
    if len(pages) != len(titles):
        raise ValueError(
            f"navigation needs one title per page: {len(pages)} pages, {len(titles)} titles"
        )

    def link(number: int) -> dict[str, str] | None:
        if not 0 <= number < len(pages):
            return None
        return {"href": pages[number], "title": titles[number]}

    return [
        {
            "index": {"href": INDEX_PAGE, "title": INDEX_LINK_TEXT},
            "previous": link(number - 1),
            "next": link(number + 1),
        }
        for number in range(len(pages))
    ]


#: A sentence's end: a full stop, question or exclamation mark, then a capital.
SENTENCE_END = re.compile(r"(?<=[.!?])\s+(?=[A-Z])")
#: Longest short text alternative, characters: about two sentences.
SHORT_ALT_MAX = 200


def short_description(description: str) -> str:
    """The first sentence of a figure's description, and the second when both are short.

    A screen reader reads an image's ``alt`` whole, every time it passes the
    image: the site gives it this short form and puts the full description
    one step away, in a ``<details>`` after the figure.

    >>> short_description("The arm at q = (30°, 45°). Tip at (2.25, 2.93) m. Axes: x [m] from -4 to 4.")
    'The arm at q = (30°, 45°). Tip at (2.25, 2.93) m.'
    >>> len(short_description("word " * 100)) <= SHORT_ALT_MAX
    True
    """
    sentences = SENTENCE_END.split(" ".join(description.split()))
    short = sentences[0]
    if len(sentences) > 1 and len(short) + 1 + len(sentences[1]) <= SHORT_ALT_MAX * 0.6:
        short += " " + sentences[1]
    if len(short) > SHORT_ALT_MAX:
        short = short[: SHORT_ALT_MAX - 1].rsplit(" ", 1)[0] + "…"
    return short


#: The course's animation wrapper (twolink_course.plot.animation_html) and its label.
ANIMATION_LABEL = re.compile(r'<div role="figure" aria-label="(?P<label>[^"]*)">')
#: A video tag's autoplay attribute (matplotlib's tag: ``controls autoplay loop``).
AUTOPLAY = re.compile(r"(<video\b[^>]*?)\sautoplay\b")


def site_outputs(notebook: dict[str, Any]) -> dict[str, Any]:
    """The notebook's outputs as the site shows them: short text alternatives, the
    full description beside them, and videos that play only where motion is welcome.

    - an image output whose metadata has an ``alt`` keeps the short form
      (:func:`short_description`) as ``alt`` and the whole as ``description``
      (the site template shows it in a ``<details>`` after the image);
    - an animation (the ``<div role="figure" aria-label=...>`` around a
      ``<video>``) is labelled by the short form, with the whole in a
      ``<details>`` after it;
    - a ``<video autoplay>`` loses ``autoplay`` and is marked
      ``data-twolink-autoplay``: the page's script starts it (muted) unless the
      reader asks for reduced motion.

    >>> cell = {"cell_type": "code", "outputs": [{"output_type": "display_data", "metadata": {},
    ...     "data": {"text/html": '<div role="figure" aria-label="Moving. Frames 1-9. Axes.">\\n'
    ...                           '<video width="4" controls autoplay loop>\\n</video>\\n</div>'}}]}
    >>> print(site_outputs({"cells": [cell]})["cells"][0]["outputs"][0]["data"]["text/html"])
    <div role="figure" aria-label="Moving. Frames 1-9.">
    <video width="4" controls loop data-twolink-autoplay>
    </video>
    </div>
    <details class="twolink-description"><summary>Description of the animation</summary><p>Moving. Frames 1-9. Axes.</p></details>
    """
    shown = copy.deepcopy(notebook)
    for cell in shown["cells"]:
        for output in cell.get("outputs", []):
            data, metadata = output.get("data", {}), output.get("metadata", {})
            image = metadata.get("image/png")
            if "image/png" in data and isinstance(image, dict):
                alt = image.get("alt")
                if isinstance(alt, str) and alt and short_description(alt) != alt:
                    image["description"] = alt
                    image["alt"] = short_description(alt)
            if "text/html" in data:
                markup = data["text/html"]
                markup = "".join(markup) if isinstance(markup, list) else markup
                data["text/html"] = _site_animation(markup)
    return shown


def _site_animation(markup: str) -> str:
    markup = AUTOPLAY.sub(lambda match: match[1], markup)
    markup = (
        re.sub(r"(<video\b[^>]*)>", r"\1 data-twolink-autoplay>", markup, count=1)
        if "<video" in markup
        else markup
    )
    found = ANIMATION_LABEL.search(markup)
    if found is None:
        return markup
    description = html.unescape(found["label"])
    short = html.escape(short_description(description), quote=True)
    markup = markup.replace(found[0], f'<div role="figure" aria-label="{short}">', 1)
    return (
        markup.rstrip("\n")
        + '\n<details class="twolink-description"><summary>Description of the animation</summary>'
        + f"<p>{html.escape(description, quote=False)}</p></details>"
    )


def build_site(
    source_dir: str | pathlib.Path, out_dir: str | pathlib.Path
) -> list[pathlib.Path]:
    """Render every notebook to HTML (nbconvert) and write an index page linking them in order."""
    source_dir, out_dir = pathlib.Path(source_dir), pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    mathjax_dir = out_dir / "mathjax"
    if not mathjax_dir.exists():
        shutil.copytree(mathjax_source(), mathjax_dir)
    local_config = mathjax_dir / "config" / "local" / "twolink.js"
    local_config.parent.mkdir(parents=True, exist_ok=True)
    local_config.write_text(MATHJAX_FONT_CONFIG, encoding="utf-8")
    notebooks = sorted(source_dir.glob("*.ipynb"))
    titles = [
        chapter_title(json.loads(path.read_text(encoding="utf-8")), path.stem)
        for path in notebooks
    ]
    links = navigation([page_name(path) for path in notebooks], titles)
    with tempfile.TemporaryDirectory() as scratch:
        # copies that carry the page's title and the links to the index and the
        # neighbouring chapters (read by tools/site_template/course/index.html.j2)
        copies = []
        for number, path in enumerate(notebooks):
            notebook = site_outputs(
                without_hidden_tests(json.loads(path.read_text(encoding="utf-8")))
            )
            stems = {other.stem for other in notebooks}
            for cell in notebook["cells"]:
                if cell["cell_type"] == "markdown":
                    cell["source"] = site_links(
                        "".join(cell["source"])
                        if isinstance(cell["source"], list)
                        else cell["source"],
                        stems,
                    )
            notebook["metadata"]["title"] = f"{titles[number]} · {SITE_TITLE}"
            notebook["metadata"]["twolink_site"] = links[number]
            copy = pathlib.Path(scratch, path.name)
            copy.write_text(json.dumps(notebook, ensure_ascii=False), encoding="utf-8")
            copies.append(copy)
        subprocess.run(
            [
                sys.executable,
                "-m",
                "nbconvert",
                "--to",
                "html",
                "--TemplateExporter.extra_template_basedirs="
                + str(ROOT / "tools" / "site_template"),
                "--template",
                "course",
                "--HTMLExporter.mathjax_url=mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full,Safe,local/twolink",
                # no "In [3]:" prompts (execution counts say nothing on a page),
                # and code highlighted with colours of at least 4.5:1 contrast
                "--HTMLExporter.exclude_input_prompt=True",
                "--HTMLExporter.exclude_output_prompt=True",
                f"--CSSHTMLHeaderPreprocessor.style={CODE_STYLE}",
                "--output-dir",
                str(out_dir),
                *map(str, copies),
            ],
            check=True,
        )
    entries = [
        f'    <li><a href="{html.escape(page_name(path))}">{html.escape(title)}</a></li>'
        for path, title in zip(notebooks, titles)
    ]
    index = "\n".join(
        [
            "<!DOCTYPE html>",
            '<html lang="en">',
            f'<head><meta charset="utf-8"><title>{SITE_TITLE}: the planar two-link arm</title>',
            '<meta name="viewport" content="width=device-width, initial-scale=1">',
            "<style>body{font-family:sans-serif;max-width:40em;margin:3em auto;line-height:1.5}"
            " a{text-decoration:underline}</style></head>",
            "<body>",
            "<main>",
            f"  <h1>{SITE_TITLE}: the planar two-link arm</h1>",
            "  <p>The course's start page and chapters, executed. Run them yourself with <code>make lab</code>.</p>",
            '  <nav aria-label="Chapters">',
            "  <ol>",
            *entries,
            "  </ol>",
            "  </nav>",
            "</main>",
            "</body>",
            "</html>",
            "",
        ]
    )
    (out_dir / INDEX_PAGE).write_text(index, encoding="utf-8")
    return [out_dir / INDEX_PAGE] + [out_dir / page_name(path) for path in notebooks]


def main(argv: Sequence[str] | None = None) -> None:
    """Build the edition named on the command line (``student`` or ``site``)."""
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("edition", choices=["student", "site"])
    parser.add_argument("--source", default=str(ROOT / "notebooks"))
    parser.add_argument("--out", default=None)
    args = parser.parse_args(argv)
    out = args.out or str(ROOT / "build" / args.edition)
    builder = build_student_edition if args.edition == "student" else build_site
    for path in builder(args.source, out):
        print(path)


if __name__ == "__main__":
    main()
