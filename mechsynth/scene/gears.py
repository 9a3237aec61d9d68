"""Scene computations for joint kinds and gear trains: ``prismatic`` and ``planetary``.

``[prismatic]`` names a chain (joint list) and a number of prismatic pairs; ``prismatic``
lists its R/P variants up to symmetry.  ``[planetary]`` names the satellites and the sun;
``planetary`` gives the lever analogue's code, W, K, D, verdict and Assur groups.
"""

from __future__ import annotations

from pydantic import StrictStr

from mechbase.schema import Table

from .registry import ComputeKind, Expectation, Run, SceneTable, Family
from .results import SceneError
from .types import Count, Flag, Int, RangeText, Text, Texts, Whole, WholeTable

__all__ = ["Prismatic", "Planetary"]


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


FAMILY.table(SceneTable("prismatic", lambda raw, path, compute: Prismatic.read(
    raw, source=path, where="[prismatic]", error=SceneError), "the chain and the number of P pairs"))
FAMILY.table(SceneTable("planetary", lambda raw, path, compute: Planetary.read(
    raw, source=path, where="[planetary]", error=SceneError), "the satellites and the sun"))


def _prismatic(run: Run) -> dict:
    from synth import Chain, parse_range, variants_of
    from synth import JointKind

    t = run.scene.tables["prismatic"]
    chain = Chain.parse(t.chain)
    variants = list(variants_of([chain], parse_range(t.pairs, "pairs"), idle=t.idle_joints))
    rows = [c.to_dict() for c in variants]
    by_dof: dict[str, int] = {}
    for r in rows:
        by_dof[str(r["dof"])] = by_dof.get(str(r["dof"]), 0) + 1
    # a cylinder: a prismatic pair between two binary links (the barrel and its rod)
    actuated = sum(1 for c in variants if not c.all_revolute and all(
        c.degrees[j[0]] == c.degrees[j[1]] == 2 for j, k in zip(c.joints, c.kinds) if k == JointKind.PRISMATIC))
    return {"count": len(rows), "by_dof": by_dof, "all_cylinders": actuated, "variants": rows}


def _planetary(run: Run) -> dict:
    from synth import planetary_row

    t = run.scene.tables["planetary"]
    row = planetary_row(t.satellites, t.sun).to_dict()
    row["assur_group_names"] = [g["name"] for g in row["assur_groups"]]
    return row


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
