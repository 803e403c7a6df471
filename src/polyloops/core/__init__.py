"""The mathematical kernel: one half-edge map, with polycubes and loop structures as views.

Nothing here draws, prints or reads files except :mod:`polyloops.core.formats`.
"""
