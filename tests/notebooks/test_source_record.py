"""The course's source record (``notebooks/source_record.ipynb``) and what rests on it.

The record says, item by item (H1.1 to H4.6), what the four pieces of
coursework asked, computed, printed and got wrong; each item has a stable
anchor named after it (``#h1-4``).  These tests hold the record and the course
together:

- the record is a page of its own, Markdown only, linked from the start page
  and never taken for a chapter;
- every number the record gives is computed by ``twolink_course.sources`` (or
  is a constant of a formula it quotes) and asserted here, item by item: a
  number added to the record without a computation here fails;
- every link to the record, in the notebooks and in ``twolink_course/sources``,
  leads to an anchor that exists, and every casebook entry of the chapters
  that link the record names its items by links.
"""

import inspect
import json
import math
import pathlib
import re
import sys

import numpy as np
import pytest

from twolink import arms, ik
from twolink_course.sources import compsys726, mae6245, me639, osake

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import course_map  # noqa: E402
import outline  # noqa: E402

NOTEBOOKS = ROOT / "notebooks"
RECORD = NOTEBOOKS / "source_record.ipynb"
ANCHOR = re.compile(r'<a id="(h\d-\d+)"></a>')
#: A link to an item of the record: ``source_record.ipynb#h3-2``.
RECORD_LINK = re.compile(r"source_record\.ipynb#([\w-]+)")
#: The items section H of the course's source material has, per piece of coursework.
ITEMS = {1: 9, 2: 5, 3: 5, 4: 6}
#: The chapters whose casebooks link the record's items (the others name them in plain text).
LINKED_CHAPTERS = ("01", "02", "03", "04", "05", "06", "07")


def cells(path):
    return json.loads(path.read_text(encoding="utf-8"))["cells"]


def text(cell):
    return "".join(cell["source"])


def record_items():
    """``{anchor: the item's text after its heading}``."""
    found = {}
    for cell in cells(RECORD):
        match = ANCHOR.match(text(cell))
        if match:
            found[match[1]] = text(cell).split("\n", 3)[-1]
    return found


# --- the page -------------------------------------------------------------------------------------


def test_the_record_is_a_markdown_page_with_one_anchor_per_item():
    content = cells(RECORD)
    assert all(cell["cell_type"] == "markdown" for cell in content)
    assert text(content[0]).startswith("# The source record")
    anchors = [match for cell in content for match in ANCHOR.findall(text(cell))]
    expected = [
        f"h{piece}-{number}"
        for piece, count in ITEMS.items()
        for number in range(1, count + 1)
    ]
    assert anchors == expected
    for cell in content:
        match = ANCHOR.match(text(cell))
        if match:  # the heading names the item: "### H3.2. ..."
            label = match[1].upper().replace("-", ".")
            assert text(cell).split("\n")[2].startswith(f"### {label}. "), label


def test_the_record_is_no_chapter_and_the_start_page_links_it():
    assert RECORD not in course_map.chapters(NOTEBOOKS)
    assert RECORD not in outline.chapters()
    start = "\n".join(text(cell) for cell in cells(NOTEBOOKS / course_map.START_PAGE))
    assert "](source_record.ipynb)" in start
    assert "](00_start_here.ipynb)" in text(cells(RECORD)[0])


def test_the_record_cites_no_file_outside_the_repository():
    record = "\n".join(text(cell) for cell in cells(RECORD))
    assert "COURSE.md" not in record and "../shared" not in record


# --- every number of the record, computed by the sources ---------------------------------------------

#: Numbers as they stand in the record: a sign (also "+"), digits, thousands commas, decimals,
#: an exponent; not a digit that is part of a name (a1, q_2, H1.4, x^2, 3x3, h3-2).
NUMBER = re.compile(
    r"(?<![\w.^√/\\{#-])[-−+]?\d+(?:,\d{3})*(?:\.\d+)?(?:e-?\d+)?(?![\w°]?\w)"
)


def numbers_in(item_text):
    """The numbers an item gives, after the words that only name things are taken out."""
    named = re.sub(r"\]\([^)]*\)", "]", item_text)  # link targets
    named = re.sub(r"\bH\d\.\d+\b", "H", named)  # item labels
    named = re.sub(r"\b(?:MAE 6245|ME 639|COMPSYS726)\b", "X", named)
    named = re.sub(
        r"\b(?:chapters?|columns?|rows?|links?|joints?|motors?) \d+(?: (?:to|and) \d+)?",
        "Y",
        named,
    )
    return set(NUMBER.findall(named))


def matches(shown, value):
    """Whether ``value`` shows as the record's ``shown`` (to the digits ``shown`` has)."""
    plain = shown.replace(",", "").replace("−", "-").lstrip("+")
    if "e" in plain:
        mantissa = plain.split("e")[0]
        digits = len(mantissa.replace("-", "").replace(".", "").lstrip("0"))
        return float(f"{value:.{digits - 1}e}") == float(plain)
    decimals = len(plain.split(".")[1]) if "." in plain else 0
    return round(float(value), decimals) == float(plain)


def _mae6245():
    roots = mae6245.x_equation_roots(mae6245.TARGET, 0.0)
    matlab, numpy_run = (
        mae6245.numerical_ik(acos=acos) for acos in ("matlab", "numpy")
    )
    phi = mae6245.circle_angles()
    theta1_grid, theta2_grid = mae6245.workspace_grid()
    (q1_low, q1_high), (q2_low, q2_high) = mae6245.TASK_RANGES_DEG
    return {
        "h1-1": {
            "10": mae6245.A1,
            "0": np.degrees(np.arccos(min(mae6245.closed_form_cosine(), 1.0))),
            "-0.7854": roots[1],
            "14.14": mae6245.fk_check(roots[1], 0.0)[0],
            "-14.14": mae6245.fk_check(roots[1], 0.0)[1],
        },
        "h1-2": {
            "0.4": mae6245.Q1_START,
            "0.7854": matlab.q[0],
            "0": matlab.q[1],
            "0.785398": matlab.q[0],
            "18": matlab.evaluations,
            "1034.6": numpy_run.q[0],
        },
        "h1-3": {
            "0.7845": mae6245.FK_CHECK_THETA1,
            "0.7854": roots[0],
            "14.1548": mae6245.fk_check()[0],
            "14.1294": mae6245.fk_check()[1],
        },
        "h1-4": {
            "12.5": mae6245.CIRCLE_CENTRE[0],
            "2": mae6245.CIRCLE_RADIUS,
            "0": phi[0],
            "0.5": mae6245.CIRCLE_STEP,
            "13": len(phi),
            "6": phi[-1],
            "0.283": 2 * np.pi - phi[-1],
            "10": mae6245.TASK_CIRCLE_POINTS[0],
            "20": mae6245.TASK_CIRCLE_POINTS[1],
        },
        "h1-5": {
            "0": q1_low,
            "90": max(q1_high, q2_high),
            "-90": q2_low,
            "0.1": mae6245.WORKSPACE_STEP,
        },
        "h1-7": {
            "1.0000000000000002": mae6245.closed_form_cosine(),
            "200.00000000000003": float(mae6245.TARGET[0]) ** 2,
            "0.000000021": abs(
                complex(np.emath.arccos(mae6245.closed_form_cosine())).imag
            ),
            "-0.7854": roots[1],
        },
        "h1-8": {
            "0": theta1_grid[0],
            "0.1": mae6245.WORKSPACE_STEP,
            "1.5": theta1_grid[-1],
            "1.529": theta2_grid[-1],
            "1.5708": np.pi / 2,
        },
        "h1-9": {
            "0.7845": mae6245.PART_E_ANGLES[0],
            "-0.7845": mae6245.PART_E_ANGLES[1],
            "0.7854": roots[0],
        },
    }


def _compsys726():
    q_source = compsys726.ik_as_written(compsys726.X_LINE)
    q_right = np.degrees(
        ik.closed_form(
            arms.ten.__class__(l1=compsys726.A1, l2=compsys726.A2),
            np.stack(
                [compsys726.X_LINE, np.full_like(compsys726.X_LINE, compsys726.Y_LINE)],
                axis=-1,
            ),
            elbow="down",
        ).q
    )
    printed = compsys726.PRINTED_ANGLES_DEG
    at_printed = compsys726.rate_as_printed(printed)
    at_unrounded = compsys726.rate_as_printed(q_source)
    return {
        "h2-3": {
            "50": compsys726.Y_LINE,
            "10": compsys726.X_LINE[0],
            "20": compsys726.X_LINE[1],
            "100": compsys726.X_LINE[-1],
            "49": q_source[0, 0],
            "172": q_source[0, 1],
            "-3.3": compsys726.truncated(q_source[-1, 0], 1),
            "90": q_source[-1, 1],
            "70.74": q_right[0, 0],
            "171.89": q_right[0, 1],
        },
        "h2-4": {
            "-10": compsys726.RATE_FACTOR,
            "10": len(compsys726.X_LINE),
            "49": printed[0, 0],
            "172": printed[0, 1],
            "61": printed[1, 0],
            "164": printed[1, 1],
            "0.6132": at_printed[0],
            "0.6066": at_unrounded[0],
            "-3.3": printed[-1, 0],
            "-3.38": q_source[-1, 0],
            "85.64": q_source[2, 0],
            "86": printed[2, 0],
        },
        "h2-5": {
            "49.09": compsys726.truncated(q_source[0, 0], 2),
            "171.89": q_source[0, 1],
            "172": q_source[0, 1],
            "49": printed[0, 0],
            "-3.3": compsys726.truncated(q_source[-1, 0], 1),
            "-3.38": q_source[-1, 0],
            "49.0965": q_source[0, 0],
        },
    }


def _osake():
    q_45, q_60 = np.radians([30.0, 45.0]), np.radians([30.0, 60.0])
    printed = osake.jacobian_as_printed(q_45)[:2]
    right = 100 * arms.osake.geometric_jacobian(q_45)[:2]
    right_tip = 100 * arms.osake.fk(q_45)
    third = osake.d02_tip_as_written(q_45)
    defaults = inspect.signature(osake.velocity_program_speed).parameters
    as_run = osake.velocity_program_speed()
    t, delta_t = defaults["t"].default, defaults["step"].default
    q_meant = np.radians([3.0 * t, 60.0])
    # the program is 3 rad/s times the tip's radius at (3 t, 60) read as radians, in cm
    assert math.isclose(
        as_run, 3.0 * 100 * np.linalg.norm(arms.osake.fk([3 * t, 60.0]))
    )
    return {
        "h3-2": {
            "30": np.degrees(q_45[0]),
            "45": np.degrees(q_45[1]),
            "-9.07": printed[0, 0],
            "-4.07": printed[0, 1],
            "15.70": printed[1, 0],
            "7.04": printed[1, 1],
            "-16.11": right[0, 0],
            "-11.11": right[0, 1],
            "11.64": right[1, 0],
            "2.98": right[1, 1],
            "0": np.linalg.det(osake.jacobian_as_printed(q_60)[:2]),
            "60": np.degrees(q_60[1]),
            "99.6": osake.L1_CM * osake.L2_CM * np.sin(q_60[1]),
        },
        "h3-3": {
            "11.5": osake.L2_CM,
            "11": osake.cpp_read_int("11.5"),
            "5": 10
            * np.linalg.norm(
                osake.cpp_fk_tip(q_45, drop_offset=False)
                - osake.cpp_fk_tip(q_45, int_lengths=False, drop_offset=False)
            ),
            "0": osake.cpp_fk_tip(q_45)[2],
        },
        "h3-4": {
            "3": np.degrees(q_meant[0]) / t,
            "60": np.degrees(q_meant[1]),
            "10.0": defaults["l1"].default,
            "11.5": defaults["l2"].default,
            "2": t,
            "1e-6": delta_t,
            "10.8975": as_run,
            "0.9757": 100
            * np.linalg.norm(arms.osake.tip_velocity(q_meant, np.radians([3.0, 0.0]))),
        },
        "h3-5": {
            "12.04": third[0],
            "12.73": third[1],
            "30": 30.0,
            "45": 45.0,
            "11.64": right_tip[0],
            "16.11": right_tip[1],
        },
    }


def _me639():
    wall = inspect.signature(me639.source_wall_search).parameters
    hit, typo = (
        me639.source_wall_search(reading=reading) for reading in ("cos", "sin")
    )
    spring = me639.source_spring_torques([[3.0, 0.0], [3.0, 1.0], [3.0, 2.0]])[:, 0]
    decimals = 4  # round(q2_abs, 4) == round(pi/4, 4), as the search tests
    half_unit_deg = np.degrees(0.5 * 10.0**-decimals)
    plot_range = me639.WORKSPACE_PLOT_DEGREES
    return {
        "h4-1": {"0": np.arccos(1.0)},  # theta >= 0: acos's smallest value
        "h4-2": {
            "100,000": wall["n_points"].default,
            "4": 4.0,
            "0": 0.0,
            "0.003": half_unit_deg,
            "3.2872": hit.p_contact[0],
            "0.7128": hit.p_contact[1],
            "910.18": hit.torques[0],
            "0.03": hit.torques[1],
            "3.4116": typo.p_contact[0],
            "0.5884": typo.p_contact[1],
            "867.11": typo.torques[0],
            "3.345": typo.p_tip_fk[0],
            "0.892": typo.p_tip_fk[1],
        },
        "h4-3": {
            "+2381.2": spring[0],
            "+2323.8": spring[1],
            "+1873.4994": spring[2],
            "0": 0.0,
            "1": 1.0,
            "2": 2.0,
            "+2381": spring[0],
            "+2324": spring[1],
            "+1873": spring[2],
            "1873": spring[2],
        },
        "h4-5": {
            "35": plot_range.start,
            "145": plot_range.stop,
            "1": plot_range.step,
        },
    }


#: Numbers that belong to a formula or a quotation the item gives, not to a result, and why.
FORMULA_NUMBERS = {
    "h1-2": {"-1": "acos's real domain [-1, 1]", "1": "acos's real domain [-1, 1]"},
    "h1-6": {"1": "the constant fmincon minimises", "0": "the constraint f(q1) = 0"},
    "h1-7": {"2": "the 2 of 2 a1 a2", "0": "theta2 = 0, as shown"},
    "h2-2": {"0": "xdot = 0, ydot = 0: the motions' definitions"},
    "h2-3": {"0": "x < 0, where atand(y/x) goes wrong"},
    "h3-1": {"1": "a rotation's determinant"},
    "h3-2": {"0": "a singular determinant"},  # also computed, above
    "h4-1": {"2": "the 2 of 2 l1 l2"},
    "h4-3": {"1": "t_1 and link 1", "2": "t_2 and link 2"},
}


#: Numbers checked by a test of their own below (a bound, or a comparison the repository
#: can only check for consistency), by the test's name.
CHECKED_APART = {
    "h1-2": {"1e-7": "test_the_round_off_numbers_are_what_the_record_says_they_are"},
    "h2-4": {
        "0.16": "test_the_rate_column_comparisons_are_consistent_with_the_reproductions",
        "1.24": "test_the_rate_column_comparisons_are_consistent_with_the_reproductions",
        "0.08": "test_the_rate_column_comparisons_are_consistent_with_the_reproductions",
    },
    "h4-3": {"1874": "test_the_spring_torque_rounds_to_1873_not_1874"},
}


def computed_numbers():
    found = {}
    for part in (_mae6245(), _compsys726(), _osake(), _me639()):
        found.update(part)
    return found


COMPUTED = computed_numbers()


@pytest.mark.parametrize("anchor", list(record_items()))
def test_every_number_of_an_item_is_computed_by_the_sources(anchor):
    item_text = record_items()[anchor]
    computed = COMPUTED.get(anchor, {})
    formula = FORMULA_NUMBERS.get(anchor, {})
    apart = CHECKED_APART.get(anchor, {})
    unaccounted = numbers_in(item_text) - set(computed) - set(formula) - set(apart)
    assert not unaccounted, (
        f"{anchor}: numbers with no computation in this test: {sorted(unaccounted)}"
    )
    wrong = {
        shown: value
        for shown, value in computed.items()
        if shown in numbers_in(item_text) and not matches(shown, value)
    }
    assert not wrong, f"{anchor}: the record's numbers against the sources: {wrong}"
    missing = set(computed) - numbers_in(item_text)
    assert not missing, f"{anchor}: computed here but not in the record: {missing}"


def test_the_round_off_numbers_are_what_the_record_says_they_are():
    # H1.2: "a q2 below 1e-7" (about 2e-8); H1.7: the exact IEEE numbers
    q2 = mae6245.numerical_ik(acos="matlab").q[1]
    assert abs(q2) < 1e-7
    assert repr(mae6245.closed_form_cosine()) == "1.0000000000000002"
    assert repr(float(mae6245.TARGET[0]) ** 2) == "200.00000000000003"
    # H1.2: the numpy run ends with q2 = nan; H3.2: singular at every pose
    assert np.isnan(mae6245.numerical_ik(acos="numpy").q[1])
    q = np.random.default_rng(42).uniform(-np.pi, np.pi, size=(100, 2))
    assert np.all(
        np.abs(np.linalg.det(osake.jacobian_as_printed(q)[..., :2, :])) < 1e-9
    )


def test_the_rate_column_comparisons_are_consistent_with_the_reproductions():
    # H2.4 compares the printed rate column (not in the repository beyond its first
    # entry) with both reproductions: within 0.16 % at the printed angles, up to 1.24 %
    # off at the unrounded ones. The two reproductions must then differ by 1.24 % +- 0.16 %
    # at most, and by at least 1.24 % - 0.16 % somewhere.
    at_printed = compsys726.rate_as_printed(compsys726.PRINTED_ANGLES_DEG)
    at_unrounded = compsys726.rate_as_printed(
        compsys726.ik_as_written(compsys726.X_LINE)
    )
    gap = 100 * np.abs(at_unrounded - at_printed) / np.abs(at_printed)
    assert 1.24 - 0.16 <= gap.max() <= 1.24 + 0.16
    item = record_items()["h2-4"]
    assert "0.16 %" in item and "1.24 %" in item
    # and "within 0.08 deg" is false for the whole-degree entries
    q_source = compsys726.ik_as_written(compsys726.X_LINE)
    whole = np.abs(compsys726.PRINTED_ANGLES_DEG[:-1] - q_source[:-1])
    assert whole.max() > 0.08


def test_the_spring_torque_rounds_to_1873_not_1874():
    third = me639.source_spring_torques([[3.0, 2.0]])[0, 0]
    assert round(third, 4) == 1873.4994 and round(third) == 1873
    assert round(round(third, 1)) == 1874  # only a double rounding gives 1874
    assert "not\n1874" in record_items()["h4-3"] or "not 1874" in record_items()["h4-3"]


# --- links to the record ---------------------------------------------------------------------------


def files_that_cite_the_record():
    notebooks = sorted(NOTEBOOKS.glob("*.ipynb"))
    modules = sorted((ROOT / "twolink_course" / "sources").glob("*.py"))
    return [*notebooks, *modules]


@pytest.mark.parametrize(
    "path", files_that_cite_the_record(), ids=lambda path: path.name
)
def test_every_link_to_the_record_finds_its_anchor(path):
    content = path.read_text(encoding="utf-8")
    if path.suffix == ".ipynb":
        content = "\n".join(text(cell) for cell in cells(path))
    anchors = set(record_items())
    broken = sorted(set(RECORD_LINK.findall(content)) - anchors)
    assert not broken, (
        f"{path.name}: links to record anchors that do not exist: {broken}"
    )
    # tests/course/test_sources_me639.py checks its own citations
    if path.name != "me639.py":
        assert "COURSE.md" not in content, (
            f"{path.name} cites a file outside the repository"
        )


@pytest.mark.parametrize(
    "path", sorted(NOTEBOOKS.glob("*.ipynb")), ids=lambda path: path.name
)
def test_links_to_the_record_are_in_markdown_cells_which_the_site_rewrites(path):
    # The static site turns `source_record.ipynb#h2-4` into `source_record.html#h2-4`
    # in Markdown cells; a link written by a code cell would lead to a missing page.
    in_code = [
        index
        for index, cell in enumerate(cells(path))
        if cell["cell_type"] == "code" and RECORD_LINK.search(text(cell))
    ]
    assert not in_code, (
        f"{path.name}: code cells {in_code} write links to the source record; "
        "put the link in the Markdown cell beside them"
    )


@pytest.mark.parametrize("number", LINKED_CHAPTERS)
def test_each_casebook_entry_links_the_items_it_names(number):
    (path,) = [path for path in outline.chapters() if path.name.startswith(number)]
    chapter = outline.outline(path)
    anchors = set(record_items())
    for entry in chapter.entries():
        body = "\n".join(
            text(cell)
            for cell in chapter.cells[entry.heading.cell : entry.end]
            if cell["cell_type"] == "markdown"
        )
        (line,) = [line for line in body.splitlines() if "Source record:" in line]
        named = re.findall(r"\[(H\d\.\d+)\]\(source_record\.ipynb#(h\d-\d+)\)", line)
        assert named, f"{path.name}, {entry.heading.text!r}: {line!r} links no item"
        for label, anchor in named:
            assert anchor in anchors and label.lower().replace(".", "-") == anchor
        plain = re.sub(r"\[H\d\.\d+\]\([^)]*\)", "", line)
        assert not re.search(r"\bH\d\.\d+\b", plain), (
            f"{path.name}: an item named without its link: {line!r}"
        )


def test_the_sources_modules_cite_their_items_by_anchor():
    for module, piece in ((mae6245, 1), (compsys726, 2), (osake, 3)):
        source = inspect.getsource(module)
        cited = set(RECORD_LINK.findall(source)) | {
            f"h{piece}-{n}" for n in re.findall(rf"``#h{piece}-(\d+)``", source)
        }
        assert cited, f"{module.__name__} cites no item of the record"
        assert cited <= set(record_items()), cited
