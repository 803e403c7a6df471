"""Types of the compiled torus search (_torus.c)."""

# (canonical twin array as uint16 bytes, layer bytes, flags: 1 a target, 2 balanced, 4 no loop of B
# lacking third-axis crossings)
LayeredChild = tuple[bytes, bytes, int]
# paths drawn, cycles closed, closed over the bound, third axis not orientable, not canonical,
# new loop in fewer than four runs
SecondCounts = tuple[int, int, int, int, int, int]
# (canonical twin array as uint16 bytes, marks as (kind, dart), whether cellular)
MarkedChild = tuple[bytes, list[tuple[str, int]], int]
# paths drawn, curves closed, closed over the bound, not canonical, not colourable
FirstCounts = tuple[int, int, int, int, int]

def children(twin: bytes, layer: bytes, limit: int, /) -> tuple[list[LayeredChild], SecondCounts]: ...
def layered_code(twin: bytes, layer: bytes, /) -> bytes: ...
def first_children(twin: bytes, marks: list[tuple[str, int]] | int, limit: int, colours: int,
                   /) -> tuple[list[MarkedChild], FirstCounts]: ...
