"""The ``segment`` command: a certified polycube segmentation of a triangle mesh."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from typing import Any

from polyloops.cli.args import MAX_WORKERS, count_arg
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    EXIT_USAGE,
    CliError,
    check_output,
    check_readable_file,
    picture_output,
    read_loop_structure,
    write_error,
    write_output,
    write_text,
)
from polyloops.segment import PRICE, Floor


def add_command(command: Callable[..., argparse.ArgumentParser]) -> None:
    p = command("segment", cmd_segment, "label each triangle of a closed mesh +X..-Z so that a polycube "
                "realises the labels, by adding and removing loops (from the sections between the levels of "
                "the surface and of its polycube-like deformation, the cube at genus 0, grids of plane "
                "sections, or --start; the best kept), the labels then polished towards the normals "
                "without changing the polycube, and patches of the graph-cut labellings (or of --guide) "
                "grafted in where the checker still finds them valid; every output is certified "
                "(exit 0 written, 1 no start or nothing certified, 2 bad input)",
                file_arg=False)
    p.add_argument("mesh", metavar="MESH", help="a closed, oriented, connected triangle mesh (.obj, .stl or "
                   "MEDIT .mesh), triangles counter-clockwise seen from outside; or example:NAME, a made "
                   "mesh (sphere, egg, pebble, torus)")
    p.add_argument("-o", "--output", metavar="LABELS", help="write one integer 0..5 per triangle of the "
                   "labelled mesh (+X -X +Y -Y +Z -Z, the labeling.txt and .flag convention)")
    p.add_argument("--mesh-out", metavar="MESH", help="write the labelled mesh (the input refined along the "
                   "loops; the input triangle of each of its triangles goes to MESH.facemap)")
    p.add_argument("--polycube", metavar="FILE", help="write the polycube of the loops (.json, .obj, ...)")
    p.add_argument("--png", metavar="FILE", help="draw the labelled mesh (two views, charts outlined, the "
                   "loops in their axes' colours) beside the loops' polycube")
    p.add_argument("--html", metavar="FILE", help="an interactive page (FILE.html): the labelled mesh, its "
                   "charts and loops, beside the polycube; turn, zoom, show or hide each part")
    p.add_argument("--budget", type=float, default=20.0, metavar="SECONDS",
                   help="seconds for the whole run, most of them searching loop moves (default 20; "
                   "finding a start on a mesh of positive genus can take longer)")
    p.add_argument("--seed", type=int, default=0, help="the seed of the search's move order (default 0)")
    p.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                   help="local worker processes searching from the starts at once (default 1; 2 uses two "
                   "cores within the same budget)")
    p.add_argument("--price", type=float, default=PRICE, metavar="P",
                   help="what a loop costs in the score: fidelity (or agreement with --guide) less P per "
                   f"loop (default {PRICE:g}; larger gives fewer loops and charts)")
    p.add_argument("--floor", choices=[f.value for f in Floor], default=Floor.REPAIRED.value,
                   help="which of the mesh's own labellings the result is never less faithful than: "
                   "those valid as they are, or also the graph-cut labelling (or the guide) once "
                   "repaired (default; 'valid' lets the price choose a coarser one with fewer loops)")
    p.add_argument("--merge", action="store_true",
                   help="relabel whole charts as a neighbour wherever the loops saved pay for the "
                   "fidelity lost (fewer charts and loops, a little less faithful; each merge "
                   "certified, never below the floor); without it, only where no fidelity is lost")
    p.add_argument("--score-csv", metavar="FILE", help="write one row per start tried: its fidelity, "
                   "agreement with the guide, loops, price, score, charts, corners, seconds, whether it "
                   "converged and was kept, or why it gave nothing")
    p.add_argument("--guide", metavar="LABELS", help="a labelling of MESH from any method (one label 0..5 "
                   "per triangle): return a certified one that keeps as much of it as it can (a valid "
                   "one unchanged) and report the share of the area labelled otherwise")
    p.add_argument("--search-only", action="store_true", help="the search's segmentation, with its loops, "
                   "whatever the mesh's own labellings are (by default a valid per-triangle or graph-cut "
                   "labelling, the latter repaired where it can be, is a candidate, and the result is never "
                   "less faithful than it)")
    p.add_argument("--start", metavar="START", help="begin from this polycube loop structure of the mesh's "
                   "genus, embedded by plane sections (any symmetry of it): a shipped class name such as "
                   "T32.1, sig:SIGNATURE, example:NAME or a structure or polycube file")


def cmd_segment(args: argparse.Namespace) -> int:
    for path in (args.output, args.mesh_out, args.mesh_out and args.mesh_out + ".facemap", args.polycube,
                 args.score_csv):
        if path:
            check_output(path)
    if args.png:
        picture_output(args.png)
    if args.html:
        picture_output(args.html, (".html", ".htm"))
    if args.budget < 0:
        raise CliError(f"--budget {args.budget}: a time budget is not negative")
    if not 0 <= args.price < 1:
        raise CliError(f"--price {args.price}: a loop's price is at least 0 and less than 1")
    from tqdm import tqdm

    from polyloops.io.files import InputError
    from polyloops.io.formats import FormatError
    from polyloops.io.labelled_mesh import read_triangle_mesh
    from polyloops.segment.from_polycube import UncertifiedError
    from polyloops.segment.run import segment_mesh
    from polyloops.segment.search import StartError
    from polyloops.segment.start import StartMismatch
    from polyloops.segment.surface import SurfaceError

    points: Any
    triangles: Any
    if args.mesh.startswith("example:"):
        from polyloops.shapes.meshes import MESH_EXAMPLES

        name = args.mesh.removeprefix("example:")
        if name not in MESH_EXAMPLES:
            names = ", ".join(sorted(MESH_EXAMPLES))
            raise CliError(f"{args.mesh}: no such mesh; the made meshes are {names}")
        points, triangles = MESH_EXAMPLES[name]()
    else:
        check_readable_file(args.mesh, limit=None)
        try:
            points, triangles = read_triangle_mesh(args.mesh)
        except InputError as err:
            raise CliError(str(err)) from None
        except FormatError as err:  # the readers' errors name the line or the face
            raise CliError(f"{getattr(err, 'where', None) or args.mesh}: {err}") from None
    start = read_start(args.start) if args.start else None
    guide = read_guide(args.guide, len(triangles)) if args.guide else None
    bar = tqdm(desc="segment", unit="start", disable=None, file=sys.stderr)
    try:
        result = segment_mesh(points, triangles, budget=args.budget, seed=args.seed, price=args.price,
                              start=start, guide=guide, direct=not args.search_only, workers=args.workers,
                              bound=Floor(args.floor), merge=args.merge,
                              on_candidate=lambda candidate: bar.update(1))
    except SurfaceError as err:
        raise CliError(f"{args.mesh}: {err}") from None
    except StartMismatch as err:
        raise CliError(f"{args.start}: not a start for {args.mesh}: {err}") from None
    except (StartError, UncertifiedError) as err:
        bar.close()
        message = f"{args.mesh}: nothing written: {err}"
        print(f"polyloops segment: {message}", file=sys.stderr)
        if args.json:
            print(json.dumps({"certified": False, "error": message, "status": EXIT_INVALID}, indent=2))
        return EXIT_INVALID
    finally:
        bar.close()
    return _write(args, result)


def read_guide(path: str, triangles: int):
    """``--guide``: one label per triangle of the mesh, read as ``segmentation`` reads LABELS."""
    from polyloops.cli.segmentation import labelled_input
    from polyloops.io.labelled_mesh import read_labels

    return labelled_input(lambda: read_labels(path, triangles), path)


def read_start(arg: str):
    """``--start``: a shipped class by name, else a FILE argument as an oriented loop structure
    (a polycube is dualized); anything unreadable is bad input (exit 2)."""
    from polyloops.catalog.census import NAME, CatalogError, shipped_class

    if NAME.fullmatch(arg):
        try:
            return shipped_class(arg)
        except CatalogError as err:
            raise CliError(f"--start {arg}: {err}") from None
    try:
        return read_loop_structure(arg, oriented=True)
    except CliError as err:
        raise CliError(str(err) if str(err).startswith(arg) else f"{arg}: {err}", EXIT_USAGE) from None


def _write(args: argparse.Namespace, result) -> int:
    from polyloops.io.labelled_mesh import labels_text
    from polyloops.io.meshes import write_triangle_mesh

    data = result.to_json()
    realised = result.report.polycube.map.num_corners
    lines = [f"{args.mesh}: certified polycube segmentation: {result.charts} charts, {result.corners} "
             f"corners, {result.loops} loops; fidelity {result.fidelity:.4f} (per-triangle bound "
             f"{result.naive_fidelity:.4f}); {result.seconds:.1f} s",
             f"  the checker: valid, realised by a polycube of {realised} corners; " + (
                 f"{result.start}: kept, no loops drawn" if result.layout is None else
                 f"the layout draws the loops' polycube of {result.polycube.map.num_corners} corners")]
    if result.guide_changed is not None:
        lines.append(f"  the guide: {100 * result.guide_changed:.2f}% of the area labelled otherwise")
    def labelled_mesh(path: str) -> None:
        write_triangle_mesh(path, result.mesh)
        write_text(path + ".facemap", "".join(f"{p}\n" for p in result.face_map))

    def picture(path: str) -> None:
        from polyloops.render.segment_result import render_segment

        render_segment(result, path)

    def page(path: str) -> None:
        from polyloops.render.segment_result import loop_curves
        from polyloops.render.segmentation_viewer import write_segmentation_viewer

        write_segmentation_viewer(result.report, path, loop_curves(result))

    outputs = [
        (args.output, "output", lambda path: write_text(path, labels_text(result.mesh)),
         f"{len(result.mesh.triangles)} labels"),
        (args.mesh_out, "mesh_out", labelled_mesh,
         "the labelled mesh, and PATH.facemap: its input triangles"),
        (args.polycube, "polycube", lambda path: write_output(path, result.polycube), "the polycube"),
        (args.png, "png", picture, "the labelled mesh and its loops, beside the polycube"),
        (args.html, "html", page, "an interactive page of the labelled mesh, its loops and polycube"),
        (args.score_csv, "score_csv", lambda path: write_text(path, result.scores_csv()),
         f"the score of each of the {len(result.candidates)} starts tried"),
    ]
    for path, key, write, what in outputs:
        if not path:
            continue
        try:
            write(path)
        except OSError as err:
            raise write_error(path, err) from None
        data[key] = path
        lines.append(f"wrote {path}: {what.replace('PATH', path)}")
    print(json.dumps(data, indent=2) if args.json else "\n".join(lines))
    return EXIT_OK
