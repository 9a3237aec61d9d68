"""Gear-train cells of an atlas: their units (one link–axis tree each), the trains of a unit, and
what the atlas keeps of them beside their chains.

A planetary gear train is stored as a chain with joint kinds (its axes revolute joints, its
meshes ``mesh`` joints; :meth:`synth.gears.GearTrain.to_chain`) in the ``chains`` table, keyed by
that chain's certificate like every chain, and a ``trains`` row: its text form in the stored
chain's labelling, its lever analogue's code, its number of carrier links, its rotation graph's
certificate and its rank in :func:`synth.gears.trains`' order (tree, then generation order).

A cell of rotation graphs keeps one train per rotation graph: the one of least rank, which is
the train ``mechsynth gears --graphs rotation`` lists.  Units finish in any order, so a unit's
train may displace the one an earlier unit stored for the same rotation graph (``rotations``
names the current one); a displaced train leaves the atlas unless another cell holds it.

Example
-------
>>> [u.key for u in plan_gear_cell(GearCell(1, 4))]
['tree 0000', 'tree 0001', 'tree 0002', 'tree 0003']
>>> [t.compact() for t, _ in unit_trains(plan_gear_cell(GearCell(1, 4))[0])]
['0-1 0-2 0-3 1~2 1~3']
"""

from __future__ import annotations

import sqlite3
from dataclasses import dataclass, replace

from ..gears.enumeration import link_axis_trees, tree_trains
from ..gears.train import GearTrain
from .grid import GearCell

__all__ = ["TrainUnit", "plan_gear_cell", "unit_trains", "train_row", "keep_representatives", "store_trains"]

_RANK_SHIFT = 32  # rank = tree index · 2^32 + position in the tree's generation order


@dataclass(frozen=True)
class TrainUnit:
    """One link–axis tree of a gear cell: the trains on it are one unit of work."""

    dof: int
    links: int
    tree: int
    axes: tuple[tuple[int, ...], ...]
    graphs: str = "displacement"

    @property
    def key(self) -> str:
        return f"tree {self.tree:04d}"

    @property
    def code(self) -> str:
        """The tree as its axes (the ``code`` column of the atlas's units)."""
        return " ".join("-".join(map(str, axis)) for axis in self.axes)


def plan_gear_cell(cell: GearCell) -> list[TrainUnit]:
    """The units of a gear cell: one per link–axis tree of n links, in the enumeration's order."""
    return [TrainUnit(cell.dof, cell.links, k, axes, cell.graphs) for k, axes in enumerate(link_axis_trees(cell.links))]


def unit_trains(unit: TrainUnit) -> list[tuple[GearTrain, int]]:
    """The trains of one unit with their ranks; in a cell of rotation graphs, the first of each
    rotation graph on this tree only."""
    found, seen = [], set()
    for position, train in enumerate(tree_trains(unit.dof, unit.links, unit.axes)):
        if unit.graphs == "rotation":
            if train.rotation_certificate in seen:
                continue
            seen.add(train.rotation_certificate)
        found.append((train, (unit.tree << _RANK_SHIFT) + position))
    return found


def train_row(train: GearTrain, certificate: str, rank: int) -> tuple:
    """The ``trains`` row of a train (given in the stored chain's labelling), keyed by the chain's certificate."""
    return (certificate, train.compact(), str(train.lever_analogue().code), len(set(train.carriers)),
            train.rotation_certificate, rank)


def keep_representatives(conn: sqlite3.Connection, cell: str, rows):
    """In a cell of rotation graphs: the unit's rows without the trains whose rotation graph the
    cell already holds by a train of lower rank, and the ids of the trains they displace."""
    keep, displaced = set(), []
    for cert, _, _, _, rotation, rank in rows.trains:
        old = conn.execute("SELECT chain, rank FROM rotations WHERE cell = ? AND rotation = ?",
                           (cell, rotation)).fetchone()
        if old is None or rank < old[1]:
            keep.add(cert)
            displaced += [] if old is None else [old[0]]
    kept = replace(rows, chains=[c for c in rows.chains if c[0] in keep],
                   link_counts=[c for c in rows.link_counts if c[0] in keep],
                   mechanisms=[m for m in rows.mechanisms if m[0] in keep],
                   trains=[t for t in rows.trains if t[0] in keep])
    return kept, displaced


def store_trains(conn: sqlite3.Connection, rows, ids: dict[str, int], displaced: list[int]) -> None:
    """Write a unit's ``trains`` rows (inside the unit's transaction); in a cell of rotation graphs
    also its representatives, and drop the displaced trains no other cell holds."""
    conn.executemany("INSERT OR IGNORE INTO trains VALUES (?, ?, ?, ?, ?, ?)",
                     [(ids[cert], *rest) for cert, *rest in rows.trains])
    if not rows.rotation:
        return
    conn.executemany("INSERT OR REPLACE INTO rotations VALUES (?, ?, ?, ?)",
                     [(rows.cell, rotation, ids[cert], rank) for cert, _, _, _, rotation, rank in rows.trains])
    for chain in displaced:
        conn.execute("DELETE FROM members WHERE cell = ? AND chain = ?", (rows.cell, chain))
        if conn.execute("SELECT 1 FROM members WHERE chain = ?", (chain,)).fetchone() is None:
            for table in ("trains", "link_counts", "mechanisms"):
                conn.execute(f"DELETE FROM {table} WHERE chain = ?", (chain,))
            conn.execute("DELETE FROM chains WHERE id = ?", (chain,))
