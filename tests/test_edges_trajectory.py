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
@example(heading=1.0, before=1.0, after=1.0, n=99, length=0.5)  # the middle sample misses the base by round-off
def test_a_line_through_the_base_of_an_equal_link_arm_is_followed_continuously(heading, before, after, n, length):
    arm = TwoLinkArm(length, length)
    direction = np.array([np.cos(heading), np.sin(heading)])
    reach = 2.0 * length
    start, end = -before / 3.5 * 0.95 * reach * direction, after / 3.5 * 0.95 * reach * direction
    line = trajectory.LinePath(start, end, duration=1.0, law="linear")
    motion = trajectory.ik_trajectory(arm, line, n=n)
    assert motion.tracking_error.max() <= 1e-12 * reach
    # each joint moves at most a few times the sample spacing over the link length (no jump of pi)
    spacing = np.hypot(*(end - start)) / (n - 1)
    assert motion.joint_steps.max() <= 8.0 * spacing / length + 1e-9
    assert len(motion.branch_switches) == 1  # the branch changes once, where the tip passes the base
    assert np.all(motion.within_limits)


def test_through_the_base_q2_passes_through_pi_and_q1_does_not_jump():
    line = trajectory.LinePath([-2.0, -1.0], [2.0, 1.0], duration=1.0, law="linear")
    motion = trajectory.ik_trajectory(arms.two_metre, line, n=51)  # sample 25 is the base itself
    assert motion.joint_steps.max() < 0.06
    k = motion.branch_switches[0]
    assert abs(abs(motion.q[k - 1, 1]) - np.pi) < 0.06 and abs(abs(motion.q[k, 1]) - np.pi) < 0.06
    # q1 -> atan2(1, 2) - pi/2 from both sides (the base sample keeps it), instead of turning by pi
    assert motion.q[25, 0] == pytest.approx(np.arctan2(1.0, 2.0) + np.pi / 2, abs=0.06) or motion.q[25, 0] == pytest.approx(
        np.arctan2(1.0, 2.0) - np.pi / 2, abs=0.06
    )


def test_samples_too_far_apart_to_join_continuously_are_an_error_naming_them():
    with pytest.raises(UnreachableError, match=r"between path points 0 and 1 .* jump by .* deg"):
        trajectory.ik_trajectory(arms.two_metre, [[3.5, 0.0], [-3.5, 0.0]])


def test_paths_on_one_branch_are_unchanged():
    line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    motion = trajectory.ik_trajectory(arms.two_metre, line, n=50)
    assert motion.branch_switches == () and motion.elbow == "down"
    assert motion.joint_steps.max() < trajectory.JUMP_TOL
