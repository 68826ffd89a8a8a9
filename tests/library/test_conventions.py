"""twolink.conventions: relative and absolute angles, wrapping, the elbow vocabulary."""

import numpy as np
import pytest
from _cases import stable_id
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from conftest import configurations
from twolink import (
    arms,
    to_absolute,
    to_relative,
    wrap_angle,
)
from twolink.conventions import ELBOW_WORDS, check_elbow


@given(q=configurations())
def test_absolute_relative_round_trip(q):
    q_abs = to_absolute(q)
    assert q_abs[1] == pytest.approx(q[0] + q[1])
    assert np.allclose(to_relative(q_abs), q)


@given(q=configurations())
def test_fk_is_the_same_in_both_conventions(q):
    arm = arms.two_metre
    q1, q2_abs = to_absolute(q)
    expected = [
        2 * np.cos(q1) + 2 * np.cos(q2_abs),
        2 * np.sin(q1) + 2 * np.sin(q2_abs),
    ]
    assert np.allclose(arm.fk(q), expected)


def test_wrap_angle_range():
    angles = np.linspace(-20, 20, 1001)
    wrapped = wrap_angle(angles)
    assert np.all(wrapped >= -np.pi) and np.all(wrapped < np.pi)
    assert np.allclose(np.cos(wrapped), np.cos(angles)) and np.allclose(
        np.sin(wrapped), np.sin(angles)
    )


@pytest.mark.parametrize(
    "bad", [None, "0.3", [0.3, 1j], True, np.inf, [np.nan]], ids=stable_id
)
def test_wrap_angle_refuses_non_angles(bad):
    with pytest.raises(ValueError, match="must be"):
        wrap_angle(bad)


finite_angles = st.floats(-1e6, 1e6, allow_nan=False)
angle_batches = hnp.arrays(
    np.float64, st.tuples(st.integers(0, 4), st.just(2)), elements=finite_angles
)


@given(q=angle_batches)
def test_absolute_and_relative_are_inverse_maps_on_batches(q):
    q_abs = to_absolute(q)
    assert q_abs.shape == q.shape
    assert np.array_equal(q_abs[..., 0], q[..., 0])
    assert np.array_equal(q_abs[..., 1], q[..., 0] + q[..., 1])
    assert np.allclose(to_relative(q_abs), q, rtol=0.0, atol=1e-9)
    assert np.allclose(to_absolute(to_relative(q)), q, rtol=0.0, atol=1e-9)


def test_conversions_return_new_arrays_and_leave_their_input_alone():
    q = np.array([0.5, 0.25])
    q_abs = to_absolute(q)
    q_abs[0] = 99.0
    assert np.array_equal(q, [0.5, 0.25])
    assert to_relative(q) is not q and np.array_equal(q, [0.5, 0.25])


@pytest.mark.parametrize(
    "convert, name", [(to_absolute, "q"), (to_relative, "q_abs")], ids=["abs", "rel"]
)
@pytest.mark.parametrize("bad", [[1.0, 2.0, 3.0], "ab", [np.nan, 0.0]], ids=stable_id)
def test_conversions_refuse_what_is_not_pairs_of_angles_naming_the_argument(
    convert, name, bad
):
    with pytest.raises(ValueError, match=rf"^{name} "):
        convert(bad)


@given(angle=finite_angles)
def test_wrap_angle_lands_in_minus_pi_to_pi_on_the_same_direction(angle):
    wrapped = wrap_angle(angle)
    assert isinstance(wrapped, np.float64)
    assert -np.pi <= wrapped < np.pi
    turns = (angle - wrapped) / (2.0 * np.pi)
    assert abs(turns - round(turns)) <= 1e-9


@given(angle=finite_angles)
def test_wrap_angle_is_idempotent(angle):
    once = wrap_angle(angle)
    assert wrap_angle(once) == once


@pytest.mark.parametrize(
    "angle",
    [np.nextafter(-np.pi, -np.inf), -np.pi, np.pi],
    ids=["just below -pi", "-pi", "pi"],
)
def test_wrap_angle_at_and_just_below_minus_pi_gives_minus_pi_not_pi(angle):
    """Just below -pi the modulo rounds a tiny negative remainder up to a whole turn."""
    assert wrap_angle(angle) == -np.pi


def test_wrap_angle_keeps_the_shape_of_a_batch():
    angles = np.array([[0.0, 4.0], [-4.0, 7.0]])
    wrapped = wrap_angle(angles)
    assert wrapped.shape == (2, 2)
    assert np.allclose(
        wrapped, [[0.0, 4.0 - 2 * np.pi], [2 * np.pi - 4.0, 7.0 - 2 * np.pi]]
    )


def test_wrap_angle_refuses_infinity_and_nan_saying_why():
    with pytest.raises(ValueError, match="angle must be finite"):
        wrap_angle([0.0, np.nan])


@pytest.mark.parametrize("word", ELBOW_WORDS)
def test_check_elbow_returns_each_word_of_the_vocabulary(word):
    assert check_elbow(word) == word


def test_check_elbow_refuses_a_known_word_it_cannot_use_saying_why():
    with pytest.raises(
        ValueError, match=r"\('down', 'up'\) here; got 'both' \(one branch\)"
    ):
        check_elbow("both", ("down", "up"), why="one branch")


@pytest.mark.parametrize("bad", ["Down", "elbow-up", None, 1, ("down",)], ids=stable_id)
def test_check_elbow_refuses_anything_else_naming_the_words(bad):
    with pytest.raises(
        ValueError, match=r"elbow must be one of \('down', 'up', 'both', 'auto'\)"
    ):
        check_elbow(bad)
