"""How long ``import twolink`` takes, in fresh processes, and what it loads.

A student's first cell imports numpy and twolink; ``import twolink`` should
add little to numpy's own import.  The package loads no scipy, sympy,
matplotlib, control or mujoco when it is imported: each module imports
scipy inside the function that needs it, so the first ``ik.minimize``,
``simulate`` or ``JointReference.from_samples`` call pays for it instead
(the rows marked "(info)" show what that first call adds).

Each row is the median over fresh Python processes (the interpreter's own
start-up is not counted: each process times its imports with
``time.perf_counter``).  The import chains run in turn, so that all of them
see the same load on a shared machine.

Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_import.py``
(``--quick`` for a smoke run with 2 processes per row, used by the test suite).
"""

import argparse
import json
import platform
import statistics
import subprocess
import sys

import numpy as np

from twolink_course.display import markdown_table

# The target of the light-import issue: import twolink after numpy, median of fresh processes.
TARGET_MS = 100.0
HEAVY = ("scipy", "sympy", "matplotlib", "control", "mujoco")

# Runs in a fresh process: imports the modules named on the command line one after the other and
# prints, for each, the seconds it took, how many modules it added to sys.modules and the heavy ones among them.
_CHILD = """
import json, sys, time
heavy = {heavy!r}
steps = []
for name in sys.argv[1:]:
    before = set(sys.modules)
    start = time.perf_counter()
    __import__(name)
    seconds = time.perf_counter() - start
    added = set(sys.modules) - before
    steps.append([seconds, len(added), sorted({{m.split(".")[0] for m in added}} & set(heavy))])
print(json.dumps(steps))
"""

# (row label, import chain, target in ms or None for information); the measured module is the chain's last.
CHAINS = [
    ("numpy (alone)", ["numpy"], None),
    ("twolink, after numpy", ["numpy", "twolink"], TARGET_MS),
    (
        "scipy.optimize, after twolink (first ik.minimize, workspace.largest_inscribed_circle)",
        ["numpy", "twolink", "scipy.optimize"],
        None,
    ),
    (
        "scipy.integrate, after twolink (first simulate, resolved_rate_trajectory)",
        ["numpy", "twolink", "scipy.integrate"],
        None,
    ),
    (
        "scipy.interpolate, after twolink (first JointReference.from_samples)",
        ["numpy", "twolink", "scipy.interpolate"],
        None,
    ),
]


def run_chain(modules):
    """One fresh process importing ``modules`` in turn: ``[seconds, modules added, heavy added]`` per step."""
    done = subprocess.run(
        [sys.executable, "-c", _CHILD.format(heavy=HEAVY), *modules],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    if done.returncode != 0:
        raise RuntimeError(
            f"importing {' then '.join(modules)} failed:\n{done.stderr[-2000:]}"
        )
    return json.loads(done.stdout)


def measure(processes):
    """Per chain: the list of its last step over ``processes`` fresh processes, the chains taken in turn."""
    samples = {label: [] for label, _, _ in CHAINS}
    for _ in range(processes):
        for label, modules, _ in CHAINS:
            samples[label].append(run_chain(modules)[-1])
    return samples


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="2 processes per row: checks the script runs, not the speed",
    )
    parser.add_argument(
        "--processes", type=int, default=15, help="fresh processes per row (default 15)"
    )
    args = parser.parse_args(argv)
    processes = 2 if args.quick else args.processes
    samples = measure(processes)

    print(
        f"# import twolink, median of {processes} fresh processes ({platform.machine()}, "
        f"{platform.python_implementation()} {platform.python_version()}, numpy {np.__version__})\n"
    )
    table = []
    met = True
    for label, _, target in CHAINS:
        steps = samples[label]
        milliseconds = 1e3 * statistics.median(step[0] for step in steps)
        added = int(statistics.median(step[1] for step in steps))
        heavy = sorted({name for step in steps for name in step[2]})
        # a row with a target meets it in time and without loading a heavy module
        meets = (
            "-"
            if target is None
            else "yes"
            if milliseconds <= target and not heavy
            else "NO"
        )
        met = met and meets != "NO"
        table.append(
            (
                label,
                f"{milliseconds:.1f}",
                str(added),
                ", ".join(heavy) or "none",
                "(info)" if target is None else f"<= {target:g} ms",
                meets,
            )
        )
    print(
        markdown_table(
            [
                "import",
                "median [ms]",
                "modules added",
                f"heavy modules added ({', '.join(HEAVY)})",
                "target",
                "meets",
            ],
            table,
        )
    )
    return met or args.quick


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
