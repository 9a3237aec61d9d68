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


# ------------------------------------------------------------------ rows that are not just the fields
@dataclasses.dataclass(frozen=True)
class _Spring(Row):
    rate: float
    note: str | None = None
    row_keys = ("rate", "per_mm=rate_per_mm", "note?")

    @property
    def rate_per_mm(self):
        return self.rate / 1000


@dataclasses.dataclass(frozen=True)
class _Design(Row):
    spring: _Spring | None
    available: bool = True

    @property
    def row_keys(self):
        return ("*spring?", "available") if self.available else ("available",)


def test_row_keys_rename_derive_and_leave_out_none():
    assert _Spring(2000.0).to_dict() == {"rate": 2000.0, "per_mm": 2.0}
    assert list(_Spring(2000.0, "wound").to_dict()) == ["rate", "per_mm", "note"]


def test_a_spread_row_puts_its_keys_in_place_and_row_keys_may_depend_on_the_result():
    assert _Design(_Spring(1000.0, "x")).to_dict() == {"rate": 1000.0, "per_mm": 1.0, "note": "x", "available": True}
    assert _Design(None).to_dict() == {"available": True}
    assert _Design(_Spring(1.0), available=False).to_dict() == {"available": False}


def test_a_value_with_a_row_of_its_own_is_printed_as_that_row():
    train = __import__("synth.gears", fromlist=["GearTrain"]).GearTrain.parse("0-1-2 2-3 0~3i 1~3")

    @dataclasses.dataclass(frozen=True)
    class Holder(Row):
        train: object

    assert Holder(train).to_dict() == {"train": train.to_dict()}


def test_balance_rows_are_typed_and_print_what_they_held():
    from balance.devices.counterweights import Counterweights
    from balance.devices.transmission import GearElement
    from balance.problems.arm import DeviceSizes, TermDevices

    assert Counterweights(False, "the arm has no links").to_dict() == {"available": False,
                                                                      "reason": "the arm has no links"}
    assert GearElement("differential", "s", carrier="a", side="b").to_dict() == {
        "element": "differential", "carrier": "a", "side": "b", "output": "s", "ratio": None, "reverses": False}
    assert GearElement("spur stage", "s", "q1", -2.0).to_dict() == {
        "element": "spur stage", "input": "q1", "output": "s", "ratio": -2.0, "reverses": True}
    term = TermDevices(0, "ψ1", 6.0, 0.0, DeviceSizes(eccentricity=0.05, r=0.1, r0=0.5)).to_dict()
    assert term["sine"] == {"eT": 6.0, "e": 0.05, "T": pytest.approx(120.0)}
    assert term["tension"]["c"] == pytest.approx(100.0) and term["tension"]["a"] == 0.5
    assert list(term["tension"]) == ["crd", "zero_at_deg", "spring_fit", "r", "r0", "a", "c"]
    assert "e" not in TermDevices(0, "ψ1", 6.0, 0.0).to_dict()["sine"]


#: the types that keep a to_dict of their own: exchange formats read back by from_dict
OWN_TO_DICT = {"Chain", "Mechanism", "Code", "ChainQuery", "GearTrain", "Linkage", "Row"}
#: not yet typed: dimensional synthesis and the curve index (synth/dimension, synth/atlas/curves.py), reworked
#: on another branch at the time this test was written
NOT_YET = {"synth/atlas/curves.py:IndexResult", "synth/dimension/_search.py:DimensionalResult"}


def test_no_result_builds_its_row_by_hand():
    """Every class of balance, mechbase, the scene runner and synth (but the exchange formats above) that
    has a row gets it from mechbase.Row: none defines to_dict."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    own = []
    for folder in ("balance", "mechbase", "mechsynth", "synth"):
        for path in (root / folder).rglob("*.py"):
            for node in ast.walk(ast.parse(path.read_text())):
                if isinstance(node, ast.ClassDef) and node.name not in OWN_TO_DICT and any(
                        isinstance(f, ast.FunctionDef) and f.name == "to_dict" for f in node.body):
                    own.append(f"{path.relative_to(root)}:{node.name}")
    assert sorted(set(own) - NOT_YET) == []


def test_gear_rows_extend_the_trains_row_and_show_only_what_was_chosen():
    from synth.gears import GearTrain, design
    from synth.gears.ratios import mechanisms

    train = GearTrain.parse("0-1-2 2-3 0~3i 1~3")
    plain = mechanisms(train)[0].to_dict()
    assert list(plain)[:len(train.to_dict())] == list(train.to_dict()) and plain["frame"] == 0
    assert "input_link" not in plain and "ratio" not in plain
    driven = mechanisms(train, input_output=True)[0].to_dict()
    assert (driven["input_link"], driven["output_link"], driven["ratio"]) == (1, 2, "(z0 + z1)/z1")
    best = design(train, 0, 1, 2, "4", tolerance="0", teeth=(17, 80), best=1)[0]
    assert best.to_dict() == {"teeth": dict(best.teeth), "ratio": "4", "ratio_value": 4.0, "error": 0.0}
