"""Speed and robustness of the kinematics core (issue: package core, chapters 1-2).

Prints one table: each figure measured on this machine beside its target.
Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_kinematics.py``
(``--quick`` for a smoke run with tiny sizes, used by the test suite: it
checks that the script runs, not the speed).
"""

import argparse
import platform

import numpy as np

from twolink import TwoLinkArm, arms, ik, wrap_angle
from twolink_course.display import markdown_table
from twolink_course.timing import median_time as _median_time


def plain_numpy_closed_form(arm, p):
    """The textbook closed form with no checks: the reference speed."""
    x, y = p[:, 0], p[:, 1]
    c2 = (x * x + y * y - arm.l1**2 - arm.l2**2) / (2 * arm.l1 * arm.l2)
    q2 = np.arccos(c2)
    q1 = np.arctan2(y, x) - np.arctan2(
        arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.cos(q2)
    )
    return q1, q2


def plain_newton_success_rate(arm, p, q0, iterations=100, tol=1e-12):
    """Full Newton steps q <- q - J^-1 (fk(q) - p), no step control: the naive method."""
    q = np.broadcast_to(np.asarray(q0, float), p.shape).copy()
    with np.errstate(all="ignore"):
        for _ in range(iterations):
            residual = arm.fk(np.nan_to_num(q)) - p
            J = arm.jacobian(np.nan_to_num(q))
            singular = np.abs(np.linalg.det(J)) < 1e-300
            J[singular] = np.eye(2)
            q = q - np.linalg.solve(J, residual[..., None])[..., 0]
            q = np.nan_to_num(q, nan=0.0, posinf=0.0, neginf=0.0)
    error = np.linalg.norm(arm.fk(wrap_angle(q)) - p, axis=-1)
    return float(np.mean(error <= tol * (arm.l1 + arm.l2)))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    quick = parser.parse_args(argv).quick
    timing_options = dict(repeat=1, min_seconds=1e-9) if quick else {}

    def median_time(function, repeat):
        return _median_time(function, **({"repeat": repeat} | timing_options))

    rng = np.random.default_rng(2024)
    arm = TwoLinkArm(1.0, 0.7)
    count = 2_000 if quick else 1_000_000
    q = rng.uniform(-np.pi, np.pi, (count, 2))
    p = arm.fk(q)

    rows = []
    seconds = median_time(lambda: ik.closed_form(arm, p), repeat=7)
    rows.append(
        (
            "ik.closed_form, 1e6 targets (vectorised; its IKResult judged by FK when built)",
            f"{seconds / count * 1e9:.1f} ns/target",
            "<= 50 ns",
            seconds / count <= 50e-9,
        )
    )
    seconds = median_time(lambda: plain_numpy_closed_form(arm, p), repeat=7)
    rows.append(
        (
            "plain numpy closed form, no checks (reference)",
            f"{seconds / count * 1e9:.1f} ns/target",
            "~25 ns",
            True,
        )
    )
    seconds = median_time(lambda: arm.fk(q), repeat=7)
    rows.append(
        (
            "arm.fk, 1e6 configurations",
            f"{seconds / count * 1e9:.1f} ns/config",
            "<= 100 ns",
            seconds / count <= 100e-9,
        )
    )
    seconds = median_time(lambda: arm.jacobian(q), repeat=7)
    rows.append(
        (
            "arm.jacobian, 1e6 configurations",
            f"{seconds / count * 1e9:.1f} ns/config",
            "<= 100 ns",
            seconds / count <= 100e-9,
        )
    )

    newton_count = 200 if quick else 100_000
    q_targets = rng.uniform(-np.pi, np.pi, (newton_count, 2))
    p_newton = arms.ten.fk(q_targets)
    result = ik.newton(arms.ten, p_newton, q0=(0.5, 1.0))
    rate = float(np.mean(result.success))
    rows.append(
        (
            f"ik.newton, 1e5 random targets, cold start (0.5, 1.0): converged (max {result.iterations.max()} it.)",
            f"{100 * rate:.3f} %",
            "100 %",
            rate == 1.0,
        )
    )
    naive = plain_newton_success_rate(arms.ten, p_newton, (0.5, 1.0))
    rows.append(
        (
            "plain full Newton steps, same targets (reference)",
            f"{100 * naive:.1f} %",
            "fails on ~7 %",
            True,
        )
    )
    seconds = median_time(
        lambda: ik.newton(arms.ten, p_newton[:10_000], q0=(0.5, 1.0)), repeat=3
    )
    per_target = seconds / len(p_newton[:10_000])
    rows.append(
        (
            f"ik.newton, vectorised over {len(p_newton[:10_000])} targets",
            f"{per_target * 1e6:.2f} us/target",
            "(info)",
            True,
        )
    )
    p_one = p_newton[0].tolist()
    seconds = median_time(lambda: ik.newton(arms.ten, p_one, q0=(0.5, 1.0)), repeat=7)
    rows.append(
        (
            "ik.newton, one target per call (floats)",
            f"{seconds * 1e6:.2f} us/call",
            "(info)",
            True,
        )
    )

    targets = arms.ten.fk(
        rng.uniform([0.0, -np.pi / 2], [np.pi / 2, np.pi / 2], (2 if quick else 20, 2))
    )
    seconds = median_time(
        lambda: ik.brute_force(arms.ten, targets, step=np.radians(1.0)), repeat=5
    )
    rows.append(
        (
            "ik.brute_force, 1 deg grid over q1 in [0, 90], q2 in [-90, 90] deg",
            f"{seconds / len(targets) * 1e3:.3f} ms/target",
            "<= 1 ms",
            seconds / len(targets) <= 1e-3,
        )
    )

    print(
        f"# twolink kinematics benchmark ({platform.processor() or platform.machine()}, numpy {np.__version__})\n"
    )
    print(
        markdown_table(
            ["quantity", "measured", "target", "meets target"],
            [(a, b, c, "yes" if ok else "NO") for a, b, c, ok in rows],
        )
    )
    return quick or all(ok for *_, ok in rows)


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
