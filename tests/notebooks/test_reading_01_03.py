"""Chapter 1 as a reader sees it: one name per matrix.

(The figure checks for every chapter are in ``tests/notebooks/test_figures.py``.)
"""

import json
import pathlib
import re

NOTEBOOK_DIR = pathlib.Path(__file__).resolve().parents[2] / "notebooks"
CHAPTERS = ["01_dh_forward_kinematics.ipynb", "03_jacobian_velocity.ipynb"]


def code_sources(name):
    content = json.loads((NOTEBOOK_DIR / name).read_text(encoding="utf-8"))
    return [
        "".join(cell["source"])
        for cell in content["cells"]
        if cell["cell_type"] == "code"
    ]


def test_chapter_1_names_the_transform_T_0_2_in_its_own_code():
    # the OSAKE source's name H_0^2 may appear in prose that attributes it; the course's own output says T_0^2
    offending = [
        source.splitlines()[0]
        for source in code_sources(CHAPTERS[0])
        if re.search(r"H_0|H_\{?0|\bH_0?2", source)
    ]
    assert not offending, f"chapter 1 code still writes H_0^2 for T_0^2: {offending}"
