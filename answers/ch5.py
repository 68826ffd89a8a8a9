"""Chapter 5 (Lagrangian dynamics): the references of exercises 5.1 to 5.6, with typical mistakes and hints.

Exercises 5.1, 5.2, 5.3 and 5.5 are graded on hidden inputs too (``RERUN``);
5.4's function on hidden cases (``HIDDEN``) with ``arm.energy`` and
``arm.mass_matrix`` switched off (``FORBIDDEN``); 5.4's hand value and 5.6 are
worked on paper and checked on their own numbers (``PEN_AND_PAPER``).
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np
from numpy.typing import NDArray

from answers import Rerun
from twolink import TwoLinkArm, arms, simulate, trajectory
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "05_lagrangian_dynamics"
Q_5_1_DEG = (30.0, 45.0)
Q_HANG_5_2_DEG = (-90.0, 0.0)
Q0_5_3_DEG, QD0_5_3, DURATION_5_3 = (0.0, 90.0), (2.0, 0.0), 5.0
Q_5_4_DEG, QD_5_4 = (30.0, 45.0), (1.0, -2.0)
Q_FROM_5_5_DEG, Q_TO_5_5_DEG, DURATION_5_5, SAMPLES_5_5 = (
    (-90.0, 0.0),
    (45.0, 60.0),
    2.0,
    2001,
)
Q_5_6_DEG, QD_5_6 = (0.0, 90.0), (1.0, 0.0)
TORQUES = ("tau1", "tau2")
#: the visible calls of kinetic_energy(arm, q, qd): (arm, q in degrees, qd in rad/s)
CASES_5_4 = (
    ({"l1": 2.0, "l2": 2.0}, (30.0, 45.0), (1.0, -2.0)),
    ({"l1": 1.0, "l2": 0.5, "m1": 2.0, "m2": 0.5}, (0.0, 90.0), (0.5, 1.5)),
    ({"l1": 1.5, "l2": 1.0, "m1": 3.0, "m2": 1.0}, (-60.0, -120.0), (2.0, 0.0)),
)
#: an accurate simulation: DOP853 at 1e-12; and solve_ivp's default method and tolerances
EXACT = {"method": "DOP853", "rtol": 1e-12, "atol": 1e-12}
SCIPY_DEFAULTS = {"method": "RK45", "rtol": 1e-3, "atol": 1e-6}


def horizontal_arm() -> TwoLinkArm:
    """The 2 m arm lying on a table (g = 0)."""
    return dataclasses.replace(arms.two_metre, g=0.0)


def _random_arm(rng: np.random.Generator, g: float = 9.81) -> TwoLinkArm:
    """An arm of uniform rods like the chapter's: 0.5 to 3 m, 0.5 to 5 kg."""
    lengths, masses = (
        rng.uniform(0.5, 3.0, 2).round(2),
        rng.uniform(0.5, 5.0, 2).round(2),
    )
    return TwoLinkArm(*lengths, *masses, g=g)


def _inputs_5_1() -> dict[str, object]:
    return {"arm_ex1": arms.two_metre, "q_ex1": np.radians(Q_5_1_DEG)}


def _answers_5_1(inputs: dict) -> dict[str, object]:
    arm, q = inputs["arm_ex1"], inputs["q_ex1"]
    tau = arm.gravity(q)
    return {
        "tau_hold_ex1": tau,
        "qdd_ex1": arm.forward_dynamics(q, np.zeros(2), [tau[0], 0.0]),
    }


def _hidden_5_1(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex1": _random_arm(rng),
        "q_ex1": rng.uniform(-np.pi, np.pi, 2).round(4),
    }


def exercise_5_1() -> ExerciseSpec:
    arm, q = arms.two_metre, np.radians(Q_5_1_DEG)
    reference = _answers_5_1(_inputs_5_1())
    tau, qdd = reference["tau_hold_ex1"], reference["qdd_ex1"]
    at_rest = np.zeros(2)
    # each weight at its link's end instead of its centre (twice the lever arm)
    c1, c12 = np.cos(q[0]), np.cos(q.sum())
    at_ends = arm.g * np.array(
        [(arm.m1 + arm.m2) * arm.l1 * c1 + arm.m2 * arm.l2 * c12, arm.m2 * arm.l2 * c12]
    )
    mass = arm.mass_matrix(q)
    return ExerciseSpec(
        "5.1",
        CHAPTER,
        (
            PartSpec(
                "tau_hold_ex1",
                "holding torques",
                "vector",
                expected=tau,
                shape=(2,),
                unit="N m",
                components=TORQUES,
                mistakes=(
                    Mistake(
                        -tau,
                        "the sign is reversed: these torques push the arm down; the "
                        "motors hold it up against its weight, tau = +g(q)",
                    ),
                    Mistake(
                        arm.gravity(np.asarray(Q_5_1_DEG)),
                        "these are the torques for the angles read as radians (30 "
                        "rad, 45 rad): convert degrees first",
                    ),
                    Mistake(
                        np.array([tau[0] - tau[1], tau[1]]),
                        "these are the motor torques of the belt-driven arm (both "
                        "motors on the ground, u1 = tau1 - tau2); the exercise's arm "
                        "has motor 2 at the elbow",
                    ),
                    Mistake(
                        at_ends,
                        "each weight acts here at its link's end; a uniform rod's "
                        "weight acts at its centre, halfway along",
                    ),
                ),
                hints=(
                    "At rest the velocities and accelerations are zero: which term "
                    "of the equations of motion is left? Reread 'The numeric "
                    "dynamics in twolink'.",
                    "The motors must supply exactly the torques that gravity's term "
                    "asks at this pose, with its sign; the package computes that "
                    "term for a pose (angles in radians).",
                ),
            ),
            PartSpec(
                "qdd_ex1",
                "accelerations",
                "vector",
                expected=qdd,
                shape=(2,),
                unit="rad/s²",
                components=("qdd1", "qdd2"),
                mistakes=(
                    Mistake(
                        np.array([0.0, -tau[1]]),
                        "this is tau - g, the unbalanced torque; the accelerations "
                        "are M(q)^-1 times it",
                    ),
                    Mistake(
                        mass @ np.array([0.0, -tau[1]]),
                        "this is M(q) times the unbalanced torque; the accelerations "
                        "need the inverse, M(q)^-1",
                    ),
                    Mistake(
                        arm.forward_dynamics(q, at_rest, at_rest),
                        "these are the accelerations with both motors off; motor 1 "
                        "keeps its holding torque",
                    ),
                    Mistake(
                        arm.forward_dynamics(q, at_rest, [0.0, tau[1]]),
                        "this is motor 1 failing; the exercise has motor 2 fail "
                        "(tau2 = 0) while motor 1 holds",
                    ),
                ),
                hints=(
                    "The arm starts at rest, so the velocity terms vanish: reread "
                    "'Free motion, simulated' for how the accelerations follow from "
                    "the torques.",
                    "Set up the torque vector with motor 1's holding torque and "
                    "motor 2's zero, then solve the equations of motion for the "
                    "accelerations (the mass matrix is not diagonal).",
                ),
            ),
        ),
    )


def stiffness(arm: TwoLinkArm, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """K = dg/dq at q (N m/rad), exact: the derivative of g(q)'s two cosine terms."""
    s1, s12 = np.sin(q[0]), np.sin(q[0] + q[1])
    outer = -arm.g * arm.m2 * arm.l2 / 2 * s12  # d/dq of the link-2 weight's term
    inner = -arm.g * (arm.m1 / 2 + arm.m2) * arm.l1 * s1
    return np.array([[inner + outer, outer], [outer, outer]])


def _inputs_5_2() -> dict[str, object]:
    return {"arm_ex2": arms.two_metre, "q_hang_ex2": np.radians(Q_HANG_5_2_DEG)}


def _answers_5_2(inputs: dict) -> dict[str, object]:
    arm, q_hang = inputs["arm_ex2"], inputs["q_hang_ex2"]
    K = stiffness(arm, q_hang)
    squares = np.linalg.eigvals(np.linalg.solve(arm.mass_matrix(q_hang), K)).real
    return {"K_ex2": K, "omega_ex2": np.sort(np.sqrt(squares))}


def _hidden_5_2(rng: np.random.Generator) -> dict[str, object]:
    return {"arm_ex2": _random_arm(rng), "q_hang_ex2": np.radians(Q_HANG_5_2_DEG)}


def exercise_5_2() -> ExerciseSpec:
    arm, q_hang = arms.two_metre, np.radians(Q_HANG_5_2_DEG)
    K = stiffness(arm, q_hang)
    mass = arm.mass_matrix(q_hang)
    squares = np.sort(np.linalg.eigvals(np.linalg.solve(mass, K)).real)
    omega = _answers_5_2(_inputs_5_2())["omega_ex2"]
    close = Tolerance(atol=1e-6, rtol=1e-6)
    return ExerciseSpec(
        "5.2",
        CHAPTER,
        (
            PartSpec(
                "K_ex2",
                "stiffness",
                "matrix",
                expected=K,
                shape=(2, 2),
                unit="N m/rad",
                tolerance=close,
                mistakes=(
                    Mistake(
                        -K,
                        "the sign is reversed (this is also K of the arm standing "
                        "straight up, an unstable equilibrium): K = +dg/dq, which is "
                        "positive definite where the arm hangs",
                    ),
                    Mistake(
                        np.radians(1.0) * K,
                        "this is the stiffness per degree: differentiate with respect "
                        "to the angles in radians",
                    ),
                    Mistake(
                        np.diag(np.diag(K)),
                        "the off-diagonal entries are missing: g1 depends on q2 and g2 "
                        "on q1, so K couples the joints",
                    ),
                ),
                hints=(
                    "K is the Jacobian of the gravity vector g(q) with respect to "
                    "q, taken at the hanging pose; reread 'Euler-Lagrange: M, C and "
                    "g' for g.",
                    "Differentiate each entry of g by each angle (symbolically, or "
                    "by central differences of arm.gravity with a small step in "
                    "radians) and evaluate at the hanging angles: K is symmetric.",
                ),
            ),
            PartSpec(
                "omega_ex2",
                "natural frequencies",
                "vector",
                expected=omega,
                shape=(2,),
                unit="rad/s",
                components=("omega1", "omega2"),
                tolerance=close,
                mistakes=(
                    Mistake(
                        squares,
                        "these are omega²; the frequencies are their square roots",
                    ),
                    Mistake(
                        omega[::-1],
                        "the order is descending; the exercise asks for ascending "
                        "order",
                    ),
                    Mistake(
                        np.sort(np.sqrt(np.linalg.eigvals(K).real)),
                        "these come from the eigenvalues of K alone; the inertia "
                        "matters: use M^-1 K",
                    ),
                    Mistake(
                        omega / (2 * np.pi),
                        "these are in hertz (cycles per second); the exercise asks "
                        "for angular frequencies in rad/s",
                    ),
                ),
                hints=(
                    "Near the equilibrium the motion is M dq'' + K dq = 0: try dq = "
                    "v cos(omega t) and see which eigenvalue problem omega solves.",
                    "The exercise names the matrix whose eigenvalues are omega²: build "
                    "it with M at the hanging pose, and mind what numpy's eigenvalues are "
                    "(squares, in no particular order).",
                ),
            ),
        ),
    )


@functools.cache
def _spins() -> dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """End states (q, qd) of the spinning arm: right, and the typical mistakes' runs."""
    q0, qd0 = np.radians(Q0_5_3_DEG), np.asarray(QD0_5_3, dtype=float)
    runs = {
        "right": (horizontal_arm(), q0, EXACT),
        "gravity": (arms.two_metre, q0, EXACT),
        "loose": (horizontal_arm(), q0, SCIPY_DEFAULTS),
        "degrees": (horizontal_arm(), np.asarray(Q0_5_3_DEG), EXACT),
    }
    ends = {}
    for name, (arm, start, solver) in runs.items():
        motion = simulate(arm, start, qd0, DURATION_5_3, **solver)
        ends[name] = (motion.q[-1], motion.qd[-1])
    return ends


def _inputs_5_3() -> dict[str, object]:
    return {
        "arm_ex3": horizontal_arm(),
        "q0_ex3": np.radians(Q0_5_3_DEG),
        "qd0_ex3": np.array(QD0_5_3),
        "duration_ex3": DURATION_5_3,
    }


def _answers_5_3(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex3"]
    motion = simulate(
        arm, inputs["q0_ex3"], inputs["qd0_ex3"], inputs["duration_ex3"], **EXACT
    )
    q_end, qd_end = motion.q[-1], motion.qd[-1]
    return {
        "q_end_ex3": q_end,
        "qd_end_ex3": qd_end,
        "p1_end_ex3": float((arm.mass_matrix(q_end) @ qd_end)[0]),
    }


def _hidden_5_3(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex3": _random_arm(rng, g=0.0),
        "q0_ex3": rng.uniform(-np.pi, np.pi, 2).round(3),
        "qd0_ex3": rng.uniform(-2.0, 2.0, 2).round(2),
        "duration_ex3": round(float(rng.uniform(2.0, 5.0)), 1),
    }


def exercise_5_3() -> ExerciseSpec:
    ends = _spins()
    q_end, qd_end = ends["right"]
    horizontal = horizontal_arm()
    momenta = horizontal.mass_matrix(q_end) @ qd_end
    gravity_q, gravity_qd = ends["gravity"]
    # runs whose energy drift is below 1e-8 (DOP853, RK45, Radau, BDF, LSODA at rtol = atol
    # = 1e-8 to 1e-10, measured) end within 2e-7 of the exact state; RK45 at 1e-6 does not
    end_state = Tolerance(atol=1e-6, rtol=0.0)
    loose = (
        "this is the end state of a simulation at scipy's default tolerances (RK45, "
        "rtol = 1e-3), whose energy drifts: tighten the tolerances until the drift "
        "is below 1e-8"
    )
    gravity_on = (
        "this is the vertical arm (g = 9.81): the exercise's arm lies on a table, "
        "g = 0 (horizontal)"
    )
    start_in_degrees = (
        "this run starts at q0 = (0, 90) read as radians: convert the start angles to "
        "radians"
    )
    return ExerciseSpec(
        "5.3",
        CHAPTER,
        (
            PartSpec(
                "q_end_ex3",
                "end angles",
                "angles",
                expected=q_end,
                shape=(2,),
                unit="rad",
                components=("q1", "q2"),
                tolerance=end_state,
                mistakes=(
                    Mistake(gravity_q, gravity_on),
                    Mistake(ends["loose"][0], loose),
                    Mistake(ends["degrees"][0], start_in_degrees),
                    Mistake(
                        np.degrees(q_end),
                        "these are degrees; the answer is in radians",
                    ),
                ),
                hints=(
                    "Reread 'Free motion, simulated' and 'Trust, but check: the "
                    "energy': which solver and tolerances keep the drift small?",
                    "Use the horizontal arm (g = 0) and start angles in radians; if "
                    ".energy_drift() is above the limit, take a higher-order method "
                    "or tighter rtol and atol before reading the last angles.",
                ),
            ),
            PartSpec(
                "qd_end_ex3",
                "end rates",
                "vector",
                expected=qd_end,
                shape=(2,),
                unit="rad/s",
                components=("qd1", "qd2"),
                tolerance=end_state,
                mistakes=(
                    Mistake(gravity_qd, gravity_on),
                    Mistake(ends["loose"][1], loose),
                    Mistake(ends["degrees"][1], start_in_degrees),
                ),
                hints=(
                    "The end rates come from the same simulation as the end angles: "
                    "reread 'Free motion, simulated'.",
                    "Take the last sample of the simulation's .qd, from the run "
                    "whose energy drift is below 1e-8.",
                ),
            ),
            PartSpec(
                "p1_end_ex3",
                "angular momentum p1",
                "number",
                expected=momenta[0],
                unit="kg m²/s",
                tolerance=Tolerance(atol=1e-6, rtol=1e-6),
                mistakes=(
                    Mistake(
                        momenta[1],
                        "this is the second entry of M(q) qd; p1 is the first",
                    ),
                    Mistake(
                        horizontal.mass_matrix(q_end)[0, 0] * qd_end[0],
                        "only M11 qd1: the elbow's rate adds M12 qd2 to p1",
                    ),
                    Mistake(
                        (arms.two_metre.mass_matrix(gravity_q) @ gravity_qd)[0],
                        "this is p1 at the end of the vertical arm's run (g = 9.81), "
                        "where gravity turns the arm and p1 is not conserved; the "
                        "exercise's arm is horizontal",
                    ),
                ),
                hints=(
                    "p1 = dL/d(qd1): reread 'Energy and the Lagrangian'; the kinetic "
                    "energy is (1/2) qd^T M(q) qd.",
                    "p1 is one entry of a matrix times a vector: which matrix, at "
                    "which state, which entry? Computed at the start it should come "
                    "out the same.",
                ),
            ),
        ),
    )


def _kinetic(arm: TwoLinkArm, q: NDArray[np.float64], qd: NDArray[np.float64]) -> float:
    kinetic, _ = arm.energy(q, qd)
    return float(kinetic)


def _case(
    arm: dict[str, float], q: NDArray[np.float64], qd: NDArray[np.float64]
) -> Case:
    return Case(
        {
            "arm": {"arm": dict(arm)},
            "q": [float(v) for v in q],
            "qd": [float(v) for v in qd],
        },
        _kinetic(TwoLinkArm(**arm), q, qd),
    )


def _with_relative_omega(arm: TwoLinkArm, q, qd) -> float:
    """T with link 2's rotational energy from qd2 alone (the first Pitfall)."""
    _, inertia_2 = arm.inertias
    omega_2 = qd[0] + qd[1]
    return _kinetic(arm, q, qd) + 0.5 * inertia_2 * (qd[1] ** 2 - omega_2**2)


def _with_end_inertias(arm: TwoLinkArm, q, qd) -> float:
    """T with the rods' inertias about their ends in 1/2 I omega^2 (the second Pitfall)."""
    ends = dataclasses.replace(
        arm, I1=arm.m1 * arm.l1**2 / 3, I2=arm.m2 * arm.l2**2 / 3
    )
    return _kinetic(ends, q, qd)


def _without_rotation(arm: TwoLinkArm, q, qd) -> float:
    """T of the centres' motion alone (the rotations about the centres left out)."""
    return _kinetic(dataclasses.replace(arm, I1=0.0, I2=0.0), q, qd)


def _on_cases(mistaken) -> list[float]:
    """What a mistaken kinetic_energy returns on each visible case of exercise 5.4."""
    return [
        mistaken(TwoLinkArm(**arm), np.radians(q_deg), np.asarray(rates, dtype=float))
        for arm, q_deg, rates in CASES_5_4
    ]


def exercise_5_4() -> ExerciseSpec:
    arm = arms.two_metre
    q, qd = np.radians(Q_5_4_DEG), np.asarray(QD_5_4, dtype=float)
    return ExerciseSpec(
        "5.4",
        CHAPTER,
        (
            PartSpec(
                "T_ex4",
                "kinetic energy",
                "number",
                expected=_kinetic(arm, q, qd),
                unit="J",
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        _with_relative_omega(arm, q, qd),
                        "link 2's rotational energy uses qd2 here, its rate relative "
                        "to link 1; kinetic energy needs its absolute angular "
                        "velocity, qd1 + qd2",
                    ),
                    Mistake(
                        _with_end_inertias(arm, q, qd),
                        "the inertias here are about the links' ends (m l²/3); beside "
                        "(1/2) m |v_c|² the rotation is about the centre (m l²/12)",
                    ),
                    Mistake(
                        _without_rotation(arm, q, qd),
                        "the rotational energies (1/2) I omega² are missing: a rod "
                        "also turns about its centre",
                    ),
                ),
                hints=(
                    "Reread 'Energy and the Lagrangian': each link's energy is its "
                    "centre's motion plus its rotation about the centre.",
                    "Find the velocity of each centre of mass (a Jacobian times qd), "
                    "the absolute angular velocity of each link, and the rods' "
                    "inertias about their centres; then add the four terms.",
                ),
            ),
            PartSpec(
                "kinetic_energy",
                "kinetic energy function",
                "function",
                cases=tuple(
                    _case(arm_data, np.radians(q_deg), np.asarray(rates))
                    for arm_data, q_deg, rates in CASES_5_4
                ),
                output=PartSpec(
                    "T", "kinetic energy", "number", unit="J", tolerance=Tolerance()
                ),
                mistakes=(
                    Mistake(
                        _on_cases(_with_relative_omega),
                        "your function gives link 2's rotational energy with qd2, its "
                        "rate relative to link 1; it needs the absolute angular "
                        "velocity, qd1 + qd2",
                    ),
                    Mistake(
                        _on_cases(_with_end_inertias),
                        "your function uses the inertias about the links' ends (m l²/3); "
                        "beside (1/2) m |v_c|² the rotation is about the centre "
                        "(arm.inertias)",
                    ),
                    Mistake(
                        _on_cases(_without_rotation),
                        "your function leaves out the rotational energies (1/2) I "
                        "omega²: a rod also turns about its centre",
                    ),
                ),
                hints=(
                    "Write the four terms of T for any arm: reread 'Energy and the "
                    "Lagrangian', and use the arm's l1, l2, m1, m2 and arm.inertias.",
                    "Centres of mass at mid-link, link 2 turning at qd1 + qd2, "
                    "inertias about the centres; your function is also called on "
                    "arms and states the notebook does not show.",
                ),
            ),
        ),
    )


def _hidden_5_4(rng: np.random.Generator, count: int) -> list[Case]:
    cases = []
    for _ in range(count):
        lengths = np.round(rng.uniform(0.3, 3.0, 2), 3)
        masses = np.round(rng.uniform(0.2, 5.0, 2), 3)
        arm = {
            "l1": float(lengths[0]),
            "l2": float(lengths[1]),
            "m1": float(masses[0]),
            "m2": float(masses[1]),
        }
        cases.append(
            _case(arm, rng.uniform(-np.pi, np.pi, 2), rng.uniform(-3.0, 3.0, 2))
        )
    return cases


HIDDEN = {("5.4", "kinetic_energy"): _hidden_5_4}


def _inputs_5_5() -> dict[str, object]:
    return {
        "arm_ex5": arms.two_metre,
        "q_from_ex5": np.radians(Q_FROM_5_5_DEG),
        "q_to_ex5": np.radians(Q_TO_5_5_DEG),
        "duration_ex5": DURATION_5_5,
    }


def _planned_work(arm: TwoLinkArm, q_from, q_to, duration: float, gravity: bool = True):
    """The motors' work on the quintic move, integrated by the trapezoidal rule."""
    t = np.linspace(0.0, duration, SAMPLES_5_5)
    s, s_rate, s_accel = trajectory.time_scaling(
        t, duration, "quintic", with_acceleration=True
    )
    move = np.asarray(q_to) - np.asarray(q_from)
    q = np.asarray(q_from) + np.outer(s, move)
    qd, qdd = np.outer(s_rate, move), np.outer(s_accel, move)
    model = arm if gravity else dataclasses.replace(arm, g=0.0)
    tau = model.inverse_dynamics(q, qd, qdd)
    return float(np.trapezoid(np.sum(qd * tau, axis=1), t))


def _answers_5_5(inputs: dict) -> dict[str, object]:
    arm = inputs["arm_ex5"]
    potential = [
        arm.energy(inputs[name], np.zeros(2))[1] for name in ("q_to_ex5", "q_from_ex5")
    ]
    return {
        "energy_change_ex5": float(potential[0] - potential[1]),
        "work_ex5": _planned_work(
            arm, inputs["q_from_ex5"], inputs["q_to_ex5"], inputs["duration_ex5"]
        ),
    }


def _hidden_5_5(rng: np.random.Generator) -> dict[str, object]:
    return {
        "arm_ex5": _random_arm(rng),
        "q_from_ex5": rng.uniform(-np.pi, np.pi, 2).round(3),
        "q_to_ex5": rng.uniform(-np.pi, np.pi, 2).round(3),
        "duration_ex5": round(float(rng.uniform(1.0, 3.0)), 1),
    }


def exercise_5_5() -> ExerciseSpec:
    inputs = _inputs_5_5()
    arm, q_from, q_to = inputs["arm_ex5"], inputs["q_from_ex5"], inputs["q_to_ex5"]
    reference = _answers_5_5(inputs)
    change = reference["energy_change_ex5"]
    _, kinetic_only = arm.energy(q_to, np.zeros(2))
    by_hand = Tolerance(significant=3)
    return ExerciseSpec(
        "5.5",
        CHAPTER,
        (
            PartSpec(
                "energy_change_ex5",
                "change of energy",
                "number",
                expected=change,
                unit="J",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        -change,
                        "the sign is reversed: the change is V at the end minus V at "
                        "the start, and the arm ends higher than it starts",
                    ),
                    Mistake(
                        float(arm.energy(q_to, np.zeros(2))[1]),
                        "this is V at the end alone; the change subtracts V at the "
                        "start (not zero: V = 0 is at shoulder height)",
                    ),
                    Mistake(
                        float(
                            arm.energy(np.degrees(q_to), np.zeros(2))[1]
                            - arm.energy(np.degrees(q_from), np.zeros(2))[1]
                        ),
                        "these are the energies for the angles read as degrees fed "
                        "to sin and cos: the angles are in radians already",
                    ),
                ),
                hints=(
                    "At rest T = 0, so the energy at each end is V alone: reread "
                    "section 2's V, or use arm.energy(q, qd), which returns (T, V).",
                    "Compute V at q_to_ex5 and at q_from_ex5, both at rest, and "
                    "subtract: end minus start.",
                ),
            ),
            PartSpec(
                "work_ex5",
                "motors' work",
                "number",
                expected=reference["work_ex5"],
                unit="J",
                tolerance=by_hand,
                mistakes=(
                    Mistake(
                        _planned_work(
                            arm, q_from, q_to, inputs["duration_ex5"], gravity=False
                        ),
                        "this is the work on the arm lying flat (g = 0), which ends "
                        "where it started in energy: the exercise's arm is vertical, "
                        "its motors also lift it",
                    ),
                    Mistake(
                        -reference["work_ex5"],
                        "the sign is reversed: the motors' power is qd^T tau, positive "
                        "while they lift the arm",
                    ),
                ),
                hints=(
                    "Section 8 turns a planned q, qd, qdd into torques; the power "
                    "the motors put in is qd^T tau at each instant (section 3).",
                    "Sample the quintic move at 2001 instants, take tau from "
                    "arm_ex5.inverse_dynamics, the power as the sum over the joints "
                    "of qd times tau, and integrate it over time with np.trapezoid.",
                ),
            ),
        ),
    )


def _c_qd(q: NDArray[np.float64], qd: NDArray[np.float64]) -> NDArray[np.float64]:
    arm = arms.two_metre
    return arm.coriolis(q, qd) @ qd


def exercise_5_6() -> ExerciseSpec:
    q, qd = np.radians(Q_5_6_DEG), np.asarray(QD_5_6)
    c_qd = _c_qd(q, qd)
    return ExerciseSpec(
        "5.6",
        CHAPTER,
        (
            PartSpec(
                "C_qd_ex6",
                "velocity torques C qd",
                "vector",
                expected=c_qd,
                shape=(2,),
                unit="N m",
                components=("shoulder", "elbow"),
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        -c_qd,
                        "the sign is reversed: h = -m2 l1 l2 sin(q2) / 2 is negative "
                        "here, so the elbow's term -h qd1² is positive",
                    ),
                    Mistake(
                        _c_qd(np.asarray(Q_5_6_DEG), qd),
                        "these are the torques with the angles read as radians: sin "
                        "of 90 degrees is 1",
                    ),
                    Mistake(
                        c_qd[::-1],
                        "the entries are swapped: the first is the shoulder's torque, "
                        "the second the elbow's",
                    ),
                ),
                hints=(
                    "Put q2 = 90 deg, qd1 = 1 rad/s and qd2 = 0 into section 3's C qd; "
                    "start with h.",
                    "h = -(1/2)(1 kg)(2 m)(2 m) sin 90 deg; with qd2 = 0 only the "
                    "elbow's term -h qd1² is left.",
                ),
            ),
            PartSpec(
                "reason_ex6",
                "reason",
                "text",
                expected="b",
                mistakes=(
                    Mistake(
                        "a",
                        "a constant rate does not remove the velocity terms (they are "
                        "quadratic in the rates, not in the accelerations), and the "
                        "elbow's term has qd1², a centrifugal term, not a Coriolis one",
                    ),
                    Mistake(
                        "c",
                        "at q2 = 90 deg sin q2 = 1: h is largest there, not zero; the "
                        "terms vanish when the arm is stretched or folded",
                    ),
                ),
                hints=(
                    "Reread the bullets after C qd in section 3: which term is "
                    "centrifugal, which Coriolis, and which terms are absent?",
                    "A centrifugal term has the square of one rate, a Coriolis term "
                    "the product of two; no joint feels the centrifugal force of "
                    "its own rotation.",
                ),
            ),
        ),
    )


#: The value exercises graded on hidden inputs too: the inputs cell, a hidden draw, the references.
RERUN = {
    "5.1": Rerun(inputs=_inputs_5_1(), hidden=_hidden_5_1, answers=_answers_5_1),
    "5.2": Rerun(inputs=_inputs_5_2(), hidden=_hidden_5_2, answers=_answers_5_2),
    "5.3": Rerun(inputs=_inputs_5_3(), hidden=_hidden_5_3, answers=_answers_5_3),
    "5.5": Rerun(inputs=_inputs_5_5(), hidden=_hidden_5_5, answers=_answers_5_5),
}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("5.4", "kinetic_energy"): (
        "twolink.arm.TwoLinkArm.energy",
        "twolink.dynamics.energy",
        "twolink.arm.TwoLinkArm.mass_matrix",
        "twolink.dynamics.mass_matrix",
    ),
}

#: Parts worked on paper: checked on the visible values only, timed as pen-and-paper parts.
PEN_AND_PAPER = (("5.4", "T_ex4"), ("5.6", "C_qd_ex6"), ("5.6", "reason_ex6"))


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_5_1(),
        exercise_5_2(),
        exercise_5_3(),
        exercise_5_4(),
        exercise_5_5(),
        exercise_5_6(),
    ]
