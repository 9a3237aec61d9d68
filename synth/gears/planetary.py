"""Planetary gear trains through their lever analogues (docs/theory.md, "Gear trains through lever analogues").

Each gear mesh becomes a binary link between the two gears' pitch points.  A train with k0
satellites has the fixed ring (the frame, link 0), the carrier (1), the sun (2), the satellites
and, per satellite, a mesh link to the ring and one to the sun.  The sun floats (held only by
its meshes) or turns on a fixed axis (a pivot on the ring).

Example
-------
>>> row = planetary_row(3)
>>> row["code"], row["dof"], row["defect"], row["determinate"]
('64200/0', 1, 0, True)
>>> [g["name"] for g in row["assur_groups"]]
['dyad', 'dyad', 'dyad', 'triad']
"""

from __future__ import annotations

from itertools import combinations

from ..structure.chain import Chain
from ..errors import InvalidOption
from ..structure.subchains import _MAX_CORE, check_subchains

__all__ = ["RING", "CARRIER", "SUN", "lever_analogue", "assur_groups", "planetary_row", "planetary_table",
           "planetary_rows"]

RING, CARRIER, SUN = 0, 1, 2
SUNS = ("floating", "fixed")


def lever_analogue(satellites: int, sun: str = "floating") -> Chain:
    """Lever analogue of a planetary train: ring 0 (frame), carrier 1, sun 2, then per satellite
    the satellite, its ring mesh link and its sun mesh link.

    >>> c = lever_analogue(3); c.links, len(c.joints), c.dof
    (12, 16, 1)
    """
    if isinstance(satellites, bool) or not isinstance(satellites, int) or satellites < 1:
        raise InvalidOption(f"a planetary train needs a whole number of satellites ≥ 1, not {satellites!r}")
    if sun not in SUNS:
        raise InvalidOption(f"the sun is {' or '.join(SUNS)}, not {sun!r}")
    joints = [(RING, CARRIER)] + ([(RING, SUN)] if sun == "fixed" else [])
    for i in range(satellites):
        planet, to_ring, to_sun = 3 + 3 * i, 4 + 3 * i, 5 + 3 * i
        joints += [(CARRIER, planet), (planet, to_ring), (to_ring, RING), (planet, to_sun), (to_sun, SUN)]
    return Chain(3 + 3 * satellites, joints)


_GROUP_NAMES = {(2, 2): "dyad", (4, 3): "triad"}  # (links, outer joints)


def assur_groups(chain: Chain, frame: int, driving: int, *, largest: int = 6) -> list[dict]:
    """Split a 1-DOF mechanism into Assur groups (W = 0, none smaller inside), smallest first.

    With the frame and the driving link placed, a set S of the other links is a group when its
    joints among S and the placed links leave 3|S| − 2p = 0 and no smaller set does; joints to
    links not yet placed are the outer joints of later groups.

    >>> [g["links"] for g in assur_groups(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)]
    [[2, 3]]
    """
    placed = {frame, driving}
    groups = []
    while len(placed) < chain.links:
        rest = [x for x in range(chain.links) if x not in placed]
        found = None
        for size in range(2, min(largest, len(rest)) + 1, 2):
            for s in combinations(rest, size):
                inner = [j for j in chain.joints
                         if any(x in s for x in j) and all(x in s or x in placed for x in j)]
                if 3 * size - 2 * sum(len(j) - 1 for j in inner) == 0:
                    found = s
                    break
            if found:
                break
        if found is None:
            return []
        outer = [list(j) for j in chain.joints if any(x in found for x in j) and any(x in placed for x in j)]
        groups.append({"name": _GROUP_NAMES.get((len(found), len(outer)), f"{len(found)}-link group"),
                       "links": list(found), "outer_joints": outer})
        placed.update(found)
    return groups


def planetary_row(satellites: int, sun: str = "floating") -> dict:
    """Code, W, K, D (against W = 1), exact sub-chain verdict and Assur groups of one train."""
    chain = lever_analogue(satellites, sun)
    report = check_subchains(chain)
    defect = chain.dof - 1
    determinate = chain.dof == 1 and defect == 0 and report.ok
    return {
        "satellites": satellites, "sun": sun, "code": str(chain.code), "links": chain.links,
        "joints": [list(j) for j in chain.joints], "dof": chain.dof, "loops": chain.loops, "defect": defect,
        "subchains": report.kind, "worst_subchain": list(report.worst), "determinate": determinate,
        "assur_groups": assur_groups(chain, RING, CARRIER) if determinate else [],
    }


def planetary_table(satellites: tuple[int, int], sun: str = "floating") -> list[dict]:
    """:func:`planetary_row` for k0 = A … B satellites.

    >>> [r["satellites"] for r in planetary_table((1, 6)) if r["determinate"]]
    [3]
    """
    return list(planetary_rows(satellites, sun))


def planetary_rows(satellites: tuple[int, int], sun: str = "floating"):
    """:func:`planetary_table` one row at a time, the range checked before the first row.

    The exact sub-chain test is exponential in the non-binary links (k0 + 3 of them): a range
    it cannot finish is refused at once rather than after the rows before it.

    >>> next(planetary_rows((30, 31)))
    Traceback (most recent call last):
    ...
    synth.errors.InvalidOption: --satellites 30..31: at most 21 satellites, whose lever analogue has 24 non-binary links (the exact sub-chain test handles up to 24)
    """
    lo, hi = satellites
    if lo < 1:
        raise InvalidOption(f"a planetary train needs at least one satellite, not {lo}")
    most = next(k for k in range(1, _MAX_CORE + 1) if _core_links(k + 1, sun) > _MAX_CORE)
    if hi > most:
        raise InvalidOption(f"--satellites {lo}..{hi}: at most {most} satellites, whose lever analogue has "
                            f"{_core_links(most, sun)} non-binary links (the exact sub-chain test handles up to "
                            f"{_MAX_CORE})")
    for k in range(lo, hi + 1):
        yield planetary_row(k, sun)


def _core_links(satellites: int, sun: str) -> int:
    """Links of the lever analogue that do not carry exactly two joints (the exact test's core)."""
    return sum(1 for d in lever_analogue(satellites, sun).degrees if d != 2)
