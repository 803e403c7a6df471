"""The switchboard of the compiled parts: one table of the eight C extensions, whether each was
built, whether it is in use, and one way to run their Python twins instead.

Each part is optional (``pip install`` builds it when a C compiler and the Python headers are
there) and has a twin that computes the same thing more slowly: the twin runs when the part was
not built, when the environment variable ``POLYLOOPS_PURE_PYTHON`` names it (``all``, or names
separated by commas: ``POLYLOOPS_PURE_PYTHON=canonical,torus``), or inside
:func:`pure_python`.  The arrangement search's twin is a generator, not a function: without it
the catalog runs plantri's generator (the same records).

>>> [part.name for part in PARTS.values()]
['canonical', 'cycles', 'raster', 'strips', 'arrangements', 'torus', 'regions', 'squares']
>>> with pure_python("canonical"):
...     in_use("canonical")
False
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from functools import lru_cache
from types import ModuleType

from polyloops.core.errors import PolyloopsError

__all__ = ["ENV", "PARTS", "CompiledError", "CompiledPart", "built", "in_use", "load", "pure_python",
           "require", "status", "why_not"]

ENV = "POLYLOOPS_PURE_PYTHON"


class CompiledError(PolyloopsError, ValueError):
    """A name that is no compiled part (in ``POLYLOOPS_PURE_PYTHON`` or :func:`pure_python`)."""


@dataclass(frozen=True)
class CompiledPart:
    """One C extension and the Python code that stands in for it."""

    name: str  # the short name POLYLOOPS_PURE_PYTHON and pure_python() take
    module: str  # the extension's module
    what: str  # what it computes
    twin: str  # what runs instead when it is not in use


PARTS: dict[str, CompiledPart] = {part.name: part for part in (
    CompiledPart("canonical", "polyloops.core._canonical", "canonical forms of small structures",
                 "the Python canonical form (polyloops.core.canonical)"),
    CompiledPart("cycles", "polyloops.core._cycles", "the count of valid additions",
                 "the Python search of the addition graph (polyloops.core.moves)"),
    CompiledPart("raster", "polyloops.render._raster", "the pictures' depth buffer",
                 "the numpy depth buffer (polyloops.render.raster)"),
    CompiledPart("strips", "polyloops.generate.plantri._strips", "the strip filter of plantri's maps",
                 "the numpy filter (polyloops.generate.plantri.quadrangulations)"),
    CompiledPart("arrangements", "polyloops.generate.loops._arrangements",
                 "the arrangement search of the loops generator",
                 "plantri's generator, which gives the same catalog records"),
    CompiledPart("torus", "polyloops.generate.torus._torus", "both stages of the torus search",
                 "the Python torus search (polyloops.generate.torus.stages)"),
    CompiledPart("regions", "polyloops.generate.torus._regions", "the torus search's region search",
                 "the Python region search (polyloops.generate.torus.regions)"),
    CompiledPart("squares", "polyloops.generate.torus._squares", "the torus search's first stage",
                 "the Python listing of square-tiled surfaces (polyloops.generate.torus.squares)"),
)}

_forced: list[frozenset[str]] = []  # the names pure_python() blocks force, innermost last
_modules: dict[str, ModuleType | None] = {}  # imported once: None when not built


def _names(words: str | tuple[str, ...], where: str) -> frozenset[str]:
    items = [w.strip() for w in (words.split(",") if isinstance(words, str) else words) if w.strip()]
    if "all" in items:
        return frozenset(PARTS)
    unknown = [w for w in items if w not in PARTS]
    if unknown:
        raise CompiledError(f"{where}: {unknown[0]!r} is no compiled part (all, or some of "
                            f"{', '.join(PARTS)})")
    return frozenset(items)


@lru_cache(maxsize=8)
def _from_env(value: str) -> frozenset[str]:
    # parsed once per value: in_use() sits on hot paths (every canonical form asks it)
    return _names(value, ENV)


def forced() -> frozenset[str]:
    """The parts whose twins run now: named by ``POLYLOOPS_PURE_PYTHON`` or a :func:`pure_python`
    block."""
    out = _from_env(os.environ.get(ENV, ""))
    for names in _forced:
        out |= names
    return out


def built(name: str) -> bool:
    """Whether the install built the part (whatever is forced)."""
    if name not in PARTS:
        raise CompiledError(f"{name!r} is no compiled part")
    if name not in _modules:
        try:
            _modules[name] = importlib.import_module(PARTS[name].module)
        except ImportError:
            _modules[name] = None
    return _modules[name] is not None


def load(name: str) -> ModuleType | None:
    """The part's module when it was built and is in use, else ``None`` (run the twin)."""
    return _modules[name] if built(name) and name not in forced() else None


def why_not(name: str) -> str:
    """Why the part does not run, in words (for messages): not built, or switched to its twin.

    >>> with pure_python("torus"):
    ...     why_not("torus")
    'is switched to its Python twin (POLYLOOPS_PURE_PYTHON, or pure_python())'
    """
    if not built(name):
        return "was not built (a C compiler and the Python headers are needed at install time)"
    return f"is switched to its Python twin ({ENV}, or pure_python())"


def require(name: str) -> ModuleType:
    """The part's module, for code that asked :func:`in_use` first; raises
    :class:`CompiledError` when it does not run."""
    part = load(name)
    if part is None:
        raise CompiledError(f"the compiled part {name!r} {why_not(name)}")
    return part


def in_use(name: str) -> bool:
    """Whether the part runs (built, and not forced to its twin)."""
    return load(name) is not None


@contextmanager
def pure_python(*names: str) -> Iterator[None]:
    """Run the Python twins of the named parts (all of them when none is named) inside the
    block, as ``POLYLOOPS_PURE_PYTHON`` does for a whole process."""
    _forced.append(_names(names or ("all",), "pure_python"))
    try:
        yield
    finally:
        _forced.pop()


@dataclass(frozen=True)
class PartStatus:
    """A part, whether it was built and whether it is in use."""

    part: CompiledPart
    built: bool
    in_use: bool


def status() -> list[PartStatus]:
    """Every part, built or not, in use or not (what ``polyloops --version`` lists)."""
    return [PartStatus(part, built(part.name), in_use(part.name)) for part in PARTS.values()]
