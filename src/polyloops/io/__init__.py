"""File formats and the file system: what polyloops reads and writes, and how.

The kernel (:mod:`polyloops.core`) reads no files; everything that touches one lives here, as
networkx keeps ``readwrite/`` apart from its algorithms.

- :mod:`polyloops.io.files`: the one writer every output goes through (links followed, devices
  and FIFOs written into, regular files replaced atomically, ``-`` for standard output) and the
  readers' checks (regular files only, bounded size).
"""
