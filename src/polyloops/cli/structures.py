"""Commands on one structure: ``examples``, ``verify``, ``info``, ``primalize``, ``dualize``,
``convert``, ``from-voxels``, ``signature`` and ``identify``."""

from __future__ import annotations

import argparse
from typing import Any

from polyloops.cli.args import SYMMETRIES, AddCommand, emit, plural, structure_facts, written
from polyloops.cli.info import format_summary
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    FORMATS,
    CliError,
    open_input,
    read_bytes_file,
    read_document,
    read_loop_structure,
    read_structure,
    read_text_file,
    write_output,
)
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LabelError
from polyloops.io.examples import EXAMPLES
from polyloops.io.formats import to_data
from polyloops.verify import Report


def cmd_examples(args: argparse.Namespace) -> int:
    from polyloops.io.examples import LABELLED_EXAMPLES

    rows: list[dict[str, Any]] = [{"name": e.name, "valid": e.valid, "description": e.description}
                                  for e in EXAMPLES.values()]
    meshes: list[dict[str, Any]] = [{"name": e.name, "valid": e.valid, "description": e.description}
                                    for e in LABELLED_EXAMPLES.values()]
    width = max(len(r["name"]) for r in rows + meshes)

    def table(items: list[dict[str, Any]]) -> list[str]:
        return [f"{r['name']:<{width}}  {'valid  ' if r['valid'] else 'invalid'}  {r['description']}"
                for r in items]

    text = "\n".join([*table(rows), "", "labelled triangle meshes, for 'polyloops segmentation "
                       "example:NAME' (valid: a polycube has these labels):", *table(meshes)])
    emit(args, {"examples": rows, "labelled_meshes": meshes}, text)
    return EXIT_OK


def format_report(source: str, report: Report) -> str:
    """A report as ``polyloops verify`` prints it: the verdict, then a row per condition in
    aligned columns, then each violation."""
    return f"{source}: {report}"


def cmd_verify(args: argparse.Namespace) -> int:
    from polyloops.cli.reach import verify_path_file
    from polyloops.verify import verify_document

    source = open_input(args.file)  # read once: a path file or a structure
    data = source.json()
    if isinstance(data, dict) and data.get("kind") == "path":
        return verify_path_file(args.file, data, args.json)
    doc = read_document(args.file, source=source)
    try:
        report = verify_document(doc)
    except LabelError as err:
        raise CliError(f"{args.file}: {err}") from None
    text = format_report(args.file, report)
    if report.violated("file convention", "outward"):  # the command line's repair
        text += f"\nrepair it with 'polyloops convert {args.file} OUT --fix-orientation'"
    emit(args, report.to_json(), text)
    return EXIT_OK if report.valid else EXIT_INVALID


def cmd_info(args: argparse.Namespace) -> int:
    from polyloops.verify.describe import describe

    summary = describe(read_structure(args.file))
    emit(args, summary, format_summary(summary))
    return EXIT_OK


def cmd_primalize(args: argparse.Namespace) -> int:
    from polyloops.core.duality import primalize

    obj = read_structure(args.file)
    if isinstance(obj, Polycube):
        raise CliError(f"{args.file}: is a polycube; primalize takes a loop structure (try dualize)")
    ls = read_loop_structure(args.file, valid=True, built=obj)
    # A structure and its mirror have one polycube; write it outward, as the format says.
    q = primalize(ls).outward()
    written(args, write_output(args.output, q), structure_facts(q), document=to_data(q))
    return EXIT_OK


def cmd_dualize(args: argparse.Namespace) -> int:
    obj = read_structure(args.file)
    if not isinstance(obj, Polycube):
        raise CliError(f"{args.file}: is a loop structure; dualize takes a polycube (try primalize)")
    ls = read_loop_structure(args.file, built=obj)
    written(args, write_output(args.output, ls), structure_facts(ls), document=to_data(ls))
    return EXIT_OK


def cmd_convert(args: argparse.Namespace) -> int:
    obj = read_structure(args.file, fix_orientation=args.fix_orientation, given=args.source_format)
    write_output(args.output, obj, args.target_format)
    written(args, None, structure_facts(obj))
    return EXIT_OK


def cmd_from_voxels(args: argparse.Namespace) -> int:
    from polyloops.io.voxels import parse_voxel_text, voxels_from_npy
    from polyloops.shapes.voxels import VoxelError, polycube_from_voxels

    try:
        cells = (voxels_from_npy(read_bytes_file(args.file)) if args.file.lower().endswith(".npy")
                 else parse_voxel_text(read_text_file(args.file)))
    except ValueError as err:
        raise CliError(f"{args.file}: {err}") from None
    try:
        q = polycube_from_voxels(cells)
    except VoxelError as err:
        raise CliError(f"{args.file}: {err}", EXIT_INVALID) from None
    cubes = len({tuple(c) for c in cells})  # a cube listed twice is one cube
    facts: dict[str, Any] = {"cubes": cubes}
    removed = ""
    if args.coarsen:
        from polyloops.shapes.coarsen import coarsen_polycube

        coarser = coarsen_polycube(q)
        q = coarser.polycube
        facts["removed loops"] = coarser.removed
        removed = f" ({plural(coarser.removed, 'loop')} removed)"
    written(args, write_output(args.output, q), {**facts, **structure_facts(q)}, document=to_data(q),
            line=f"{plural(cubes, 'cube')}: a polycube with {plural(q.map.num_corners, 'corner')} and "
            f"{plural(q.map.num_faces, 'face')}, genus {q.genus}{removed}, written to {args.output}")
    return EXIT_OK


def cmd_signature(args: argparse.Namespace) -> int:
    from polyloops.core.canonical import canonical_form

    form = canonical_form(read_loop_structure(args.file), args.symmetry)
    data = {"signature": form.signature, "symmetry": args.symmetry, "automorphisms": form.automorphisms}
    if form.achiral is not None:
        data["chiral"] = not form.achiral
    emit(args, data, f"{form.signature}\n(symmetry {args.symmetry}, automorphism group of order "
         f"{form.automorphisms})")
    return EXIT_OK


def cmd_identify(args: argparse.Namespace) -> int:
    from polyloops.catalog.census import CatalogError, identify

    ls = read_loop_structure(args.file, oriented=True)
    try:
        found = identify(ls, args.catalog)
    except CatalogError as err:
        raise CliError(str(err), err.status) from None
    if found.name is not None:
        text = f"{args.file}: {found.name}"
    elif found.not_polycube is not None:
        text = (f"{args.file}: not in the catalog: it is no polycube ({found.not_polycube}; "
                f"'polyloops verify {args.file}' lists every violation)")
    elif found.genus != found.catalog_genus:
        text = (f"{args.file}: not in the catalog (genus {found.genus}; "
                f"the catalog has genus {found.catalog_genus})")
    elif found.beyond:
        text = (f"{args.file}: not in the catalog (it has {found.corners} corners; "
                f"the catalog goes to {found.max_corners})")
    else:
        text = f"{args.file}: not in the catalog"
    emit(args, found.to_json(), text)
    return EXIT_OK if found.name is not None else EXIT_INVALID


def add_commands(command: AddCommand) -> None:
    command("examples", cmd_examples, "list the bundled examples", file_arg=False)
    # verify also checks path files ({"kind": "path"}) step by step
    command("verify", cmd_verify, "check a file against the paper's definitions "
            "(Definition 1 for a polycube, Definitions 3 and 4 and Theorem 3 for a loop structure)")
    p = command("primalize", cmd_primalize, "the polycube of a polycube loop structure (Theorem 2), "
                "compact coordinates from the level graphs")
    p.add_argument("-o", "--output", metavar="OUT", help="write here (.obj for Wavefront OBJ, else JSON)")
    p = command("dualize", cmd_dualize, "the oriented loop structure of a polycube (Theorem 1)")
    p.add_argument("-o", "--output", metavar="OUT", help="write JSON here instead of to standard output")
    p = command("convert", cmd_convert, "write a polycube or loop structure in another format: "
                "polyloops JSON, DualCube's Abstract Polycube Graph (.graph, .apg), an OBJ quad mesh "
                "(.obj, polycubes only) or plantri's planar code (.pc, .plc: the quad map alone), "
                "chosen by extension or by --from/--to")
    p.add_argument("output", metavar="OUT", help="the file to write (.graph/.apg, .obj, .pc, else JSON)")
    p.add_argument("--from", dest="source_format", choices=FORMATS,
                   help="the format of FILE (default: by its extension)")
    p.add_argument("--to", dest="target_format", choices=FORMATS,
                   help="the format of OUT (default: by its extension)")
    p.add_argument("--fix-orientation", action="store_true",
                   help="turn an inside-out polycube (faces clockwise seen from outside) outward")
    p = command("from-voxels", cmd_from_voxels, "the polycube bounding a set of unit cubes: FILE is a "
                "text file of 'x y z' lines or a 3D NumPy .npy grid of booleans; where cubes only "
                "touch along an edge or at a corner the surface is split there", file_arg=False)
    p.add_argument("file", metavar="FILE", help="cubes: 'x y z' per line (# comments), or a .npy grid")
    p.add_argument("-o", "--output", metavar="OUT", help="write the polycube here (.json, .graph, .obj); "
                   "default: JSON on standard output")
    p.add_argument("--coarsen", action="store_true", help="remove the loops that only subdivide flat "
                   "faces while the structure stays valid (a 3x3x2 ring of cubes becomes the square "
                   "ring T32.1); the polycube gets compact coordinates")
    p = command("signature", cmd_signature, "a canonical name: equal exactly for isomorphic "
                "structures (mirror images of the surface identified); use it as sig:NAME anywhere")
    p.add_argument("--symmetry", choices=SYMMETRIES, default="full",
                   help="full (the default, as in pl.signature and the catalog's signature column): up "
                   "to all 48 signed permutations of the axes; rotation: up to the 24 rotations; "
                   "labelled: axes fixed (order-equivalence)")
    p = command("identify", cmd_identify, "the catalog name of a polycube or loop structure (any "
                "numbering, position or mirror image); exit 1 when it is not in the catalog")
    p.add_argument("--catalog", metavar="DIR", help="a catalog directory (default: the shipped "
                   "genus-0 catalog, installed with the package)")
    command("info", cmd_info, "corners, faces, loops, genus, zones, level graphs and corner degrees")
