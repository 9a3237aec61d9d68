"""Which chain is this, read from anywhere: :func:`identify` and :func:`identify_all` read a source in
any format (:mod:`synth.exchange`) and identify each chain it holds
(:func:`synth.analysis.identify.identify_entry`: id, code, row in its listing, symmetry, names).

>>> identify("0-1 1-2 2-3 3-0 0-4 4-5 5-1", frame=3).inversion
['Watt I']
"""

from __future__ import annotations

from dataclasses import replace

from ..analysis.identify import Identity, identify_entry
from ..errors import InvalidOption
from . import in_motion_space, read

__all__ = ["identify", "identify_all"]


def identify_all(source, *, fmt: str | None = None, frame=None, h: int | None = None,
                 index: bool | None = None) -> list[Identity]:
    """:func:`identify` every chain of a source (a file or text may hold several)."""
    entries = read(source, fmt)
    if frame is not None and len(entries) > 1:
        raise InvalidOption(f"a frame names one link of one chain, and the source holds {len(entries)} chains")
    out = []
    for entry in entries:
        if h is not None and h != entry.chain.h and entry.chain.classes is not None:
            raise InvalidOption(f"the chain names its loop classes (its other links are of class {entry.chain.h}): "
                                f"h = {h} contradicts them")
        entry = in_motion_space(entry, h)
        if frame is not None:
            names = entry.names or [str(i) for i in range(entry.chain.links)]
            if str(frame) not in names:
                raise InvalidOption(f"the frame {frame} is not a link of the chain ({names[0]} … {names[-1]})")
            entry = replace(entry, frame=names.index(str(frame)), input_link=None)  # an input went with its frame
        out.append(identify_entry(entry, index=index))
    return out


def identify(source, *, fmt: str | None = None, frame=None, h: int | None = None,
             index: bool | None = None) -> Identity:
    """Identify one chain or mechanism.

    Parameters
    ----------
    source : Chain, Mechanism, networkx graph, path or text
        Anything :func:`synth.exchange.read` reads: a joint list (``"0-1 1=2 2-3 3-0"``), a JSON
        row, a file in any of :data:`synth.exchange.FORMATS`, ``Chain.to_networkx()``.
    fmt : str, optional
        The input format, when it is not to be detected.
    frame : link, optional
        Fix this link (as the source names it): identify the mechanism.
    h : int, optional
        Motion space of the loops, for a source that states none (default the chain's own: 3 for
        a joint list); a source that states another h is refused.
    index : bool, optional
        Find the chain's row in its code's listing: None (default) where listing every chain of
        its link count is estimated to take at most :data:`INDEX_SECONDS` on one core
        (:func:`index_size`), True always, False never.

    Returns
    -------
    Identity

    Raises
    ------
    MalformedChain
        The source cannot be read as a chain (one sentence: what, and where).
    InvalidOption
        The source holds several chains (use :func:`identify_all`), or the frame is no link.
    """
    found = identify_all(source, fmt=fmt, frame=frame, h=h, index=index)
    if len(found) != 1:
        raise InvalidOption(f"the source holds {len(found)} chains: identify_all identifies each")
    return found[0]
