"""Cartesian paths with a time law, and the joint motions that follow them.

A path says where the tip should be at each instant: :class:`LinePath` (a
straight segment) and :class:`CirclePath`, both run through a time law
(:func:`time_scaling`: constant speed, or cubic / quintic polynomials that
start and stop smoothly).  ``path.at(t)`` gives the tip's position and
velocity at times ``t`` (and, with ``with_acceleration=True``, its
acceleration).  Two ways turn a path into joint angles:

- :func:`ik_trajectory`: closed-form IK at every sample, on one elbow branch
  for the whole path (no branch flips mid-path) with the angles kept
  continuous (no 2 pi jumps) and within the joint limits; the joint rates
  and accelerations are exact, ``qd = J^-1 v`` and ``qdd = J^-1 (a - Jdot qd)``;
- :func:`resolved_rate_trajectory`: integrate the joint rates
  ``qd = J^-1 (v_ref + gain (p_ref - p))`` (Whitney's resolved-rate control),
  using :func:`twolink.velocity.joint_rates` or its damped variant.

Both give a :class:`JointTrajectory` (times, angles, rates, accelerations),
which becomes a controller's reference with
:meth:`JointTrajectory.joint_reference` (no refitting: the interpolant
matches ``q``, ``qd`` and ``qdd`` at every sample).  A path that leaves the
workspace raises :class:`twolink.UnreachableError` naming the first sample
out of reach, never a NaN.

Examples
--------
>>> from twolink import arms, trajectory
>>> line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
>>> motion = trajectory.ik_trajectory(arms.two_metre, line, n=50)
>>> motion.q.shape, motion.qdd.shape, bool(motion.tracking_error().max() < 1e-12)
((50, 2), (50, 2), True)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._integration import EXPLICIT_METHODS, integrate, solver_options
from ._validate import (
    as_configuration,
    as_count,
    as_finite_scalar,
    as_flag,
    as_length,
    as_pairs,
    as_time_span,
    finite_result,
    real_array,
    require_arm,
)
from ._values import Value, freeze
from .budgets import (
    DEFAULT_MAX_EVALUATIONS,
    DEFAULT_MAX_WALL_TIME,
    MAX_SAMPLES,
    EvaluationBudget,
)
from .conventions import check_elbow, wrap_angle
from .errors import InputTypeError, SingularityError, UnreachableError
from .ik import LIMIT_TOL, solutions_within_limits
from .kinematics import (
    fk,
    jacobian,
    jacobian_rate,
    require_nonsingular,
    require_within_reach,
)
from .references import JointReference
from .velocity import joint_rates, joint_rates_dls
from .workspace import describe_limits, require_reachable

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "TIME_LAWS",
    "time_scaling",
    "LinePath",
    "CirclePath",
    "JointTrajectory",
    "ik_trajectory",
    "resolved_rate_trajectory",
]

#: The time laws :func:`time_scaling` knows.
TIME_LAWS = ("linear", "cubic", "quintic")

_BRANCHES = ("down", "up")

#: Why ``elbow="both"`` means nothing for a trajectory (see :func:`twolink.conventions.check_elbow`).
_ONE_BRANCH = (
    "a path follows one branch at a time: trace it once with 'down' and once with 'up'"
)

# what time_scaling, at and sample return: two, three or four float arrays
_Array = NDArray[np.float64]
_Two = tuple[NDArray[np.float64], NDArray[np.float64]]
_Three = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]
_Four = tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]
]


@overload
def time_scaling(
    t: ArrayLike,
    duration: float,
    law: str = ...,
    with_acceleration: Literal[False] = ...,
) -> _Two: ...
@overload
def time_scaling(
    t: ArrayLike, duration: float, law: str, with_acceleration: Literal[True]
) -> _Three: ...
@overload
def time_scaling(
    t: ArrayLike, duration: float, law: str = ..., *, with_acceleration: Literal[True]
) -> _Three: ...
@overload
def time_scaling(
    t: ArrayLike, duration: float, law: str = ..., with_acceleration: bool = ...
) -> _Two | _Three: ...
def time_scaling(
    t: ArrayLike, duration: float, law: str = "quintic", with_acceleration: bool = False
) -> _Two | _Three:
    """Progress ``s(t)`` from 0 to 1 over ``[0, duration]``, its rate ``ds/dt`` and (optionally) ``d2s/dt2``.

    With ``tau = t / duration`` (clipped to [0, 1]):

    - ``"linear"``: ``s = tau``, constant speed (the speed jumps at both ends);
    - ``"cubic"``: ``s = 3 tau^2 - 2 tau^3``, zero speed at both ends;
    - ``"quintic"``: ``s = 10 tau^3 - 15 tau^4 + 6 tau^5``, zero speed and
      zero acceleration at both ends.

    Parameters
    ----------
    t : array_like
        Times in seconds.
    duration : float
        Seconds (> 0).
    law : {"linear", "cubic", "quintic"}
    with_acceleration : bool
        Also return ``s_ddot`` (what inverse dynamics needs).

    Returns
    -------
    s, s_dot[, s_ddot] : numpy.ndarray
        Same shape as ``t``; ``s_dot`` in 1/s and ``s_ddot`` in 1/s^2 (0
        outside the interval; the linear law's acceleration is 0 inside and
        impulsive at the ends, which this cannot represent).

    Examples
    --------
    >>> s, s_dot = time_scaling([0.0, 1.0, 2.0], 2.0, "cubic")
    >>> s, s_dot
    (array([0. , 0.5, 1. ]), array([0.  , 0.75, 0.  ]))
    >>> time_scaling([0.5, 1.0], 2.0, "quintic", with_acceleration=True)[2]
    array([1.40625, 0.     ])
    """
    duration = as_time_span(duration, "duration (s)")
    _check_law(law)
    with_acceleration = as_flag(with_acceleration, "with_acceleration")
    times = real_array(t, "t (s)")
    if not np.all(np.isfinite(times)):
        raise ValueError("t must be finite times in seconds")
    tau = np.clip(times / duration, 0.0, 1.0)
    inside = (times >= 0.0) & (times <= duration)
    if law == "linear":
        s, ds, dds = tau, np.ones_like(tau), np.zeros_like(tau)
    elif law == "cubic":
        s, ds, dds = (
            tau * tau * (3.0 - 2.0 * tau),
            6.0 * tau * (1.0 - tau),
            6.0 - 12.0 * tau,
        )
    else:
        s = tau**3 * (10.0 - 15.0 * tau + 6.0 * tau * tau)
        ds = 30.0 * tau * tau * (1.0 - tau) ** 2
        dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)
    s_dot = np.where(inside, ds / duration, 0.0)
    if not with_acceleration:
        return s, s_dot
    return s, s_dot, np.where(inside, dds / duration**2, 0.0)


def _check_law(law: object) -> str:
    """``law`` if it is one of :data:`TIME_LAWS`, else an error naming it and them."""
    if not isinstance(law, str) or law not in TIME_LAWS:
        raise ValueError(f"law must be one of {TIME_LAWS}; got {law!r}")
    return law


def _point(value: ArrayLike, name: str) -> _Array:
    return as_configuration(value, name, what="one (x, y) point", unit="metres")


#: Largest ``gain * duration`` of :func:`resolved_rate_trajectory`: the tracking error
#: decays as ``exp(-gain t)``, at round-off within ``1e-9 duration`` already.
MAX_FEEDBACK = 1e9

#: Most turns of a :class:`CirclePath` either way: at ``2 pi 1e6`` rad float64 still
#: places the angle to about 1e-9 rad, so a point on the circle to 1e-9 of the radius.
MAX_TURNS = 1e6


def _sample_times(duration: float, n: int) -> _Array:
    n = as_count(n, "n (samples, both ends included)", minimum=2, maximum=MAX_SAMPLES)
    return np.linspace(0.0, duration, n)


class _TimedPath:
    """What :class:`LinePath` and :class:`CirclePath` share: ``at`` and ``sample``."""

    duration: float

    def _at(self, t: ArrayLike) -> _Three:
        raise NotImplementedError

    @overload
    def at(self, t: ArrayLike, with_acceleration: Literal[False] = ...) -> _Two: ...
    @overload
    def at(self, t: ArrayLike, with_acceleration: Literal[True]) -> _Three: ...
    @overload
    def at(self, t: ArrayLike, with_acceleration: bool = ...) -> _Two | _Three: ...
    def at(self, t: ArrayLike, with_acceleration: bool = False) -> _Two | _Three:
        """Tip position (m), velocity (m/s) and, optionally, acceleration (m/s^2) at times ``t`` (s).

        Parameters
        ----------
        t : array_like
            Times in seconds; before 0 the path waits at its start, after
            ``duration`` at its end (zero velocity and acceleration there).
        with_acceleration : bool
            Also return the acceleration (as :func:`time_scaling` does).

        Returns
        -------
        p, v[, a] : numpy.ndarray, each of shape ``t.shape + (2,)``
        """
        with_acceleration = as_flag(with_acceleration, "with_acceleration")
        p, v, a = self._at(t)
        return (p, v, a) if with_acceleration else (p, v)

    @overload
    def sample(
        self, n: int = ..., with_acceleration: Literal[False] = ...
    ) -> _Three: ...
    @overload
    def sample(self, n: int, with_acceleration: Literal[True]) -> _Four: ...
    @overload
    def sample(self, n: int = ..., *, with_acceleration: Literal[True]) -> _Four: ...
    @overload
    def sample(self, n: int = ..., with_acceleration: bool = ...) -> _Three | _Four: ...
    def sample(self, n: int = 50, with_acceleration: bool = False) -> _Three | _Four:
        """``n`` evenly spaced instants over ``[0, duration]`` (both ends): ``(t, p, v)`` or ``(t, p, v, a)``.

        Shapes ``(n,)`` for ``t`` (s) and ``(n, 2)`` for ``p`` (m), ``v`` (m/s)
        and ``a`` (m/s^2, with ``with_acceleration=True``).
        """
        with_acceleration = as_flag(with_acceleration, "with_acceleration")
        t = _sample_times(self.duration, n)
        p, v, a = self._at(t)
        return (t, p, v, a) if with_acceleration else (t, p, v)


@dataclass(frozen=True, init=False)
class LinePath(_TimedPath):
    """The straight segment from ``p_start`` to ``p_end``, travelled in ``duration`` seconds.

    Parameters
    ----------
    p_start, p_end : array_like, shape (2,)
        End points, metres (stored as tuples of floats).
    duration : float
        Seconds (> 0).
    law : {"linear", "cubic", "quintic"}
        Time law (:func:`time_scaling`).

    Examples
    --------
    >>> line = LinePath([0.0, 0.0], [3.0, 4.0], duration=2.0, law="linear")
    >>> line.length
    5.0
    >>> p, v = line.at(1.0)
    >>> p, v
    (array([1.5, 2. ]), array([1.5, 2. ]))
    >>> line.at(1.0, with_acceleration=True)[2]    # constant speed: no acceleration
    array([0., 0.])
    """

    p_start: tuple[float, float]
    p_end: tuple[float, float]
    duration: float
    law: str

    def __init__(
        self,
        p_start: ArrayLike,
        p_end: ArrayLike,
        duration: float,
        law: str = "quintic",
    ) -> None:
        object.__setattr__(self, "p_start", tuple(_point(p_start, "p_start").tolist()))
        object.__setattr__(self, "p_end", tuple(_point(p_end, "p_end").tolist()))
        object.__setattr__(
            self,
            "duration",
            as_time_span(duration, "duration (s)"),
        )
        object.__setattr__(self, "law", law)
        time_scaling(0.0, self.duration, self.law)  # checks the law's name

    @property
    def length(self) -> float:
        """Length of the segment, metres."""
        return float(
            np.hypot(self.p_end[0] - self.p_start[0], self.p_end[1] - self.p_start[1])
        )

    def _at(self, t: ArrayLike) -> _Three:
        s, s_dot, s_ddot = time_scaling(
            t, self.duration, self.law, with_acceleration=True
        )
        with np.errstate(
            over="ignore", invalid="ignore"
        ):  # _finite_motion names an overflow
            start, chord = (
                np.asarray(self.p_start),
                np.subtract(self.p_end, self.p_start),
            )
            p, v, a = (
                start + np.multiply.outer(s, chord),
                np.multiply.outer(s_dot, chord),
                np.multiply.outer(s_ddot, chord),
            )
        return _finite_motion(self, p, v, a)


@dataclass(frozen=True, init=False)
class CirclePath(_TimedPath):
    """``turns`` times round a circle, counter-clockwise from ``start_angle``, in ``duration`` seconds.

    Parameters
    ----------
    centre : array_like, shape (2,)
        Centre, metres (stored as a tuple of floats).
    radius : float
        Radius (> 0), metres.
    duration : float
        Seconds (> 0).
    law : {"linear", "cubic", "quintic"}
        Time law (:func:`time_scaling`).
    start_angle : float
        Angle of the first point about the centre, radians.
    turns : float
        How far round (negative: clockwise); 1 is a closed circle.  Non-zero,
        at most ``MAX_TURNS`` = 1e6 round either way (beyond that the angle
        ``2 pi turns`` is too large for float64 to place a point on the
        circle to better than 1e-9 of its radius).

    Raises
    ------
    ValueError
        For a centre that is not one finite point, a radius or duration
        that is not finite and positive, an unknown law, or a ``turns``
        that is zero, not finite or beyond ``MAX_TURNS``.

    Examples
    --------
    >>> circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="linear")
    >>> p, v, a = circle.at(1.0, with_acceleration=True)   # a quarter of the way round
    >>> p.round(12), (v * 2 / np.pi).round(12)
    (array([12.5, 14.5]), array([-1.,  0.]))
    >>> speed = 2 * np.pi * circle.radius / circle.duration     # constant: pi m/s
    >>> (a * circle.radius / speed**2).round(12) + 0.0          # centripetal, speed^2 / r towards the centre
    array([ 0., -1.])
    """

    centre: tuple[float, float]
    radius: float
    duration: float
    law: str
    start_angle: float
    turns: float

    def __init__(
        self,
        centre: ArrayLike,
        radius: float,
        duration: float,
        law: str = "quintic",
        start_angle: float = 0.0,
        turns: float = 1.0,
    ) -> None:
        object.__setattr__(self, "centre", tuple(_point(centre, "centre").tolist()))
        object.__setattr__(
            self,
            "radius",
            as_length(radius, "radius (m)"),
        )
        object.__setattr__(
            self,
            "duration",
            as_time_span(duration, "duration (s)"),
        )
        object.__setattr__(self, "law", law)
        object.__setattr__(
            self, "start_angle", as_finite_scalar(start_angle, "start_angle (rad)")
        )
        turns = as_finite_scalar(turns, "turns")
        if turns == 0.0 or abs(turns) > MAX_TURNS:
            raise ValueError(
                f"turns must be non-zero and at most {MAX_TURNS:.0e} round either way (1 is once round, "
                f"counter-clockwise); got {turns:.6g}"
            )
        object.__setattr__(self, "turns", turns)
        time_scaling(0.0, self.duration, self.law)

    @property
    def length(self) -> float:
        """Length of the path, metres."""
        return float(2.0 * np.pi * self.radius * abs(self.turns))

    def _at(self, t: ArrayLike) -> _Three:
        s, s_dot, s_ddot = time_scaling(
            t, self.duration, self.law, with_acceleration=True
        )
        with np.errstate(
            over="ignore", invalid="ignore"
        ):  # _finite_motion names an overflow
            sweep = 2.0 * np.pi * self.turns
            # the start reduced exactly first: added to a large start the sweep would round away
            angle = wrap_angle(self.start_angle) + sweep * s
            rate, angular_acceleration = sweep * s_dot, sweep * s_ddot  # rad/s, rad/s^2
            direction = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
            tangent = np.stack([-np.sin(angle), np.cos(angle)], axis=-1)
            p = np.asarray(self.centre) + self.radius * direction
            v = (self.radius * rate)[..., None] * tangent
            # tangential r theta'' along the tangent, centripetal r theta'^2 towards the centre
            a = (self.radius * angular_acceleration)[..., None] * tangent
            a -= (self.radius * rate * rate)[..., None] * direction
        return _finite_motion(self, p, v, a)


def _finite_motion(path: _TimedPath, p: _Array, v: _Array, a: _Array) -> _Three:
    """``(p, v, a)`` of a path if all are finite, else an error saying which overflows float64."""
    for values, what in (
        (p, "positions (m)"),
        (v, "velocities (m/s)"),
        (a, "accelerations (m/s^2)"),
    ):
        finite_result(
            values, f"path's {what}", f"{path!r} is too large or too fast for float64"
        )
    return p, v, a


#: What :func:`ik_trajectory` follows: a timed path, or points in order.
Path = LinePath | CirclePath


@dataclass(frozen=True, eq=False)
class JointTrajectory(Value):
    """A joint motion that follows a Cartesian path, sampled at ``len(t)`` instants.

    Attributes
    ----------
    arm : TwoLinkArm
    t : numpy.ndarray, shape (n,)
        Times in seconds (for a path given as points: the sample index).
    q : numpy.ndarray, shape (n, 2)
        Joint angles in radians (continuous: no 2 pi jumps).
    qd : numpy.ndarray, shape (n, 2)
        Joint rates in rad/s.
    qdd : numpy.ndarray, shape (n, 2)
        Joint accelerations in rad/s^2.
    p_ref : numpy.ndarray, shape (n, 2)
        Where the path wants the tip, metres.
    elbow : str
        ``"down"`` or ``"up"``: the branch followed (at the start, for resolved rate).
    method : str
        ``"closed form"`` or ``"resolved rate"``.
    branch_switches : tuple of int
        Samples at which the elbow branch changes, where the path passes a
        singular point (through the base of an equal-link arm the only
        continuous joint path switches branch there, ``q2`` passing
        through ``+-pi``); empty for a path on one branch.
    """

    arm: TwoLinkArm
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    qd: NDArray[np.float64]
    qdd: NDArray[np.float64]
    p_ref: NDArray[np.float64]
    elbow: str
    method: str
    branch_switches: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        freeze(self)

    @property
    def p_tip(self) -> NDArray[np.float64]:
        """Where the tip actually is, ``fk(q)``: shape (n, 2), metres."""
        return fk(self.arm, self.q)

    def tracking_error(
        self, path: Path | JointTrajectory | ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """Distance of the tip from where ``path`` wants it, ``|p_tip - p_path|`` per sample: shape (n,), metres.

        The same method as :meth:`twolink.SimulationResult.tracking_error`.

        Parameters
        ----------
        path : LinePath, CirclePath, JointTrajectory or array_like, optional
            What the tip should follow, read by :func:`path_positions` at
            this trajectory's times ``t``.  ``None`` (default): this
            trajectory's own path, ``p_ref``.

        Examples
        --------
        >>> from twolink import arms
        >>> line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
        >>> motion = ik_trajectory(arms.two_metre, line, n=20)
        >>> bool(motion.tracking_error().max() < 1e-12), bool(motion.tracking_error(line).max() < 1e-12)
        (True, True)
        >>> float(motion.tracking_error([-1.0, 3.5])[0].round(6))   # from the line's end, at the start
        3.535534
        """
        wanted = self.p_ref if path is None else path_positions(path, self.t)
        difference = self.p_tip - wanted
        return np.hypot(difference[:, 0], difference[:, 1])

    @property
    def joint_steps(self) -> NDArray[np.float64]:
        """Largest joint change between consecutive samples, ``max_j |q[k+1, j] - q[k, j]|``: shape (n - 1,), rad."""
        return np.max(np.abs(np.diff(self.q, axis=0)), axis=-1)

    @property
    def within_limits(self) -> NDArray[np.bool_]:
        """Whether each sample respects the arm's joint limits, shape (n,)."""
        return np.asarray(self.arm.within_limits(self.q, tol=LIMIT_TOL), dtype=bool)

    def joint_reference(self) -> JointReference:
        """This motion as a controller's reference, matching ``q``, ``qd`` and ``qdd`` at every sample.

        The piecewise quintic Hermite interpolant of the samples
        (:meth:`twolink.references.JointReference.from_derivatives`, scipy's
        ``BPoly.from_derivatives``): on each interval the one quintic with
        the samples' angles, rates and accelerations at both ends (no fit,
        no spline refitted through ``q`` alone), so the reference
        reproduces the samples (the angles exactly, the rates and
        accelerations to round-off) and has continuous rate and
        acceleration.  Between samples it
        differs from the path's exact joint motion by ``O(h^6)`` in the
        interval ``h``.  Outside ``[t[0], t[-1]]`` it holds the end position
        at rest (zero rate and acceleration), like
        :meth:`twolink.references.JointReference.from_samples`.

        Returns
        -------
        twolink.references.JointReference
            For :class:`~twolink.controllers.JointPD` or
            :class:`~twolink.controllers.ComputedTorque` (``reference=``).

        Examples
        --------
        >>> from twolink import arms
        >>> motion = ik_trajectory(arms.two_metre, LinePath([3.0, -1.0], [3.0, 1.0], duration=2.0), n=21)
        >>> q_ref, qd_ref, qdd_ref = motion.joint_reference()(motion.t[5])
        >>> bool(np.all(q_ref == motion.q[5]))
        True
        >>> bool(np.allclose(qd_ref, motion.qd[5], rtol=0.0, atol=1e-12) and np.allclose(qdd_ref, motion.qdd[5], rtol=0.0, atol=1e-12))
        True
        """
        return JointReference.from_derivatives(self.t, self.q, self.qd, self.qdd)


def path_positions(
    path: Path | JointTrajectory | ArrayLike, t: ArrayLike
) -> NDArray[np.float64]:
    """Where ``path`` wants the tip at the times ``t``: shape ``(len(t), 2)``, metres.

    What :meth:`JointTrajectory.tracking_error` and
    :meth:`twolink.SimulationResult.tracking_error` compare the tip with.

    Parameters
    ----------
    path : LinePath, CirclePath, JointTrajectory or array_like
        - a path object (anything with ``at(t)``): its position at each
          time (before its start and after its end it waits at its ends);
        - a :class:`JointTrajectory`: its ``p_ref``; ``t`` must be its own
          sample times (simulate with ``t_eval=trajectory.t``, or pass the
          path object, which has a position at every time);
        - points: shape ``(len(t), 2)``, one per time, or ``(2,)``, the
          same point at every time (a fixed target).
    t : array_like, shape (n,)
        Times in seconds.

    Raises
    ------
    ValueError
        For times that are not a 1-D array of finite numbers, points of
        another shape, or a trajectory sampled at other times.
    twolink.InputTypeError
        For anything else.

    Examples
    --------
    >>> line = LinePath([0.0, 0.0], [2.0, 0.0], duration=1.0, law="linear")
    >>> path_positions(line, [0.0, 0.5, 3.0])
    array([[0., 0.],
           [1., 0.],
           [2., 0.]])
    >>> path_positions([1.0, 2.0], [0.0, 1.0])
    array([[1., 2.],
           [1., 2.]])
    """
    times = real_array(t, "t (s)")
    if times.ndim != 1 or not np.all(np.isfinite(times)):
        raise ValueError(
            f"t must be a 1-D array of finite times (s); got shape {times.shape}"
        )
    if isinstance(path, JointTrajectory):
        same = path.t.shape == times.shape and bool(
            np.allclose(
                path.t,
                times,
                rtol=0.0,
                atol=1e-12 * max(1.0, float(np.max(np.abs(times), initial=0.0))),
            )
        )
        if not same:
            span = f"[{times[0]:.6g}, {times[-1]:.6g}] s" if times.size else "no time"
            raise ValueError(
                f"the trajectory is sampled at {len(path.t)} times over [{path.t[0]:.6g}, {path.t[-1]:.6g}] s, "
                f"not at these {times.size} times over {span}: simulate with t_eval=trajectory.t, or pass the "
                "path object (LinePath, CirclePath), which has a position at every time"
            )
        return np.array(path.p_ref, dtype=float)
    at = getattr(path, "at", None)
    if callable(at):
        return np.asarray(at(times)[0], dtype=float)
    try:
        points = as_pairs(path, "path points (m)")
    except InputTypeError:
        raise InputTypeError(
            "path must be a LinePath or CirclePath, a JointTrajectory, or points of shape (n, 2) or (2,) in "
            f"metres; got {type(path).__name__}"
        ) from None
    if points.shape == (2,):
        return np.broadcast_to(points, (times.size, 2)).copy()
    if points.shape != (times.size, 2):
        raise ValueError(
            f"path points must have shape ({times.size}, 2), one (x, y) per time, or (2,), one fixed point; "
            f"got shape {points.shape}"
        )
    return np.array(points, dtype=float)


def _path_samples(
    path: Path | ArrayLike, n: int
) -> tuple[_Array, _Array, _Array, _Array, bool]:
    """``(t, p, v, a, timed)`` from a path object, or from an (m, 2) array of points (then ``t`` counts samples)."""
    sample = getattr(path, "sample", None)
    if callable(sample):
        t, p, v, a = sample(n, with_acceleration=True)
        return t, p, v, a, True
    points = as_pairs(path, "path")
    if points.ndim != 2 or len(points) < 2:
        raise ValueError(
            f"a path of points must have shape (m, 2) with m >= 2; got {points.shape}"
        )
    t = np.arange(len(points), dtype=float)
    v = np.gradient(points, t, axis=0)
    return t, points, v, np.gradient(v, t, axis=0), False


def _choose_branch(
    arm: TwoLinkArm, points: _Array, valid: NDArray[np.bool_], elbow: str
) -> int:
    """The one branch used for the whole path, or a clear error."""
    valid_everywhere = np.all(valid, axis=0)
    wanted = _BRANCHES if elbow == "auto" else (elbow,)
    for name in wanted:
        if valid_everywhere[_BRANCHES.index(name)]:
            return _BRANCHES.index(name)
    leaves = []
    for name in wanted:
        first = int(np.flatnonzero(~valid[:, _BRANCHES.index(name)])[0])
        x, y = points[first]
        leaves.append(
            f"elbow {name} leaves them at path point {first} ({x:.6g}, {y:.6g})"
        )
    advice = (
        "every point is reachable, but not on one branch: split the path, or let it pass through a "
        "stretched or folded (singular) pose where the branches meet"
        if elbow == "auto"
        else "try elbow='auto' or the other branch"
    )
    raise UnreachableError(
        f"no elbow branch stays within the joint limits ({describe_limits(arm)}) along the whole path: "
        f"{'; '.join(leaves)}; {advice}"
    )


def _continuous(q_branch: _Array) -> _Array:
    """Unwrap each joint along the path (no 2 pi jumps), keeping the first sample as it is."""
    return np.unwrap(q_branch, axis=0)


#: Largest joint change (rad) accepted between two consecutive samples of
#: :func:`ik_trajectory`: a larger one is a jump (no continuous joint path
#: joins the samples, or they are too far apart to tell).
JUMP_TOL = np.pi / 2

#: ``|sin q2|`` below which the two elbow branches meet (a stretched or folded
#: pose) and :func:`ik_trajectory` may switch from one to the other.
BRANCH_MEET_TOL = 1e-6


def _nearest_turn(angles: _Array, reference: _Array) -> _Array:
    """``angles`` shifted by multiples of 2 pi (per joint) to lie nearest ``reference``."""
    return angles - 2.0 * np.pi * np.round((angles - reference) / (2.0 * np.pi))


#: A path point closer to the base than this fraction of ``l1 + l2`` counts as the
#: base itself (on an equal-link arm, where ``q1`` is free there): a sample
#: meant to be the base often misses it by round-off, in an arbitrary direction.
BASE_ROUNDOFF = 1e-12


def _switching_path(
    arm: TwoLinkArm,
    points: _Array,
    q_both: _Array,
    valid: NDArray[np.bool_],
    start_branch: int,
) -> tuple[_Array, NDArray[np.int_]] | None:
    """A continuous joint path that may change branch where the branches meet, or None.

    At each sample the branch stays the same unless the pose is singular
    (``|sin q2| <= BRANCH_MEET_TOL``), where the other branch is taken when
    it is the nearer one, or unless staying would jump by more than
    ``JUMP_TOL`` while the other branch is a smaller step (the samples
    straddle a singular pose); at the base of an equal-link arm (where ``q1`` is
    free) ``q1`` is kept from the previous sample.
    """
    count = len(points)
    q = np.empty((count, 2))
    branches = np.empty(count, dtype=int)
    branch = start_branch
    q[0] = q_both[0, branch]
    branches[0] = branch
    r_min = arm.reach[0]
    for k in range(1, count):
        candidates = _nearest_turn(q_both[k], q[k - 1])
        # within round-off of the base the point's direction (and so q1) means nothing
        at_base = r_min == 0.0 and not np.hypot(*points[k]) > BASE_ROUNDOFF * (
            arm.l1 + arm.l2
        )
        if at_base:  # every q1 puts the tip there: keep the previous one
            candidates[:, 0] = q[k - 1, 0]
        steps = np.max(np.abs(candidates - q[k - 1]), axis=-1)
        steps = np.where(valid[k], steps, np.inf)
        meet = (
            abs(np.sin(q[k - 1, 1])) <= BRANCH_MEET_TOL
            or abs(np.sin(candidates[branch, 1])) <= BRANCH_MEET_TOL
        )
        # switch at a singular pose when the other branch is nearer, or between two samples that
        # straddle one (staying would jump, the other branch is a small step away)
        if (meet and steps[1 - branch] < steps[branch]) or (
            steps[branch] > JUMP_TOL >= steps[1 - branch]
        ):
            branch = 1 - branch
        q[k] = candidates[branch]
        branches[k] = branch
    if not np.all(valid[np.arange(count), branches]):
        return None
    return q, branches


def _first_jump(q: _Array) -> tuple[int, float] | None:
    steps = np.max(np.abs(np.diff(q, axis=0)), axis=-1)
    jumps = np.flatnonzero(steps > JUMP_TOL)
    return (int(jumps[0]), float(steps[jumps[0]])) if jumps.size else None


def _times(matrix: _Array, vector: _Array) -> _Array:
    """``A x`` over leading axes."""
    return np.einsum("...ij,...j->...i", matrix, vector)


def _transposed_times(matrix: _Array, vector: _Array) -> _Array:
    """``A^T x`` over leading axes."""
    return np.einsum("...ji,...j->...i", matrix, vector)


#: Below this ``|sin q2|`` :func:`ik_trajectory` takes finite-difference joint
#: rates and accelerations instead of ``J^-1 v`` and ``J^-1 (a - Jdot qd)``
#: (whose sizes grow as ``1 / |sin q2|`` and faster).
RATE_SINGULARITY_TOL = 1e-3


def _finite_differences(values: _Array, t: _Array) -> _Array:
    """``d values / dt`` by :func:`numpy.gradient` (second order, also at the ends when there are 3 samples)."""
    return (
        np.gradient(values, t, axis=0, edge_order=2)
        if len(t) > 2
        else np.gradient(values, t, axis=0)
    )


def ik_trajectory(
    arm: TwoLinkArm, path: Path | ArrayLike, n: int = 50, elbow: str = "auto"
) -> JointTrajectory:
    """Joint angles along a path from the closed form, on one elbow branch throughout.

    Each sample is solved in closed form (:func:`twolink.ik.solutions_within_limits`,
    both branches), then one branch is kept for every sample, so the elbow never
    flips mid-path, and the angles are unwrapped so they never jump by ``2 pi``.
    Where one branch is not continuous (a line through the base of an
    equal-link arm: ``q1`` would jump by ``pi``) or not within the limits,
    the branch changes where the two branches meet (a singular pose,
    ``q2`` passing ``0`` or ``+-pi``) if that gives a continuous path;
    ``branch_switches`` lists those samples.  No joint ever changes by more
    than ``JUMP_TOL`` between two samples: otherwise the error names them.

    Joint rates and accelerations are exact for a path object, from the
    path's own velocity ``v`` and acceleration ``a``: ``qd = J^-1 v`` and
    ``qdd = J^-1 (a - Jdot qd)`` (differentiating ``v = J qd``).  For a list
    of points, and at samples within ``RATE_SINGULARITY_TOL`` of a singular
    pose (where ``J^-1`` blows up), they are finite differences, of the
    angles and then of the rates (second order, :func:`numpy.gradient`).

    Parameters
    ----------
    arm : TwoLinkArm
    path : LinePath, CirclePath or array_like of shape (m, 2)
        A path object (sampled ``n`` times over its duration), or points in
        order (then ``t`` is the sample index and ``n`` is ignored).
    n : int
        Number of samples, both ends included (>= 2).
    elbow : {"auto", "down", "up"}
        The branch (:data:`twolink.conventions.ELBOW_WORDS`: ``"down"`` is
        ``q2 >= 0``).  ``"auto"`` takes elbow down if it stays within the
        limits along the whole path, else elbow up.  ``"both"`` is refused:
        a path follows one branch at a time (trace it twice instead).

    Returns
    -------
    JointTrajectory
        ``t`` (s), ``q`` (rad), ``qd`` (rad/s) and ``qdd`` (rad/s^2) at the
        samples, shapes (n,) and (n, 2).

    Raises
    ------
    twolink.UnreachableError
        If a sample is outside the reach (the message of
        :func:`twolink.kinematics.require_within_reach`: the first point,
        its distance, the reach) or the joint limits (the message of
        :func:`twolink.workspace.require_reachable`), if no branch (single,
        or switching where the branches meet) stays within the limits along
        the path, or if no continuous joint path joins two samples (the
        message names them and the jump).
    ValueError
        For an ``elbow`` outside ``("down", "up", "auto")``.

    Examples
    --------
    >>> from twolink import arms
    >>> circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="linear")
    >>> motion = ik_trajectory(arms.ten, circle, n=20)
    >>> motion.elbow, bool(np.all(motion.within_limits)), bool(motion.joint_steps.max() < 0.2)
    ('down', True, True)
    >>> ik_trajectory(arms.ten, LinePath([12.0, 12.0], [16.0, 16.0], duration=1.0, law="linear"), n=5)
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: path point (15, 15) (index (3,), first of 2) is 21.2132 m from the base; this arm reaches distances in [0, 20] m (l1=10, l2=10)
    """
    require_arm(arm)
    elbow = check_elbow(elbow, ("down", "up", "auto"), why=_ONE_BRANCH)
    t, points, v_path, a_path, timed = _path_samples(path, n)
    require_within_reach(arm, points, what="path point")
    require_reachable(arm, points, what="path point")  # the joint limits
    q_both, valid = solutions_within_limits(arm, points)
    switches: tuple[int, ...] = ()
    branch: int | None
    q: NDArray[np.float64] | None
    jump: tuple[int, float] | None
    no_single_branch: UnreachableError | None = None
    try:
        branch = _choose_branch(arm, points, valid, elbow)
        q = _continuous(q_both[:, branch, :])
        jump = _first_jump(q)
    except UnreachableError as exc:
        branch, q, jump, no_single_branch = None, None, None, exc
    if branch is None or jump is not None:
        # one branch throughout is not continuous (or not within limits): switch where the branches meet
        starts = [_BRANCHES.index(elbow)] if elbow in _BRANCHES else [0, 1]
        found = None
        for start in starts:
            if not valid[0, start]:
                continue
            candidate = _switching_path(arm, points, q_both, valid, start)
            if candidate is not None and _first_jump(candidate[0]) is None:
                found = (start, *candidate)
                break
        if found is None:
            if no_single_branch is not None:
                raise no_single_branch
            assert jump is not None and branch is not None
            k, size = jump
            raise UnreachableError(
                f"no continuous joint path follows the path: between path points {k} and {k + 1} "
                f"({points[k][0]:.6g}, {points[k][1]:.6g}) -> ({points[k + 1][0]:.6g}, {points[k + 1][1]:.6g}) "
                f"the joints would jump by {np.degrees(size):.4g} deg (more than JUMP_TOL = "
                f"{np.degrees(JUMP_TOL):.4g} deg) on the elbow-{_BRANCHES[branch]} branch, and switching branch "
                "where the branches meet does not help: sample the path more finely or keep it away from "
                "the singular points"
            )
        branch, q, branches = found
        switches = tuple(int(k) for k in np.flatnonzero(np.diff(branches)) + 1)
    assert q is not None and branch is not None
    if arm.has_limits and not np.all(arm.within_limits(q, tol=LIMIT_TOL)):
        first = int(np.flatnonzero(~arm.within_limits(q, tol=LIMIT_TOL))[0])
        raise UnreachableError(
            f"the elbow-{_BRANCHES[branch]} branch cannot follow the path continuously within the joint limits "
            f"({describe_limits(arm)}): it would have to wrap round by 360 deg at path point {first}"
        )
    qd = _finite_differences(q, t)
    regular = (
        np.abs(np.sin(q[:, 1])) > RATE_SINGULARITY_TOL
        if timed
        else np.zeros(len(t), dtype=bool)
    )
    if np.any(regular):
        qd[regular] = joint_rates(arm, q[regular], v_path[regular])
    qdd = _finite_differences(qd, t)
    if np.any(regular):
        # differentiating v = J qd: a = J qdd + Jdot qd
        centripetal = _times(jacobian_rate(arm, q[regular], qd[regular]), qd[regular])
        qdd[regular] = joint_rates(arm, q[regular], a_path[regular] - centripetal)
    return JointTrajectory(
        arm=arm,
        t=t,
        q=q,
        qd=qd,
        qdd=qdd,
        p_ref=points,
        elbow=_BRANCHES[branch],
        method="closed form",
        branch_switches=switches,
    )


def resolved_rate_trajectory(
    arm: TwoLinkArm,
    path: Path,
    n: int = 50,
    q0: ArrayLike | None = None,
    elbow: str = "auto",
    gain: float = 10.0,
    damping: float = 0.0,
    rtol: float = 1e-8,
    method: str | None = None,
    max_evaluations: int = DEFAULT_MAX_EVALUATIONS,
    max_wall_time: float = DEFAULT_MAX_WALL_TIME,
) -> JointTrajectory:
    """Follow a path by resolved-rate control: integrate ``qd = J^-1 (v_ref + gain (p_ref - fk(q)))``.

    The joint rates come from :func:`twolink.velocity.joint_rates` (exact
    inverse) or, with ``damping > 0``, :func:`twolink.velocity.joint_rates_dls`;
    the motion is integrated with :func:`scipy.integrate.solve_ivp` and
    sampled at ``n`` instants.  The position feedback ``gain`` pulls the tip
    back to the path; without it (``gain=0``) integration errors accumulate.

    Parameters
    ----------
    arm : TwoLinkArm
    path : LinePath or CirclePath
        Needs ``at(t)`` for the reference position, velocity and acceleration at any time.
    n : int
        Output samples over ``[0, duration]`` (>= 2).
    q0 : array_like, shape (2,), optional
        Start configuration, radians; default: the closed form at the path's
        start on the branch :func:`ik_trajectory` would choose.
    elbow : {"auto", "down", "up"}
        Branch of the default start (as in :func:`ik_trajectory`; ``"both"``
        is refused).  With ``q0`` given, ``"down"`` or ``"up"`` must be
        ``q0``'s own branch.
    gain : float
        Position feedback gain, 1/s (>= 0), with ``gain * duration`` at most
        ``MAX_FEEDBACK`` = 1e9: the tracking error decays as
        ``exp(-gain t)``, so a larger gain only makes the integration
        stiffer (the error is at round-off within a billionth of the path's
        duration already).
    damping : float
        Damped-least-squares damping, m/rad (>= 0); 0 uses the exact inverse.
    rtol : float
        Relative tolerance of the integrator.
    method : str, optional
        ``solve_ivp``'s method.  ``None`` chooses: ``"RK45"``, or the
        stiffness-switching ``"LSODA"`` when the feedback is stiff (the tracking error
        decays at the rate ``gain``, so an explicit method would need about
        ``gain * duration`` steps; above 1e4 of them LSODA is used).
    max_evaluations : int
        Budget of rate evaluations (default 1e6); when it runs out a
        :class:`twolink.SimulationError` says where and what to change.
    max_wall_time : float
        Budget of wall-clock seconds (default ``DEFAULT_MAX_WALL_TIME`` = 30),
        with the same error.

    Returns
    -------
    JointTrajectory
        ``qd`` (rad/s) holds the commanded rates at the samples and ``qdd``
        (rad/s^2) their exact time derivative along the motion (from the
        path's acceleration, differentiating the rate law; no finite
        differences).

    Raises
    ------
    twolink.UnreachableError
        If the sampled path leaves the workspace (checked before integrating).
    twolink.SingularityError
        If the exact inverse meets a singularity (the message gives the time).
    twolink.SimulationError
        If the integration fails or uses up ``max_evaluations`` or ``max_wall_time``.
    ValueError
        For bad arguments (a ``gain`` beyond ``MAX_FEEDBACK / duration``
        among them), or a ``q0`` on the other branch than ``elbow``.

    Examples
    --------
    >>> from twolink import arms
    >>> line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    >>> motion = resolved_rate_trajectory(arms.two_metre, line, n=50)
    >>> bool(motion.tracking_error().max() < 1e-6)
    True
    """
    require_arm(arm)
    if not callable(getattr(path, "at", None)):
        raise ValueError(
            "resolved_rate_trajectory needs a path object with at(t) (LinePath or CirclePath)"
        )
    elbow = check_elbow(elbow, ("down", "up", "auto"), why=_ONE_BRANCH)
    gain = as_finite_scalar(gain, "gain (1/s)", minimum=0.0)
    damping = as_finite_scalar(damping, "damping (m/rad)", minimum=0.0)
    rtol = as_finite_scalar(rtol, "rtol", minimum=0.0, strictly=True)
    budget = EvaluationBudget(max_evaluations, max_wall_time)
    t, points, v_ref, a_ref = path.sample(n, with_acceleration=True)
    duration = float(t[-1] - t[0])
    if gain * duration > MAX_FEEDBACK:
        raise ValueError(
            f"gain (1/s) times the path's duration must be at most MAX_FEEDBACK = {MAX_FEEDBACK:.0e}; got "
            f"gain = {gain:.3g} 1/s over {duration:.6g} s: the tracking error decays as exp(-gain t), so "
            f"a gain above {MAX_FEEDBACK / duration:.3g} 1/s only makes the integration stiff"
        )
    if q0 is None:
        start = ik_trajectory(arm, points, elbow=elbow)
        q_begin, start_branch = start.q[0], start.elbow
    else:
        require_within_reach(arm, points, what="path point")
        require_reachable(arm, points, what="path point")  # the joint limits
        q_begin = as_configuration(q0, "q0")
        start_branch = "down" if np.sin(q_begin[1]) >= 0.0 else "up"
        if elbow != "auto" and np.sin(q_begin[1]) != 0.0 and elbow != start_branch:
            raise ValueError(
                f"q0 = ({q_begin[0]:.6g}, {q_begin[1]:.6g}) rad is on the elbow-{start_branch} branch, but "
                f"elbow={elbow!r} was asked for: leave elbow='auto' to start from q0's branch"
            )

    def command(now: float, q: NDArray[np.float64]) -> NDArray[np.float64]:
        p_now, v_now = path.at(now)
        return v_now + gain * (p_now - fk(arm, q))

    def rates(now: float, q: NDArray[np.float64]) -> NDArray[np.float64]:
        v_command = command(now, q)
        if damping > 0.0:
            return joint_rates_dls(arm, q, v_command, damping)
        try:
            return joint_rates(arm, q, v_command)
        except SingularityError:
            pass
        try:  # the package's one singularity message, with the time
            require_nonsingular(arm, q, f"resolved rate at t = {now:.6g} s")
        except SingularityError as exc:
            raise SingularityError(
                f"{exc}; pass damping > 0 (damped least squares) to pass it"
            ) from None
        return joint_rates(
            arm, q, v_command
        )  # raises joint_rates' own error (its tolerance)

    if method is None:
        method = "LSODA" if gain * duration / 3.3 > 1e4 else "RK45"
    options = solver_options(
        {"method": method, "rtol": rtol, "atol": rtol * 1e-2},
        duration,
        budget.max_evaluations,
    )
    advice = (
        "pass method='LSODA' or 'Radau' (the feedback is stiff)"
        if method in EXPLICIT_METHODS
        else "loosen rtol or lower the gain"
    )

    def shifted(now: float, q: NDArray[np.float64]) -> NDArray[np.float64]:
        return rates(t[0] + now, q)  # the integration runs from 0 over the duration

    solution = integrate(
        shifted,
        duration,
        q_begin,
        t_eval=t - t[0],
        options=options,
        budget=budget,
        what=f"resolved rate (gain {gain:.3g} 1/s)",
        state_text=lambda q: f"q = ({q[0]:.6g}, {q[1]:.6g}) rad",
        advice=lambda stop: advice,
    )
    q = solution.y.T
    qd = np.array([rates(now, q_now) for now, q_now in zip(t, q)])
    qdd = _rate_derivative(arm, q, qd, points, v_ref, a_ref, gain, damping)
    return JointTrajectory(
        arm=arm,
        t=t,
        q=q,
        qd=qd,
        qdd=qdd,
        p_ref=points,
        elbow=start_branch,
        method="resolved rate",
    )


def _rate_derivative(
    arm: TwoLinkArm,
    q: _Array,
    qd: _Array,
    p_ref: _Array,
    v_ref: _Array,
    a_ref: _Array,
    gain: float,
    damping: float,
) -> _Array:
    """``d qd / dt`` of the resolved-rate law along the motion, exactly.

    The rates solve ``(J^T J + damping^2 I) qd = J^T v_c`` with the command
    ``v_c = v_ref + gain (p_ref - fk(q))``, whose derivative is
    ``a_ref + gain (v_ref - J qd)``.  Differentiating,
    ``(J^T J + damping^2 I) qdd = J^T (v_c' - Jdot qd) + Jdot^T (v_c - J qd)``;
    without damping that is ``J^-1 (v_c' - Jdot qd)``.
    """
    J = jacobian(arm, q)
    J_rate = jacobian_rate(arm, q, qd)
    v_tip = _times(J, qd)
    v_command = v_ref + gain * (p_ref - fk(arm, q))
    wanted = (
        a_ref + gain * (v_ref - v_tip) - _times(J_rate, qd)
    )  # J qdd should give this
    if damping == 0.0:
        return joint_rates(arm, q, wanted)
    # (J^T J + damping^2 I)^-1 = V diag(1 / (s^2 + damping^2)) V^T, with J = U diag(s) V^T
    _, singular_values, Vt = np.linalg.svd(J)
    residual_term = _times(Vt, _transposed_times(J_rate, v_command - v_tip)) / (
        singular_values**2 + damping**2
    )
    return joint_rates_dls(arm, q, wanted, damping) + _transposed_times(
        Vt, residual_term
    )
