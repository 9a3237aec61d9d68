"""Figures written one way: the same figure gives the same bytes.

matplotlib stamps an SVG with the date and clip-path ids drawn at random, and SVG and PNG files
with its own version.  Every figure the project writes goes through :func:`save_figure`, which
fixes the salt of the SVG ids, keeps SVG text as text (searchable, selectable) and leaves the
date and the writer's version out of the file.

>>> import io, matplotlib
>>> matplotlib.use("Agg")
>>> import matplotlib.pyplot as plt
>>> def picture():
...     fig, ax = plt.subplots(figsize=(2, 2)); ax.fill([0, 1, 1], [0, 0, 1]); ax.set_title("a triangle")
...     out = io.BytesIO(); save_figure(fig, out, fmt="svg"); plt.close(fig)
...     return out.getvalue()
>>> first = picture(); first == picture(), b"<dc:date>" in first, b"a triangle" in first
(True, False, True)
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["save_figure"]

#: the settings under which a figure is written: stable SVG ids, SVG text kept as text
_STABLE = {"svg.hashsalt": "mechsynth", "svg.fonttype": "none"}

#: per format, the metadata keys matplotlib would fill with the date or its version
_NO_STAMP = {"svg": {"Date": None, "Creator": None}, "png": {"Software": None},
             "pdf": {"CreationDate": None, "Creator": None, "Producer": None}}


def save_figure(fig, target, *, fmt: str | None = None, **options) -> None:
    """Write the matplotlib figure ``fig`` to ``target`` (a path, or a file object with ``fmt``)
    byte for byte the same each time.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; it is not closed.
    target : str, Path or file object
        Where to write; a path's suffix names the format unless ``fmt`` does.
    fmt : str, optional
        ``svg``, ``png``, ``pdf`` or any format matplotlib writes.
    **options
        Passed to ``Figure.savefig`` (``dpi``, ``bbox_inches``, …).

    Raises
    ------
    OSError
        The target cannot be written (the caller names it in its own sentence).

    Examples
    --------
    >>> import io, tempfile, matplotlib
    >>> matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> fig, ax = plt.subplots(figsize=(1, 1)); _ = ax.plot([0, 1], [1, 0])
    >>> path = Path(tempfile.mkdtemp()) / "line.png"
    >>> save_figure(fig, path, dpi=50); first = path.read_bytes(); save_figure(fig, path, dpi=50)
    >>> path.read_bytes() == first, b"Matplotlib" in first
    (True, False)
    >>> plt.close(fig)
    """
    import matplotlib

    fmt = (fmt or Path(target).suffix.lstrip(".")).lower()
    stamp = {"metadata": _NO_STAMP[fmt]} if fmt in _NO_STAMP else {}
    with matplotlib.rc_context(_STABLE):
        fig.savefig(target, format=fmt, **stamp, **options)
