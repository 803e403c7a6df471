"""The largest sizes the searches take, in one place (the command line offers the same).

A catalog run goes to at most :data:`MAX_CATALOG_CORNERS` corners: the compiled searches hold
256 crossings and plantri's planar code 255 vertices, and the catalog grows about 4.5 times per
two corners (40 corners take hours), so a larger bound is a typo, refused before any work
rather than left to overflow an array.
"""

MAX_CATALOG_CORNERS = 96
