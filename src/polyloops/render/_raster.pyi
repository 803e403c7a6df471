"""Types of the compiled depth buffer of a polycube's triangles (_raster.c)."""

import numpy as np

def fill(tris: bytes, u: bytes, v: bytes, left: float, top: float, step: float, tie: float,
         face: np.ndarray, depth: np.ndarray, point: np.ndarray, /) -> None:
    """Rasterise the triangles (19 float64 each) into the writable buffers, in place."""
