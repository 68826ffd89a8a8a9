"""A chapter, used as a student uses it: JupyterLab in Chromium, Run All, play.

For the chapter (``RUN_IN_JUPYTERLAB``): open it, Run All Cells from the menu, wait for the kernel to
go idle, then assert there is no error or stderr output, every interactive
explorer the notebook builds (``twolink_course.explorer.Explorer``) is rendered,
moving each of its sliders with the keyboard changes its readout and the
pixels of its figure, each explorer is drawn complete after its moves, and
every animation is present and plays.  Chapter 5 (``ALSO_DRAWN_COMPLETE``), whose
explorer once stayed blank after Run All, is run and moved for the completeness
check alone.  Screenshots go to build/screenshots/.
"""

import base64
import json
import os
import re

import a11y  # tools/a11y.py: tools/ is on the path (tests/browser/conftest.py, loaded first)
import pytest

from .conftest import ROOT, SCREENSHOTS, lab_browser

#: The one chapter run in JupyterLab: the quickest with an explorer and a video.  What
#: JupyterLab adds (widgets that render and follow a hand, videos that play, axe on
#: the notebook) is the kit's, the same in every chapter; each chapter's own prose and
#: outputs are checked by axe on its static page (tests/browser/test_static_site.py),
#: its explorers moved to their ends in its kernel (notebooks/NN_x.ipynb::figures).
RUN_IN_JUPYTERLAB = [ROOT / "notebooks" / "04_statics_wall.ipynb"]

#: Also run in JupyterLab, for its explorers' completeness after Run All and a move
#: alone: chapter 5's explorer was the one that stayed blank (the page's draw request
#: ran while a move changed the canvas), its curves move the most.
#: ``TWOLINK_BROWSER_EVERY_CHAPTER=1`` checks every other chapter's explorers too (a
#: release check: about a minute a chapter).
ALSO_DRAWN_COMPLETE = (
    [
        path
        for path in sorted((ROOT / "notebooks").glob("0[1-9]_*.ipynb"))
        if path not in RUN_IN_JUPYTERLAB
    ]
    if os.environ.get("TWOLINK_BROWSER_EVERY_CHAPTER") == "1"
    else [ROOT / "notebooks" / "05_lagrangian_dynamics.ipynb"]
)


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


# An explorer's canvas as the page shows it (ipympl draws the figure on its first <canvas>).
CANVAS_PNG = """box => box.querySelector('.jupyter-matplotlib-canvas-div canvas').toDataURL('image/png')"""

#: Of the dark pixels (text, axes, ticks, lines) of an explorer's stored first
#: state, the share that must be dark (within a pixel) in the page's canvas after
#: its moves.  Complete pictures kept 0.76 (chapter 5, whose curves move most)
#: to 0.97 in every chapter; a blank canvas keeps 0, and the picture of the bug
#: (the axes' white background with only the moved artists on it) keeps only
#: what the moved artists happen to cover.
KEPT_INK = 0.6


def stored_explorer_pictures(path):
    """The first-state PNG each explorer stored beside its widgets, in order."""
    pictures = []
    for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
        for output in cell.get("outputs", []):
            data = output.get("data", {})
            if WIDGET_VIEW in data and "image/png" in data:
                pictures.append(data["image/png"])
    return pictures


def _ink(image):
    """Dark pixels of an RGBA picture on white: luminance below 160 of 255."""
    import numpy as np

    pixels = np.asarray(image.convert("RGBA"), dtype=float)
    alpha = pixels[..., 3:4] / 255.0
    rgb = pixels[..., :3] * alpha + 255.0 * (1.0 - alpha)  # on the page's white
    return rgb @ np.array([0.299, 0.587, 0.114]) < 160.0


def kept_ink(stored_png_base64, canvas_data_url):
    """The share of the stored picture's dark pixels that are dark in the canvas too."""
    import base64
    import io

    import numpy as np
    from PIL import Image

    stored = Image.open(io.BytesIO(base64.b64decode(stored_png_base64)))
    shown = Image.open(io.BytesIO(base64.b64decode(canvas_data_url.split(",", 1)[1])))
    stored = stored.convert("RGBA").resize(shown.size, Image.Resampling.BOX)
    ink, shown_ink = _ink(stored), _ink(shown)
    # a pixel of the static draw counts as kept when the canvas is dark within one
    # pixel of it (the page's 1x drawing and the stored 2x picture, halved, differ in
    # anti-aliasing by a pixel)
    near = shown_ink.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near |= np.roll(np.roll(shown_ink, dy, axis=0), dx, axis=1)
    return float((ink & near).sum() / max(1, ink.sum()))


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.parametrize(
    "path", RUN_IN_JUPYTERLAB, ids=[path.name for path in RUN_IN_JUPYTERLAB]
)
def test_chapter_runs_and_plays_in_jupyterlab(jupyterlab, page, path):
    try:
        run_chapter(jupyterlab, page, path)
    finally:
        lab_browser.shut_down_kernels(jupyterlab)


def open_and_run_all(jupyterlab, page, path):
    """Open the server's copy of a chapter, Run All, wait for idle; no error or stderr output."""
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
    return panel


def move_every_slider(page, panel, path):
    """Each explorer rendered; each slider moved by a key changes its readout, picture and sentence."""
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    interactive_count, _ = expected_widgets(path)
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
    return containers, moved


def assert_drawn_complete(path, containers):
    """Each explorer's canvas after its moves keeps its static draw's axes, labels and legend."""
    # every explorer complete after its moves: the axes, labels and legend of its
    # static draw (the first state stored beside the widgets) are in the page's canvas
    stored = stored_explorer_pictures(path)
    assert len(stored) == containers.count(), (path.name, len(stored))
    for index in range(containers.count()):
        container = containers.nth(index)
        container.scroll_into_view_if_needed()
        canvas_png = container.evaluate(CANVAS_PNG)
        share = kept_ink(stored[index], canvas_png)
        (SCREENSHOTS / f"{path.stem}-explorer-{index}-canvas.png").write_bytes(
            base64.b64decode(canvas_png.split(",", 1)[1])
        )
        container.screenshot(
            path=str(SCREENSHOTS / f"{path.stem}-explorer-{index}.png")
        )
        print(
            f"{path.name}: explorer {index} keeps {share:.2f} of its static draw's ink"
        )
        assert share >= KEPT_INK, (
            f"{path.name}: explorer {index} shows {share:.2f} of its figure's axes, labels "
            f"and legend after a move (at least {KEPT_INK} expected): screenshot in {SCREENSHOTS}"
        )


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.parametrize(
    "path", ALSO_DRAWN_COMPLETE, ids=[path.name for path in ALSO_DRAWN_COMPLETE]
)
def test_explorers_are_drawn_complete_after_run_all_and_a_move(jupyterlab, page, path):
    try:
        panel = open_and_run_all(jupyterlab, page, path)
        containers, moved = move_every_slider(page, panel, path)
        assert_drawn_complete(path, containers)
        print(f"{path.name}: {containers.count()} explorers, sliders moved {moved}")
    finally:
        lab_browser.shut_down_kernels(jupyterlab)


def run_chapter(jupyterlab, page, path):
    panel = open_and_run_all(jupyterlab, page, path)
    containers, moved = move_every_slider(page, panel, path)
    assert_drawn_complete(path, containers)
    _, animation_count = expected_widgets(path)

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

    # axe-core on what the course puts in the notebook (prose and outputs): no critical
    # or serious violation; what it finds in JupyterLab's own interface is printed
    course_parts = [
        f".jp-NotebookPanel:not(.lm-mod-hidden) {part}"
        for part in (".jp-RenderedMarkdown", ".jp-OutputArea")
    ]
    in_course = a11y.violations(page, include=course_parts)
    assert not a11y.blocking(in_course), (path.name, a11y.blocking(in_course))
    course_rules = {violation["id"] for violation in in_course}
    in_jupyterlab = [
        f"{violation['id']} ({violation['impact']}, {len(violation['nodes'])})"
        for violation in a11y.violations(page)
        if violation["id"] not in course_rules
    ]
    print(f"{path.name}: axe in JupyterLab's own interface: {in_jupyterlab}")

    if containers.count():
        containers.first.scroll_into_view_if_needed()
    page.screenshot(path=str(SCREENSHOTS / f"{path.stem}.png"))
    print(
        f"{path.name}: {containers.count()} explorers, sliders moved {moved}, {videos.count()} videos played"
    )


# --- figures' text alternatives (labextension/: twolink-figure-alt) -----------------------

IMAGE_TYPES = ("image/png", "image/jpeg", "image/gif")
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"


def image_outputs(notebook):
    """``(mime type, alt or None)`` of each stored output JupyterLab shows as a bitmap, in order.

    Outputs with one image type besides text/plain and a widget view: a
    notebook opened from disk is untrusted, and JupyterLab then shows an
    explorer's PNG fallback, not the (unsafe) widget renderer.  alt is the
    output's ``metadata[mime type]["alt"]`` when that is a string.
    """
    found = []
    for cell in notebook["cells"]:
        for output in cell.get("outputs", []):
            shown = set(output.get("data", {})) - {"text/plain", WIDGET_VIEW}
            if len(shown) == 1 and (mime := shown.pop()) in IMAGE_TYPES:
                alt = output.get("metadata", {}).get(mime, {}).get("alt")
                found.append((mime, alt if isinstance(alt, str) else None))
    return found


def probe_notebook():
    """Stored image outputs: with an alt, without metadata, with a non-string or empty alt."""
    import base64
    import io

    import nbformat
    from PIL import Image

    def encoded(fmt):
        buffer = io.BytesIO()
        Image.new("RGB", (12, 8), "#1f77b4").save(buffer, format=fmt)
        return base64.b64encode(buffer.getvalue()).decode()

    def output(mime, metadata=None, kind="display_data"):
        fmt = mime.split("/")[1].upper()
        data = {mime: encoded(fmt), "text/plain": "<Figure>"}
        if kind == "execute_result":
            return nbformat.v4.new_output(
                kind, data=data, metadata=metadata or {}, execution_count=1
            )
        return nbformat.v4.new_output(kind, data=data, metadata=metadata or {})

    alt = 'The arm at q = (30°, 45°): "tip" at x < 0.12 m & y > 0.16 m.'
    outputs = [
        output("image/png", {"image/png": {"width": 120, "height": 80, "alt": alt}}),
        output("image/png"),
        output("image/png", {"image/png": {"width": 120, "height": 80}}),
        output("image/png", {"image/png": {"alt": 3}}),
        output("image/png", {"image/png": {"alt": ""}}),
        output("image/jpeg", {"image/jpeg": {"alt": "A JPEG figure."}}),
        output("image/gif", {"image/gif": {"alt": "A GIF figure."}}),
        output("image/png", {"image/png": {"alt": "Returned."}}, "execute_result"),
    ]
    cells = [nbformat.v4.new_code_cell("figure", outputs=[item]) for item in outputs]
    kernel = {"name": "python3", "display_name": "Python 3", "language": "python"}
    return nbformat.v4.new_notebook(cells=cells, metadata={"kernelspec": kernel})


RENDERED_IMAGES = """() => [...document.querySelectorAll(
    '.jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea-output[data-mime-type^="image/"]'
)].filter(node => node.querySelector('img')).map(node => {
    const img = node.querySelector('img');
    return [node.dataset.mimeType, img.getAttribute('alt'), img.getAttribute('width')];
})"""


def rendered_images(jupyterlab, page, name, count):
    """``[mime type, alt attribute or None, width attribute or None]`` of each image output of a notebook."""
    page.goto(
        f"{jupyterlab['url']}/lab/workspaces/alt-{name.removesuffix('.ipynb')}"
        f"/tree/{name}?reset&token={jupyterlab['token']}"
    )
    panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
    panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
    accept_kernel_dialog(page)
    page.wait_for_function(
        f"() => ({RENDERED_IMAGES})().length >= {count}", timeout=60_000
    )
    return page.evaluate(RENDERED_IMAGES)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_image_outputs_carry_their_alt_text_in_jupyterlab(jupyterlab, page):
    """Stored outputs, not run: each <img> has exactly its output's metadata alt, or no alt."""
    import nbformat

    try:
        page.goto(f"{jupyterlab['url']}/lab?token={jupyterlab['token']}")
        config = json.loads(page.locator("#jupyter-config-data").text_content())
        names = [ext["name"] for ext in config.get("federated_extensions", [])]
        assert "twolink-figure-alt" in names, (
            f"JupyterLab did not load twolink-figure-alt (run `make install`): {names}"
        )

        probe = probe_notebook()
        nbformat.write(probe, jupyterlab["notebooks"] / "alt_probe.ipynb")
        expected = image_outputs(probe)
        rendered = rendered_images(jupyterlab, page, "alt_probe.ipynb", len(expected))
        assert [(mime, alt) for mime, alt, _ in rendered] == expected
        assert expected[0][1].startswith("The arm") and expected[1][1] is None
        assert expected[4] == ("image/png", "")  # an empty alt (decorative) is kept
        # width and height stay JupyterLab's: from the metadata, as before
        assert [width for *_, width in rendered[:3]] == ["120", None, "120"]

        # the server's copy of chapter 1, as it was when the server started
        chapter = jupyterlab["notebooks"] / "01_dh_forward_kinematics.ipynb"
        expected = image_outputs(json.loads(chapter.read_text(encoding="utf-8")))
        assert any(alt for _, alt in expected), f"{chapter.name}: no figure has alt"
        rendered = rendered_images(jupyterlab, page, chapter.name, len(expected))
        assert [(mime, alt) for mime, alt, _ in rendered] == expected
    finally:
        lab_browser.shut_down_kernels(jupyterlab)


# --- slider handles named by their description (labextension/: src/a11y.ts) ---------------


def slider_probe_notebook():
    """A slider with a description, a range slider (two handles), a slider without one, a wide and a narrow LaTeX output."""
    import nbformat

    sources = [
        'import ipywidgets\nq1 = ipywidgets.IntSlider(description="q1 [deg]")\nq1',
        'span = ipywidgets.FloatRangeSlider(description="span [m]")\nspan',
        "bare = ipywidgets.IntSlider()\nbare",
        'from IPython.display import Latex\nLatex("$$" + " + ".join(f"x_{{{i}}}" for i in range(120)) + "$$")',
        'Latex("$$a + b$$")',
    ]
    kernel = {"name": "python3", "display_name": "Python 3", "language": "python"}
    return nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source) for source in sources],
        metadata={"kernelspec": kernel},
    )


@pytest.mark.infrastructure
@pytest.mark.browser
def test_slider_handles_are_named_by_their_description_in_jupyterlab(jupyterlab, page):
    """ipywidgets' noUiSlider handles (role=slider) take the widget's description as their name.

    A slider without a description stays unnamed (nothing is invented); a
    LaTeX output wider than the notebook is a tab stop whose arrow keys
    scroll it, a narrow one is not.
    """
    import nbformat

    try:
        nbformat.write(
            slider_probe_notebook(), jupyterlab["notebooks"] / "slider_probe.ipynb"
        )
        page.goto(
            f"{jupyterlab['url']}/lab/workspaces/slider-probe/tree/slider_probe.ipynb"
            f"?reset&token={jupyterlab['token']}"
        )
        panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
        panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
        accept_kernel_dialog(page)
        wait_until_idle(page, 90_000)
        run_all_cells(page)
        wait_for_all_cells(page, 120_000)
        wait_until_idle(page, 120_000)
        panel.locator(".noUi-handle").nth(3).wait_for(timeout=30_000)

        q1 = page.get_by_role("slider", name="q1 [deg]", exact=True)
        assert q1.count() == 1
        label = panel.locator(".widget-label", has_text="q1 [deg]")
        assert q1.get_attribute("aria-labelledby") == label.get_attribute("id")
        assert page.get_by_role("slider", name="span [m]", exact=True).count() == 2
        handles = panel.locator(".noUi-handle")
        assert handles.count() == 4
        unnamed = handles.nth(3)
        assert [
            unnamed.get_attribute(name) for name in ("aria-labelledby", "aria-label")
        ] == [None, None]
        # the handle still works as before: the keyboard moves it
        q1.focus()
        page.keyboard.press("ArrowRight")
        assert q1.get_attribute("aria-valuenow") == "1.0"

        wide, narrow = panel.locator("[data-mime-type='text/latex']").all()
        page.wait_for_function(
            "e => e.getAttribute('tabindex') === '0'",
            arg=wide.element_handle(),
            timeout=10_000,
        )
        assert narrow.get_attribute("tabindex") is None
        wide.focus()
        page.keyboard.press("ArrowRight")
        page.wait_for_function(
            "e => e.scrollLeft > 0", arg=wide.element_handle(), timeout=5_000
        )

        # the name follows the description; an emptied description (ipywidgets
        # hides the label, keeping its old text) names nothing
        panel.locator(".jp-Cell").last.click()
        page.keyboard.press("Escape")
        page.keyboard.press("b")
        page.keyboard.press("Enter")
        page.keyboard.type('q1.description = ""; bare.description = "q2 [deg]"')
        page.keyboard.press("Shift+Enter")
        page.get_by_role("slider", name="q2 [deg]", exact=True).wait_for(timeout=30_000)
        page.wait_for_function(
            "e => !e.hasAttribute('aria-labelledby')",
            arg=handles.first.element_handle(),
            timeout=10_000,
        )
        parts = [".jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea"]
        found = [
            v
            for v in a11y.violations(page, include=parts)
            if v["id"] == "aria-input-field-name"
        ]
        assert [len(v["nodes"]) for v in found] == [1]  # q1, now without a description
    finally:
        lab_browser.shut_down_kernels(jupyterlab)


# --- animations: described, and still for readers who ask for reduced motion ------------


def video_probe_notebook():
    """One animation of the course's kit, as a chapter shows it."""
    import nbformat

    source = (
        "import numpy as np\n"
        "from twolink import arms\n"
        "from twolink_course import plot\n"
        "plot.animation_html(plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.0, 1.0], 8)))"
    )
    kernel = {"name": "python3", "display_name": "Python 3", "language": "python"}
    return nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source)], metadata={"kernelspec": kernel}
    )


VIDEO_STATES = """() => [...document.querySelectorAll(
    '.jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea-output video'
)].map(video => ({
    paused: video.paused, time: video.currentTime, autoplay: video.autoplay,
    label: video.closest('[role=figure]') && video.closest('[role=figure]').getAttribute('aria-label'),
}))"""


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.parametrize("reduced_motion", ["reduce", "no-preference"])
def test_videos_are_described_and_hold_still_for_reduced_motion_in_jupyterlab(
    jupyterlab, browser, reduced_motion
):
    import nbformat

    name = f"video_probe_{reduced_motion}.ipynb"
    nbformat.write(video_probe_notebook(), jupyterlab["notebooks"] / name)
    context = browser.new_context(
        viewport={"width": 1400, "height": 1000}, reduced_motion=reduced_motion
    )
    try:
        page = context.new_page()
        page.goto(
            f"{jupyterlab['url']}/lab/workspaces/video-{reduced_motion}/tree/{name}"
            f"?reset&token={jupyterlab['token']}"
        )
        panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
        panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
        accept_kernel_dialog(page)
        wait_until_idle(page, 90_000)
        run_all_cells(page)
        panel.locator(".jp-OutputArea-output video").first.wait_for(timeout=120_000)
        page.wait_for_timeout(1500)
        (video,) = page.evaluate(VIDEO_STATES)
        # the text alternative, generated from the animation's data
        assert (
            video["label"] and "An animation of the arm in 8 frames" in video["label"]
        )
        if reduced_motion == "reduce":
            assert video["paused"] and video["time"] == 0 and not video["autoplay"], (
                video
            )
        else:
            assert video["autoplay"] and not video["paused"] and video["time"] > 0, (
                video
            )
    finally:
        context.close()
        lab_browser.shut_down_kernels(jupyterlab)


# --- choices: their labels in the label column, their buttons on the same row ------------


@pytest.mark.infrastructure
@pytest.mark.browser
def test_a_choices_label_sits_in_the_label_column_beside_its_buttons(jupyterlab, page):
    import nbformat

    source = (
        "import ipywidgets\n"
        "from twolink_course import explorer\n"
        "ipywidgets.VBox([explorer.slider('q1', 'deg', 0, -90, 90, 5), "
        "explorer.choice('elbow', ['either', 'down', 'up'], 'either')])"
    )
    kernel = {"name": "python3", "display_name": "Python 3", "language": "python"}
    notebook = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_code_cell(source)], metadata={"kernelspec": kernel}
    )
    nbformat.write(notebook, jupyterlab["notebooks"] / "choice_probe.ipynb")
    try:
        page.goto(
            f"{jupyterlab['url']}/lab/workspaces/choice-probe/tree/choice_probe.ipynb"
            f"?reset&token={jupyterlab['token']}"
        )
        panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
        panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
        accept_kernel_dialog(page)
        wait_until_idle(page, 90_000)
        run_all_cells(page)
        panel.locator(".widget-toggle-buttons button").last.wait_for(timeout=60_000)
        boxes = page.evaluate(
            """() => {
                const box = e => { const r = e.getBoundingClientRect(); return {left: r.left, right: r.right, top: r.top, bottom: r.bottom}; };
                const slider = document.querySelector('.widget-slider .widget-label');
                const choice = document.querySelector('.widget-toggle-buttons .widget-label');
                const buttons = [...document.querySelectorAll('.widget-toggle-buttons button')].map(box);
                return {slider: box(slider), choice: box(choice), buttons};
            }"""
        )
        slider, choice, buttons = boxes["slider"], boxes["choice"], boxes["buttons"]
        assert abs(choice["right"] - slider["right"]) <= 2, (
            boxes
        )  # one label column (2 px: margins)
        assert all(button["left"] >= choice["right"] - 1 for button in buttons), boxes
        rows = {round(button["top"]) for button in buttons}
        assert len(rows) == 1, boxes  # the buttons on one row
        assert choice["bottom"] > min(rows) and choice["top"] < buttons[0]["bottom"], (
            boxes
        )
    finally:
        lab_browser.shut_down_kernels(jupyterlab)
