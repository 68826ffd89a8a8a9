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
import course_map  # noqa: E402
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
        source = "\n".join(
            "".join(cell["source"])
            for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]
        )
        images = page.locator(".jp-OutputArea-output img")
        if path.name != course_map.START_PAGE:  # the start page is text only
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
