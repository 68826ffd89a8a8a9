"""A newcomer's first ``make lab``: from a fresh clone until the start page is served.

Clones the repository's committed state (``git clone`` of HEAD, or ``--rev``;
uncommitted changes are not included, and the script says so) into a
temporary folder, runs ``make lab LAB_ARGS="--no-browser --port N ..."`` there
on a free port, and measures the wall time from the start of ``make`` until
JupyterLab serves the start page (``/api/contents/00_start_here.ipynb``
answers 200 to the server's token).  Then it stops the server (the whole
process group) and removes the folder.

One row per installer: pip (with ``uv`` taken off the PATH), then uv when
``uv`` is on the PATH (the Makefile uses it when it finds it).  Columns: the
install (make's start until it starts JupyterLab: the venv, the packages, the
JupyterLab extension's link), the server start (until the start page is
served), the total, and the size of the new ``.venv``.  The header says
whether pip's and uv's caches were warm (their size before the run) and
which local wheel sources pip's configuration adds.

Every wait has a budget (``--budget`` seconds for the whole run, default 900);
exceeding it, ``make`` failing or the page missing stops the run with the end
of make's output.

Run with ``make bench-first-lab`` or ``.venv/bin/python
benchmarks/bench_first_lab.py`` (``--rev 62f40bd --page
01_dh_forward_kinematics.ipynb`` measures an older commit, before the start
page existed).  ``--quick`` (used by the test suite) installs nothing: the
clone's ``make lab`` uses this Python's environment (``VENV=``, its install
stamps taken as up to date), so only the clone, the server start and the
clean-up are exercised.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import platform
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from twolink_course.display import markdown_table  # noqa: E402

#: The issue's target for the first ``make lab`` on these machines, seconds.
TARGET_S = 60.0
START_PAGE = "00_start_here.ipynb"
#: The install stamps of the Makefile (the course's and the developers'; older
#: commits have only the second): ``--quick`` marks them up to date with ``-o``.
STAMPS = (".course-stamp", ".installed-stamp")


class BenchError(RuntimeError):
    """A run that did not reach the start page (with the reason and make's output)."""


def free_port() -> int:
    """A TCP port free on 127.0.0.1 now (the kernel's choice)."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def folder_size(path: Path) -> int:
    """Bytes of the regular files under ``path`` (symbolic links not followed)."""
    total = 0
    for folder, _, files in os.walk(path):
        for name in files:
            with contextlib.suppress(OSError):
                stat = os.lstat(os.path.join(folder, name))
                if not os.path.islink(os.path.join(folder, name)):
                    total += stat.st_size
    return total


def path_without(program: str) -> str:
    """This PATH without the folders that hold ``program``."""
    folders = os.environ.get("PATH", "").split(os.pathsep)
    return os.pathsep.join(
        folder
        for folder in folders
        if folder and not os.access(os.path.join(folder, program), os.X_OK)
    )


def cache_report() -> str:
    """pip's and uv's cache folders and sizes now (0 MB: cold), and pip's local wheel sources."""
    parts = []
    pip_cache = subprocess.run(
        [sys.executable, "-m", "pip", "cache", "dir"],
        capture_output=True,
        text=True,
        timeout=60,
    ).stdout.strip()
    if pip_cache:
        size = folder_size(Path(pip_cache)) / 1e6
        parts.append(
            f"pip cache {pip_cache}: {size:.0f} MB ({'warm' if size > 1 else 'cold'})"
        )
    config = subprocess.run(
        [sys.executable, "-m", "pip", "config", "list"],
        capture_output=True,
        text=True,
        timeout=60,
    ).stdout
    sources = [
        line.strip()
        for line in config.splitlines()
        if "find-links" in line or "index-url" in line
    ]
    if os.environ.get("PIP_FIND_LINKS"):
        sources.append(f"PIP_FIND_LINKS={os.environ['PIP_FIND_LINKS']}")
    if sources:
        parts.append("pip's local sources: " + "; ".join(sources))
    uv = shutil.which("uv")
    if uv:
        uv_cache = subprocess.run(
            [uv, "cache", "dir"], capture_output=True, text=True, timeout=60
        ).stdout.strip()
        if uv_cache:
            size = folder_size(Path(uv_cache)) / 1e6
            parts.append(
                f"uv cache {uv_cache}: {size:.0f} MB ({'warm' if size > 1 else 'cold'})"
            )
    return "; ".join(parts) or "no pip cache found"


def clone(rev: str, destination: Path) -> None:
    """``git clone`` of this repository into ``destination``, at ``rev``."""
    for command in (
        ["git", "clone", "--quiet", "--no-hardlinks", str(ROOT), str(destination)],
        ["git", "-C", str(destination), "checkout", "--quiet", rev],
    ):
        done = subprocess.run(command, capture_output=True, text=True, timeout=300)
        if done.returncode != 0:
            raise BenchError(f"{' '.join(command)} failed: {done.stderr[-2000:]}")


def page_status(port: int, token: str, page: str) -> int | None:
    """The HTTP status of the start page's contents request, None while the server does not answer."""
    request = urllib.request.Request(
        f"http://127.0.0.1:{port}/api/contents/{page}?content=0",
        headers={"Authorization": f"token {token}"},
    )
    try:
        with urllib.request.urlopen(request, timeout=5) as response:
            return int(response.status)
    except urllib.error.HTTPError as error:
        return int(error.code)
    except (urllib.error.URLError, ConnectionError, TimeoutError, OSError):
        return None


def stop(process: subprocess.Popen[str]) -> None:
    """Stop ``make`` and everything it started (its own process group), within 30 s."""
    if process.poll() is not None:
        return
    for sig, wait in ((signal.SIGTERM, 20.0), (signal.SIGKILL, 10.0)):
        with contextlib.suppress(ProcessLookupError):
            os.killpg(process.pid, sig)
        try:
            process.wait(timeout=wait)
            return
        except subprocess.TimeoutExpired:
            continue
    raise BenchError(f"make lab (process group {process.pid}) did not stop")


#: The steps of a first ``make lab``, each starting when make echoes a command
#: holding the marker (the venv's creation, silent, starts with make).
STEPS = (
    ("venv (and pip's upgrade)", None),
    ("packages", "-r requirements.txt -c constraints.txt"),
    ("bytecode (compileall)", "-m compileall"),
    ("JupyterLab extension link", "labextensions/twolink-figure-alt"),
    ("JupyterLab's start", "jupyter lab "),
)


def phases(lines: list[tuple[float, str]], total: float) -> dict[str, float]:
    """Seconds per step of ``STEPS`` found in make's timestamped output (until ``total``)."""
    starts = [(STEPS[0][0], 0.0)]
    for name, marker in STEPS[1:]:
        found = next((t for t, line in lines if marker in line), None)
        if found is not None:
            starts.append((name, found))
    ends = [t for _, t in starts[1:]] + [total]
    return {name: end - t for (name, t), end in zip(starts, ends)}


def first_lab(
    rev: str, page: str, installer: str, budget: float, quick: bool
) -> dict[str, object]:
    """One first ``make lab`` in a fresh clone: phase times (s), venv size (MB), the installer make reported."""
    env = {
        key: value
        for key, value in os.environ.items()
        if key not in ("VIRTUAL_ENV", "PYTHONPATH", "MAKEFLAGS", "MFLAGS")
    }
    if installer == "pip":
        env["PATH"] = path_without("uv")
    port, token = free_port(), secrets.token_hex(16)
    with tempfile.TemporaryDirectory(prefix="twolink-first-lab-") as tmp:
        source = Path(tmp) / "twolink"
        clone(rev, source)
        if not (source / "notebooks" / page).is_file():
            raise BenchError(
                f"notebooks/{page} is not in the clone of {rev!r} (not committed yet?)"
            )
        env["JUPYTER_RUNTIME_DIR"] = str(Path(tmp) / "runtime")
        lab_args = f"--no-browser --port {port} --IdentityProvider.token={token}"
        command = ["make", "--no-print-directory", "lab", f"LAB_ARGS={lab_args}"]
        if quick:
            venv = Path(sys.prefix)
            command += [f"VENV={venv}"] + [
                arg for stamp in STAMPS for arg in ("-o", str(venv / stamp))
            ]
        lines: list[tuple[float, str]] = []
        start = time.perf_counter()
        process = subprocess.Popen(
            command,
            cwd=source,
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,  # its own process group: stop() ends them all
        )

        def read() -> None:
            assert process.stdout is not None
            for line in process.stdout:
                lines.append((time.perf_counter() - start, line.rstrip()))

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        try:
            while True:
                elapsed = time.perf_counter() - start
                status = page_status(port, token, page)
                if status == 200:
                    total = time.perf_counter() - start
                    break
                if status is not None:
                    raise BenchError(f"the server answers {status} for {page}")
                if process.poll() is not None:
                    raise BenchError(f"make lab exited with {process.returncode}")
                if elapsed > budget:
                    raise BenchError(
                        f"the start page was not served within the budget of {budget:.0f} s"
                    )
                time.sleep(0.2)
        except BenchError as error:
            stop(process)
            reader.join(timeout=10)
            tail = "\n".join(line for _, line in lines[-40:])
            raise BenchError(
                f"{installer}: {error}\nmake's output ended:\n{tail}"
            ) from None
        stop(process)
        reader.join(timeout=10)
        steps = phases(lines, total)
        install = total - steps.get("JupyterLab's start", 0.0)
        said = next(
            (
                line
                for _, line in lines
                if line.startswith("make: installing the course")
            ),
            "",
        )
        venv_mb = 0.0 if quick else folder_size(source / ".venv") / 1e6
    return {
        "installer": installer if not quick else "none (--quick: this venv)",
        "install": install,
        "server": total - install,
        "total": total,
        "venv": venv_mb,
        "said": said,
        "steps": steps,
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rev", default="HEAD", help="the commit to clone (HEAD)")
    parser.add_argument(
        "--page",
        default=START_PAGE,
        help=f"the notebook whose serving ends the run ({START_PAGE})",
    )
    parser.add_argument(
        "--installer",
        choices=("all", "pip", "uv"),
        default="all",
        help="pip, uv, or all: pip, then uv if it is on the PATH (all)",
    )
    parser.add_argument(
        "--budget", type=float, default=900.0, help="seconds allowed per run (900)"
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="no install: this environment's venv; only the clone and the server start",
    )
    args = parser.parse_args()
    if args.quick:
        args.budget = min(args.budget, 180.0)
    rev = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--short", args.rev],
        capture_output=True,
        text=True,
        timeout=60,
    ).stdout.strip()
    if not rev:
        sys.exit(f"bench_first_lab: {args.rev!r} is not a commit of {ROOT}")
    dirty = subprocess.run(
        ["git", "-C", str(ROOT), "status", "--porcelain", "--untracked-files=no"],
        capture_output=True,
        text=True,
        timeout=60,
    ).stdout.strip()
    installers = (
        ["pip"]
        if args.quick
        else [args.installer]
        if args.installer != "all"
        else ["pip"] + (["uv"] if shutil.which("uv") else [])
    )
    if "uv" in installers and not shutil.which("uv"):
        sys.exit("bench_first_lab: --installer uv, but uv is not on the PATH")
    print(
        f"# First `make lab` of a fresh clone of {rev} until the start page {args.page} is served "
        f"({platform.machine()}, {os.cpu_count()} CPUs, Python {platform.python_version()}; "
        f"load average {os.getloadavg()[0]:.1f}; target {TARGET_S:.0f} s)\n"
    )
    if dirty and args.rev == "HEAD":
        print(
            "Uncommitted changes in the working tree are not included (git clone of HEAD).\n"
        )
    print(f"Caches before the runs: {cache_report()}.\n")
    rows, notes, all_steps = [], [], []
    for installer in installers:
        try:
            result = first_lab(rev, args.page, installer, args.budget, args.quick)
        except BenchError as error:
            sys.exit(f"bench_first_lab: {error}")
        rows.append(
            [
                result["installer"],
                result["install"],
                result["server"],
                result["total"],
                "-" if args.quick else f"{result['venv']:.0f}",
                "yes" if float(result["total"]) <= TARGET_S else "no",  # type: ignore[arg-type]
            ]
        )
        all_steps.append(result["steps"])
        if result["said"]:
            notes.append(f"{installer}: {result['said']}")
    print(
        markdown_table(
            [
                "installer",
                "install (s)",
                "server (s)",
                "total (s)",
                ".venv (MB)",
                "within target",
            ],
            rows,
            ["", ".1f", ".1f", ".1f", "", ""],
        )
    )
    if not args.quick:
        names = [name for name, _ in STEPS]
        print(
            "\nWhere the time goes (s, from the moments make echoes its commands; "
            "-: no such step):\n"
        )
        print(
            markdown_table(
                ["installer", *names],
                [
                    [
                        row[0],
                        *(
                            f"{steps[name]:.1f}" if name in steps else "-"
                            for name in names
                        ),
                    ]
                    for row, steps in zip(rows, all_steps)
                ],
            )
        )
    if notes:
        print("\n" + "\n".join(notes))


if __name__ == "__main__":
    main()
