"""Classical names of chains and of their inversions (mechanisms), from a small table.

Each entry is a chain as the textbooks draw it, written here with its links numbered, its name,
and the names of its inversions by fixed link.  A chain has the name when it is the same chain
(equal certificates, joint kinds included); a mechanism has the inversion's name when fixing
its frame gives the same mechanism as fixing that link of the entry (equal mechanism
certificates), so any numbering of the links finds it.  Structure alone decides: inversions
that differ only by link lengths (crank-rocker or double-crank four-bars) share one name, and
two classical inversions that are structurally the same mechanism (the slider-crank's guide
fixed or its slider fixed) share one entry, which says so.

The definitions, checked in ``tests/analysis/test_classical.py`` on every numbering:

* **Watt chain**: the six-bar whose two ternary links are jointed directly; **Watt I** fixes a
  binary link, **Watt II** a ternary one (two four-bars in series).
* **Stephenson chain**: the six-bar whose ternary links are not jointed; **Stephenson I** fixes
  a binary link jointed to both ternary links, **Stephenson II** a binary link jointed to one,
  **Stephenson III** a ternary link (a four-bar with a dyad from its coupler to the frame).
* **Slider-crank chain**: a four-bar loop with one prismatic pair.  Fixing a link of the
  prismatic pair (the guide: 1st inversion, the engine; or the slider: 4th, the hand pump)
  gives one structure, fixing one of the others (the crank: 2nd, Whitworth quick return and
  rotary engine; or the connecting rod: 3rd, oscillating cylinder) the other.
* **Double-slider chain**: a four-bar loop with two adjacent prismatic pairs; the **elliptical
  trammel** fixes the link carrying both, the **Scotch yoke** a link with one prismatic and
  one revolute pair, the **Oldham coupling** the link with two revolute pairs.
* **Assur group of class II** (a dyad): with its base link, a triangle of three links (W = 0);
  the dyad's type lists its outer, middle and outer pair: RRR, RRP, RPR, PRP, RPP.
* **Assur group of class III** (a triad): a ternary link and three binary links, each binary
  link jointed to the base; with its base, two ternary links joined by three binary links
  (W = 0).  Fixing a binary link instead leaves a closed contour of four links with two outer
  pairs: an Assur group of class IV (order 2).
* **Four-bar** and **five-bar** chains: one loop of four (W = 1) or five (W = 2) links, all
  pins.

Example
-------
>>> from synth.structure.chain import Chain
>>> watt = Chain.parse("0-2 2-4 4-1 1-0 0-3 3-5 5-1")
>>> chain_names(watt), inversion_names(watt, 0), inversion_names(watt, 2)
(['Watt chain'], ['Watt II'], ['Watt I'])
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

from ..structure.chain import Chain, Mechanism

__all__ = ["Classical", "TABLE", "chain_names", "inversion_names"]


@dataclass(frozen=True)
class Classical:
    """One named chain: its joint list, its name, and the names of its inversions by fixed link
    (links of one symmetry orbit give the same inversion: one of them is listed)."""

    chain: str
    name: str
    inversions: tuple[tuple[int, str], ...] = ()


TABLE = (
    Classical("0-1 1-2 2-3 3-0", "four-bar chain", ((0, "four-bar linkage"),)),
    Classical("0-1 1-2 2-3 3-4 4-0", "five-bar chain", ((0, "five-bar linkage"),)),
    # 0 guide (frame of the engine), 1 crank, 2 connecting rod, 3 slider
    Classical("0-1 1-2 2-3 3=0", "slider-crank chain", (
        (0, "slider-crank, 1st inversion (guide fixed) = 4th inversion (slider fixed: hand pump)"),
        (1, "slider-crank, 2nd inversion (crank fixed: Whitworth quick return, rotary engine) = 3rd inversion "
            "(connecting rod fixed: oscillating cylinder)"))),
    # 0 carries both prismatic pairs, 1 and 2 one prismatic and one revolute pair, 3 two revolute pairs
    Classical("0=1 1-3 3-2 2=0", "double-slider chain", (
        (0, "elliptical trammel"), (1, "Scotch yoke"), (3, "Oldham coupling"))),
    # 0 and 1 ternary, jointed directly
    Classical("0-1 1-2 2-3 3-0 0-4 4-5 5-1", "Watt chain", ((0, "Watt II"), (2, "Watt I"))),
    # 0 and 1 ternary; 2 and 3 jointed to both; 4 and 5 the two-link path
    Classical("0-2 2-1 0-3 3-1 0-4 4-5 5-1", "Stephenson chain", (
        (2, "Stephenson I"), (4, "Stephenson II"), (0, "Stephenson III"))),
    # a dyad (links 1, 2, middle pair 1-2) on its base 0
    Classical("0-1 1-2 2-0", "Assur group of class II (a dyad) with its base", ((0, "dyad RRR"),)),
    Classical("0-1 1-2 2=0", "Assur group of class II (a dyad) with its base", ((0, "dyad RRP"), (1, "dyad RPR"))),
    Classical("0=1 1-2 2=0", "Assur group of class II (a dyad) with its base", ((0, "dyad PRP"), (1, "dyad RPP"))),
    # a triad (ternary 1, binary 2, 3, 4) on its base 0
    Classical("0-2 2-1 0-3 3-1 0-4 4-1", "Assur group of class III (a triad) with its base", (
        (0, "triad (Assur group of class III)"), (2, "Assur group of class IV, order 2 (a four-link contour)"))),
)


@lru_cache(maxsize=1)
def _by_certificate() -> dict[str, list[tuple[Chain, Classical]]]:
    found: dict[str, list] = {}
    for entry in TABLE:
        chain = Chain.parse(entry.chain)
        found.setdefault(chain.certificate, []).append((chain, entry))
    return found


def chain_names(chain: Chain) -> list[str]:
    """The classical names of a chain (empty where it has none).

    >>> chain_names(Chain.parse("0-1 1=2 2-3 3-0"))
    ['slider-crank chain']
    """
    return [entry.name for _, entry in _by_certificate().get(chain.certificate, [])]


def inversion_names(chain: Chain, frame: int) -> list[str]:
    """The classical names of the mechanism that fixes ``frame`` of ``chain`` (empty where none).

    >>> inversion_names(Chain.parse("0-1 1-2 2=3 3-0"), 3)[0].startswith("slider-crank, 1st inversion")
    True
    """
    wanted = Mechanism(chain, frame).certificate
    return [name for known, entry in _by_certificate().get(chain.certificate, [])
            for link, name in entry.inversions if Mechanism(known, link).certificate == wanted]
