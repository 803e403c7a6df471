"""Writing files so that no half-written file is ever left: through a temporary file in the
same directory and a rename (atomic on POSIX and Windows).

>>> import tempfile, pathlib
>>> with tempfile.TemporaryDirectory() as tmp:
...     write_atomic(pathlib.Path(tmp) / "a.txt", "hello")
...     print((pathlib.Path(tmp) / "a.txt").read_text(), len(list(pathlib.Path(tmp).iterdir())))
hello 1
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path


def _default_mode() -> int:
    """The permissions a plain ``open(path, "w")`` would give (0o666 less the umask)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def replace_atomic(tmp: str, target: str | os.PathLike[str]) -> None:
    """Give a finished temporary file ordinary permissions and move it into place."""
    os.chmod(tmp, _default_mode())
    os.replace(tmp, target)


def write_atomic(path: str | os.PathLike[str], text: str | bytes) -> None:
    """Write text (UTF-8) or bytes through a temporary file and rename, so no half-written
    file is ever left."""
    target = Path(path)
    fd, tmp = tempfile.mkstemp(dir=target.parent or ".", prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(text.encode("utf-8") if isinstance(text, str) else text)
        replace_atomic(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
