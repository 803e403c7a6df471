"""The ``corners`` command: the 126 configurations, or their classes under a symmetry."""

from __future__ import annotations

import argparse

from polyloops.cli.args import SYMMETRIES_WITH_ALIASES, AddCommand, emit
from polyloops.cli.load import EXIT_OK, CliError, picture_output


def cmd_corners(args: argparse.Namespace) -> int:
    from polyloops.generate.corners import corner_classes, corner_rows

    pictures = [(picture_output(path, (f".{draw}",)), draw)
                for path, draw in ((args.png, "png"), (args.svg, "svg")) if path]  # checked before drawing
    for path, draw in pictures:
        from polyloops.render.corners import corner_sheet

        try:
            corner_sheet(path)
        except (OSError, ValueError) as err:
            raise CliError(f"{path}: cannot write the {draw} picture: {err}") from None
    drawn = "".join(f"\ndrew the 126 configurations to {path}" for path, _ in pictures)
    if args.symmetry in ("labelled", "none"):
        rows = corner_rows(args.witnesses)
        text = "\n".join(
            f"{r['id']:>3}  {r['category']:<18} {' '.join(r['directions']):<20} "  # type: ignore[arg-type]
            + (", ".join(r["examples"]) or "-")  # type: ignore[arg-type]
            + (f"   witness {r['witness_cubes']}" if args.witnesses else "")
            for r in rows)
        shown = sum(1 for r in rows if r["examples"])
        header = (f"{len(rows)} corner configurations (id, category, directions counter-clockwise, "
                  f"bundled examples that contain it); {shown} appear in the bundled examples")
        emit(args, {"symmetry": "labelled", "configurations": rows, "pictures": [p for p, _ in pictures]},
             header + "\n" + text + drawn)
        return EXIT_OK
    classes = [c.to_json() for c in corner_classes(args.symmetry)]
    text = "\n".join(f"{r['class']:>3}  {r['category']:<18} size {r['size']:>2}  "
                     f"{' '.join(r['representative']):<20} members {r['members']}"  # type: ignore[arg-type]
                     for r in classes)
    header = f"{len(classes)} classes of corner configurations under symmetry '{args.symmetry}'"
    emit(args, {"symmetry": str(args.symmetry), "classes": classes, "pictures": [p for p, _ in pictures]},
         header + "\n" + text + drawn)
    return EXIT_OK


def add_commands(command: AddCommand) -> None:
    p = command("corners", cmd_corners, "the 126 polycube corner configurations, by category, "
                "or their classes under rotations or all signed permutations", file_arg=False)
    p.add_argument("--symmetry", choices=SYMMETRIES_WITH_ALIASES, default="labelled",
                   help="labelled: one row per configuration (default; 'none' is an older name for "
                   "it); rotation: classes under the 24 rotations; full: under all 48 signed "
                   "permutations, the same modes as 'polyloops signature'")
    p.add_argument("--witnesses", action="store_true",
                   help="for each configuration, a small set of unit cubes whose polycube has that corner")
    p.add_argument("--png", metavar="FILE", help="draw every configuration on one sheet (PNG)")
    p.add_argument("--svg", metavar="FILE", help="the same sheet as SVG")
