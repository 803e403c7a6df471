"""Where a catalog's candidate maps come from: the :class:`~polyloops.generate.base.Generator`
interface and its registry, one folder per generator (``plantri``, ``loops``, ``torus``), the
spill format the searches share, their bounds, and the 126 corner configurations."""
