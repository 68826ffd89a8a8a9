"""Batches: every vectorised operation of twolink beside plain numpy expressions of the same formulas.

A batch call (1e5 configurations, targets or states at once) should cost
what the formula costs: the package's checks are one pass over the input,
and its results are built in place.  Each row times one twolink call and
the same formula written as a user would write it with numpy, the arm's
constants computed once, outside the timed call (the floor), in
alternating batches so that both see the same load, and gives their ratio.

- ``ik.closed_form``: the floor is the textbook closed form (``arccos``,
  two ``arctan2``), no checks, returning the angles; twolink also tests the
  reach and returns an ``IKResult`` whose residuals come from forward
  kinematics of its answers, so that it says truthfully which targets are
  reached.

Times are CPU seconds of this process (``time.process_time``): on a
machine shared with other work, wall time also counts the other processes,
and a ratio of two wall times measured a second apart varies by 2x.

Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_batch.py``
(``--quick`` for a smoke run with tiny sizes, used by the test suite).
"""

import argparse
import math
import platform
import time
import timeit

import numpy as np

from twolink import TwoLinkArm, dynamics, ik, kinematics, velocity
from twolink_course.display import markdown_table

#: Largest ratio twolink / floor accepted (None: a row for information).
TARGET_RATIO = 1.15
CLOSED_FORM_TARGET_RATIO = 1.5


def interleaved_medians(first, second, repeat, min_seconds):
    """Median seconds of one call of ``first()`` and of ``second()``, timed in alternating batches."""
    timers = [
        timeit.Timer(first, timer=time.process_time),
        timeit.Timer(second, timer=time.process_time),
    ]
    numbers = []
    for timer in timers:
        number = 1
        while True:
            elapsed = timer.timeit(number=number)
            if elapsed >= min_seconds / 10 or number >= 10**6:
                break
            number *= 10
        numbers.append(
            max(1, int(math.ceil(number * min_seconds / max(elapsed, 1e-12))))
        )
    samples = ([], [])
    for _ in range(repeat):
        for timer, number, sample in zip(timers, numbers, samples):
            sample.append(timer.timeit(number=number) / number)
    return float(np.median(samples[0])), float(np.median(samples[1]))


# --- the floors: the formulas in plain numpy, constants computed once by the caller


def constants_of(arm):
    """What a user computes once per arm for the dynamics below (uniform rods, centres at mid-link)."""
    inertia_1, inertia_2 = arm.inertias
    lc1, lc2 = arm.l1 / 2.0, arm.l2 / 2.0
    alpha = inertia_1 + inertia_2 + arm.m1 * lc1**2 + arm.m2 * (arm.l1**2 + lc2**2)
    beta = arm.m2 * arm.l1 * lc2
    delta = inertia_2 + arm.m2 * lc2**2
    gamma1 = (arm.m1 * lc1 + arm.m2 * arm.l1) * arm.g
    gamma2 = arm.m2 * lc2 * arm.g
    return alpha, beta, delta, gamma1, gamma2


def floor_fk(l1, l2, q):
    q1, q12 = q[:, 0], q[:, 0] + q[:, 1]
    p = np.empty(q.shape)
    p[:, 0] = l1 * np.cos(q1) + l2 * np.cos(q12)
    p[:, 1] = l1 * np.sin(q1) + l2 * np.sin(q12)
    return p


def floor_jacobian(l1, l2, q):
    q1, q12 = q[:, 0], q[:, 0] + q[:, 1]
    s12, c12 = np.sin(q12), np.cos(q12)
    J = np.empty((len(q), 2, 2))
    J[:, 0, 0] = -l1 * np.sin(q1) - l2 * s12
    J[:, 0, 1] = -l2 * s12
    J[:, 1, 0] = l1 * np.cos(q1) + l2 * c12
    J[:, 1, 1] = l2 * c12
    return J


def floor_joint_torques(l1, l2, q, force):
    J = floor_jacobian(l1, l2, q)
    return np.einsum("nji,nj->ni", J, force)


def floor_tip_velocity(l1, l2, q, qd):
    return np.einsum("nij,nj->ni", floor_jacobian(l1, l2, q), qd)


def floor_joint_rates(l1, l2, q, v):
    J = floor_jacobian(l1, l2, q)
    det = l1 * l2 * np.sin(q[:, 1])
    qd = np.empty(q.shape)
    qd[:, 0] = (J[:, 1, 1] * v[:, 0] - J[:, 0, 1] * v[:, 1]) / det
    qd[:, 1] = (J[:, 0, 0] * v[:, 1] - J[:, 1, 0] * v[:, 0]) / det
    return qd


def floor_manipulability(l1, l2, q):
    return np.abs(l1 * l2 * np.sin(q[:, 1]))


def floor_closed_form(l1, l2, p):
    """The textbook closed form, elbow down, no checks."""
    x, y = p[:, 0], p[:, 1]
    c2 = (x * x + y * y - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)
    q2 = np.arccos(c2)
    q1 = np.arctan2(y, x) - np.arctan2(l2 * np.sin(q2), l1 + l2 * np.cos(q2))
    return q1, q2


def floor_mass_matrix(constants, q):
    alpha, beta, delta = constants[:3]
    beta_cos = beta * np.cos(q[:, 1])
    M = np.empty((len(q), 2, 2))
    M[:, 0, 0] = alpha + 2.0 * beta_cos
    M[:, 0, 1] = M[:, 1, 0] = delta + beta_cos
    M[:, 1, 1] = delta
    return M


def floor_coriolis(constants, q, qd):
    h = -constants[1] * np.sin(q[:, 1])
    C = np.zeros((len(q), 2, 2))
    C[:, 0, 0] = h * qd[:, 1]
    C[:, 0, 1] = h * (qd[:, 0] + qd[:, 1])
    C[:, 1, 0] = -h * qd[:, 0]
    return C


def floor_gravity(constants, q):
    gamma1, gamma2 = constants[3:]
    g2 = gamma2 * np.cos(q[:, 0] + q[:, 1])
    g = np.empty(q.shape)
    g[:, 0] = gamma1 * np.cos(q[:, 0]) + g2
    g[:, 1] = g2
    return g


def floor_inverse_dynamics(constants, q, qd, qdd):
    alpha, beta, delta, gamma1, gamma2 = constants
    c2, s2 = np.cos(q[:, 1]), np.sin(q[:, 1])
    m11, m12 = alpha + 2.0 * beta * c2, delta + beta * c2
    h = -beta * s2
    qd1, qd2 = qd[:, 0], qd[:, 1]
    g2 = gamma2 * np.cos(q[:, 0] + q[:, 1])
    tau = np.empty(q.shape)
    tau[:, 0] = (
        m11 * qdd[:, 0]
        + m12 * qdd[:, 1]
        + h * (2.0 * qd1 + qd2) * qd2
        + gamma1 * np.cos(q[:, 0])
        + g2
    )
    tau[:, 1] = m12 * qdd[:, 0] + delta * qdd[:, 1] - h * qd1 * qd1 + g2
    return tau


def floor_forward_dynamics(constants, q, qd, tau):
    alpha, beta, delta, gamma1, gamma2 = constants
    c2, s2 = np.cos(q[:, 1]), np.sin(q[:, 1])
    m11, m12 = alpha + 2.0 * beta * c2, delta + beta * c2
    h = -beta * s2
    qd1, qd2 = qd[:, 0], qd[:, 1]
    g2 = gamma2 * np.cos(q[:, 0] + q[:, 1])
    r1 = tau[:, 0] - h * (2.0 * qd1 + qd2) * qd2 - gamma1 * np.cos(q[:, 0]) - g2
    r2 = tau[:, 1] + h * qd1 * qd1 - g2
    det = m11 * delta - m12 * m12
    qdd = np.empty(q.shape)
    qdd[:, 0] = (delta * r1 - m12 * r2) / det
    qdd[:, 1] = (m11 * r2 - m12 * r1) / det
    return qdd


def floor_energy(constants, q, qd):
    alpha, beta, delta, gamma1, gamma2 = constants
    c2 = np.cos(q[:, 1])
    m11, m12 = alpha + 2.0 * beta * c2, delta + beta * c2
    qd1, qd2 = qd[:, 0], qd[:, 1]
    kinetic = 0.5 * (m11 * qd1 * qd1 + 2.0 * m12 * qd1 * qd2 + delta * qd2 * qd2)
    potential = gamma1 * np.sin(q[:, 0]) + gamma2 * np.sin(q[:, 0] + q[:, 1])
    return kinetic, potential


def check_floors_agree(arm, constants, q, qd, qdd, tau, force, p):
    """The floors compute what twolink computes (else the ratios mean nothing)."""
    l1, l2 = arm.l1, arm.l2
    close = dict(rtol=1e-9, atol=1e-9)
    assert np.allclose(floor_fk(l1, l2, q), arm.fk(q), **close)
    assert np.allclose(floor_jacobian(l1, l2, q), arm.jacobian(q), **close)
    assert np.allclose(
        floor_joint_torques(l1, l2, q, force), arm.joint_torques(q, force), **close
    )
    assert np.allclose(
        floor_tip_velocity(l1, l2, q, qd), arm.tip_velocity(q, qd), **close
    )
    assert np.allclose(
        floor_joint_rates(l1, l2, q, qd), arm.joint_rates(q, qd), rtol=1e-6, atol=1e-6
    )
    assert np.allclose(floor_manipulability(l1, l2, q), arm.manipulability(q), **close)
    difference = (
        np.column_stack(floor_closed_form(l1, l2, p)) - ik.closed_form(arm, p).q
    )
    assert np.allclose(
        np.sin(difference), 0.0, atol=1e-6
    )  # the same angles, up to whole turns
    assert np.allclose(floor_mass_matrix(constants, q), arm.mass_matrix(q), **close)
    assert np.allclose(floor_coriolis(constants, q, qd), arm.coriolis(q, qd), **close)
    assert np.allclose(floor_gravity(constants, q), arm.gravity(q), **close)
    assert np.allclose(
        floor_inverse_dynamics(constants, q, qd, qdd),
        arm.inverse_dynamics(q, qd, qdd),
        **close,
    )
    assert np.allclose(
        floor_forward_dynamics(constants, q, qd, tau),
        arm.forward_dynamics(q, qd, tau),
        **close,
    )
    assert np.allclose(floor_energy(constants, q, qd), arm.energy(q, qd), **close)


def batch_rows(count, repeat, min_seconds):
    arm = TwoLinkArm(l1=1.0, l2=0.7, m1=2.0, m2=1.2)
    constants = constants_of(arm)
    l1, l2 = arm.l1, arm.l2
    rng = np.random.default_rng(31)
    q = rng.uniform(-np.pi, np.pi, (count, 2))
    q[:, 1] = np.where(np.abs(np.sin(q[:, 1])) < 1e-3, 1.0, q[:, 1])  # no singular pose
    qd, qdd, tau, force = rng.uniform(-3.0, 3.0, (4, count, 2))
    p = arm.fk(rng.uniform([-np.pi, 0.2], [np.pi, 2.9], (count, 2)))
    check_floors_agree(arm, constants, q, qd, qdd, tau, force, p)

    cases = [
        ("kinematics.fk", lambda: kinematics.fk(arm, q), lambda: floor_fk(l1, l2, q)),
        (
            "kinematics.jacobian",
            lambda: kinematics.jacobian(arm, q),
            lambda: floor_jacobian(l1, l2, q),
        ),
        (
            "kinematics.joint_torques",
            lambda: kinematics.joint_torques(arm, q, force),
            lambda: floor_joint_torques(l1, l2, q, force),
        ),
        (
            "velocity.tip_velocity",
            lambda: velocity.tip_velocity(arm, q, qd),
            lambda: floor_tip_velocity(l1, l2, q, qd),
        ),
        (
            "velocity.joint_rates",
            lambda: velocity.joint_rates(arm, q, qd),
            lambda: floor_joint_rates(l1, l2, q, qd),
        ),
        (
            "velocity.manipulability",
            lambda: velocity.manipulability(arm, q),
            lambda: floor_manipulability(l1, l2, q),
        ),
        (
            "ik.closed_form",
            lambda: ik.closed_form(arm, p),
            lambda: floor_closed_form(l1, l2, p),
        ),
        (
            "ik.closed_form, elbow='both' (beside the floor's one branch)",
            lambda: ik.closed_form(arm, p, elbow="both"),
            lambda: floor_closed_form(l1, l2, p),
        ),
        (
            "dynamics.mass_matrix",
            lambda: dynamics.mass_matrix(arm, q),
            lambda: floor_mass_matrix(constants, q),
        ),
        (
            "dynamics.coriolis",
            lambda: dynamics.coriolis(arm, q, qd),
            lambda: floor_coriolis(constants, q, qd),
        ),
        (
            "dynamics.gravity",
            lambda: dynamics.gravity(arm, q),
            lambda: floor_gravity(constants, q),
        ),
        (
            "dynamics.inverse_dynamics",
            lambda: dynamics.inverse_dynamics(arm, q, qd, qdd),
            lambda: floor_inverse_dynamics(constants, q, qd, qdd),
        ),
        (
            "dynamics.forward_dynamics",
            lambda: dynamics.forward_dynamics(arm, q, qd, tau),
            lambda: floor_forward_dynamics(constants, q, qd, tau),
        ),
        (
            "dynamics.energy",
            lambda: dynamics.energy(arm, q, qd),
            lambda: floor_energy(constants, q, qd),
        ),
    ]
    rows = []
    for name, twolink_call, floor_call in cases:
        t_twolink, t_floor = interleaved_medians(
            twolink_call, floor_call, repeat, min_seconds
        )
        if name == "ik.closed_form":
            target = CLOSED_FORM_TARGET_RATIO
        elif name.startswith("ik.closed_form,"):
            target = None  # two answers per target: for information
        else:
            target = TARGET_RATIO
        rows.append((name, t_twolink, t_floor, t_twolink / t_floor, target))
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    args = parser.parse_args(argv)
    count, repeat, min_seconds = (200, 1, 1e-9) if args.quick else (100_000, 15, 0.05)
    rows = batch_rows(count, repeat, min_seconds)
    print(
        f"# twolink, batches of {count} beside plain numpy ({platform.machine()}, "
        f"{platform.python_implementation()} {platform.python_version()}, numpy {np.__version__}; "
        "CPU time of this process)\n"
    )
    table = [
        (
            name,
            f"{t_twolink * 1e3:.3f}",
            f"{t_floor * 1e3:.3f}",
            f"{ratio:.2f}x",
            "(info)" if target is None else f"<= {target:g}x",
            "-" if target is None else "yes" if ratio <= target else "NO",
        )
        for name, t_twolink, t_floor, ratio, target in rows
    ]
    print(
        markdown_table(
            [
                "batch operation",
                "twolink [ms]",
                "plain numpy [ms]",
                "ratio",
                "target",
                "meets",
            ],
            table,
        )
    )
    return args.quick or all(
        target is None or ratio <= target for *_, ratio, target in rows
    )


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
