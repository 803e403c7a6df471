"""Types of the compiled first stage of the torus search (_squares.c)."""

# nodes, leaves, leaves of a lower genus, not canonical, subtrees split among shares
SquareCounts = tuple[int, int, int, int, int]

def bases(crossings: int, genus: int, res: int = 0, mod: int = 1, split: int = -1, keep: bool = True,
          /) -> tuple[list[bytes] | int, SquareCounts]: ...
