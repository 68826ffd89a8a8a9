"""Fixtures for the browser suite: a private JupyterLab server and a headless Chromium.

The server and the browser come from ``tools/lab_browser.py`` (shared with
``benchmarks/bench_widgets.py``): Debian's Chromium at /usr/bin/chromium
(``apt-get install -y chromium``) and the ``playwright`` Python package; a
browser is never downloaded.  Without them every browser test is skipped with
the reason.  Server and browser are always shut down, even when a test fails;
the server's process group and its kernels are also killed when pytest is
interrupted (SIGINT), terminated (SIGTERM) or exits without running the
fixture's teardown (``PROCESS_GROUPS``).
"""

import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

import lab_browser  # noqa: E402

SCREENSHOTS = ROOT / "build" / "screenshots"
PROCESS_GROUPS = lab_browser.PROCESS_GROUPS


def pytest_collection_modifyitems(config, items):
    reason = lab_browser.missing()
    for item in items:
        if "browser" in item.keywords and reason:
            item.add_marker(pytest.mark.skip(reason=reason))


@pytest.fixture(scope="session")
def browser():
    with lab_browser.chromium() as chromium:
        yield chromium


@pytest.fixture()
def page(browser):
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    try:
        yield page
    finally:
        context.close()


@pytest.fixture(scope="session")
def jupyterlab(tmp_path_factory):
    """A JupyterLab server on 127.0.0.1 serving a copy of the notebooks; yields its base URL and token."""
    with lab_browser.jupyterlab(tmp_path_factory.mktemp("jupyterlab")) as lab:
        yield lab
