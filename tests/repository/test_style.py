"""Style: ``ruff check`` and ``ruff format --check`` pass on everything ruff is told to
read (pyproject.toml's [tool.ruff]: the package, tests, tools, benchmarks and the
notebooks' code cells)."""

import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _ruff(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "ruff", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_ruff_is_configured_for_the_notebooks_and_the_course_line_length():
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["ruff"]
    assert "*.ipynb" in config["extend-include"]
    assert config["line-length"] == 88


def test_ruff_check_finds_nothing():
    result = _ruff("check", "--output-format", "concise", ".")
    assert result.returncode == 0, f"ruff check:\n{result.stdout}{result.stderr}"


def test_ruff_format_changes_nothing():
    result = _ruff("format", "--check", ".")
    assert result.returncode == 0, (
        f"ruff format --check (run `.venv/bin/ruff format` to fix):\n"
        f"{result.stdout}{result.stderr}"
    )


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
