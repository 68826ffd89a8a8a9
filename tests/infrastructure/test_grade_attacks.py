"""The attacks on ``make grade``, each a returned notebook built here and graded with its classmates.

Every attack is chapter 1's student edition with the attack added (a cell
after the imports, or changed check cells).  Graded together with two
honest classmates (one solved, one untouched), the suite asserts: no attack
gains a pass; the classmates' results are what they are when graded alone;
the repository, the classmates' files and the grades are unchanged; the run
ends within its limits and leaves no process behind.  What the sandbox
refuses inside the kernel (reading, writing, the network, memory and
process floods) is asserted from the attacks' own words in
``tests/infrastructure/test_sandbox.py``.
"""

import csv
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import pytest
from test_grade import UNSAFE, results, solved, student_chapter

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402

pytestmark = [
    pytest.mark.infrastructure,
    pytest.mark.skipif(
        UNSAFE, reason="no sandbox on this machine: the attacks need one"
    ),
]

SOLVED_LINES = "\n".join(
    f"print('Exercise {number} ({label}): correct.')"
    for number, label in [
        ("1.1", "tip position"),
        ("1.2", "T_02"),
        ("1.2", "tip height"),
        ("1.2", "tip x axis"),
        ("1.3", "relative angles"),
        ("1.3", "tip"),
        ("1.4", "tip_position(arm, q)"),
    ]
)
#: Answers taken from elsewhere: every stub becomes ``name = STOLEN.get("name", ...)``.
STEAL = (
    "import json, pathlib, re\n"
    "STOLEN = {{}}\n"
    "def steal(path):\n"
    "    try:\n"
    "        cells = json.loads(pathlib.Path(path).read_text())['cells']\n"
    "    except (OSError, ValueError):\n"
    "        return\n"
    "    for cell in cells:\n"
    "        source = ''.join(cell['source'])\n"
    "        if 'BEGIN SOLUTION' in source or '_ex' in source:\n"
    "            scope = dict(globals())\n"
    "            try:\n"
    "                exec(source, scope)\n"
    "            except Exception:\n"
    "                continue\n"
    "            STOLEN.update({{k: v for k, v in scope.items() if k.endswith('_ex1') or k.startswith('tip_position')}})\n"
)
FROM_CMDLINE = (
    "import os\n"
    "for pid in os.listdir('/proc'):\n"
    "    try:\n"
    "        words = open(f'/proc/{{pid}}/cmdline', 'rb').read().split(b'\\0')\n"
    "    except OSError:\n"
    "        continue\n"
    "    for word in words:\n"
    "        folder = pathlib.Path(word.decode(errors='replace'))\n"
    "        if word and folder.is_dir() and folder.name == 'submissions':\n"
    "            for found in folder.glob('*.ipynb'):\n"
    "                steal(found)\n"
)

#: name: (the attack cell, how the notebook is changed besides, what the attacker hopes)
ATTACK_CELLS = {
    # text counts as a verdict
    "print_the_verdicts": SOLVED_LINES,
    # the student's code judges itself
    "replace_the_check": (
        "from twolink_course import selfcheck\n"
        "selfcheck.check = lambda *a, **k: print('Exercise 1.1 (tip position): correct.')"
    ),
    "replace_the_judge": (
        "from twolink_course.exercises import judging\n"
        "judging.judge = lambda part, answer: judging.Verdict(True, '')\n"
        "judging.judge_function = lambda part, function, cases: judging.Verdict(True, '')"
    ),
    "replace_the_serializer": (
        "import json\n"
        "real_dumps = json.dumps\n"
        "json.dumps = lambda *a, **k: real_dumps(*a, **k)"
    ),
    "rebind_the_name_selfcheck": (
        "import types\n"
        "selfcheck = types.SimpleNamespace(check=lambda *a, **k: print('correct'))"
    ),
    "silence_the_probe": "get_ipython = lambda: None",
    "replace_a_builtin": "import builtins\nbuiltins.print = lambda *a, **k: None",
    # the instructor's solutions and the classmates' files
    "run_the_instructor_solutions": STEAL + "steal({instructor!r})\nsteal({answers!r})",
    "copy_a_classmate": STEAL + FROM_CMDLINE + "steal({classmate!r})",
    "overwrite_a_classmate": (
        "for path in ({classmate!r}, {victim!r}):\n"
        "    try:\n"
        "        open(path, 'w').write('{{}}')\n"
        "    except OSError:\n"
        "        pass"
    ),
    "patch_the_package": (
        "import twolink_course.selfcheck\n"
        "try:\n"
        "    open(twolink_course.selfcheck.__file__, 'a').write('\\n# patched\\n')\n"
        "except OSError:\n"
        "    pass"
    ),
    "leave_a_startup_file": (
        "import pathlib\n"
        "for home in (pathlib.Path.home(), pathlib.Path({grader_home!r})):\n"
        "    folder = home / '.ipython/profile_default/startup'\n"
        "    try:\n"
        "        folder.mkdir(parents=True, exist_ok=True)\n"
        "        (folder / '00-pass.py').write_text({solved_lines!r})\n"
        "    except OSError:\n"
        "        pass"
    ),
    "forge_a_summary_line": (
        "import os\n"
        "forged = b'\\nzz_mallory.ipynb: 7 passed, 0 not solved, 0 wrong\\n'\n"
        "os.write(1, forged)\nos.write(2, forged)"
    ),
    "rewrite_the_grades_later": (
        "import subprocess\n"
        "subprocess.Popen(['sh', '-c', 'sleep 3; echo forged > {grades}'], start_new_session=True)\n"
        "subprocess.Popen(['sleep', '1000'], start_new_session=True)"
    ),
    # no limits
    "kill_the_grader": (
        "import os, signal\n"
        "for target in (0, -1):\n"
        "    try:\n"
        "        os.kill(target, signal.SIGKILL) if target else os.killpg(0, signal.SIGKILL)\n"
        "    except OSError:\n"
        "        pass"
    ),
    "stop_itself": "import os, signal\nos.kill(os.getpid(), signal.SIGSTOP)",
    "flood_the_output": "for _ in range(60):\n    print('x' * 1_000_000)",
    "loop_forever": "while True:\n    pass",
    "fork_a_spinner": (
        "import os\nif os.fork() == 0:\n    os.setsid()\n    while True:\n        pass"
    ),
}
#: Attacks on the check cells themselves.
CHECK_CELL_ATTACKS = (
    "delete_the_check_cells",
    "edit_the_check_cells",
    "stored_outputs_of_skipped_cells",
)
CELL_SECONDS, NOTEBOOK_SECONDS = 10.0, 60.0


def attacked_notebook(student_edition, name, paths):
    """Chapter 1 (student edition) attacked by ``name``."""
    notebook = student_chapter(student_edition)
    cells = notebook["cells"]
    checks = [i for i, cell in enumerate(cells) if grade.check_number(cell) is not None]
    if name == "delete_the_check_cells":
        notebook["cells"] = [cell for i, cell in enumerate(cells) if i not in checks]
        return notebook
    if name == "edit_the_check_cells":
        for i in checks:
            cells[i]["source"] = SOLVED_LINES
        return notebook
    if name == "stored_outputs_of_skipped_cells":
        for i in checks:
            cells[i]["metadata"]["tags"] = ["skip-execution"]
            cells[i]["outputs"] = [
                {"output_type": "stream", "name": "stdout", "text": SOLVED_LINES}
            ]
        return notebook
    code = ATTACK_CELLS[name].format(
        solved_lines=SOLVED_LINES, **{k: str(v) for k, v in paths.items()}
    )
    imports = next(
        i
        for i, cell in enumerate(cells)
        if "from twolink import" in "".join(cell["source"])
    )
    cells.insert(
        imports + 1,
        {
            "cell_type": "code",
            "id": f"attack-{name}",
            "metadata": {},
            "outputs": [],
            "execution_count": None,
            "source": code,
        },
    )
    if "STOLEN" in code:
        for cell in cells:
            source = "".join(cell["source"])
            for line in source.splitlines():
                if line.endswith("= ...  # your code here"):
                    answer = line.split(" = ")[0]
                    source = source.replace(
                        line, f"{answer} = STOLEN.get({answer!r}, ...)"
                    )
            cell["source"] = source
    return notebook


def git_status():
    return subprocess.run(
        ["git", "status", "--porcelain", "--ignored=no"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


@pytest.fixture(scope="module")
def attacked(tmp_path_factory, student_edition):
    tmp_path = tmp_path_factory.mktemp("attacks")
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    out = tmp_path / "grades" / "grades.csv"
    classmate, victim = (
        submissions / "aa_classmate_solved.ipynb",
        submissions / "ab_classmate_untouched.ipynb",
    )
    classmate.write_text(json.dumps(solved(student_edition)), encoding="utf-8")
    victim.write_text(json.dumps(student_chapter(student_edition)), encoding="utf-8")
    alone = tmp_path / "alone"
    alone.mkdir()
    for path in (classmate, victim):
        (alone / path.name).write_bytes(path.read_bytes())
    limits = grade.Limits(CELL_SECONDS, NOTEBOOK_SECONDS)
    grade.grade_folder(alone, tmp_path / "alone.csv", jobs=2, limits=limits, seed=5)
    paths = {
        "instructor": ROOT / "notebooks" / "01_dh_forward_kinematics.ipynb",
        "answers": ROOT / "answers" / "ch1.py",
        "classmate": classmate,
        "victim": victim,
        "grades": out,
        "grader_home": pathlib.Path.home(),
    }
    for name in [*ATTACK_CELLS, *CHECK_CELL_ATTACKS]:
        (submissions / f"{name}.ipynb").write_text(
            json.dumps(attacked_notebook(student_edition, name, paths)),
            encoding="utf-8",
        )
    before = {
        "classmates": {path: path.read_bytes() for path in (classmate, victim)},
        "git": git_status(),
        "startup": sorted((pathlib.Path.home() / ".ipython").rglob("*")),
    }
    started = time.monotonic()
    with tempfile.TemporaryFile() as terminal:  # what the grader's terminal would show
        saved = os.dup(1), os.dup(2)
        os.dup2(terminal.fileno(), 1)
        os.dup2(terminal.fileno(), 2)
        try:
            os.write(2, b"the capture works\n")
            lines = grade.grade_folder(submissions, out, jobs=2, limits=limits, seed=5)
        finally:
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        terminal.seek(0)
        shown = terminal.read().decode(errors="replace")
    seconds = time.monotonic() - started
    grades_then = out.read_text(encoding="utf-8")
    time.sleep(5)  # longer than the detached writer waits
    return {
        "lines": lines,
        "terminal": shown,
        "rows": list(csv.DictReader(out.open(encoding="utf-8"))),
        "alone": list(csv.DictReader((tmp_path / "alone.csv").open(encoding="utf-8"))),
        "seconds": seconds,
        "grades_changed_later": out.read_text(encoding="utf-8") != grades_then,
        "before": before,
        "after": {
            "classmates": {path: path.read_bytes() for path in (classmate, victim)},
            "git": git_status(),
            "startup": sorted((pathlib.Path.home() / ".ipython").rglob("*")),
        },
    }


ATTACKS = [*ATTACK_CELLS, *CHECK_CELL_ATTACKS]


@pytest.mark.parametrize("name", ATTACKS)
def test_no_attack_gains_a_pass(attacked, name):
    found = results(attacked["rows"], f"{name}.ipynb")
    assert found, f"{name}: no rows"
    assert "passed" not in found.values(), (name, found)


EXPECTED = {
    "replace_the_check": "tampered",
    "replace_the_judge": "tampered",
    "replace_the_serializer": "tampered",
    "rebind_the_name_selfcheck": "tampered",
    "silence_the_probe": "tampered",
    "replace_a_builtin": "tampered",
    "print_the_verdicts": "not solved",
    "delete_the_check_cells": "not solved",
    "edit_the_check_cells": "not solved",
    "stored_outputs_of_skipped_cells": "not solved",
    "run_the_instructor_solutions": "not solved",
    "copy_a_classmate": "not solved",
    "forge_a_summary_line": "not solved",
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_each_attack_gets_the_result_it_deserves(attacked, name):
    found = results(attacked["rows"], f"{name}.ipynb")
    assert set(found.values()) == {EXPECTED[name]}, (name, found)


def test_classmates_are_graded_as_when_alone(attacked):
    for name in ("aa_classmate_solved.ipynb", "ab_classmate_untouched.ipynb"):
        assert results(attacked["rows"], name) == results(attacked["alone"], name)
    assert set(results(attacked["rows"], "aa_classmate_solved.ipynb").values()) == {
        "passed"
    }


def test_nothing_outside_the_sandbox_changed(attacked):
    before, after = attacked["before"], attacked["after"]
    assert after["classmates"] == before["classmates"]
    assert after["git"] == before["git"], "the repository changed (git status)"
    assert after["startup"] == before["startup"], (
        "a file appeared in the grader's ~/.ipython"
    )
    assert not attacked["grades_changed_later"]
    assert "zz_mallory" not in attacked["terminal"], (
        "a kernel wrote to the grader's terminal"
    )
    assert "the capture works" in attacked["terminal"]


def test_the_run_ends_within_its_limits_and_leaves_no_process(attacked):
    failures = {
        row["student file"]: row["result"]
        for row in attacked["rows"]
        if row["exercise"] == "(none)"
    }
    assert failures["kill_the_grader.ipynb"] == "failed to run: the kernel died"
    assert (
        failures["stop_itself.ipynb"]
        == f"failed to run: stopped after {NOTEBOOK_SECONDS:g} s (the notebook's time limit)"
    )
    assert failures["flood_the_output.ipynb"].startswith(
        "failed to run: its outputs passed"
    )
    assert (
        "loop_forever.ipynb" not in failures
    )  # the cell was interrupted; the notebook went on
    assert len({row["student file"] for row in attacked["rows"]}) == len(ATTACKS) + 2
    # one notebook at a time could take the whole notebook limit; two at a time, the run takes less
    assert attacked["seconds"] < (len(ATTACKS) + 2) * NOTEBOOK_SECONDS / 2
    leftovers = subprocess.run(
        ["pgrep", "-f", "sleep 1000|twolink-grade-"], capture_output=True, text=True
    )
    assert leftovers.stdout.strip() == "", "processes outlived their notebook"
