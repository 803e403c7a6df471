"""Catalogs: the pipeline that runs a generator's jobs and merges them (:mod:`~polyloops.catalog.run`),
the classes a map carries (:mod:`~polyloops.catalog.classes`), the record
(:mod:`~polyloops.catalog.records`) and the census a directory holds
(:mod:`~polyloops.catalog.census`)."""
