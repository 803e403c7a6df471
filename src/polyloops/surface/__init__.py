"""Surfaces that are not polycubes: the labelled triangle mesh (:mod:`~polyloops.surface.mesh`,
the data model every reader, checker and constructor of segmentations shares) and the
constructions of one from the kernel's objects (:mod:`~polyloops.surface.construct`).  It reads
no file (``polyloops.io`` does) and imports only the kernel."""
