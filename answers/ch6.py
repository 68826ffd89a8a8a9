"""Chapter 6 (spring and impedance control): the references of exercises 6.1 to 6.4, with typical mistakes and hints."""

from __future__ import annotations

import numpy as np
import scipy.optimize
from numpy.typing import NDArray

from twolink import arms, controllers, ik, linearization
from twolink.arm import TwoLinkArm
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "06_spring_impedance_control"
K_SOURCE, REST_POINT = 600.0, (3.0, 1.0)  # N/m, m: the chapter's spring
K_6_1, TIP_6_1 = ((600.0, 0.0), (0.0, 200.0)), (2.6, 0.3)  # held on the elbow-up branch
SAG_LIMIT_6_3 = 0.005  # m
TORQUES = ("tau1", "tau2")
#: 6.4's visible calls: (l1, l2), q (rad), p_rest (m), k (N/m)
CASES_6_4 = (
    ((2.0, 2.0), (0.3, 0.9), (3.0, 1.0), 600.0),
    ((1.0, 0.5), (-0.4, 2.1), (0.2, 1.1), 150.0),
    ((0.6, 1.5), (2.5, -1.2), (-1.0, -0.5), 40.0),
)


def _arm() -> TwoLinkArm:
    return arms.two_metre


def _q_rest() -> NDArray[np.float64]:
    """The 2 m arm's elbow-down pose with the tip at the rest point (3, 1)."""
    return ik.closed_form(_arm(), REST_POINT, elbow="down").q


def _spring_torque(arm: TwoLinkArm, q, p_rest, stiffness) -> NDArray[np.float64]:
    spring = controllers.CartesianSpring(arm, stiffness, np.asarray(p_rest, float))
    return np.asarray(spring.torque(np.asarray(q, float)), dtype=float)


def exercise_6_1() -> ExerciseSpec:
    arm, K = _arm(), np.array(K_6_1)
    q_up = ik.closed_form(arm, TIP_6_1, elbow="up").q
    q_down = ik.closed_form(arm, TIP_6_1, elbow="down").q
    force = K @ (np.asarray(REST_POINT) - arm.fk(q_up))
    tau = _spring_torque(arm, q_up, REST_POINT, K)
    return ExerciseSpec(
        "6.1",
        CHAPTER,
        (
            PartSpec(
                "tau_ex1",
                "torques",
                "vector",
                expected=tau,
                shape=(2,),
                unit="N m",
                components=TORQUES,
                mistakes=(
                    Mistake(
                        _spring_torque(arm, q_down, REST_POINT, K),
                        "these are the torques of the elbow-down arm (q2 > 0): the "
                        "exercise holds the tip on the elbow-up branch",
                    ),
                    Mistake(
                        -tau,
                        "the sign is reversed: the spring pulls the tip TOWARDS the "
                        "rest point, so its force is K (x0 - x)",
                    ),
                    Mistake(
                        _spring_torque(arm, q_up, REST_POINT, K_SOURCE),
                        "these are the torques of the scalar spring k = 600 N/m; this "
                        "spring is softer vertically: use the whole matrix K",
                    ),
                    Mistake(
                        _spring_torque(arm, q_up, REST_POINT, np.diag([200.0, 600.0])),
                        "the stiffnesses are swapped: 600 N/m acts along x and "
                        "200 N/m along y",
                    ),
                    Mistake(
                        arm.jacobian(q_up) @ force,
                        "this is J F, the Jacobian times the force; torques come from "
                        "its transpose",
                    ),
                    Mistake(
                        tau + arm.gravity(q_up),
                        "these include the links' weight, g(q): the exercise asks for "
                        "the spring's torques only",
                    ),
                ),
                hints=(
                    "Reread 'The idea: torques that feel like a spring': the spring "
                    "gives a force at the tip, and the motors make it with J^T.",
                    "First the pose: inverse kinematics on the elbow-up branch (q2 < "
                    "0). Then the force K (x0 - x) at that tip, then J^T at that pose.",
                ),
            ),
        ),
    )


def _loop_poles(damping) -> NDArray[np.float64]:
    """The linearised impedance loop's poles at (3, 1) for ``damping``: real parts, sorted."""
    controller = controllers.Impedance(
        _arm(), K_SOURCE, damping, np.asarray(REST_POINT)
    )
    loop = linearization.linearize(_arm(), controller, _q_rest())
    return np.sort(np.linalg.eigvals(loop.A).real)


def _sqrtm(S: NDArray[np.float64]) -> NDArray[np.float64]:
    w, V = np.linalg.eigh(S)
    return (V * np.sqrt(w)) @ V.T


def exercise_6_2() -> ExerciseSpec:
    Lambda = linearization.tip_mass(_arm(), _q_rest())
    D = np.asarray(
        linearization.critical_damping(_arm(), _q_rest(), K_SOURCE, kind="matrix"),
        dtype=float,
    )
    d_c = float(linearization.critical_damping(_arm(), _q_rest(), K_SOURCE))
    Omega = _sqrtm(K_SOURCE * np.linalg.inv(Lambda))
    omega = np.sqrt(K_SOURCE / np.linalg.eigvalsh(Lambda))  # light mode first
    poles = np.sort(np.repeat(-omega, 2))
    masses = np.linalg.eigvalsh(Lambda)  # light, heavy
    zeta = d_c / (2.0 * np.sqrt(K_SOURCE * masses))
    wrong_d = {
        "scalar": d_c * np.eye(2),
        "z": 2.0 * Omega,
        "half": _sqrtm(K_SOURCE * Lambda),
        "unrooted": 2.0 * np.sqrt(K_SOURCE) * Lambda,
        "entrywise": 2.0 * np.sqrt(K_SOURCE * Lambda),
    }
    return ExerciseSpec(
        "6.2",
        CHAPTER,
        (
            PartSpec(
                "D_ex2",
                "damping matrix",
                "matrix",
                expected=D,
                shape=(2, 2),
                unit="N s/m",
                tolerance=Tolerance(atol=1e-6, rtol=1e-7),
                mistakes=(
                    Mistake(
                        wrong_d["scalar"],
                        "this is the scalar critical damping d_c times the identity: "
                        "critical for the heavy direction only, the light one is "
                        "overdamped",
                    ),
                    Mistake(
                        wrong_d["z"],
                        "this is 2 Omega, the damping in the z coordinates; bring it "
                        "back to the tip's coordinates with Lambda^1/2 on both sides",
                    ),
                    Mistake(
                        wrong_d["half"],
                        "half the damping: a critically damped mode needs "
                        "d = 2 sqrt(k m), the factor 2 is missing",
                    ),
                    Mistake(
                        wrong_d["unrooted"],
                        "the tip mass is not square-rooted: it enters the critical "
                        "damping as Lambda^1/2",
                    ),
                    Mistake(
                        wrong_d["entrywise"],
                        "np.sqrt takes the square root of each entry; a matrix's "
                        "square root is scipy.linalg.sqrtm",
                    ),
                ),
                hints=(
                    "Reread 'Impedance control: damping chosen with python-control' "
                    "and the exercise's change of coordinates x = Lambda^-1/2 z: in z "
                    "each mode is a mass-spring-damper of unit mass.",
                    "In z, critical damping is 2 Omega; the damping in x is that "
                    "matrix with Lambda^1/2 multiplied on each side.",
                ),
            ),
            PartSpec(
                "poles_ex2",
                "poles",
                "vector",
                expected=poles,
                shape=(4,),
                unit="1/s",
                components=("pole 1", "pole 2", "pole 3", "pole 4"),
                # a double pole is computed to about sqrt(machine epsilon) only
                tolerance=Tolerance(atol=1e-5, rtol=1e-5),
                mistakes=(
                    Mistake(
                        _loop_poles(d_c),
                        "these are the poles of the scalar damping d_c: the light "
                        "mode's pair is split (overdamped); use your D_ex2",
                    ),
                    Mistake(
                        -poles,
                        "these are positive: the natural frequencies |p|, or the "
                        "poles with the sign lost; a damped loop's poles have "
                        "negative real parts",
                    ),
                    Mistake(
                        poles[::-1],
                        "these are sorted from the least negative; sort them from the "
                        "most negative (np.sort)",
                    ),
                    Mistake(
                        _loop_poles(wrong_d["z"]),
                        "these are the poles with D = 2 Omega (the z coordinates' "
                        "damping, not brought back to x)",
                    ),
                ),
                hints=(
                    "Build controllers.Impedance with your D_ex2, linearise it at "
                    "the rest pose as in 'Impedance control: damping chosen with "
                    "python-control', and ask control.poles.",
                    "Critically damped modes give real poles in pairs; report the "
                    "real parts, sorted from the most negative.",
                ),
            ),
            PartSpec(
                "zeta_modes_ex2",
                "damping ratios under d_c",
                "vector",
                expected=zeta,
                shape=(2,),
                components=("zeta_light", "zeta_heavy"),
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        np.ones(2),
                        "control.damp says 1 for every real pole, overdamped or not; "
                        "use zeta = d / (2 sqrt(k lambda)) with each direction's mass",
                    ),
                    Mistake(
                        zeta[::-1],
                        "the order is swapped: the light direction first, then the "
                        "heavy one",
                    ),
                    Mistake(
                        1.0 / zeta,
                        "these are upside down: zeta = d / (2 sqrt(k lambda))",
                    ),
                    Mistake(
                        d_c / (2.0 * np.sqrt(K_SOURCE * np.diag(Lambda))),
                        "these use the diagonal entries of Lambda; the directions' "
                        "masses are its eigenvalues",
                    ),
                ),
                hints=(
                    "Reread how 'Impedance control: damping chosen with "
                    "python-control' splits the tip into two eigen-directions, each "
                    "its own mass-spring-damper.",
                    "Each direction's mass is an eigenvalue of Lambda; its damping "
                    "ratio is d over twice the square root of k times that mass.",
                ),
            ),
        ),
    )


def _sag(stiffness_value: float, component: slice = slice(None)) -> float:
    """How far (m) the vertical arm's tip rests from (3, 1) without gravity compensation."""
    controller = controllers.Impedance(
        _arm(),
        stiffness_value,
        0.0,
        np.asarray(REST_POINT),
        gravity_compensation=False,
    )
    rest = _arm().fk(linearization.equilibrium(_arm(), controller, _q_rest()))
    return float(np.linalg.norm((rest - np.asarray(REST_POINT))[component]))


def _stiffness_for(sag: float, component: slice = slice(None)) -> float:
    return float(
        scipy.optimize.brentq(
            lambda k: _sag(k, component) - sag, 100.0, 1e6, xtol=1e-9, rtol=1e-14
        )
    )


def exercise_6_3() -> ExerciseSpec:
    k = _stiffness_for(SAG_LIMIT_6_3)
    J = _arm().jacobian(_q_rest())
    linear = float(
        np.linalg.norm(np.linalg.solve(J.T, _arm().gravity(_q_rest()))) / SAG_LIMIT_6_3
    )
    return ExerciseSpec(
        "6.3",
        CHAPTER,
        (
            PartSpec(
                "k_ex3",
                "stiffness",
                "number",
                expected=k,
                unit="N/m",
                tolerance=Tolerance(significant=4),
                mistakes=(
                    Mistake(
                        K_SOURCE,
                        "this is the chapter's spring, k = 600 N/m: with it the tip "
                        "rests more than 5 mm away",
                    ),
                    Mistake(
                        _stiffness_for(SAG_LIMIT_6_3 / 10),
                        "this keeps the tip within 0.5 mm: 5 mm is 0.005 m",
                    ),
                    Mistake(
                        _stiffness_for(SAG_LIMIT_6_3 * 10),
                        "this lets the tip rest 5 cm away: 5 mm is 0.005 m",
                    ),
                    Mistake(
                        -k,
                        "a stiffness is positive: a negative spring pushes the tip "
                        "away from its rest point",
                    ),
                    Mistake(
                        _stiffness_for(SAG_LIMIT_6_3, slice(1, 2)),
                        "this bounds the vertical drop only; the tip also moves "
                        "sideways: bound its distance from the rest point",
                    ),
                    Mistake(
                        linear,
                        "close, but this is the linear estimate at the rest pose; the "
                        "arm sags into another pose, where J and g(q) differ: solve "
                        "for the true resting pose",
                    ),
                ),
                hints=(
                    "Reread the Pitfall 'forgetting gravity': the tip rests where "
                    "the spring balances the weight, closer for a stiffer spring.",
                    "Write the distance of the resting tip from (3, 1) as a "
                    "function of k (linearization.equilibrium finds the resting "
                    "pose), then find where it equals 5 mm with a root finder.",
                ),
            ),
        ),
    )


def _case_6_4(lengths, q, p_rest, k) -> Case:
    arm = TwoLinkArm(l1=lengths[0], l2=lengths[1])
    return Case(
        {
            "arm": {"arm": {"l1": float(lengths[0]), "l2": float(lengths[1])}},
            "q": [float(v) for v in q],
            "p_rest": [float(v) for v in p_rest],
            "k": float(k),
        },
        _spring_torque(arm, q, p_rest, k).tolist(),
    )


def _wrong_6_4(how: str) -> list[list[float]]:
    """What a mistaken spring_torques returns on each visible case."""
    values = []
    for lengths, q, p_rest, k in CASES_6_4:
        arm = TwoLinkArm(l1=lengths[0], l2=lengths[1])
        swapped = TwoLinkArm(l1=lengths[1], l2=lengths[0])
        q, p_rest = np.asarray(q), np.asarray(p_rest)
        J, p = arm.jacobian(q), arm.fk(q)
        value = {
            "sign": J.T @ (k * (p - p_rest)),
            "J": J @ (k * (p_rest - p)),
            "anchored": J.T @ (k * p),
            "swapped": swapped.jacobian(q).T @ (k * (p_rest - swapped.fk(q))),
            "gravity": J.T @ (k * (p_rest - p)) + arm.gravity(q),
        }[how]
        values.append(np.asarray(value, dtype=float).tolist())
    return values


def exercise_6_4() -> ExerciseSpec:
    output = PartSpec(
        "tau",
        "torques",
        "vector",
        shape=(2,),
        unit="N m",
        components=TORQUES,
        tolerance=Tolerance(atol=1e-7, rtol=1e-7),
    )
    return ExerciseSpec(
        "6.4",
        CHAPTER,
        (
            PartSpec(
                "spring_torques",
                "spring torques function",
                "function",
                cases=tuple(_case_6_4(*case) for case in CASES_6_4),
                output=output,
                mistakes=(
                    Mistake(
                        _wrong_6_4("sign"),
                        "your spring pushes the tip away from p_rest: its force is "
                        "k (p_rest - x), towards the rest point",
                    ),
                    Mistake(
                        _wrong_6_4("J"),
                        "your function returns J F, the Jacobian times the force; "
                        "torques come from its transpose",
                    ),
                    Mistake(
                        _wrong_6_4("anchored"),
                        "your spring is anchored at the origin (F = k x): the force "
                        "must depend on p_rest - x",
                    ),
                    Mistake(
                        _wrong_6_4("swapped"),
                        "your function swaps the links: l1 is the shoulder's link, "
                        "l2 the elbow's",
                    ),
                    Mistake(
                        _wrong_6_4("gravity"),
                        "your function adds the weight of the links: return the "
                        "spring's torques only",
                    ),
                ),
                hints=(
                    "Reread 'The idea: torques that feel like a spring': the "
                    "function is the spring law for any arm, pose, rest point and "
                    "stiffness.",
                    "Use the arm's own forward kinematics and Jacobian at q, the "
                    "force k (p_rest - x) at the tip, and the transpose of the "
                    "Jacobian; no weight.",
                ),
            ),
        ),
    )


def _hidden_6_4(rng: np.random.Generator, count: int) -> list[Case]:
    """Random arms, poses, rest points (anywhere within twice the reach) and stiffnesses."""
    cases = []
    while len(cases) < count:
        lengths = np.round(rng.uniform(0.2, 3.0, 2), 3)
        q = np.round(rng.uniform(-np.pi, np.pi, 2), 4)
        reach = lengths.sum()
        p_rest = np.round(rng.uniform(-1.5 * reach, 1.5 * reach, 2), 3)
        k = float(np.round(rng.uniform(10.0, 2000.0), 1))
        case = _case_6_4(tuple(lengths), tuple(q), tuple(p_rest), k)
        if all(case.arguments != _case_6_4(*c).arguments for c in CASES_6_4):
            cases.append(case)
    return cases


HIDDEN = {("6.4", "spring_torques"): _hidden_6_4}


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [exercise_6_1(), exercise_6_2(), exercise_6_3(), exercise_6_4()]
