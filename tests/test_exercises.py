"""The exercises (twolink.exercises) through their self-checks, tested.

For every exercise:

- the worked solution passes: the solution cell is taken from the notebook and
  run after the earlier cells it needs (a backward slice of the chapter), so
  the notebook and its check cannot drift apart;
- the student edition's stub reports "not solved yet" for every part;
- the wrong answers of ``WRONG`` (the table of plausible mistakes) are rejected,
  each with the other parts still passing (no part blames a sibling);
- the equivalent forms of ``EQUIVALENT`` are accepted;
- a part left unsolved makes no sibling fail.
"""

import ast
import builtins
import contextlib
import dataclasses
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
    arms,
    controllers,
    exercises,
    ik,
    linearization,
    selfcheck,
    simulate,
    trajectory,
    workspace,
)
from twolink.exercises import ch3, ch5, ch6, ch7, judging
from twolink.sources import compsys726

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT))
import editions  # noqa: E402

import answers  # noqa: E402

#: A seed the notebooks never hold (the grader has its own).
HIDDEN_TEST_SEED = 5_318_008

NUMBERS = [exercise.number for exercise in exercises.all_exercises()]


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


def _right_answers():
    two, ten, osake = arms.two_metre, arms.ten, arms.osake
    answers = {}
    q = np.radians([45.0, -30.0])
    answers["1.1"] = {
        "p_tip_ex1": [
            osake.l1 * np.cos(q[0]) + osake.l2 * np.cos(q.sum()),
            osake.l1 * np.sin(q[0]) + osake.l2 * np.sin(q.sum()),
        ]
    }
    T = osake.transforms(np.radians([120.0, -45.0]))[1]
    answers["1.2"] = {"T_02_ex2": T, "z_tip_ex2": T[2, 3], "z_axis_ex2": T[:3, 2]}
    q_abs = np.radians([60.0, 150.0])
    answers["1.3"] = {
        "q_rel_ex3": [q_abs[0], q_abs[1] - q_abs[0]],
        "p_tip_ex3": two.l1 * np.array([np.cos(q_abs[0]), np.sin(q_abs[0])])
        + two.l2 * np.array([np.cos(q_abs[1]), np.sin(q_abs[1])]),
    }
    answers["2.1"] = {
        "q_elbow_up": ik.closed_form(ten, [12.0, 4.0], elbow="up").q,
        "up_within_limits": False,
    }
    step = 2 * 0.01 / 30.0
    answers["2.2"] = {
        "step_1cm_deg": np.degrees(step),
        "grid_points_1cm": (np.ceil(np.pi / 2 / step) + 1)
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
    answers["3.1"] = {
        "qd_ex1": np.linalg.solve(two.jacobian(np.radians([20.0, 70.0])), [0.0, 0.2])
    }
    answers["3.2"] = {"tip_speed_ex2": np.hypot(osake.l1, osake.l2) * np.radians(5.0)}
    arm_line = ch3.arm_3_3()
    q2_grid = np.radians(np.arange(0.5, 180.0, 0.5))
    cond = np.linalg.cond(
        arm_line.jacobian(np.stack([np.zeros_like(q2_grid), q2_grid], -1))
    )
    answers["3.3"] = {
        "q2_best_deg_ex3": np.degrees(q2_grid[np.argmin(cond)]),
        "cond_best_ex3": cond.min(),
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
    q51 = np.radians([30.0, 45.0])
    answers["5.1"] = {
        "tau_hold_ex1": two.inverse_dynamics(q51, [0.0, 0.0], [0.0, 0.0]),
        "qdd_ex1": np.linalg.solve(two.mass_matrix(q51), [0.0, -two.gravity(q51)[1]]),
    }
    K = ch5.stiffness_5_2()
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
    answers["5.3"] = {
        "spin_ex3": spin,
        "q_end_ex3": spin.q[-1],
        "qd_end_ex3": spin.qd[-1],
        "drift_ex3": spin.energy_drift(),
        "p1_end_ex3": (horizontal.mass_matrix(spin.q[-1]) @ spin.qd[-1])[0],
    }
    q_up = ik.closed_form(two, [3.0, 0.5], elbow="up").q
    answers["6.1"] = {
        "tau_ex1": two.jacobian(q_up).T
        @ np.diag([600.0, 200.0])
        @ (np.array([3.0, 1.0]) - two.fk(q_up))
    }
    q_rest = ik.closed_form(two, [3.0, 1.0]).q
    Lambda = linearization.tip_mass(two, q_rest)
    w, V = np.linalg.eigh(Lambda)
    D = (
        2.0 * np.sqrt(600.0) * (V * np.sqrt(w)) @ V.T
    )  # 2 Lambda^1/2 (k Lambda^-1)^1/2 Lambda^1/2 = 2 sqrt(k) Lambda^1/2
    control = pytest.importorskip("control")
    loop = linearization.linearize(
        two,
        controllers.Impedance(two, 600.0, (D + D.T) / 2, np.array([3.0, 1.0])),
        q_rest,
    )
    answers["6.2"] = {
        "D_ex2": D,
        "poles_ex2": control.poles(loop),
        "zeta_ex2": control.damp(loop, doprint=False)[1],
    }
    import scipy.optimize

    answers["6.3"] = {
        "k_ex3": scipy.optimize.brentq(
            lambda k: ch6.sag_6_3(k) - 0.005, 600.0, 20000.0, xtol=1e-6
        )
    }
    answers["7.1"] = {
        "rho_two_metre": workspace.largest_inscribed_circle(arms.two_metre_limited)[1]
    }
    radius = float(workspace.clearance(ten, [14.0, 6.0], elbow="up"))
    motion = trajectory.ik_trajectory(
        ten,
        trajectory.CirclePath([14.0, 6.0], 0.999 * radius, duration=3.0, law="quintic"),
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


def _scalar_damping_poles():
    control = pytest.importorskip("control")
    q_rest = ik.closed_form(arms.two_metre, [3.0, 1.0]).q
    d = linearization.critical_damping(arms.two_metre, q_rest, 600.0)
    return control.poles(
        linearization.linearize(
            arms.two_metre,
            controllers.Impedance(arms.two_metre, 600.0, d, np.array([3.0, 1.0])),
            q_rest,
        )
    )


#: exercise -> [(what the mistake is, {part: wrong value (a function of the right answers)})]
WRONG = {
    "1.1": [
        (
            "degrees fed to cos/sin",
            {"p_tip_ex1": lambda r: arms.osake.fk([45.0, -30.0])},
        ),
        (
            "sin and cos swapped",
            {"p_tip_ex1": lambda r: np.asarray(r["p_tip_ex1"])[::-1]},
        ),
        (
            "l1 and l2 swapped",
            {
                "p_tip_ex1": lambda r: [
                    arms.osake.l2 * np.cos(np.pi / 4)
                    + arms.osake.l1 * np.cos(np.pi / 12),
                    arms.osake.l2 * np.sin(np.pi / 4)
                    + arms.osake.l1 * np.sin(np.pi / 12),
                ]
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
        ("the x axis for the z axis", {"z_axis_ex2": lambda r: r["T_02_ex2"][:3, 0]}),
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
    "2.1": [
        (
            "the elbow-down branch",
            {
                "q_elbow_up": lambda r: (
                    ik.closed_form(arms.ten, [12.0, 4.0], elbow="down").q
                )
            },
        ),
        ("degrees", {"q_elbow_up": lambda r: np.degrees(r["q_elbow_up"])}),
        (
            "atan for atan2 (q1 off by pi)",
            {"q_elbow_up": lambda r: np.asarray(r["q_elbow_up"]) + [np.pi, 0.0]},
        ),
        ("within limits claimed", {"up_within_limits": lambda r: True}),
        ("a string for a bool", {"up_within_limits": lambda r: "no"}),
    ],
    "2.2": [
        (
            "step left in radians",
            {"step_1cm_deg": lambda r: np.radians(r["step_1cm_deg"])},
        ),
        ("factor 2 missing", {"step_1cm_deg": lambda r: r["step_1cm_deg"] / 2}),
        ("a1 + a2 for a1 + 2 a2", {"step_1cm_deg": lambda r: r["step_1cm_deg"] * 1.5}),
        (
            "the missing +1",
            {
                "grid_points_1cm": lambda r: (
                    np.floor(np.pi / 2 / (0.02 / 30)) * np.floor(np.pi / (0.02 / 30))
                )
            },
        ),
        (
            "the upper ends missed (floor + 1)",
            {
                "grid_points_1cm": lambda r: (
                    (np.floor(np.pi / 2 / (0.02 / 30)) + 1)
                    * (np.floor(np.pi / (0.02 / 30)) + 1)
                )
            },
        ),
        (
            "range / step, not whole",
            {
                "grid_points_1cm": lambda r: (
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
    "3.1": [
        (
            "J^T v",
            {
                "qd_ex1": lambda r: (
                    arms.two_metre.jacobian(np.radians([20.0, 70.0])).T @ [0.0, 0.2]
                )
            },
        ),
        ("swapped sign", {"qd_ex1": lambda r: -np.asarray(r["qd_ex1"])}),
        (
            "degrees in J",
            {
                "qd_ex1": lambda r: np.linalg.solve(
                    arms.two_metre.jacobian([20.0, 70.0]), [0.0, 0.2]
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
        ("a 2 deg grid's answer", {"q2_best_deg_ex3": lambda r: 132.9}),
        (
            "sigma_min / sigma_max",
            {"cond_best_ex3": lambda r: 1.0 / r["cond_best_ex3"]},
        ),
        ("cond of J J^T", {"cond_best_ex3": lambda r: r["cond_best_ex3"] ** 2}),
        (
            "the condition number at 90 deg",
            {"cond_best_ex3": lambda r: float(ch3.condition_3_3(np.pi / 2)[0])},
        ),
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
        ("loose tolerances (drift too large)", {"spin_ex3": lambda r: _loose_spin()}),
        ("made-up drift", {"drift_ex3": lambda r: 5e-9}),
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
        ("a number for the simulation", {"spin_ex3": lambda r: 1e-9}),
    ],
    "6.1": [
        (
            "the elbow-down branch",
            {
                "tau_ex1": lambda r: controllers.CartesianSpring(
                    arms.two_metre, np.diag([600.0, 200.0]), np.array([3.0, 1.0])
                ).torque(ik.closed_form(arms.two_metre, [3.0, 0.5]).q)
            },
        ),
        ("F = K (x - x0)", {"tau_ex1": lambda r: -np.asarray(r["tau_ex1"])}),
        (
            "scalar k = 600",
            {
                "tau_ex1": lambda r: controllers.CartesianSpring(
                    arms.two_metre, 600.0, np.array([3.0, 1.0])
                ).torque(ik.closed_form(arms.two_metre, [3.0, 0.5], elbow="up").q)
            },
        ),
    ],
    "6.2": [
        (
            "scalar critical damping times I",
            {
                "D_ex2": lambda r: (
                    linearization.critical_damping(
                        arms.two_metre,
                        ik.closed_form(arms.two_metre, [3.0, 1.0]).q,
                        600.0,
                    )
                    * np.eye(2)
                )
            },
        ),
        (
            "poles of the scalar damping",
            {"poles_ex2": lambda r: _scalar_damping_poles()},
        ),
        (
            "the undamped loop's poles",
            {"poles_ex2": lambda r: 1j * np.asarray(r["poles_ex2"]).real},
        ),
        (
            "two poles only",
            {"poles_ex2": lambda r: np.unique(np.round(np.real(r["poles_ex2"]), 6))},
        ),
        ("wn for zeta", {"zeta_ex2": lambda r: np.abs(r["poles_ex2"])}),
    ],
    "6.3": [
        ("the source's k = 600", {"k_ex3": lambda r: 600.0}),
        ("ten times too stiff", {"k_ex3": lambda r: 10 * r["k_ex3"]}),
        ("for a 5 cm sag", {"k_ex3": lambda r: r["k_ex3"] / 10}),
        ("negative", {"k_ex3": lambda r: -r["k_ex3"]}),
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
            {"radius_up": lambda r: arms.ten.reach[1] - np.hypot(14.0, 6.0)},
        ),
        (
            "the elbow-down room",
            {
                "radius_up": lambda r: float(
                    workspace.clearance(arms.ten, [14.0, 6.0], elbow="down")
                )
            },
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
                            [14.0, 6.0],
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
                "z_axis_ex2": lambda r: list(r["z_axis_ex2"]),
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
        ("numpy's bool", {"up_within_limits": lambda r: np.bool_(False)}),
    ],
    "2.2": [
        ("an int count", {"grid_points_1cm": lambda r: int(r["grid_points_1cm"])}),
        (
            "a numpy float step",
            {"step_1cm_deg": lambda r: np.float64(r["step_1cm_deg"])},
        ),
    ],
    "2.3": [
        (
            "trailing newline",
            {"unreachable_message": lambda r: r["unreachable_message"] + "\n"},
        )
    ],
    "3.1": [("a list", {"qd_ex1": lambda r: list(r["qd_ex1"])})],
    "3.2": [
        (
            "a size-one array",
            {"tip_speed_ex2": lambda r: np.array([r["tip_speed_ex2"]])},
        )
    ],
    "3.3": [
        (
            "the mirror elbow (-q2)",
            {"q2_best_deg_ex3": lambda r: -r["q2_best_deg_ex3"]},
        ),
        (
            "the exact optimum",
            {
                "q2_best_deg_ex3": lambda r: np.degrees(np.arccos(-2 / 3)),
                "cond_best_ex3": lambda r: (1 + np.sqrt(5)) / 2,
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
    "6.1": [("a list", {"tau_ex1": lambda r: list(r["tau_ex1"])})],
    "6.2": [
        (
            "poles as real numbers, any order",
            {"poles_ex2": lambda r: np.real(r["poles_ex2"])[::-1].tolist()},
        ),
        (
            "the symmetrised D",
            {
                "D_ex2": lambda r: (
                    (np.asarray(r["D_ex2"]) + np.asarray(r["D_ex2"]).T) / 2
                )
            },
        ),
    ],
    "6.3": [
        ("slightly stiffer than the smallest", {"k_ex3": lambda r: 1.002 * r["k_ex3"]})
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
    "7.3": [("the exact peak", {"max_joint_rate": lambda r: ch7.peak_rate_7_3()})],
}


def _apply(right_answers, changes):
    answers = dict(right_answers)
    for name, make in changes.items():
        answers[name] = make(right_answers)
    return answers


def test_every_exercise_has_wrong_and_equivalent_answers():
    assert len(NUMBERS) == 21
    for number in NUMBERS:
        assert len(WRONG[number]) >= 2, number
        assert len(EQUIVALENT[number]) >= 1, number
    assert sum(len(exercises.get(number).parts) for number in NUMBERS) >= 37


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
    # the closed forms agree with the numerical tools they stand in for
    q2 = np.radians(np.linspace(1.0, 179.0, 3561))
    assert (
        abs(
            np.degrees(q2[np.argmin(ch3.condition_3_3(q2))])
            - np.degrees(ch3.roundest_3_3())
        )
        < 0.05
    )
    assert np.isclose(
        ch7.radius_7_1(),
        workspace.largest_inscribed_circle(arms.two_metre_limited)[1],
        atol=1e-6,
    )
    arm_line = ch3.arm_3_3()
    assert (arm_line.l1, arm_line.l2) == (compsys726.A1 / 100, compsys726.A2 / 100)
    for (
        number
    ) in NUMBERS:  # no check cell needs a reference: every part has a judge and a hint
        for part in exercises.get(number).parts:
            assert part.name.isidentifier()
            if isinstance(
                part, exercises.spec.PartSpec
            ):  # judged from its stored specification
                assert len(part.hints) >= 2
            else:
                assert callable(part.judge) and part.hint


# ------------------------------------------------------------- the notebooks' own solutions

NOTEBOOKS = {
    path.name[:2]: path for path in sorted((ROOT / "notebooks").glob("*.ipynb"))
}
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
    """The code cells before ``cells[index]`` that define what it (transitively) reads, in order."""
    _, needed = _cell_names("".join(cells[index]["source"]))
    needed -= SETUP_NAMES
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
                exec(compile(source, "<notebook cell>", "exec"), namespace)
    finally:
        os.chdir(cwd)
        plt.close("all")


@pytest.mark.parametrize("number", NUMBERS)
def test_notebook_solution_passes_and_its_stub_is_not_solved(number):
    path, cells, index = _exercise_cells(number)
    namespace = {}
    try:
        _run(_backward_slice(cells, index), namespace)
    except Exception as error:  # pragma: no cover - reported with the chapter's name
        pytest.fail(
            f"{path.name}: the cells exercise {number} needs raise {type(error).__name__}: {error}"
        )
    setup = dict(namespace)
    solution = "".join(cells[index]["source"])
    _run([solution], namespace)
    parts = [part.name for part in exercises.get(number).parts]
    missing = [name for name in parts if name not in namespace]
    assert not missing, (
        f"{path.name}: the solution of exercise {number} does not set {missing}"
    )
    status, lines = statuses(number, {name: namespace[name] for name in parts})
    assert set(status.values()) == {"correct"}, lines
    stub = editions.stub_source(solution, set(parts))
    assert editions.BEGIN not in stub
    student = dict(setup)
    _run([stub], student)
    status, lines = statuses(number, {name: student.get(name, ...) for name in parts})
    assert set(status.values()) == {"not solved yet"}, lines


FUNCTION_PARTS = [
    (number, part.name)
    for number in NUMBERS
    for part in exercises.get(number).parts
    if getattr(part, "kind", None) == "function"
]


@pytest.mark.parametrize(
    "number, name", FUNCTION_PARTS, ids=[f"{n}-{p}" for n, p in FUNCTION_PARTS]
)
def test_the_notebook_solution_function_passes_hidden_cases(number, name):
    # graded on inputs the notebook never holds: a seed only the grader (here, the test) has
    path, cells, index = _exercise_cells(number)
    namespace = {}
    _run(_backward_slice(cells, index), namespace)
    _run(["".join(cells[index]["source"])], namespace)
    part = next(part for part in exercises.get(number).parts if part.name == name)
    hidden = answers.hidden_cases(number, name, seed=HIDDEN_TEST_SEED)
    verdict = judging.judge_function(part, namespace[name], hidden)
    assert verdict.right, f"{path.name} exercise {number}: {verdict.message}"


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
