"""The documentation site: its landing page and an example page open in Chromium with
their figures, and the gallery holds every numbered example with the figures it made.

The site is built by ``python -m sphinx -W -b html docs docs/_build/html`` (README;
``.ci/run`` builds it before the tests, warnings as errors, every example run); these
tests look at what that build wrote. A figure that is missing — an image file the page
names that is not there, or an example that drew nothing — fails them.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest

from _browser import CHROMIUM, not_blank, playwright_chromium

ROOT = Path(__file__).resolve().parents[1]
SITE = ROOT / "docs" / "_build" / "html"
EXAMPLES = sorted((ROOT / "examples").glob("[0-9][0-9]_*.py"))
BROWSER_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking"]
BUILD = "python -m sphinx -W -b html docs docs/_build/html"


@pytest.fixture(scope="module")
def site() -> Path:
    if not (SITE / "index.html").is_file():
        message = f"the documentation site is not built: run `{BUILD}` first"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message + " (.ci/run builds it before the tests)")
        pytest.skip(message)
    return SITE


def _images(page: Path) -> list[str]:
    return re.findall(r'<img[^>]*\ssrc="([^"]+)"', page.read_text(encoding="utf-8"))


def test_the_gallery_holds_every_example_with_its_figures(site):
    assert 8 <= len(EXAMPLES) <= 12
    index = (site / "auto_examples" / "index.html").read_text(encoding="utf-8")
    for example in EXAMPLES:
        page = site / "auto_examples" / f"{example.stem}.html"
        assert page.is_file(), f"{example.name} has no page"
        assert f"{example.stem}.html" in index, f"{example.name} is not in the gallery"
        figures = [src for src in _images(page) if "sphx_glr_" in src]
        assert figures, f"{example.name} drew no figure"
        for src in figures:  # every figure the page names was written
            assert (page.parent / src).is_file(), f"{example.name}: {src} is missing"


@pytest.mark.parametrize(
    ("page", "least"),
    [("index.html", 1), ("auto_examples/04_fit_state_space.html", 1)],
)
def test_a_page_renders_with_its_figures(site, page, least, tmp_path):
    """The page loads, every image on it is decoded (naturalWidth > 0; a missing file is
    0), it shows at least ``least`` figures made by the gallery, and the screenshots of
    the page and of its first figure are not blank."""
    shot = tmp_path / "page.png"
    with playwright_chromium() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=BROWSER_ARGS)
        try:
            view = browser.new_page(viewport={"width": 1280, "height": 1100})
            errors: list[str] = []
            view.on("pageerror", lambda e: errors.append(str(e)))
            view.goto((site / page).as_uri())
            view.wait_for_load_state("load")
            images = view.evaluate(
                "Array.from(document.images).map(i => [i.getAttribute('src'), "
                "i.complete ? i.naturalWidth : 0])"
            )
            view.screenshot(path=str(shot), full_page=False)
            figure = view.locator("img[src*='sphx_glr_']").first
            figure.scroll_into_view_if_needed()
            figure.screenshot(path=str(shot.with_suffix(".figure.png")))
        finally:
            browser.close()
    assert not errors, errors
    assert images and all(width > 0 for _, width in images), images
    assert sum("sphx_glr_" in src for src, _ in images) >= least, images
    for png in (shot, shot.with_suffix(".figure.png")):
        spread, ink = not_blank(png)
        assert spread > 0.05 and ink > 0.02, f"{page}: blank {png.name} {spread} {ink}"


def test_equations_render_offline(site):
    """A theory page's equations are typeset by the MathJax the site carries
    (``_static/mathjax``), every request staying on the local files: the site reads
    right without network (this machine has none, as many users' offshore have none)."""
    page = site / "theory" / "retardation.html"
    text = page.read_text(encoding="utf-8")
    assert "_static/mathjax/tex-chtml.js" in text and "cdn.jsdelivr" not in text
    assert (site / "_static" / "mathjax" / "tex-chtml.js").is_file()
    with playwright_chromium() as p:
        browser = p.chromium.launch(executable_path=str(CHROMIUM), args=BROWSER_ARGS)
        try:
            view = browser.new_page()
            requests: list[str] = []
            view.on("request", lambda r: requests.append(r.url))
            view.goto(page.as_uri())
            view.wait_for_function(
                "document.querySelectorAll('mjx-container').length > 0", timeout=30_000
            )
            typeset = view.evaluate("document.querySelectorAll('mjx-container').length")
            raw = view.evaluate("document.body.innerText.includes('\\\\int')")
        finally:
            browser.close()
    assert typeset >= 3, typeset
    assert not raw  # no equation left as TeX source
    assert all(u.startswith(("file:", "data:")) for u in requests), requests
