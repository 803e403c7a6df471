"""Regenerate src/polyloops/examples/*.json from their builders.

Run from the repository root: ``python tools/make_examples.py``.  The test
suite checks that the shipped files equal what this would write.
"""

from pathlib import Path

from polyloops.core.examples import EXAMPLES
from polyloops.core.formats import dumps, write_atomic

OUT = Path(__file__).resolve().parent.parent / "src" / "polyloops" / "examples"

if __name__ == "__main__":
    for name, ex in EXAMPLES.items():
        write_atomic(OUT / f"{name}.json", dumps(ex.build()))
        print(f"wrote {name}.json")
