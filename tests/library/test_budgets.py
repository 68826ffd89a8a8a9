"""The package's budgets live in one module: twolink.budgets."""

import sys

import numpy as np
import pytest

from twolink import budgets, trajectory, workspace


def test_max_samples_is_one_constant_reexported():
    assert trajectory.MAX_SAMPLES is budgets.MAX_SAMPLES
    assert workspace.MAX_SAMPLES is budgets.MAX_SAMPLES


def test_max_samples_bounds_the_sample_counts():
    with pytest.raises(ValueError, match="10000000"):
        workspace.circle_points([0.0, 0.0], 1.0, n=budgets.MAX_SAMPLES + 1)


def test_simulation_results_share_one_read_only_helper():
    import twolink.engine  # noqa: F401  (the module, not a function)

    simulate_module = sys.modules["twolink.simulation"]
    engine_module = sys.modules["twolink.engine"]
    assert not hasattr(simulate_module, "_frozen") and not hasattr(
        engine_module, "_frozen"
    )
    from twolink._validate import frozen_array

    array = frozen_array(np.arange(3))
    assert array.dtype == float and not array.flags.writeable


def test_simulate_and_resolved_rate_spend_the_same_budget():
    from twolink import TwoLinkArm, simulate
    from twolink.errors import SimulationError

    arm = TwoLinkArm(1.0, 1.0)
    with pytest.raises(SimulationError, match=r"max_evaluations = 20 evaluations"):
        simulate(arm, [0.3, 0.4], [0.0, 0.0], 10.0, max_evaluations=20)
    path = trajectory.LinePath([1.2, 0.3], [0.3, 1.2], duration=1.0)
    with pytest.raises(SimulationError, match=r"max_evaluations = 20 evaluations"):
        trajectory.resolved_rate_trajectory(arm, path, max_evaluations=20)


def test_a_budget_refuses_junk():
    with pytest.raises(ValueError, match="max_wall_time"):
        budgets.EvaluationBudget(10, -1.0)
    budget = budgets.EvaluationBudget(10, 1e-9)
    budget.deadline = budget.started - 1.0  # spent
    assert budget.out_of_time() and budget.spend() == "max_wall_time"
