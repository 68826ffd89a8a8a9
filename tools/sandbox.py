"""A kernel in a sandbox, for grading untrusted notebooks: bubblewrap, a user of its own, limits per notebook.

:class:`SandboxKernelManager` starts the grader's own Python's IPython kernel inside

- ``bwrap`` (Debian's ``bubblewrap``): a filesystem built from an allow-list
  (the system's ``/usr`` and ``/etc``, the Python installation, the
  environment and the two packages, read-only; nothing else of the machine:
  no home, no repository, no submissions, no grades), the working folder
  (also ``HOME``), ``/tmp`` and ``/dev/shm`` as tmpfs of a fixed size, the
  notebook's own file read-only in the working folder, no network (every
  namespace unshared), a new session, the environment built from
  :func:`environment` alone (``--clearenv``), the whole sandbox killed with its
  parent;
- ``setpriv`` as an unprivileged user of its own, with no capabilities (a
  grader running as root; otherwise ``bwrap``'s user namespace);
- ``prlimit`` limits per process: address space, CPU seconds, processes,
  file size, open files;
- and limits on the notebook as a whole: with control groups
  (:class:`Cgroups`: v1 hierarchies or v2, where the grader may create them)
  its processes together may use ``Limits.memory_bytes`` of memory (tmpfs
  files included) and ``Limits.processes`` processes, and their CPU time is
  counted; without them the kernel stays one process (a seccomp filter,
  :func:`one_process_filter`, refuses ``fork``, and ``clone`` other than a
  thread's), so its address-space limit bounds its memory.

The kernel talks to the grader over Unix sockets (``transport="ipc"``) in a
folder of the grader's scratch folder bound into the sandbox at the same
path; the scratch folder is the grader's alone (mode 0700), so no other user
of the machine reads a copy of a submission or the kernel's key.

:func:`Isolation.detect` says what this machine offers (and
:func:`Isolation.unavailable` why there is no sandbox at all).
"""

from __future__ import annotations

import dataclasses
import importlib.util
import os
import pathlib
import platform
import shlex
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import time
from collections.abc import Mapping, Sequence
from typing import Any

from jupyter_client.manager import AsyncKernelManager

GIB, MIB = 2**30, 2**20
#: The unprivileged user (and group) a kernel runs as by default.  Kernels that
#: run at the same time need users of their own: a process limit counts every
#: process of its user, so one notebook's process flood would otherwise starve
#: another's kernel.
NOBODY = 65534
#: Inside the sandbox: the working folder, which is also the kernel's home.
WORKDIR = pathlib.PurePosixPath("/home/student")
#: The system folders every sandbox reads (those that exist; symbolic links, such
#: as a merged /usr's ``/bin -> usr/bin``, are made again as links).
SYSTEM = ("/usr", "/etc", "/bin", "/sbin", "/lib", "/lib64", "/lib32", "/libx32")
#: The packages a graded notebook imports: the library and the course kit (bound read-only).
PACKAGES = ("twolink", "twolink_course")


def user_for(process_id: int) -> int:
    """An unused user id of its own for the sandbox started by process ``process_id``.

    >>> user_for(1234)
    101234
    """
    return 100_000 + process_id


@dataclasses.dataclass(frozen=True)
class Limits:
    """What one notebook may use.

    ``memory_bytes``, ``processes``: the notebook as a whole (its control
    groups); ``address_space_bytes``: each process (``RLIMIT_AS``; numpy,
    OpenBLAS and MuJoCo reserve far more address space than they touch), which
    is the whole notebook's bound where there are no control groups (one
    process); the tmpfs sizes bound what it writes, ``file_bytes`` each file.
    """

    memory_bytes: int = 2 * GIB
    address_space_bytes: int = 6 * GIB
    cpu_seconds: int = 600
    processes: int = 64  # processes and threads, together
    file_bytes: int = 200 * MIB  # the largest file it may write
    tmp_bytes: int = 256 * MIB
    shm_bytes: int = 64 * MIB
    workdir_bytes: int = 256 * MIB
    open_files: int = 1024

    def words(self) -> str:
        """The limits in one line, for the grader's first line.

        >>> Limits().words()
        'memory 2 GiB, 64 processes, CPU 600 s, files: /tmp 256 MiB, /dev/shm 64 MiB, working folder 256 MiB'
        """
        return (
            f"memory {_size(self.memory_bytes)}, {self.processes} processes, CPU "
            f"{self.cpu_seconds} s, files: /tmp {_size(self.tmp_bytes)}, /dev/shm "
            f"{_size(self.shm_bytes)}, working folder {_size(self.workdir_bytes)}"
        )


def _size(count: int) -> str:
    """A size in GiB or MiB: ``_size(2 * GIB)`` is ``'2 GiB'``."""
    return f"{count / GIB:g} GiB" if count >= GIB else f"{count / MIB:g} MiB"


# ------------------------------------------------------------------ control groups


@dataclasses.dataclass(frozen=True)
class Cgroups:
    """Where the grader may make a notebook's control groups: v1 hierarchies, or one v2 folder.

    ``folders``: controller -> the folder under which a notebook's group is made
    (``{"memory": ..., "pids": ..., "cpuacct": ...}`` for v1; one folder under
    ``"unified"`` for v2).
    """

    version: int
    folders: Mapping[str, str]

    @classmethod
    def detect(cls, mounts: str = "/proc/self/mounts") -> Cgroups | None:
        """The control groups this grader may make with memory and process limits, or None."""
        try:
            lines = pathlib.Path(mounts).read_text(encoding="utf-8").splitlines()
        except OSError:
            return None
        v1: dict[str, str] = {}
        v2: str | None = None
        for line in lines:
            fields = line.split()
            if len(fields) < 4:
                continue
            if fields[2] == "cgroup2":
                v2 = fields[1]
            elif fields[2] == "cgroup":
                for controller in ("memory", "pids", "cpuacct"):
                    if controller in fields[3].split(","):
                        v1[controller] = fields[1]
        if {"memory", "pids"} <= set(v1):
            found = cls(1, v1)
            if found._writable():
                return found
        if v2 is not None:
            controllers = pathlib.Path(v2, "cgroup.controllers")
            try:
                offered = controllers.read_text(encoding="ascii").split()
            except OSError:
                offered = []
            if {"memory", "pids"} <= set(offered):
                found = cls(2, {"unified": str(pathlib.Path(v2, "twolink-grade"))})
                if found._writable():
                    return found
        return None

    def _writable(self) -> bool:
        """Whether a group can be made (and removed) under every folder."""
        probe = f"twolink-probe-{os.getpid()}"
        try:
            if self.version == 2:
                _enable_v2(pathlib.Path(self.folders["unified"]))
            for folder in set(self.folders.values()):
                path = pathlib.Path(folder, probe)
                path.mkdir()
                path.rmdir()
        except OSError:
            return False
        return True

    def make(self, name: str, limits: Limits) -> NotebookGroup:
        """A notebook's groups named ``name``, with ``limits`` written."""
        paths = {
            controller: pathlib.Path(folder, name)
            for controller, folder in self.folders.items()
        }
        for path in set(paths.values()):
            path.mkdir(exist_ok=True)
        group = NotebookGroup(self.version, paths)
        group.limit(limits)
        return group


def _enable_v2(folder: pathlib.Path) -> None:
    """Make the v2 folder of the grader's groups and give its children memory, pids and cpu."""
    folder.mkdir(exist_ok=True)
    for parent in (folder.parent, folder):
        offered = (parent / "cgroup.controllers").read_text(encoding="ascii").split()
        wanted = [c for c in ("memory", "pids", "cpu") if c in offered]
        (parent / "cgroup.subtree_control").write_text(
            " ".join(f"+{c}" for c in wanted), encoding="ascii"
        )


@dataclasses.dataclass
class NotebookGroup:
    """One notebook's control groups: its limits, what it used, and its removal."""

    version: int
    paths: Mapping[str, pathlib.Path]

    def _write(self, controller: str, name: str, value: str) -> bool:
        path = self.paths.get(controller)
        if path is None or not (path / name).exists():
            return False
        (path / name).write_text(value, encoding="ascii")
        return True

    def _read(self, controller: str, name: str) -> str:
        path = self.paths.get(controller)
        try:
            return (path / name).read_text(encoding="ascii") if path else ""
        except OSError:
            return ""

    def limit(self, limits: Limits) -> None:
        """Write the memory (swap included where counted) and process limits."""
        if self.version == 1:
            self._write("memory", "memory.limit_in_bytes", str(limits.memory_bytes))
            self._write(
                "memory", "memory.memsw.limit_in_bytes", str(limits.memory_bytes)
            )
            self._write("pids", "pids.max", str(limits.processes))
        else:
            self._write("unified", "memory.max", str(limits.memory_bytes))
            self._write("unified", "memory.swap.max", "0")
            self._write("unified", "pids.max", str(limits.processes))

    def procs_files(self) -> list[str]:
        """The files a process writes its id to, to join every group."""
        return sorted({str(path / "cgroup.procs") for path in self.paths.values()})

    def _events(self, controller: str, name: str) -> dict[str, int]:
        found = {}
        for line in self._read(controller, name).splitlines():
            key, _, value = line.partition(" ")
            if value.strip().isdigit():
                found[key] = int(value)
        return found

    def used(self) -> dict[str, Any]:
        """What the notebook used: ``memory_oom`` (kills), ``memory_peak`` (bytes),
        ``processes_refused`` (forks refused at the limit), ``cpu_seconds``."""
        if self.version == 1:
            oom = self._events("memory", "memory.oom_control").get("oom_kill", 0)
            peak = self._read("memory", "memory.max_usage_in_bytes").strip()
            refused = self._events("pids", "pids.events").get("max", 0)
            cpu = self._read("cpuacct", "cpuacct.usage").strip()
            seconds = int(cpu) / 1e9 if cpu.isdigit() else None
        else:
            oom = self._events("unified", "memory.events").get("oom_kill", 0)
            peak = self._read("unified", "memory.peak").strip()
            refused = self._events("unified", "pids.events").get("max", 0)
            usage = self._events("unified", "cpu.stat").get("usage_usec")
            seconds = usage / 1e6 if usage is not None else None
        return {
            "memory_oom": oom,
            "memory_peak": int(peak) if peak.isdigit() else None,
            "processes_refused": refused,
            "cpu_seconds": seconds,
        }

    def remove(self, budget_seconds: float = 10.0) -> None:
        """Kill every process still in the groups, then remove them (within a budget)."""
        deadline = time.monotonic() + budget_seconds
        for path in self.paths.values():
            while path.exists():
                for pid in _pids(path):
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except OSError:
                        pass
                try:
                    path.rmdir()
                except OSError:  # busy while its last processes exit
                    if time.monotonic() > deadline:
                        break
                    time.sleep(0.05)


def _pids(path: pathlib.Path) -> list[int]:
    try:
        text = (path / "cgroup.procs").read_text(encoding="ascii")
    except OSError:
        return []
    return [int(word) for word in text.split() if word.isdigit()]


# ------------------------------------------------------------------ one process without control groups


def one_process_filter() -> bytes:
    """A seccomp filter (classic BPF, x86-64) that refuses new processes and allows threads.

    ``fork``, ``vfork``, x32 system calls and any other architecture's get
    ``EPERM``; ``clone3`` gets ``ENOSYS`` (its flags cannot be read, and the C
    library then falls back to ``clone``); ``clone`` without ``CLONE_THREAD``
    gets ``EPERM``; everything else is allowed.

    >>> len(one_process_filter()) % 8, len(one_process_filter()) // 8
    (0, 14)
    """
    load, jeq, jge, jset, ret = 0x20, 0x15, 0x35, 0x45, 0x06
    allow, errno = 0x7FFF0000, 0x00050000
    eperm, enosys = 1, 38
    arch_x86_64, clone_thread = 0xC000003E, 0x00010000
    fork, vfork, clone, clone3 = 57, 58, 56, 435
    # (code, jump-if-true label, jump-if-false label, k); a label is an index
    ALLOW, DENY, NOSYS = 11, 12, 13
    program = [
        (load, None, None, 4),  # 0: the architecture
        (jeq, 2, DENY, arch_x86_64),  # 1
        (load, None, None, 0),  # 2: the system call's number
        (jge, DENY, 4, 0x40000000),  # 3: x32
        (jeq, DENY, 5, fork),  # 4
        (jeq, DENY, 6, vfork),  # 5
        (jeq, NOSYS, 7, clone3),  # 6
        (jeq, 9, ALLOW, clone),  # 7
        (ret, None, None, allow),  # 8 (unused: keeps the labels below fixed)
        (load, None, None, 16),  # 9: clone's flags (its first argument, low half)
        (jset, ALLOW, DENY, clone_thread),  # 10
        (ret, None, None, allow),  # 11 ALLOW
        (ret, None, None, errno | eperm),  # 12 DENY
        (ret, None, None, errno | enosys),  # 13 NOSYS
    ]
    packed = b""
    for index, (code, true, false, k) in enumerate(program):
        jt = 0 if true is None else true - index - 1
        jf = 0 if false is None else false - index - 1
        packed += struct.pack("=HBBI", code, jt, jf, k)
    return packed


# ------------------------------------------------------------------ what the machine offers


@dataclasses.dataclass(frozen=True)
class Isolation:
    """What sandboxes this machine gives: the programs, the control groups, or the one-process filter."""

    bwrap: str
    setpriv: str | None
    prlimit: str
    cgroups: Cgroups | None
    filter_file: str | None  # the one-process filter, where there are no control groups

    @staticmethod
    def missing() -> list[str]:
        """The programs a sandbox needs that this machine lacks (empty: it can sandbox)."""
        needed = (
            ("bwrap", "setpriv", "prlimit")
            if os.geteuid() == 0
            else ("bwrap", "prlimit")
        )
        return [name for name in needed if shutil.which(name) is None]

    @classmethod
    def detect(cls, scratch: pathlib.Path) -> Isolation:
        """What this machine offers (the programs must be there: see :meth:`missing`).

        Without control groups on x86-64, the one-process filter is written to ``scratch``.
        """
        absent = cls.missing()
        if absent:
            raise RuntimeError(f"{', '.join(absent)} not found")
        cgroups = Cgroups.detect()
        filter_file = None
        if cgroups is None and platform.machine() in ("x86_64", "AMD64"):
            path = scratch / "one-process.bpf"
            path.write_bytes(one_process_filter())
            filter_file = str(path)
        return cls(
            bwrap=str(shutil.which("bwrap")),
            setpriv=shutil.which("setpriv") if os.geteuid() == 0 else None,
            prlimit=str(shutil.which("prlimit")),
            cgroups=cgroups,
            filter_file=filter_file,
        )

    def words(self) -> str:
        """How the notebook as a whole is limited here, in words."""
        if self.cgroups is not None:
            return f"control groups v{self.cgroups.version} (memory, processes, CPU time per notebook)"
        if self.filter_file is not None:
            return "no control groups: each kernel is one process (seccomp), its address space limited"
        return (
            "no control groups and no one-process filter here: limits apply per process"
        )


def unavailable() -> str | None:
    """Why no sandbox can be had on this machine (a program missing, bwrap refused), or None.

    Runs ``true`` in the sandbox once, so that a ``bwrap`` that is installed
    but not allowed (no user namespaces, no privileges) is found before grading.
    """
    absent = Isolation.missing()
    if absent:
        return f"{', '.join(absent)} not found (Debian: apt-get install bubblewrap util-linux)"
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="twolink-sandbox-check-"))
    try:
        isolation = Isolation(
            bwrap=str(shutil.which("bwrap")),
            setpriv=shutil.which("setpriv") if os.geteuid() == 0 else None,
            prlimit=str(shutil.which("prlimit")),
            cgroups=None,
            filter_file=None,
        )
        runtime = scratch / "runtime"
        runtime.mkdir()
        command = command_prefix(runtime, isolation, Limits()) + ["/bin/true"]
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
        shutil.rmtree(scratch, ignore_errors=True)


# ------------------------------------------------------------------ the command


def needed_paths() -> list[pathlib.Path]:
    """What a kernel reads besides the system: the Python installation, the environment, the
    two packages (the library twolink and the course kit twolink_course), each both where it
    is reached (a symbolic link to a venv) and where it really is.

    >>> pathlib.Path(sys.prefix).resolve() in needed_paths()
    True
    """
    paths = [pathlib.Path(sys.base_prefix), pathlib.Path(sys.prefix)]
    for package in PACKAGES:
        spec = importlib.util.find_spec(package)  # finds it without importing it
        if spec is not None and spec.origin is not None:
            paths.append(pathlib.Path(spec.origin).parent)
    found = {path.absolute() for path in paths} | {path.resolve() for path in paths}
    return sorted(found)


def environment(extra: Mapping[str, str] | None = None) -> dict[str, str]:
    """The kernel's whole environment: an allow-list, nothing of the grader's.

    >>> sorted(environment({"TWOLINK_GRADING": "1"}))[:4]
    ['HOME', 'IPYTHONDIR', 'LANG', 'LC_ALL']
    """
    variables = {
        "HOME": str(WORKDIR),
        "PATH": f"{pathlib.Path(sys.executable).parent}:/usr/local/bin:/usr/bin:/bin",
        "LANG": "C.UTF-8",
        "LC_ALL": "C.UTF-8",
        "TMPDIR": "/tmp",
        "IPYTHONDIR": str(WORKDIR / ".ipython"),
        "MPLCONFIGDIR": str(WORKDIR / ".matplotlib"),
        # one BLAS thread: two kernels on two cores do not take turns on them
        "OPENBLAS_NUM_THREADS": "1",
        "OMP_NUM_THREADS": "1",
        "MKL_NUM_THREADS": "1",
        "PYDEVD_DISABLE_FILE_VALIDATION": "1",
    }
    variables.update(extra or {})
    return variables


def _system_binds() -> list[str]:
    binds = []
    for name in SYSTEM:
        path = pathlib.Path(name)
        if path.is_symlink():
            binds += ["--symlink", os.readlink(path), name]
        elif path.is_dir():
            binds += ["--ro-bind", name, name]
    return binds


def command_prefix(
    runtime: pathlib.Path,
    isolation: Isolation,
    limits: Limits,
    *,
    user: int = NOBODY,
    variables: Mapping[str, str] | None = None,
    submission: pathlib.Path | None = None,
    group: NotebookGroup | None = None,
) -> list[str]:
    """The command that runs a program in the sandbox (the program's argv follows it).

    ``runtime``: the folder of the kernel's sockets and connection file,
    bound at the same path; ``submission``: the notebook's own file, shown
    read-only in the working folder; ``group``: the notebook's control
    groups, joined before ``bwrap`` starts.
    """
    prefix = [isolation.bwrap]
    if isolation.setpriv is None:
        prefix += ["--unshare-user"]
    prefix += [
        "--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts",
        "--unshare-cgroup-try",
        "--die-with-parent",
        "--new-session",
        "--clearenv",
    ]  # fmt: skip
    prefix += _system_binds()
    prefix += ["--dev", "/dev", "--proc", "/proc"]
    prefix += ["--perms", "1777", "--size", str(limits.tmp_bytes), "--tmpfs", "/tmp"]
    prefix += [
        "--perms",
        "1777",
        "--size",
        str(limits.shm_bytes),
        "--tmpfs",
        "/dev/shm",
    ]
    prefix += [
        "--perms",
        "0777",
        "--size",
        str(limits.workdir_bytes),
        "--tmpfs",
        str(WORKDIR),
    ]
    system = [pathlib.Path(name) for name in SYSTEM]
    binds = [
        path
        for path in needed_paths()
        if not any(path.is_relative_to(root) for root in system)
    ]
    made: set[pathlib.Path] = {pathlib.Path("/"), pathlib.Path("/tmp")}
    for path in [*binds, runtime]:
        # the folders above a bound one: made readable (bwrap would make them 0700)
        for parent in reversed(path.parents):
            if parent not in made and not any(
                parent.is_relative_to(root) for root in system
            ):
                prefix += ["--perms", "0755", "--dir", str(parent)]
                made.add(parent)
        kind = "--bind" if path == runtime else "--ro-bind"
        prefix += [kind, str(path), str(path)]
    if submission is not None:
        prefix += ["--ro-bind", str(submission), str(WORKDIR / "submission.ipynb")]
    prefix += ["--chdir", str(WORKDIR)]
    for name, value in environment(variables).items():
        prefix += ["--setenv", name, value]
    if isolation.filter_file is not None:
        prefix += ["--seccomp", "9"]
    if isolation.setpriv is not None:
        prefix += [
            "--",
            isolation.setpriv, f"--reuid={user}", f"--regid={user}", "--clear-groups",
            "--inh-caps=-all", "--bounding-set=-all",
        ]  # fmt: skip
    prefix += [
        "--",
        isolation.prlimit,
        f"--as={limits.address_space_bytes}",
        f"--cpu={limits.cpu_seconds}",
        f"--nproc={max(limits.processes, 256)}",
        f"--fsize={limits.file_bytes}",
        f"--nofile={limits.open_files}",
        "--",
    ]  # fmt: skip
    joins = group.procs_files() if group is not None else []
    if joins or isolation.filter_file is not None:
        # a shell joins the groups, then becomes bwrap (the filter on its descriptor 9)
        script = "".join(
            f"echo $$ > {shlex.quote(path)} || exit 125; " for path in joins
        )
        script += 'exec "$@"'
        if isolation.filter_file is not None:
            script += f" 9< {shlex.quote(isolation.filter_file)}"
        prefix = ["/bin/sh", "-c", script, "sh", *prefix]
    return prefix


# ------------------------------------------------------------------ the kernel manager


class SandboxKernelManager(AsyncKernelManager):
    """The grader's own Python's IPython kernel, started in the sandbox of :func:`command_prefix`, over Unix sockets."""

    def __init__(
        self,
        scratch: pathlib.Path,
        isolation: Isolation,
        limits: Limits = Limits(),
        *,
        user: int = NOBODY,
        variables: Mapping[str, str] | None = None,
        submission: pathlib.Path | None = None,
        group_name: str = "",
        **kwargs: Any,
    ) -> None:
        self._runtime = pathlib.Path(
            tempfile.mkdtemp(prefix="kernel-", dir=scratch)
        ).resolve()
        super().__init__(transport="ipc", ip=str(self._runtime / "kernel"), **kwargs)
        self.connection_file = str(self._runtime / "connection.json")
        self._isolation = isolation
        self._limits = limits
        self._user = user
        self._variables = dict(variables or {})
        self._submission = submission
        self.group: NotebookGroup | None = None
        if isolation.cgroups is not None:
            self.group = isolation.cgroups.make(
                self._runtime.name + f"-{os.getpid()}", limits
            )
        if isolation.setpriv is not None:
            # the kernel's user makes its sockets here; the scratch folder above is 0700
            self._runtime.chmod(0o777)

    @property
    def kernel_spec(self) -> Any:
        """The kernel's spec, interrupted by a message: a signal would reach ``bwrap``, not the kernel."""
        spec = super().kernel_spec
        if spec is not None:
            spec.interrupt_mode = "message"
        return spec

    def format_kernel_cmd(self, extra_arguments: list[str] | None = None) -> list[str]:
        # the grader's own Python, whatever kernel spec is installed
        kernel = [
            sys.executable, "-m", "ipykernel_launcher", "-f", self.connection_file,
            "--HistoryManager.enabled=False",
        ]  # fmt: skip
        return (
            command_prefix(
                self._runtime,
                self._isolation,
                self._limits,
                user=self._user,
                variables=self._variables,
                submission=self._submission,
                group=self.group,
            )
            + kernel
        )

    async def _async_pre_start_kernel(
        self, **kw: Any
    ) -> tuple[list[str], dict[str, Any]]:
        command, kw = await super()._async_pre_start_kernel(**kw)
        # the key is in it: readable by the kernel's user; its folder is in the
        # grader's scratch folder (0700)
        mode = stat.S_IRUSR | stat.S_IWUSR
        os.chmod(
            self.connection_file,
            mode | (stat.S_IROTH if self._isolation.setpriv else 0),
        )
        kw.pop(
            "cwd", None
        )  # bwrap --chdir sets it; the grader's cwd is not in the sandbox
        kw["env"] = {"PATH": os.environ.get("PATH", "/usr/bin:/bin")}  # bwrap's own
        return command, kw

    def finish(self) -> dict[str, Any]:
        """After the kernel is shut down: what the notebook used; its groups and sockets removed."""
        used: dict[str, Any] = {}
        try:
            if self.group is not None:
                used = self.group.used()
                self.group.remove()
        finally:
            shutil.rmtree(self._runtime, ignore_errors=True)
        return used


def overruns(used: Mapping[str, Any], limits: Limits) -> list[str]:
    """Each limit the notebook as a whole ran into, in words, from what its groups counted.

    >>> overruns({"memory_oom": 1, "processes_refused": 3}, Limits())
    ['used more than 2 GiB of memory (the limit per notebook): a process was killed', 'started more than 64 processes and threads (the limit per notebook): 3 refused']
    """
    found = []
    if used.get("memory_oom"):
        found.append(
            f"used more than {_size(limits.memory_bytes)} of memory (the limit per "
            "notebook): a process was killed"
        )
    if used.get("processes_refused"):
        found.append(
            f"started more than {limits.processes} processes and threads (the limit per "
            f"notebook): {used['processes_refused']} refused"
        )
    return found


def full_disk(errors: Sequence[str], limits: Limits) -> list[str]:
    """The file limits a notebook's cell errors show it ran into, in words.

    >>> full_disk(["cell 3: OSError: [Errno 28] No space left on device"], Limits())
    ['wrote more than its disk space (/tmp 256 MiB, /dev/shm 64 MiB, working folder 256 MiB: the limit per notebook)']
    """
    found = []
    if any("No space left on device" in error for error in errors):
        found.append(
            f"wrote more than its disk space (/tmp {_size(limits.tmp_bytes)}, /dev/shm "
            f"{_size(limits.shm_bytes)}, working folder {_size(limits.workdir_bytes)}: "
            "the limit per notebook)"
        )
    if any("File too large" in error for error in errors):
        found.append(
            f"wrote a file larger than {_size(limits.file_bytes)} (the limit per file)"
        )
    return found
