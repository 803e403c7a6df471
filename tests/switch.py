"""Tests choose a compiled part or its Python twin through the switchboard
(:mod:`polyloops.core.compiled`), never through module flags."""

from collections.abc import Iterator
from contextlib import contextmanager

import pytest

from polyloops.core import compiled


@contextmanager
def running(name: str, compiled_part: bool) -> Iterator[None]:
    """Inside the block, part ``name`` runs compiled (``compiled_part``; the test skips, saying
    why, when it does not run here) or as its Python twin."""
    if compiled_part:
        if not compiled.in_use(name):
            pytest.skip(f"the compiled part {name} {compiled.why_not(name)}")
        yield
    else:
        with compiled.pure_python(name):
            yield


def needs(name: str) -> pytest.MarkDecorator:
    """Skip a test of a compiled part when that part does not run here."""
    return pytest.mark.skipif(not compiled.in_use(name), reason=f"the compiled part {name} does not run here "
                              f"(not built, or {compiled.ENV} names it)")
