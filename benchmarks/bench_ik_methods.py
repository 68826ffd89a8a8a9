"""The IK methods compared on the source's circle: time per target and error (chapter 7).

The source exercise (COURSE.md B, timing) solves IK at every point of a
circle with each method and asks which can run in real time.  This script
answers it for the a1 = a2 = 10 arm and the circle centred (12.5, 12.5) with
radius 2, at 20 points: every method per call (one target per call, what a
controller does each cycle) and vectorised (all targets in one call), brute
force at four grid resolutions, all timed with :func:`twolink_course.timing.median_time`
(median of timeit repeats).  When ``roboticstoolbox-python`` is importable
(an optional extra, never a requirement of the course) the same targets are
also solved with its ``ik_LM``.

Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_ik_methods.py``
(``--quick`` for a smoke run with tiny sizes, used by the test suite: it
checks that the script runs, not the speed).
"""

import argparse
import platform

import numpy as np

from twolink import arms, workspace
from twolink_course import timing
from twolink_course.display import markdown_table

#: The control rate the real-time question is asked against.
CONTROL_RATE_HZ = 1000.0
#: ... and the accuracy a real-time answer must have, metres.
ACCURACY_M = 1e-3
CIRCLE_CENTRE, CIRCLE_RADIUS, CIRCLE_POINTS = (12.5, 12.5), 2.0, 20
Q0 = (0.5, 1.0)
BRUTE_FORCE_STEPS_DEG = (1.0, 0.5, 0.25, 0.1)


def twolink_rows(arm, targets, steps_deg=BRUTE_FORCE_STEPS_DEG, repeat=3):
    rows = []
    for per_call in (True, False):
        mode = "per call" if per_call else "vectorised"
        methods = [name for name in timing.IK_METHODS if name != "brute force"]
        for row in timing.compare_ik_methods(
            arm, targets, q0=Q0, methods=methods, repeat=repeat, per_call=per_call
        ):
            rows.append(
                (
                    row["method"],
                    mode,
                    row["seconds_per_target"],
                    row["max_residual"],
                    row["solved"],
                )
            )
        for step_deg in steps_deg:
            (row,) = timing.compare_ik_methods(
                arm,
                targets,
                step=np.radians(step_deg),
                methods=["brute force"],
                repeat=repeat,
                per_call=per_call,
            )
            rows.append(
                (
                    f"brute force, {step_deg:g} deg grid",
                    mode,
                    row["seconds_per_target"],
                    row["max_residual"],
                    row["solved"],
                )
            )
    return rows


def robotics_toolbox_rows(arm, targets, repeat=3):
    """``ik_LM`` of the Robotics Toolbox on the same targets, or no rows if it is not installed."""
    try:
        import roboticstoolbox as rtb
    except ImportError:
        return (
            [],
            "roboticstoolbox-python is not installed: no ik_LM row (optional extra)",
        )
    robot = rtb.DHRobot(
        [rtb.RevoluteDH(a=arm.l1), rtb.RevoluteDH(a=arm.l2)], name="two-link"
    )
    ets = (
        robot.ets()
    )  # built once: robot.ik_LM rebuilds it on every call (~20x the C++ solve)
    poses = []
    for x, y in targets:
        pose = np.eye(4)
        pose[:2, 3] = (x, y)
        poses.append(pose)
    mask = np.array(
        [1.0, 1.0, 0.0, 0.0, 0.0, 0.0]
    )  # position only: a planar arm cannot choose its orientation
    rows = []
    for label, tol in (("default tol 1e-6", 1e-6), ("tol 1e-20", 1e-20)):

        def solve_all(tol=tol):
            return [
                ets.ik_LM(pose, q0=np.array(Q0), mask=mask, tol=tol) for pose in poses
            ]

        solutions = solve_all()
        q = np.array([solution[0] for solution in solutions])
        residual = np.hypot(*(arm.fk(q) - targets).T)
        seconds = timing.median_time(solve_all, repeat=repeat) / len(targets)
        solved = float(np.mean(residual <= 1e-9 * (arm.l1 + arm.l2)))
        rows.append(
            (
                f"roboticstoolbox ik_LM ({label})",
                "per call",
                seconds,
                float(residual.max()),
                solved,
            )
        )
    return rows, f"roboticstoolbox-python {rtb.__version__}"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    quick = parser.parse_args(argv).quick
    points, steps_deg, repeat = (
        (3, (2.0,), 1) if quick else (CIRCLE_POINTS, BRUTE_FORCE_STEPS_DEG, 3)
    )
    arm = arms.ten
    targets = workspace.circle_points(CIRCLE_CENTRE, CIRCLE_RADIUS, points)
    rows = twolink_rows(arm, targets, steps_deg, repeat)
    extra_rows, extra_note = robotics_toolbox_rows(arm, targets, repeat)
    rows += extra_rows
    budget = 1.0 / CONTROL_RATE_HZ
    print(
        f"# IK methods on the source circle (a1 = a2 = 10, centre {CIRCLE_CENTRE}, radius {CIRCLE_RADIUS:g}, "
        f"{points} points)\n"
    )
    print(
        f"Python {platform.python_version()}, numpy {np.__version__}, {platform.machine()}; {extra_note}. "
        f"Time per target is the median of timeit repeats; error is |fk(q) - p| recomputed with twolink's FK; "
        f"'solved' counts targets within 1e-9 of the reach (brute force: within its grid bound). "
        f"Real time means one target solved within one {1e3 * budget:g} ms cycle of a {CONTROL_RATE_HZ:g} Hz loop "
        f"and to within {1e3 * ACCURACY_M:g} mm.\n"
    )
    table = [
        (
            name,
            mode,
            seconds * 1e6,
            error,
            f"{100 * solved:.0f} %",
            "yes" if seconds <= budget else "no",
            "**yes**" if seconds <= budget and error <= ACCURACY_M else "no",
        )
        for name, mode, seconds, error, solved in rows
    ]
    print(
        markdown_table(
            [
                "method",
                "calls",
                "time per target [us]",
                "max error [m]",
                "solved",
                "within 1 ms",
                "real time",
            ],
            table,
            ["", "", ".2f", ".1e", "", "", ""],
        )
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
