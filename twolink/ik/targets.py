"""Checks on IK targets shared by every solver: finite, and inside the reach."""

import numpy as np

from .._validate import as_pairs, require_arm
from ..errors import UnreachableError

__all__ = ["REACH_RTOL", "as_targets", "raise_unreachable", "check_reachable"]

#: Targets up to ``REACH_RTOL * (l1 + l2)`` outside the reach annulus are
#: accepted and solved as the nearest boundary configuration (round-off at
#: full stretch or full fold), anything further raises UnreachableError.
REACH_RTOL = 1e-10


def as_targets(p):
    """Targets as a float array ``(..., 2)``; ``ValueError`` if NaN or infinite."""
    return as_pairs(p, "target p")


def raise_unreachable(arm, p, outside):
    """Raise :class:`UnreachableError` naming the first target where ``outside`` is true."""
    index = tuple(int(i) for i in np.argwhere(outside)[0]) if np.ndim(outside) else ()
    target = p[index]
    distance = float(np.hypot(target[0], target[1]))
    r_min, r_max = arm.reach
    count = int(np.count_nonzero(outside))
    where = f" (index {index}, first of {count})" if p.size > 2 else ""
    raise UnreachableError(
        f"target ({target[0]:.6g}, {target[1]:.6g}){where} is {distance:.6g} m from the base; "
        f"this arm reaches distances in [{r_min:.6g}, {r_max:.6g}] m "
        f"(l1={arm.l1:.6g}, l2={arm.l2:.6g})"
    )


def check_reachable(arm, p):
    """Return targets ``p`` as an array, raising if any is non-finite or out of reach.

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> check_reachable(TwoLinkArm(1.0, 1.0), [3.0, 4.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: target (3, 4) is 5 m from the base; this arm reaches distances in [0, 2] m (l1=1, l2=1)
    """
    p = as_targets(p)
    require_arm(arm)
    r_min, r_max = arm.reach
    slack = REACH_RTOL * r_max
    distance = np.hypot(p[..., 0], p[..., 1])
    outside = (distance > r_max + slack) | (distance < r_min - slack)
    if np.any(outside):
        raise_unreachable(arm, p, outside)
    return p
