"""The readable form of :func:`polyloops.verify.describe.describe`, for ``polyloops info``."""

from __future__ import annotations

from typing import Any

from polyloops.core.words import plural


def format_summary(s: dict[str, Any]) -> str:
    """The readable form of :func:`describe`."""
    lines = [
        f"kind      {s['kind']}",
        f"corners   {s['corners']}    edges {s['edges']}    faces {s['faces']}    genus {s['genus']}",
        "degrees   " + "  ".join(f"{d}:{n}" for d, n in s["corner_degrees"].items()),
    ]
    cats = "  ".join(f"{c}:{n}" for c, n in s["corner_categories"].items() if n)
    if cats:
        lines.append(f"category  {cats}   (configuration ids {s['corner_configurations']})")
    if s["unclassified_corners"]:
        lines.append(f"          {plural(s['unclassified_corners'], 'corner')} "
                     f"{'is' if s['unclassified_corners'] == 1 else 'are'} no polycube corner"
                     + ("" if s.get("oriented", True) else " (no sides to tell)"))
    if "bounding_box" in s:
        lines.append(f"box       {s['bounding_box'][0]} .. {s['bounding_box'][1]}")
    if "dual" in s:
        lines.append(f"dual      {s['dual']}")
    if s.get("loops") is not None:
        lines.append("loops     " + "  ".join(f"{a}:{n}" for a, n in s["loops"].items())
                     + ("" if s["oriented"] else "   (labelled, not oriented)"))
        if s["self_crossing_loops"]:
            lines.append(f"crossing  loops crossing themselves: {s['self_crossing_loops']}")
        for a in "XYZ":
            z = s["zones"][a]
            t = s["theorem3"][a]
            row = f"{a}-zones   {z['count']} (genera {z['genera']})"
            if "level_graphs" in s:
                g = s["level_graphs"][a]
                row += (f"; {a}-graph {plural(g['vertices'], 'vertex', 'vertices')}, "
                        f"{plural(g['arcs'], 'arc')}, ") + (
                    "acyclic" if g["acyclic"] else "HAS A CYCLE")
            row += f"; Theorem 3: {t['E']} = {t['g']} + {t['V']} - 1 - {t['Gamma']}"
            row += "" if t["holds"] else " FAILS"
            lines.append(row)
        if "hole_orientation" in s:
            from polyloops.core.holes import HoleOrientation

            holes = HoleOrientation({k: tuple(v) for k, v in s["hole_orientation"].items()})
            lines.append(f"holes     {holes}   (intersection numbers of the loops of two axes; "
                         "loop moves keep them)")
    return "\n".join(lines)
