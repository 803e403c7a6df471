"""Pictures and pages: polycubes with their loops, zones and level graphs, sheets of many,
the corner table, labelled meshes (matplotlib on its headless Agg backend, with an exact
depth test), the interactive viewer (plotly, one self-contained HTML page), the catalog's
gallery (static HTML), and Jupyter's inline pictures.  It may import everything below it
(``core``, ``io``, ``verify``, ``solvers``, ``enumerate``, ``segmentation``); outputs go
through :mod:`polyloops.io.files`."""
