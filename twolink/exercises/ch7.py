"""Chapter 7 (workspace and trajectories): exercises 7.1 to 7.3."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .. import arms, trajectory, workspace
from ..ik.analytic import closed_form
from .registry import Part, Wrong, close, matches, reference, register, scalar

CHAPTER = "07_workspace_trajectories"
LIMIT_DEG_7_1 = 35.0  # arms.two_metre_limited: link angles in [35, 145] deg
CENTRE_7_2, SHRINK_7_2, DURATION_7_2, SAMPLES_7_2 = (14.0, 6.0), 0.999, 3.0, 60
LINE_7_3, DURATION_7_3, RTOL_7_3 = ((-3.5, 1.0), (-1.0, 3.5)), 5.0, 1e-6


@reference
def radius_7_1() -> float:
    """The largest inscribed circle's radius of arms.two_metre_limited, from the tangency condition.

    Centre (0, R - rho), R = l1 + l2, touching from outside the circles of
    radius l2 about the elbows l1 (+-cos 35, sin 35):
    (l1 c)^2 + (R - rho - l1 s)^2 = (l2 + rho)^2, linear in rho.
    """
    arm = arms.two_metre_limited
    c, s = np.cos(np.radians(LIMIT_DEG_7_1)), np.sin(np.radians(LIMIT_DEG_7_1))
    height = arm.l1 + arm.l2 - arm.l1 * s
    return float(
        ((arm.l1 * c) ** 2 + height**2 - arm.l2**2) / (2 * height + 2 * arm.l2)
    )


def judge_radius_7_1(answer: object, siblings: dict[str, object]) -> None:
    rho = scalar(answer)
    arm = arms.two_metre_limited
    if rho <= 0:
        raise Wrong("a radius is positive")
    c, s = (
        np.cos(LIMIT_DEG_7_1),
        np.sin(LIMIT_DEG_7_1),
    )  # the mistake: degrees fed to cos and sin
    height = arm.l1 + arm.l2 - arm.l1 * s
    if matches(
        close,
        rho,
        ((arm.l1 * c) ** 2 + height**2 - arm.l2**2) / (2 * height + 2 * arm.l2),
        atol=1e-6,
    ):
        raise Wrong(
            "35 went into cos and sin as radians: use np.radians(35) (or sp.rad(35))"
        )
    close(rho, radius_7_1(), atol=1e-6)


@reference
def radius_7_2() -> float:
    """The room about (14, 6) on arms.ten's elbow-up branch."""
    return float(workspace.clearance(arms.ten, CENTRE_7_2, elbow="up"))


@reference
def largest_step_7_2() -> float:
    """The largest joint step (deg) tracing 0.999 of that circle in 3 s, quintic law, 60 samples."""
    path = trajectory.CirclePath(
        CENTRE_7_2, SHRINK_7_2 * radius_7_2(), duration=DURATION_7_2, law="quintic"
    )
    motion = trajectory.ik_trajectory(arms.ten, path, n=SAMPLES_7_2, elbow="up")
    return float(np.degrees(motion.joint_steps.max()))


def judge_radius_7_2(answer: object, siblings: dict[str, object]) -> None:
    radius = scalar(answer)
    for elbow, name in (("auto", "either branch"), ("down", "the elbow-down branch")):
        other = float(workspace.clearance(arms.ten, CENTRE_7_2, elbow=elbow))
        if not np.isclose(other, radius_7_2(), atol=1e-6) and matches(
            close, radius, other, atol=1e-9
        ):
            raise Wrong(f"this is the room on {name}; the task is elbow up")
    close(radius, radius_7_2(), atol=1e-9)


def judge_step_7_2(answer: object, siblings: dict[str, object]) -> None:
    step_deg = scalar(answer)
    if matches(close, step_deg, np.radians(largest_step_7_2()), atol=1e-6):
        raise Wrong("this is in radians; the task asks for degrees")
    close(step_deg, largest_step_7_2(), atol=1e-6)


def _line_path() -> trajectory.LinePath:
    return trajectory.LinePath(*LINE_7_3, duration=DURATION_7_3, law="quintic")


def _peak_rate_at(t: ArrayLike, elbow: str) -> NDArray[np.float64]:
    p, v = _line_path().at(np.atleast_1d(t))
    return np.abs(
        arms.two_metre.joint_rates(closed_form(arms.two_metre, p, elbow=elbow).q, v)
    ).max(axis=-1)


@reference
def peak_rate_7_3() -> float:
    """The largest |joint rate| (rad/s) of the line task, quintic law: exact rates, refined near the peak."""
    path = _line_path()
    motion = trajectory.ik_trajectory(arms.two_metre, path, n=20001)
    t, _, v = path.sample(20001)
    rates = np.abs(arms.two_metre.joint_rates(motion.q, v)).max(axis=-1)
    i = int(np.argmax(rates))
    low, high = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
    import scipy.optimize  # here, not at the top: import twolink stays light

    best = scipy.optimize.minimize_scalar(
        lambda time: -_peak_rate_at(time, motion.elbow)[0],
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return float(max(rates[i], -best.fun))


def judge_rate_7_3(answer: object, siblings: dict[str, object]) -> None:
    rate = scalar(answer)
    if matches(close, rate, np.degrees(peak_rate_7_3()), rtol=1e-3):
        raise Wrong("this is in deg/s; the task asks for rad/s")
    error = abs(rate - peak_rate_7_3()) / peak_rate_7_3()
    if rate < peak_rate_7_3() and error > RTOL_7_3:
        raise Wrong(
            f"{error:.2g} relative below the peak (allowed {RTOL_7_3:g}): sample more finely"
        )
    close(rate, peak_rate_7_3(), rtol=RTOL_7_3)


register(
    "7.1",
    Part(
        "rho_two_metre",
        "radius",
        judge_radius_7_1,
        "distance between the centres = 2 + rho; the equation is linear in rho",
    ),
    chapter=CHAPTER,
)
register(
    "7.2",
    Part(
        "radius_up",
        "radius",
        judge_radius_7_2,
        "workspace.clearance with elbow='up' is the room about a point on that branch",
    ),
    Part(
        "largest_step_deg",
        "step",
        judge_step_7_2,
        "JointTrajectory.joint_steps, in radians: convert",
    ),
    chapter=CHAPTER,
)
register(
    "7.3",
    Part(
        "max_joint_rate",
        "peak joint rate",
        judge_rate_7_3,
        "ik_trajectory(...).qd holds the joint rates; take the largest absolute value over enough samples",
    ),
    chapter=CHAPTER,
)
