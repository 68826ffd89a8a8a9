"""Timing and comparing IK solvers: the measurements behind "can it run in real time?".

One implementation serves the notebooks (chapters 2 and 7) and the benchmark
scripts, so every table in the course is measured the same way: ``timeit``
with several repeats, the median reported.
"""

from __future__ import annotations

import timeit
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink import ik
from twolink._validate import InputTypeError, as_count, as_finite_scalar, as_pairs
from twolink.kinematics import require_within_reach

from .runmode import grading

if TYPE_CHECKING:
    from twolink.arm import TwoLinkArm

#: Longest measurement :func:`median_time` accepts per batch, seconds.
MAX_SECONDS = 60.0

__all__ = ["median_time", "IK_METHODS", "compare_ik_methods"]


def median_time(
    function: Callable[[], object], repeat: int = 5, min_seconds: float = 0.05
) -> float:
    """Median wall time of one call of ``function()``, in seconds.

    Calls are batched so that each measurement lasts about ``min_seconds``
    (the batch size is calibrated from a first run of at least a tenth of
    that, far cheaper than :meth:`timeit.Timer.autorange`'s fixed 0.2 s, which
    dominated notebooks timing several methods); the median of ``repeat``
    batches resists the odd slow run.

    While grading (``TWOLINK_GRADING=1``, :mod:`twolink_course.runmode`) the
    function is called once and that call is timed: timings are shown,
    never checked, and a grader need not wait for calibrated batches.

    Parameters
    ----------
    function : callable
        Called with no arguments.
    repeat : int
        Number of timed batches (the median is kept).
    min_seconds : float
        Duration of each batch, seconds (at most ``MAX_SECONDS``).

    Returns
    -------
    float
        Seconds per call.

    Examples
    --------
    >>> seconds = median_time(lambda: sum(range(100)), repeat=3)
    >>> 0 < seconds < 1e-3
    True
    """
    repeat = as_count(repeat, "repeat", minimum=1, maximum=1000)
    min_seconds = as_finite_scalar(
        min_seconds, "min_seconds (s)", minimum=0.0, strictly=True
    )
    if min_seconds > MAX_SECONDS:
        raise ValueError(
            f"min_seconds must be at most {MAX_SECONDS} s (a timing budget, not a wait); got {min_seconds}"
        )
    if not callable(function):
        raise InputTypeError(
            f"function must be a callable of no arguments; got {function!r}"
        )
    timer = timeit.Timer(function)
    if grading():  # one call, timed once: no answer depends on a timing
        return max(timer.timeit(number=1), 1e-12)  # never 0: notebooks divide by it
    number = 1
    while True:  # 1, 10, 100, ... calls until a run lasts a tenth of min_seconds
        elapsed = timer.timeit(number=number)
        if elapsed >= min_seconds / 10 or number >= 10**9:
            break
        number *= 10
    number = max(1, int(np.ceil(number * min_seconds / max(elapsed, 1e-12))))
    return float(np.median(timer.repeat(repeat=repeat, number=number)) / number)


# a solver as timed: ``solve(arm, p)`` returns the IK result for targets ``p``.
_Solver = Callable[[Any, Any], ik.IKResult]


def _solvers(q0: tuple[float, ...], step: float) -> dict[str, _Solver]:
    """Every method, as a call returning its :class:`~twolink.ik.IKResult` (the timing reads its ``q``)."""
    return {
        "closed form": lambda arm, p: ik.closed_form(arm, p, elbow="down"),
        "newton": lambda arm, p: ik.newton(arm, p, q0=q0),
        "minimize (BFGS)": lambda arm, p: ik.minimize(arm, p, q0=q0),
        "minimize (SLSQP, constrained)": lambda arm, p: ik.minimize(
            arm, p, q0=q0, constrained=True
        ),
        "brute force": lambda arm, p: ik.brute_force(arm, p, step=step),
    }


#: The method names :func:`compare_ik_methods` knows, fastest first.
IK_METHODS = tuple(_solvers((0.5, 1.0), 1.0))


def compare_ik_methods(
    arm: TwoLinkArm,
    targets: ArrayLike,
    q0: ArrayLike = (0.5, 1.0),
    step: float = float(np.radians(1.0)),
    methods: Sequence[str] = IK_METHODS,
    repeat: int = 3,
    per_call: bool = True,
) -> list[dict[str, Any]]:
    """Time every IK method on the same targets and report its accuracy.

    Parameters
    ----------
    arm : TwoLinkArm
    targets : array_like, shape (n, 2)
        Reachable targets in metres.
    q0 : array_like, shape (2,)
        Start for the iterative methods, radians.
    step : float
        Grid step of the brute-force method, radians.
    methods : sequence of str
        Names from :data:`IK_METHODS`.
    repeat : int
        Timing repeats (the median is kept).
    per_call : bool
        True: solve the targets one call each, in a Python loop (what a
        controller does once per cycle).  False: one vectorised call for all.

    Returns
    -------
    list of dict
        One row per method: ``method``, ``seconds_per_target``,
        ``max_residual`` (m, recomputed with FK from each method's ``q``)
        and ``solved`` (fraction of targets whose residual is below 1e-9 of
        the reach, or the grid bound for brute force).  The timed calls
        include building each method's :class:`~twolink.ik.IKResult`.

    Examples
    --------
    >>> from twolink import arms
    >>> rows = compare_ik_methods(arms.ten, [[10.0, 10.0], [12.0, 9.0]], methods=["closed form"], repeat=1)
    >>> rows[0]["method"], rows[0]["solved"], rows[0]["max_residual"] < 1e-12
    ('closed form', 1.0, True)
    """
    points: NDArray[np.float64] = require_within_reach(
        arm, as_pairs(targets, "targets")
    )
    repeat = as_count(repeat, "repeat", minimum=1, maximum=1000)
    if points.ndim != 2 or len(points) == 0:
        raise ValueError(
            f"targets must have shape (n, 2) with n >= 1 (nothing to time otherwise); got {points.shape}"
        )
    solvers = _solvers(tuple(as_pairs(q0, "q0").tolist()), step)
    unknown = [name for name in methods if name not in solvers]
    if unknown:
        raise ValueError(f"unknown methods {unknown}; choose from {IK_METHODS}")
    rows = []
    for name in methods:
        solve = solvers[name]
        if per_call:
            q = np.array([solve(arm, p).q for p in points])

            def run(solve: _Solver = solve) -> None:
                for p in points:
                    solve(arm, p)

        else:
            q = solve(arm, points).q

            def run(solve: _Solver = solve) -> None:
                solve(arm, points)

        residual = np.hypot(*(arm.fk(q) - points).T)
        tolerance = (
            (arm.l1 + 2 * arm.l2) * step / 2
            if name == "brute force"
            else 1e-9 * (arm.l1 + arm.l2)
        )
        rows.append(
            {
                "method": name,
                "seconds_per_target": median_time(run, repeat=repeat) / len(points),
                "max_residual": float(residual.max()),
                "solved": float(np.mean(residual <= tolerance)),
            }
        )
    return rows
