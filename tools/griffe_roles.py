"""A griffe extension for the API reference: Sphinx roles in docstrings (``:func:`name```,
``:class:`~a.b.C```, ``:mod:``, ``:meth:``, ``:attr:``, ``:data:``, ``:exc:``, ``:obj:``)
become links to the objects they name, as mkdocs-autorefs writes them.

Names are resolved as Python would see them from the docstring's object (its scope, then its
parents', imports included), so the docstrings keep the style ``help()`` and Sphinx read.  A
name that resolves to no object the site shows (private, without a docstring, outside the
package, such as ``time.monotonic``) becomes plain code, never a broken link.  ``~`` shows
the last component only, as in Sphinx.
"""

from __future__ import annotations

import re
from typing import Any

from griffe import Alias, Extension, Module, Object

ROLE = re.compile(r":(?:func|class|mod|meth|attr|data|exc|obj):`(~?)([^`]+)`")
PACKAGE = "polyloops"
# Subpackages have a page each (docs/api/NAME.md) rather than an entry: a link to the page.
PAGES = {f"{PACKAGE}.{name}": f"{name}.md" for name in
         ("core", "io", "verify", "solvers", "enumerate", "segmentation", "render")}
PAGES[PACKAGE] = "index.md"


def _shown(pkg: Module, path: str) -> Object | Alias | None:
    """The object at ``path`` when the site shows it (public all the way down, with a
    docstring), following re-exports to where the object is defined."""
    if path != PACKAGE and not path.startswith(PACKAGE + "."):
        return None
    parts = path.split(".")[1:]
    if any(p.startswith("_") for p in parts):
        return None
    try:
        obj: Object | Alias = pkg[".".join(parts)] if parts else pkg
    except (KeyError, ValueError):
        return None
    try:
        if isinstance(obj, Alias):
            obj = obj.final_target
        if any(p.startswith("_") for p in obj.path.split(".")):
            return None
        return obj if obj.docstring is not None else None
    except Exception:  # an alias that leads outside what griffe loaded
        return None


def _target(obj: Object, name: str) -> str | None:
    """The full path ``name`` refers to from ``obj``'s docstring."""
    if name.startswith(PACKAGE + ".") or name == PACKAGE:
        return name
    head, _, rest = name.partition(".")
    scope: Object | None = obj
    while scope is not None:
        try:
            base = scope.resolve(head)
        except Exception:  # not a name in this scope
            scope = scope.parent
            continue
        return f"{base}.{rest}" if rest else base
    return None


def link_roles(pkg: Module, obj: Object, text: str) -> str:
    def replace(match: re.Match[str]) -> str:
        short, name = match.group(1) == "~", match.group(2).strip()
        shown = name.rsplit(".", 1)[-1] if short else name
        path = _target(obj, name)
        if path in PAGES:  # every API page is in docs/api/, so the link is relative to it
            return f"[`{shown}`]({PAGES[path]})"
        target = _shown(pkg, path) if path is not None else None
        if target is None:
            return f"`{shown}`"
        return f"[`{shown}`][{target.path}]"

    return ROLE.sub(replace, text)


def _walk(obj: Object):
    yield obj
    for member in obj.members.values():
        if not isinstance(member, Alias):
            yield from _walk(member)


class SphinxRoles(Extension):
    def on_package(self, *, pkg: Module, **kwargs: Any) -> None:
        if pkg.name != PACKAGE:
            return
        for obj in _walk(pkg):
            if obj.docstring is not None and ":" in obj.docstring.value:
                obj.docstring.value = link_roles(pkg, obj, obj.docstring.value)
