"""Edges of trajectories: paths through singular points (issue 11, class 4)."""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from twolink import TwoLinkArm, UnreachableError, arms, trajectory


@settings(max_examples=60)
@given(
    heading=st.floats(-np.pi, np.pi),
    before=st.floats(0.2, 3.5),
    after=st.floats(0.2, 3.5),
    n=st.integers(8, 200),
    length=st.sampled_from([0.5, 2.0, 3.0]),
)
@example(
    heading=1.0, before=1.0, after=1.0, n=99, length=0.5
)  # the middle sample misses the base by round-off
def test_a_line_through_the_base_of_an_equal_link_arm_is_followed_continuously(
    heading, before, after, n, length
):
    arm = TwoLinkArm(length, length)
    direction = np.array([np.cos(heading), np.sin(heading)])
    reach = 2.0 * length
    start, end = (
        -before / 3.5 * 0.95 * reach * direction,
        after / 3.5 * 0.95 * reach * direction,
    )
    line = trajectory.LinePath(start, end, duration=1.0, law="linear")
    motion = trajectory.ik_trajectory(arm, line, n=n)
    assert motion.tracking_error().max() <= 1e-12 * reach
    # each joint moves at most a few times the sample spacing over the link length (no jump of pi)
    spacing = np.hypot(*(end - start)) / (n - 1)
    assert motion.joint_steps.max() <= 8.0 * spacing / length + 1e-9
    assert (
        len(motion.branch_switches) == 1
    )  # the branch changes once, where the tip passes the base
    assert np.all(motion.within_limits)


def test_through_the_base_q2_passes_through_pi_and_q1_does_not_jump():
    line = trajectory.LinePath([-2.0, -1.0], [2.0, 1.0], duration=1.0, law="linear")
    motion = trajectory.ik_trajectory(
        arms.two_metre, line, n=51
    )  # sample 25 is the base itself
    assert motion.joint_steps.max() < 0.06
    k = motion.branch_switches[0]
    assert (
        abs(abs(motion.q[k - 1, 1]) - np.pi) < 0.06
        and abs(abs(motion.q[k, 1]) - np.pi) < 0.06
    )
    # q1 -> atan2(1, 2) - pi/2 from both sides (the base sample keeps it), instead of turning by pi
    assert motion.q[25, 0] == pytest.approx(
        np.arctan2(1.0, 2.0) + np.pi / 2, abs=0.06
    ) or motion.q[25, 0] == pytest.approx(np.arctan2(1.0, 2.0) - np.pi / 2, abs=0.06)


def test_samples_too_far_apart_to_join_continuously_are_an_error_naming_them():
    with pytest.raises(
        UnreachableError, match=r"between path points 0 and 1 .* jump by .* deg"
    ):
        trajectory.ik_trajectory(arms.two_metre, [[3.5, 0.0], [-3.5, 0.0]])


def test_paths_on_one_branch_are_unchanged():
    line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    motion = trajectory.ik_trajectory(arms.two_metre, line, n=50)
    assert motion.branch_switches == () and motion.elbow == "down"
    assert motion.joint_steps.max() < trajectory.JUMP_TOL


# ---------------------------------------------------------------- issue 12: vocabulary and data that flows


@pytest.mark.parametrize("word", ["Down", "elbow-up", None, 1])
def test_an_elbow_outside_the_vocabulary_is_refused_naming_the_words(word):
    line = trajectory.LinePath([12.0, 12.0], [13.0, 14.0], duration=1.0)
    with pytest.raises(
        ValueError, match=r"elbow must be one of \('down', 'up', 'auto'\)"
    ):
        trajectory.ik_trajectory(arms.ten, line, n=5, elbow=word)
    with pytest.raises(
        ValueError, match=r"elbow must be one of \('down', 'up', 'auto'\)"
    ):
        trajectory.resolved_rate_trajectory(arms.ten, line, n=5, elbow=word)


def test_a_two_sample_trajectory_still_gives_a_reference():
    motion = trajectory.ik_trajectory(arms.two_metre, [[3.0, 0.5], [3.0, 1.0]])
    assert motion.t.tolist() == [0.0, 1.0] and np.all(np.isfinite(motion.qdd))
    reference = motion.joint_reference()
    for k in range(2):
        assert all(
            np.array_equal(got, want[k])
            for got, want in zip(
                reference(motion.t[k]), (motion.q, motion.qd, motion.qdd)
            )
        )
    middle = reference(0.5)[0]
    assert np.all(
        (np.minimum(*motion.q) - 0.1 < middle) & (middle < np.maximum(*motion.q) + 0.1)
    )


def test_path_positions_needs_a_1d_array_of_finite_times():
    line = trajectory.LinePath([0.0, 0.0], [1.0, 0.0], duration=1.0)
    with pytest.raises(
        ValueError,
        match=r"t must be a 1-D array of finite times \(s\); got shape \(2, 1\)",
    ):
        trajectory.path_positions(line, [[0.0], [1.0]])
    with pytest.raises(ValueError, match="t must be a 1-D array of finite times"):
        trajectory.path_positions(line, [0.0, np.nan])


def test_damped_resolved_rate_from_a_singular_pose_has_finite_accelerations():
    line = trajectory.LinePath([4.0, 0.0], [3.0, 1.0], duration=1.0)
    damped = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=20, damping=0.05
    )
    assert abs(np.sin(damped.q[0, 1])) < 1e-12
    assert np.all(np.isfinite(damped.qdd)) and np.abs(damped.qdd).max() > 0.0
