"""The mathematical kernel: one half-edge map, with polycubes and loop structures as views.

What lives here: the half-edge map (:mod:`~polyloops.core.halfedge`), loops and segments
(:mod:`~polyloops.core.loops`), polycubes and loop structures, zones and level graphs,
duality (Theorems 1 and 2), corner configurations, canonical forms and signatures, symmetry
modes, loop moves, hole orientation, unit-cube constructions and the labellings a quad map
carries.  Nothing here draws, prints, reads or writes files, or imports anything above it:
file formats and the bundled examples are in :mod:`polyloops.io`.
"""
