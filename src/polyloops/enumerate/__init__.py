"""Enumerations, catalogs and reachability, built on the kernel.

What lives here: the 126 corner configurations (:mod:`~polyloops.enumerate.corners`); the
catalog pipeline (:mod:`~polyloops.enumerate.catalog_run`) with its generators
(:mod:`~polyloops.enumerate.generators`: plantri's quadrangulations filtered,
:mod:`~polyloops.enumerate.quadrangulations`, and arrangements of loops,
:mod:`~polyloops.enumerate.arrangements`), the classes a map carries
(:mod:`~polyloops.enumerate.catalog`), the record (:mod:`~polyloops.enumerate.records`) and
the census (:mod:`~polyloops.enumerate.census`); reachability by loop moves
(:mod:`~polyloops.enumerate.reach`), the genus-0 conjecture and its certificates
(:mod:`~polyloops.enumerate.conjecture`), time-budgeted listing of moves
(:mod:`~polyloops.enumerate.listing`), and local or Dask workers
(:mod:`~polyloops.enumerate.parallel`).  It may import the kernel, ``io``, ``verify`` and
``solvers``.
"""
