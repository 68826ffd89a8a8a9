"""Running a twolink arm in MuJoCo: the hand-derived dynamics checked by a real physics engine.

The model is :func:`twolink.export.to_mjcf`'s: the same rods, gravity along
-y (magnitude ``arm.g``), motors on both joints applying the ``tau`` of
``M qdd + C qd + g = tau`` (N m), no damping.  MuJoCo is an optional
dependency (``pip install "twolink[mujoco]"``); it is imported only when a
function here is called, which raises :class:`ImportError` naming itself and
the install command when it is missing.

* :func:`build_model` -- the ``mujoco.MjModel`` of an arm;
* :func:`joint_accelerations` -- MuJoCo's ``qdd`` (``mj_forward``) for a
  state and motor torques, to compare with
  :func:`twolink.dynamics.forward_dynamics`;
* :func:`simulate_in_mujoco` -- the arm moved by MuJoCo (fixed step, RK4) from
  ``(q0, qd0)``, free or driven by torques ``tau(t, q, qd)`` -- the same
  callables (controllers) :func:`twolink.simulate` takes;
* :func:`wall_push` -- the course's wall problem: the arm at the contact
  configuration of :func:`twolink.statics.wall_contact`, the statics torques
  applied, MuJoCo's contact force once settled.

Force conventions are twolink's: ``force_by_tip`` is what the tip exerts on
the wall; the wall pushes back on the tip with ``-force_by_tip``;
``tau = J^T force_by_tip`` holds it (:func:`twolink.kinematics.joint_torques`).

Examples
--------
>>> from twolink import TwoLinkArm, engine
>>> arm = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2)
>>> qdd_mujoco = engine.joint_accelerations(engine.build_model(arm), [0.3, -0.5], [0.2, 1.0], [1.0, -2.0])
>>> bool(np.allclose(qdd_mujoco, arm.forward_dynamics([0.3, -0.5], [0.2, 1.0], [1.0, -2.0]), rtol=1e-12))
True
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from . import export
from ._optional import require
from ._validate import (
    as_configuration,
    as_count,
    as_finite_scalar,
    as_time_span,
    torque_floats,
)
from ._values import Value, freeze
from .budgets import DEFAULT_MAX_WALL_TIME, EvaluationBudget
from .conventions import check_elbow
from .errors import SimulationError
from .kinematics import jacobian
from .simulation import SimulationResult
from .statics import Wall, as_wall, wall_contact

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = [
    "build_model",
    "joint_accelerations",
    "simulate_in_mujoco",
    "EngineResult",
    "wall_push",
    "WallPush",
    "DEFAULT_TIMESTEP",
    "WALL_SOLIMP",
    "MAX_STEPS",
]

#: The default fixed step of :func:`simulate_in_mujoco`, seconds: RK4 at 0.1 ms keeps
#: the 2 m arm's free swing within 1e-9 rad of scipy's DOP853 at 1e-10 over 2 s.
DEFAULT_TIMESTEP = 1e-4

#: :func:`wall_push`'s constraint impedance (MuJoCo's ``solimp``: dmin,
#: dmax, width, midpoint, power): ``d = 0.99`` everywhere, so the constraint
#: keeps 99 % of the stiffness its reference asks for (MuJoCo's default is
#: 0.9 to 0.95).
WALL_SOLIMP = (0.99, 0.99, 0.001, 0.5, 2.0)

#: Most steps any function here takes (a budget: nothing runs forever).
MAX_STEPS = 2_000_000


_WARNING_TYPE: Any = None  # mujoco.mjtWarning, set at the first import


def _mujoco(function: str) -> Any:
    global _WARNING_TYPE
    mujoco = require("mujoco", f"twolink.engine.{function}")
    _WARNING_TYPE = mujoco.mjtWarning
    return mujoco


def build_model(arm: TwoLinkArm, **mjcf_options: Any) -> Any:
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


#: What each single-state argument is, for :func:`twolink._validate.as_configuration`'s message.
_ONE = {
    "q": {"what": "one configuration", "unit": "radians"},
    "q0": {"what": "one configuration", "unit": "radians"},
    "qd": {"what": "one pair of joint rates", "unit": "rad/s"},
    "qd0": {"what": "one pair of joint rates", "unit": "rad/s"},
    "tau": {"what": "one pair of torques", "unit": "N m"},
    "torque (N m)": {"what": "one pair of constant torques", "unit": "N m"},
}


def _one(value: ArrayLike, name: str) -> NDArray[np.float64]:
    return as_configuration(value, name, **_ONE[name])


def _check_model(model: Any, who: str) -> None:
    if (
        not (hasattr(model, "nq") and hasattr(model, "opt"))
        or model.nq != 2
        or model.nu != 2
    ):
        raise ValueError(
            f"{who} needs the mujoco.MjModel of a two-link arm (engine.build_model(arm)); got {model!r}"
        )


def joint_accelerations(
    model: Any, q: ArrayLike, qd: ArrayLike, tau: ArrayLike
) -> NDArray[np.float64]:
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
    data.qpos[:] = _one(q, "q")
    data.qvel[:] = _one(qd, "qd")
    data.ctrl[:] = _one(tau, "tau")
    mujoco.mj_forward(model, data)
    return data.qacc.copy()


@dataclass(frozen=True, kw_only=True, eq=False)
class EngineResult(SimulationResult):
    """A motion computed by MuJoCo: a :class:`twolink.SimulationResult` plus the tip and the contact.

    Attributes (besides :class:`~twolink.SimulationResult`'s; ``status`` is
    0, ``nfev`` counts MuJoCo steps)
    ----------
    p_tip_mujoco : numpy.ndarray, shape (n, 2)
        The tip position MuJoCo's own kinematics computes (site ``tip``),
        metres; :attr:`p_tip` (inherited) is twolink's ``fk(q)`` of MuJoCo's
        joint angles, equal to it to round-off (tested).
    force_by_tip : numpy.ndarray, shape (n, 2)
        The force the tip exerts on the wall (N), from ``mj_contactForce``;
        zeros without contact.  The wall pushes on the tip with
        ``-force_by_tip``.
    timestep : float
        MuJoCo's fixed step, seconds.
    """

    p_tip_mujoco: NDArray[np.float64]
    force_by_tip: NDArray[np.float64]
    timestep: float


def _force_by_tip(
    mujoco: Any, model: Any, data: Any, wall_id: int, buffer: NDArray[np.float64]
) -> NDArray[np.float64]:
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
_BAD_STATE_WARNINGS = (
    "mjWARN_BADQPOS",
    "mjWARN_BADQVEL",
    "mjWARN_BADQACC",
    "mjWARN_BADCTRL",
)


def _check_state(data: Any, t: float, who: str) -> None:
    qpos, qvel = data.qpos, data.qvel
    warnings = data.warning
    bad = [
        name
        for name in _BAD_STATE_WARNINGS
        if warnings[int(getattr(_WARNING_TYPE, name))].number
    ]
    if bad or not math.isfinite(
        qpos[0] + qpos[1] + qvel[0] + qvel[1]
    ):  # NaN or inf anywhere makes the sum so
        reason = (
            f"MuJoCo warned {', '.join(bad)}"
            if bad
            else "MuJoCo's state became NaN or infinite"
        )
        raise SimulationError(
            f"{who}: {reason} at or before t = {t:.6g} s "
            "(a state or torque that is NaN, infinite or larger than 1e10: try a smaller timestep, "
            "smaller torques or gains)"
        )


def simulate_in_mujoco(
    arm: TwoLinkArm,
    q0: ArrayLike,
    qd0: ArrayLike,
    t_end: float,
    torque: Callable[[float, NDArray[np.float64], NDArray[np.float64]], ArrayLike]
    | ArrayLike
    | None = None,
    *,
    timestep: float = DEFAULT_TIMESTEP,
    sample_every: int = 1,
    integrator: str = "RK4",
    max_wall_time: float = DEFAULT_MAX_WALL_TIME,
    **mjcf_options: Any,
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
    max_wall_time : float
        Budget of wall-clock seconds (default ``DEFAULT_MAX_WALL_TIME`` =
        30), read at every step as :func:`twolink.simulate` reads it: a slow
        torque function stops there, named as the cause.
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
        finite numbers at the start), or more than :data:`MAX_STEPS` steps.
    SimulationError
        When MuJoCo's state blows up (NaN), the torque callable fails past
        the start, or the wall time runs out; the message names the time.
    ImportError
        Without MuJoCo installed.

    Examples
    --------
    Held by its gravity torques the arm stays put; free, the same start
    falls exactly as :func:`twolink.simulate` says:

    >>> from twolink import arms, engine, simulate
    >>> arm = arms.two_metre
    >>> held = engine.simulate_in_mujoco(arm, [np.pi / 4, 0.0], [0.0, 0.0], 0.5, torque=lambda t, q, qd: arm.gravity(q))
    >>> bool(np.allclose(held.q, [np.pi / 4, 0.0], atol=1e-9))
    True
    >>> free = engine.simulate_in_mujoco(arm, [np.pi / 4, 0.0], [0.0, 0.0], 1.0, sample_every=100)
    >>> reference = simulate(arm, [np.pi / 4, 0.0], [0.0, 0.0], 1.0, t_eval=free.t)
    >>> bool(np.max(np.abs(free.q - reference.q)) < 1e-9)
    True
    """
    mujoco = _mujoco("simulate_in_mujoco")
    start, rate_start = _one(q0, "q0"), _one(qd0, "qd0")
    t_end = as_time_span(t_end, "t_end (s)")
    timestep = as_time_span(timestep, "timestep (s)")
    sample_every = as_count(sample_every, "sample_every (steps)", minimum=1)
    n_steps = int(round(t_end / timestep))
    if not 1 <= n_steps <= MAX_STEPS:
        raise ValueError(
            f"t_end / timestep = {t_end:.6g} / {timestep:.6g} s gives {n_steps} steps; allowed 1 to {MAX_STEPS}"
        )
    budget = EvaluationBudget(n_steps + 1, max_wall_time)
    constant: tuple[float, float] | None = None
    if torque is None:
        constant = (0.0, 0.0)
    elif not callable(torque):
        tau1, tau2 = _one(torque, "torque (N m)").tolist()
        constant = (tau1, tau2)
    model = build_model(arm, timestep=timestep, integrator=integrator, **mjcf_options)
    data = mujoco.MjData(model)
    data.qpos[:], data.qvel[:] = start, rate_start
    tip_id = model.site("tip").id
    wall_id = (
        model.geom("wall").id
        if "wall" in mjcf_options and mjcf_options["wall"] is not None
        else None
    )
    buffer = np.zeros(6)
    if sample_every > n_steps:
        raise ValueError(
            f"sample_every must be at most the number of steps, {n_steps}; got {sample_every}"
        )
    n_samples = n_steps // sample_every + 1
    times = np.empty(n_samples)
    q, qd, tau, p_tip, force = (np.zeros((n_samples, 2)) for _ in range(5))

    def record(row: int, t: float, tau_now: tuple[float, float]) -> None:
        times[row], q[row], qd[row], tau[row] = t, data.qpos, data.qvel, tau_now
        p_tip[row] = data.site_xpos[tip_id][:2]
        if wall_id is not None:
            force[row] = _force_by_tip(mujoco, model, data, wall_id, buffer)

    def torques_now(t: float) -> tuple[float, float]:
        spent = budget.spend()
        if spent is not None:
            raise SimulationError(
                f"engine.simulate_in_mujoco used up its budget of {budget.describe(spent)} at t = {t:.6g} s "
                f"of {t_end:.6g} s after {budget.evaluations - 1} steps: "
                + (
                    "torque(t, q, qd) is slow; make it faster or raise max_wall_time"
                    if constant is None
                    else "take fewer steps (a larger timestep, a shorter t_end) or raise max_wall_time"
                )
            )
        if constant is not None:
            return constant
        assert callable(torque)  # constant is None only for a callable torque
        try:
            return torque_floats(torque(t, data.qpos.copy(), data.qvel.copy()), t)
        except ValueError as exc:
            if (
                budget.evaluations == 1
            ):  # at the start: the torque function, not the motion
                raise
            raise SimulationError(
                f"the motion failed at t = {t:.6g} s in the state q = ({data.qpos[0]:.6g}, "
                f"{data.qpos[1]:.6g}) rad, qd = ({data.qvel[0]:.6g}, {data.qvel[1]:.6g}) rad/s: {exc}"
            ) from None

    if wall_id is None and not arm.has_limits:
        # no limit, no wall: nothing for MuJoCo's constraint solver to do (halves the cost of a step)
        model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
    refresh = (
        mujoco.mj_kinematics if wall_id is None else mujoco.mj_forward
    )  # what the recorded values need
    mujoco.mj_forward(model, data)
    tau_now = torques_now(0.0)
    record(0, 0.0, tau_now)
    if (
        constant is not None
    ):  # free motion or constant torques: MuJoCo takes sample_every steps per call
        data.ctrl[:] = constant
        for row in range(1, n_samples):
            mujoco.mj_step(model, data, sample_every)
            t = row * sample_every * timestep
            _check_state(data, t, "engine.simulate_in_mujoco")
            torques_now(t)  # reads the clock
            refresh(model, data)
            record(row, t, constant)
    else:
        for step in range(1, (n_samples - 1) * sample_every + 1):
            data.ctrl[:] = tau_now
            mujoco.mj_step(model, data)
            t = step * timestep
            _check_state(data, t, "engine.simulate_in_mujoco")
            tau_now = torques_now(t)
            if step % sample_every == 0:
                # mj_step leaves the position-dependent quantities (site_xpos, contacts) at the
                # step's start; refresh them for the new state before recording
                refresh(model, data)
                record(step // sample_every, t, tau_now)
    return EngineResult(
        arm=arm,
        t=times,
        q=q,
        qd=qd,
        tau=tau,
        status=0,
        message=f"MuJoCo {integrator}, fixed step {timestep:.6g} s, {(n_samples - 1) * sample_every} steps",
        nfev=(n_samples - 1) * sample_every,
        p_tip_mujoco=p_tip,
        force_by_tip=force,
        timestep=timestep,
    )


@dataclass(frozen=True, eq=False)
class WallPush(Value):
    """The arm pushing on a wall in MuJoCo, settled (see :func:`wall_push`).

    All forces are ``force_by_tip``: what the tip exerts on the wall (the
    wall pushes back on the tip with the opposite).

    Attributes
    ----------
    arm : TwoLinkArm
        The arm simulated.
    wall : twolink.statics.Wall
        The wall pushed on.
    elbow : str
        The branch of :func:`twolink.statics.wall_contact` used
        (``"down"``, ``"up"``, or ``"stretched"``/``"folded"`` for a wall
        with one contact configuration).
    force_magnitude : float
        The normal force the statics torques are computed for, N.
    q_contact : numpy.ndarray, shape (2,)
        The statics' contact configuration (the start), rad.
    tau : numpy.ndarray, shape (2,)
        The constant motor torques applied: ``J^T force_by_tip_expected``
        plus the arm's gravity torques ``g(q_contact)``, N m.
    q_settled, qd_settled : numpy.ndarray, shape (2,)
        MuJoCo's configuration (rad) and rates (rad/s) at the end.
    force_by_tip : numpy.ndarray, shape (2,)
        The force MuJoCo's contact says the tip exerts on the wall at the
        end (``mj_contactForce``), N.
    penetration : float
        How far the tip point is beyond the wall's line at the end, metres.
    normal_drift : float
        Change of :attr:`force_by_tip_normal` over the last tenth of the
        run, N (small when settled).
    steps : int
        MuJoCo steps taken.
    """

    arm: TwoLinkArm
    wall: Wall
    elbow: str
    force_magnitude: float
    q_contact: NDArray[np.float64]
    tau: NDArray[np.float64]
    q_settled: NDArray[np.float64]
    qd_settled: NDArray[np.float64]
    force_by_tip: NDArray[np.float64]
    penetration: float
    normal_drift: float
    steps: int

    def __post_init__(self) -> None:
        freeze(self)

    @property
    def normal(self) -> NDArray[np.float64]:
        """The wall's unit normal from the base's side into the wall."""
        return self.wall.into_wall()

    @property
    def force_by_tip_expected(self) -> NDArray[np.float64]:
        """The force the statics says the tip exerts on the wall, ``force_magnitude * normal``, N."""
        return self.force_magnitude * self.normal

    @property
    def force_by_tip_normal(self) -> float:
        """:attr:`force_by_tip`'s component along the normal into the wall, N."""
        return float(self.force_by_tip @ self.normal)

    @property
    def force_by_tip_tangential(self) -> float:
        """:attr:`force_by_tip`'s component along the wall (the normal turned +90 degrees), N."""
        normal = self.normal
        return float(self.force_by_tip @ np.array([-normal[1], normal[0]]))

    @property
    def force_by_tip_balancing(self) -> NDArray[np.float64]:
        """The force that exactly balances ``tau`` at MuJoCo's settled configuration, N.

        ``J(q_settled)^-T (tau - g(q_settled))``: what MuJoCo's
        :attr:`force_by_tip` should be for a settled arm.
        """
        q = self.q_settled
        return np.asarray(
            np.linalg.solve(jacobian(self.arm, q).T, self.tau - self.arm.gravity(q)),
            dtype=np.float64,
        )

    @property
    def relative_error(self) -> float:
        """``|force_by_tip_normal - force_magnitude| / force_magnitude`` (the agreement with the statics)."""
        return (
            abs(self.force_by_tip_normal - self.force_magnitude) / self.force_magnitude
        )


def wall_push(
    arm: TwoLinkArm,
    wall: Wall | ArrayLike,
    force_magnitude: float,
    elbow: str = "down",
    *,
    duration: float = 0.2,
    timestep: float = DEFAULT_TIMESTEP,
    contact_solref: tuple[float, float] | None = None,
    contact_solimp: Sequence[float] | None = WALL_SOLIMP,
    impratio: float = 100.0,
) -> WallPush:
    """The course's wall problem in MuJoCo: statics torques applied, the contact force read back.

    The arm starts at rest at the contact configuration of
    :func:`twolink.statics.wall_contact` (link 2 perpendicular to the wall,
    the tip on it), with the wall as a MuJoCo plane, and the motors apply the
    constant torques ``tau = J^T force_by_tip + g(q)`` that, by the statics, push with
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
    wall : Wall or array_like, shape (2, 2)
        The wall, or two points on it (see :func:`twolink.statics.as_wall`).
    force_magnitude : float
        The normal force the statics torques are computed for, N (>= 0).
    elbow : {"down", "up", "auto"}
        The branch of :func:`twolink.statics.wall_contact`: ``"down"``
        (``q2 >= 0``) or ``"up"`` (``q2 <= 0``); ``"auto"`` is ``"down"``.
        A wall at the edge of the reach has one contact configuration
        (stretched or folded), on both branches: every word gives it.
        ``"both"`` is refused (one simulation is one configuration).
    duration : float
        Simulated time, seconds (> 0); at most :data:`MAX_STEPS` steps.
    timestep : float
        MuJoCo's step, seconds.
    contact_solref : pair of float, optional
        ``(timeconst, dampratio)``; default ``(2 timestep, 1)`` (the stiffest
        MuJoCo allows for the step, critically damped).
    contact_solimp : sequence of float or None
        MuJoCo's ``solimp``; default :data:`WALL_SOLIMP` (None: MuJoCo's own).
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
        For bad arguments.
    SimulationError
        When MuJoCo's state blows up.
    ImportError
        Without MuJoCo installed.

    Examples
    --------
    The course's wall ``x + y = 4``, the 2 m arm, 500 N:

    >>> from twolink import arms, engine
    >>> push = engine.wall_push(arms.two_metre, [[4.0, 0.0], [0.0, 4.0]], 500.0, elbow="up")
    >>> round(push.force_by_tip_normal, 2), bool(push.relative_error < 1e-4), bool(push.penetration < 1e-4)
    (500.0, True, True)
    """
    mujoco = _mujoco("wall_push")
    elbow = check_elbow(
        elbow, ("down", "up", "auto"), why="wall_push simulates one configuration"
    )
    the_wall = as_wall(wall)
    duration = as_time_span(duration, "duration (s)")
    timestep = as_time_span(timestep, "timestep (s)")
    impratio = as_finite_scalar(impratio, "impratio", minimum=1.0)
    n_steps = int(round(duration / timestep))
    if not 10 <= n_steps <= MAX_STEPS:
        raise ValueError(
            f"duration / timestep gives {n_steps} steps; allowed 10 to {MAX_STEPS}"
        )
    contact = wall_contact(arm, the_wall, force_magnitude, include_gravity=True)
    row = (
        contact.branch("down" if elbow == "auto" else elbow)
        if len(contact.elbow) > 1
        else 0
    )
    q_contact, tau = contact.q[row], contact.tau[row]
    solref = (2.0 * timestep, 1.0) if contact_solref is None else contact_solref
    model = build_model(
        arm,
        wall=the_wall,
        timestep=timestep,
        contact_solref=solref,
        contact_solimp=contact_solimp,
    )
    model.opt.impratio = impratio
    data = mujoco.MjData(model)
    data.qpos[:] = q_contact
    data.ctrl[:] = tau
    wall_id = model.geom("wall").id
    buffer = np.zeros(6)
    normal = the_wall.into_wall()
    last_tenth = n_steps - max(1, n_steps // 10)
    mujoco.mj_step(model, data, last_tenth)
    _check_state(data, last_tenth * timestep, "engine.wall_push")
    mujoco.mj_forward(model, data)
    normal_before = float(_force_by_tip(mujoco, model, data, wall_id, buffer) @ normal)
    mujoco.mj_step(model, data, n_steps - last_tenth)
    _check_state(data, n_steps * timestep, "engine.wall_push")
    mujoco.mj_forward(model, data)
    force_by_tip = _force_by_tip(mujoco, model, data, wall_id, buffer)
    q_settled = data.qpos.copy()
    return WallPush(
        arm=arm,
        wall=the_wall,
        elbow=contact.elbow[row],
        force_magnitude=contact.force_magnitude,
        q_contact=q_contact.copy(),
        tau=tau.copy(),
        q_settled=q_settled,
        qd_settled=data.qvel.copy(),
        force_by_tip=force_by_tip,
        penetration=float((arm.fk(q_settled) - the_wall.point) @ normal),
        normal_drift=abs(float(force_by_tip @ normal) - normal_before),
        steps=n_steps,
    )
