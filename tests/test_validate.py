"""The shared input checks: what any public function refuses, however deeply it is hidden in the input."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from twolink import arms, ik, simulate, velocity
from twolink._validate import as_flag, real_array
from twolink.errors import InputTypeError

ARM = arms.two_metre
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
