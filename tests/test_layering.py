"""The layering holds: each subpackage imports only from the layers below it, at module level
or inside a function (read from the source, so a lazy import counts too), so there is no import
cycle between subpackages; and no module imports one that imports it back.

The layers, lowest first: ``core`` (the kernel), ``parallel`` (workers), ``shapes`` (boxes, unions
of cubes, coarsenings), ``surface`` (the
labelled triangle mesh), ``io`` (files and formats), ``verify``, ``solvers``, ``generate``
(candidate maps), ``catalog`` (the pipeline, records, census), ``reach`` (moves, the
conjecture), ``segmentation`` (the checker), ``segment`` (constructors), ``render``, ``cli``."""

import ast
import functools
import subprocess
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parent.parent / "src" / "polyloops"
CORE = PACKAGE / "core"
ABOVE = ("parallel", "shapes", "surface", "io", "verify", "solvers", "generate", "catalog", "reach",
         "segmentation", "segment", "render", "cli")
LAYERS = ("core", *ABOVE)


@functools.cache
def parsed(path: Path) -> ast.Module:
    """A module's syntax tree, parsed once for all the tests here (none changes it)."""
    return ast.parse(path.read_text(encoding="utf-8"))


def imported_modules(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(parsed(path)):
        if isinstance(node, ast.ImportFrom) and node.module:
            names.add(node.module)
        elif isinstance(node, ast.Import):
            names |= {alias.name for alias in node.names}
    return names


def test_core_imports_nothing_above_it():
    offenders = {}
    for path in sorted(CORE.glob("*.py")):
        bad = sorted(m for m in imported_modules(path)
                     if m.startswith("polyloops.") and m.split(".")[1] in ABOVE)
        if bad:
            offenders[path.name] = bad
    assert offenders == {}


def test_pictures_still_registered_and_import_stays_light():
    """Jupyter still gets pictures, and importing polyloops does not load matplotlib."""
    code = ("import sys, polyloops; from polyloops.io.examples import load_example; "
            "print('matplotlib' in sys.modules, hasattr(load_example('cube'), '_repr_png_'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "True"]


def test_import_and_help_stay_light():
    """``import polyloops`` and ``polyloops --help`` load none of the heavy libraries (they
    cost most of a second together); each is imported where it is used.  Measured: about
    0.15 s for the import and 0.17 s for --help (docs/performance.md)."""
    heavy = ["networkx", "sympy", "pysat", "z3", "scipy", "matplotlib", "meshio", "dask"]
    code = ("import sys, polyloops\nfrom polyloops.cli.main import build_parser\n"
            "build_parser().format_help()\n"
            f"print(sorted(h for h in {heavy!r} if h in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_every_error_polyloops_defines_derives_from_one_base():
    """Walk every module: each exception class polyloops defines is a PolyloopsError (the CLI's
    own CliError aside, which carries an exit status, not a finding)."""
    import importlib
    import inspect
    import pkgutil

    import polyloops
    from polyloops.core.errors import PolyloopsError

    found = []
    for info in pkgutil.walk_packages(polyloops.__path__, "polyloops."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if cls.__module__ == info.name and issubclass(cls, BaseException):
                found.append(cls)
    strays = [c.__qualname__ for c in found if not issubclass(c, PolyloopsError) and c.__name__ != "CliError"]
    assert len(found) > 10 and strays == []


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def resolved_imports(path: Path, lazy: bool = True) -> set[str]:
    """Every polyloops module a file imports (with ``lazy``, inside functions too);
    ``from pkg import name`` counts as ``pkg.name`` when that is a module, and relative imports
    are resolved.  Imports for annotations only (``if TYPE_CHECKING``) do not count."""
    me = module_name(path)
    package = me if path.name == "__init__.py" else me.rpartition(".")[0]
    tree = parsed(path)
    typing_only = {id(n) for block in ast.walk(tree) if isinstance(block, ast.If)
                   and ast.unparse(block.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING")
                   for stmt in block.body for n in ast.walk(stmt)}
    nested = {id(n) for fn in ast.walk(tree) if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef))
              for n in ast.walk(fn)}
    out = set()
    for node in ast.walk(tree):
        if not lazy and id(node) in nested:
            continue
        if id(node) in typing_only:  # annotations only: never imported at run time
            continue
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, *([node.module] if node.module else [])])
            for alias in node.names:
                sub = PACKAGE.parent / Path(*f"{base}.{alias.name}".split("."))
                out.add(f"{base}.{alias.name}" if sub.with_suffix(".py").exists() or sub.is_dir() else base)
    return {m for m in out if m.split(".")[0] == "polyloops"}


def layer(module: str) -> int | None:
    parts = module.split(".")
    return LAYERS.index(parts[1]) if len(parts) > 1 and parts[1] in LAYERS else None


def test_every_subpackage_imports_only_from_below():
    upward = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        me = module_name(path)
        mine = layer(me)
        if mine is None:
            continue
        bad = sorted(m for m in resolved_imports(path) if (other := layer(m)) is not None and other > mine)
        if bad:
            upward[me] = bad
    assert upward == {}


# The one kind of lazy import that closes a circle: the model's convenience methods
# (``Polycube.dualize``, ``LoopStructure.primalize``) call the duality module, as networkx's graph
# methods call its algorithms.  Two classes whose methods return each other's type close a circle
# however the code is cut, short of dropping the methods; no other circle is allowed.
LAZY_CIRCLES = {frozenset({"polyloops.core.duality", "polyloops.core.polycube"}),
                frozenset({"polyloops.core.duality", "polyloops.core.structure"})}


def import_circles(lazy: bool) -> list[list[str]]:
    """The circles of the modules' import graph (with ``lazy``, imports inside functions
    count); a package's __init__ re-exporting its own modules is not a circle of meaning."""
    import networkx as nx

    graph = nx.DiGraph()
    for path in PACKAGE.rglob("*.py"):
        me = module_name(path)
        graph.add_edges_from((me, m) for m in resolved_imports(path, lazy=lazy) if m != me)
    graph.remove_edges_from([(u, v) for u, v in graph.edges if v.startswith(u + ".")])
    return list(nx.simple_cycles(graph))


def test_lazy_imports_close_no_other_circle():
    """Counting the imports inside functions too, the only circles are those listed above."""
    assert {frozenset(c) for c in import_circles(lazy=True)} <= LAZY_CIRCLES


def test_no_room_holds_more_than_a_quarter_of_the_lines():
    """The library is spread over its rooms: none holds a quarter of its lines (modules at the
    top of the package count as rooms of their own)."""
    from collections import Counter

    lines: Counter[str] = Counter()
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE).parts
        lines[parts[0] if len(parts) > 1 else path.stem] += len(path.read_text(encoding="utf-8").splitlines())
    total = sum(lines.values())
    assert max(lines.values()) < total / 4, lines.most_common(3)


def test_no_import_cycle_between_modules():
    """No module imports at load time a module that imports it back, directly or through
    others.  (Lazy imports between subpackages only go down, by the test above; inside the
    kernel, the model's convenience methods ``Polycube.dualize`` and
    ``LoopStructure.primalize`` call the duality module lazily, as networkx's graph methods
    call its algorithms.)"""
    assert import_circles(lazy=False) == []


def test_core_imports_nothing_from_io():
    """The kernel reads no files: nothing in core/ imports polyloops.io, even lazily."""
    bad = {path.name: sorted(m for m in resolved_imports(path) if m.startswith("polyloops.io"))
           for path in sorted(CORE.glob("*.py"))}
    assert {k: v for k, v in bad.items() if v} == {}


# What reading or parsing a file looks like in source (``json.loads``, ``Path.read_text``,
# ``np.load``, ``sqlite3.connect``, a bare ``open``): the command line leaves it to polyloops.io.
PARSING_METHODS = {"loads", "load", "read_text", "read_bytes", "connect", "fromfile", "genfromtxt", "loadtxt"}
PARSING_MODULES = {"sqlite3", "meshio", "csv", "pickle", "tempfile"}


def test_the_command_line_parses_no_file_itself():
    """Each command parses arguments and calls the library: no ``open``, ``json.loads``,
    ``Path.read_text``, SQLite or meshio in cli/ (``json.dumps`` for printing is fine)."""
    offenders = {}
    for path in sorted((PACKAGE / "cli").glob("*.py")):
        found = set()
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Call):
                func = node.func
                if isinstance(func, ast.Attribute) and func.attr in PARSING_METHODS:
                    found.add(func.attr)
                elif isinstance(func, ast.Name) and func.id == "open":
                    found.add("open")
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                found |= {n for n in names if n.split(".")[0] in PARSING_MODULES}
        if found:
            offenders[path.name] = sorted(found)
    assert offenders == {}


def test_the_architecture_page_states_these_layers():
    """docs/architecture.md lists the layers in the order this test enforces, each allowed to
    import exactly the layers below it."""
    import re

    text = (PACKAGE.parent.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| `(\w+)` \| [^|]+ \| ([^|]+) \|$", text, re.M)
    assert [name for name, _ in rows] == list(LAYERS)
    for i, (name, allowed) in enumerate(rows):
        named = re.findall(r"`(\w+)`", allowed)
        assert named == list(LAYERS[:i]) or (allowed.strip().startswith("all of the above") and i > 3) \
            or (i == 0 and "nothing" in allowed), (name, allowed)


def test_the_command_pins_blas_threads_and_the_library_does_not():
    """``polyloops`` and ``python -m polyloops`` start with one BLAS thread (numpy's OpenBLAS
    would start a spinning thread per core); ``import polyloops`` in a program leaves it alone."""
    import os

    blas = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
    env = {k: v for k, v in os.environ.items() if k not in blas}
    show = "import os, polyloops; print(os.environ.get('OPENBLAS_NUM_THREADS'))"

    def run(code: str) -> str:
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                              check=True)
        return done.stdout.strip()

    assert run(show) == "None"  # a program that imports polyloops
    assert run("import sys; sys.argv = ['/usr/bin/polyloops', 'verify']; " + show) == "1"  # the command


def test_library_messages_name_no_command_line_flag():
    """Outside cli/, no string (docstrings aside) names a flag (``--max-corners``) or a command
    (``'polyloops verify'``): the library speaks of its parameters, the command line adds its
    own advice."""
    import re

    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if "cli" in path.relative_to(PACKAGE).parts:
            continue
        tree = parsed(path)
        docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                      if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                      and node.body and isinstance(node.body[0], ast.Expr)
                      and isinstance(node.body[0].value, ast.Constant)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings \
                    and re.search(r"(?<![\w-])--[a-z][a-z-]+|'polyloops [a-z]", node.value):
                found.append(f"{path.relative_to(PACKAGE)}:{node.lineno}: {node.value[:60]}")
    assert found == []
