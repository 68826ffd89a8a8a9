"""A private JupyterLab server and a headless Chromium, for the browser suite and
``benchmarks/bench_widgets.py``.

Debian's Chromium (``/usr/bin/chromium``, or ``TWOLINK_CHROMIUM``) and the
``playwright`` package; no browser is ever downloaded.  The server runs in its
own process group with its own settings folders, and is always stopped with
its kernels (which jupyter_client starts in sessions of their own), also when
the process is interrupted (SIGINT), terminated (SIGTERM) or exits.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import os
import pathlib
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from typing import Any

ROOT = pathlib.Path(__file__).resolve().parents[1]
#: The course's server extension (tools/lab_server/twolink_nodelay.py): kernel
#: messages reach the browser without Nagle's delay, as in ``make lab``.
SERVER_EXTENSION_PATH = ROOT / "tools" / "lab_server"
SERVER_EXTENSION_ARGS = ["--ServerApp.jpserver_extensions=twolink_nodelay=True"]
CHROMIUM = os.environ.get("TWOLINK_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--autoplay-policy=no-user-gesture-required",
]
#: JupyterLab user settings for the server: render every cell (no virtual
#: scrolling, so all outputs are in the page) and no news pop-ups.
LAB_SETTINGS = {
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {
        "windowingMode": "none"
    },
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {
        "fetchNews": "false",
        "checkForUpdates": False,
    },
}


def missing() -> str | None:
    """Why a browser cannot run here (``None`` when it can)."""
    if not os.path.exists(CHROMIUM):
        return f"Chromium not found at {CHROMIUM} (apt-get install -y chromium)"
    try:
        import playwright  # noqa: F401
    except ImportError:
        return "the playwright package is not installed (pip install playwright)"
    return None


class ProcessGroups:
    """Processes started in their own session, killed with all their descendants' groups.

    ``stop_all`` runs at exit and on SIGTERM / SIGINT (then the previous
    handler runs: pytest's KeyboardInterrupt, or the default termination).
    """

    def __init__(self):
        self.processes = []
        self.previous = {}

    def start(self, command, **popen_options):
        process = subprocess.Popen(command, start_new_session=True, **popen_options)
        self.processes.append(process)
        self._install()
        return process

    def _install(self):
        if self.previous:
            return
        atexit.register(self.stop_all)
        for signum in (signal.SIGTERM, signal.SIGINT):
            try:
                self.previous[signum] = signal.signal(signum, self._on_signal)
            except (
                ValueError
            ):  # not the main thread: atexit and the fixture's teardown remain
                pass

    def _on_signal(self, signum, frame):
        self.stop_all()
        previous = self.previous.get(signum, signal.SIG_DFL)
        if callable(previous):
            previous(signum, frame)
        elif previous != signal.SIG_IGN:
            signal.signal(signum, signal.SIG_DFL)
            os.kill(os.getpid(), signum)

    @staticmethod
    def _descendants(pid):
        children = {}
        for stat in pathlib.Path("/proc").glob("[0-9]*/stat"):
            try:
                fields = stat.read_text().rsplit(")", 1)[1].split()
            except (OSError, IndexError):
                continue
            children.setdefault(int(fields[1]), []).append(int(stat.parent.name))
        found, todo = [], [pid]
        while todo:
            for child in children.get(todo.pop(), []):
                found.append(child)
                todo.append(child)
        return found

    #: After the process has exited, how long its descendants' groups have to follow
    #: a signal before the next one, seconds.
    GRACE = 0.5

    def stop(self, process, timeout=20.0):
        """SIGTERM the process's group and its descendants' groups, SIGKILL what is left after ``timeout``."""
        groups = {process.pid}
        for pid in self._descendants(process.pid):
            try:
                groups.add(os.getpgid(pid))
            except ProcessLookupError:
                pass
        for sig in (signal.SIGTERM, signal.SIGKILL):
            for group in groups:
                try:
                    os.killpg(group, sig)
                except (ProcessLookupError, PermissionError):
                    pass
            try:
                process.wait(timeout=timeout if sig == signal.SIGTERM else 5.0)
            except subprocess.TimeoutExpired:
                continue
            deadline = time.monotonic() + self.GRACE
            while True:
                alive = [group for group in groups if self._group_alive(group)]
                if not alive or time.monotonic() > deadline:
                    break
                time.sleep(0.02)
            if not alive:
                break
            groups = set(alive)
        if process in self.processes:
            self.processes.remove(process)

    @staticmethod
    def _group_alive(group):
        """Whether a process of the group still runs (a zombie, dead but not yet reaped, does not)."""
        for stat in pathlib.Path("/proc").glob("[0-9]*/stat"):
            try:
                fields = stat.read_text().rsplit(")", 1)[1].split()
            except (OSError, IndexError):
                continue
            if int(fields[2]) == group and fields[0] != "Z":
                return True
        return False

    def stop_all(self):
        for process in list(self.processes):
            self.stop(process, timeout=5.0)


PROCESS_GROUPS = ProcessGroups()


def free_port():
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@contextlib.contextmanager
def chromium() -> Iterator[Any]:
    """A headless Chromium (playwright's ``Browser``), closed at the end.

    ``TWOLINK_BROWSER_HEADED=1`` opens a window instead (on a display: under
    ``xvfb-run`` on a machine without one), as a student's browser draws.
    """
    from playwright.sync_api import sync_playwright

    headed = os.environ.get("TWOLINK_BROWSER_HEADED") == "1"
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(
            executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=not headed
        )
        try:
            yield browser
        finally:
            browser.close()


@contextlib.contextmanager
def jupyterlab(home: pathlib.Path, *, nodelay: bool = True) -> Iterator[dict[str, Any]]:
    """A JupyterLab server on 127.0.0.1 serving a copy of the notebooks in ``home``.

    Yields ``{"url", "token", "notebooks"}``; the server (and its kernels) stop
    at the end.  ``nodelay``: load the course's server extension, as ``make
    lab`` does (``False``: a stock server, for comparison).
    """
    notebooks = home / "notebooks"
    shutil.copytree(ROOT / "notebooks", notebooks)
    token = secrets.token_hex(16)
    port = free_port()
    env = dict(os.environ)
    env.pop("MPLBACKEND", None)
    if nodelay:
        env["PYTHONPATH"] = os.pathsep.join(
            [str(SERVER_EXTENSION_PATH), *filter(None, [env.get("PYTHONPATH")])]
        )
    for name in (
        "JUPYTER_CONFIG_DIR",
        "JUPYTER_RUNTIME_DIR",
        "JUPYTERLAB_SETTINGS_DIR",
        "JUPYTERLAB_WORKSPACES_DIR",
    ):
        env[name] = str(home / name.lower())
    for name, values in LAB_SETTINGS.items():
        settings_file = pathlib.Path(env["JUPYTERLAB_SETTINGS_DIR"]) / name
        settings_file.parent.mkdir(parents=True, exist_ok=True)
        settings_file.write_text(json.dumps(values))
    with open(home / "server.log", "w") as log:
        server = PROCESS_GROUPS.start(
            [
                sys.executable,
                "-m",
                "jupyterlab",
                "--no-browser",
                "--allow-root",
                "--ServerApp.ip=127.0.0.1",
                f"--ServerApp.port={port}",
                "--ServerApp.port_retries=0",
                f"--IdentityProvider.token={token}",
                f"--ServerApp.root_dir={notebooks}",
                "--LabApp.news_url=",
                "--LabApp.check_for_updates_class=jupyterlab.NeverCheckForUpdate",
                *(SERVER_EXTENSION_ARGS if nodelay else []),
            ],
            env=env,
            stdout=log,
            stderr=subprocess.STDOUT,
        )
        base_url = f"http://127.0.0.1:{port}"
        try:
            deadline = time.monotonic() + 60
            while True:
                if server.poll() is not None:
                    raise RuntimeError(
                        f"JupyterLab exited with {server.returncode}: "
                        f"{(home / 'server.log').read_text()[-2000:]}"
                    )
                try:
                    urllib.request.urlopen(
                        f"{base_url}/api/status?token={token}", timeout=2
                    ).close()
                    break
                except OSError:
                    if time.monotonic() > deadline:
                        raise RuntimeError(
                            "JupyterLab did not answer within 60 s"
                        ) from None
                    time.sleep(0.1)
            yield {"url": base_url, "token": token, "notebooks": notebooks}
        finally:
            PROCESS_GROUPS.stop(server)


def shut_down_kernels(
    lab: dict[str, Any], budget: float = 30.0, retry_every: float = 0.5
) -> None:
    """Stop every kernel the server runs, so chapters do not pile up kernels.

    A kernel that the page is starting or stopping at that moment can make the
    server answer 500 to the list, or 404 to a kernel gone meanwhile: the list
    is asked again every ``retry_every`` seconds until ``budget`` seconds have
    passed, and a kernel already gone counts as stopped.
    """
    base = f"{lab['url']}/api/kernels"
    headers = {"Authorization": f"token {lab['token']}"}
    deadline = time.monotonic() + budget
    while True:
        try:
            request = urllib.request.Request(base, headers=headers)
            with urllib.request.urlopen(request, timeout=10) as response:
                kernels = json.load(response)
            for kernel in kernels:
                request = urllib.request.Request(
                    f"{base}/{kernel['id']}", headers=headers, method="DELETE"
                )
                try:
                    urllib.request.urlopen(request, timeout=10).close()
                except urllib.error.HTTPError as error:
                    if error.code != 404:  # 404: stopped meanwhile
                        raise
            return
        except urllib.error.HTTPError as error:
            if error.code < 500 or time.monotonic() > deadline:
                raise RuntimeError(
                    f"JupyterLab answered {error.code} to stopping its kernels "
                    f"for {budget:g} s ({error.reason})"
                ) from error
            time.sleep(retry_every)
