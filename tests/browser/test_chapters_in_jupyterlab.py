"""A chapter, used as a student uses it: JupyterLab in Chromium, Run All, play;
and the course's JupyterLab extension on a probe notebook.

For a chapter: open it and check that its stored figures carry their alt text,
Run All Cells from the menu, wait for the kernel to go idle, then assert there is
no error or stderr output and (:func:`check_the_chapter_as_run`) every interactive
explorer the notebook builds (``twolink_course.explorer.Explorer``) is rendered,
moving each of its sliders with the keyboard changes its readout and the pixels of
its figure, each explorer is drawn complete after its moves, every animation is
present and plays, and axe-core finds nothing critical or serious in what the
course puts in the notebook.  Screenshots go to build/screenshots/.  ``make test``
runs chapter 1 so, as a student first meets it: in the student edition's first
run, after the reload (tests/browser/test_student_edition.py);
``TWOLINK_BROWSER_EVERY_CHAPTER=1`` runs every chapter so here (a release check).

The generic checks (figures' alt text, slider handles named by their description,
videos still for reduced motion, a choice's label in the label column) share one
probe notebook (``probe_notebook``), opened and run once for the module.
"""

import base64
import json
import os
import re
import urllib.request

import a11y  # tools/a11y.py: tools/ is on the path (tests/browser/conftest.py, loaded first)
import pytest

from .conftest import ROOT, SCREENSHOTS

#: Every chapter, run whole in JupyterLab here when ``TWOLINK_BROWSER_EVERY_CHAPTER=1``
#: (a release check: about a minute a chapter).  ``make test`` runs one chapter whole
#: in JupyterLab, chapter 1 in the student edition's first run (its checks:
#: :func:`check_the_chapter_as_run`).  What JupyterLab adds (widgets that render and
#: follow a hand, videos that play, axe on the notebook) is the kit's, the same in
#: every chapter, and the probe notebook below checks it too; each chapter's own
#: prose and outputs are checked by axe on its static page
#: (tests/browser/test_static_site.py), its explorers moved to their ends in its
#: kernel (notebooks/NN_x.ipynb::figures), and a draw the page asks for waits for a
#: move (tests/course/test_explorer.py: chapter 5's explorer once stayed blank after
#: Run All and a move).
EVERY_CHAPTER = sorted((ROOT / "notebooks").glob("0[1-9]_*.ipynb"))
RELEASE_CHECK = os.environ.get("TWOLINK_BROWSER_EVERY_CHAPTER") == "1"


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


# --- the chapter, run whole -----------------------------------------------------------------


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.skipif(
    not RELEASE_CHECK,
    reason="a release check (TWOLINK_BROWSER_EVERY_CHAPTER=1); make test runs chapter 1 "
    "so in the student edition (tests/browser/test_student_edition.py)",
)
@pytest.mark.parametrize(
    "path", EVERY_CHAPTER, ids=[path.name for path in EVERY_CHAPTER]
)
def test_chapter_runs_and_plays_in_jupyterlab(jupyterlab, page, path, request):
    # what axe finds in JupyterLab's own interface is only printed: looked for when
    # the output is shown (pytest -s, as make browser-test runs)
    shown = request.config.getoption("capture") == "no"
    try:
        run_chapter(jupyterlab, page, path, axe_jupyterlab=shown)
    finally:
        shut_down_kernel_of(jupyterlab, path.name)


def shut_down_kernel_of(jupyterlab, name):
    """Stop the kernel of the server's notebook ``name`` (its session), and no other."""
    base = f"{jupyterlab['url']}/api/sessions"
    headers = {"Authorization": f"token {jupyterlab['token']}"}
    request = urllib.request.Request(base, headers=headers)
    with urllib.request.urlopen(request, timeout=10) as response:
        sessions = json.load(response)
    for session in sessions:
        if session["path"] == name:
            request = urllib.request.Request(
                f"{base}/{session['id']}", headers=headers, method="DELETE"
            )
            urllib.request.urlopen(request, timeout=30).close()


def open_notebook(jupyterlab, page, name, workspace):
    """Open the server's notebook ``name`` in a workspace of its own (no tabs of others restored)."""
    page.goto(
        f"{jupyterlab['url']}/lab/workspaces/{workspace}/tree/{name}"
        f"?reset&token={jupyterlab['token']}"
    )
    panel = page.locator(".jp-NotebookPanel:not(.lm-mod-hidden)")
    panel.locator(".jp-Cell").first.wait_for(timeout=90_000)
    accept_kernel_dialog(page)
    return panel


def run_all(page, panel, name, timeout_ms):
    """Run All once the kernel is idle, wait for idle again; no error or stderr output."""
    wait_until_idle(page, 90_000)
    run_all_cells(page)
    wait_for_all_cells(page, timeout_ms)
    wait_until_idle(page, timeout_ms)
    assert_no_error_output(panel, name)


def assert_no_error_output(panel, name):
    """No cell of the notebook in ``panel`` shows an error or writes to stderr."""
    for kind in ("error", "stderr"):
        found = panel.locator(f"[data-mime-type='application/vnd.jupyter.{kind}']")
        assert found.count() == 0, (
            f"{name}: {kind} output: {found.first.inner_text()[:500]}"
        )


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


def run_chapter(jupyterlab, page, path, axe_jupyterlab=True):
    panel = open_notebook(jupyterlab, page, path.name, path.stem)
    # as stored, before Run All: each figure's <img> has its output's alt
    # (the server's copy of the chapter, as it was when the server started)
    expected = image_outputs(json.loads(path.read_text(encoding="utf-8")))
    assert any(alt for _, alt in expected), f"{path.name}: no figure has alt"
    rendered = rendered_images(page, len(expected))
    assert [(mime, alt) for mime, alt, _ in rendered] == expected

    run_all(page, panel, path.name, 300_000)
    check_the_chapter_as_run(page, panel, path, axe_jupyterlab)


def check_the_chapter_as_run(page, panel, path, axe_jupyterlab=False):
    """Chapter ``path`` in ``panel`` after Run All (and :func:`assert_no_error_output`): its
    explorers rendered, each slider moved by a key changes its readout, picture and
    sentence, each drawn complete after its moves; its animations play; axe-core finds
    nothing critical or serious in what the course puts in the notebook
    (``axe_jupyterlab``: what it finds in JupyterLab's own interface is printed)."""
    containers, moved = move_every_slider(page, panel, path)
    assert_drawn_complete(path, containers)
    _, animation_count = expected_widgets(path)

    videos = panel.locator(".jp-OutputArea-output video")
    assert videos.count() >= animation_count, (
        f"{path.name}: {videos.count()} videos, {animation_count} animations built"
    )
    for index in range(videos.count()):
        videos.nth(index).evaluate("video => { video.muted = true; video.play(); }")
        page.wait_for_function(
            VIDEO_MOVED, arg=videos.nth(index).element_handle(), timeout=15_000
        )
        state = videos.nth(index).evaluate(
            """video => {
                const result = {duration: video.duration, time: video.currentTime, error: video.error && video.error.code};
                video.pause();
                return result;
            }"""
        )
        assert state["error"] is None and state["duration"] > 0, (
            f"{path.name}: video {index} {state}"
        )

    # axe-core on what the course puts in the notebook (prose and outputs): no critical
    # or serious violation; what it finds in JupyterLab's own interface is printed
    # (``axe_jupyterlab``)
    course_parts = [
        f".jp-NotebookPanel:not(.lm-mod-hidden) {part}"
        for part in (".jp-RenderedMarkdown", ".jp-OutputArea")
    ]
    in_course = a11y.violations(page, include=course_parts)
    assert not a11y.blocking(in_course), (path.name, a11y.blocking(in_course))
    if axe_jupyterlab:
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


#: True once the video plays with its time past 0 (or has played: a looping video
#: is back at 0 for a moment at each loop).
VIDEO_MOVED = """video => {
    if (!video.paused && video.currentTime > 0) video.dataset.twolinkMoved = '1';
    return video.dataset.twolinkMoved === '1';
}"""


# --- the probe notebook: the extension's and the kit's generic checks ----------------------

IMAGE_TYPES = ("image/png", "image/jpeg", "image/gif")
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
KERNEL = {"name": "python3", "display_name": "Python 3", "language": "python"}


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


def image_cells():
    """Stored image outputs: with an alt, without metadata, with a non-string or empty alt.

    Their sources do nothing: Run All clears these outputs once they have been read.
    """
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
    return [
        nbformat.v4.new_code_cell("# a stored figure", outputs=[item])
        for item in outputs
    ]


def slider_cells():
    """A slider with a description, a range slider (two handles), a slider without one, a wide and a narrow LaTeX output."""
    import nbformat

    sources = [
        'import ipywidgets\nq1 = ipywidgets.IntSlider(description="q1 [deg]")\nq1',
        'span = ipywidgets.FloatRangeSlider(description="span [m]")\nspan',
        "bare = ipywidgets.IntSlider()\nbare",
        'from IPython.display import Latex\nLatex("$$" + " + ".join(f"x_{{{i}}}" for i in range(120)) + "$$")',
        'Latex("$$a + b$$")',
    ]
    return [nbformat.v4.new_code_cell(source) for source in sources]


def video_cells():
    """One animation of the course's kit, made, then shown as a chapter shows it (a cell's value)."""
    import nbformat

    sources = [
        "import numpy as np\n"
        "from twolink import arms\n"
        "from twolink_course import plot\n"
        "video = plot.animation_html(plot.animate_arm(arms.two_metre, np.linspace([0.0, 0.0], [1.0, 1.0], 8)))",
        "video",
    ]
    return [nbformat.v4.new_code_cell(source) for source in sources]


def choice_cells():
    """A slider and a choice in one box, as an explorer lays them out."""
    import nbformat

    source = (
        "import ipywidgets\n"
        "from twolink_course import explorer\n"
        "ipywidgets.VBox([explorer.slider('angle', 'deg', 0, -90, 90, 5), "
        "explorer.choice('elbow', ['either', 'down', 'up'], 'either')])"
    )
    return [nbformat.v4.new_code_cell(source)]


PROBES = {
    "images": image_cells,
    "sliders": slider_cells,
    "video": video_cells,
    "choice": choice_cells,
}


def probe_notebook():
    """The probes' cells in one notebook, and the range of cell indices of each probe."""
    import nbformat

    cells, ranges = [], {}
    for name, make in PROBES.items():
        made = make()
        ranges[name] = range(len(cells), len(cells) + len(made))
        cells.extend(made)
    notebook = nbformat.v4.new_notebook(cells=cells, metadata={"kernelspec": KERNEL})
    return notebook, ranges


RENDERED_IMAGES = """() => [...document.querySelectorAll(
    '.jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea-output[data-mime-type^="image/"]'
)].filter(node => node.querySelector('img')).map(node => {
    const img = node.querySelector('img');
    return [node.dataset.mimeType, img.getAttribute('alt'), img.getAttribute('width')];
})"""


def rendered_images(page, count):
    """``[mime type, alt attribute or None, width attribute or None]`` of each image output of the open notebook."""
    page.wait_for_function(
        f"() => ({RENDERED_IMAGES})().length >= {count}", timeout=60_000
    )
    return page.evaluate(RENDERED_IMAGES)


class Probe:
    """The probe notebook open in JupyterLab, run once: its page, panel, cells and stored images."""

    def __init__(self, page, panel, notebook, ranges, images):
        self.page, self.panel, self.notebook = page, panel, notebook
        self.ranges, self.images = ranges, images

    def cells(self, probe):
        """The cells of one probe (a name of ``PROBES``), in order."""
        every = self.panel.locator(".jp-Cell")
        return [every.nth(index) for index in self.ranges[probe]]


PROBE = "probe.ipynb"


@pytest.fixture(scope="module")
def probe(jupyterlab, browser):
    """The probe notebook, opened (its stored figures read as shown) and run, once for the module."""
    import nbformat

    notebook, ranges = probe_notebook()
    nbformat.write(notebook, jupyterlab["notebooks"] / PROBE)
    context = browser.new_context(
        viewport={"width": 1400, "height": 1000}, reduced_motion="no-preference"
    )
    context.add_init_script(MARK_PLAYED)
    try:
        page = context.new_page()
        panel = open_notebook(jupyterlab, page, PROBE, "probe")
        images = rendered_images(page, len(image_outputs(notebook)))
        run_all(page, panel, PROBE, 120_000)
        yield Probe(page, panel, notebook, ranges, images)
    finally:
        context.close()
        shut_down_kernel_of(jupyterlab, PROBE)


# --- figures' text alternatives (labextension/: twolink-figure-alt) -----------------------


@pytest.mark.infrastructure
@pytest.mark.browser
def test_image_outputs_carry_their_alt_text_in_jupyterlab(probe):
    """Stored outputs, not run: each <img> has exactly its output's metadata alt, or no alt.

    (A chapter's stored figures: ``test_chapter_runs_and_plays_in_jupyterlab``.)
    """
    config = json.loads(probe.page.locator("#jupyter-config-data").text_content())
    names = [ext["name"] for ext in config.get("federated_extensions", [])]
    assert "twolink-figure-alt" in names, (
        f"JupyterLab did not load twolink-figure-alt (run `make install`): {names}"
    )
    expected = image_outputs(probe.notebook)
    rendered = probe.images
    assert [(mime, alt) for mime, alt, _ in rendered] == expected
    assert expected[0][1].startswith("The arm") and expected[1][1] is None
    assert expected[4] == ("image/png", "")  # an empty alt (decorative) is kept
    # width and height stay JupyterLab's: from the metadata, as before
    assert [width for *_, width in rendered[:3]] == ["120", None, "120"]


# --- slider handles named by their description (labextension/: src/a11y.ts) ---------------


@pytest.mark.infrastructure
@pytest.mark.browser
def test_slider_handles_are_named_by_their_description_in_jupyterlab(probe):
    """ipywidgets' noUiSlider handles (role=slider) take the widget's description as their name.

    A slider without a description stays unnamed (nothing is invented); a
    LaTeX output wider than the notebook is a tab stop whose arrow keys
    scroll it, a narrow one is not.
    """
    page, panel = probe.page, probe.panel
    q1_cell, span_cell, bare_cell, wide_cell, narrow_cell = probe.cells("sliders")
    sliders = (q1_cell, span_cell, bare_cell)
    for cell, count in zip(sliders, (1, 2, 1)):
        cell.locator(".noUi-handle").nth(count - 1).wait_for(timeout=30_000)

    q1 = q1_cell.get_by_role("slider", name="q1 [deg]", exact=True)
    assert q1.count() == 1
    label = q1_cell.locator(".widget-label", has_text="q1 [deg]")
    assert q1.get_attribute("aria-labelledby") == label.get_attribute("id")
    assert span_cell.get_by_role("slider", name="span [m]", exact=True).count() == 2
    assert [cell.locator(".noUi-handle").count() for cell in sliders] == [1, 2, 1]
    unnamed = bare_cell.locator(".noUi-handle")
    assert [
        unnamed.get_attribute(name) for name in ("aria-labelledby", "aria-label")
    ] == [None, None]
    # the handle still works as before: the keyboard moves it
    q1.focus()
    page.keyboard.press("ArrowRight")
    assert q1.get_attribute("aria-valuenow") == "1.0"

    wide = wide_cell.locator("[data-mime-type='text/latex']")
    narrow = narrow_cell.locator("[data-mime-type='text/latex']")
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
    panel.locator(".jp-Cell").last.locator(".jp-InputArea-editor").click()
    page.keyboard.press("Escape")
    page.keyboard.press("b")
    page.keyboard.press("Enter")
    page.keyboard.type('q1.description = ""; bare.description = "q2 [deg]"')
    page.keyboard.press("Shift+Enter")
    bare_cell.get_by_role("slider", name="q2 [deg]", exact=True).wait_for(
        timeout=30_000
    )
    page.wait_for_function(
        "e => !e.hasAttribute('aria-labelledby')",
        arg=q1_cell.locator(".noUi-handle").element_handle(),
        timeout=10_000,
    )
    parts = [".jp-NotebookPanel:not(.lm-mod-hidden) .jp-OutputArea"]
    found = [
        v
        for v in a11y.violations(page, include=parts)
        if v["id"] == "aria-input-field-name"
    ]
    assert [len(v["nodes"]) for v in found] == [1]  # q1, now without a description


# --- animations: described, and still for readers who ask for reduced motion ------------

#: How long a video must stay still under reduced motion once its first frame is
#: there, milliseconds: a playing video's time moves from its first frame on, and its
#: timeupdate event fires at least every 250 ms.
HOLD_STILL_MS = 500

#: Marks each video that was ever asked to play (its play event), from the page's
#: first script on: media events do not bubble, but the document sees them captured.
MARK_PLAYED = """document.addEventListener('play', event => {
    event.target.dataset.twolinkPlayed = '1';
}, true);"""

VIDEO_STATE = """video => ({
    paused: video.paused, time: video.currentTime, autoplay: video.autoplay,
    played: video.dataset.twolinkPlayed === '1',
    label: video.closest('[role=figure]') && video.closest('[role=figure]').getAttribute('aria-label'),
})"""


@pytest.mark.infrastructure
@pytest.mark.browser
@pytest.mark.parametrize("reduced_motion", ["reduce", "no-preference"])
def test_videos_are_described_and_hold_still_for_reduced_motion_in_jupyterlab(
    probe, reduced_motion
):
    """The video cell is run again with the reader's preference set: the video it
    shows plays by itself, or holds still for a reader who asks for reduced motion."""
    page = probe.page
    cell = probe.cells("video")[-1]
    page.emulate_media(reduced_motion=reduced_motion)
    try:
        cell.locator("video").evaluate_all(
            "videos => videos.forEach(video => video.setAttribute('data-twolink-shown', ''))"
        )
        cell.locator(".jp-InputArea-editor").click()
        page.keyboard.press("Control+Enter")  # the cell again: a new video
        video = cell.locator(".jp-OutputArea-output video:not([data-twolink-shown])")
        video.wait_for(timeout=60_000)
        if reduced_motion == "reduce":
            page.wait_for_function(
                "video => video.readyState >= 2",
                arg=video.element_handle(),
                timeout=15_000,
            )
            page.wait_for_timeout(HOLD_STILL_MS)
        else:
            page.wait_for_function(
                VIDEO_MOVED, arg=video.element_handle(), timeout=15_000
            )
        state = video.evaluate(VIDEO_STATE)
    finally:
        page.emulate_media(reduced_motion="no-preference")
    # the text alternative, generated from the animation's data
    assert state["label"] and "An animation of the arm in 8 frames" in state["label"]
    if reduced_motion == "reduce":
        assert state["paused"] and state["time"] == 0 and not state["autoplay"], state
        assert not state["played"], state  # not even for a moment
    else:
        assert state["autoplay"] and state["played"], state


# --- choices: their labels in the label column, their buttons on the same row ------------


@pytest.mark.infrastructure
@pytest.mark.browser
def test_a_choices_label_sits_in_the_label_column_beside_its_buttons(probe):
    (cell,) = probe.cells("choice")
    cell.locator(".widget-toggle-buttons button").last.wait_for(timeout=60_000)
    boxes = cell.evaluate(
        """cell => {
            const box = e => { const r = e.getBoundingClientRect(); return {left: r.left, right: r.right, top: r.top, bottom: r.bottom}; };
            const slider = cell.querySelector('.widget-slider .widget-label');
            const choice = cell.querySelector('.widget-toggle-buttons .widget-label');
            const buttons = [...cell.querySelectorAll('.widget-toggle-buttons button')].map(box);
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
    assert choice["bottom"] > min(rows) and choice["top"] < buttons[0]["bottom"], boxes
