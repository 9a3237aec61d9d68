"""Typed results print the rows the hand-written dicts printed: fields in the same order, tuples as
lists, nested results as dicts (mechbase.Row), and they cannot be changed once made."""

import dataclasses
import json

import pytest

from mechbase import Row, as_row
from synth import Chain, Code, chain_repairs, code_repairs
from synth.gears import count_trains, planetary_row


def test_a_chain_repair_is_the_row_it_was():
    (r,) = chain_repairs(Chain.parse("0-1 1-2 2-0 0-3 3-4 4-5 5-1"), limit=1)
    assert list(r.to_dict()) == ["edits", "code", "chain", "dof"]
    assert r.to_dict() == {"edits": list(r.edits), "code": r.code, "chain": r.chain, "dof": r.dof}
    assert Chain.parse(r.chain).dof == r.dof == 1 and isinstance(r.edits, tuple)


def test_a_code_repair_has_no_dof():
    r = code_repairs(Code.parse("6301/0"), 2, limit=1)[0]
    assert list(r.to_dict()) == ["edits", "code", "chain"] and Code.parse(r.code).dof() == 2


def test_a_planetary_row_prints_its_groups_as_rows():
    row = planetary_row(3)
    out = json.loads(json.dumps(row.to_dict()))
    assert list(out)[:4] == ["satellites", "sun", "code", "links"] and list(out)[-1] == "assur_groups"
    assert out["assur_groups"][3] == {"name": "triad", "links": [2, 9, 10, 11],
                                      "outer_joints": [[3, 9], [4, 10], [5, 11]]}
    assert out["joints"] == [list(j) for j in row.joints] and out["redundant_joints"] is None


def test_counts_of_gear_trains_are_typed_and_read_as_before():
    counts = count_trains(1, 5)
    assert counts["count"] == counts.count == sum(counts.by_code.values()) == 13
    assert json.dumps(counts.to_dict()) == json.dumps({"count": 13, "by_code": dict(counts.by_code)})


def test_results_are_frozen():
    row = planetary_row(1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        row.dof = 2


def test_as_row_converts_nested_values_and_leaves_the_rest():
    @dataclasses.dataclass(frozen=True)
    class Inner(Row):
        pair: tuple[int, int]

    @dataclasses.dataclass(frozen=True)
    class Outer(Row):
        inner: Inner
        table: dict
        text: str

    value = Outer(Inner((1, 2)), {"a": (Inner((3, 4)),)}, "x")
    assert value.to_dict() == {"inner": {"pair": [1, 2]}, "table": {"a": [{"pair": [3, 4]}]}, "text": "x"}
    assert as_row(Outer) is Outer  # a class is no value
