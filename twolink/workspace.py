"""The workspace: which tip positions an arm reaches within its joint limits.

Without limits a 2R arm reaches the annulus ``|l1 - l2| <= |p| <= l1 + l2``.
Joint limits cut that down.  The module answers, for either limit convention
of :class:`~twolink.TwoLinkArm` (``limit_convention="relative"`` bounds ``(q1, q2)``,
``limit_convention="absolute"`` bounds the link angles ``(q1, q1 + q2)``):

- :func:`is_reachable`: is a point reached by a configuration within limits?
- :func:`sample_reachable`: random configurations within limits and their tips.
- :func:`candidate_arcs` / :func:`boundary_arcs`: the boundary as exact arcs
  (one joint at a limit or at a singular value, the other swept).
- :func:`clearance` and :func:`largest_inscribed_circle`: how much room there is,
  measured by :func:`distance_to_arcs` (exact distances to all arcs at once).
- :class:`BranchTable` and :func:`largest_circle_on_grid`: the same answers fast
  enough for a slider, for arms that differ only in their limits (IK solved
  once for a fixed set of points, only the limit test redone, by comparisons of
  angles wrapped once) and a coarse-to-fine search for a large circle from points
  known to be inside.
- :func:`circle_points`: equally spaced targets on a circle.
- :func:`require_reachable`: the same test, raising a clear error naming the
  first point that is out of the workspace.

The functions with an ``elbow`` parameter read it in one way
(:data:`twolink.conventions.ELBOW_WORDS`): ``"auto"`` (the default), the
workspace of either branch (a point counts when some configuration within
the limits reaches it); ``"down"`` / ``"up"``, the workspace of that branch
only (a motion that must not flip its elbow); ``"both"``, the points reached
on both branches within the limits (where the arm may choose either elbow).
The limit-aware inverse kinematics they build on is
:func:`twolink.ik.solutions_within_limits`.

Examples
--------
>>> from twolink import arms, workspace
>>> workspace.is_reachable(arms.ten, [[12.5, 12.5], [5.0, -15.0], [0.0, 0.0]])
array([ True, False, False])
"""

from __future__ import annotations

import dataclasses
import time
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import (
    InputTypeError,
    as_count,
    as_finite_scalar,
    as_length,
    as_pairs,
    require_arm,
)
from ._values import same, value_key
from .arcs import Arc, arc_distance, circle_intersections
from .budgets import DEFAULT_MAX_WALL_TIME, MAX_SAMPLES
from .conventions import check_elbow, to_absolute, to_relative, wrap_angle
from .errors import UnreachableError
from .ik.analytic import closed_form
from .ik.limits import (
    LIMIT_TOL,
    free_q1_at_base,
    move_into_limits,
    solutions_within_limits,
)
from .kinematics import require_within_reach

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "is_reachable",
    "sample_reachable",
    "boundary_arcs",
    "distance_to_arcs",
    "clearance",
    "largest_inscribed_circle",
    "BranchTable",
    "largest_circle_on_grid",
    "circle_points",
]

_TWO_PI = 2.0 * np.pi


#: The ring radius of :func:`boundary_arcs`, relative to the reach: above the slack ``LIMIT_TOL``
#: (1e-7 rad) at the limits, which a smaller ring would not leave, and small beside the
#: narrowest part of a workspace, across which a larger ring would reach.
PROBE_RANGE = (1e-6, 1e-2)

#: Reachable points :func:`largest_inscribed_circle` samples to pick its starts from (so at most this many starts).
START_CANDIDATES = 4000

#: Most refinement rounds of :func:`largest_circle_on_grid` (each divides its step by 3:
#: 3**30 ~ 2e14, about the ratio of a reach to its round-off).
MAX_REFINEMENTS = 30

#: The pattern of one refinement round of :func:`largest_circle_on_grid`: 7 x 7 points,
#: ``-3 .. 3`` steps either way (so a round covers the spacing of the round before).
_REFINE_PATTERN = np.stack(np.meshgrid(*[np.arange(-3.0, 4.0)] * 2), axis=-1).reshape(
    -1, 2
)


def describe_limits(arm: TwoLinkArm) -> str:
    """The joint limits in words and degrees, for messages and tables.

    Examples
    --------
    >>> from twolink import arms
    >>> describe_limits(arms.ten)
    'q1 in [0, 90] deg, q2 in [-90, 90] deg (relative joint angles)'
    >>> describe_limits(arms.two_metre_limited)
    'link 1 angle q1 in [35, 145] deg, link 2 angle q1 + q2 in [35, 145] deg (absolute angles from the x-axis)'
    >>> describe_limits(None)
    Traceback (most recent call last):
    ...
    twolink.errors.InputTypeError: arm must be a twolink.TwoLinkArm; got None (NoneType)
    """
    require_arm(arm)
    if arm.q_min is None or arm.q_max is None:
        return "no joint limits"
    low, high = np.degrees(arm.q_min), np.degrees(arm.q_max)
    if arm.limit_convention == "relative":
        return (
            f"q1 in [{low[0]:.6g}, {high[0]:.6g}] deg, q2 in [{low[1]:.6g}, {high[1]:.6g}] deg "
            "(relative joint angles)"
        )
    return (
        f"link 1 angle q1 in [{low[0]:.6g}, {high[0]:.6g}] deg, link 2 angle q1 + q2 in "
        f"[{low[1]:.6g}, {high[1]:.6g}] deg (absolute angles from the x-axis)"
    )


def _on_branches(valid: NDArray[np.bool_], elbow: str) -> NDArray[np.bool_]:
    """Per point, whether the branches ``elbow`` asks for reach it (``valid``: shape (..., 2), down, up)."""
    if elbow == "auto":
        return valid[..., 0] | valid[..., 1]
    if elbow == "both":
        return valid[..., 0] & valid[..., 1]
    return valid[..., 0 if elbow == "down" else 1]


def is_reachable(
    arm: TwoLinkArm, p: ArrayLike, tol: float = LIMIT_TOL, elbow: str = "auto"
) -> NDArray[np.bool_]:
    """Whether a configuration within the joint limits puts the tip at ``p``.

    Vectorised: solves both closed-form branches at every point and checks
    them against the limits in the arm's convention (angles compared modulo
    ``2 pi``; :func:`twolink.ik.solutions_within_limits`).  Points outside
    the reach annulus are unreachable whatever the limits.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Tip positions, metres.
    tol : float
        Slack in radians at each limit (a point on the boundary counts as inside).
    elbow : {"auto", "down", "up", "both"}
        ``"auto"``: either branch will do.  ``"down"`` / ``"up"``: only that
        branch counts (the workspace of a motion that must not flip its
        elbow).  ``"both"``: both branches must reach the point within the
        limits (the arm can take it with either elbow).

    Returns
    -------
    numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> from twolink import arms
    >>> is_reachable(arms.two_metre_limited, [[0.0, 3.0], [0.0, 2.0], [3.0, 0.0]])
    array([ True, False, False])
    >>> is_reachable(arms.two_metre, [[0.0, 0.0], [0.0, 4.5]])
    array([ True, False])
    >>> is_reachable(arms.ten, [[15.0, 1.0], [1.0, 15.0], [12.5, 12.5]], elbow="down")
    array([False,  True,  True])
    >>> is_reachable(arms.ten, [[15.0, 1.0], [1.0, 15.0], [12.5, 12.5]], elbow="both")
    array([False, False,  True])
    """
    elbow = check_elbow(elbow)
    return _on_branches(solutions_within_limits(arm, p, tol)[1], elbow)


def require_reachable(
    arm: TwoLinkArm, p: ArrayLike, what: str = "point", tol: float = LIMIT_TOL
) -> NDArray[np.float64]:
    """Return ``p`` as an array, or raise naming the first point out of the workspace.

    Out of the reach annulus, the message is the package's one reach message
    (:func:`twolink.kinematics.require_within_reach`); inside it but outside
    the joint limits, the message has the same beginning and then gives the
    limits and both IK branches in degrees.

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
        Points (a path, in order), metres.
    what : str
        How to call a point in the message, e.g. ``"path point"``.
    tol : float
        Slack at the joint limits, radians.

    Returns
    -------
    numpy.ndarray, shape (..., 2)

    Raises
    ------
    twolink.UnreachableError
        Naming the first unreachable point: its coordinates, its index in a
        batch (and how many are unreachable), its distance from the base,
        and either the reach interval (outside the annulus) or the joint
        limits with both IK branches in degrees (inside the annulus but
        outside the limits).

    Examples
    --------
    >>> from twolink import arms
    >>> require_reachable(arms.ten, [[12.5, 12.5], [20.0, 5.0]], what="path point")
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: path point (20, 5) (index (1,), first of 1) is 20.6155 m from the base; this arm reaches distances in [0, 20] m (l1=10, l2=10)
    >>> require_reachable(arms.ten, [-12.0, 12.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: point (-12, 12) is 16.9706 m from the base, inside the reach [0, 20] m but outside the joint limits: q1 in [0, 90] deg, q2 in [-90, 90] deg (relative joint angles); elbow down needs q = (103.1, 63.9) deg, elbow up q = (166.9, -63.9) deg
    """
    points: NDArray[np.float64] = as_pairs(p, "p")
    require_within_reach(arm, points, what=what)
    reachable = np.any(solutions_within_limits(arm, points, tol)[1], axis=-1)
    if np.all(reachable):
        return points
    index = tuple(int(i) for i in np.argwhere(~reachable)[0]) if reachable.ndim else ()
    x, y = points[index]
    where = (
        f" (index {index}, first of {int(np.count_nonzero(~reachable))})"
        if reachable.ndim
        else ""
    )
    r_min, r_max = arm.reach
    # each angle shown as the turn nearest the middle of its limit interval: how far outside it is
    q_plain = closed_form(arm, points[index], elbow="both").q
    angles = to_absolute(q_plain) if arm.limit_convention == "absolute" else q_plain
    middle = (np.asarray(arm.q_min) + np.asarray(arm.q_max)) / 2.0
    down, up = np.degrees(middle + wrap_angle(angles - middle))
    needs = "link angles (q1, q1 + q2)" if arm.limit_convention == "absolute" else "q"
    raise UnreachableError(
        f"{what} ({x:.6g}, {y:.6g}){where} is {float(np.hypot(x, y)):.6g} m from the base, inside the reach "
        f"[{r_min:.6g}, {r_max:.6g}] m but outside the joint limits: "
        f"{describe_limits(arm)}; elbow down needs {needs} = ({down[0]:.4g}, {down[1]:.4g}) deg, "
        f"elbow up {needs} = ({up[0]:.4g}, {up[1]:.4g}) deg"
    )


def sample_reachable(
    arm: TwoLinkArm, n: int = 2000, seed: int | None = 0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Random configurations within the limits and the tip positions they reach.

    Configurations are uniform over the joint-limit box in the arm's
    convention (over ``[-pi, pi)^2`` without limits), so the points are
    denser where the map from joints to tip compresses area (near the
    singular circles).

    Parameters
    ----------
    arm : TwoLinkArm
    n : int
        Number of samples.
    seed : int or None
        Seed of :func:`numpy.random.default_rng`, for reproducible figures.

    Returns
    -------
    p : numpy.ndarray, shape (n, 2)
        Tip positions, metres.
    q : numpy.ndarray, shape (n, 2)
        Relative joint angles, radians (within limits).

    Examples
    --------
    >>> from twolink import arms
    >>> p, q = sample_reachable(arms.ten, n=500)
    >>> p.shape, bool(np.all(arms.ten.within_limits(q))), bool(np.all(is_reachable(arms.ten, p)))
    ((500, 2), True, True)
    """
    require_arm(arm)
    n = as_count(n, "n (samples)", minimum=1, maximum=MAX_SAMPLES)
    if seed is not None:
        seed = as_count(seed, "seed (None or an integer >= 0)", minimum=0)
    rng = np.random.default_rng(seed)
    if arm.has_limits:
        low, high = np.asarray(arm.q_min), np.asarray(arm.q_max)
    else:
        low, high = np.full(2, -np.pi), np.full(2, np.pi)
    angles = rng.uniform(low, high, size=(n, 2))
    q = (
        to_relative(angles)
        if arm.has_limits and arm.limit_convention == "absolute"
        else angles
    )
    return arm.fk(q), q


def _within_turns(
    angle: NDArray[np.float64], low: float, high: float, tol: float
) -> NDArray[np.bool_]:
    """Whether wrapped angles (in ``[-pi, pi)``) lie in ``[low - tol, high + tol]`` modulo ``2 pi``.

    The rule of :func:`twolink.ik.limits.move_into_limits` (some whole turn of the
    angle lies in the interval), by comparisons only: the interval is moved
    by whole turns to start in ``[-pi, pi)``, and an interval that runs past
    ``pi`` also holds the angles a turn below its end.
    """
    low, high = low - tol, high + tol
    if high - low >= _TWO_PI:  # a full turn: every angle
        return np.ones(angle.shape, dtype=np.bool_)
    shift = _TWO_PI * np.floor((low + np.pi) / _TWO_PI)
    low, high = low - shift, high - shift
    inside = (angle >= low) & (angle <= high)
    if high >= np.pi:
        inside |= angle <= high - _TWO_PI
    if low < -np.pi:  # only by round-off of the shift
        inside |= angle >= low + _TWO_PI
    return inside


class BranchTable:
    """Both IK branches at fixed points, solved once, for arms that differ only in their limits.

    :func:`is_reachable` solves the closed form at every point, then applies
    the package's limit rule (:func:`twolink.ik.solutions_within_limits`:
    each angle moved by whole turns into its interval, with the slack
    ``tol``).  The solving depends on the link lengths only.  A table solves
    it once and stores, per branch, the angles each limit convention limits,
    wrapped to ``[-pi, pi)``: ``(q1, q2)`` for relative limits, the link
    angles ``(q1, q1 + q2)`` for absolute ones.  :meth:`within_limits` and
    :meth:`reachable` then only compare those angles with the limits: each
    in its interval modulo ``2 pi``, with the slack ``tol``, the rule of
    :func:`twolink.ik.limits.move_into_limits`.  That is tens of times faster
    than solving again or moving the angles by turns
    (``benchmarks/bench_workspace.py``): fast enough for a slider that
    changes the limits over a shading grid.  The answer is what
    :func:`twolink.ik.solutions_within_limits` and :func:`is_reachable` give
    for the same arm and points (tested), except for an angle within
    round-off (about ``1e-15`` rad) of a limit widened by ``tol``, where the
    two ways of reducing it by whole turns can round apart.  At the base of
    an arm with ``l1 == l2``, which the folded arm reaches with any ``q1``,
    the table applies the package's rule itself
    (:func:`twolink.ik.turns.free_q1_at_base`).
    :meth:`solutions_within_limits` also returns the angles moved into the
    limits, computed as the package computes them (exactly its answer).

    Parameters
    ----------
    arm : TwoLinkArm
        Gives the link lengths (its limits, if any, are not used).
    p : array_like, shape (..., 2)
        The points, metres; at most ``MAX_SAMPLES`` of them.

    Raises
    ------
    ValueError
        For more than ``MAX_SAMPLES`` points, or (in the methods) an arm with
        other link lengths.

    Examples
    --------
    >>> from dataclasses import replace
    >>> from twolink import arms
    >>> table = BranchTable(arms.ten, [[12.5, 12.5], [15.0, 1.0], [1.0, 15.0], [0.0, 0.0]])
    >>> table.within_limits(arms.ten)  # elbow down, elbow up
    array([[ True,  True],
           [False,  True],
           [ True, False],
           [False, False]])
    >>> wider = replace(arms.ten, q_min=(-np.pi / 2, -np.pi), q_max=(np.pi / 2, np.pi))
    >>> table.reachable(wider), is_reachable(wider, table.points)
    (array([ True,  True,  True,  True]), array([ True,  True,  True,  True]))
    >>> table.reachable(arms.ten, elbow="down")
    array([ True, False,  True, False])
    >>> table.reachable(arms.two_metre_limited)
    Traceback (most recent call last):
    ...
    ValueError: this BranchTable was solved for l1 = 10, l2 = 10; got an arm with l1 = 2, l2 = 2 (make a table for it)
    """

    def __init__(self, arm: TwoLinkArm, p: ArrayLike) -> None:
        require_arm(arm)
        points: NDArray[np.float64] = as_pairs(p, "p")
        count = int(np.prod(points.shape[:-1]))
        if count > MAX_SAMPLES:
            raise ValueError(
                f"p holds {count} points; a BranchTable takes at most MAX_SAMPLES = {MAX_SAMPLES}"
            )
        self.l1, self.l2 = float(arm.l1), float(arm.l2)
        self.points = points.copy()
        self.points.setflags(write=False)
        links = (
            dataclasses.replace(arm, q_min=None, q_max=None) if arm.has_limits else arm
        )
        # without limits nothing is moved: the closed form's two branches, and the reach test
        self._q_both, in_reach = solutions_within_limits(links, points)
        self._in_reach: NDArray[np.bool_] = in_reach[..., 0]
        # the angles each convention limits, wrapped once, as contiguous (..., 2) arrays (down, up)
        self._wrapped: dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]] = {}
        for convention, limited in (
            ("relative", self._q_both),
            ("absolute", to_absolute(self._q_both)),
        ):
            angles = np.asarray(wrap_angle(limited), dtype=float)
            self._wrapped[convention] = (angles[..., 0].copy(), angles[..., 1].copy())
        # where any q1 reaches the point (the base of an equal-link arm): the package's own rule there
        self._at_base: NDArray[np.bool_] = (
            free_q1_at_base(links, points)[0] & self._in_reach
        )

    def __eq__(self, other: object) -> bool:
        """Tables of the same link lengths and points are equal (the rest follows from them)."""
        if type(other) is not BranchTable:
            return NotImplemented
        return (self.l1, self.l2) == (other.l1, other.l2) and same(
            self.points, other.points
        )

    def __hash__(self) -> int:
        return hash((self.l1, self.l2, value_key(self.points)))

    def _require_links(self, arm: TwoLinkArm) -> None:
        require_arm(arm)
        if float(arm.l1) != self.l1 or float(arm.l2) != self.l2:
            raise ValueError(
                f"this BranchTable was solved for l1 = {self.l1:g}, l2 = {self.l2:g}; got an arm with "
                f"l1 = {arm.l1:g}, l2 = {arm.l2:g} (make a table for it)"
            )

    def solutions_within_limits(
        self, arm: TwoLinkArm, tol: float = LIMIT_TOL
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """``twolink.ik.solutions_within_limits(arm, self.points, tol)``, from the stored branches.

        The angles are moved into the limits as the package moves them
        (:func:`twolink.ik.limits.move_into_limits`), so this gives exactly
        what the package gives; when only the answer is needed,
        :meth:`within_limits` is faster.

        Parameters
        ----------
        arm : TwoLinkArm
            Same link lengths as the table's; any limits, either convention.
        tol : float
            Slack in radians at each limit.

        Returns
        -------
        q_both : numpy.ndarray, shape (..., 2, 2)
            Elbow down ``[..., 0, :]`` and up ``[..., 1, :]``, moved into the limits where possible.
        valid : numpy.ndarray of bool, shape (..., 2)
            Whether each branch reaches its point within the limits.
        """
        self._require_links(arm)
        tol = as_finite_scalar(tol, "tol (rad)", minimum=0.0)
        return self._moved_into(arm, self._q_both, self._in_reach, self._at_base, tol)

    @staticmethod
    def _moved_into(
        arm: TwoLinkArm,
        q_both: NDArray[np.float64],
        in_reach: NDArray[np.bool_],
        at_base: NDArray[np.bool_],
        tol: float,
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """The package's rule on stored branches: free ``q1`` at the base, then whole turns into the limits."""
        q_both = q_both.copy()
        valid = np.repeat(in_reach[..., None], 2, axis=-1)
        if not arm.has_limits:
            return q_both, valid
        free_q1 = free_q1_at_base(arm, np.zeros(2))[1]
        if free_q1 is not None:
            q_both[at_base, :, 0] = free_q1
        q_both, inside = move_into_limits(arm, q_both, tol)
        return q_both, valid & inside

    def within_limits(
        self, arm: TwoLinkArm, tol: float = LIMIT_TOL
    ) -> NDArray[np.bool_]:
        """Whether each branch reaches its point within ``arm``'s limits: ``solutions_within_limits(arm, tol)[1]``.

        By comparisons of the stored wrapped angles with the limits (see the
        class: the same answer, but for round-off at a limit plus ``tol``).

        Parameters
        ----------
        arm : TwoLinkArm
            Same link lengths as the table's; any limits, either convention.
        tol : float
            Slack in radians at each limit.

        Returns
        -------
        numpy.ndarray of bool, shape (..., 2)
            Elbow down ``[..., 0]``, elbow up ``[..., 1]``.
        """
        self._require_links(arm)
        tol = as_finite_scalar(tol, "tol (rad)", minimum=0.0)
        if arm.q_min is None or arm.q_max is None:
            return np.repeat(self._in_reach[..., None], 2, axis=-1)
        first, second = self._wrapped[arm.limit_convention]
        (low_1, low_2), (high_1, high_2) = arm.q_min, arm.q_max
        valid = _within_turns(first, low_1, high_1, tol)
        valid &= _within_turns(second, low_2, high_2, tol)
        valid &= self._in_reach[..., None]
        if np.any(self._at_base):
            valid[self._at_base] = self._moved_into(
                arm,
                self._q_both[self._at_base],
                self._in_reach[self._at_base],
                np.ones(np.count_nonzero(self._at_base), dtype=np.bool_),
                tol,
            )[1]
        return valid

    def reachable(
        self, arm: TwoLinkArm, tol: float = LIMIT_TOL, elbow: str = "auto"
    ) -> NDArray[np.bool_]:
        """``is_reachable(arm, self.points, tol, elbow)``, from the stored branches.

        Parameters
        ----------
        arm : TwoLinkArm
            Same link lengths as the table's; any limits, either convention.
        tol : float
            Slack in radians at each limit.
        elbow : {"auto", "down", "up", "both"}
            Which branches count, as for :func:`is_reachable`.

        Returns
        -------
        numpy.ndarray of bool, shape (...)
        """
        elbow = check_elbow(elbow)
        return _on_branches(self.within_limits(arm, tol), elbow)


def _polar_offset(arm: TwoLinkArm, q2: float) -> tuple[float, float]:
    """Radius and polar angle offset of the tip for fixed ``q2``: ``p = r (cos(q1 + psi), sin(q1 + psi))``."""
    radius = float(np.hypot(arm.l1 + arm.l2 * np.cos(q2), arm.l2 * np.sin(q2)))
    return radius, float(np.arctan2(arm.l2 * np.sin(q2), arm.l1 + arm.l2 * np.cos(q2)))


def _values_in(value: float, low: float, high: float) -> list[float]:
    """``value + 2 pi k`` lying in ``[low, high]``, for the k that give one."""
    first = np.ceil((low - value) / _TWO_PI - 1e-12)
    last = np.floor((high - value) / _TWO_PI + 1e-12)
    return [float(value + _TWO_PI * k) for k in np.arange(first, last + 1)]


def _overlaps(
    low_a: float, high_a: float, low_b: float, high_b: float
) -> list[tuple[float, float]]:
    """Intervals where ``[low_a, high_a]`` meets ``[low_b, high_b] + 2 pi k`` (for any k)."""
    intervals = []
    for k in range(-2, 3):
        low = max(low_a, low_b + _TWO_PI * k)
        high = min(high_a, high_b + _TWO_PI * k)
        if (
            high > low
        ):  # a single shared angle is a corner, already an end point of the edge arcs
            intervals.append((low, high))
    return intervals


def _label(name: str, angle: float) -> str:
    return f"{name} = {np.degrees(angle):.6g} deg"


def candidate_arcs(arm: TwoLinkArm) -> list[Arc]:
    """Every curve the workspace boundary can be made of, as exact arcs.

    The boundary of the reachable set lies on the images of the edges of the
    joint-limit box (one joint at a limit, the other swept through its range)
    and of the singular configurations inside the box (full stretch
    ``q2 = 0``, full fold ``q2 = pi``), and each of those images is a circular
    arc.  Parts of some arcs run through the inside of the set (the same
    points are reached by the other branch); :func:`boundary_arcs` keeps only
    the parts on the boundary.

    Relative limits: ``q1`` at a limit traces a circle of radius ``l2`` about
    the elbow; ``q2`` at a limit (or at 0 or pi) traces a circle about the base.
    Absolute limits: link 1 at a limit traces a circle of radius ``l2`` about
    the elbow; link 2 at a limit, a circle of radius ``l1`` about the point
    ``l2 (cos q12, sin q12)``.

    Returns
    -------
    list of twolink.arcs.Arc
        Each labelled with what traces it; ``kind`` is ``"joint limit"`` or ``"singular"``.

    Examples
    --------
    >>> from twolink import arms
    >>> [arc.label for arc in candidate_arcs(arms.ten)]
    ['q1 = 0 deg', 'q1 = 90 deg', 'q2 = -90 deg', 'q2 = 90 deg', 'q2 = 0 deg (full stretch)']
    >>> [arc.label for arc in candidate_arcs(arms.two_metre)]
    ['q2 = 0 deg (full stretch)', 'q2 = 180 deg (full fold)']
    """
    require_arm(arm)
    l1, l2 = arm.l1, arm.l2
    origin = (0.0, 0.0)
    if not arm.has_limits:
        low, high = np.array([-np.pi, -np.pi]), np.array([np.pi, np.pi])
        convention = "relative"
    else:
        low, high = np.asarray(arm.q_min), np.asarray(arm.q_max)
        convention = arm.limit_convention
    span = np.minimum(high - low, _TWO_PI)
    bounded = high - low < _TWO_PI
    arcs: list[Arc] = []
    if convention == "relative":
        if bounded[0]:
            for q1 in (low[0], high[0]):
                elbow_point = (l1 * np.cos(q1), l1 * np.sin(q1))
                arcs.append(
                    Arc(
                        elbow_point,
                        l2,
                        q1 + low[1],
                        span[1],
                        _label("q1", q1),
                        "joint limit",
                    )
                )
        if bounded[1]:
            for q2 in (low[1], high[1]):
                radius, offset = _polar_offset(arm, q2)
                arcs.append(
                    Arc(
                        origin,
                        radius,
                        low[0] + offset,
                        span[0],
                        _label("q2", q2),
                        "joint limit",
                    )
                )
        for singular, name in ((0.0, "full stretch"), (np.pi, "full fold")):
            for q2 in _values_in(singular, low[1], high[1])[:1]:
                radius, offset = _polar_offset(arm, q2)
                arcs.append(
                    Arc(
                        origin,
                        radius,
                        low[0] + offset,
                        span[0],
                        f"{_label('q2', singular)} ({name})",
                        "singular",
                    )
                )
        return arcs
    if bounded[0]:
        for q1 in (low[0], high[0]):
            elbow_point = (l1 * np.cos(q1), l1 * np.sin(q1))
            arcs.append(
                Arc(elbow_point, l2, low[1], span[1], _label("q1", q1), "joint limit")
            )
    if bounded[1]:
        for q12 in (low[1], high[1]):
            centre = (l2 * np.cos(q12), l2 * np.sin(q12))
            arcs.append(
                Arc(centre, l1, low[0], span[0], _label("q1 + q2", q12), "joint limit")
            )
    # Full stretch: link angles equal; full fold: link 2 turned back by pi.
    for shift, name, radius in (
        (0.0, "full stretch", l1 + l2),
        (np.pi, "full fold", abs(l1 - l2)),
    ):
        for first, last in _overlaps(low[0], high[0], low[1] - shift, high[1] - shift):
            offset = 0.0 if (shift == 0.0 or l1 >= l2) else np.pi
            arcs.append(
                Arc(
                    origin,
                    radius,
                    first + offset,
                    last - first,
                    f"{_label('q2', shift)} ({name})",
                    "singular",
                )
            )
    return arcs


def _same_circle(arc_a: Arc, arc_b: Arc, scale: float) -> bool:
    return bool(
        np.hypot(arc_a.centre[0] - arc_b.centre[0], arc_a.centre[1] - arc_b.centre[1])
        <= 1e-12 * scale
        and abs(arc_a.radius - arc_b.radius) <= 1e-12 * scale
    )


def _same_arc(arc_a: Arc, arc_b: Arc, scale: float) -> bool:
    if not _same_circle(arc_a, arc_b, scale):
        return False
    # same end points and same midpoint (two halves of a circle share their end points)
    points_a = arc_a.point_at(np.array([0.0, 0.5, 1.0]))
    points_b = arc_b.point_at(np.array([0.0, 0.5, 1.0]))
    close = 1e-9 * scale
    return bool(
        np.abs(points_a - points_b).max() <= close
        or np.abs(points_a - points_b[::-1]).max() <= close
    )


def boundary_arcs(
    arm: TwoLinkArm, probe: float = 1e-5, elbow: str = "auto"
) -> list[Arc]:
    """The boundary of the reachable set, as exact arcs.

    Method: every candidate arc (:func:`candidate_arcs`) is cut where it
    meets another candidate (circle-circle intersections, exact), so each
    piece lies either wholly on the boundary, wholly inside the set or wholly
    outside it (possible for one branch only).  A piece is kept when its
    midpoint is reachable and some point of a small ring around it (radius
    ``probe * (l1 + l2)``) is not.  Where two arcs touch tangentially (an
    edge arc meets a singular circle tangentially at a singular pose) their
    computed crossings are ``sqrt(eps)`` apart; pieces shorter than
    ``1e-6 (l1 + l2)`` from such cuts are dropped, unless they are the whole
    boundary (joint limits narrower than that: a workspace that small is
    all slivers).

    Parameters
    ----------
    arm : TwoLinkArm
    probe : float
        Ring radius relative to the reach used to tell boundary from inside,
        within ``PROBE_RANGE`` = [1e-6, 1e-2].
    elbow : {"auto", "down", "up", "both"}
        Whose workspace: of either branch (``"auto"``), of one branch only
        (``"down"`` / ``"up"``; the singular arcs ``q2 = 0``, ``pi``, where the
        branches meet, bound it), or of the points both branches reach
        within the limits (``"both"``).

    Returns
    -------
    list of twolink.arcs.Arc

    Examples
    --------
    >>> from twolink import arms
    >>> [arc.label for arc in boundary_arcs(arms.ten)]
    ['q1 = 0 deg', 'q1 = 90 deg', 'q2 = -90 deg', 'q2 = 90 deg', 'q2 = 0 deg (full stretch)']
    >>> outer = boundary_arcs(arms.ten)[-1]
    >>> float(outer.radius), round(float(np.degrees(abs(outer.sweep))), 9)
    (20.0, 90.0)
    >>> [arc.label for arc in boundary_arcs(arms.ten, elbow="down")]
    ['q1 = 0 deg', 'q1 = 90 deg', 'q2 = 90 deg', 'q2 = 0 deg (full stretch)']
    >>> boundary_arcs(arms.ten, 0)
    Traceback (most recent call last):
    ...
    ValueError: probe (ring radius / reach) must be in [1e-06, 0.01]; got 0.0
    """
    require_arm(arm)
    probe = as_finite_scalar(probe, "probe (ring radius / reach)")
    if not PROBE_RANGE[0] <= probe <= PROBE_RANGE[1]:
        raise ValueError(
            f"probe (ring radius / reach) must be in [{PROBE_RANGE[0]:g}, {PROBE_RANGE[1]:g}]; got {probe}"
        )
    elbow = check_elbow(elbow)
    scale = arm.reach[1]
    candidates = candidate_arcs(arm)
    pieces: list[Arc] = []
    for index, arc in enumerate(candidates):
        cuts: list[float] = []
        for other_index, other in enumerate(candidates):
            if other_index == index:
                continue
            if _same_circle(arc, other, scale):
                crossings = other.end_points
            else:
                crossings = circle_intersections(
                    arc.centre, arc.radius, other.centre, other.radius
                )
            if len(crossings):
                fractions = arc.fraction_of(crossings)
                cuts.extend(fractions[fractions >= 0.0])
        pieces.extend(arc.split(cuts))
    directions = np.linspace(0.0, _TWO_PI, 16, endpoint=False)
    ring = probe * scale * np.c_[np.cos(directions), np.sin(directions)]
    midpoints = np.array([piece.point_at(0.5) for piece in pieces])
    outside = ~is_reachable(arm, midpoints[:, None, :] + ring, elbow=elbow)
    on_edge = np.any(outside, axis=1) & is_reachable(arm, midpoints, elbow=elbow)
    edge = [piece for piece, piece_on_edge in zip(pieces, on_edge) if piece_on_edge]
    whole = [
        piece
        for piece in edge
        if not 0.0 < piece.radius * abs(piece.sweep) < 1e-6 * scale
    ]
    kept: list[Arc] = []
    # slivers are kept only when they are the whole boundary (limits narrower than 1e-6 of the reach)
    for piece in whole or edge:
        if not any(_same_arc(piece, other, scale) for other in kept):
            kept.append(piece)
    return kept


#: Most point-arc pairs :func:`distance_to_arcs` measures in one numpy call (memory: a few
#: arrays of this many floats, 8 MB each); more points are measured in blocks.
_DISTANCE_BLOCK = 1_000_000


def _arc_arrays(arcs: list[Arc] | tuple[Arc, ...]) -> tuple[NDArray[np.float64], ...]:
    """Centre ``(k, 1, 2)``, radius, start, sweep ``(k, 1)`` and the end points ``(k, 1, 2)`` of ``k`` arcs."""
    centre, radius, start, sweep = (
        np.array([getattr(arc, name) for arc in arcs], dtype=float)[:, None]
        for name in ("centre", "radius", "start", "sweep")
    )
    ends = np.array([arc.end_points for arc in arcs])[:, :, None]
    return centre, radius, start, sweep, ends[:, 0], ends[:, 1]


def _nearest_arc_distance(
    points: NDArray[np.float64], arrays: tuple[NDArray[np.float64], ...]
) -> NDArray[np.float64]:
    """Distance from points ``(n, 2)`` to the nearest of the arcs of :func:`_arc_arrays`.

    :func:`twolink.arcs.arc_distance` (the formula of
    :meth:`twolink.arcs.Arc.distance`) on arrays of arcs: all arcs in one
    numpy call per block of ``_DISTANCE_BLOCK`` point-arc pairs.
    """
    block = max(1, _DISTANCE_BLOCK // len(arrays[1]))
    if len(points) > block:
        return np.concatenate(
            [
                _nearest_arc_distance(points[first : first + block], arrays)
                for first in range(0, len(points), block)
            ]
        )
    return arc_distance(points, *arrays).min(axis=0)


def _require_arcs(arcs: object) -> None:
    if not isinstance(arcs, (list, tuple)) or not all(
        isinstance(arc, Arc) for arc in arcs
    ):
        raise InputTypeError(
            f"arcs must be a list of twolink.arcs.Arc (from workspace.boundary_arcs); got {arcs!r}"
        )


def distance_to_arcs(p: ArrayLike, arcs: list[Arc]) -> NDArray[np.float64]:
    """Distance from points to the nearest of some arcs, exactly, for all arcs at once.

    ``min(arc.distance(p) for arc in arcs)`` (:meth:`twolink.arcs.Arc.distance`:
    inside an arc's angular span the nearest point is the radial projection
    onto its circle, outside it the nearer end point), in one numpy call over
    points and arcs instead of one per arc (in blocks, for many points):
    what :func:`clearance` and :func:`largest_circle_on_grid` measure with.

    Parameters
    ----------
    p : array_like, shape (..., 2)
        Points, metres.
    arcs : list of twolink.arcs.Arc
        For example a workspace's :func:`boundary_arcs`.

    Returns
    -------
    numpy.ndarray, shape (...)
        Metres; ``inf`` everywhere when there are no arcs.

    Raises
    ------
    twolink.errors.InputTypeError
        When ``arcs`` is not a list of arcs.
    ValueError
        For points that are not finite pairs.

    Examples
    --------
    >>> from twolink.arcs import Arc
    >>> quarter = Arc((0.0, 0.0), 2.0, 0.0, np.pi / 2)
    >>> point = Arc((3.0, 0.0), 0.0, 0.0, 0.0)
    >>> distance_to_arcs([[3.0, 1.0], [0.0, 0.0], [-2.0, -1.0]], [quarter, point]).round(12)
    array([1.        , 2.        , 3.60555128])
    >>> distance_to_arcs([0.0, 0.0], [])
    array(inf)
    """
    _require_arcs(arcs)
    points: NDArray[np.float64] = as_pairs(p, "p")
    flat = points.reshape(-1, 2)
    if not arcs:
        return np.full(points.shape[:-1], np.inf)
    return _nearest_arc_distance(flat, _arc_arrays(arcs)).reshape(points.shape[:-1])


def clearance(
    arm: TwoLinkArm, p: ArrayLike, arcs: list[Arc] | None = None, elbow: str = "auto"
) -> NDArray[np.float64]:
    """Signed distance from points to the edge of the reachable set, metres.

    Positive inside (the radius of the largest circle about ``p`` that fits
    in the workspace), negative outside, exact: distances to the boundary
    arcs, not to sampled points.  ``-inf`` everywhere when nothing is
    reachable (an ``elbow`` branch entirely outside the limits).

    Parameters
    ----------
    arm : TwoLinkArm
    p : array_like, shape (..., 2)
    arcs : list of Arc, optional
        :func:`boundary_arcs` of the arm (same ``elbow``), if already computed.
    elbow : {"auto", "down", "up", "both"}
        Room in the workspace of either branch (``"auto"``), of one branch
        only, or of the points both branches reach (as :func:`boundary_arcs`).

    Returns
    -------
    numpy.ndarray, shape (...)

    Examples
    --------
    >>> from twolink import arms
    >>> clearance(arms.ten, [[12.5, 12.5], [0.0, 0.0]]).round(6)
    array([  2.32233 , -14.142136])
    """
    points: NDArray[np.float64] = as_pairs(p, "p")
    elbow = check_elbow(elbow)
    if arcs is None:
        arcs = boundary_arcs(arm, elbow=elbow)
    else:
        require_arm(arm)
        _require_arcs(arcs)
    if not arcs:  # nothing is reachable (one branch may be entirely outside the limits)
        return np.full(points.shape[:-1], -np.inf)
    return _signed_clearance(arm, points, _arc_arrays(arcs), elbow)


def _signed_clearance(
    arm: TwoLinkArm,
    points: NDArray[np.float64],
    arrays: tuple[NDArray[np.float64], ...],
    elbow: str,
) -> NDArray[np.float64]:
    """:func:`clearance` of checked points ``(..., 2)``, measured to the arcs of
    :func:`_arc_arrays` (built once by a caller that measures many times)."""
    distance = _nearest_arc_distance(points.reshape(-1, 2), arrays).reshape(
        points.shape[:-1]
    )
    return np.where(is_reachable(arm, points, elbow=elbow), distance, -distance)


class _OutOfTime(Exception):
    """Raised inside the optimiser's objective when the wall-time budget is spent (never reaches users)."""


def largest_inscribed_circle(
    arm: TwoLinkArm,
    starts: int = 6,
    seed: int | None = 0,
    elbow: str = "auto",
    max_wall_time: float = DEFAULT_MAX_WALL_TIME,
) -> tuple[NDArray[np.float64], float]:
    """The largest circle that fits inside the reachable set: ``(centre, radius)``.

    Method: maximise :func:`clearance` (exact distance to the boundary arcs,
    negative outside the set) over the centre with
    :func:`scipy.optimize.minimize` (Nelder-Mead, which needs no gradient:
    clearance is a minimum of distances and has kinks).  The starts are the
    ``starts`` sampled reachable points with the most clearance, kept apart so
    that separate lobes of the workspace are all tried.

    Accuracy: the radius returned is the exact clearance of the centre
    returned, so the circle always fits; it falls short of the true maximum
    by the optimiser's tolerance, about ``1e-9 (l1 + l2)`` (checked in the
    tests against the closed form ``10 - 5 sqrt 2`` for :data:`twolink.arms.ten`).
    The centre need not be unique: for a workspace whose narrowest part is an
    annulus band, every centre along the band's mid-circle that keeps the
    circle inside gives the same radius; one of them is returned.

    Parameters
    ----------
    arm : TwoLinkArm
    starts : int
        Number of optimiser starts, at most ``START_CANDIDATES`` = 4000 (the
        reachable points sampled to choose them from); each takes about 0.2 s.
    seed : int or None
        Seed for the sampled starting points.
    elbow : {"auto", "down", "up", "both"}
        The largest circle in the workspace of either branch (``"auto"``),
        of one branch only (a circle the arm can trace without flipping its
        elbow), or of the points both branches reach.
    max_wall_time : float
        Budget of wall-clock seconds (default ``DEFAULT_MAX_WALL_TIME`` = 30):
        nothing runs for minutes.

    Returns
    -------
    centre : numpy.ndarray, shape (2,)
    radius : float

    Raises
    ------
    ValueError
        For a bad ``starts``, ``elbow`` or budget, or when no point is reachable.
    RuntimeError
        When the starts use up ``max_wall_time`` (the message says how many
        were done and what to change).

    Examples
    --------
    >>> from twolink import arms
    >>> centre, radius = largest_inscribed_circle(arms.ten)
    >>> round(radius, 6), round(float(10 - 5 * np.sqrt(2)), 6)
    (2.928932, 2.928932)
    >>> round(float(np.hypot(*centre)), 6)  # on the mid-circle of the band 10 sqrt 2 <= r <= 20
    17.071068
    """
    require_arm(arm)
    starts = as_count(starts, "starts", minimum=1, maximum=START_CANDIDATES)
    elbow = check_elbow(elbow)
    max_wall_time = as_finite_scalar(
        max_wall_time, "max_wall_time (s)", minimum=0.0, strictly=True
    )
    deadline = time.monotonic() + max_wall_time
    arcs = boundary_arcs(arm, elbow=elbow)
    if not arcs:
        reached = {
            "auto": "reaches any point",
            "down": "is elbow down",
            "up": "is elbow up",
            "both": "reaches a point that the other branch reaches too",
        }[elbow]
        raise ValueError(
            f"no circle fits: no configuration within the joint limits ({describe_limits(arm)}) {reached}"
        )
    scale = arm.reach[1]
    arrays = _arc_arrays(arcs)  # once: the optimisers measure thousands of times
    samples, _ = sample_reachable(arm, n=START_CANDIDATES, seed=seed)
    room = _signed_clearance(arm, samples, arrays, elbow)
    chosen: list[int] = []
    for index in np.argsort(room)[::-1]:
        if all(
            np.hypot(*(samples[index] - samples[other])) > 0.5 * room[index]
            for other in chosen
        ):
            chosen.append(index)
        if len(chosen) == starts:
            break

    def negative_clearance(centre: NDArray[np.float64]) -> float:
        if time.monotonic() > deadline:
            raise _OutOfTime
        return -float(_signed_clearance(arm, centre, arrays, elbow))

    import scipy.optimize  # here, not at the top: import twolink stays light

    best_centre, best_radius = samples[chosen[0]], float(room[chosen[0]])
    for done, index in enumerate(chosen):
        try:
            outcome = scipy.optimize.minimize(
                negative_clearance,
                samples[index],
                method="Nelder-Mead",
                options={
                    "xatol": 1e-12 * scale,
                    "fatol": 1e-14 * scale,
                    "maxiter": 4000,
                    "maxfev": 8000,
                },
            )
        except _OutOfTime:
            raise RuntimeError(
                f"largest_inscribed_circle used up its budget of max_wall_time = {max_wall_time:.3g} s after "
                f"{done} of {len(chosen)} starts (best radius so far {best_radius:.6g} m): pass fewer starts "
                f"(the default is 6) or a larger max_wall_time"
            ) from None
        radius = float(_signed_clearance(arm, outcome.x, arrays, elbow))
        if radius > best_radius:
            best_centre, best_radius = np.asarray(outcome.x, dtype=float), radius
    return best_centre, best_radius


def largest_circle_on_grid(
    arcs: list[Arc], candidates: ArrayLike, spacing: float, tol: float
) -> tuple[NDArray[np.float64] | None, float]:
    """A large circle inside a workspace, by a grid search: fast, not the largest.

    Method: the candidate farthest from the boundary arcs, then rounds of
    7 x 7 points about the best centre so far, ``spacing / 3`` apart in the
    first round and a third as far apart in each next one, until that step
    is at most ``tol``.  A round only tries points nearer the best centre than
    its radius: they are inside the workspace (the disc about an inside point
    with its clearance as radius holds no boundary point), so no
    reachability test is needed, and the radius is the exact distance to
    the arcs (:func:`distance_to_arcs`, all arcs in one numpy call per
    round).  For the largest circle, :func:`largest_inscribed_circle` (an
    optimiser, about a second; this takes a fraction of a millisecond for
    chapter 7's grid: ``benchmarks/bench_workspace.py``).

    Accuracy: the circle always fits (its radius is the exact clearance of
    its centre), and when the largest circle's centre lies within
    ``spacing / sqrt 2`` of a candidate (a grid of that spacing covering the
    workspace) the radius is at most ``spacing / sqrt 2`` short of the
    largest (clearance changes no faster than the centre moves); in practice
    it is within about ``tol`` (tested against :func:`largest_inscribed_circle`).

    Parameters
    ----------
    arcs : list of twolink.arcs.Arc
        The workspace's :func:`boundary_arcs` (with the ``elbow`` the
        candidates were chosen for).
    candidates : array_like, shape (..., 2)
        Start points **inside** the workspace, for example the points of a
        grid that :func:`is_reachable` (or :meth:`BranchTable.reachable`)
        accepts; at most ``MAX_SAMPLES``.
    spacing : float
        Distance between neighbouring candidates, metres (> 0).
    tol : float
        The search stops when its step is at most this, metres (> 0); at most
        ``MAX_REFINEMENTS`` = 30 rounds (``spacing / tol`` up to ``3**31``).

    Returns
    -------
    centre : numpy.ndarray, shape (2,), or None
        ``None`` when there are no arcs or no candidates (no circle to grow).
    radius : float
        Its distance to the arcs, metres; ``0.0`` with ``centre=None``.

    Raises
    ------
    ValueError
        For a ``spacing`` or ``tol`` that is not positive and finite, more
        than ``MAX_REFINEMENTS`` rounds, or too many candidates.

    Examples
    --------
    >>> from twolink import arms
    >>> axis = np.linspace(-22.0, 22.0, 45)  # 1 m apart
    >>> grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    >>> inside = grid[is_reachable(arms.ten, grid)]
    >>> centre, radius = largest_circle_on_grid(boundary_arcs(arms.ten), inside, 1.0, 1e-3)
    >>> round(radius, 3), round(float(10 - 5 * np.sqrt(2)), 3)  # the largest: 10 - 5 sqrt 2
    (2.929, 2.929)
    >>> bool(clearance(arms.ten, centre) >= radius - 1e-12)
    True
    >>> largest_circle_on_grid([], inside, 1.0, 1e-3)
    (None, 0.0)
    >>> largest_circle_on_grid(boundary_arcs(arms.ten), inside, 1.0, 1e-20)
    Traceback (most recent call last):
    ...
    ValueError: tol = 1e-20 m needs 41 refinement rounds from spacing = 1 m; at most MAX_REFINEMENTS = 30 (spacing / tol up to 3**31)
    """
    _require_arcs(arcs)
    points: NDArray[np.float64] = as_pairs(candidates, "candidates").reshape(-1, 2)
    if len(points) > MAX_SAMPLES:
        raise ValueError(
            f"{len(points)} candidates; largest_circle_on_grid takes at most MAX_SAMPLES = {MAX_SAMPLES}"
        )
    spacing = as_finite_scalar(spacing, "spacing (m)", minimum=0.0, strictly=True)
    tol = as_finite_scalar(tol, "tol (m)", minimum=0.0, strictly=True)
    steps: list[float] = []
    step = spacing / 3.0
    while step > tol and len(steps) <= MAX_REFINEMENTS:
        steps.append(step)
        step /= 3.0
    if len(steps) > MAX_REFINEMENTS:
        needed = int(np.ceil(np.log(spacing / tol) / np.log(3.0))) - 1
        raise ValueError(
            f"tol = {tol:g} m needs {needed} refinement rounds from spacing = {spacing:g} m; at most "
            f"MAX_REFINEMENTS = {MAX_REFINEMENTS} (spacing / tol up to 3**{MAX_REFINEMENTS + 1})"
        )
    if not arcs or len(points) == 0:
        return None, 0.0

    arrays = _arc_arrays(arcs)  # once; then one numpy call per round
    room = _nearest_arc_distance(points, arrays)
    best = int(np.argmax(room))
    centre, radius = points[best].copy(), float(room[best])
    for step in steps:  # at most MAX_REFINEMENTS rounds of 49 points
        near = centre + step * _REFINE_PATTERN
        near = near[np.hypot(*(near - centre).T) < radius]
        if len(near):
            room = _nearest_arc_distance(near, arrays)
            if room.max() > radius:
                best = int(np.argmax(room))
                centre, radius = near[best], float(room[best])
    return centre, radius


def circle_points(
    centre: ArrayLike, radius: float, n: int, start_angle: float = 0.0
) -> NDArray[np.float64]:
    """``n`` equally spaced points on a circle, counter-clockwise from ``start_angle``.

    The last point is one step before the first (no repeated point).

    Parameters
    ----------
    centre : pair of float
        Centre, metres.
    radius : float
        Radius (> 0), metres.
    n : int
        Number of points (>= 1).
    start_angle : float
        Angle of the first point about the centre, radians.

    Returns
    -------
    numpy.ndarray, shape (n, 2)

    Examples
    --------
    >>> circle_points([12.5, 12.5], 2.0, 4).round(12)
    array([[14.5, 12.5],
           [12.5, 14.5],
           [10.5, 12.5],
           [12.5, 10.5]])
    """
    centre_xy: NDArray[np.float64] = as_pairs(centre, "centre")
    if centre_xy.shape != (2,):
        raise ValueError(f"centre must be one (x, y) pair; got shape {centre_xy.shape}")
    radius = as_length(radius, "radius (m)")
    # reduced exactly first: added to a large start angle the steps would round away
    start_angle = float(wrap_angle(as_finite_scalar(start_angle, "start_angle (rad)")))
    n = as_count(n, "n (points)", minimum=1, maximum=MAX_SAMPLES)
    angle = start_angle + _TWO_PI * np.arange(n) / n
    return centre_xy + radius * np.c_[np.cos(angle), np.sin(angle)]
