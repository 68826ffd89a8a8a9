"""Only what the answers depend on (tools/grade_prune.py): statements kept and dropped by the names they bind and read."""

import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from grade_prune import needed  # noqa: E402


def cut(cells, root, names=(), release=None, roots=None):
    """The cells cut for the root cell ``root`` (the grader reading ``names``)."""
    return needed(
        cells,
        roots if roots is not None else {root},
        names,
        release if release is not None else set(cells),
    )


def test_a_figure_and_a_derivation_no_answer_reads_are_dropped():
    cells = [
        "import numpy as np\nimport sympy as sp",
        "x = sp.Symbol('x')\nderivative = sp.diff(x**3, x)",
        "q = np.zeros(2)",
        "answer = q + 1",
    ]
    assert cut(cells, 3) == [
        "import numpy as np",
        "",
        "q = np.zeros(2)",
        "answer = q + 1",
    ]


def test_a_name_bound_again_needs_only_its_last_binding():
    cells = [
        "import numpy as np",
        "q = np.ones(2)\nexpensive = q.sum()",
        "q = np.zeros(2)",
        "answer = q + 1",
    ]
    assert cut(cells, 3) == [
        "import numpy as np",
        "",
        "q = np.zeros(2)",
        "answer = q + 1",
    ]


def test_a_binding_in_a_branch_does_not_hide_the_one_before():
    cells = ["q = 1", "if flag:\n    q = 2", "answer = q", "flag = True"]
    kept = cut(cells, 2)
    assert kept[0] == "q = 1" and kept[1].startswith("if flag")


def test_a_function_reads_its_globals_when_called_so_later_bindings_count():
    cells = [
        "def f():\n    return helper() + scale",
        "def helper():\n    return 1",
        "scale = 2\nscale_unused = 3",
        "answer = f()",
    ]
    assert cut(cells, 3) == [cells[0], cells[1], "scale = 2", "answer = f()"]


def test_a_change_in_place_is_a_binding():
    cells = [
        "values = [3, 1]",
        "values.sort()",
        "values[0] = 5",
        "plot(values)",
        "answer = values",
    ]
    kept = cut(cells, 4)
    # the course's own cells: a method call or an index changes the object; passing it to a
    # function is trusted not to
    assert kept[:4] == ["values = [3, 1]", "values.sort()", "values[0] = 5", ""]


def test_a_student_s_cell_counts_as_changing_what_it_passes_to_a_function():
    cells = [
        "values = [3, 1]",
        "shuffle(values)",
        "answer = values",
        "def shuffle(v):\n    v.reverse()",
    ]
    release = {cells[0], cells[2], cells[3]}  # cell 1 is the student's
    assert cut(cells, 2, release=release)[1] == "shuffle(values)"
    assert cut(cells, 2)[1] == ""  # as a cell of the course's, it is trusted


def test_magics_and_cells_that_do_not_parse():
    cells = [
        "%matplotlib inline\nimport numpy as np",
        "this is not python",
        "answer = np.pi",
    ]
    kept = cut(cells, 2)
    assert kept[0] == "import numpy as np" and kept[1] == ""


def test_a_star_import_is_always_kept():
    cells = ["from math import *", "answer = pi"]
    assert cut(cells, 1) == cells


def test_a_student_s_needed_cell_that_reads_the_namespace_keeps_everything():
    cells = ["x = 1\ny = 2", "answer = globals()['x']"]
    assert cut(cells, 1, release={cells[0]}) == cells
    assert cut(cells, 1, release=set(cells)) == ["", cells[1]]  # the course's: known


def test_what_the_grader_reads_at_the_end_is_needed():
    cells = ["tip_answer = 4", "other = 5"]
    assert needed(cells, set(), ["tip_answer"], set(cells)) == ["tip_answer = 4", ""]


def test_a_decorated_function_keeps_its_decorator():
    cells = [
        "import functools",
        "@functools.cache\ndef f(x):\n    return x",
        "answer = f(1)",
    ]
    assert cut(cells, 2)[1] == cells[1]
