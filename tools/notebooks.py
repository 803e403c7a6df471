"""Notebooks in the docs site, executed when the site is built (an mkdocs hook).

A page that holds the line ``<!-- notebook: NAME.ipynb -->`` gets, in its place, the notebook
``docs/NAME.ipynb`` run cell by cell in one namespace (as a kernel runs them), in a scratch
directory: each markdown cell as it is, each code cell as code, then what it printed, the
value of its last line when that is an expression (as Jupyter shows it), and the pictures it
wrote (PNG files, inlined).  The outputs are computed at every build, so they cannot go stale;
a cell that raises fails the build, naming the notebook and the cell.

Jupyter itself is not needed: the cells are plain Python.  ``render_notebook`` is what the
tests call too.
"""

from __future__ import annotations

import ast
import base64
import contextlib
import io
import json
import os
import re
import tempfile
from pathlib import Path
from typing import Any

MARKER = re.compile(r"<!--\s*notebook:\s*(\S+\.ipynb)\s*-->")
LONG = 60  # output lines shown before the rest is cut


class NotebookError(Exception):
    """A cell that raised."""


def _run_cell(source: str, namespace: dict[str, Any], label: str) -> tuple[str, str | None]:
    """Run one cell; its printed text and the repr of its last line's value (or ``None``)."""
    tree = ast.parse(source, label)
    last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
    assert last is None or isinstance(last, ast.Expr)  # for the type checker: popped as checked
    out = io.StringIO()
    value = None
    try:
        with contextlib.redirect_stdout(out):
            exec(compile(tree, label, "exec"), namespace)
            if last is not None:
                result = eval(compile(ast.Expression(last.value), label, "eval"), namespace)
                if result is not None:
                    value = repr(result)
    except Exception as err:  # the build names the cell
        raise NotebookError(f"{label}: {type(err).__name__}: {err}") from err
    return out.getvalue(), value


def _fence(text: str, lang: str = "") -> str:
    lines = text.rstrip("\n").splitlines()
    if len(lines) > LONG:
        lines = [*lines[:LONG], f"... ({len(lines) - LONG} more lines)"]
    return f"```{lang}\n" + "\n".join(lines) + "\n```\n"


def render_notebook(path: Path) -> str:
    """The notebook as Markdown with the outputs of running it now."""
    notebook = json.loads(path.read_text(encoding="utf-8"))
    parts: list[str] = []
    namespace: dict[str, Any] = {"__name__": f"__{path.stem}__"}
    home = os.getcwd()
    with tempfile.TemporaryDirectory() as scratch:
        os.chdir(scratch)
        try:
            number = 0
            for cell in notebook["cells"]:
                source = "".join(cell["source"])
                if cell["cell_type"] == "markdown":
                    parts.append(source.strip() + "\n")
                    continue
                if cell["cell_type"] != "code":
                    continue
                number += 1
                before = {p: p.stat().st_mtime_ns for p in Path(scratch).glob("*.png")}
                printed, value = _run_cell(source, namespace, f"{path.name}, cell {number}")
                parts.append(_fence(source, "python"))
                shown = printed + (value + "\n" if value is not None else "")
                if shown.strip():
                    parts.append(_fence(shown, "text"))
                for png in sorted(Path(scratch).glob("*.png")):
                    if before.get(png) != png.stat().st_mtime_ns:
                        data = base64.b64encode(png.read_bytes()).decode("ascii")
                        parts.append(f"![{png.name}](data:image/png;base64,{data})\n")
        finally:
            os.chdir(home)
    return "\n".join(parts)


def on_page_markdown(markdown: str, page: Any, config: Any, files: Any) -> str:
    """mkdocs: put each marked notebook, run now, in its page."""
    docs = Path(config["docs_dir"])

    def run(match: re.Match[str]) -> str:
        return render_notebook(docs / match.group(1))

    return MARKER.sub(run, markdown)
