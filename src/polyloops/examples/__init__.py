"""JSON files of the bundled examples (see :mod:`polyloops.io.examples`)."""
