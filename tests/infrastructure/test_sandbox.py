"""The grader's sandbox (tools/sandbox.py): what a kernel inside it can read, write, reach and use.

Each attack runs as a cell in a kernel started by ``SandboxKernelManager``
and prints what it achieved; the test asserts the sandbox refused it.  On
this machine (Debian's bubblewrap, run as root, control groups v1) the
sandbox runs: the tests that need one skip, saying why, where it does not.
"""

import json
import os
import pathlib
import struct
import subprocess
import sys

import nbformat
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade_run  # noqa: E402
import sandbox  # noqa: E402
from jupyter_core.utils import run_sync  # noqa: E402
from nbclient import NotebookClient  # noqa: E402

REASON = sandbox.unavailable()
needs_sandbox = pytest.mark.skipif(
    REASON is not None, reason=f"no sandbox on this machine: {REASON}"
)
MIB = 2**20


def isolation(cgroups=None, filter_file=None):
    return sandbox.Isolation(
        "/usr/bin/bwrap", "/usr/bin/setpriv", "/usr/bin/prlimit", cgroups, filter_file
    )


def test_the_command_builds_the_sandbox_from_an_allow_list(tmp_path):
    limits = sandbox.Limits(
        address_space_bytes=2**30, cpu_seconds=60, processes=32, tmp_bytes=8 * MIB
    )
    command = sandbox.command_prefix(
        tmp_path / "run",
        isolation(),
        limits,
        user=101234,
        variables={"TWOLINK_GRADING": "1"},
        submission=tmp_path / "s.ipynb",
    )
    text = " ".join(command)
    assert (
        command[0] == "/usr/bin/bwrap" and "--ro-bind / /" not in text
    )  # nothing of the machine by default
    assert "--ro-bind /usr /usr" in text and "--clearenv" in command
    for flag in (
        "--unshare-net",
        "--unshare-pid",
        "--unshare-ipc",
        "--die-with-parent",
        "--new-session",
    ):
        assert flag in command
    assert (
        f"--size {8 * MIB} --tmpfs /tmp" in text
        and "--tmpfs /dev/shm" in text
        and "--tmpfs /home/student" in text
    )
    assert f"--bind {tmp_path / 'run'} {tmp_path / 'run'}" in text
    assert f"--ro-bind {tmp_path / 's.ipynb'} /home/student/submission.ipynb" in text
    assert (
        "--setenv TWOLINK_GRADING 1" in text
        and "--setenv OPENBLAS_NUM_THREADS 1" in text
    )
    assert "--reuid=101234" in text
    assert "--as=1073741824" in command and "--cpu=60" in command
    assert command[-1] == "--"
    if pathlib.Path("/bin").is_symlink():
        assert f"--symlink {os.readlink('/bin')} /bin" in text


def test_the_kernel_s_environment_is_the_allow_list_alone(monkeypatch):
    monkeypatch.setenv("TEACHERS_SECRET", "hunter2")
    found = sandbox.environment({"TWOLINK_GRADING": "1"})
    assert "TEACHERS_SECRET" not in found and found["TWOLINK_GRADING"] == "1"
    assert set(found) == {
        "HOME", "PATH", "LANG", "LC_ALL", "TMPDIR", "IPYTHONDIR", "MPLCONFIGDIR", "OPENBLAS_NUM_THREADS",
        "OMP_NUM_THREADS", "MKL_NUM_THREADS", "PYDEVD_DISABLE_FILE_VALIDATION", "TWOLINK_GRADING",
    }  # fmt: skip


def test_groups_are_joined_and_the_filter_opened_before_bwrap_starts(tmp_path):
    group = sandbox.NotebookGroup(1, {"memory": tmp_path / "m", "pids": tmp_path / "p"})
    command = sandbox.command_prefix(
        tmp_path,
        isolation(filter_file=str(tmp_path / "f.bpf")),
        sandbox.Limits(),
        group=group,
    )
    assert command[:2] == ["/bin/sh", "-c"]
    assert f"echo $$ > {tmp_path / 'm' / 'cgroup.procs'} || exit 125" in command[2]
    assert (
        command[2].endswith(f'exec "$@" 9< {tmp_path / "f.bpf"}')
        and "--seccomp" in command
    )


def test_user_for_gives_each_grader_process_a_user_of_its_own():
    assert sandbox.user_for(1) != sandbox.user_for(2) and sandbox.user_for(1) >= 100_000


def test_unavailable_says_what_is_missing(monkeypatch):
    monkeypatch.setattr(sandbox.shutil, "which", lambda name: None)
    assert sandbox.unavailable().startswith("bwrap")
    assert "apt-get install bubblewrap" in sandbox.unavailable()


def test_the_one_process_filter_refuses_forks_and_allows_threads():
    program = sandbox.one_process_filter()
    instructions = [
        struct.unpack("=HBBI", program[i : i + 8]) for i in range(0, len(program), 8)
    ]
    returns = [k for code, _, _, k in instructions if code == 0x06]
    assert (
        0x7FFF0000 in returns and 0x00050001 in returns and 0x00050026 in returns
    )  # allow, EPERM, ENOSYS
    assert (
        0x45,
        0,
        1,
        0x10000,
    ) in instructions  # clone with CLONE_THREAD: allowed, else refused
    for index, (code, jt, jf, _) in enumerate(instructions):
        if code in (0x15, 0x35, 0x45):  # every jump lands inside the program
            assert index + 1 + max(jt, jf) < len(instructions)


def fake_mounts(tmp_path, version):
    mounts = tmp_path / "mounts"
    if version == 1:
        lines = []
        for controller in ("memory", "pids", "cpuacct"):
            folder = tmp_path / controller
            folder.mkdir()
            lines.append(f"cgroup {folder} cgroup rw,relatime,{controller} 0 0")
        mounts.write_text("\n".join(lines) + "\n")
    else:
        root = tmp_path / "unified"
        root.mkdir()
        (root / "cgroup.controllers").write_text("cpu memory pids\n")
        (root / "cgroup.subtree_control").write_text("")
        mounts.write_text(f"cgroup2 {root} cgroup2 rw 0 0\n")
    return mounts


@pytest.mark.parametrize("version", [1, 2])
def test_control_groups_are_found_and_a_notebook_s_limits_written(
    tmp_path, version, monkeypatch
):
    monkeypatch.setattr(
        sandbox.NotebookGroup, "remove", lambda self, budget_seconds=10.0: None
    )
    mounts = fake_mounts(tmp_path, version)
    if (
        version == 2
    ):  # a folder of the grader's groups, given memory, pids and cpu for its children
        made = tmp_path / "unified" / "twolink-grade"
        monkeypatch.setattr(
            sandbox,
            "_enable_v2",
            lambda folder: (
                made.mkdir(exist_ok=True),
                (made / "cgroup.subtree_control").write_text(""),
            ),
        )
    cgroups = sandbox.Cgroups.detect(str(mounts))
    assert cgroups is not None and cgroups.version == version
    for folder in cgroups.folders.values():
        pathlib.Path(folder).mkdir(exist_ok=True)
    files = (
        {"memory.limit_in_bytes", "memory.memsw.limit_in_bytes", "pids.max"}
        if version == 1
        else {"memory.max", "memory.swap.max", "pids.max"}
    )
    original_mkdir = pathlib.Path.mkdir

    def mkdir(
        self, *args, **kwargs
    ):  # a group's folder, as the kernel makes it: with its files
        original_mkdir(self, *args, **kwargs)
        for name in files:
            (self / name).write_text("max")

    monkeypatch.setattr(pathlib.Path, "mkdir", mkdir)
    group = cgroups.make(
        "notebook-1", sandbox.Limits(memory_bytes=123 * MIB, processes=17)
    )

    def read(controller, name):
        return (group.paths[controller] / name).read_text()

    if version == 1:
        assert read("memory", "memory.limit_in_bytes") == str(123 * MIB)
        assert read("memory", "memory.memsw.limit_in_bytes") == str(123 * MIB)
        assert read("pids", "pids.max") == "17"
    else:
        assert read("unified", "memory.max") == str(123 * MIB)
        assert read("unified", "memory.swap.max") == "0"
        assert read("unified", "pids.max") == "17"


def test_no_control_groups_where_they_cannot_be_made(tmp_path):
    (tmp_path / "mounts").write_text("proc /proc proc rw 0 0\n")
    assert sandbox.Cgroups.detect(str(tmp_path / "mounts")) is None


def test_what_a_group_counted_is_told_in_words():
    limits = sandbox.Limits(memory_bytes=512 * MIB)
    assert sandbox.overruns({"memory_oom": 2, "processes_refused": 0}, limits) == [
        "used more than 512 MiB of memory (the limit per notebook): a process was killed"
    ]
    assert sandbox.full_disk(
        ["cell 2: OSError: [Errno 27] File too large"], limits
    ) == ["wrote a file larger than 200 MiB (the limit per file)"]


# ------------------------------------------------------------------ in a real sandbox

ATTACKS = {
    "read_a_classmate_s_folder": (
        "import os\ntry:\n    print(sorted(os.listdir({classmates!r})))\nexcept OSError as error:\n    print('refused', type(error).__name__)",
        "refused FileNotFoundError",
    ),
    "read_the_repository": (
        "import os\nprint('answers' in os.listdir({root!r}) or 'notebooks' in os.listdir({root!r}))",
        "False",  # only the two packages of the repository are bound
    ),
    "read_the_grader_home": (
        "import os\ntry:\n    print(os.listdir({home!r}))\nexcept OSError as error:\n    print('refused', type(error).__name__)",
        None,  # absent, or an empty folder made for a path below it: checked below
    ),
    "write_the_package": (
        "try:\n    open({package_file!r}, 'a').write('# patched')\n    print('wrote')\nexcept OSError as error:\n    print('refused', error.errno)",
        "refused",
    ),
    "reach_the_network": (
        "import socket\ntry:\n    socket.create_connection(('1.1.1.1', 80), timeout=2)\n    print('connected')\n"
        "except OSError as error:\n    print('refused', type(error).__name__)",
        "refused OSError",
    ),
    "read_the_teacher_s_environment": ("import os\nprint(sorted(os.environ))", None),
    "see_the_grader": (
        "import os\nprint(sorted(int(p) for p in os.listdir('/proc') if p.isdigit())[:1])",
        "[1]",
    ),
    "read_its_own_submission": ("print(open('submission.ipynb').read()[:1])", "{"),
    "fill_the_tmpfs": (
        "import os\nfull = []\nfor folder in ('/tmp', '/dev/shm', os.path.expanduser('~')):\n"
        "    try:\n        with open(os.path.join(folder, 'flood'), 'wb') as handle:\n"
        "            for _ in range(64):\n                handle.write(bytes(2**20))\n        full.append('wrote')\n"
        "    except OSError as error:\n        full.append(error.strerror)\nprint(full)",
        "['No space left on device', 'No space left on device', 'No space left on device']",
    ),
}


@pytest.fixture(scope="module")
def printed(tmp_path_factory):
    if REASON is not None:
        pytest.skip(f"no sandbox on this machine: {REASON}")
    folder = tmp_path_factory.mktemp("sandboxed")
    classmates = folder / "class" / "bob"
    classmates.mkdir(parents=True)
    (classmates / "01.ipynb").write_text("{}", encoding="utf-8")
    submission = folder / "submission.ipynb"
    submission.write_text("{}", encoding="utf-8")
    values = {
        "classmates": str(classmates),
        "root": str(ROOT),
        "home": str(pathlib.Path.home()),
        "package_file": str(ROOT / "twolink_course" / "selfcheck.py"),
    }
    notebook = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_code_cell(code.format(**values))
            for code, _ in ATTACKS.values()
        ]
    )
    scratch = grade_run.make_scratch()
    found = sandbox.Isolation.detect(scratch)
    limits = sandbox.Limits(
        tmp_bytes=16 * MIB, shm_bytes=16 * MIB, workdir_bytes=16 * MIB
    )
    os.environ["TEACHERS_SECRET"] = (
        "hunter2"  # the grader's environment: never the kernel's
    )
    manager = sandbox.SandboxKernelManager(
        scratch, found, limits, user=sandbox.user_for(1), submission=submission
    )
    try:
        NotebookClient(notebook, km=manager, timeout=60, allow_errors=True).execute()
    finally:
        del os.environ["TEACHERS_SECRET"]
        if manager.has_kernel:
            run_sync(manager.shutdown_kernel)(now=True)
        manager.finish()
        grade_run.remove_scratch(grade_run.Setting(scratch, found))
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
def test_the_grader_home_and_environment_are_out_of_reach(printed):
    assert (
        printed["read_the_grader_home"].startswith("refused")
        or "wt-grading" not in printed["read_the_grader_home"]
    )
    variables = json.loads(printed["read_the_teacher_s_environment"].replace("'", '"'))
    assert (
        "TEACHERS_SECRET" not in variables
    )  # set for the grader while the kernel started
    # nothing else of the grader's: what is there is the allow-list or set by ipykernel itself
    assert set(sandbox.environment({})) <= set(variables)
    assert not {
        name
        for name in variables
        if name.startswith(("PYTEST", "VIRTUAL_ENV", "JUPYTER", "SSH", "XDG"))
    }


@pytest.fixture(scope="module")
def runner():
    """A runner of the grader's, its worker shared by the tests that run a notebook through it."""
    if REASON is not None:
        pytest.skip(f"no sandbox on this machine: {REASON}")
    scratch = grade_run.make_scratch()
    setting = grade_run.Setting(scratch, sandbox.Isolation.detect(scratch))
    found = grade_run.Runner(setting)
    yield found
    found.close()
    grade_run.remove_scratch(setting)


def graded_alone(runner, sources, limits, cgroups=True):
    """Run ``sources`` as a notebook through the grader's worker, with ``limits`` and with or without control groups."""
    scratch = runner.setting.scratch
    found = sandbox.Isolation.detect(scratch)
    if not cgroups:
        path = scratch / "one-process.bpf"
        path.write_bytes(sandbox.one_process_filter())
        found = sandbox.Isolation(
            found.bwrap, found.setpriv, found.prlimit, None, str(path)
        )
    runner.setting = grade_run.Setting(scratch, found, grade_run.Limits(30, 90, limits))
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source) for source in sources]
    )
    return runner.run(notebook)


#: Three processes of 300 MiB each: each holds its block until all three have one or were killed.
MEMORY_FLOOD = (
    "import subprocess, sys\n"
    "code = 'import sys; block = bytearray(300 * 2**20); print(1, flush=True); sys.stdin.read()'\n"
    "started = [subprocess.Popen([sys.executable, '-c', code], stdin=subprocess.PIPE, stdout=subprocess.PIPE)"
    " for _ in range(3)]\n"
    "held = [process.stdout.readline() == b'1\\n' for process in started]\n"
    "for process in started:\n    process.stdin.close()\n"
    "print(held, [process.wait() for process in started])"
)


@pytest.mark.infrastructure
@needs_sandbox
@pytest.mark.skipif(
    sandbox.Cgroups.detect() is None,
    reason="no control groups the grader may make here",
)
def test_memory_taken_by_several_processes_is_limited_as_a_whole(runner):
    limits = sandbox.Limits(memory_bytes=512 * MIB, address_space_bytes=6 * 2**30)
    ran = graded_alone(runner, [MEMORY_FLOOD], limits)
    assert (
        "used more than 512 MiB of memory (the limit per notebook): a process was killed"
        in ran["limits"]
    )
    assert ran["cpu_seconds"] is not None


@pytest.mark.infrastructure
@needs_sandbox
def test_without_control_groups_a_kernel_is_one_process_with_its_address_space_limited(
    runner,
):
    sources = [
        "import threading\nthread = threading.Thread(target=print, args=('a thread runs',))\nthread.start()\nthread.join()",
        MEMORY_FLOOD,
        "try:\n    block = bytearray(2 * 2**30)\n    print('took 2 GiB')\nexcept MemoryError:\n    print('refused MemoryError')",
    ]
    limits = sandbox.Limits(address_space_bytes=1536 * MIB)
    ran = graded_alone(runner, sources, limits, cgroups=False)
    assert ran["failure"] is None
    assert ran["errors"][0].startswith(
        "cell 2: PermissionError: [Errno 1] Operation not permitted"
    )


@pytest.mark.infrastructure
@needs_sandbox
def test_a_venv_reached_through_a_symbolic_link_runs_in_the_sandbox(tmp_path):
    link = tmp_path / "venv-link"
    link.symlink_to(pathlib.Path(sys.prefix).resolve())
    script = (
        "import sys, pathlib, subprocess\n"
        f"sys.path.insert(0, {str(ROOT / 'tools')!r})\n"
        "import sandbox\n"
        f"runtime = pathlib.Path({str(tmp_path / 'run')!r}); runtime.mkdir(); runtime.chmod(0o777)\n"
        "found = sandbox.Isolation.detect(runtime)\n"
        "command = sandbox.command_prefix(runtime, sandbox.Isolation(found.bwrap, found.setpriv, found.prlimit, None, None), sandbox.Limits())\n"
        "print(subprocess.run(command + [sys.executable, '-c', 'import twolink_course.selfcheck; print(\"ran\")'], capture_output=True, text=True).stdout)\n"
    )
    result = subprocess.run(
        [str(link / "bin" / "python"), "-c", script],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert "ran" in result.stdout, result.stderr[-2000:]
