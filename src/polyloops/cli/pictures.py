"""The picture commands: ``render`` (one structure) and ``sheet`` (many, with captions)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from polyloops.cli.args import (
    FILE_HELP,
    MAX_WORKERS,
    AddCommand,
    catalog_dir,
    count_arg,
    genus_option,
    plural,
    written,
)
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    CliError,
    output_dir,
    picture_output,
    read_structure,
    write_error,
)
from polyloops.core.directions import Axis
from polyloops.core.duality import DualityError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure


def cmd_render(args: argparse.Namespace) -> int:
    from polyloops.core.duality import dualize
    from polyloops.render.level_graphs import render_level_graphs
    from polyloops.render.polycube import PictureError, render_polycube
    from polyloops.verify import verify

    out = picture_output(args.output)
    args.level_graphs_beside = bool(args.zones and args.level_graphs)
    obj = read_structure(args.file)
    report = verify(obj)
    ls = dualize(obj) if isinstance(obj, Polycube) and report.valid else obj
    if isinstance(ls, LoopStructure) and not ls.oriented:
        raise CliError(f"{args.file}: is a labelled loop structure without sides; orient it first")
    drew, status = "polycube", EXIT_OK
    try:
        if args.level_graphs and not args.zones:
            if not isinstance(ls, LoopStructure):
                raise CliError(f"{args.file}: not a polycube, so it has no loop structure", EXIT_INVALID)
            render_level_graphs(ls, out)
            drew = "level graphs"
        else:
            title = None if report.valid else f"not valid: {report.first_violation()}"[:110]
            zones = Axis.parse(args.zones) if args.zones else None
            try:
                render_polycube(obj, out, views=args.views, loops=args.loops, title=title, zones=zones,
                                level_graph=args.level_graphs_beside, grid=args.grid)
            except DualityError as err:
                # No polycube to draw: as for 'view', exit 1; the level graphs show why.
                render_level_graphs(obj, out)  # type: ignore[arg-type]
                drew, status = "level graphs", EXIT_INVALID
                print(f"polyloops render: {args.file}: no polycube to draw: {err}; drew its level graphs "
                      "instead", file=sys.stderr)
    except PictureError as err:
        raise CliError(f"{args.file}: {err}") from None
    except OSError as err:
        raise write_error(out, err) from None
    views = args.views if drew == "polycube" else 0
    shown = f"the polycube in {plural(views, 'view')}" if views else f"the {drew}"
    written(args, None, {"drew": drew, "views": views, "valid": report.valid}, f"drew {shown} to {out}")
    return status


def cmd_view(args: argparse.Namespace) -> int:
    from polyloops.render.polycube import PictureError
    from polyloops.render.viewer import write_viewer

    picture_output(args.output, (".html", ".htm"))
    if args.labels is not None:
        return _view_segmentation(args)
    obj = read_structure(args.file)
    if isinstance(obj, LoopStructure) and not obj.oriented:
        raise CliError(f"{args.file}: is a labelled loop structure without sides; orient it first")
    try:
        write_viewer(obj, args.output, title=_caption(args.file, obj))
    except DualityError as err:
        raise CliError(f"{args.file}: no polycube to draw: {err}", EXIT_INVALID) from None
    except PictureError as err:
        raise CliError(f"{args.file}: {err}") from None
    except OSError as err:
        raise write_error(args.output, err) from None
    written(args, None, {"page": "viewer"}, f"wrote {args.output}: open it in a browser (no network needed)")
    return EXIT_OK


def _view_segmentation(args: argparse.Namespace) -> int:
    """``view MESH --labels LABELS``: the labelled mesh beside the polycube that realises it;
    written whatever the verdict, exit 1 when the labels are invalid."""
    from polyloops.cli.segmentation import checked_segmentation
    from polyloops.render.segmentation_viewer import write_segmentation_viewer

    report = checked_segmentation(args.file, args.labels)
    try:
        write_segmentation_viewer(report, args.output)
    except OSError as err:
        raise write_error(args.output, err) from None
    verdict = {True: "valid", False: "invalid", None: "undecided"}[report.valid]
    written(args, None, {"page": "segmentation", "valid": report.valid},
            f"wrote {args.output}: the labelled mesh ({verdict})"
            + (", beside its polycube" if report.polycube is not None else "")
            + "; open it in a browser (no network needed)")
    return EXIT_INVALID if report.valid is False else EXIT_OK


def cmd_gallery(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from polyloops.catalog.census import CatalogError, read_catalog
    from polyloops.render.gallery import build_gallery

    out = output_dir(args.output)
    try:
        census = read_catalog(catalog_dir(args.dir, args.genus))
    except CatalogError as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    total = len(census.entries) if args.limit is None else min(args.limit, len(census.entries))
    bar = tqdm(total=total, desc="gallery", unit="class", disable=None, file=sys.stderr)
    try:
        built = build_gallery(census, out, args.limit, progress=lambda _: bar.update(1),
                              workers=args.workers)
    except ValueError as err:  # a record whose signature does not decode
        raise CliError(f"{census.directory}: {err}") from None
    except OSError as err:
        raise write_error(out, err) from None
    finally:
        bar.close()
    index = out / "index.html"
    written(args, None, {"classes": built.classes, "index": str(index)},
            f"wrote {plural(built.classes, 'class', 'classes')} to {index} (open it in a browser; no "
            "network needed)")
    return EXIT_OK


def _is_dir(path: Path) -> bool:
    try:
        return path.is_dir()
    except OSError:  # a name too long for the file system, for example
        return False


def _caption(source: str, obj: Any) -> str:
    """A structure's catalog name when the shipped catalog has it, else where it came from;
    never a cut-off signature."""
    from polyloops.catalog.census import CatalogError, identify

    try:
        found = identify(obj).name
    except CatalogError:  # no shipped catalog next to this install
        found = None
    if found:
        return found
    label = "signature" if source.startswith("sig:") else source if source.startswith("example:") \
        else Path(source).name
    return f"{label} ({obj.map.num_corners} corners)"


def cmd_sheet(args: argparse.Namespace) -> int:
    from polyloops.catalog.census import CatalogError, read_catalog
    from polyloops.render.polycube import PictureError
    from polyloops.render.sheet import render_sheet

    out = picture_output(args.output)
    items: list[tuple[str, Any]] = []
    for source in args.sources or [str(catalog_dir(None, args.genus))]:
        path = Path(source)
        if not source.startswith(("sig:", "example:")) and _is_dir(path):
            if not (path / "catalog.jsonl").is_file():
                raise CliError(f"{source}: a directory, but no catalog.jsonl in it")
            try:
                entries = list(read_catalog(path).entries)  # checked as every reader checks it
            except CatalogError as err:
                raise CliError(str(err), getattr(err, "status", 2)) from None
            for i, entry in enumerate(entries):
                if args.limit is not None and len(items) >= args.limit:
                    break  # the structures past the limit are not built
                try:
                    items.append((entry.name or f"#{i} {entry.corners}c", entry.structure()))
                except ValueError as err:  # a signature that does not decode
                    raise CliError(f"{path / 'catalog.jsonl'}: line {i + 1}: not a catalog record: "
                                   f"{err}") from None
        else:
            obj = read_structure(source)
            items.append((_caption(source, obj), obj))
    if args.limit is not None:
        items = items[: args.limit]
    if not items:
        raise CliError("nothing to draw")
    from tqdm import tqdm

    bar = tqdm(total=len(items), desc="sheet", unit="picture", disable=None, file=sys.stderr)
    try:
        render_sheet(items, out, columns=args.columns, workers=args.workers, progress=lambda: bar.update(1))
    except DualityError as err:
        raise CliError(f"cannot draw: {err}", EXIT_INVALID) from None
    except PictureError as err:
        raise CliError(f"cannot draw: {err}") from None
    except ValueError as err:  # an ending that is neither .png nor .svg
        raise CliError(str(err)) from None
    except OSError as err:
        raise write_error(out, err) from None
    finally:
        bar.close()
    written(args, None, {"pictures": len(items)}, f"drew {plural(len(items), 'polycube')} to {out}")
    return EXIT_OK


def add_commands(command: AddCommand) -> None:
    p = command("render", cmd_render, "draw the polycube in 3D with its loops (a loop structure is "
                "primalized first), or its three level graphs; exit 1 when it has no polycube (its "
                "level graphs are drawn instead)")
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="OUT.png or OUT.svg")
    p.add_argument("--views", type=count_arg(1, 8), default=1, metavar="N",
                   help="N views from different octants (1 to 8)")
    p.add_argument("--loops", action=argparse.BooleanOptionalAction, default=True,
                   help="draw the loops on the surface (default) or not")
    p.add_argument("--level-graphs", action="store_true", help="draw the X-, Y- and Z-graphs instead "
                   "(with --zones: that axis' level graph beside the polycube, in the same shades)")
    p.add_argument("--zones", choices=("X", "Y", "Z"), help="shade the zones of this axis in alternating "
                   "greys, as in the paper's figure of zones and level graphs")
    p.add_argument("--grid", action="store_true", help="draw the unit grid on the faces too")
    p = command("view", cmd_view, "an interactive 3D viewer in one self-contained HTML page: turn and "
                "zoom the polycube, show or hide each axis' loops and the corners, hover to name "
                "faces, zones, loops and corners; exit 1 when it has no polycube")
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="OUT.html")
    p.add_argument("--labels", metavar="LABELS", help="FILE is a triangle mesh (.obj, .stl or MEDIT .mesh) "
                   "and LABELS one label 0..5 per triangle: show the labelled segmentation (charts, the "
                   "witness when invalid) beside the polycube that realises it; exit 1 when invalid")
    p = command("gallery", cmd_gallery, "a catalog as a static site: every class with its picture, name, "
                "corners, loops per axis, corner categories, chirality and irreducibility, filters by "
                "these columns, a button that copies the signature, and a viewer page per class "
                "(resumable)", file_arg=False)
    p.add_argument("dir", metavar="DIR", nargs="?", help="a catalog directory (default: the shipped "
                   "one of --genus)")
    genus_option(p)
    p.add_argument("-o", "--output", metavar="SITE", required=True, help="the site's directory")
    p.add_argument("--limit", type=count_arg(1), metavar="N", help="only the first N classes")
    p.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                   help="local worker processes drawing the pictures and pages")
    p = command("sheet", cmd_sheet, "a grid of small renders with captions, from files or a catalog "
                "directory", file_arg=False)
    p.add_argument("sources", metavar="DIR|FILE", nargs="*", help="catalog directories or " + FILE_HELP
                   + " (default: the shipped catalog of --genus)")
    genus_option(p)
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="OUT.png or OUT.svg")
    p.add_argument("--columns", type=count_arg(1), default=6, metavar="N", help="pictures per row")
    p.add_argument("--limit", type=count_arg(1), metavar="N", help="draw at most N")
    p.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                   help="local worker processes drawing the pictures (PNG sheets)")
