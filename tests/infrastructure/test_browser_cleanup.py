"""The browser suite leaves no JupyterLab server or kernel behind when pytest is killed, interrupted or exits.

A stand-in for the server (a process that starts a "kernel" in a session of
its own, as jupyter_client does) is started through the suite's
``PROCESS_GROUPS``; the process that started it is then sent SIGTERM or
SIGINT, or exits without any teardown.  Both stand-ins must be gone.
"""

import os
import pathlib
import signal
import subprocess
import sys
import textwrap
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]

RUNNER = textwrap.dedent(f"""
    import importlib.util, subprocess, sys, time
    spec = importlib.util.spec_from_file_location("browser_conftest", {str(ROOT / "tests" / "browser" / "conftest.py")!r})
    suite = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(suite)
    fake_server = (
        "import subprocess, sys, time\\n"
        "kernel = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(600)'], start_new_session=True)\\n"
        "print(kernel.pid, flush=True)\\n"
        "time.sleep(600)\\n"
    )
    server = suite.PROCESS_GROUPS.start(
        [sys.executable, "-c", fake_server], stdout=subprocess.PIPE, text=True
    )
    kernel = int(server.stdout.readline())  # the kernel runs
    print(server.pid, flush=True)
    print(kernel, flush=True)
    if sys.argv[1] == "exit":
        sys.exit(0)
    time.sleep(600)
""")


def alive(pid):
    try:
        state = (
            pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        )
    except (OSError, IndexError):
        return False
    return state != "Z"


@pytest.mark.infrastructure
@pytest.mark.skipif(not pathlib.Path("/proc").is_dir(), reason="needs /proc (Linux)")
@pytest.mark.parametrize("how", ["SIGTERM", "SIGINT", "exit"])
def test_server_and_kernel_are_gone_after(how):
    runner = subprocess.Popen(
        [sys.executable, "-c", RUNNER, how],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        pids = [int(runner.stdout.readline()), int(runner.stdout.readline())]
        assert all(alive(pid) for pid in pids)
        if how != "exit":
            runner.send_signal(getattr(signal, how))
        runner.wait(timeout=30)
        deadline = time.monotonic() + 10
        while any(alive(pid) for pid in pids) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not [pid for pid in pids if alive(pid)], (
            f"left running after {how}: {pids}"
        )
    finally:
        runner.kill()
        for pid in pids if "pids" in locals() else []:
            if alive(pid):
                os.kill(pid, signal.SIGKILL)


class _KernelsAPI:
    """A stand-in for the server's /api/kernels: ``errors`` 500s to the list first, then two kernels."""

    def __init__(self, errors):
        import http.server
        import threading

        api = self
        self.errors, self.deleted = errors, []

        class Handler(http.server.BaseHTTPRequestHandler):
            def log_message(self, *args):
                pass

            def do_GET(self):
                if api.errors:
                    api.errors -= 1
                    self.send_error(500)
                    return
                body = b'[{"id": "a"}, {"id": "b"}]'
                self.send_response(200)
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def do_DELETE(self):
                kernel = self.path.rsplit("/", 1)[-1]
                api.deleted.append(kernel)
                self.send_response(
                    404 if kernel == "b" else 204
                )  # b: stopped meanwhile
                self.send_header("Content-Length", "0")
                self.end_headers()

        self.server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        # a short poll, so that shutdown() returns at once
        threading.Thread(
            target=self.server.serve_forever,
            kwargs={"poll_interval": 0.05},
            daemon=True,
        ).start()
        self.lab = {"url": f"http://127.0.0.1:{self.server.server_port}", "token": "t"}


def test_shutting_down_kernels_outlasts_a_server_error_and_a_kernel_gone_meanwhile():
    sys.path.insert(0, str(ROOT / "tools"))
    import lab_browser

    api = _KernelsAPI(errors=2)
    try:
        lab_browser.shut_down_kernels(api.lab, budget=10.0, retry_every=0.05)
        assert api.deleted == ["a", "b"] and api.errors == 0
    finally:
        api.server.shutdown()


def test_shutting_down_kernels_gives_up_with_a_clear_error_after_its_budget():
    sys.path.insert(0, str(ROOT / "tools"))
    import lab_browser

    api = _KernelsAPI(errors=10**6)
    try:
        with pytest.raises(
            RuntimeError, match="answered 500 to stopping its kernels for 0.2 s"
        ):
            lab_browser.shut_down_kernels(api.lab, budget=0.2, retry_every=0.05)
        assert api.deleted == []
    finally:
        api.server.shutdown()
