"""twolink_course.runmode: the grading switch, read from TWOLINK_GRADING at each call.

What each heavy function does with the switch on is tested with it:
tests/course/test_plot.py (animation_html), tests/course/test_explorer.py, tests/course/test_inline.py
(figures) and tests/course/test_timing.py (median_time); a chapter whose
self-checks print the same lines with the switch on as off, in
tests/infrastructure/test_runmode_chapter.py.
"""

import pytest

from twolink.errors import InputTypeError
from twolink_course import runmode


@pytest.mark.parametrize(
    ("value", "expected"), [("1", True), ("0", False), ("", False), (None, False)]
)
def test_the_switch_is_read_from_the_environment_at_each_call(
    monkeypatch, value, expected
):
    monkeypatch.setenv(runmode.VARIABLE, "1" if not expected else "0")
    assert runmode.grading() is (not expected)  # read now, not at import
    if value is None:
        monkeypatch.delenv(runmode.VARIABLE)
    else:
        monkeypatch.setenv(runmode.VARIABLE, value)
    assert runmode.grading() is expected


@pytest.mark.parametrize(
    "value", ["yes", "true", "on", "2", " 1", "1 ", "01", "\n", "TRUE", "1\n0"]
)
def test_any_other_value_is_refused_naming_the_variable_and_its_values(
    monkeypatch, value
):
    monkeypatch.setenv(runmode.VARIABLE, value)
    with pytest.raises(ValueError) as caught:
        runmode.grading()
    message = str(caught.value)
    assert message.startswith("TWOLINK_GRADING must be")
    assert '"1"' in message and '"0"' in message and "unset" in message
    assert repr(value) in message


def test_a_long_value_is_quoted_in_part(monkeypatch):
    monkeypatch.setenv(runmode.VARIABLE, "x" * 5000)
    with pytest.raises(ValueError, match=r"got 'x{40}\.\.\.'$"):
        runmode.grading()


def test_the_skipped_note_names_what_and_the_switch():
    note = runmode.skipped_note("animation")
    assert note.startswith("animation skipped while grading")
    assert "TWOLINK_GRADING=1" in note
    for junk in ("", "  ", None, 3):
        with pytest.raises(InputTypeError, match="what must be a non-empty str"):
            runmode.skipped_note(junk)
