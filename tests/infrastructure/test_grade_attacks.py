"""The attacks on ``make grade``, each a returned notebook built here and graded with its classmates.

Two suites.  The first: chapter 1's student edition with the attack added at
the top of its first answer cell (a cell that always runs), or changed check
cells, graded together with two honest classmates (one solved, one
untouched): no attack gains a pass; the classmates' results are what they
are when graded alone; the repository, the classmates' files and the grades
are unchanged; the run ends within its limits and leaves no process behind.

The second: the small course of ``tests/_grading_course.py``, whose value
exercise is graded on hidden inputs, attacked by what made a known number
earn points (typed in from the store, a classmate or the self-check's
messages; a report forged by a kernel callback or by rewriting the kernel's
outgoing messages; a self-check replaced through ``functools.wraps``), by
nan, by memory over several processes and files filling the tmpfs (each a
row in words), by a classmate's folder when each student's folder is graded
alone, and by the teacher's environment.  What the sandbox refuses inside
the kernel is asserted from the attacks' own words in ``tests/infrastructure/test_sandbox.py``.
"""

import csv
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

import _grading_course as course_9
import pytest
from test_grade import UNSAFE, results, solved, student_chapter

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import grade  # noqa: E402
import grade_plan  # noqa: E402
import grade_read  # noqa: E402
import grade_release  # noqa: E402
import grade_verdicts  # noqa: E402
import grading_probe  # noqa: E402
import sandbox  # noqa: E402

import answers  # noqa: E402
from twolink_course import exercises  # noqa: E402

pytestmark = [
    pytest.mark.infrastructure,
    pytest.mark.skipif(
        UNSAFE, reason="no sandbox on this machine: the attacks need one"
    ),
]

#: What the self-check prints for chapter 1 solved, every part (from the store).
SOLVED_LINES = "\n".join(
    f"print('Exercise {e.number} ({p.label}): correct.')"
    for e in exercises.all_exercises()
    if e.chapter == "01_dh_forward_kinematics"
    for p in e.parts
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
    "silence_the_probe": (
        "import IPython.display\nIPython.display.publish_display_data = lambda *a, **k: None"
    ),
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
    checks = [
        i
        for i, cell in enumerate(cells)
        if grade_release.check_number(
            grade_read.Cell(cell["cell_type"], "".join(cell["source"]))
        )
        is not None
    ]
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
    first_answer = next(
        cell
        for cell in cells
        if "p_tip_ex1 = ...  # your code here" in "".join(cell["source"])
    )
    first_answer["source"] = code + "\n" + "".join(first_answer["source"])
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


# ------------------------------------------------------------------ the small course: known numbers, forged reports, limits

#: Exercise 9.1 answered with the numbers right on the visible inputs: what reading the store, copying a
#: classmate or probing the self-check's messages gives.
KNOWN = "p_ex1 = np.array({tip!r})\nreach_ex1 = {reach!r}"
#: name: (what replaces exercise 9.1's answer cell (KNOWN first, so the visible answers are right), 9.3's)
COURSE_ATTACKS = {
    "known_numbers": ("", None),
    "forge_the_report_in_a_callback": (
        "def forge(result):\n"
        "    pass  # would rewrite the probe's outputs after each cell\n"
        "get_ipython().events.register('post_run_cell', forge)",
        None,
    ),
    "forge_the_kernel_s_messages": (
        "session = get_ipython().kernel.session\n"
        "real_pack = session.pack\n"
        "session.pack = lambda message: real_pack(message)  # would rewrite every outgoing message",
        None,
    ),
    "wrap_the_self_check": (
        "import functools\n"
        "real_check = selfcheck.check\n"
        "selfcheck.check = functools.wraps(real_check)(lambda *a, **k: real_check(*a, **k))",
        None,
    ),
    "nan_everywhere": (
        "p_ex1 = np.full(2, np.nan)\nreach_ex1 = float('nan')",
        "faster_ex3 = float('nan')",
    ),
    "memory_over_processes": (
        "",
        "import subprocess, sys\n"
        "code = 'import time; block = bytearray(400 * 2**20); time.sleep(30)'\n"
        "started = [subprocess.Popen([sys.executable, '-c', code]) for _ in range(3)]\n"
        "[process.wait() for process in started]\nfaster_ex3 = True",
    ),
    "fill_the_disk": (
        "",
        "import os\nfor folder in ('/tmp', '/dev/shm', os.path.expanduser('~')):\n"
        "    with open(os.path.join(folder, 'flood'), 'wb') as handle:\n"
        "        for _ in range(64):\n            handle.write(bytes(2**20))\nfaster_ex3 = True",
    ),
    "read_the_teacher_s_environment": (
        "",
        "import os\nfaster_ex3 = True if 'TWOLINK_TEST_SECRET' in os.environ else ...",
    ),
}
COURSE_EXPECTED = {
    "known_numbers": {("9.1", "tip"): "wrong", ("9.1", "reach"): "wrong"},
    "forge_the_report_in_a_callback": "tampered",
    "forge_the_kernel_s_messages": "tampered",
    "wrap_the_self_check": "tampered",
    "nan_everywhere": {
        ("9.1", "tip"): "wrong",
        ("9.1", "reach"): "wrong",
        ("9.3", "faster"): "wrong",
    },
    "read_the_teacher_s_environment": {("9.3", "faster"): "not solved"},
}
COURSE_LIMITS = grade.Limits(
    30.0,
    120.0,
    sandbox.Limits(
        memory_bytes=512 * 2**20,
        tmp_bytes=16 * 2**20,
        shm_bytes=16 * 2**20,
        workdir_bytes=16 * 2**20,
    ),
)


def known_numbers():
    tip, reach = (part.expected for part in course_9.exercises()[0].parts)
    return KNOWN.format(tip=[float(v) for v in tip], reach=float(reach))


@pytest.fixture(scope="module")
def course_attacked(tmp_path_factory):
    tmp_path = tmp_path_factory.mktemp("course-attacks")
    course_9.write_course(tmp_path / "course")
    course = grade_release.Course.read(tmp_path / "course", course_9.REFERENCES)
    submissions = tmp_path / "submissions"
    name = f"{course_9.STEM}.ipynb"
    course_9.returned(submissions / "honest", name, course_9.RIGHT)
    for attack, (first, third) in COURSE_ATTACKS.items():
        answers_ = {**course_9.RIGHT, "9.1": known_numbers() + "\n" + first}
        if third is not None:
            answers_["9.3"] = third
        course_9.returned(submissions / attack, name, answers_)
    os.environ["TWOLINK_TEST_SECRET"] = (
        "1"  # the teacher's environment, never the kernel's
    )
    try:
        graded = []
        grade.grade_folder(
            submissions,
            tmp_path / "out" / "grades.csv",
            jobs=2,
            limits=COURSE_LIMITS,
            seed=13,
            course=course,
            graded_out=graded,
        )
    finally:
        del os.environ["TWOLINK_TEST_SECRET"]
    # graded one student's folder at a time: a classmate's folder beside it is out of reach
    thief = tmp_path / "class" / "zed"
    course_9.returned(tmp_path / "class" / "amy", name, course_9.RIGHT)
    steal = (
        f"import json\ntry:\n    json.load(open({str(tmp_path / 'class' / 'amy' / name)!r}))\n    faster_ex3 = True\n"
        "except OSError:\n    faster_ex3 = ..."
    )
    course_9.returned(thief, name, {**course_9.RIGHT, "9.3": steal})
    alone = []
    grade.grade_folder(
        thief, tmp_path / "zed.csv", jobs=1, seed=13, course=course, graded_out=alone
    )
    return {g.file.split("/")[0]: g for g in graded + alone}


def course_results(course_attacked, name):
    return {(v.number, v.part): v.result for v in course_attacked[name].verdicts}


@pytest.mark.parametrize("name", sorted(COURSE_EXPECTED))
def test_a_known_number_or_a_forged_report_earns_nothing(course_attacked, name):
    found = course_results(course_attacked, name)
    expected = COURSE_EXPECTED[name]
    if isinstance(expected, str):
        assert set(found.values()) == {expected}, found
    else:
        assert {key: found[key] for key in expected} == expected, found


def test_the_honest_classmate_passes_every_part(course_attacked):
    assert set(course_results(course_attacked, "honest").values()) == {"passed"}


def test_memory_over_several_processes_and_a_full_disk_are_rows_in_words(
    course_attacked,
):
    memory = course_attacked["memory_over_processes"]
    if sandbox.Cgroups.detect() is not None:
        assert memory.limits == [
            "used more than 512 MiB of memory (the limit per notebook): a process was killed"
        ]
    else:  # one process: the subprocesses are refused
        assert any("PermissionError" in note for note in memory.notes)
    assert (
        course_results(course_attacked, "memory_over_processes")["9.3", "faster"]
        != "passed"
    )
    disk = course_attacked["fill_the_disk"]
    assert disk.limits == [
        "wrote more than its disk space (/tmp 16 MiB, /dev/shm 16 MiB, working folder 16 MiB: the limit per notebook)"
    ]
    assert (
        course_results(course_attacked, "fill_the_disk")["9.3", "faster"]
        == "not solved"
    )


def test_a_classmate_s_folder_is_out_of_reach_when_each_folder_is_graded_alone(
    course_attacked,
):
    assert (
        course_results(course_attacked, course_9.STEM + ".ipynb")["9.3", "faster"]
        == "not solved"
    )


@pytest.fixture(scope="module")
def repository_plan():
    """The plan of the repository's chapters (seed 5): their hidden draws, one hidden call each."""
    course = grade_release.Course.read(ROOT / "notebooks", grade.REFERENCES)
    return grade_plan.Plan.drawn(course, seed=5, count=1, draws=3)


RERUN_PARTS = [
    (number, part)
    for number in sorted(answers.rerun_specs())
    for part in exercises.get(number).parts
    if part.kind != "function" and (number, part.name) not in answers.on_paper()
]


@pytest.mark.parametrize(
    "number, part", RERUN_PARTS, ids=[f"{n}-{p.name}" for n, p in RERUN_PARTS]
)
def test_a_value_read_from_the_store_earns_nothing_where_the_chapter_reruns_the_exercise(
    repository_plan, number, part
):
    """For every value part of the repository's chapters graded on hidden inputs: its stored value fails the draws."""
    plan = repository_plan
    exercise = exercises.get(number)
    stored = grading_probe.encode(part.expected)
    found = {"visible": {"exercise": number, "answers": {part.name: stored}, "fingerprints": {}},
             "draws": {i: {"exercise": number, "draw": i, "answers": {part.name: stored}} for i in range(3)}}  # fmt: skip
    rows, _ = grade_verdicts.verdicts(
        [exercise], [number], {"reports": {number: found}}, plan, {}
    )
    assert [row.result for row in rows if row.part == part.label] == ["wrong"]
