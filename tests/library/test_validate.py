"""The shared input checks: what any public function refuses, however deeply it is hidden in the input.

Each kind of argument is checked by one helper of ``twolink._validate``
(``as_pairs`` and its fast path ``pair_floats`` for pairs, ``as_finite_scalar``
for numbers, ``require_arm`` for arms, ``as_count`` for counts): each helper
meets its whole table of bad values here, and each entry point one
representative, a value a careless conversion would accept (a bool among the
numbers of a pair, a number in a string, a dict shaped like an arm), which it
must refuse naming its own argument: so the entry point hands that argument
to the helper.
"""

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
from twolink._validate import (
    as_count,
    as_finite_scalar,
    as_flag,
    as_pairs,
    pair_floats,
    real_array,
    require_arm,
)
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


#: Each function reading a pair, and the name of the argument that reads it.
PAIR_FUNCTIONS = {
    "fk": (lambda q: ARM.fk(q), "q"),
    "jacobian": (lambda q: ARM.jacobian(q), "q"),
    "joint_positions": (lambda q: ARM.joint_positions(q), "q"),
    "mass_matrix": (lambda q: ARM.mass_matrix(q), "q"),
    "forward_dynamics": (
        lambda q: ARM.forward_dynamics(q, [0.0, 0.0], [0.0, 0.0]),
        "q",
    ),
    "inverse_dynamics": (
        lambda qd: ARM.inverse_dynamics([0.0, 0.0], qd, [0.0, 0.0]),
        "qd",
    ),
    "joint_rates_dls": (lambda v: ARM.joint_rates_dls([0.3, 1.0], v, 0.1), "v_tip"),
    "closed_form": (lambda p: ik.closed_form(ARM, p).q, "target p"),
    "newton": (lambda q0: ik.newton(ARM, [3.0, 1.0], q0=q0), "q0"),
    "is_reachable": (lambda p: workspace.is_reachable(ARM, p), "p"),
    "within_limits": (lambda q: ARM.within_limits(q), "q"),
    "simulate": (lambda q0: simulate(ARM, q0, [0.0, 0.0], 0.1), "q0"),
}


@pytest.mark.parametrize("bad", BAD_PAIRS, ids=stable_id)
def test_the_pair_check_refuses_complex_bool_str_none_and_objects(bad):
    assert pair_floats(bad) is None  # the fast path leaves it to as_pairs
    with pytest.raises(ValueError, match=r"^q must (be|have)"):
        as_pairs(bad, "q")


@pytest.mark.parametrize("function", PAIR_FUNCTIONS, ids=str)
def test_every_pair_argument_is_checked_under_its_name(function):
    call, name = PAIR_FUNCTIONS[function]
    with pytest.raises(InputTypeError, match=rf"^{name} must be real numbers"):
        call([True, 0.5])


def test_complex_input_is_refused_not_stripped_of_its_imaginary_part():
    with pytest.raises(InputTypeError, match="real numbers"):
        ARM.fk(np.array([0.3, 0.5 + 1e-3j]))


@pytest.mark.parametrize("bad", BAD_NUMBERS, ids=stable_id)
def test_the_number_check_refuses_non_numbers(bad):
    with pytest.raises(InputTypeError, match=r"^x \(m\) must be a real number"):
        as_finite_scalar(bad, "x (m)")


#: Each function reading a number, and the name (with its unit) it refuses it under.
SCALAR_CALLS = {
    "within_limits-tol": (lambda x: ARM.within_limits([0.1, 0.2], tol=x), "tol"),
    "joint_rates-tol": (
        lambda x: ARM.joint_rates([0.3, 1.0], [0.0, 1.0], tol=x),
        "tol",
    ),
    "dls-damping": (
        lambda x: ARM.joint_rates_dls([0.3, 1.0], [0.0, 1.0], damping=x),
        "damping",
    ),
    "dh_matrix-d": (lambda x: dh.dh_matrix(0.3, x, 1.0, 0.0), "d"),
    "Arc-radius": (lambda x: arcs.Arc((0.0, 0.0), x, 0.0, 1.0), "radius"),
    "circle_intersections": (
        lambda x: arcs.circle_intersections((0.0, 0.0), x, (1.0, 0.0), 1.0),
        "radius_a",
    ),
    "brute_force-step": (lambda x: ik.brute_force(ARM, [3.0, 1.0], step=x), "step"),
    "simulate-t_end": (lambda x: simulate(ARM, [0.0, 0.0], [0.0, 0.0], x), "t_end"),
    "time_scaling-duration": (lambda x: trajectory.time_scaling(0.5, x), "duration"),
    "spring-stiffness": (lambda x: CartesianSpring(ARM, x, [3.0, 1.0]), "stiffness"),
    "wall_contact-force": (
        lambda x: statics.wall_contact(
            ARM, statics.Wall.through([4.0, 0.0], [0.0, 4.0]), x
        ),
        "force_magnitude",
    ),
}


@pytest.mark.parametrize("call", SCALAR_CALLS, ids=str)
def test_every_number_argument_is_checked_under_its_name(call):
    function, name = SCALAR_CALLS[call]
    with pytest.raises(InputTypeError, match=rf"^{name}\b.* must be a real number"):
        function("12")


@pytest.mark.parametrize(
    "not_an_arm", [None, 3.0, "arm", object(), {"l1": 1.0}], ids=stable_id
)
def test_the_arm_check_refuses_anything_but_an_arm(not_an_arm):
    with pytest.raises(TypeError, match=r"^arm must be a twolink.TwoLinkArm"):
        require_arm(not_an_arm)


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
def test_anything_but_an_arm_is_a_type_error_naming_arm(call):
    with pytest.raises(TypeError, match=r"arm must be a twolink.TwoLinkArm"):
        call({"l1": 2.0, "l2": 2.0})


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
def test_the_count_check_takes_integers_at_least_their_minimum(bad, error):
    with pytest.raises(error, match=r"^n must be an integer"):
        as_count(bad, "n", minimum=1, maximum=10**6)


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
def test_every_count_argument_is_checked_under_its_name(call, name):
    with pytest.raises(InputTypeError, match=rf"^{name}\b.* must be an integer"):
        call("10")
