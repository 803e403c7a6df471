"""Constructors of polycube segmentations, beside the checker that certifies what they build.

A constructor takes a surface (or a polycube) and returns a labelled mesh together with the
report of :func:`polyloops.segmentation.check_segmentation` on it; it never hands out a labelling
the checker has not passed.  :mod:`~polyloops.segment.from_polycube` labels a polycube's own
quads by their normals; the constructor by loop moves of the paper's Section 5 (``polyloops
segment``) lives here too."""

# of fidelity, a loop's price in segment's score (the default of --price); kept here, where the
# command line reads it without importing the search
PRICE = 0.001
