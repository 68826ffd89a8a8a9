"""Speed of the workspace calls a slider makes (issue 23: chapter 7's explorer).

Prints one table: :meth:`twolink.workspace.BranchTable.reachable` (the limit
test redone for new limits, IK solved once) on chapter 7's 200 x 200 shading
grid (40,000 points, both conventions; beside it
:meth:`~twolink.workspace.BranchTable.solutions_within_limits`, which moves
the angles by whole turns too, and :func:`twolink.workspace.is_reachable`,
which solves IK again), and
:func:`twolink.workspace.largest_circle_on_grid` from that grid's reachable
points 5 apart (chapter 7's circle search).
Run with ``.venv/bin/python benchmarks/bench_workspace.py`` (``--quick`` for
a smoke run with a small grid, used by the test suite: it checks that the
script runs, not the speed).
"""

import argparse
import platform
from dataclasses import replace

import numpy as np

from twolink import arms, workspace
from twolink_course.display import markdown_table
from twolink_course.timing import median_time as _median_time


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="small grid: checks the script runs, not the speed",
    )
    quick = parser.parse_args(argv).quick
    timing_options = dict(repeat=1, min_seconds=1e-9) if quick else {"repeat": 7}

    def median_time(function):
        return _median_time(function, **timing_options)

    side, stride = (40, 1) if quick else (200, 5)  # chapter 7: 200 x 200, every 5th
    axis = np.linspace(-20.0, 20.0, side)
    spacing = float(axis[1] - axis[0])
    grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    on_search = np.zeros((side, side), dtype=bool)
    on_search[::stride, ::stride] = True
    on_search = on_search.ravel()
    table = workspace.BranchTable(arms.ten, grid)
    absolute = replace(
        arms.ten,
        q_min=arms.two_metre_limited.q_min,
        q_max=arms.two_metre_limited.q_max,
        limit_convention="absolute",
    )
    rows = []
    for arm, name in ((arms.ten, "relative"), (absolute, "absolute")):
        seconds = median_time(lambda: table.reachable(arm))
        rows.append(
            [
                f"BranchTable.reachable, {len(grid)} points, {name} limits",
                f"{seconds * 1e3:.2f} ms",
            ]
        )
    seconds = median_time(lambda: table.solutions_within_limits(arms.ten))
    rows.append(
        [
            f"BranchTable.solutions_within_limits, {len(grid)} points (angles moved by turns too)",
            f"{seconds * 1e3:.2f} ms",
        ]
    )
    seconds = median_time(lambda: workspace.is_reachable(arms.ten, grid))
    rows.append(
        [
            f"is_reachable, {len(grid)} points (IK solved again; scale)",
            f"{seconds * 1e3:.2f} ms",
        ]
    )
    for arm, name in ((arms.ten, "relative"), (absolute, "absolute")):
        for elbow in ("auto", "down"):
            arcs = workspace.boundary_arcs(arm, elbow=elbow)
            valid = workspace.is_reachable(arm, grid, elbow=elbow)
            starts = grid[valid & on_search]
            seconds = median_time(
                lambda: workspace.largest_circle_on_grid(
                    arcs, starts, stride * spacing, 0.005
                )
            )
            rows.append(
                [
                    f"largest_circle_on_grid, {name} limits, elbow {elbow}: {len(arcs)} arcs, "
                    f"{len(starts)} starts, tol 5 mm",
                    f"{seconds * 1e3:.2f} ms",
                ]
            )
    print(
        f"# twolink workspace benchmark ({platform.processor() or platform.machine()}, "
        f"{platform.system()}, Python {platform.python_version()}, numpy {np.__version__})\n"
    )
    print(markdown_table(["operation", "median time"], rows, ["", ""]))


if __name__ == "__main__":
    main()
