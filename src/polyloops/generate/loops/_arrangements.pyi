"""Types of the compiled arrangement search (_arrangements.c)."""

# (canonical twin array as uint16 bytes, whether the arrangement is a candidate map)
Child = tuple[bytes, int]
# curves drawn, curves closed, closed curves over the bound, closed curves not canonical,
# closed curves whose child's crossing graph is not 3-colourable (cut 4), closed curves over
# cut 5's bound (regions with several sides on one loop)
Counts = tuple[int, int, int, int, int, int]

def children(rot: bytes, twin: bytes, limit: int, colour_cut: bool = True, meet_cut: bool = True,
             /) -> tuple[list[Child], Counts]: ...
def canonical(rot: bytes, twin: bytes, meet_cut: bool = True, /) -> tuple[bytes, int]: ...
