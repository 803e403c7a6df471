"""Draw the pictures of docs/segmentation.md from the bundled labelled meshes.

Run from the repository root: ``python tools/segmentation_pictures.py``.
"""

from pathlib import Path

from polyloops.io.examples import labelled_mesh_example
from polyloops.render.polycube import render_polycube
from polyloops.render.segmentation import render_segmentation
from polyloops.segmentation import check_segmentation

OUT = Path(__file__).resolve().parent.parent / "docs" / "images"

if __name__ == "__main__":
    for name in ("sokolov-ramp", "overhang"):
        report = check_segmentation(labelled_mesh_example(name))
        render_segmentation(report, OUT / f"segmentation-{name}.png")
        print(f"wrote segmentation-{name}.png")
        if report.polycube is not None:
            render_polycube(report.polycube, OUT / f"segmentation-{name}-polycube.png", views=2,
                            title=f"the polycube that realises the labels of {name}", size=3.2)
            print(f"wrote segmentation-{name}-polycube.png")
