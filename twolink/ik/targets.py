"""The check every IK solver applies to its targets: finite pairs, inside the reach."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .._validate import as_pairs
from ..kinematics import require_within_reach

if TYPE_CHECKING:
    from ..arm import TwoLinkArm

__all__ = []


def reachable_targets(arm: TwoLinkArm, p: ArrayLike) -> NDArray[np.float64]:
    """Targets ``p`` as a float array ``(..., 2)``, or the package's refusal.

    ``ValueError`` names ``target p`` when ``p`` is not finite pairs;
    :func:`twolink.kinematics.require_within_reach` (the one reach test)
    raises :class:`~twolink.UnreachableError` for a target out of reach.
    The array returned is never the caller's (a solver's result keeps it).

    Examples
    --------
    >>> from twolink import TwoLinkArm
    >>> reachable_targets(TwoLinkArm(1.0, 1.0), [[1.0, 0.0], [3.0, 4.0]])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: target (3, 4) (index (1,), first of 1) is 5 m from the base; this arm reaches distances in [0, 2] m (l1=1, l2=1)
    """
    targets = as_pairs(p, "target p")
    if isinstance(p, np.ndarray) and np.may_share_memory(targets, p):
        targets = targets.copy()
    require_within_reach(arm, targets)
    return targets
