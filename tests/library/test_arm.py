"""TwoLinkArm: construction, validation, limits and the methods' wrappers (the presets: tests/library/test_arms.py)."""

import dataclasses
import warnings

import numpy as np
import pytest
from _cases import BAD_NUMBERS, stable_id
from hypothesis import given, settings
from hypothesis import strategies as st

import twolink
from twolink import (
    TwoLinkArm,
    arms,
    ik,
)
from twolink.arm import LENGTH_RANGE
from twolink.errors import InputTypeError


def test_defaults_and_fields():
    arm = TwoLinkArm(1.5, 0.5)
    assert (arm.m1, arm.m2, arm.g, arm.d) == (1.0, 1.0, 9.81, 0.0)
    assert arm.q_min is None and arm.q_max is None and not arm.has_limits
    assert arm.reach == (1.0, 2.0)


def test_frozen():
    arm = TwoLinkArm(1.0, 1.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        arm.l1 = 2.0


def test_uniform_rod_inertias_and_override():
    arm = TwoLinkArm(2.0, 1.0, m1=3.0, m2=6.0)
    assert arm.inertias == pytest.approx((3.0 * 4.0 / 12.0, 6.0 / 12.0))
    assert TwoLinkArm(2.0, 1.0, I1=0.7, I2=0.2).inertias == (0.7, 0.2)
    # replace() recomputes the rod inertia from the new length
    assert dataclasses.replace(arm, l1=4.0).inertias[0] == pytest.approx(
        3.0 * 16.0 / 12.0
    )


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"l1": 0.0, "l2": 1.0}, "l1 (link 1 length, m) must be > 0"),
        ({"l1": 1.0, "l2": -2.0}, "l2 (link 2 length, m) must be > 0"),
        ({"l1": float("nan"), "l2": 1.0}, "must be finite"),
        ({"l1": 1.0, "l2": 1.0, "m1": -1.0}, "m1 (link 1 mass, kg) must be >= 0"),
        ({"l1": 1.0, "l2": 1.0, "m2": float("inf")}, "must be finite"),
        ({"l1": 1.0, "l2": 1.0, "g": float("nan")}, "g (m/s^2) must be finite"),
        ({"l1": 1.0, "l2": 1.0, "q_min": (0.0, 0.0)}, "given together"),
        (
            {"l1": 1.0, "l2": 1.0, "q_min": (1.0, 0.0), "q_max": (0.0, 1.0)},
            "q_min must be <= q_max",
        ),
        ({"l1": 1.0, "l2": 1.0, "q_min": (0.0,), "q_max": (1.0, 1.0)}, "two angles"),
        (
            {"l1": 1.0, "l2": 1.0, "q_min": (0.0, float("nan")), "q_max": (1.0, 1.0)},
            "finite",
        ),
        ({"l1": 1.0, "l2": 1.0, "I1": -0.1}, "I1 (inertia, kg m^2) must be >= 0"),
        (
            {"l1": 1.0, "l2": 1.0, "limit_convention": "degrees"},
            "limit_convention must be one of",
        ),
        ({"l1": "one", "l2": 1.0}, "must be a real number"),
    ],
)
def test_invalid_parameters_raise_value_error(kwargs, fragment):
    with pytest.raises(
        ValueError,
        match=fragment.replace("(", r"\(").replace(")", r"\)").replace("^", r"\^"),
    ):
        TwoLinkArm(**kwargs)


def test_within_limits_relative_and_absolute():
    inside, outside = np.radians([45.0, -45.0]), np.radians([45.0, -100.0])
    assert arms.ten.within_limits([inside, outside]).tolist() == [True, False]
    # Absolute limits bound q1 and q1 + q2: q = (40, 100) deg has q1 + q2 = 140 (inside),
    # q = (40, 110) deg has 150 (outside), q = (30, 40) deg has q1 = 30 (outside).
    q = np.radians([[40.0, 100.0], [40.0, 110.0], [30.0, 40.0]])
    assert arms.two_metre_limited.within_limits(q).tolist() == [True, False, False]
    assert TwoLinkArm(1.0, 1.0).within_limits(np.zeros((4, 2))).all()


def test_public_api_names():
    for name in [
        "TwoLinkArm",
        "arms",
        "ik",
        "to_absolute",
        "to_relative",
        "UnreachableError",
        "SingularityError",
    ]:
        assert hasattr(twolink, name), name
    assert issubclass(twolink.UnreachableError, ValueError)
    assert issubclass(twolink.SingularityError, ValueError)
    for name in ["closed_form", "newton", "minimize", "brute_force", "IKResult"]:
        assert hasattr(twolink.ik, name), name


# ----------------------------------------------------------------- within_limits: one formula, one type per input
angles_around = st.floats(-4.0, 4.0, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(angles_around, angles_around, st.sampled_from(["relative", "absolute"]))
def test_within_limits_of_one_configuration_is_a_bool_equal_to_the_batch(
    q1, q2, convention
):
    arm = TwoLinkArm(
        1.0, 1.0, q_min=(-1.0, -2.0), q_max=(1.5, 2.5), limit_convention=convention
    )
    for q in (
        [q1, q2],
        (q1, q2),
        np.array([q1, q2]),
        np.array([q1, q2], dtype=np.float32),
    ):
        one = arm.within_limits(q)
        assert type(one) is bool
    batch = arm.within_limits(np.array([[q1, q2]]))
    assert isinstance(batch, np.ndarray) and batch.dtype == bool and batch.shape == (1,)
    assert arm.within_limits([q1, q2]) == bool(batch[0])
    # a configuration exactly on a limit counts as inside on both paths
    on_limit = [1.5, 2.5 - 1.5] if convention == "absolute" else [1.5, 2.5]
    assert (
        arm.within_limits(on_limit) is True
        and arm.within_limits(np.array([on_limit]))[0]
    )


def test_within_limits_of_an_arm_without_limits_has_the_same_types():
    """It gave a 0-d array here (and numpy.bool_ for an arm with limits): a bool, or an array for a batch."""
    free = TwoLinkArm(1.0, 1.0)
    assert (
        free.within_limits([9.0, -9.0]) is True
        and free.within_limits(np.array([9.0, -9.0])) is True
    )
    batch = free.within_limits(np.zeros((3, 4, 2)))
    assert (
        isinstance(batch, np.ndarray)
        and batch.dtype == bool
        and batch.shape == (3, 4)
        and batch.all()
    )
    assert (
        arms.ten.within_limits([0.5, 1.0]) is True
        and arms.ten.within_limits([-0.5, 1.0]) is False
    )


@pytest.mark.parametrize("tol", [-1e-3, float("nan"), "0.1", None], ids=repr)
def test_within_limits_checks_its_tolerance_for_one_configuration_as_for_a_batch(tol):
    for q in ([0.1, 0.2], np.array([[0.1, 0.2]])):
        with pytest.raises(ValueError, match=r"tol \(rad\)"):
            arms.ten.within_limits(q, tol=tol)


# ----------------------------- magnitudes: parameters outside the representable range
@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"l1": 1e155, "l2": 1.0}, "l1"),
        ({"l1": 1.0, "l2": 1e-160}, "l2"),
        ({"l1": 1.0, "l2": 1.0, "m1": 1e300}, "m1"),
        ({"l1": 1.0, "l2": 1.0, "m2": 1e200}, "m2"),
        ({"l1": 1.0, "l2": 1.0, "I1": 1e200}, "I1"),
        ({"l1": 1.0, "l2": 1.0, "g": 1e300}, "g"),
    ],
)
def test_parameters_outside_the_representable_range_are_refused_naming_the_range(
    kwargs, name
):
    with pytest.raises(
        ValueError, match=rf"{name} .* is outside the representable range"
    ):
        TwoLinkArm(**kwargs)


@pytest.mark.parametrize("length", [LENGTH_RANGE[0], 1e-30, 1.0, 1e30, LENGTH_RANGE[1]])
def test_arms_at_the_ends_of_the_range_are_exact(length):
    arm = TwoLinkArm(
        length, length, m1=2.0, m2=3.0, g=0.0
    )  # with gravity, tiny arms are all weight (qdd lost to m g l)
    q = np.array([0.4, 1.1])
    qdd_wanted = np.array([0.8, -1.3])
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow or underflow warnings either
        p = arm.fk(q)
        assert np.allclose(ik.closed_form(arm, p).q, q, rtol=1e-12)
        tau = arm.inverse_dynamics(q, [0.3, -0.2], qdd_wanted)
        qdd = arm.forward_dynamics(q, [0.3, -0.2], tau)
    assert np.all(np.isfinite(tau))
    assert np.allclose(qdd, qdd_wanted, rtol=1e-9, atol=1e-9)


# ------------------------------------------------------------ types of the parameters
@pytest.mark.parametrize("bad", BAD_NUMBERS, ids=stable_id)
@pytest.mark.parametrize("field", ["l1", "l2", "m1", "m2", "g", "d", "I1", "I2"])
def test_arm_parameters_refuse_non_numbers(field, bad):
    kwargs = {"l1": 1.0, "l2": 1.0, field: bad}
    if bad is None and field in ("I1", "I2"):
        return  # None is the documented default (uniform rod)
    with pytest.raises(InputTypeError, match=field):
        TwoLinkArm(**kwargs)


@pytest.mark.parametrize(
    "bad",
    ["12", "ab", [1.0, "2"], [True, 1.0], [1j, 1.0], 5.0, [[0.0, 1.0]]],
    ids=stable_id,
)
def test_joint_limits_refuse_strings_and_other_non_angles(bad):
    with pytest.raises(ValueError, match="q_min"):
        TwoLinkArm(1.0, 1.0, q_min=bad, q_max=(1.0, 1.0))


@pytest.mark.parametrize("bad", [None, 1, ["relative"]], ids=stable_id)
def test_limit_convention_must_be_a_name(bad):
    with pytest.raises(ValueError, match="limit_convention must be one of"):
        TwoLinkArm(1.0, 1.0, limit_convention=bad)
