"""Strength tests of :mod:`synth.atlas.trains`, light enough to judge it in mutation runs: the units of a
gear cell against the enumerator's trees, ranks by hand, each column of a ``trains`` row against the
train's own properties, and the keeping, displacing and dropping of rotation representatives on a
small hand-built database (every row written out), then one tiny grid run whose units finish in
reverse order."""

from __future__ import annotations

import sqlite3
from dataclasses import dataclass, field

from synth.atlas import run_grid
from synth.atlas.grid import GearCell, parse_grid
from synth.atlas.trains import TrainUnit, keep_representatives, plan_gear_cell, store_trains, train_row, unit_trains
from synth.gears import GearTrain, trains
from synth.gears.enumeration import link_axis_trees, tree_trains

from .helpers import units_in_reverse


def test_the_units_of_a_gear_cell_are_its_link_axis_trees_in_order():
    units = plan_gear_cell(GearCell(2, 5, "rotation"))
    assert [u.axes for u in units] == list(link_axis_trees(5))
    assert [u.tree for u in units] == list(range(9))
    assert {(u.dof, u.links, u.graphs) for u in units} == {(2, 5, "rotation")}
    # the key and the code column of the first and last units, written out
    assert (units[0].key, units[0].code) == ("tree 0000", "0-1-4 0-2 0-3")
    assert (units[8].key, units[8].code) == ("tree 0008", "0-1 0-2 0-3 1-4")
    assert TrainUnit(1, 5, 12345, ((0, 1),)).key == "tree 12345"
    assert plan_gear_cell(GearCell(1, 5))[3].graphs == "displacement"


def test_a_units_trains_are_ranked_by_tree_then_generation_order():
    unit = TrainUnit(1, 5, 1, ((0, 1, 4), (0, 2), (1, 3)))
    got = unit_trains(unit)
    wanted = list(tree_trains(1, 5, unit.axes))
    assert [t.compact() for t, _ in got] == [t.compact() for t in wanted] and len(got) == 2
    assert [rank for _, rank in got] == [2 ** 32, 2 ** 32 + 1]  # tree 1, positions 0 and 1


def test_a_rotation_unit_keeps_the_first_train_of_each_rotation_graph():
    six = plan_gear_cell(GearCell(1, 6, "rotation"))
    kept_in_some_unit = 0
    for unit in six:
        every = list(tree_trains(1, 6, unit.axes))
        got = unit_trains(unit)
        # one train per rotation graph met on the tree, each the first of its graph in generation order
        first = {}
        for position, train in enumerate(every):
            first.setdefault(train.rotation_certificate, (position, train.compact()))
        assert sorted((rank - (unit.tree << 32), train.compact()) for train, rank in got) == sorted(first.values())
        kept_in_some_unit += len(got) < len(every)
    assert kept_in_some_unit  # the case is one where some tree has two trains of one rotation graph
    # over the whole cell, the least rank of each rotation graph gives the cell's 27 representatives
    least = {}
    for unit in six:
        for train, rank in unit_trains(unit):
            if rank < least.get(train.rotation_certificate, (rank + 1,))[0]:
                least[train.rotation_certificate] = (rank, train.to_chain().certificate)
    assert {c for _, c in least.values()} == {t.to_chain().certificate for t in trains(1, 6, "rotation")}


def test_a_trains_row_is_the_trains_own_description():
    # two meshes on one carrier: two carrier entries but one carrier link
    train = GearTrain.parse("0-1 0-2 0-3 1~2 1~3")
    assert train.carriers == (0, 0)
    row = train_row(train, "CERT", 7)
    assert row == ("CERT", "0-1 0-2 0-3 1~2 1~3", str(train.lever_analogue().code), 1, train.rotation_certificate, 7)
    assert row[2] == "42/0"
    planetary = GearTrain.parse("0-1-3-4 1-2 2~3 2~4")  # a planet 2 on carrier 1, meshing with sun 3 and ring 4
    assert planetary.carriers == (1, 1) and train_row(planetary, "X", 0)[3] == 1


@dataclass
class _Rows:
    """A unit's rows as the atlas run hands them (only the fields the trains module reads)."""

    cell: str
    chains: list = field(default_factory=list)
    link_counts: list = field(default_factory=list)
    mechanisms: list = field(default_factory=list)
    trains: list = field(default_factory=list)
    rotation: bool = True
    unit: str = "tree 0003"


def _db() -> sqlite3.Connection:
    conn = sqlite3.connect(":memory:")
    conn.executescript("""
        CREATE TABLE chains (id INTEGER PRIMARY KEY, certificate TEXT);
        CREATE TABLE link_counts (chain INTEGER, degree INTEGER, count INTEGER);
        CREATE TABLE trains (chain INTEGER PRIMARY KEY, train TEXT, lever_code TEXT, carriers INTEGER,
                             rotation TEXT, rank INTEGER);
        CREATE TABLE rotations (cell TEXT, rotation TEXT, chain INTEGER, rank INTEGER, PRIMARY KEY (cell, rotation));
        CREATE TABLE members (cell TEXT, chain INTEGER, PRIMARY KEY (cell, chain));
        CREATE TABLE mechanisms (chain INTEGER, frame INTEGER, input_link INTEGER);
    """)
    return conn


def _train(cert: str, rotation: str, rank: int) -> tuple:
    return (cert, f"train {cert}", "42/0", 1, rotation, rank)


def test_keep_representatives_keeps_lower_ranks_and_names_what_they_displace():
    conn = _db()
    conn.executemany("INSERT INTO rotations VALUES (?, ?, ?, ?)",
                     [("C", "r1", 7, 5), ("C", "r3", 8, 9), ("C", "r4", 9, 2), ("other", "r2", 10, 0)])
    rows = _Rows("C", chains=[("a", 1), ("b", 2), ("c", 3), ("d", 4)],
                 link_counts=[("a", 2, 4), ("c", 2, 4), ("b", 3, 1)],
                 mechanisms=[("d", 0, -1), ("a", 1, -1), ("b", 0, -1)],
                 trains=[_train("a", "r1", 3),   # lower than the stored 5: kept, displaces chain 7
                         _train("b", "r2", 10),  # r2 is held in another cell only: kept, displaces nothing
                         _train("c", "r3", 9),   # the same rank as the stored train: not kept
                         _train("d", "r4", 3)])  # higher than the stored 2: not kept
    kept, displaced = keep_representatives(conn, "C", rows)
    assert displaced == [7]
    assert kept.chains == [("a", 1), ("b", 2)]
    assert kept.link_counts == [("a", 2, 4), ("b", 3, 1)]
    assert kept.mechanisms == [("a", 1, -1), ("b", 0, -1)]
    assert kept.trains == [_train("a", "r1", 3), _train("b", "r2", 10)]
    assert (kept.cell, kept.unit, kept.rotation) == ("C", "tree 0003", True)
    assert rows.chains == [("a", 1), ("b", 2), ("c", 3), ("d", 4)]  # the unit's own rows are not changed
    # two displaced trains are both named, in the order of the unit's rows
    conn.execute("INSERT INTO rotations VALUES ('C', 'r5', 11, 40)")
    _, displaced = keep_representatives(conn, "C", _Rows("C", trains=[_train("e", "r5", 1), _train("f", "r1", 0)]))
    assert displaced == [11, 7]


def _table(conn, table: str) -> list:
    return sorted(conn.execute(f"SELECT * FROM {table}"))


def test_store_trains_writes_rows_and_drops_displaced_trains_no_other_cell_holds():
    conn = _db()
    conn.executemany("INSERT INTO chains VALUES (?, ?)", [(i, f"c{i}") for i in (1, 2, 3, 4)])
    conn.executemany("INSERT INTO members VALUES (?, ?)", [("C", 1), ("C", 2), ("D", 2), ("C", 3), ("C", 4)])
    conn.executemany("INSERT INTO trains VALUES (?, ?, ?, ?, ?, ?)",
                     [(1, "old 1", "42/0", 1, "r1", 5), (2, "old 2", "42/0", 1, "r2", 6)])
    conn.executemany("INSERT INTO link_counts VALUES (?, ?, ?)", [(1, 2, 4), (2, 2, 4)])
    conn.executemany("INSERT INTO mechanisms VALUES (?, ?, ?)", [(1, 0, -1), (2, 0, -1)])
    conn.executemany("INSERT INTO rotations VALUES (?, ?, ?, ?)", [("C", "r1", 1, 5), ("C", "r2", 2, 6)])
    rows = _Rows("C", trains=[_train("x", "r1", 3), _train("y", "r2", 4)])
    store_trains(conn, rows, {"x": 3, "y": 4}, [1, 2])
    # chain 1 was in cell C alone: gone with its rows; chain 2 is still in cell D: only its membership of C goes
    assert _table(conn, "chains") == [(2, "c2"), (3, "c3"), (4, "c4")]
    assert _table(conn, "members") == [("C", 3), ("C", 4), ("D", 2)]
    assert _table(conn, "trains") == [(2, "old 2", "42/0", 1, "r2", 6), (3, "train x", "42/0", 1, "r1", 3),
                                      (4, "train y", "42/0", 1, "r2", 4)]
    assert _table(conn, "link_counts") == [(2, 2, 4)]
    assert _table(conn, "mechanisms") == [(2, 0, -1)]
    assert _table(conn, "rotations") == [("C", "r1", 3, 3), ("C", "r2", 4, 4)]


def test_store_trains_of_a_displacement_cell_writes_only_trains_and_keeps_a_stored_row():
    conn = _db()
    conn.execute("INSERT INTO trains VALUES (5, 'first', '42/0', 1, 'r1', 0)")
    conn.execute("INSERT INTO members VALUES ('C', 5)")
    rows = _Rows("C", trains=[_train("p", "r1", 9), _train("q", "r2", 8)], rotation=False)
    store_trains(conn, rows, {"p": 5, "q": 6}, [5])
    assert _table(conn, "trains") == [(5, "first", "42/0", 1, "r1", 0), (6, "train q", "42/0", 1, "r2", 8)]
    assert _table(conn, "rotations") == [] and _table(conn, "members") == [("C", 5)]


def test_a_rotation_cell_run_in_reverse_keeps_the_representatives(tmp_path, monkeypatch):
    units_in_reverse(monkeypatch)
    db = tmp_path / "reversed.sqlite"
    run_grid(parse_grid('[[gears]]\nlinks = 6\ngraphs = "rotation"\n'), db, workers=1, progress=False)
    wanted = {t.to_chain().certificate for t in trains(1, 6, "rotation")}
    with sqlite3.connect(db) as conn:
        got = {c for (c,) in conn.execute("SELECT c.certificate FROM members m JOIN chains c ON c.id = m.chain")}
        ranks = dict(conn.execute("SELECT c.certificate, t.rank FROM trains t JOIN chains c ON c.id = t.chain"))
        assert conn.execute("SELECT COUNT(*) FROM chains").fetchone()[0] == 27
        assert conn.execute("SELECT COUNT(*) FROM rotations").fetchone()[0] == 27
    assert got == wanted
    # each stored rank is the least rank of its rotation graph over the whole cell, counted anew
    least = {}
    for unit in plan_gear_cell(GearCell(1, 6, "rotation")):
        for position, train in enumerate(tree_trains(1, 6, unit.axes)):
            key = train.rotation_certificate
            least[key] = min(least.get(key, 1 << 62), unit.tree * 2 ** 32 + position)
    assert sorted(ranks.values()) == sorted(least.values())
