"""Style: ``make test`` runs ``ruff check`` and ``ruff format --check`` on everything
ruff is told to read (pyproject.toml's [tool.ruff]: the package, tests, tools,
benchmarks and the notebooks' code cells); here, that it is told to and does.

The static checks (import-linter's layers, ruff's lint and format, mypy) run
once each, as commands of ``make test`` before pytest, leaving no cache in the
checkout, not as tests: a test would run them again in each worker that
collects it, and hide their output in a report."""

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _ruff(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "ruff", *args, "--no-cache"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_ruff_is_configured_for_the_notebooks_and_the_course_line_length():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["ruff"]
    assert "*.ipynb" in config["extend-include"]
    assert config["line-length"] == 88


def test_make_test_runs_each_static_check_once_leaving_no_cache():
    recipe = make_test_recipe()
    for command in (
        "$(BIN)/lint-imports --no-cache",
        "$(BIN)/ruff check --no-cache",
        "$(BIN)/ruff format --check --no-cache",
        '$(BIN)/mypy --num-workers=auto --cache-dir="$$cache"',
    ):
        assert recipe.count(command) == 1, (command, recipe)
    # mypy's workers need a cache: a temporary folder, removed whether mypy passed or not
    assert "cache=$$(mktemp -d)" in recipe, recipe
    assert '; typed=$$?; rm -rf "$$cache"; exit $$typed' in recipe, recipe
    assert recipe.splitlines()[-1] == "$(BIN)/python -m pytest", "pytest last"


def make_test_recipe() -> str:
    """The commands of the Makefile's ``test`` target."""
    lines = (ROOT / "Makefile").read_text(encoding="utf-8").splitlines()
    start = lines.index("test: $(STAMP)") + 1
    recipe = []
    for line in lines[start:]:
        if not line.startswith("\t"):
            break
        recipe.append(line.strip())
    return "\n".join(recipe)


@pytest.mark.parametrize(
    "path",
    ["twolink/arm.py", "tests/conftest.py", "notebooks/01_dh_forward_kinematics.ipynb"],
)
def test_ruff_reads_each_kind_of_file(path):
    """The check covers the file (a file ruff skipped would pass silently)."""
    result = _ruff("check", "--show-files", ".")
    assert result.returncode == 0, result.stderr
    listed = {
        Path(line).resolve() for line in result.stdout.splitlines() if line.strip()
    }
    assert (ROOT / path).resolve() in listed
