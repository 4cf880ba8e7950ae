"""A headless Chromium driven by Playwright, for what looks at the explorer's page
without a person: the browser tests, the frame-rate script and the documentation's
screenshots. Playwright's own browser download is not used: the system's Chromium (Debian's
``chromium`` package) is, found by :func:`chromium_executable`."""

from __future__ import annotations

import os
import shutil

#: Flags for a headless Chromium on a machine without a display or outside network (no
#: sandbox as root; no background connections, which a closed network refuses).
CHROMIUM_FLAGS = ("--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                  "--disable-sync", "--no-first-run")


def chromium_executable() -> str | None:
    """The Chromium to drive: ``$BARANOV_CHROMIUM`` if set, else the first of
    ``chromium``, ``chromium-browser``, ``google-chrome`` on the PATH; None if none is."""
    if os.environ.get("BARANOV_CHROMIUM"):
        return os.environ["BARANOV_CHROMIUM"]
    return next((path for name in ("chromium", "chromium-browser", "google-chrome") if (path := shutil.which(name))), None)


def missing_browser() -> str | None:
    """Why no page can be driven here (Playwright or Chromium missing), or None."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install -e '.[test]')"
    if chromium_executable() is None:
        return "no Chromium on the PATH (Debian: apt-get install chromium; or set BARANOV_CHROMIUM)"
    return None


def launch_chromium(playwright):
    """A headless Chromium browser of ``playwright`` (``sync_playwright()``'s object)."""
    return playwright.chromium.launch(executable_path=chromium_executable(), args=list(CHROMIUM_FLAGS))
