"""The grader's sandbox (tools/sandbox.py): what a kernel inside it can read, write, reach and use.

Each attack runs as a cell in a kernel started by ``SandboxKernelManager``
and prints what it achieved; the test asserts the sandbox refused it.
"""

import pathlib
import sys

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import sandbox  # noqa: E402
from jupyter_core.utils import run_sync  # noqa: E402
from nbclient import NotebookClient  # noqa: E402

REASON = sandbox.unavailable()


def test_the_command_hides_folders_drops_privileges_and_sets_limits(tmp_path):
    limits = sandbox.Limits(memory_bytes=2**30, cpu_seconds=60, processes=32)
    command = sandbox.command_prefix(
        tmp_path / "work",
        tmp_path / "run",
        [tmp_path / "secret"],
        limits,
        user=101234,
        environment={"TWOLINK_GRADING": "1"},
    )
    text = " ".join(command)
    assert command[0] == "bwrap" and "--ro-bind / /" in text
    assert (
        "--unshare-net" in command
        and "--unshare-pid" in command
        and "--die-with-parent" in command
    )
    assert f"--bind {tmp_path / 'work'} {tmp_path / 'work'}" in text
    assert "--setenv TWOLINK_GRADING 1" in text
    assert (
        "--as=1073741824" in command
        and "--cpu=60" in command
        and "--nproc=32" in command
    )
    assert command[-1] == "--"
    secret = tmp_path / "secret"
    assert (
        f"--tmpfs {secret}" not in text
    )  # a folder that does not exist is not hidden (bwrap would fail)
    secret.mkdir()
    command = sandbox.command_prefix(
        tmp_path / "work", tmp_path / "run", [secret], limits
    )
    assert f"--tmpfs {secret.resolve()}" in " ".join(command)
    # a hidden file (a git worktree's .git is a file) is covered, not mounted over
    # by a tmpfs, which bwrap cannot do (the sandbox would not start)
    pointer = tmp_path / "gitdir-pointer"
    pointer.write_text("gitdir: /elsewhere\n", encoding="utf-8")
    command = sandbox.command_prefix(
        tmp_path / "work", tmp_path / "run", [pointer], limits
    )
    text = " ".join(command)
    assert f"--ro-bind /dev/null {pointer.resolve()}" in text
    assert f"--tmpfs {pointer.resolve()}" not in text


def test_user_for_gives_each_grader_process_a_user_of_its_own():
    assert sandbox.user_for(1) != sandbox.user_for(2)
    assert sandbox.user_for(1) >= 100_000  # above the machine's own users


def test_unavailable_says_what_is_missing(monkeypatch):
    monkeypatch.setattr(sandbox.shutil, "which", lambda name: None)
    assert sandbox.unavailable().startswith("bwrap")
    assert "apt-get install bubblewrap" in sandbox.unavailable()


ATTACKS = {
    "read_the_hidden_folder": (
        "import os\nprint(sorted(os.listdir({hidden!r})))",
        "[]",
    ),
    "read_a_file_in_it": (
        "try:\n    print(open({hidden_file!r}).read())\nexcept OSError as error:\n    print('refused', type(error).__name__)",
        "refused FileNotFoundError",
    ),
    "write_the_repository": (
        "try:\n    open({package_file!r}, 'a').write('# patched')\n    print('wrote')\n"
        "except OSError as error:\n    print('refused', error.errno)",
        "refused",  # EACCES or EROFS: not the kernel's, on a read-only file system
    ),
    "write_the_grader_home": (
        "import pathlib\ntry:\n    (pathlib.Path({grader_home!r}) / 'x').write_text('x')\n    print('wrote', pathlib.Path.home())\n"
        "except OSError as error:\n    print('refused', error.errno)",
        None,  # the home is an empty tmpfs the kernel cannot write (or its own): checked below
    ),
    "reach_the_network": (
        "import socket\ntry:\n    socket.create_connection(('1.1.1.1', 80), timeout=2)\n    print('connected')\n"
        "except OSError as error:\n    print('refused', type(error).__name__)",
        "refused OSError",
    ),
    "take_the_memory": (
        "try:\n    block = bytearray(8 * 2**30)\n    print('took 8 GiB')\nexcept MemoryError:\n    print('refused MemoryError')",
        "refused MemoryError",
    ),
    "flood_processes": (
        "import subprocess\nstarted = []\ntry:\n    for _ in range(100):\n        started.append(subprocess.Popen(['sleep', '30']))\n"
        "    print('started 100')\nexcept OSError as error:\n    print('refused', type(error).__name__)\n"
        "for process in started:\n    process.kill()",
        "refused BlockingIOError",
    ),
    "see_the_grader": (
        "import os\nprint(sorted(int(p) for p in os.listdir('/proc') if p.isdigit())[:1])",
        "[1]",  # its own process namespace: the sandbox's init, not the machine's
    ),
}


@pytest.fixture(scope="module")
def printed(tmp_path_factory):
    if REASON is not None:
        pytest.skip(f"no sandbox on this machine: {REASON}")
    folder = tmp_path_factory.mktemp("sandboxed")
    hidden = folder / "hidden"
    hidden.mkdir()
    (hidden / "classmate.ipynb").write_text("{}", encoding="utf-8")
    values = {
        "hidden": str(hidden),
        "hidden_file": str(hidden / "classmate.ipynb"),
        "package_file": str(ROOT / "twolink_course" / "selfcheck.py"),
        "grader_home": str(pathlib.Path.home()),
    }
    notebook = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_code_cell(code.format(**values))
            for code, _ in ATTACKS.values()
        ]
    )
    workdir = folder / "work"
    workdir.mkdir()
    limits = sandbox.Limits(memory_bytes=4 * 2**30, processes=64)
    manager = sandbox.SandboxKernelManager(
        workdir, hidden=[hidden], limits=limits, user=sandbox.user_for(1)
    )
    try:
        NotebookClient(notebook, km=manager, timeout=60, allow_errors=True).execute()
    finally:
        if manager.has_kernel:
            run_sync(manager.shutdown_kernel)(now=True)
        manager.cleanup_runtime()
    return {
        name: "".join(output.get("text", "") for output in cell.outputs).strip()
        for name, cell in zip(ATTACKS, notebook.cells)
    }


@pytest.mark.infrastructure
@pytest.mark.parametrize(
    "name", [name for name, (_, expected) in ATTACKS.items() if expected is not None]
)
def test_the_sandbox_refuses(printed, name):
    assert printed[name].startswith(ATTACKS[name][1]), (name, printed[name])


@pytest.mark.infrastructure
def test_the_grader_home_is_out_of_reach(printed):
    assert not (pathlib.Path.home() / "x").exists()
    assert (
        printed["write_the_grader_home"].startswith("refused")
        or str(pathlib.Path.home()) not in printed["write_the_grader_home"]
    )
