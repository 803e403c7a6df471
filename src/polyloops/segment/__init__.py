"""Constructors of polycube segmentations, beside the checker that certifies what they build.

A constructor takes a surface (or a polycube) and returns a labelled mesh together with the
report of :func:`polyloops.segmentation.check_segmentation` on it; it never hands out a labelling
the checker has not passed.  :mod:`~polyloops.segment.from_polycube` labels a polycube's own
quads by their normals; the constructor by loop moves of the paper's Section 5 (``polyloops
segment``) lives here too."""

from enum import Enum

# of fidelity, a loop's price in segment's score (the default of --price); kept here, where the
# command line reads it without importing the search
PRICE = 0.001


class Floor(Enum):
    """Which valid labellings of the mesh bound ``segment``'s result from below (its fidelity,
    or its agreement with a guide): those the checker finds valid as they are (the per-triangle
    and the graph-cut labelling), or also the graph-cut labelling (or the guide) once repaired
    (the default: fidelity first).  Below the floor nothing is kept, whatever its score; above
    it the best score wins.  Kept here, beside :data:`PRICE`, for the command line."""

    VALID = "valid"
    REPAIRED = "repaired"
