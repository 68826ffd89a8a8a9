"""The shared input checks: what any public function refuses, however deeply it is hidden in the input."""

import numpy as np
import pytest
from _cases import BAD_NUMBERS, stable_id
from hypothesis import given
from hypothesis import strategies as st

from twolink import (
    CartesianSpring,
    Impedance,
    JointPD,
    arcs,
    arms,
    dh,
    dynamics,
    ik,
    kinematics,
    simulate,
    statics,
    trajectory,
    velocity,
    workspace,
)
from twolink._validate import as_flag, real_array
from twolink.errors import InputTypeError
from twolink_course import timing

ARM = arms.two_metre
EMPTY_SHAPES = [(0, 2), (3, 0, 2), (0, 0, 2)]
MASKED_START = np.ma.masked_array([0.3, 99.0], mask=[False, True])


def test_simulate_refuses_a_masked_start_instead_of_using_its_hidden_values():
    with pytest.raises(
        InputTypeError,
        match=r"q0 must be real numbers .*got a masked array \(numpy\.ma\).*filled",
    ):
        simulate(ARM, MASKED_START, [0.0, 0.0], 0.1)


@pytest.mark.parametrize(
    "call",
    [
        lambda bad: ARM.fk(bad),
        lambda bad: ARM.jacobian(bad),
        lambda bad: ik.closed_form(ARM, bad),
        lambda bad: velocity.tip_velocity(ARM, [0.3, 0.2], bad),
        lambda bad: simulate(ARM, [0.3, 0.2], bad, 0.1),
    ],
    ids=["fk", "jacobian", "closed_form", "tip_velocity", "simulate qd0"],
)
def test_masked_arrays_are_refused_wherever_pairs_are_read(call):
    with pytest.raises(InputTypeError, match=r"masked array"):
        call(np.ma.masked_array([3.0, 1.0], mask=[False, True]))


def test_a_bool_inside_a_nested_list_is_refused_not_read_as_one():
    with pytest.raises(
        InputTypeError, match=r"q must be real numbers .*\(entry \(0, 1\) is bool\)"
    ):
        ARM.fk([[0.3, True]])


@st.composite
def nested_with_one_bool(draw):
    """Rows of two floats, nested 1 to 3 deep, with one entry replaced by a bool; and that entry's index."""
    depth = draw(st.integers(1, 3))
    shape = tuple(
        draw(st.lists(st.integers(1, 3), min_size=depth - 1, max_size=depth - 1))
    ) + (2,)
    values = np.zeros(shape).tolist()
    index = tuple(draw(st.integers(0, size - 1)) for size in shape)
    row = values
    for position in index[:-1]:
        row = row[position]
    row[index[-1]] = draw(st.booleans())
    return values, index


@given(nested_with_one_bool())
def test_a_bool_at_any_depth_is_refused_naming_its_index(case):
    values, index = case
    with pytest.raises(InputTypeError, match=rf"\(entry {re_index(index)} is bool\)"):
        real_array(values, "q")


def re_index(index):
    return (
        "\\("
        + ", ".join(str(i) for i in index)
        + (",\\)" if len(index) == 1 else "\\)")
    )


@pytest.mark.parametrize(
    "bad",
    [
        [np.array([True, False]), [1.0, 2.0]],
        [[1.0, None]],
        [[1.0, "2"]],
        [[1.0, 2j]],
        [[b"a", 1.0]],
    ],
)
def test_other_coerced_entries_inside_nested_lists_are_refused(bad):
    with pytest.raises(
        InputTypeError, match=r"q must be real numbers; got .*\(entry \(\d, ?\d?\) is "
    ):
        real_array(bad, "q")


def test_plain_nested_numbers_are_read_unchanged():
    assert real_array([[1, 2.5], (3, np.float64(4.0))], "q").tolist() == [
        [1.0, 2.5],
        [3.0, 4.0],
    ]


@pytest.mark.parametrize("bad", ["False", "True", 0, 1, None, 1.0])
def test_flags_take_only_true_or_false(bad):
    with pytest.raises(
        InputTypeError, match=r"constrained must be True or False; got "
    ):
        as_flag(bad, "constrained")


# ------------------------------------ empty batches through every vectorised function
@pytest.mark.parametrize("shape", EMPTY_SHAPES)
def test_empty_batches_through_the_vectorised_functions(shape):
    from twolink import velocity

    arm, empty = arms.ten, np.empty(shape)
    lead = shape[:-1]
    assert ik.closed_form(arm, empty).q.shape == shape
    assert ik.closed_form(arm, empty, elbow="both").q.shape == (2,) + shape
    assert arm.fk(empty).shape == shape and arm.jacobian(empty).shape == lead + (2, 2)
    assert arm.forward_dynamics(empty, empty, empty).shape == shape
    assert arm.forward_dynamics(empty, empty, empty, empty).shape == shape
    assert arm.inverse_dynamics(empty, empty, empty).shape == shape
    assert arm.joint_rates(empty, empty).shape == shape
    assert arm.joint_rates_dls(empty, empty, 0.1).shape == shape
    assert velocity.velocity_ellipse(arm, empty).semi_axes.shape == shape
    assert workspace.is_reachable(arm, empty).shape == lead


# ------------------------------ types at the boundary: refused clearly, never coerced


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


# ------------------------------------------------------------------- counts and sizes
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
