"""Cartesian paths with a time law, and the joint motions that follow them.

A path says where the tip should be at each instant: :class:`LinePath` (a
straight segment) and :class:`CirclePath`, both run through a time law
(:func:`time_scaling`: constant speed, or cubic / quintic polynomials that
start and stop smoothly).  Two ways turn a path into joint angles:

- :func:`ik_trajectory`: closed-form IK at every sample, on one elbow branch
  for the whole path (no branch flips mid-path) with the angles kept
  continuous (no 2 pi jumps) and within the joint limits;
- :func:`resolved_rate_trajectory`: integrate the joint rates
  ``qd = J^-1 (v_ref + gain (p_ref - p))`` (Whitney's resolved-rate control),
  using :func:`twolink.velocity.joint_rates` or its damped variant.

A path that leaves the workspace raises :class:`twolink.UnreachableError`
naming the first sample out of reach, never a NaN.

Examples
--------
>>> from twolink import arms, trajectory
>>> line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
>>> motion = trajectory.ik_trajectory(arms.two_metre, line, n=50)
>>> motion.q.shape, bool(motion.tracking_error.max() < 1e-12)
((50, 2), True)
"""

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from ._validate import as_count, as_finite_scalar, as_pairs, real_array, require_arm
from .errors import SimulationError, SingularityError, UnreachableError
from .simulate import DEFAULT_MAX_EVALUATIONS
from .kinematics import fk
from .velocity import joint_rates, joint_rates_dls
from .workspace import LIMIT_TOL, describe_limits, require_reachable, solutions_within_limits

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


def time_scaling(t, duration, law="quintic", with_acceleration=False):
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
    duration = as_finite_scalar(duration, "duration (s)", minimum=0.0, strictly=True)
    if law not in TIME_LAWS:
        raise ValueError(f"law must be one of {TIME_LAWS}; got {law!r}")
    t = real_array(t, "t (s)")
    if not np.all(np.isfinite(t)):
        raise ValueError("t must be finite times in seconds")
    tau = np.clip(t / duration, 0.0, 1.0)
    inside = (t >= 0.0) & (t <= duration)
    if law == "linear":
        s, ds, dds = tau, np.ones_like(tau), np.zeros_like(tau)
    elif law == "cubic":
        s, ds, dds = tau * tau * (3.0 - 2.0 * tau), 6.0 * tau * (1.0 - tau), 6.0 - 12.0 * tau
    else:
        s = tau**3 * (10.0 - 15.0 * tau + 6.0 * tau * tau)
        ds = 30.0 * tau * tau * (1.0 - tau) ** 2
        dds = 60.0 * tau * (1.0 - tau) * (1.0 - 2.0 * tau)
    s_dot = np.where(inside, ds / duration, 0.0)
    if not with_acceleration:
        return s, s_dot
    return s, s_dot, np.where(inside, dds / duration**2, 0.0)


def _point(value, name):
    point = as_pairs(value, name)
    if point.shape != (2,):
        raise ValueError(f"{name} must be one (x, y) pair in metres; got shape {point.shape}")
    return point


def _sample_times(duration, n):
    n = as_count(n, "n (samples, both ends included)", minimum=2, maximum=MAX_SAMPLES)
    return np.linspace(0.0, duration, n)


#: Most samples a path may be cut into (memory budget: a few arrays of n x 2 floats, ~100 MB).
MAX_SAMPLES = 10_000_000


@dataclass(frozen=True)
class LinePath:
    """The straight segment from ``p_start`` to ``p_end``, travelled in ``duration`` seconds.

    Parameters
    ----------
    p_start, p_end : pair of float
        End points, metres.
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
    """

    p_start: tuple
    p_end: tuple
    duration: float
    law: str = "quintic"

    def __post_init__(self):
        object.__setattr__(self, "p_start", tuple(_point(self.p_start, "p_start")))
        object.__setattr__(self, "p_end", tuple(_point(self.p_end, "p_end")))
        object.__setattr__(
            self, "duration", as_finite_scalar(self.duration, "duration (s)", minimum=0.0, strictly=True)
        )
        time_scaling(0.0, self.duration, self.law)  # checks the law's name

    @property
    def length(self):
        """Length of the segment, metres."""
        return float(np.hypot(self.p_end[0] - self.p_start[0], self.p_end[1] - self.p_start[1]))

    def at(self, t):
        """Tip position and velocity at times ``t``: two arrays of shape ``t.shape + (2,)``."""
        s, s_dot = time_scaling(t, self.duration, self.law)
        start, chord = np.asarray(self.p_start), np.subtract(self.p_end, self.p_start)
        return start + np.multiply.outer(s, chord), np.multiply.outer(s_dot, chord)

    def sample(self, n=50):
        """``n`` evenly spaced instants over ``[0, duration]`` (both ends): ``(t, p, v)``."""
        t = _sample_times(self.duration, n)
        return (t, *self.at(t))


@dataclass(frozen=True)
class CirclePath:
    """``turns`` times round a circle, counter-clockwise from ``start_angle``, in ``duration`` seconds.

    Parameters
    ----------
    centre : pair of float
        Centre, metres.
    radius : float
        Radius (> 0), metres.
    duration : float
        Seconds (> 0).
    law : {"linear", "cubic", "quintic"}
        Time law (:func:`time_scaling`).
    start_angle : float
        Angle of the first point about the centre, radians.
    turns : float
        How far round (negative: clockwise); 1 is a closed circle.

    Examples
    --------
    >>> circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="linear")
    >>> p, v = circle.at(1.0)   # a quarter of the way round
    >>> p.round(12), (v * 2 / np.pi).round(12)
    (array([12.5, 14.5]), array([-1.,  0.]))
    """

    centre: tuple
    radius: float
    duration: float
    law: str = "quintic"
    start_angle: float = 0.0
    turns: float = 1.0

    def __post_init__(self):
        object.__setattr__(self, "centre", tuple(_point(self.centre, "centre")))
        object.__setattr__(self, "radius", as_finite_scalar(self.radius, "radius (m)", minimum=0.0, strictly=True))
        object.__setattr__(
            self, "duration", as_finite_scalar(self.duration, "duration (s)", minimum=0.0, strictly=True)
        )
        object.__setattr__(self, "start_angle", as_finite_scalar(self.start_angle, "start_angle (rad)"))
        turns = as_finite_scalar(self.turns, "turns")
        if turns == 0.0:
            raise ValueError("turns must be non-zero (1 is once round, counter-clockwise)")
        object.__setattr__(self, "turns", turns)
        time_scaling(0.0, self.duration, self.law)

    @property
    def length(self):
        """Length of the path, metres."""
        return float(2.0 * np.pi * self.radius * abs(self.turns))

    def at(self, t):
        """Tip position and velocity at times ``t``: two arrays of shape ``t.shape + (2,)``."""
        s, s_dot = time_scaling(t, self.duration, self.law)
        sweep = 2.0 * np.pi * self.turns
        angle = self.start_angle + sweep * s
        direction = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
        tangent = np.stack([-np.sin(angle), np.cos(angle)], axis=-1)
        p = np.asarray(self.centre) + self.radius * direction
        return p, (self.radius * sweep * s_dot)[..., None] * tangent

    def sample(self, n=50):
        """``n`` evenly spaced instants over ``[0, duration]`` (both ends): ``(t, p, v)``."""
        t = _sample_times(self.duration, n)
        return (t, *self.at(t))


@dataclass(frozen=True)
class JointTrajectory:
    """A joint motion that follows a Cartesian path, sampled at ``len(t)`` instants.

    Attributes
    ----------
    arm : TwoLinkArm
    t : numpy.ndarray, shape (n,)
        Times in seconds.
    q : numpy.ndarray, shape (n, 2)
        Joint angles in radians (continuous: no 2 pi jumps).
    qd : numpy.ndarray, shape (n, 2)
        Joint rates in rad/s.
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

    arm: object
    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    p_ref: np.ndarray
    elbow: str
    method: str
    branch_switches: tuple = ()

    @property
    def p_tip(self):
        """Where the tip actually is, ``fk(q)``, metres."""
        return fk(self.arm, self.q)

    @property
    def tracking_error(self):
        """``|p_tip - p_ref|`` per sample, metres."""
        return np.hypot(*(self.p_tip - self.p_ref).T)

    @property
    def joint_steps(self):
        """Largest joint change between consecutive samples, ``max_j |q[k+1, j] - q[k, j]|``, shape (n - 1,)."""
        return np.max(np.abs(np.diff(self.q, axis=0)), axis=-1)

    @property
    def within_limits(self):
        """Whether each sample respects the arm's joint limits, shape (n,)."""
        return self.arm.within_limits(self.q, tol=LIMIT_TOL)


def _path_samples(path, n):
    """``(t, p, v)`` from a path object, or from an (m, 2) array of points (then ``t`` counts samples)."""
    if hasattr(path, "sample"):
        return path.sample(n)
    points = as_pairs(path, "path")
    if points.ndim != 2 or len(points) < 2:
        raise ValueError(f"a path of points must have shape (m, 2) with m >= 2; got {points.shape}")
    t = np.arange(len(points), dtype=float)
    return t, points, np.gradient(points, t, axis=0)


def _choose_branch(arm, points, valid, elbow):
    """The one branch used for the whole path, or a clear error."""
    if elbow not in _BRANCHES + ("auto",):
        raise ValueError(f"elbow must be 'down', 'up' or 'auto'; got {elbow!r}")
    valid_everywhere = np.all(valid, axis=0)
    wanted = _BRANCHES if elbow == "auto" else (elbow,)
    for name in wanted:
        if valid_everywhere[_BRANCHES.index(name)]:
            return _BRANCHES.index(name)
    leaves = []
    for name in wanted:
        first = int(np.flatnonzero(~valid[:, _BRANCHES.index(name)])[0])
        x, y = points[first]
        leaves.append(f"elbow {name} leaves them at path point {first} ({x:.6g}, {y:.6g})")
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


def _continuous(q_branch):
    """Unwrap each joint along the path (no 2 pi jumps), keeping the first sample as it is."""
    return np.unwrap(q_branch, axis=0)


#: Largest joint change (rad) accepted between two consecutive samples of
#: :func:`ik_trajectory`: a larger one is a jump (no continuous joint path
#: joins the samples, or they are too far apart to tell).
JUMP_TOL = np.pi / 2

#: ``|sin q2|`` below which the two elbow branches meet (a stretched or folded
#: pose) and :func:`ik_trajectory` may switch from one to the other.
BRANCH_MEET_TOL = 1e-6


def _nearest_turn(angles, reference):
    """``angles`` shifted by multiples of 2 pi (per joint) to lie nearest ``reference``."""
    return angles - 2.0 * np.pi * np.round((angles - reference) / (2.0 * np.pi))


#: A path point closer to the base than this fraction of ``l1 + l2`` counts as the
#: base itself (on an equal-link arm, where ``q1`` is free there): a sample
#: meant to be the base often misses it by round-off, in an arbitrary direction.
BASE_ROUNDOFF = 1e-12


def _switching_path(arm, points, q_both, valid, start_branch):
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
        at_base = r_min == 0.0 and not np.hypot(*points[k]) > BASE_ROUNDOFF * (arm.l1 + arm.l2)
        if at_base:  # every q1 puts the tip there: keep the previous one
            candidates[:, 0] = q[k - 1, 0]
        steps = np.max(np.abs(candidates - q[k - 1]), axis=-1)
        steps = np.where(valid[k], steps, np.inf)
        meet = abs(np.sin(q[k - 1, 1])) <= BRANCH_MEET_TOL or abs(np.sin(candidates[branch, 1])) <= BRANCH_MEET_TOL
        # switch at a singular pose when the other branch is nearer, or between two samples that
        # straddle one (staying would jump, the other branch is a small step away)
        if (meet and steps[1 - branch] < steps[branch]) or (steps[branch] > JUMP_TOL >= steps[1 - branch]):
            branch = 1 - branch
        q[k] = candidates[branch]
        branches[k] = branch
    if not np.all(valid[np.arange(count), branches]):
        return None
    return q, branches


def _first_jump(q):
    steps = np.max(np.abs(np.diff(q, axis=0)), axis=-1)
    jumps = np.flatnonzero(steps > JUMP_TOL)
    return (int(jumps[0]), float(steps[jumps[0]])) if jumps.size else None


#: Below this ``|sin q2|`` :func:`ik_trajectory` takes finite-difference joint
#: rates instead of ``J^-1 v`` (whose size grows as ``1 / |sin q2|``).
RATE_SINGULARITY_TOL = 1e-3


def ik_trajectory(arm, path, n=50, elbow="auto"):
    """Joint angles along a path from the closed form, on one elbow branch throughout.

    Each sample is solved in closed form (:func:`twolink.workspace.solutions_within_limits`,
    both branches), then one branch is kept for every sample, so the elbow never
    flips mid-path, and the angles are unwrapped so they never jump by ``2 pi``.
    Where one branch is not continuous (a line through the base of an
    equal-link arm: ``q1`` would jump by ``pi``) or not within the limits,
    the branch changes where the two branches meet (a singular pose,
    ``q2`` passing ``0`` or ``+-pi``) if that gives a continuous path;
    ``branch_switches`` lists those samples.  No joint ever changes by more
    than ``JUMP_TOL`` between two samples: otherwise the error names them.
    Joint rates are exact, ``J^-1 v`` from the path's own velocity, for a
    path object; for a list of points, and at samples within
    ``RATE_SINGULARITY_TOL`` of a singular circle (where ``J^-1 v`` blows up),
    they are finite differences of the angles (second order,
    :func:`numpy.gradient`).

    Parameters
    ----------
    arm : TwoLinkArm
    path : LinePath, CirclePath or array_like of shape (m, 2)
        A path object (sampled ``n`` times over its duration), or points in
        order (then ``t`` is the sample index and ``n`` is ignored).
    n : int
        Number of samples, both ends included (>= 2).
    elbow : {"auto", "down", "up"}
        The branch.  ``"auto"`` takes elbow down if it stays within the limits
        along the whole path, else elbow up.

    Returns
    -------
    JointTrajectory

    Raises
    ------
    twolink.UnreachableError
        If a sample is outside the workspace (the message names the first one:
        index, coordinates, distance, reach or limits), if no branch (single,
        or switching where the branches meet) stays within the limits along
        the path, or if no continuous joint path joins two samples (the
        message names them and the jump).

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
    twolink.errors.UnreachableError: path point 3 (of 5) at (15, 15) is 21.2132 m from the base, outside the reach [0, 20] m of this arm (l1=10, l2=10)
    """
    require_arm(arm)
    t, points, v_path = _path_samples(path, n)
    require_reachable(arm, points, what="path point")
    q_both, valid = solutions_within_limits(arm, points)
    switches = ()
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
            if branch is None:
                raise no_single_branch
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
    if arm.has_limits and not np.all(arm.within_limits(q, tol=LIMIT_TOL)):
        first = int(np.flatnonzero(~arm.within_limits(q, tol=LIMIT_TOL))[0])
        raise UnreachableError(
            f"the elbow-{_BRANCHES[branch]} branch cannot follow the path continuously within the joint limits "
            f"({describe_limits(arm)}): it would have to wrap round by 360 deg at path point {first}"
        )
    qd = np.gradient(q, t, axis=0, edge_order=2) if len(t) > 2 else np.gradient(q, t, axis=0)
    if hasattr(path, "sample"):
        regular = np.abs(np.sin(q[:, 1])) > RATE_SINGULARITY_TOL
        if np.any(regular):
            qd[regular] = joint_rates(arm, q[regular], v_path[regular])
    return JointTrajectory(
        arm=arm, t=t, q=q, qd=qd, p_ref=points, elbow=_BRANCHES[branch], method="closed form",
        branch_switches=switches,
    )


def resolved_rate_trajectory(
    arm, path, n=50, q_start=None, elbow="auto", gain=10.0, damping=0.0, rtol=1e-8, method=None,
    max_evaluations=DEFAULT_MAX_EVALUATIONS,
):
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
        Needs ``at(t)`` for the reference position and velocity at any time.
    n : int
        Output samples over ``[0, duration]`` (>= 2).
    q_start : array_like, shape (2,), optional
        Start configuration, radians; default: the closed form at the path's
        start on the branch :func:`ik_trajectory` would choose.
    elbow : {"auto", "down", "up"}
        Branch for the default start.
    gain : float
        Position feedback gain, 1/s (>= 0).
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

    Returns
    -------
    JointTrajectory
        ``qd`` holds the commanded rates at the samples.

    Raises
    ------
    twolink.UnreachableError
        If the sampled path leaves the workspace (checked before integrating).
    twolink.SingularityError
        If the exact inverse meets a singularity (the message gives the time).
    twolink.SimulationError
        If the integration fails or uses up ``max_evaluations``.

    Examples
    --------
    >>> from twolink import arms
    >>> line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    >>> motion = resolved_rate_trajectory(arms.two_metre, line, n=50)
    >>> bool(motion.tracking_error.max() < 1e-6)
    True
    """
    require_arm(arm)
    if not hasattr(path, "at"):
        raise ValueError("resolved_rate_trajectory needs a path object with at(t) (LinePath or CirclePath)")
    gain = as_finite_scalar(gain, "gain (1/s)", minimum=0.0)
    damping = as_finite_scalar(damping, "damping (m/rad)", minimum=0.0)
    rtol = as_finite_scalar(rtol, "rtol", minimum=0.0, strictly=True)
    max_evaluations = as_count(max_evaluations, "max_evaluations", minimum=1)
    t, points, _ = path.sample(n)
    start_branch = elbow
    if q_start is None:
        start = ik_trajectory(arm, points, elbow=elbow)
        q_start, start_branch = start.q[0], start.elbow
    else:
        require_reachable(arm, points, what="path point")
        q_start = as_pairs(q_start, "q_start")
        if q_start.shape != (2,):
            raise ValueError(f"q_start must be one configuration of shape (2,); got {q_start.shape}")
        start_branch = "down" if np.sin(q_start[1]) >= 0.0 else "up"

    def rates(time, q):
        p_ref, v_ref = path.at(time)
        v_command = v_ref + gain * (p_ref - fk(arm, q))
        if damping > 0.0:
            return joint_rates_dls(arm, q, v_command, damping)
        try:
            return joint_rates(arm, q, v_command)
        except SingularityError as exc:
            raise SingularityError(f"resolved rate met a singularity at t = {time:.6g} s: {exc}") from exc

    if method is None:
        method = "LSODA" if gain * (t[-1] - t[0]) / 3.3 > 1e4 else "RK45"
    evaluations = 0

    def budgeted_rates(time, q):
        nonlocal evaluations
        evaluations += 1
        if evaluations > max_evaluations:
            raise SimulationError(
                f"resolved rate used up its budget of max_evaluations = {max_evaluations} at t = {time:.6g} s "
                f"(method {method!r}, gain {gain:.3g} 1/s): "
                + ("pass method='LSODA' or 'Radau' (the feedback is stiff)" if method in ("RK23", "RK45", "DOP853") else "loosen rtol or lower the gain")
            )
        return rates(time, q)

    solution = solve_ivp(budgeted_rates, (t[0], t[-1]), q_start, t_eval=t, rtol=rtol, atol=rtol * 1e-2, method=method)
    if not solution.success:
        raise SimulationError(f"resolved rate: the integration failed at t = {solution.t[-1]:.6g} s: {solution.message}")
    q = solution.y.T
    qd = np.array([rates(time, q_now) for time, q_now in zip(t, q)])
    return JointTrajectory(arm=arm, t=t, q=q, qd=qd, p_ref=points, elbow=start_branch, method="resolved rate")
