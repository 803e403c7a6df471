"""The kernel imports nothing above it: no module of ``polyloops.core`` imports from
``verify``, ``solvers``, ``enumerate``, ``segmentation``, ``render`` or ``cli``, at module level
or inside a function (read from the source, so a lazy import counts too)."""

import ast
import subprocess
import sys
from pathlib import Path

CORE = Path(__file__).resolve().parent.parent / "src" / "polyloops" / "core"
ABOVE = ("verify", "solvers", "enumerate", "segmentation", "render", "cli")


def imported_modules(path: Path) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
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
    code = ("import sys, polyloops; from polyloops.core.examples import load_example; "
            "print('matplotlib' in sys.modules, hasattr(load_example('cube'), '_repr_png_'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "True"]


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
