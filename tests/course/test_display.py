"""twolink_course.display: Markdown tables, angles in degrees, refusals printed instead of tracebacks."""

import inspect
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from twolink import SingularityError, UnreachableError, arms, ik
from twolink.errors import InputTypeError
from twolink_course import display

ANGLES = re.compile(r"\((-?\d+(?:\.\d+)?)°, (-?\d+(?:\.\d+)?)°\)")


@pytest.mark.parametrize("name", display.__all__)
def test_every_public_name_is_fully_annotated(name):
    item = getattr(display, name)
    if inspect.isclass(item):
        return
    signature = inspect.signature(item)
    assert all(
        p.annotation is not inspect.Parameter.empty
        for p in signature.parameters.values()
    )
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
    assert np.all(
        np.abs(shown - np.degrees(q)) <= 0.5 * 10.0**-digits * (1 + 1e-9) + 1e-9
    )
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
        (
            [[0.1, 0.2]],
            1,
            ValueError,
            r"q must be one configuration of shape \(2,\) \(radians\)",
        ),
        ([0.1, np.nan], 1, ValueError, "q must be finite"),
        (
            [0.1, 0.2],
            -1,
            ValueError,
            r"digits \(decimals shown\) must be an integer >= 0",
        ),
        (
            [0.1, 0.2],
            1.5,
            ValueError,
            r"digits \(decimals shown\) must be an integer >= 0",
        ),
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
            _ = 1 / 0
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
        (
            {"errors": ValueError},
            "errors must be a non-empty tuple of exception classes",
        ),
        ({"errors": ()}, "errors must be a non-empty tuple of exception classes"),
        (
            {"errors": (ValueError, "KeyError")},
            "errors must be a non-empty tuple of exception classes",
        ),
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


# ------------------------------------------------------------------ numbers that read the same on every machine

BOUND_TEXT = re.compile(r"(below|at most) (\S+)(?: (.+))?")


@given(
    value=st.floats(-1e3, 1e3, allow_nan=False),
    exponent=st.integers(-16, 3),
    unit=st.sampled_from(["", "m", "rad", "N m"]),
)
def test_below_states_a_true_bound_or_refuses(value, exponent, unit):
    bound = 10.0**exponent
    if abs(value) < bound:
        text = display.below(value, bound, unit)
        kind, shown, shown_unit = BOUND_TEXT.fullmatch(text).groups()
        assert kind == "below" and float(shown) == pytest.approx(bound, rel=1e-12)
        assert (shown_unit or "") == unit
        assert (
            "e-0" not in text and "e+" not in text
        )  # plain exponents: 1e-5, not 1e-05
    else:
        with pytest.raises(display.BoundError, match="not below the stated bound"):
            display.below(value, bound, unit)


@given(noise=st.floats(0.0, 1e-13), sign=st.sampled_from([-1.0, 1.0]))
def test_below_reads_the_same_for_any_round_off_under_the_bound(noise, sign):
    # The point of the helper: two machines whose round-off differs print one text.
    assert (
        display.below(sign * noise, 1e-12, "m")
        == display.below(2.2e-16, 1e-12, "m")
        == "below 1e-12 m"
    )


def test_below_checks_the_largest_entry_of_an_array():
    assert display.below([[1e-15, -3e-13], [0.0, 2e-14]], 1e-12) == "below 1e-12"
    with pytest.raises(display.BoundError, match="largest magnitude 0.002"):
        display.below([1e-15, -2e-3], 1e-3, "m")


def test_at_most_allows_equality_and_refuses_more():
    assert display.at_most(8, 8, "iterations") == "at most 8 iterations"
    assert display.at_most([0, 3, 7], 8) == "at most 8"
    with pytest.raises(
        display.BoundError, match="exceeds the stated bound 8 iterations"
    ):
        display.at_most(9, 8, "iterations")


@pytest.mark.parametrize("function", [display.below, display.at_most])
@pytest.mark.parametrize(
    "value, bound, error, message",
    [
        (float("nan"), 1.0, ValueError, "NaN or infinite"),
        ([1e-3, float("inf")], 1.0, ValueError, "NaN or infinite"),
        ([], 1.0, ValueError, "empty"),
        ("small", 1.0, ValueError, "value"),
        (1e-9, float("nan"), ValueError, "bound"),
        (1e-9, -1.0, ValueError, "bound"),
        (1e-9, "1e-6", ValueError, "bound"),
    ],
)
def test_bounds_refuse_what_cannot_be_bounded(function, value, bound, error, message):
    with pytest.raises(error, match=message):
        function(value, bound)


def test_below_refuses_a_zero_bound():
    with pytest.raises(ValueError, match="bound"):
        display.below(0.0, 0.0)


@pytest.mark.parametrize(
    "function", [display.below, display.at_most, display.rounded, display.significant]
)
def test_number_helpers_refuse_a_unit_that_is_not_text(function):
    with pytest.raises(InputTypeError, match="unit must be a string"):
        function(1e-20, 1, 3)


@given(
    value=st.floats(-1e6, 1e6, allow_nan=False),
    decimals=st.integers(0, 6),
    noise=st.floats(-1.0, 1.0),
)
def test_rounded_hides_noise_far_below_its_last_decimal(value, decimals, noise):
    text = display.rounded(value, decimals)
    assert float(text) == pytest.approx(
        round(value, decimals), abs=10.0**-decimals * 1e-6
    )
    assert not text.startswith("-0") or float(text) != 0.0  # never "-0.00"
    step = 10.0**-decimals
    # A perturbation a thousandth of a step changes the text only when the value sits that close to a rounding tie.
    nudged = display.rounded(value + noise * step * 1e-3, decimals)
    if abs(abs(value / step) % 1.0 - 0.5) > 2e-3 and abs(value) < 1e5:
        assert nudged == text


def test_rounded_examples_and_shapes():
    assert (
        display.rounded(500.5405, 1, "N")
        == display.rounded(500.5362, 1, "N")
        == "500.5 N"
    )
    assert display.rounded([1.2, -1e-17], 2, "m") == "(1.20, 0.00) m"
    assert display.rounded(-1e-17, 0) == "0"
    with pytest.raises(ValueError, match="one number or a vector"):
        display.rounded([[1.0]], 1)
    with pytest.raises(ValueError, match="NaN or infinite"):
        display.rounded(float("inf"), 1)
    with pytest.raises(ValueError, match="decimals"):
        display.rounded(1.0, -1)


@given(
    value=st.floats(-1e12, 1e12, allow_nan=False).filter(
        lambda v: v == 0 or abs(v) > 1e-12
    ),
    digits=st.integers(1, 8),
)
def test_significant_reads_back_within_its_digits(value, digits):
    text = display.significant(value, digits)
    assert "e+" not in text and "e-0" not in text and not text.endswith(".")
    assert float(text) == pytest.approx(
        value, rel=0.5 * 10.0 ** (1 - digits) * (1 + 1e-9), abs=1e-300
    )


def test_significant_examples():
    assert display.significant(0.013333333, 3, "m/s") == "0.0133 m/s"
    assert display.significant([25000.0, -0.5], 2) == "(2.5e4, -0.50)"
    assert display.significant(1.0, 3) == "1.00"
    assert display.significant(-0.0, 2) == "0.0"
    with pytest.raises(ValueError, match="digits"):
        display.significant(1.0, 0)


@pytest.mark.parametrize(
    "bound, shown",
    [
        (0.5, "0.5"),
        (0.01, "0.01"),
        (5e-3, "5e-3"),
        (1e-3, "1e-3"),
        (1e-4, "1e-4"),
        (2.5e-5, "2.5e-5"),
        (1e-12, "1e-12"),
        (1e6, "1e6"),
    ],
)
def test_every_small_bound_reads_in_one_style(bound, shown):
    assert display.below(0.0, bound) == f"below {shown}"


def test_the_degree_sign_follows_the_number_and_other_units_a_space():
    assert display.rounded(45.0, 1, "°") == "45.0°"
    assert display.at_most(7.4, 8, "°") == "at most 8°"
    assert display.rounded(45.0, 1, "deg") == "45.0 deg"
