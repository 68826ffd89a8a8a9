"""The default budgets of every integration in the package (one place, so that no module imports another for them).

:func:`twolink.simulation.simulate` and
:func:`twolink.trajectory.resolved_rate_trajectory` stop with a
:class:`~twolink.errors.SimulationError` that names the budget when one is
spent, and :func:`twolink.workspace.largest_inscribed_circle` (wall time
only) with a :class:`RuntimeError`; callers pass larger ones explicitly.

Examples
--------
>>> DEFAULT_MAX_EVALUATIONS, DEFAULT_MAX_WALL_TIME
(1000000, 30.0)

:data:`MAX_SAMPLES` bounds the samples a path (:mod:`twolink.trajectory`) or a
workspace helper (:mod:`twolink.workspace`) makes; both modules re-export it.

>>> MAX_SAMPLES
10000000
"""

from __future__ import annotations

import time
from typing import Literal

from ._validate import as_count, as_finite_scalar

__all__ = ["DEFAULT_MAX_EVALUATIONS", "DEFAULT_MAX_WALL_TIME", "MAX_SAMPLES"]

#: Most samples a path is cut into or a workspace helper makes (memory budget:
#: 1e7 x 2 floats, 160 MB per array).
MAX_SAMPLES = 10_000_000

#: Right-hand-side evaluations (a free motion of 10 s takes about 7e3; a stiff
#: loop on an explicit method takes millions).
DEFAULT_MAX_EVALUATIONS = 1_000_000

#: Wall-clock seconds.
DEFAULT_MAX_WALL_TIME = 30.0


class EvaluationBudget:
    """The budget of one integration: right-hand-side evaluations and wall time.

    One copy of the check that :func:`twolink.simulation.simulate` and
    :func:`twolink.trajectory.resolved_rate_trajectory` make at every
    evaluation of their right-hand side.

    Parameters
    ----------
    max_evaluations : int
        At least 1.
    max_wall_time : float
        Seconds from now, > 0.

    Raises
    ------
    ValueError, TypeError
        For a budget that is not a positive count or a positive finite time.

    Examples
    --------
    >>> budget = EvaluationBudget(2, 30.0)
    >>> budget.spend(), budget.spend(), budget.spend()
    (None, None, 'max_evaluations')
    >>> budget.describe("max_evaluations"), budget.evaluations
    ('max_evaluations = 2 evaluations', 3)
    >>> EvaluationBudget(0, 1.0)
    Traceback (most recent call last):
    ...
    ValueError: max_evaluations must be an integer >= 1; got 0
    """

    def __init__(self, max_evaluations: object, max_wall_time: object) -> None:
        self.max_evaluations = as_count(max_evaluations, "max_evaluations", minimum=1)
        self.max_wall_time = as_finite_scalar(
            max_wall_time, "max_wall_time (s)", minimum=0.0, strictly=True
        )
        self.started = time.monotonic()
        self.deadline = self.started + self.max_wall_time
        self.evaluations = 0

    def out_of_time(self) -> bool:
        """True once the wall time is spent."""
        return time.monotonic() > self.deadline

    def spend(self) -> Literal["max_evaluations", "max_wall_time"] | None:
        """Count one evaluation; the budget then overrun, or None (the clock is read at every call)."""
        self.evaluations += 1
        if self.evaluations > self.max_evaluations:
            return "max_evaluations"
        if (
            time.monotonic() > self.deadline
        ):  # one call of a slow torque function may take seconds
            return "max_wall_time"
        return None

    def describe(self, which: str) -> str:
        """``"max_evaluations = N evaluations"`` or ``"max_wall_time = T s"``, for a message."""
        if which == "max_evaluations":
            return f"max_evaluations = {self.max_evaluations} evaluations"
        return f"max_wall_time = {self.max_wall_time:.3g} s"
