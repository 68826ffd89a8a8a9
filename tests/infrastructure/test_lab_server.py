"""The course's Jupyter server: kernel websockets without Nagle's delay, and ``make lab`` itself.

``tools/lab_server/twolink_nodelay.py`` is loaded by ``make lab``, the browser
suite and ``benchmarks/bench_widgets.py``.  Its speed is measured by the
benchmark, not here; these tests check that it does what it says and is
loaded where it should be.  The last test runs ``make lab`` (in this
environment, nothing installed) and checks that it sends the browser to the
start page.
"""

import asyncio
import http.client
import json
import os
import pathlib
import secrets
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT / "tools" / "lab_server"))

import lab_browser  # noqa: E402
import twolink_nodelay  # noqa: E402
from _cases import in_fresh_thread  # noqa: E402
from jupyter_server.services.kernels.websocket import (  # noqa: E402
    KernelWebsocketHandler,
)


class _Log:
    def __init__(self):
        self.lines = []

    def info(self, line):
        self.lines.append(line)


class _App:
    def __init__(self):
        self.log = _Log()


def test_open_turns_nagle_off_before_the_handler_runs():
    calls = []

    class Handler:
        def set_nodelay(self, value):
            calls.append(("set_nodelay", value))

        async def open(self, kernel_id):
            calls.append(("open", kernel_id))
            return "opened"

    Handler.open = twolink_nodelay.nodelay_open(Handler.open)
    assert in_fresh_thread(asyncio.run, Handler().open("k1")) == "opened"
    assert calls == [("set_nodelay", True), ("open", "k1")]


def test_loading_twice_wraps_the_kernel_handler_once(monkeypatch):
    original = KernelWebsocketHandler.open
    monkeypatch.setattr(KernelWebsocketHandler, "open", original)
    app = _App()
    twolink_nodelay._load_jupyter_server_extension(app)
    once = KernelWebsocketHandler.open
    twolink_nodelay._load_jupyter_server_extension(app)
    assert KernelWebsocketHandler.open is once
    assert once.__wrapped__ is original
    assert any("twolink_nodelay" in line for line in app.log.lines)


def test_make_lab_loads_the_extension():
    done = subprocess.run(
        # the course's install stamp taken as up to date: the dry run shows make lab's own command
        ["make", "-n", "lab", "-o", ".venv/.course-stamp"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        check=True,
    )
    command = done.stdout
    assert "tools/lab_server" in command and "PYTHONPATH=" in command
    assert lab_browser.SERVER_EXTENSION_ARGS[0] in command


@pytest.mark.infrastructure
def test_the_course_server_loads_it_and_runs_a_kernel():
    with tempfile.TemporaryDirectory() as home:
        with lab_browser.jupyterlab(pathlib.Path(home)) as lab:
            headers = {"Authorization": f"token {lab['token']}"}
            request = urllib.request.Request(
                f"{lab['url']}/api/kernels", data=b"{}", headers=headers, method="POST"
            )
            with urllib.request.urlopen(request, timeout=60) as response:
                kernel = json.load(response)
            assert kernel["id"]
            lab_browser.shut_down_kernels(lab)
        log = (pathlib.Path(home) / "server.log").read_text()
    assert "twolink_nodelay: kernel websockets send without Nagle's delay" in log


START_PAGE = "00_start_here.ipynb"


@pytest.mark.infrastructure
def test_make_lab_sends_the_browser_to_the_start_page(tmp_path):
    """``make lab`` (this venv, its install stamps taken as up to date) redirects ``/`` to
    ``/lab/tree/00_start_here.ipynb``, the URL it opens, and serves that notebook.  (That
    JupyterLab 4 then opens the notebook instead of the Launcher was checked in Chromium.)"""
    venv = pathlib.Path(sys.prefix)
    port, token = lab_browser.free_port(), secrets.token_hex(16)
    env = {**os.environ, "JUPYTER_RUNTIME_DIR": str(tmp_path / "runtime")}
    env.pop("PYTHONPATH", None)
    log = tmp_path / "make-lab.log"
    with open(log, "w") as out:
        server = subprocess.Popen(
            [
                "make",
                "--no-print-directory",
                "lab",
                f"VENV={venv}",
                f"WORK={tmp_path / 'work'}",  # the learner's copies, out of the checkout
                *("-o", f"{venv}/.course-stamp", "-o", f"{venv}/.installed-stamp"),
                f"LAB_ARGS=--no-browser --port {port} --IdentityProvider.token={token}",
            ],
            cwd=ROOT,
            env=env,
            stdout=out,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    try:
        deadline = time.monotonic() + 90
        while True:
            assert server.poll() is None, f"make lab exited: {log.read_text()[-3000:]}"
            try:
                connection = http.client.HTTPConnection("127.0.0.1", port, timeout=5)
                connection.request("GET", f"/?token={token}")
                response = connection.getresponse()
                break
            except OSError:
                assert time.monotonic() < deadline, (
                    f"no answer within 90 s: {log.read_text()[-3000:]}"
                )
                time.sleep(0.3)
        assert response.status == 302, response.status
        assert response.getheader("Location", "").startswith(
            f"/lab/tree/{START_PAGE}?"
        ), response.getheader("Location")
        request = urllib.request.Request(
            f"http://127.0.0.1:{port}/api/contents/{START_PAGE}?content=0",
            headers={"Authorization": f"token {token}"},
        )
        with urllib.request.urlopen(request, timeout=30) as contents:
            assert json.load(contents)["type"] == "notebook"
    finally:
        os.killpg(server.pid, signal.SIGTERM)
        try:
            server.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)
            server.wait(timeout=10)
    assert f"/lab/tree/{START_PAGE}" in log.read_text()
