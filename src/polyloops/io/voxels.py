"""Unit cubes from files: ``x y z`` lines and NumPy ``.npy`` grids (what
``polyloops from-voxels`` reads); :func:`polyloops.shapes.voxels.polycube_from_voxels` builds the
polycube.

>>> parse_voxel_text("0 0 0\\n1 0 0\\n")
[(0, 0, 0), (1, 0, 0)]
"""

from __future__ import annotations

from polyloops.shapes.voxels import Cell, voxels_from_grid

__all__ = ["parse_voxel_text", "voxels_from_npy"]


def parse_voxel_text(text: str) -> list[Cell]:
    """Cubes from text: one ``x y z`` (integers) per line; blank lines and ``#`` comments are
    skipped.  Raises :class:`ValueError` naming the line of a problem.

    >>> parse_voxel_text("# an L\\n0 0 0\\n1 0 0\\n0 1 0\\n")
    [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    """
    cells: list[Cell] = []
    for number, line in enumerate(text.splitlines(), 1):
        words = line.split("#", 1)[0].split()
        if not words:
            continue
        try:
            if len(words) != 3:
                raise ValueError
            x, y, z = (int(w) for w in words)
        except ValueError:
            raise ValueError(f"line {number}: a cube is three integers 'x y z', "
                             f"not {line.strip()!r}") from None
        cells.append((x, y, z))
    if not cells:
        raise ValueError("no cubes: expected lines 'x y z'")
    return cells


def voxels_from_npy(data: bytes) -> list[Cell]:
    """Cubes from the bytes of a NumPy ``.npy`` file holding a 3D grid (no pickles).
    Raises ``ValueError`` naming the problem for anything else.

    >>> import io, numpy as np
    >>> buf = io.BytesIO(); np.save(buf, np.ones((1, 1, 2), dtype=bool))
    >>> voxels_from_npy(buf.getvalue())
    [(0, 0, 0), (0, 0, 1)]
    """
    import io

    import numpy as np

    try:
        stream = io.BytesIO(data)
        major, _ = np.lib.format.read_magic(stream)
        fmt = np.lib.format
        read_header = fmt.read_array_header_1_0 if major == 1 else fmt.read_array_header_2_0
        shape, _, dtype = read_header(stream)
        need = int(np.prod(shape, dtype=object)) * dtype.itemsize
        if need > len(data) - stream.tell():  # a header may declare far more than the file holds
            raise ValueError(f"the header declares shape {shape} ({need} bytes), but the file holds "
                             f"{len(data) - stream.tell()} bytes of data")
        grid = np.load(io.BytesIO(data), allow_pickle=False)
    except (ValueError, OSError, EOFError) as err:
        # numpy's own messages run over lines (a huge header's has three): the first, on one line
        first = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
        message = " ".join(w if len(w) <= 80 else w[:60] + "..." for w in first.split(" "))
        raise ValueError(f"not a NumPy .npy array: {message}") from None
    return voxels_from_grid(grid)
