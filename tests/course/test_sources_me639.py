"""The ME 639 2R mini-project reproduced (twolink_course.sources.me639): its printed numbers from its own methods.

The numbers are the facts of the course's source record (``notebooks/source_record.ipynb``,
items H4.1 to H4.6); each test asserts that the reproduction of the source's method yields
them, and compares with the package's correct answer.
"""

import re
from decimal import ROUND_HALF_UP, Decimal

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from twolink import UnreachableError, Wall, arms, to_relative, wall_contact
from twolink_course.sources import me639

arm = arms.two_metre
q1_values = st.floats(min_value=-np.pi, max_value=np.pi, allow_nan=False)
elbow_values = st.floats(min_value=0.05, max_value=np.pi - 0.05, allow_nan=False)


# --- H4.1: the IK line in both readings ---------------------------------------------------------------------------


@given(q1=q1_values, q2=elbow_values)
def test_cos_reading_inverts_forward_kinematics_on_the_elbow_down_branch(q1, q2):
    p_tip = arm.fk([q1, q2])
    q_abs = me639.source_ik(p_tip, reading="cos")
    q_dh = to_relative(q_abs)
    assert np.allclose(arm.fk(q_dh), p_tip, atol=1e-9)
    assert np.isclose(
        q_dh[1], q2, atol=1e-6
    )  # acos gives the elbow angle in [0, pi]: the "down" branch
    assert np.allclose(me639.source_fk(q_abs), p_tip, atol=1e-9)


@given(q1=q1_values, q2=elbow_values)
def test_sin_reading_keeps_the_elbow_angle_and_moves_link_1(q1, q2):
    p_tip = arm.fk([q1, q2])
    q_cos = to_relative(me639.source_ik(p_tip, reading="cos"))
    q_sin = to_relative(me639.source_ik(p_tip, reading="sin"))
    assert np.isclose(q_sin[1], q_cos[1], atol=1e-9)
    # the two readings agree only where sin(theta) = cos(theta)
    same_line = np.isclose(np.sin(q_cos[1]), np.cos(q_cos[1]), atol=1e-6)
    missed = np.linalg.norm(
        me639.source_fk(me639.source_ik(p_tip, reading="sin")) - p_tip
    )
    assert same_line or missed > 1e-9


def test_source_ik_rejects_bad_input_by_name():
    with pytest.raises(UnreachableError, match="p_tip"):
        me639.source_ik([5.0, 0.0])
    with pytest.raises(ValueError, match="reading"):
        me639.source_ik([3.0, 1.0], reading="tan")
    with pytest.raises(ValueError, match="p_tip"):
        me639.source_ik([np.nan, 1.0])
    with pytest.raises(ValueError, match="l1"):
        me639.source_ik([1.0, 1.0], l1=0.0)


# --- H4.2: the wall search ------------------------------------------------------------------------------------------


def test_wall_search_with_the_correct_ik_reproduces_the_printed_contact_and_torques():
    hit = me639.source_wall_search(reading="cos")
    assert tuple(hit.p_contact.round(4)) == (3.2872, 0.7128)
    assert round(float(hit.torques[0]), 2) == 910.18
    assert round(float(hit.torques[1]), 2) == 0.03
    # ... and it is right to four digits: the closed form's elbow-down contact
    exact = wall_contact(arm, Wall.through([4.0, 0.0], [0.0, 4.0]), 500.0)
    down = exact.branch("down")
    assert np.allclose(hit.p_contact, exact.p_contact[down], atol=1e-4)
    assert np.isclose(hit.torques[0], exact.tau[down, 0], atol=5e-3)
    assert np.allclose(to_relative(hit.q_abs), exact.q[down], atol=1e-4)
    assert np.isclose(hit.p_tip_fk.sum(), 4.0, atol=1e-9)  # on the wall


def test_wall_search_with_the_sin_typo_reproduces_its_contact_and_misses_the_wall():
    typo = me639.source_wall_search(reading="sin")
    assert tuple(typo.p_contact.round(4)) == (3.4116, 0.5884)
    assert round(float(typo.torques[0]), 2) == 867.11
    assert tuple(typo.p_tip_fk.round(3)) == (3.345, 0.892)
    off_wall = (typo.p_tip_fk.sum() - 4.0) / np.sqrt(2.0)
    assert off_wall > 0.1  # the real tip is inside the wall by more than 10 cm


def test_wall_search_t2_is_the_rounding_tolerance_times_l2_n():
    hit = me639.source_wall_search(reading="cos")
    # T2 = l2 |N| sin(pi/4 - q2_abs): the force is along link 2 up to the search's tolerance
    assert np.isclose(
        hit.torques[1], 2.0 * 500.0 * np.sin(np.pi / 4 - hit.q_abs[1]), rtol=1e-9
    )
    assert abs(hit.q_abs[1] - np.pi / 4) < 5e-5


def test_wall_search_rejects_bad_arguments():
    with pytest.raises(ValueError, match="n_points"):
        me639.source_wall_search(n_points=1)
    with pytest.raises(ValueError, match="matched"):
        me639.source_wall_search(n_points=7)


# --- H4.2/H4.3: torque conventions -----------------------------------------------------------------------------------


@given(q1=q1_values, q2=elbow_values, fx=st.floats(-1e3, 1e3), fy=st.floats(-1e3, 1e3))
def test_source_torques_are_the_motor_torques_of_the_dh_torques(q1, q2, fx, fy):
    q_dh = np.array([q1, q2])
    tau_dh = arm.joint_torques(q_dh, [fx, fy])
    q_abs = np.array([q1, q1 + q2])
    u = me639.source_link_torques(q_abs, [fx, fy])
    assert np.allclose(u, me639.dh_to_motor_torques(tau_dh), atol=1e-9)
    assert np.allclose(me639.motor_to_dh_torques(u), tau_dh, atol=1e-9)


# --- H4.3: the spring -----------------------------------------------------------------------------------------------


def test_spring_reproduces_the_motor_1_torques():
    p_line = [[3.0, 0.0], [3.0, 1.0], [3.0, 2.0]]
    t = me639.source_spring_torques(p_line)
    assert round(float(t[0, 0]), 1) == 2381.2 and round(float(t[0, 0])) == 2381
    assert round(float(t[1, 0]), 1) == 2323.8 and round(float(t[1, 0])) == 2324
    # H4.3: 1873.4994 rounds to 1873; only rounding its one-decimal 1873.5 again gives 1874
    assert round(float(t[2, 0]), 4) == 1873.4994
    assert int(Decimal(float(t[2, 0])).quantize(Decimal(1), ROUND_HALF_UP)) == 1873
    assert (
        int(Decimal(f"{float(t[2, 0]):.1f}").quantize(Decimal(1), ROUND_HALF_UP))
        == 1874
    )
    assert np.all(t[:, 0] > 0)  # every motor-1 torque positive, none zero
    # in DH the same torques have tau1 = 0: F = k x is radial, no moment about the shoulder
    tau_dh = me639.motor_to_dh_torques(t)
    assert np.allclose(tau_dh[:, 0], 0.0, atol=1e-9)


def test_correct_spring_in_both_conventions():
    q_dh = to_relative(me639.source_ik([[3.0, 0.0], [3.0, 1.0], [3.0, 2.0]]))
    tau_dh = me639.correct_spring_torques_dh(q_dh, [3.0, 1.0])
    assert np.allclose(
        tau_dh[:, 0], [1800.0, 0.0, -1800.0], atol=1e-9
    )  # tau1 = x F_y, F_y = k (1 - y)
    u = me639.dh_to_motor_torques(tau_dh)
    assert np.allclose(u[:, 1], tau_dh[:, 1]) and np.allclose(
        u[:, 0], tau_dh[:, 0] - tau_dh[:, 1]
    )
    assert np.allclose(u[0], [900.0, 900.0], atol=1e-9)


# --- H4.5: the workspace plot's range --------------------------------------------------------------------------------


def test_workspace_plot_samples_range_35_145_and_leaves_out_145():
    assert me639.WORKSPACE_PLOT_DEGREES == range(35, 145, 1)
    assert 145 not in me639.WORKSPACE_PLOT_DEGREES
    p = me639.source_workspace_points()
    assert p.shape == (110 * 110, 2)
    # the corner at 145 deg, both links, is missing: the leftmost tip is at 144 deg
    assert round(float(p[:, 0].min()), 3) == -3.236
    corner_145 = me639.source_fk(np.radians([145.0, 145.0]))
    assert round(float(corner_145[0]), 3) == -3.277
    assert round(float(p[:, 0].max()), 3) == 3.277  # the 35 deg corner is there


def test_the_projects_own_tasks_use_angles_outside_35_145_deg():
    # a plot range, not stated joint limits: the wall contact, the spring's rest point
    # and the line's start need absolute angles outside [35, 145] deg
    for p_tip in ([3.2872, 0.7128], [3.0, 1.0], [-3.5, 1.0]):
        q_deg = np.degrees(me639.source_ik(p_tip))
        assert np.any((q_deg < 35.0) | (q_deg > 145.0)), p_tip


# --- the reproduced IK's branch: elbow down is the one that gives H4.2's and H4.3's numbers --------------------------


def test_only_the_elbow_down_branch_gives_the_records_numbers():
    # its IK takes theta = acos(...) in [0, pi] (elbow down), one branch: the one that
    # gives H4.2's and H4.3's numbers
    from twolink import ik, to_absolute

    s = np.linspace(0.0, 1.0, 100_000)
    p_wall = np.stack([4.0 - 4.0 * s, 4.0 * s], axis=-1)
    for elbow, contact in (("down", (3.2872, 0.7128)), ("up", None)):
        q_abs = to_absolute(ik.closed_form(arm, p_wall, elbow=elbow).q)
        hits = np.flatnonzero(np.round(q_abs[:, 1], 4) == round(np.pi / 4, 4))
        found = tuple(p_wall[hits[0]].round(4)) if hits.size else None
        assert (found == contact) if contact else (found != (3.2872, 0.7128))
    p_spring = np.array([[3.0, 0.0], [3.0, 1.0], [3.0, 2.0]])
    for elbow in ("down", "up"):
        q_abs = to_absolute(ik.closed_form(arm, p_spring, elbow=elbow).q)
        t1 = me639.source_link_torques(q_abs, 600.0 * p_spring)[:, 0]
        record = np.allclose(t1, [2381.2, 2323.8, 1873.4994], atol=0.05)
        assert record == (elbow == "down"), (elbow, t1)
    assert np.allclose(
        me639.source_ik(p_spring), to_absolute(ik.closed_form(arm, p_spring).q)
    )


# --- the record it rests on: anchors inside the repository, nothing outside it --------------------------------------


def test_the_module_cites_the_source_record_by_its_anchors_and_nothing_outside():
    source = me639.__doc__ + "".join(
        getattr(me639, name).__doc__ or "" for name in me639.__all__
    )
    text = __import__("inspect").getsource(me639)
    assert "COURSE.md" not in text and "../shared" not in text
    anchors = set(re.findall(r"source_record\.ipynb#(h\d-\d+)", source))
    assert anchors == {f"h4-{item}" for item in range(1, 7)}, anchors
    # the IK is the author's (cos) by default: the transcription's sin is never its mistake
    assert "artifact" in me639.source_ik.__doc__
    assert me639.source_ik.__kwdefaults__["reading"] == "cos"
