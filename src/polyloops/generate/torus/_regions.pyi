"""Types of the compiled region search of the torus (_regions.c)."""

# region choices, over the budget, inconsistent, one way round, complete, kept
RegionCounts = tuple[int, int, int, int, int, int]

def systems(spec: bytes, max_options: int = 50000, /) -> tuple[list[bytes], RegionCounts]: ...
