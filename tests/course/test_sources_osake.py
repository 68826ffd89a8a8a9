"""The OSAKE mini-project reproduced (twolink_course.sources.osake), and the course's corrections.

Lengths in the source module are in its unit, centimetres; the package's arm
``arms.osake`` is in metres, hence the factor 100 below.
"""

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from conftest import angles, configurations
from twolink import arms
from twolink_course.sources import osake

CM = 100.0  # centimetres per metre
q_example = np.radians([30.0, 45.0])


def right_h02_cm(q):
    H = arms.osake.transforms(q)[1].copy()
    H[..., :3, 3] *= CM
    return H


def test_the_module_uses_the_osake_arm():
    assert (osake.L1_CM, osake.L2_CM, osake.D_CM) == pytest.approx(
        (CM * arms.osake.l1, CM * arms.osake.l2, CM * arms.osake.d)
    )


# --- H3.1: the hand-expanded H_0^2
@given(q=configurations())
def test_expanded_h02_rotation_block_has_determinant_cos_squared_q2(q):
    H_wrong = osake.h02_as_expanded(q)
    assert np.isclose(np.linalg.det(H_wrong[:2, :2]), np.cos(q[1]) ** 2, atol=1e-12)
    assert np.isclose(np.linalg.det(right_h02_cm(q)[:2, :2]), 1.0, atol=1e-12)


@given(q1=angles)
def test_expanded_h02_is_right_when_the_arm_is_stretched(q1):
    assert np.allclose(
        osake.h02_as_expanded([q1, 0.0]), right_h02_cm([q1, 0.0]), atol=1e-12
    )


@given(q=configurations())
def test_expanded_h02_misplaces_the_tip_whenever_the_elbow_is_bent(q):
    assume(abs(q[1]) > 0.05)
    error_cm = np.linalg.norm(osake.h02_as_expanded(q)[:2, 3] - right_h02_cm(q)[:2, 3])
    assert error_cm > 0.01


def test_expanded_h02_at_30_45_degrees():
    H_wrong, H_right = osake.h02_as_expanded(q_example), right_h02_cm(q_example)
    c1, s1, c2 = np.cos(q_example[0]), np.sin(q_example[0]), np.cos(q_example[1])
    l1, l2 = osake.L1_CM, osake.L2_CM
    assert np.allclose(H_wrong[:2, 3], [l2 * c1 + l1 * c1 * c2, l2 * s1 + l1 * s1 * c2])
    assert np.allclose(H_wrong[:2, :2], c2 * np.array([[c1, -s1], [s1, c1]]))
    assert np.isclose(np.linalg.det(H_wrong[:2, :2]), 0.5)
    error_cm = np.linalg.norm(H_wrong[:2, 3] - H_right[:2, 3])
    assert (
        6.0 < error_cm < 9.0
    )  # the tip is off by several centimetres on a 21.5 cm arm
    assert np.allclose(
        H_wrong[2:, :], H_right[2:, :]
    )  # the height row and the last row are right


def test_expanded_h02_numbers_at_30_45_degrees():
    # cos q1 cos q2 for cos(q1 + q2), sin q1 cos q2 for sin(q1 + q2), l1 and l2 swapped
    H_wrong = osake.h02_as_expanded(q_example)
    assert np.allclose(
        H_wrong,
        [
            [0.6124, -0.3536, 0.0, 16.0830],
            [0.3536, 0.6124, 0.0, 9.2855],
            [0.0, 0.0, 1.0, 6.5],
            [0.0, 0.0, 0.0, 1.0],
        ],
        atol=5e-5,
        rtol=0.0,
    )
    assert np.allclose(
        right_h02_cm(q_example)[:3, 3], [11.6367, 16.1081, 6.5], atol=5e-5, rtol=0.0
    )


# --- H3.2: the Jacobian printed under the derivation carries the expanded H_0^2's product error
def right_jacobian_cm(q):
    return arms.osake.geometric_jacobian(q) * np.array(
        [[CM], [CM], [CM], [1.0], [1.0], [1.0]]
    )


@given(q=configurations())
def test_printed_jacobian_has_single_angle_products_where_the_angle_sums_belong(q):
    # right: l2 (-s12, c12) in both columns, plus the l1 lever in column 1; printed, read
    # as products: s12 -> s1 c2 in column 1, s1 s2 in column 2; c12 -> c1 c2, c1 s2
    J_printed, J_right = osake.jacobian_as_printed(q), right_jacobian_cm(q)
    (c1, c2), (s1, s2) = np.cos(q), np.sin(q)
    s12, c12 = np.sin(q.sum()), np.cos(q.sum())
    l2 = osake.L2_CM
    assert np.allclose(
        J_printed[:2] - J_right[:2],
        l2 * np.array([[s12 - s1 * c2, s12 - s1 * s2], [c1 * c2 - c12, c1 * s2 - c12]]),
        atol=1e-12,
    )
    assert np.allclose(
        J_printed[2:], J_right[2:], atol=0.0
    )  # v_z = 0, omega = (0, 0, 1)


@given(q=configurations())
def test_printed_jacobian_columns_are_parallel_so_it_is_singular_everywhere(q):
    # source record H3.2: column 1 = (l1 + l2 c2)(-s1, c1), column 2 = l2 s2 (-s1, c1)
    (c1, c2), (s1, s2) = np.cos(q), np.sin(q)
    J_printed = osake.jacobian_as_printed(q)[:2]
    direction = np.array([-s1, c1])
    assert np.allclose(
        J_printed[:, 0], (osake.L1_CM + osake.L2_CM * c2) * direction, atol=1e-12
    )
    assert np.allclose(J_printed[:, 1], osake.L2_CM * s2 * direction, atol=1e-12)
    assert abs(np.linalg.det(J_printed)) < 1e-9
    # the right block is singular only where sin q2 = 0
    right = np.linalg.det(right_jacobian_cm(q)[:2])
    assert np.isclose(right, osake.L1_CM * osake.L2_CM * s2, atol=1e-9)


def test_printed_jacobian_columns_are_parallel_not_equal_and_hide_it_at_45_degrees():
    J_45 = osake.jacobian_as_printed(q_example)[:2]
    assert not np.allclose(J_45[:, 0], J_45[:, 1])  # parallel, not equal
    q_60 = np.radians([30.0, 60.0])
    assert abs(np.linalg.det(osake.jacobian_as_printed(q_60)[:2])) < 1e-12
    assert round(np.linalg.det(right_jacobian_cm(q_60)[:2]), 1) == 99.6  # cm^2


def test_printed_jacobian_at_30_45_degrees_gives_the_record_numbers():
    record_cm = np.array(
        [[-9.07, -4.07], [15.70, 7.04]]
    )  # the source record's numbers (H3.2), cm per rad
    right_cm = np.array([[-16.11, -11.11], [11.64, 2.98]])
    J_printed = osake.jacobian_as_printed(q_example)
    assert J_printed.shape == (6, 2)
    assert np.allclose(J_printed[:2], record_cm, atol=0.005, rtol=0.0)
    assert np.allclose(right_jacobian_cm(q_example)[:2], right_cm, atol=0.005, rtol=0.0)


def test_printed_jacobian_checks_its_inputs():
    with pytest.raises(ValueError, match="q"):
        osake.jacobian_as_printed([0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match="l2"):
        osake.jacobian_as_printed([0.1, 0.2], l2=0.0)


def test_printed_jacobian_broadcasts_over_configurations():
    q_many = np.random.default_rng(3).uniform(-np.pi, np.pi, size=(4, 5, 2))
    J_many = osake.jacobian_as_printed(q_many)
    assert J_many.shape == (4, 5, 6, 2)
    assert np.allclose(J_many[2, 3], osake.jacobian_as_printed(q_many[2, 3]))


# --- H3.3: the C++ forward-kinematics program
@given(
    value=st.floats(min_value=0.0, max_value=1e6, allow_nan=False),
    decimals=st.integers(0, 4),
)
def test_cpp_read_int_truncates_a_typed_decimal(value, decimals):
    typed = f"{value:.{decimals}f}"
    assert osake.cpp_read_int(typed) == int(typed.split(".")[0])


def test_cpp_read_int_rejects_text():
    with pytest.raises(ValueError, match="typed must start with an integer"):
        osake.cpp_read_int("eleven")


@given(q=configurations())
def test_cpp_fk_without_its_mistakes_is_the_package_fk(q):
    assert np.allclose(
        osake.cpp_fk_tip(q, int_lengths=False, drop_offset=False),
        right_h02_cm(q)[:3, 3],
        atol=1e-12,
    )


@given(q=configurations())
def test_cpp_fk_int_lengths_cost_5_mm_and_the_dropped_offset_6_5_cm(q):
    p_right = right_h02_cm(q)[:3, 3]
    p_int = osake.cpp_fk_tip(q, drop_offset=False)
    p_no_offset = osake.cpp_fk_tip(q, int_lengths=False)
    p_source = osake.cpp_fk_tip(q)
    assert np.isclose(
        np.linalg.norm(p_int - p_right), osake.L2_CM - 11.0
    )  # 0.5 cm, along link 2
    assert np.allclose(p_no_offset[:2], p_right[:2]) and np.isclose(
        p_right[2] - p_no_offset[2], osake.D_CM
    )
    assert np.isclose(
        np.linalg.norm(p_source - p_right), np.hypot(osake.L2_CM - 11.0, osake.D_CM)
    )


def test_cpp_fk_tip_at_30_45_degrees():
    # 10 and 11.5 typed, stored as int 10 and 11; H01's z-offset 0
    p_source = osake.cpp_fk_tip(q_example)
    p_right = right_h02_cm(q_example)[:3, 3]
    assert np.allclose(p_source, [11.5073, 15.6252, 0.0], atol=5e-5, rtol=0.0)
    assert np.allclose(p_right, [11.6367, 16.1081, 6.5], atol=5e-5, rtol=0.0)
    assert round(10.0 * np.linalg.norm(p_source - p_right), 1) == 65.2  # mm
    assert [osake.cpp_read_int(typed) for typed in ("10", "11.5")] == [10, 11]


@given(
    left=st.lists(
        st.lists(st.floats(-10, 10), min_size=4, max_size=4), min_size=4, max_size=4
    ),
    right=st.lists(
        st.lists(st.floats(-10, 10), min_size=4, max_size=4), min_size=4, max_size=4
    ),
)
def test_triple_loop_is_the_matrix_product(left, right):
    assert np.allclose(
        osake.matmul_triple_loop(left, right),
        np.array(left) @ np.array(right),
        atol=1e-9,
    )


# --- H3.4: the C++ velocity program (l1 = 10.0, l2 = 11.5, t = 2, forward difference, delta_t = 1e-6)
def exact_program_speed(l1=osake.L1_CM, l2=osake.L2_CM):
    """The program's number with the exact slope (3, 0) of its angle functions: 3 rad/s times |p| at 60 rad."""
    return 3.0 * np.sqrt(l1**2 + l2**2 + 2 * l1 * l2 * np.cos(60.0))


def forward_difference_bound(t, step):
    """Relative error the program's forward difference of 3 t can carry: round-off only (the function is linear).

    fl(t + step), 3 fl(t + step) and 3 t each round by at most eps/2 of a number
    of size 3 (|t| + step), and the difference is divided by 3 step: at most
    1.5 eps (|t| + step) / step of the slope 3.  The angles themselves round
    too: theta1 = 3 t and theta1 + theta2 carry absolute errors up to eps times
    their size, which the lever arms l1 and l2 turn into position errors; the
    tip's radius |p| = 3.6 cm at 60 rad comes out of a cancellation of 10 cm
    and 11.5 cm terms, so divide by it.  Add a few dozen eps for the
    subtraction, the division, J and the norm.
    """
    eps = np.finfo(float).eps
    radius_cm = exact_program_speed() / 3.0
    angle_term = (
        osake.L1_CM * 3.0 * abs(t) + osake.L2_CM * (3.0 * abs(t) + 60.0)
    ) / radius_cm
    return eps * (2.0 * (abs(t) + step) / step + angle_term + 32.0)


def test_velocity_program_gives_the_record_s_reproduced_number():
    # source record H3.4: the source shows no output; run as written it gives 10.8975
    assert not hasattr(osake, "PRINTED_SPEED_CM_S")
    assert round(osake.velocity_program_speed(), 4) == 10.8975  # t = 2, 1e-6 s
    assert round(osake.velocity_program_speed(t=2.0, step=1e-6), 4) == 10.8975


def test_velocity_program_forward_difference_costs_only_round_off_at_t_2():
    t, step = 2.0, 1e-6
    as_run, exact = osake.velocity_program_speed(t, step=step), exact_program_speed()
    bound = forward_difference_bound(t, step)
    assert bound < 1e-9
    assert abs(as_run - exact) <= bound * exact


@given(
    t=st.floats(min_value=-120.0, max_value=120.0),
    step=st.sampled_from([1e-6, 1e-4, 1e-2, 1.0]),
)
def test_velocity_program_is_three_rad_per_s_times_the_radius_at_60_rad_for_any_t(
    t, step
):
    as_run = osake.velocity_program_speed(t, step=step)
    assert (
        abs(as_run - exact_program_speed())
        <= forward_difference_bound(t, step) * exact_program_speed()
    )


def test_velocity_program_number_against_the_jacobian():
    as_run = osake.velocity_program_speed()
    q = np.radians([3.0 * 2.0, 60.0])  # t = 2 s: theta1 = 6 deg, theta2 = 60 deg
    right_cm_s = CM * np.linalg.norm(arms.osake.tip_velocity(q, np.radians([3.0, 0.0])))
    assert np.isclose(
        right_cm_s, np.radians(3.0) * CM * np.linalg.norm(arms.osake.fk(q))
    )
    assert round(right_cm_s, 4) == 0.9757
    assert 11.1 < as_run / right_cm_s < 11.2
    # each mistake alone: 3 used as rad/s multiplies by 180/pi; 60 rad for 60 deg shrinks the radius
    rate_only = CM * np.linalg.norm(arms.osake.tip_velocity(q, [3.0, 0.0]))
    assert np.isclose(rate_only / right_cm_s, 180.0 / np.pi)
    angle_only = CM * np.linalg.norm(
        arms.osake.tip_velocity([6.0, 60.0], np.radians([3.0, 0.0]))
    )
    assert np.isclose(as_run / angle_only, 180.0 / np.pi)
    # the program is the package's tip velocity at its radian-read angles and rates
    assert np.isclose(
        as_run,
        CM * np.linalg.norm(arms.osake.tip_velocity([6.0, 60.0], [3.0, 0.0])),
        rtol=1e-9,
    )


def test_velocity_program_checks_its_inputs():
    with pytest.raises(ValueError, match="step"):
        osake.velocity_program_speed(step=0.0)
    with pytest.raises(ValueError, match="step"):
        osake.velocity_program_speed(2.0, step=-1e-6)
    with pytest.raises(ValueError, match="t"):
        osake.velocity_program_speed(float("nan"))
    with pytest.raises(ValueError, match="l2"):
        osake.velocity_program_speed(l2=0.0)


# --- H3.5: the vector d_0^2 under the expanded H_0^2, a third tip
@given(q=configurations())
def test_d02_tip_as_written_has_the_lengths_and_sine_cosine_swapped(q):
    (c1, _), (s1, s2) = np.cos(q), np.sin(q)
    l1, l2 = osake.L1_CM, osake.L2_CM
    assert np.allclose(
        osake.d02_tip_as_written(q), [l2 * c1 * s2 + l1 * s1, l2 * s1 * s2 + l1 * c1]
    )


def test_d02_tip_as_written_is_a_third_tip_at_30_45_degrees():
    third = osake.d02_tip_as_written(q_example)
    assert np.round(third, 2).tolist() == [12.04, 12.73]
    right = right_h02_cm(q_example)[:2, 3]
    expanded = osake.h02_as_expanded(q_example)[:2, 3]
    assert np.round(right, 2).tolist() == [11.64, 16.11]
    assert min(np.linalg.norm(third - right), np.linalg.norm(third - expanded)) > 1.0


def test_d02_tip_as_written_checks_its_inputs():
    with pytest.raises(ValueError, match="q"):
        osake.d02_tip_as_written([0.1])
    with pytest.raises(ValueError, match="l1"):
        osake.d02_tip_as_written([0.1, 0.2], l1=-1.0)
