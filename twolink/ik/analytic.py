"""Closed-form inverse kinematics of the planar 2R arm (cosine rule + atan2).

One target given as a pair of floats is solved on Python floats with the
:mod:`math` module, evaluating the same expressions in the same order as the
vectorised path (the tests compare the two to 1e-12, at the reach boundary
too); anything else, and every error, goes through the vectorised path.
"""

import math

import numpy as np

from .._validate import arm_lengths, pair_floats, require_arm
from .targets import REACH_RTOL, as_targets, raise_unreachable

__all__ = ["closed_form", "ELBOW_BRANCHES"]

ELBOW_BRANCHES = ("down", "up", "both")


def closed_form(arm, p, elbow="down"):
    """Joint angles that put the tip at ``p``, from the cosine rule.

    ``cos q2 = (x^2 + y^2 - l1^2 - l2^2) / (2 l1 l2)``, ``q2 = +-acos(cos q2)``,
    and ``q1 = atan2(y, x) - atan2(l2 sin q2, l1 + l2 cos q2)``, evaluated as
    one ``atan2`` so that ``q1`` lies in ``(-pi, pi]``.

    Branch naming, defined by the sign of ``q2`` because picture-based names
    are easy to swap (libraries have shipped the two labels the wrong way
    round): ``"down"`` is the branch with ``q2 >= 0``; with the arm reaching to
    the right along +x its elbow sits below the base-to-tip line.  ``"up"`` is
    ``q2 <= 0``, the elbow above that line.  The two meet at full stretch and
    full fold (``q2 = 0`` or ``pi``), where the root is double.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Target tip positions ``(x, y)`` in metres.
    elbow : {"down", "up", "both"}
        Which branch to return.

    Returns
    -------
    numpy.ndarray
        Shape ``(..., 2)`` for one branch; ``(..., 2, 2)`` for ``"both"``,
        with ``[..., 0, :]`` the down branch and ``[..., 1, :]`` the up branch.

    Raises
    ------
    twolink.UnreachableError
        If a target is further than ``REACH_RTOL * (l1 + l2)`` outside the
        annulus ``r_min <= |p| <= r_max``; the message gives the target's
        distance and the reach interval.  Targets within that tolerance (round
        off at full stretch or full fold) are solved at the boundary.
    ValueError
        For NaN or infinite targets, a wrong shape or an unknown ``elbow``.

    Notes
    -----
    Joint limits are not applied: both branches are returned whatever the
    limits; use ``arm.within_limits`` to filter.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> q = ik.closed_form(arms.ten, [10 * np.sqrt(2), 10 * np.sqrt(2)])
    >>> q / np.pi
    array([0.25, 0.  ])
    >>> q_both = ik.closed_form(arms.ten, [10.0, 10.0], elbow="both")
    >>> np.degrees(q_both).round(6)
    array([[  0.,  90.],
           [ 90., -90.]])
    >>> ik.closed_form(arms.ten, [30.0, 0.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: target (30, 0) is 30 m from the base; this arm reaches distances in [0, 20] m (l1=10, l2=10)
    """
    if elbow not in ELBOW_BRANCHES:
        raise ValueError(f"elbow must be one of {ELBOW_BRANCHES}; got {elbow!r}")
    target = pair_floats(p)
    if target is not None:  # one target on floats: the steps below, written out (a call costs as much)
        derived = getattr(arm, "_derived", None)
        terms = derived.get("closed_form") if derived is not None else None
        try:
            l1, l2 = arm.l1, arm.l2
        except AttributeError:
            l1, l2 = arm_lengths(arm)  # not an arm: raises, naming it
        r_min_squared, r_max_squared, inverse, low_outer, low_inner = terms or _reach_terms(arm)
        x, y = target
        r_squared = x * x + y * y
        one_minus_c2 = (r_max_squared - r_squared) * inverse
        one_plus_c2 = (r_squared - r_min_squared) * inverse
        if one_minus_c2 >= low_outer and one_plus_c2 >= low_inner:  # else the vectorised path raises
            if one_minus_c2 < 0.0:
                one_minus_c2 = 0.0
            if one_plus_c2 < 0.0:
                one_plus_c2 = 0.0
            s2 = math.sqrt(one_minus_c2 * one_plus_c2)  # sin q2 of the down branch, >= 0
            k1 = one_plus_c2 * l2 + (l1 - l2)  # l1 + l2 cos q2, accurate near full fold
            q2_down = math.atan2(s2, (one_plus_c2 - one_minus_c2) * 0.5)
            s2 *= l2
            xk1, yk1, xk2, yk2 = x * k1, y * k1, x * s2, y * s2
            if elbow != "both":
                q = np.empty(2)  # then two item assignments: faster than np.array of a list
                if elbow == "down":
                    q[0], q[1] = math.atan2(yk1 - xk2, xk1 + yk2), q2_down
                else:
                    q[0], q[1] = math.atan2(yk1 + xk2, xk1 - yk2), -q2_down
                return q
            q_both = np.array([math.atan2(yk1 - xk2, xk1 + yk2), q2_down, math.atan2(yk1 + xk2, xk1 - yk2), -q2_down])
            q_both.shape = (2, 2)
            return q_both
    p = as_targets(p)
    try:
        arm.l1, arm.l2
    except AttributeError:
        require_arm(arm)
    if p.ndim == 1:  # one target: solve as a batch of one (keeps every temporary an array)
        return closed_form(arm, p[None, :], elbow)[0]
    l1, l2 = arm.l1, arm.l2
    r_min_squared, r_max_squared, inverse, low_outer, low_inner = _reach_terms(arm)
    x = p[..., 0]
    y = p[..., 1]

    # 1 - cos q2 and 1 + cos q2 straight from r^2, without forming cos q2 first:
    # (r_max^2 - r^2) and (r^2 - r_min^2) keep their relative accuracy at full
    # stretch and full fold, where 1 -+ cos q2 would cancel catastrophically.
    r_squared = x * x
    r_squared += y * y
    one_minus_c2 = r_max_squared - r_squared
    one_minus_c2 *= inverse
    one_plus_c2 = r_squared
    one_plus_c2 -= r_min_squared
    one_plus_c2 *= inverse
    if one_minus_c2.size and (one_minus_c2.min() < low_outer or one_plus_c2.min() < low_inner):
        raise_unreachable(arm, p, (one_minus_c2 < low_outer) | (one_plus_c2 < low_inner))
    np.maximum(one_minus_c2, 0.0, out=one_minus_c2)
    np.maximum(one_plus_c2, 0.0, out=one_plus_c2)

    s2 = one_minus_c2 * one_plus_c2
    np.sqrt(s2, out=s2)  # sin q2 of the down branch, >= 0
    c2 = one_plus_c2 - one_minus_c2
    c2 *= 0.5
    k1 = one_plus_c2
    k1 *= l2
    k1 += l1 - l2  # l1 + l2 cos q2, accurate near full fold
    xk1 = x * k1
    yk1 = y * k1
    np.arctan2(s2, c2, out=c2)  # c2 now holds q2 of the down branch
    q2_down = c2
    s2 *= l2  # l2 sin q2
    xk2 = x * s2
    yk2 = y * s2

    shape = p.shape[:-1]
    if elbow == "both":
        q_both = np.empty(shape + (2, 2))
        np.arctan2(yk1 - xk2, xk1 + yk2, out=q_both[..., 0, 0])
        q_both[..., 0, 1] = q2_down
        np.arctan2(yk1 + xk2, xk1 - yk2, out=q_both[..., 1, 0])
        np.negative(q2_down, out=q_both[..., 1, 1])
        return q_both

    q = np.empty(shape + (2,))
    if elbow == "down":
        yk1 -= xk2
        xk1 += yk2
        q[..., 1] = q2_down
    else:
        yk1 += xk2
        xk1 -= yk2
        np.negative(q2_down, out=q[..., 1])
    np.arctan2(yk1, xk1, out=q[..., 0])
    return q


def _reach_terms(arm):
    """``(r_min^2, r_max^2, 1 / (2 l1 l2), low_outer, low_inner)`` of the cosine rule, cached per arm.

    ``low_outer`` and ``low_inner`` are the lowest accepted ``1 - cos q2`` and
    ``1 + cos q2``: the annulus widened by ``REACH_RTOL * r_max``.
    """
    derived = getattr(arm, "_derived", None)
    if derived is None:  # not a TwoLinkArm
        return _compute_reach_terms(arm.l1, arm.l2)
    terms = derived.get("closed_form")
    if terms is None:
        terms = derived["closed_form"] = _compute_reach_terms(arm.l1, arm.l2)
    return terms


def _compute_reach_terms(l1, l2):
    r_min, r_max = abs(l1 - l2), l1 + l2
    slack = REACH_RTOL * r_max
    inverse = 1.0 / (2.0 * l1 * l2)
    low_outer = (r_max * r_max - (r_max + slack) ** 2) * inverse
    low_inner = (max(r_min - slack, 0.0) ** 2 - r_min * r_min) * inverse
    return r_min * r_min, r_max * r_max, inverse, low_outer, low_inner

