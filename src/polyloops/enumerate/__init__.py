"""Enumerations: corner configurations, loop moves, catalogs."""
