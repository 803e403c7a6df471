"""Headless Chromium for the tests of the viewer and the gallery.

Chromium comes from Debian's package ``chromium``, installed by ``.ci/run`` on CI (the tests
install nothing); where it is missing, the browser tests are skipped with the reason.
Playwright (a test extra) drives it; it is given Debian's binary, never a browser of its own.
"""

from __future__ import annotations

import shutil

FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def find_chromium() -> tuple[str | None, str]:
    """The Chromium binary, or ``None`` and why the browser tests skip.  The tests install
    nothing: on CI, ``.ci/run`` installs Debian's ``chromium`` before the tests run."""
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path, ""
    return None, "headless Chromium is not installed (Debian: apt-get install chromium; .ci/run installs it)"
