"""Running a twolink arm in MuJoCo: the hand-derived dynamics checked by a real physics engine.

The model is :func:`twolink.export.to_mjcf`'s: the same rods, gravity along
-y (magnitude ``arm.g``), motors on both joints applying the ``tau`` of
``M qdd + C qd + g = tau`` (N m), no damping.  MuJoCo is an optional
dependency (``pip install "twolink[course]"``); it is imported only when a
function here is called, which raises :class:`ImportError` naming itself and
the install command when it is missing.

* :func:`build_model` -- the ``mujoco.MjModel`` of an arm;
* :func:`joint_accelerations` -- MuJoCo's ``qdd`` (``mj_forward``) for a
  state and motor torques, to compare with
  :func:`twolink.dynamics.forward_dynamics`;
* :func:`simulate` -- the arm moved by MuJoCo (fixed step, RK4) from
  ``(q0, qd0)``, free or driven by torques ``tau(t, q, qd)`` -- the same
  callables (controllers) :func:`twolink.simulate` takes;
* :func:`wall_push` -- the course's wall problem: the arm at the contact
  configuration of :func:`twolink.statics.wall_contact`, the statics torques
  applied, MuJoCo's contact force once settled.

Force conventions are twolink's: ``force`` is what the tip exerts on the
wall; the wall pushes back with ``-force``; ``tau = J^T force`` holds it
(:func:`twolink.kinematics.joint_torques`).

Examples
--------
>>> from twolink import TwoLinkArm, engine
>>> arm = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)
>>> qdd_mujoco = engine.joint_accelerations(engine.build_model(arm), [0.3, -0.5], [0.2, 1.0], [1.0, -2.0])
>>> bool(np.allclose(qdd_mujoco, arm.forward_dynamics([0.3, -0.5], [0.2, 1.0], [1.0, -2.0]), rtol=1e-12))
True
"""

import math
from dataclasses import dataclass

import numpy as np

from . import export
from ._optional import require
from ._validate import as_finite_scalar, as_pairs
from .dynamics import _torque_floats
from .kinematics import jacobian
from .simulate import SimulationError, SimulationResult
from .statics import wall_contact

__all__ = [
    "build_model",
    "joint_accelerations",
    "simulate",
    "EngineResult",
    "wall_push",
    "WallPush",
    "DEFAULT_TIMESTEP",
    "WALL_SOLIMP",
    "MAX_STEPS",
]

#: The default fixed step of :func:`simulate`, seconds: RK4 at 0.1 ms keeps
#: the 2 m arm's free swing within 1e-9 rad of scipy's DOP853 at 1e-10 over 2 s.
DEFAULT_TIMESTEP = 1e-4

#: :func:`wall_push`'s constraint impedance (MuJoCo's ``solimp``: dmin,
#: dmax, width, midpoint, power): ``d = 0.99`` everywhere, so the constraint
#: keeps 99 % of the stiffness its reference asks for (MuJoCo's default is
#: 0.9 to 0.95).
WALL_SOLIMP = (0.99, 0.99, 0.001, 0.5, 2.0)

#: Most steps any function here takes (a budget: nothing runs forever).
MAX_STEPS = 2_000_000


_WARNING_TYPE = None  # mujoco.mjtWarning, set at the first import


def _mujoco(function):
    global _WARNING_TYPE
    mujoco = require("mujoco", f"twolink.engine.{function}")
    _WARNING_TYPE = mujoco.mjtWarning
    return mujoco


def build_model(arm, **mjcf_options):
    """The ``mujoco.MjModel`` of the arm, from :func:`twolink.export.to_mjcf`.

    Parameters
    ----------
    arm : TwoLinkArm
    **mjcf_options
        Passed to :func:`~twolink.export.to_mjcf` (``wall``, ``timestep``,
        ``integrator``, ``contact_solref``, ...).

    Returns
    -------
    mujoco.MjModel
        With MuJoCo's automatic reset on bad accelerations switched off
        (``mjDSBL_AUTORESET``), so a blown-up state stays visible as NaN
        instead of silently jumping back to the start.

    Raises
    ------
    ImportError
        Without MuJoCo installed.

    Examples
    --------
    >>> from twolink import arms, engine
    >>> model = engine.build_model(arms.ten)
    >>> model.nq, model.nu, model.jnt_range.round(6).tolist()
    (2, 2, [[0.0, 1.570796], [-1.570796, 1.570796]])
    """
    mujoco = _mujoco("build_model")
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arm, **mjcf_options))
    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_AUTORESET)
    return model


def _one_pair(value, name):
    pair = as_pairs(value, name)
    if pair.shape != (2,):
        raise ValueError(f"{name} must be one pair of shape (2,); got shape {pair.shape}")
    return pair


def _check_model(model, who):
    if not (hasattr(model, "nq") and hasattr(model, "opt")) or model.nq != 2 or model.nu != 2:
        raise ValueError(f"{who} needs the mujoco.MjModel of a two-link arm (engine.build_model(arm)); got {model!r}")


def joint_accelerations(model, q, qd, tau):
    """MuJoCo's joint accelerations ``qdd`` for a state and motor torques.

    Sets ``qpos = q``, ``qvel = qd``, ``ctrl = tau`` on fresh data and calls
    ``mj_forward``; returns ``data.qacc``.  For a model of
    :func:`build_model` this is ``M^-1 (tau - C qd - g)``, computed by
    MuJoCo's own recursive algorithms (and including joint-limit or contact
    forces if the state touches a limit or the wall).

    Parameters
    ----------
    model : mujoco.MjModel
        A two-joint, two-motor model (:func:`build_model`).
    q, qd, tau : array_like, shape (2,)
        Joint angles (rad), rates (rad/s), motor torques (N m).

    Returns
    -------
    numpy.ndarray, shape (2,)
        rad/s^2.

    Examples
    --------
    Released from rest straight out along x:

    >>> from twolink import TwoLinkArm, engine
    >>> model = engine.build_model(TwoLinkArm(2.0, 2.0, m1=1.0, m2=1.0, g=10.0))
    >>> engine.joint_accelerations(model, [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]).round(6)
    array([-6.428571,  8.571429])
    """
    mujoco = _mujoco("joint_accelerations")
    _check_model(model, "joint_accelerations")
    data = mujoco.MjData(model)
    data.qpos[:] = _one_pair(q, "q")
    data.qvel[:] = _one_pair(qd, "qd")
    data.ctrl[:] = _one_pair(tau, "tau")
    mujoco.mj_forward(model, data)
    return data.qacc.copy()


@dataclass(frozen=True)
class EngineResult(SimulationResult):
    """A motion computed by MuJoCo: a :class:`twolink.SimulationResult` plus the tip and the contact.

    Attributes (besides :class:`~twolink.SimulationResult`'s; ``status`` is
    0, ``nfev`` counts MuJoCo steps)
    ----------
    p_tip : numpy.ndarray, shape (n, 2)
        The tip position MuJoCo computes (site ``tip``), metres.
    force_on_wall : numpy.ndarray, shape (n, 2)
        The force the tip exerts on the wall (N), from ``mj_contactForce``;
        zeros without contact.
    timestep : float
        MuJoCo's fixed step, seconds.
    """

    p_tip: np.ndarray = None
    force_on_wall: np.ndarray = None
    timestep: float = None


def _frozen(array):
    array = np.array(array, dtype=float)
    array.setflags(write=False)
    return array


def _force_on_wall(mujoco, model, data, wall_id, buffer):
    """Sum over active contacts of the force the tip exerts on the wall, world (x, y), N."""
    total = np.zeros(3)
    for index in range(data.ncon):
        contact = data.contact[index]
        if wall_id not in (contact.geom1, contact.geom2):
            continue
        mujoco.mj_contactForce(model, data, index, buffer)
        # buffer: (normal, tangent 1, tangent 2) components in the contact frame,
        # the force geom1 exerts on geom2 (the frame's normal points from geom1 to geom2)
        force = contact.frame.reshape(3, 3).T @ buffer[:3]
        total += force if contact.geom2 == wall_id else -force
    return total[:2]


#: MuJoCo's warnings that mean the simulation went wrong (it then zeroes the bad value and goes on).
_BAD_STATE_WARNINGS = ("mjWARN_BADQPOS", "mjWARN_BADQVEL", "mjWARN_BADQACC", "mjWARN_BADCTRL")


def _check_state(data, t, who):
    qpos, qvel = data.qpos, data.qvel
    warnings = data.warning
    bad = [name for name in _BAD_STATE_WARNINGS if warnings[int(getattr(_WARNING_TYPE, name))].number]
    if bad or not math.isfinite(qpos[0] + qpos[1] + qvel[0] + qvel[1]):  # NaN or inf anywhere makes the sum so
        reason = f"MuJoCo warned {', '.join(bad)}" if bad else "MuJoCo's state became NaN or infinite"
        raise SimulationError(
            f"{who}: {reason} at or before t = {t:.6g} s "
            "(a state or torque that is NaN, infinite or larger than 1e10: try a smaller timestep, "
            "smaller torques or gains)"
        )


def simulate(
    arm,
    q0,
    qd0,
    t_end,
    torque=None,
    *,
    timestep: float = DEFAULT_TIMESTEP,
    sample_every: int = 1,
    integrator: str = "RK4",
    **mjcf_options,
) -> EngineResult:
    """Move the arm in MuJoCo from ``(q0, qd0)`` at ``t = 0`` to ``t_end``, fixed step.

    Each step first evaluates the torques from MuJoCo's current state
    (``torque(t, q, qd)``), puts them in ``data.ctrl`` and calls
    ``mj_step`` (RK4 by default): the torques are held over the step (a
    zero-order hold, as a digital controller does), while
    :func:`twolink.simulate` evaluates them continuously.  For free motion
    or constant torques the two integrate the same equation; with a
    controller they differ by O(timestep).

    Parameters
    ----------
    arm : TwoLinkArm
    q0, qd0 : array_like, shape (2,)
        Initial joint angles (rad) and rates (rad/s).
    t_end : float
        End time, seconds (> 0); rounded to a whole number of steps.
    torque : callable or array_like, optional
        ``torque(t, q, qd) -> tau`` (N m), the interface of
        :func:`twolink.simulate`, so the same controller objects
        (:class:`twolink.controllers.Impedance`, ...) drive both; or two
        constant torques; ``None`` (default) is free motion.
    timestep : float
        MuJoCo's step, seconds (> 0).
    sample_every : int
        Record every ``sample_every``-th step (1 to the number of steps); the
        run ends at the last recorded step, so ``t_end`` is best a multiple of
        ``sample_every * timestep``.
    integrator : str
        MuJoCo's integrator (see :func:`twolink.export.to_mjcf`).
    **mjcf_options
        More :func:`~twolink.export.to_mjcf` options, e.g. ``wall``.

    Returns
    -------
    EngineResult
        Times, ``q``, ``qd``, the torques applied, the tip and the force on
        the wall at the recorded steps.

    Raises
    ------
    ValueError
        For bad arguments (also a torque callable returning other than two
        finite numbers), or more than :data:`MAX_STEPS` steps.
    SimulationError
        When MuJoCo's state blows up (NaN); the message names the time.
    ImportError
        Without MuJoCo installed.

    Examples
    --------
    Held by its gravity torques the arm stays put; free, the same start
    falls exactly as :func:`twolink.simulate` says:

    >>> from twolink import arms, engine, simulate
    >>> arm = arms.two_metre
    >>> held = engine.simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 0.5, torque=lambda t, q, qd: arm.gravity(q))
    >>> bool(np.allclose(held.q, [np.pi / 4, 0.0], atol=1e-9))
    True
    >>> free = engine.simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 1.0, sample_every=100)
    >>> reference = simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 1.0, t_eval=free.t)
    >>> bool(np.max(np.abs(free.q - reference.q)) < 1e-9)
    True
    """
    mujoco = _mujoco("simulate")
    q0, qd0 = _one_pair(q0, "q0"), _one_pair(qd0, "qd0")
    t_end = as_finite_scalar(t_end, "t_end (s)", minimum=0.0, strictly=True)
    timestep = as_finite_scalar(timestep, "timestep (s)", minimum=0.0, strictly=True)
    if isinstance(sample_every, bool) or not isinstance(sample_every, (int, np.integer)) or sample_every < 1:
        raise ValueError(f"sample_every must be an integer >= 1 (steps); got {sample_every!r}")
    n_steps = int(round(t_end / timestep))
    if not 1 <= n_steps <= MAX_STEPS:
        raise ValueError(
            f"t_end / timestep = {t_end:.6g} / {timestep:.6g} s gives {n_steps} steps; allowed 1 to {MAX_STEPS}"
        )
    constant = None
    if torque is None:
        constant = (0.0, 0.0)
    elif not callable(torque):
        constant = tuple(_one_pair(torque, "torque (N m)").tolist())
    model = build_model(arm, timestep=timestep, integrator=integrator, **mjcf_options)
    data = mujoco.MjData(model)
    data.qpos[:], data.qvel[:] = q0, qd0
    tip_id = model.site("tip").id
    wall_id = model.geom("wall").id if "wall" in mjcf_options and mjcf_options["wall"] is not None else None
    buffer = np.zeros(6)
    if sample_every > n_steps:
        raise ValueError(f"sample_every must be at most the number of steps, {n_steps}; got {sample_every}")
    n_samples = n_steps // sample_every + 1
    times = np.empty(n_samples)
    q, qd, tau, p_tip, force = (np.zeros((n_samples, 2)) for _ in range(5))

    def record(row, t, tau_now):
        times[row], q[row], qd[row], tau[row] = t, data.qpos, data.qvel, tau_now
        p_tip[row] = data.site_xpos[tip_id][:2]
        if wall_id is not None:
            force[row] = _force_on_wall(mujoco, model, data, wall_id, buffer)

    def torques_now(t):
        if constant is not None:
            return constant
        return _torque_floats(torque(t, data.qpos.copy(), data.qvel.copy()), t)

    if wall_id is None and not arm.has_limits:
        # no limit, no wall: nothing for MuJoCo's constraint solver to do (halves the cost of a step)
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
    refresh = mujoco.mj_kinematics if wall_id is None else mujoco.mj_forward  # what the recorded values need
    mujoco.mj_forward(model, data)
    tau_now = torques_now(0.0)
    record(0, 0.0, tau_now)
    if constant is not None:  # free motion or constant torques: MuJoCo takes sample_every steps per call
        data.ctrl[:] = constant
        for row in range(1, n_samples):
            mujoco.mj_step(model, data, sample_every)
            t = row * sample_every * timestep
            _check_state(data, t, "engine.simulate")
            refresh(model, data)
            record(row, t, constant)
    else:
        for step in range(1, (n_samples - 1) * sample_every + 1):
            data.ctrl[:] = tau_now
            mujoco.mj_step(model, data)
            t = step * timestep
            _check_state(data, t, "engine.simulate")
            tau_now = torques_now(t)
            if step % sample_every == 0:
                # mj_step leaves the position-dependent quantities (site_xpos, contacts) at the
                # step's start; refresh them for the new state before recording
                refresh(model, data)
                record(step // sample_every, t, tau_now)
    return EngineResult(
        arm=arm,
        t=_frozen(times),
        q=_frozen(q),
        qd=_frozen(qd),
        tau=_frozen(tau),
        status=0,
        message=f"MuJoCo {integrator}, fixed step {timestep:.6g} s, {(n_samples - 1) * sample_every} steps",
        nfev=(n_samples - 1) * sample_every,
        p_tip=_frozen(p_tip),
        force_on_wall=_frozen(force),
        timestep=timestep,
    )


@dataclass(frozen=True)
class WallPush:
    """The arm pushing on a wall in MuJoCo, settled (see :func:`wall_push`).

    Attributes
    ----------
    elbow : str
        The branch of :func:`twolink.statics.wall_contact` used.
    q_contact : numpy.ndarray, shape (2,)
        The statics' contact configuration (the start), rad.
    tau : numpy.ndarray, shape (2,)
        The constant motor torques applied: ``J^T F`` plus the arm's gravity
        torques ``g(q_contact)``, N m.
    force_expected : numpy.ndarray, shape (2,)
        The force the statics says the tip exerts on the wall (magnitude
        ``force_magnitude`` along the normal into the wall), N.
    q_settled, qd_settled : numpy.ndarray, shape (2,)
        MuJoCo's configuration (rad) and rates (rad/s) at the end.
    force_on_wall : numpy.ndarray, shape (2,)
        The force MuJoCo's contact puts on the wall at the end
        (``mj_contactForce``), N.
    force_normal, force_tangential : float
        Its components along the normal into the wall and along the wall, N.
    force_statics_settled : numpy.ndarray, shape (2,)
        The force that exactly balances ``tau`` at MuJoCo's settled
        configuration, ``J(q_settled)^-T (tau - g(q_settled))``, N: what
        MuJoCo's force should be for a settled arm.
    penetration : float
        How far the tip point is beyond the wall's line at the end, metres.
    force_drift : float
        Change of ``force_normal`` over the last tenth of the run, N (small
        when settled).
    steps : int
        MuJoCo steps taken.
    """

    elbow: str
    q_contact: np.ndarray
    tau: np.ndarray
    force_expected: np.ndarray
    q_settled: np.ndarray
    qd_settled: np.ndarray
    force_on_wall: np.ndarray
    force_normal: float
    force_tangential: float
    force_statics_settled: np.ndarray
    penetration: float
    force_drift: float
    steps: int

    @property
    def relative_error(self):
        """``|force_normal - force_magnitude| / force_magnitude`` (the agreement with the statics)."""
        magnitude = float(np.hypot(*self.force_expected))
        return abs(self.force_normal - magnitude) / magnitude


def wall_push(
    arm,
    wall,
    force_magnitude,
    elbow: str = "down",
    *,
    duration: float = 0.2,
    timestep: float = DEFAULT_TIMESTEP,
    contact_solref=None,
    contact_solimp=WALL_SOLIMP,
    impratio: float = 100.0,
) -> WallPush:
    """The course's wall problem in MuJoCo: statics torques applied, the contact force read back.

    The arm starts at rest at the contact configuration of
    :func:`twolink.statics.wall_contact` (link 2 perpendicular to the wall,
    the tip on it), with the wall as a MuJoCo plane, and the motors apply the
    constant torques ``tau = J^T F + g(q)`` that, by the statics, push with
    ``force_magnitude`` along the normal (``g(q)`` holds the arm's weight;
    zero for a horizontal arm).  MuJoCo steps for ``duration`` seconds and
    the contact force it computes is reported.

    **What soft contact does.**  MuJoCo's contacts are soft: a contact force
    exists only while the tip is pushed slightly into the wall, like a very
    stiff spring-damper whose reference acceleration is ``-b v - k r``
    (``r`` the penetration) with ``k = 1 / (dmax^2 timeconst^2
    dampratio^2)`` from ``solref = (timeconst, dampratio)``, of which the
    constraint keeps the fraction ``d`` (``solimp``'s impedance).  Once
    settled, the contact force is not set by the softness: it is the force
    that balances the torques, ``J(q)^-T (tau - g(q))``.  The softness sets
    how far the tip sinks in, and that moves the arm slightly away from the
    statics' configuration, so ``J`` and with it the force change slightly:
    the error in the force is of the order of the penetration over the
    link lengths.  With MuJoCo's defaults (``timeconst = 0.02`` s,
    ``d = 0.9..0.95``, ``impratio = 1``) the 2 m arm sinks about 3 mm under
    500 N and reads about 500.5 N.  The sinking here comes mostly from the
    friction rows of MuJoCo's (pyramidal) friction cone, whose softness is
    divided by ``impratio``: the defaults below (``timeconst = 2 timestep``,
    ``d = 0.99``, ``impratio = 100``) give about 8 micrometres and 500.0015 N.
    Friction is needed: with constant torques the contact configuration is
    an unstable equilibrium for sliding along a frictionless wall.

    Parameters
    ----------
    arm : TwoLinkArm
    wall : Wall or pair of points
        The wall (see :func:`twolink.export.to_mjcf`).
    force_magnitude : float
        The normal force the statics torques are computed for, N (>= 0).
    elbow : str
        The branch: ``"down"``, ``"up"``, or ``"stretched"``/``"folded"``
        when the wall allows only one configuration.
    duration : float
        Simulated time, seconds (> 0); at most :data:`MAX_STEPS` steps.
    timestep : float
        MuJoCo's step, seconds.
    contact_solref : pair of float, optional
        ``(timeconst, dampratio)``; default ``(2 timestep, 1)`` (the stiffest
        MuJoCo allows for the step, critically damped).
    contact_solimp : sequence of float
        MuJoCo's ``solimp``; default :data:`WALL_SOLIMP`.
    impratio : float
        MuJoCo's ratio of frictional to normal constraint impedance (>= 1).

    Returns
    -------
    WallPush

    Raises
    ------
    twolink.UnreachableError
        When no configuration has link 2 perpendicular to the wall.
    ValueError
        For bad arguments or an ``elbow`` this wall does not have.
    SimulationError
        When MuJoCo's state blows up.
    ImportError
        Without MuJoCo installed.

    Examples
    --------
    The course's wall ``x + y = 4``, the 2 m arm, 500 N:

    >>> from twolink import arms, engine
    >>> push = engine.wall_push(arms.two_metre, [[4.0, 0.0], [0.0, 4.0]], 500.0, elbow="up")
    >>> round(push.force_normal, 2), bool(push.relative_error < 1e-4), bool(push.penetration < 1e-4)
    (500.0, True, True)
    """
    mujoco = _mujoco("wall_push")
    wall = export._as_wall(wall)
    if wall is None:
        raise ValueError("wall_push needs a wall (a twolink.statics.Wall or two points on it); got None")
    duration = as_finite_scalar(duration, "duration (s)", minimum=0.0, strictly=True)
    timestep = as_finite_scalar(timestep, "timestep (s)", minimum=0.0, strictly=True)
    impratio = as_finite_scalar(impratio, "impratio", minimum=1.0)
    n_steps = int(round(duration / timestep))
    if not 10 <= n_steps <= MAX_STEPS:
        raise ValueError(f"duration / timestep gives {n_steps} steps; allowed 10 to {MAX_STEPS}")
    contact = wall_contact(arm, wall, force_magnitude, include_gravity=True)
    row = contact.branch(elbow)
    q_contact, tau = contact.q[row], contact.tau[row]
    solref = (2.0 * timestep, 1.0) if contact_solref is None else contact_solref
    model = build_model(arm, wall=wall, timestep=timestep, contact_solref=solref, contact_solimp=contact_solimp)
    model.opt.impratio = impratio
    data = mujoco.MjData(model)
    data.qpos[:] = q_contact
    data.ctrl[:] = tau
    wall_id = model.geom("wall").id
    buffer = np.zeros(6)
    normal = wall.into_wall()
    last_tenth = n_steps - max(1, n_steps // 10)
    mujoco.mj_step(model, data, last_tenth)
    _check_state(data, last_tenth * timestep, "engine.wall_push")
    mujoco.mj_forward(model, data)
    force_before = float(_force_on_wall(mujoco, model, data, wall_id, buffer) @ normal)
    mujoco.mj_step(model, data, n_steps - last_tenth)
    _check_state(data, n_steps * timestep, "engine.wall_push")
    mujoco.mj_forward(model, data)
    force = _force_on_wall(mujoco, model, data, wall_id, buffer)
    q_settled = data.qpos.copy()
    force_statics = np.linalg.solve(jacobian(arm, q_settled).T, tau - arm.gravity(q_settled))
    along = np.array([-normal[1], normal[0]])
    return WallPush(
        elbow=contact.elbow[row],
        q_contact=q_contact.copy(),
        tau=tau.copy(),
        force_expected=contact.force.copy(),
        q_settled=q_settled,
        qd_settled=data.qvel.copy(),
        force_on_wall=force,
        force_normal=float(force @ normal),
        force_tangential=float(force @ along),
        force_statics_settled=force_statics,
        penetration=float((arm.fk(q_settled) - wall.point) @ normal),
        force_drift=abs(float(force @ normal) - force_before),
        steps=n_steps,
    )
