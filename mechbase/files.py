"""Text files read in one way: a missing or unreadable file is one sentence that names it.

>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "target.csv"; _ = path.write_text("x,y")
>>> read_text(path, error=ValueError, what="target file")
'x,y'
>>> try:
...     read_text(path.with_name("none.csv"), error=ValueError, what="target file")
... except ValueError as exc:
...     print(str(exc).split("/")[-1])
none.csv'
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["read_text"]


def read_text(path: str | Path, *, error: type[Exception], what: str = "file") -> str:
    """The UTF-8 text of ``path``, or ``error``: "no WHAT 'PATH'" or "cannot read 'PATH': why"."""
    try:
        return Path(path).read_text(encoding="utf-8")
    except FileNotFoundError:
        raise error(f"no {what} {str(path)!r}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise error(f"cannot read {str(path)!r}: {getattr(exc, 'strerror', None) or exc}") from None
