"""The static edition in a browser: every page loads offline, with figures, the
explorers' described first states and playable animations."""

import functools
import http.server
import json
import sys
import threading

import pytest

from .conftest import ROOT

sys.path.insert(0, str(ROOT / "tools"))
import editions  # noqa: E402

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    editions.build_site(ROOT / "notebooks", out)
    handler = functools.partial(
        http.server.SimpleHTTPRequestHandler, directory=str(out)
    )
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


@pytest.mark.infrastructure
@pytest.mark.browser
def test_index_links_every_chapter_in_order_and_each_page_is_complete(site, page):
    failures = []
    local = ("http://127.0.0.1", "data:", "blob:", "about:blank")
    # about:blank (an empty frame some scripts create) is not a network load
    page.on(
        "requestfailed",
        lambda request: (
            request.url == "about:blank"
            or failures.append(f"failed ({request.failure}): {request.url}")
        ),
    )
    page.on(
        "response",
        lambda response: (
            response.status >= 400
            and failures.append(f"{response.status}: {response.url}")
        ),
    )
    page.on(
        "request",
        lambda request: (
            request.url.startswith(local) or failures.append(f"external: {request.url}")
        ),
    )

    page.goto(f"{site}/index.html")
    links = page.locator("ol li a")
    hrefs = [links.nth(index).get_attribute("href") for index in range(links.count())]
    assert hrefs == [path.with_suffix(".html").name for path in NOTEBOOKS]

    for path, href in zip(NOTEBOOKS, hrefs):
        page.goto(f"{site}/index.html")
        page.locator(f"a[href='{href}']").click()
        page.wait_for_load_state("load")
        if page.evaluate("() => Boolean(window.MathJax && window.MathJax.Hub)"):
            # let MathJax finish typesetting (it loads fonts as it goes) before looking or leaving
            page.evaluate("() => new Promise(resolve => MathJax.Hub.Queue(resolve))")
        page.wait_for_load_state("networkidle")
        cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
        source = "\n".join("".join(cell["source"]) for cell in cells)
        stored_images = [
            output
            for cell in cells
            for output in cell.get("outputs", [])
            if any(mime.startswith("image/") for mime in output.get("data", {}))
        ]
        images = page.locator(".jp-OutputArea-output img")
        if stored_images:  # the start page and the source record are text only
            assert images.count() >= 1, f"{href}: no figures"
        broken = page.evaluate(
            "() => [...document.querySelectorAll('img')].filter(i => !(i.complete && i.naturalWidth > 0)).length"
        )
        assert broken == 0, f"{href}: {broken} images failed to render"
        # an explorer shows its first state, described by its alternative text,
        # never the text of its widgets
        described = page.locator(
            ".jp-OutputArea-output img[alt]:not([alt^='No description'])"
        )
        assert described.count() >= source.count("explorer.Explorer("), (
            f"{href}: an explorer's picture has no description"
        )
        text = page.inner_text("body")
        for widget_text in ("interactive(children", "VBox(children", "Canvas(toolbar"):
            assert widget_text not in text, f"{href}: shows {widget_text!r}"
        videos = page.locator("video")
        assert videos.count() >= source.count("animation_html("), (
            f"{href}: animations missing"
        )
        for index in range(videos.count()):
            state = videos.nth(index).evaluate(
                """async video => {
                    video.muted = true;
                    await video.play();
                    await new Promise(resolve => setTimeout(resolve, 500));
                    return {duration: video.duration, time: video.currentTime};
                }"""
            )
            assert state["duration"] > 0 and state["time"] > 0, (
                f"{href}: video {index} does not play: {state}"
            )
        if "$" in source:
            rendered = page.locator(".MathJax, .MathJax_Display")
            assert rendered.count() > 0, (
                f"{href}: LaTeX in the notebook but no MathJax output in the page"
            )
    assert not failures, failures


#: The pages axe-core checks whole: the index, the start page and the first chapter hold
#: everything the site's template makes (header, navigation, skip link, highlighted
#: code, typeset maths), the same on every page; on the others it checks what each
#: chapter brings, its prose and its outputs (a chapter's code cells are most of its
#: elements, and most of axe's time).
WHOLE_PAGES = 3
CHAPTER_PARTS = (".jp-RenderedMarkdown", ".jp-OutputArea")


@pytest.mark.infrastructure
@pytest.mark.browser
def test_every_page_is_accessible_titled_skippable_and_linked_in_order(site, page):
    """axe-core finds nothing critical or serious; a page has its chapter's title, a skip
    link to the chapter, previous/next links in order, and figures with real descriptions."""
    import a11y

    pages = ["index.html"] + [path.with_suffix(".html").name for path in NOTEBOOKS]
    for number, name in enumerate(pages):
        page.goto(f"{site}/{name}")
        a11y.settle(page)
        include = None if number < WHOLE_PAGES else CHAPTER_PARTS
        problems = a11y.blocking(a11y.violations(page, include=include))
        assert not problems, (name, problems)
        assert page.locator("main").count() == 1, f"{name}: one main landmark"
        if name == "index.html":
            continue
        path = NOTEBOOKS[number - 1]
        title = editions.chapter_title(
            json.loads(path.read_text(encoding="utf-8")), path.stem
        )
        assert page.title() == f"{title} · {editions.SITE_TITLE}"
        page.keyboard.press("Tab")  # the first stop: the skip link, shown when focused
        skip = page.locator(":focus")
        assert skip.inner_text() == "Skip to the chapter" and skip.is_visible()
        page.keyboard.press("Enter")
        assert page.evaluate("() => document.activeElement.id") == "content"
        links = page.locator("header nav a")
        hrefs = [
            links.nth(index).get_attribute("href") for index in range(links.count())
        ]
        expected = (
            ([pages[number - 1]] if number > 1 else [])
            + ["index.html"]
            + ([pages[number + 1]] if number + 1 < len(pages) else [])
        )
        assert hrefs == expected, (name, hrefs)
        undescribed = page.locator(
            ".jp-OutputArea-output img:not([alt]), "
            ".jp-OutputArea-output img[alt^='No description'], "
            ".jp-OutputArea-output img[alt='']"
        )
        assert undescribed.count() == 0, (
            f"{name}: {undescribed.count()} figures without a description"
        )


def _tab_stops(page, count):
    """The hrefs of the first ``count`` elements Tab reaches from the top of the page."""
    stops = []
    for _ in range(count):
        page.keyboard.press("Tab")
        stops.append(page.evaluate("() => document.activeElement.getAttribute('href')"))
    return stops


@pytest.mark.infrastructure
@pytest.mark.browser
def test_the_chapters_are_walked_by_keyboard_from_the_index_and_back(site, page):
    """Tab and Enter alone: the index's first link opens the first chapter; on each
    chapter Tab reaches the skip link, then previous, index and next in that order;
    Enter on next opens the next chapter, and the last chapter's index link returns."""
    pages = [path.with_suffix(".html").name for path in NOTEBOOKS]
    page.goto(f"{site}/index.html")
    page.wait_for_load_state("load")
    assert _tab_stops(page, 1) == [pages[0]]
    page.keyboard.press("Enter")
    for number, name in enumerate(pages):
        page.wait_for_url(f"{site}/{name}")
        page.wait_for_load_state("load")
        expected = (
            ["#content"]
            + ([pages[number - 1]] if number > 0 else [])
            + ["index.html"]
            + ([pages[number + 1]] if number + 1 < len(pages) else [])
        )
        assert _tab_stops(page, len(expected)) == expected, name
        page.keyboard.press(
            "Enter"
        )  # on the last stop: next, or the index after the last chapter
    page.wait_for_url(f"{site}/index.html")
    assert page.title() == f"{editions.SITE_TITLE}: the planar two-link arm"


#: The page's Tab stops, as the browser's sequential navigation finds them:
#: focusable (a link, a control, a summary, tabindex >= 0), not disabled, shown.
TAB_STOPS = """() => [...document.querySelectorAll('*')].filter(element => {
    if (element.tabIndex < 0 || element.disabled) return false;
    if (!(element.matches('a[href], button, input, select, textarea, summary, video[controls], [tabindex]'))) return false;
    const style = getComputedStyle(element);
    return style.visibility !== 'hidden' && element.getClientRects().length > 0;
}).map(element => ({
    tag: element.tagName.toLowerCase(),
    cls: String(element.className || ''),
    formula: Boolean(element.closest('.MathJax, .MathJax_Display, .MathJax_Preview, mjx-container')),
    // as the page's own script decides: the box or the code block inside it scrolls
    scrolls: element.scrollWidth > element.clientWidth || element.scrollHeight > element.clientHeight
        || Boolean(element.querySelector('pre') && element.querySelector('pre').scrollWidth > element.querySelector('pre').clientWidth),
}))"""


@pytest.mark.infrastructure
@pytest.mark.browser
def test_formulas_and_code_cells_are_no_tab_stops(site, page):
    """One stop per cell at most: a code cell or an output only while it scrolls; no formula."""
    for path in NOTEBOOKS:
        name = path.with_suffix(".html").name
        page.goto(f"{site}/{name}")
        page.wait_for_load_state("load")
        if page.evaluate("() => Boolean(window.MathJax && window.MathJax.Hub)"):
            page.evaluate("() => new Promise(resolve => MathJax.Hub.Queue(resolve))")
        stops = page.evaluate(TAB_STOPS)
        formulas = [stop for stop in stops if stop["formula"]]
        cells = [
            stop
            for stop in stops
            if "jp-Cell-inputWrapper" in stop["cls"]
            or "jp-OutputArea-output" in stop["cls"]
        ]
        print(
            f"{name}: {len(stops)} Tab stops, {len(cells)} scrolling cells or outputs"
        )
        assert not formulas, f"{name}: {len(formulas)} formulas are Tab stops"
        assert all(stop["scrolls"] for stop in cells), (
            f"{name}: {sum(not stop['scrolls'] for stop in cells)} cells or outputs that do "
            "not scroll are Tab stops"
        )


@pytest.mark.infrastructure
@pytest.mark.browser
def test_figures_have_a_short_alt_and_the_whole_description_one_step_away(site, page):
    for path in NOTEBOOKS:
        name = path.with_suffix(".html").name
        page.goto(f"{site}/{name}")
        page.wait_for_load_state("load")
        alts = page.evaluate(
            "() => [...document.querySelectorAll('.jp-OutputArea-output img[alt]')].map(i => i.alt)"
        )
        assert all(len(alt) <= editions.SHORT_ALT_MAX for alt in alts), (
            name,
            max(map(len, alts), default=0),
        )
        details = page.locator(".twolink-description")
        for index in range(details.count()):
            summary = details.nth(index).locator("summary")
            summary.focus()
            page.keyboard.press("Enter")  # one step: the full description opens
            assert details.nth(index).evaluate("d => d.open")
            assert details.nth(index).locator("p").inner_text().strip()


def _video_states(browser, url, reduced_motion):
    context = browser.new_context(reduced_motion=reduced_motion)
    try:
        page = context.new_page()
        page.goto(url)
        page.wait_for_load_state("load")
        page.wait_for_timeout(1500)
        return page.evaluate(
            """() => [...document.querySelectorAll('video')].map(video => ({
                paused: video.paused, time: video.currentTime, autoplay: video.autoplay,
                label: video.closest('[role=figure]') && video.closest('[role=figure]').getAttribute('aria-label'),
                described: Boolean(video.closest('.jp-OutputArea-output').querySelector('details.twolink-description p')),
            }))"""
        )
    finally:
        context.close()


@pytest.mark.infrastructure
@pytest.mark.browser
def test_videos_are_described_and_hold_still_for_readers_who_ask_for_reduced_motion(
    site, browser
):
    with_video = [
        path
        for path in NOTEBOOKS
        if "animation_html(" in path.read_text(encoding="utf-8")
    ]
    assert with_video
    for path in with_video:
        url = f"{site}/{path.with_suffix('.html').name}"
        still = _video_states(browser, url, "reduce")
        moving = _video_states(browser, url, "no-preference")
        assert still and len(still) == len(moving)
        for video in still:
            assert video["paused"] and video["time"] == 0 and not video["autoplay"], (
                path.name,
                video,
            )
        for video in moving:
            assert not video["paused"] and video["time"] > 0, (path.name, video)
        for video in still:  # a short label, the whole description one step away
            assert video["label"] and len(video["label"]) <= editions.SHORT_ALT_MAX
            assert video["described"], (path.name, video)
