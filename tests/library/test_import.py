"""``import twolink`` is light: no scipy, sympy, matplotlib, control or mujoco until a function needs it.

Each module imports scipy inside the function that calls it.  One walk of
both packages' sources (:mod:`ast`, nothing imported) follows every import a
module runs when it is imported (at module level, in class bodies, under
``if`` and ``try``; not in functions, not under ``if TYPE_CHECKING:``),
through the packages' own modules and their parent packages, to the heavy
libraries it reaches: none for every module of the library but the one built
on sympy (and of the course kit, but the modules built on matplotlib), and only
its own library for each module built on one.  One fresh
interpreter then imports twolink for real: no heavy library is loaded, and
every public name is there without loading scipy.  A function that imports
scipy late is run by its module's tests, each call running its import.  How
long the import takes is measured by ``benchmarks/bench_import.py``, not here.
"""

import ast
import json
import os
import pathlib
import subprocess
import sys
import textwrap

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGES = ("twolink", "twolink_course")
HEAVY = ("scipy", "sympy", "matplotlib", "control", "mujoco")
# The modules that exist to use a heavy library, and the one they load: chapters import them by name.
HEAVY_BY_DESIGN = {
    "twolink_course.plot": "matplotlib",
    "twolink_course.diagrams": "matplotlib",
    "twolink_course.explorer": "matplotlib",
    "twolink_course.explorers.ch1": "matplotlib",  # chapter 1's explorer, built on explorer
    "twolink_course.explorers.ch2": "matplotlib",  # chapter 2's explorer, built on explorer
    "twolink_course.explorers.ch3": "matplotlib",  # chapter 3's explorer, built on explorer
    "twolink_course.explorers.ch4": "matplotlib",  # chapter 4's explorer, built on explorer
    "twolink_course.explorers.ch5": "matplotlib",  # chapter 5's explorer, built on explorer
    "twolink_course.explorers.ch6": "matplotlib",  # chapter 6's explorer, built on explorer
    "twolink_course.explorers.ch7": "matplotlib",  # chapter 7's explorer, built on explorer
    "twolink_course.figure_style": "matplotlib",
    "twolink_course.alttext": "matplotlib",
    "twolink_course.inline": "matplotlib",
    "twolink_course.video": "matplotlib",
    "twolink.symbolic": "sympy",
}


def _module_name(path: pathlib.Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _sources() -> dict[str, pathlib.Path]:
    return {
        _module_name(path): path
        for package in PACKAGES
        for path in sorted((ROOT / package).rglob("*.py"))
    }


def _is_type_checking(node: ast.If) -> bool:
    return ast.unparse(node.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING")


def imports_at_import_time(tree: ast.Module) -> list[ast.Import | ast.ImportFrom]:
    """The import statements a module runs when it is imported."""
    found, todo = [], list(tree.body)
    while todo:
        node = todo.pop(0)
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            continue  # runs when called
        elif isinstance(node, ast.If) and _is_type_checking(node):
            todo.extend(node.orelse)
        else:
            todo.extend(
                child
                for child in ast.iter_child_nodes(node)
                if isinstance(child, ast.stmt)
            )
    return found


def imported_names(module: str, node: ast.Import | ast.ImportFrom, sources) -> set[str]:
    """The modules a statement imports: the packages' own by full name, others by top-level name."""
    if isinstance(node, ast.Import):
        names = [alias.name for alias in node.names]
    else:
        if node.level:
            package = module.split(".")
            is_package = sources[module].name == "__init__.py"
            base = package[: len(package) - node.level + (1 if is_package else 0)]
            source = ".".join(base + ([node.module] if node.module else []))
        else:
            source = node.module
        names = [source] + [f"{source}.{alias.name}" for alias in node.names]
    found = set()
    for name in names:
        if name.split(".")[0] in PACKAGES:
            if name in sources:
                found.add(name)
        else:
            found.add(name.split(".")[0])
    return found


def import_graph() -> dict[str, set[str]]:
    """``{module: modules and libraries its import runs}``, parent packages included."""
    sources = _sources()
    graph = {}
    for module, path in sources.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        edges = set()
        for node in imports_at_import_time(tree):
            edges |= imported_names(module, node, sources)
        parts = module.split(".")
        edges |= {".".join(parts[:end]) for end in range(1, len(parts))}  # parents
        graph[module] = edges - {module}
    return graph


def heavy_libraries_of(module: str, graph: dict[str, set[str]]) -> set[str]:
    """The heavy libraries importing ``module`` loads, through the packages' own modules."""
    seen, todo, heavy = set(), [module], set()
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        for edge in graph.get(name, ()):
            if edge in graph:
                todo.append(edge)
            elif edge in HEAVY:
                heavy.add(edge)
    return heavy


def expected_heavy(module: str) -> set[str]:
    for owner, library in HEAVY_BY_DESIGN.items():
        if module == owner or module.startswith(owner + "."):
            return {library}
    return set()


def test_every_module_loads_only_the_heavy_library_it_is_built_on():
    graph = import_graph()
    wrong = {
        module: sorted(heavy_libraries_of(module, graph))
        for module in graph
        if heavy_libraries_of(module, graph) != expected_heavy(module)
    }
    assert not wrong, (
        f"heavy libraries loaded at import: {wrong}; import them inside the "
        "function that needs them (# here, not at the top: import twolink stays light)"
    )


def test_the_walk_sees_imports_where_they_run(tmp_path):
    tree = ast.parse(
        textwrap.dedent("""
        import numpy
        from typing import TYPE_CHECKING
        if TYPE_CHECKING:
            import scipy
        try:
            import matplotlib
        except ImportError:
            pass
        class Plot:
            import sympy
        def late():
            import mujoco
        """)
    )
    names = {
        alias.name for node in imports_at_import_time(tree) for alias in node.names
    }
    assert names == {"numpy", "TYPE_CHECKING", "matplotlib", "sympy"}


def test_the_walk_follows_the_packages_own_imports_to_a_heavy_library():
    graph = import_graph()
    assert "twolink.ik" in graph["twolink.ik.analytic"]  # its parent package
    assert "twolink" in graph["twolink.kinematics"]
    assert heavy_libraries_of("twolink.symbolic.kinematics", graph) == {"sympy"}
    graph["twolink.kinematics"] = graph["twolink.kinematics"] | {"twolink.symbolic"}
    assert heavy_libraries_of("twolink.arm", graph) == {
        "sympy"
    }  # arm imports kinematics


def run_fresh(code: str) -> str:
    """Run ``code`` in a fresh interpreter and return what it printed (the test fails on any error)."""
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join(
            filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])
        ),
    )
    done = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=ROOT,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return done.stdout


def test_import_twolink_is_light_and_has_every_public_name():
    printed = run_fresh(f"""
        import json, sys
        import twolink
        loaded = sorted({{name.split(".")[0] for name in sys.modules}} & set({HEAVY!r}))
        missing = [name for name in twolink.__all__ if not hasattr(twolink, name)]
        print(json.dumps([loaded, missing, "scipy" in sys.modules]))
    """)
    loaded, missing, scipy_after_lookup = json.loads(printed.splitlines()[-1])
    assert loaded == [], f"import twolink loaded {loaded}"
    assert missing == [], (
        f"names in twolink.__all__ missing after import twolink: {missing}"
    )
    assert not scipy_after_lookup, "looking up the public names loaded scipy"


@pytest.mark.parametrize("module", sorted(HEAVY_BY_DESIGN))
def test_each_module_built_on_a_heavy_library_exists(module):
    assert module in _sources(), f"{module} is gone: drop it from HEAVY_BY_DESIGN"
