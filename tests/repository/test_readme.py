"""The README's Python examples run as written (an example that never runs goes stale)."""

import pathlib
import re

import pytest

README = (pathlib.Path(__file__).resolve().parents[2] / "README.md").read_text(
    encoding="utf-8"
)
EXAMPLES = re.findall(r"```python\n(.*?)```", README, flags=re.S)


def test_the_readme_has_python_examples():
    assert EXAMPLES


@pytest.mark.parametrize("index", range(len(EXAMPLES)))
def test_a_readme_example_runs(index, capsys):
    exec(compile(EXAMPLES[index], f"README.md example {index + 1}", "exec"), {})
    assert capsys.readouterr().out  # each example prints what it shows


ROOT = pathlib.Path(__file__).resolve().parents[2]
MAKEFILE = (ROOT / "Makefile").read_text(encoding="utf-8")


def makefile_targets():
    return set(re.findall(r"^([a-z][a-z-]*):", MAKEFILE, flags=re.M))


def test_every_make_command_the_readme_names_exists():
    named = set(re.findall(r"\bmake ([a-z][a-z-]*)", README))
    assert {"lab", "test"} <= named
    missing = named - makefile_targets()
    assert not missing, (
        f"README names make targets the Makefile lacks: {sorted(missing)}"
    )


def test_every_repository_path_the_readme_names_in_backticks_exists():
    # `notebooks/...`, `tools/...`, `benchmarks/...`, `tests/...` and top-level files named in code spans
    paths = set(
        re.findall(
            r"`((?:notebooks|tools|benchmarks|tests|labextension|\.github|\.binder|\.ci)/[\w./-]+)`",
            README,
        )
    )
    assert paths
    missing = sorted(path for path in paths if not (ROOT / path.rstrip("/")).exists())
    assert not missing, f"README names paths that do not exist: {missing}"
