"""TOML files read in one way, every failure one sentence that names the file; values written back.

The caller says what the file is (``what``: "scene file", "grid file"…) and which error to raise;
a directory given where a file is wanted can carry a hint of what to do instead.

>>> import tempfile, pathlib
>>> path = pathlib.Path(tempfile.mkdtemp()) / "a.toml"; _ = path.write_text("x = 1")
>>> read_toml(path, error=ValueError)
{'x': 1}
>>> try:
...     read_toml(path.with_name("b.toml"), what="scene file", error=ValueError)
... except ValueError as exc:
...     print(str(exc).split("/")[-1])
b.toml: no such scene file.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["read_toml", "read_toml_text", "toml_value"]


def read_toml(path: str | Path, *, error: type[Exception], what: str = "file", directory: str = "") -> dict:
    """The tables of the TOML file ``path``, or ``error`` with one sentence: missing, a directory
    (``directory``: what to do instead), not text, unreadable, or not valid TOML (with its line)."""
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except FileNotFoundError:
        raise error(f"{path}: no such {what}.") from None
    except IsADirectoryError:
        raise error(f"{path}: is a directory, not a {what}{'; ' + directory if directory else ''}.") from None
    except OSError as exc:
        raise error(f"{path}: cannot be read ({exc.strerror or exc}).") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise error(f"{path}: not a text file (byte {exc.start} is not UTF-8).") from None
    return read_toml_text(text, error=error, source=str(path))


def read_toml_text(text: str, *, error: type[Exception], source: str) -> dict:
    """The tables of TOML ``text`` (read from ``source``), or ``error``: "SOURCE: not valid TOML (…)."

    >>> read_toml_text("a = [1, 2", error=ValueError, source="x.toml")
    Traceback (most recent call last):
    ...
    ValueError: x.toml: not valid TOML (Unclosed array (at end of document)).
    """
    import tomllib  # 4 ms: loaded by the commands that read a TOML file, not by every command

    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise error(f"{source}: not valid TOML ({exc}).") from None


def toml_value(value) -> str:
    """``value`` (strings, booleans, numbers, lists and dicts of them, as JSON holds) written as a TOML value:
    a dict as an inline table, so that ``key = toml_value(v)`` is one line of a table that ``tomllib`` reads back.

    >>> print(toml_value({"P": {"link": 2, "at": [2.5, 4.5]}, "on": True, "name": "Watt"}))
    { "P" = { "link" = 2, "at" = [2.5, 4.5] }, "on" = true, "name" = "Watt" }
    """
    import json

    if isinstance(value, str):
        # a JSON string is a TOML basic string, escapes included, once DEL (a control character to TOML) is escaped
        return json.dumps(value, ensure_ascii=False).replace("\x7f", "\\u007f")
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(x) for x in value) + "]"
    return "{ " + ", ".join(f"{toml_value(str(k))} = {toml_value(x)}" for k, x in value.items()) + " }"
