"""Regenerate src/polyloops/examples/*.json (and the labelled meshes) from their builders.

Run from the repository root: ``python tools/make_examples.py``.  The test
suite checks that the shipped files equal what this would write.
"""

from pathlib import Path

from polyloops.io.examples import EXAMPLES, LABELLED_EXAMPLES
from polyloops.io.files import write_atomic
from polyloops.io.formats import dumps
from polyloops.io.labelled_mesh import labels_text, triangle_obj_text

OUT = Path(__file__).resolve().parent.parent / "src" / "polyloops" / "examples"

if __name__ == "__main__":
    for name, ex in EXAMPLES.items():
        write_atomic(OUT / f"{name}.json", dumps(ex.build()))
        print(f"wrote {name}.json")
    for name, lex in LABELLED_EXAMPLES.items():
        mesh = lex.build()
        write_atomic(OUT / f"{name}.obj", triangle_obj_text(mesh))
        write_atomic(OUT / f"{name}.labels", labels_text(mesh))
        print(f"wrote {name}.obj and {name}.labels")
