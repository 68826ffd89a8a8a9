"""Every ordinary way of getting the course works: licence, Binder, conda, the lock file, the bare library.

The slow test here installs the wheel (the student edition's, built once per
test run) and imports it in a venv that has only the library's three
dependencies (numpy, scipy, sympy).
"""

import ast
import importlib.metadata
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import textwrap
import tomllib

import _venvs
import pytest
from packaging.specifiers import SpecifierSet
from packaging.utils import canonicalize_name

ROOT = pathlib.Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
README = (ROOT / "README.md").read_text(encoding="utf-8")
#: Import names of the optional dependencies: the library's two (mujoco, control: extras of
#: their own) and the course kit's (the ``course`` extra, which includes both).
COURSE_ONLY = {
    "control",
    "imageio_ffmpeg",
    "ipywidgets",
    "ipympl",
    "IPython",
    "matplotlib",
    "mujoco",
    "jupyterlab",
}
#: The library's dependencies (pip install twolink).
CORE = ["numpy", "scipy", "sympy"]
#: The course's requirements (make lab) and the developers' (make test and the rest).
REQUIREMENTS = [ROOT / "requirements.txt", ROOT / "requirements-dev.txt"]
#: Tools learners need not install: they go with the developers' requirements.
DEVELOPERS_TOOLS = {
    "pytest",
    "pytest-xdist",
    "hypothesis",
    "nbval",
    "nbstripout",
    "nbgrader",
    "ruff",
    "mypy",
    "build",
    "twine",
    "check-jsonschema",
    "playwright",
    "axe-playwright-python",
    "colorspacious",
}


def pins(path):
    """``{canonical name: version}`` of the ``name==version`` lines of a requirements file."""
    found = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        match = re.match(r"^([A-Za-z0-9][A-Za-z0-9._-]*)==([^\s;#]+)", line.strip())
        if match:
            found[canonicalize_name(match[1])] = match[2]
    return found


# --- 1. licence ------------------------------------------------------------------------------------------------


def test_licence_covers_the_code_and_the_text():
    licence = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert "MIT License" in licence and "Permission is hereby granted" in licence
    assert (
        "Creative Commons Attribution 4.0 International" in licence
        and "CC BY 4.0" in licence
    )
    assert "the twolink authors" in licence
    assert PYPROJECT["project"]["license"] == "MIT"
    assert PYPROJECT["project"]["license-files"] == ["LICENSE"], (
        "the wheel must carry LICENSE"
    )
    assert "MIT" in README and "CC BY 4.0" in README and "## How to cite" in README


# --- 2. Binder and conda ------------------------------------------------------------------------------------------


def binder_python():
    text = (ROOT / ".binder" / "runtime.txt").read_text(encoding="utf-8").strip()
    match = re.fullmatch(r"python-(3\.\d+)", text)
    assert match, (
        f".binder/runtime.txt should read python-3.X (repo2docker's form), not {text!r}"
    )
    return match[1]


def conda_python():
    match = re.search(
        r"^\s*-\s*python\s*=\s*(3\.\d+)\s*$",
        (ROOT / "environment.yml").read_text(),
        re.M,
    )
    assert match, "environment.yml should pin python=3.X"
    return match[1]


def lock_python():
    """The Python ``make lock`` ran with, from constraints.txt's header."""
    match = re.search(
        r"\(Python (3\.\d+\.\d+)\)",
        (ROOT / "constraints.txt").read_text(encoding="utf-8"),
    )
    assert match, (
        "constraints.txt's first line should name the Python it was generated with"
    )
    return match[1]


def pinned_requires_python():
    """``{name: Requires-Python}`` of every pinned distribution, read from the installed (pinned) one."""
    pinned = {
        **pins(ROOT / "constraints.txt"),
        **pins(ROOT / "requirements.txt"),
        **pins(ROOT / "requirements-dev.txt"),
    }
    found = {}
    for name, version in pinned.items():
        dist = importlib.metadata.distribution(name)
        assert dist.version == version, (
            f"{name} {dist.version} is installed, {version} is pinned: run `make install`"
        )
        found[name] = dist.metadata.get("Requires-Python") or ""
    return found


def unsupported(python, requires):
    return {
        name: spec
        for name, spec in requires.items()
        if spec and not SpecifierSet(spec).contains(python)
    }


def test_binder_and_conda_python_satisfy_every_pinned_requirement():
    """repo2docker (python-3.X) and conda (python=3.X) install the newest 3.X release: every pinned package must
    accept 3.X from the patch release the lock was made with (3.X.p) to the newest (3.X.99 stands for it)."""
    requires = pinned_requires_python()
    assert len(requires) >= 100, "constraints.txt should pin the whole environment"
    locked = lock_python()
    for where, python in [
        (".binder/runtime.txt", binder_python()),
        ("environment.yml", conda_python()),
    ]:
        assert locked.startswith(python + "."), (
            f"{where} says Python {python}, the lock was made with {locked}"
        )
        for version in (locked, f"{python}.99"):
            refused = unsupported(version, requires)
            assert not refused, f"{where}: Python {version} is refused by {refused}"
    # repo2docker's default Python (3.10) is refused by numpy 2.4, and 3.11.0 by soupsieve: the check can fail.
    assert "numpy" in unsupported("3.10.99", requires)
    assert SpecifierSet(PYPROJECT["project"]["requires-python"]).contains(locked)


def test_binder_and_conda_install_the_requirements_with_the_lock():
    binder = (ROOT / ".binder" / "requirements.txt").read_text(encoding="utf-8").split()
    assert "../requirements.txt" in binder and "../constraints.txt" in binder
    conda = (ROOT / "environment.yml").read_text(encoding="utf-8")
    assert re.search(r"-\s+-r requirements\.txt", conda) and re.search(
        r"-\s+-c constraints\.txt", conda
    )
    # At the root, an environment.yml would switch Binder to conda; .binder/ keeps it on runtime.txt + pip.
    assert (ROOT / ".binder").is_dir()


def test_readme_online_links_are_generated_from_project_urls(tmp_path):
    result = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "links.py"), "--check"],
        capture_output=True,
        text=True,
    )
    assert result.returncode == 0, result.stderr
    assert "## Run it online" in README
    # A fork changes the URL in one place and every link follows.
    fork_pyproject = tmp_path / "pyproject.toml"
    fork_pyproject.write_text(
        re.sub(
            r'Repository = "[^"]*"',
            'Repository = "https://github.com/someone/fork"',
            (ROOT / "pyproject.toml").read_text(encoding="utf-8"),
        )
    )
    fork_readme = tmp_path / "README.md"
    fork_readme.write_text(README)
    subprocess.run(
        [
            sys.executable,
            str(ROOT / "tools" / "links.py"),
            "--write",
            "--pyproject",
            str(fork_pyproject),
            "--readme",
            str(fork_readme),
        ],
        check=True,
    )
    text = fork_readme.read_text()
    assert "https://mybinder.org/v2/gh/someone/fork/main" in text
    assert (
        "https://colab.research.google.com/github/someone/fork/blob/main/notebooks/"
        in text
    )
    assert "twolink[course] @ git+https://github.com/someone/fork" in text
    stale = subprocess.run(
        [
            sys.executable,
            str(ROOT / "tools" / "links.py"),
            "--check",
            "--readme",
            str(ROOT / "README.md"),
            "--pyproject",
            str(fork_pyproject),
        ],
        capture_output=True,
        text=True,
    )
    assert stale.returncode == 1, "README links not matching the URL must be caught"


# --- 6. the lock file -------------------------------------------------------------------------------------------


def test_constraints_pin_every_package_a_clean_install_brings():
    constraints = pins(ROOT / "constraints.txt")
    direct = []
    for requirements in REQUIREMENTS:
        for name, version in pins(requirements).items():
            assert constraints.get(name) == version, (
                f"{requirements.name} pins {name}=={version}, constraints.txt {constraints.get(name)}"
            )
            direct.append(name)
    needed = _venvs.closure([*direct, *CORE])
    unpinned = {
        dist.metadata["Name"]
        for dist in needed
        if canonicalize_name(dist.metadata["Name"]) not in constraints
    }
    assert not unpinned, (
        f"not pinned in constraints.txt (run `make lock`): {sorted(unpinned)}"
    )
    for dist in needed:
        assert constraints[canonicalize_name(dist.metadata["Name"])] == dist.version


def requirement_lines(path):
    """The requirement lines of a requirements file (comments and blank lines left out)."""
    lines = (line.split("#")[0].strip() for line in path.read_text().splitlines())
    return [line for line in lines if line]


def test_every_requirement_is_pinned_exactly():
    for requirements in REQUIREMENTS:
        lines = requirement_lines(requirements)
        loose = [
            line
            for line in lines
            if not line.startswith(("-r ", "-e "))
            and canonicalize_name(re.split(r"[=<>!~\[ ;]", line)[0])
            not in pins(requirements)
        ]
        assert not loose, f"{requirements.name}: not pinned with ==: {loose}"


def test_learners_get_the_course_and_developers_the_course_and_their_tools():
    course, dev = pins(ROOT / "requirements.txt"), pins(ROOT / "requirements-dev.txt")
    assert requirement_lines(ROOT / "requirements.txt").count("-e .") == 1
    assert (
        requirement_lines(ROOT / "requirements-dev.txt")[0] == "-r requirements.txt"
    ), "requirements-dev.txt should start by including the course's requirements.txt"
    assert not DEVELOPERS_TOOLS & set(course), (
        f"requirements.txt (what make lab installs) holds developers' tools: "
        f"{sorted(DEVELOPERS_TOOLS & set(course))}"
    )
    assert DEVELOPERS_TOOLS <= set(dev), sorted(DEVELOPERS_TOOLS - set(dev))
    assert not set(course) & set(dev), "a package named in both files"
    assert {"jupyterlab", "ipykernel", "mujoco", *CORE} <= set(course)


def test_the_course_file_brings_every_module_the_chapters_import():
    """What a chapter imports (its code cells' import statements) comes with requirements.txt, not
    with the developers' tools only: the third-party modules' distributions are in its closure."""
    from importlib.metadata import packages_distributions

    imported = set()
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "code":
                source = "".join(cell["source"])
                imported |= set(
                    re.findall(r"^\s*(?:import|from)\s+(\w+)", source, re.M)
                )
    assert {"numpy", "twolink", "twolink_course"} <= imported, sorted(imported)
    providers = packages_distributions()
    third_party = {
        module: providers[module]
        for module in imported - {"twolink", "twolink_course"}
        if module not in sys.stdlib_module_names
    }
    assert "numpy" in third_party, third_party
    closure = {
        canonicalize_name(dist.metadata["Name"])
        for dist in _venvs.closure([*pins(ROOT / "requirements.txt"), *CORE])
    }
    missing = {
        module: names
        for module, names in third_party.items()
        if not {canonicalize_name(name) for name in names} & closure
    }
    assert not missing, (
        f"the chapters import these, requirements.txt does not bring them: {missing}"
    )


def test_the_extras_follow_the_requirement_files():
    extras = PYPROJECT["project"]["optional-dependencies"]
    names = {
        extra: {canonicalize_name(re.split(r"[=<>!~\[ ;]", item)[0]) for item in items}
        for extra, items in extras.items()
    }
    course = set(pins(ROOT / "requirements.txt")) - set(CORE)
    assert names["course"] == course, (
        "the course extra should name what requirements.txt adds to the core: "
        f"{sorted(names['course'] ^ course)}"
    )
    dev = set(pins(ROOT / "requirements-dev.txt"))
    assert names["dev"] == dev, sorted(names["dev"] ^ dev)
    assert names["test"] <= dev, sorted(names["test"] - dev)
    core = {
        canonicalize_name(re.split(r"[=<>!~ ;]", item)[0])
        for item in PYPROJECT["project"]["dependencies"]
    }
    assert core == set(CORE)
    assert names["mujoco"] == {"mujoco"} and names["control"] == {"control"}
    assert names["mujoco"] | names["control"] <= names["course"]


def make_dry_run(*args, env=None):
    return subprocess.run(
        ["make", "-n", "-B", "--no-print-directory", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
        env=env,
    ).stdout


def installs(dry_run):
    """The requirement files the install commands of a dry run install, in order."""
    return re.findall(
        r"pip install .*-r (requirements[\w-]*\.txt) -c constraints\.txt", dry_run
    )


def test_make_install_uses_the_lock_and_make_lock_regenerates_it():
    install = make_dry_run("install")
    assert installs(install) == ["requirements.txt"], install
    assert installs(make_dry_run("install-dev")) == [
        "requirements.txt",
        "requirements-dev.txt",
    ]
    lock = make_dry_run("lock")
    assert (
        "-m venv build/lock-venv" in lock
        and "pip install --quiet -r requirements-dev.txt" in lock
        and "pip freeze --all --exclude-editable" in lock
        and "> constraints.txt.new" in lock
    )


def test_make_lab_installs_the_course_only_and_make_test_the_developers_tools_too():
    # a learner's make lab and a teacher's make student and make grade: the course's install
    for target in ("lab", "student", "grade"):
        assert installs(make_dry_run(target)) == ["requirements.txt"], target
    for target in (
        "test",
        "portable",
        "notebooks",
        "site",
        "dist",
        "bench",
        "browser-test",
    ):
        assert installs(make_dry_run(target)) == [
            "requirements.txt",
            "requirements-dev.txt",
        ], target


def test_make_installs_with_uv_when_it_is_on_the_path_and_says_which(tmp_path):
    fake = tmp_path / "uv"
    fake.write_text("#!/bin/sh\nexit 0\n")
    fake.chmod(0o755)
    path = os.environ.get("PATH", "")
    with_uv = make_dry_run("install", env={**os.environ, "PATH": f"{tmp_path}:{path}"})
    assert re.search(
        rf"^(PYTHONWARNINGS=\x22[^\x22]*\x22 )?{re.escape(str(fake))} pip install .*--python \.venv/bin/python -r requirements\.txt -c constraints\.txt( \|\|.*)?$",
        with_uv,
        re.M,
    ), with_uv
    assert "with uv" in with_uv and "-m pip install" not in with_uv
    without = os.pathsep.join(
        folder
        for folder in path.split(os.pathsep)
        if not os.access(os.path.join(folder, "uv"), os.X_OK)
    )
    with_pip = make_dry_run("install", env={**os.environ, "PATH": without})
    assert re.search(
        r"^(PYTHONWARNINGS=\x22[^\x22]*\x22 )?\.venv/bin/python -m pip install .*-r requirements\.txt -c constraints\.txt( \|\|.*)?$",
        with_pip,
        re.M,
    ), with_pip
    assert "with pip (uv is not on the PATH" in with_pip and "uv pip" not in with_pip


# --- 7. make lab: LAB_ARGS, the start page, root ------------------------------------------------------------------


def lab_command(*args):
    lines = make_dry_run("lab", *args).splitlines()
    return [line for line in lines if "jupyter lab" in line], lines


def test_make_lab_passes_extra_jupyterlab_arguments():
    lab, _ = lab_command("LAB_ARGS=--no-browser --port 8890")
    assert lab and lab[-1].rstrip().endswith("--no-browser --port 8890"), lab


def test_make_lab_opens_the_start_page_of_the_learners_copies():
    lab, lines = lab_command()
    assert "--ServerApp.root_dir=work " in lab[-1]
    assert "--LabApp.default_url=/lab/tree/00_start_here.ipynb" in lab[-1], lab
    (copy,) = [line for line in lines if "cp " in line]
    assert lines.index(copy) < lines.index(lab[-1])


def _learners_clone(tmp_path):
    """A clone's files make lab needs to copy the chapters: the Makefile, notebooks/, .gitignore."""
    clone = tmp_path / "clone"
    (clone / "notebooks").mkdir(parents=True)
    shutil.copy(ROOT / "Makefile", clone)
    shutil.copy(ROOT / ".gitignore", clone)
    for name in ("00_start_here.ipynb", "01_dh_forward_kinematics.ipynb"):
        shutil.copy(ROOT / "notebooks" / name, clone / "notebooks")
    subprocess.run(["git", "init", "-q"], cwd=clone, check=True)
    subprocess.run(["git", "add", "-A"], cwd=clone, check=True)
    subprocess.run(
        ["git", "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-qm", "c"],
        cwd=clone,
        check=True,
    )
    return clone


def _make(clone, *args):
    return subprocess.run(
        ["make", "--no-print-directory", *args],
        cwd=clone,
        capture_output=True,
        text=True,
        check=False,
        timeout=300,
    )


def test_running_and_saving_chapters_leaves_the_clone_clean(tmp_path):
    clone = _learners_clone(tmp_path)
    # make lab's copy step, as it runs before JupyterLab starts
    copy = [line for line in lab_command()[1] if "cp " in line][0]
    subprocess.run(["sh", "-c", copy], cwd=clone, check=True)
    chapter = clone / "work" / "01_dh_forward_kinematics.ipynb"
    assert chapter.read_bytes() == (clone / "notebooks" / chapter.name).read_bytes()
    chapter.write_text("{}")  # run, edited and saved by the learner (autosave)
    status = subprocess.run(
        ["git", "status", "--porcelain"],
        cwd=clone,
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert status == "", status
    subprocess.run(["sh", "-c", copy], cwd=clone, check=True)
    assert chapter.read_text() == "{}"  # a second make lab keeps the learner's work
    done = _make(clone, "fresh", f"NOTEBOOK={chapter.name}")
    assert done.returncode == 0, done.stderr
    assert chapter.read_bytes() == (clone / "notebooks" / chapter.name).read_bytes()
    assert (clone / "work" / f"{chapter.name}~").read_text() == "{}"
    refused = _make(clone, "fresh", "NOTEBOOK=no_such_chapter.ipynb")
    assert refused.returncode == 2 and "usage: make fresh" in refused.stdout


def test_make_lab_hides_nbgrader_and_the_news_prompt():
    lab, _ = lab_command()
    for name in ("formgrader", "validate_assignment", "assignment_list", "course_list"):
        assert (
            f"--ServerApp.jpserver_extensions=nbgrader.server_extensions.{name}=False"
            in lab[-1]
        )
    settings = ROOT / "tools" / "lab_server" / "settings"
    assert f'--LabApp.app_settings_dir="{settings}"' in lab[-1]
    page_config = json.loads((settings / "page_config.json").read_text())
    assert page_config["disabledExtensions"] == {"@jupyter/nbgrader": True}
    overrides = json.loads((settings / "overrides.json").read_text())
    assert overrides["@jupyterlab/apputils-extension:notification"] == {
        "fetchNews": "false",
        "checkForUpdates": False,
    }


def _fake_python(tmp_path, version):
    """A python3 that says it is ``version`` and fails the course's version check."""
    fake = tmp_path / "python-old"
    fake.write_text(
        "#!/bin/sh\n"
        f'case "$*" in *--version*) echo "Python {version}";; *) exit 1;; esac\n'
    )
    fake.chmod(0o755)
    return fake


def test_an_old_python_is_refused_before_any_install_and_leaves_no_venv(tmp_path):
    venv = tmp_path / "venv"
    done = _make(
        ROOT, "install", f"PYTHON={_fake_python(tmp_path, '3.10.12')}", f"VENV={venv}"
    )
    assert done.returncode != 0
    assert "the course needs Python 3.11 or newer" in done.stdout
    assert (
        "Python 3.10.12" in done.stdout and "make lab PYTHON=python3.11" in done.stdout
    )
    assert "installing the course" not in done.stdout  # refused before the install
    assert not venv.exists()
    missing = _make(ROOT, "install", "PYTHON=no-such-python3", f"VENV={venv}")
    assert missing.returncode != 0 and "no-such-python3 was not found" in missing.stdout


def test_a_venv_made_by_an_old_python_is_reported_not_reused(tmp_path):
    venv = tmp_path / "venv"
    (venv / "bin").mkdir(parents=True)
    shutil.copy(_fake_python(tmp_path, "3.9.2"), venv / "bin" / "python")
    done = _make(ROOT, "install", f"VENV={venv}")
    assert done.returncode != 0
    assert f"rm -rf {venv} && make lab PYTHON=python3.11" in done.stdout, done.stdout


def _python_whose_venvs_share_its_pip(tmp_path):
    """This Python, whose ``-m venv`` makes a venv that uses the base Python's pip (and
    packages) instead of installing its own: a second, where ensurepip takes several."""
    python = tmp_path / "python-quick-venv"
    python.write_text(
        "#!/bin/sh\n"
        'if [ "$1" = -m ] && [ "$2" = venv ]; then shift 2; '
        f'exec "{sys._base_executable}" -m venv --without-pip --system-site-packages "$@"; fi\n'
        f'exec "{sys._base_executable}" "$@"\n'
    )
    python.chmod(0o755)
    return python


@pytest.mark.infrastructure
def test_a_failed_install_removes_the_venv_it_made(tmp_path, monkeypatch):
    # pip's upgrade of itself in the new venv finds no index and keeps the pip it has
    monkeypatch.setenv("PIP_CONFIG_FILE", os.devnull)
    monkeypatch.setenv("PIP_NO_INDEX", "1")
    venv = tmp_path / "venv"
    done = _make(
        ROOT,
        "install",
        f"PYTHON={_python_whose_venvs_share_its_pip(tmp_path)}",
        f"VENV={venv}",
        "INSTALL=false",
    )
    assert done.returncode != 0
    # the venv was made and pip upgraded: the install itself failed
    assert "false -r requirements.txt -c constraints.txt" in done.stdout, done.stdout
    assert "the install failed, so the new" in done.stdout, done.stdout
    assert not venv.exists()


def test_make_lab_says_why_it_allows_root():
    lab, lines = lab_command("ALLOW_ROOT=--allow-root")
    assert "--allow-root" in lab[-1]
    (note,) = [line for line in lines if "--allow-root is added" in line]
    assert "you are root" in note and "run make lab as an ordinary user" in note
    assert lines.index(note) < lines.index(lab[-1])
    lab, lines = lab_command("ALLOW_ROOT=")
    assert "--allow-root" not in "\n".join(lines)


# --- 4. the library without the course -------------------------------------------------------------------------------


def test_the_version_is_written_once():
    import twolink

    assert (
        "version" not in PYPROJECT["project"]
        and "version" in PYPROJECT["project"]["dynamic"]
    )
    assert PYPROJECT["tool"]["setuptools"]["dynamic"]["version"] == {
        "attr": "twolink.__version__"
    }
    assert importlib.metadata.version("twolink") == twolink.__version__


def course_only_imports():
    """``(file, line, module)`` of every import statement of an optional module in the library."""
    found = []
    for path in sorted((ROOT / "twolink").rglob("*.py")):
        if path.name == "_optional.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module or ""]
            found += [
                (path.relative_to(ROOT), node.lineno, name)
                for name in names
                if name.split(".")[0] in COURSE_ONLY
            ]
    return found


def test_course_only_modules_are_imported_only_through_require():
    assert not course_only_imports(), (
        "import course-only modules with twolink._optional.require(module, 'twolink.module.function'), so a user "
        f"without them learns what to install: {course_only_imports()}"
    )


@pytest.mark.parametrize("function", ["linearize", "closed_loop_system"])
def test_a_function_without_its_course_dependency_names_itself_and_the_extra(
    monkeypatch, function
):
    from twolink import arms, controllers, ik, linearization

    monkeypatch.setitem(
        sys.modules, "control", None
    )  # as if python-control were not installed
    arm = arms.two_metre
    q_rest = ik.closed_form(arm, [3.0, 1.0]).q
    impedance = controllers.Impedance(arm, 600.0, 50.0, [3.0, 1.0])
    args = (arm, impedance, q_rest) if function == "linearize" else (arm, impedance)
    with pytest.raises(
        ImportError,
        match=rf'twolink\.linearization\.{function} needs control.*pip install "twolink\[control\]"',
    ):
        getattr(linearization, function)(*args)


def small_animation():
    from twolink import arms
    from twolink_course import plot

    return plot.animate_arm(
        arms.two_metre, [[0.0, 0.0], [0.2, 0.3], [0.4, 0.6]], interval=50
    )


def test_animation_html_is_a_video_with_ffmpeg():
    from twolink_course import plot

    html = plot.animation_html(small_animation())._repr_html_()
    assert (
        "<video" in html
        and "data:video/mp4;base64," in html
        and "imageio-ffmpeg" not in html
    )


def test_animation_html_falls_back_to_javascript_without_ffmpeg(monkeypatch):
    from twolink_course import plot

    monkeypatch.setitem(sys.modules, "imageio_ffmpeg", None)
    html = plot.animation_html(small_animation())._repr_html_()
    assert "<video" not in html and "<script" in html and "animation" in html.lower()
    assert (
        "imageio-ffmpeg) is not installed" in html
        and 'pip install "twolink[course]"' in html
    )


BARE_SCRIPT = textwrap.dedent("""
    import importlib, importlib.metadata, importlib.util, pkgutil, sys
    import numpy as np
    for name in {course_only!r}:
        assert importlib.util.find_spec(name) is None, f"{{name}} is importable: the venv is not bare"
    import twolink
    assert twolink.__file__.startswith(sys.prefix), twolink.__file__
    modules = sorted(m.name for m in pkgutil.walk_packages(twolink.__path__, "twolink."))
    for name in modules:
        importlib.import_module(name)
    assert importlib.metadata.version("twolink") == twolink.__version__
    assert any(f.name == "LICENSE" for f in importlib.metadata.files("twolink"))
    from twolink import arms, controllers, ik, linearization, simulate
    try:
        import twolink_course
    except ImportError as error:
        assert 'pip install "twolink[course]"' in str(error), error
    else:
        raise AssertionError("twolink_course imported without the course's dependencies")
    arm = twolink.TwoLinkArm(l1=2.0, l2=2.0, m1=1.0, m2=1.0)
    q = ik.closed_form(arm, [3.0, 1.0], elbow="down").q
    assert np.allclose(arm.fk(q), [3.0, 1.0])
    assert np.allclose(arm.joint_torques(q, [0.0, -10.0]), arm.jacobian(q).T @ [0.0, -10.0])
    result = simulate(arm, [0.5, 0.0], [0.0, 0.0], 0.2)
    assert np.all(np.isfinite(result.q))
    impedance = controllers.Impedance(arm, 600.0, 50.0, [3.0, 1.0])
    for function, args in [(linearization.linearize, (arm, impedance, q)),
                           (linearization.closed_loop_system, (arm, impedance))]:
        try:
            function(*args)
        except ImportError as error:
            assert function.__name__ in str(error) and 'pip install "twolink[control]"' in str(error), error
        else:
            raise AssertionError(f"{{function.__name__}} worked without python-control")
    print("ok", twolink.__version__, len(modules), "modules")
""")


@pytest.mark.infrastructure
def test_the_wheel_works_with_only_the_librarys_three_dependencies(
    tmp_path, edition_wheel
):
    """The wheel, installed (dependencies checked, nothing downloaded) in a venv with numpy, scipy
    and sympy only; every library module imports, the optional functions and the course kit explain
    what to install."""
    # the student edition's (editions.build_wheel, once per test run): built from the
    # files git tracks, so a module deleted since setuptools last filled build/lib
    # cannot slip in
    wheel = edition_wheel
    try:
        python = _venvs.bare_venv(tmp_path, CORE)
    except (
        OSError,
        subprocess.CalledProcessError,
    ) as error:  # pragma: no cover - depends on the machine
        pytest.skip(f"cannot create a virtual environment here: {error}")
    installed = _venvs.pip(
        python, "install", "--no-index", "--quiet", str(wheel), cwd=tmp_path
    )
    assert installed.returncode == 0, installed.stderr[-3000:]
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    run = subprocess.run(
        [str(python), "-c", BARE_SCRIPT.format(course_only=sorted(COURSE_ONLY))],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env=env,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr[-3000:]
    assert run.stdout.startswith("ok "), run.stdout
