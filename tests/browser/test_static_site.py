"""The static edition in a browser: every page loads offline, with figures, the
explorers' described first states and playable animations; axe-core finds nothing
critical or serious; titles, the skip link and previous/next links in order; the
chapters walked by keyboard; no formula or non-scrolling cell a Tab stop; short
alternative texts with the whole description one step away; videos that hold still
for readers who ask for reduced motion and move for the others.

One walk (the ``walk`` fixture) loads each page once, as a reader walks them by
keyboard: the index, its first link, each chapter's "next" link, the last chapter's
link back to the index.  It checks everything about a page while it is there, and
opens each chapter once more in a plain tab (``plain_context``): under reduced motion,
where its videos must hold still, and without MathJax, where axe-core checks the
chapter's prose and outputs (typeset maths more than triples a chapter page's elements
and doubles axe's time; axe checks it on the pages it checks whole).  The walk goes in two
lanes, two tabs side by side (``SECOND_LANE``): while one tab loads, typesets or
runs axe-core, the other works.  Each test below asserts one property over every
page from what the walk found: a failure on one page does not stop the walk, and a
test fails unless its check ran to the end on each page.  The site is built once
per run (``course_site``, tests/conftest.py) and shared with
tests/infrastructure/test_static_site.py.
"""

import contextlib
import json
import sys

import pytest

from .conftest import ROOT

sys.path.insert(0, str(ROOT / "tools"))
import a11y  # noqa: E402
import editions  # noqa: E402

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
CHAPTERS = [editions.page_name(path) for path in NOTEBOOKS]
PAGES = [editions.INDEX_PAGE, *CHAPTERS]
#: The walk's last step: the last chapter's index link leads back to the index.
BACK_TO_THE_INDEX = f"{editions.INDEX_PAGE} (back)"
#: What the walk checks on each page, one test each (below).
PROPERTIES = (
    "complete",
    "accessible",
    "keyboard",
    "tab_stops",
    "descriptions",
    "motion",
)

#: The pages axe-core checks whole: the index, the start page and the first chapter hold
#: everything the site's template makes (header, navigation, skip link, highlighted
#: code, typeset maths), the same on every page; on the others it checks what each
#: chapter brings, its prose and its outputs (a chapter's code cells are most of its
#: elements, and most of axe's time).
WHOLE_PAGES = 3
CHAPTER_PARTS = (".jp-RenderedMarkdown", ".jp-OutputArea")
#: axe checks a chapter's parts in the plain tab, where MathJax does not run (its
#: formulas are text there, in the colour of the text around them): typeset, they are
#: about three quarters of a chapter page's elements, and axe takes twice as long.
#: :data:`MATHS_IN_THE_TEXT_S_COLOURS` holds each typeset formula to the colour of the
#: text around it, whose contrast axe checks; axe checks typeset maths on the pages it
#: checks whole.

#: The site's own copy of MathJax (``make site`` ships it beside the pages).
MATHJAX_FOLDER = "mathjax"

#: How long a page's videos have to start by themselves, milliseconds.
VIDEO_START_BUDGET_MS = 15_000
#: How long a video must stay still under reduced motion once its first frame is
#: there, milliseconds: a playing video's time moves from its first frame on, and its
#: timeupdate event fires at least every 250 ms.
HOLD_STILL_MS = 500


def notebook_source(path):
    """A notebook's cells, and all their sources as one text."""
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    return cells, "\n".join("".join(cell["source"]) for cell in cells)


class Walk:
    """What the walk found: for each property, the failures and the pages checked to the end."""

    def __init__(self):
        self.failures = {name: [] for name in PROPERTIES}
        self.checked = {name: [] for name in PROPERTIES}

    @contextlib.contextmanager
    def check(self, name, page_name):
        """One property's checks of one page: a failure is recorded, the walk goes on."""
        try:
            yield
        except Exception as error:  # an assertion, a timeout, an error in the page
            self.failures[name].append(f"{page_name}: {type(error).__name__}: {error}")
        else:
            self.checked[name].append(page_name)

    def assert_passed(self, name, pages):
        """No failure of the property, and its check ran to the end once on each of ``pages``."""
        assert not self.failures[name], "\n".join(self.failures[name])
        assert sorted(self.checked[name]) == sorted(pages), (
            f"{name} was not checked once on every page: {self.checked[name]}"
        )


#: The walk goes in two lanes, each in a tab of its own (a renderer process of its
#: own), side by side: the first from the index through the chapters before this
#: one, whose page the last of them leads to by its "next" link; the second from this
#: chapter's page to the last chapter and back to the index.
SECOND_LANE = len(CHAPTERS) // 2


@pytest.fixture(scope="module")
def walk(course_site, browser):
    found = Walk()
    with a11y.served(course_site) as site:
        context = browser.new_context(
            viewport={"width": 1400, "height": 1000}, reduced_motion="no-preference"
        )
        plain = plain_context(browser)
        try:
            side_by_side(
                [
                    first_lane(context.new_page(), plain.new_page(), site, found),
                    second_lane(context.new_page(), plain.new_page(), site, found),
                ]
            )
        finally:
            plain.close()
            context.close()
    return found


def plain_context(browser):
    """Tabs for a reader who asks for reduced motion, whose pages MathJax does not typeset.

    Each video asked to play is marked (:data:`MARK_PLAYED`).  The videos are the
    page's own script's, which never waits for MathJax.
    """
    context = browser.new_context(
        viewport={"width": 1400, "height": 1000}, reduced_motion="reduce"
    )
    context.add_init_script(MARK_PLAYED)
    context.route(f"**/{MATHJAX_FOLDER}/**", lambda route: route.abort())
    return context


def side_by_side(lanes):
    """Run the lanes' steps in turns: a lane yields when its page has work of its own
    to do (load, typeset, run axe-core), and the other lane goes on meanwhile."""
    lanes = list(lanes)
    while lanes:
        for lane in list(lanes):
            try:
                next(lane)
            except StopIteration:
                lanes.remove(lane)


def first_lane(page, plain, site, walk):
    stop_watching = watch_the_network(page, walk)
    page.goto(f"{site}/{editions.INDEX_PAGE}", wait_until="commit")
    yield  # the page loads
    a11y.settle(page)
    yield from index_steps(page, walk)
    leave(page, walk, editions.INDEX_PAGE, [CHAPTERS[0]], f"{site}/{CHAPTERS[0]}")
    for number in range(SECOND_LANE):
        yield from chapter_steps(page, plain, site, walk, number)
    # the second lane's first page is there: it is checked in the second lane
    stop_watching()
    page.goto("about:blank")


def second_lane(page, plain, site, walk):
    watch_the_network(page, walk)
    page.goto(f"{site}/{CHAPTERS[SECOND_LANE]}", wait_until="commit")
    for number in range(SECOND_LANE, len(CHAPTERS)):
        yield from chapter_steps(page, plain, site, walk, number)
    with walk.check("keyboard", BACK_TO_THE_INDEX):
        page.wait_for_load_state("load")
        assert page.title() == f"{editions.SITE_TITLE}: the planar two-link arm"


def watch_the_network(page, walk):
    """Record each failed, erroneous (400 and up) or external request of the page
    as a failure of ``complete``; returns a function that stops recording."""
    local = ("http://127.0.0.1", "data:", "blob:", "about:blank")
    network = walk.failures["complete"]
    handlers = {
        # about:blank (an empty frame some scripts create) is not a network load
        "requestfailed": lambda request: (
            request.url == "about:blank"
            or network.append(f"failed ({request.failure}): {request.url}")
        ),
        "response": lambda response: (
            response.status >= 400
            and network.append(f"{response.status}: {response.url}")
        ),
        "request": lambda request: (
            request.url.startswith(local) or network.append(f"external: {request.url}")
        ),
    }
    for event, handler in handlers.items():
        page.on(event, handler)

    def stop():
        for event, handler in handlers.items():
            page.remove_listener(event, handler)

    return stop


def index_steps(page, walk):
    name = editions.INDEX_PAGE
    with walk.check("complete", name):
        links = page.locator("ol li a")
        hrefs = [
            links.nth(index).get_attribute("href") for index in range(links.count())
        ]
        assert hrefs == CHAPTERS
    with walk.check("accessible", name):
        a11y.start_violations(page)
        yield  # axe-core works
        problems = a11y.blocking(a11y.finish_violations(page))
        assert not problems, problems
        assert page.locator("main").count() == 1, "one main landmark"
    with walk.check("keyboard", name):
        stops = tab_stops(page, 1)
        assert stops == [CHAPTERS[0]], f"Tab reaches {stops}, not {CHAPTERS[0]}"


def chapter_steps(page, plain, site, walk, number):
    """Everything about chapter ``number``'s page, reached a moment ago, and its plain
    visit in the plain tab (:func:`plain_context`); then on to the next."""
    name, path = CHAPTERS[number], NOTEBOOKS[number]
    expected = ["#content", *neighbours(number)]
    plain.goto(f"{site}/{name}", wait_until="commit")
    yield  # the page loads and typesets; the plain tab loads
    try:
        a11y.settle(page)
    except Exception as error:  # the checks below tell what is missing
        walk.failures["complete"].append(f"{name}: did not settle: {error}")
    with walk.check("keyboard", name):
        # as the page came: Tab reaches the skip link, then previous, index and next
        stops = tab_stops(page, len(expected))
        assert stops == expected, f"Tab reaches {stops}, not {expected}"
    cells, source = notebook_source(path)
    with walk.check("complete", name):
        check_complete(page, name, cells, source)
    with walk.check("accessible", name):
        whole = number + 1 < WHOLE_PAGES
        # the whole page as it is, maths typeset; or the chapter's parts in the plain tab
        checked = page if whole else plain
        checked.wait_for_load_state("load", timeout=a11y.SETTLE_BUDGET_MS)
        assert checked.title() == page.title(), (name, checked.url, checked.title())
        a11y.start_violations(checked, None if whole else CHAPTER_PARTS)
        yield  # axe-core works
        check_accessible(page, number, path, a11y.finish_violations(checked))
        drawn_otherwise = page.evaluate(MATHS_IN_THE_TEXT_S_COLOURS)
        assert drawn_otherwise == [], (name, drawn_otherwise[:3])
    with walk.check("tab_stops", name):
        check_tab_stops(page, name)
    with walk.check("descriptions", name):
        check_descriptions(page, name)
    if "animation_html(" in source or page.locator("video").count():
        with walk.check("motion", name):
            check_motion(page, plain, name)
    leave(page, walk, name, expected, f"{site}/{expected[-1]}")


def neighbours(number):
    """The links at the top of chapter ``number``'s page: previous, index, next."""
    return (
        ([CHAPTERS[number - 1]] if number > 0 else [])
        + [editions.INDEX_PAGE]
        + ([CHAPTERS[number + 1]] if number + 1 < len(CHAPTERS) else [])
    )


def leave(page, walk, name, expected, url):
    """From the top of the page, Tab to the last of the ``expected`` stops and press Enter.

    Returns once the browser goes to ``url``.  When the keyboard does not lead
    there, the failure is recorded and the walk goes on from ``url``.
    """
    try:
        focus_from_the_top(page)
        stops = tab_stops(page, len(expected))
        assert stops == expected, f"Tab reaches {stops}, not {expected}"
        page.keyboard.press("Enter")
        page.wait_for_url(url, wait_until="commit")
    except Exception as error:
        walk.failures["keyboard"].append(f"{name}: leaving by keyboard: {error}")
        page.goto(url, wait_until="commit")


def focus_from_the_top(page):
    """Focus as on a page just loaded: the next Tab goes to the page's first stop."""
    page.evaluate(
        """() => {
            const body = document.body;
            body.tabIndex = -1;
            body.focus();
            body.removeAttribute('tabindex');
            window.scrollTo(0, 0);
        }"""
    )


def tab_stops(page, count):
    """The hrefs of the next ``count`` elements Tab reaches."""
    stops = []
    for _ in range(count):
        page.keyboard.press("Tab")
        stops.append(page.evaluate("() => document.activeElement.getAttribute('href')"))
    return stops


def check_complete(page, name, cells, source):
    """Figures render, explorers show their described first state, animations play, maths is typeset."""
    stored_images = [
        output
        for cell in cells
        for output in cell.get("outputs", [])
        if any(mime.startswith("image/") for mime in output.get("data", {}))
    ]
    images = page.locator(".jp-OutputArea-output img")
    if stored_images:  # the start page and the source record are text only
        assert images.count() >= 1, f"{name}: no figures"
    broken = page.evaluate(
        "() => [...document.querySelectorAll('img')].filter(i => !(i.complete && i.naturalWidth > 0)).length"
    )
    assert broken == 0, f"{name}: {broken} images failed to render"
    # an explorer shows its first state, described by its alternative text,
    # never the text of its widgets
    described = page.locator(
        ".jp-OutputArea-output img[alt]:not([alt^='No description'])"
    )
    assert described.count() >= source.count("explorer.Explorer("), (
        f"{name}: an explorer's picture has no description"
    )
    text = page.inner_text("body")
    for widget_text in ("interactive(children", "VBox(children", "Canvas(toolbar"):
        assert widget_text not in text, f"{name}: shows {widget_text!r}"
    videos = page.locator("video")
    assert videos.count() >= source.count("animation_html("), (
        f"{name}: animations missing"
    )
    if videos.count():
        wait_until_every_video_moved(page)
    if "$" in source:
        rendered = page.locator(".MathJax, .MathJax_Display")
        assert rendered.count() > 0, (
            f"{name}: LaTeX in the notebook but no MathJax output in the page"
        )


#: True once each video of the page has been seen playing, its time past 0 (a looping
#: video is back at 0 for a moment at each loop, so each is remembered once seen).
EVERY_VIDEO_MOVED = """() => {
    const videos = [...document.querySelectorAll('video')];
    window.twolinkMoved = window.twolinkMoved || new Set();
    videos.forEach((video, index) => {
        if (!video.paused && video.currentTime > 0 && video.duration > 0 && !video.error) {
            window.twolinkMoved.add(index);
        }
    });
    return window.twolinkMoved.size === videos.length;
}"""


def wait_until_every_video_moved(page):
    page.wait_for_function(EVERY_VIDEO_MOVED, timeout=VIDEO_START_BUDGET_MS)


#: The typeset maths' elements whose colour differs from the text around the formula
#: (its container's parent) or that have a background of their own: none, so a formula
#: has the contrast of that text (a ``\\color`` in the LaTeX would show here).
MATHS_IN_THE_TEXT_S_COLOURS = """() => [...document.querySelectorAll('.MathJax, .MathJax_Display')]
    .flatMap(formula => {
        const text = getComputedStyle(formula.parentElement).color;
        return [formula, ...formula.querySelectorAll('*')].filter(element => {
            const style = getComputedStyle(element);
            return style.color !== text || style.backgroundColor !== 'rgba(0, 0, 0, 0)';
        }).map(element => element.outerHTML.slice(0, 120));
    })"""


def check_accessible(page, number, path, violations):
    """axe-core's ``violations`` hold nothing critical or serious; one main landmark, the
    chapter's title, previous/next links in order, figures with real descriptions, a skip
    link to the chapter."""
    name = CHAPTERS[number]
    problems = a11y.blocking(violations)
    assert not problems, (name, problems)
    assert page.locator("main").count() == 1, f"{name}: one main landmark"
    title = editions.chapter_title(
        json.loads(path.read_text(encoding="utf-8")), path.stem
    )
    assert page.title() == f"{title} · {editions.SITE_TITLE}", name
    links = page.locator("header nav a")
    hrefs = [links.nth(index).get_attribute("href") for index in range(links.count())]
    assert hrefs == neighbours(number), (name, hrefs)
    undescribed = page.locator(
        ".jp-OutputArea-output img:not([alt]), "
        ".jp-OutputArea-output img[alt^='No description'], "
        ".jp-OutputArea-output img[alt='']"
    )
    assert undescribed.count() == 0, (
        f"{name}: {undescribed.count()} figures without a description"
    )
    focus_from_the_top(page)
    page.keyboard.press("Tab")  # the first stop: the skip link, shown when focused
    skip = page.locator(":focus")
    assert skip.inner_text() == "Skip to the chapter", (name, skip.inner_text())
    assert skip.is_visible(), f"{name}: the focused skip link is hidden"
    page.keyboard.press("Enter")
    focused = page.evaluate("() => document.activeElement.id")
    assert focused == "content", f"{name}: the skip link focused {focused!r}"


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


def check_tab_stops(page, name):
    """One stop per cell at most: a code cell or an output only while it scrolls; no formula."""
    stops = page.evaluate(TAB_STOPS)
    formulas = [stop for stop in stops if stop["formula"]]
    cells = [
        stop
        for stop in stops
        if "jp-Cell-inputWrapper" in stop["cls"]
        or "jp-OutputArea-output" in stop["cls"]
    ]
    print(f"{name}: {len(stops)} Tab stops, {len(cells)} scrolling cells or outputs")
    assert not formulas, f"{name}: {len(formulas)} formulas are Tab stops"
    assert all(stop["scrolls"] for stop in cells), (
        f"{name}: {sum(not stop['scrolls'] for stop in cells)} cells or outputs that do "
        "not scroll are Tab stops"
    )


#: Each figure's description: a ``details`` whose ``summary`` is shown and is a Tab stop
#: (what Enter opens in every browser), with its text in a ``p``.
DESCRIPTIONS = """() => [...document.querySelectorAll('.twolink-description')].map(d => {
    const summary = d.querySelector(':scope > summary');
    const text = d.querySelector('p');
    return {
        details: d.tagName === 'DETAILS',
        summary: Boolean(summary) && summary.tabIndex >= 0 && summary.getClientRects().length > 0,
        text: text ? text.textContent.trim() : '',
    };
})"""


def check_descriptions(page, name):
    """A figure's alt is short; the whole description is one step (Enter) away: each is
    a details with a summary shown in the Tab order and its text; the first opens on
    Enter, as a browser opens any of them."""
    alts = page.evaluate(
        "() => [...document.querySelectorAll('.jp-OutputArea-output img[alt]')].map(i => i.alt)"
    )
    assert all(len(alt) <= editions.SHORT_ALT_MAX for alt in alts), (
        name,
        max(map(len, alts), default=0),
    )
    found = page.evaluate(DESCRIPTIONS)
    unreachable = [
        index
        for index, one in enumerate(found)
        if not (one["details"] and one["summary"] and one["text"])
    ]
    assert not unreachable, (name, [found[index] for index in unreachable])
    if found:
        first = page.locator(".twolink-description").first
        first.locator("summary").focus()
        page.keyboard.press("Enter")  # one step: the full description opens
        assert first.evaluate("d => d.open"), (
            f"{name}: Enter did not open a description"
        )


#: Marks each video that was ever asked to play (its play event), from the page's
#: first script on: media events do not bubble, but the document sees them captured.
MARK_PLAYED = """document.addEventListener('play', event => {
    event.target.dataset.twolinkPlayed = '1';
}, true);"""

VIDEO_STATES = """() => [...document.querySelectorAll('video')].map(video => ({
    paused: video.paused, time: video.currentTime, autoplay: video.autoplay,
    played: video.dataset.twolinkPlayed === '1',
    label: video.closest('[role=figure]') && video.closest('[role=figure]').getAttribute('aria-label'),
    described: Boolean(video.closest('.jp-OutputArea-output').querySelector('details.twolink-description p')),
}))"""


def check_motion(page, plain, name):
    """Videos move by themselves here; in the plain tab, for a reader who asks for
    reduced motion, they hold still; each has a short label and its whole description."""
    wait_until_every_video_moved(page)
    moving = page.evaluate(VIDEO_STATES)
    still = still_videos(plain, len(moving))
    assert still and len(still) == len(moving), (name, moving, still)
    for video in still:
        assert video["paused"] and video["time"] == 0 and not video["autoplay"], (
            name,
            video,
        )
        assert not video["played"], (name, video)
    for video in moving:  # a short label, the whole description one step away
        assert video["autoplay"], (name, video)
        assert video["label"] and len(video["label"]) <= editions.SHORT_ALT_MAX
        assert video["described"], (name, video)


def still_videos(plain, count):
    """The video states of the plain tab's page (reduced motion), once each of its
    ``count`` videos has its first frame and :data:`HOLD_STILL_MS` more have passed;
    ``played``: a play event since the page loaded, however early or late the video
    would have moved."""
    plain.wait_for_function(
        """count => {
            const videos = [...document.querySelectorAll('video')];
            return videos.length === count && videos.every(video => video.readyState >= 2);
        }""",
        arg=count,
        timeout=VIDEO_START_BUDGET_MS,
    )
    plain.wait_for_timeout(HOLD_STILL_MS)
    return plain.evaluate(VIDEO_STATES)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_index_links_every_chapter_in_order_and_each_page_is_complete(walk):
    """The index links every chapter in order; each page loads with nothing from the
    network, its figures render, its explorers show their described first state, its
    animations play and its LaTeX is typeset."""
    walk.assert_passed("complete", PAGES)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_every_page_is_accessible_titled_skippable_and_linked_in_order(walk):
    """axe-core finds nothing critical or serious; a page has its chapter's title, a skip
    link to the chapter, previous/next links in order, and figures with real descriptions."""
    walk.assert_passed("accessible", PAGES)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_the_chapters_are_walked_by_keyboard_from_the_index_and_back(walk):
    """Tab and Enter alone: the index's first link opens the first chapter; on each
    chapter Tab reaches the skip link, then previous, index and next in that order;
    Enter on next opens the next chapter, and the last chapter's index link returns."""
    walk.assert_passed("keyboard", [*PAGES, BACK_TO_THE_INDEX])


@pytest.mark.infrastructure
@pytest.mark.browser
def test_formulas_and_code_cells_are_no_tab_stops(walk):
    """One stop per cell at most: a code cell or an output only while it scrolls; no formula."""
    walk.assert_passed("tab_stops", CHAPTERS)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_figures_have_a_short_alt_and_the_whole_description_one_step_away(walk):
    walk.assert_passed("descriptions", CHAPTERS)


@pytest.mark.infrastructure
@pytest.mark.browser
def test_videos_are_described_and_hold_still_for_readers_who_ask_for_reduced_motion(
    walk,
):
    """Every page with an animation (and any other page with a video) is checked."""
    animated = [
        name
        for name, path in zip(CHAPTERS, NOTEBOOKS)
        if "animation_html(" in path.read_text(encoding="utf-8")
    ]
    assert animated
    assert not walk.failures["motion"], "\n".join(walk.failures["motion"])
    assert set(animated) <= set(walk.checked["motion"]), walk.checked["motion"]
