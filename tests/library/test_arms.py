"""twolink.arms: the preset arms are the sources' arms, frozen."""

import dataclasses

import numpy as np
import pytest

from twolink import (
    TwoLinkArm,
    arms,
)


def test_presets_match_the_sources():
    assert (arms.two_metre.l1, arms.two_metre.l2) == (2.0, 2.0)
    assert (arms.ten.l1, arms.ten.l2) == (10.0, 10.0)
    assert np.allclose(np.degrees(arms.ten.q_min), [0.0, -90.0])
    assert np.allclose(np.degrees(arms.ten.q_max), [90.0, 90.0])
    assert (arms.osake.l1, arms.osake.l2, arms.osake.d) == (0.10, 0.115, 0.065)
    assert arms.two_metre_limited.limit_convention == "absolute"
    assert np.allclose(np.degrees(arms.two_metre_limited.q_min), [35.0, 35.0])
    assert np.allclose(np.degrees(arms.two_metre_limited.q_max), [145.0, 145.0])


PRESETS = {name: getattr(arms, name) for name in arms.__all__}


def test_every_preset_is_an_arm():
    assert set(PRESETS) == {"two_metre", "two_metre_limited", "ten", "osake"}
    assert all(isinstance(arm, TwoLinkArm) for arm in PRESETS.values())


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_presets_are_frozen_and_replace_makes_a_variant(name):
    preset = PRESETS[name]
    with pytest.raises(dataclasses.FrozenInstanceError):
        preset.l1 = 3.0
    variant = dataclasses.replace(preset, l1=3.0)
    assert variant.l1 == 3.0 and variant.l2 == preset.l2
    assert preset.l1 != 3.0


def test_presets_reach_what_their_sources_say():
    assert arms.two_metre.reach == pytest.approx((0.0, 4.0))
    assert arms.ten.reach == pytest.approx((0.0, 20.0))
    assert arms.osake.reach == pytest.approx((0.015, 0.215))
    assert not arms.two_metre.has_limits and arms.ten.has_limits


def test_the_limited_two_metre_arm_bounds_link_angles_not_joint_angles():
    """(40, 110) deg puts link 2 at 150 deg, outside; read as joint limits q2 = 110 is inside."""
    inside, outside = np.radians([40.0, 100.0]), np.radians([40.0, 110.0])
    assert arms.two_metre_limited.within_limits(inside)
    assert not arms.two_metre_limited.within_limits(outside)
    assert (
        TwoLinkArm(
            2.0,
            2.0,
            q_min=arms.two_metre_limited.q_min,
            q_max=arms.two_metre_limited.q_max,
        ).within_limits(outside)
        is True
    )
