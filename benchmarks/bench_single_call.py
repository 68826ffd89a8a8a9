"""One call at a time: twolink beside a plain-Python version of the same formula.

Students call the package one configuration, one target, one state at a time
(in loops, widgets, controllers).  This script times each public entry point
on a single input and divides by the time of a plain-Python (``math`` module)
implementation of the same formula, measured in the same run, so the ratio
does not depend on the machine.  It also times the vectorised (batched) call
per element, to show that the single-input path does not cost the batch path
anything, and the same ``solve_ivp`` call with twolink's right-hand side and
with a plain-Python one.

What each side does, so the ratios compare like with like:

- ``ik.closed_form``: twolink checks the arm, the target and the elbow word,
  tests the reach (with its round-off tolerance), solves one branch and
  returns an ``IKResult``, a frozen dataclass whose fields are computed when
  it is built: forward kinematics of ``q``, the residual, success, the joint
  limits and the message.  The plain version tests the reach, solves the
  same branch and returns the two angles as a tuple: it does not judge its
  answer (the target accepts 4x for the judging, up from 3x).
- ``ik.closed_form, judged alike`` (for information, no target): the same
  twolink call beside a plain version that judges its answer too: it
  recomputes the tip by forward kinematics and returns
  ``(q1, q2, residual, success)`` as Python numbers.
- ``ik.newton``: both iterate to the same tolerance from the same start;
  twolink returns an ``IKResult``, the plain version the two angles.
- ``mass_matrix``, ``forward_dynamics``, ``inverse_dynamics``: the plain
  versions take the arm's constants (``alpha, beta, delta, gamma1,
  gamma2``) computed once, outside the timed call, as a user's own code
  would (twolink keeps them on the arm); they return floats, twolink an
  array, after checking its input.

Run with ``make bench`` or ``.venv/bin/python benchmarks/bench_single_call.py``
(``--quick`` for a smoke run with tiny sizes, used by the test suite).
Each pair (twolink, plain) is timed in alternating batches, in CPU seconds
of this process (``time.process_time``), so that both see the same load on a
shared machine and other processes do not enter the ratio; the table gives
the medians.
"""

import argparse
import math
import platform
import time
import timeit

import numpy as np
from scipy.integrate import solve_ivp

from twolink import TwoLinkArm, dynamics, ik, simulate
from twolink_course.display import markdown_table
from twolink_course.timing import median_time

# The per-call targets of the speed issue: twolink / plain Python (None: a row for information, no target).
TARGET_RATIO = {
    "fk": 2.5,
    "jacobian": 3.0,
    "ik.closed_form": 4.0,
    "ik.closed_form, judged alike": None,
    "ik.newton": 3.0,
    "mass_matrix": 4.5,  # a 2x2 array (0.4 us to make) against four floats in tuples
    "forward_dynamics": 2.0,
    "inverse_dynamics": 2.0,
}
SIMULATE_TARGET_RATIO = 1.2


# --- plain-Python references: the same formulas, floats and the math module only


def plain_fk(l1, l2, q1, q2):
    q12 = q1 + q2
    return (
        l1 * math.cos(q1) + l2 * math.cos(q12),
        l1 * math.sin(q1) + l2 * math.sin(q12),
    )


def plain_jacobian(l1, l2, q1, q2):
    q12 = q1 + q2
    s1, c1, s12, c12 = math.sin(q1), math.cos(q1), math.sin(q12), math.cos(q12)
    return ((-l1 * s1 - l2 * s12, -l2 * s12), (l1 * c1 + l2 * c12, l2 * c12))


def plain_closed_form(l1, l2, x, y):
    """Elbow-down closed form with the reach check a correct solver needs: ``(q1, q2)``."""
    r_squared = x * x + y * y
    c2 = (r_squared - l1 * l1 - l2 * l2) / (2.0 * l1 * l2)
    if not -1.0 <= c2 <= 1.0:
        raise ValueError("unreachable")
    q2 = math.acos(c2)
    q1 = math.atan2(y, x) - math.atan2(l2 * math.sin(q2), l1 + l2 * c2)
    return q1, q2


def plain_closed_form_judged(l1, l2, x, y, tol=1e-9):
    """:func:`plain_closed_form`, then its answer judged by forward kinematics: ``(q1, q2, residual, success)``."""
    q1, q2 = plain_closed_form(l1, l2, x, y)
    tip_x, tip_y = plain_fk(l1, l2, q1, q2)
    residual = math.hypot(tip_x - x, tip_y - y)
    return q1, q2, residual, residual <= tol * (l1 + l2)


def plain_newton(l1, l2, x, y, q1=0.5, q2=1.0, tol=1e-12, max_iter=100):
    """Newton on fk(q) = p with a backtracking (halving) step: 2x2 solve by Cramer's rule."""
    fx, fy = plain_fk(l1, l2, q1, q2)
    rx, ry = fx - x, fy - y
    error = math.hypot(rx, ry)
    threshold = tol * (l1 + l2)
    for _ in range(max_iter):
        if error <= threshold:
            break
        (a, b), (c, d) = plain_jacobian(l1, l2, q1, q2)
        det = a * d - b * c
        if det == 0.0:
            det = 1e-300
        dq1 = -(d * rx - b * ry) / det
        dq2 = -(-c * rx + a * ry) / det
        step = 1.0
        while step > 1e-10:
            t1, t2 = q1 + step * dq1, q2 + step * dq2
            fx, fy = plain_fk(l1, l2, t1, t2)
            trial_error = math.hypot(fx - x, fy - y)
            if trial_error < error:
                q1, q2, rx, ry, error = t1, t2, fx - x, fy - y, trial_error
                break
            step *= 0.5
        else:
            break
    return q1, q2


def plain_constants(arm):
    """The arm's constants of the uniform-rod model, computed once per arm (as a user's own code does).

    ``(alpha, beta, delta, gamma1, gamma2)``: ``M11 = alpha + 2 beta cos q2``,
    ``M12 = delta + beta cos q2``, ``M22 = delta``, ``h = beta sin q2``,
    ``g1 = gamma1 cos q1 + gamma2 cos q12``, ``g2 = gamma2 cos q12``.
    """
    I1, I2 = arm.inertias
    lc1, lc2 = arm.l1 / 2.0, arm.l2 / 2.0
    m1, m2, l1, g = arm.m1, arm.m2, arm.l1, arm.g
    return (
        I1 + I2 + m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2),
        m2 * l1 * lc2,
        I2 + m2 * lc2 * lc2,
        (m1 * lc1 + m2 * l1) * g,
        m2 * lc2 * g,
    )


def plain_dynamics_terms(constants, q1, q2, qd1, qd2):
    """M, the Coriolis/centrifugal vector and gravity of the uniform-rod model (floats)."""
    alpha, beta, delta, gamma1, gamma2 = constants
    c2, s2 = math.cos(q2), math.sin(q2)
    m11 = alpha + 2.0 * beta * c2
    m12 = delta + beta * c2
    h = beta * s2
    bias1 = -h * (2.0 * qd1 * qd2 + qd2 * qd2)
    bias2 = h * qd1 * qd1
    c1, c12 = math.cos(q1), math.cos(q1 + q2)
    gravity2 = gamma2 * c12
    return m11, m12, delta, bias1 + gamma1 * c1 + gravity2, bias2 + gravity2


def plain_mass_matrix(constants, q2):
    """``M(q)`` as four floats: ``((M11, M12), (M12, M22))``."""
    alpha, beta, delta = constants[:3]
    beta_cos = beta * math.cos(q2)
    m12 = delta + beta_cos
    return ((alpha + 2.0 * beta_cos, m12), (m12, delta))


def plain_forward_dynamics(constants, q1, q2, qd1, qd2, tau1, tau2):
    m11, m12, m22, n1, n2 = plain_dynamics_terms(constants, q1, q2, qd1, qd2)
    rhs1, rhs2 = tau1 - n1, tau2 - n2
    det = m11 * m22 - m12 * m12
    return ((m22 * rhs1 - m12 * rhs2) / det, (m11 * rhs2 - m12 * rhs1) / det)


def plain_inverse_dynamics(constants, q1, q2, qd1, qd2, qdd1, qdd2):
    m11, m12, m22, n1, n2 = plain_dynamics_terms(constants, q1, q2, qd1, qd2)
    return (m11 * qdd1 + m12 * qdd2 + n1, m12 * qdd1 + m22 * qdd2 + n2)


def plain_state_derivative(arm):
    constants = plain_constants(arm)

    def free_motion(t, state):
        q1, q2, qd1, qd2 = state
        qdd1, qdd2 = plain_forward_dynamics(constants, q1, q2, qd1, qd2, 0.0, 0.0)
        return [qd1, qd2, qdd1, qdd2]

    return free_motion


# --- measurement


def check_references_agree(arm, q, qd, tau, p):
    """The plain versions compute what twolink computes (else the ratios mean nothing)."""
    q1, q2 = q
    assert np.allclose(plain_fk(arm.l1, arm.l2, q1, q2), arm.fk(q), rtol=0, atol=1e-12)
    assert np.allclose(
        plain_jacobian(arm.l1, arm.l2, q1, q2), arm.jacobian(q), rtol=0, atol=1e-12
    )
    result = ik.closed_form(arm, p, elbow="down")
    assert np.allclose(plain_closed_form(arm.l1, arm.l2, *p), result.q, atol=1e-9)
    *_, plain_residual, plain_success = plain_closed_form_judged(arm.l1, arm.l2, *p)
    assert (
        plain_success
        and bool(result.success)
        and abs(plain_residual - float(result.residual)) <= 1e-12
    )
    assert np.allclose(
        plain_mass_matrix(plain_constants(arm), q[1]),
        dynamics.mass_matrix(arm, q),
        rtol=1e-12,
        atol=0,
    )
    q_newton = plain_newton(arm.l1, arm.l2, *p)
    assert np.allclose(plain_fk(arm.l1, arm.l2, *q_newton), p, atol=1e-9)
    constants = plain_constants(arm)
    assert np.allclose(
        plain_forward_dynamics(constants, *q, *qd, *tau),
        dynamics.forward_dynamics(arm, q, qd, tau),
        rtol=1e-9,
        atol=1e-9,
    )
    qdd = dynamics.forward_dynamics(arm, q, qd, tau)
    assert np.allclose(
        plain_inverse_dynamics(constants, *q, *qd, *qdd), tau, rtol=1e-9, atol=1e-9
    )


def interleaved_medians(first, second, repeat, min_seconds):
    """Median time of one call of ``first()`` and of ``second()``, measured in alternation.

    On a shared machine the load changes from second to second; timing the
    two one after the other in alternating batches (each lasting about
    ``min_seconds``), in CPU time, lets both see the same load, so their
    ratio is steadier than that of two separate :func:`median_time` runs.
    """
    timers = [
        timeit.Timer(first, timer=time.process_time),
        timeit.Timer(second, timer=time.process_time),
    ]
    numbers = []
    for timer in timers:  # calls per batch, calibrated as median_time does
        number = 1
        while True:
            elapsed = timer.timeit(number=number)
            if elapsed >= min_seconds / 10 or number >= 10**9:
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


def single_call_rows(arm, repeat, min_seconds, batch):
    rng = np.random.default_rng(13)
    q = np.array([0.4, 1.1])
    qd = np.array([0.3, -0.8])
    tau = np.array([2.0, -1.0])
    qdd = np.array([1.5, 0.2])
    p = arm.fk(q)
    check_references_agree(arm, q, qd, tau, p)
    q_list, p_list = q.tolist(), p.tolist()
    l1, l2 = arm.l1, arm.l2
    constants = plain_constants(arm)  # once, outside the timed calls

    q_batch = rng.uniform(-np.pi, np.pi, (batch, 2))
    qd_batch = rng.uniform(-2.0, 2.0, (batch, 2))
    tau_batch = rng.uniform(-5.0, 5.0, (batch, 2))
    p_batch = arm.fk(rng.uniform([0.2, 0.3], [1.2, 2.5], (batch, 2)))

    cases = [
        (
            "fk",
            lambda: arm.fk(q_list),
            lambda: plain_fk(l1, l2, *q_list),
            lambda: arm.fk(q_batch),
        ),
        (
            "jacobian",
            lambda: arm.jacobian(q_list),
            lambda: plain_jacobian(l1, l2, *q_list),
            lambda: arm.jacobian(q_batch),
        ),
        (
            "ik.closed_form",
            lambda: ik.closed_form(arm, p_list, elbow="down"),
            lambda: plain_closed_form(l1, l2, *p_list),
            lambda: ik.closed_form(arm, p_batch, elbow="down"),
        ),
        (
            "ik.closed_form, judged alike",
            lambda: ik.closed_form(arm, p_list, elbow="down"),
            lambda: plain_closed_form_judged(l1, l2, *p_list),
            lambda: ik.closed_form(arm, p_batch, elbow="down"),
        ),
        (
            "ik.newton",
            lambda: ik.newton(arm, p_list, q0=(0.5, 1.0)),
            lambda: plain_newton(l1, l2, *p_list),
            lambda: ik.newton(arm, p_batch, q0=(0.5, 1.0)),
        ),
        (
            "mass_matrix",
            lambda: dynamics.mass_matrix(arm, q_list),
            lambda: plain_mass_matrix(constants, q_list[1]),
            lambda: dynamics.mass_matrix(arm, q_batch),
        ),
        (
            "forward_dynamics",
            lambda: dynamics.forward_dynamics(arm, q_list, qd.tolist(), tau.tolist()),
            lambda: plain_forward_dynamics(
                constants, *q_list, *qd.tolist(), *tau.tolist()
            ),
            lambda: dynamics.forward_dynamics(arm, q_batch, qd_batch, tau_batch),
        ),
        (
            "inverse_dynamics",
            lambda: dynamics.inverse_dynamics(arm, q_list, qd.tolist(), qdd.tolist()),
            lambda: plain_inverse_dynamics(
                constants, *q_list, *qd.tolist(), *qdd.tolist()
            ),
            lambda: dynamics.inverse_dynamics(arm, q_batch, qd_batch, tau_batch),
        ),
    ]
    rows = []
    for name, twolink_call, plain_call, batch_call in cases:
        t_twolink, t_plain = interleaved_medians(
            twolink_call, plain_call, repeat, min_seconds
        )
        t_batch = (
            median_time(batch_call, repeat=repeat, min_seconds=min_seconds) / batch
        )
        ratio = t_twolink / t_plain
        rows.append((name, t_twolink, t_plain, ratio, TARGET_RATIO[name], t_batch))
    return rows


def simulate_row(arm, t_end, repeat):
    q0, qd0 = np.array([np.pi / 4, 0.0]), np.zeros(2)
    options = dict(method="DOP853", rtol=1e-10, atol=1e-10)
    plain_rhs = plain_state_derivative(arm)
    state0 = np.concatenate([q0, qd0])
    t_twolink, t_plain = interleaved_medians(
        lambda: simulate(arm, q0, qd0, t_end, **options),
        lambda: solve_ivp(plain_rhs, (0.0, t_end), state0, **options),
        repeat,
        1e-9,
    )
    return t_twolink, t_plain, t_twolink / t_plain


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    args = parser.parse_args(argv)
    repeat, min_seconds, batch, t_end = (
        (1, 1e-9, 100, 0.2) if args.quick else (15, 0.02, 100_000, 10.0)
    )

    arm = TwoLinkArm(l1=1.0, l2=0.7, m1=2.0, m2=1.2)
    rows = single_call_rows(arm, repeat, min_seconds, batch)
    t_sim, t_sim_plain, sim_ratio = simulate_row(
        arm, t_end, repeat=1 if args.quick else 5
    )

    print(
        f"# twolink, one call at a time ({platform.machine()}, {platform.python_implementation()} "
        f"{platform.python_version()}, numpy {np.__version__})\n"
    )
    table = []
    for name, t_twolink, t_plain, ratio, target, t_batch in rows:
        table.append(
            (
                name,
                f"{t_twolink * 1e6:.2f}",
                f"{t_plain * 1e6:.2f}",
                f"{ratio:.2f}x",
                "(info)" if target is None else f"<= {target:g}x",
                "-" if target is None else "yes" if ratio <= target else "NO",
                f"{t_batch * 1e9:.0f}",
            )
        )
    table.append(
        (
            f"simulate, {t_end:g} s free motion, DOP853 rtol 1e-10",
            f"{t_sim * 1e6:.0f}",
            f"{t_sim_plain * 1e6:.0f}",
            f"{sim_ratio:.2f}x",
            f"<= {SIMULATE_TARGET_RATIO:g}x",
            "yes" if sim_ratio <= SIMULATE_TARGET_RATIO else "NO",
            "",
        )
    )
    print(
        markdown_table(
            [
                "call (one input)",
                "twolink [us]",
                "plain Python [us]",
                "ratio",
                "target",
                "meets",
                "batched [ns/item]",
            ],
            table,
        )
    )
    met = (
        all(target is None or ratio <= target for _, _, _, ratio, target, _ in rows)
        and sim_ratio <= SIMULATE_TARGET_RATIO
    )
    return met or args.quick


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
