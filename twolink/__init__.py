"""twolink: the planar two-link (2R) robot arm, for teaching and for use.

Conventions: DH / relative joint angles (``q2`` measured from link 1),
radians, SI units.  Start with :class:`TwoLinkArm` and the presets in
:mod:`twolink.arms`; inverse kinematics lives in :mod:`twolink.ik`.

``import twolink`` loads numpy and no other library: scipy is imported by the
first call that needs it (``ik.minimize``, ``simulate``, ...) and sympy by
:mod:`twolink.symbolic`.  The library draws nothing: the course's figures,
explorers and exercises are the course kit, :mod:`twolink_course`, which
imports this package (never the reverse).

Examples
--------
>>> import numpy as np
>>> import twolink
>>> arm = twolink.TwoLinkArm(l1=2.0, l2=2.0)
>>> q = twolink.ik.closed_form(arm, [3.0, 1.0], elbow="down").q
>>> arm.fk(q).round(12)
array([3., 1.])
"""

from . import (
    arcs,
    arms,
    contact,
    controllers,
    dynamics,
    ik,
    linearization,
    references,
    statics,
    stiffness,
    trajectory,
    velocity,
    workspace,
)
from .arm import TwoLinkArm
from .controllers import (
    CartesianSpring,
    ComputedTorque,
    Impedance,
    JointPD,
)
from .conventions import to_absolute, to_relative, wrap_angle
from .errors import SingularityError, UnreachableError
from .linearization import linearize
from .references import JointReference
from .simulation import SimulationError, SimulationResult, simulate
from .statics import Wall, WallContact, wall_contact

__version__ = "0.1.0"

__all__ = [
    "TwoLinkArm",
    "arms",
    "ik",
    "to_absolute",
    "to_relative",
    "wrap_angle",
    "UnreachableError",
    "SingularityError",
    "velocity",
    "statics",
    "Wall",
    "WallContact",
    "wall_contact",
    "dynamics",
    "simulate",
    "SimulationResult",
    "SimulationError",
    "arcs",
    "workspace",
    "trajectory",
    "controllers",
    "references",
    "contact",
    "linearization",
    "stiffness",
    "CartesianSpring",
    "Impedance",
    "JointPD",
    "ComputedTorque",
    "JointReference",
    "linearize",
]
