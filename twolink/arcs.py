"""Circular arcs in the plane: the pieces the workspace boundary is made of.

With one joint angle held fixed (at a joint limit, or at a singular value such
as ``q2 = 0``) and the other swept, the tip of a 2R arm moves on a circle.
So the boundary of the reachable set is a union of circular arcs, and
distances to it can be computed exactly instead of from sampled points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validate import as_count, as_finite_scalar, as_pairs, real_array
from .conventions import wrap_angle
from .errors import InputTypeError
from .kinematics import LARGE_ANGLE

#: Most points :meth:`Arc.points` makes (memory budget: 1e7 x 2 floats, 160 MB).
MAX_POINTS = 10_000_000

__all__ = ["Arc"]

_TWO_PI = 2.0 * np.pi


def arc_distance(
    p: NDArray[np.float64],
    centre: ArrayLike,
    radius: ArrayLike,
    start: ArrayLike,
    sweep: ArrayLike,
    end_a: ArrayLike,
    end_b: ArrayLike,
) -> NDArray[np.float64]:
    """Distance from points ``p`` (..., 2) to arcs given by arrays, broadcast.

    The formula behind :meth:`Arc.distance` (and
    :func:`twolink.workspace.distance_to_arcs`, which passes many arcs at
    once): inside the arc's angular span (every angle for a full circle) the
    nearest point is the radial projection onto the circle, outside it the
    nearer end point.  A zero radius needs no case of its own: its ends are
    its centre; nor does a zero sweep: its span is its one point.  No checks: the callers check their inputs.

    Examples
    --------
    >>> ends = Arc((0.0, 0.0), 1.0, 0.0, np.pi / 2).end_points
    >>> arc_distance(np.array([[2.0, 0.0], [-1.0, -1.0]]), (0.0, 0.0), 1.0, 0.0, np.pi / 2, *ends).round(12)
    array([1.        , 2.23606798])
    """
    centre, radius, start, sweep, end_a, end_b = (
        np.asarray(value, dtype=float)
        for value in (centre, radius, start, sweep, end_a, end_b)
    )
    offset = p - centre
    from_centre = np.hypot(offset[..., 0], offset[..., 1])
    # the direction of travel: +1 for a zero sweep too (np.sign's 0 put every point on its span)
    direction = np.where(sweep < 0.0, -1.0, 1.0)
    along = np.mod(
        (np.arctan2(offset[..., 1], offset[..., 0]) - start) * direction, _TWO_PI
    )
    to_ends = np.minimum(
        np.hypot(*np.moveaxis(p - end_a, -1, 0)),
        np.hypot(*np.moveaxis(p - end_b, -1, 0)),
    )
    on_span = (along <= np.abs(sweep)) | (np.abs(sweep) >= _TWO_PI)
    return np.where(on_span, np.abs(from_centre - radius), to_ends)


#: The kinds of arc of a workspace's boundary (``""``: none said).
ARC_KINDS = ("", "joint limit", "singular", "reach")


@dataclass(frozen=True)
class Arc:
    """The arc ``centre + radius * (cos a, sin a)`` for ``a`` from ``start`` to ``start + sweep``.

    Parameters
    ----------
    centre : pair of float
        Centre of the circle, metres (any pair of real numbers, stored as a
        tuple of two floats).
    radius : float
        Radius (>= 0; 0 makes the arc a single point), metres.
    start : float
        Angle of the first end point about the centre, radians.
    sweep : float
        Signed angle swept, radians, ``|sweep| <= 2 pi`` (``2 pi``: a full circle).
    label : str
        What traces the arc, e.g. ``"q1 = 0 deg"``.
    kind : {"", "joint limit", "singular", "reach"}
        What kind of boundary it is (:data:`ARC_KINDS`; ``""``: none said).

    Examples
    --------
    >>> quarter = Arc((0.0, 0.0), 2.0, 0.0, np.pi / 2)
    >>> quarter.points(3).round(12)
    array([[2.        , 0.        ],
           [1.41421356, 1.41421356],
           [0.        , 2.        ]])
    >>> quarter.distance([[3.0, 0.0], [0.0, 0.0], [-2.0, -1.0]]).round(12)
    array([1.        , 2.        , 3.60555128])
    """

    centre: tuple[float, float]
    radius: float
    start: float
    sweep: float
    label: str = ""
    kind: str = ""

    def __post_init__(self) -> None:
        centre = as_pairs(self.centre, "centre")
        if centre.shape != (2,):
            raise ValueError(
                f"centre must be one (x, y) pair; got shape {centre.shape}"
            )
        object.__setattr__(self, "centre", (float(centre[0]), float(centre[1])))
        object.__setattr__(
            self, "radius", as_finite_scalar(self.radius, "radius (m)", minimum=0.0)
        )
        start = as_finite_scalar(self.start, "start (rad)")
        if (
            not -LARGE_ANGLE <= start <= LARGE_ANGLE
        ):  # reduced exactly: a sweep added to it would round away
            start = float(wrap_angle(start))
        object.__setattr__(self, "start", start)
        sweep = as_finite_scalar(self.sweep, "sweep (rad)")
        if abs(sweep) > _TWO_PI * (1.0 + 1e-12):
            raise ValueError(f"sweep must satisfy |sweep| <= 2 pi; got {sweep}")
        object.__setattr__(self, "sweep", sweep)
        if not isinstance(self.label, str):
            raise InputTypeError(f"label must be a string; got {self.label!r}")
        if not isinstance(self.kind, str) or self.kind not in ARC_KINDS:
            raise ValueError(f"kind must be one of {ARC_KINDS}; got {self.kind!r}")

    def point_at(self, fraction: ArrayLike) -> NDArray[np.float64]:
        """Points at ``fraction`` (0 = start, 1 = end) along the arc, shape ``(..., 2)``.

        Fractions are finite real numbers (outside ``[0, 1]`` they go on
        round the arc's circle); NaN and infinity are refused.

        Examples
        --------
        >>> Arc((0.0, 0.0), 1.0, 0.0, np.pi).point_at(0.5).round(12) + 0.0
        array([0., 1.])
        >>> Arc((0.0, 0.0), 1.0, 0.0, np.pi).point_at(float("nan"))
        Traceback (most recent call last):
        ...
        ValueError: fraction must be finite numbers (0 = start, 1 = end of the arc); entry () is nan
        """
        angle = self.start + self.sweep * _finite_fractions(fraction, "fraction")
        points = np.empty(angle.shape + (2,))
        points[..., 0] = self.centre[0] + self.radius * np.cos(angle)
        points[..., 1] = self.centre[1] + self.radius * np.sin(angle)
        return points

    def points(self, n: int = 100) -> NDArray[np.float64]:
        """``n`` equally spaced points from start to end (both included), shape ``(n, 2)``."""
        n = as_count(n, "n", minimum=2, maximum=MAX_POINTS)
        return self.point_at(np.linspace(0.0, 1.0, n))

    @property
    def end_points(self) -> NDArray[np.float64]:
        """The first and last point, shape ``(2, 2)``."""
        return self.point_at(np.array([0.0, 1.0]))

    def fraction_of(self, p: ArrayLike) -> NDArray[np.float64]:
        """Where points on the arc's circle lie along the arc: fractions in ``[0, 1]``.

        Points off the arc (outside its angular span) get ``-1``, and so does
        every point for a degenerate arc (radius or sweep 0), which has no
        inside to cut.

        Examples
        --------
        >>> Arc((0.0, 0.0), 1.0, 0.0, np.pi).fraction_of([[0.0, 1.0], [0.0, -1.0]])
        array([ 0.5, -1. ])
        """
        p = as_pairs(p, "p")
        angle = np.arctan2(p[..., 1] - self.centre[1], p[..., 0] - self.centre[0])
        span = abs(self.sweep)
        if span == 0.0 or self.radius == 0.0:
            return np.full(p.shape[:-1], -1.0)
        along = np.mod((angle - self.start) * np.sign(self.sweep), _TWO_PI)
        # within round-off of the start, seen from below (2 pi - tiny): that is the start
        along = np.where(along > _TWO_PI - 1e-12, 0.0, along)
        return np.where(
            along <= span * (1.0 + 1e-12), np.minimum(along / span, 1.0), -1.0
        )

    def distance(self, p: ArrayLike) -> NDArray[np.float64]:
        """Euclidean distance from points ``p`` (..., 2) to the arc, exactly.

        Inside the arc's angular span the nearest point is the radial
        projection onto the circle; outside it, the nearer end point.
        """
        ends = self.end_points
        return arc_distance(
            as_pairs(p, "p"),
            np.asarray(self.centre),
            self.radius,
            self.start,
            self.sweep,
            ends[0],
            ends[1],
        )

    def split(self, fractions: ArrayLike) -> list[Arc]:
        """Cut the arc at the given fractions into consecutive pieces.

        Fractions (a number or a flat list) lie in ``[0, 1]`` (0 = start, 1 = end), in any order;
        cuts at the ends or repeated (within 1e-9) cut nothing.  NaN,
        infinity and fractions outside ``[0, 1]`` are refused.

        Examples
        --------
        >>> pieces = Arc((0.0, 0.0), 1.0, 0.0, np.pi).split([0.5])
        >>> [round(piece.sweep / np.pi, 12) for piece in pieces]
        [0.5, 0.5]
        >>> Arc((0.0, 0.0), 1.0, 0.0, np.pi).split([float("nan")])
        Traceback (most recent call last):
        ...
        ValueError: fractions must be finite numbers (0 = start, 1 = end of the arc); entry (0,) is nan
        """
        cuts = _finite_fractions(fractions, "fractions")
        if cuts.ndim > 1:
            raise ValueError(
                f"fractions must be a number or a flat list of numbers; got shape {cuts.shape}"
            )
        cuts = cuts.ravel()
        if np.any((cuts < 0.0) | (cuts > 1.0)):
            outside = cuts[(cuts < 0.0) | (cuts > 1.0)][0]
            raise ValueError(
                f"fractions must lie in [0, 1] (0 = start, 1 = end of the arc); got {outside}"
            )
        cuts = np.unique(cuts)
        cuts = cuts[(cuts > 1e-9) & (cuts < 1.0 - 1e-9)]
        edges = np.concatenate([[0.0], cuts, [1.0]])
        return [
            Arc(
                self.centre,
                self.radius,
                self.start + self.sweep * low,
                self.sweep * (high - low),
                self.label,
                self.kind,
            )
            for low, high in zip(edges[:-1], edges[1:])
        ]


def _finite_fractions(values: ArrayLike, name: str) -> NDArray[np.float64]:
    """``values`` as a float array of finite fractions along an arc, or an error naming the first that is not."""
    fractions = real_array(values, name)
    if not np.all(np.isfinite(fractions)):
        bad = tuple(int(i) for i in np.argwhere(~np.isfinite(fractions))[0])
        raise ValueError(
            f"{name} must be finite numbers (0 = start, 1 = end of the arc); entry {bad} is {fractions[bad]}"
        )
    return fractions


def circle_intersections(
    centre_a: ArrayLike, radius_a: float, centre_b: ArrayLike, radius_b: float
) -> NDArray[np.float64]:
    """Intersection points of two circles, shape ``(k, 2)`` with k = 0, 1 or 2.

    Concentric circles give no points (identical circles included: the
    caller decides what overlapping arcs mean).

    Examples
    --------
    >>> circle_intersections((0.0, 0.0), 1.0, (1.0, 0.0), 1.0).round(12)
    array([[ 0.5      , -0.8660254],
           [ 0.5      ,  0.8660254]])
    >>> circle_intersections((0.0, 0.0), 1.0, (3.0, 0.0), 1.0).shape
    (0, 2)
    """
    centre_a = as_pairs(centre_a, "centre_a")
    centre_b = as_pairs(centre_b, "centre_b")
    radius_a = as_finite_scalar(radius_a, "radius_a (m)", minimum=0.0)
    radius_b = as_finite_scalar(radius_b, "radius_b (m)", minimum=0.0)
    between = centre_b - centre_a
    distance = float(np.hypot(*between))
    scale = max(radius_a, radius_b, distance, 1e-300)
    if distance <= 1e-14 * scale:
        return np.empty((0, 2))
    if (
        distance > radius_a + radius_b + 1e-12 * scale
        or distance < abs(radius_a - radius_b) - 1e-12 * scale
    ):
        return np.empty((0, 2))
    along = (radius_a**2 - radius_b**2 + distance**2) / (2.0 * distance)
    height = np.sqrt(max(radius_a**2 - along**2, 0.0))
    unit = between / distance
    normal = np.array([-unit[1], unit[0]])
    foot = centre_a + along * unit
    if height <= 1e-12 * scale:
        return foot[None, :]
    return np.array([foot - height * normal, foot + height * normal])
