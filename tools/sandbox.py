"""A kernel in a sandbox, for grading untrusted notebooks: bubblewrap, an unprivileged user, limits.

:class:`SandboxKernelManager` starts the ordinary IPython kernel inside

- ``setpriv`` as an unprivileged user of its own, with no capabilities (so a
  process limit applies, and nothing the grader owns is writable),
- ``prlimit`` limits: address space, CPU seconds, processes, file size, open files,
- ``bwrap`` (Debian's ``bubblewrap``): the filesystem read-only, ``/tmp`` and
  ``HOME`` private, the folders in ``hidden`` (submissions, grades, the
  instructor's notebooks and answers) replaced by empty ones, only the
  notebook's own working folder writable, no network (every namespace
  unshared), a new session, and the whole sandbox killed with its parent.

The kernel talks to the grader over Unix sockets (``transport="ipc"``) in a
folder bound into the sandbox, so no network is needed.  A grader without
``bwrap`` or ``setpriv`` cannot sandbox: :func:`missing` says what is missing.

Usage (a kernel manager for nbclient)::

    manager = SandboxKernelManager(workdir=folder, hidden=[submissions], limits=Limits())
    NotebookClient(notebook, km=manager).execute()
"""

from __future__ import annotations

import dataclasses
import importlib.util
import os
import pathlib
import shutil
import stat
import subprocess
import sys
import tempfile
from collections.abc import Mapping, Sequence
from typing import Any

from jupyter_client.manager import AsyncKernelManager

#: The unprivileged user (and group) a kernel runs as by default.  Kernels that
#: run at the same time need users of their own: a process limit counts every
#: process of its user, so one notebook's process flood would otherwise starve
#: another's kernel.
NOBODY = 65534


def user_for(process_id: int) -> int:
    """An unused user id of its own for the sandbox started by process ``process_id``.

    >>> user_for(1234)
    101234
    """
    return 100_000 + process_id


@dataclasses.dataclass(frozen=True)
class Limits:
    """What one notebook's kernel may use."""

    memory_bytes: int = 6 * 2**30  # address space, numpy/OpenBLAS/MuJoCo reserve a lot
    cpu_seconds: int = 600
    processes: int = 256  # threads included, over every process of the sandbox's user
    file_bytes: int = 200 * 2**20  # the largest file it may write
    open_files: int = 1024


def missing() -> list[str]:
    """The programs a sandbox needs that this machine lacks (empty: it can sandbox)."""
    needed = (
        ("bwrap", "setpriv", "prlimit") if os.geteuid() == 0 else ("bwrap", "prlimit")
    )
    return [name for name in needed if shutil.which(name) is None]


def unavailable() -> str | None:
    """Why no sandbox can be had on this machine (a program missing, bwrap refused), or None.

    Runs ``true`` in the sandbox once, so that a ``bwrap`` that is installed
    but not allowed (no user namespaces, no privileges) is found before grading.
    """
    absent = missing()
    if absent:
        return f"{', '.join(absent)} not found (Debian: apt-get install bubblewrap util-linux)"
    folder = pathlib.Path(tempfile.mkdtemp(prefix="twolink-sandbox-check-"))
    try:
        command = command_prefix(folder, folder, [], Limits()) + ["true"]
        try:
            finished = subprocess.run(
                command, capture_output=True, text=True, timeout=30, check=False
            )
        except (OSError, subprocess.TimeoutExpired) as error:
            return f"bwrap could not run: {error}"
        if finished.returncode != 0:
            reason = (finished.stderr.strip().splitlines() or ["no message"])[-1]
            return f"bwrap refused to start a sandbox: {reason[:200]}"
        return None
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def command_prefix(
    workdir: pathlib.Path,
    runtime: pathlib.Path,
    hidden: Sequence[pathlib.Path],
    limits: Limits,
    user: int = NOBODY,
    environment: Mapping[str, str] | None = None,
) -> list[str]:
    """The command that runs a program in the sandbox (the program's argv follows it).

    ``bwrap`` (started by the grader) builds the filesystem view and the
    namespaces; inside it, for a grader running as root, ``setpriv`` drops to
    the unprivileged ``user`` with no capabilities (a grader that is not root
    gets a user namespace of its own from ``bwrap`` instead), and ``prlimit``
    sets the limits.  ``environment``: variables set in the sandbox.
    """
    home = workdir / "home"
    prefix = [
        "bwrap",
        "--ro-bind", "/", "/",
        "--dev", "/dev",
        "--proc", "/proc",
        "--perms", "1777", "--tmpfs", "/tmp",
        "--perms", "1777", "--tmpfs", "/dev/shm",
    ]  # fmt: skip
    # the grader's home is private too
    grader_home = pathlib.Path.home().resolve()
    prefix += ["--perms", "0755", "--tmpfs", str(grader_home)]
    # what the kernel runs on is bound back read-only wherever it lives (pyenv
    # in the home, a clone and its venv in /tmp)
    masked = [pathlib.Path("/tmp"), grader_home]
    for path in needed_paths():
        below = next((root for root in masked if path.is_relative_to(root)), None)
        if below is None or path == below:
            continue
        for parent in reversed(path.relative_to(below).parents[:-1]):
            prefix += ["--perms", "0755", "--dir", str(below / parent)]
        prefix += ["--ro-bind", str(path), str(path)]
    # last, so that a hidden folder inside a bound-back one stays hidden; a hidden
    # file (a git worktree's .git is one) is covered by an empty one
    for path in hidden:
        if path.is_dir():
            prefix += ["--tmpfs", str(path.resolve())]
        elif path.exists():
            prefix += ["--ro-bind", "/dev/null", str(path.resolve())]
    prefix += [
        "--bind", str(workdir), str(workdir),
        "--bind", str(runtime), str(runtime),
        "--chdir", str(workdir),
        "--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts",
        "--unshare-cgroup-try",
        "--die-with-parent",
        "--new-session",
        "--setenv", "HOME", str(home),
        "--setenv", "IPYTHONDIR", str(home / ".ipython"),
        "--setenv", "MPLCONFIGDIR", str(home / ".matplotlib"),
        "--setenv", "TMPDIR", str(workdir),
        # in its own process namespace the kernel's parent is the sandbox's init
        # (pid 1), which ipykernel's parent poller would take for an exit
        "--unsetenv", "JPY_PARENT_PID",
    ]  # fmt: skip
    for name, value in (environment or {}).items():
        prefix += ["--setenv", name, value]
    if os.geteuid() == 0:
        prefix += [
            "--",
            "setpriv", f"--reuid={user}", f"--regid={user}", "--clear-groups",
            "--inh-caps=-all", "--bounding-set=-all",
        ]  # fmt: skip
    else:
        prefix[1:1] = ["--unshare-user"]
    prefix += [
        "--",
        "prlimit",
        f"--as={limits.memory_bytes}",
        f"--cpu={limits.cpu_seconds}",
        f"--nproc={limits.processes}",
        f"--fsize={limits.file_bytes}",
        f"--nofile={limits.open_files}",
        "--",
    ]  # fmt: skip
    return prefix


#: The packages a graded notebook imports: the library and the course kit (bound read-only).
PACKAGES = ("twolink", "twolink_course")


def needed_paths() -> list[pathlib.Path]:
    """What a kernel needs to read: the Python installation, the environment, and the two
    packages, the library twolink and the course kit twolink_course.

    >>> pathlib.Path(sys.prefix).resolve() in needed_paths()
    True
    """
    paths = [pathlib.Path(sys.base_prefix), pathlib.Path(sys.prefix)]
    for package in PACKAGES:
        spec = importlib.util.find_spec(package)  # finds it without importing it
        if spec is not None and spec.origin is not None:
            paths.append(pathlib.Path(spec.origin).parent)
    return sorted({path.resolve() for path in paths})


class SandboxKernelManager(AsyncKernelManager):
    """An IPython kernel started in the sandbox of :func:`command_prefix`, over Unix sockets."""

    def __init__(
        self,
        workdir: pathlib.Path,
        hidden: Sequence[pathlib.Path] = (),
        limits: Limits = Limits(),
        user: int = NOBODY,
        environment: Mapping[str, str] | None = None,
        **kwargs: Any,
    ) -> None:
        self._runtime = pathlib.Path(tempfile.mkdtemp(prefix="twolink-kernel-"))
        super().__init__(transport="ipc", ip=str(self._runtime / "kernel"), **kwargs)
        self.connection_file = str(self._runtime / "connection.json")
        self._workdir = workdir
        self._hidden = list(hidden)
        self._limits = limits
        self._user = user
        self._environment = dict(environment or {})
        (workdir / "home").mkdir(exist_ok=True)
        for folder in (self._runtime, workdir, workdir / "home"):
            # the kernel's user reads the connection file and makes its sockets here
            folder.chmod(0o777)

    @property
    def kernel_spec(self) -> Any:
        """The kernel's spec, interrupted by a message: a signal would reach ``bwrap``, not the kernel."""
        spec = super().kernel_spec
        if spec is not None:
            spec.interrupt_mode = "message"
        return spec

    def format_kernel_cmd(self, extra_arguments: list[str] | None = None) -> list[str]:
        command = super().format_kernel_cmd(extra_arguments)
        prefix = command_prefix(
            self._workdir,
            self._runtime,
            self._hidden,
            self._limits,
            self._user,
            self._environment,
        )
        return prefix + command

    async def _async_pre_start_kernel(
        self, **kw: Any
    ) -> tuple[list[str], dict[str, Any]]:
        command, kw = await super()._async_pre_start_kernel(**kw)
        # the key is in it: readable by the kernel's user; the folder is the grader's, in a
        # /tmp that every sandbox replaces by its own
        os.chmod(self.connection_file, stat.S_IRUSR | stat.S_IWUSR | stat.S_IROTH)
        kw.pop("cwd", None)  # bwrap --chdir sets it; the grader's cwd may be hidden
        return command, kw

    def cleanup_runtime(self) -> None:
        """Remove the sockets' folder (after the kernel is shut down)."""
        shutil.rmtree(self._runtime, ignore_errors=True)
