"""Headless Chromium for the tests of the viewer and the gallery.

Chromium comes from Debian's package ``chromium``.  Where it is missing, the test set-up
installs it when it may (running as root with apt-get, and ``CI`` set, as on the project's CI
machines, or ``POLYLOOPS_INSTALL_BROWSER=1``); elsewhere the browser tests are skipped with
the reason.  Playwright (a test extra) drives it; it is given Debian's binary, never a browser
of its own.
"""

from __future__ import annotations

import os
import shutil
import subprocess

FLAGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def find_chromium() -> tuple[str | None, str]:
    """The Chromium binary, installing Debian's package if allowed; else ``None`` and why."""
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path, ""
    allowed = os.environ.get("CI") == "true" or os.environ.get("POLYLOOPS_INSTALL_BROWSER") == "1"
    if not allowed:
        return None, "headless Chromium is not installed (apt-get install chromium; CI installs it)"
    if not hasattr(os, "geteuid") or os.geteuid() != 0 or shutil.which("apt-get") is None:
        return None, "headless Chromium is missing and cannot be installed here (needs root and apt-get)"
    import fcntl
    import tempfile

    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive"}
    # Test workers run in parallel: one installs, the others wait for it, then find it.
    with open(os.path.join(tempfile.gettempdir(), "polyloops-chromium.lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if shutil.which("chromium") is None:
            try:
                subprocess.run(["apt-get", "update", "-qq"], check=True, capture_output=True, timeout=300,
                               env=env)
                subprocess.run(["apt-get", "install", "-y", "-qq", "chromium"], check=True,
                               capture_output=True, timeout=900, env=env)
            except (subprocess.SubprocessError, OSError) as err:
                return None, f"installing Debian's chromium failed: {err}"
    path = shutil.which("chromium")
    return (path, "") if path else (None, "Debian's chromium installed no chromium command")
