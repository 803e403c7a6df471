"""Files and formats: everything polyloops reads and writes, and how.

The kernel (:mod:`polyloops.core`) reads no files; everything that touches one lives here, as
networkx keeps ``readwrite/`` apart from its algorithms.

- :mod:`~polyloops.io.files`: the one writer every output goes through (links followed,
  devices and FIFOs written into, regular files replaced atomically, ``-`` for standard
  output) and the readers' checks (regular files only, bounded size);
- :mod:`~polyloops.io.registry`: the formats by name, extension and content, behind every
  command and ``polyloops.read`` / ``polyloops.write``;
- :mod:`~polyloops.io.formats`: polyloops JSON and the :class:`~polyloops.io.formats.Document`
  every reader produces; :mod:`~polyloops.io.exchange`: DualCube's ``.graph`` and Wavefront
  OBJ; :mod:`~polyloops.io.planar_code`: plantri's planar code; :mod:`~polyloops.io.meshes`:
  meshes through meshio; :mod:`~polyloops.io.voxels`: unit cubes from text and ``.npy``;
  :mod:`~polyloops.io.labelled_mesh`: labelled triangle meshes;
- :mod:`~polyloops.io.examples`: the bundled examples (package data).
"""
