"""Grid files key by key: the cells of each (W, n, h) worked out by hand from n = W + 1 + (h − 1)·K, every
cell key's parts, the query a cell stands for, gear cells, and every refusal's whole sentence."""

from __future__ import annotations

import pytest

from mechbase.schema import Table
from synth.atlas.grid import Cell, GearCell, GridFileError, _values, load_grid, parse_grid
from synth.structure.query import ChainQuery
from tests.refusals import refused


def _cells(text: str) -> list[tuple[int, int, int]]:
    return [(c.dof, c.links, c.h) for c in parse_grid(text).cells]


def test_the_cells_are_the_triples_with_a_whole_number_of_loops():
    # W = 1, n = 4..9, h = 2..4: K = (n − 2)/(h − 1) whole and ≥ 1
    #   h = 2: n = 3.. → 4, 5, 6, 7, 8, 9; h = 3: 4, 6, 8; h = 4: 5, 8
    expected = [(1, n, 2) for n in range(4, 10)] + [(1, n, 3) for n in (4, 6, 8)] + [(1, n, 4) for n in (5, 8)]
    assert _cells('dof = 1\nlinks = "4..9"\nh = "2..4"') == expected
    # given by loops: n = W + 1 + (h − 1)·K for K = 1, 2 and W = 0, 2 (sorted by h, W, n)
    assert _cells('dof = [2, 0]\nloops = "1..2"\nh = [5, 3]') == [
        (0, 3, 3), (0, 5, 3), (2, 5, 3), (2, 7, 3), (0, 5, 5), (0, 9, 5), (2, 7, 5), (2, 11, 5)]
    assert [c.loops for c in parse_grid('dof = [2, 0]\nloops = "1..2"\nh = [5, 3]').cells] == [1, 2, 1, 2, 1, 2, 1, 2]
    # h = 2: n = W + 2 is the smallest cell (K = 1); n = W + 1 would have no loop
    assert _cells('dof = 1\nlinks = "2..4"\nh = 2') == [(1, 3, 2), (1, 4, 2)]
    assert Cell(1, 8, (0, 0), h=4).loops == 2 and Cell(2, 11, (0, 0), h=5).loops == 2 and Cell(1, 10, (0, 0)).loops == 4


def test_open_chains_may_have_no_loop():
    # n1 = 0..2: K ≥ 0, so n = W + 1 is a cell (a serial arm of W + 1 links)
    assert _cells('dof = 2\nlinks = "3..5"\nn1 = "0..2"') == [(2, 3, 3), (2, 5, 3)]
    (cell, _) = parse_grid('dof = 2\nlinks = "3..5"\nn1 = "0..2"').cells
    assert cell.n1 == (0, 2) and cell.key == "W=2 n=3 v=0..0 rigid=0 frac=1 planar=0 n1=0..2"
    assert parse_grid('dof = 2\nlinks = 5\nn1 = "1.."').cells[0].key.endswith(" n1=1..")
    # without single-joint links K ≥ 1: n = W + 1 is no cell
    assert _cells('dof = 2\nlinks = "3..5"') == [(2, 5, 3)]
    with pytest.raises(GridFileError) as e:
        parse_grid("dof = 2\nlinks = 3", source="g.toml")
    assert str(e.value) == ("grid file g.toml: no (W, n, h) of the ranges gives a whole number of loops K ≥ 1 "
                            "(n = W + 1 + (h − 1)·K).")


def test_every_part_of_a_cell_key():
    text = ('dof = 1\nlinks = 6\nv = "1.."\nrigid_subchains = true\nfractionated = false\nplanar_only = true\n'
            'prismatic = "1..2"\nidle_joints = true\nrequire = ["3=1..", "4=0"]\n')
    (cell,) = parse_grid(text).cells
    assert cell.key == ("W=1 n=6 v=1.. rigid=1 frac=0 planar=1 p=1..2 idle=1 require=3=1..,4=0..0")
    assert (cell.v, cell.rigid_subchains, cell.fractionated, cell.planar_only, cell.prismatic, cell.idle_joints) == (
        (1, None), True, False, True, (1, 2), True)
    assert cell.require == ((3, (1, None)), (4, (0, 0)))
    assert Cell(1, 6, (0, 2), prismatic=(1, None)).key == "W=1 n=6 v=0..2 rigid=0 frac=1 planar=0 p=1.."
    assert Cell(1, 8, (0, 0), h=4).key == "W=1 n=8 v=0..0 rigid=0 frac=1 planar=0 h=4"
    assert Cell(1, 6, (0, 0), prismatic=(0, 1)).key.endswith(" p=0..1")  # not idle: no idle=…
    assert Cell(1, 5, (0, 0), n1=(1, 1)).key.endswith(" n1=1..1")


def test_a_cell_selects_what_its_key_says():
    cell = Cell(1, 6, (0, 1), rigid_subchains=True, fractionated=False, planar_only=True,
                require=((3, (1, None)),), h=3, n1=(0, 0), prismatic=(1, 2), idle_joints=True)
    assert cell.selection() == dict(v=(0, 1), rigid_subchains=True, fractionated=False, planar_only=True,
                                    require={3: (1, None)}, h=3, n1=(0, 0))
    query = cell.query()
    assert query == ChainQuery(1, 6, v=(0, 1), rigid_subchains=True, fractionated=False, planar_only=True,
                               require={3: (1, None)}, n1=(0, 0), prismatic=(1, 2), idle_joints=True)
    assert Cell(1, 6, (0, 0)).selection()["require"] is None
    plain = Cell(1, 6, (0, 0)).query()
    assert plain.prismatic is None and plain == ChainQuery(1, 6, v=(0, 0), rigid_subchains=False, n1=(0, 0))
    assert Cell(1, 5, (0, 0), h=4).query() == ChainQuery(1, 5, v=(0, 0), rigid_subchains=False, h=4, n1=(0, 0))


def test_defaults_of_the_conventions():
    (truss,) = parse_grid("dof = 0\nlinks = 5").cells
    (mechanism,) = parse_grid("dof = 1\nlinks = 4").cells
    assert truss.rigid_subchains and not mechanism.rigid_subchains
    assert mechanism.fractionated and not mechanism.planar_only and mechanism.v == (0, 0)
    assert mechanism.prismatic == (0, 0) and not mechanism.idle_joints and mechanism.h == 3 and mechanism.n1 == (0, 0)
    (kept,) = parse_grid("dof = 0\nlinks = 5\nrigid_subchains = false").cells
    assert not kept.rigid_subchains
    assert parse_grid("dof = 1\nlinks = 4\nrigid_subchains = true").cells[0].rigid_subchains


def test_a_block_given_loops_drops_the_top_levels_links_and_the_other_way_round():
    grid = parse_grid("dof = 1\nlinks = 4\n[[block]]\n[[block]]\nloops = 2\n")
    assert [(c.dof, c.links) for c in grid.cells] == [(1, 4), (1, 6)]
    grid = parse_grid('dof = 1\nloops = 1\n[[block]]\nlinks = 8\n')
    assert [(c.dof, c.links) for c in grid.cells] == [(1, 8)]


def test_a_list_of_values_is_sorted_and_a_range_is_closed():
    assert _cells("dof = 1\nlinks = [8, 4, 8, 6]") == [(1, 4, 3), (1, 6, 3), (1, 8, 3)]
    assert _cells('dof = "1..2"\nlinks = "4..5"') == [(1, 4, 3), (2, 5, 3)]
    assert _cells("dof = 1\nlinks = 40") == [(1, 40, 3)]  # the largest that is accepted


def test_the_grid_and_its_options():
    grid = parse_grid('name = "mine"\ndescription = "a test"\ninput_link = true\ndof = 1\nlinks = 4', source="x.toml")
    assert (grid.name, grid.description, grid.input_link, grid.source) == ("mine", "a test", True, "x.toml")
    plain = parse_grid("dof = 1\nlinks = 4")
    assert (plain.name, plain.description, plain.input_link, plain.source, plain.gear_cells) == (
        "grid", "", False, "<string>", ())
    assert parse_grid("dof = 1\nlinks = 4", default_name="other").name == "other"


def test_a_grid_file_is_named_after_its_stem(tmp_path):
    path = tmp_path / "grid_tiny.toml"
    path.write_text("dof = 1\nlinks = 4\n", encoding="utf-8")
    grid = load_grid(path)
    assert (grid.name, grid.source) == ("tiny", str(path))
    other = tmp_path / "mine.toml"
    other.write_text("dof = 1\nlinks = 4\n")
    assert load_grid(other).name == "mine"


def test_files_that_cannot_be_read_are_one_sentence(tmp_path):
    with pytest.raises(GridFileError) as e:
        load_grid(tmp_path / "none.toml")
    assert str(e.value) == f"grid file {tmp_path / 'none.toml'} does not exist."
    binary = tmp_path / "b.toml"
    binary.write_bytes(b"dof = 1\n\xff\xfe")
    with pytest.raises(GridFileError) as e:
        load_grid(binary)
    assert str(e.value) == f"grid file {binary} is not a text file (byte 8 is not UTF-8); a grid is a TOML file."
    with pytest.raises(GridFileError) as e:
        load_grid(tmp_path)
    assert str(e.value) == f"cannot read grid file {tmp_path}: Is a directory."


def test_gear_cells():
    grid = parse_grid('[[gears]]\ndof = "1..2"\nlinks = [6, 4]\ngraphs = "rotation"\n[[gears]]\nlinks = 4\n'
                      '[[gears]]\nlinks = 4\ngraphs = "rotation"\n')
    assert not grid.cells
    assert [(c.dof, c.links, c.graphs) for c in grid.gear_cells] == [
        (1, 4, "rotation"), (1, 6, "rotation"), (2, 4, "rotation"), (2, 6, "rotation"), (1, 4, "displacement")]
    assert GearCell(2, 6).key == "gears F=2 n=6 graphs=displacement"
    # top-level chain keys make chain cells beside the gear cells
    grid = parse_grid('dof = 1\nlinks = 4\n[[gears]]\nlinks = 12\n')
    assert [c.key for c in grid.cells] == ["W=1 n=4 v=0..0 rigid=0 frac=1 planar=0"]
    assert [c.key for c in grid.gear_cells] == ["gears F=1 n=12 graphs=displacement"]


@pytest.mark.parametrize("text, sentence", [
    ('[[gears]]\ndof = 2\nlinks = "3..5"', "[[gears]] 1 key 'links': a gear train with F = 2 needs at least 4 links "
                                          "(one mesh), not 3."),
    ('[[gears]]\nlinks = 4\n[[gears]]\nlinks = 13', "[[gears]] 2 key 'links': gear trains are enumerated up to 12 "
                                                   "links, not 13."),
    ('[[gears]]\nlinks = 4\ngraphs = "other"', "[[gears]] 1 key 'graphs' must be \"displacement\" or \"rotation\", "
                                               "not 'other'."),
    ('[[gears]]\ndof = 0\nlinks = 5', "[[gears]] 1 key 'dof' must be at least 1, not 0."),
    ('[[gears]]\nlinks = 1', "[[gears]] 1 key 'links' must be at least 2, not 1."),
    ("links = 4", "key 'dof' (W) is missing."),
    ("dof = 1\nlinks = 4\nloops = 1", "needs exactly one of 'links' (n) and 'loops' (K)."),
    ("dof = 1", "needs exactly one of 'links' (n) and 'loops' (K)."),
    ("dof = 1\nlinks = 8\nh = 7", "key 'h': the motion space of a loop is 2 … 6, not 7."),
    ("dof = 1\nlinks = 8\nh = [3, 9, 4]", "key 'h': the motion space of a loop is 2 … 6, not 9."),
    ("dof = 1\nlinks = 8\nh = 1", "key 'h' must be at least 2, not 1."),
    ("dof = 1\nlinks = 0", "key 'links' must be at least 1, not 0."),
    ('dof = 1\nlinks = "4..42"', "42 links is beyond what a grid run can finish (at most 40)."),
    ("dof = 1\nloops = 20", "42 links is beyond what a grid run can finish (at most 40)."),
    ("dof = 1\nlinks = 6\nprismatic = 1\nh = [3, 5]", "key 'prismatic': prismatic pairs are assigned in planar "
                                                       "chains (h = 3) only."),
    ("dof = 1\nlinks = 6\nidle_joints = true", "key 'idle_joints' goes with 'prismatic' (an all-revolute chain has "
                                               "no idle joint)."),
    ('dof = 1\nlinks = 6\nrequire = ["0=1"]', "key 'require': a link carries at least one joint; requirement on "
                                              "n0 is impossible."),
    ('dof = 1\n[[block]]\nlinks = 6\n[[block]]\nlinks = 5', "[[block]] 2 no (W, n, h) of the ranges gives a whole "
                                                           "number of loops K ≥ 1 (n = W + 1 + (h − 1)·K)."),
    ('dof = 1\nlinks = "4.."', "key 'links' is the range '4..' with no upper end"),
])
def test_every_refusal_is_its_sentence(text, sentence):
    assert refused(GridFileError, parse_grid, text, source="g.toml").startswith("grid file g.toml: " + sentence)


def test_the_value_type_of_the_keys_reads_numbers_ranges_and_lists():
    """The type a grid key's value takes (built once, when the module is imported), built here anew."""

    class Keys(Table):
        count: _values(2)

    def read(value):
        return Keys.read({"count": value}, source="f", where="", error=GridFileError).count

    assert read([5, 2, 5, 3]) == [2, 3, 5] and read("2..4") == [2, 3, 4] and read(7) == [7]
    for value, sentence in (([], "key 'count' must be a whole number, a range \"A..B\" or a list of whole numbers, "
                                 "not []."),
                            ([1, 4], "key 'count' must be at least 2, not [1, 4]."),
                            ("3..", "key 'count' is the range '3..' with no upper end.")):
        with pytest.raises(GridFileError) as e:
            read(value)
        assert str(e.value) == "f: " + sentence
