"""Scene computations for joint kinds and gear trains: ``prismatic`` and ``planetary``.

``[prismatic]`` names a chain (joint list) and a number of prismatic pairs; ``prismatic``
lists its R/P variants up to symmetry.  ``[planetary]`` names the satellites and the sun;
``planetary`` gives the lever analogue's code, W, K, D, verdict and Assur groups.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pydantic import StrictStr

from mechbase import Row
from mechbase.schema import Table

from .registry import ComputeKind, Expectation, Run, SceneTable, Family
from .types import Count, Flag, Int, RangeText, Text, Texts, Whole, WholeTable

__all__ = ["Prismatic", "Planetary", "Variants", "PlanetaryLever"]


class Prismatic(Table):
    """The ``[prismatic]`` table: a chain and how many of its revolute pairs become prismatic."""

    chain: StrictStr
    pairs: RangeText
    idle_joints: Flag = False


class Planetary(Table):
    """The ``[planetary]`` table: a planetary train's satellites and sun."""

    satellites: Count
    sun: Text = "floating"


FAMILY = Family("gears")  # its tables and computations, registered by mechsynth.scene


FAMILY.table(SceneTable.typed("prismatic", Prismatic, "the chain and the number of P pairs"))
FAMILY.table(SceneTable.typed("planetary", Planetary, "the satellites and the sun"))


@dataclass(frozen=True)
class Variants(Row):
    """``prismatic``: the R/P variants of the chain, how many by W, and those whose every P pair is a cylinder."""

    count: int
    by_dof: dict[str, int]
    all_cylinders: int
    variants: tuple[Any, ...]


@dataclass(frozen=True)
class PlanetaryLever(Row):
    """``planetary``: the train's row and the names of its Assur groups."""

    train: Any
    row_keys = ("*train", "assur_group_names")

    @property
    def assur_group_names(self) -> list[str]:
        return [g.name for g in self.train.assur_groups]


def _prismatic(run: Run) -> Variants:
    from synth import Chain, parse_range, variants_of
    from synth import JointKind

    t = run.scene.tables["prismatic"]
    chain = Chain.parse(t.chain)
    variants = tuple(variants_of([chain], parse_range(t.pairs, "pairs"), idle=t.idle_joints))
    by_dof: dict[str, int] = {}
    for c in variants:
        by_dof[str(c.dof)] = by_dof.get(str(c.dof), 0) + 1
    # a cylinder: a prismatic pair between two binary links (the barrel and its rod)
    actuated = sum(1 for c in variants if not c.all_revolute and all(
        c.degrees[j[0]] == c.degrees[j[1]] == 2 for j, k in zip(c.joints, c.kinds) if k == JointKind.PRISMATIC))
    return Variants(len(variants), by_dof, actuated, variants)


def _planetary(run: Run) -> PlanetaryLever:
    from synth import planetary_row

    t = run.scene.tables["planetary"]
    return PlanetaryLever(planetary_row(t.satellites, t.sun))


FAMILY.kind(ComputeKind(
    "prismatic", "R/P variants of a chain up to symmetry (wedge rule, idle joints left out)", "prismatic",
    _prismatic, expect={"variants": Expectation(Whole, ("count",)), "variants_by_dof": Expectation(WholeTable, ("by_dof",)),
                              "variants_all_cylinders": Expectation(Whole, ("all_cylinders",))},
    report=lambda r: [f"{r['count']} variants, by W: {r['by_dof']}; every P pair a cylinder: {r['all_cylinders']}"]))
FAMILY.kind(ComputeKind(
    "planetary", "a planetary train's lever analogue: code, W, K, D, verdict, Assur groups", "planetary",
    _planetary, expect={"train_code": Expectation(Text, ("code",)), "train_dof": Expectation(Int, ("dof",)),
                        "train_loops": Expectation(Whole, ("loops",)), "train_defect": Expectation(Int, ("defect",)),
                        "determinate": Expectation(Flag),
                        "assur_groups": Expectation(Texts, ("assur_group_names",))},
    report=lambda r: [f"{r['code']}: W = {r['dof']}, K = {r['loops']}, D = {r['defect']}, "
                      f"sub-chains {r['subchains']}, Assur groups {' '.join(r['assur_group_names']) or '-'}"]))
