"""The static edition's navigation (``make site``, ``tools/editions.py``), read from its HTML.

Each page's title is its chapter's title (the notebook's first ``# `` heading,
never the file name); the index links every chapter in order; every chapter
page links the index and its previous and next chapters, in a labelled
``<nav>`` at its top and again at its end, with real links (an ``href``, text,
no ``tabindex="-1"``): every page is reachable from the index and leads back
to it, next and previous walk the chapters in order, the first chapter has no
previous one and the last no next one.  The quick tests check the titles and
the links the builder computes; the infrastructure ones build a site (a small
course made here; the real chapters' site is built once per run and shared with
the browser suite) and parse the pages.
``tests/browser/test_static_site.py`` follows the same links in Chromium, by
keyboard, and runs axe-core on every page.  The start page is the site's first
page, and the links the notebooks' Markdown makes between notebooks
(``02_inverse_kinematics.ipynb``, written by ``tools/course_map.py``) lead to
the pages (``02_inverse_kinematics.html``).
"""

import functools
import html.parser
import json
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import editions  # noqa: E402

NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


def markdown_cell(source):
    return {"cell_type": "markdown", "metadata": {}, "source": source}


def code_cell(source):
    return {
        "cell_type": "code",
        "metadata": {},
        "source": source,
        "outputs": [],
        "execution_count": None,
    }


def notebook(*cells):
    return {
        "cells": list(cells),
        "metadata": {
            "kernelspec": {"name": "python3", "display_name": "Python 3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


# --- titles ---------------------------------------------------------------------------------------------------


def test_the_title_is_the_first_level_one_heading_as_plain_text():
    book = notebook(
        code_cell("# a comment, not a heading\nx = 1"),
        markdown_cell(
            ["## Setup first\n", "\n", "```python\n", "# in a fence\n", "```\n"]
        ),
        markdown_cell(
            "#not a heading\n# Chapter 9: **Fast** `ik` with [SciPy](https://x.org) ##\n"
        ),
        markdown_cell("# A later title\n"),
    )
    assert editions.chapter_title(book, "09_fast_ik") == "Chapter 9: Fast ik with SciPy"


def test_without_a_level_one_heading_the_first_heading_then_the_file_name():
    assert (
        editions.chapter_title(
            notebook(markdown_cell("Text.\n\n### Third\n## Second\n")), "x"
        )
        == "Third"
    )
    assert (
        editions.chapter_title(notebook(markdown_cell("No heading at all.")), "09_x")
        == "09_x"
    )
    # a heading whose text is only markup is no title
    assert editions.chapter_title(
        notebook(markdown_cell("# <br>\n## Real\n")), "x"
    ) == ("Real")


def first_level_one_heading(path):
    """The text after ``# `` on the first such line of the notebook's Markdown, read plainly."""
    for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    raise AssertionError(f"{path.name} has no '# ' heading")


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[path.name for path in NOTEBOOKS])
def test_each_chapter_is_titled_by_its_heading_not_its_file_name(path):
    title = editions.chapter_title(
        json.loads(path.read_text(encoding="utf-8")), path.stem
    )
    assert title == first_level_one_heading(path)
    assert path.stem not in title


def test_the_chapter_titles_tell_the_pages_apart():
    titles = [
        editions.chapter_title(json.loads(path.read_text(encoding="utf-8")), path.stem)
        for path in NOTEBOOKS
    ]
    assert len(set(titles)) == len(titles) == len(NOTEBOOKS) >= 2, titles


# --- links, as computed -------------------------------------------------------------------------------------------


def walk(links, pages, start, direction):
    """Pages visited from ``start`` following ``direction`` links (each page at most once)."""
    visited = [start]
    for _ in range(len(pages)):
        step = links[pages.index(visited[-1])][direction]
        if step is None:
            return visited
        visited.append(step["href"])
    raise AssertionError(f"the {direction} links go round in a circle: {visited}")


@pytest.mark.parametrize("count", [1, 2, 5])
def test_previous_and_next_walk_the_chapters_in_order(count):
    pages = [f"{number:02d}_chapter.html" for number in range(count)]
    titles = [f"Chapter {number}" for number in range(count)]
    links = editions.navigation(pages, titles)
    assert walk(links, pages, pages[0], "next") == pages
    assert walk(links, pages, pages[-1], "previous") == pages[::-1]
    assert links[0]["previous"] is None and links[-1]["next"] is None
    for number, link in enumerate(links):
        assert link["index"] == {
            "href": editions.INDEX_PAGE,
            "title": editions.INDEX_LINK_TEXT,
        }
        for direction, other in (("previous", number - 1), ("next", number + 1)):
            if 0 <= other < count:
                assert link[direction] == {"href": pages[other], "title": titles[other]}


def test_links_between_notebooks_lead_to_their_pages():
    pages = {"00_start_here", "02_ik"}
    markdown = (
        "[Next: Chapter 2, IK](02_ik.ipynb) and [its setup](02_ik.ipynb#Setup); "
        "[start](00_start_here.ipynb); [elsewhere](https://x.org/02_ik.ipynb), "
        "[not on the site](99_gone.ipynb), [a folder](sub/02_ik.ipynb), `02_ik.ipynb`"
    )
    assert editions.site_links(markdown, pages) == (
        "[Next: Chapter 2, IK](02_ik.html) and [its setup](02_ik.html#Setup); "
        "[start](00_start_here.html); [elsewhere](https://x.org/02_ik.ipynb), "
        "[not on the site](99_gone.ipynb), [a folder](sub/02_ik.ipynb), `02_ik.ipynb`"
    )


def test_navigation_needs_a_title_per_page():
    with pytest.raises(ValueError, match="one title per page: 2 pages, 1 titles"):
        editions.navigation(["a.html", "b.html"], ["A"])


# --- links, as built ---------------------------------------------------------------------------------------------


class Page(html.parser.HTMLParser):
    """What a page shows of its navigation: title, landmarks and every link of every ``<nav>``."""

    def __init__(self, text):
        super().__init__()
        self.title = ""
        self.navs = []  # {"label", "region", "links": [{"href", "rel", "text", "tabindex"}]}
        self.mains = 0
        self.open = []  # the open header/footer/main/nav/a elements, innermost last
        self.in_title = False
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == "title":
            self.in_title = True
        if tag == "main":
            self.mains += 1
        if tag in ("header", "footer", "main"):
            self.open.append(tag)
        elif tag == "nav":
            regions = [
                name for name in self.open if name in ("header", "footer", "main")
            ]
            self.navs.append(
                {
                    "label": attrs.get("aria-label"),
                    "region": regions[-1] if regions else None,
                    "hidden": "hidden" in attrs or attrs.get("aria-hidden") == "true",
                    "links": [],
                }
            )
            self.open.append(tag)
        elif tag == "a" and "nav" in self.open:
            self.navs[-1]["links"].append(
                {
                    "href": attrs.get("href"),
                    "rel": attrs.get("rel"),
                    "tabindex": attrs.get("tabindex"),
                    "text": "",
                }
            )
            self.open.append(tag)

    def handle_endtag(self, tag):
        if tag == "title":
            self.in_title = False
        if tag in self.open:
            del self.open[len(self.open) - 1 - self.open[::-1].index(tag) :]

    def handle_data(self, data):
        if self.in_title:
            self.title += data
        if self.open and self.open[-1] == "a":
            self.navs[-1]["links"][-1]["text"] += data


@functools.cache
def read_page(site, name):
    """The page ``name`` of a built ``site``, parsed once (the sites are not changed once built)."""
    return Page((site / name).read_text(encoding="utf-8"))


class Links(html.parser.HTMLParser):
    """Every ``href`` of a page's links, with the link's text."""

    def __init__(self, text):
        super().__init__()
        self.links = []  # [href, text]
        self.depth = 0
        self.feed(text)
        self.close()

    def handle_starttag(self, tag, attrs):
        if tag == "a":
            self.links.append([dict(attrs).get("href"), ""])
            self.depth += 1

    def handle_endtag(self, tag):
        if tag == "a":
            self.depth = max(self.depth - 1, 0)

    def handle_data(self, data):
        if self.depth:
            self.links[-1][1] += data


def local_links(site, name):
    """``(file, text)`` of every link of a page to another file of the site (anchors and URLs left out)."""
    page = Links((site / name).read_text(encoding="utf-8"))
    return [
        (href.split("#")[0], " ".join(text.split()))
        for href, text in page.links
        if href and not href.startswith(("#", "http:", "https:", "mailto:"))
    ]


def check_site(site, notebooks):
    """Every navigation property of a built site whose chapters are ``notebooks`` (in order)."""
    pages = [editions.page_name(path) for path in notebooks]
    titles = [
        editions.chapter_title(json.loads(path.read_text(encoding="utf-8")), path.stem)
        for path in notebooks
    ]
    index = read_page(site, editions.INDEX_PAGE)
    assert index.mains == 1
    (chapters,) = [nav for nav in index.navs if nav["links"]]
    assert chapters["label"], "the index's list of chapters is a labelled <nav>"
    assert [link["href"] for link in chapters["links"]] == pages
    assert [" ".join(link["text"].split()) for link in chapters["links"]] == titles

    reached = {editions.INDEX_PAGE}
    to_visit = [editions.INDEX_PAGE]
    while to_visit:  # every page reachable from the index, by links alone
        name = to_visit.pop()
        for nav in read_page(site, name).navs:
            for link in nav["links"]:
                if link["href"] not in reached:
                    assert (site / link["href"]).is_file(), (name, link)
                    reached.add(link["href"])
                    to_visit.append(link["href"])
    assert reached == {editions.INDEX_PAGE, *pages}

    following = {}
    for number, (name, title) in enumerate(zip(pages, titles)):
        page = read_page(site, name)
        assert page.title == f"{title} · {editions.SITE_TITLE}", name
        assert name.removesuffix(".html") not in page.title
        assert page.mains == 1, f"{name}: one main landmark"
        navs = [nav for nav in page.navs if nav["region"] in ("header", "footer")]
        assert [nav["region"] for nav in navs] == ["header", "footer"], page.navs
        labels = [nav["label"] for nav in navs]
        assert all(labels) and len(set(labels)) == 2, (
            f"{name}: each <nav> needs its own aria-label: {labels}"
        )
        expected = (
            ([("prev", pages[number - 1], titles[number - 1])] if number > 0 else [])
            + [(None, editions.INDEX_PAGE, editions.INDEX_LINK_TEXT)]
            + (
                [("next", pages[number + 1], titles[number + 1])]
                if number + 1 < len(pages)
                else []
            )
        )
        for nav in navs:
            assert not nav["hidden"], name
            for link in nav["links"]:
                assert link["tabindex"] is None, (
                    f"{name}: {link} is not keyboard reachable"
                )
            shown = [
                (link["rel"], link["href"], " ".join(link["text"].split()))
                for link in nav["links"]
            ]
            assert shown == expected, (name, nav["label"], shown)
        following[name] = {rel: href for rel, href, _ in expected if rel}
    # the chains: next from the first chapter visits every chapter in order, previous from the last goes back
    chain = [pages[0]]
    while "next" in following[chain[-1]] and len(chain) <= len(pages):
        chain.append(following[chain[-1]]["next"])
    assert chain == pages
    back = [pages[-1]]
    while "prev" in following[back[-1]] and len(back) <= len(pages):
        back.append(following[back[-1]]["prev"])
    assert back == pages[::-1]
    assert "prev" not in following[pages[0]] and "next" not in following[pages[-1]]


@pytest.mark.infrastructure
def test_a_small_course_gets_titled_pages_linked_both_ways(tmp_path):
    """Three chapters whose file names say nothing of their titles, one titled below a lower heading."""
    source = tmp_path / "notebooks"
    source.mkdir()
    chapters = {
        "b_first.ipynb": notebook(
            markdown_cell("# Alpha: *where* the tip is\n\nText."), code_cell("x = 1")
        ),
        "c_second.ipynb": notebook(
            markdown_cell("## Before\n"), markdown_cell("# Beta & 'gamma' < delta\n")
        ),
        "d_third.ipynb": notebook(markdown_cell("# Delta\n"), code_cell("y = 2")),
    }
    for name, book in chapters.items():
        (source / name).write_text(json.dumps(book), encoding="utf-8")
    site = tmp_path / "site"
    written = editions.build_site(source, site)
    assert [path.name for path in written] == [
        "index.html",
        "b_first.html",
        "c_second.html",
        "d_third.html",
    ]
    notebooks = sorted(source.glob("*.ipynb"))
    check_site(site, notebooks)
    assert [read_page(site, editions.page_name(path)).title for path in notebooks] == [
        "Alpha: where the tip is · twolink",
        "Beta & 'gamma' < delta · twolink",
        "Delta · twolink",
    ]


@pytest.mark.infrastructure
def test_the_course_site_is_titled_and_linked_in_chapter_order(course_site):
    """The site of the real chapters (tests/conftest.py's ``course_site``: one build per run,
    shared with tests/browser/test_static_site.py)."""
    site = course_site
    check_site(site, NOTEBOOKS)
    for path in NOTEBOOKS:
        title = read_page(site, editions.page_name(path)).title
        assert title == f"{first_level_one_heading(path)} · {editions.SITE_TITLE}"
    # the start page first; the links the notebooks make between them lead to pages that exist
    assert NOTEBOOKS[0].name == "00_start_here.ipynb"
    start = editions.page_name(NOTEBOOKS[0])
    for path in NOTEBOOKS:
        name = editions.page_name(path)
        links = local_links(site, name)
        assert not [href for href, _ in links if href.endswith(".ipynb")], name
        for href, _ in links:
            assert (site / href).is_file(), (name, href)
        targets = {href for href, _ in links}
        if path == NOTEBOOKS[0]:
            assert {editions.page_name(other) for other in NOTEBOOKS[1:]} <= targets
        else:
            assert start in targets, f"{name} does not link the start page"
