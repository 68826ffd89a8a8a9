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

ROOT = pathlib.Path(__file__).resolve().parents[1]

RUNNER = textwrap.dedent(f"""
    import importlib.util, sys, time
    spec = importlib.util.spec_from_file_location("browser_conftest", {str(ROOT / "tests" / "browser" / "conftest.py")!r})
    suite = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(suite)
    fake_server = (
        "import subprocess, sys, time\\n"
        "kernel = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(600)'], start_new_session=True)\\n"
        "print(kernel.pid, flush=True)\\n"
        "time.sleep(600)\\n"
    )
    server = suite.PROCESS_GROUPS.start([sys.executable, "-c", fake_server])
    print(server.pid, flush=True)
    if sys.argv[1] == "exit":
        time.sleep(1.0)
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
