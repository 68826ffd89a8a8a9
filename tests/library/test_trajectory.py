"""Cartesian paths, time laws and the joint trajectories that follow them."""

import time
from types import SimpleNamespace

import numpy as np
import pytest
import scipy.integrate
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from conftest import unit
from twolink import (
    SimulationError,
    SingularityError,
    TwoLinkArm,
    UnreachableError,
    arms,
    controllers,
    ik,
    simulate,
    trajectory,
    workspace,
)
from twolink.trajectory import CirclePath, LinePath

TEN_ARCS = {
    elbow: workspace.boundary_arcs(arms.ten, elbow=elbow) for elbow in ("down", "up")
}
durations = st.floats(min_value=0.1, max_value=20.0)
laws = st.sampled_from(trajectory.TIME_LAWS)
#: The parameters of a CirclePath, drawn together (the circle tests share them).
CIRCLES = {
    "centre": st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    "radius": st.floats(0.1, 5),
    "duration": durations,
    "law": laws,
    "start": st.floats(-np.pi, np.pi),
    "turns": st.sampled_from([1.0, -1.0, 0.25, 2.0]),
}


# ---------------------------------------------------------------- time laws and paths


@given(duration=durations, law=laws)
def test_time_law_runs_from_zero_to_one_monotonically_with_the_right_rate(
    duration, law
):
    t = np.linspace(0.0, duration, 2001)
    s, s_dot = trajectory.time_scaling(t, duration, law)
    assert s[0] == 0.0 and s[-1] == pytest.approx(1.0, abs=1e-15)
    assert np.all(np.diff(s) >= 0.0)
    assert np.all(s_dot >= 0.0)
    # the rate is the derivative of s (central differences, O(dt^2))
    dt = t[1] - t[0]
    assert np.allclose(s_dot[1:-1], (s[2:] - s[:-2]) / (2 * dt), atol=1e-5 / duration)


@given(duration=durations)
def test_cubic_and_quintic_start_and_stop_at_rest_quintic_also_without_acceleration(
    duration,
):
    for law in ("cubic", "quintic"):
        _, s_dot = trajectory.time_scaling(np.array([0.0, duration]), duration, law)
        assert np.all(s_dot == 0.0)
    h = duration * 1e-4
    _, s_dot = trajectory.time_scaling(
        np.array([0.0, h, duration - h, duration]), duration, "quintic"
    )
    assert (
        abs(s_dot[1] - s_dot[0]) / h < 1e-2 / duration**2
    )  # acceleration ~ 0 at the start
    assert abs(s_dot[3] - s_dot[2]) / h < 1e-2 / duration**2  # and at the end
    _, s_dot = trajectory.time_scaling(np.array([0.0, h]), duration, "cubic")
    assert (s_dot[1] - s_dot[0]) / h == pytest.approx(
        6.0 / duration**2, rel=1e-3
    )  # cubic starts with a jerk


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
def test_line_path_runs_along_the_segment_with_consistent_velocity(
    start, end, duration, law
):
    line = LinePath(start, end, duration, law)
    t, p, v = line.sample(401)
    assert np.allclose(p[0], start) and np.allclose(p[-1], end)
    chord = np.subtract(end, start)
    # every point on the segment: cross product with the chord is zero
    offsets = p - np.asarray(start)
    assert np.allclose(
        offsets[:, 0] * chord[1] - offsets[:, 1] * chord[0], 0.0, atol=1e-9
    )
    dt = t[1] - t[0]
    assert np.allclose(
        v[1:-1], (p[2:] - p[:-2]) / (2 * dt), atol=1e-3 * (1 + line.length) / duration
    )


@given(**CIRCLES)
def test_circle_path_stays_on_the_circle_with_consistent_velocity(
    centre, radius, duration, law, start, turns
):
    circle = CirclePath(centre, radius, duration, law, start_angle=start, turns=turns)
    t, p, v = circle.sample(801)
    assert np.allclose(np.hypot(*(p - np.asarray(centre)).T), radius)
    assert np.allclose(
        p[0], np.asarray(centre) + radius * np.array([np.cos(start), np.sin(start)])
    )
    dt = t[1] - t[0]
    assert np.allclose(
        v[1:-1], (p[2:] - p[:-2]) / (2 * dt), atol=1e-3 * (1 + circle.length) / duration
    )
    assert circle.length == pytest.approx(2 * np.pi * radius * abs(turns))


def test_paths_refuse_bad_input():
    with pytest.raises(ValueError, match="p_start"):
        LinePath([0.0, 0.0, 1.0], [1.0, 1.0], 1.0)
    with pytest.raises(ValueError, match="radius"):
        CirclePath([0.0, 0.0], -1.0, 1.0)
    with pytest.raises(ValueError, match="turns"):
        CirclePath([0.0, 0.0], 1.0, 1.0, turns=0.0)
    with pytest.raises(
        ValueError, match=r"n \(samples, both ends included\) must be an integer >= 2"
    ):
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
    centre_distance = (
        10 * np.sqrt(2) + 0.6 + radius_fraction * (20 - 10 * np.sqrt(2) - 1.2)
    )
    centre = centre_distance * np.array([np.cos(heading), np.sin(heading)])
    room = float(workspace.clearance(arms.ten, centre, TEN_ARCS[elbow], elbow=elbow))
    radius = size * (
        room - 0.5
    )  # keep 0.5 m from the edge (and so from the singular circle r = 20)
    assume(radius > 0.05)
    motion = trajectory.ik_trajectory(
        arms.ten,
        CirclePath(centre, radius, 3.0, law, start_angle=start),
        n=200,
        elbow=elbow,
    )
    assert motion.elbow == elbow
    assert np.all(motion.within_limits)
    assert motion.tracking_error().max() <= 1e-12 * 20
    assert np.all(motion.joint_steps <= step_bound(arms.ten, motion))
    # one branch throughout: sin q2 never changes sign
    assert np.all(np.sign(np.sin(motion.q[:, 1])) == (1.0 if elbow == "down" else -1.0))


def test_a_circle_inside_the_workspace_may_still_need_a_branch_flip():
    """The largest circle centred on the 45 deg line touches the inner edge where only elbow up
    (left of 45 deg) or only elbow down (right of it) is within the limits."""
    centre, radius = (
        np.array([1.0, 1.0]) * (20.0 - (10 - 5 * np.sqrt(2))) / np.sqrt(2),
        10 - 5 * np.sqrt(2),
    )
    circle = CirclePath(centre, radius * (1 - 1e-6), 4.0)
    assert np.all(workspace.is_reachable(arms.ten, circle.sample(100)[1]))
    with pytest.raises(
        UnreachableError, match="no elbow branch stays within the joint limits"
    ):
        trajectory.ik_trajectory(arms.ten, circle, n=100)
    # the one-branch largest circle is as large and can be traced
    centre_down, radius_down = workspace.largest_inscribed_circle(
        arms.ten, elbow="down"
    )
    assert radius_down == pytest.approx(radius, abs=1e-8)
    motion = trajectory.ik_trajectory(
        arms.ten, CirclePath(centre_down, radius_down, 4.0), n=100, elbow="down"
    )
    assert np.all(motion.within_limits)


def test_the_line_task_on_the_two_metre_arm_is_continuous_on_both_branches():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="linear")
    for elbow in ("down", "up"):
        motion = trajectory.ik_trajectory(arms.two_metre, line, n=50, elbow=elbow)
        assert motion.elbow == elbow
        assert motion.tracking_error().max() <= 1e-12 * 4
        assert np.all(motion.joint_steps <= step_bound(arms.two_metre, motion))
    # the naive per-point closed form on the up branch wraps q1 past -180 deg: a 360 deg jump
    naive = ik.closed_form(arms.two_metre, line.sample(50)[1], elbow="up").q
    naive_steps = np.max(np.abs(np.diff(naive, axis=0)), axis=-1)
    assert naive_steps.max() > np.pi
    assert np.any(naive_steps > step_bound(arms.two_metre, motion))


def test_auto_branch_prefers_down_and_falls_back_to_up_when_down_leaves_the_limits():
    line = LinePath(
        [12.5, 12.5], [15.0, 1.0], duration=2.0
    )  # elbow down needs q1 < 0 near (15, 1)
    motion = trajectory.ik_trajectory(arms.ten, line, n=30)
    assert motion.elbow == "up" and np.all(motion.within_limits)
    with pytest.raises(
        UnreachableError, match=r"elbow down leaves them at path point \d+"
    ):
        trajectory.ik_trajectory(arms.ten, line, n=30, elbow="down")
    assert (
        trajectory.ik_trajectory(
            arms.ten, LinePath([12.5, 12.5], [13.0, 14.0], 1.0), n=10
        ).elbow
        == "down"
    )


def test_a_path_needing_a_branch_flip_is_refused_with_both_points_named():
    # an arc at r = 17 from -5 deg (only elbow up within limits) to 95 deg (only elbow down)
    arc = CirclePath(
        [0.0, 0.0], 17.0, 2.0, start_angle=np.radians(-5.0), turns=100.0 / 360.0
    )
    assert np.all(
        workspace.is_reachable(arms.ten, arc.sample(40)[1])
    )  # every point is fine on its own
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.ten, arc, n=40)
    message = str(caught.value)
    assert "no elbow branch stays within the joint limits" in message
    assert "elbow down leaves them at path point 0" in message
    assert "elbow up leaves them at path point" in message


def test_a_path_leaving_the_workspace_names_the_first_unreachable_point():
    """The package's one reach message (kinematics.require_within_reach): the point, its index, how many are out."""
    line = LinePath([12.0, 12.0], [16.0, 16.0], duration=1.0, law="linear")
    t, p, _ = line.sample(41)
    outside = np.hypot(*p.T) > 20.0
    first_out = int(np.flatnonzero(outside)[0])
    expected = (
        f"path point ({p[first_out, 0]:.6g}, {p[first_out, 1]:.6g}) (index ({first_out},), first of "
        f"{np.count_nonzero(outside)}) is {np.hypot(*p[first_out]):.6g} m from the base; "
        "this arm reaches distances in [0, 20] m (l1=10, l2=10)"
    )
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.ten, line, n=41)
    assert str(caught.value) == expected
    for q0 in (None, [0.5, 1.0]):
        with pytest.raises(UnreachableError) as caught:
            trajectory.resolved_rate_trajectory(arms.ten, line, n=41, q0=q0)
        assert str(caught.value) == expected


def test_a_path_leaving_the_limits_but_not_the_reach_says_so():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    with pytest.raises(UnreachableError) as caught:
        trajectory.ik_trajectory(arms.two_metre_limited, line, n=50)
    message = str(caught.value)
    assert message.startswith(
        "path point (-3.5, 1) (index (0,), first of 35) is 3.64005 m from the base, inside the reach"
    )
    assert "outside the joint limits" in message and "[35, 145] deg" in message


def test_points_can_be_given_directly_and_bad_arguments_are_refused():
    points = workspace.circle_points([12.5, 12.5], 2.0, 16)
    motion = trajectory.ik_trajectory(arms.ten, points)
    assert np.array_equal(motion.t, np.arange(16.0)) and motion.q.shape == (16, 2)
    with pytest.raises(
        ValueError,
        match=r"elbow must be one of \('down', 'up', 'auto'\); got 'sideways'",
    ):
        trajectory.ik_trajectory(arms.ten, points, elbow="sideways")
    with pytest.raises(
        ValueError, match=r"here; got 'both' \(a path follows one branch at a time"
    ):
        trajectory.ik_trajectory(arms.ten, points, elbow="both")
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
    assert rate.tracking_error().max() < 1e-6
    assert np.allclose(rate.q, closed.q, atol=1e-6)
    assert np.all(rate.within_limits)


def test_resolved_rate_feedback_pulls_a_displaced_start_back_onto_the_path():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="linear")
    q0 = trajectory.ik_trajectory(arms.two_metre, line).q[0] + [0.05, -0.05]
    open_loop = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=50, q0=q0, gain=0.0
    )
    closed_loop = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=50, q0=q0, gain=10.0
    )
    initial = open_loop.tracking_error()[0]
    assert initial > 0.05
    # without feedback the offset is carried along (the velocity is right, the position is not) ...
    assert open_loop.tracking_error()[-1] > 0.5 * initial
    # ... with it the error decays like exp(-gain t): e^-50 after 5 s, down to the integrator's tolerance
    assert closed_loop.tracking_error()[-1] < 1e-6 * initial


def test_resolved_rate_from_a_singular_pose_raises_unless_damped():
    # starting at full stretch (4, 0): sin q2 = 0, J cannot be inverted
    line = LinePath([4.0, 0.0], [3.0, 1.0], duration=1.0)
    with pytest.raises(
        SingularityError,
        match=r"^resolved rate at t = 0 s needs J invertible, but q = \(0, 0\) rad is singular: .*damping > 0",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, n=20)
    damped = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=20, damping=0.05
    )
    assert np.all(np.isfinite(damped.q)) and np.all(np.isfinite(damped.qd))
    # bounded rates: the tip lags at first, then catches up with the path
    assert damped.tracking_error().max() < 0.05
    assert damped.tracking_error()[-1] < 1e-3


def test_resolved_rate_refuses_bad_arguments():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    with pytest.raises(ValueError, match="path object"):
        trajectory.resolved_rate_trajectory(arms.two_metre, [[1.0, 1.0], [2.0, 2.0]])
    with pytest.raises(ValueError, match="gain"):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, gain=-1.0)
    with pytest.raises(
        ValueError,
        match=r"q0 must be one configuration of shape \(2,\) \(radians\); got shape \(1, 2\)",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, q0=[[0.0, 1.0]])
    with pytest.raises(
        ValueError,
        match=r"elbow must be one of \('down', 'up', 'auto'\) here; got 'both' \(a path follows one branch",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, elbow="both")
    q_up = trajectory.ik_trajectory(arms.two_metre, line, elbow="up").q[0]
    with pytest.raises(
        ValueError,
        match=r"q0 = .* rad is on the elbow-up branch, but elbow='down' was asked for",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, q0=q_up, elbow="down")
    assert (
        trajectory.resolved_rate_trajectory(
            arms.two_metre, line, n=5, q0=q_up, elbow="up"
        ).elbow
        == "up"
    )


def test_resolved_rate_tracks_a_constant_speed_line_with_the_commanded_velocity():
    arm = arms.two_metre
    q0 = ik.closed_form(arm, [3.0, -1.0]).q
    line = trajectory.LinePath([3.0, -1.0], [3.0, 1.0], duration=2.0, law="linear")
    motion = trajectory.resolved_rate_trajectory(arm, line, n=21, q0=q0)
    assert motion.tracking_error().max() < 1e-6
    assert np.allclose(motion.p_tip[-1], [3.0, 1.0], atol=1e-6)
    assert np.allclose(arm.tip_velocity(motion.q, motion.qd), [0.0, 1.0], atol=1e-4)


def test_damping_bounds_the_joint_rates_near_a_singularity_at_a_tracking_cost():
    """A line 5 cm from the base of the equal-link arm passes the folded singularity."""
    arm = arms.two_metre
    q0 = ik.closed_form(arm, [-1.5, 0.05]).q
    line = trajectory.LinePath([-1.5, 0.05], [1.5, 0.05], duration=3.0, law="linear")
    exact = trajectory.resolved_rate_trajectory(arm, line, n=301, q0=q0)
    damped = trajectory.resolved_rate_trajectory(arm, line, n=301, q0=q0, damping=0.3)
    assert np.abs(exact.qd).max() > 10.0 * np.abs(damped.qd).max()
    v_command = np.array([1.0, 0.0]) + 10.0 * (
        damped.p_ref - damped.p_tip
    )  # v_ref + gain * error
    # the DLS inverse caps the rates at |v| / (2 lambda)
    assert np.all(
        np.linalg.norm(damped.qd, axis=1)
        <= np.linalg.norm(v_command, axis=1) / (2 * 0.3) + 1e-9
    )
    assert exact.tracking_error().max() < 1e-4 < damped.tracking_error().max()


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


# ---------------------------------------------------------------- path accelerations


def assert_acceleration_is_the_derivative_of_velocity(path):
    """a(t) against the central difference of v(t), inside the path (the linear law's ends are impulsive)."""
    duration = path.duration
    t = np.linspace(0.01, 0.99, 99) * duration
    h = 1e-5 * duration
    _, v, a = path.at(t, with_acceleration=True)
    _, v_plus = path.at(t + h)
    _, v_minus = path.at(t - h)
    scale = np.abs(a).max() + np.abs(v).max() / duration + 1e-12
    assert np.allclose(a, (v_plus - v_minus) / (2 * h), rtol=0.0, atol=1e-6 * scale)
    # the two-value form is the same position and velocity
    p_two, v_two = path.at(t)
    p_three, v_three, _ = path.at(t, with_acceleration=True)
    assert np.array_equal(p_two, p_three) and np.array_equal(v_two, v_three)


@given(
    start=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    end=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    duration=durations,
    law=laws,
)
def test_line_path_acceleration_is_the_derivative_of_its_velocity(
    start, end, duration, law
):
    line = LinePath(start, end, duration, law)
    assert_acceleration_is_the_derivative_of_velocity(line)
    t, p, v, a = line.sample(11, with_acceleration=True)
    # along the chord: no sideways acceleration on a straight line
    chord = np.subtract(end, start)
    assert np.allclose(
        a[:, 0] * chord[1] - a[:, 1] * chord[0], 0.0, atol=1e-9 * (1 + np.abs(a).max())
    )
    assert np.array_equal(a, line.at(t, with_acceleration=True)[2])


@given(**CIRCLES)
def test_circle_path_acceleration_is_the_derivative_of_its_velocity(
    centre, radius, duration, law, start, turns
):
    circle = CirclePath(centre, radius, duration, law, start_angle=start, turns=turns)
    assert_acceleration_is_the_derivative_of_velocity(circle)


@given(
    centre=st.tuples(st.floats(-5, 5), st.floats(-5, 5)),
    radius=st.floats(0.1, 5),
    duration=durations,
    start=st.floats(-np.pi, np.pi),
    turns=st.sampled_from([1.0, -1.0, 0.25, 2.0]),
)
def test_a_circle_at_constant_speed_accelerates_towards_its_centre_by_speed_squared_over_radius(
    centre, radius, duration, start, turns
):
    circle = CirclePath(
        centre, radius, duration, "linear", start_angle=start, turns=turns
    )
    t = np.linspace(0.0, duration, 17)[1:-1]
    p, v, a = circle.at(t, with_acceleration=True)
    speed = circle.length / duration
    assert np.allclose(np.linalg.norm(v, axis=-1), speed)
    towards_centre = (np.asarray(centre) - p) / radius
    assert np.allclose(
        a,
        (speed**2 / radius) * towards_centre,
        rtol=1e-9,
        atol=1e-9 * speed**2 / radius,
    )


def test_paths_wait_at_their_ends_at_rest():
    circle = CirclePath([1.0, 1.0], 0.5, duration=2.0, law="linear")
    p, v, a = circle.at([-1.0, 3.0], with_acceleration=True)
    assert (
        np.allclose(p, [[1.5, 1.0], [1.5, 1.0]])
        and np.all(v == 0.0)
        and np.all(a == 0.0)
    )


# ---------------------------------------------------------------- joint accelerations


def tip_acceleration(arm, q, qd, qdd):
    """d2/dt2 of fk(q(t)), written out with absolute link angles (independent of the package's J and Jdot)."""
    angle_1, angle_12 = q[:, 0], q[:, 0] + q[:, 1]
    rate_1, rate_12 = qd[:, 0], qd[:, 0] + qd[:, 1]
    accel_1, accel_12 = qdd[:, 0], qdd[:, 0] + qdd[:, 1]
    x = -arm.l1 * (np.cos(angle_1) * rate_1**2 + np.sin(angle_1) * accel_1) - arm.l2 * (
        np.cos(angle_12) * rate_12**2 + np.sin(angle_12) * accel_12
    )
    y = -arm.l1 * (np.sin(angle_1) * rate_1**2 - np.cos(angle_1) * accel_1) - arm.l2 * (
        np.sin(angle_12) * rate_12**2 - np.cos(angle_12) * accel_12
    )
    return np.column_stack([x, y])


@settings(max_examples=50)
@given(
    elbow=st.sampled_from(["down", "up"]),
    law=laws,
    radius=st.floats(0.05, 1.5),
    start=st.floats(-np.pi, np.pi),
    turns=st.sampled_from([1.0, -1.0, 0.5]),
)
def test_ik_trajectory_accelerations_are_exact_for_path_objects(
    elbow, law, radius, start, turns
):
    """J qd = v and d2/dt2 fk(q) = a at every sample, to round-off: no finite differences."""
    arm = arms.two_metre
    circle = CirclePath(
        [2.0, 1.0], radius, duration=3.0, law=law, start_angle=start, turns=turns
    )
    motion = trajectory.ik_trajectory(arm, circle, n=25, elbow=elbow)
    _, _, v, a = circle.sample(25, with_acceleration=True)
    assert motion.qdd.shape == motion.q.shape == (25, 2)
    assert np.allclose(
        arm.tip_velocity(motion.q, motion.qd),
        v,
        rtol=0,
        atol=1e-12 * (1 + np.abs(v).max()),
    )
    got = tip_acceleration(arm, motion.q, motion.qd, motion.qdd)
    assert np.allclose(got, a, rtol=0, atol=1e-11 * (1 + np.abs(a).max()))


def test_ik_trajectory_accelerations_agree_with_finite_differences_of_the_rates():
    circle = CirclePath([12.5, 12.5], 2.0, duration=4.0, law="quintic")
    motion = trajectory.ik_trajectory(arms.ten, circle, n=4001)
    differences = np.gradient(motion.qd, motion.t, axis=0)
    assert np.allclose(
        motion.qdd[1:-1],
        differences[1:-1],
        rtol=0,
        atol=1e-5 * np.abs(motion.qdd).max(),
    )
    # the quintic law starts and ends at rest without acceleration: so do the joints
    assert np.all(motion.qd[[0, -1]] == 0.0) and np.allclose(
        motion.qdd[[0, -1]], 0.0, atol=1e-15
    )


def test_points_give_finite_difference_rates_and_accelerations():
    points = workspace.circle_points([12.5, 12.5], 2.0, 16)
    motion = trajectory.ik_trajectory(arms.ten, points)
    assert np.array_equal(
        motion.qd, np.gradient(motion.q, motion.t, axis=0, edge_order=2)
    )
    assert np.array_equal(
        motion.qdd, np.gradient(motion.qd, motion.t, axis=0, edge_order=2)
    )


def test_near_a_singularity_the_rates_and_accelerations_fall_back_to_finite_differences():
    """A line through the base of the equal-link arm passes the folded pose: finite, continuous values there."""
    line = LinePath([-2.0, -1.0], [2.0, 1.0], duration=1.0, law="quintic")
    motion = trajectory.ik_trajectory(arms.two_metre, line, n=51)
    singular = np.abs(np.sin(motion.q[:, 1])) <= trajectory.RATE_SINGULARITY_TOL
    assert (
        np.any(singular)
        and np.all(np.isfinite(motion.qd))
        and np.all(np.isfinite(motion.qdd))
    )
    regular = ~singular
    _, _, v, a = line.sample(51, with_acceleration=True)
    assert np.allclose(
        arms.two_metre.tip_velocity(motion.q[regular], motion.qd[regular]),
        v[regular],
        atol=1e-9,
    )
    assert np.allclose(
        tip_acceleration(arms.two_metre, motion.q, motion.qd, motion.qdd)[regular],
        a[regular],
        atol=1e-8,
    )


@pytest.mark.parametrize("damping", [0.0, 0.3])
def test_resolved_rate_accelerations_are_the_derivative_of_the_commanded_rates(damping):
    """Past the base (where damping matters: smallest singular value ~ 0.25 m/rad) from a displaced start (the feedback acts).

    Every millisecond: the central differences' own error is then about 1e-5 of
    the largest acceleration, a tenth of what the comparison allows.
    """
    arm = arms.two_metre
    line = LinePath([-1.5, 0.5], [1.5, 0.5], duration=3.0, law="cubic")
    q0 = ik.closed_form(arm, [-1.5, 0.5]).q + [0.02, -0.02]
    motion = trajectory.resolved_rate_trajectory(
        arm, line, n=3001, q0=q0, damping=damping, rtol=1e-11
    )
    differences = np.gradient(motion.qd, motion.t, axis=0)
    interior = slice(2, -2)
    scale = np.abs(motion.qdd).max()
    assert scale > 1.0
    assert np.allclose(
        motion.qdd[interior], differences[interior], rtol=0, atol=1e-4 * scale
    )


# ---------------------------------------------------------------- joint references


@settings(max_examples=50)
@given(
    steps=st.lists(st.floats(1e-3, 2.0), min_size=1, max_size=12),
    start=st.floats(-5.0, 5.0),
    seed=st.integers(0, 2**32 - 1),
)
def test_joint_reference_reproduces_the_samples_and_is_smooth_between_them(
    steps, start, seed
):
    rng = np.random.default_rng(seed)
    t = start + np.concatenate([[0.0], np.cumsum(steps)])
    count = len(t)
    q, qd, qdd = rng.uniform(-3.0, 3.0, (3, count, 2))
    motion = trajectory.JointTrajectory(
        arm=arms.two_metre,
        t=t,
        q=q,
        qd=qd,
        qdd=qdd,
        p_ref=arms.two_metre.fk(q),
        elbow="down",
        method="closed form",
    )
    reference = motion.joint_reference()
    for k in range(count):
        q_ref, qd_ref, qdd_ref = reference(t[k])
        # the angles exactly; the rates and accelerations to the round-off of the
        # polynomial's coefficients (angles, h rates, h^2 accelerations), divided by h and h^2
        h = min(np.diff(t)[max(k - 1, 0) : k + 1])
        assert np.array_equal(q_ref, q[k])
        assert np.allclose(qd_ref, qd[k], rtol=0, atol=1e-13 * (3.0 + 3.0 / h))
        assert np.allclose(
            qdd_ref, qdd[k], rtol=0, atol=1e-13 * (3.0 + 3.0 / h + 3.0 / h**2)
        )
    # inside an interval, rate and acceleration are the derivatives of the position and the rate
    k = int(rng.integers(count - 1))
    h = t[k + 1] - t[k]
    middle, step = t[k] + rng.uniform(0.1, 0.9) * h, 1e-4 * h
    before, after = reference(middle - step), reference(middle + step)
    now = reference(middle)
    for order in (0, 1):
        slope = (after[order] - before[order]) / (2 * step)
        size = max(1.0, np.abs(now[order + 1]).max(), np.abs(slope).max())
        assert np.allclose(
            now[order + 1], slope, rtol=0, atol=1e-5 * size * (1 + 1 / h)
        )
    # outside the samples: held at the ends, at rest
    q_before, qd_before, qdd_before = reference(t[0] - 1.0)
    q_after, qd_after, qdd_after = reference(t[-1] + 1.0)
    assert np.array_equal(q_before, q[0]) and np.array_equal(q_after, q[-1])
    assert (
        not np.any(qd_before)
        and not np.any(qdd_before)
        and not np.any(qd_after)
        and not np.any(qdd_after)
    )


def test_a_trajectorys_reference_is_quintic_its_error_falls_with_the_sixth_power_of_the_step():
    arm = arms.two_metre
    circle = CirclePath((2.5, 1.0), 0.75, duration=2.0, law="quintic")
    t_fine = np.linspace(0.0, 2.0, 2001)
    errors = []
    for n in (26, 51):
        reference = trajectory.ik_trajectory(arm, circle, n=n).joint_reference()
        q_fine = np.array([reference(time)[0] for time in t_fine])
        errors.append(np.hypot(*(arm.fk(q_fine) - circle.at(t_fine)[0]).T).max())
    assert (
        errors[1] < 1e-6 and errors[0] / errors[1] > 32.0
    )  # halving h: 2^6 = 64 for a quintic, 16 for a cubic


def test_computed_torque_tracking_a_trajectorys_reference_follows_the_path():
    """No spline refit: the arm follows the joint reference, so its tip follows the circle to the interpolation error."""
    arm = arms.two_metre
    circle = CirclePath((2.5, 1.0), 0.75, duration=2.0, law="quintic")
    motion = trajectory.ik_trajectory(arm, circle, n=51, elbow="down")
    reference = motion.joint_reference()
    t = np.linspace(0.0, 2.5, 251)
    q_reference = np.array([reference(time)[0] for time in t])
    interpolation = np.hypot(*(arm.fk(q_reference) - circle.at(t)[0]).T)
    tracker = controllers.ComputedTorque(arm, kp=400.0, kd=40.0, reference=reference)
    run = simulate(arm, motion.q[0], motion.qd[0], 2.5, torque=tracker, t_eval=t)
    error = run.tracking_error(circle)
    assert error.max() < 1e-6
    assert np.allclose(
        error, interpolation, rtol=0, atol=1e-8
    )  # the solver adds (almost) nothing
    # PD with gravity compensation lags, less with stiffer gains, and settles once the reference stops
    M_start = arm.mass_matrix(motion.q[0])
    lags = []
    for omega_n in (20.0, 80.0):
        pd = controllers.JointPD(
            arm, kp=omega_n**2 * M_start, kd=2 * omega_n * M_start, reference=reference
        )
        pd_run = simulate(arm, motion.q[0], motion.qd[0], 2.5, torque=pd, t_eval=t)
        lags.append(pd_run.tracking_error(circle))
        assert lags[-1][-1] < 1e-4
    assert lags[1].max() < 0.02 and lags[1].max() < lags[0].max() / 10


# ---------------------------------------------------------------- tracking error


def test_tracking_error_takes_a_path_a_trajectory_or_points():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0, law="linear")
    q0 = trajectory.ik_trajectory(arms.two_metre, line).q[0] + [0.05, -0.05]
    motion = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=30, q0=q0, gain=1.0
    )
    by_hand = np.linalg.norm(
        arms.two_metre.fk(motion.q) - line.at(motion.t)[0], axis=-1
    )
    assert by_hand[0] > 0.05
    assert np.array_equal(motion.p_tip, arms.two_metre.fk(motion.q))
    for path in (None, line, motion, motion.p_ref):
        assert np.allclose(motion.tracking_error(path), by_hand, rtol=0, atol=1e-15)
    assert np.allclose(
        motion.tracking_error(line.p_end),
        np.linalg.norm(motion.p_tip - line.p_end, axis=-1),
    )


def test_tracking_error_refuses_what_it_cannot_compare():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=5.0)
    motion = trajectory.ik_trajectory(arms.two_metre, line, n=20)
    other = trajectory.ik_trajectory(arms.two_metre, line, n=21)
    with pytest.raises(
        ValueError,
        match=r"sampled at 21 times .* not at these 20 times .* t_eval=trajectory.t",
    ):
        motion.tracking_error(other)
    with pytest.raises(ValueError, match=r"path points must have shape \(20, 2\)"):
        motion.tracking_error(motion.p_ref[:5])
    with pytest.raises(
        TypeError,
        match="path must be a LinePath or CirclePath, a JointTrajectory, or points",
    ):
        motion.tracking_error("the line")


# ----------------------------------------------------------------- edges: huge turns and gains, the budgets
@pytest.mark.parametrize("turns", [1e308, -1e7, 0.0])
def test_a_circle_refuses_turns_beyond_what_float64_can_place(turns):
    with pytest.raises(
        ValueError, match=r"turns must be non-zero and at most 1e\+06 round either way"
    ):
        CirclePath([3.0, 0.0], 0.5, 2.0, turns=turns)


def test_a_million_turns_still_give_points_on_the_circle():
    circle = CirclePath([3.0, 0.0], 0.5, 2.0, law="linear", turns=-trajectory.MAX_TURNS)
    p, v = circle.at(np.linspace(0.0, 2.0, 7))
    assert np.allclose(np.hypot(*(p - [3.0, 0.0]).T), 0.5, rtol=0.0, atol=1e-9)
    assert np.all(np.isfinite(v))


def test_a_path_too_large_for_float64_is_an_overflow_error_not_nan():
    with pytest.raises(
        OverflowError, match=r"the path's positions \(m\) overflow float64"
    ):
        LinePath([-1e308, 0.0], [1e308, 0.0], duration=1.0).at(0.5)


def test_resolved_rate_refuses_a_gain_beyond_the_feedback_bound_at_once():
    line = LinePath([3.0, 1.0], [3.0, 0.5], duration=1.0)
    with pytest.raises(
        ValueError,
        match=r"gain \(1/s\) times the path's duration must be at most MAX_FEEDBACK = 1e\+09",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, gain=1e308)


def test_resolved_rate_at_the_feedback_bound_still_tracks_the_path():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=1.0)
    motion = trajectory.resolved_rate_trajectory(
        arms.two_metre, line, n=20, gain=trajectory.MAX_FEEDBACK
    )
    assert motion.tracking_error().max() < 1e-6


def test_resolved_rate_stops_at_its_wall_time_budget_naming_it():
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=1.0)
    with pytest.raises(
        SimulationError,
        match=r"resolved rate \(gain 10 1/s\) used up its budget of max_wall_time = 1e-06 s at t = .* "
        r"with method 'RK45' \(state q = \(",
    ):
        trajectory.resolved_rate_trajectory(
            arms.two_metre, line, n=20, max_wall_time=1e-6
        )


def test_a_failed_resolved_rate_integration_names_the_time_it_reached(monkeypatch):
    """A solver that fails on its first step has no output times: the message still says where it stopped."""

    def failing_at_once(fun, t_span, y0, **options):
        fun(0.25, y0)
        return SimpleNamespace(
            success=False,
            status=-1,
            t=np.empty(0),
            message="Required step size is less than spacing between numbers.",
        )

    monkeypatch.setattr(
        scipy.integrate, "solve_ivp", failing_at_once
    )  # imported by the call: patch it at the source
    line = LinePath([-3.5, 1.0], [-1.0, 3.5], duration=1.0)
    with pytest.raises(
        SimulationError,
        match=r"resolved rate \(gain 10 1/s\) failed at t = 0.25 s of 1 s with method 'RK45': Required step",
    ):
        trajectory.resolved_rate_trajectory(arms.two_metre, line, n=20)


# ------------------------------------------------------ paths through singular points
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


# ------------------------------------------------ one vocabulary, and data that flows
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
            np.allclose(got, want[k], rtol=0.0, atol=1e-14)
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


def test_resolved_rate_with_a_huge_gain_runs_in_seconds():
    line = trajectory.LinePath([-3.5, 1.0], [-1.0, 3.5], duration=1.0)
    start = time.monotonic()
    motion = trajectory.resolved_rate_trajectory(arms.two_metre, line, n=20, gain=1e6)
    assert time.monotonic() - start < 10.0
    assert motion.tracking_error().max() < 1e-6
