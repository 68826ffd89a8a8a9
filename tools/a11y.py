"""Accessibility checks with axe-core in headless Chromium: the static site's pages, counted by rule.

``python tools/a11y.py [--site DIR]`` builds the static edition (or uses
``DIR`` when it holds one), opens every page in Chromium, runs axe-core on it
and prints the violations as a table: rule, impact, elements, pages.  The
browser suite (``tests/browser/``) asserts on the same results through
:func:`violations`.

axe-core's script comes from the ``axe-playwright-python`` package (which
ships ``axe.min.js``; pinned in ``requirements.txt``), injected into the page
by Playwright: nothing is fetched from the network.
"""

from __future__ import annotations

import argparse
import collections
import functools
import http.server
import json
import pathlib
import sys
import tempfile
import threading
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))

import lab_browser  # noqa: E402

#: The impacts the course allows none of in what it controls.
BLOCKING = ("critical", "serious")


def axe_source() -> str:
    """The text of ``axe.min.js`` (axe-core) shipped by the ``axe-playwright-python`` package."""
    import axe_playwright_python

    return (
        pathlib.Path(axe_playwright_python.__file__).parent / "axe.min.js"
    ).read_text(encoding="utf-8")


#: How long axe-core may take on one page, milliseconds.
AXE_BUDGET_MS = 300_000


def violations(page: Any, include: Sequence[str] | None = None) -> list[dict[str, Any]]:
    """axe-core's violations on the page as it is now (axe's default rules: WCAG 2.x A and AA, best practices).

    ``include``: CSS selectors limiting the check to those parts of the page
    (e.g. a notebook's outputs in JupyterLab); ``None`` checks the whole
    page. Each violation is axe's result: ``id`` (the rule), ``impact``,
    ``help`` and ``nodes`` (the elements: ``target`` selectors and the
    start of their ``html``).
    """
    start_violations(page, include)
    return finish_violations(page)


def start_violations(page: Any, include: Sequence[str] | None = None) -> None:
    """Start axe-core on the page as it is now and return at once (as :func:`violations`).

    :func:`finish_violations` waits for the result: meanwhile another page of
    the browser can work (a page of its own runs in a process of its own).
    """
    if not page.evaluate("() => typeof window.axe !== 'undefined'"):
        page.add_script_tag(content=axe_source())
    context = (
        "document"
        if include is None
        else json.dumps({"include": [[selector] for selector in include]})
    )
    page.evaluate(
        f"""() => {{
            window.twolinkAxe = {{done: false}};
            axe.run({context}, {{resultTypes: ['violations']}}).then(result => {{
                window.twolinkAxe = {{done: true, violations: result.violations.map(v => ({{
                    id: v.id, impact: v.impact, help: v.help,
                    nodes: v.nodes.map(n => ({{target: n.target, html: n.html.slice(0, 200)}})),
                }}))}};
            }}, error => {{ window.twolinkAxe = {{done: true, error: String(error)}}; }});
        }}"""
    )


def finish_violations(
    page: Any, budget_ms: float = AXE_BUDGET_MS
) -> list[dict[str, Any]]:
    """The violations :func:`start_violations` found on the page, within ``budget_ms``."""
    page.wait_for_function(
        "() => window.twolinkAxe.done", polling=100, timeout=budget_ms
    )
    found = page.evaluate("() => window.twolinkAxe")
    if "error" in found:
        raise RuntimeError(f"axe-core failed: {found['error']}")
    return found["violations"]


def blocking(found: list[dict[str, Any]]) -> list[str]:
    """One line per critical or serious violation: rule, impact, count and the first elements."""
    return [
        f"{violation['id']} ({violation['impact']}, {len(violation['nodes'])} elements): "
        f"{violation['help']}; e.g. {[node['html'] for node in violation['nodes'][:2]]}"
        for violation in found
        if violation["impact"] in BLOCKING
    ]


def by_rule(found: dict[str, list[dict[str, Any]]]) -> list[tuple[str, str, int, int]]:
    """``(rule, impact, elements, pages)`` over pages' violations, worst impact first."""
    order = {"critical": 0, "serious": 1, "moderate": 2, "minor": 3}
    elements: collections.Counter[str] = collections.Counter()
    pages: collections.Counter[str] = collections.Counter()
    impact: dict[str, str] = {}
    for page_violations in found.values():
        for violation in page_violations:
            elements[violation["id"]] += len(violation["nodes"])
            pages[violation["id"]] += 1
            impact[violation["id"]] = violation["impact"] or "?"
    return sorted(
        ((rule, impact[rule], elements[rule], pages[rule]) for rule in elements),
        key=lambda row: (order.get(row[1], 9), -row[2], row[0]),
    )


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: Any) -> None:  # noqa: A002
        pass  # no line per request


@contextmanager
def served(folder: pathlib.Path) -> Iterator[str]:
    """A local HTTP server for ``folder``; yields its base URL."""
    handler = functools.partial(_QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}"
    finally:
        server.shutdown()
        server.server_close()


#: How long a page may take to load and typeset its formulas, milliseconds.
SETTLE_BUDGET_MS = 60_000


def settle(page: Any, budget_ms: float = SETTLE_BUDGET_MS) -> None:
    """Wait until the page has loaded and MathJax (if any) has typeset it, each within ``budget_ms``."""
    page.wait_for_load_state("load", timeout=budget_ms)
    if page.evaluate("() => Boolean(window.MathJax && window.MathJax.Hub)"):
        # a flag MathJax's queue sets once it has typeset the page (and loaded its fonts)
        page.evaluate(
            "() => { window.twolinkTypeset = false; MathJax.Hub.Queue(() => { window.twolinkTypeset = true; }); }"
        )
        page.wait_for_function(
            "() => window.twolinkTypeset === true", timeout=budget_ms
        )
    page.wait_for_load_state("networkidle", timeout=budget_ms)


def site_violations(site: pathlib.Path) -> dict[str, list[dict[str, Any]]]:
    """axe-core's violations on every HTML page of the built site, by page name."""
    found = {}
    with served(site) as url, lab_browser.chromium() as browser:
        context = browser.new_context(viewport={"width": 1280, "height": 900})
        page = context.new_page()
        for path in sorted(site.glob("*.html")):
            page.goto(f"{url}/{path.name}")
            settle(page)
            found[path.name] = violations(page)
        context.close()
    return found


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--site", help="a built site to check (default: build one)")
    args = parser.parse_args(argv)
    reason = lab_browser.missing()
    if reason:
        print(f"a11y: skipped: {reason}")
        return 0
    import editions

    with tempfile.TemporaryDirectory() as scratch:
        site = pathlib.Path(args.site) if args.site else pathlib.Path(scratch)
        if not args.site:
            editions.build_site(ROOT / "notebooks", site)
        found = site_violations(site)
    rows = by_rule(found)
    print(f"# axe-core on the static site: {len(found)} pages\n")
    print("| rule | impact | elements | pages |\n|---|---|---|---|")
    for rule, impact, elements, pages in rows:
        print(f"| {rule} | {impact} | {elements} | {pages} |")
    blocking = sum(row[2] for row in rows if row[1] in BLOCKING)
    print(f"\n{blocking} elements with critical or serious violations.")
    return 0


if __name__ == "__main__":
    sys.exit(main())
