"""One vocabulary across the package: every public name means one thing.

The tests walk the public API (every public module, its ``__all__``, public
classes and their methods) so that a function added later is checked too.
"""

import dataclasses
import importlib
import inspect
import pkgutil

import numpy as np
import pytest

import twolink
import twolink.engine
import twolink.statics
import twolink.trajectory
import twolink.workspace
from twolink import arms
from twolink.conventions import ELBOW_WORDS


def _public_modules():
    modules = [twolink]
    for info in pkgutil.walk_packages(twolink.__path__, "twolink."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        try:
            modules.append(importlib.import_module(info.name))
        except ImportError:  # a course-only module whose extra is missing
            continue
    return modules


def _public_callables():
    """``{qualified name: callable}`` for every public function, class and method."""
    found = {}
    for module in _public_modules():
        names = getattr(
            module,
            "__all__",
            [name for name in vars(module) if not name.startswith("_")],
        )
        for name in names:
            value = getattr(module, name, None)
            if inspect.isfunction(value) and value.__module__.startswith("twolink"):
                found[f"{value.__module__}.{value.__qualname__}"] = value
            elif inspect.isclass(value) and value.__module__.startswith("twolink"):
                found[f"{value.__module__}.{value.__qualname__}"] = value
                for attribute, member in vars(value).items():
                    if attribute.startswith("_") and attribute not in (
                        "__init__",
                        "__call__",
                    ):
                        continue
                    function = (
                        member.__func__
                        if isinstance(member, (classmethod, staticmethod))
                        else member
                    )
                    if inspect.isfunction(function):
                        found[
                            f"{value.__module__}.{value.__qualname__}.{attribute}"
                        ] = function
    return found


CALLABLES = _public_callables()


def _parameters(function):
    try:
        return inspect.signature(function).parameters
    except (TypeError, ValueError):
        return {}


def test_the_walk_finds_the_api():
    assert len(CALLABLES) > 150
    assert "twolink.ik.analytic.closed_form" in CALLABLES
    assert "twolink.arm.TwoLinkArm.fk" in CALLABLES


# ----------------------------------------------------------------------------- elbow

#: Every public callable with an ``elbow`` parameter, with a call that supplies the rest.
ELBOW_CALLS = {
    "twolink.ik.analytic.closed_form": lambda elbow: twolink.ik.closed_form(
        arms.ten, [10.0, 10.0], elbow=elbow
    ),
    "twolink.trajectory.ik_trajectory": lambda elbow: twolink.trajectory.ik_trajectory(
        arms.ten,
        twolink.trajectory.LinePath([12.0, 12.0], [13.0, 14.0], duration=1.0),
        n=5,
        elbow=elbow,
    ),
    "twolink.trajectory.resolved_rate_trajectory": lambda elbow: (
        twolink.trajectory.resolved_rate_trajectory(
            arms.ten,
            twolink.trajectory.LinePath([12.0, 12.0], [13.0, 14.0], duration=1.0),
            n=5,
            elbow=elbow,
        )
    ),
    "twolink.engine.wall_push": lambda elbow: twolink.engine.wall_push(
        arms.two_metre,
        twolink.statics.Wall([1.5, 0.0], [1.0, 0.0]),
        10.0,
        duration=0.05,
        elbow=elbow,
    ),
    "twolink.workspace.is_reachable": lambda elbow: twolink.workspace.is_reachable(
        arms.ten, [10.0, 10.0], elbow=elbow
    ),
    "twolink.workspace.boundary_arcs": lambda elbow: twolink.workspace.boundary_arcs(
        arms.ten, elbow=elbow
    ),
    "twolink.workspace.clearance": lambda elbow: twolink.workspace.clearance(
        arms.ten, [10.0, 10.0], elbow=elbow
    ),
    "twolink.workspace.largest_inscribed_circle": lambda elbow: (
        twolink.workspace.largest_inscribed_circle(arms.ten, starts=1, elbow=elbow)
    ),
    "twolink.workspace.BranchTable.reachable": lambda elbow: (
        twolink.workspace.BranchTable(arms.ten, [[10.0, 10.0]]).reachable(
            arms.ten, elbow=elbow
        )
    ),
}

#: Callables whose ``elbow`` is not a branch choice but a label of a result (documented).
ELBOW_LABELS = {
    "twolink.statics.WallContact",
    "twolink.statics.WallContact.__init__",
    "twolink.statics.WallContact.branch",
    "twolink.engine.WallPush",
    "twolink.engine.WallPush.__init__",
    "twolink.trajectory.JointTrajectory",
    "twolink.trajectory.JointTrajectory.__init__",
}


def _with_elbow():
    return sorted(
        name for name, function in CALLABLES.items() if "elbow" in _parameters(function)
    )


def test_every_elbow_parameter_is_known_here():
    """A new function with an ``elbow`` parameter must join ELBOW_CALLS (and so the tests below)."""
    validator = {"twolink.conventions.check_elbow"}  # the one check they all call
    assert set(_with_elbow()) - ELBOW_LABELS - validator == set(ELBOW_CALLS)


@pytest.mark.parametrize("name", sorted(ELBOW_CALLS))
def test_elbow_defaults_to_a_word_of_the_vocabulary(name):
    default = _parameters(CALLABLES[name])["elbow"].default
    assert default in ELBOW_WORDS


@pytest.mark.parametrize("name", sorted(ELBOW_CALLS))
@pytest.mark.parametrize("word", ["down", "up", "auto"])
def test_every_elbow_parameter_accepts_down_up_and_auto(name, word):
    ELBOW_CALLS[name](word)


@pytest.mark.parametrize("name", sorted(ELBOW_CALLS))
def test_both_is_given_a_meaning_or_refused_with_a_reason(name):
    try:
        ELBOW_CALLS[name]("both")
    except ValueError as error:
        message = str(error)
        assert (
            message.startswith("elbow must be one of")
            and "here; got 'both' (" in message
        ), message


@pytest.mark.parametrize("name", sorted(ELBOW_CALLS))
@pytest.mark.parametrize("word", ["elbow-up", "Down", None, 1])
def test_a_word_outside_the_vocabulary_is_refused_naming_the_words(name, word):
    with pytest.raises(ValueError, match="elbow must be one of"):
        ELBOW_CALLS[name](word)


def test_down_and_up_mean_the_same_branch_everywhere():
    """closed form's branches are the trajectory's and the workspace's: q2 >= 0 is down."""
    q_down = twolink.ik.closed_form(arms.ten, [12.0, 12.0], elbow="down").q
    q_up = twolink.ik.closed_form(arms.ten, [12.0, 12.0], elbow="up").q
    assert q_down[1] > 0 > q_up[1]
    path = twolink.trajectory.LinePath([12.0, 12.0], [13.0, 14.0], duration=1.0)
    for word, sign in (("down", 1.0), ("up", -1.0)):
        trajectory = twolink.trajectory.ik_trajectory(arms.ten, path, n=5, elbow=word)
        assert np.all(sign * trajectory.q[:, 1] > 0)


# ----------------------------------------------------------------------------- names

#: Parameter names retired for the one vocabulary, and what to say instead.
RETIRED = {
    "force": "force_by_tip (exerted by the tip) or force_on_tip (acting on the tip)",
    "center": "centre",
    "q_guess": "q0",
    "q_start": "q0",
    "q_init": "q0",
    "guess": "q0",
}


def test_no_public_parameter_uses_a_retired_name():
    offenders = [
        f"{name}({parameter}): say {RETIRED[parameter]}"
        for name, function in CALLABLES.items()
        for parameter in _parameters(function)
        if parameter in RETIRED
    ]
    assert not offenders, offenders


def test_no_public_attribute_or_name_is_spelled_center():
    offenders = []
    for module in _public_modules():
        offenders += [
            f"{module.__name__}.{name}"
            for name in vars(module)
            if "center" in name.lower()
        ]
    for name, value in CALLABLES.items():
        if inspect.isclass(value):
            fields = (
                [field.name for field in dataclasses.fields(value)]
                if dataclasses.is_dataclass(value)
                else []
            )
            offenders += [
                f"{name}.{attribute}"
                for attribute in list(vars(value)) + fields
                if "center" in attribute.lower()
            ]
        offenders += [
            f"{name}({parameter})"
            for parameter in _parameters(value)
            if "center" in parameter.lower()
        ]
    assert not offenders, offenders


def test_force_names_say_which_force():
    """Every public force parameter says whether the tip exerts it or feels it."""
    offenders = [
        f"{name}({parameter})"
        for name, function in CALLABLES.items()
        for parameter in _parameters(function)
        if "force" in parameter
        and parameter not in ("force_by_tip", "force_on_tip", "force_magnitude")
    ]
    assert not offenders, offenders


def test_ax_is_keyword_only_wherever_it_appears():
    offenders = [
        name
        for name, function in CALLABLES.items()
        if "ax" in _parameters(function)
        and _parameters(function)["ax"].kind is not inspect.Parameter.KEYWORD_ONLY
    ]
    assert not offenders, offenders


def test_ax_comes_first_among_the_keyword_only_parameters():
    offenders = []
    for name, function in CALLABLES.items():
        keyword_only = [
            p
            for p, v in _parameters(function).items()
            if v.kind is inspect.Parameter.KEYWORD_ONLY
        ]
        if "ax" in keyword_only and keyword_only[0] != "ax":
            offenders.append(f"{name}: {keyword_only}")
    assert not offenders, offenders


def test_the_limit_convention_is_named_as_such():
    arm = twolink.TwoLinkArm(1.0, 1.0)
    assert arm.limit_convention == "relative"
    assert not hasattr(arm, "limits")


# ----------------------------------------------------------------------------- IK results


@pytest.mark.parametrize(
    "solve",
    [
        lambda p: twolink.ik.closed_form(arms.ten, p),
        lambda p: twolink.ik.newton(arms.ten, p, q0=(0.5, 1.0)),
        lambda p: twolink.ik.minimize(arms.ten, p, q0=(0.5, 1.0)),
        lambda p: twolink.ik.brute_force(arms.ten, p),
    ],
    ids=["closed_form", "newton", "minimize", "brute_force"],
)
def test_every_ik_solver_returns_an_ikresult(solve):
    result = solve([10.0, 10.0])
    assert isinstance(result, twolink.ik.IKResult)
    assert result.q.shape == (2,) and bool(result.success)
    assert float(result.residual) == pytest.approx(
        float(np.hypot(*(arms.ten.fk(result.q) - [10.0, 10.0]))), abs=1e-15
    )
