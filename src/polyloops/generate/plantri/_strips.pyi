"""Types of the compiled strip filter (_strips.c)."""

def filter_maps(records: object, n: int, max_degree: int, /) -> tuple[bytes, int]:
    """(the records whose strips are all simple closed curves, the number of them); records:
    any object with the buffer protocol (a numpy array of planar-code rows)."""
