"""Types at the boundary (class 7) and counts and sizes (class 8): refused clearly, never coerced."""

import numpy as np
import pytest

from twolink import (
    CartesianSpring,
    Impedance,
    JointPD,
    TwoLinkArm,
    arcs,
    arms,
    dh,
    dynamics,
    ik,
    kinematics,
    simulate,
    statics,
    timing,
    trajectory,
    velocity,
    workspace,
    wrap_angle,
)
from twolink.errors import InputTypeError

ARM = arms.two_metre
BAD_NUMBERS = [
    None,
    "12",
    "abc",
    True,
    False,
    1 + 2j,
    np.complex128(1.0),
    object(),
    [1.0],
    {"x": 1},
]


def stable_id(value):
    """A test id that is the same in every process (no memory addresses)."""
    return "object" if type(value) is object else repr(value)


BAD_PAIRS = [
    None,
    "ab",
    [1.0, None],
    [1.0, "2"],
    [True, 0.5],
    [1.0, 2j],
    np.array([1.0, 2j]),
    np.array([True, False]),
    [None, 1.0],
]


@pytest.mark.parametrize("bad", BAD_NUMBERS, ids=stable_id)
@pytest.mark.parametrize("field", ["l1", "l2", "m1", "m2", "g", "d", "I1", "I2"])
def test_arm_parameters_refuse_non_numbers(field, bad):
    kwargs = {"l1": 1.0, "l2": 1.0, field: bad}
    if bad is None and field in ("I1", "I2"):
        return  # None is the documented default (uniform rod)
    with pytest.raises(InputTypeError, match=field):
        TwoLinkArm(**kwargs)


@pytest.mark.parametrize(
    "bad",
    ["12", "ab", [1.0, "2"], [True, 1.0], [1j, 1.0], 5.0, [[0.0, 1.0]]],
    ids=stable_id,
)
def test_joint_limits_refuse_strings_and_other_non_angles(bad):
    with pytest.raises(ValueError, match="q_min"):
        TwoLinkArm(1.0, 1.0, q_min=bad, q_max=(1.0, 1.0))


@pytest.mark.parametrize("bad", [None, 1, ["relative"]], ids=stable_id)
def test_limit_convention_must_be_a_name(bad):
    with pytest.raises(ValueError, match="limit_convention must be one of"):
        TwoLinkArm(1.0, 1.0, limit_convention=bad)


PAIR_FUNCTIONS = {
    "fk": lambda q: ARM.fk(q),
    "jacobian": lambda q: ARM.jacobian(q),
    "joint_positions": lambda q: ARM.joint_positions(q),
    "mass_matrix": lambda q: ARM.mass_matrix(q),
    "forward_dynamics": lambda q: ARM.forward_dynamics(q, [0.0, 0.0], [0.0, 0.0]),
    "inverse_dynamics": lambda q: ARM.inverse_dynamics([0.0, 0.0], q, [0.0, 0.0]),
    "joint_rates_dls": lambda q: ARM.joint_rates_dls([0.3, 1.0], q, 0.1),
    "closed_form": lambda q: ik.closed_form(ARM, q).q,
    "newton": lambda q: ik.newton(ARM, [3.0, 1.0], q0=q),
    "is_reachable": lambda q: workspace.is_reachable(ARM, q),
    "within_limits": lambda q: ARM.within_limits(q),
    "simulate": lambda q: simulate(ARM, q, [0.0, 0.0], 0.1),
}


@pytest.mark.parametrize("bad", BAD_PAIRS, ids=stable_id)
@pytest.mark.parametrize("function", PAIR_FUNCTIONS, ids=str)
def test_pairs_refuse_complex_bool_str_none_and_objects(function, bad):
    with pytest.raises(ValueError, match=r"must be|must have"):
        PAIR_FUNCTIONS[function](bad)


def test_complex_input_is_refused_not_stripped_of_its_imaginary_part():
    with pytest.raises(InputTypeError, match="real numbers"):
        ARM.fk(np.array([0.3, 0.5 + 1e-3j]))


@pytest.mark.parametrize("bad", BAD_NUMBERS, ids=stable_id)
@pytest.mark.parametrize(
    "call",
    [
        lambda x: ARM.within_limits([0.1, 0.2], tol=x),
        lambda x: ARM.joint_rates([0.3, 1.0], [0.0, 1.0], tol=x),
        lambda x: ARM.joint_rates_dls([0.3, 1.0], [0.0, 1.0], damping=x),
        lambda x: dh.dh_matrix(0.3, x, 1.0, 0.0),
        lambda x: arcs.Arc((0.0, 0.0), x, 0.0, 1.0),
        lambda x: arcs.circle_intersections((0.0, 0.0), x, (1.0, 0.0), 1.0),
        lambda x: ik.brute_force(ARM, [3.0, 1.0], step=x),
        lambda x: simulate(ARM, [0.0, 0.0], [0.0, 0.0], x),
        lambda x: trajectory.time_scaling(0.5, x),
        lambda x: CartesianSpring(ARM, x, [3.0, 1.0]),
        lambda x: statics.wall_contact(
            ARM, statics.Wall.through([4.0, 0.0], [0.0, 4.0]), x
        ),
    ],
    ids=[
        "within_limits-tol",
        "joint_rates-tol",
        "dls-damping",
        "dh_matrix-d",
        "Arc-radius",
        "circle_intersections",
        "brute_force-step",
        "simulate-t_end",
        "time_scaling-duration",
        "spring-stiffness",
        "wall_contact-force",
    ],
)
def test_scalars_refuse_non_numbers(call, bad):
    if isinstance(bad, list):
        pytest.skip(
            "a one-element list is a matrix or array argument for some of these"
        )
    with pytest.raises(ValueError, match=r"must be"):
        call(bad)


@pytest.mark.parametrize(
    "bad", [None, "0.3", [0.3, 1j], True, np.inf, [np.nan]], ids=stable_id
)
def test_wrap_angle_and_dh_refuse_non_angles(bad):
    with pytest.raises(ValueError, match="must be"):
        wrap_angle(bad)
    with pytest.raises(ValueError, match="must be"):
        dh.dh_matrix(bad, 0.0, 1.0, 0.0)


@pytest.mark.parametrize(
    "not_an_arm", [None, 3.0, "arm", object(), {"l1": 1.0}], ids=stable_id
)
@pytest.mark.parametrize(
    "call",
    [
        lambda arm: kinematics.fk(arm, [0.1, 0.2]),
        lambda arm: kinematics.jacobian(arm, [0.1, 0.2]),
        lambda arm: kinematics.reach(arm),
        lambda arm: dynamics.forward_dynamics(arm, [0.1, 0.2], [0.0, 0.0], [0.0, 0.0]),
        lambda arm: dynamics.mass_matrix(arm, [0.1, 0.2]),
        lambda arm: velocity.joint_rates(arm, [0.1, 0.0], [0.0, 1.0]),
        lambda arm: velocity.manipulability(arm, [0.1, 0.2]),
        lambda arm: ik.closed_form(arm, [1.0, 1.0]).q,
        lambda arm: ik.newton(arm, [1.0, 1.0]),
        lambda arm: ik.brute_force(arm, [1.0, 1.0]),
        lambda arm: workspace.is_reachable(arm, [1.0, 1.0]),
        lambda arm: dh.dh_table(arm),
        lambda arm: simulate(arm, [0.0, 0.0], [0.0, 0.0], 1.0),
        lambda arm: trajectory.ik_trajectory(arm, [[1.0, 1.0], [1.0, 1.5]]),
        lambda arm: statics.wall_contact(
            arm, statics.Wall.through([4.0, 0.0], [0.0, 4.0]), 1.0
        ),
        lambda arm: Impedance(arm, 1.0, 1.0, [1.0, 1.0]),
        lambda arm: JointPD(arm, 1.0, 1.0, [0.0, 0.0]),
    ],
)
def test_anything_but_an_arm_is_a_type_error_naming_arm(call, not_an_arm):
    with pytest.raises(TypeError, match=r"arm"):
        call(not_an_arm)


# ----------------------------------------------------------------- class 8: counts and sizes
BAD_COUNTS = [
    (0, ValueError),
    (-3, ValueError),
    (2.5, ValueError),
    ("10", TypeError),
    (None, TypeError),
    (True, TypeError),
    (np.nan, ValueError),
    (np.inf, ValueError),
    (10**30, ValueError),
]


@pytest.mark.parametrize("bad, error", BAD_COUNTS, ids=lambda v: repr(v))
@pytest.mark.parametrize(
    "call, name",
    [
        (lambda n: trajectory.LinePath([0.0, 1.0], [1.0, 1.0], 1.0).sample(n), "n"),
        (lambda n: workspace.sample_reachable(ARM, n=n), "n"),
        (lambda n: workspace.circle_points([0.0, 0.0], 1.0, n), "n"),
        (lambda n: arcs.Arc((0.0, 0.0), 1.0, 0.0, 1.0).points(n), "n"),
        (lambda n: velocity.Ellipse(np.zeros(2), np.ones(2), np.eye(2)).points(n), "n"),
        (lambda n: ik.newton(ARM, [3.0, 1.0], max_iter=n), "max_iter"),
        (lambda n: timing.median_time(lambda: None, repeat=n), "repeat"),
        (lambda n: simulate(ARM, [0.0, 0.0], [0.0, 0.0], 0.1).frames(n), "max_frames"),
    ],
    ids=[
        "LinePath.sample",
        "sample_reachable",
        "circle_points",
        "Arc.points",
        "Ellipse.points",
        "newton",
        "median_time",
        "frames",
    ],
)
def test_counts_are_integers_at_least_their_minimum(call, name, bad, error):
    if bad == 10**30 and name in ("max_iter", "max_frames"):
        pytest.skip(
            "no memory behind this count: a huge value only caps a loop that stops earlier"
        )
    with pytest.raises(error, match=name):
        call(bad)


def test_a_grid_beyond_the_memory_budget_is_refused_up_front_naming_points_and_limit():
    with pytest.raises(
        ValueError, match=r"would hold .* points, more than MAX_AXIS_POINTS"
    ):
        ik.brute_force(ARM, [3.0, 1.0], step=1e-12)
    with pytest.raises(
        ValueError,
        match=r"grid of \d+ x \d+ = .* points per target, more than MAX_GRID_POINTS",
    ):
        ik.brute_force(ARM, [3.0, 1.0], step=1e-4)


def test_sample_counts_beyond_the_memory_budget_are_refused():
    with pytest.raises(
        ValueError, match=r"n \(samples\) must be an integer <= 10000000"
    ):
        workspace.sample_reachable(ARM, n=5 * 10**9)


@pytest.mark.parametrize("seconds", [np.inf, np.nan, 1e9, -1.0, 0.0])
def test_timing_helpers_refuse_infinite_budgets(seconds):
    with pytest.raises(ValueError, match="min_seconds"):
        timing.median_time(lambda: None, min_seconds=seconds)
