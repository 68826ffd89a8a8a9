"""Every chapter, used as a student uses it: JupyterLab in Chromium, Run All, play.

For each notebook: open it, Run All Cells from the menu, wait for the kernel to
go idle, then assert there is no error or stderr output, every interactive
explorer the notebook builds (``twolink.explorer.Explorer``) is rendered,
moving each of its sliders with the keyboard changes its readout and the
pixels of its figure, and every animation is present
and plays.  A screenshot per chapter goes to build/screenshots/.
"""

import json
import re

import pytest

from .conftest import ROOT, SCREENSHOTS, lab_browser

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


def expected_widgets(path):
    source = "\n".join(
        "".join(cell["source"])
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]
        if cell["cell_type"] == "code"
    )
    return source.count("explorer.Explorer("), source.count("animation_html(")


def wait_until_idle(page, timeout_ms):
    page.wait_for_function(
        """() => {
            const bar = document.querySelector('#jp-main-statusbar');
            return bar && /\\|\\s*Idle/.test(bar.innerText);
        }""",
        timeout=timeout_ms,
    )


def accept_kernel_dialog(page):
    dialog = page.locator(".jp-Dialog .jp-mod-accept")
    if dialog.count():
        dialog.first.click()


def run_all_cells(page):
    page.locator(".lm-MenuBar-itemLabel", has_text=re.compile(r"^Run$")).click()
    page.locator(".lm-Menu-itemLabel", has_text=re.compile(r"^Run All Cells$")).click()


def wait_for_all_cells(page, timeout_ms):
    page.wait_for_function(
        """() => {
            const prompts = [...document.querySelectorAll('.jp-NotebookPanel:not(.lm-mod-hidden) .jp-CodeCell .jp-InputPrompt')];
            return prompts.length > 0 && prompts.every(p => /\\[\\d+\\]/.test(p.innerText));
        }""",
        timeout=timeout_ms,
    )


# A signature of what an explorer shows: the pixels of its canvases (ipympl).
PICTURE = """box => {
    let hash = 0;
    for (const canvas of box.querySelectorAll('canvas')) {
        if (!canvas.width || !canvas.height) continue;
        const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
        for (let i = 0; i < data.length; i += 4) hash = (hash * 31 + data[i] + data[i + 1] + data[i + 2]) | 0;
    }
    return hash;
}"""


def picture(container):
    return container.evaluate(PICTURE)


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_chapter_runs_and_plays_in_jupyterlab(jupyterlab, page, path):
    try:
        run_chapter(jupyterlab, page, path)
    finally:
        lab_browser.shut_down_kernels(jupyterlab)


def run_chapter(jupyterlab, page, path):
    # a workspace of its own, so tabs of earlier chapters are not restored
    page.goto(
        f"{jupyterlab['url']}/lab/workspaces/{path.stem}/tree/{path.name}?reset&token={jupyterlab['token']}"
    )
    panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
    panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
    accept_kernel_dialog(page)
    wait_until_idle(page, 90_000)
    run_all_cells(page)
    wait_for_all_cells(page, 300_000)
    wait_until_idle(page, 300_000)

    errors = panel.locator("[data-mime-type='application/vnd.jupyter.error']")
    assert errors.count() == 0, (
        f"{path.name}: error output: {errors.first.inner_text()[:500]}"
    )
    stderr = panel.locator("[data-mime-type='application/vnd.jupyter.stderr']")
    assert stderr.count() == 0, (
        f"{path.name}: stderr output: {stderr.first.inner_text()[:500]}"
    )

    interactive_count, animation_count = expected_widgets(path)
    containers = panel.locator(".twolink-explorer")
    assert containers.count() == interactive_count, (
        f"{path.name}: {containers.count()} explorers rendered, {interactive_count} built"
    )
    moved = []
    for index in range(containers.count()):
        container = containers.nth(index)
        sliders = container.locator(".widget-slider")
        assert sliders.count() >= 1, (
            f"{path.name}: interactive widget {index} has no slider"
        )
        container.scroll_into_view_if_needed()
        sentence = container.locator(".widget-html-content").last
        sentence_before = sentence.inner_text()
        assert sentence_before.strip(), (
            f"{path.name}: explorer {index} shows no sentence under its figure"
        )
        for slider_index in range(sliders.count()):
            slider = sliders.nth(slider_index)
            readout = slider.locator(".widget-readout")
            before_value = readout.inner_text()
            before_figure = picture(container)
            slider.locator(".noUi-handle").first.focus()
            page.keyboard.press("ArrowRight")
            if (
                readout.inner_text() == before_value
            ):  # at the top of its range: go the other way
                page.keyboard.press("ArrowLeft")
                page.keyboard.press("ArrowLeft")
            page.wait_for_function(
                "([element, value]) => element.innerText !== value",
                arg=[readout.element_handle(), before_value],
                timeout=10_000,
            )
            page.wait_for_function(
                f"([box, before]) => ({PICTURE})(box) !== before",
                arg=[container.element_handle(), before_figure],
                timeout=30_000,
            )
            moved.append(
                f"{index}:{slider.locator('.widget-label').first.inner_text()}"
            )
        # the text alternative follows the figure once the hand stops
        page.wait_for_function(
            "([element, value]) => element.innerText !== value",
            arg=[sentence.element_handle(), sentence_before],
            timeout=10_000,
        )
    assert len(moved) >= interactive_count

    videos = panel.locator(".jp-OutputArea-output video")
    assert videos.count() >= animation_count, (
        f"{path.name}: {videos.count()} videos, {animation_count} animations built"
    )
    for index in range(videos.count()):
        state = videos.nth(index).evaluate(
            """async video => {
                video.muted = true;
                if (video.readyState < 1) {
                    await new Promise(resolve => { video.onloadedmetadata = resolve; setTimeout(resolve, 10000); });
                }
                await video.play();
                await new Promise(resolve => setTimeout(resolve, 600));
                const result = {duration: video.duration, time: video.currentTime, error: video.error && video.error.code};
                video.pause();
                return result;
            }"""
        )
        assert state["error"] is None and state["duration"] > 0 and state["time"] > 0, (
            f"{path.name}: video {index} {state}"
        )

    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    if containers.count():
        containers.first.scroll_into_view_if_needed()
    page.screenshot(path=str(SCREENSHOTS / f"{path.stem}.png"))
    print(
        f"{path.name}: {containers.count()} explorers, sliders moved {moved}, {videos.count()} videos played"
    )
