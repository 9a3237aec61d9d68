"""The source's planetary layout — k satellites on one carrier, a fixed ring, a floating or fixed
sun — as a gear train, judged by the general analysis of a chain with gear meshes
(docs/gears.md, "Any gear train by its lever analogue").

The train: ring 0 (the frame), carrier 1 on the ring's axis, sun 2, satellites 3 … k + 2 each on
an axis of its own on the carrier, meshing the ring inside (``0~3i``) and the sun (``2~3@1``: the
carrier holds that mesh too).  The sun floats (held by its meshes only) or turns on a fixed axis
of the ring.  W, K, D, the sub-chain verdict and the lever analogue's code are those of
:func:`~synth.analysis.chains.analyze_chain` on :meth:`GearTrain.to_chain`; the Assur groups
split the lever analogue (ring fixed, carrier driving).

Example
-------
>>> row = planetary_row(3)
>>> row.code, row.dof, row.defect, row.determinate
('64200/0', 1, 0, True)
>>> [g.name for g in row.assur_groups]
['dyad', 'dyad', 'dyad', 'triad']
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from mechbase import Row

from ..structure.chain import Chain
from ..errors import InvalidOption
from ..structure.kinds import lever_analogue as lever_of
from ..structure.subchains import MAX_CORE
from .train import GearTrain

__all__ = ["RING", "CARRIER", "SUN", "AssurGroup", "PlanetaryRow", "planetary_train", "lever_analogue",
           "assur_groups", "planetary_row", "planetary_table", "planetary_rows"]

RING, CARRIER, SUN = 0, 1, 2
SUNS = ("floating", "fixed")


def planetary_train(satellites: int, sun: str = "floating") -> GearTrain:
    """The planetary train with ``satellites`` planets: ring 0 fixed, carrier 1, sun 2, planets 3, 4, ….

    >>> planetary_train(3).compact()
    '0-1 1-3 1-4 1-5 0~3i 0~4i 0~5i 2~3@1 2~4@1 2~5@1'
    >>> planetary_train(1, "fixed").compact()
    '0-1 0-2 1-3 0~3i 2~3@1'
    """
    if isinstance(satellites, bool) or not isinstance(satellites, int) or satellites < 1:
        raise InvalidOption(f"a planetary train needs a whole number of satellites ≥ 1, not {satellites!r}")
    if sun not in SUNS:
        raise InvalidOption(f"the sun is {' or '.join(SUNS)}, not {sun!r}")
    planets = range(3, 3 + satellites)
    axes = [(RING, CARRIER)] + ([(RING, SUN)] if sun == "fixed" else []) + [(CARRIER, p) for p in planets]
    meshes = [(RING, p) for p in planets] + [(SUN, p) for p in planets]
    return GearTrain(3 + satellites, axes, meshes, [CARRIER] * len(meshes),
                     [True] * satellites + [False] * satellites, RING)


def lever_analogue(satellites: int, sun: str = "floating") -> Chain:
    """Lever analogue of the planetary train: its links, then a binary link per mesh.

    >>> c = lever_analogue(3); c.links, len(c.joints), c.dof
    (12, 16, 1)
    """
    return planetary_train(satellites, sun).lever_analogue()


_GROUP_NAMES = {(2, 2): "dyad", (4, 3): "triad"}  # (links, outer joints)


@dataclass(frozen=True)
class AssurGroup(Row):
    """An Assur group: its ``name`` (dyad, triad, …), its ``links`` and the joints that join it to
    the links placed before it (``outer_joints``)."""

    name: str
    links: tuple[int, ...]
    outer_joints: tuple[tuple[int, ...], ...]


@dataclass(frozen=True)
class PlanetaryRow(Row):
    """One planetary train as its lever analogue shows it: code, W, K, D against W = 1, the exact
    sub-chain verdict and, for a determinate train, its Assur groups."""

    satellites: int
    sun: str
    code: str
    links: int
    joints: tuple[tuple[int, ...], ...]
    train: str
    dof: int
    loops: int
    defect: int
    subchains: str
    worst_subchain: tuple[int, ...]
    redundant_joints: tuple[tuple[int, ...], ...] | None
    determinate: bool
    assur_groups: tuple[AssurGroup, ...]


def assur_groups(chain: Chain, frame: int, driving: int, *, largest: int = 6) -> list[AssurGroup]:
    """Split a 1-DOF mechanism into Assur groups (W = 0, none smaller inside), smallest first.

    With the frame and the driving link placed, a set S of the other links is a group when its
    joints among S and the placed links leave 3|S| − 2p = 0 and no smaller set does; joints to
    links not yet placed are the outer joints of later groups.

    >>> [g.links for g in assur_groups(Chain.parse("0-1 1-2 2-3 3-0"), 0, 1)]
    [(2, 3)]
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
        outer = tuple(j for j in chain.joints if any(x in found for x in j) and any(x in placed for x in j))
        groups.append(AssurGroup(_GROUP_NAMES.get((len(found), len(outer)), f"{len(found)}-link group"),
                                 tuple(found), outer))
        placed.update(found)
    return groups


def planetary_row(satellites: int, sun: str = "floating") -> PlanetaryRow:
    """Code, W, K, D (against W = 1), exact sub-chain verdict and Assur groups of one train, from
    the general analysis of the train as a chain with gear meshes."""
    from ..analysis.chains import analyze_chain

    chain = planetary_train(satellites, sun).to_chain()
    report = analyze_chain(chain, dof=1)
    lever = lever_of(chain)
    determinate = report.dof_count == 1 and report.defect == 0 and report.subchain_defect == "none"
    return PlanetaryRow(satellites, sun, report.lever_analogue, lever.links, tuple(lever.joints), chain.compact(),
                        report.dof_count, report.loops, report.defect, report.subchain_defect,
                        tuple(report.worst_subchain),
                        None if report.redundant_joints is None else tuple(report.redundant_joints), determinate,
                        tuple(assur_groups(lever, RING, CARRIER)) if determinate else ())


def planetary_table(satellites: tuple[int, int], sun: str = "floating") -> list[PlanetaryRow]:
    """:func:`planetary_row` for k0 = A … B satellites.

    >>> [r.satellites for r in planetary_table((1, 6)) if r.determinate]
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
    synth.errors.InvalidOption: 30..31 satellites: at most 21, whose lever analogue has 24 non-binary links (the exact sub-chain test handles up to 24)
    """
    lo, hi = satellites
    if lo < 1:
        raise InvalidOption(f"a planetary train needs at least one satellite, not {lo}")
    most = next(k for k in range(1, MAX_CORE + 1) if _core_links(k + 1, sun) > MAX_CORE)
    if hi > most:
        raise InvalidOption(f"{lo}..{hi} satellites: at most {most}, whose lever analogue has "
                            f"{_core_links(most, sun)} non-binary links (the exact sub-chain test handles up to "
                            f"{MAX_CORE})")
    for k in range(lo, hi + 1):
        yield planetary_row(k, sun)


def _core_links(satellites: int, sun: str) -> int:
    """Links of the lever analogue that do not carry exactly two joints (the exact test's core)."""
    return sum(1 for d in lever_analogue(satellites, sun).degrees if d != 2)
