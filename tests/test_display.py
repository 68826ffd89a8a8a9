"""twolink.display: Markdown tables, angles in degrees, refusals printed instead of tracebacks."""

import inspect
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from twolink import SingularityError, UnreachableError, arms, display, ik
from twolink.errors import InputTypeError

ANGLES = re.compile(r"\((-?\d+(?:\.\d+)?)°, (-?\d+(?:\.\d+)?)°\)")


@pytest.mark.parametrize("name", display.__all__)
def test_every_public_name_is_fully_annotated(name):
    item = getattr(display, name)
    if inspect.isclass(item):
        return
    signature = inspect.signature(item)
    assert all(p.annotation is not inspect.Parameter.empty for p in signature.parameters.values())
    assert signature.return_annotation is not inspect.Signature.empty


# ------------------------------------------------------------------ angles_deg


@given(
    q=st.tuples(st.floats(-10.0, 10.0), st.floats(-10.0, 10.0)),
    digits=st.integers(0, 6),
)
def test_angles_deg_reads_back_to_the_angles_within_its_rounding(q, digits):
    text = display.angles_deg(q, digits=digits)
    match = ANGLES.fullmatch(text)
    assert match, text
    shown = np.array([float(group) for group in match.groups()])
    assert np.all(np.abs(shown - np.degrees(q)) <= 0.5 * 10.0**-digits * (1 + 1e-9) + 1e-9)
    for group in match.groups():
        assert len(group.partition(".")[2]) == digits
        assert not re.fullmatch(r"-0(\.0*)?", group), f"negative zero shown in {text}"


def test_angles_deg_examples():
    assert display.angles_deg(np.radians([30.0, 45.0])) == "(30.0°, 45.0°)"
    assert display.angles_deg([np.pi / 4, 0.0], digits=0) == "(45°, 0°)"
    assert display.angles_deg(np.radians([-0.04, 179.96])) == "(0.0°, 180.0°)"


@pytest.mark.parametrize(
    "q, digits, error, message",
    [
        ([[0.1, 0.2]], 1, ValueError, r"q must be one configuration of shape \(2,\) \(radians\)"),
        ([0.1, np.nan], 1, ValueError, "q must be finite"),
        ([0.1, 0.2], -1, ValueError, r"digits \(decimals shown\) must be an integer >= 0"),
        ([0.1, 0.2], 1.5, ValueError, r"digits \(decimals shown\) must be an integer >= 0"),
        (["a", 0.2], 1, InputTypeError, "q must be"),
    ],
)
def test_angles_deg_refuses_bad_input(q, digits, error, message):
    with pytest.raises(error, match=message):
        display.angles_deg(q, digits=digits)


# ------------------------------------------------------------------ print_error


def test_print_error_prints_a_refusal_with_its_prefix_and_keeps_it(capsys):
    with display.print_error("twolink: ") as caught:
        ik.closed_form(arms.two_metre, [5.0, 0.0])
    printed = capsys.readouterr().out
    assert isinstance(caught.error, UnreachableError)
    assert printed == f"twolink: UnreachableError: {caught.error}\n"


def test_print_error_catches_singularities_by_default(capsys):
    with display.print_error() as caught:
        arms.two_metre.joint_rates([0.3, 0.0], [0.0, 1.0])
    assert isinstance(caught.error, SingularityError)
    assert capsys.readouterr().out.startswith("SingularityError: ")


def test_print_error_stops_the_block_at_the_error(capsys):
    reached = []
    with display.print_error():
        ik.closed_form(arms.two_metre, [5.0, 0.0])
        reached.append("after")
    assert reached == []


def test_print_error_prints_nothing_when_nothing_is_refused(capsys):
    with display.print_error("never: ") as caught:
        q = ik.closed_form(arms.two_metre, [3.0, 1.0]).q
    assert caught.error is None and capsys.readouterr().out == ""
    assert np.allclose(arms.two_metre.fk(q), [3.0, 1.0])


def test_print_error_lets_other_errors_through(capsys):
    with pytest.raises(ValueError, match="must have shape"):
        with display.print_error():
            ik.closed_form(arms.two_metre, [1.0, 2.0, 3.0])
    with pytest.raises(ZeroDivisionError):
        with display.print_error(errors=(ValueError,)):
            1 / 0
    assert capsys.readouterr().out == ""


def test_print_error_catches_what_it_is_told_to(capsys):
    with display.print_error(errors=(ValueError,)) as caught:
        float("not a number")
    assert type(caught.error) is ValueError
    assert capsys.readouterr().out == f"ValueError: {caught.error}\n"


@pytest.mark.parametrize(
    "arguments, message",
    [
        ({"prefix": 3}, "prefix must be a string"),
        ({"errors": ValueError}, "errors must be a non-empty tuple of exception classes"),
        ({"errors": ()}, "errors must be a non-empty tuple of exception classes"),
        ({"errors": (ValueError, "KeyError")}, "errors must be a non-empty tuple of exception classes"),
    ],
)
def test_print_error_refuses_bad_arguments(arguments, message):
    with pytest.raises(InputTypeError, match=message):
        with display.print_error(**arguments):
            pass


# ------------------------------------------------------------------ markdown_table


def test_markdown_table_refuses_rows_and_formats_of_the_wrong_length():
    with pytest.raises(ValueError, match="formats has 1 entries for 2 columns"):
        display.markdown_table(["x", "y"], [[1, 2]], [".1f"])
    with pytest.raises(ValueError, match="has 3 cells for 2 columns"):
        display.markdown_table(["x", "y"], [[1, 2, 3]])
