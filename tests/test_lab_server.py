"""The course's Jupyter server extension: kernel websockets without Nagle's delay.

``tools/lab_server/twolink_nodelay.py`` is loaded by ``make lab``, the browser
suite and ``benchmarks/bench_widgets.py``.  Its speed is measured by the
benchmark, not here; these tests check that it does what it says and is
loaded where it should be.
"""

import asyncio
import json
import pathlib
import subprocess
import sys
import tempfile
import urllib.request

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
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
        ["make", "-n", "lab", "STAMP=Makefile"],
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
