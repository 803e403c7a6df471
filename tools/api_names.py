"""The table of polyloops' top-level names for docs/api/index.md: each name, the first line
of its docstring, and a link to its entry in the reference (where it is defined).

Usage: python tools/api_names.py   (prints the table; tests/test_docs.py checks the page has it)
"""

from __future__ import annotations

import inspect
import re

import polyloops

SKIP = {"__version__"}


def rows() -> list[tuple[str, str, str]]:
    """(name, summary, defining path) for every name in ``polyloops.__all__``."""
    out = []
    for name in sorted(n for n in polyloops.__all__ if n not in SKIP):
        obj = getattr(polyloops, name)
        if callable(obj) and hasattr(obj, "__qualname__"):  # classes, functions, cached functions
            path = f"{obj.__module__}.{obj.__qualname__}"
            doc = inspect.getdoc(obj) or ""
        else:  # a value: documented where it is defined
            path = f"polyloops.io.examples.{name}"  # EXAMPLES, the one value exported
            doc = "The bundled polycubes and loop structures by name."
        summary = first_sentence(doc)
        out.append((name, summary, path))
    return out


def first_sentence(doc: str) -> str:
    """The docstring's first sentence, its roles and double backticks as plain code."""
    text = doc.split("\n\n")[0].replace("\n", " ").strip()
    text = re.sub(r":[a-z]+:`~?([^`]+)`", lambda m: f"`{m.group(1).rsplit('.', 1)[-1]}`", text)
    text = text.replace("``", "`")
    end = re.search(r"[.:](\s|$)", text)
    return text[: end.start() + 1].rstrip(":") + ("" if text[: end.start() + 1].endswith(".") else ".") \
        if end else text


def table() -> str:
    lines = ["| name | what it is | defined in |", "|---|---|---|"]
    for name, summary, path in rows():
        module = path.rsplit(".", 1)[0] if not path.endswith(name) else path[: -len(name) - 1]
        cell = summary.replace("|", "\\|")
        lines.append(f"| [`{name}`][{path}] | {cell} | `{module}` |")
    return "\n".join(lines)


if __name__ == "__main__":
    print(table())
