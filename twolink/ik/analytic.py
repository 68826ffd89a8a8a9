"""Closed-form inverse kinematics of the planar 2R arm (cosine rule + atan2).

The formula is written once, in two small functions of floats or arrays
(:func:`_cosine_rule` and :func:`_branch_angles`): one
target given as a pair of floats evaluates them with the :mod:`math` module,
a batch with numpy; anything else, and every error, goes through the
vectorised path.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._derived import derived
from .._validate import arm_lengths, as_pairs, pair_floats, require_arm
from ..conventions import check_elbow
from ..kinematics import (
    BLOCK_ROWS,
    REACH_RTOL,
    angle_sum_trig,
    require_within_reach,
    tip_from_trig,
)
from .result import IKResult, assemble_result, one_answer_result
from .turns import free_q1_at_base, move_into_limits

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = ["closed_form", "CLOSED_FORM_RTOL"]

#: The closed form succeeds where ``|fk(q) - p| <= CLOSED_FORM_RTOL * (l1 + l2)``:
#: round-off only (targets accepted just outside the reach, by at most
#: ``REACH_RTOL * (l1 + l2)``, are solved at the boundary within it too).
CLOSED_FORM_RTOL = 1e-9

METHOD = "closed-form"

# the one-target path's functions, bound once (a global and an attribute lookup each cost a few % of a call)
_sqrt, _atan2, _array = math.sqrt, math.atan2, np.array
_BRANCH_WORDS = {
    "down": "elbow down",
    "up": "elbow up",
    "both": "both branches",
    "auto": "elbow down, no joint limits",
}


def closed_form(arm: TwoLinkArm, p: ArrayLike, elbow: str = "down") -> IKResult:
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
    elbow : {"down", "up", "both", "auto"}
        Which branch to return (:data:`twolink.conventions.ELBOW_WORDS`):

        - ``"down"`` / ``"up"``: that branch, whatever the joint limits;
        - ``"both"``: both branches, stacked on a new leading axis, down first;
        - ``"auto"``: per target, the first branch within the arm's joint
          limits, down preferred, judged as
          :func:`twolink.ik.solutions_within_limits` judges it (angles moved
          by whole turns into the limits where that helps, which then lie
          outside ``(-pi, pi]``); the down branch for an arm without limits.
          A target with neither branch within the limits gets the down
          branch, with ``within_limits`` false (and the message says so).

    Returns
    -------
    IKResult
        ``method="closed-form"``, ``iterations`` 0.  ``q`` has shape
        ``(..., 2)``; for ``"both"`` ``(2, ..., 2)``, ``q[0]`` the down
        branch and ``q[1]`` the up branch, and every field has that leading
        axis of 2.  ``residual`` is recomputed from ``q`` by forward
        kinematics when the result is built (in a batch block by block with
        the answers, taking ``cos q2`` and ``sin q2`` from the unit vector
        ``q2`` is the ``atan2`` of: equal to round-off); ``success`` where
        it is at most ``CLOSED_FORM_RTOL * (l1 + l2)`` (round-off: the closed
        form is exact, also for links as unequal as 1e-9 and 1e9 m).  ``within_limits`` is not
        applied except by ``"auto"``: check it.

    Raises
    ------
    twolink.UnreachableError
        If a target is further than ``REACH_RTOL * (l1 + l2)`` outside the
        annulus ``r_min <= |p| <= r_max`` (the message gives the target's
        distance and the reach interval).  The closed form has no approximate
        answer to return there, unlike :func:`twolink.ik.brute_force`'s
        nearest grid point.  Targets within that tolerance (round-off at full
        stretch or full fold) are solved at the boundary.
    ValueError
        For NaN or infinite targets, a wrong shape or an unknown ``elbow``.

    Examples
    --------
    >>> from twolink import arms, ik
    >>> result = ik.closed_form(arms.ten, [10 * np.sqrt(2), 10 * np.sqrt(2)])
    >>> result.q / np.pi
    array([0.25, 0.  ])
    >>> result.success, result.residual < 1e-12, result.method
    (True, True, 'closed-form')
    >>> q_both = ik.closed_form(arms.ten, [10.0, 10.0], elbow="both").q
    >>> np.degrees(q_both).round(6)
    array([[  0.,  90.],
           [ 90., -90.]])

    ``"auto"`` keeps to the joint limits (arms.ten: ``0 <= q1 <= 90`` deg):

    >>> ik.closed_form(arms.ten, [18.0, 2.0], elbow="down").within_limits
    False
    >>> auto = ik.closed_form(arms.ten, [18.0, 2.0], elbow="auto")
    >>> np.degrees(auto.q).round(3), auto.within_limits
    (array([ 31.444, -50.208]), True)
    >>> ik.closed_form(arms.ten, [12.0, 4.0], elbow="auto").message  # q1 < 0 down, q2 < -90 deg up
    'solved 1 target in closed form, elbow auto: 0 down and 0 up within the joint limits, 1 with neither branch within them (given elbow down); 1 of 1 answers violate the joint limits (see within_limits)'
    >>> ik.closed_form(arms.ten, [30.0, 0.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: target (30, 0) is 30 m from the base; this arm reaches distances in [0, 20] m (l1=10, l2=10)
    """
    target = pair_floats(p)
    if target is not None and type(elbow) is str:
        # one target on floats: the formula with math, as the vectorised path evaluates it with numpy
        try:
            l1, l2 = arm.l1, arm.l2
        except AttributeError:  # not an arm: arm_lengths raises, naming it
            l1, l2 = arm_lengths(arm)
        terms = derived(arm, "closed_form", _reach_terms_of)
        (
            r_min_squared,
            r_max_squared,
            inverse,
            low_outer,
            low_inner,
            threshold,
            messages,
        ) = terms
        x, y = target
        one_minus_c2, one_plus_c2 = _cosine_rule(
            x, y, r_min_squared, r_max_squared, inverse
        )
        if (
            one_minus_c2 >= low_outer and one_plus_c2 >= low_inner
        ):  # else the vectorised path raises
            if one_minus_c2 < 0.0:  # round-off at full stretch
                one_minus_c2 = 0.0
            if one_plus_c2 < 0.0:  # round-off at full fold
                one_plus_c2 = 0.0
            # the two sum to 2: the larger from the smaller, which is the accurate one (_cosine_rule)
            if one_minus_c2 <= one_plus_c2:
                one_plus_c2 = 2.0 - one_minus_c2
            else:
                one_minus_c2 = 2.0 - one_plus_c2
            if (
                elbow == "down"
                or elbow == "up"
                or (elbow == "auto" and arm.q_min is None)
            ):
                sign = -1.0 if elbow == "up" else 1.0  # "auto" without limits: down
                q1, q2 = _branch_angles(
                    l1, l2, x, y, one_minus_c2, one_plus_c2, sign, _sqrt, _atan2
                )
                return one_answer_result(
                    arm,
                    x,
                    y,
                    q1,
                    q2,
                    0,
                    threshold,
                    METHOD,
                    messages[elbow],
                    _failure_detail,
                )
            if elbow == "both":
                # down then up, written out: a comprehension here would make the
                # variables it reads closure cells, slower on every call
                q_both = _array(
                    [
                        _branch_angles(
                            l1, l2, x, y, one_minus_c2, one_plus_c2, 1.0, _sqrt, _atan2
                        ),
                        _branch_angles(
                            l1, l2, x, y, one_minus_c2, one_plus_c2, -1.0, _sqrt, _atan2
                        ),
                    ]
                )
                return assemble_result(
                    arm,
                    target,
                    q_both,
                    0,
                    threshold,
                    METHOD,
                    messages[elbow],
                    _failure_detail,
                )
            # "auto" with joint limits, or not an elbow word: the vectorised path
    elbow = check_elbow(elbow)
    targets: NDArray[np.float64] = as_pairs(p, "target p")
    try:
        _lengths = arm.l1, arm.l2  # the cheap check of an arm-like object
    except AttributeError:
        require_arm(arm)
    terms = _reach_terms(arm)
    flat = targets.reshape(-1, 2)
    count = len(flat)
    if elbow == "auto" and arm.has_limits:
        q_flat, message = _within_limits_first(arm, targets, flat, terms)
        residual = None  # the angles were moved by turns: judged by forward kinematics
    else:
        q_flat, residual = _branches(
            arm, targets, flat, terms, "down" if elbow == "auto" else elbow
        )
        message = f"solved {count} target{'s' if count != 1 else ''} in closed form ({_BRANCH_WORDS[elbow]})"
    q = q_flat.reshape(((2,) if elbow == "both" else ()) + targets.shape)
    return assemble_result(
        arm,
        targets,
        q,
        0,
        terms[5],
        METHOD,
        message,
        _failure_detail,
        residual=residual,
    )


def _failure_detail(index: int, residual: float) -> str:
    return f"residual {residual:.3g} m above the round-off bound CLOSED_FORM_RTOL (l1 + l2)"


def _within_limits_first(
    arm: TwoLinkArm, p: NDArray[np.float64], flat: NDArray[np.float64], terms: _Terms
) -> tuple[NDArray[np.float64], str]:
    """``elbow="auto"`` for an arm with limits: per target the down branch, else up, moved into the limits.

    At the base of an equal-link arm, where every ``q1`` reaches, both
    branches take the ``q1`` that :func:`twolink.ik.solutions_within_limits`
    takes (:func:`twolink.ik.limits.free_q1_at_base`), so the two agree.
    """
    q_both = _branches(arm, p, flat, terms, "both")[0]
    at_base, free_q1 = free_q1_at_base(arm, flat)
    if free_q1 is not None:
        q_both[:, at_base, 0] = free_q1
    moved, inside = move_into_limits(arm, q_both)
    q = np.where(inside[0][:, None], moved[0], q_both[0])
    take_up = ~inside[0] & inside[1]
    q[take_up] = moved[1][take_up]
    neither = int(np.count_nonzero(~(inside[0] | inside[1])))
    count = len(flat)
    message = (
        f"solved {count} target{'s' if count != 1 else ''} in closed form, elbow auto: "
        f"{int(np.count_nonzero(inside[0]))} down and {int(np.count_nonzero(take_up))} up within the joint limits"
    )
    if neither:
        message += f", {neither} with neither branch within them (given elbow down)"
    return q, message


def _branches(
    arm: TwoLinkArm,
    p: NDArray[np.float64],
    flat: NDArray[np.float64],
    terms: _Terms,
    elbow: str,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The closed form on flat targets ``(n, 2)``, and each answer's residual ``|fk(q) - p|``.

    ``q`` of shape ``(n, 2)`` for one branch, ``(2, n, 2)`` for ``"both"``;
    the residuals ``(n,)`` or ``(2, n)``, by forward kinematics of the
    answers, block by block with them (while the block is in the CPU cache).
    ``p`` is the targets as given, for the reach error's message.
    """
    l1, l2 = arm.l1, arm.l2
    r_min_squared, r_max_squared, inverse, low_outer, low_inner = terms[:5]
    q = np.empty((2, len(flat), 2) if elbow == "both" else (len(flat), 2))
    residual = np.empty(q.shape[:-1])
    for start in range(
        0, len(flat), BLOCK_ROWS
    ):  # block by block: the temporaries stay in the CPU cache
        block = slice(start, start + BLOCK_ROWS)
        x, y = flat[block, 0], flat[block, 1]
        one_minus_c2, one_plus_c2 = _cosine_rule(
            x, y, r_min_squared, r_max_squared, inverse
        )
        if one_minus_c2.min() < low_outer or one_plus_c2.min() < low_inner:
            # the one reach test raises, naming the first target out of reach (a target this test put out
            # by one rounding on the edge of REACH_RTOL and it puts in is solved at the boundary below)
            require_within_reach(arm, p)
        np.maximum(one_minus_c2, 0.0, out=one_minus_c2)  # round-off at full stretch
        np.maximum(one_plus_c2, 0.0, out=one_plus_c2)  # round-off at full fold
        # the two sum to 2: the larger from the smaller, which is the accurate one (_cosine_rule)
        minus_smaller = one_minus_c2 <= one_plus_c2
        one_plus_c2 = np.where(minus_smaller, 2.0 - one_minus_c2, one_plus_c2)
        one_minus_c2 = np.where(minus_smaller, one_minus_c2, 2.0 - one_plus_c2)
        for out, misses, sign in (
            ((q[0], residual[0], 1.0), (q[1], residual[1], -1.0))
            if elbow == "both"
            else ((q, residual, 1.0 if elbow == "down" else -1.0),)
        ):
            q1, q2 = _branch_angles(
                l1, l2, x, y, one_minus_c2, one_plus_c2, sign, np.sqrt, np.arctan2
            )
            out[block, 0], out[block, 1] = q1, q2
            # forward kinematics of the answer: cos and sin of q1, and of q2 the pair it is
            # the atan2 of (its cosine and sine, to round-off), which saves two of the four
            cos_q2, sin_q2 = _elbow_trig(one_minus_c2, one_plus_c2, sign, np.sqrt)
            c1, s1 = np.cos(q1), np.sin(q1)
            c12, s12 = angle_sum_trig(c1, s1, cos_q2, sin_q2)
            tip_x, tip_y = tip_from_trig(l1, l2, c1, s1, c12, s12)
            tip_x -= x
            tip_y -= y
            misses[block] = np.sqrt(tip_x * tip_x + tip_y * tip_y)
    return q, residual


# ---------------------------------------------------------------- the formula (floats or arrays)
def _cosine_rule(
    x: Any, y: Any, r_min_squared: float, r_max_squared: float, inverse: float
) -> tuple[Any, Any]:
    """``(1 - cos q2, 1 + cos q2)`` of the cosine rule ``cos q2 = (r^2 - l1^2 - l2^2) / (2 l1 l2)``.

    Taken straight from ``r^2 = x^2 + y^2`` as ``(r_max^2 - r^2) / (2 l1 l2)``
    and ``(r^2 - r_min^2) / (2 l1 l2)`` (``inverse`` is ``1 / (2 l1 l2)``),
    without forming ``cos q2`` first: they keep their relative accuracy at
    full stretch and full fold, where ``1 -+ cos q2`` would cancel.  Floats
    or arrays; negative (by round-off, or out of reach) outside the annulus.

    The two sum to 2, and the callers (after clipping them at 0) take the
    larger as 2 minus the smaller, which is the accurate one: where the
    annulus is thinner than the round-off of ``r^2`` (links of 1e-9 and
    1e9 m), both come out as round-off and ``cos q2`` would be no angle at
    all (both 0 put the tip at the opposite point).
    """
    r_squared = x * x + y * y
    return (r_max_squared - r_squared) * inverse, (r_squared - r_min_squared) * inverse


def _branch_angles(
    l1: float,
    l2: float,
    x: Any,
    y: Any,
    one_minus_c2: Any,
    one_plus_c2: Any,
    sign: float,
    sqrt: Callable[[Any], Any],
    atan2: Callable[[Any, Any], Any],
) -> tuple[Any, Any]:
    """``(q1, q2)`` of one branch from :func:`_cosine_rule`'s ``1 -+ cos q2`` (clipped at 0).

    ``sign`` is ``+1`` for the down branch (``q2 >= 0``), ``-1`` for up:
    ``sin q2 = sign sqrt((1 - cos q2)(1 + cos q2))``, ``q2 = atan2(sin q2, cos q2)``,
    and ``q1 = atan2(y, x) - atan2(k2, k1)`` with ``k1 = l1 + l2 cos q2``
    (written ``l2 (1 + cos q2) + (l1 - l2)``, accurate near full fold) and
    ``k2 = l2 sin q2``, evaluated as one ``atan2(y k1 - x k2, x k1 + y k2)``
    so that ``q1`` lies in ``(-pi, pi]``.  ``sqrt``/``atan2`` from
    :mod:`math` (floats) or numpy (arrays).
    """
    cos_q2, sin_q2 = _elbow_trig(one_minus_c2, one_plus_c2, sign, sqrt)
    k1 = one_plus_c2 * l2 + (l1 - l2)
    k2 = l2 * sin_q2
    return atan2(y * k1 - x * k2, x * k1 + y * k2), atan2(sin_q2, cos_q2)


def _elbow_trig(
    one_minus_c2: Any, one_plus_c2: Any, sign: float, sqrt: Callable[[Any], Any]
) -> tuple[Any, Any]:
    """``(cos q2, sin q2)`` of one branch: ``((1 + c2) - (1 - c2)) / 2`` and ``sign sqrt((1 - c2)(1 + c2))``.

    With the two halves summing to 2 (:func:`_cosine_rule`) they are a unit
    vector, so they are the cosine and sine of ``q2 = atan2(sin q2, cos q2)``
    to round-off.
    """
    return (one_plus_c2 - one_minus_c2) * 0.5, sign * sqrt(one_minus_c2 * one_plus_c2)


# r_min^2, r_max^2, 1 / (2 l1 l2), low_outer, low_inner, the success threshold, the message of one target per elbow
_Terms = tuple[float, float, float, float, float, float, dict[str, str]]


def _reach_terms(arm: TwoLinkArm) -> _Terms:
    """``(r_min^2, r_max^2, 1 / (2 l1 l2), low_outer, low_inner, threshold, messages)``, once per arm.

    ``low_outer`` and ``low_inner`` are the lowest accepted ``1 - cos q2`` and
    ``1 + cos q2``: the annulus widened by ``REACH_RTOL * r_max``;
    ``threshold`` is the success bound ``CLOSED_FORM_RTOL * r_max``, and
    ``messages[elbow]`` the message of one target solved.
    """
    return derived(arm, "closed_form", _reach_terms_of)


def _reach_terms_of(arm: TwoLinkArm) -> _Terms:
    return _compute_reach_terms(arm.l1, arm.l2)


def _compute_reach_terms(l1: float, l2: float) -> _Terms:
    r_min, r_max = abs(l1 - l2), l1 + l2
    slack = REACH_RTOL * r_max
    inverse = 1.0 / (2.0 * l1 * l2)
    low_outer = (r_max * r_max - (r_max + slack) ** 2) * inverse
    low_inner = (max(r_min - slack, 0.0) ** 2 - r_min * r_min) * inverse
    messages = {
        elbow: f"solved 1 target in closed form ({words})"
        for elbow, words in _BRANCH_WORDS.items()
    }
    return (
        r_min * r_min,
        r_max * r_max,
        inverse,
        low_outer,
        low_inner,
        CLOSED_FORM_RTOL * r_max,
        messages,
    )
