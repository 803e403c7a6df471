"""Reachability by loop moves: the search (:mod:`~polyloops.reach.search`), the conjecture and
its certificates (:mod:`~polyloops.reach.conjecture`), the move graph of a catalog
(:mod:`~polyloops.reach.move_graph`), listings of moves under a budget
(:mod:`~polyloops.reach.listing`) and the catalogs' cross-checks
(:mod:`~polyloops.reach.crosscheck`)."""
