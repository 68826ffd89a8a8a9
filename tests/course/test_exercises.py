"""The exercises (twolink_course.exercises) through their self-checks, tested.

For every exercise:

- the wrong answers of ``WRONG`` (the table of plausible mistakes) are rejected,
  each with the other parts still passing (no part blames a sibling);
- the equivalent forms of ``EQUIVALENT`` are accepted;
- a part left unsolved makes no sibling fail;
- each check cell of a chapter is one ``selfcheck.check`` call on the answers' names.

The chapters' worked solutions are checked in nbval's run of each chapter
(``notebooks/NN_x.ipynb::exercises``, tests/notebooks/chapter_checks.py): each
passes its self-check, its student-edition stub says "not solved yet", and a
function part passes hidden cases (a seed the notebook never holds).

The right answers are computed here from the package's primitives or by hand,
never read from ``answers/``; the chapters' ``RERUN`` and ``FORBIDDEN`` entries
(the interface with the grader) are tested at the end: each inputs cell binds its
entry's inputs, each worked solution run on hidden inputs gives the entry's
references, each forbidden call exists and the exercise states its rules.
"""

import ast
import builtins
import contextlib
import dataclasses
import importlib
import io
import json
import os
import pathlib
import re
import sys

import numpy as np
import pytest
from IPython.core.inputtransformer2 import TransformerManager

from twolink import (
    TwoLinkArm,
    arms,
    controllers,
    ik,
    linearization,
    simulate,
    to_relative,
    trajectory,
    workspace,
)
from twolink_course import (
    exercises,
    selfcheck,
)
from twolink_course.exercises import judging
from twolink_course.sources import compsys726

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import editions  # noqa: E402

import answers  # noqa: E402

#: A seed the notebooks never hold (the grader has its own).
HIDDEN_TEST_SEED = 5_318_008

NUMBERS = [exercise.number for exercise in exercises.all_exercises()]
FUNCTION_PARTS = [
    (number, part.name)
    for number in NUMBERS
    for part in exercises.get(number).parts
    if getattr(part, "kind", None) == "function"
]


def statuses(number, answers):
    with contextlib.redirect_stdout(io.StringIO()) as printed:
        report = selfcheck.check(number, **answers)
    lines = printed.getvalue().splitlines()
    assert len(lines) == len(report) == len(exercises.get(number).parts)
    return {
        exercises.get(number).parts[i].name: result.status
        for i, result in enumerate(report)
    }, lines


# ------------------------------------------------------------- right answers, computed here independently


def _hanging_stiffness():
    """K = dg/dq of the 2 m arm hanging at (-90, 0) deg, by hand from its uniform rods."""
    two = arms.two_metre
    s1, s12 = np.sin(np.radians(-90.0)), np.sin(np.radians(-90.0))
    # g1 = g ((m1/2 + m2) l1 cos q1 + m2 l2/2 cos(q1 + q2)), g2 = g m2 l2/2 cos(q1 + q2)
    b = two.g * (two.m1 / 2 + two.m2) * two.l1 * s1
    c = two.g * two.m2 * two.l2 / 2 * s12
    return -np.array([[b + c, c], [c, c]])


def _kinetic_energy(arm, q, qd):
    """T (J) of two uniform rods, by hand: centres at mid-link, m l^2/12 about them."""
    (c1, s1), (c12, s12) = (
        (np.cos(q[0]), np.sin(q[0])),
        (
            np.cos(q[0] + q[1]),
            np.sin(q[0] + q[1]),
        ),
    )
    w1, w2 = qd[0], qd[0] + qd[1]
    v1 = arm.l1 / 2 * w1 * np.array([-s1, c1])
    v2 = arm.l1 * w1 * np.array([-s1, c1]) + arm.l2 / 2 * w2 * np.array([-s12, c12])
    return 0.5 * (
        arm.m1 * v1 @ v1
        + arm.m1 * arm.l1**2 / 12 * w1**2
        + arm.m2 * v2 @ v2
        + arm.m2 * arm.l2**2 / 12 * w2**2
    )


def _potential_5_5(q):
    """V (J) of the 2 m arm's rods at q, by hand: g (m1 y_c1 + m2 y_c2)."""
    two = arms.two_metre
    y_c1 = two.l1 / 2 * np.sin(q[0])
    y_c2 = two.l1 * np.sin(q[0]) + two.l2 / 2 * np.sin(q[0] + q[1])
    return two.g * (two.m1 * y_c1 + two.m2 * y_c2)


def _sag(k):
    """How far (m) the vertical 2 m arm's tip rests from (3, 1) under a spring k, no gravity compensation."""
    two, rest = arms.two_metre, np.array([3.0, 1.0])
    controller = controllers.Impedance(two, k, 0.0, rest, gravity_compensation=False)
    q_rest = ik.closed_form(two, rest).q
    return np.linalg.norm(
        two.fk(linearization.equilibrium(two, controller, q_rest)) - rest
    )


def _moments(arm, q, force_by_tip):
    """The joint torques of a tip force as its moments about the joints (no J, no joint_torques)."""
    base, elbow, tip = arm.joint_positions(np.asarray(q, dtype=float))
    fx, fy = force_by_tip
    return np.array(
        [
            (tip - base)[0] * fy - (tip - base)[1] * fx,
            (tip - elbow)[0] * fy - (tip - elbow)[1] * fx,
        ]
    )


def _tip(arm, q):
    """The tip (x, y) of ``arm`` at ``q`` by the formula, without the package's fk."""
    return np.array(
        [
            arm.l1 * np.cos(q[0]) + arm.l2 * np.cos(q[0] + q[1]),
            arm.l1 * np.sin(q[0]) + arm.l2 * np.sin(q[0] + q[1]),
        ]
    )


def _reachable_by_hand(arm, p, elbows=("down", "up")):
    """Within the limits on one of ``elbows``: closed-form IK, angles taken modulo 2 pi."""
    if not arm.reach[0] <= np.hypot(*p) <= arm.reach[1]:
        return False
    low, high = np.array(arm.q_min), np.array(arm.q_max)
    for elbow in elbows:
        q = ik.closed_form(arm, np.asarray(p, dtype=float), elbow=elbow).q
        angles = (
            np.array([q[0], q[0] + q[1]]) if arm.limit_convention == "absolute" else q
        )
        # each angle's offset past its low limit, on the turn that starts there
        offset = np.mod(angles - low + 1e-9, 2 * np.pi) - 1e-9
        if np.all(offset <= high - low + 1e-9):
            return True
    return False


def _elbow(arm, p, sign):
    """The closed form's branch with q2 of ``sign`` (-1: up), by the cosine rule and atan2."""
    c2 = (p[0] ** 2 + p[1] ** 2 - arm.l1**2 - arm.l2**2) / (2 * arm.l1 * arm.l2)
    q2 = sign * np.arccos(np.clip(c2, -1.0, 1.0))
    q1 = np.arctan2(p[1], p[0]) - np.arctan2(
        arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.cos(q2)
    )
    return np.array([q1, q2])


def _elbow_up(arm, p):
    """The elbow-up angles, without the package's IK."""
    return _elbow(arm, p, -1.0)


def _jacobian(arm, q):
    """J of ``arm`` at ``q`` by hand, without the package's jacobian."""
    s1, c1, s12, c12 = (
        np.sin(q[0]),
        np.cos(q[0]),
        np.sin(q[0] + q[1]),
        np.cos(q[0] + q[1]),
    )
    return np.array(
        [
            [-arm.l1 * s1 - arm.l2 * s12, -arm.l2 * s12],
            [arm.l1 * c1 + arm.l2 * c12, arm.l2 * c12],
        ]
    )


def _solve_rates(arm, q, v_tip):
    return np.linalg.solve(_jacobian(arm, q), v_tip)


def _dls(lambda_squared, transpose=True, normal=False):
    """Exercise 3.6's damped rates, written the ways a student might."""
    q, v = (
        np.radians([30.0, 3.0]),
        0.1 * np.array([np.cos(np.radians(31.5)), np.sin(np.radians(31.5))]),
    )
    J = _jacobian(arms.two_metre, q)
    if normal:
        return np.linalg.solve(J.T @ J + lambda_squared * np.eye(2), J.T @ v)
    w = np.linalg.solve(J @ J.T + lambda_squared * np.eye(2), v)
    return J.T @ w if transpose else w


def _right_answers():
    two, ten, osake = arms.two_metre, arms.ten, arms.osake
    answers = {}
    q = np.radians([50.0, -30.0])
    answers["1.1"] = {
        "p_tip_ex1": [
            osake.l1 * np.cos(q[0]) + osake.l2 * np.cos(q.sum()),
            osake.l1 * np.sin(q[0]) + osake.l2 * np.sin(q.sum()),
        ]
    }
    # link 2 on a 2 cm spacer: the second row's d lifts the tip along the base's z
    T = osake.transforms(np.radians([120.0, -45.0]))[1].copy()
    T[2, 3] += 0.02
    answers["1.2"] = {"T_02_ex2": T, "z_tip_ex2": T[2, 3], "x_axis_ex2": T[:3, 0]}
    q_abs = np.radians([60.0, 150.0])
    answers["1.3"] = {
        "q_rel_ex3": [q_abs[0], q_abs[1] - q_abs[0]],
        "p_tip_ex3": two.l1 * np.array([np.cos(q_abs[0]), np.sin(q_abs[0])])
        + two.l2 * np.array([np.cos(q_abs[1]), np.sin(q_abs[1])]),
    }
    answers["1.4"] = {"tip_position": _tip}
    # the bench arm (0.30 m, 0.20 m, its plane 0.05 m up) at (90, -90) deg: the elbow at
    # (0, 0.30, 0.05), link 2 along q1 + q2 = 0
    answers["1.5"] = {
        "dh_ex5": [[0.05, 0.30, 0.0], [0.0, 0.20, 0.0]],
        "o1_ex5": [0.0, 0.30, 0.05],
        "x2_ex5": [1.0, 0.0, 0.0],
    }
    # at (14, 9) elbow up is q = (66.4, -67.4) deg, within [0, 90] x [-90, 90] deg; elbow
    # down, (-0.9, 67.4) deg, is not
    answers["2.1"] = {
        "q_elbow_up": _elbow_up(ten, [14.0, 9.0]),
        "up_within_limits": True,
    }
    step = 2 * 0.01 / 30.0
    answers["2.2"] = {
        "step_deg_ex2": np.degrees(step),
        "grid_points_ex2": (np.ceil(np.pi / 2 / step) + 1)
        * (np.ceil(np.pi / step) + 1),
    }  # both ends on the grid
    try:
        ik.closed_form(ten, [15.0, 16.0])
    except ValueError as error:
        message = str(error)
    answers["2.3"] = {
        "unreachable_message": message,
        "distance_beyond_reach": np.sqrt(481.0) - 20.0,
    }
    answers["2.4"] = {"elbow_up_angles": _elbow_up}
    seconds = np.array([3.2e-6, 9.7e-6, 9.4e-4, 2.9e-4, 2.7e-4])
    answers["2.5"] = {
        "margins_ex5": 1e-3 / seconds,  # closed form, newton, BFGS, SLSQP, brute force
        "fit_with_margin_ex5": 4,  # all but BFGS fit 3 times over
        "reason_ex5": "b",
    }
    answers["3.1"] = {
        "joint_rates": _solve_rates,
        "qd_ex1": _solve_rates(two, np.radians([20.0, 70.0]), [0.0, 0.2]),
    }
    answers["3.2"] = {"tip_speed_ex2": np.hypot(osake.l1, osake.l2) * np.radians(5.0)}
    q2_grid = np.radians(np.arange(0.5, 180.0, 0.5))
    cond = np.linalg.cond(
        osake.jacobian(np.stack([np.zeros_like(q2_grid), q2_grid], -1))
    )
    answers["3.3"] = {
        "q2_best_deg_ex3": np.degrees(q2_grid[np.argmin(cond)]),
        "cond_best_ex3": cond.min(),
    }
    # exercise 3.4: column i stacks z x (o2 - o_(i-1)) over z, z = (0, 0, 1), on the OSAKE arm
    q34 = np.radians([40.0, -70.0])
    elbow, tip = osake.joint_positions(q34)[1:]
    turn = np.array([[0.0, -1.0], [1.0, 0.0]])  # z x r in the plane
    answers["3.4"] = {
        "J_geo_ex4": np.vstack(
            [
                np.column_stack([turn @ tip, turn @ (tip - elbow)]),
                np.zeros((3, 2)),
                [1, 1],
            ]
        )
    }
    answers["3.5"] = {
        "det_J_ex5": 0.06 * np.sin(np.radians(30.0)),
        "singular_q2_deg_ex5": [0, 180],
    }
    q36 = np.radians([30.0, 3.0])
    v36 = 0.1 * np.array([np.cos(np.radians(31.5)), np.sin(np.radians(31.5))])
    J36 = _jacobian(two, q36)
    U, sigma, Vt = np.linalg.svd(
        J36
    )  # DLS: each singular direction times sigma / (sigma^2 + 0.01)
    answers["3.6"] = {
        "qd_exact_ex6": np.linalg.solve(J36, v36),
        "qd_dls_ex6": Vt.T @ (sigma / (sigma**2 + 0.1**2) * (U.T @ v36)),
    }
    answers["4.1"] = {
        "tau_ex1": two.jacobian(np.radians([30.0, 60.0])).T @ [0.0, -100.0]
    }
    # the tip at (3, 1) on the wall x = 3 m: the cosine rule for q2, then q1
    c2 = (3.0**2 + 1.0**2 - 2 * 2.0**2) / (2 * 2.0 * 2.0)
    q2_down = np.arccos(c2)
    q1_down = np.arctan2(1.0, 3.0) - np.arctan2(2.0 * np.sin(q2_down), 2.0 + 2.0 * c2)
    elbow = 2.0 * np.array([np.cos(q1_down), np.sin(q1_down)])
    answers["4.2"] = {
        "q_down_ex2": np.array([q1_down, q2_down]),
        # moments of (200, 0) N at the tip about the base and about the elbow
        "tau_down_ex2": np.array([-1.0 * 200.0, -(1.0 - elbow[1]) * 200.0]),
    }
    q43 = np.radians([30.0, -60.0])
    answers["4.3"] = {
        "tau_ex3": two.jacobian(q43).T @ [0.0, 20.0 * two.g] + two.gravity(q43)
    }
    answers["4.4"] = {"wall_torques": _moments}
    # at (0, 90) deg: s1 = 0, c1 = 1, s12 = 1, c12 = 0; J J^T = [[8, -4], [-4, 4]] has
    # the eigenvalues 6 +- 2 sqrt(5) = (sqrt(5) +- 1)^2, so sigma = sqrt(5) +- 1
    answers["4.5"] = {
        "J_ex5": [[-2.0, -2.0], [2.0, 0.0]],
        "force_axes_ex5": [1 / (np.sqrt(5) - 1), 1 / (np.sqrt(5) + 1)],
        "reason_ex5": "b",
    }
    q51 = np.radians([30.0, 45.0])
    answers["5.1"] = {
        "tau_hold_ex1": two.inverse_dynamics(q51, [0.0, 0.0], [0.0, 0.0]),
        "qdd_ex1": np.linalg.solve(two.mass_matrix(q51), [0.0, -two.gravity(q51)[1]]),
    }
    K = _hanging_stiffness()
    answers["5.2"] = {
        "K_ex2": K,
        "omega_ex2": np.sort(
            np.sqrt(
                np.linalg.eigvals(
                    np.linalg.solve(two.mass_matrix(np.radians([-90.0, 0.0])), K)
                ).real
            )
        ),
    }
    horizontal = dataclasses.replace(two, g=0.0)
    q0, qd0 = np.radians([0.0, 90.0]), np.array([2.0, 0.0])
    spin = simulate(horizontal, q0, qd0, 5.0, method="DOP853", rtol=1e-10, atol=1e-10)
    assert spin.energy_drift() < 1e-8
    answers["5.3"] = {
        "q_end_ex3": spin.q[-1],
        "qd_end_ex3": spin.qd[-1],
        "p1_end_ex3": (horizontal.mass_matrix(spin.q[-1]) @ spin.qd[-1])[0],
    }
    answers["5.4"] = {
        "T_ex4": _kinetic_energy(two, np.radians([30.0, 45.0]), np.array([1.0, -2.0])),
        "kinetic_energy": _kinetic_energy,
    }
    # the planned move starts and ends at rest: the motors' work is the change of V
    energy_change = _potential_5_5(np.radians([45.0, 60.0])) - _potential_5_5(
        np.radians([-90.0, 0.0])
    )
    answers["5.5"] = {"energy_change_ex5": energy_change, "work_ex5": energy_change}
    # h = -m2 l1 l2 sin(q2) / 2 = -2 at q2 = 90 deg; C qd = (h (2 qd1 qd2 + qd2^2), -h qd1^2)
    answers["5.6"] = {"C_qd_ex6": [0.0, 2.0], "reason_ex6": "b"}
    q_up = ik.closed_form(two, [2.6, 0.3], elbow="up").q
    answers["6.1"] = {
        "tau_ex1": two.jacobian(q_up).T
        @ np.diag([600.0, 200.0])
        @ (np.array([3.0, 1.0]) - two.fk(q_up))
    }
    # the tip mass at (3, 1) elbow down, by the 2x2 rules: (J M^-1 J^T)^-1
    q_rest = ik.closed_form(two, [3.0, 1.0]).q
    J, M = two.jacobian(q_rest), two.mass_matrix(q_rest)
    (a, b), (c, d) = J @ np.linalg.inv(M) @ J.T
    Lambda = np.array([[d, -b], [-c, a]]) / (a * d - b * c)
    trace, det = np.trace(Lambda), np.linalg.det(Lambda)
    light, heavy = (trace + np.array([-1.0, 1.0]) * np.sqrt(trace**2 - 4 * det)) / 2
    answers["6.2"] = {
        "Lambda_ex2": Lambda,
        "masses_ex2": [light, heavy],
        "d_c_ex2": 2 * np.sqrt(600.0 * heavy),
        "zeta_light_ex2": np.sqrt(heavy / light),  # 2 sqrt(k heavy) / (2 sqrt(k light))
    }
    import scipy.optimize

    # the boundary where the tip rests exactly 5 mm away, then the next whole N/m up
    boundary = scipy.optimize.brentq(
        lambda k: _sag(k) - 0.005, 600.0, 20000.0, xtol=1e-9
    )
    answers["6.3"] = {"k_ex3": int(np.ceil(boundary))}
    J5 = two.jacobian(np.radians([-20.0, 70.0]))
    answers["6.5"] = {
        "K_joint_ex5": 600.0 * J5.T @ J5,
        "offset_ex5": 300.0 / 600.0 + 300.0 / 1e5,
    }
    answers["6.4"] = {
        "spring_torques": lambda arm, q, p_rest, k: (
            arm.jacobian(q).T @ (k * (np.asarray(p_rest) - arm.fk(q)))
        )
    }
    answers["7.1"] = {
        "rho_two_metre": workspace.largest_inscribed_circle(arms.two_metre_limited)[1]
    }
    radius = float(workspace.clearance(ten, [11.5, 12.0], elbow="up"))
    motion = trajectory.ik_trajectory(
        ten,
        trajectory.CirclePath(
            [11.5, 12.0], 0.999 * radius, duration=3.0, law="quintic"
        ),
        n=60,
        elbow="up",
    )
    answers["7.2"] = {
        "radius_up": radius,
        "largest_step_deg": np.degrees(motion.joint_steps.max()),
    }
    fine = trajectory.ik_trajectory(
        two,
        trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="quintic"),
        n=4001,
    )
    answers["7.3"] = {"max_joint_rate": np.abs(fine.qd).max()}
    answers["7.4"] = {"reachable": _reachable_by_hand}
    # 1 kHz on the 4 s quintic circle: the joints' largest change between samples
    circle = trajectory.CirclePath([12.5, 12.5], 2.0, duration=4.0, law="quintic")
    q_dense = ik.closed_form(ten, circle.sample(4001)[1], elbow="down").q
    answers["7.5"] = {
        "largest_step_ex5": np.abs(np.diff(q_dense, axis=0)).max(),
        "budget_share_ex5": (20 + 6 * 6) / 1000,  # us at the slowest point, of 1 ms
        "reason_ex5": "a",
    }
    return answers


@pytest.fixture(scope="module")
def right():
    return _right_answers()


def _coarse_rate(n):
    motion = trajectory.ik_trajectory(
        arms.two_metre,
        trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="quintic"),
        n=n,
    )
    return float(np.abs(motion.qd).max())


def _loose_spin():
    horizontal = dataclasses.replace(arms.two_metre, g=0.0)
    return simulate(
        horizontal, np.radians([0.0, 90.0]), [2.0, 0.0], 5.0, rtol=1e-6, atol=1e-6
    )  # RK45, loose: drift above 1e-8


def _roundest_osake():
    """The OSAKE arm's roundest elbow angle (rad), exact: cos q2 = -2 l1 l2 / (l1^2 + 2 l2^2)."""
    l1, l2 = arms.osake.l1, arms.osake.l2
    return np.arccos(-2 * l1 * l2 / (l1**2 + 2 * l2**2))


def _kinetic_energy_relative(arm, q, qd):
    """The typical slip: link 2's rotation at its relative rate qd2, not qd1 + qd2."""
    slip = arm.m2 * arm.l2**2 / 12 / 2 * (qd[1] ** 2 - (qd[0] + qd[1]) ** 2)
    return _kinetic_energy(arm, q, qd) + slip


def _exact_peak_rate():
    """The line task's peak |joint rate|, refined between samples (bounded search on t)."""
    import scipy.optimize

    two = arms.two_metre
    path = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="quintic")
    motion = trajectory.ik_trajectory(two, path, n=4001)

    def rate(t):
        p, v = path.at(np.atleast_1d(t))
        q = ik.closed_form(two, p, elbow=motion.elbow).q
        return float(np.abs(two.joint_rates(q, v)).max())

    i = int(np.argmax(np.abs(motion.qd).max(axis=1)))
    best = scipy.optimize.minimize_scalar(
        lambda t: -rate(t),
        bounds=(motion.t[max(i - 1, 0)], motion.t[min(i + 1, len(motion.t) - 1)]),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return -best.fun


#: exercise -> [(what the mistake is, {part: wrong value (a function of the right answers)})]
WRONG = {
    "1.1": [
        (
            "degrees fed to cos/sin",
            {"p_tip_ex1": lambda r: arms.osake.fk([50.0, -30.0])},
        ),
        (
            "q2's sign flipped",
            {"p_tip_ex1": lambda r: arms.osake.fk(np.radians([50.0, 30.0]))},
        ),
        (
            "sin and cos swapped",
            {"p_tip_ex1": lambda r: np.asarray(r["p_tip_ex1"])[::-1]},
        ),
        (
            "l1 and l2 swapped",
            {
                "p_tip_ex1": lambda r: _tip(
                    TwoLinkArm(l1=arms.osake.l2, l2=arms.osake.l1),
                    np.radians([50.0, -30.0]),
                )
            },
        ),
    ],
    "1.2": [
        (
            "A2 @ A1",
            {
                "T_02_ex2": lambda r: (
                    np.linalg.solve(
                        arms.osake.transforms(np.radians([120.0, -45.0]))[0],
                        r["T_02_ex2"],
                    )
                    @ arms.osake.transforms(np.radians([120.0, -45.0]))[0]
                )
            },
        ),
        ("the z axis for the x axis", {"x_axis_ex2": lambda r: r["T_02_ex2"][:3, 2]}),
        (
            "the spacer left out",
            {
                "T_02_ex2": lambda r: arms.osake.transforms(np.radians([120.0, -45.0]))[
                    1
                ],
                "z_tip_ex2": lambda r: arms.osake.d,
            },
        ),
        ("height from the wrong entry", {"z_tip_ex2": lambda r: r["T_02_ex2"][1, 3]}),
        ("a 3x3 rotation for T_02", {"T_02_ex2": lambda r: r["T_02_ex2"][:3, :3]}),
    ],
    "1.3": [
        (
            "to_absolute for to_relative",
            {"q_rel_ex3": lambda r: [np.pi / 3, np.pi / 3 + 5 * np.pi / 6]},
        ),
        ("degrees", {"q_rel_ex3": lambda r: [60.0, 90.0]}),
        (
            "fk of the absolute angles",
            {"p_tip_ex3": lambda r: arms.two_metre.fk(np.radians([60.0, 150.0]))},
        ),
    ],
    "1.4": [
        (
            "links swapped",
            {
                "tip_position": lambda r: (
                    lambda arm, q: _tip(TwoLinkArm(l1=arm.l2, l2=arm.l1), q)
                )
            },
        ),
        (
            "the OSAKE arm's lengths",
            {"tip_position": lambda r: lambda arm, q: _tip(arms.osake, q)},
        ),
        (
            "q2 as absolute",
            {"tip_position": lambda r: lambda arm, q: _tip(arm, to_relative(q))},
        ),
        (
            "q converted to radians again",
            {"tip_position": lambda r: lambda arm, q: _tip(arm, np.radians(q))},
        ),
    ],
    "1.5": [
        (
            "d and a swapped",
            {"dh_ex5": lambda r: [[0.30, 0.05, 0.0], [0.20, 0.0, 0.0]]},
        ),
        ("a twist of 90 deg", {"dh_ex5": lambda r: [[0.05, 0.3, 90], [0, 0.2, 90]]}),
        ("centimetres", {"dh_ex5": lambda r: [[5.0, 30.0, 0.0], [0.0, 20.0, 0.0]]}),
        ("the elbow at height 0", {"o1_ex5": lambda r: [0.0, 0.30, 0.0]}),
        ("the tip for frame 1", {"o1_ex5": lambda r: [0.20, 0.30, 0.05]}),
        ("x1 for x2", {"x2_ex5": lambda r: [0.0, 1.0, 0.0]}),
        ("q2 read as absolute", {"x2_ex5": lambda r: [0.0, -1.0, 0.0]}),
    ],
    "2.1": [
        (
            "the elbow-down branch",
            {
                "q_elbow_up": lambda r: (
                    ik.closed_form(arms.ten, [14.0, 9.0], elbow="down").q
                )
            },
        ),
        ("degrees", {"q_elbow_up": lambda r: np.degrees(r["q_elbow_up"])}),
        (
            "atan for atan2 (q1 off by pi)",
            {"q_elbow_up": lambda r: np.asarray(r["q_elbow_up"]) + [np.pi, 0.0]},
        ),
        ("the elbow-down branch's limits", {"up_within_limits": lambda r: False}),
        ("a string for a bool", {"up_within_limits": lambda r: "yes"}),
    ],
    "2.2": [
        (
            "step left in radians",
            {"step_deg_ex2": lambda r: np.radians(r["step_deg_ex2"])},
        ),
        ("factor 2 missing", {"step_deg_ex2": lambda r: r["step_deg_ex2"] / 2}),
        ("a1 + a2 for a1 + 2 a2", {"step_deg_ex2": lambda r: r["step_deg_ex2"] * 1.5}),
        (
            "the missing +1",
            {
                "grid_points_ex2": lambda r: (
                    np.floor(np.pi / 2 / (0.02 / 30)) * np.floor(np.pi / (0.02 / 30))
                )
            },
        ),
        (
            "the upper ends missed (floor + 1)",
            {
                "grid_points_ex2": lambda r: (
                    (np.floor(np.pi / 2 / (0.02 / 30)) + 1)
                    * (np.floor(np.pi / (0.02 / 30)) + 1)
                )
            },
        ),
        (
            "range / step, not whole",
            {
                "grid_points_ex2": lambda r: (
                    (np.pi / 2 / (0.02 / 30)) * (np.pi / (0.02 / 30))
                )
            },
        ),
    ],
    "2.3": [
        (
            "the error object",
            {"unreachable_message": lambda r: ValueError(r["unreachable_message"])},
        ),
        (
            "another target's message",
            {
                "unreachable_message": lambda r: r["unreachable_message"].replace(
                    "21.9", "22.9"
                )
            },
        ),
        (
            "swapped sign",
            {"distance_beyond_reach": lambda r: -r["distance_beyond_reach"]},
        ),
        (
            "one link's reach",
            {"distance_beyond_reach": lambda r: np.sqrt(481.0) - 10.0},
        ),
    ],
    "2.4": [
        (
            "the elbow-down branch",
            {"elbow_up_angles": lambda r: lambda arm, p: _elbow(arm, p, +1.0)},
        ),
        (
            "atan(y / x) for atan2",
            {
                "elbow_up_angles": lambda r: (
                    lambda arm, p: (
                        r["elbow_up_angles"](arm, p)
                        + [np.arctan(p[1] / p[0]) - np.arctan2(p[1], p[0]), 0.0]
                    )
                )
            },
        ),
        (
            "arms.ten's lengths for every arm",
            {
                "elbow_up_angles": lambda r: (
                    lambda arm, p: r["elbow_up_angles"](arms.ten, p)
                )
            },
        ),
    ],
    "2.5": [
        ("shares of the budget", {"margins_ex5": lambda r: 1 / r["margins_ex5"]}),
        ("every method that fits", {"fit_with_margin_ex5": lambda r: 5}),
        ("fits as measured", {"reason_ex5": lambda r: "a"}),
        ("only a closed form", {"reason_ex5": lambda r: "c"}),
    ],
    "3.1": [
        (
            "J^T v",
            {
                "qd_ex1": lambda r: (
                    _jacobian(arms.two_metre, np.radians([20.0, 70.0])).T @ [0.0, 0.2]
                )
            },
        ),
        ("swapped sign", {"qd_ex1": lambda r: -np.asarray(r["qd_ex1"])}),
        (
            "a J^T v function",
            {
                "joint_rates": lambda r: (
                    lambda arm, q, v_tip: _jacobian(arm, q).T @ v_tip
                )
            },
        ),
        (
            "a function with l1 and l2 swapped",
            {
                "joint_rates": lambda r: (
                    lambda arm, q, v_tip: _solve_rates(
                        TwoLinkArm(l1=arm.l2, l2=arm.l1), q, v_tip
                    )
                )
            },
        ),
        (
            "degrees in J",
            {
                "qd_ex1": lambda r: _solve_rates(
                    arms.two_metre, [20.0, 70.0], [0.0, 0.2]
                )
            },
        ),
    ],
    "3.2": [
        (
            "omega in deg/s",
            {"tip_speed_ex2": lambda r: np.hypot(arms.osake.l1, arms.osake.l2) * 5.0},
        ),
        (
            "l1 + l2 for |p|",
            {
                "tip_speed_ex2": lambda r: (
                    (arms.osake.l1 + arms.osake.l2) * np.radians(5.0)
                )
            },
        ),
        ("mm/s", {"tip_speed_ex2": lambda r: 1000 * r["tip_speed_ex2"]}),
    ],
    "3.3": [
        ("90 deg (largest manipulability)", {"q2_best_deg_ex3": lambda r: 90.0}),
        ("radians", {"q2_best_deg_ex3": lambda r: np.radians(r["q2_best_deg_ex3"])}),
        (
            "the equal-link arm's angle",
            {"q2_best_deg_ex3": lambda r: np.degrees(np.arccos(-2 / 3))},
        ),
        (
            "sigma_min / sigma_max",
            {"cond_best_ex3": lambda r: 1.0 / r["cond_best_ex3"]},
        ),
        ("cond of J J^T", {"cond_best_ex3": lambda r: r["cond_best_ex3"] ** 2}),
        (
            "the condition number at 90 deg",
            {
                "cond_best_ex3": lambda r: np.linalg.cond(
                    arms.osake.jacobian([0.0, np.pi / 2])
                )
            },
        ),
    ],
    "3.4": [
        (
            "both levers from the base",
            {
                "J_geo_ex4": lambda r: np.vstack(
                    [
                        np.repeat(np.asarray(r["J_geo_ex4"])[:, :1], 2, axis=1)[:3],
                        np.asarray(r["J_geo_ex4"])[3:],
                    ]
                )
            },
        ),
        (
            "no angular rows",
            {
                "J_geo_ex4": lambda r: np.vstack(
                    [np.asarray(r["J_geo_ex4"])[:3], np.zeros((3, 2))]
                )
            },
        ),
        (
            "the 2x2 Jacobian only",
            {"J_geo_ex4": lambda r: np.asarray(r["J_geo_ex4"])[:2]},
        ),
    ],
    "3.5": [
        ("cos q2", {"det_J_ex5": lambda r: 0.06 * np.cos(np.radians(30.0))}),
        ("sin(q1 + q2)", {"det_J_ex5": lambda r: 0.06 * np.sin(np.radians(70.0))}),
        ("where det J is largest", {"singular_q2_deg_ex5": lambda r: [-90.0, 90.0]}),
        ("folded in radians", {"singular_q2_deg_ex5": lambda r: [0.0, np.pi]}),
    ],
    "3.6": [
        ("the damped rates for the exact", {"qd_exact_ex6": lambda r: r["qd_dls_ex6"]}),
        ("lambda, not lambda squared", {"qd_dls_ex6": lambda r: _dls(0.1)}),
        ("J^T missing", {"qd_dls_ex6": lambda r: _dls(0.01, transpose=False)}),
    ],
    "4.1": [
        ("F up (swapped sign)", {"tau_ex1": lambda r: -np.asarray(r["tau_ex1"])}),
        (
            "J F for J^T F",
            {
                "tau_ex1": lambda r: (
                    arms.two_metre.jacobian(np.radians([30.0, 60.0])) @ [0.0, -100.0]
                )
            },
        ),
        (
            "degrees",
            {
                "tau_ex1": lambda r: arms.two_metre.joint_torques(
                    [30.0, 60.0], [0.0, -100.0]
                )
            },
        ),
    ],
    "4.2": [
        (
            "the elbow-up branch",
            {
                "q_down_ex2": lambda r: (
                    ik.closed_form(arms.two_metre, [3.0, 1.0], elbow="up").q
                )
            },
        ),
        ("degrees", {"q_down_ex2": lambda r: np.degrees(r["q_down_ex2"])}),
        ("the pull", {"tau_down_ex2": lambda r: -np.asarray(r["tau_down_ex2"])}),
        ("force times reach", {"tau_down_ex2": lambda r: [200.0 * 4.0, 200.0 * 2.0]}),
    ],
    "4.3": [
        (
            "load pushed down",
            {
                "tau_ex3": lambda r: (
                    arms.two_metre.joint_torques(
                        np.radians([30.0, -60.0]), [0.0, -20.0 * 9.81]
                    )
                    + arms.two_metre.gravity(np.radians([30.0, -60.0]))
                )
            },
        ),
        (
            "arm's weight missing",
            {
                "tau_ex3": lambda r: arms.two_metre.joint_torques(
                    np.radians([30.0, -60.0]), [0.0, 20.0 * 9.81]
                )
            },
        ),
        (
            "load in kg, not N (g missing)",
            {
                "tau_ex3": lambda r: (
                    arms.two_metre.joint_torques(np.radians([30.0, -60.0]), [0.0, 20.0])
                    + arms.two_metre.gravity(np.radians([30.0, -60.0]))
                )
            },
        ),
    ],
    "4.4": [
        (
            "the force on the tip",
            {
                "wall_torques": lambda r: (
                    lambda arm, q, force_by_tip: -_moments(arm, q, force_by_tip)
                )
            },
        ),
        (
            "tau2 about the base",
            {
                "wall_torques": lambda r: (
                    lambda arm, q, force_by_tip: _moments(arm, q, force_by_tip)[[0, 0]]
                )
            },
        ),
        (
            "degrees",
            {
                "wall_torques": lambda r: (
                    lambda arm, q, force_by_tip: _moments(
                        arm, np.radians(q), force_by_tip
                    )
                )
            },
        ),
    ],
    "4.5": [
        ("J transposed", {"J_ex5": lambda r: np.transpose(r["J_ex5"])}),
        (
            "the singular values",
            {"force_axes_ex5": lambda r: [np.sqrt(5) + 1, np.sqrt(5) - 1]},
        ),
        ("the shortest first", {"force_axes_ex5": lambda r: r["force_axes_ex5"][::-1]}),
        (
            "1 / lambda",
            {
                "force_axes_ex5": lambda r: [
                    1 / (6 - np.sqrt(20)),
                    1 / (6 + np.sqrt(20)),
                ]
            },
        ),
        ("stronger motors", {"reason_ex5": lambda r: "a"}),
        ("det J largest", {"reason_ex5": lambda r: "c"}),
        ("the right letter in a list", {"reason_ex5": lambda r: ["b"]}),
    ],
    "5.1": [
        ("-g(q)", {"tau_hold_ex1": lambda r: -np.asarray(r["tau_hold_ex1"])}),
        (
            "M^-1 missing",
            {
                "qdd_ex1": lambda r: [
                    0.0,
                    -arms.two_metre.gravity(np.radians([30.0, 45.0]))[1],
                ]
            },
        ),
        (
            "both motors off",
            {
                "qdd_ex1": lambda r: arms.two_metre.forward_dynamics(
                    np.radians([30.0, 45.0]), [0, 0], [0, 0]
                )
            },
        ),
    ],
    "5.2": [
        ("K = -dg/dq", {"K_ex2": lambda r: -np.asarray(r["K_ex2"])}),
        (
            "omega^2 not square-rooted",
            {"omega_ex2": lambda r: np.asarray(r["omega_ex2"]) ** 2},
        ),
        ("descending", {"omega_ex2": lambda r: np.asarray(r["omega_ex2"])[::-1]}),
        (
            "eigenvalues of K alone",
            {
                "omega_ex2": lambda r: np.sort(
                    np.sqrt(np.abs(np.linalg.eigvals(r["K_ex2"])))
                )
            },
        ),
        ("nan from a negative K", {"omega_ex2": lambda r: [np.nan, 1.0]}),
    ],
    "5.3": [
        (
            "loose tolerances (drift too large)",
            {
                "q_end_ex3": lambda r: _loose_spin().q[-1],
                "qd_end_ex3": lambda r: _loose_spin().qd[-1],
            },
        ),
        (
            "the vertical arm",
            {
                "q_end_ex3": lambda r: simulate(
                    arms.two_metre,
                    np.radians([0.0, 90.0]),
                    [2.0, 0.0],
                    5.0,
                    method="DOP853",
                    rtol=1e-10,
                    atol=1e-10,
                ).q[-1]
            },
        ),
        ("end angles in degrees", {"q_end_ex3": lambda r: np.degrees(r["q_end_ex3"])}),
        (
            "start state for the end",
            {
                "q_end_ex3": lambda r: np.radians([0.0, 90.0]),
                "qd_end_ex3": lambda r: [2.0, 0.0],
            },
        ),
        (
            "p1 from the second row",
            {
                "p1_end_ex3": lambda r: (
                    dataclasses.replace(arms.two_metre, g=0.0).mass_matrix(
                        r["q_end_ex3"]
                    )
                    @ r["qd_end_ex3"]
                )[1]
            },
        ),
    ],
    "5.4": [
        (
            "omega2 = qd2 in T",
            {
                "T_ex4": lambda r: _kinetic_energy_relative(
                    arms.two_metre, np.radians([30.0, 45.0]), np.array([1.0, -2.0])
                )
            },
        ),
        (
            "the relative rate in the function",
            {"kinetic_energy": lambda r: _kinetic_energy_relative},
        ),
        (
            "a tuple (T, 0.0)",
            {
                "kinetic_energy": lambda r: (
                    lambda arm, q, qd: (_kinetic_energy(arm, q, qd), 0.0)
                )
            },
        ),
    ],
    "5.5": [
        (
            "V at the end only",
            {"energy_change_ex5": lambda r: _potential_5_5(np.radians([45.0, 60.0]))},
        ),
        ("the sign reversed", {"work_ex5": lambda r: -r["work_ex5"]}),
        ("the flat arm's work", {"work_ex5": lambda r: 0.0}),
    ],
    "5.6": [
        ("h taken positive", {"C_qd_ex6": lambda r: [0.0, -2.0]}),
        ("swapped entries", {"C_qd_ex6": lambda r: [2.0, 0.0]}),
        ("a constant rate", {"reason_ex6": lambda r: "a"}),
        ("zero at 90 deg", {"reason_ex6": lambda r: "c"}),
    ],
    "6.1": [
        (
            "the elbow-down branch",
            {
                "tau_ex1": lambda r: controllers.CartesianSpring(
                    arms.two_metre, np.diag([600.0, 200.0]), np.array([3.0, 1.0])
                ).torque(ik.closed_form(arms.two_metre, [2.6, 0.3]).q)
            },
        ),
        ("F = K (x - x0)", {"tau_ex1": lambda r: -np.asarray(r["tau_ex1"])}),
        (
            "scalar k = 600",
            {
                "tau_ex1": lambda r: controllers.CartesianSpring(
                    arms.two_metre, 600.0, np.array([3.0, 1.0])
                ).torque(ik.closed_form(arms.two_metre, [2.6, 0.3], elbow="up").q)
            },
        ),
    ],
    "6.2": [
        (
            "J M^-1 J^T, not inverted",
            {"Lambda_ex2": lambda r: np.linalg.inv(r["Lambda_ex2"])},
        ),
        ("heavy first", {"masses_ex2": lambda r: r["masses_ex2"][::-1]}),
        (
            "the light direction's d",
            {"d_c_ex2": lambda r: 2 * np.sqrt(600.0 * r["masses_ex2"][0])},
        ),
        ("the factor 2 missing", {"d_c_ex2": lambda r: r["d_c_ex2"] / 2}),
        ("zeta = 1 for both", {"zeta_light_ex2": lambda r: 1.0}),
    ],
    "6.3": [
        ("the source's k = 600", {"k_ex3": lambda r: 600.0}),
        ("the boundary itself, unrounded", {"k_ex3": lambda r: r["k_ex3"] - 0.5}),
        ("rounded down", {"k_ex3": lambda r: r["k_ex3"] - 1}),
        ("ten times too stiff", {"k_ex3": lambda r: 10 * r["k_ex3"]}),
        ("negative", {"k_ex3": lambda r: -r["k_ex3"]}),
    ],
    "6.5": [
        (
            "J K J^T",
            {
                "K_joint_ex5": lambda r: (
                    600.0
                    * (lambda J: J @ J.T)(
                        arms.two_metre.jacobian(np.radians([-20.0, 70.0]))
                    )
                )
            },
        ),
        ("the tip's stiffness", {"K_joint_ex5": lambda r: 600.0 * np.eye(2)}),
        ("the spring's stretch only", {"offset_ex5": lambda r: 0.5}),
    ],
    "6.4": [
        (
            "the sign reversed",
            {
                "spring_torques": lambda r: (
                    lambda arm, q, p_rest, k: (
                        arm.jacobian(q).T @ (k * (arm.fk(q) - np.asarray(p_rest)))
                    )
                )
            },
        ),
        (
            "J for J^T",
            {
                "spring_torques": lambda r: (
                    lambda arm, q, p_rest, k: (
                        arm.jacobian(q) @ (k * (np.asarray(p_rest) - arm.fk(q)))
                    )
                )
            },
        ),
    ],
    "7.1": [
        (
            "degrees in cos/sin",
            {
                "rho_two_metre": lambda r: float(
                    ((2 * np.cos(35)) ** 2 + (4 - 2 * np.sin(35)) ** 2 - 4)
                    / (2 * (4 - 2 * np.sin(35)) + 4)
                )
            },
        ),
        (
            "internal tangency (2 - rho)",
            {
                "rho_two_metre": lambda r: float(
                    (
                        (2 * np.cos(np.radians(35))) ** 2
                        + (4 - 2 * np.sin(np.radians(35))) ** 2
                        - 4
                    )
                    / (2 * (4 - 2 * np.sin(np.radians(35))) - 4)
                )
            },
        ),
        ("the unlimited arm's reach", {"rho_two_metre": lambda r: 2.0}),
    ],
    "7.2": [
        (
            "the outer gap, limits ignored",
            {"radius_up": lambda r: arms.ten.reach[1] - np.hypot(11.5, 12.0)},
        ),
        (
            "the elbow-down room",
            {
                "radius_up": lambda r: float(
                    workspace.clearance(arms.ten, [11.5, 12.0], elbow="down")
                )
            },
        ),
        (
            "the either-branch room",
            {"radius_up": lambda r: float(workspace.clearance(arms.ten, [11.5, 12.0]))},
        ),
        (
            "step in radians",
            {"largest_step_deg": lambda r: np.radians(r["largest_step_deg"])},
        ),
        (
            "61 samples",
            {
                "largest_step_deg": lambda r: np.degrees(
                    trajectory.ik_trajectory(
                        arms.ten,
                        trajectory.CirclePath(
                            [11.5, 12.0],
                            0.999 * r["radius_up"],
                            duration=3.0,
                            law="quintic",
                        ),
                        n=61,
                        elbow="up",
                    ).joint_steps.max()
                )
            },
        ),
    ],
    "7.3": [
        ("too few samples (201)", {"max_joint_rate": lambda r: _coarse_rate(201)}),
        ("too few samples (501)", {"max_joint_rate": lambda r: _coarse_rate(501)}),
        ("deg/s", {"max_joint_rate": lambda r: np.degrees(r["max_joint_rate"])}),
        (
            "the other joint's peak",
            {
                "max_joint_rate": lambda r: float(
                    np.abs(
                        trajectory.ik_trajectory(
                            arms.two_metre,
                            trajectory.LinePath(
                                [-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="quintic"
                            ),
                            n=4001,
                        ).qd
                    )
                    .max(axis=0)
                    .min()
                )
            },
        ),
        (
            "qd.max() without abs",
            {
                "max_joint_rate": lambda r: float(
                    trajectory.ik_trajectory(
                        arms.two_metre,
                        trajectory.LinePath(
                            [-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="quintic"
                        ),
                        n=4001,
                    ).qd.min()
                )
            },
        ),
    ],
    "7.4": [
        (
            "the limits ignored",
            {
                "reachable": lambda r: (
                    lambda arm, p: arm.reach[0] <= np.hypot(*p) <= arm.reach[1]
                )
            },
        ),
        (
            "elbow down only",
            {
                "reachable": lambda r: (
                    lambda arm, p: _reachable_by_hand(arm, p, ("down",))
                )
            },
        ),
        (
            "elbow up only",
            {"reachable": lambda r: lambda arm, p: _reachable_by_hand(arm, p, ("up",))},
        ),
    ],
    "7.5": [
        (
            "in degrees",
            {"largest_step_ex5": lambda r: np.degrees(r["largest_step_ex5"])},
        ),
        ("one iteration only", {"budget_share_ex5": lambda r: 0.026}),
        ("a percentage", {"budget_share_ex5": lambda r: 5.6}),
        ("the points too far apart", {"reason_ex5": lambda r: "b"}),
    ],
}

#: exercise -> [(the form, {part: an equivalent right value})]
EQUIVALENT = {
    "1.1": [
        ("a list", {"p_tip_ex1": lambda r: list(map(float, r["p_tip_ex1"]))}),
        ("a tuple", {"p_tip_ex1": lambda r: tuple(r["p_tip_ex1"])}),
    ],
    "1.2": [
        (
            "nested lists and a list",
            {
                "T_02_ex2": lambda r: np.asarray(r["T_02_ex2"]).tolist(),
                "x_axis_ex2": lambda r: list(r["x_axis_ex2"]),
            },
        ),
        (
            "a 1x1 array for the height",
            {"z_tip_ex2": lambda r: np.array([r["z_tip_ex2"]])},
        ),
    ],
    "1.3": [
        (
            "q1 + 2 pi, q2 - 2 pi",
            {
                "q_rel_ex3": lambda r: (
                    np.asarray(r["q_rel_ex3"]) + [2 * np.pi, -2 * np.pi]
                )
            },
        ),
        ("a tuple", {"p_tip_ex3": lambda r: tuple(r["p_tip_ex3"])}),
    ],
    "1.4": [
        (
            "a tuple returned",
            {"tip_position": lambda r: lambda arm, q: tuple(_tip(arm, q))},
        )
    ],
    "1.5": [
        (
            "3 significant figures, lists and a tuple",
            {
                "dh_ex5": lambda r: [[0.05, 0.3, 0], [0, 0.2, 0]],
                "o1_ex5": lambda r: (0, 0.3, 0.05),
                "x2_ex5": lambda r: np.array([1, 0, 0]),
            },
        )
    ],
    "2.1": [
        (
            "q1 - 2 pi, as a list",
            {
                "q_elbow_up": lambda r: [
                    r["q_elbow_up"][0] - 2 * np.pi,
                    r["q_elbow_up"][1],
                ]
            },
        ),
        ("numpy's bool", {"up_within_limits": lambda r: np.bool_(True)}),
    ],
    "2.2": [
        ("an int count", {"grid_points_ex2": lambda r: int(r["grid_points_ex2"])}),
        (
            "a numpy float step",
            {"step_deg_ex2": lambda r: np.float64(r["step_deg_ex2"])},
        ),
    ],
    "2.3": [
        (
            "trailing newline",
            {"unreachable_message": lambda r: r["unreachable_message"] + "\n"},
        )
    ],
    "2.4": [
        (
            "a list, q1 a whole turn on",
            {
                "elbow_up_angles": lambda r: (
                    lambda arm, p: list(r["elbow_up_angles"](arm, p) + [2 * np.pi, 0.0])
                )
            },
        )
    ],
    "2.5": [
        (
            "a list, and a spaced letter",
            {
                "margins_ex5": lambda r: list(r["margins_ex5"]),
                "reason_ex5": lambda r: " b ",
            },
        ),
        ("a numpy count", {"fit_with_margin_ex5": lambda r: np.int64(4)}),
    ],
    "3.1": [
        ("a list", {"qd_ex1": lambda r: list(r["qd_ex1"])}),
        (
            "a function returning a list",
            {
                "joint_rates": lambda r: (
                    lambda arm, q, v_tip: list(r["joint_rates"](arm, q, v_tip))
                )
            },
        ),
    ],
    "3.2": [
        (
            "a size-one array",
            {"tip_speed_ex2": lambda r: np.array([r["tip_speed_ex2"]])},
        ),
        (
            "to 3 significant figures",
            {"tip_speed_ex2": lambda r: float(f"{r['tip_speed_ex2']:.3g}")},
        ),
    ],
    "3.4": [
        ("nested lists", {"J_geo_ex4": lambda r: np.asarray(r["J_geo_ex4"]).tolist()})
    ],
    "3.5": [
        (
            "3 significant figures, a tuple of ints",
            {"det_J_ex5": lambda r: 0.03, "singular_q2_deg_ex5": lambda r: (0, 180)},
        )
    ],
    "3.6": [
        (
            "the normal equations' form, (J^T J + lambda^2 I)^-1 J^T v, and lists",
            {
                "qd_dls_ex6": lambda r: list(_dls(0.01, normal=True)),
                "qd_exact_ex6": lambda r: list(r["qd_exact_ex6"]),
            },
        )
    ],
    "3.3": [
        (
            "the exact optimum",
            {
                "q2_best_deg_ex3": lambda r: np.degrees(_roundest_osake()),
                "cond_best_ex3": lambda r: np.linalg.cond(
                    arms.osake.jacobian([0.0, _roundest_osake()])
                ),
            },
        ),
    ],
    "4.1": [("a tuple", {"tau_ex1": lambda r: tuple(r["tau_ex1"])})],
    "4.2": [
        (
            "q1 + 2 pi",
            {"q_down_ex2": lambda r: np.asarray(r["q_down_ex2"]) + [2 * np.pi, 0.0]},
        )
    ],
    "4.3": [("a list", {"tau_ex3": lambda r: list(r["tau_ex3"])})],
    "4.4": [
        (
            "a list",
            {
                "wall_torques": lambda r: (
                    lambda arm, q, force_by_tip: list(_moments(arm, q, force_by_tip))
                )
            },
        )
    ],
    "4.5": [
        (
            "3 significant figures",
            {
                "force_axes_ex5": lambda r: [0.809, 0.309],
                "J_ex5": lambda r: [[-2, -2], [2, 0]],
            },
        ),
        ("spaces around the letter", {"reason_ex5": lambda r: " b "}),
    ],
    "5.1": [
        (
            "lists",
            {
                "tau_hold_ex1": lambda r: list(r["tau_hold_ex1"]),
                "qdd_ex1": lambda r: list(r["qdd_ex1"]),
            },
        )
    ],
    "5.2": [
        (
            "K from the symbolic g (exact)",
            {"K_ex2": lambda r: np.asarray(r["K_ex2"]).T},
        ),
        ("a list", {"omega_ex2": lambda r: list(r["omega_ex2"])}),
    ],
    "5.3": [
        (
            "end angles + 2 pi",
            {"q_end_ex3": lambda r: np.asarray(r["q_end_ex3"]) + 2 * np.pi},
        ),
        ("a list of rates", {"qd_end_ex3": lambda r: list(r["qd_end_ex3"])}),
    ],
    "5.4": [
        ("3 significant figures", {"T_ex4": lambda r: float(f"{r['T_ex4']:.3g}")}),
        (
            "a numpy number",
            {
                "kinetic_energy": lambda r: (
                    lambda arm, q, qd: np.float64(_kinetic_energy(arm, q, qd))
                )
            },
        ),
    ],
    "5.5": [
        (
            "3 significant figures",
            {
                "energy_change_ex5": lambda r: float(f"{r['energy_change_ex5']:.3g}"),
                "work_ex5": lambda r: float(f"{r['work_ex5']:.3g}"),
            },
        ),
    ],
    "5.6": [
        (
            "a list, a spaced letter",
            {"C_qd_ex6": lambda r: [0, 2], "reason_ex6": lambda r: " b"},
        )
    ],
    "6.1": [("a list", {"tau_ex1": lambda r: list(r["tau_ex1"])})],
    "6.2": [
        (
            "3 significant figures",
            {
                "masses_ex2": lambda r: [float(f"{m:.3g}") for m in r["masses_ex2"]],
                "d_c_ex2": lambda r: float(f"{r['d_c_ex2']:.3g}"),
                "zeta_light_ex2": lambda r: float(f"{r['zeta_light_ex2']:.3g}"),
            },
        ),
        (
            "Lambda as nested lists",
            {"Lambda_ex2": lambda r: np.asarray(r["Lambda_ex2"]).tolist()},
        ),
    ],
    "6.3": [("a float", {"k_ex3": lambda r: float(r["k_ex3"])})],
    "6.5": [
        (
            "a list, 3 significant figures",
            {
                "K_joint_ex5": lambda r: np.asarray(r["K_joint_ex5"]).tolist(),
                "offset_ex5": lambda r: 0.503,
            },
        )
    ],
    "6.4": [
        (
            "a list",
            {
                "spring_torques": lambda r: (
                    lambda arm, q, p_rest, k: list(
                        r["spring_torques"](arm, q, p_rest, k)
                    )
                )
            },
        )
    ],
    "7.1": [
        ("a numpy float", {"rho_two_metre": lambda r: np.float64(r["rho_two_metre"])})
    ],
    "7.2": [
        (
            "numpy floats",
            {
                "radius_up": lambda r: np.float64(r["radius_up"]),
                "largest_step_deg": lambda r: np.array(r["largest_step_deg"]),
            },
        )
    ],
    "7.3": [("the exact peak", {"max_joint_rate": lambda r: _exact_peak_rate()})],
    "7.4": [
        (
            "numpy's bool",
            {"reachable": lambda r: lambda arm, p: np.bool_(r["reachable"](arm, p))},
        )
    ],
    "7.5": [
        (
            "a numpy float and the letter spaced",
            {
                "largest_step_ex5": lambda r: np.float64(r["largest_step_ex5"]),
                "reason_ex5": lambda r: "a ",
            },
        )
    ],
}


def _apply(right_answers, changes):
    answers = dict(right_answers)
    for name, make in changes.items():
        answers[name] = make(right_answers)
    return answers


#: Each chapter's exercises: (how many, how many parts, the exercises with a function part).
EXERCISE_COUNTS = {
    1: (5, 10, ("1.4",)),
    2: (5, 10, ("2.4",)),
    3: (6, 10, ("3.1",)),
    4: (5, 8, ("4.4",)),
    5: (6, 13, ("5.4",)),
    6: (5, 9, ("6.4",)),
    7: (5, 8, ("7.4",)),
}


def test_every_exercise_has_wrong_and_equivalent_answers():
    for number in NUMBERS:
        assert len(WRONG[number]) >= 2, number
        assert len(EQUIVALENT[number]) >= 1, number
    counts = {
        chapter: (
            len(numbers := [n for n in NUMBERS if n.split(".")[0] == str(chapter)]),
            sum(len(exercises.get(number).parts) for number in numbers),
            tuple(n for n, _ in FUNCTION_PARTS if n in numbers),
        )
        for chapter in EXERCISE_COUNTS
    }
    assert counts == EXERCISE_COUNTS
    assert len(NUMBERS) == sum(count for count, _, _ in EXERCISE_COUNTS.values())


@pytest.mark.parametrize("number", NUMBERS)
def test_right_answers_pass(number, right):
    status, lines = statuses(number, right[number])
    assert set(status.values()) == {"correct"}, lines


@pytest.mark.parametrize("number", NUMBERS)
def test_unsolved_parts_say_not_solved_and_blame_no_sibling(number, right):
    parts = [part.name for part in exercises.get(number).parts]
    status, lines = statuses(number, {name: ... for name in parts})
    assert set(status.values()) == {"not solved yet"}, lines
    assert all("replace the ..." in line for line in lines)
    for missing in parts:  # one part unsolved (None or ...), the others right
        answers = dict(right[number], **{missing: None})
        status, lines = statuses(number, answers)
        assert status[missing] == "not solved yet", lines
        assert all(status[name] == "correct" for name in parts if name != missing), (
            lines
        )


@pytest.mark.parametrize(
    "number, mistake",
    [(n, m) for n in NUMBERS for m in range(len(WRONG[n]))],
    ids=[f"{n}-{WRONG[n][m][0]}" for n in NUMBERS for m in range(len(WRONG[n]))],
)
def test_wrong_answers_are_rejected(number, mistake, right):
    what, changes = WRONG[number][mistake]
    status, lines = statuses(number, _apply(right[number], changes))
    for name in changes:
        assert status[name] == "wrong", f"{number}, {what}: {lines}"
    wrong_lines = [line for line in lines if ": wrong: " in line]
    assert all(
        re.search(r" Hint( \d+ of \d+)?: ", line) and "\n" not in line
        for line in wrong_lines
    )
    assert all("could not use" not in line for line in wrong_lines), (
        lines
    )  # a reason, not a crash


@pytest.mark.parametrize(
    "number, form",
    [(n, m) for n in NUMBERS for m in range(len(EQUIVALENT[n]))],
    ids=[
        f"{n}-{EQUIVALENT[n][m][0]}" for n in NUMBERS for m in range(len(EQUIVALENT[n]))
    ],
)
def test_equivalent_forms_are_accepted(number, form, right):
    what, changes = EQUIVALENT[number][form]
    status, lines = statuses(number, _apply(right[number], changes))
    assert set(status.values()) == {"correct"}, f"{number}, {what}: {lines}"


def test_references_are_computed_by_the_package():
    # the test's closed forms agree with the numerical tools they stand in for
    q2 = np.radians(np.linspace(1.0, 179.0, 3561))
    cond = np.linalg.cond(
        arms.osake.jacobian(np.stack([np.zeros_like(q2), q2], axis=-1))
    )
    assert abs(np.degrees(q2[np.argmin(cond)] - _roundest_osake())) < 0.05
    # the table's arm (compsys726) has the equal-link arm's condition-number curve,
    # so "the equal-link arm's angle" of 3.3 is also the table arm's
    table = TwoLinkArm(l1=compsys726.A1 / 100, l2=compsys726.A2 / 100)
    equal = TwoLinkArm(l1=1.0, l2=1.0)
    for arm in (table, equal):
        curve = np.linalg.cond(arm.jacobian(np.stack([np.zeros_like(q2), q2], -1)))
        assert (
            abs(np.degrees(q2[np.argmin(curve)]) - np.degrees(np.arccos(-2 / 3))) < 0.05
        )
    c, s = np.cos(np.radians(35.0)), np.sin(np.radians(35.0))
    rho = ((2 * c) ** 2 + (4 - 2 * s) ** 2 - 4) / (2 * (4 - 2 * s) + 4)
    assert np.isclose(
        rho,
        workspace.largest_inscribed_circle(arms.two_metre_limited)[1],
        atol=1e-6,
    )  # the closed form the 7.1 mistakes of WRONG vary
    K = _hanging_stiffness()
    q_hang, h = np.radians([-90.0, 0.0]), 1e-6
    central = np.column_stack(
        [
            (
                arms.two_metre.gravity(q_hang + h * e)
                - arms.two_metre.gravity(q_hang - h * e)
            )
            / (2 * h)
            for e in np.eye(2)
        ]
    )
    assert np.allclose(K, central, atol=1e-6)
    rng = np.random.default_rng(HIDDEN_TEST_SEED)
    for _ in range(
        5
    ):  # the hand-written T is arm.energy's, on arms and states drawn here
        arm = TwoLinkArm(*rng.uniform(0.3, 3.0, 2), *rng.uniform(0.2, 5.0, 2))
        q, qd = rng.uniform(-np.pi, np.pi, 2), rng.uniform(-3.0, 3.0, 2)
        assert np.isclose(_kinetic_energy(arm, q, qd), arm.energy(q, qd)[0])
    assert _exact_peak_rate() >= _coarse_rate(4001)
    assert abs(_sag(600.0)) > 0.005  # the source's spring sags more than 5 mm
    for number in NUMBERS:  # no check cell needs a reference: every part is specified
        for part in exercises.get(number).parts:
            assert isinstance(part, exercises.spec.PartSpec)
            assert part.name.isidentifier()
            assert len(part.hints) >= 2, (number, part.name)
            if part.kind == "function":
                assert part.output is not None and len(part.cases) >= 3
                assert len(part.mistakes) >= 2, (number, part.name)


# ------------------------------------------------------------- the notebooks' own solutions

NOTEBOOKS = {
    path.name[:2]: path
    for path in sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
}


def _check_cells(cells):
    return [
        (index, "".join(cell["source"]))
        for index, cell in enumerate(cells)
        if cell["cell_type"] == "code" and "selfcheck." in "".join(cell["source"])
    ]


@pytest.mark.parametrize(
    "chapter", sorted(NOTEBOOKS), ids=[NOTEBOOKS[c].name for c in sorted(NOTEBOOKS)]
)
def test_check_cells_hold_no_reference(chapter):
    """Each check cell is one ``selfcheck.check("N.M", answer, ...)`` on the answers' names, nothing computed."""
    path = NOTEBOOKS[chapter]
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    checked = []
    for index, source in _check_cells(cells):
        # the hidden score line nbgrader reads (tools/nbgrader_cells.py) aside
        source = editions.strip_hidden_tests(source)
        tree = ast.parse(source)
        assert len(tree.body) == 1, (
            f"{path.name} cell {index}: a check cell is one call, got:\n{source}"
        )
        statement = tree.body[0]
        call = (
            statement.value if isinstance(statement, (ast.Assign, ast.Expr)) else None
        )
        assert (
            isinstance(call, ast.Call) and ast.unparse(call.func) == "selfcheck.check"
        ), f"{path.name} cell {index}: {source}"
        if isinstance(statement, ast.Expr):
            assert source.rstrip().endswith(";"), (
                f"{path.name} cell {index}: end the check with ; (no stray output)"
            )
        number, *answers = call.args
        assert isinstance(number, ast.Constant) and number.value in NUMBERS, (
            f"{path.name} cell {index}: {source}"
        )
        assert (
            all(isinstance(answer, ast.Name) for answer in answers)
            and not call.keywords
        ), (
            f"{path.name} cell {index}: the check passes the answers' names only, nothing computed: {source}"
        )
        assert [answer.id for answer in answers] == [
            part.name for part in exercises.get(number.value).parts
        ], f"{path.name} cell {index}: exercise {number.value}'s parts in order"
        checked.append(number.value)
    chapter_numbers = [n for n in NUMBERS if n.split(".")[0] == str(int(chapter))]
    assert checked == chapter_numbers, (
        f"{path.name} checks {checked}, its exercises are {chapter_numbers}"
    )


# ------------------------------------------------------------- value exercises graded on hidden inputs

#: Every value exercise re-run on hidden inputs: its chapter module's RERUN entry (answers/chN.py).
RERUNS = [
    (number, rerun)
    for name in answers.chapter_names()
    for number, rerun in getattr(answers.chapter(name), "RERUN", {}).items()
]


# The exercise's cells run here, outside nbval's run of the chapter: the solution cell and
# the cells it reads (its backward slice), with inputs the notebook never holds.
SETUP_NAMES = set(dir(builtins))


def _cell_names(source):
    tree = ast.parse(source)
    stored, loaded = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            (stored if isinstance(node.ctx, ast.Store) else loaded).add(node.id)
        elif isinstance(node, (ast.FunctionDef, ast.ClassDef, ast.AsyncFunctionDef)):
            stored.add(node.name)
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            stored.update(
                (alias.asname or alias.name).split(".")[0] for alias in node.names
            )
        elif isinstance(node, ast.arg):
            stored.add(node.arg)
    return stored, loaded


def _exercise_cells(number):
    path = NOTEBOOKS[f"0{number.split('.')[0]}"]
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    for index, cell in enumerate(cells):
        source = "".join(cell["source"])
        if (
            cell["cell_type"] == "code"
            and source.startswith(f"# Exercise {number}")
            and editions.BEGIN in source
        ):
            return path, cells, index
    raise AssertionError(
        f"{path.name} has no solution cell starting '# Exercise {number}'"
    )


def _backward_slice(cells, index):
    """The code cells before ``cells[index]`` that define what it (transitively) reads, in order.

    A name ``cells[index]`` binds itself (a solution's own variables) is not
    looked for before it: were it read before it is bound, the run here fails
    with a NameError instead of taking the chapter's value of that name.
    """
    bound, needed = _cell_names("".join(cells[index]["source"]))
    needed -= SETUP_NAMES | bound
    chosen = []
    for cell in reversed(cells[:index]):
        if cell["cell_type"] != "code":
            continue
        source = TransformerManager().transform_cell(
            "".join(cell["source"])
        )  # IPython syntax (%pip) as Python
        if source.lstrip().startswith(("%", "!", "get_ipython()")):
            continue
        stored, loaded = _cell_names(source)
        if stored & needed:
            chosen.append(source)
            needed = (needed - stored) | (loaded - SETUP_NAMES)
    return chosen[::-1]


def _run(sources, namespace):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cwd = os.getcwd()
    os.chdir(ROOT / "notebooks")
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            for source in sources:
                exec(compile(source, "<notebook cell>", "exec"), namespace)  # noqa: S102
    finally:
        os.chdir(cwd)
        plt.close("all")


def _inputs_cell(cells, index):
    """The cell right before the solution cell, which must be the exercise's inputs cell."""
    cell = cells[index - 1]
    assert cell["cell_type"] == "code"
    return "".join(cell["source"])


def _same(a, b):
    if isinstance(a, TwoLinkArm) or isinstance(b, TwoLinkArm):
        return a == b
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    return np.allclose(
        np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=0, atol=0
    )


@pytest.mark.parametrize("number, rerun", RERUNS, ids=[n for n, _ in RERUNS])
def test_the_inputs_cell_binds_exactly_the_rerun_inputs(number, rerun):
    _, cells, index = _exercise_cells(number)
    source = _inputs_cell(cells, index)
    first, *lines = source.splitlines()
    assert first == f"# Inputs of exercise {number}"
    tree = ast.parse("\n".join(lines))
    assert all(
        isinstance(node, ast.Assign)
        and len(node.targets) == 1
        and isinstance(node.targets[0], ast.Name)
        for node in tree.body
    ), f"exercise {number}: the inputs cell holds only assignments name = expression"
    bound = [node.targets[0].id for node in tree.body]
    assert bound == list(rerun.inputs), (bound, list(rerun.inputs))
    namespace = {}
    _run(_backward_slice(cells, index - 1), namespace)
    _run([source], namespace)
    for name, value in rerun.inputs.items():
        assert _same(namespace[name], value), (number, name)


@pytest.mark.parametrize("number, rerun", RERUNS, ids=[n for n, _ in RERUNS])
def test_the_solution_computes_from_the_inputs_on_hidden_ones(number, rerun):
    # the worked solution, run on inputs the notebook never holds, gives the references
    _, cells, index = _exercise_cells(number)
    solution = "".join(cells[index]["source"])
    parts = {part.name for part in exercises.get(number).parts}
    visible = rerun.answers(rerun.inputs)
    assert set(visible) <= parts and visible
    status, lines = statuses(
        number,
        {
            name: visible.get(name, ...)
            for name in (p.name for p in exercises.get(number).parts)
        },
    )
    assert all(status[name] == "correct" for name in visible), lines
    setup = {}
    _run(_backward_slice(cells, index), setup)  # the chapter's cells the solution needs
    by_name = {part.name: part for part in exercises.get(number).parts}
    for seed in range(3):
        hidden = rerun.hidden(np.random.default_rng(HIDDEN_TEST_SEED + seed))
        assert hidden.keys() == rerun.inputs.keys()
        namespace = dict(setup, **hidden)
        _run([solution], namespace)
        for name, expected in rerun.answers(hidden).items():
            # judged as the visible answer is, with the hidden reference in its place
            part = dataclasses.replace(by_name[name], expected=expected, mistakes=())
            verdict = judging.judge(part, namespace[name])
            assert verdict.right, (number, name, seed, verdict.message)


# ------------------------------------------------------------- function exercises' rules

#: Every function part's forbidden calls: its chapter module's FORBIDDEN entry.
FORBIDDEN = [
    (number, part, paths)
    for name in answers.chapter_names()
    for (number, part), paths in getattr(answers.chapter(name), "FORBIDDEN", {}).items()
]


def _resolve(dotted):
    """The object a dotted import path names (a module's function or a class's method)."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            found = importlib.import_module(".".join(parts[:cut]))
        except ModuleNotFoundError:
            continue
        for attribute in parts[cut:]:
            found = getattr(found, attribute)
        return found
    raise AssertionError(f"{dotted} names no module")


@pytest.mark.parametrize(
    "number, part, paths",
    FORBIDDEN,
    ids=[f"{n}-{p}" for n, p, _ in FORBIDDEN],
)
def test_forbidden_calls_exist_and_the_exercise_states_its_rules(number, part, paths):
    assert part in {p.name for p in exercises.get(number).parts}
    for dotted in paths:
        assert callable(_resolve(dotted)), dotted
    _, cells, index = _exercise_cells(number)
    text = " ".join(
        "".join(cell["source"])
        for cell in cells[:index]
        if cell["cell_type"] == "markdown"
        and f"**Exercise {number}" in "".join(cell["source"])
    )
    assert "**Rules:**" in text and "switched off" in text, number
    spec = next(p for p in exercises.get(number).parts if p.name == part)
    for argument in spec.cases[0].arguments:
        assert f"`{argument}`" in text, (
            number,
            argument,
        )  # the parameter names, as given
    called = {dotted.rsplit(".", 1)[-1] for dotted in paths}
    assert any(f"{name}`" in text for name in called), number
