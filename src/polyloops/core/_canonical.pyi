"""Types of the compiled canonical form (_canonical.c)."""

def canonical(nxt: bytes, twin: bytes, prev: bytes, base: bytes, tables: bytes, dets: bytes,
              /) -> tuple[bytes, int, int]:
    """(the least code as int32 bytes, the number of roots reaching it, the determinants among
    them as a mask: bit 0 for +1, bit 1 for -1); every argument int32 bytes."""

def encode(code: bytes, oriented: bool, /) -> str:
    """The signature text of a canonical code (int32 bytes)."""
