"""twolink.errors: what each exception is, and that the package raises it."""

import numpy as np
import pytest

import twolink
from twolink import arms, errors, ik


def test_the_errors_are_value_errors_except_the_simulations():
    assert issubclass(errors.UnreachableError, ValueError)
    assert issubclass(errors.SingularityError, ValueError)
    assert issubclass(errors.SimulationError, RuntimeError)
    assert not issubclass(errors.SimulationError, ValueError)
    assert issubclass(errors.InputTypeError, TypeError)
    assert issubclass(errors.InputTypeError, ValueError)


def test_the_package_exports_each_error():
    for name in ["UnreachableError", "SingularityError", "SimulationError"]:
        assert getattr(twolink, name) is getattr(errors, name)


def test_an_unreachable_target_names_its_distance_and_the_reach():
    with pytest.raises(ValueError) as caught:
        ik.closed_form(arms.two_metre, [5.0, 0.0])
    assert type(caught.value) is errors.UnreachableError
    assert "5 m from the base" in str(caught.value) and "[0, 4] m" in str(caught.value)


def test_a_singular_configuration_names_itself():
    with pytest.raises(
        errors.SingularityError, match=r"q = \(0.3, 0\) rad is singular"
    ):
        arms.two_metre.joint_rates([0.3, 0.0], [0.0, 1.0])


@pytest.mark.parametrize("caught_as", [TypeError, ValueError])
def test_a_wrong_type_is_caught_as_a_type_error_or_a_value_error(caught_as):
    with pytest.raises(caught_as, match="l1"):
        twolink.TwoLinkArm("one", 1.0)


def test_torques_that_turn_nan_during_a_simulation_are_a_simulation_error():
    with pytest.raises(errors.SimulationError):
        twolink.simulate(
            arms.two_metre,
            [0.3, 0.4],
            [0.0, 0.0],
            1.0,
            torque=lambda t, q, qd: [np.nan if t > 0.1 else 0.0, 0.0],
        )
