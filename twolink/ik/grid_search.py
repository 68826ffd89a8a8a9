"""Inverse kinematics by exhaustive search over a joint-space grid."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_finite_scalar, real_array
from ..kinematics import distance_outside_reach
from .limits import solutions_within_limits
from .result import IKResult, assemble_result
from .targets import reachable_targets

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["brute_force", "MAX_AXIS_POINTS", "MAX_GRID_POINTS"]

#: Grid points evaluated at once: bounds memory however fine the step, and keeps
#: each chunk (a few 256 KB arrays) in cache; larger chunks measured 2-3x slower.
GRID_CHUNK = 1 << 15

#: Most values on one grid axis (memory budget: a few arrays of this many floats, ~80 MB each).
MAX_AXIS_POINTS = 10_000_000

#: Most grid points searched per target (time budget: about a minute at ~50 ns per point).
MAX_GRID_POINTS = 1_000_000_000


def grid_axis(low: float, high: float, step: float) -> NDArray[np.float64]:
    """Grid values ``low, low + step, ...`` and always ``high`` itself.

    When the range is not a whole number of steps the last spacing is
    shorter: both ends of a joint range are always on the grid (a solution
    on a joint limit is found exactly).

    Examples
    --------
    >>> np.degrees(grid_axis(0.0, np.radians(90.0), np.radians(30.0))).round(9)
    array([ 0., 30., 60., 90.])
    >>> np.degrees(grid_axis(0.0, np.radians(90.0), np.radians(40.0))).round(9)
    array([ 0., 40., 80., 90.])
    >>> grid_axis(0.0, 1.0, 0.0)
    Traceback (most recent call last):
    ...
    ValueError: step (radians) must be > 0.0; got 0.0

    Raises
    ------
    ValueError
        For ends that are not finite with ``low <= high``, a step that is
        not finite and positive, or more than ``MAX_AXIS_POINTS`` values.
    """
    low = as_finite_scalar(low, "low (radians)")
    high = as_finite_scalar(high, "high (radians)")
    step = as_finite_scalar(step, "step (radians)", minimum=0.0, strictly=True)
    if low > high:
        raise ValueError(
            f"a grid axis needs low <= high; got [{low:.6g}, {high:.6g}] rad"
        )
    intervals = (high - low) / step
    if not intervals < MAX_AXIS_POINTS:
        raise ValueError(
            f"a grid axis over [{low:.6g}, {high:.6g}] rad with step {step:.3g} rad would hold "
            f"{intervals + 1:.3g} points, more than MAX_AXIS_POINTS = {MAX_AXIS_POINTS:.0e}: use a larger step"
        )
    count = int(np.floor(intervals + 1e-9)) + 1
    axis = low + step * np.arange(count, dtype=np.float64)
    if high - axis[-1] > 1e-9 * step:
        axis = np.append(axis, high)
    return axis


def _joint_ranges(
    arm: TwoLinkArm,
    q1_range: tuple[float, float] | None,
    q2_range: tuple[float, float] | None,
) -> list[tuple[float, float]]:
    ranges = []
    q_min, q_max = arm.q_min, arm.q_max
    for joint, given in enumerate((q1_range, q2_range)):
        name = f"q{joint + 1}_range"
        if given is None:
            low, high = -np.pi, np.pi
        else:
            ends = real_array(
                given, name, "None or a pair (low, high) of angles in radians"
            )
            if ends.shape != (2,) or not np.all(np.isfinite(ends)):
                raise ValueError(
                    f"{name} must be None or a pair (low, high) of finite angles in radians; got {given!r}"
                )
            low, high = ends.tolist()
        # relative limits bound both joints; absolute ones bound q1 here (link 2 is masked on the grid)
        if (
            q_min is not None
            and q_max is not None
            and (arm.limit_convention == "relative" or joint == 0)
        ):
            low, high = max(low, q_min[joint]), min(high, q_max[joint])
        if low > high:
            raise ValueError(
                f"q{joint + 1} range [{low:.6g}, {high:.6g}] rad is empty "
                "(after intersecting with the arm's joint limits)"
            )
        ranges.append((low, high))
    return ranges


def _best_on_grid(
    arm: TwoLinkArm,
    p_target: NDArray[np.float64],
    q1_axis: NDArray[np.float64],
    q2_axis: NDArray[np.float64],
    absolute_limits: tuple[float, float] | None,
) -> tuple[float, float]:
    """The grid point ``(q1, q2)`` nearest the target, by rows of q1 in chunks.

    With ``a = elbow - p`` the squared distance is
    ``|a|^2 + l2^2 + 2 l2 (cos q2 (c1 ax + s1 ay) + sin q2 (c1 ay - s1 ax))``,
    so each chunk costs two outer products and no trigonometry.
    """
    c1, s1 = np.cos(q1_axis), np.sin(q1_axis)
    c2, s2 = np.cos(q2_axis), np.sin(q2_axis)
    a_x = arm.l1 * c1 - p_target[0]
    a_y = arm.l1 * s1 - p_target[1]
    alpha = c1 * a_x + s1 * a_y
    beta = c1 * a_y - s1 * a_x
    offset = (a_x**2 + a_y**2 + arm.l2**2) / (2.0 * arm.l2)
    rows_per_chunk = max(1, GRID_CHUNK // len(q2_axis))
    best = (np.inf, float(q1_axis[0]), float(q2_axis[0]))
    for start in range(0, len(q1_axis), rows_per_chunk):
        rows = slice(start, start + rows_per_chunk)
        score = np.multiply.outer(alpha[rows], c2)
        score += np.multiply.outer(beta[rows], s2)
        score += offset[rows, None]
        if absolute_limits is not None:
            q2_abs = np.add.outer(q1_axis[rows], q2_axis)
            low, high = absolute_limits
            score[(q2_abs < low - 1e-12) | (q2_abs > high + 1e-12)] = np.inf
        flat = int(np.argmin(score))
        row, column = divmod(flat, len(q2_axis))
        if score[row, column] < best[0]:
            best = (score[row, column], q1_axis[start + row], q2_axis[column])
    if absolute_limits is not None:
        # link 2 along each of its absolute limits, row by row: a limit narrower than the step
        # (a single angle) holds no grid point of q2
        for limit in absolute_limits:
            q2_edge = limit - q1_axis
            score = alpha * np.cos(q2_edge) + beta * np.sin(q2_edge) + offset
            score[(q2_edge < q2_axis[0]) | (q2_edge > q2_axis[-1])] = np.inf
            row = int(np.argmin(score))
            if score[row] < best[0]:
                best = (score[row], q1_axis[row], q2_edge[row])
    return best[1], best[2]


def brute_force(
    arm: TwoLinkArm,
    p: ArrayLike,
    q1_range: tuple[float, float] | None = None,
    q2_range: tuple[float, float] | None = None,
    step: float = float(np.radians(1.0)),
) -> IKResult:
    """The grid point ``(q1, q2)`` whose tip lies nearest each target.

    The grid covers ``q1_range`` x ``q2_range`` (radians, inclusive) with
    spacing ``step``, intersected with the arm's joint limits (absolute-angle
    limits mask grid points instead, and link 2 is also tried along each of
    its absolute limits, so that a limit narrower than the step, even a
    single angle, is found).  The search works in chunks of
    ``GRID_CHUNK`` points, so memory stays bounded however fine the step.  The
    number of grid points grows as ``1 / step^2``; the time approaches that
    growth once the grid work dominates the fixed cost of a call.

    Both ends of each range are on the grid (the last spacing may be
    shorter), so a grid point lies within ``step / 2`` of the exact solution
    in each joint and the tip error is at most ``(l1 + 2 l2) * step / 2``:
    ``success`` is true when the residual is within that bound, the grid
    point respects the joint limits and the target lies in the workspace the
    limits leave (:func:`twolink.workspace.is_reachable`); false otherwise
    (the target needs angles outside the range or the limits).

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Target tip positions in metres.
    q1_range, q2_range : pair of float, optional
        Search ranges in radians; default ``(-pi, pi)`` within the limits.
    step : float
        Grid spacing in radians (> 0).

    Returns
    -------
    IKResult
        ``method="brute-force"``; ``iterations`` is the number of grid points.

    Raises
    ------
    twolink.UnreachableError
        For targets outside the reach annulus.
    ValueError
        For NaN/inf targets, an empty range or a non-positive step.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.brute_force(arms.ten, [10.0, 10.0], step=np.radians(1.0))
    >>> np.degrees(result.q).round(6), bool(result.success)
    (array([ 0., 90.]), True)
    >>> int(result.iterations)
    16471
    """
    p = reachable_targets(arm, p)
    step = as_finite_scalar(step, "step (radians)", minimum=0.0, strictly=True)
    (q1_low, q1_high), (q2_low, q2_high) = _joint_ranges(arm, q1_range, q2_range)
    q1_axis = grid_axis(q1_low, q1_high, step)
    q2_axis = grid_axis(q2_low, q2_high, step)
    if len(q1_axis) * len(q2_axis) > MAX_GRID_POINTS:
        raise ValueError(
            f"a step of {step:.3g} rad makes a grid of {len(q1_axis)} x {len(q2_axis)} = "
            f"{len(q1_axis) * len(q2_axis):.3g} points per target, more than MAX_GRID_POINTS = "
            f"{MAX_GRID_POINTS:.0e}: use a larger step"
        )
    absolute_limits = None
    if (
        arm.q_min is not None
        and arm.q_max is not None
        and arm.limit_convention == "absolute"
    ):
        absolute_limits = (arm.q_min[1], arm.q_max[1])

    p_flat = p.reshape(-1, 2)
    q = np.empty_like(p_flat)
    for index, p_target in enumerate(p_flat):
        q[index] = _best_on_grid(arm, p_target, q1_axis, q2_axis, absolute_limits)

    bound = (arm.l1 + 2.0 * arm.l2) * step / 2.0
    grid_points = len(q1_axis) * len(q2_axis)
    # success needs a grid point within the bound, the point within the limits, and the target
    # inside the workspace the limits leave (a target just outside it is near a limit's grid point)
    within = np.asarray(arm.within_limits(q))
    reachable = np.ravel(
        np.any(solutions_within_limits(arm, p_flat)[1], axis=-1)
    )  # workspace.is_reachable
    threshold = np.where(
        within & reachable, bound + distance_outside_reach(arm, p_flat), -np.inf
    )

    def failure_detail(index: int, residual: float) -> str:
        if not reachable[index]:
            return f"the target is outside the workspace the joint limits leave (best residual {residual:.3g} m)"
        if not within[index]:
            return "no grid point within the joint limits (the searched range and the limits do not meet)"
        return (
            f"best residual {residual:.3g} m, above the grid bound {bound:.3g} m: "
            "the solution lies outside the searched range"
        )

    return assemble_result(
        arm,
        p,
        q.reshape(p.shape),
        grid_points,
        threshold,
        "brute-force",
        solved_message=f"all {len(q)} targets within the grid bound {bound:.3g} m ({grid_points} points)",
        failure_detail=failure_detail,
    )
