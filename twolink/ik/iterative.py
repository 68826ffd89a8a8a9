"""Newton's method on the forward-kinematics equations, vectorised over targets.

One target and one start given as pairs of floats are solved by a plain
Python loop with the :mod:`math` module, a batch by the same loop on numpy
arrays: the same formulas (the tip and Jacobian of
:mod:`twolink.kinematics`, the step :func:`_lm_step`, the wrap
:func:`_wrap`, each written once for floats and arrays), the same acceptance
and damping schedule, the same result.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._derived import has_cache
from .._validate import (
    as_count,
    as_finite_scalar,
    broadcast_start,
    pair_floats,
    require_arm,
)
from ..conventions import wrap_angle
from ..kinematics import (
    REACH_RTOL,
    distance_outside_reach,
    jacobian_from_trig,
    tip_from_trig,
)
from .result import IKResult, assemble_result, one_answer_result
from .targets import reachable_targets

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["newton", "TOL_MAX"]

#: The largest ``tol`` :func:`newton` accepts: success then means a tip within
#: 1 % of the reach ``l1 + l2`` of the target.  Beyond it "success" would say
#: little (at ``tol = 2`` every answer succeeds: no tip within the reach is
#: further than ``2 (l1 + l2)`` from a reachable target).
TOL_MAX = 1e-2


def newton(
    arm: TwoLinkArm,
    p: ArrayLike,
    q0: ArrayLike = (0.5, 1.0),
    tol: float = 1e-12,
    max_iter: int = 100,
) -> IKResult:
    """Solve ``fk(q) = p`` by Newton's method with step control and angle wrapping.

    Each iteration takes the damped Newton (Levenberg-Marquardt) step
    ``dq = -(J^T J + lam I)^(-1) J^T (fk(q) - p)`` and keeps it only if it
    lowers the residual; ``lam`` shrinks after a good step (tending to the
    full Newton step ``-J^(-1) r``, which converges quadratically) and grows
    after a bad one (tending to a short gradient step).  Angles are wrapped to
    ``[-pi, pi)`` after each step.  Plain full Newton steps from a cold start
    overshoot or stall near singular configurations; this control makes the
    iteration converge from almost every start, not from all: a stretched
    or folded start whose arm points along the target (``q0 = (0, 0)`` for
    ``p = (3, 0)`` on the 2 m arm) has a zero gradient, and the iteration
    stops there with ``success`` false.  Joint limits are not applied: read
    the result's ``within_limits``.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Target tip positions in metres.
    q0 : array_like, shape (2,) or (..., 2)
        Starting joint angles in radians (broadcast against the targets).
    tol : float
        Success when ``|fk(q) - p| <= tol * (l1 + l2)`` (plus the distance
        outside the reach for targets on a boundary within round-off); in
        ``(0, TOL_MAX]`` (``TOL_MAX = 0.01``).
    max_iter : int
        Iteration cap per target.

    Returns
    -------
    IKResult
        ``method="newton"``; the branch found depends on ``q0``.

    Raises
    ------
    twolink.UnreachableError
        For targets outside the reach (message gives distance and reach).
    ValueError
        For NaN/inf targets or starts, a ``tol`` outside ``(0, TOL_MAX]``
        or a non-positive ``max_iter``.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.newton(arms.ten, [[10.0, 10.0], [-5.0, 12.0]], q0=[0.5, 1.0])
    >>> result.success
    array([ True,  True])
    >>> bool(np.all(result.residual < 1e-10))
    True
    """
    target = pair_floats(p)
    q0_pair = pair_floats(q0) if target is not None else None
    if target is not None and q0_pair is not None:
        if not has_cache(arm):  # a TwoLinkArm is an arm; check anything else
            require_arm(arm)
        distance = math.hypot(target[0], target[1])
        r_min, r_max = abs(arm.l1 - arm.l2), arm.l1 + arm.l2
        slack = REACH_RTOL * r_max
        # one target well inside the reach (a target on the edge of the tolerance is left to
        # the one reach test, whose np.hypot may round differently) and one start: solve on floats
        if (r_min - slack) * _INSIDE_UP < distance < (r_max + slack) * _INSIDE_DOWN:
            # the checks of the vectorised path, short-cut for the usual positive float and int
            if not (type(tol) is float and 0.0 < tol <= TOL_MAX):
                tol = _checked_tol(tol, arm.l1 + arm.l2)
            if not (type(max_iter) is int and max_iter >= 1):
                max_iter = as_count(max_iter, "max_iter", minimum=1)
            return _newton_pair(arm, target, q0_pair, distance, tol, max_iter)
    p = reachable_targets(arm, p)
    tol = _checked_tol(tol, arm.l1 + arm.l2)
    max_iter = as_count(max_iter, "max_iter", minimum=1)
    p_flat = p.reshape(-1, 2)
    q_start = wrap_angle(broadcast_start(q0, p.shape, "q0")).reshape(-1, 2)
    q1, q2 = q_start[:, 0].copy(), q_start[:, 1].copy()
    x, y = p_flat[:, 0], p_flat[:, 1]

    l1, l2 = arm.l1, arm.l2
    scale = l1 + l2
    threshold = tol * scale + distance_outside_reach(arm, p_flat)
    # per target: the angles, their sines and cosines (shared by fk and J), residual and error
    c1, s1, c12, s12, s2 = _trig(np.cos, np.sin, q1, q2)
    tip_x, tip_y = tip_from_trig(l1, l2, c1, s1, c12, s12)
    rx, ry = tip_x - x, tip_y - y
    error = np.sqrt(rx * rx + ry * ry)
    damping = np.full(len(q1), DAMPING_START * scale**2)
    damping_cap = DAMPING_CAP * scale**2
    iterations = np.zeros(len(q1), dtype=int)
    active = np.flatnonzero(error > threshold)
    with np.errstate(
        divide="ignore", invalid="ignore"
    ):  # det = 0 (damping underflowed at a singular J): rejected
        for _ in range(max_iter):
            if active.size == 0:
                break
            J_entries = jacobian_from_trig(
                l1, l2, c1[active], s1[active], c12[active], s12[active]
            )
            dq1, dq2 = _lm_step(
                *J_entries,
                l1 * l2 * s2[active],
                rx[active],
                ry[active],
                damping[active],
            )
            t1 = _wrap(q1[active] + dq1)
            t2 = _wrap(q2[active] + dq2)
            trial = _trig(np.cos, np.sin, t1, t2)
            tip_x, tip_y = tip_from_trig(l1, l2, *trial[:4])
            trx, try_ = tip_x - x[active], tip_y - y[active]
            error_trial = np.sqrt(trx * trx + try_ * try_)
            better = error_trial < error[active]
            accepted = active[better]
            q1[accepted], q2[accepted] = t1[better], t2[better]
            for cached, new in zip((c1, s1, c12, s12, s2), trial):
                cached[accepted] = new[better]
            rx[accepted], ry[accepted], error[accepted] = (
                trx[better],
                try_[better],
                error_trial[better],
            )
            damping[accepted] *= DAMPING_DOWN
            damping[active[~better]] *= DAMPING_UP
            iterations[active] += 1
            still = (error[active] > threshold[active]) & (
                damping[active] < damping_cap
            )
            active = active[still]

    q = np.stack([q1, q2], axis=-1).reshape(p.shape)
    return assemble_result(
        arm,
        p,
        q,
        iterations,
        threshold,
        "newton",
        solved_message=_solved_message(len(q), iterations.max(initial=0)),
        failure_detail=lambda index, residual: _failure_detail(
            residual, iterations[index]
        ),
    )


_INSIDE_UP, _INSIDE_DOWN = 1.0 + 1e-15, 1.0 - 1e-15

# The damping schedule of Levenberg-Marquardt, in units of (l1 + l2)^2.
DAMPING_START, DAMPING_CAP, DAMPING_DOWN, DAMPING_UP = 1e-3, 1e12, 0.2, 10.0


def _solved_message(count: int, most_iterations: int) -> str:
    return f"converged for all {count} targets (max {most_iterations} iterations)"


def _failure_detail(residual: float, iterations: int) -> str:
    return f"did not converge: residual {residual:.3g} m after {iterations} iterations"


def _checked_tol(tol: object, reach: float) -> float:
    """``tol`` as a float in ``(0, TOL_MAX]``, or a ValueError saying what it would mean."""
    value = as_finite_scalar(tol, "tol", minimum=0.0, strictly=True)
    if value > TOL_MAX:
        raise ValueError(
            f"tol = {value:.3g} would count a tip up to {value * reach:.3g} m from the target as success "
            f"(tol is relative to the reach l1 + l2 = {reach:.6g} m); tol must be in (0, {TOL_MAX:g}]"
        )
    return value


# ---------------------------------------------------------------- the formulas (floats or arrays)
_Number = TypeVar("_Number", float, NDArray[np.float64])


_PI, _TWO_PI = math.pi, 2.0 * math.pi


def _wrap(angle: _Number) -> _Number:
    """Angles wrapped to ``[-pi, pi)`` (as :func:`twolink.wrap_angle`), floats or arrays."""
    return (angle + _PI) % _TWO_PI - _PI


def _trig(
    cos: Callable[[Any], Any], sin: Callable[[Any], Any], q1: Any, q2: Any
) -> tuple[Any, Any, Any, Any, Any]:
    """``(cos q1, sin q1, cos q12, sin q12, sin q2)``; ``cos``/``sin`` from :mod:`math` or numpy."""
    q12 = q1 + q2  # wrapped angles: a sum of two angles in [-pi, pi)
    return cos(q1), sin(q1), cos(q12), sin(q12), sin(q2)


def _lm_step(
    j11: Any, j12: Any, j21: Any, j22: Any, det_j: Any, rx: Any, ry: Any, damping: Any
) -> tuple[Any, Any]:
    """The damped Newton step ``-(J^T J + lam I)^(-1) J^T r`` as two components, floats or arrays.

    ``J = [[j11, j12], [j21, j22]]`` (from :func:`twolink.kinematics.jacobian_from_trig`),
    ``det_j = det J = l1 l2 sin q2``, ``r = (rx, ry) = fk(q) - p`` and
    ``lam = damping``.  The 2x2 system is solved with its adjugate; its
    determinant ``det(J)^2 + lam (|J|_F^2 + lam)`` is a sum of non-negative
    terms (no cancellation near a singular ``J``).  On floats a zero
    determinant (the damping underflowed at a singular ``J``) raises
    ZeroDivisionError; on arrays it gives inf or NaN.
    """
    a = j11 * j11 + j21 * j21
    d = j12 * j12 + j22 * j22
    b = j11 * j12 + j21 * j22
    g1 = j11 * rx + j21 * ry
    g2 = j12 * rx + j22 * ry
    det = det_j * det_j + damping * (a + d + damping)
    return (b * g2 - (d + damping) * g1) / det, (b * g1 - (a + damping) * g2) / det


def _newton_pair(
    arm: TwoLinkArm,
    target: tuple[float, float],
    q0: tuple[float, float],
    distance: float,
    tol: float,
    max_iter: int,
) -> IKResult:
    """:func:`newton` for one target on floats: the same iteration as the vectorised path."""
    l1, l2 = arm.l1, arm.l2
    x, y = target
    scale = l1 + l2
    threshold = tol * scale + max(0.0, distance - scale, abs(l1 - l2) - distance)
    cos, sin, sqrt, l1l2 = math.cos, math.sin, math.sqrt, l1 * l2
    q1, q2 = _wrap(q0[0]), _wrap(q0[1])
    c1, s1, c12, s12, s2 = _trig(cos, sin, q1, q2)
    tip_x, tip_y = tip_from_trig(l1, l2, c1, s1, c12, s12)
    rx, ry = tip_x - x, tip_y - y
    error = sqrt(rx * rx + ry * ry)
    damping = DAMPING_START * scale * scale
    damping_cap = DAMPING_CAP * scale * scale
    iterations = 0
    if error > threshold:
        for iterations in range(1, max_iter + 1):  # noqa: B007 (read after the loop)
            j11, j12, j21, j22 = jacobian_from_trig(l1, l2, c1, s1, c12, s12)
            try:
                dq1, dq2 = _lm_step(j11, j12, j21, j22, l1l2 * s2, rx, ry, damping)
            except (
                ZeroDivisionError
            ):  # the damping underflowed at a singular J; the step is rejected
                dq1 = dq2 = math.nan
            t1, t2 = _wrap(q1 + dq1), _wrap(q2 + dq2)
            tc1, ts1, tc12, ts12, ts2 = _trig(cos, sin, t1, t2)
            tip_x, tip_y = tip_from_trig(l1, l2, tc1, ts1, tc12, ts12)
            trx, try_ = tip_x - x, tip_y - y
            error_trial = sqrt(trx * trx + try_ * try_)
            if error_trial < error:
                q1, q2 = t1, t2
                c1, s1, c12, s12, s2 = tc1, ts1, tc12, ts12, ts2
                rx, ry, error = trx, try_, error_trial
                damping *= DAMPING_DOWN
            else:
                damping *= DAMPING_UP
            if not (error > threshold and damping < damping_cap):
                break
    return one_answer_result(
        arm,
        x,
        y,
        q1,
        q2,
        iterations,
        threshold,
        "newton",
        _solved_message(1, iterations),
        lambda index, residual: _failure_detail(residual, iterations),
    )
