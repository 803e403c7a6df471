"""Types of the compiled count of the addition graph's cycles (_cycles.c)."""

def count(indptr: bytes, succ: bytes, target: bytes, out_indptr: bytes, out_darts: bytes, allowed: bytes,
          starts: bytes, max_count: int, seconds: float, /) -> tuple[int, int]:
    """(the number of cycles found, 0 when complete / 1 stopped by max_count / 2 by the time
    limit); arrays as int32 bytes, ``allowed`` as one byte per dart."""
