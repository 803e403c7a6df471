"""The documentation: every exported function documented in full with a runnable example
(the examples run as doctests), the docs site builds with warnings as errors, the tutorial
notebook runs, and the table of the paper's statements points at real functions and tests."""

import importlib
import inspect
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PUBLIC = ["polyloops", "polyloops.verify", "polyloops.solvers"]


def exported():
    for name in PUBLIC:
        module = importlib.import_module(name)
        for attr in module.__all__:
            yield f"{name}.{attr}", getattr(module, attr)


@pytest.mark.parametrize("qualname, obj", [pytest.param(q, o, id=q) for q, o in exported()
                                           if inspect.isfunction(o)])
def test_every_exported_function_is_documented_in_full(qualname, obj):
    """Parameters, Returns and an example always; Raises when the function raises (a
    ``raise`` in its own body), and never a Raises section that says "never"."""
    import ast
    import textwrap

    doc = inspect.getdoc(obj) or ""
    params = [p for p in inspect.signature(obj).parameters if p not in ("self", "cls")]
    tree = ast.parse(textwrap.dedent(inspect.getsource(obj)))
    raises = any(isinstance(node, ast.Raise) for node in ast.walk(tree))
    wanted = ("Returns", "Raises") if raises else ("Returns",)
    missing = [s for s in wanted if not re.search(rf"^{s}\n-+$", doc, re.M)]
    if re.search(r"^Raises\n-+\n\w+\n\s+Never\b", doc, re.M):
        missing.append("a Raises section that names something raised (not 'Never')")
    if params and not re.search(r"^Parameters\n-+$", doc, re.M):
        missing.append("Parameters")
    if ">>>" not in doc:
        missing.append("an example")
    for p in params:  # every parameter named in the Parameters section
        if not re.search(rf"^{p}\b|^[\w, ]*\b{p}\b[\w, ]*:$", doc, re.M):
            missing.append(f"parameter {p}")
    assert missing == [], f"{qualname}: missing {', '.join(missing)}"


def test_every_exported_class_has_a_docstring():
    bare = [q for q, o in exported() if inspect.isclass(o) and not (o.__doc__ or "").strip()]
    assert bare == []


@pytest.mark.skipif(importlib.util.find_spec("mkdocs") is None,
                    reason="mkdocs is a test extra; not installed")
def test_docs_site_builds_without_warnings(tmp_path):
    """The site, with its API reference generated from the docstrings (mkdocstrings); any
    warning (a broken link, a docstring griffe cannot parse) fails the build."""
    res = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path)],
                         cwd=ROOT, capture_output=True, text=True, check=False)
    assert res.returncode == 0, res.stderr[-3000:]
    api = (tmp_path / "api" / "core" / "index.html").read_text(encoding="utf-8")
    assert "dualize" in api and "Parameters" in api
    # Sphinx roles in docstrings are links (tools/griffe_roles.py), never raw text.
    import re

    raw = re.compile(r":(func|class|mod|meth|attr|data|exc|obj):")
    pages = sorted((tmp_path / "api").rglob("*.html"))
    assert pages and not [p.name for p in pages if raw.search(p.read_text(encoding="utf-8"))]
    # removals' docstring names :func:`check_removal`: a link to its entry on the same page
    assert 'href="#polyloops.core.moves.check_removal"' in api
    # The tutorials are run by the build: their printed outputs and pictures are in the pages.
    tutorial = (tmp_path / "tutorial" / "index.html").read_text(encoding="utf-8")
    assert "loops per axis" in tutorial and tutorial.count("data:image/png;base64,") >= 2
    reach = (tmp_path / "tutorial-reachability" / "index.html").read_text(encoding="utf-8")
    assert "P26.20 has 26 corners" in reach and "-&gt; 26 corners" in reach


@pytest.mark.parametrize("name", ["tutorial", "tutorial-reachability"])
def test_tutorial_notebook_runs(tmp_path, monkeypatch, name):
    """Every code cell of a tutorial, in order, in one namespace (as a kernel would run
    them), in a scratch directory; the notebook's own assertions check its results."""
    notebook = json.loads((ROOT / "docs" / f"{name}.ipynb").read_text(encoding="utf-8"))
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__tutorial__"}
    cells = [c for c in notebook["cells"] if c["cell_type"] == "code"]
    assert len(cells) >= 5
    for i, cell in enumerate(cells):
        source = "".join(cell["source"])
        exec(compile(source, f"tutorial cell {i}", "exec"), namespace)
    if name == "tutorial":
        assert list(tmp_path.glob("*.png")), "the tutorial draws pictures"


def resolve(ref: str):
    """The object a dotted name names: the longest importable module, then attributes."""
    parts = ref.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        for attr in parts[k:]:
            obj = getattr(obj, attr, None)
        return obj
    return None


def test_statement_table_names_real_functions_and_tests():
    """docs/statements.md maps each of the paper's statements to a function and to tests;
    every function it names imports, and every test it names exists."""
    text = (ROOT / "docs" / "statements.md").read_text(encoding="utf-8")
    rows = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line][1:]
    assert len(rows) >= 10
    test_sources = {p.name: p.read_text(encoding="utf-8") for p in (ROOT / "tests").glob("test_*.py")}
    for row in rows:
        for ref in re.findall(r"`(polyloops\.[\w.]+)`", row):
            assert resolve(ref) is not None, ref
        for file, test in re.findall(r"`(test_\w+\.py)::(\w+)`", row):
            assert re.search(rf"def {test}\b", test_sources[file]), f"{file}::{test}"
        assert re.search(r"`test_\w+\.py::\w+`", row), f"no test named in: {row}"


def test_mkdocs_config_lists_every_page():
    config = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    pages = {p.relative_to(ROOT / "docs").as_posix() for p in (ROOT / "docs").rglob("*.md")}
    unlisted = sorted(p for p in pages if p not in config)
    assert unlisted == []



def test_every_public_name_has_a_docstring():
    """Every public function, class, method and property of the library (the command line
    aside) says what it is: the API reference is generated from these."""
    import pkgutil

    import polyloops

    missing = []
    for info in pkgutil.walk_packages(polyloops.__path__, "polyloops."):
        if info.name.endswith("__main__") or ".cli" in info.name:
            continue
        module = importlib.import_module(info.name)
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != info.name:
                continue
            if not (inspect.isfunction(obj) or inspect.isclass(obj)):
                continue
            doc = (obj.__doc__ or "").strip()
            if not doc or (inspect.isclass(obj) and doc.startswith(name + "(")):  # a dataclass's default
                missing.append(f"{info.name}.{name}")
            if inspect.isclass(obj):
                for member, value in vars(obj).items():
                    func = value.fget if isinstance(value, property) else getattr(value, "func", value)
                    undocumented = inspect.isfunction(func) and not (func.__doc__ or "").strip()
                    if undocumented and not member.startswith("_"):
                        missing.append(f"{info.name}.{name}.{member}")
    assert missing == []


def test_the_api_reference_covers_every_module():
    """Each library module has a ``::: module`` entry in docs/api (the command line aside)."""
    import pkgutil

    import polyloops

    text = "\n".join(p.read_text(encoding="utf-8") for p in (ROOT / "docs" / "api").glob("*.md"))
    listed = set(re.findall(r"^::: ([\w.]+)", text, re.M))
    modules = {info.name for info in pkgutil.walk_packages(polyloops.__path__, "polyloops.")
               if not re.search(r"\.(cli|examples)\b|__main__|\._", info.name)}
    # Packages whose __init__ holds an API of its own are listed too; the others are folders.
    with_api = {"polyloops.verify", "polyloops.solvers", "polyloops.segmentation"}
    missing = sorted(m for m in modules - listed
                     if not importlib.import_module(m).__file__.endswith("__init__.py") or m in with_api)
    assert missing == []


def test_the_api_overview_lists_every_top_level_name():
    """docs/api/index.md carries the table tools/api_names.py generates: every name in
    ``polyloops.__all__`` with its summary and where it is defined."""
    import importlib.util as util

    spec = util.spec_from_file_location("api_names", ROOT / "tools" / "api_names.py")
    assert spec is not None and spec.loader is not None
    module = util.module_from_spec(spec)
    spec.loader.exec_module(module)
    page = (ROOT / "docs" / "api" / "index.md").read_text(encoding="utf-8")
    assert module.table() in page, "regenerate with: python tools/api_names.py"
    import polyloops

    listed = {row[0] for row in module.rows()}
    assert listed == set(polyloops.__all__) - module.SKIP




def test_one_table_of_layers_and_every_package_in_it():
    """docs/architecture.md holds the one table of the layers, a row per package; the API index
    links a page per package and keeps no table of its own."""
    import pkgutil

    import polyloops

    packages = {info.name.split(".")[1] for info in pkgutil.iter_modules(polyloops.__path__, "polyloops.")
                if info.ispkg} - {"cli", "examples", "catalogs"}
    architecture = (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8")
    rows = set(re.findall(r"^\| `(\w+)` \|", architecture, re.M))
    assert packages <= rows
    index = (ROOT / "docs" / "api" / "index.md").read_text(encoding="utf-8")
    assert "| package |" not in index
    assert all(f"[`polyloops.{p}`]({p}.md)" in index for p in packages)


def test_the_citation_file_states_this_release_and_the_shipped_ranges():
    import yaml

    import polyloops

    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    assert cff["cff-version"] == "1.2.0" and cff["license"] == "MIT"
    assert cff["version"] == polyloops.__version__
    for genus in (0, 1):
        summary = json.loads((ROOT / "catalogs" / f"genus{genus}" / "summary.json").read_text())
        top = max(int(n) for n in summary["counts"])
        assert f"genus-{genus} polycubes through {top} corners" in " ".join(cff["abstract"].split())
    assert (ROOT / "LICENSE").read_text().startswith("MIT License")


def test_no_page_keeps_a_placeholder():
    """A figure left as a template's name (``G2_TOTAL``) in a page's prose is a number never
    measured in; code spans, code blocks and comments may name constants."""
    left = []
    for page in [*sorted((ROOT / "docs").rglob("*.md")), ROOT / "README.md"]:
        text = re.sub(r"```.*?```|`[^`]*`|<!--.*?-->", "", page.read_text(), flags=re.S)
        left += [f"{page.name}: {m}" for m in re.findall(r"\b[A-Z][A-Z0-9]*_[A-Z0-9_]+\b", text)]
    assert not left
