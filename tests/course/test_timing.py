"""The IK comparison used by chapters 2 and 7 and by the benchmarks."""

import numpy as np
import pytest

from twolink import arms
from twolink_course import timing


def circle(n=6):
    angle = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.c_[12.5 + 2 * np.cos(angle), 12.5 + 2 * np.sin(angle)]


@pytest.mark.parametrize("per_call", [True, False])
def test_every_method_reports_accuracy_from_fk(per_call):
    rows = timing.compare_ik_methods(arms.ten, circle(), repeat=1, per_call=per_call)
    assert [row["method"] for row in rows] == list(timing.IK_METHODS)
    for row in rows:
        assert row["seconds_per_target"] > 0
        assert row["solved"] == 1.0, row
    by_name = {row["method"]: row for row in rows}
    assert by_name["closed form"]["max_residual"] < 1e-12
    # brute force error is set by the grid: about the grid bound, far above the others
    assert (
        1e-4 < by_name["brute force"]["max_residual"] <= (10 + 20) * np.radians(1.0) / 2
    )


def test_unknown_method_and_bad_targets():
    with pytest.raises(ValueError, match="unknown methods"):
        timing.compare_ik_methods(arms.ten, circle(), methods=["magic"])
    with pytest.raises(ValueError, match="shape \\(n, 2\\)"):
        timing.compare_ik_methods(arms.ten, [10.0, 10.0])
    with pytest.raises(ValueError, match="repeat must be"):
        timing.median_time(lambda: None, repeat=0)


def test_timing_an_empty_batch_is_refused_clearly():
    from twolink_course import timing

    with pytest.raises(ValueError, match=r"n >= 1"):
        timing.compare_ik_methods(
            arms.ten, np.empty((0, 2)), methods=["closed form"], repeat=1
        )


@pytest.mark.parametrize("seconds", [np.inf, np.nan, 1e9, -1.0, 0.0])
def test_timing_helpers_refuse_infinite_budgets(seconds):
    with pytest.raises(ValueError, match="min_seconds"):
        timing.median_time(lambda: None, min_seconds=seconds)


def test_while_grading_a_timing_is_one_call_timed_once(monkeypatch):
    calls = []
    seconds_taught = timing.median_time(lambda: calls.append(1), repeat=3)
    assert len(calls) > 3 and seconds_taught > 0  # calibrated batches
    monkeypatch.setenv("TWOLINK_GRADING", "1")
    calls.clear()
    assert timing.median_time(lambda: calls.append(1), repeat=3) > 0
    assert calls == [1]
    # bad input is refused as without the switch
    with pytest.raises(ValueError, match="min_seconds"):
        timing.median_time(lambda: None, min_seconds=np.inf)
    rows = timing.compare_ik_methods(arms.ten, circle(), repeat=3)
    assert all(row["seconds_per_target"] > 0 and row["solved"] == 1.0 for row in rows)
