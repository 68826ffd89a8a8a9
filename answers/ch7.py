"""Chapter 7 (workspace and trajectories): the references of exercises 7.1 to 7.5, with typical mistakes and hints.

Exercises 7.2, 7.3 and 7.5 are graded on hidden inputs too (``RERUN``); 7.4's
function on hidden cases (``HIDDEN``) with the package's reachability tests
switched off (``FORBIDDEN``); 7.1 and parts of 7.5 are worked on paper
(``PEN_AND_PAPER``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
import scipy.optimize

from answers import Rerun
from answers._draws import first_valid
from twolink import TwoLinkArm, arms, ik, trajectory, workspace
from twolink_course.exercises.spec import (
    Case,
    ExerciseSpec,
    Mistake,
    PartSpec,
    Tolerance,
)

CHAPTER = "07_workspace_trajectories"
LIMIT_DEG_7_1 = 35.0  # arms.two_metre_limited: link angles in [35, 145] deg
CENTRE_7_2, SHRINK_7_2, DURATION_7_2, SAMPLES_7_2 = (11.5, 12.0), 0.999, 3.0, 60
LINE_7_3, DURATION_7_3, RTOL_7_3 = ((-3.5, 1.0), (-1.0, 3.5)), 5.0, 1e-6
SECTION_SAMPLES_7_3 = 50  # the line task's samples in the chapter's section
CENTRE_7_5, RADIUS_7_5, DURATION_7_5, SAMPLES_7_5 = (12.5, 12.5), 2.0, 4.0, 4001
CIRCLE_POINTS_7_5 = 16  # section 5's points
BUDGET_SHARE_7_5 = (20e-6 + 6 * 6e-6) / 1e-3  # a call's 20 us and 6 iterations of 6 us


# ------------------------------------------------------------------ 7.1


def _rho_7_1(
    elbow_distance: float, cos_35: float, sin_35: float, outside: bool
) -> float:
    """The radius from (elbow_distance cos, R - rho - elbow_distance sin)^2 = (l2 +- rho)^2."""
    arm = arms.two_metre_limited
    height = arm.l1 + arm.l2 - elbow_distance * sin_35
    sign = 1.0 if outside else -1.0
    return float(
        ((elbow_distance * cos_35) ** 2 + height**2 - arm.l2**2)
        / (2 * height + sign * 2 * arm.l2)
    )


def exercise_7_1() -> ExerciseSpec:
    arm = arms.two_metre_limited
    c, s = np.cos(np.radians(LIMIT_DEG_7_1)), np.sin(np.radians(LIMIT_DEG_7_1))
    rho = _rho_7_1(arm.l1, c, s, outside=True)
    numeric = workspace.largest_inscribed_circle(arm)[1]
    assert abs(rho - numeric) < 1e-6, (rho, numeric)  # the closed form is the largest
    return ExerciseSpec(
        "7.1",
        CHAPTER,
        (
            PartSpec(
                "rho_two_metre",
                "radius",
                "number",
                expected=rho,
                unit="m",
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        _rho_7_1(
                            arm.l1,
                            np.cos(LIMIT_DEG_7_1),
                            np.sin(LIMIT_DEG_7_1),
                            outside=True,
                        ),
                        "35 went into cos and sin as radians: convert the degrees "
                        "first (np.radians, or sp.rad with sympy)",
                    ),
                    Mistake(
                        _rho_7_1(arm.l1, c, s, outside=False),
                        "this radius makes the circle touch the elbow circles from "
                        "inside (distance between the centres rho - 2): it touches them "
                        "from outside, so the distance is 2 + rho",
                    ),
                    Mistake(
                        _rho_7_1(1.0, c, s, outside=True),
                        "the elbows are l1 = 2 m from the base, not 1 m: each elbow "
                        "point is 2 times (cos, sin) of the limit angle",
                    ),
                    Mistake(
                        _rho_7_1(arm.l1, s, c, outside=True),
                        "cos and sin are swapped in the elbow's position: its x is "
                        "2 cos 35°, its height 2 sin 35°",
                    ),
                ),
                hints=(
                    "Reread 'Both workspaces' (which arcs bound the limited 2 m arm) "
                    "and 'The largest circle, in closed form': where does the largest "
                    "circle touch those arcs?",
                    "Two circles that touch from outside have their centres the sum "
                    "of their radii apart. Write the squared distance from (0, 4 - "
                    "rho) to one elbow point, angles in radians: the rho squared "
                    "cancels and the equation is linear in rho.",
                ),
            ),
        ),
    )


# ------------------------------------------------------------------ 7.2


def _largest_step_deg(
    radius: float,
    n: int = SAMPLES_7_2,
    law: str = "quintic",
    arm: TwoLinkArm = arms.ten,
    centre: object = CENTRE_7_2,
    duration: float = DURATION_7_2,
) -> float:
    path = trajectory.CirclePath(centre, radius, duration=duration, law=law)
    motion = trajectory.ik_trajectory(arm, path, n=n, elbow="up")
    return float(np.degrees(motion.joint_steps.max()))


def _inputs_7_2() -> dict[str, object]:
    return {
        "arm_ex2": arms.ten,
        "centre_ex2": np.array(CENTRE_7_2),
        "duration_ex2": DURATION_7_2,
        "samples_ex2": SAMPLES_7_2,
    }


def _answers_7_2(inputs: dict) -> dict[str, object]:
    arm, centre = inputs["arm_ex2"], inputs["centre_ex2"]
    radius = float(workspace.clearance(arm, centre, elbow="up"))
    step = _largest_step_deg(
        SHRINK_7_2 * radius,
        n=inputs["samples_ex2"],
        arm=arm,
        centre=centre,
        duration=inputs["duration_ex2"],
    )
    return {"radius_up": radius, "largest_step_deg": step}


def _draw_7_2(rng: np.random.Generator) -> dict[str, object] | None:
    inputs = {
        "arm_ex2": arms.ten,
        "centre_ex2": rng.uniform(2.0, 18.0, 2).round(2),
        "duration_ex2": round(float(rng.uniform(2.0, 5.0)), 1),
        "samples_ex2": int(rng.integers(40, 100)),
    }
    if workspace.clearance(arms.ten, inputs["centre_ex2"], elbow="up") < 1.0:
        return None
    try:
        _answers_7_2(inputs)
    except ValueError:  # a circle the branch cannot trace whole
        return None
    return inputs


def _hidden_7_2(rng: np.random.Generator) -> dict[str, object]:
    """Another centre with room on the elbow-up branch of arms.ten, and another timing."""
    return first_valid(_draw_7_2, rng, what="exercise 7.2's hidden inputs")


def exercise_7_2() -> ExerciseSpec:
    arm = arms.ten
    room = {
        elbow: float(workspace.clearance(arm, CENTRE_7_2, elbow=elbow))
        for elbow in ("auto", "down", "up")
    }
    radius_up = room["up"]
    step = _largest_step_deg(SHRINK_7_2 * radius_up)
    return ExerciseSpec(
        "7.2",
        CHAPTER,
        (
            PartSpec(
                "radius_up",
                "radius",
                "number",
                expected=radius_up,
                unit="m",
                mistakes=(
                    Mistake(
                        room["auto"],
                        "this is the room on either branch: the circle is traced with "
                        "the elbow up throughout, whose own workspace has less room "
                        "about this centre",
                    ),
                    Mistake(
                        room["down"],
                        "this is the room on the elbow-down branch; the task is elbow up",
                    ),
                    Mistake(
                        arm.reach[1] - float(np.hypot(*CENTRE_7_2)),
                        "this is the distance to the outer reach circle: it ignores the "
                        "joint limits, whose arcs come nearer",
                    ),
                ),
                hints=(
                    "Reread 'A circle in the workspace, and the largest one': the room "
                    "about a point is its clearance, the distance to the workspace's "
                    "edge.",
                    "A motion that must not flip its elbow lives in the workspace of "
                    "one branch, whose edge is not that of the either-branch "
                    "workspace: the package's clearance can be told which branch "
                    "counts.",
                ),
            ),
            PartSpec(
                "largest_step_deg",
                "largest joint step",
                "number",
                expected=step,
                unit="deg",
                mistakes=(
                    Mistake(
                        float(np.radians(step)),
                        "this is in radians; the task asks for degrees",
                    ),
                    Mistake(
                        _largest_step_deg(SHRINK_7_2 * radius_up, n=SAMPLES_7_2 + 1),
                        "this is the step for one sample too many: the task takes 60 "
                        "samples, both ends included",
                    ),
                    Mistake(
                        _largest_step_deg(SHRINK_7_2 * radius_up, law="linear"),
                        "this is the constant-speed ('linear') law's step: the task "
                        "uses the quintic law, which is fastest mid-way",
                    ),
                    Mistake(
                        _largest_step_deg(SHRINK_7_2 * radius_up, law="cubic"),
                        "this is the cubic law's step: the task uses the quintic law",
                    ),
                ),
                hints=(
                    "Reread 'The arm on the circle': a CirclePath with a time law, "
                    "then ik_trajectory on one branch.",
                    "The motion's joint steps hold, in radians, the largest change of "
                    "either joint between consecutive samples; use the samples, "
                    "duration and law the task states, and convert the largest.",
                ),
            ),
        ),
    )


# ------------------------------------------------------------------ 7.3


def _line(
    law: str, ends=LINE_7_3, duration: float = DURATION_7_3
) -> trajectory.LinePath:
    return trajectory.LinePath(*ends, duration=duration, law=law)


def _peak_rate(
    law: str = "quintic",
    joint: int | None = None,
    arm: TwoLinkArm = arms.two_metre,
    ends=LINE_7_3,
    duration: float = DURATION_7_3,
) -> float:
    """The largest |joint rate| (rad/s) of a line task: exact rates, refined near the peak.

    ``joint`` None: either joint; 0 or 1: that joint only.
    """
    path = _line(law, ends, duration)
    columns = slice(None) if joint is None else slice(joint, joint + 1)

    def rate(t: float | np.ndarray, elbow: str) -> np.ndarray:
        p, v = path.at(np.atleast_1d(t))
        q = ik.closed_form(arm, p, elbow=elbow).q
        return np.abs(arm.joint_rates(q, v)[..., columns]).max(axis=-1)

    motion = trajectory.ik_trajectory(arm, path, n=20001)
    t = motion.t
    rates = rate(t, motion.elbow)
    i = int(np.argmax(rates))
    low, high = t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)]
    best = scipy.optimize.minimize_scalar(
        lambda time: -rate(time, motion.elbow)[0],
        bounds=(low, high),
        method="bounded",
        options={"xatol": 1e-10},
    )
    return float(max(rates[i], -best.fun))


def _inputs_7_3() -> dict[str, object]:
    return {
        "arm_ex3": arms.two_metre,
        "line_start_ex3": np.array(LINE_7_3[0]),
        "line_end_ex3": np.array(LINE_7_3[1]),
        "duration_ex3": DURATION_7_3,
    }


def _answers_7_3(inputs: dict) -> dict[str, object]:
    ends = (inputs["line_start_ex3"], inputs["line_end_ex3"])
    return {
        "max_joint_rate": _peak_rate(
            arm=inputs["arm_ex3"], ends=ends, duration=inputs["duration_ex3"]
        )
    }


def _draw_7_3(rng: np.random.Generator) -> dict[str, object] | None:
    arm = arms.two_metre
    ends = [
        arm.fk([rng.uniform(-np.pi, np.pi), rng.uniform(0.6, 2.2)]) for _ in range(2)
    ]
    start, end = (np.round(point, 2) for point in ends)
    inputs = {
        "arm_ex3": arm,
        "line_start_ex3": start,
        "line_end_ex3": end,
        "duration_ex3": round(float(rng.uniform(2.0, 6.0)), 1),
    }
    path = _line("quintic", (start, end), inputs["duration_ex3"])
    try:  # on one branch, and the chapter's 2001 samples meet the 1e-6 asked
        sampled = trajectory.ik_trajectory(arm, path, n=2001)
        peak = _answers_7_3(inputs)["max_joint_rate"]
    except ValueError:
        return None
    if (
        np.linalg.norm(end - start) > 1.0
        and abs(np.abs(sampled.qd).max() - peak) < 1e-7 * peak
    ):
        return inputs
    return None


def _hidden_7_3(rng: np.random.Generator) -> dict[str, object]:
    """Another line well inside the 2 m arm's reach, away from its base, another duration."""
    return first_valid(_draw_7_3, rng, what="exercise 7.3's hidden inputs")


def exercise_7_3() -> ExerciseSpec:
    peak = _peak_rate()
    sampled = trajectory.ik_trajectory(
        arms.two_metre, _line("quintic"), n=SECTION_SAMPLES_7_3
    )
    return ExerciseSpec(
        "7.3",
        CHAPTER,
        (
            PartSpec(
                "max_joint_rate",
                "peak joint rate",
                "number",
                expected=peak,
                unit="rad/s",
                tolerance=Tolerance(atol=0.0, rtol=RTOL_7_3),
                mistakes=(
                    Mistake(
                        float(np.degrees(peak)),
                        "this is in deg/s; the task asks for rad/s",
                    ),
                    Mistake(
                        float(np.abs(sampled.qd).max()),
                        "this is the peak over the section's 50 samples: the true peak "
                        "falls between samples, so sample more finely",
                    ),
                    Mistake(
                        -peak,
                        "this rate is negative: the largest joint rate is the largest "
                        "in size, its absolute value",
                    ),
                    Mistake(
                        _peak_rate(joint=1),
                        "this is joint 2's peak (also what qd.max() gives without abs): "
                        "joint 1's rate is larger in size, though negative",
                    ),
                    Mistake(
                        _peak_rate(law="linear"),
                        "this is the peak with the constant-speed ('linear') law; the "
                        "task uses the quintic law",
                    ),
                ),
                hints=(
                    "Reread 'Straight-line tracking on the 2 m arm': with the quintic "
                    "law the joint rates peak somewhere between the samples.",
                    "A motion's qd holds both joints' rates at every sample; a rate's "
                    "size is its absolute value. Raise the number of samples until the "
                    "peak no longer changes in its sixth significant digit.",
                ),
            ),
        ),
    )


# ------------------------------------------------------------------ 7.4: a function


def _arm_argument(arm: TwoLinkArm) -> dict[str, object]:
    """An arm with limits as a case's argument (``{"arm": {...}}``)."""
    return {
        "arm": {
            "l1": float(arm.l1),
            "l2": float(arm.l2),
            "q_min": [float(v) for v in arm.q_min],
            "q_max": [float(v) for v in arm.q_max],
            "limit_convention": arm.limit_convention,
        }
    }


#: An arm whose q1 limits run past 180 deg: atan2's angles need comparing modulo 360 deg.
WRAP_ARM_7_4 = TwoLinkArm(
    l1=1.0,
    l2=0.6,
    q_min=(np.radians(100.0), np.radians(-120.0)),
    q_max=(np.radians(260.0), np.radians(120.0)),
)

#: The visible calls of reachable(arm, p): each mistake below answers one of them wrongly.
VISIBLE_7_4 = (
    (arms.ten, (12.5, 12.5)),  # both branches
    (arms.ten, (15.0, 1.0)),  # elbow up only
    (arms.ten, (1.0, 15.0)),  # elbow down only
    (arms.ten, (21.0, 0.0)),  # beyond the reach
    (arms.two_metre_limited, (0.0, 3.0)),  # absolute limits, reached
    (arms.two_metre_limited, (3.0, 1.0)),  # within the reach, outside the limits
    (arms.two_metre_limited, (-1.0, 3.0)),  # relative limits would allow it
    (WRAP_ARM_7_4, (-0.8, -0.8)),  # q1 near -130 deg = 230 deg, inside [100, 260]
)


def reachable_7_4(arm: TwoLinkArm, p: object) -> bool:
    """The reference: a configuration within the arm's limits, on either branch, puts the tip at p."""
    return bool(workspace.is_reachable(arm, np.asarray(p, dtype=float)))


def _in_annulus(arm: TwoLinkArm, p: object) -> bool:
    low, high = arm.reach
    return bool(low <= np.hypot(*np.asarray(p, dtype=float)) <= high)


def _limits_ignored(arm: TwoLinkArm, p: object) -> bool:
    return _in_annulus(arm, p)


def _one_branch(elbow: str) -> Callable[[TwoLinkArm, object], bool]:
    def reachable(arm: TwoLinkArm, p: object) -> bool:
        return bool(
            workspace.is_reachable(arm, np.asarray(p, dtype=float), elbow=elbow)
        )

    return reachable


def _not_wrapped(arm: TwoLinkArm, p: object) -> bool:
    """The angles as atan2 gives them, compared with the limits without turning them."""
    if not _in_annulus(arm, p):
        return False
    q = ik.closed_form(arm, np.asarray(p, dtype=float), elbow="both").q
    if arm.limit_convention == "absolute":
        q = np.stack([q[:, 0], q[:, 0] + q[:, 1]], axis=-1)
    low, high = np.array(arm.q_min), np.array(arm.q_max)
    inside = (q >= low - ik.LIMIT_TOL) & (q <= high + ik.LIMIT_TOL)
    return bool(np.any(np.all(inside, axis=-1)))


def _convention_ignored(arm: TwoLinkArm, p: object) -> bool:
    return reachable_7_4(dataclasses.replace(arm, limit_convention="relative"), p)


def exercise_7_4() -> ExerciseSpec:
    def returns(function: Callable[[TwoLinkArm, object], bool]) -> list[bool]:
        return [function(arm, p) for arm, p in VISIBLE_7_4]

    cases = tuple(
        Case(
            {"arm": _arm_argument(arm), "p": [float(x) for x in p]},
            reachable_7_4(arm, p),
        )
        for arm, p in VISIBLE_7_4
    )
    return ExerciseSpec(
        "7.4",
        CHAPTER,
        (
            PartSpec(
                "reachable",
                "function reachable(arm, p)",
                "function",
                cases=cases,
                output=PartSpec("reachable", "answer", "bool"),
                mistakes=(
                    Mistake(
                        returns(_limits_ignored),
                        "your function ignores the joint limits: a point within the "
                        "links' reach can still need angles outside them",
                    ),
                    Mistake(
                        returns(_one_branch("down")),
                        "your function counts the elbow-down branch only: a point that "
                        "only the elbow-up branch reaches within the limits is "
                        "reachable too",
                    ),
                    Mistake(
                        returns(_one_branch("up")),
                        "your function counts the elbow-up branch only: a point that "
                        "only the elbow-down branch reaches within the limits is "
                        "reachable too",
                    ),
                    Mistake(
                        returns(_not_wrapped),
                        "your function compares the angles as atan2 returns them, in "
                        "(-180°, 180°], with limits that run past 180°: compare them "
                        "modulo a full turn",
                    ),
                    Mistake(
                        returns(_convention_ignored),
                        "your function checks q2 against the limits of an arm whose "
                        "limits are absolute: there they bound the link angles q1 and "
                        "q1 + q2 (arm.limit_convention says which)",
                    ),
                ),
                hints=(
                    "Reread 'Is a point reachable?': both elbow branches, each checked "
                    "against the limits in the arm's own convention.",
                    "Chapter 2's closed form gives both branches; a point outside the "
                    "reach annulus has none. Which angles do absolute limits bound?",
                    "Compare an angle with its interval modulo a full turn: shift it "
                    "by whole turns to the turn nearest the interval first.",
                ),
            ),
        ),
    )


def _robust(arm: TwoLinkArm, p: np.ndarray, answer: bool) -> bool:
    """Whether points 1e-3 reach around p give the same answer (p is not on an edge)."""
    step = 1e-3 * arm.reach[1]
    around = p + step * np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [0, 0]])
    return bool(np.all(workspace.is_reachable(arm, around) == answer))


def hidden_7_4(rng: np.random.Generator, count: int) -> list[Case]:
    """Random arms with limits in either convention, half reachable points, half not."""
    visible = {
        (repr(_arm_argument(arm)), tuple(map(float, p))) for arm, p in VISIBLE_7_4
    }
    cases: list[Case] = []
    while len(cases) < count:
        low = rng.uniform(-180.0, 180.0, 2)
        width = rng.uniform(60.0, 300.0, 2)
        arm = TwoLinkArm(
            l1=round(float(rng.uniform(0.5, 3.0)), 3),
            l2=round(float(rng.uniform(0.5, 3.0)), 3),
            q_min=tuple(np.radians(np.round(low, 1))),
            q_max=tuple(np.radians(np.round(low + width, 1))),
            limit_convention=str(rng.choice(["relative", "absolute"])),
        )
        want = len(cases) % 2 == 0  # alternately a reachable and an unreachable point
        for _ in range(200):
            if want:  # the tip of a configuration within the limits
                angles = rng.uniform(arm.q_min, arm.q_max)
                q = (
                    angles
                    if arm.limit_convention == "relative"
                    else np.array([angles[0], angles[1] - angles[0]])
                )
                p = np.round(arm.fk(q), 3)
            else:
                p = np.round(rng.uniform(-1.2, 1.2, 2) * arm.reach[1], 3)
            if (
                reachable_7_4(arm, p) == want
                and _robust(arm, p, want)
                and (repr(_arm_argument(arm)), tuple(map(float, p))) not in visible
            ):
                cases.append(
                    Case({"arm": _arm_argument(arm), "p": [float(x) for x in p]}, want)
                )
                break
    order = rng.permutation(len(cases))
    return [cases[i] for i in order]


HIDDEN = {("7.4", "reachable"): hidden_7_4}


# ------------------------------------------------------------------ 7.5


def _inputs_7_5() -> dict[str, object]:
    return {
        "arm_ex5": arms.ten,
        "centre_ex5": np.array(CENTRE_7_5),
        "radius_ex5": RADIUS_7_5,
        "samples_ex5": SAMPLES_7_5,
    }


def _largest_step_7_5(
    inputs: dict, law: str = "quintic", n: int | None = None
) -> float:
    path = trajectory.CirclePath(
        inputs["centre_ex5"], inputs["radius_ex5"], duration=DURATION_7_5, law=law
    )
    samples = inputs["samples_ex5"] if n is None else n
    return float(
        trajectory.ik_trajectory(inputs["arm_ex5"], path, n=samples).joint_steps.max()
    )


def _answers_7_5(inputs: dict) -> dict[str, object]:
    return {
        "largest_step_ex5": _largest_step_7_5(inputs),
        "budget_share_ex5": BUDGET_SHARE_7_5,
        "reason_ex5": "a",
    }


def _draw_7_5(rng: np.random.Generator) -> dict[str, object] | None:
    centre = rng.uniform(4.0, 16.0, 2).round(2)
    room = float(workspace.clearance(arms.ten, centre))
    if room < 1.0:
        return None
    inputs = {
        "arm_ex5": arms.ten,
        "centre_ex5": centre,
        "radius_ex5": round(float(rng.uniform(0.5, room * 0.9)), 2),
        "samples_ex5": int(rng.integers(1000, 5000)),
    }
    try:
        _answers_7_5(inputs)
    except ValueError:  # no branch traces it whole
        return None
    return inputs


def _hidden_7_5(rng: np.random.Generator) -> dict[str, object]:
    """Another circle traced whole on one branch of arms.ten, at another sampling rate."""
    return first_valid(_draw_7_5, rng, what="exercise 7.5's hidden inputs")


def exercise_7_5() -> ExerciseSpec:
    inputs = _inputs_7_5()
    step = _largest_step_7_5(inputs)
    return ExerciseSpec(
        "7.5",
        CHAPTER,
        (
            PartSpec(
                "largest_step_ex5",
                "warm start's largest distance",
                "number",
                expected=step,
                unit="rad",
                tolerance=Tolerance(atol=1e-9, rtol=1e-6),
                mistakes=(
                    Mistake(
                        float(np.degrees(step)),
                        "this is in degrees; the exercise asks for radians",
                    ),
                    Mistake(
                        _largest_step_7_5(inputs, n=CIRCLE_POINTS_7_5),
                        "this is the step between the 16 points of section 5; at 1 kHz "
                        "the samples are 1 ms apart: use the exercise's samples",
                    ),
                    Mistake(
                        _largest_step_7_5(inputs, law="linear"),
                        "this is the constant-speed law; section 5's path uses the "
                        "quintic law",
                    ),
                ),
                hints=(
                    "Section 6: at 1 kHz each sample starts from the previous one's "
                    "answer; the distance between them is the change of the joint angles.",
                    "Make section 5's CirclePath (4 s, quintic), solve it with "
                    "trajectory.ik_trajectory at the exercise's samples, and take the "
                    "largest of its joint_steps, in radians.",
                ),
            ),
            PartSpec(
                "budget_share_ex5",
                "share of the cycle",
                "number",
                expected=BUDGET_SHARE_7_5,
                tolerance=Tolerance(significant=3),
                mistakes=(
                    Mistake(
                        (20e-6 + 6e-6) / 1e-3,
                        "this counts one iteration: the slowest point needs 6",
                    ),
                    Mistake(
                        6 * 6e-6 / 1e-3,
                        "the call's own 20 us are missing",
                    ),
                    Mistake(
                        100 * BUDGET_SHARE_7_5,
                        "this is a percentage; give the share as a number between 0 "
                        "and 1",
                    ),
                ),
                hints=(
                    "The time at the slowest point is the call's own time plus its "
                    "iterations' time; the share is that over the cycle.",
                    "20 us + 6 x 6 us, over 1 ms (1000 us).",
                ),
            ),
            PartSpec(
                "reason_ex5",
                "reason",
                "text",
                expected="a",
                mistakes=(
                    Mistake(
                        "b",
                        "at 1 kHz the samples are millimetres apart, yet Newton still "
                        "takes a few iterations: closeness is not what limits the saving",
                    ),
                    Mistake(
                        "c",
                        "Newton's iterations start from the guess and improve it; a "
                        "better guess does help, only by little",
                    ),
                ),
                hints=(
                    "Reread section 6's sentence on why warm starts save little.",
                    "How fast does Newton's error shrink from one iteration to the "
                    "next, near the answer?",
                ),
            ),
        ),
    )


#: The value exercises graded on hidden inputs too: the inputs cell, a hidden draw, the references.
RERUN = {
    "7.2": Rerun(inputs=_inputs_7_2(), hidden=_hidden_7_2, answers=_answers_7_2),
    "7.3": Rerun(inputs=_inputs_7_3(), hidden=_hidden_7_3, answers=_answers_7_3),
    "7.5": Rerun(inputs=_inputs_7_5(), hidden=_hidden_7_5, answers=_answers_7_5),
}

#: The package's one-liners a function part must not call (dotted paths): switched off while it runs.
FORBIDDEN = {
    ("7.4", "reachable"): (
        "twolink.workspace.is_reachable",
        "twolink.workspace.require_reachable",
        "twolink.workspace.clearance",
        "twolink.workspace.BranchTable",
        "twolink.ik.limits.solutions_within_limits",
        "twolink.ik.turns.move_into_limits",
        "twolink.trajectory.ik_trajectory",
    ),
}

#: Parts worked on paper: checked on the visible values only (7.5's also on hidden
#: runs, where they do not change), timed as pen-and-paper parts.
PEN_AND_PAPER = (
    ("7.1", "rho_two_metre"),
    ("7.5", "budget_share_ex5"),
    ("7.5", "reason_ex5"),
)


def exercises() -> list[ExerciseSpec]:
    """The chapter's exercises, computed from their data."""
    return [
        exercise_7_1(),
        exercise_7_2(),
        exercise_7_3(),
        exercise_7_4(),
        exercise_7_5(),
    ]
