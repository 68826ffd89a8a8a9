"""Fixtures for the browser suite: a private JupyterLab server and a headless Chromium.

The suite needs Debian's Chromium at /usr/bin/chromium (``apt-get install -y
chromium``) and the ``playwright`` Python package; it never downloads a
browser.  Without them every browser test is skipped with the reason.  Server
and browser are always shut down, even when a test fails; the server's process
group and its kernels (which jupyter_client starts in sessions of their own)
are also killed when pytest is interrupted (SIGINT), terminated (SIGTERM) or
exits without running the fixture's teardown.
"""

import atexit
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
import urllib.request

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
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
SCREENSHOTS = ROOT / "build" / "screenshots"
#: JupyterLab user settings for the test server: render every cell (no
#: virtual scrolling, so all outputs are in the page) and no news pop-ups.
LAB_SETTINGS = {
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {
        "windowingMode": "none"
    },
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {
        "fetchNews": "false",
        "checkForUpdates": False,
    },
}


def pytest_collection_modifyitems(config, items):
    reason = None
    if not os.path.exists(CHROMIUM):
        reason = f"Chromium not found at {CHROMIUM} (apt-get install -y chromium)"
    else:
        try:
            import playwright  # noqa: F401
        except ImportError:
            reason = "the playwright package is not installed (pip install playwright)"
    for item in items:
        if "browser" in item.keywords and reason:
            item.add_marker(pytest.mark.skip(reason=reason))


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
            alive = [group for group in groups if self._group_alive(group)]
            if not alive:
                break
            groups = set(alive)
            time.sleep(0.5)
        if process in self.processes:
            self.processes.remove(process)

    @staticmethod
    def _group_alive(group):
        try:
            os.killpg(group, 0)
        except (ProcessLookupError, PermissionError):
            return False
        return True

    def stop_all(self):
        for process in list(self.processes):
            self.stop(process, timeout=5.0)


PROCESS_GROUPS = ProcessGroups()


def free_port():
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


@pytest.fixture(scope="session")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        chromium = playwright.chromium.launch(
            executable_path=CHROMIUM, args=CHROMIUM_ARGS, headless=True
        )
        try:
            yield chromium
        finally:
            chromium.close()


@pytest.fixture()
def page(browser):
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    try:
        yield page
    finally:
        context.close()


@pytest.fixture(scope="session")
def jupyterlab(tmp_path_factory):
    """A JupyterLab server on 127.0.0.1 serving a copy of the notebooks; yields its base URL and token."""
    home = tmp_path_factory.mktemp("jupyterlab")
    notebooks = home / "notebooks"
    shutil.copytree(ROOT / "notebooks", notebooks)
    token = secrets.token_hex(16)
    port = free_port()
    env = dict(os.environ)
    env.pop("MPLBACKEND", None)
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
    log = open(home / "server.log", "w")
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
                    f"JupyterLab exited with {server.returncode}: {(home / 'server.log').read_text()[-2000:]}"
                )
            try:
                urllib.request.urlopen(
                    f"{base_url}/api/status?token={token}", timeout=2
                )
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise RuntimeError(
                        "JupyterLab did not answer within 60 s"
                    ) from None
                time.sleep(0.5)
        yield {"url": base_url, "token": token, "notebooks": notebooks}
    finally:
        PROCESS_GROUPS.stop(server)
        log.close()
