"""The workspace with joint limits: reachability, boundary arcs, clearance, largest circle."""

import re
from dataclasses import replace

import numpy as np
import pytest
from _cases import limited_arms, stable_id
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from conftest import angles, lengths, unit
from twolink import (
    TwoLinkArm,
    UnreachableError,
    arms,
    ik,
    kinematics,
    to_absolute,
    workspace,
    wrap_angle,
)
from twolink.arcs import Arc, circle_intersections
from twolink.errors import InputTypeError


def configuration_within(arm, fractions):
    """The configuration at ``fractions`` (each in [0, 1]) across the limit box, in relative angles."""
    angles_in_box = np.asarray(arm.q_min) + np.asarray(fractions) * (
        np.asarray(arm.q_max) - np.asarray(arm.q_min)
    )
    if arm.limit_convention == "absolute":
        return np.array([angles_in_box[0], angles_in_box[1] - angles_in_box[0]])
    return angles_in_box


# ---------------------------------------------------------------- reachability, independent descriptions


def ten_region(p, elbow="auto"):
    """arms.ten by geometry: tip at distance r = 20 cos(q2 / 2) in direction q1 + q2 / 2, so
    10 sqrt 2 <= r <= 20 and q1 = direction -+ acos(r / 20) in [0, 90] deg (- elbow down, + up)."""
    r = np.hypot(p[..., 0], p[..., 1])
    direction = np.arctan2(p[..., 1], p[..., 0])
    half_bend = np.arccos(np.clip(r / 20.0, -1.0, 1.0))
    in_band = (r >= 10 * np.sqrt(2)) & (r <= 20.0)
    down = (direction - half_bend >= 0.0) & (direction - half_bend <= np.pi / 2)
    up = (direction + half_bend >= 0.0) & (direction + half_bend <= np.pi / 2)
    return (
        in_band & {"auto": down | up, "down": down, "up": up, "both": down & up}[elbow]
    )


def two_metre_limited_region(p):
    """arms.two_metre_limited by geometry: equal links, so the link angles are
    direction -+ acos(r / 4), and both must lie in [35, 145] deg."""
    r = np.hypot(p[..., 0], p[..., 1])
    direction = np.arctan2(p[..., 1], p[..., 0])
    half_bend = np.arccos(np.clip(r / 4.0, -1.0, 1.0))
    low, high = np.radians(35.0), np.radians(145.0)
    return (r <= 4.0) & (direction - half_bend >= low) & (direction + half_bend <= high)


@pytest.mark.parametrize(
    "arm, region, box, elbow",
    [
        (arms.ten, ten_region, (-25.0, 25.0), "auto"),
        (arms.ten, ten_region, (-25.0, 25.0), "down"),
        (arms.ten, ten_region, (-25.0, 25.0), "up"),
        (arms.ten, ten_region, (0.0, 20.0), "both"),  # a smaller region: a smaller box
        (arms.two_metre_limited, two_metre_limited_region, (-5.0, 5.0), "auto"),
    ],
    ids=[
        "ten (relative limits)",
        "ten, elbow down",
        "ten, elbow up",
        "ten, both elbows",
        "two_metre_limited (absolute limits)",
    ],
)
def test_is_reachable_matches_the_geometric_description(arm, region, box, elbow):
    rng = np.random.default_rng(7)
    p = rng.uniform(box[0], box[1], size=(20_000, 2))
    expected = region(p) if arm is arms.two_metre_limited else region(p, elbow)
    got = workspace.is_reachable(arm, p, elbow=elbow)
    assert expected.sum() > 500 and (~expected).sum() > 500  # both kinds are tested
    # points within round-off of the boundary may go either way; nothing else may disagree
    disagree = got != expected
    assert np.all(np.abs(workspace.clearance(arm, p[disagree], elbow=elbow)) < 1e-6)
    assert disagree.sum() <= 2


def test_the_two_branch_workspaces_of_the_ten_arm_are_mirror_images():
    # q -> (90 deg - q1 - q2, q2 -> -q2) mirrors the tip in the 45 deg line and swaps the branches
    rng = np.random.default_rng(5)
    p = rng.uniform(-25, 25, size=(5000, 2))
    assert np.array_equal(
        workspace.is_reachable(arms.ten, p, elbow="down"),
        workspace.is_reachable(arms.ten, p[:, ::-1], elbow="up"),
    )
    both = workspace.is_reachable(
        arms.ten, p, elbow="both"
    )  # the region of both is its own mirror image
    assert (
        np.array_equal(both, workspace.is_reachable(arms.ten, p[:, ::-1], elbow="both"))
        and both.sum() > 50
    )


@pytest.mark.parametrize("elbow", [None, "either", "elbow down", 0], ids=repr)
def test_workspace_functions_name_the_elbow_words(elbow):
    words = re.escape("elbow must be one of ('down', 'up', 'both', 'auto')")
    for call in (
        lambda: workspace.is_reachable(arms.ten, [12.5, 12.5], elbow=elbow),
        lambda: workspace.boundary_arcs(arms.ten, elbow=elbow),
        lambda: workspace.clearance(arms.ten, [12.5, 12.5], elbow=elbow),
        lambda: workspace.largest_inscribed_circle(arms.ten, elbow=elbow),
    ):
        with pytest.raises(ValueError, match=words):
            call()


def test_the_elbow_words_of_is_reachable():
    p = np.array(
        [[15.0, 1.0], [1.0, 15.0], [12.5, 12.5], [5.0, -15.0]]
    )  # up only, down only, both, neither
    valid = ik.solutions_within_limits(arms.ten, p)[1]
    assert valid.tolist() == [
        [False, True],
        [True, False],
        [True, True],
        [False, False],
    ]
    expected = {
        "auto": [1, 1, 1, 0],
        "down": [0, 1, 1, 0],
        "up": [1, 0, 1, 0],
        "both": [0, 0, 1, 0],
    }
    for elbow, reached in expected.items():
        assert workspace.is_reachable(arms.ten, p, elbow=elbow).tolist() == [
            bool(r) for r in reached
        ], elbow
    assert workspace.is_reachable(arms.ten, [12.5, 12.5]).ndim == 0


def test_solutions_within_limits_lives_in_ik_and_workspace_builds_on_it():
    assert (
        "solutions_within_limits" not in workspace.__all__
        and "solutions_within_limits" in ik.__all__
    )
    assert workspace.LIMIT_TOL is ik.LIMIT_TOL
    import twolink.workspace as module

    assert (
        module.solutions_within_limits is ik.solutions_within_limits
    )  # imported, not a copy


@pytest.mark.parametrize(
    "arm",
    [arms.ten, arms.two_metre_limited, arms.two_metre],
    ids=lambda arm: str(arm.limit_convention),
)
def test_every_point_returned_as_reachable_is_reached_by_ik_within_limits(arm):
    rng = np.random.default_rng(3)
    scale = arm.reach[1] * 1.2
    p = rng.uniform(-scale, scale, size=(5000, 2))
    reachable = workspace.is_reachable(arm, p)
    q_both, valid = ik.solutions_within_limits(arm, p)
    assert np.array_equal(reachable, valid.any(axis=-1))
    for branch in (0, 1):
        chosen = valid[:, branch]
        q = q_both[chosen, branch]
        assert np.all(arm.within_limits(q, tol=workspace.LIMIT_TOL))
        assert (
            np.max(np.hypot(*(arm.fk(q) - p[chosen]).T), initial=0.0)
            <= 1e-12 * arm.reach[1]
        )


def test_sampled_points_are_reachable_and_their_configurations_within_limits():
    for arm in (arms.ten, arms.two_metre_limited, arms.two_metre):
        p, q = workspace.sample_reachable(arm, n=3000, seed=11)
        assert np.all(arm.within_limits(q))
        assert np.allclose(arm.fk(q), p)
        assert np.all(workspace.is_reachable(arm, p))


# the folded equal-link arm: fk lands a round-off from the base, in a direction that says nothing about q1
@example(
    arm=TwoLinkArm(1.0, 1.0, q_min=(1.0, np.pi), q_max=(2.0, np.pi + 1.0)), u=0.0, v=0.0
)
@example(
    arm=TwoLinkArm(
        1.0,
        1.0,
        q_min=(1.0, np.pi + 1.0),
        q_max=(2.0, np.pi + 2.0),
        limit_convention="absolute",
    ),
    u=0.0,
    v=0.0,
)
@given(arm=limited_arms(), u=unit, v=unit)
def test_every_configuration_within_limits_reaches_a_reachable_point(arm, u, v):
    """Completeness: with the soundness test above, is_reachable(p) <=> some configuration within limits reaches p."""
    q = configuration_within(arm, [u, v])
    assert arm.within_limits(q)
    assert workspace.is_reachable(arm, arm.fk(q))


@given(arm=limited_arms(), fraction=unit, heading=angles)
def test_reachable_points_of_random_limited_arms_have_a_valid_configuration(
    arm, fraction, heading
):
    r_min, r_max = arm.reach
    radius = r_min + fraction * (r_max - r_min)
    p = radius * np.array([np.cos(heading), np.sin(heading)])
    q_both, valid = ik.solutions_within_limits(arm, p)
    assert workspace.is_reachable(arm, p) == valid.any()
    for q in q_both[valid]:
        assert arm.within_limits(q, tol=workspace.LIMIT_TOL)
        assert np.linalg.norm(arm.fk(q) - p) <= 1e-9 * r_max


def test_points_outside_are_rejected():
    # outside the reach annulus, whatever the limits
    assert not workspace.is_reachable(arms.ten, [20.001, 0.0])
    assert not workspace.is_reachable(arms.two_metre, [0.0, 4.0 + 1e-6])
    assert workspace.is_reachable(arms.two_metre, [0.0, 0.0])
    # inside the annulus but only by configurations that break the limits
    assert not workspace.is_reachable(arms.ten, [0.0, 0.0])  # needs q2 = 180 deg
    assert workspace.is_reachable(
        arms.ten, [-10.0, 10.0]
    )  # the corner q = (90, 90) deg
    assert not workspace.is_reachable(arms.ten, [-12.0, 12.0])  # needs q1 > 90 deg
    assert not workspace.is_reachable(arms.ten, [5.0, -15.0])  # needs q1 < 0
    assert not workspace.is_reachable(
        arms.two_metre_limited, [-3.5, 1.0]
    )  # link 2 at 188.5 deg
    assert not workspace.is_reachable(
        arms.two_metre_limited, [0.0, 2.0]
    )  # links 120 deg apart > 110
    for q_outside in (
        [np.radians(-50.0), np.radians(30.0)],
        [np.radians(40.0), np.radians(120.0)],
    ):
        # for arms.ten, the other branch of these is outside the limits too
        p = arms.ten.fk(q_outside)
        _, valid = ik.solutions_within_limits(arms.ten, p)
        assert not valid.any() and not workspace.is_reachable(arms.ten, p)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="finite"):
        workspace.is_reachable(arms.ten, [np.nan, 1.0])
    with pytest.raises(ValueError, match="shape"):
        workspace.is_reachable(arms.ten, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=r"n \(samples\) must be an integer >= 1"):
        workspace.sample_reachable(arms.ten, n=0)


# ---------------------------------------------------------------- the first unreachable point


def test_require_reachable_names_the_first_point_outside_the_reach():
    path = np.array(
        [[12.0, 12.0], [13.0, 13.0], [14.5, 14.5], [15.0, 15.0]]
    )  # |p| = 20.5 at index 2
    with pytest.raises(UnreachableError) as caught:
        workspace.require_reachable(arms.ten, path, what="path point")
    message = str(caught.value)
    assert message.startswith("path point (14.5, 14.5) (index (2,), first of 2) is ")
    assert f"{np.hypot(14.5, 14.5):.6g} m" in message
    assert "[0, 20] m" in message
    assert "nan" not in message.lower()
    with pytest.raises(UnreachableError) as reach:  # the one reach test, one message
        kinematics.require_within_reach(arms.ten, path, what="path point")
    assert str(reach.value) == message


def test_require_reachable_names_the_limits_when_inside_the_reach():
    path = np.array(
        [[12.5, 12.5], [0.0, 16.0], [-12.0, 12.0]]
    )  # (0, 16): direction 90 deg, fine; (-12, 12) is not
    with pytest.raises(UnreachableError) as caught:
        workspace.require_reachable(arms.ten, path, what="path point")
    message = str(caught.value)
    assert message.startswith(
        f"path point (-12, 12) (index (2,), first of 1) is {np.hypot(12, 12):.6g} m from the base"
    )
    assert "inside the reach [0, 20] m but outside the joint limits" in message
    assert workspace.describe_limits(arms.ten) in message
    numbers = [
        float(value)
        for value in re.findall(r"q = \(([-\d.e+]+), ([-\d.e+]+)\) deg", message)[0]
    ]
    assert numbers[0] > 90.0  # the elbow-down q1 breaks q1 <= 90 deg


def test_require_reachable_returns_the_points_when_all_are_inside():
    points = workspace.circle_points([12.5, 12.5], 2.0, 12)
    assert np.array_equal(workspace.require_reachable(arms.ten, points), points)


# ---------------------------------------------------------------- boundary arcs


@pytest.mark.parametrize(
    "arm", [arms.ten, arms.two_metre_limited], ids=["ten", "two_metre_limited"]
)
def test_candidate_arcs_are_traced_by_configurations_within_limits(arm):
    for arc in workspace.candidate_arcs(arm):
        points = arc.points(50)
        assert np.all(workspace.is_reachable(arm, points)), arc.label


@pytest.mark.parametrize(
    "arm",
    [arms.ten, arms.two_metre_limited, arms.two_metre],
    ids=["ten", "two_metre_limited", "two_metre"],
)
def test_boundary_arcs_separate_reachable_from_unreachable(arm):
    arcs = workspace.boundary_arcs(arm)
    assert arcs
    probe = 1e-4 * arm.reach[1]
    for arc in arcs:
        if arc.radius == 0.0:
            continue
        fractions = np.linspace(0.05, 0.95, 19)
        on_arc = arc.point_at(fractions)
        outward = (on_arc - np.asarray(arc.centre)) / arc.radius
        inside = workspace.is_reachable(arm, on_arc - probe * outward)
        outside = workspace.is_reachable(arm, on_arc + probe * outward)
        assert np.all(inside != outside), arc.label


@settings(max_examples=60)
@given(arm=limited_arms(), elbow=st.sampled_from(["auto", "down", "up", "both"]))
def test_boundary_arcs_and_clearance_of_random_limited_arms(arm, elbow):
    """No boundary arc runs through the inside, and the sign of clearance is reachability."""
    arcs = workspace.boundary_arcs(arm, elbow=elbow)
    if (
        not arcs
    ):  # one branch may reach nothing within the limits: then no configuration is on it
        p, q = workspace.sample_reachable(arm, 500)
        if elbow == "both":  # and then no point is reached on both branches
            assert not np.any(workspace.is_reachable(arm, p, elbow="both"))
        else:
            assert elbow != "auto" and np.all(
                np.sin(q[:, 1]) * (1 if elbow == "down" else -1) <= 1e-6
            )
        assert np.all(
            workspace.clearance(arm, [[0.0, 0.0], [1.0, 1.0]], arcs, elbow=elbow)
            == -np.inf
        )
        return
    assert arcs
    probe = 1e-4 * arm.reach[1]
    directions = np.linspace(0, 2 * np.pi, 256, endpoint=False)
    ring = probe * np.c_[np.cos(directions), np.sin(directions)]
    for arc in arcs:
        on_arc = arc.point_at(np.linspace(0.1, 0.9, 9))
        assert np.all(workspace.is_reachable(arm, on_arc, elbow=elbow)), arc
        assert not np.any(
            workspace.is_reachable(arm, on_arc[:, None, :] + ring, elbow=elbow).all(
                axis=1
            )
        ), arc
    rng = np.random.default_rng(0)
    p = rng.uniform(-1.1, 1.1, (2000, 2)) * arm.reach[1]
    room = workspace.clearance(arm, p, arcs, elbow=elbow)
    disagree = (room > 0) != workspace.is_reachable(arm, p, elbow=elbow)
    assert np.all(np.abs(room[disagree]) < 1e-6 * arm.reach[1])


def test_boundary_of_the_ten_arm_is_the_expected_five_arcs():
    arcs = {arc.label: arc for arc in workspace.boundary_arcs(arms.ten)}
    assert set(arcs) == {
        "q1 = 0 deg",
        "q1 = 90 deg",
        "q2 = -90 deg",
        "q2 = 90 deg",
        "q2 = 0 deg (full stretch)",
    }
    assert arcs["q2 = 0 deg (full stretch)"].radius == pytest.approx(20.0)
    assert arcs["q2 = 90 deg"].radius == pytest.approx(10 * np.sqrt(2))
    # q1 = 0: only the half with q2 <= 0 (elbow up, tip below the x-axis) is on the boundary
    assert np.all(arcs["q1 = 0 deg"].points(10)[:, 1] <= 1e-9)
    for arc in arcs.values():
        assert abs(arc.sweep) == pytest.approx(np.pi / 2)


# ---------------------------------------------------------------- clearance and the largest circle


#: The ten arm's boundary arcs, traced once for the examples that all ask about that arm.
TEN_ARCS = workspace.boundary_arcs(arms.ten)


@given(fraction=unit, heading=st.floats(0.0, np.pi / 2))
def test_clearance_is_the_radius_of_the_largest_circle_about_a_point(fraction, heading):
    arm = arms.ten
    arcs = TEN_ARCS
    radius = 10 * np.sqrt(2) + 1e-3 + fraction * (20 - 10 * np.sqrt(2) - 2e-3)
    p = radius * np.array([np.cos(heading), np.sin(heading)])
    room = float(workspace.clearance(arm, p, arcs))
    assert room > 0
    around = np.linspace(0.0, 2 * np.pi, 4000, endpoint=False)
    ring = np.c_[np.cos(around), np.sin(around)]
    assert np.all(workspace.is_reachable(arm, p + room * (1 - 1e-6) * ring))
    assert not np.all(workspace.is_reachable(arm, p + room * (1 + 1e-3) * ring))


def test_clearance_is_negative_outside():
    assert workspace.clearance(arms.ten, [0.0, 0.0]) == pytest.approx(-10 * np.sqrt(2))
    assert workspace.clearance(arms.ten, [25.0, 0.0]) < 0


def test_largest_circle_of_the_ten_arm_matches_the_closed_form():
    # The set lies in the annulus sqrt(a1^2 + a2^2) <= r <= a1 + a2 (|q2| <= 90 deg), whose
    # widest circle has diameter a1 + a2 - sqrt(a1^2 + a2^2); one fits (direction 45 deg).
    exact = (20.0 - np.sqrt(10.0**2 + 10.0**2)) / 2.0
    centre, radius = workspace.largest_inscribed_circle(arms.ten)
    assert abs(radius - exact) <= 1e-3  # within a millimetre of the exact radius
    assert abs(radius - exact) <= 1e-9 * arms.ten.reach[1]  # the docstring's claim
    assert np.hypot(*centre) == pytest.approx(20.0 - exact, abs=1e-6)
    on_circle = workspace.circle_points(centre, radius * (1 - 1e-9), 720)
    assert np.all(workspace.is_reachable(arms.ten, on_circle))


def test_largest_circle_of_the_limited_two_metre_arm_matches_its_closed_form():
    # Symmetric about the y-axis: centre (0, 4 - rho) touching the outer arc r = 4 and, outside,
    # the circle of radius 2 about the elbow 2 (cos 35, sin 35): rho = 4 (1 - s) / (3 - s), s = sin 35 deg.
    s = np.sin(np.radians(35.0))
    exact = 4 * (1 - s) / (3 - s)
    centre, radius = workspace.largest_inscribed_circle(arms.two_metre_limited)
    assert abs(radius - exact) <= 1e-9 * 4.0
    assert np.allclose(centre, [0.0, 4.0 - exact], atol=1e-6)


def test_largest_circle_of_an_arm_without_limits_is_the_reach_disc_or_band():
    centre, radius = workspace.largest_inscribed_circle(arms.two_metre)
    assert radius == pytest.approx(4.0, abs=1e-8) and np.allclose(
        centre, 0.0, atol=1e-6
    )
    centre, radius = workspace.largest_inscribed_circle(TwoLinkArm(3.0, 1.0))
    assert radius == pytest.approx(1.0, abs=1e-8) and np.hypot(
        *centre
    ) == pytest.approx(3.0, abs=1e-6)


# ---------------------------------------------------------------- circle points and arcs


@given(
    x=st.floats(-10, 10),
    y=st.floats(-10, 10),
    radius=st.floats(0.01, 10),
    n=st.integers(1, 40),
    start=angles,
)
def test_circle_points_are_equally_spaced_on_the_circle(x, y, radius, n, start):
    points = workspace.circle_points([x, y], radius, n, start_angle=start)
    assert points.shape == (n, 2)
    assert np.allclose(np.hypot(points[:, 0] - x, points[:, 1] - y), radius)
    if n >= 2:
        steps = np.hypot(*np.diff(np.vstack([points, points[:1]]), axis=0).T)
        assert np.allclose(steps, 2 * radius * np.sin(np.pi / n))


def test_circle_points_refuses_bad_input():
    for bad in (
        dict(radius=0.0, n=5),
        dict(radius=1.0, n=0),
        dict(radius=1.0, n=2.5),
        dict(radius=np.inf, n=3),
    ):
        with pytest.raises(ValueError):
            workspace.circle_points([0.0, 0.0], **bad)


@given(
    radius=st.floats(0.1, 5),
    start=angles,
    sweep=st.floats(-2 * np.pi, 2 * np.pi),
    px=st.floats(-8, 8),
    py=st.floats(-8, 8),
)
def test_arc_distance_is_the_distance_to_its_nearest_point(
    radius, start, sweep, px, py
):
    assume(abs(sweep) > 1e-3)
    arc = Arc((0.5, -0.3), radius, start, sweep)
    dense = arc.points(20001)
    brute = np.min(np.hypot(*(dense - [px, py]).T))
    exact = float(arc.distance([px, py]))
    assert exact <= brute + 1e-12
    assert (
        brute - exact <= radius * abs(sweep) / 20000
    )  # the dense points are this far apart at most


@given(
    ax=st.floats(-3, 3),
    ay=st.floats(-3, 3),
    ra=st.floats(0.1, 3),
    bx=st.floats(-3, 3),
    by=st.floats(-3, 3),
    rb=st.floats(0.1, 3),
)
def test_circle_intersections_lie_on_both_circles(ax, ay, ra, bx, by, rb):
    points = circle_intersections((ax, ay), ra, (bx, by), rb)
    for point in points:
        assert np.hypot(point[0] - ax, point[1] - ay) == pytest.approx(ra, abs=1e-7)
        assert np.hypot(point[0] - bx, point[1] - by) == pytest.approx(rb, abs=1e-7)
    distance = np.hypot(bx - ax, by - ay)
    if abs(ra - rb) + 1e-6 < distance < ra + rb - 1e-6:
        assert len(points) == 2


def test_arc_split_and_fraction_round_trip():
    arc = Arc((1.0, 2.0), 3.0, 0.3, -2.0)
    pieces = arc.split([0.25, 0.5])
    assert sum(piece.sweep for piece in pieces) == pytest.approx(arc.sweep)
    assert np.allclose(pieces[1].end_points, arc.point_at(np.array([0.25, 0.5])))
    assert np.allclose(
        arc.fraction_of(arc.point_at(np.array([0.0, 0.3, 1.0]))), [0.0, 0.3, 1.0]
    )
    assert (
        arc.fraction_of(
            arc.point_at(np.array(1.5)) * 0
            + [1.0 + 3.0 * np.cos(1.0), 2.0 + 3.0 * np.sin(1.0)]
        )
        == -1.0
    )


def test_limit_description_is_in_degrees_and_names_the_convention():
    assert "relative" in workspace.describe_limits(arms.ten)
    assert "absolute" in workspace.describe_limits(arms.two_metre_limited)
    assert workspace.describe_limits(arms.two_metre) == "no joint limits"
    assert np.allclose(
        np.degrees(
            to_absolute(configuration_within(arms.two_metre_limited, [0.0, 1.0]))
        ),
        [35.0, 145.0],
    )


@given(arm=limited_arms(), fraction=unit, heading=angles)
def test_closed_form_auto_is_within_the_limits_exactly_where_the_point_is_reachable(
    arm, fraction, heading
):
    r_min, r_max = arm.reach
    p = (r_min + fraction * (r_max - r_min)) * np.array(
        [np.cos(heading), np.sin(heading)]
    )
    auto = ik.closed_form(arm, p, elbow="auto")
    assert bool(arm.within_limits(auto.q, tol=ik.LIMIT_TOL)) == bool(
        workspace.is_reachable(arm, p)
    )
    assert auto.success and auto.residual <= 1e-9 * r_max


# ----------------------------------------------------------------- edges: arguments refused with their names
@pytest.mark.parametrize("probe", [0, -1, 1e-9, 0.5])
def test_boundary_arcs_refuses_a_probe_ring_outside_its_range(probe):
    with pytest.raises(
        ValueError,
        match=r"probe \(ring radius / reach\) must be in \[1e-06, 0.01\]; got ",
    ):
        workspace.boundary_arcs(arms.ten, probe)


def test_boundary_arcs_refuses_a_string_probe():
    with pytest.raises(
        InputTypeError,
        match=r"probe \(ring radius / reach\) must be a real number; got 'x'",
    ):
        workspace.boundary_arcs(arms.ten, "x")


@pytest.mark.parametrize("probe", list(workspace.PROBE_RANGE))
def test_boundary_arcs_at_either_end_of_the_probe_range_finds_the_same_edges(probe):
    assert [arc.label for arc in workspace.boundary_arcs(arms.ten, probe)] == [
        arc.label for arc in workspace.boundary_arcs(arms.ten)
    ]


@pytest.mark.parametrize(
    "call",
    [workspace.describe_limits, workspace.candidate_arcs, workspace.sample_reachable],
)
def test_none_for_the_arm_is_refused_naming_arm(call):
    with pytest.raises(
        InputTypeError, match=r"arm must be a twolink.TwoLinkArm; got None"
    ):
        call(None)


def test_largest_inscribed_circle_refuses_more_starts_than_it_has_candidates_at_once():
    with pytest.raises(
        ValueError, match=r"starts must be an integer <= 4000; got 1000000000000"
    ):
        workspace.largest_inscribed_circle(arms.ten, starts=10**12)


def test_largest_inscribed_circle_stops_at_its_wall_time_budget_saying_what_to_change():
    with pytest.raises(
        RuntimeError,
        match=r"used up its budget of max_wall_time = 0.3 s after \d+ of \d+ starts .*fewer starts",
    ):
        workspace.largest_inscribed_circle(arms.ten, starts=200, max_wall_time=0.3)


@pytest.mark.parametrize("convention", ["relative", "absolute"])
def test_the_base_is_reachable_when_a_folded_configuration_is_within_the_limits(
    convention,
):
    """At the base of an equal-link arm every q1 reaches: both branches take one within the limits."""
    q_min, q_max = (
        ((1.0, np.pi), (2.0, np.pi + 1.0))
        if convention == "relative"
        else ((1.0, np.pi + 1.0), (2.0, np.pi + 2.0))
    )
    arm = TwoLinkArm(1.0, 1.0, q_min=q_min, q_max=q_max, limit_convention=convention)
    q_folded = [1.5, np.pi]  # relative angles
    assert arm.within_limits(q_folded)
    p = np.array([arm.fk(q_folded), [0.0, 0.0], [-1e-16, 0.0]])
    assert workspace.is_reachable(arm, p, elbow="both").all()
    q_both, valid = ik.solutions_within_limits(arm, p)
    assert valid.all() and arm.within_limits(q_both, tol=workspace.LIMIT_TOL).all()
    assert np.max(np.hypot(*(arm.fk(q_both) - p[:, None, :]).T)) <= 1e-13
    auto = ik.closed_form(arm, p, elbow="auto")  # the same choice
    assert auto.within_limits.all() and auto.all_success
    for target in p:
        assert ik.closed_form(arm, target.tolist(), elbow="auto").within_limits
    narrow = TwoLinkArm(
        1.0, 1.0, q_min=(0.0, 0.0), q_max=(0.5, 3.0), limit_convention=convention
    )
    assert not workspace.is_reachable(
        narrow, [0.0, 0.0]
    )  # no folded configuration within these limits
    assert not ik.closed_form(narrow, [0.0, 0.0], elbow="auto").within_limits
    unequal = TwoLinkArm(
        1.0, 1.0 + 1e-6, q_min=q_min, q_max=q_max, limit_convention=convention
    )
    assert not workspace.is_reachable(unequal, [0.0, 0.0])  # the base is out of reach


def test_sample_counts_beyond_the_memory_budget_are_refused():
    with pytest.raises(
        ValueError, match=r"n \(samples\) must be an integer <= 10000000"
    ):
        workspace.sample_reachable(arms.two_metre, n=5 * 10**9)


# ---------------------------------------------------------------- fast answers for a slider: BranchTable, grid search


def _points_about(arm, rng, count=300):
    """Random points over the reach square, the base, and tips of configurations on the limit box's edges."""
    scale = arm.reach[1] * 1.2
    random = rng.uniform(-scale, scale, size=(count, 2))
    edge = np.array(
        [
            configuration_within(arm, fractions)
            for fractions in ([0.0, 0.3], [1.0, 0.7], [0.4, 0.0], [0.6, 1.0], [0, 0])
        ]
    )
    return np.vstack([random, arm.fk(edge), [[0.0, 0.0]]])


def _at_a_slack_edge(arm, points, tol=ik.LIMIT_TOL, margin=1e-12):
    """Per point and branch, whether an angle the arm limits lies within round-off of a limit widened by
    ``tol`` (modulo 2 pi): only there may BranchTable's comparisons of wrapped angles and the package's
    whole turns round apart (hypothesis finds such ties: limits of one arm at another's plus LIMIT_TOL)."""
    if not arm.has_limits:
        return np.zeros(np.shape(points)[:-1] + (2,), dtype=bool)
    q_both = ik.solutions_within_limits(TwoLinkArm(arm.l1, arm.l2), points)[0]
    limited = to_absolute(q_both) if arm.limit_convention == "absolute" else q_both
    edges = np.array([np.asarray(arm.q_min) - tol, np.asarray(arm.q_max) + tol])
    gap = np.abs(
        wrap_angle(limited[..., None, :] - edges)
    )  # (..., branch, edge, joint)
    return np.any(gap < margin, axis=(-2, -1))


def _same_but_at_slack_edges(got, expected, arm, points, tol=ik.LIMIT_TOL):
    """got == expected (per point and branch, or per point) everywhere but at _at_a_slack_edge."""
    tied = _at_a_slack_edge(arm, points, tol)
    if got.ndim < tied.ndim:
        tied = np.any(tied, axis=-1)
    assert np.array_equal(got[~tied], expected[~tied])


@settings(max_examples=60)
@given(arm=limited_arms(), other=limited_arms(), seed=st.integers(0, 2**16))
def test_a_branch_table_answers_as_is_reachable_for_any_limits_on_its_links(
    arm, other, seed
):
    """Solved once for the links, the table gives exactly what the package's limit rule gives."""
    points = _points_about(arm, np.random.default_rng(seed))
    # the table of one arm's links serves every arm with those links, whatever its limits
    same_links = TwoLinkArm(
        arm.l1,
        arm.l2,
        q_min=other.q_min,
        q_max=other.q_max,
        limit_convention=other.limit_convention,
    )
    table = workspace.BranchTable(TwoLinkArm(arm.l1, arm.l2), points)
    for limited in (arm, same_links, TwoLinkArm(arm.l1, arm.l2)):
        q_both, valid = table.solutions_within_limits(limited)
        q_expected, valid_expected = ik.solutions_within_limits(limited, points)
        assert np.array_equal(valid, valid_expected)
        assert np.array_equal(q_both, q_expected)
        for column, elbow in enumerate(("down", "up")):
            assert np.array_equal(
                valid[:, column], workspace.is_reachable(limited, points, elbow=elbow)
            )
        # the comparisons of wrapped angles: the same, but for round-off at a limit + LIMIT_TOL
        _same_but_at_slack_edges(
            table.within_limits(limited), valid_expected, limited, points
        )
        _same_but_at_slack_edges(
            table.reachable(limited),
            workspace.is_reachable(limited, points),
            limited,
            points,
        )


def test_a_branch_table_keeps_the_shape_of_its_points_and_refuses_other_links():
    axis = np.linspace(-22.0, 22.0, 9)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1)
    table = workspace.BranchTable(arms.ten, grid)
    assert table.reachable(arms.ten).shape == (9, 9)
    assert np.array_equal(
        table.reachable(arms.ten), workspace.is_reachable(arms.ten, grid)
    )
    with pytest.raises(
        ValueError, match=r"solved for l1 = 10, l2 = 10; got an arm with l1 = 2"
    ):
        table.solutions_within_limits(arms.two_metre)
    with pytest.raises(InputTypeError, match="arm must be a twolink.TwoLinkArm"):
        table.reachable(None)
    with pytest.raises(ValueError, match="tol"):
        table.reachable(arms.ten, tol=-1.0)
    with pytest.raises(ValueError, match="p"):
        workspace.BranchTable(arms.ten, [[1.0, 2.0, 3.0]])


def test_a_branch_table_refuses_more_points_than_the_memory_budget(monkeypatch):
    monkeypatch.setattr(workspace, "MAX_SAMPLES", 10)
    with pytest.raises(
        ValueError,
        match=r"p holds 11 points; a BranchTable takes at most MAX_SAMPLES = 10",
    ):
        workspace.BranchTable(arms.ten, np.zeros((11, 2)))


def _grid_inside(arm, spacing, elbow="auto"):
    extent = arm.reach[1] * 1.1
    axis = np.arange(-extent, extent + spacing / 2, spacing)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    return grid[workspace.is_reachable(arm, grid, elbow=elbow)]


@settings(max_examples=15, deadline=None)
@given(arm=limited_arms(), elbow=st.sampled_from(["auto", "down", "up"]))
def test_the_grid_circle_fits_and_is_near_the_optimisers(arm, elbow):
    """The grid's circle fits (checked by is_reachable around it) and is at most spacing / sqrt 2
    short of largest_inscribed_circle's (its centre is that near a grid point, and clearance is
    1-Lipschitz): no larger than the largest circle, hence within a spacing of it."""
    scale = arm.reach[1]
    spacing, tol = scale / 12, 1e-4 * scale
    arcs = workspace.boundary_arcs(arm, elbow=elbow)
    centre, radius = workspace.largest_circle_on_grid(
        arcs, _grid_inside(arm, spacing, elbow), spacing, tol
    )
    try:
        _, best = workspace.largest_inscribed_circle(arm, starts=2, elbow=elbow)
    except ValueError:  # nothing reachable on this branch: no arcs, no candidates
        assert centre is None and radius == 0.0
        return
    if centre is None:  # the workspace slips between the grid points: then it is thin
        assert best <= spacing / np.sqrt(2)
        return
    assert radius == pytest.approx(
        float(workspace.clearance(arm, centre, arcs, elbow=elbow)), abs=1e-12 * scale
    )
    ring = workspace.circle_points(centre, radius * (1 - 1e-6), 90)
    assert np.all(workspace.is_reachable(arm, ring, elbow=elbow))
    assert radius >= best - spacing / np.sqrt(2) - 1e-9 * scale


@pytest.mark.parametrize(
    "arm, exact",
    [
        (arms.ten, 10 - 5 * np.sqrt(2)),
        (
            arms.two_metre_limited,
            4 * (1 - np.sin(np.radians(35))) / (3 - np.sin(np.radians(35))),
        ),
    ],
    ids=["ten", "two_metre_limited"],
)
def test_the_grid_circle_of_the_course_arms_is_within_its_tolerance_of_the_closed_form(
    arm, exact
):
    spacing = arm.reach[1] / 40
    tol = 1e-4 * arm.reach[1]
    centre, radius = workspace.largest_circle_on_grid(
        workspace.boundary_arcs(arm), _grid_inside(arm, spacing), spacing, tol
    )
    assert exact - 2 * tol <= radius <= exact + 1e-12 * arm.reach[1]


def test_largest_circle_on_grid_refuses_bad_input_and_answers_none_when_nothing_is_inside():
    arcs = workspace.boundary_arcs(arms.ten)
    inside = [[17.0, 5.0]]
    assert workspace.largest_circle_on_grid(arcs, np.zeros((0, 2)), 1.0, 0.1) == (
        None,
        0.0,
    )
    assert workspace.largest_circle_on_grid([], inside, 1.0, 0.1) == (None, 0.0)
    with pytest.raises(InputTypeError, match="arcs must be a list of twolink.arcs.Arc"):
        workspace.largest_circle_on_grid(arms.ten, inside, 1.0, 0.1)
    for spacing, tol in ((0.0, 0.1), (1.0, -0.1), (np.nan, 0.1), (1.0, np.inf)):
        with pytest.raises(ValueError, match="spacing|tol"):
            workspace.largest_circle_on_grid(arcs, inside, spacing, tol)
    with pytest.raises(ValueError, match="MAX_REFINEMENTS = 30"):
        workspace.largest_circle_on_grid(arcs, inside, 1.0, 1e-16)
    # tol at least a third of the spacing: no refinement, the best candidate itself
    centre, radius = workspace.largest_circle_on_grid(arcs, inside, 1.0, 1.0)
    assert np.array_equal(centre, inside[0]) and radius == pytest.approx(
        float(workspace.clearance(arms.ten, inside[0]))
    )


# ---------------------------------------------------------------- the fast paths against the package's own rule


@st.composite
def _limit_ranges(draw):
    """A (low, high) pair of limits, radians: any interval, one reaching -+180 deg, a full turn or more, or one angle."""
    kind = draw(
        st.sampled_from(["any", "to 180", "from -180", "full turn", "one angle"])
    )
    low = draw(st.floats(-2 * np.pi, 2 * np.pi))
    if kind == "any":
        return low, low + draw(st.floats(0.0, 2.5 * np.pi))
    if kind == "to 180":
        return draw(st.floats(-np.pi, np.pi)), np.pi
    if kind == "from -180":
        return -np.pi, draw(st.floats(-np.pi, np.pi))
    if kind == "full turn":
        return low, low + draw(
            st.sampled_from([2 * np.pi, 2 * np.pi + 1e-3, 3 * np.pi])
        )
    return low, low


@st.composite
def _slider_arms(draw):
    """Arms with limits of every kind (_limit_ranges), either convention; equal links half the time (the base)."""
    l1 = draw(lengths)
    l2 = (
        l1
        if draw(st.booleans())
        else draw(st.floats(max(0.05, l1 / 20), min(20.0, 20 * l1)))
    )
    (low_1, high_1), (low_2, high_2) = draw(_limit_ranges()), draw(_limit_ranges())
    return TwoLinkArm(
        l1,
        l2,
        q_min=(low_1, low_2),
        q_max=(high_1, high_2),
        limit_convention=draw(st.sampled_from(["relative", "absolute"])),
    )


def _points_near_the_edges(arm, rng, count=200):
    """Random points, tips of configurations at the limit box's corners and on its edges, points a hair beside those, the base."""
    corners = [configuration_within(arm, f) for f in ([0, 0], [0, 1], [1, 0], [1, 1])]
    edges = [
        configuration_within(arm, [edge, fraction] if side else [fraction, edge])
        for edge, fraction, side in zip(
            rng.integers(0, 2, count),
            rng.uniform(0, 1, count),
            rng.integers(0, 2, count),
        )
    ]
    on_edges = arm.fk(np.array(corners + edges))
    beside = on_edges + rng.normal(scale=1e-9 * arm.reach[1], size=on_edges.shape)
    scale = 1.2 * arm.reach[1]
    random = rng.uniform(-scale, scale, size=(count, 2))
    return np.vstack([random, on_edges, beside, [[0.0, 0.0]]])


@settings(max_examples=150)
@given(arm=_slider_arms(), seed=st.integers(0, 2**16))
@example(  # the explorer's sliders at their ends: both angles from -180 to 180 deg
    arm=TwoLinkArm(10.0, 10.0, q_min=(-np.pi, -np.pi), q_max=(np.pi, np.pi)), seed=0
)
@example(  # a single link-2 angle at -180 deg, absolute
    arm=TwoLinkArm(
        10.0,
        10.0,
        q_min=(np.pi / 2, -np.pi),
        q_max=(np.pi / 2, -np.pi),
        limit_convention="absolute",
    ),
    seed=1,
)
def test_the_branch_tables_comparisons_decide_as_solutions_within_limits(arm, seed):
    """BranchTable.within_limits (wrapped angles compared) = ik.solutions_within_limits (angles moved by
    turns), on random points, on the limit box's edges and a hair beside them, and at the base."""
    points = _points_near_the_edges(arm, np.random.default_rng(seed))
    table = workspace.BranchTable(TwoLinkArm(arm.l1, arm.l2), points)
    expected = ik.solutions_within_limits(arm, points)[1]
    _same_but_at_slack_edges(table.within_limits(arm), expected, arm, points)
    for elbow in ("auto", "down", "up", "both"):
        _same_but_at_slack_edges(
            table.reachable(arm, elbow=elbow),
            workspace.is_reachable(arm, points, elbow=elbow),
            arm,
            points,
        )
    # the slack is the package's too (tol = 0 would put the points on the limits at round-off)
    _same_but_at_slack_edges(
        table.within_limits(arm, 1e-3),
        ik.solutions_within_limits(arm, points, 1e-3)[1],
        arm,
        points,
        1e-3,
    )


def test_the_branch_table_refuses_a_bad_elbow_word():
    table = workspace.BranchTable(arms.ten, [[12.5, 12.5]])
    with pytest.raises(ValueError, match="elbow"):
        table.reachable(arms.ten, elbow="sideways")
    with pytest.raises(ValueError, match="tol"):
        table.within_limits(arms.ten, tol=np.nan)


@st.composite
def _arcs(draw):
    """Arcs of every kind: any sweep of either sign, full circles, zero radius, zero sweep."""
    centre = (draw(st.floats(-5, 5)), draw(st.floats(-5, 5)))
    radius = draw(st.one_of(st.just(0.0), st.floats(1e-3, 5)))
    sweep = draw(
        st.one_of(
            st.floats(-2 * np.pi, 2 * np.pi),
            st.sampled_from([2 * np.pi, -2 * np.pi, 0.0, np.pi, -np.pi]),
        )
    )
    return Arc(centre, radius, draw(st.floats(-4 * np.pi, 4 * np.pi)), sweep)


@given(
    arcs=st.lists(_arcs(), min_size=1, max_size=8),
    seed=st.integers(0, 2**16),
)
def test_distance_to_arcs_is_the_nearest_arc_distance(arcs, seed):
    """All arcs at once = the minimum of Arc.distance over the arcs, at random points, the arcs' ends and centres."""
    rng = np.random.default_rng(seed)
    points = np.vstack(
        [rng.uniform(-10, 10, size=(50, 2))]
        + [arc.end_points for arc in arcs]
        + [arc.point_at(0.5) for arc in arcs]
        + [arc.centre for arc in arcs]
    )
    expected = np.min([arc.distance(points) for arc in arcs], axis=0)
    got = workspace.distance_to_arcs(points, arcs)
    np.testing.assert_allclose(got, expected, rtol=0.0, atol=1e-12)
    # any shape of points, and a single point
    assert workspace.distance_to_arcs(points.reshape(-1, 1, 2), arcs).shape == (
        len(points),
        1,
    )
    assert float(workspace.distance_to_arcs(points[0], arcs)) == pytest.approx(
        expected[0], abs=1e-12
    )


def test_distance_to_arcs_in_blocks_is_the_same(monkeypatch):
    arcs = workspace.boundary_arcs(arms.ten)
    points = np.random.default_rng(3).uniform(-25, 25, size=(1000, 2))
    whole = workspace.distance_to_arcs(points, arcs)
    monkeypatch.setattr(workspace, "_DISTANCE_BLOCK", 7 * len(arcs))
    assert np.array_equal(workspace.distance_to_arcs(points, arcs), whole)


def test_distance_to_arcs_refuses_bad_input_and_is_inf_without_arcs():
    arcs = workspace.boundary_arcs(arms.ten)
    with pytest.raises(InputTypeError, match="arcs must be a list of twolink.arcs.Arc"):
        workspace.distance_to_arcs([0.0, 0.0], arms.ten)
    with pytest.raises(InputTypeError, match="arcs must be a list"):
        workspace.distance_to_arcs([0.0, 0.0], [arcs[0], "arc"])
    with pytest.raises(ValueError, match="p"):
        workspace.distance_to_arcs([[np.nan, 0.0]], arcs)
    assert np.array_equal(
        workspace.distance_to_arcs(np.zeros((3, 2)), []), np.full(3, np.inf)
    )
    assert workspace.distance_to_arcs(np.zeros((0, 2)), arcs).shape == (0,)


def _largest_circle_on_grid_one_arc_at_a_time(arcs, candidates, spacing, tol):
    """The reference: largest_circle_on_grid arc by arc with Arc.distance, as it was written first."""
    points = np.asarray(candidates, dtype=float).reshape(-1, 2)
    if not arcs or len(points) == 0:
        return None, 0.0

    def distance(p):
        return np.min([arc.distance(p) for arc in arcs], axis=0)

    pattern = np.stack(np.meshgrid(*[np.arange(-3.0, 4.0)] * 2), axis=-1).reshape(-1, 2)
    room = distance(points)
    best = int(np.argmax(room))
    centre, radius = points[best].copy(), float(room[best])
    step = spacing / 3.0
    while step > tol:
        near = centre + step * pattern
        near = near[np.hypot(*(near - centre).T) < radius]
        if len(near):
            room = distance(near)
            if room.max() > radius:
                best = int(np.argmax(room))
                centre, radius = near[best], float(room[best])
        step /= 3.0
    return centre, radius


# chapter 7's explorer: limits (degrees) the sliders can set, its 200 x 200 grid and its circle search
CHAPTER_7_LIMITS = [
    ((0, 90), (-90, 90), "relative"),
    ((35, 145), (35, 145), "absolute"),
    ((-180, 180), (-180, 180), "relative"),
    ((-180, 180), (-180, 180), "absolute"),
    ((-180, -90), (90, 180), "relative"),
    ((-45, 180), (-180, 0), "absolute"),
    ((0, 0), (90, 90), "relative"),
    ((90, 90), (-180, -180), "absolute"),
    ((-180, 180), (-20, 20), "relative"),
    ((60, 180), (-180, 180), "absolute"),
]


@pytest.fixture(scope="module")
def chapter_7_grid():
    axis = np.linspace(-20.0, 20.0, 200)
    grid = np.stack(np.meshgrid(axis, axis), axis=-1).reshape(-1, 2)
    on_search = np.zeros((200, 200), dtype=bool)
    on_search[::5, ::5] = True
    return (
        grid,
        on_search.ravel(),
        5 * (axis[1] - axis[0]),
        workspace.BranchTable(arms.ten, grid),
    )


@pytest.mark.parametrize("limits", CHAPTER_7_LIMITS, ids=stable_id)
def test_chapter_7s_limit_test_and_circle_search_are_the_packages_and_as_before(
    limits, chapter_7_grid
):
    grid, on_search, spacing, table = chapter_7_grid
    (low_1, high_1), (low_2, high_2), convention = limits
    arm = replace(
        arms.ten,
        q_min=tuple(np.radians([low_1, low_2])),
        q_max=tuple(np.radians([high_1, high_2])),
        limit_convention=convention,
    )
    valid = table.within_limits(arm)
    assert np.array_equal(valid, ik.solutions_within_limits(arm, grid)[1])
    for elbow in ("auto", "down", "up"):
        starts = grid[table.reachable(arm, elbow=elbow) & on_search]
        arcs = workspace.boundary_arcs(arm, elbow=elbow)
        centre, radius = workspace.largest_circle_on_grid(arcs, starts, spacing, 0.005)
        centre_before, radius_before = _largest_circle_on_grid_one_arc_at_a_time(
            arcs, starts, spacing, 0.005
        )
        if centre_before is None:
            assert centre is None and radius == 0.0
            continue
        # the same circle, to round-off (the same formula, for all arcs in one numpy call)
        np.testing.assert_allclose(
            centre, centre_before, rtol=0.0, atol=1e-12 * arm.reach[1]
        )
        assert radius == pytest.approx(radius_before, abs=1e-12 * arm.reach[1])


@pytest.mark.parametrize("width", [0.0, 1e-12, 1e-9, 1e-7])
def test_limits_narrower_than_the_sliver_cut_keep_their_boundary(width):
    """A workspace smaller than ``1e-6`` of the reach is all slivers: they are its boundary
    (limits 1e-12 wide gave no arc, and a clearance of -inf at the reachable points)."""
    arm = TwoLinkArm(1.0, 1.0, q_min=(0.3, 0.5), q_max=(0.3 + width, 0.5 + width))
    arcs = workspace.boundary_arcs(arm)
    assert arcs
    inside = arm.fk([0.3 + width / 2, 0.5 + width / 2])
    room = workspace.clearance(arm, inside, arcs)
    assert 0.0 <= room <= 2.0 * width + 1e-15
    assert workspace.clearance(arm, [0.0, 0.0], arcs) == pytest.approx(
        -np.hypot(*inside), rel=1e-6
    )
