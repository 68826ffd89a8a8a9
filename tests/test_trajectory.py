"""Cartesian paths, time laws and the joint trajectories that follow them."""

import numpy as np
import pytest
from conftest import unit
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from twolink import SingularityError, UnreachableError, arms, ik, trajectory, workspace
from twolink.trajectory import CirclePath, LinePath

TEN_ARCS = {elbow: workspace.boundary_arcs(arms.ten, elbow=elbow) for elbow in ("down", "up")}
durations = st.floats(min_value=0.1, max_value=20.0)
laws = st.sampled_from(trajectory.TIME_LAWS)


# ---------------------------------------------------------------- time laws and paths


@given(duration=durations, law=laws)
def test_time_law_runs_from_zero_to_one_monotonically_with_the_right_rate(duration, law):
    t = np.linspace(0.0, duration, 2001)
    s, s_dot = trajectory.time_scaling(t, duration, law)
    assert s[0] == 0.0 and s[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.all(np.diff(s) >= 0.0)
    assert np.all(s_dot >= 0.0)
    # the rate is the derivative of s (central differences, O(dt^2))
    dt = t[1] - t[0]
    assert np.allclose(s_dot[1:-1], (s[2:] - s[:-2]) / (2 * dt), atol=1e-5 / duration)


@given(duration=durations)
def test_cubic_and_quintic_start_and_stop_at_rest_quintic_also_without_acceleration(duration):
    for law in ("cubic", "quintic"):
        _, s_dot = trajectory.time_scaling(np.array([0.0, duration]), duration, law)
        assert np.all(s_dot == 0.0)
    h = duration * 1e-4
    _, s_dot = trajectory.time_scaling(np.array([0.0, h, duration - h, duration]), duration, "quintic")
    assert abs(s_dot[1] - s_dot[0]) / h < 1e-2 / duration**2  # acceleration ~ 0 at the start
    assert abs(s_dot[3] - s_dot[2]) / h < 1e-2 / duration**2  # and at the end
    _, s_dot = trajectory.time_scaling(np.array([0.0, h]), duration, "cubic")
    assert (s_dot[1] - s_dot[0]) / h == pytest.approx(6.0 / duration**2, rel=1e-3)  # cubic starts with a jerk


def test_time_law_refuses_bad_input():
    with pytest.raises(ValueError, match="law must be one of"):
        trajectory.time_scaling(0.5, 1.0, "septic")
    with pytest.raises(ValueError, match="duration"):
        trajectory.time_scaling(0.5, 0.0)
    with pytest.raises(ValueError, match="finite"):
        trajectory.time_scaling([np.nan], 1.0)


@given(
    start=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    end=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    duration=durations,
    law=laws,
)
def test_line_path_runs_along_the_segment_with_consistent_velocity(start, end, duration, law):
    line = LinePath(start, end, duration, law)
    t, p, v = line.sample(401)
    assert np.allclose(p[0], start) and np.allclose(p[-1], end)
    chord = np.subtract(end, start)
    # every point on the segment: cross product with the chord is zero
    offsets = p - np.asarray(start)
    assert np.allclose(offsets[:, 0] * chord[1] - offsets[:, 1] * chord[0], 0.0, atol=1e-9)
    dt = t[1] - t[0]
    assert np.allclose(v[1:-1], (p[2:] - p[:-2]) / (2 * dt), atol=1e-3 * (1 + line.length) / duration)


@given(
    centre=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    radius=st.floats(0.1, 5),
    duration=durations,
    law=laws,
    start=st.floats(-np.pi, np.pi),
    turns=st.sampled_from([1.0, -1.0, 0.25, 2.0]),
)
def test_circle_path_stays_on_the_circle_with_consistent_velocity(centre, radius, duration, law, start, turns):
    circle = CirclePath(centre, radius, duration, law, start_angle=start, turns=turns)
    t, p, v = circle.sample(801)
    assert np.allclose(np.hypot(*(p - np.asarray(centre)).T), radius)
    assert np.allclose(p[0], np.asarray(centre) + radius * np.array([np.cos(start), np.sin(start)]))
    dt = t[1] - t[0]
    assert np.allclose(v[1:-1], (p[2:] - p[:-2]) / (2 * dt), atol=1e-3 * (1 + circle.length) / duration)
    assert circle.length == pytest.approx(2 * np.pi * radius * abs(turns))


def test_paths_refuse_bad_input():
    with pytest.raises(ValueError, match="p_start"):
        LinePath([0.0, 0.0, 1.0], [1.0, 1.0], 1.0)
    with pytest.raises(ValueError, match="radius"):
        CirclePath([0.0, 0.0], -1.0, 1.0)
    with pytest.raises(ValueError, match="turns"):
        CirclePath([0.0, 0.0], 1.0, 1.0, turns=0.0)
    with pytest.raises(ValueError, match=r"n \(samples, both ends included\) must be an integer >= 2"):
        LinePath([0.0, 0.0], [1.0, 1.0], 1.0).sample(1)


# ---------------------------------------------------------------- joint trajectories from the closed form


def step_bound(arm, motion, margin=1.5):
    """Largest joint change a continuous motion may make per step: |dq| <= |J^-1| |dp| to first order."""
    singular_values = np.linalg.svd(arm.jacobian(motion.q), compute_uv=False)
    inverse_norm = 1.0 / singular_values[:, -1]
    worst = np.maximum(inverse_norm[:-1], inverse_norm[1:])
    return margin * worst * np.hypot(*np.diff(motion.p_ref, axis=0).T)


@settings(max_examples=100)
@given(
    elbow=st.sampled_from(["down", "up"]),
    radius_fraction=unit,
    heading=st.floats(0.0, np.pi / 2),
    size=st.floats(0.05, 1.0),
    law=laws,
    start=st.floats(-np.pi, np.pi),
)
def test_circles_inside_one_branch_workspace_give_jump_free_trajectories_within_limits(
    elbow, radius_fraction, heading, size, law, start
):
    centre_distance = 10 * np.sqrt(2) + 0.6 + radius_fraction * (20 - 10 * np.sqrt(2) - 1.2)
    centre = centre_distance * np.array([np.cos(heading), np.sin(heading)])
    room = float(workspace.clearance(arms.ten, centre, TEN_ARCS[elbow], elbow=elbow))
    radius = size * (room - 0.5)  # keep 0.5 m from the edge (and so from the singular circle r = 20)
    assume(radius > 0.05)
    motion = trajectory.ik_trajectory(arms.ten, CirclePath(centre, radius, 3.0, law, start_angle=start), n=200, elbow=elbow)
    assert motion.elbow == elbow
    assert np.all(motion.within_limits)
    assert motion.tracking_error.max() <= 1e-12 * 20
    assert np.all(motion.joint_steps <= step_bound(arms.ten, motion))
    # one branch throughout: sin q2 never changes sign
    assert np.all(np.sign(np.sin(motion.q[:, 1])) == (1.0 if elbow == "down" else -1.0))


def test_a_circle_inside_the_workspace_may_still_need_a_branch_flip():
    """The largest circle centred on the 45 deg line touches the inner edge where only elbow up
    (left of 45 deg) or only elbow down (right of it) is within the limits."""
    centre, radius = np.array([1.0, 1.0]) * (20.0 - (10 - 5 * np.sqrt(2))) / np.sqrt(2), 10 - 5 * np.sqrt(2)
    circle = CirclePath(centre, radius * (1 - 1e-6), 4.0)
    assert np.all(workspace.is_reachable(arms.ten, circle.sample(100)[1]))
    with pytest.raises(UnreachableError, match="no elbow branch stays within the joint limits"):
        trajectory.ik_trajectory(arms.ten, circle, n=100)
    # the one-branch largest circle is as large and can be traced
    centre_down, radius_down = workspace.largest_inscribed_circle(arms.ten, elbow="down")
    assert radius_down == pytest.approx(radius, abs=1e-8)
    motion = trajectory.ik_trajectory(arms.ten, CirclePath(centre_down, radius_down, 4.0), n=100, elbow="down")
    assert np.all(motion.within_limits)


def test_the_line_task_on_the_two_metre_arm_is_continuous_on_both_branches():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="linear")
    for elbow in ("down", "up"):
        motion = trajectory.ik_trajectory(arms.two_metre, line, n=50, elbow=elbow)
        assert motion.elbow == elbow
        assert motion.tracking_error.max() <= 1e-12 * 4
        assert np.all(motion.joint_steps <= step_bound(arms.two_metre, motion))
    # the naive per-point closed form on the up branch wraps q1 past -180 deg: a 360 deg jump
    naive = ik.closed_form(arms.two_metre, line.sample(50)[1], elbow="up").q
    naive_steps = np.max(np.abs(np.diff(naive, axis=0)), axis=-1)
    assert naive_steps.max() > np.pi
    assert np.any(naive_steps > step_bound(arms.two_metre, motion))


def test_auto_branch_prefers_down_and_falls_back_to_up_when_down_leaves_the_limits():
    line = LinePath([12.5, 12.5], [15.0, 1.0], duration=2.0)  # elbow down needs q1 < 0 near (15, 1)
    motion = trajectory.ik_trajectory(arms.ten, line, n=30)
    assert motion.elbow == "up" and np.all(motion.within_limits)
    with pytest.raises(UnreachableError, match=r"elbow down leaves them at path point \d+"):
        trajectory.ik_trajectory(arms.ten, line, n=30, elbow="down")
    assert trajectory.ik_trajectory(arms.ten, LinePath([12.5, 12.5], [13.0, 14.0], 1.0), n=10).elbow == "down"


def test_a_path_needing_a_branch_flip_is_refused_with_both_points_named():
    # an arc at r = 17 from -5 deg (only elbow up within limits) to 95 deg (only elbow down)
    arc = CirclePath([0.0, 0.0], 17.0, 2.0, start_angle=np.radians(-5.0), turns=100.0 / 360.0)
    assert np.all(workspace.is_reachable(arms.ten, arc.sample(40)[1]))  # every point is fine on its own
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.ten, arc, n=40)
    message = str(caught.value)
    assert "no elbow branch stays within the joint limits" in message
    assert "elbow down leaves them at path point 0" in message
    assert "elbow up leaves them at path point" in message


def test_a_path_leaving_the_workspace_names_the_first_unreachable_point():
    line = LinePath([12.0, 12.0], [16.0, 16.0], duration=1.0, law="linear")
    t, p, _ = line.sample(41)
    first_out = int(np.flatnonzero(np.hypot(*p.T) > 20.0)[0])
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.ten, line, n=41)
    message = str(caught.value)
    assert message.startswith(f"path point {first_out} (of 41) at ({p[first_out, 0]:.6g}, {p[first_out, 1]:.6g})")
    assert "outside the reach [0, 20] m" in message
    with pytest.raises(UnreachableError, match=f"path point {first_out} "):
        trajectory.resolved_rate_trajectory(arms.ten, line, n=41)


def test_a_path_leaving_the_limits_but_not_the_reach_says_so():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.two_metre_limited, line, n=50)
    message = str(caught.value)
    assert message.startswith("path point 0 (of 50) at (-3.5, 1)")
    assert "outside the joint limits" in message and "[35, 145] deg" in message


def test_points_can_be_given_directly_and_bad_arguments_are_refused():
    points = workspace.circle_points([12.5, 12.5], 2.0, 16)
    motion = trajectory.ik_trajectory(arms.ten, points)
    assert np.array_equal(motion.t, np.arange(16.0)) and motion.q.shape == (16, 2)
    with pytest.raises(ValueError, match="elbow must be"):
        trajectory.ik_trajectory(arms.ten, points, elbow="sideways")
    with pytest.raises(ValueError, match="shape"):
        trajectory.ik_trajectory(arms.ten, [[12.5, 12.5]])


def test_joint_rates_of_the_ik_trajectory_match_the_inverse_jacobian():
    circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="quintic")
    motion = trajectory.ik_trajectory(arms.ten, circle, n=400)
    _, v = circle.at(motion.t)
    exact = arms.ten.joint_rates(motion.q, v)
    assert np.allclose(motion.qd, exact, atol=1e-3 * np.abs(exact).max())


# ---------------------------------------------------------------- resolved rate


@pytest.mark.parametrize("law", trajectory.TIME_LAWS)
def test_resolved_rate_follows_the_same_joint_path_as_the_closed_form(law):
    circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law=law)
    closed = trajectory.ik_trajectory(arms.ten, circle, n=50)
    rate = trajectory.resolved_rate_trajectory(arms.ten, circle, n=50)
    assert rate.method == "resolved rate" and rate.elbow == closed.elbow
    assert rate.tracking_error.max() < 1e-6
    assert np.allclose(rate.q, closed.q, atol=1e-6)
    assert np.all(rate.within_limits)


def test_resolved_rate_feedback_pulls_a_displaced_start_back_onto_the_path():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="linear")
    q_start = trajectory.ik_trajectory(arms.two_metre, line).q[0] + [0.05, -0.05]
    open_loop = trajectory.resolved_rate_trajectory(arms.two_metre, line, n=50, q_start=q_start, gain=0.0)
    closed_loop = trajectory.resolved_rate_trajectory(arms.two_metre, line, n=50, q_start=q_start, gain=10.0)
    initial = open_loop.tracking_error[0]
    assert initial > 0.05
    # without feedback the offset is carried along (the velocity is right, the position is not) ...
    assert open_loop.tracking_error[-1] > 0.5 * initial
    # ... with it the error decays like exp(-gain t): e^-50 after 5 s, down to the integrator's tolerance
    assert closed_loop.tracking_error[-1] < 1e-6 * initial


def test_resolved_rate_from_a_singular_pose_raises_unless_damped():
    # starting at full stretch (4, 0): sin q2 = 0, J cannot be inverted
    line = LinePath([4.0, 0.0], [3.0, 1.0], duration=1.0)
    with pytest.raises(SingularityError, match=r"at t = 0 s: q = \(0, 0\) rad is singular"):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, n=20)
    damped = trajectory.resolved_rate_trajectory(arms.two_metre, line, n=20, damping=0.05)
    assert np.all(np.isfinite(damped.q)) and np.all(np.isfinite(damped.qd))
    # bounded rates: the tip lags at first, then catches up with the path
    assert damped.tracking_error.max() < 0.05
    assert damped.tracking_error[-1] < 1e-3


def test_resolved_rate_refuses_bad_arguments():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    with pytest.raises(ValueError, match="path object"):
        trajectory.resolved_rate_trajectory(arms.two_metre, [[1.0, 1.0], [2.0, 2.0]])
    with pytest.raises(ValueError, match="gain"):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, gain=-1.0)
    with pytest.raises(ValueError, match="q_start"):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, q_start=[0.0, 1.0, 2.0])


def test_resolved_rate_tracks_a_constant_speed_line_with_the_commanded_velocity():
    arm = arms.two_metre
    q_start = ik.closed_form(arm, [3.0, -1.0]).q
    line = trajectory.LinePath([3.0, -1.0], [3.0, 1.0], duration=2.0, law="linear")
    motion = trajectory.resolved_rate_trajectory(arm, line, n=21, q_start=q_start)
    assert motion.tracking_error.max() < 1e-6
    assert np.allclose(motion.p_tip[-1], [3.0, 1.0], atol=1e-6)
    assert np.allclose(arm.tip_velocity(motion.q, motion.qd), [0.0, 1.0], atol=1e-4)


def test_damping_bounds_the_joint_rates_near_a_singularity_at_a_tracking_cost():
    """A line 5 cm from the base of the equal-link arm passes the folded singularity."""
    arm = arms.two_metre
    q_start = ik.closed_form(arm, [-1.5, 0.05]).q
    line = trajectory.LinePath([-1.5, 0.05], [1.5, 0.05], duration=3.0, law="linear")
    exact = trajectory.resolved_rate_trajectory(arm, line, n=301, q_start=q_start)
    damped = trajectory.resolved_rate_trajectory(arm, line, n=301, q_start=q_start, damping=0.3)
    assert np.abs(exact.qd).max() > 10.0 * np.abs(damped.qd).max()
    v_command = np.array([1.0, 0.0]) + 10.0 * (damped.p_ref - damped.p_tip)  # v_ref + gain * error
    # the DLS inverse caps the rates at |v| / (2 lambda)
    assert np.all(np.linalg.norm(damped.qd, axis=1) <= np.linalg.norm(v_command, axis=1) / (2 * 0.3) + 1e-9)
    assert exact.tracking_error.max() < 1e-4 < damped.tracking_error.max()


@pytest.mark.parametrize("law", ["cubic", "quintic"])
def test_time_scaling_acceleration_matches_finite_differences(law):
    t = np.linspace(0.1, 1.9, 37)
    h = 1e-5
    _, s_dot, s_ddot = trajectory.time_scaling(t, 2.0, law, with_acceleration=True)
    _, s_dot_plus = trajectory.time_scaling(t + h, 2.0, law)
    _, s_dot_minus = trajectory.time_scaling(t - h, 2.0, law)
    assert np.allclose(s_ddot, (s_dot_plus - s_dot_minus) / (2 * h), atol=1e-6)
    assert np.allclose(s_dot, trajectory.time_scaling(t, 2.0, law)[1])


def test_ik_trajectory_rates_are_exact_for_path_objects():
    """J qd reproduces the path's velocity, including at rest at both ends of a quintic move."""
    circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="quintic")
    motion = trajectory.ik_trajectory(arms.ten, circle, n=30)
    _, _, v_path = circle.sample(30)
    assert np.allclose(arms.ten.tip_velocity(motion.q, motion.qd), v_path, atol=1e-12)
    assert np.allclose(motion.qd[[0, -1]], 0.0, atol=1e-15)

