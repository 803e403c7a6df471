"""The base of every error polyloops raises on purpose.

Each error keeps the built-in base it always had (most are ``ValueError``), so existing
``except ValueError`` code still works, and also derives from :class:`PolyloopsError`, so a
caller can catch everything polyloops says about its input in one clause, and nothing else:

>>> from polyloops.io.formats import FormatError
>>> issubclass(FormatError, PolyloopsError), issubclass(FormatError, ValueError)
(True, True)
"""

from __future__ import annotations


class PolyloopsError(Exception):
    """Raised by polyloops about its input or its search, never for a bug."""
