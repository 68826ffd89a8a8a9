"""MAE 6245, reproduced (twolink_course.sources.mae6245).

For every number its solution printed (the course's source record,
``notebooks/source_record.ipynb``, items H1.1 to H1.9), the reproduction of its
method must give it to the printed rounding; beside it, the corrected value
computed by the package.
"""

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from conftest import angles
from twolink import arms, ik, wrap_angle
from twolink_course.sources import mae6245

ARM = arms.ten


# H1.1: the closed form on the x-equation only ------------------------------------------------


def test_closed_form_reproduces_the_printed_plus_minus_0_7854():
    roots = mae6245.x_equation_roots(mae6245.TARGET, theta2=0.0)
    assert np.round(roots, 4).tolist() == [0.7854, -0.7854]


def test_the_minus_root_is_spurious_and_the_package_gives_only_the_plus_root():
    plus, minus = mae6245.x_equation_roots(mae6245.TARGET, theta2=0.0)
    target = np.array(mae6245.TARGET)
    assert np.allclose(ARM.fk([plus, 0.0]), target, atol=1e-12)
    assert np.allclose(ARM.fk([minus, 0.0]), [target[0], -target[1]], atol=1e-12)
    assert np.round(ARM.fk([minus, 0.0]), 2).tolist() == [14.14, -14.14]  # H1.1
    assert round(float(np.hypot(*(ARM.fk([minus, 0.0]) - target))), 2) == 28.28
    q_both = ik.closed_form(ARM, target, elbow="both").q
    assert np.allclose(q_both, [[np.pi / 4, 0.0], [np.pi / 4, 0.0]], atol=1e-12)


@given(q1=angles, q2=angles)
def test_both_x_equation_roots_solve_the_x_equation_and_the_other_lands_on_the_mirror_point(
    q1, q2
):
    target = ARM.fk([q1, q2])
    assume(
        np.hypot(*target) > 0.5
    )  # not folded: the x-equation still fixes q1 up to the two roots
    assume(
        abs(target[0]) < 0.999 * np.hypot(10 + 10 * np.cos(q2), 10 * np.sin(q2))
    )  # two distinct roots
    roots = mae6245.x_equation_roots(target, theta2=q2)
    tips = np.array([ARM.fk([root, q2]) for root in roots])
    assert np.allclose(tips[:, 0], target[0], atol=1e-9)
    # one root is the configuration itself, the other reaches (x, -y): same distance, same x
    matches = [np.allclose(wrap_angle(root - q1), 0.0, atol=1e-7) for root in roots]
    assert any(matches)
    other = tips[matches.index(False)] if not all(matches) else tips[1]
    assert np.allclose(other, [target[0], -target[1]], atol=1e-7)


def test_x_equation_roots_refuses_an_x_beyond_reach():
    with pytest.raises(ValueError, match="no real root"):
        mae6245.x_equation_roots([25.0, 0.0], theta2=0.0)


# H1.2: fminunc on abs of the y-residual, acos from the x-equation ------------------------------


def test_numerical_ik_with_matlab_acos_reproduces_the_printed_0_7854_and_0():
    run = mae6245.numerical_ik(acos="matlab")
    assert run.success
    assert round(float(run.q[0]), 4) == 0.7854
    assert round(float(run.q[1]), 4) == 0.0 and run.q2_imag == 0.0
    assert abs(run.q[0] - np.pi / 4) < 1e-6 and abs(run.q[1]) < 1e-6
    assert round(float(run.q[0]), 6) == 0.785398  # H1.2: q1 = 0.785398, q2 ~ 2e-8
    assert run.evaluations == 18  # H1.2: 18 evaluations with scipy's BFGS from 0.4
    # it did leave the real domain of acos on the way, and MATLAB's complex acos carried it through
    arguments = (mae6245.TARGET[0] - 10 * np.cos(run.q1_trials)) / 10
    assert np.any(np.abs(arguments) > 1) and np.all(np.isfinite(run.objective_trials))


def test_numerical_ik_with_numpy_arccos_fails_silently_on_the_same_target():
    run = mae6245.numerical_ik(acos="numpy")
    assert not run.success
    assert np.isnan(run.q[1])
    assert round(float(run.q[0]), 1) == 1034.6  # H1.2: the run ends at q1 = 1034.6
    assert np.isnan(run.objective_trials[2])  # the first trial step already returns nan
    assert np.isfinite(run.objective_trials[:2]).all()


def test_acos_only_gives_link_2_directions_in_0_to_pi():
    # a target of the arm's workspace whose in-limits configuration has link 2 pointing down
    q_in_limits = np.radians([10.0, -60.0])
    target = ARM.fk(q_in_limits)
    assert ARM.within_limits(q_in_limits) and q_in_limits.sum() < 0
    q1_grid = np.linspace(-np.pi, np.pi, 20001)
    residual = mae6245.y_residual(q1_grid, target)
    zeros = q1_grid[residual < 1e-2]
    # the objective's only zero is the other branch, link 1 at -50 deg, outside the q1 limits
    assert np.allclose(zeros, np.radians(-50.0), atol=1e-3)
    run = mae6245.numerical_ik(target, acos="matlab")
    assert np.hypot(*(ARM.fk(np.real(run.q)) - target)) > 1.0


def test_numerical_ik_rejects_an_unknown_acos():
    with pytest.raises(ValueError, match="acos must be one of"):
        mae6245.numerical_ik(acos="octave")


def test_the_module_says_what_the_solution_contains_and_what_it_lacks():
    # H1.5: the task asks for brute force and tic/toc; the solution has neither
    text = " ".join(mae6245.__doc__.split())
    assert "no brute-force IK function, no measured times" in text
    assert '"would typically be"' in text and '"in increasing order"' in text
    assert "brute-force grid)" not in text and "by far" not in text


# H1.3: the FK check typed with 0.7845 ------------------------------------------------------------


def test_fk_check_reproduces_the_printed_14_1548_14_1294():
    assert mae6245.FK_CHECK_THETA1 == 0.7845  # a digit swap of the printed 0.7854
    assert np.round(mae6245.fk_check(), 4).tolist() == [14.1548, 14.1294]
    assert np.allclose(mae6245.fk_check(), ARM.fk([0.7845, 0.0]), atol=1e-12)


def test_fk_check_with_the_intended_angle_lands_on_the_target():
    error_typo = np.hypot(*(mae6245.fk_check(0.7845) - np.array(mae6245.TARGET)))
    error_intended = np.hypot(*(mae6245.fk_check(0.7854) - np.array(mae6245.TARGET)))
    assert (
        round(float(error_typo), 4) == 0.0180
    )  # 20 x 0.0009 rad (minus the rounding of 0.7854)
    assert error_intended < 1e-3 and error_intended < error_typo / 20


# H1.4: phi = 0:0.5:2*pi --------------------------------------------------------------------------


def test_circle_angles_are_13_with_a_short_last_gap():
    phi = mae6245.circle_angles()
    gaps = np.diff(np.append(phi, 2 * np.pi))
    assert len(phi) == 13 and phi[-1] == 6.0
    assert np.allclose(gaps[:-1], 0.5) and round(float(gaps[-1]), 3) == 0.283


@given(n=st.integers(min_value=10, max_value=20))
def test_linspace_without_end_point_gives_equal_gaps(n):
    phi = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    gaps = np.diff(np.append(phi, 2 * np.pi))
    assert np.allclose(gaps, 2 * np.pi / n)


def test_circle_angles_rejects_a_non_positive_step():
    with pytest.raises(ValueError, match="step must be > 0"):
        mae6245.circle_angles(0.0)


def test_the_module_says_what_the_task_asks_for_the_numerical_part_and_the_points():
    # H1.5: the task does not name fminunc; H1.4: "preferably equi-distant" is a preference
    text = " ".join(mae6245.__doc__.split())
    assert (
        '"one of the numerical techniques shown in class (root finding or '
        'optimization)"' in text
    )
    assert "Its worked solution chose MATLAB's ``fminunc`` for (b)" in text
    assert '"(preferably equi-distant)": a preference, not a requirement' in text


# H1.7: the closed form's cosine at its own target --------------------------------------------------


def test_closed_form_cosine_is_just_above_one_at_the_solution_s_target():
    x = mae6245.TARGET[0]
    assert repr(float(x * x)) == "200.00000000000003"
    cosine = mae6245.closed_form_cosine()
    assert repr(cosine) == "1.0000000000000002" and cosine > 1.0
    # MATLAB's acos there is complex (numpy's emath gives the same modulus)
    assert round(abs(complex(np.emath.arccos(cosine)).imag), 9) == 2.1e-08
    with np.errstate(invalid="ignore"):
        assert np.isnan(np.arccos(np.array(cosine)))  # numpy's arccos: nan
    assert np.isclose(mae6245.closed_form_cosine([15.0, 10.0]), 0.625)


@given(
    x=st.floats(-20.0, 20.0, allow_nan=False), y=st.floats(-20.0, 20.0, allow_nan=False)
)
def test_closed_form_cosine_is_the_cosine_rule(x, y):
    assert np.isclose(
        mae6245.closed_form_cosine([x, y]),
        (x * x + y * y - 200.0) / 200.0,
        rtol=1e-12,
        atol=1e-12,
    )


# H1.8: its workspace grid stops short of pi/2 ------------------------------------------------------


def test_workspace_grid_stops_short_of_pi_over_2():
    theta1, theta2 = mae6245.workspace_grid()
    assert round(float(theta1[-1]), 3) == 1.5 and round(float(theta2[-1]), 3) == 1.529
    assert theta1[-1] < np.pi / 2 and theta2[-1] < np.pi / 2
    assert theta1[0] == 0.0 and theta2[0] == -np.pi / 2
    assert np.allclose(np.diff(theta1), 0.1) and np.allclose(np.diff(theta2), 0.1)


@given(
    start=st.floats(-10.0, 10.0),
    step=st.floats(0.01, 2.0),
    span=st.floats(0.0, 20.0),
)
def test_colon_never_passes_its_bound_and_misses_it_by_less_than_a_step(
    start, step, span
):
    values = mae6245.colon(start, step, start + span)
    assert values[0] == start and values[-1] <= start + span + 1e-9
    assert start + span - values[-1] < step + 1e-9


def test_colon_refuses_a_bad_step_or_range():
    with pytest.raises(ValueError, match="step must be > 0"):
        mae6245.colon(0.0, -0.1, 1.0)
    with pytest.raises(ValueError, match="start <= stop"):
        mae6245.colon(1.0, 0.1, 0.0)


# H1.9: its part (e) draws the arm with the digit swap again -------------------------------------


def test_part_e_draws_the_arm_at_the_swapped_digits():
    assert mae6245.PART_E_ANGLES == (0.7845, -0.7845)
    assert mae6245.PART_E_ANGLES[0] == mae6245.FK_CHECK_THETA1
