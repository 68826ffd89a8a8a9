"""The default budgets of every integration in the package (one place, so that no module imports another for them).

:func:`twolink.simulate.simulate` and
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

__all__ = ["DEFAULT_MAX_EVALUATIONS", "DEFAULT_MAX_WALL_TIME", "MAX_SAMPLES"]

#: Most samples a path is cut into or a workspace helper makes (memory budget:
#: 1e7 x 2 floats, 160 MB per array).
MAX_SAMPLES = 10_000_000

#: Right-hand-side evaluations (a free motion of 10 s takes about 7e3; a stiff
#: loop on an explicit method takes millions).
DEFAULT_MAX_EVALUATIONS = 1_000_000

#: Wall-clock seconds.
DEFAULT_MAX_WALL_TIME = 30.0
