"""Ready to publish: ``make dist`` and the GitHub Actions workflows.

``make dist`` builds the sdist and the wheel (``python -m build``: the wheel
from the sdist) and checks both with ``twine check --strict``; the slow test
here runs the target on a copy of the committed files and looks inside what it
built: the exercises' encoded store and ``py.typed`` are in the wheel, the
instructor's ``answers/`` and the ``notebooks/`` are in neither file.
(``tests/infrastructure/test_packaging.py`` installs a wheel in a bare venv; this builds
what would be uploaded.)

``.github/workflows/ci.yml`` runs ``.ci/run`` on pushes and pull requests,
``.github/workflows/site.yml`` builds the static site and uploads it as an
artifact; both are validated offline against GitHub's workflow schema, the
copy that ships with check-jsonschema (``--builtin-schema
vendor.github-workflows``).
"""

import email.parser
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tarfile
import zipfile

import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
WORKFLOWS = ROOT / ".github" / "workflows"
#: What ``python -m build`` reads from the tree: the Makefile's target, the
#: project, the package, the JupyterLab extension (data-files) and the tests
#: (setuptools puts ``tests/test*.py`` in an sdist by default).
BUILD_INPUTS = [
    "Makefile",
    "pyproject.toml",
    "README.md",
    "LICENSE*",
    "twolink",
    "twolink_course",
    "labextension",
    "tests",
]
#: Folders of the repository that neither the sdist nor the wheel may carry.
NEVER_SHIPPED = ("answers", "notebooks")


def tracked_copy(destination, pathspecs):
    """The committed files under ``pathspecs``, copied to ``destination`` (as they are now).

    Untracked files (a stray module, ``__pycache__``, ``build/``) would end up
    in an sdist built in the checkout; a copy holds exactly what a clone does.
    """
    listed = subprocess.run(
        ["git", "ls-files", "-z", "--", *pathspecs],
        cwd=ROOT,
        capture_output=True,
    )
    if listed.returncode != 0 or not listed.stdout:
        pytest.skip(f"not a git checkout: {listed.stderr.decode()[-300:]}")
    for name in filter(None, listed.stdout.decode().split("\0")):
        if (ROOT / name).is_file():
            (destination / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, destination / name)
    return destination


def make_dry_run(*args):
    return subprocess.run(
        ["make", "-n", "--no-print-directory", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def test_make_dist_builds_with_build_and_checks_with_twine():
    lines = make_dry_run("-o", ".venv/.installed-stamp", "dist").splitlines()
    assert any(
        re.search(r"python -m build --outdir dist \.$", line) for line in lines
    ), lines
    assert any(
        re.search(r"python -m twine check --strict dist/twolink-\*$", line)
        for line in lines
    ), lines
    elsewhere = make_dry_run("-o", ".venv/.installed-stamp", "dist", "DIST=/tmp/x")
    assert "--outdir /tmp/x ." in elsewhere and "check --strict /tmp/x/twolink-*" in (
        elsewhere
    )
    assert "make dist " in make_dry_run("help")


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """``make dist`` on a copy of the committed files: (sdist, wheel, make's output)."""
    tmp = tmp_path_factory.mktemp("dist")
    source = tracked_copy(tmp / "source", BUILD_INPUTS)
    venv = ROOT / ".venv"
    if not (venv / "bin" / "python").is_file():
        venv = pathlib.Path(sys.prefix)
    out = tmp / "dist"
    run = subprocess.run(
        [
            "make",
            "--no-print-directory",
            f"VENV={venv}",
            # the venv is the one running these tests: make must not reinstall it
            "-o",
            f"{venv}/.installed-stamp",
            "dist",
            f"DIST={out}",
        ],
        cwd=source,
        capture_output=True,
        text=True,
        env={**os.environ, "COLUMNS": "400"},  # twine's report on one line per file
        timeout=600,
    )
    assert run.returncode == 0, (run.stdout[-3000:], run.stderr[-3000:])
    (sdist,) = out.glob("twolink-*.tar.gz")
    (wheel,) = out.glob("twolink-*.whl")
    return sdist, wheel, run.stdout


def committed(pattern):
    """The committed files matching a git pathspec, as paths relative to the repository."""
    listed = subprocess.run(
        ["git", "ls-files", "--", pattern],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return set(listed.stdout.split())


@pytest.mark.infrastructure
def test_make_dist_builds_an_sdist_and_a_wheel_that_twine_passes(built):
    import twolink

    sdist, wheel, output = built
    assert sdist.name == f"twolink-{twolink.__version__}.tar.gz"
    assert wheel.name == f"twolink-{twolink.__version__}-py3-none-any.whl"
    # twine's report, without its colours and the line breaks it puts even inside a long path
    report = re.sub(r"\s+", "", re.sub(r"\x1b\[[0-9;]*m", "", output))
    checked = re.findall(r"Checking(\S+?):PASSED", report)
    assert sorted(pathlib.Path(name).name for name in checked) == sorted(
        [sdist.name, wheel.name]
    ), output[-2000:]
    with zipfile.ZipFile(wheel) as archive:
        metadata = archive.read(
            f"twolink-{twolink.__version__}.dist-info/METADATA"
        ).decode()
    fields = email.parser.Parser().parsestr(metadata)
    assert fields["Name"] == "twolink" and fields["Version"] == twolink.__version__
    assert fields["License-Expression"] == "MIT"
    assert fields["Description-Content-Type"] == "text/markdown"
    assert "# twolink: the planar two-link arm" in fields.get_payload()


@pytest.mark.infrastructure
def test_the_wheel_holds_the_package_its_store_and_types_and_nothing_else(built):
    _, wheel, _ = built
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
    modules = {name for name in committed("twolink/*.py")}
    assert modules and modules <= names, sorted(modules - names)
    store = committed("twolink_course/exercises/store/*.txt")
    assert len(store) >= 7, store
    assert store <= names, sorted(store - names)
    assert "twolink/py.typed" in names and "twolink_course/py.typed" in names
    assert any(
        name.endswith("labextensions/twolink-figure-alt/package.json") for name in names
    ), "the JupyterLab extension's data-files are missing"
    for name in names:
        top, *inside = name.split("/")
        assert top in ("twolink", "twolink_course") or top.startswith("twolink-"), name
        assert not {*NEVER_SHIPPED, "tests", "tools"} & set(inside), name


@pytest.mark.infrastructure
def test_the_sdist_holds_the_sources_and_no_answers_or_notebooks(built):
    import twolink

    sdist, _, _ = built
    prefix = f"twolink-{twolink.__version__}/"
    with tarfile.open(sdist) as archive:
        names = {name.removeprefix(prefix) for name in archive.getnames()}
    for needed in ("pyproject.toml", "README.md", "LICENSE", "PKG-INFO"):
        assert needed in names, needed
    missing = (committed("twolink") | committed("twolink_course")) - names
    assert not missing, sorted(missing)
    for folder in NEVER_SHIPPED:
        shipped = [name for name in names if name.split("/")[0] == folder]
        assert not shipped, shipped


# --- the workflows ---------------------------------------------------------------------------------------------


def validate(*paths):
    """check-jsonschema against its built-in copy of GitHub's workflow schema, with the network cut off;
    its report as JSON (``errors`` and ``parse_errors`` name the file of each)."""
    blocked = "http://127.0.0.1:9"  # a proxy that refuses: any download fails at once
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "check_jsonschema",
            "--builtin-schema",
            "vendor.github-workflows",
            "--output-format",
            "json",
            *map(str, paths),
        ],
        capture_output=True,
        text=True,
        env={
            **os.environ,
            "HTTP_PROXY": blocked,
            "HTTPS_PROXY": blocked,
            "http_proxy": blocked,
            "https_proxy": blocked,
            "NO_PROXY": "",
            "no_proxy": "",
        },
        timeout=120,
    )


#: ci.yml broken three ways, each caught by the schema: (old text, new text, the schema's complaint).
BREAKAGES = {
    "key": ("runs-on: ubuntu-latest", "runs_on: ubuntu-latest", "'runs-on' is a required property"),
    "event": ("  pull_request:", "  pull_requests:", "'pull_requests': None"),
    "type": ("timeout-minutes: 60", "timeout-minutes: soon", "'soon' is not of type 'number'"),
}  # fmt: skip


@pytest.fixture(scope="module")
def validated(tmp_path_factory):
    """One run of the schema check over the workflows and a broken copy of ci.yml for each of
    ``BREAKAGES``: (its exit status, ``{file: [messages]}`` of the files it found wrong, the
    broken copies by name)."""
    tmp = tmp_path_factory.mktemp("workflows")
    text = (WORKFLOWS / "ci.yml").read_text(encoding="utf-8")
    broken = {}
    for name, (old, new, _) in BREAKAGES.items():
        assert old in text, old
        broken[name] = tmp / name / "ci.yml"
        broken[name].parent.mkdir()
        broken[name].write_text(text.replace(old, new), encoding="utf-8")
    result = validate(*sorted(WORKFLOWS.glob("*.yml")), *broken.values())
    report = json.loads(result.stdout)
    wrong = {}
    for error in report["errors"] + report["parse_errors"]:
        messages = [error.get("message", "")]
        for match in ("best_match", "best_deep_match"):
            messages.append(error.get(match, {}).get("message", ""))
        wrong.setdefault(pathlib.Path(error["filename"]), []).extend(messages)
    return result.returncode, wrong, broken


def workflow(name):
    text = (WORKFLOWS / name).read_text(encoding="utf-8")
    data = yaml.safe_load(text)
    # YAML 1.1 reads the key `on` as True
    data["on"] = data.pop(True, data.get("on"))
    return data


def steps(data):
    return [step for job in data["jobs"].values() for step in job["steps"]]


def test_the_workflows_are_valid_github_workflows(validated):
    _, wrong, _ = validated
    paths = sorted(WORKFLOWS.glob("*.yml"))
    assert {path.name for path in paths} >= {"ci.yml", "site.yml"}
    for path in paths:
        assert path not in wrong, wrong[path]


@pytest.mark.parametrize("breakage", BREAKAGES)
def test_the_schema_check_catches_a_broken_workflow(validated, breakage):
    returncode, wrong, broken = validated
    assert returncode == 1
    messages = wrong.get(broken[breakage], [])
    assert any(BREAKAGES[breakage][2] in message for message in messages), messages


def test_ci_runs_ci_run_on_every_push_and_pull_request():
    data = workflow("ci.yml")
    assert "push" in data["on"] and "pull_request" in data["on"]
    assert data["on"]["push"] is None and data["on"]["pull_request"] is None, (
        "every branch, no filter"
    )
    (job,) = data["jobs"].values()
    assert job["runs-on"] == "ubuntu-latest"
    runs = [step.get("run", "").strip() for step in steps(data) if "run" in step]
    # make test, then the benchmarks' quick runs as a step of their own, then make portable
    assert runs == ["bash .ci/run test", "bash .ci/run bench", "bash .ci/run portable"]
    assert any(
        step.get("uses", "").startswith("actions/checkout@") for step in steps(data)
    )
    # .ci/run needs python3, make and apt-get for Debian's chromium and bubblewrap:
    # a Debian image of the Python the course is locked with
    image = job["container"]["image"]
    python = (
        (ROOT / ".binder" / "runtime.txt").read_text().strip().removeprefix("python-")
    )
    assert re.fullmatch(rf"python:{re.escape(python)}-(bookworm|trixie)", image), image
    assert "--privileged" in job["container"]["options"], "bubblewrap needs namespaces"
    ci_run = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert "apt-get install" in ci_run and "chromium" in ci_run
    for command in ("make test", "make bench-quick", "make portable"):
        assert command in ci_run, command
    assert "set -- test bench portable" in ci_run  # all three without an argument


def test_site_builds_the_static_site_and_uploads_it():
    data = workflow("site.yml")
    assert "push" in data["on"] and "pull_request" in data["on"]
    (job,) = data["jobs"].values()
    assert job["runs-on"] == "ubuntu-latest"
    names = [step.get("run", step.get("uses", "")) for step in steps(data)]
    build = names.index("make site")
    (upload,) = [
        number
        for number, step in enumerate(steps(data))
        if step.get("uses", "").startswith("actions/upload-artifact@")
    ]
    assert build < upload, names
    assert steps(data)[upload]["with"]["path"].rstrip("/") == "build/site"
    assert steps(data)[upload]["with"]["if-no-files-found"] == "error"
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert re.search(
        r"^site: .*\n\t.*editions\.py site --out build/site$", makefile, re.M
    )
