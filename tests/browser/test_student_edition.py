"""The student edition's first run, as a student meets it: a Jupyter without twolink.

A JupyterLab whose environment has neither twolink nor the widgets (JupyterLab,
its kernel, pip and the course's other packages, linked from this environment
by ``tests/_venvs.py``) opens chapter 1 of the unzipped edition (built once per
test run: ``student_edition_bundle`` in ``tests/conftest.py``); Run All runs the
install cell, which installs the wheel beside it and the widgets (offline, from
``widget_wheels``: real wheels, whose JupyterLab extensions pip writes into the
environment) and prints the one line that says to reload; after the reload, Run
All shows the chapter's explorer, and the chapter is checked as a student uses it
(``check_the_chapter_as_run``: its sliders move its figure, drawn complete, its
animations play, axe-core on what the course puts in it).  This is the one chapter
``make test`` runs whole in JupyterLab.
"""

import os
import pathlib
import re
import secrets
import subprocess
import sys
import time
import urllib.request
import zipfile

import pytest

from .conftest import ROOT, lab_browser
from .test_chapters_in_jupyterlab import (
    accept_kernel_dialog,
    assert_no_error_output,
    check_the_chapter_as_run,
    run_all_cells,
    wait_for_all_cells,
    wait_until_idle,
)

sys.path.insert(0, str(ROOT / "tests"))
import _venvs  # noqa: E402
import install_cell  # noqa: E402

CHAPTER = "01_dh_forward_kinematics.ipynb"


def _serve(python, folder, home, pip_environment):
    """JupyterLab from ``python``'s environment on ``folder``, its kernels' pip offline
    (``pip_environment``); returns (server, url, token)."""
    import jupyterlab

    token = secrets.token_hex(16)
    port = lab_browser.free_port()
    env = {
        key: value
        for key, value in os.environ.items()
        if key != "MPLBACKEND" and not key.startswith("PIP_")
    }
    env.update(pip_environment)
    for name in (
        "JUPYTER_CONFIG_DIR",
        "JUPYTER_RUNTIME_DIR",
        "JUPYTERLAB_SETTINGS_DIR",
    ):
        env[name] = str(home / name.lower())
    env["JUPYTER_DATA_DIR"] = str(
        home / "data"
    )  # no labextension of this machine's user
    settings = pathlib.Path(env["JUPYTERLAB_SETTINGS_DIR"])
    for name, values in lab_browser.LAB_SETTINGS.items():
        (settings / name).parent.mkdir(parents=True, exist_ok=True)
        (settings / name).write_text(__import__("json").dumps(values))
    # JupyterLab's own page files (its data files live in this environment's prefix)
    app_dir = pathlib.Path(jupyterlab.__file__).parents[4] / "share" / "jupyter" / "lab"
    log = open(home / "server.log", "w")
    server = lab_browser.PROCESS_GROUPS.start(
        [
            str(python),
            "-m",
            "jupyterlab",
            "--no-browser",
            "--allow-root",
            "--ServerApp.ip=127.0.0.1",
            f"--ServerApp.port={port}",
            f"--IdentityProvider.token={token}",
            f"--ServerApp.root_dir={folder}",
            f"--LabApp.app_dir={app_dir}",
            "--LabApp.news_url=",
        ],
        env=env,
        cwd=home,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    url = f"http://127.0.0.1:{port}"
    deadline = time.monotonic() + 90
    while True:
        try:
            urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2).close()
            break
        except OSError:
            if server.poll() is not None or time.monotonic() > deadline:
                lab_browser.PROCESS_GROUPS.stop(server)
                raise RuntimeError((home / "server.log").read_text()[-2000:]) from None
            time.sleep(0.5)
    return server, url, token


@pytest.mark.infrastructure
@pytest.mark.browser
def test_the_editions_first_run_installs_then_says_to_reload_and_then_shows_sliders(
    tmp_path, page, student_edition_bundle, widget_wheels
):
    with zipfile.ZipFile(student_edition_bundle[-1]) as bundle:
        bundle.extractall(tmp_path / "away")
    edition = tmp_path / "away" / "student"
    python = _venvs.bare_venv(
        tmp_path,
        [*_venvs.requirements("twolink", "course"), "pip"],
        without=["twolink", *widget_wheels.names],
    )
    # away from the repository, whose folder would put its twolink on sys.path
    probe = subprocess.run(
        [str(python), "-c", "import twolink"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert "No module named 'twolink'" in probe.stderr
    widgets = subprocess.run(
        [str(python), "-c", "import jupyterlab_widgets"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    assert widgets.returncode != 0, "the student's Jupyter must lack the widgets"

    home = tmp_path / "home"
    home.mkdir()
    server, url, token = _serve(python, edition, home, widget_wheels.pip_environment())
    try:
        page.goto(f"{url}/lab/tree/{CHAPTER}?token={token}")
        panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
        panel.locator(".jp-Cell").first.wait_for(timeout=120_000)
        accept_kernel_dialog(page)
        wait_until_idle(page, 120_000)
        run_all_cells(page)
        wait_for_all_cells(page, 300_000)  # the install (offline) and the chapter
        wait_until_idle(page, 300_000)
        first_output = panel.locator(".jp-CodeCell").first.locator(".jp-OutputArea")
        said = first_output.inner_text()
        assert install_cell.RELOAD_LINE in said, said
        assert (
            panel.locator(".twolink-explorer").count() == 0
        )  # no sliders before the reload

        # as the line says: reload, then Run All in the same kernel (outputs cleared
        # first, so that the wait below is for this run's prompts)
        page.reload()
        panel.locator(".jp-Cell").first.wait_for(timeout=120_000)
        accept_kernel_dialog(page)
        wait_until_idle(page, 120_000)
        page.locator(".lm-MenuBar-itemLabel", has_text=re.compile(r"^Edit$")).click()
        page.locator(
            ".lm-Menu-itemLabel", has_text=re.compile(r"^Clear Outputs of All Cells$")
        ).click()
        page.wait_for_function(
            """() => [...document.querySelectorAll(
                '.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell .jp-InputPrompt')]
                .every(p => !/\\[\\d+\\]/.test(p.innerText))""",
            timeout=60_000,
        )
        assert panel.locator(".twolink-explorer").count() == 0
        run_all_cells(page)
        wait_for_all_cells(page, 300_000)
        wait_until_idle(page, 300_000)
        explorers = panel.locator(".twolink-explorer")
        explorers.first.locator("canvas").first.wait_for(timeout=60_000)
        assert explorers.first.locator(".widget-slider").count() >= 1
        assert_no_error_output(panel, CHAPTER)
        # the repository's chapter: its code and its explorers' stored first states
        check_the_chapter_as_run(page, panel, ROOT / "notebooks" / CHAPTER)
    finally:
        lab_browser.PROCESS_GROUPS.stop(server)
