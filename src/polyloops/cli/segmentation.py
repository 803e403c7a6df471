"""The ``segmentation`` command: is a labelled triangle mesh a polycube segmentation?"""

from __future__ import annotations

import argparse
import json
import os
import sys
from collections.abc import Callable
from typing import TypeVar

from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    CliError,
    check_output,
    picture_output,
    write_error,
    write_output,
)
from polyloops.core.halfedge import MapError
from polyloops.core.words import plural
from polyloops.io.files import InputError
from polyloops.io.labelled_mesh import LabelledMeshError
from polyloops.io.labelled_mesh import read_labelled_mesh as read_mesh_files
from polyloops.surface.mesh import LabelledMesh

T = TypeVar("T")


def add_command(command: Callable[..., argparse.ArgumentParser]) -> None:
    p = command("segmentation", cmd_segmentation, "check a labelled triangle mesh: the local criteria of "
                "labelling methods, the global test of the level graphs, and a polycube that realises "
                "the labels (exit 0 valid or undecided, 1 invalid)", file_arg=False)
    p.add_argument("mesh", metavar="MESH", help="a closed triangle mesh (.obj, .stl or MEDIT .mesh), or "
                   "example:NAME (a bundled labelled mesh, or any bundled polycube labelled by its normals)")
    p.add_argument("labels", metavar="LABELS", nargs="?",
                   help="one integer per triangle in face order, 0..5 for +X -X +Y -Y +Z -Z "
                   "(not needed with example:NAME)")
    p.add_argument("-o", "--output", metavar="POLYCUBE",
                   help="write the polycube that realises the labels (.json, .graph, .obj)")
    p.add_argument("--png", metavar="FILE", help="draw the labelled mesh, with the witness when invalid")
    p.add_argument("--html", metavar="FILE", help="an interactive page (FILE.html): the labelled mesh, its "
                   "charts (the witness in red when invalid), beside the realising polycube")


def read_labelled_mesh(mesh_arg: str, labels_arg: str | None) -> LabelledMesh:
    """The MESH and LABELS arguments as a labelled mesh; problems name the file."""
    if mesh_arg.startswith("example:"):
        from polyloops.io.examples import labelled_mesh_example

        if labels_arg is not None:
            raise CliError(f"{labels_arg}: an example brings its own labels; give MESH alone")
        try:
            return labelled_mesh_example(mesh_arg.removeprefix("example:"))
        except KeyError as err:
            raise CliError(f"{mesh_arg}: {err.args[0]}") from None
    if labels_arg is None:
        raise CliError(f"{mesh_arg}: give the LABELS file too (one integer per triangle)")
    return labelled_input(lambda: read_mesh_files(mesh_arg, labels_arg), mesh_arg)


def labelled_input(read: Callable[[], T], source: str) -> T:
    """``read()``, its problems as one-line usage errors naming the file at fault (``source``
    when the reader does not say which)."""
    try:
        return read()
    except InputError as err:
        raise CliError(str(err)) from None
    except LabelledMeshError as err:
        raise CliError(f"{err.where or source}: {err}") from None


def format_report(source: str, report) -> str:
    seg = report.segmentation
    verdict = {True: "valid", False: "INVALID", None: "undecided"}[report.valid]
    lines = [f"{source}: labelled segmentation: {verdict}",
             f"  charts {len(seg.charts)}  boundaries {len(seg.boundaries)}  corners {len(seg.corners)}"]
    local = report.local
    lines.append(f"  local criteria: {'pass' if local.valid else plural(len(local.violations), 'violation')}")
    lines += [f"    {v.rule}: {v.message}" for v in local.violations]
    g = report.global_
    state = {True: "pass", False: "FAIL", None: "not decided"}[g.valid]
    why = f" ({g.reason})" if g.reason and g.valid is None else ""
    lines.append(f"  global test (level graphs): {state}{why}")
    if g.witness is not None:
        charts = ", ".join(map(str, g.witness.charts(seg)))
        lines.append(f"    witness: {g.witness.describe(seg)}; charts {charts}")
    if report.polycube is not None:
        q = report.polycube
        lines.append(f"  realised by a polycube of {q.map.num_corners} corners and {q.map.num_faces} quads "
                     "(Definition 1 holds)")
    elif report.valid is None:
        lines.append(f"  undecided: {report.reason}")
    return "\n".join(lines)


def cmd_segmentation(args: argparse.Namespace) -> int:
    if args.png:
        picture_output(args.png)
    if args.html:
        picture_output(args.html, (".html", ".htm"))
    if args.output:
        check_output(args.output)
    from tqdm import tqdm

    # Steps: the mesh read, checked, and with --png each of the picture's two views and its file.
    bar = tqdm(total=2 + (3 if args.png else 0), desc="segmentation", unit="step", disable=None,
               file=sys.stderr)
    try:
        return _segmentation(args, lambda _: bar.update(1))
    finally:
        bar.close()


def checked_segmentation(mesh_arg: str, labels_arg: str | None, step: Callable[[str], None] = lambda _: None):
    """The checker's report on the MESH and LABELS arguments; problems name the file."""
    from polyloops.segmentation import check_segmentation

    mesh = read_labelled_mesh(mesh_arg, labels_arg)
    step("read")
    try:
        report = check_segmentation(mesh)
    except MapError as err:
        raise CliError(f"{mesh_arg}: not a closed oriented surface: {err}") from None
    step("checked")
    return report


def _segmentation(args: argparse.Namespace, step: Callable[[str], None]) -> int:
    report = checked_segmentation(args.mesh, args.labels, step)
    if args.output:
        if report.polycube is None:
            print(f"polyloops segmentation: {args.output}: not written: no polycube was built "
                  f"({'invalid' if report.valid is False else 'undecided'})", file=sys.stderr)
        else:
            write_output(args.output, report.polycube)
    if args.html:
        from polyloops.render.segmentation_viewer import write_segmentation_viewer

        try:
            write_segmentation_viewer(report, args.html)
        except OSError as err:
            raise write_error(args.html, err) from None
    if args.png:
        from polyloops.render.segmentation import render_segmentation

        try:
            render_segmentation(report, args.png, progress=step)
        except OSError as err:
            raise write_error(args.png, err) from None
    source = args.mesh if args.labels is None else f"{args.mesh} + {os.path.basename(args.labels)}"
    data = report.to_json()
    text = format_report(source, report)
    if args.output and report.polycube is not None:
        data["output"] = args.output
        text += f"\nwrote {args.output}: the realising polycube"
    if args.png:
        data["png"] = args.png
        text += f"\ndrew the labelled mesh to {args.png}"
    if args.html:
        data["html"] = args.html
        text += f"\nwrote {args.html}: an interactive page of the labelled mesh"
    print(json.dumps(data, indent=2) if args.json else text)
    return EXIT_INVALID if report.valid is False else EXIT_OK
