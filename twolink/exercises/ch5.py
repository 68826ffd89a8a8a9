"""Chapter 5 (Lagrangian dynamics): exercises 5.1 to 5.3."""

from __future__ import annotations

import dataclasses

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import arms
from ..arm import TwoLinkArm
from ..dynamics import energy
from ..simulation import SimulationResult, simulate
from .registry import (
    Part,
    Wrong,
    angles_close,
    close,
    matches,
    numbers,
    reference,
    register,
    scalar,
    usable,
)

CHAPTER = "05_lagrangian_dynamics"
Q_5_1_DEG = (30.0, 45.0)
Q_HANG_5_2_DEG = (-90.0, 0.0)
Q0_5_3_DEG, QD0_5_3, DURATION_5_3, DRIFT_LIMIT_5_3 = (0.0, 90.0), (2.0, 0.0), 5.0, 1e-8


def horizontal_arm() -> TwoLinkArm:
    """The 2 m arm lying on a table (g = 0)."""
    return dataclasses.replace(arms.two_metre, g=0.0)


def judge_holding_5_1(answer: object, siblings: dict[str, object]) -> None:
    tau = numbers(answer, (2,))
    g_q = arms.two_metre.gravity(np.radians(Q_5_1_DEG))
    if matches(close, tau, -g_q, atol=1e-9):
        raise Wrong("the sign is reversed: the motors balance g(q), tau = +g(q)")
    close(tau, g_q, atol=1e-9)


def judge_failure_5_1(answer: object, siblings: dict[str, object]) -> None:
    qdd = numbers(answer, (2,))
    arm, q = arms.two_metre, np.radians(Q_5_1_DEG)
    g_q = arm.gravity(q)
    if matches(close, qdd, np.array([0.0, -g_q[1]]), atol=1e-9):
        raise Wrong("this is tau - g; the accelerations are M^-1 (tau - g)")
    if matches(close, qdd, arm.forward_dynamics(q, [0.0, 0.0], [0.0, 0.0]), atol=1e-9):
        raise Wrong(
            "these are the accelerations with both motors off; motor 1 keeps its holding torque"
        )
    close(qdd, arm.forward_dynamics(q, [0.0, 0.0], [g_q[0], 0.0]), atol=1e-9)


@reference
def stiffness_5_2() -> NDArray[np.float64]:
    """K = dg/dq at q = (-90, 0) deg, by central differences of arm.gravity."""
    arm, q_hang, step = arms.two_metre, np.radians(Q_HANG_5_2_DEG), 1e-6
    return np.column_stack(
        [
            (arm.gravity(q_hang + step * e) - arm.gravity(q_hang - step * e))
            / (2 * step)
            for e in np.eye(2)
        ]
    )


@reference
def frequencies_5_2() -> NDArray[np.float64]:
    """The natural angular frequencies (rad/s, ascending): omega^2 the eigenvalues of M^-1 K."""
    mass = arms.two_metre.mass_matrix(np.radians(Q_HANG_5_2_DEG))
    return np.sort(
        np.sqrt(np.linalg.eigvals(np.linalg.solve(mass, stiffness_5_2())).real)
    )


def judge_stiffness_5_2(answer: object, siblings: dict[str, object]) -> None:
    K = numbers(answer, (2, 2))
    if matches(close, K, -stiffness_5_2(), atol=1e-6):
        raise Wrong(
            "the sign is reversed: K = +dg/dq, positive definite at a stable equilibrium"
        )
    close(K, stiffness_5_2(), atol=1e-6)


def judge_frequencies_5_2(answer: object, siblings: dict[str, object]) -> None:
    omega = numbers(answer, (2,))
    if matches(close, omega, frequencies_5_2() ** 2, atol=1e-6):
        raise Wrong("these are omega^2; take square roots")
    if matches(close, omega, frequencies_5_2()[::-1], atol=1e-6):
        raise Wrong("the task asks for ascending order")
    if matches(
        close,
        np.sort(omega),
        np.sort(np.sqrt(np.abs(np.linalg.eigvals(stiffness_5_2())))),
        atol=1e-6,
    ):
        raise Wrong("these come from the eigenvalues of K alone; use M^-1 K")
    close(omega, frequencies_5_2(), atol=1e-6)


@reference
def reference_5_3() -> SimulationResult:
    """The spinning horizontal arm simulated to 1e-12 (DOP853)."""
    return simulate(
        horizontal_arm(),
        np.radians(Q0_5_3_DEG),
        QD0_5_3,
        DURATION_5_3,
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
    )


def _start_5_3() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return np.radians(Q0_5_3_DEG), np.asarray(QD0_5_3, dtype=float)


def _energy_drift(q: ArrayLike, qd: ArrayLike) -> float:
    """max |E - E(0)| / max T over samples, as SimulationResult.energy_drift."""
    kinetic, potential = energy(horizontal_arm(), q, qd)
    total = kinetic + potential
    return float(np.max(np.abs(total - total[0])) / np.max(kinetic))


def _end_angles(answer: object) -> NDArray[np.float64]:
    q_end = numbers(answer, (2,))
    angles_close(q_end, reference_5_3().q[-1], atol=1e-5)
    return q_end


def _end_rates(answer: object) -> NDArray[np.float64]:
    qd_end = numbers(answer, (2,))
    close(qd_end, reference_5_3().qd[-1], atol=1e-5)
    return qd_end


def _motion(
    answer: object,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The learner's simulation result as (t, q, qd) arrays, checked for shape."""
    if not all(hasattr(answer, name) for name in ("t", "q", "qd")):
        raise Wrong(
            f"expected the result of simulate(...) (with .t, .q, .qd), got a {type(answer).__name__}"
        )
    # read by name: the answer is any object with .t, .q, .qd (checked above)
    t = np.asarray(getattr(answer, "t"), dtype=np.float64)  # noqa: B009
    n = t.shape[0] if t.ndim == 1 else 0
    if n < 2:
        raise Wrong("expected a simulation with at least two samples in .t")
    q, qd = getattr(answer, "q"), getattr(answer, "qd")  # noqa: B009
    return t, numbers(q, (n, 2), "its .q"), numbers(qd, (n, 2), "its .qd")


def _judged_motion(
    answer: object,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The learner's simulation as :func:`_motion` reads it, after :func:`judge_simulation_5_3` passed it."""
    judge_simulation_5_3(answer, {})
    return _motion(answer)


def judge_end_angles_5_3(answer: object, siblings: dict[str, object]) -> None:
    _end_angles(answer)


def judge_end_rates_5_3(answer: object, siblings: dict[str, object]) -> None:
    _end_rates(answer)


def judge_simulation_5_3(answer: object, siblings: dict[str, object]) -> None:
    t, q, qd = _motion(answer)
    q0, qd0 = _start_5_3()
    if abs(t[0]) > 1e-12 or abs(t[-1] - DURATION_5_3) > 1e-9:
        raise Wrong(
            f"it runs from {t[0]:g} s to {t[-1]:g} s; the task is 0 to {DURATION_5_3:g} s"
        )
    if not (np.allclose(q[0], q0, atol=1e-12) and np.allclose(qd[0], qd0, atol=1e-12)):
        raise Wrong("it does not start at q = (0, 90) deg, qd = (2, 0) rad/s")
    drift = _energy_drift(q, qd)
    if drift >= DRIFT_LIMIT_5_3:
        raise Wrong(
            f"its energy drifts by {drift:.2g} relative, not below {DRIFT_LIMIT_5_3:g}"
        )
    try:
        angles_close(q[-1], reference_5_3().q[-1], atol=1e-5)
        close(qd[-1], reference_5_3().qd[-1], atol=1e-5)
    except Wrong as wrong:
        raise Wrong(f"its end state is not the spinning arm's ({wrong})") from None


def judge_drift_5_3(answer: object, siblings: dict[str, object]) -> None:
    drift = scalar(answer)
    motion = usable(siblings, "spin_ex3", _judged_motion)
    if motion is not None:
        measured = _energy_drift(motion[1], motion[2])
        if not np.isclose(drift, measured, rtol=1e-6, atol=1e-15):
            raise Wrong(
                f"not the drift of your simulation spin_ex3 (spin_ex3.energy_drift() gives {measured:.3g})"
            )
        return
    if not 0.0 < drift < DRIFT_LIMIT_5_3:
        raise Wrong(f"a drift of {drift:.3g} is not in (0, {DRIFT_LIMIT_5_3:g})")
    end = (
        usable(siblings, "q_end_ex3", _end_angles),
        usable(siblings, "qd_end_ex3", _end_rates),
    )
    if end[0] is not None and end[1] is not None:
        q0, qd0 = _start_5_3()
        end_drift = _energy_drift(np.array([q0, end[0]]), np.array([qd0, end[1]]))
        if drift < 0.5 * end_drift:
            raise Wrong(
                f"smaller than the drift of your own end state ({end_drift:.2g})"
            )


def judge_momentum_5_3(answer: object, siblings: dict[str, object]) -> None:
    p1 = scalar(answer)
    arm = horizontal_arm()
    q_end = usable(siblings, "q_end_ex3", _end_angles)
    qd_end = usable(siblings, "qd_end_ex3", _end_rates)
    if q_end is None or qd_end is None:
        q_end, qd_end = reference_5_3().q[-1], reference_5_3().qd[-1]
    q0, qd0 = _start_5_3()
    p1_start = float((arm.mass_matrix(q0) @ qd0)[0])
    if matches(close, p1, (arm.mass_matrix(q_end) @ qd_end)[1], atol=1e-6):
        raise Wrong("this is the second row of M qd; p1 is the first, (M qd)[0]")
    at_end = float((arm.mass_matrix(q_end) @ qd_end)[0])
    if not np.isclose(p1, at_end, rtol=1e-9, atol=1e-12):
        raise Wrong(
            f"not (M(q) qd)[0] at the end state (off by {abs(p1 - at_end):.3g})"
        )
    close(p1, p1_start, atol=1e-6)


register(
    "5.1",
    Part(
        "tau_hold_ex1",
        "holding torques",
        judge_holding_5_1,
        "at rest M qdd and C qd vanish: tau = g(q)",
    ),
    Part(
        "qdd_ex1",
        "motor 2 fails",
        judge_failure_5_1,
        "qdd = M^-1 (tau - C qd - g) with tau = (g1, 0)",
    ),
    chapter=CHAPTER,
)
register(
    "5.2",
    Part(
        "K_ex2",
        "stiffness",
        judge_stiffness_5_2,
        "K[i, j] = d g_i / d q_j at q = (-90, 0) deg; K is symmetric",
    ),
    Part(
        "omega_ex2",
        "frequencies",
        judge_frequencies_5_2,
        "omega^2 are the eigenvalues of M^-1 K; take square roots and sort",
    ),
    chapter=CHAPTER,
)
register(
    "5.3",
    Part(
        "spin_ex3",
        "simulation",
        judge_simulation_5_3,
        "simulate(horizontal, q0_ex3, qd0_ex3, 5.0, method='DOP853', rtol=1e-10, atol=1e-10)",
    ),
    Part(
        "q_end_ex3",
        "end angles",
        judge_end_angles_5_3,
        "the .q[-1] of your simulation, radians",
    ),
    Part(
        "qd_end_ex3",
        "end rates",
        judge_end_rates_5_3,
        "the .qd[-1] of the same simulation, rad/s",
    ),
    Part(
        "drift_ex3",
        "energy drift",
        judge_drift_5_3,
        "spin_ex3.energy_drift(); above 1e-8, tighten the tolerances: DOP853 with rtol = atol = 1e-10",
    ),
    Part(
        "p1_end_ex3",
        "angular momentum",
        judge_momentum_5_3,
        "p1 = (M(q) qd)[0] at your end state; it should equal its starting value",
    ),
    chapter=CHAPTER,
)
