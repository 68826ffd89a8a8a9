"""`pytest --nbval` works from the root and from inside notebooks/ (the sanitize file is found from the root).

The runs (pytest's own, in this process: ``pytester``) use a copy of the
repository's pytest set-up (pyproject.toml, conftest.py,
tests/nbval_sanitize.cfg) with one tiny notebook whose stored
output only matches after sanitising (a random video payload, what the
sanitize file masks), so each run
fails unless the sanitize file is found, and does not depend on chapters
that other work is changing.  Without the root conftest.py the run from
notebooks/ fails: the last test shows it.
"""

import pathlib
import shutil

import nbformat
import pytest

pytest_plugins = ["pytester"]

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture()
def repository(pytester):
    tmp_path = pytester.path
    shutil.copy(ROOT / "pyproject.toml", tmp_path)
    shutil.copy(ROOT / "conftest.py", tmp_path)
    (tmp_path / "notebooks").mkdir()
    (tmp_path / "tests").mkdir()
    shutil.copy(ROOT / "tests" / "nbval_sanitize.cfg", tmp_path / "tests")
    cell = nbformat.v4.new_code_cell(
        "import base64, os\nprint('data:video/mp4;base64,' + base64.b64encode(os.urandom(24)).decode())"
    )
    cell.execution_count = 1
    cell.outputs = [
        nbformat.v4.new_output(
            "stream",
            name="stdout",
            text="data:video/mp4;base64,AAAAIGZ0eXBNNFYgAAACAE00ViBp\n",
        )
    ]
    notebook = nbformat.v4.new_notebook(cells=[cell])
    nbformat.write(notebook, tmp_path / "notebooks" / "00_random_id.ipynb")
    return tmp_path


def pytest_in(pytester, monkeypatch, folder, *args):
    """``pytest *args`` run from ``folder``: pytest's own, in this process (no second interpreter to start).

    Every wait has a budget: nbval's kernel start (60 s) and each cell's (60 s).
    """
    monkeypatch.chdir(folder)
    return pytester.runpytest_inprocess(
        "-n", "0", "-p", "no:cacheprovider", "--nbval-cell-timeout", "60", *args
    )


@pytest.mark.infrastructure
def test_pytest_nbval_runs_from_inside_notebooks(repository, pytester, monkeypatch):
    """From the root the relative path exists anyway (make test runs from there)."""
    result = pytest_in(
        pytester, monkeypatch, repository / "notebooks", "--nbval", "00_random_id.ipynb"
    )
    out, err = result.stdout.str(), result.stderr.str()
    assert result.ret == 0, out[-3000:] + err[-2000:]
    assert "1 passed" in out


@pytest.mark.infrastructure
def test_without_the_root_conftest_the_run_from_notebooks_fails(
    repository, pytester, monkeypatch
):
    (repository / "conftest.py").unlink()
    result = pytest_in(
        pytester, monkeypatch, repository / "notebooks", "--nbval", "00_random_id.ipynb"
    )
    out, err = result.stdout.str(), result.stderr.str()
    assert result.ret != 0
    assert "sanitize.cfg" in out + err
