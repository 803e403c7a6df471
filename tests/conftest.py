import os
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

sys.path.insert(0, str(Path(__file__).parent))

# A deterministic CI profile (40 examples a property keeps the default run under 3 minutes on
# 2 cores); "dev" explores more (HYPOTHESIS_PROFILE=dev).
settings.register_profile("ci", max_examples=40, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("dev", max_examples=200, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


def pytest_addoption(parser):
    parser.addoption("--run-slow", action="store_true", help="also run tests marked slow")


# Doctests of modules whose examples need a compiled part (the arrangement search has no Python
# twin: without it, plantri's generator makes the catalog).
DOCTESTS_NEEDING = {"src/polyloops/generate/loops/arrangements.py": "arrangements"}


def pytest_collection_modifyitems(config, items):
    from polyloops.core import compiled

    for item in items:
        part = DOCTESTS_NEEDING.get(item.nodeid.split("::")[0])
        if part is not None and not compiled.in_use(part):
            item.add_marker(pytest.mark.skip(reason=f"the compiled part {part} {compiled.why_not(part)}"))
    if config.getoption("--run-slow"):
        return
    skip = pytest.mark.skip(reason="slow: run with --run-slow")
    for item in items:
        if "slow" in item.keywords:
            item.add_marker(skip)


@pytest.fixture(scope="session")
def chromium():
    """One headless Chromium for the session (Debian's, driven by Playwright), or a skip that
    says why there is none."""
    from browser import FLAGS, find_chromium

    path, why = find_chromium()
    if path is None:
        pytest.skip(why)
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        pytest.skip("playwright (a test extra) is not installed")
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=path, args=FLAGS)
        yield browser
        browser.close()
