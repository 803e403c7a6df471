"""Orientation solvers for labelled loop structures (exhaustive, SAT, SMT)."""
