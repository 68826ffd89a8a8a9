"""twolink.ik.targets."""

import numpy as np
import pytest

from twolink import TwoLinkArm, UnreachableError, arms
from twolink.ik.targets import reachable_targets


def test_reachable_targets_are_a_float_copy_never_the_callers_array():
    p = np.array([[3.0, 1.0], [0.0, 2.0]])
    targets = reachable_targets(arms.two_metre, p)
    assert targets.dtype == np.float64 and np.array_equal(targets, p)
    assert not np.may_share_memory(targets, p)
    assert reachable_targets(arms.two_metre, [3, 1]).dtype == np.float64


def test_a_target_out_of_reach_is_an_unreachable_error_naming_it():
    with pytest.raises(
        UnreachableError, match=r"target \(3, 4\) .* is 5 m from the base"
    ):
        reachable_targets(TwoLinkArm(1.0, 1.0), [[1.0, 0.0], [3.0, 4.0]])


@pytest.mark.parametrize("bad", [[1.0, 2.0, 3.0], [np.nan, 1.0], "ab", None], ids=repr)
def test_targets_that_are_not_finite_pairs_are_refused_naming_target_p(bad):
    with pytest.raises(ValueError, match="target p"):
        reachable_targets(arms.two_metre, bad)


def test_an_empty_batch_of_targets_is_an_empty_array():
    assert reachable_targets(arms.two_metre, np.empty((0, 2))).shape == (0, 2)
