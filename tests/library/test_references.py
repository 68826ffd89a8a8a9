"""twolink.references: joint references from functions, constants and samples."""

import numpy as np
import pytest

from twolink.references import JointReference

ZERO = np.zeros(2)


def test_reference_from_samples_reproduces_a_cubic_and_holds_its_ends():
    t = np.linspace(0.0, 2.0, 9)
    q = np.column_stack([t**3 - t, 0.5 * t**2])
    qd = np.column_stack([3 * t**2 - 1, t])
    reference = JointReference.from_samples(t, q, qd)  # clamped ends: exact for a cubic
    for time in [0.1, 0.77, 1.5, 1.99]:
        q_ref, qd_ref, qdd_ref = reference(time)
        assert np.allclose(q_ref, [time**3 - time, 0.5 * time**2], atol=1e-12)
        assert np.allclose(qd_ref, [3 * time**2 - 1, time], atol=1e-12)
        assert np.allclose(qdd_ref, [6 * time, 1.0], atol=1e-11)
    for time, end in [(-1.0, 0), (3.0, -1)]:
        q_ref, qd_ref, qdd_ref = reference(time)
        assert (
            np.array_equal(q_ref, q[end])
            and np.array_equal(qd_ref, ZERO)
            and np.array_equal(qdd_ref, ZERO)
        )


@pytest.mark.parametrize(
    "t, q, message",
    [
        ([0.0, 1.0, 1.0, 2.0], np.zeros((4, 2)), "strictly increasing"),
        ([0.0, 1.0, 2.0, 3.0], np.zeros((3, 2)), r"must have shape \(4, 2\)"),
        ([0.0, 1.0, 2.0], np.zeros((3, 2)), "at least 4 samples"),
        ([0.0, 1.0, 2.0, 3.0], [[0, 0], [0, 0], [0, np.nan], [0, 0]], "finite"),
    ],
)
def test_reference_from_bad_samples_raises(t, q, message):
    with pytest.raises(ValueError, match=message):
        JointReference.from_samples(t, q)


def test_a_constant_reference_holds_its_pair_at_rest():
    hold = JointReference.constant([0.5, 1.0])
    for time in [0.0, 2.0, 1e6]:
        q_ref, qd_ref, qdd_ref = hold(time)
        assert np.array_equal(q_ref, [0.5, 1.0])
        assert np.array_equal(qd_ref, ZERO) and np.array_equal(qdd_ref, ZERO)


def test_a_reference_of_functions_gives_their_values():
    wave = JointReference(
        lambda t: [np.sin(t), 0.0],
        lambda t: [np.cos(t), 0.0],
        lambda t: [-np.sin(t), 0.0],
    )
    q_ref, qd_ref, qdd_ref = wave(0.5)
    assert np.allclose(q_ref, [np.sin(0.5), 0.0])
    assert np.allclose(qd_ref, [np.cos(0.5), 0.0])
    assert np.allclose(qdd_ref, [-np.sin(0.5), 0.0])


@pytest.mark.parametrize("bad", [3.0, None, "sin"])
def test_a_reference_that_is_not_a_function_of_time_is_refused(bad):
    with pytest.raises(ValueError, match="must be a callable of time"):
        JointReference(bad, np.cos, np.sin)
