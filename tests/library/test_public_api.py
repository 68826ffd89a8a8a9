"""The public API, walked: every object behaves like a value, every argument refuses junk in the package's words.

The walk finds every public function, class and method (the ``__all__`` of
every public module of ``twolink``), so that one added later must join the
registries below (:data:`CALLS`: a valid call of each; :data:`EXAMPLES`: an
instance of each class) or the exemptions, with its reason.  Then:

- every public object pickles (a parameter sweep sends controllers, paths
  and results through :mod:`multiprocessing`) and compares equal to its
  copy, its deep copy and its unpickled self, and hashes alike (or refuses
  a hash with a message saying why);
- every argument of every call, given a generated bad value (a string, a
  NaN, an infinity, a time delta, a complex number, a boolean, ``None``
  where it is not allowed, an object, a wrongly nested list), raises a
  ``ValueError`` or ``TypeError`` raised by the package itself (its own
  frame last in the traceback: never numpy's, scipy's or Python's words)
  whose message names the argument.
"""

import copy
import importlib
import inspect
import pathlib
import pickle
import pkgutil
import traceback

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import twolink
import twolink.engine
import twolink.export
import twolink.symbolic
from twolink import (
    TwoLinkArm,
    arcs,
    arms,
    contact,
    controllers,
    conventions,
    dh,
    dynamics,
    ik,
    kinematics,
    linearization,
    references,
    simulation,
    statics,
    stiffness,
    trajectory,
    velocity,
    workspace,
)
from twolink import symbolic as sym

PACKAGE = pathlib.Path(twolink.__file__).resolve().parent

HAS_MUJOCO = importlib.util.find_spec("mujoco") is not None
HAS_CONTROL = importlib.util.find_spec("control") is not None


def _public_objects():
    """``{qualified name: object}`` of every public function and class, found through ``__all__``."""
    modules = [twolink]
    for info in pkgutil.walk_packages(twolink.__path__, "twolink."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        modules.append(importlib.import_module(info.name))
    found = {}
    for module in modules:
        for name in getattr(module, "__all__", []):
            value = getattr(module, name)
            if inspect.ismodule(value) or not callable(value):
                continue
            home = getattr(value, "__module__", module.__name__)
            qualified = f"{home}.{getattr(value, '__qualname__', name)}"
            found.setdefault(qualified, value)
    return found


PUBLIC = _public_objects()


def _public_methods():
    """``{qualified name: function}`` of the public methods (and ``__call__``) of the public classes.

    A class's own, and those it inherits from a private base of the package
    (``LinePath.at`` from ``_TimedPath``); not those of a public base, walked there.
    """
    found = {}
    for qualified, value in PUBLIC.items():
        if not inspect.isclass(value):
            continue
        for klass in value.__mro__:
            if not klass.__module__.startswith("twolink"):
                continue
            if klass is not value and not klass.__name__.startswith("_"):
                continue
            for attribute, member in vars(klass).items():
                function = (
                    member.__func__
                    if isinstance(member, (classmethod, staticmethod))
                    else member
                )
                if not inspect.isfunction(function):
                    continue
                if attribute.startswith("_") and attribute != "__call__":
                    continue
                found.setdefault(f"{qualified}.{attribute}", function)
    return found


METHODS = _public_methods()

# ----------------------------------------------------------------------------- examples
ARM = arms.two_metre
LIMITED = arms.ten
Q = [0.3, 1.1]
QD = [0.2, -0.4]
P = ARM.fk(Q).tolist()
WALL = statics.Wall([3.0, 0.0], [1.0, 0.0])
LINE = trajectory.LinePath([3.0, 0.0], [3.0, 1.0], duration=1.0)
CIRCLE = trajectory.CirclePath([2.5, 1.0], 0.5, duration=1.0)
MOTION = trajectory.ik_trajectory(ARM, LINE, n=6)
REFERENCE = MOTION.joint_reference()
SPRING = controllers.CartesianSpring(ARM, 600.0, [3.0, 1.0])
IMPEDANCE = controllers.Impedance(ARM, 600.0, 50.0, [3.0, 1.0])
PD = controllers.JointPD(ARM, 100.0, 20.0, Q)
COMPUTED = controllers.ComputedTorque(ARM, 100.0, 20.0, REFERENCE)
SPRING_WALL = contact.SpringWall(WALL, 1e4, 10.0)
PUSHED = contact.TipForce(ARM, IMPEDANCE, SPRING_WALL)
RUN = simulation.simulate(ARM, Q, QD, 0.05, torque=PD)
QUICK = simulation.simulate_quick(ARM, Q, QD, [0.0, 0.05])
ARC = arcs.Arc((0.0, 0.0), 2.0, 0.0, np.pi / 2, "quarter", "reach")
ARCS = workspace.boundary_arcs(LIMITED)
TABLE = workspace.BranchTable(LIMITED, [[12.5, 12.5], [15.0, 1.0]])
ELLIPSE = velocity.velocity_ellipse(ARM, Q)
CONTACT = statics.wall_contact(ARM, WALL, 10.0)
RESULT = ik.closed_form(ARM, P)
BATCH_RESULT = ik.closed_form(ARM, [P, P], elbow="both")
EQUATIONS = sym.equations_of_motion("relative")
NUMERIC = sym.lambdify_dynamics("relative")
DH_ROW = dh.dh_table(ARM)[0]
SYMBOLS = sym.dynamics_symbols()
COORDINATES = [SYMBOLS["q1"], SYMBOLS["q2"]]
RATES = [SYMBOLS["qd1"], SYMBOLS["qd2"]]
ACCELERATIONS = [SYMBOLS["qdd1"], SYMBOLS["qdd2"]]


def _lazy_engine():
    from twolink import engine

    return engine


#: An instance of every public class (a zero-argument function making it).
EXAMPLES = {
    "twolink.arcs.Arc": lambda: ARC,
    "twolink.arm.TwoLinkArm": lambda: LIMITED,
    "twolink.contact.SpringWall": lambda: SPRING_WALL,
    "twolink.contact.TipForce": lambda: PUSHED,
    "twolink.controllers.CartesianSpring": lambda: SPRING,
    "twolink.controllers.ComputedTorque": lambda: COMPUTED,
    "twolink.controllers.Impedance": lambda: IMPEDANCE,
    "twolink.controllers.JointPD": lambda: PD,
    "twolink.dh.DHRow": lambda: DH_ROW,
    "twolink.engine.EngineResult": lambda: _lazy_engine().simulate_in_mujoco(
        ARM, Q, QD, 0.01, PD, sample_every=10
    ),
    "twolink.engine.WallPush": lambda: _lazy_engine().wall_push(
        ARM, [[4.0, 0.0], [0.0, 4.0]], 100.0, duration=0.01
    ),
    "twolink.errors.InputTypeError": lambda: twolink.errors.InputTypeError("q"),
    "twolink.errors.SimulationError": lambda: twolink.errors.SimulationError("t"),
    "twolink.errors.SingularityError": lambda: twolink.errors.SingularityError("q"),
    "twolink.errors.UnreachableError": lambda: twolink.errors.UnreachableError("p"),
    "twolink.ik.result.IKResult": lambda: BATCH_RESULT,
    "twolink.references.JointReference": lambda: REFERENCE,
    "twolink.simulation.SimulationResult": lambda: RUN,
    "twolink.statics.Wall": lambda: WALL,
    "twolink.statics.WallContact": lambda: CONTACT,
    "twolink.symbolic.dynamics.EquationsOfMotion": lambda: EQUATIONS,
    "twolink.symbolic.dynamics.NumericDynamics": lambda: NUMERIC,
    "twolink.trajectory.CirclePath": lambda: CIRCLE,
    "twolink.trajectory.JointTrajectory": lambda: MOTION,
    "twolink.trajectory.LinePath": lambda: LINE,
    "twolink.velocity.Ellipse": lambda: ELLIPSE,
    "twolink.workspace.BranchTable": lambda: TABLE,
}

#: More instances whose values differ in kind from the ones above (references made otherwise, ...).
MORE_EXAMPLES = {
    "a constant reference": lambda: references.JointReference.constant(Q),
    "a spline reference": lambda: references.JointReference.from_samples(
        [0.0, 0.5, 1.0, 1.5], [Q, QD, Q, QD]
    ),
    "JointPD of a trajectory": lambda: controllers.JointPD(ARM, 10.0, 1.0, REFERENCE),
    "a quick run": lambda: QUICK,
    "one IK result": lambda: RESULT,
    "a run with events": lambda: simulation.simulate(
        ARM, Q, QD, 0.05, events=lambda t, y: y[1] - 10.0
    ),
    "a resolved-rate motion": lambda: trajectory.resolved_rate_trajectory(
        ARM, LINE, n=5
    ),
}


def _example(name):
    if name.startswith("twolink.engine.") and not HAS_MUJOCO:
        pytest.skip("MuJoCo is not installed")
    return EXAMPLES[name]()


def test_every_public_class_has_an_example():
    classes = {name for name, value in PUBLIC.items() if inspect.isclass(value)}
    assert classes == set(EXAMPLES)


def _values():
    return sorted(EXAMPLES) + sorted(MORE_EXAMPLES)


def _make(name):
    return _example(name) if name in EXAMPLES else MORE_EXAMPLES[name]()


def _same(first, second):
    """Equal, for exceptions by their type and message (Python compares them by identity)."""
    if isinstance(first, BaseException):
        return type(first) is type(second) and first.args == second.args
    return first == second


@pytest.mark.parametrize("name", _values())
def test_every_public_object_pickles_and_equals_its_copies(name):
    value = _make(name)
    for other in (
        copy.copy(value),
        copy.deepcopy(value),
        pickle.loads(pickle.dumps(value)),
    ):
        assert _same(other, value) and _same(value, other)
        assert type(other) is type(value)
    # an exception is compared and hashed by identity, as every exception
    if isinstance(value, BaseException):
        return
    try:
        hashed = hash(value)
    except TypeError as error:  # unhashable on purpose: the message says why
        assert type(value).__name__ in str(error) and "hash" in str(error)
    else:
        assert hash(pickle.loads(pickle.dumps(value))) == hashed
        assert hash(copy.copy(value)) == hashed


@pytest.mark.parametrize(
    "name",
    [
        "twolink.controllers.CartesianSpring",
        "twolink.controllers.Impedance",
        "twolink.controllers.JointPD",
        "twolink.controllers.ComputedTorque",
        "twolink.contact.TipForce",
    ],
)
def test_an_unpickled_controller_gives_the_same_torques(name):
    controller = _make(name)
    again = pickle.loads(pickle.dumps(controller))
    for t in (0.0, 0.37, 2.0):
        assert np.array_equal(controller(t, Q, QD), again(t, Q, QD))


def test_values_that_differ_compare_unequal():
    assert statics.Wall([3.0, 0.0], [1.0, 0.0]) != statics.Wall([3.0, 0.0], [0.0, 1.0])
    assert RUN != QUICK
    assert controllers.JointPD(ARM, 10.0, 1.0, Q) != controllers.JointPD(
        ARM, 10.0, 2.0, Q
    )
    assert REFERENCE != references.JointReference.constant(Q)
    assert MOTION != trajectory.ik_trajectory(ARM, LINE, n=7)


def test_a_value_objects_arrays_cannot_change_under_it():
    for value in (WALL, RUN, MOTION, ELLIPSE, CONTACT, SPRING):
        arrays = [
            field
            for field in vars(value).values()
            if isinstance(field, np.ndarray) and field.size
        ]
        assert arrays, value
        for array in arrays:
            with pytest.raises(ValueError, match="read-only"):
                array.flat[0] = 1.0


# ----------------------------------------------------------------------------- bad arguments

#: A valid call of every public function and method: ``name -> (callable, keyword arguments)``.
CALLS = {
    # conventions
    "twolink.conventions.to_absolute": lambda: (conventions.to_absolute, {"q": Q}),
    "twolink.conventions.to_relative": lambda: (
        conventions.to_relative,
        {"q_abs": Q},
    ),
    "twolink.conventions.wrap_angle": lambda: (conventions.wrap_angle, {"angle": 7.0}),
    # dh
    "twolink.dh.dh_matrix": lambda: (
        dh.dh_matrix,
        {"theta": 0.3, "d": 0.1, "a": 2.0, "alpha": 0.0},
    ),
    "twolink.dh.dh_table": lambda: (dh.dh_table, {"arm": ARM}),
    "twolink.dh.geometric_jacobian": lambda: (
        dh.geometric_jacobian,
        {"arm": ARM, "q": Q},
    ),
    "twolink.dh.transforms": lambda: (dh.transforms, {"arm": ARM, "q": Q}),
    # kinematics
    "twolink.kinematics.fk": lambda: (kinematics.fk, {"arm": ARM, "q": Q}),
    "twolink.kinematics.jacobian": lambda: (kinematics.jacobian, {"arm": ARM, "q": Q}),
    "twolink.kinematics.jacobian_derivative": lambda: (
        kinematics.jacobian_derivative,
        {"arm": ARM, "q": Q},
    ),
    "twolink.kinematics.jacobian_rate": lambda: (
        kinematics.jacobian_rate,
        {"arm": ARM, "q": Q, "qd": QD},
    ),
    "twolink.kinematics.joint_positions": lambda: (
        kinematics.joint_positions,
        {"arm": ARM, "q": Q},
    ),
    "twolink.kinematics.joint_torques": lambda: (
        kinematics.joint_torques,
        {"arm": ARM, "q": Q, "force_by_tip": [1.0, 2.0]},
    ),
    "twolink.kinematics.reach": lambda: (kinematics.reach, {"arm": ARM}),
    "twolink.kinematics.distance_outside_reach": lambda: (
        kinematics.distance_outside_reach,
        {"arm": ARM, "p": P},
    ),
    # velocity
    "twolink.velocity.tip_velocity": lambda: (
        velocity.tip_velocity,
        {"arm": ARM, "q": Q, "qd": QD},
    ),
    "twolink.velocity.joint_rates": lambda: (
        velocity.joint_rates,
        {"arm": ARM, "q": Q, "v_tip": [0.1, 0.2], "tol": 1e-6},
    ),
    "twolink.velocity.joint_rates_dls": lambda: (
        velocity.joint_rates_dls,
        {"arm": ARM, "q": Q, "v_tip": [0.1, 0.2], "damping": 0.01},
    ),
    "twolink.velocity.manipulability": lambda: (
        velocity.manipulability,
        {"arm": ARM, "q": Q},
    ),
    "twolink.velocity.velocity_ellipse": lambda: (
        velocity.velocity_ellipse,
        {"arm": ARM, "q": Q},
    ),
    "twolink.velocity.force_ellipse": lambda: (
        velocity.force_ellipse,
        {"arm": ARM, "q": Q},
    ),
    "twolink.velocity.Ellipse.points": lambda: (
        ELLIPSE.points,
        {"n": 8, "scale": 1.0, "clip": 10.0},
    ),
    # dynamics
    "twolink.dynamics.mass_matrix": lambda: (
        dynamics.mass_matrix,
        {"arm": ARM, "q": Q},
    ),
    "twolink.dynamics.coriolis": lambda: (
        dynamics.coriolis,
        {"arm": ARM, "q": Q, "qd": QD},
    ),
    "twolink.dynamics.gravity": lambda: (dynamics.gravity, {"arm": ARM, "q": Q}),
    "twolink.dynamics.mass_matrix_derivative": lambda: (
        dynamics.mass_matrix_derivative,
        {"arm": ARM, "q": Q},
    ),
    "twolink.dynamics.gravity_jacobian": lambda: (
        dynamics.gravity_jacobian,
        {"arm": ARM, "q": Q},
    ),
    "twolink.dynamics.inverse_dynamics": lambda: (
        dynamics.inverse_dynamics,
        {"arm": ARM, "q": Q, "qd": QD, "qdd": QD, "force_by_tip": [1.0, 0.0]},
    ),
    "twolink.dynamics.forward_dynamics": lambda: (
        dynamics.forward_dynamics,
        {"arm": ARM, "q": Q, "qd": QD, "tau": QD, "force_by_tip": [1.0, 0.0]},
    ),
    "twolink.dynamics.energy": lambda: (
        dynamics.energy,
        {"arm": ARM, "q": Q, "qd": QD},
    ),
    "twolink.dynamics.state_derivative": lambda: (
        dynamics.state_derivative,
        {"arm": ARM, "torque": PD},
    ),
    # the arm's methods
    **{
        f"twolink.arm.TwoLinkArm.{method}": (
            lambda method=method, arguments=arguments: (
                getattr(LIMITED, method),
                arguments,
            )
        )
        for method, arguments in {
            "within_limits": {"q": Q, "tol": 1e-9},
            "fk": {"q": Q},
            "joint_positions": {"q": Q},
            "jacobian": {"q": Q},
            "joint_torques": {"q": Q, "force_by_tip": [1.0, 0.0]},
            "dh_table": {},
            "transforms": {"q": Q},
            "geometric_jacobian": {"q": Q},
            "tip_velocity": {"q": Q, "qd": QD},
            "joint_rates": {"q": Q, "v_tip": QD, "tol": 1e-6},
            "joint_rates_dls": {"q": Q, "v_tip": QD, "damping": 0.1},
            "manipulability": {"q": Q},
            "mass_matrix": {"q": Q},
            "coriolis": {"q": Q, "qd": QD},
            "gravity": {"q": Q},
            "inverse_dynamics": {"q": Q, "qd": QD, "qdd": QD, "force_by_tip": QD},
            "forward_dynamics": {"q": Q, "qd": QD, "tau": QD, "force_by_tip": QD},
            "energy": {"q": Q, "qd": QD},
        }.items()
    },
    "twolink.arm.TwoLinkArm": lambda: (
        TwoLinkArm,
        {
            "l1": 2.0,
            "l2": 1.5,
            "m1": 1.0,
            "m2": 2.0,
            "g": 9.81,
            "d": 0.1,
            "q_min": (-1.0, -2.0),
            "q_max": (1.0, 2.0),
            "I1": 0.3,
            "I2": 0.4,
            "limit_convention": "absolute",
        },
    ),
    # statics and contact
    "twolink.statics.Wall": lambda: (
        statics.Wall,
        {"point": [3.0, 0.0], "normal": [1.0, 0.0]},
    ),
    "twolink.statics.Wall.through": lambda: (
        statics.Wall.through,
        {"p_a": [4.0, 0.0], "p_b": [0.0, 4.0]},
    ),
    "twolink.statics.Wall.signed_distance": lambda: (WALL.signed_distance, {"p": P}),
    "twolink.statics.Wall.distance_from_base": lambda: (WALL.distance_from_base, {}),
    "twolink.statics.Wall.into_wall": lambda: (WALL.into_wall, {}),
    "twolink.statics.wall_contact": lambda: (
        statics.wall_contact,
        {"arm": ARM, "wall": WALL, "force_magnitude": 10.0, "include_gravity": True},
    ),
    "twolink.statics.WallContact.branch": lambda: (CONTACT.branch, {"elbow": "up"}),
    "twolink.contact.SpringWall": lambda: (
        contact.SpringWall,
        {"wall": WALL, "stiffness": 1e4, "damping": 1.0},
    ),
    "twolink.contact.SpringWall.penetration": lambda: (
        SPRING_WALL.penetration,
        {"p": P},
    ),
    "twolink.contact.SpringWall.force_on_tip": lambda: (
        SPRING_WALL.force_on_tip,
        {"p": P, "v": QD},
    ),
    "twolink.contact.SpringWall.__call__": lambda: (
        SPRING_WALL,
        {"t": 0.0, "p": P, "v": QD},
    ),
    "twolink.contact.TipForce": lambda: (
        contact.TipForce,
        {"arm": ARM, "controller": PD, "force_on_tip": [1.0, 0.0]},
    ),
    **{
        f"twolink.contact.TipForce.{method}": (
            lambda method=method: (
                getattr(PUSHED, method),
                {"t": 0.1, "q": Q, "qd": QD},
            )
        )
        for method in ("force_on_tip_at", "motor_torque", "__call__")
    },
    # controllers
    "twolink.controllers.CartesianSpring": lambda: (
        controllers.CartesianSpring,
        {"arm": ARM, "stiffness": 600.0, "rest_point": [3.0, 1.0]},
    ),
    "twolink.controllers.CartesianSpring.force_on_tip": lambda: (
        SPRING.force_on_tip,
        {"q": Q},
    ),
    "twolink.controllers.CartesianSpring.torque": lambda: (SPRING.torque, {"q": Q}),
    "twolink.controllers.CartesianSpring.potential_energy": lambda: (
        SPRING.potential_energy,
        {"q": Q},
    ),
    "twolink.controllers.CartesianSpring.__call__": lambda: (
        SPRING,
        {"t": 0.0, "q": Q, "qd": QD},
    ),
    "twolink.controllers.CartesianSpring.torque_derivatives": lambda: (
        SPRING.torque_derivatives,
        {"t": 0.0, "q": Q},
    ),
    "twolink.controllers.Impedance": lambda: (
        controllers.Impedance,
        {
            "arm": ARM,
            "stiffness": 600.0,
            "damping": 50.0,
            "rest_point": [3.0, 1.0],
            "gravity_compensation": False,
        },
    ),
    "twolink.controllers.Impedance.force_on_tip": lambda: (
        IMPEDANCE.force_on_tip,
        {"q": Q, "qd": QD},
    ),
    "twolink.controllers.Impedance.torque": lambda: (
        IMPEDANCE.torque,
        {"q": Q, "qd": QD},
    ),
    "twolink.controllers.Impedance.potential_energy": lambda: (
        IMPEDANCE.potential_energy,
        {"q": Q},
    ),
    "twolink.controllers.Impedance.__call__": lambda: (
        IMPEDANCE,
        {"t": 0.0, "q": Q, "qd": QD},
    ),
    "twolink.controllers.Impedance.torque_derivatives": lambda: (
        IMPEDANCE.torque_derivatives,
        {"t": 0.0, "q": Q},
    ),
    "twolink.controllers.JointPD": lambda: (
        controllers.JointPD,
        {
            "arm": ARM,
            "kp": 100.0,
            "kd": 20.0,
            "reference": Q,
            "gravity_compensation": False,
        },
    ),
    "twolink.controllers.JointPD.__call__": lambda: (
        PD,
        {"t": 0.0, "q": Q, "qd": QD},
    ),
    "twolink.controllers.JointPD.torque_derivatives": lambda: (
        PD.torque_derivatives,
        {"t": 0.0, "q": Q},
    ),
    "twolink.controllers.ComputedTorque": lambda: (
        controllers.ComputedTorque,
        {"arm": ARM, "kp": 100.0, "kd": 20.0, "reference": REFERENCE, "model": ARM},
    ),
    "twolink.controllers.ComputedTorque.commanded_acceleration": lambda: (
        COMPUTED.commanded_acceleration,
        {"t": 0.1, "q": Q, "qd": QD},
    ),
    "twolink.controllers.ComputedTorque.__call__": lambda: (
        COMPUTED,
        {"t": 0.1, "q": Q, "qd": QD},
    ),
    "twolink.controllers.ComputedTorque.torque_derivatives": lambda: (
        COMPUTED.torque_derivatives,
        {"t": 0.1, "q": Q},
    ),
    # references
    "twolink.references.JointReference": lambda: (
        references.JointReference,
        {
            "position": REFERENCE.position,
            "velocity": REFERENCE.velocity,
            "acceleration": REFERENCE.acceleration,
        },
    ),
    "twolink.references.JointReference.__call__": lambda: (REFERENCE, {"t": 0.2}),
    "twolink.references.JointReference.constant": lambda: (
        references.JointReference.constant,
        {"q_ref": Q},
    ),
    "twolink.references.JointReference.from_samples": lambda: (
        references.JointReference.from_samples,
        {"t": [0.0, 1.0], "q": [Q, QD], "qd": [QD, Q]},
    ),
    "twolink.references.JointReference.from_derivatives": lambda: (
        references.JointReference.from_derivatives,
        {"t": [0.0, 1.0], "q": [Q, QD], "qd": [QD, Q], "qdd": [Q, Q]},
    ),
    # simulation
    "twolink.simulation.simulate": lambda: (
        simulation.simulate,
        {
            "arm": ARM,
            "q0": Q,
            "qd0": QD,
            "t_end": 0.05,
            "torque": PD,
            "t_eval": [0.0, 0.05],
            "max_evaluations": 10_000,
            "max_wall_time": 10.0,
        },
    ),
    "twolink.simulation.simulate_quick": lambda: (
        simulation.simulate_quick,
        {
            "arm": ARM,
            "q0": Q,
            "qd0": QD,
            "t_eval": [0.0, 0.05],
            "torque": PD,
            "rtol": 1e-6,
            "atol": 1e-6,
            "max_evaluations": 10_000,
            "max_wall_time": 10.0,
        },
    ),
    "twolink.simulation.SimulationResult.tracking_error": lambda: (
        RUN.tracking_error,
        {"path": P},
    ),
    "twolink.simulation.SimulationResult.energy": lambda: (
        RUN.energy,
        {"extra_potential": SPRING.potential_energy},
    ),
    "twolink.simulation.SimulationResult.energy_drift": lambda: (
        RUN.energy_drift,
        {"extra_potential": SPRING.potential_energy},
    ),
    "twolink.simulation.SimulationResult.frames": lambda: (
        RUN.frames,
        {"max_frames": 3},
    ),
    # trajectories
    "twolink.trajectory.time_scaling": lambda: (
        trajectory.time_scaling,
        {"t": [0.0, 0.5], "duration": 1.0, "law": "cubic", "with_acceleration": True},
    ),
    "twolink.trajectory.LinePath": lambda: (
        trajectory.LinePath,
        {"p_start": [3.0, 0.0], "p_end": [3.0, 1.0], "duration": 1.0, "law": "cubic"},
    ),
    "twolink.trajectory.CirclePath": lambda: (
        trajectory.CirclePath,
        {
            "centre": [2.5, 1.0],
            "radius": 0.5,
            "duration": 1.0,
            "law": "linear",
            "start_angle": 0.2,
            "turns": 2.0,
        },
    ),
    **{
        f"twolink.trajectory.{path}.{method}": (
            lambda value=value, method=method, arguments=arguments: (
                getattr(value, method),
                arguments,
            )
        )
        for path, value in (("LinePath", LINE), ("CirclePath", CIRCLE))
        for method, arguments in (
            ("at", {"t": [0.0, 0.5], "with_acceleration": True}),
            ("sample", {"n": 5, "with_acceleration": True}),
        )
    },
    "twolink.trajectory.JointTrajectory.tracking_error": lambda: (
        MOTION.tracking_error,
        {"path": LINE},
    ),
    "twolink.trajectory.JointTrajectory.joint_reference": lambda: (
        MOTION.joint_reference,
        {},
    ),
    "twolink.trajectory.ik_trajectory": lambda: (
        trajectory.ik_trajectory,
        {"arm": ARM, "path": LINE, "n": 5, "elbow": "down"},
    ),
    "twolink.trajectory.resolved_rate_trajectory": lambda: (
        trajectory.resolved_rate_trajectory,
        {
            "arm": ARM,
            "path": LINE,
            "n": 5,
            "q0": MOTION.q[0],
            "elbow": "auto",
            "gain": 5.0,
            "damping": 0.0,
            "rtol": 1e-6,
            "method": "RK45",
            "max_evaluations": 10_000,
            "max_wall_time": 10.0,
        },
    ),
    # ik
    "twolink.ik.analytic.closed_form": lambda: (
        ik.closed_form,
        {"arm": ARM, "p": P, "elbow": "up"},
    ),
    "twolink.ik.iterative.newton": lambda: (
        ik.newton,
        {"arm": ARM, "p": P, "q0": [0.5, 1.0], "tol": 1e-10, "max_iter": 50},
    ),
    "twolink.ik.optimize.minimize": lambda: (
        ik.minimize,
        {"arm": ARM, "p": P, "q0": [0.5, 1.0], "constrained": False, "tol": 1e-6},
    ),
    "twolink.ik.grid_search.brute_force": lambda: (
        ik.brute_force,
        {
            "arm": ARM,
            "p": P,
            "q1_range": (0.0, 1.0),
            "q2_range": (0.5, 1.5),
            "step": 0.05,
        },
    ),
    "twolink.ik.limits.solutions_within_limits": lambda: (
        ik.solutions_within_limits,
        {"arm": LIMITED, "p": [12.5, 12.5], "tol": 1e-7},
    ),
    "twolink.ik.turns.move_into_limits": lambda: (
        ik.turns.move_into_limits,
        {"arm": LIMITED, "q": [0.3, 0.2], "tol": 1e-7},
    ),
    # workspace
    "twolink.workspace.is_reachable": lambda: (
        workspace.is_reachable,
        {"arm": LIMITED, "p": [12.5, 12.5], "tol": 1e-7, "elbow": "down"},
    ),
    "twolink.workspace.sample_reachable": lambda: (
        workspace.sample_reachable,
        {"arm": LIMITED, "n": 5, "seed": 3},
    ),
    "twolink.workspace.boundary_arcs": lambda: (
        workspace.boundary_arcs,
        {"arm": LIMITED, "probe": 1e-5, "elbow": "down"},
    ),
    "twolink.workspace.distance_to_arcs": lambda: (
        workspace.distance_to_arcs,
        {"p": [12.5, 12.5], "arcs": ARCS},
    ),
    "twolink.workspace.clearance": lambda: (
        workspace.clearance,
        {"arm": LIMITED, "p": [12.5, 12.5], "arcs": ARCS, "elbow": "auto"},
    ),
    "twolink.workspace.largest_inscribed_circle": lambda: (
        workspace.largest_inscribed_circle,
        {
            "arm": LIMITED,
            "starts": 1,
            "seed": 1,
            "elbow": "auto",
            "max_wall_time": 20.0,
        },
    ),
    "twolink.workspace.largest_circle_on_grid": lambda: (
        workspace.largest_circle_on_grid,
        {"arcs": ARCS, "candidates": [[12.5, 12.5]], "spacing": 0.5, "tol": 1e-6},
    ),
    "twolink.workspace.circle_points": lambda: (
        workspace.circle_points,
        {"centre": [12.5, 12.5], "radius": 2.0, "n": 4, "start_angle": 0.1},
    ),
    "twolink.workspace.BranchTable": lambda: (
        workspace.BranchTable,
        {"arm": LIMITED, "p": [[12.5, 12.5]]},
    ),
    **{
        f"twolink.workspace.BranchTable.{method}": (
            lambda method=method, arguments=arguments: (
                getattr(TABLE, method),
                arguments,
            )
        )
        for method, arguments in (
            ("solutions_within_limits", {"arm": LIMITED, "tol": 1e-7}),
            ("within_limits", {"arm": LIMITED, "tol": 1e-7}),
            ("reachable", {"arm": LIMITED, "tol": 1e-7, "elbow": "up"}),
        )
    },
    # arcs
    "twolink.arcs.Arc": lambda: (
        arcs.Arc,
        {
            "centre": (1.0, 0.0),
            "radius": 2.0,
            "start": 0.0,
            "sweep": 1.0,
            "label": "an arc",
            "kind": "reach",
        },
    ),
    "twolink.arcs.Arc.point_at": lambda: (ARC.point_at, {"fraction": [0.0, 0.5]}),
    "twolink.arcs.Arc.points": lambda: (ARC.points, {"n": 5}),
    "twolink.arcs.Arc.fraction_of": lambda: (ARC.fraction_of, {"p": [0.0, 2.0]}),
    "twolink.arcs.Arc.distance": lambda: (ARC.distance, {"p": [0.0, 3.0]}),
    "twolink.arcs.Arc.split": lambda: (ARC.split, {"fractions": [0.5]}),
    # stiffness
    "twolink.stiffness.joint_stiffness": lambda: (
        stiffness.joint_stiffness,
        {"arm": ARM, "q": Q, "tip_stiffness": 1000.0},
    ),
    "twolink.stiffness.tip_stiffness": lambda: (
        stiffness.tip_stiffness,
        {"arm": ARM, "q": Q, "joint_stiffness": 100.0},
    ),
    "twolink.stiffness.stiffness_ellipse": lambda: (
        stiffness.stiffness_ellipse,
        {"arm": ARM, "q": Q, "tip_stiffness": 1000.0},
    ),
    # linearization
    "twolink.linearization.tip_mass": lambda: (
        linearization.tip_mass,
        {"arm": ARM, "q": Q},
    ),
    "twolink.linearization.critical_damping": lambda: (
        linearization.critical_damping,
        {"arm": ARM, "q": Q, "stiffness": 600.0, "kind": "matrix"},
    ),
    "twolink.linearization.equilibrium": lambda: (
        linearization.equilibrium,
        {"arm": ARM, "controller": PD, "q0": Q, "t": 0.0, "tol": 1e-10},
    ),
    "twolink.linearization.closed_loop_matrices": lambda: (
        linearization.closed_loop_matrices,
        {
            "arm": ARM,
            "controller": controllers.JointPD(ARM, 100.0, 20.0, Q),
            "q_eq": Q,
            "t": 0.0,
            "tol": 1e-6,
        },
    ),
    "twolink.linearization.linearize": lambda: (
        linearization.linearize,
        {
            "arm": ARM,
            "controller": controllers.JointPD(ARM, 100.0, 20.0, Q),
            "q_eq": Q,
            "t": 0.0,
            "tol": 1e-6,
            "name": "pd",
        },
    ),
    "twolink.linearization.closed_loop_system": lambda: (
        linearization.closed_loop_system,
        {"arm": ARM, "controller": PD, "name": "pd"},
    ),
    # export
    "twolink.export.to_mjcf": lambda: (
        twolink.export.to_mjcf,
        {
            "arm": LIMITED,
            "wall": WALL,
            "tip_site": True,
            "tip_radius": 0.1,
            "timestep": 1e-3,
            "integrator": "RK4",
            "contact_solref": (0.02, 1.0),
            "contact_solimp": (0.9, 0.95, 0.001, 0.5, 2.0),
            "model_name": "arm",
        },
    ),
    "twolink.export.to_urdf": lambda: (
        twolink.export.to_urdf,
        {
            "arm": LIMITED,
            "z_up": True,
            "effort_limit": 100.0,
            "velocity_limit": 10.0,
            "robot_name": "arm",
        },
    ),
    # engine
    "twolink.engine.build_model": lambda: (
        _lazy_engine().build_model,
        {"arm": ARM},
    ),
    "twolink.engine.joint_accelerations": lambda: (
        _lazy_engine().joint_accelerations,
        {"model": _lazy_engine().build_model(ARM), "q": Q, "qd": QD, "tau": QD},
    ),
    "twolink.engine.simulate_in_mujoco": lambda: (
        _lazy_engine().simulate_in_mujoco,
        {
            "arm": ARM,
            "q0": Q,
            "qd0": QD,
            "t_end": 0.01,
            "torque": PD,
            "timestep": 1e-3,
            "sample_every": 2,
            "integrator": "RK4",
            "max_wall_time": 10.0,
        },
    ),
    "twolink.engine.wall_push": lambda: (
        _lazy_engine().wall_push,
        {
            "arm": ARM,
            "wall": [[4.0, 0.0], [0.0, 4.0]],
            "force_magnitude": 100.0,
            "elbow": "up",
            "duration": 0.01,
            "timestep": 1e-3,
            "contact_solref": (0.002, 1.0),
            "contact_solimp": (0.99, 0.99, 0.001, 0.5, 2.0),
            "impratio": 100.0,
        },
    ),
    # symbolic
    "twolink.symbolic.kinematics.planar_symbols": lambda: (sym.planar_symbols, {}),
    "twolink.symbolic.kinematics.dh_matrix": lambda: (
        sym.dh_matrix,
        {"theta": SYMBOLS["q1"], "d": 0.0, "a": SYMBOLS["l1"], "alpha": 0},
    ),
    "twolink.symbolic.kinematics.planar_fk": lambda: (
        sym.planar_fk,
        {"with_offset": True},
    ),
    "twolink.symbolic.dynamics.dynamics_symbols": lambda: (sym.dynamics_symbols, {}),
    "twolink.symbolic.dynamics.equations_of_motion": lambda: (
        sym.equations_of_motion,
        {"model": "absolute"},
    ),
    "twolink.symbolic.dynamics.EquationsOfMotion.residual": lambda: (
        EQUATIONS.residual,
        {},
    ),
    "twolink.symbolic.dynamics.christoffel_coriolis": lambda: (
        sym.christoffel_coriolis,
        {"M": EQUATIONS.M, "coordinates": COORDINATES, "rates": RATES},
    ),
    "twolink.symbolic.dynamics.time_derivative": lambda: (
        sym.time_derivative,
        {
            "expr": EQUATIONS.kinetic,
            "coordinates": COORDINATES,
            "rates": RATES,
            "accelerations": ACCELERATIONS,
        },
    ),
    "twolink.symbolic.dynamics.lambdify_dynamics": lambda: (
        sym.lambdify_dynamics,
        {"equations": "relative"},
    ),
    **{
        f"twolink.symbolic.dynamics.NumericDynamics.{method}": (
            lambda method=method, arguments=arguments: (
                getattr(NUMERIC, method),
                arguments,
            )
        )
        for method, arguments in (
            ("mass_matrix", {"arm": ARM, "q": Q}),
            ("coriolis", {"arm": ARM, "q": Q, "qd": QD}),
            ("gravity", {"arm": ARM, "q": Q}),
        )
    },
}

#: Public callables without a bad-argument walk, and why.
NOT_WALKED = {
    # records the package builds and returns, whose fields it has computed and checked
    "twolink.simulation.SimulationResult": "a result the package builds",
    "twolink.engine.EngineResult": "a result the package builds",
    "twolink.engine.WallPush": "a result the package builds",
    "twolink.statics.WallContact": "a result the package builds",
    "twolink.trajectory.JointTrajectory": "a result the package builds",
    "twolink.ik.result.IKResult": "a result the package builds",
    "twolink.velocity.Ellipse": "a result the package builds",
    "twolink.dh.DHRow": "a result the package builds (a named tuple)",
    "twolink.symbolic.dynamics.EquationsOfMotion": "a result the package builds",
    "twolink.symbolic.dynamics.NumericDynamics": "built by lambdify_dynamics",
    # exceptions: any message is a message
    "twolink.errors.InputTypeError": "an exception",
    "twolink.errors.SimulationError": "an exception",
    "twolink.errors.SingularityError": "an exception",
    "twolink.errors.UnreachableError": "an exception",
}


def test_every_public_callable_is_walked_or_exempt_with_a_reason():
    assert (set(PUBLIC) | set(METHODS)) - set(NOT_WALKED) == set(CALLS)


def _call(name):
    if (
        name.startswith("twolink.engine.") or "EngineResult" in name
    ) and not HAS_MUJOCO:
        pytest.skip("MuJoCo is not installed")
    if (
        name.startswith("twolink.linearization.")
        and not HAS_CONTROL
        and name.endswith(("linearize", "closed_loop_system"))
    ):
        pytest.skip("python-control is not installed")
    return CALLS[name]()


@pytest.mark.parametrize("name", sorted(CALLS))
def test_every_registered_call_is_valid_and_names_every_argument(name):
    function, arguments = _call(name)
    parameters = {
        parameter.name
        for parameter in inspect.signature(function).parameters.values()
        if parameter.kind
        not in (inspect.Parameter.VAR_POSITIONAL, inspect.Parameter.VAR_KEYWORD)
    }
    assert set(arguments) == parameters, "register every argument"
    function(**arguments)


#: Free text: any string is a valid value.
FREE_TEXT = {
    ("twolink.arcs.Arc", "label"),
    ("twolink.linearization.linearize", "name"),
    ("twolink.linearization.closed_loop_system", "name"),
}

#: Names that go into XML: any printable string (a control character cannot be written).
XML_NAMES = {
    ("twolink.export.to_mjcf", "model_name"),
    ("twolink.export.to_urdf", "robot_name"),
}

#: Arrays of any shape (times, angles, fractions): a nested list is no junk there.
ANY_SHAPE = {
    ("twolink.trajectory.time_scaling", "t"),
    ("twolink.trajectory.LinePath.at", "t"),
    ("twolink.trajectory.CirclePath.at", "t"),
    ("twolink.conventions.wrap_angle", "angle"),
    ("twolink.dh.dh_matrix", "theta"),
    ("twolink.arcs.Arc.point_at", "fraction"),
}

#: Symbolic entries that take a symbol's name (a Python identifier) as well as an expression.
SYMBOL_NAMES = {
    ("twolink.symbolic.kinematics.dh_matrix", name)
    for name in ("theta", "d", "a", "alpha")
}

#: The words the package's arguments take (a generated string may happen to be one).
WORDS = {
    *conventions.ELBOW_WORDS,
    *trajectory.TIME_LAWS,
    *twolink.export.INTEGRATORS,
    "relative",
    "absolute",
    "scalar",
    "matrix",
    "RK45",
    "RK23",
    "DOP853",
    "Radau",
    "BDF",
    "LSODA",
}


def _junk(name, parameter, default, optional):
    """Values no argument of this kind accepts."""
    values = [
        object(),
        float("nan"),
        float("inf"),
        np.timedelta64(1, "s"),
        1 + 2j,
        {"x": 1.0},
    ]
    if (name, parameter) not in ANY_SHAPE:
        values.append([[[0.5]]])
    if (name, parameter) in XML_NAMES:
        values += ["a name\x01with a control character", "a<b", ""]
    elif (name, parameter) not in FREE_TEXT:
        values += ["not a name" if (name, parameter) in SYMBOL_NAMES else "junk"]
        if default != "":  # the empty string is a valid value where it is the default
            values.append("")
    if not optional:
        values.append(None)
    if not isinstance(default, bool):
        values.append(True)
    return values


def _valid_text(name, parameter, text, default):
    """Whether a generated string is a valid value after all."""
    if (name, parameter) in FREE_TEXT or text in WORDS or text == default:
        return True
    if (name, parameter) in XML_NAMES:
        return text.isprintable() and not any(c in text for c in "<>&\"'")
    return (name, parameter) in SYMBOL_NAMES and text.isidentifier()


def _walked():
    cases = []
    for name in sorted(CALLS):
        try:
            function, arguments = CALLS[name]()
        except Exception:  # noqa: BLE001 - an optional engine missing: skipped in the test
            function, arguments = None, {}
        signature = inspect.signature(function) if function is not None else None
        for parameter in arguments:
            declared = signature.parameters[parameter]
            default = declared.default
            default = None if default is inspect.Parameter.empty else default
            optional = declared.default is None or "None" in str(declared.annotation)
            cases.append((name, parameter, default, optional))
    return cases


WALKED = _walked()


def _raised_by_the_package(error):
    """Whether the innermost frame of ``error``'s traceback is the package's own code."""
    frames = traceback.extract_tb(error.__traceback__)
    return bool(frames) and pathlib.Path(frames[-1].filename).resolve().is_relative_to(
        PACKAGE
    )


@pytest.mark.parametrize(
    "name, parameter, default, optional",
    WALKED,
    ids=[
        f"{name.removeprefix('twolink.')}-{parameter}" for name, parameter, *_ in WALKED
    ],
)
@settings(
    max_examples=12,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(data=st.data())
def test_a_bad_value_of_any_argument_is_refused_naming_it(
    name, parameter, default, optional, data
):
    function, arguments = _call(name)
    junk = st.sampled_from(_junk(name, parameter, default, optional))
    if (name, parameter) not in FREE_TEXT:  # no generated string is junk there
        junk = st.one_of(
            junk,
            st.text(min_size=1, max_size=5).filter(
                lambda text: not _valid_text(name, parameter, text, default)
            ),
        )
    bad = data.draw(junk, label="bad value")
    try:
        function(**{**arguments, parameter: bad})
    except (ValueError, TypeError) as error:
        message = str(error)
        assert _raised_by_the_package(error), (
            f"{name}({parameter}={bad!r}) raised {type(error).__name__} outside the package: {message}"
        )
        words = parameter.replace("_", " ")
        assert parameter in message or words in message, (
            f"{name}({parameter}={bad!r}): the message does not name {parameter!r}: {message}"
        )
    else:
        pytest.fail(f"{name}({parameter}={bad!r}) was accepted")


README = PACKAGE.parent / "README.md"


def _public_modules():
    modules = [twolink]
    for info in pkgutil.walk_packages(twolink.__path__, "twolink."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            modules.append(importlib.import_module(info.name))
    return modules


def test_the_readme_lists_the_public_names_of_every_module():
    """README's "Using twolink in your own code" names each module's ``__all__`` (for a module
    inside a sub-package, what the sub-package does not export), no more, no less."""
    text = README.read_text(encoding="utf-8")
    section = text.split("## Using twolink in your own code", 1)[1].split("\n## ", 1)[0]
    listed = {
        line.split("`")[1]: set(line.split(":", 1)[1].replace("`", "").split(", "))
        for line in section.splitlines()
        if line.startswith("- `twolink")
    }
    expected = {}
    for module in _public_modules():
        names = set(module.__all__)
        parent = module.__name__.rpartition(".")[0]
        if parent not in ("", "twolink"):
            names -= set(importlib.import_module(parent).__all__)
        if names:
            expected[module.__name__] = {name.strip() for name in names}
    listed = {
        module: {name.strip() for name in names} for module, names in listed.items()
    }
    assert listed == expected
