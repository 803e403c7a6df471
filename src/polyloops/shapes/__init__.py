"""Polycubes and loop structures built from other data: boxes and other small shapes
(:mod:`~polyloops.shapes.builders`), unions of unit cubes (:mod:`~polyloops.shapes.voxels`),
and coarsenings that remove the loops subdividing flat faces (:mod:`~polyloops.shapes.coarsen`).
It builds on the kernel and reads no file."""
