"""Model files of a :class:`~twolink.TwoLinkArm`: MJCF for MuJoCo, URDF for ROS and friends.

Both functions return text (nothing here imports MuJoCo).  The models hold
exactly the arm twolink simulates, so that an engine reading them computes
the same dynamics (the tests check MuJoCo's joint accelerations against
:func:`twolink.dynamics.forward_dynamics` to 1e-9):

* the arm moves in the x-y plane; two hinges about z: joint ``q1`` at the
  base (at height ``arm.d`` on z), joint ``q2`` at the elbow, angles in
  radians in twolink's relative (DH) convention;
* each link is a rod with its centre of mass at mid-link, its mass and its
  inertia ``arm.inertias`` about the centre of mass about z (and y); the
  inertia about the rod's own axis (x), which no planar motion feels but
  engines need positive, is derived from the link's shape in the file, a
  solid cylinder of radius ``l / 100``: ``m (l / 100)^2 / 2``, at most the
  inertia about z (so the three satisfy the triangle inequality however a
  custom ``I1``, ``I2`` is chosen);
* gravity of magnitude ``arm.g`` along -y (a vertical arm; ``g = 0`` is a
  horizontal arm).  MJCF carries it; URDF has no gravity (see
  :func:`to_urdf`);
* motors on both joints, gear 1: motor ``k`` applies the torque ``tau_k``
  (N m) of ``M qdd + C qd + g = tau``, with no control limits;
* no joint damping, armature, friction or springs;
* joint limits as joint ranges (the relative convention), or, for an arm with
  ``limit_convention="absolute"``, a range on joint 1 and a range on the fixed tendon
  ``q1 + q2`` (the absolute angle of link 2).

Names in the models: bodies ``link1``, ``link2``; joints ``q1``, ``q2``;
motors ``tau1``, ``tau2``; site ``tip`` at the tip (MJCF); geoms ``tip``
(a small sphere) and ``wall`` (MJCF).

Examples
--------
>>> from twolink import TwoLinkArm, export
>>> mjcf = export.to_mjcf(TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2))
>>> '<joint name="q2" type="hinge" axis="0 0 1" limited="false"/>' in mjcf
True
>>> '<option timestep="0.0001" integrator="RK4" gravity="0 -9.81 0"/>' in mjcf
True
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ._validate import (
    as_finite_scalar,
    as_flag,
    as_length,
    as_time_span,
    real_array,
    require_arm,
)
from .statics import Wall, as_wall

if TYPE_CHECKING:
    from .arm import TwoLinkArm

__all__ = ["to_mjcf", "to_urdf", "INTEGRATORS"]

#: MuJoCo's integrators (``<option integrator=...>``).
INTEGRATORS = ("Euler", "RK4", "implicit", "implicitfast")

#: A link's radius in the models, as a fraction of its length: the capsule or cylinder drawn,
#: and the solid cylinder its axial inertia is derived from.
RADIUS_RATIO = 1e-2

#: MuJoCo's smallest mass and inertia of a moving body (its ``mjMINVAL``): below it MuJoCo
#: refuses the model.
MUJOCO_MINIMUM = 1e-15


def _num(value: float) -> str:
    """A float written so that it reads back exactly (shortest round-trip repr)."""
    value = float(value)
    if value == 0.0:
        return "0"
    return repr(value)


def _nums(*values: float) -> str:
    return " ".join(_num(v) for v in values)


def _link_inertias(
    arm: TwoLinkArm, who: str, minimum: float = 0.0
) -> list[tuple[float, float, float]]:
    """``[(mass, axial inertia, inertia), ...]`` of both links, each above ``minimum`` (engines refuse less).

    The axial inertia (about the rod's own axis) is that of a solid cylinder
    of radius ``RADIUS_RATIO * l``, ``m r^2 / 2``, at most the inertia about
    z: a body symmetric about its axis has an axial inertia of at most
    twice its transverse one (the triangle inequality engines check).
    """
    links = []
    for k, (length, mass, inertia) in enumerate(
        zip((arm.l1, arm.l2), (arm.m1, arm.m2), arm.inertias), start=1
    ):
        radius = RADIUS_RATIO * length
        axial = min(mass * radius * radius / 2.0, inertia)
        if not (mass > minimum and axial > minimum):
            smallest = (
                "exactly 0" if minimum == 0.0 else f"{minimum:.0e} (MuJoCo's mjMINVAL)"
            )
            raise ValueError(
                f"{who}: link {k} has mass {mass:.6g} kg and inertias {axial:.6g} (about its own axis, "
                f"m (l/100)^2 / 2 for l{k} = {length:.6g} m) and {inertia:.6g} kg m^2; the engine needs each "
                f"above {smallest}: give m{k} > 0 (and I{k} > 0 or None for a uniform rod), or, for a "
                "link this light and small, choose units in which its numbers are larger (grams, "
                "centimetres)"
            )
        links.append((mass, axial, inertia))
    return links


def _xml_name(value: object, name: str) -> str:
    """``value`` as a name in XML: a non-empty string of printable characters, without < > & or quotes."""
    if (
        not isinstance(value, str)
        or not value
        or not value.isprintable()
        or any(c in value for c in "<>&\"'")
    ):
        raise ValueError(
            f"{name} must be a non-empty string of printable characters without <, >, &, \" or '; got {value!r}"
        )
    return value


def _numbers(value: object, name: str) -> tuple[float, ...]:
    """``value`` as a tuple of finite floats from a 1-D sequence of real numbers (a string is no sequence of numbers)."""
    numbers = real_array(value, name, "None or a sequence of real numbers")
    if numbers.ndim != 1:
        raise ValueError(
            f"{name} must be None or a sequence of real numbers; got shape {numbers.shape}"
        )
    if not np.all(np.isfinite(numbers)):
        raise ValueError(f"{name} must be finite numbers; got {numbers.tolist()}")
    return tuple(numbers.tolist())


def to_mjcf(
    arm: TwoLinkArm,
    *,
    wall: Wall | ArrayLike | None = None,
    tip_site: bool = True,
    tip_radius: float | None = None,
    timestep: float = 1e-4,
    integrator: str = "RK4",
    contact_solref: Iterable[float] | None = None,
    contact_solimp: Iterable[float] | None = None,
    model_name: str = "twolink",
) -> str:
    """An MJCF model (MuJoCo's XML) of the arm, optionally with a wall.

    The model holds the arm's exact dynamics (see the module's notes): for
    the same ``q``, ``qd`` and motor torques ``tau`` (``data.ctrl``),
    MuJoCo's ``mj_forward`` gives ``data.qacc`` equal to
    ``arm.forward_dynamics(q, qd, tau)``.  Read it with
    ``mujoco.MjModel.from_xml_string(text)``, or use
    :func:`twolink.engine.build_model`.

    Contacts: the links never collide with anything.  The only geom that can
    touch something is a small sphere at the tip (geom ``tip``, ``contype=1``,
    ``conaffinity=0``), and the only thing it can touch is the wall
    (``contype=0``, ``conaffinity=1``), so the one possible contact is tip
    against wall.

    Parameters
    ----------
    arm : TwoLinkArm
        Each link needs a mass and inertias (about its axis, ``m (l/100)^2
        / 2`` at most its inertia about z, and about z) above MuJoCo's
        smallest, 1e-15 (it refuses lighter moving bodies): a link of 1 mm
        and 1 g has 5e-14 kg m^2 about its axis; one much smaller is
        refused with an error that says so (choose units in which its
        numbers are larger).
    wall : Wall or array_like of shape (2, 2), optional
        A straight wall in the arm's plane (:class:`twolink.statics.Wall`,
        or two points on it).  It becomes an infinite plane geom ``wall``
        whose free side faces the base (the side of
        :meth:`~twolink.statics.Wall.into_wall`'s opposite); the plane is put
        ``tip_radius`` behind the line, so that the tip sphere touches it when
        the tip point (the sphere's centre, twolink's tip) reaches the line.
    tip_site : bool
        Add the site ``tip`` at the tip (for reading the tip position from
        ``data.site_xpos``).
    tip_radius : float, optional
        Radius of the tip's contact sphere, metres (> 0); default
        ``(l1 + l2) / 1000``.
    timestep : float
        Simulation step, seconds (> 0).
    integrator : {"RK4", "Euler", "implicit", "implicitfast"}
        MuJoCo's integrator.  RK4 (default) is the fixed-step 4th-order
        Runge-Kutta method; the others add MuJoCo's implicit treatment of
        damping, which this model does not have.
    contact_solref, contact_solimp : iterable of float, optional
        The wall's soft-contact parameters (MuJoCo's ``solref``, 2 numbers,
        and ``solimp``, 3 or 5 numbers); ``None`` keeps MuJoCo's defaults
        (``solref = (0.02, 1)``: a time constant of 20 ms; ``solimp = (0.9,
        0.95, 0.001, 0.5, 2)``).  See :func:`twolink.engine.wall_push` for
        what they do to a contact force.
    model_name : str
        The model's name: printable characters, without ``<``, ``>``,
        ``&`` or quotes (a control character cannot be written in XML).

    Returns
    -------
    str
        The MJCF text.

    Raises
    ------
    ValueError
        For an argument that is not what is described above, or a link
        without mass or inertia.
    twolink.errors.InputTypeError
        When ``arm`` is not an arm (a ``TypeError`` and a ``ValueError``).

    Examples
    --------
    The 2 m arm of the course, with the wall ``x + y = 4``:

    >>> from twolink import arms, export
    >>> mjcf = export.to_mjcf(arms.two_metre, wall=[[4.0, 0.0], [0.0, 4.0]])
    >>> print([line.strip() for line in mjcf.splitlines() if "inertial" in line][0])
    <inertial pos="1.0 0 0" mass="1.0" diaginertia="0.0002 0.3333333333333333 0.3333333333333333"/>
    >>> print([line.strip() for line in mjcf.splitlines() if 'name="wall"' in line][0])
    <geom name="wall" type="plane" pos="2.002828427124746 2.002828427124746 0" zaxis="-0.7071067811865475 -0.7071067811865475 0" size="0 0 0.1" contype="0" conaffinity="1" rgba="0.6 0.6 0.6 0.5"/>
    >>> export.to_mjcf(arms.two_metre, integrator="rk4")
    Traceback (most recent call last):
    ...
    ValueError: integrator must be one of ('Euler', 'RK4', 'implicit', 'implicitfast'); got 'rk4'
    """
    require_arm(arm)
    (m1, axial_1, inertia_1), (m2, axial_2, inertia_2) = _link_inertias(
        arm, "to_mjcf", MUJOCO_MINIMUM
    )
    try:
        wall_line = None if wall is None else as_wall(wall)
    except (
        ValueError
    ) as error:  # the same refusal, saying that None (no wall) is allowed here too
        raise ValueError(
            f"wall must be None (no wall) or {str(error).removeprefix('wall must be ')}"
        ) from None
    reach = arm.l1 + arm.l2
    tip_radius = reach / 1000.0 if tip_radius is None else tip_radius
    tip_radius = as_length(tip_radius, "tip_radius (m)")
    timestep = as_time_span(timestep, "timestep (s)")
    if not isinstance(integrator, str) or integrator not in INTEGRATORS:
        raise ValueError(f"integrator must be one of {INTEGRATORS}; got {integrator!r}")
    tip_site = as_flag(tip_site, "tip_site")
    contact = ""
    if contact_solref is not None:
        solref = _numbers(contact_solref, "contact_solref")
        if len(solref) != 2:
            raise ValueError(
                f"contact_solref must be 2 numbers (timeconst, dampratio); got {solref}"
            )
        contact += f' solref="{_nums(*solref)}"'
    if contact_solimp is not None:
        solimp = _numbers(contact_solimp, "contact_solimp")
        if len(solimp) not in (3, 5):
            raise ValueError(
                f"contact_solimp must be 3 or 5 numbers (dmin, dmax, width[, midpoint, power]); got {solimp}"
            )
        contact += f' solimp="{_nums(*solimp)}"'
    model_name = _xml_name(model_name, "model_name")

    joint_ranges = ['limited="false"', 'limited="false"']
    tendon = ""
    if arm.q_min is not None and arm.q_max is not None:  # arm.has_limits
        low, high = arm.q_min, arm.q_max
        joint_ranges[0] = f'limited="true" range="{_nums(low[0], high[0])}"'
        if arm.limit_convention == "relative":
            joint_ranges[1] = f'limited="true" range="{_nums(low[1], high[1])}"'
        else:  # q1 + q2, the absolute angle of link 2, is bounded: a fixed tendon with a range
            tendon = (
                "  <tendon>\n"
                f'    <fixed name="q1_plus_q2" limited="true" range="{_nums(low[1], high[1])}">\n'
                '      <joint joint="q1" coef="1"/>\n'
                '      <joint joint="q2" coef="1"/>\n'
                "    </fixed>\n"
                "  </tendon>\n"
            )
    rod_radius = (RADIUS_RATIO * arm.l1, RADIUS_RATIO * arm.l2)
    site = (
        f'        <site name="tip" pos="{_num(arm.l2)} 0 0" size="{_num(2 * tip_radius)}"/>\n'
        if tip_site
        else ""
    )
    wall_geom = ""
    if wall_line is not None:
        normal = wall_line.into_wall()  # from the base's side into the wall
        foot = float(wall_line.point @ normal) * normal + tip_radius * normal
        wall_geom = (
            f'    <geom name="wall" type="plane" pos="{_nums(foot[0], foot[1], arm.d)}" '
            f'zaxis="{_nums(-normal[0], -normal[1], 0.0)}" size="0 0 {_num(reach / 40.0)}" '
            f'contype="0" conaffinity="1"{contact} rgba="0.6 0.6 0.6 0.5"/>\n'
        )

    def inertial(length: float, mass: float, axial: float, inertia: float) -> str:
        return (
            f'<inertial pos="{_num(length / 2.0)} 0 0" mass="{_num(mass)}" '
            f'diaginertia="{_nums(axial, inertia, inertia)}"/>'
        )

    return (
        f'<mujoco model="{model_name}">\n'
        '  <compiler angle="radian" inertiafromgeom="false" autolimits="false"/>\n'
        f'  <option timestep="{_num(timestep)}" integrator="{integrator}" gravity="{_nums(0.0, -arm.g, 0.0)}"/>\n'
        "  <worldbody>\n"
        f'    <body name="link1" pos="{_nums(0.0, 0.0, arm.d)}">\n'
        f'      <joint name="q1" type="hinge" axis="0 0 1" {joint_ranges[0]}/>\n'
        f"      {inertial(arm.l1, m1, axial_1, inertia_1)}\n"
        f'      <geom name="link1" type="capsule" pos="{_num(arm.l1 / 2.0)} 0 0" zaxis="1 0 0" '
        f'size="{_nums(rod_radius[0], arm.l1 / 2.0)}" '
        'contype="0" conaffinity="0" rgba="0.2 0.4 0.8 1"/>\n'
        f'      <body name="link2" pos="{_num(arm.l1)} 0 0">\n'
        f'        <joint name="q2" type="hinge" axis="0 0 1" {joint_ranges[1]}/>\n'
        f"        {inertial(arm.l2, m2, axial_2, inertia_2)}\n"
        f'        <geom name="link2" type="capsule" pos="{_num(arm.l2 / 2.0)} 0 0" zaxis="1 0 0" '
        f'size="{_nums(rod_radius[1], arm.l2 / 2.0)}" '
        'contype="0" conaffinity="0" rgba="0.8 0.4 0.2 1"/>\n'
        f'        <geom name="tip" type="sphere" pos="{_num(arm.l2)} 0 0" size="{_num(tip_radius)}" '
        'contype="1" conaffinity="0" rgba="0.1 0.1 0.1 1"/>\n'
        f"{site}"
        "      </body>\n"
        "    </body>\n"
        f"{wall_geom}"
        "  </worldbody>\n"
        f"{tendon}"
        "  <actuator>\n"
        '    <motor name="tau1" joint="q1" gear="1" ctrllimited="false"/>\n'
        '    <motor name="tau2" joint="q2" gear="1" ctrllimited="false"/>\n'
        "  </actuator>\n"
        "</mujoco>\n"
    )


def to_urdf(
    arm: TwoLinkArm,
    *,
    z_up: bool = False,
    effort_limit: float = 1e6,
    velocity_limit: float = 1e6,
    robot_name: str = "twolink",
) -> str:
    """A URDF model of the arm, for ROS, roboticstoolbox, pinocchio or MuJoCo.

    Links ``base`` (fixed, massless), ``link1``, ``link2`` and ``tip`` (a
    massless frame at the tip, fixed to ``link2``); joints ``q1`` and ``q2``,
    revolute about z (``continuous`` when the arm has no limits), with the
    arm's relative joint limits as ``<limit lower upper>``.  Inertias are
    given about each link's centre of mass at mid-link, as in the module's
    notes.  Visual and collision elements: the cylinder of radius ``l / 100``
    the axial inertia is derived from.

    **Gravity is not part of a URDF**: the simulator sets it.  With the
    default ``z_up=False`` the arm moves in the x-y plane and twolink's
    gravity (along -y) must be set in the simulator, e.g. in MuJoCo
    ``model.opt.gravity[:] = (0, -arm.g, 0)`` after loading (MuJoCo's own
    default, -9.81 along z, is perpendicular to the arm's plane: a
    horizontal arm).  With ``z_up=True`` the base is turned about x by
    +90 deg, so the arm moves in the world's x-z plane with its y axis along
    world z: the usual world gravity ``(0, 0, -g)`` of ROS and MuJoCo is
    then twolink's vertical arm with ``g`` its magnitude.

    MuJoCo reads the result as it is (``mujoco.MjModel.from_xml_string``);
    it needs no ``<mujoco>`` extension element.  Its URDF import drops
    visual elements by default (``<compiler discardvisual="true">``) and
    fuses the massless ``tip`` frame into ``link2``.

    Parameters
    ----------
    arm : TwoLinkArm
        Its links need mass and inertia (> 0).  Its limits must be relative
        (URDF limits are per joint; an arm with
        ``limit_convention="absolute"`` bounds ``q1 + q2``, which URDF cannot say).
    z_up : bool
        Turn the arm's plane upright as described above.
    effort_limit, velocity_limit : float
        The ``effort`` (N m) and ``velocity`` (rad/s) of each ``<limit>``
        element, which URDF requires and twolink does not have: large
        numbers by default.  Only written for limited joints.
    robot_name : str
        The robot's name: printable characters, without ``<``, ``>``,
        ``&`` or quotes.

    Returns
    -------
    str
        The URDF text.

    Raises
    ------
    ValueError
        For an arm with absolute limits or other bad arguments.
    twolink.errors.InputTypeError
        When ``arm`` is not an arm (a ``TypeError`` and a ``ValueError``).

    Examples
    --------
    >>> from twolink import arms, export
    >>> urdf = export.to_urdf(arms.ten)
    >>> print([line.strip() for line in urdf.splitlines() if "<limit" in line][1])
    <limit lower="-1.5707963267948966" upper="1.5707963267948966" effort="1000000.0" velocity="1000000.0"/>
    >>> export.to_urdf(arms.two_metre_limited)
    Traceback (most recent call last):
    ...
    ValueError: to_urdf: this arm's limits bound the absolute angles (q1, q1 + q2), which URDF's per-joint limits cannot express; use an arm with relative limits (or none) and enforce the absolute ones elsewhere
    """
    require_arm(arm)
    (m1, axial_1, inertia_1), (m2, axial_2, inertia_2) = _link_inertias(arm, "to_urdf")
    if arm.has_limits and arm.limit_convention != "relative":
        raise ValueError(
            "to_urdf: this arm's limits bound the absolute angles (q1, q1 + q2), which URDF's per-joint "
            "limits cannot express; use an arm with relative limits (or none) and enforce the absolute ones "
            "elsewhere"
        )
    z_up = as_flag(z_up, "z_up")
    effort_limit = as_finite_scalar(
        effort_limit, "effort_limit (N m)", minimum=0.0, strictly=True
    )
    velocity_limit = as_finite_scalar(
        velocity_limit, "velocity_limit (rad/s)", minimum=0.0, strictly=True
    )
    robot_name = _xml_name(robot_name, "robot_name")

    def link(
        name: str, length: float, mass: float, axial: float, inertia: float
    ) -> str:
        # the solid cylinder the axial inertia is derived from, along x (a URDF cylinder is along z)
        cylinder = f'<geometry><cylinder radius="{_num(RADIUS_RATIO * length)}" length="{_num(length)}"/></geometry>'
        centre = f'<origin xyz="{_num(length / 2.0)} 0 0" rpy="0 0 0"/>'
        along_x = (
            f'<origin xyz="{_num(length / 2.0)} 0 0" rpy="0 {_num(np.pi / 2.0)} 0"/>'
        )
        return (
            f'  <link name="{name}">\n'
            "    <inertial>\n"
            f"      {centre}\n"
            f'      <mass value="{_num(mass)}"/>\n'
            f'      <inertia ixx="{_num(axial)}" ixy="0" ixz="0" '
            f'iyy="{_num(inertia)}" iyz="0" izz="{_num(inertia)}"/>\n'
            "    </inertial>\n"
            f"    <visual>{along_x}{cylinder}</visual>\n"
            f"    <collision>{along_x}{cylinder}</collision>\n"
            "  </link>\n"
        )

    def joint(name: str, parent: str, child: str, xyz: str, rpy: str, k: int) -> str:
        if arm.q_min is not None and arm.q_max is not None:  # arm.has_limits
            kind = "revolute"
            limit = (
                f'    <limit lower="{_num(arm.q_min[k])}" upper="{_num(arm.q_max[k])}" '
                f'effort="{_num(effort_limit)}" velocity="{_num(velocity_limit)}"/>\n'
            )
        else:
            kind, limit = "continuous", ""
        return (
            f'  <joint name="{name}" type="{kind}">\n'
            f'    <parent link="{parent}"/>\n'
            f'    <child link="{child}"/>\n'
            f'    <origin xyz="{xyz}" rpy="{rpy}"/>\n'
            '    <axis xyz="0 0 1"/>\n'
            f"{limit}"
            "  </joint>\n"
        )

    base_rpy = f"{_num(np.pi / 2.0)} 0 0" if z_up else "0 0 0"
    base_xyz = f"0 {_num(-arm.d)} 0" if z_up else f"0 0 {_num(arm.d)}"
    return (
        '<?xml version="1.0"?>\n'
        f'<robot name="{robot_name}">\n'
        '  <link name="base"/>\n'
        f"{joint('q1', 'base', 'link1', base_xyz, base_rpy, 0)}"
        f"{link('link1', arm.l1, m1, axial_1, inertia_1)}"
        f"{joint('q2', 'link1', 'link2', f'{_num(arm.l1)} 0 0', '0 0 0', 1)}"
        f"{link('link2', arm.l2, m2, axial_2, inertia_2)}"
        '  <joint name="tip" type="fixed">\n'
        '    <parent link="link2"/>\n'
        '    <child link="tip"/>\n'
        f'    <origin xyz="{_num(arm.l2)} 0 0" rpy="0 0 0"/>\n'
        "  </joint>\n"
        '  <link name="tip"/>\n'
        "</robot>\n"
    )
