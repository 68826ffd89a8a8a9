"""The chapters' first code cell installs twolink where it is missing, and nothing in a clone.

``tools/install_cell.py`` writes that cell.  Its choice of source (a wheel
beside the notebook, then TWOLINK_SOURCE, then the index) is tested by running
the cell's own code with ``import twolink`` made to fail and ``%pip``
replaced, so nothing is installed; then in real kernels: one in the project's
environment (it must not call pip) and one in a throwaway venv that has every
course package but not twolink (it must install twolink from the source named
by TWOLINK_SOURCE, here the student edition's wheel of this checkout).  The
student edition's run from its own wheel, in a fresh venv, is in
``tests/infrastructure/test_student_edition.py``.
"""

import contextlib
import copy
import io
import os
import pathlib
import subprocess
import sys

import _venvs
import nbformat
import pytest
from IPython.core.inputtransformer2 import TransformerManager
from nbclient import NotebookClient

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import install_cell  # noqa: E402

CHAPTER_1 = ROOT / "notebooks" / "01_dh_forward_kinematics.ipynb"


def code_sources(notebook):
    return [cell.source for cell in notebook.cells if cell.cell_type == "code"]


def test_apply_inserts_the_cell_first_and_is_idempotent():
    original = nbformat.read(CHAPTER_1, as_version=4)
    original_code = [
        source
        for source in code_sources(original)
        if not source.startswith(install_cell.MARKER)
    ]
    notebook = copy.deepcopy(original)
    install_cell.apply(notebook)
    assert code_sources(notebook)[0] == install_cell.install_cell_source()
    assert code_sources(notebook)[1:] == original_code, (
        "the chapter's own code cells must follow unchanged"
    )
    once = nbformat.writes(notebook)
    assert install_cell.apply(notebook) is False
    assert nbformat.writes(notebook) == once
    assert install_cell.is_up_to_date(notebook)


def test_apply_updates_an_outdated_install_cell_in_place():
    notebook = nbformat.read(CHAPTER_1, as_version=4)
    install_cell.apply(notebook)
    first = next(cell for cell in notebook.cells if cell.cell_type == "code")
    first.source = install_cell.MARKER + "\n%pip install something-old"
    count = len(notebook.cells)
    assert not install_cell.is_up_to_date(notebook)
    assert install_cell.apply(notebook) is True
    assert len(notebook.cells) == count, (
        "an outdated install cell is replaced, not duplicated"
    )
    assert install_cell.is_up_to_date(notebook)


def test_check_mode_fails_on_a_stale_notebook_and_passes_once_applied(tmp_path, capsys):
    notebook = nbformat.read(CHAPTER_1, as_version=4)
    notebook.cells = [
        cell
        for cell in notebook.cells
        if not cell.source.startswith(install_cell.MARKER)
    ]
    path = tmp_path / "chapter.ipynb"
    nbformat.write(notebook, path)
    # the command line once (its exit status); then the same main() in this process
    stale = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "install_cell.py"), "--check", str(path)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert stale.returncode == 1 and "not the install cell" in stale.stderr
    assert install_cell.main(["--check", str(path)]) == 1
    assert install_cell.main([str(path)]) == 0
    assert "install cell written" in capsys.readouterr().out
    assert install_cell.main(["--check", str(path)]) == 0, capsys.readouterr().err


def test_every_chapter_starts_with_the_install_cell(capsys):
    """Fails until `python tools/install_cell.py` has been run on the notebooks (and they re-executed)."""
    assert install_cell.main(["--check"]) == 0, capsys.readouterr().err


def test_the_cell_names_the_source_variable_and_the_course_extra():
    source = install_cell.install_cell_source()
    assert install_cell.SOURCE_VARIABLE in source and "twolink[course]" in source
    assert source.count("%pip install") == 1


def test_the_start_page_gets_no_install_cell(capsys):
    """Without arguments the tool treats the chapters only: the start page has no code to set up
    (a notebook without code cells fails ``--check`` when it is named)."""
    start_page = ROOT / "notebooks" / "00_start_here.ipynb"
    assert install_cell.main(["--check"]) == 0, capsys.readouterr().err
    start = nbformat.read(start_page, as_version=4)
    assert not code_sources(start)
    assert install_cell.main(["--check", str(start_page)]) == 1


# --- the cell's choice of source, with pip replaced -----------------------------------------------------------


class FakeShell:
    """Stands in for IPython: records each line magic, expanded as IPython expands it; pip "installs" a stub."""

    def __init__(self, namespace):
        self.namespace = namespace
        self.calls = []

    def run_line_magic(self, name, line, _stack_depth=1):
        self.calls.append((name, line.format(**self.namespace)))
        if name == "pip":  # the cell imports twolink again after installing it
            import types

            sys.modules["twolink"] = types.ModuleType("twolink")


def run_cell_without_twolink(
    folder, monkeypatch, files=(), variable=None, default="twolink[course]"
):
    """Run the install cell's code in ``folder`` where ``import twolink`` fails; (pip lines, printed text)."""
    for name in files:
        (folder / name).write_bytes(b"")
    monkeypatch.chdir(folder)
    if variable is None:
        monkeypatch.delenv(install_cell.SOURCE_VARIABLE, raising=False)
    else:
        monkeypatch.setenv(install_cell.SOURCE_VARIABLE, variable)
    monkeypatch.setitem(sys.modules, "twolink", None)  # import twolink: ImportError
    code = TransformerManager().transform_cell(
        install_cell.install_cell_source(default)
    )
    namespace = {}
    shell = FakeShell(namespace)
    namespace["get_ipython"] = lambda: shell
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(code, namespace)
    assert namespace["twolink"] is sys.modules["twolink"], (
        "the cell imports twolink last"
    )
    return [line for name, line in shell.calls if name == "pip"], printed.getvalue()


WHEEL = "twolink-0.1.0-py3-none-any.whl"


def test_a_wheel_beside_the_notebook_comes_first(tmp_path, monkeypatch):
    pip, printed = run_cell_without_twolink(
        tmp_path, monkeypatch, files=[WHEEL, "notes.whl"], variable="/elsewhere[course]"
    )
    assert pip == [f'install --quiet "{WHEEL}[course]"']
    assert printed == (
        f"twolink is not installed here: installing {WHEEL}[course] "
        f"from {install_cell.FROM_WHEEL}\n"
    )


def test_without_a_wheel_TWOLINK_SOURCE_comes_next(tmp_path, monkeypatch):
    pip, printed = run_cell_without_twolink(
        tmp_path, monkeypatch, files=["twolink.txt"], variable="/src/twolink[course]"
    )
    assert pip == ['install --quiet "/src/twolink[course]"']
    assert printed.endswith(f"from {install_cell.FROM_VARIABLE}\n"), printed


@pytest.mark.parametrize("variable", [None, ""])
def test_without_either_the_index_or_the_repository(tmp_path, monkeypatch, variable):
    pip, printed = run_cell_without_twolink(tmp_path, monkeypatch, variable=variable)
    assert pip == ['install --quiet "twolink[course]"']
    assert printed.endswith(f"from {install_cell.FROM_INDEX}\n"), printed
    url = "twolink[course] @ git+https://github.com/someone/twolink"
    pip, printed = run_cell_without_twolink(
        tmp_path, monkeypatch, variable=variable, default=url
    )
    assert pip == [f'install --quiet "{url}"']
    assert printed.endswith("from the repository\n"), printed


def test_where_twolink_imports_the_cell_does_nothing(tmp_path, monkeypatch):
    (tmp_path / WHEEL).write_bytes(b"")
    monkeypatch.chdir(tmp_path)
    namespace = {}
    shell = FakeShell(namespace)
    namespace["get_ipython"] = lambda: shell
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        exec(
            TransformerManager().transform_cell(install_cell.install_cell_source()),
            namespace,
        )
    assert shell.calls == [] and printed.getvalue() == ""


def run_cells(
    sources, kernel_name="python3", kernel_spec_manager=None, cwd=None, timeout=240
):
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [nbformat.v4.new_code_cell(source) for source in sources]
    options = {
        "timeout": timeout,
        "kernel_name": kernel_name,
        "resources": {"metadata": {"path": str(cwd)}},
    }
    if kernel_spec_manager is not None:
        from jupyter_client import KernelManager

        options["km"] = KernelManager(
            kernel_name=kernel_name, kernel_spec_manager=kernel_spec_manager
        )
    NotebookClient(notebook, **options).execute()
    return [
        "".join(
            output.get("text", "")
            for output in cell.outputs
            if output.output_type == "stream"
        )
        for cell in notebook.cells
    ]


SPY_ON_PIP = """\
calls = []
_shell = get_ipython()
_run_line_magic = _shell.run_line_magic
def _spy(name, line, *args, **kwargs):
    calls.append((name, line))
    if name != "pip":
        return _run_line_magic(name, line, *args, **kwargs)
_shell.run_line_magic = _spy
"""


def test_in_a_clone_the_cell_installs_nothing(tmp_path, monkeypatch):
    """In the project's environment twolink imports, so the cell must not reach %pip."""
    monkeypatch.setenv("TWOLINK_SOURCE", str(tmp_path / "does-not-exist"))
    outputs = run_cells(
        [
            SPY_ON_PIP,
            "%pwd",
            install_cell.install_cell_source(),
            "print(calls, twolink.__name__)",
        ],
        cwd=tmp_path,
    )
    assert outputs[-1].strip() == "[('pwd', '')] twolink", (
        "the spy must see line magics, and no %pip"
    )
    assert "installing" not in outputs[2]


@pytest.mark.infrastructure
def test_without_twolink_the_cell_installs_it_from_TWOLINK_SOURCE(
    tmp_path, monkeypatch, edition_wheel
):
    """A kernel in a venv with every course package except twolink: the cell installs twolink from the
    source TWOLINK_SOURCE names (here the wheel of this checkout the student edition holds, in a folder
    that is not the kernel's), then `import twolink` works there and finds the installed copy.
    (That pip builds twolink from a source folder: ``editions.build_wheel``, ``make dist``.)"""
    try:
        python = _venvs.bare_venv(
            tmp_path, _venvs.installed_except(["twolink"]), with_dependencies=False
        )
    except (
        OSError,
        subprocess.CalledProcessError,
    ) as error:  # pragma: no cover - depends on the machine
        pytest.skip(f"cannot create a virtual environment here: {error}")
    probe = subprocess.run(
        [str(python), "-c", "import twolink"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert probe.returncode != 0 and "No module named 'twolink'" in probe.stderr, (
        "the venv must lack twolink"
    )
    assert not list(tmp_path.glob(install_cell.WHEEL_PATTERN))
    source = f"{edition_wheel}[course]"

    from jupyter_client.kernelspec import KernelSpecManager

    _venvs.kernel_spec(
        tmp_path / "kernels", "without-twolink", python, "without twolink"
    )
    monkeypatch.delenv("PYTHONPATH", raising=False)
    monkeypatch.setenv("TWOLINK_SOURCE", source)
    # offline: everything twolink needs is there
    monkeypatch.setenv("PIP_CONFIG_FILE", os.devnull)
    monkeypatch.setenv("PIP_NO_INDEX", "1")
    outputs = run_cells(
        [
            "import importlib.util, sys\nprint(importlib.util.find_spec('twolink') is None, sys.prefix)",
            install_cell.install_cell_source(),
            "import twolink\nprint(twolink.__file__)\nprint(twolink.TwoLinkArm(l1=2.0, l2=2.0).fk([0.0, 0.0]))",
        ],
        kernel_name="without-twolink",
        kernel_spec_manager=KernelSpecManager(kernel_dirs=[str(tmp_path / "kernels")]),
        cwd=tmp_path,
    )
    assert outputs[0].split() == ["True", str(tmp_path / "venv")], outputs[0]
    assert f"installing {source} from {install_cell.FROM_VARIABLE}" in outputs[1], (
        outputs[1]
    )
    location, fk = outputs[2].strip().splitlines()
    assert location.startswith(str(tmp_path / "venv")), (
        f"twolink imported from {location}, not the venv"
    )
    assert fk == "[4. 0.]"
