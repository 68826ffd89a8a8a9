"""The attacks on ``make grade``: one class of the small course, each attack a returned notebook graded with its classmates.

The class is the small course of ``tests/_grading_course.py`` (9.1 a value
exercise graded on hidden inputs, 9.2 a function, 9.3 a yes/no): two honest
classmates (one solved, one untouched) and one notebook per attack, graded
together, three at a time, with time limits small enough that the attacks
which wait for a limit end in seconds.  The attacks:

- added at the top of exercise 9.1's answer cell of the untouched chapter (a
  cell that always runs, and that the probe runs again on hidden inputs):
  verdicts printed as text; the self-check, the judge, the serializer, the
  probe's output or a builtin replaced; the instructor's files or a
  classmate's read; a classmate's file overwritten; the package patched; a
  startup file left; a summary line forged on the terminal; the grades
  rewritten later; the grader killed; a kernel that stops itself, floods its
  output, loops or forks a spinner;
- the check cells deleted, edited, or skipped with stored outputs;
- with 9.1 answered by numbers right on its visible inputs (what the store, a
  classmate or the self-check's messages give) and the rest solved: a report
  forged by a kernel callback or by rewriting the kernel's outgoing messages,
  the self-check replaced through ``functools.wraps``; memory over several
  processes and files filling the tmpfs (each a row in words); the teacher's
  environment read; a classmate's folder beside the graded one read.

No attack gains a pass and each gets the result it deserves; the classmates
get what their answers earn; the repository, the classmates' files, the
grades and the grader's terminal are unchanged; the run ends within its
limits and leaves no process behind.  Numbers typed in and nan without an
attack: the class of ``tests/infrastructure/test_grade.py``.  What the
sandbox refuses inside the kernel: ``tests/infrastructure/test_sandbox.py``.
"""

import contextlib
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

import _grading_course as course_9
import pytest
from test_grade import UNSAFE, results

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

NAME = f"{course_9.STEM}.ipynb"
#: What the self-check would print for the chapter solved, every part.
SOLVED_LINES = "\n".join(
    f"print('Exercise {e.number} ({p.label}): correct.')"
    for e in course_9.exercises()
    for p in e.parts
)
#: The answers' names: what a thief takes.
ANSWER_NAMES = tuple(p.name for e in course_9.exercises() for p in e.parts)
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
    "            STOLEN.update({{k: v for k, v in scope.items() if k in {names!r}}})\n"
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
    "        try:\n"
    "            if word and folder.is_dir() and folder.name == 'submissions':\n"
    "                for found in folder.glob('*.ipynb'):\n"
    "                    steal(found)\n"
    "        except OSError:  # a word too long for a path\n"
    "            continue\n"
)

#: name: the code added at the top of 9.1's answer cell of the untouched chapter
ATTACK_CELLS = {
    # text counts as a verdict
    "print_the_verdicts": SOLVED_LINES,
    # the student's code judges itself
    "replace_the_check": (
        "from twolink_course import selfcheck\n"
        "selfcheck.check = lambda *a, **k: print('Exercise 9.1 (tip): correct.')"
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
        "forged = b'\\nzz_mallory.ipynb: 4 passed, 0 not solved, 0 wrong\\n'\n"
        "os.write(1, forged)\nos.write(2, forged)"
    ),
    "rewrite_the_grades_later": (
        "import subprocess\n"
        "subprocess.Popen(['sh', '-c', 'sleep {writer_seconds}; echo forged > {grades}; echo forged > {grades}.forged'],"
        " start_new_session=True)\n"
        "subprocess.Popen(['sleep', '{sleeper_seconds}'], start_new_session=True)"
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
#: Exercise 9.1 answered with the numbers right on the visible inputs: what reading the store, copying a
#: classmate or probing the self-check's messages gives.
KNOWN = "p_ex1 = np.array({tip!r})\nreach_ex1 = {reach!r}"
#: name: (what follows KNOWN in 9.1's answer cell (the visible answers are right), 9.3's answer cell or
#: None: solved); 9.2 solved.
COURSE_ATTACKS = {
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
    "memory_over_processes": (
        "",
        # each process holds its block until all have one or were killed: the answer, only if none was
        "import subprocess, sys\n"
        "code = 'import sys; block = bytearray(400 * 2**20); print(1, flush=True); sys.stdin.read()'\n"
        "started = [subprocess.Popen([sys.executable, '-c', code], stdin=subprocess.PIPE, stdout=subprocess.PIPE)"
        " for _ in range(3)]\n"
        "held = [process.stdout.readline() == b'1\\n' for process in started]\n"
        "for process in started:\n    process.stdin.close()\n    process.wait()\n"
        "faster_ex3 = True if all(held) else ...",
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
    "read_a_classmate_s_folder": (
        "",
        "import json\ntry:\n    json.load(open({beside!r}))\n    faster_ex3 = True\n"
        "except OSError:\n    faster_ex3 = ...",
    ),
}
ATTACKS = [*ATTACK_CELLS, *CHECK_CELL_ATTACKS, *COURSE_ATTACKS]
CLASSMATES = ("aa_classmate_solved", "ab_classmate_untouched")
#: Each cell's and each notebook's time limit: an honest notebook of the small course takes a
#: second or two; stop_itself waits for the notebook's, loop_forever for the cell's twice (its
#: answer cell, then the probe's run of it on hidden inputs), well within the notebook's.
CELL_SECONDS, NOTEBOOK_SECONDS = 4.0, 20.0
#: Notebooks graded at a time: more than the cores, as the attacks that wait for a limit use none.
JOBS = 3
LIMITS = grade.Limits(
    CELL_SECONDS,
    NOTEBOOK_SECONDS,
    sandbox.Limits(
        memory_bytes=512 * 2**20,
        tmp_bytes=16 * 2**20,
        shm_bytes=16 * 2**20,
        workdir_bytes=16 * 2**20,
    ),
)
#: The attacks that wait for a limit: graded first, so that their waits overlap the others' runs.
WAITING = ("stop_itself", "loop_forever")
#: How long the detached writer of rewrite_the_grades_later waits before writing.
WRITER_SECONDS = 1


def file_of(name):
    """The returned file of attack or classmate ``name`` (those in WAITING sort first)."""
    return f"{'0_' if name in WAITING else ''}{name}.ipynb"


def known_numbers():
    tip, reach = (part.expected for part in course_9.exercises()[0].parts)
    return KNOWN.format(tip=[float(v) for v in tip], reach=float(reach))


def check_cells(cells):
    return [
        i
        for i, cell in enumerate(cells)
        if grade_release.check_number(
            grade_read.Cell(cell["cell_type"], cell["source"])
        )
        is not None
    ]


def attacked_notebook(name, paths):
    """The small course's chapter attacked by ``name`` (JSON data)."""
    if name in COURSE_ATTACKS:
        first, third = COURSE_ATTACKS[name]
        solutions = {
            **course_9.RIGHT,
            "9.1": known_numbers() + "\n" + first.format(**paths),
        }
        if third is not None:
            solutions["9.3"] = third.format(**paths)
        return course_9.chapter(solutions)
    notebook = course_9.chapter(course_9.STUBS)
    cells = notebook["cells"]
    if name == "delete_the_check_cells":
        checks = check_cells(cells)
        notebook["cells"] = [cell for i, cell in enumerate(cells) if i not in checks]
        return notebook
    if name == "edit_the_check_cells":
        for i in check_cells(cells):
            cells[i]["source"] = SOLVED_LINES
        return notebook
    if name == "stored_outputs_of_skipped_cells":
        for i in check_cells(cells):
            cells[i]["metadata"]["tags"] = ["skip-execution"]
            cells[i]["outputs"] = [
                {"output_type": "stream", "name": "stdout", "text": SOLVED_LINES}
            ]
        return notebook
    code = ATTACK_CELLS[name].format(**paths)
    first_answer = next(
        cell for cell in cells if cell["source"] == course_9.STUBS["9.1"]
    )
    first_answer["source"] = code + "\n" + first_answer["source"]
    if "STOLEN" in code:
        for cell in cells:
            lines = []
            for line in cell["source"].splitlines():
                if line.endswith("= ...  # your code here"):
                    answer = line.split(" = ")[0]
                    line = f"{answer} = STOLEN.get({answer!r}, ...)"
                lines.append(line)
            cell["source"] = "\n".join(lines)
    return notebook


def git_status():
    return subprocess.run(
        ["git", "status", "--porcelain", "--ignored=no"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def startup_files():
    """The files of the grader's IPython startup folders (every profile)."""
    return sorted((pathlib.Path.home() / ".ipython").glob("profile_*/startup/*"))


@contextlib.contextmanager
def scratch_in(folder):
    """The grader's scratch folder made in ``folder``: what a run leaves is told apart from other runs'."""
    saved = tempfile.tempdir
    tempfile.tempdir = str(folder)
    try:
        yield
    finally:
        tempfile.tempdir = saved


def ours(pattern):
    """The command lines of running processes that match ``pattern`` (``pgrep -f``)."""
    found = subprocess.run(
        ["pgrep", "-a", "-f", pattern], capture_output=True, text=True, timeout=30
    )
    return found.stdout.strip()


@pytest.fixture(scope="module")
def attacked(tmp_path_factory):
    # this run's own, with a short path (the kernels' sockets are made in it)
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="twolink-test-"))
    try:
        yield graded_class(tmp_path_factory.mktemp("attacks"), scratch)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def graded_class(tmp_path, scratch):
    """The class graded, with what it showed and left, and what was there before and after."""
    course_9.write_course(tmp_path / "course")
    course = grade_release.Course.read(tmp_path / "course", course_9.REFERENCES)
    submissions = tmp_path / "submissions"
    submissions.mkdir()
    out = tmp_path / "grades" / "grades.csv"
    classmate = course_9.returned(submissions, file_of(CLASSMATES[0]), course_9.RIGHT)
    victim = course_9.returned(submissions, file_of(CLASSMATES[1]))
    # a classmate's folder beside the graded one: the teacher grades one folder at a time
    beside = course_9.returned(tmp_path / "amy", NAME, course_9.RIGHT)
    paths = {
        "instructor": str(tmp_path / "course" / NAME),
        "answers": str(ROOT / "tests" / "_grading_course.py"),
        "classmate": str(classmate),
        "victim": str(victim),
        "beside": str(beside),
        "grades": str(out),
        "grader_home": str(pathlib.Path.home()),
        "solved_lines": SOLVED_LINES,
        "names": ANSWER_NAMES,
        "writer_seconds": WRITER_SECONDS,
        # a command line of this run's alone
        "sleeper_seconds": 10**6 + os.getpid(),
    }
    for name in ATTACKS:
        (submissions / file_of(name)).write_text(
            json.dumps(attacked_notebook(name, paths)), encoding="utf-8"
        )
    before = {
        "classmates": {path: path.read_bytes() for path in (classmate, victim)},
        "git": git_status(),
        "startup": startup_files(),
    }
    graded = []
    started = time.monotonic()
    # the teacher's environment, never the kernel's
    os.environ["TWOLINK_TEST_SECRET"] = "1"
    with tempfile.TemporaryFile() as terminal:  # what the grader's terminal would show
        saved = os.dup(1), os.dup(2)
        os.dup2(terminal.fileno(), 1)
        os.dup2(terminal.fileno(), 2)
        try:
            os.write(2, b"the capture works\n")
            with scratch_in(scratch):
                lines = grade.grade_folder(
                    submissions,
                    out,
                    jobs=JOBS,
                    limits=LIMITS,
                    seed=5,
                    course=course,
                    graded_out=graded,
                )
        finally:
            del os.environ["TWOLINK_TEST_SECRET"]
            os.dup2(saved[0], 1)
            os.dup2(saved[1], 2)
            os.close(saved[0])
            os.close(saved[1])
        terminal.seek(0)
        shown = terminal.read().decode(errors="replace")
    ended = time.monotonic()
    grades_then = out.read_text(encoding="utf-8")
    after = {
        "classmates": {path: path.read_bytes() for path in (classmate, victim)},
        "git": git_status(),
        "startup": startup_files(),
    }
    time.sleep(max(0.0, ended + WRITER_SECONDS + 1 - time.monotonic()))
    left = {
        "scratch": sorted(scratch.iterdir()),
        "processes": ours(f"{scratch}|sleep {paths['sleeper_seconds']}"),
    }
    return {
        "lines": lines,
        "terminal": shown,
        "rows": list(csv.DictReader(out.open(encoding="utf-8"))),
        "graded": {g.file: g for g in graded},
        "seconds": ended - started,
        "grades_changed_later": out.read_text(encoding="utf-8") != grades_then
        or pathlib.Path(f"{out}.forged").exists(),
        "left": left,
        "before": before,
        "after": after,
    }


@pytest.mark.parametrize("name", ATTACKS)
def test_no_attack_gains_a_pass(attacked, name):
    found = results(attacked["rows"], file_of(name))
    assert found, f"{name}: no rows"
    if name in COURSE_ATTACKS:  # 9.2 came with it, solved
        found = {key: result for key, result in found.items() if key[0] != "9.2"}
    assert "passed" not in found.values(), (name, found)


EXPECTED = {
    "replace_the_check": "tampered",
    "replace_the_judge": "tampered",
    "replace_the_serializer": "tampered",
    "rebind_the_name_selfcheck": "tampered",
    "silence_the_probe": "tampered",
    "replace_a_builtin": "tampered",
    "forge_the_report_in_a_callback": "tampered",
    "forge_the_kernel_s_messages": "tampered",
    "wrap_the_self_check": "tampered",
    "print_the_verdicts": "not solved",
    "delete_the_check_cells": "not solved",
    "edit_the_check_cells": "not solved",
    "stored_outputs_of_skipped_cells": "not solved",
    "run_the_instructor_solutions": "not solved",
    "copy_a_classmate": "not solved",
    "forge_a_summary_line": "not solved",
    # the other parts solved: only the part the attack answers is looked at
    "read_the_teacher_s_environment": {("9.3", "faster"): "not solved"},
    "read_a_classmate_s_folder": {("9.3", "faster"): "not solved"},
}


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_each_attack_gets_the_result_it_deserves(attacked, name):
    found = results(attacked["rows"], file_of(name))
    expected = EXPECTED[name]
    if isinstance(expected, str):
        assert set(found.values()) == {expected}, (name, found)
    else:
        assert {key: found[key] for key in expected} == expected, (name, found)


def test_the_classmates_get_what_their_answers_earn(attacked):
    """What the same answers earn graded without attackers (the class of test_grade.py): every part."""
    parts = {(e.number, p.label) for e in course_9.exercises() for p in e.parts}
    for name, earned in zip(CLASSMATES, ("passed", "not solved")):
        assert results(attacked["rows"], file_of(name)) == dict.fromkeys(parts, earned)
        graded = attacked["graded"][file_of(name)]
        assert not graded.failure and not graded.limits and not graded.notes, graded


def test_memory_over_several_processes_and_a_full_disk_are_rows_in_words(attacked):
    memory = attacked["graded"][file_of("memory_over_processes")]
    if sandbox.Cgroups.detect() is not None:
        assert memory.limits == [
            "used more than 512 MiB of memory (the limit per notebook): a process was killed"
        ]
    else:  # one process: the subprocesses are refused
        assert any("PermissionError" in note for note in memory.notes)
    disk = attacked["graded"][file_of("fill_the_disk")]
    assert disk.limits == [
        "wrote more than its disk space (/tmp 16 MiB, /dev/shm 16 MiB, working folder 16 MiB: the limit per notebook)"
    ]
    assert (
        results(attacked["rows"], file_of("fill_the_disk"))["9.3", "faster"]
        == "not solved"
    )


def test_nothing_outside_the_sandbox_changed(attacked):
    before, after = attacked["before"], attacked["after"]
    assert after["classmates"] == before["classmates"]
    assert after["git"] == before["git"], "the repository changed (git status)"
    assert after["startup"] == before["startup"], (
        "a file appeared in the grader's ~/.ipython startup folder"
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
    assert failures[file_of("kill_the_grader")] == "failed to run: the kernel died"
    assert (
        failures[file_of("stop_itself")]
        == f"failed to run: stopped after {NOTEBOOK_SECONDS:g} s (the notebook's time limit)"
    )
    assert failures[file_of("flood_the_output")].startswith(
        "failed to run: its outputs passed"
    )
    assert (
        file_of("loop_forever") not in failures
    )  # the cell was interrupted; the notebook went on
    notebooks = len(ATTACKS) + len(CLASSMATES)
    assert len({row["student file"] for row in attacked["rows"]}) == notebooks
    # one notebook at a time could take the whole notebook limit; JOBS at a time, the run takes less
    assert attacked["seconds"] < notebooks * NOTEBOOK_SECONDS / JOBS
    assert attacked["left"]["processes"] == "", "processes outlived their notebook"
    assert attacked["left"]["scratch"] == [], "the grader's scratch folder was left"


# ------------------------------------------------------------------ the store's values, where the chapter reruns the exercise


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
