"""Draw the pictures of docs/segmentation.md from the bundled labelled meshes, and of a
segmentation ``polyloops segment`` builds on the made mesh ``pebble`` (seed 0, a budget that lets
the search converge, so the pictures are the same on any machine).

Run from the repository root: ``python tools/segmentation_pictures.py``.
"""

from pathlib import Path

from polyloops.core.directions import Axis
from polyloops.io.examples import labelled_mesh_example
from polyloops.render.loops_on_surface import render_loops_on_surface
from polyloops.render.polycube import render_polycube
from polyloops.render.segmentation import render_segmentation
from polyloops.segment.run import segment_mesh
from polyloops.segmentation import check_segmentation
from polyloops.shapes.meshes import MESH_EXAMPLES

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
    # the search's own segmentation, run until it converges: the same on any machine
    done = segment_mesh(*MESH_EXAMPLES["pebble"](), budget=600.0, seed=0, direct=False)
    assert done.converged and done.layout is not None
    e = done.layout.embedded
    edges = {edge: Axis(lp.axis_in(e.refined)) for lp in e.loops for edge in lp.edges()}
    render_loops_on_surface(e.refined.points, e.refined.triangles, e.region, edges,
                            OUT / "segment-pebble-loops.png",
                            title=f"the {done.loops} loops on the surface (plane sections)")
    render_segmentation(done.report, OUT / "segment-pebble.png")
    render_polycube(done.polycube, OUT / "segment-pebble-polycube.png", views=2,
                    title=f"the polycube of its {done.loops} loops", size=3.2)
    print("wrote segment-pebble-loops.png, segment-pebble.png and segment-pebble-polycube.png")
