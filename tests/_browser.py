"""Headless Chromium for the tests that open pages (the HTML report, the docs site):
Debian's browser driven by Playwright, and a check that a screenshot is not blank."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

CHROMIUM = Path("/usr/bin/chromium")


def playwright_chromium():
    """Playwright's sync context for Debian's Chromium; a skip without it, a failure
    under ``CI=true`` (where the browser test must run)."""
    if not CHROMIUM.exists():
        message = f"Chromium not found at {CHROMIUM} (apt-get install chromium)"
        if os.environ.get("CI", "").lower() == "true":
            pytest.fail(message + "; under CI=true the browser test must run")
        pytest.skip(message)
    sync_api = pytest.importorskip("playwright.sync_api")
    return sync_api.sync_playwright()


def not_blank(png: Path) -> tuple[float, float]:
    """(standard deviation of the grey levels, share of non-white pixels)."""
    from matplotlib.image import imread

    grey = imread(png)[..., :3].mean(axis=2)
    return float(grey.std()), float((grey < 0.95).mean())
