"""The benchmark scripts run and print their tables (``--quick`` sizes; timings are not tested).

Speed is measured in ``benchmarks/`` (``make bench``), never asserted by a
unit test: a loaded machine would make such a test flaky.  What a test can
check is that every script still runs against the package and prints a
markdown table naming the machine.  These runs are not part of ``make test``
(pyproject.toml's ``testpaths`` leave ``tests/benchmarks`` out): ``make
bench-quick`` runs them, and CI runs it as its own step after ``make test``, so
a broken benchmark still fails CI without a contributor's test run waiting
for it.
"""

import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPTS = sorted((ROOT / "benchmarks").glob("bench_*.py"))
sys.path.insert(0, str(ROOT / "tools"))

import lab_browser  # noqa: E402

# bench_widgets drives JupyterLab in Chromium: a browser test, skipped without one
BROWSER_SCRIPTS = {"bench_widgets.py"}
BROWSER_MISSING = lab_browser.missing()


def _case(script):
    if script.name not in BROWSER_SCRIPTS:
        return script
    return pytest.param(
        script,
        marks=[
            pytest.mark.browser,
            pytest.mark.infrastructure,
            pytest.mark.skipif(bool(BROWSER_MISSING), reason=str(BROWSER_MISSING)),
        ],
    )


def test_every_benchmark_script_is_covered():
    names = {script.name for script in SCRIPTS}
    assert {
        "bench_single_call.py",
        "bench_kinematics.py",
        "bench_dynamics.py",
        "bench_ik_methods.py",
        "bench_import.py",
        "bench_widgets.py",
    } <= names


@pytest.mark.parametrize(
    "script", [_case(s) for s in SCRIPTS], ids=lambda path: path.name
)
def test_benchmark_runs_quick_and_prints_a_table(script):
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join(
            filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])
        ),
    )
    env.setdefault("MPLBACKEND", "Agg")
    done = subprocess.run(
        [sys.executable, str(script), "--quick"],
        capture_output=True,
        text=True,
        timeout=240,
        cwd=ROOT,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    lines = done.stdout.splitlines()
    assert lines and lines[0].startswith("# "), done.stdout[:500]
    header = next(index for index, line in enumerate(lines) if line.startswith("| "))
    assert set(lines[header + 1].replace("|", "").strip()) <= set("-: "), (
        "no markdown table rule under the header"
    )
    rows = [line for line in lines[header + 2 :] if line.startswith("| ")]
    assert rows, "the table has no rows"
    assert all(line.count("|") == lines[header].count("|") for line in rows), (
        "ragged table"
    )
    assert "nan" not in done.stdout.lower().replace("nanosec", ""), "a NaN in the table"


def test_peers_script_reports_missing_peers_clearly():
    """benchmarks/peers.py (make bench-peers) says what is missing instead of failing with a traceback."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "peers.py"), "--quick"],
        capture_output=True,
        text=True,
        timeout=240,
        cwd=ROOT,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    assert "| " in done.stdout
    assert "Traceback" not in done.stdout + done.stderr
