"""Scene computations for gear trains: ``gear train`` (one train: W, K, D, the sub-chain verdict and
the lever analogue's code from the general analysis of the train as a chain with gear meshes,
speed ratios, tooth design, schematic) and ``gear atlas`` (the counts of a size).

``[gear_train]`` names a train in the text form of ``mechsynth gears --train`` and, optionally,
mechanisms as ``[frame, input, output]`` triples, tooth numbers, and a ratio to design teeth for.
``[gear_atlas]`` names F and n, and optionally a train that must be found among them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Annotated, Any

from pydantic import Field, StrictInt, StrictStr

from mechbase import Row
from mechbase.schema import Table

from .registry import ComputeKind, Expectation, Run, SceneTable, Family
from .results import SceneError
from .types import Count, Flag, Int, Number, Numbers, Text, Texts, Whole, WholeTable

__all__ = ["GearTrainTable", "GearAtlasTable", "TrainAnalysis", "GearCensus"]

Triples = Annotated[list[Annotated[list[Annotated[StrictInt, Field(ge=0)]], Field(min_length=3, max_length=3)]],
                    Field(min_length=1)]


class GearTrainTable(Table):
    """The ``[gear_train]`` table."""

    train: StrictStr
    required_dof: Count = 1  # the W that D is measured against
    mechanisms: Triples | None = None  # [frame, input, output] each
    compound: list[Whole] = []
    teeth: WholeTable | None = None
    ratio: Text | None = None  # design tooth numbers for the first mechanism
    tolerance: Text = "1%"
    teeth_range: Text = "17..150"
    planets: Count | None = None
    best: Count = 3
    drawing: Flag = False


class GearAtlasTable(Table):
    """The ``[gear_atlas]`` table."""

    dof: Count = 1
    links: Count
    contains: StrictStr | None = None  # a train (text form) that must be in the atlas


FAMILY = Family("gear_trains")  # its tables and computations, registered by mechsynth.scene


FAMILY.table(SceneTable.typed("gear_train", GearTrainTable, "the train (and its mechanisms, teeth, ratio)"))
FAMILY.table(SceneTable.typed("gear_atlas", GearAtlasTable, "the DOF and the number of links"))


@dataclass(frozen=True)
class TrainAnalysis(Row):
    """``gear train``: the train's W, K, D and verdict as a chain, its lever analogue, the speed ratios of
    its mechanisms and, when asked, the tooth designs and the schematic written."""

    train: str
    dof: int
    generic_dof: int
    loops: int
    defect: int
    subchains: str
    redundant_joints: tuple
    lever_code: str
    lever_dof: int
    rigid_free: bool
    fractionated: bool
    certificate: str
    ratio_formulas: tuple[str, ...] = ()
    ratio_values: tuple[float, ...] = ()
    designs: tuple[Any, ...] | None = None
    files: tuple[str, ...] | None = None
    row_keys = ("train", "dof", "generic_dof", "loops", "defect", "subchains", "redundant_joints", "lever_code",
                "lever_dof", "rigid_free", "fractionated", "certificate", "ratio_formulas", "ratio_values",
                "designs?", "best_error?", "best_ratio?", "files?")

    @property
    def best_error(self) -> float | None:
        return float(self.designs[0].error) if self.designs else None

    @property
    def best_ratio(self) -> float | None:
        return float(self.designs[0].ratio) if self.designs else None


@dataclass(frozen=True)
class GearCensus(Row):
    """``gear atlas``: the displacement and rotation graphs of F DOF and n links, and whether a train is among them."""

    displacement: int
    rotation: int
    contains: bool | None = None
    row_keys = ("displacement", "rotation", "contains?")


def _gear_train(run: Run) -> TrainAnalysis:
    from synth import analyze_chain, parse_range
    from synth.gears import GearTrain, design, speed_ratio

    t = run.scene.tables["gear_train"]
    first = t.mechanisms[0] if t.mechanisms else None
    train = GearTrain.parse(t.train, first[0] if first else None)
    a = analyze_chain(train.to_chain(), dof=t.required_dof)  # the general path: the train as a chain
    formulas, values = [], []
    for frame, i, o in t.mechanisms or ():
        formula = speed_ratio(train, frame, i, o, t.compound)
        formulas.append(formula.text)
        if t.teeth:
            values.append(float(formula.evaluate(t.teeth)))
    out = TrainAnalysis(train.compact(), a.dof_count, a.dof, a.loops, a.defect, a.subchain_defect,
                        tuple(a.redundant_joints or ()), a.lever_analogue, train.lever_analogue().dof,
                        train.is_rigid_free(), train.is_fractionated(), train.certificate, tuple(formulas), tuple(values))
    if t.ratio is not None:
        if first is None:
            raise SceneError(f"{run.scene.path}: [gear_train] ratio needs mechanisms = [[frame, input, output]].")
        lo, hi = parse_range(t.teeth_range, "teeth_range")
        out = replace(out, designs=tuple(design(train, *first, t.ratio, tolerance=t.tolerance, teeth=(lo, hi),
                                                 planets=t.planets, compound=t.compound, best=t.best)))
    if t.drawing:
        picture = run.picture(f"{run.scene.name}.svg")
        if picture is not None:
            from synth.draw import draw_train

            best = (out.designs[0].teeth if out.designs else None) or t.teeth
            draw_train(train, picture, teeth=best, compound=t.compound)
            out = replace(out, files=(str(picture),))
    return out


def _gear_atlas(run: Run) -> GearCensus:
    from synth.gears import GearTrain, census, trains

    t = run.scene.tables["gear_atlas"]
    found = census(t.dof, t.links)
    contains = None
    if t.contains is not None:
        wanted = GearTrain.parse(t.contains)
        plain = GearTrain(wanted.links, wanted.axes, wanted.meshes, wanted.carriers)  # mesh kinds aside
        contains = any(x.certificate == plain.certificate for x in trains(t.dof, t.links))
    return GearCensus(found["displacement"], found["rotation"], contains)


FAMILY.kind(ComputeKind(
    "gear train", "one gear train: W, K, D and verdict of its lever analogue, speed ratios, tooth design",
    "gear_train", _gear_train,
    expect={"train_dof": Expectation(Int, ("dof",)), "train_loops": Expectation(Whole, ("loops",)),
            "train_defect": Expectation(Int, ("defect",)), "subchains": Expectation(Text),
            "lever_code": Expectation(Text),
            "lever_dof": Expectation(Int), "rigid_free": Expectation(Flag), "fractionated": Expectation(Flag),
            "ratio_formulas": Expectation(Texts), "ratio_values": Expectation(Numbers),
            "best_ratio": Expectation(Number), "best_error": Expectation(Number, below=True)},
    report=lambda r: [f"{r['train']}: W = {r['dof']}, K = {r['loops']}, D = {r['defect']}, lever analogue "
                      f"{r['lever_code']}, sub-chains {r['subchains']}; ratios {', '.join(r['ratio_formulas']) or '-'}"]))
FAMILY.kind(ComputeKind(
    "gear atlas", "every planetary gear train of F DOF and n links: displacement and rotation graphs", "gear_atlas",
    _gear_atlas, expect={"displacement_graphs": Expectation(Whole, ("displacement",)),
                         "rotation_graphs": Expectation(Whole, ("rotation",)), "contains": Expectation(Flag)},
    report=lambda r: [f"{r['displacement']} displacement graphs, {r['rotation']} rotation graphs"]))
