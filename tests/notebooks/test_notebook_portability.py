"""Every number a chapter stores reads the same on every machine.

Strict nbval compares stored outputs exactly, so a stored digit of round-off
(which another CPU, BLAS kernel or OS prints differently) fails for someone.
`make portable` runs the chapters under emulated numeric environments; these
checks read the committed notebooks for what can be told without running
them: no hand-rolled scientific format of a number in code, timings never
compared, nothing machine-specific stored, and a sanitize file that masks only
what is truly random, each line saying why.
"""

import json
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOTEBOOK_DIR = ROOT / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
SANITIZE = ROOT / "tests" / "nbval_sanitize.cfg"

# f"{x:.1e}", f"{x:e}", f"{x:10.3E}"; "%.2e" % x; format(x, ".2e"); np.format_float_scientific.
SCIENTIFIC_FORMATS = [
    re.compile(r"\{[^{}]*:[<>^=+\- #0-9,_]*(?:\.\d+)?[eE]\}"),
    re.compile(r"%[-+ #0]*\d*(?:\.\d+)?[eE]\b"),
    re.compile(r"format\([^()]*,\s*[\"'][^\"']*[eE][\"']\s*\)"),
    re.compile(r"format_float_scientific"),
]
TIMING_CALLS = re.compile(
    r"perf_counter|process_time|\btimeit\b|time\.time\(|\btiming\.\w+\("
)
MACHINE_SPECIFIC = {
    "an absolute path": re.compile(
        r"(?<![\w.])(?:/home/|/root/|/tmp/|/work/|/Users/|/usr/|[A-Z]:\\\\)"
    ),
    "an object address": re.compile(r"\b0x[0-9a-fA-F]{6,}\b| object at "),
    "a python-control system counter": re.compile(r"\bsys\[\d+\]"),
    "a date": re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b"),
    "a process or kernel id": re.compile(r"\b(?:pid|kernel[_ ]id)\b", re.IGNORECASE),
}
# What nbval compares (it never compares images or widget views); video payloads are sanitized.
COMPARED = ("text/plain", "text/markdown", "text/html", "text/latex")
VIDEO_PAYLOAD = re.compile(r"data:video/mp4;base64,[A-Za-z0-9+/=\n]+")
# A number in e-notation at round-off size: it must be a stated bound ("below 1e-12"), not a measurement.
TINY_NUMBER = re.compile(r"(?<![\w.])\d(?:\.\d+)?[eE]-(?:0?[7-9]|[1-9]\d)\b")
# "below 1e-12", "tolerance 1e-8", or a bound word and then the bound's formula: "no more than `RTOL` x (a1 + a2) = 2e-9".
BOUND_WORDS = re.compile(
    r"(?:below|at most|less than|no more than|tolerance|tol|bound|under|within)(?:\W*|\b[^;|\n]{0,80}=\s*)$",
    re.IGNORECASE,
)
REFUSAL = re.compile(
    r"^.*\b(?:UnreachableError|SingularityError|ValueError|TypeError): .*$",
    re.MULTILINE,
)
# A number typed in the code (an input such as q2 = 1e-7, a tolerance) is exact, not a measurement.
LITERAL = re.compile(r"(?<![\w.])\d+(?:\.\d+)?[eE]-?\d+")


@pytest.fixture(params=NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def notebook(request):
    return request.param, json.loads(request.param.read_text(encoding="utf-8"))


def code_cells(content):
    return [
        (index, cell)
        for index, cell in enumerate(content["cells"])
        if cell["cell_type"] == "code"
    ]


def compared_texts(cell):
    """The stored texts strict nbval compares for one cell (none for a cell nbval ignores or skips).

    nbval reads the markers as a first-line comment (``# NBVAL_IGNORE_OUTPUT``) or as
    the cell's metadata tags (``nbval-ignore-output``), which a reader does not see.
    """
    first_line = ("".join(cell["source"]).lstrip().splitlines() or [""])[0]
    if "NBVAL_IGNORE_OUTPUT" in first_line or "NBVAL_SKIP" in first_line:
        return []
    if {"nbval-ignore-output", "nbval-skip"} & set(
        cell.get("metadata", {}).get("tags", [])
    ):
        return []
    texts = []
    for output in cell.get("outputs", []):
        if output["output_type"] == "stream":
            texts.append("".join(output["text"]))
        for mime, value in output.get("data", {}).items():
            if mime in COMPARED:
                texts.append(
                    VIDEO_PAYLOAD.sub(
                        "", "".join(value) if isinstance(value, list) else str(value)
                    )
                )
    return texts


def test_no_hand_rolled_scientific_format_in_code(notebook):
    path, content = notebook
    found = [
        f"cell {index}: {match.group(0)!r}"
        for index, cell in code_cells(content)
        for pattern in SCIENTIFIC_FORMATS
        for match in pattern.finditer("".join(cell["source"]))
    ]
    assert not found, (
        f"{path.name}: scientific formats in code ({'; '.join(found)}): show a round-off quantity as a bound "
        "(twolink_course.display.below) and a settled value with display.rounded / display.significant"
    )


def test_cells_that_time_things_are_never_compared(notebook):
    path, content = notebook
    compared = [
        f"cell {index}"
        for index, cell in code_cells(content)
        if TIMING_CALLS.search("".join(cell["source"])) and compared_texts(cell)
    ]
    assert not compared, (
        f"{path.name}: {', '.join(compared)} time something and store compared output: start the cell with "
        "the nbval-ignore-output tag and build any prose about the timings in that cell, from that run"
    )


def test_no_machine_specific_text_in_outputs(notebook):
    path, content = notebook
    found = [
        f"cell {index}: {what} ({match.group(0)!r})"
        for index, cell in enumerate(content["cells"])
        for text in compared_texts(cell)
        for what, pattern in MACHINE_SPECIFIC.items()
        for match in [pattern.search(text)]
        if match
    ]
    assert not found, f"{path.name}: machine-specific outputs: {'; '.join(found)}"


def test_round_off_sized_numbers_are_shown_as_bounds(notebook):
    path, content = notebook
    code = "\n".join("".join(cell["source"]) for _, cell in code_cells(content))
    inputs = {float(literal) for literal in LITERAL.findall(code)}
    found = []
    for index, cell in enumerate(content["cells"]):
        texts = (
            compared_texts(cell)
            if cell["cell_type"] == "code"
            else ["".join(cell["source"])]
        )
        for text in texts:
            # A refusal printed by display.print_error quotes the package's message about the input it refused.
            text = REFUSAL.sub("", text)
            for match in TINY_NUMBER.finditer(text):
                before = text[max(0, match.start() - 100) : match.start()]
                if (
                    not BOUND_WORDS.search(before)
                    and float(match.group(0)) not in inputs
                ):
                    found.append(f"cell {index}: ...{before[-40:]}{match.group(0)}")
    assert not found, (
        f"{path.name}: numbers at round-off size shown as measurements ({'; '.join(found)}): another machine prints "
        "other digits; show them as bounds with twolink_course.display.below"
    )


def test_the_sanitize_file_masks_only_what_is_random_and_says_why():
    lines = SANITIZE.read_text(encoding="utf-8").splitlines()
    pairs = [index for index, line in enumerate(lines) if line.startswith("regex: ")]
    assert pairs, "nbval_sanitize.cfg has no patterns"
    for index in pairs:
        assert index + 1 < len(lines) and lines[index + 1].startswith("replace: "), (
            f"line {index + 1}: a regex without its replace"
        )
        assert (
            index > 0
            and lines[index - 1].startswith("#")
            and len(lines[index - 1]) > 20
        ), (
            f"nbval_sanitize.cfg line {index + 1}: say in a comment line above it why this output is truly random"
        )
    for line in lines:
        assert line == line.rstrip(), (
            f"trailing space in nbval_sanitize.cfg (nbval would keep it): {line!r}"
        )
        assert line.startswith(("regex: ", "replace: ", "#")) or not line.strip(), (
            f"stray line in nbval_sanitize.cfg: {line!r}"
        )
