"""Circular arcs: points along them and cuts, with NaN and fractions outside the arc refused."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from twolink.arcs import Arc

HALF = Arc((0.0, 0.0), 1.0, 0.0, np.pi)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), [0.5, float("nan")]])
def test_point_at_refuses_nan_and_infinity(bad):
    with pytest.raises(
        ValueError,
        match=r"fraction must be finite numbers \(0 = start, 1 = end of the arc\); entry ",
    ):
        HALF.point_at(bad)


@pytest.mark.parametrize("bad", [float("nan"), [0.5, float("-inf")]])
def test_split_refuses_nan_instead_of_returning_the_whole_arc(bad):
    with pytest.raises(ValueError, match=r"fractions must be finite numbers"):
        HALF.split(bad)


@pytest.mark.parametrize("bad", [-0.5, 1.5, [0.2, 3.0]])
def test_split_refuses_fractions_outside_the_arc(bad):
    with pytest.raises(ValueError, match=r"fractions must lie in \[0, 1\]"):
        HALF.split(bad)


@given(st.lists(st.floats(0.0, 1.0), max_size=6))
def test_split_pieces_join_up_into_the_arc(fractions):
    pieces = HALF.split(fractions)
    assert pieces[0].start == HALF.start
    assert np.isclose(
        sum(piece.sweep for piece in pieces), HALF.sweep, rtol=0.0, atol=1e-12
    )
    for before, after in zip(pieces, pieces[1:]):
        assert np.isclose(
            before.start + before.sweep, after.start, rtol=0.0, atol=1e-12
        )


@given(heading=st.floats(0.0, 2 * np.pi), start=st.floats(-np.pi, np.pi))
def test_an_arc_of_zero_sweep_is_its_one_point(heading, start):
    """A point on the arc's circle but off its one point is that far from it (np.sign(0)
    put every point of the circle on the span of a zero sweep: distance 0)."""
    arc = Arc((0.5, -0.25), 2.0, start, 0.0)
    point = np.array([0.5, -0.25]) + 2.0 * np.array([np.cos(heading), np.sin(heading)])
    assert arc.distance(point) == pytest.approx(
        np.hypot(*(point - arc.end_points[0])), abs=1e-12
    )
