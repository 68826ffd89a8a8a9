"""twolink_course.exercises.forbidden: the package's own answer unavailable, by whatever name it is reached."""

import sys
import threading

import numpy as np
import pytest

from twolink import TwoLinkArm, kinematics, workspace
from twolink_course.exercises import forbidden

ARM = TwoLinkArm(1.0, 0.5)
FK = ("twolink.arm.TwoLinkArm.fk", "twolink.kinematics.fk")


def outcome(function, paths=FK):
    """What ``function()`` returned or raised while ``paths`` were unavailable, and what was called."""
    with forbidden.unavailable(paths) as called:
        try:
            result = function()
        except forbidden.ForbiddenCall as error:
            result = error
    return result, called


def test_a_method_an_alias_and_a_copy_of_the_function_are_all_stopped():
    alias = kinematics.fk
    copy = type(kinematics.fk)(kinematics.fk.__code__, kinematics.fk.__globals__)
    for function in (
        lambda: ARM.fk([0.1, 0.2]),
        lambda: alias(ARM, [0.1, 0.2]),
        lambda: copy(ARM, [0.1, 0.2]),
        lambda: getattr(ARM, "f" + "k")([0.1, 0.2]),  # a name built at run time
    ):
        result, called = outcome(function)
        assert isinstance(result, forbidden.ForbiddenCall)
        assert called and called[0] in FK
        assert str(result).startswith("this exercise asks you to write it yourself")


def test_a_call_caught_by_the_learner_is_still_recorded():
    def hides_it():
        try:
            return ARM.fk([0.1, 0.2])
        except Exception:
            return "caught"

    result, called = outcome(hides_it)
    assert result == "caught" and called == ["twolink.arm.TwoLinkArm.fk"]


def test_a_call_in_a_thread_is_stopped_too():
    seen = []

    def in_a_thread():
        def run():
            try:
                kinematics.fk(ARM, [0.0, 0.0])
                seen.append("ran")
            except forbidden.ForbiddenCall:
                seen.append("stopped")

        thread = threading.Thread(target=run)
        thread.start()
        thread.join(10)

    _, called = outcome(in_a_thread)
    assert seen == ["stopped"] and called == ["twolink.kinematics.fk"]


def test_other_calls_run_and_the_profile_hooks_are_put_back():
    def mine(frame, event, argument):
        return None

    sys.setprofile(mine)
    try:
        result, called = outcome(lambda: ARM.jacobian([0.1, 0.2]))
        assert sys.getprofile() is mine
    finally:
        sys.setprofile(None)
    assert called == [] and np.shape(result) == (2, 2)
    assert threading.getprofile() is None


def test_nothing_forbidden_costs_nothing():
    with forbidden.unavailable(()) as called:
        assert sys.getprofile() is None
        ARM.fk([0.0, 0.0])
    assert called == []


def test_a_module_function_and_a_class_are_named_as_a_learner_writes_them():
    assert (
        forbidden.reason("twolink.workspace.is_reachable")
        == "this exercise asks you to write it yourself: workspace.is_reachable is the package's answer"
    )
    assert (
        forbidden.shown_name("twolink.arm.TwoLinkArm.joint_rates") == "arm.joint_rates"
    )
    result, called = outcome(
        lambda: workspace.is_reachable(ARM, [0.5, 0.5]),
        ("twolink.workspace.is_reachable",),
    )
    assert called == ["twolink.workspace.is_reachable"]


@pytest.mark.parametrize(
    "path", ["twolink.kinematics.no_such_function", "no_such_package.f", "twolink"]
)
def test_a_path_that_names_no_callable_is_refused_naming_it(path):
    with pytest.raises(ValueError, match=f"forbidden call {path!r}: no such callable"):
        with forbidden.unavailable([path]):
            pass
