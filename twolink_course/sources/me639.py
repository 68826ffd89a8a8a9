"""The ME 639 2R mini-project, reproduced: l1 = l2 = 2 m, absolute angles, motor 2 on the ground.

The project measures **both** link angles from the x-axis (``q1`` and
``q2_abs = q1 + q2``), as for a belt drive with motor 2 on the ground.  This
module reproduces its methods as the course's source record gives them
(``notebooks/source_record.ipynb``, items H4.1 to H4.6, each at the anchor
``#h4-1`` ... ``#h4-6``), so that the course (chapters 4-7) and the tests can
show its numbers coming out of its own formulas:

- :func:`source_ik`: its inverse kinematics, printed whole in each of its
  programs (``source_record.ipynb#h4-1``):
  ``theta = acos((x^2 + y^2 - l1^2 - l2^2) / (2 l1 l2))``,
  ``q1 = atan2(y, x) - atan2(l2 sin(theta), l1 + l2 cos(theta))``,
  ``q2_abs = q1 + theta``.  In the transcription three programs break the
  ``q1`` line after ``l1 + l2 * np.sin(theta)))`` with an orphan line
  ``np.cos(theta)))``; the spring program reads ``cos``.  That is almost
  certainly an artifact of the transcription: the author's code is the
  correct ``cos``, the default here.  ``reading="sin"`` computes the line as
  transcribed, to show what such a typo would do (a general lesson, never the
  project's mistake).
- :func:`source_wall_search`: its wall search, 100,000 points from (4, 0) to
  (0, 4), stopped at the first point whose rounded absolute link-2 angle equals
  ``round(pi/4, 4)``; with its torque formulas (``source_record.ipynb#h4-2``).
- :func:`source_spring_torques`: its spring, ``F = k (x, y)`` (anchored at the
  origin), torques in its own convention (``source_record.ipynb#h4-3``).
- :func:`correct_spring_torques_dh` and :func:`dh_to_motor_torques`: the correct
  law ``tau = J^T k (x0 - x)`` and the conversion to the source's convention.
- :func:`source_workspace_points`: the tips its workspace plot draws, both
  absolute angles over ``range(35, 145, 1)`` degrees (``source_record.ipynb#h4-5``).
  That is a plot range, not joint limits: the project states no joint limits
  anywhere, and its own wall, spring and line tasks use angles outside
  [35, 145] deg.  The course takes [35, 145] deg as example limits
  (``twolink.arms.two_metre_limited``), its own choice suggested by that plot
  range.  The project labels its torques "N" where N m belongs.

Its animations (``source_record.ipynb#h4-4``) draw both links at the forward
kinematics of the commanded angles, with a dashed trace of the planned points:
an IK error would show as the tip leaving the trace.  Its kinetic energy
(``source_record.ipynb#h4-6``) is right; chapter 5 shows it.

The package itself works in relative (DH) angles; convert the absolute angles
returned here with :func:`twolink.to_relative`.

Examples
--------
>>> import numpy as np
>>> import twolink
>>> q_abs = source_ik([3.0, 1.0])                   # the correct ("cos") reading
>>> q_dh = twolink.to_relative(q_abs)               # (q1, q2_abs - q1)
>>> twolink.TwoLinkArm(2.0, 2.0).fk(q_dh).round(12)
array([3., 1.])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from twolink._validate import as_finite_scalar, as_pairs
from twolink.arm import TwoLinkArm
from twolink.errors import UnreachableError

__all__ = [
    "READINGS",
    "source_ik",
    "source_fk",
    "source_link_torques",
    "WallSearchResult",
    "source_wall_search",
    "source_spring_torques",
    "correct_spring_torques_dh",
    "dh_to_motor_torques",
    "motor_to_dh_torques",
    "WORKSPACE_PLOT_DEGREES",
    "source_workspace_points",
]

#: The two readings of the transcribed IK line for q1 (``source_record.ipynb#h4-1``):
#: ``"cos"`` the author's code, ``"sin"`` the transcription's artifact read literally.
READINGS = ("sin", "cos")

_ACOS_SLACK = 1e-12  # rounding slack on the cosine at full stretch


def _check_reading(reading: str) -> None:
    if reading not in READINGS:
        raise ValueError(
            f"reading must be 'cos' (the author's code) or 'sin' (the transcription's "
            f"artifact, read literally); got {reading!r}"
        )


def source_ik(
    p_tip: ArrayLike, *, reading: str = "cos", l1: float = 2.0, l2: float = 2.0
) -> NDArray[np.float64]:
    """The source's inverse kinematics: absolute link angles ``(q1, q2_abs)`` for a tip point.

    As printed whole in each of its programs (``source_record.ipynb#h4-1``):
    the elbow angle (link 2 relative to link 1)
    ``theta = acos((x^2 + y^2 - l1^2 - l2^2) / (2 l1 l2))`` (``theta`` in
    ``[0, pi]``: one branch, the package's ``elbow="down"``), then
    ``q1 = atan2(y, x) - atan2(l2 sin(theta), l1 + l2 cos(theta))`` and
    ``q2_abs = q1 + theta``.  In the transcription the wall, trajectory and
    workspace programs break the ``q1`` line after ``l1 + l2 * np.sin(theta)))``
    and continue on an orphan line ``np.cos(theta)))``; the spring program
    reads ``cos``.  That is almost certainly an artifact of the transcription,
    so the author's code is the correct ``cos`` (the default).
    ``reading="sin"`` reads the transcribed line literally: what such a typo
    would do, a general lesson and never the project's mistake.

    Parameters
    ----------
    p_tip : array_like, shape (..., 2)
        Tip targets ``(x, y)``, metres.
    reading : {"cos", "sin"}
        ``"cos"``, the author's code; ``"sin"``, the transcription read literally.
    l1, l2 : float
        Link lengths, metres (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        Absolute angles ``(q1, q2_abs)`` in radians, both from the x-axis.
        Convert to the package's DH angles with :func:`twolink.to_relative`.

    Raises
    ------
    ValueError
        For NaN/inf or badly shaped targets, non-positive lengths or an unknown reading.
    twolink.UnreachableError
        For targets outside the annulus ``|l1 - l2| <= r <= l1 + l2`` (this
        reproduction's ``acos`` has no real angle there).

    Examples
    --------
    The reproduced IK at the spring task's rest point (3, 1), in degrees:

    >>> np.degrees(source_ik([3.0, 1.0])).round(2)
    array([-19.33,  56.2 ])

    Read literally, the transcription's ``sin`` moves link 1 (the elbow angle
    ``theta`` is the same), so the tip would miss:

    >>> q_sin = source_ik([3.4116, 0.5884], reading="sin")
    >>> source_fk(q_sin).round(3)
    array([3.345, 0.892])
    >>> source_ik([5.0, 0.0])
    Traceback (most recent call last):
    ...
    twolink.errors.UnreachableError: p_tip (5, 0) is 5 m from the base; the arm reaches from 0 to 4 m
    """
    _check_reading(reading)
    l1 = as_finite_scalar(l1, "l1", minimum=0.0, strictly=True)
    l2 = as_finite_scalar(l2, "l2", minimum=0.0, strictly=True)
    targets = as_pairs(p_tip, "p_tip")
    x, y = targets[..., 0], targets[..., 1]
    cos_theta = (x**2 + y**2 - l1**2 - l2**2) / (2.0 * l1 * l2)
    bad = np.abs(cos_theta) > 1.0 + _ACOS_SLACK
    if np.any(bad):
        p_bad = targets[bad] if targets.ndim > 1 else targets
        p_bad = np.atleast_2d(p_bad)[0]
        r = float(np.hypot(p_bad[0], p_bad[1]))
        raise UnreachableError(
            f"p_tip ({p_bad[0]:.6g}, {p_bad[1]:.6g}) is {r:.6g} m from the base; "
            f"the arm reaches from {abs(l1 - l2):.6g} to {l1 + l2:.6g} m"
        )
    theta = np.arccos(np.clip(cos_theta, -1.0, 1.0))
    second = np.sin(theta) if reading == "sin" else np.cos(theta)
    q1 = np.arctan2(y, x) - np.arctan2(l2 * np.sin(theta), l1 + l2 * second)
    return np.stack([q1, q1 + theta], axis=-1)


def source_fk(
    q_abs: ArrayLike, *, l1: float = 2.0, l2: float = 2.0
) -> NDArray[np.float64]:
    """Tip position from absolute link angles: ``(l1 cos q1 + l2 cos q2_abs, l1 sin q1 + l2 sin q2_abs)``.

    Where the arm's tip really is for the angles the source commanded.

    Parameters
    ----------
    q_abs : array_like, shape (..., 2)
        Absolute link angles, radians.
    l1, l2 : float
        Link lengths, metres (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        The tip ``(x, y)``, metres.

    Examples
    --------
    >>> source_fk([0.0, np.pi / 2]).round(12)
    array([2., 2.])
    """
    l1 = as_finite_scalar(l1, "l1", minimum=0.0, strictly=True)
    l2 = as_finite_scalar(l2, "l2", minimum=0.0, strictly=True)
    angles = as_pairs(q_abs, "q_abs")
    q1, q2 = angles[..., 0], angles[..., 1]
    return np.stack(
        [l1 * np.cos(q1) + l2 * np.cos(q2), l1 * np.sin(q1) + l2 * np.sin(q2)], axis=-1
    )


def source_link_torques(
    q_abs: ArrayLike, force_by_tip: ArrayLike, *, l1: float = 2.0, l2: float = 2.0
) -> NDArray[np.float64]:
    """The source's torque formulas: ``T_i = l_i (F_y cos q_i - F_x sin q_i)``, absolute angles.

    With ``F = force_by_tip``, the force the tip exerts, these are the motor
    torques of the absolute-angle model (motor 2 on the ground) that hold it,
    ``J_abs^T force_by_tip``.  They relate to the DH torques by
    ``T1 = tau1_DH - tau2_DH``, ``T2 = tau2_DH`` (:func:`dh_to_motor_torques`).

    Parameters
    ----------
    q_abs : array_like, shape (..., 2)
        Absolute link angles, radians.
    force_by_tip : array_like, shape (..., 2)
        The force the tip exerts ON the environment, newtons (the push into
        the wall in :func:`source_wall_search`; the source's spring force
        ``k (x, y)`` in :func:`source_spring_torques`).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``(T1, T2)`` in N m.

    Examples
    --------
    A force along link 2 gives ``T2 = 0``:

    >>> source_link_torques([0.0, np.pi / 4], [100.0, 100.0]).round(9)
    array([200.,   0.])
    """
    l1 = as_finite_scalar(l1, "l1", minimum=0.0, strictly=True)
    l2 = as_finite_scalar(l2, "l2", minimum=0.0, strictly=True)
    angles = as_pairs(q_abs, "q_abs")
    force = as_pairs(force_by_tip, "force_by_tip")
    fx, fy = force[..., 0], force[..., 1]
    t1 = l1 * (fy * np.cos(angles[..., 0]) - fx * np.sin(angles[..., 0]))
    t2 = l2 * (fy * np.cos(angles[..., 1]) - fx * np.sin(angles[..., 1]))
    return np.stack(np.broadcast_arrays(t1, t2), axis=-1)


@dataclass(frozen=True)
class WallSearchResult:
    """The first match of the source's wall search.

    Attributes
    ----------
    index : int
        Index of the first matching point among the ``n_points``.
    p_contact : numpy.ndarray, shape (2,)
        The wall point the search stopped at, metres.
    q_abs : numpy.ndarray, shape (2,)
        The reproduced IK's absolute angles for it, radians.
    torques : numpy.ndarray, shape (2,)
        ``(T1, T2)`` from :func:`source_link_torques`, N m.
    p_tip_fk : numpy.ndarray, shape (2,)
        Where the arm's tip really is for ``q_abs`` (forward kinematics), metres.
    """

    index: int
    p_contact: NDArray[np.float64]
    q_abs: NDArray[np.float64]
    torques: NDArray[np.float64]
    p_tip_fk: NDArray[np.float64]


def source_wall_search(
    *,
    reading: str = "cos",
    n_points: int = 100_000,
    force_magnitude: float = 500.0,
    l1: float = 2.0,
    l2: float = 2.0,
) -> WallSearchResult:
    """The source's wall search, vectorised: the first point with ``round(q2_abs, 4) == round(pi/4, 4)``.

    The source walks ``n_points`` equally spaced points from (4, 0) to (0, 4)
    (the wall ``x + y = 4``), solves its IK at each (here the reproduced
    :func:`source_ik`) and stops at
    the **first** one whose absolute link-2 angle, rounded to four decimals in
    radians, equals ``round(pi/4, 4) = 0.7854`` (link 2 perpendicular to the
    wall, to about +-0.003 deg).  The torques use the normal force
    ``N = force_magnitude (1, 1)/sqrt(2)`` (the push into the wall) in
    :func:`source_link_torques`.  This does the same work on all points at once.

    Parameters
    ----------
    reading : {"cos", "sin"}
        ``"cos"``, the author's IK; ``"sin"``, its transcribed line read literally
        (``source_record.ipynb#h4-1``).
    n_points : int
        Number of points along the wall (the source used 100,000; at least 2).
    force_magnitude : float
        Magnitude of the push the tip exerts on the wall, newtons.
    l1, l2 : float
        Link lengths, metres.

    Returns
    -------
    WallSearchResult

    Raises
    ------
    ValueError
        For a bad ``reading`` or ``n_points``, or when no point matches.

    Examples
    --------
    With its IK the search finds the right contact, to four digits
    (``source_record.ipynb#h4-2``):

    >>> hit = source_wall_search(reading="cos")
    >>> hit.p_contact.round(4), hit.torques.round(2)
    (array([3.2872, 0.7128]), array([9.1018e+02, 3.0000e-02]))

    Had its ``q1`` line read ``sin``, as the transcription does literally, it would
    stop elsewhere, with the real tip off the wall:

    >>> typo = source_wall_search(reading="sin")
    >>> typo.p_contact.round(4), round(float(typo.torques[0]), 2), typo.p_tip_fk.round(3)
    (array([3.4116, 0.5884]), 867.11, array([3.345, 0.892]))
    """
    _check_reading(reading)
    if (
        isinstance(n_points, bool)
        or not isinstance(n_points, (int, np.integer))
        or n_points < 2
    ):
        raise ValueError(f"n_points must be an integer >= 2; got {n_points!r}")
    force_magnitude = as_finite_scalar(force_magnitude, "force_magnitude (N)")
    s = np.linspace(0.0, 1.0, int(n_points))
    p_wall = np.stack([4.0 - 4.0 * s, 4.0 * s], axis=-1)
    q_abs = source_ik(p_wall, reading=reading, l1=l1, l2=l2)
    hits = np.flatnonzero(np.round(q_abs[:, 1], 4) == round(np.pi / 4, 4))
    if hits.size == 0:
        raise ValueError(
            f"no point of the {n_points} matched round(q2_abs, 4) == {round(np.pi / 4, 4)}"
        )
    i = int(hits[0])
    force = force_magnitude * np.array([1.0, 1.0]) / np.sqrt(2.0)
    return WallSearchResult(
        index=i,
        p_contact=p_wall[i],
        q_abs=q_abs[i],
        torques=source_link_torques(q_abs[i], force, l1=l1, l2=l2),
        p_tip_fk=source_fk(q_abs[i], l1=l1, l2=l2),
    )


def source_spring_torques(
    p_tip: ArrayLike, *, k: float = 600.0, l1: float = 2.0, l2: float = 2.0
) -> NDArray[np.float64]:
    """The source's spring torques: ``F = k (x, y)`` and ``t_i = k y l_i cos q_i - k x l_i sin q_i``.

    The spring is anchored at the origin (``x`` where ``x0 - x`` belongs)
    (``source_record.ipynb#h4-3``); the angles are the absolute angles of its
    IK, :func:`source_ik` (one branch, the package's ``elbow="down"``).  The
    torques are in the source's convention (motor 2 on the ground,
    :func:`source_link_torques`).

    Parameters
    ----------
    p_tip : array_like, shape (..., 2)
        Tip positions, metres.
    k : float
        Spring constant, N/m.
    l1, l2 : float
        Link lengths, metres (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``(t1, t2)`` in N m, the source's convention.

    Examples
    --------
    Along x = 3 at y = 0, 1, 2 (motor 1 is not zero in this convention):

    >>> p = [[3.0, 0.0], [3.0, 1.0], [3.0, 2.0]]
    >>> source_spring_torques(p).round(1)
    array([[ 2381.2, -2381.2],
           [ 2323.8, -2323.8],
           [ 1873.5, -1873.5]])

    To the nearest N m the motor-1 torques are +2381, +2324 and +1873: the third
    is 1873.4994 N m, which rounds to 1873 (rounding its one-decimal 1873.5 again
    would give 1874, a double rounding):

    >>> source_spring_torques(p)[:, 0].round(4)
    array([2381.1762, 2323.79  , 1873.4994])
    >>> source_spring_torques(p)[:, 0].round()
    array([2381., 2324., 1873.])
    """
    k = as_finite_scalar(k, "k")
    points = as_pairs(p_tip, "p_tip")
    q_abs = source_ik(points, reading="cos", l1=l1, l2=l2)
    return source_link_torques(q_abs, k * points, l1=l1, l2=l2)


def correct_spring_torques_dh(
    q_dh: ArrayLike,
    p_rest: ArrayLike,
    *,
    k: float = 600.0,
    l1: float = 2.0,
    l2: float = 2.0,
) -> NDArray[np.float64]:
    """The correct spring law in DH torques: ``tau = J(q)^T k (x0 - x)``.

    Parameters
    ----------
    q_dh : array_like, shape (..., 2)
        Relative (DH) joint angles, radians.
    p_rest : array_like, shape (2,)
        The spring's rest point ``x0``, metres.
    k : float
        Spring constant, N/m.
    l1, l2 : float
        Link lengths, metres (> 0).

    Returns
    -------
    numpy.ndarray, shape (..., 2)
        ``(tau1, tau2)`` in DH convention, N m: :func:`twolink.kinematics.joint_torques`
        of the spring's force ``k (x0 - x)``.

    Examples
    --------
    At the rest point the spring is silent:

    >>> import twolink
    >>> q = twolink.to_relative(source_ik([3.0, 1.0]))
    >>> correct_spring_torques_dh(q, [3.0, 1.0]).round(9) + 0.0
    array([0., 0.])
    """
    k = as_finite_scalar(k, "k")
    rest = as_pairs(p_rest, "p_rest")
    arm = TwoLinkArm(l1=l1, l2=l2)
    q = as_pairs(q_dh, "q_dh")
    spring_force_on_tip = k * (rest - arm.fk(q))
    # J^T F, the torque the spring applies at the joints: minus the torque that holds force_by_tip = -F
    return -arm.joint_torques(q, force_by_tip=-spring_force_on_tip)


def dh_to_motor_torques(tau_dh: ArrayLike) -> NDArray[np.float64]:
    """DH joint torques to the source's motor torques: ``u1 = tau1 - tau2``, ``u2 = tau2``.

    With motor 2 on the ground driving link 2's absolute angle, the virtual
    work ``tau1 dq1 + tau2 dq2 = u1 dq1 + u2 d(q1 + q2)`` gives this map.

    Examples
    --------
    >>> dh_to_motor_torques([0.0, -2381.0])
    array([ 2381., -2381.])
    """
    tau = as_pairs(tau_dh, "tau_dh")
    u = tau.copy()
    u[..., 0] = tau[..., 0] - tau[..., 1]
    return u


def motor_to_dh_torques(u_motor: ArrayLike) -> NDArray[np.float64]:
    """The source's motor torques to DH joint torques: ``tau1 = u1 + u2``, ``tau2 = u2``.

    Examples
    --------
    >>> motor_to_dh_torques([2381.0, -2381.0])
    array([    0., -2381.])
    """
    u = as_pairs(u_motor, "u_motor")
    tau = u.copy()
    tau[..., 0] = u[..., 0] + u[..., 1]
    return tau


#: The whole degrees the project's workspace plot samples for both absolute link
#: angles, ``range(35, 145, 1)`` (``source_record.ipynb#h4-5``): a plot range, which
#: leaves out 145 deg; the project states no joint limits.
WORKSPACE_PLOT_DEGREES = range(35, 145, 1)


def source_workspace_points(*, l1: float = 2.0, l2: float = 2.0) -> NDArray[np.float64]:
    """The tips the project's workspace plot draws: both absolute angles over ``range(35, 145, 1)`` deg.

    Every pair ``(q1, q2_abs)`` of whole degrees from :data:`WORKSPACE_PLOT_DEGREES`
    (``q1`` in the outer loop), through :func:`source_fk`.  Python's ``range``
    stops before its end, so 145 deg is never used.  The range belongs to the
    plot: the project states no joint limits, and its own wall, spring and line
    tasks use angles outside [35, 145] deg (``source_record.ipynb#h4-5``).

    Parameters
    ----------
    l1, l2 : float
        Link lengths, metres (> 0).

    Returns
    -------
    numpy.ndarray, shape (12100, 2)
        The tips ``(x, y)``, metres, 110 x 110 configurations.

    Examples
    --------
    >>> p = source_workspace_points()
    >>> p.shape, WORKSPACE_PLOT_DEGREES[-1]
    ((12100, 2), 144)
    >>> p[:, 0].min().round(3), p[:, 0].max().round(3)
    (np.float64(-3.236), np.float64(3.277))
    """
    degrees = np.radians(np.array(WORKSPACE_PLOT_DEGREES, dtype=float))
    q1_abs, q2_abs = np.meshgrid(degrees, degrees, indexing="ij")
    angles = np.column_stack([q1_abs.ravel(), q2_abs.ravel()])
    return source_fk(angles, l1=l1, l2=l2)
