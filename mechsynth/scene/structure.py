"""Structural computations of a scene: ``codes``, ``count``, ``chains``, ``mechanisms``, ``analysis``, ``drawing``.

They read the ``[structure]`` table (:class:`Structure`) and, for the drawing,
``[drawing]``.  Each imports only what it needs, when it runs: codes build the CP-SAT
counting model and never the graph realisation, the analysis of a code is pure
arithmetic.

To add a ``[structure]`` key, add one field to :class:`Structure` with :func:`key`,
naming the computations that use it; a scene that gives the key to no such
computation is refused.

>>> Structure.model_fields["dof"].json_schema_extra["used_by"]
['analysis', 'chains', 'codes', 'count', 'drawing', 'mechanisms']
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, StrictInt, StrictStr, ValidationInfo, model_validator

from mechbase import Row
from mechbase.schema import FileName, Table, expect, refine

from . import compare
from .registry import ComputeKind, Expectation, Run, SceneTable, Family
from .results import Scene
from .types import (Count, Flag, Int, IndexTable, RangeText, Require, Text, Whole, WholeTable, Wholes)

__all__ = ["Structure", "Drawing", "CODES", "CHAINS", "ANALYSIS", "CodeList", "ChainCount", "ListedChain",
           "ChainListing", "MechanismCount", "CodeAnalysis", "Sheet"]

CODES = ("codes",)
CHAINS = ("count", "chains", "mechanisms", "drawing")
ANALYSIS = ("analysis",)


# --------------------------------------------------------------------------- value types
def _standard_code(text: str) -> str:
    from synth import Code
    from synth import MalformedCode

    try:
        Code.parse(text)
    except MalformedCode as exc:
        raise ValueError(f"holds {text!r}, which is not a standard code ({str(exc).rstrip('.')})") from None
    return text


def _canonical(texts) -> list[str]:
    from synth import Code

    return [str(Code.parse(t)) for t in texts]


CodeText = Annotated[StrictStr, refine(_standard_code), expect('a standard code such as "6301/0"')]
Codes = Annotated[list[CodeText], expect('a list of standard codes such as ["6301/0"]')]
CodeTable = Annotated[dict[Annotated[str, refine(_standard_code)], Whole],
                      expect('a table of counts by code such as { "6301/0" = 15 }')]


def _pair(value):
    return tuple(value) if isinstance(value, list) else value


#: v: one count, a range, or a pair [A, B].
VRange = Annotated[RangeText | Annotated[list[Annotated[StrictInt, Field(ge=0)]], Field(min_length=2, max_length=2)],
                   refine(_pair), expect('a whole number, a range "A..B" or a pair [A, B]')]
Degree = Annotated[Annotated[StrictInt, Field(ge=2)] | Annotated[StrictStr, Field(pattern=r"(?i)^\s*K\s*\+\s*[1W]\s*$")],
                   refine(lambda x: x if isinstance(x, int) else x.replace(" ", "").upper()),
                   expect('a whole number ≥ 2, "K+1" or "K+W"')]


def key(meaning: str, *used_by: str, default: Any = None) -> Any:
    """A ``[structure]`` field: what it means and the computations that use it."""
    return Field(default, description=meaning, json_schema_extra={"used_by": sorted(used_by)})


# --------------------------------------------------------------------------- tables
class Structure(Table):
    """The ``[structure]`` table of a structural scene (every key optional unless a computation needs it)."""

    dof: Whole | None = key("the required mobility W", *CODES, *CHAINS, *ANALYSIS)
    loops: RangeText | None = key("K, independent loops", *CODES, *CHAINS)
    links: RangeText | None = key("n, links with the frame", *CODES, *CHAINS)
    loop_classes: IndexTable("a table of loop classes { H = K_H, … } with whole numbers") | None = key(
        "K_h of a heterogeneous system (chains: a base of the higher class on a chain of the lower)",
        *CODES, *ANALYSIS, *CHAINS)
    h: Count = key("motion space of a loop", *CODES, *ANALYSIS, *CHAINS, default=3)
    f: Whole = key("extra mobility of multi-DOF pairs", *CODES, *ANALYSIS, *CHAINS, default=0)
    v: VRange | None = key("multiple-joint count", *CODES, *CHAINS, *ANALYSIS)
    n1: RangeText | None = key("single-joint links (open chains)", *CODES, *CHAINS)
    max_link_degree: Degree | None = key("largest joints on one link", *CODES)
    max_multiplicity: Count | None = key("largest links on one joint", *CODES, *CHAINS)
    compositions: Flag = key("split v into v2-v3-…", *CODES, default=False)
    require: Require | None = key("design constraints on n_I", *CODES, *CHAINS)
    cranks: IndexTable("a table { I = C, … }: a link with I joints carrying at least C cranks", 1) | None = key(
        "required sub-structure: a link with I joints carrying C cranks", *CHAINS)
    rigid_subchains: Flag | None = key("allow rigid sub-chains", *CHAINS)
    fractionated: Flag = key("keep fractionated chains", *CHAINS, default=True)
    planar_only: Flag = key("keep planar graphs only", *CHAINS, default=False)
    prismatic: RangeText | None = key("chains with A…B prismatic pairs (W counts their wedge loops)", *CHAINS)
    idle_joints: Flag = key("with prismatic: keep chains with joints that never move", *CHAINS, default=False)
    cylinders: Text | None = key("with prismatic: the mechanisms' prismatic pairs by kind, e.g. "
                                 "'floating=1,swinging=2'", "mechanisms", "drawing")
    input_link: Flag = key("mark an input link too", "mechanisms", "drawing", default=False)
    code: CodeText | None = key("one standard code", *ANALYSIS, *CHAINS)
    counts: IndexTable("a table of link counts { I = n_I, … } with whole numbers") | None = key(
        "explicit link counts { 1 = n1, 2 = n2, … }", *ANALYSIS)
    chain: Text | None = key("a chain as a joint list '0-1 1-2 …' (chains: with loop_classes, every base on it)",
                             *ANALYSIS, *CHAINS)

    @model_validator(mode="after")
    def _every_key_used(self, info: ValidationInfo):
        compute = set((info.context or {}).get("compute", ()))
        for name in sorted(self.given(), key=list(type(self).model_fields).index):
            field = type(self).model_fields[name]
            used_by = field.json_schema_extra["used_by"]
            if not compute & set(used_by):
                mine = sorted(compute & {*CODES, *CHAINS, *ANALYSIS})
                raise ValueError(f"key '{name}' ({field.description}) is not used by compute {mine}; "
                                 f"remove it or add one of {used_by}")
        return self


class Drawing(Table):
    """The ``[drawing]`` table: the atlas sheet of a ``drawing`` computation."""

    out: FileName | None = None
    mechanisms: Flag = False
    columns: Count | None = None
    title: Text | None = None
    labels: Flag | None = None  # default: numbered on sheets of mechanisms (their captions name links)
    limit: Count = 200


FAMILY = Family("structure")  # its tables and computations, registered by mechsynth.scene


FAMILY.table(SceneTable.typed("structure", Structure, "dof and loops, links, a code, counts or a chain"))
FAMILY.table(SceneTable.typed("drawing", Drawing, "the sheet's options"))


# --------------------------------------------------------------------------- checks
def _needs_dof(scene: Scene, s: Structure, what: str) -> None:
    if s.dof is None:
        raise scene.error(f"[structure] needs the key 'dof' (the required mobility W, a whole number ≥ 0) for {what}")


def _check_codes(scene: Scene) -> None:
    s = scene.tables["structure"]
    _refuse_unused(scene, s)
    _needs_dof(scene, s, "the codes")
    if sum(x is not None for x in (s.loops, s.links, s.loop_classes)) != 1:
        raise scene.error("[structure] needs exactly one of 'loops', 'links' or 'loop_classes' for the codes")


#: each structural computation, as a refusal names it
_WORDS = {"codes": "the codes", "count": "the count of chains", "chains": "chains", "mechanisms": "mechanisms",
          "drawing": "drawings", "analysis": "the analysis"}


def _named(computes) -> str:
    """Structural computations in words, in the order of :data:`_WORDS`.

    >>> _named(["drawing", "count"])
    'the count of chains and drawings'
    """
    words = [_WORDS[c] for c in _WORDS if c in computes]
    return " and ".join([", ".join(words[:-1]), words[-1]] if len(words) > 1 else words)


def _asked(scene: Scene) -> str:
    """The computations listing chains that the scene asks for, in words: a refusal names those, not the others.

    >>> _asked(Scene("t.toml", "t", "", ("count", "drawing"), {}, {}))
    'the count of chains and drawings'
    """
    return _named([c for c in CHAINS if c in scene.compute])


def _check_chains(scene: Scene) -> None:
    s = scene.tables["structure"]
    _refuse_unused(scene, s)
    given = s.chain is not None and s.loop_classes is None  # one chain given by hand: its W is its count's
    asked = _asked(scene)
    if not given:
        _needs_dof(scene, s, asked)
    if s.input_link and s.dof == 0 and not given:  # as 'mechanisms --input-link' refuses it: the chains are trusses
        from synth import truss_has_no_input

        raise scene.error(str(truss_has_no_input("the chains of [structure] have", "the key 'input_link'")))
    if s.f != 0:
        raise scene.error(f"[structure] key 'f' must be 0 for {asked} "
                          "(type synthesis builds chains with one-DOF pairs)")
    if not 2 <= s.h <= 6:
        raise scene.error(f"[structure] key 'h' must be 2 … 6 for {asked}, not {s.h}")
    for name in ("loops", "links"):
        value = getattr(s, name)
        if isinstance(value, str) and ".." in value:
            raise scene.error(f"[structure] key '{name}' must be one whole number for {asked}, not the range "
                              f"{value!r}")
    if given:
        return _check_given_chain(scene, s)
    if s.loop_classes is not None:
        if s.loops is not None or s.prismatic is not None or s.n1 is not None:  # (an 'h' beside it: _refuse_unused)
            raise scene.error("[structure] key 'loop_classes' gives each loop's motion space and the links: it does "
                              f"not go with 'loops', 'prismatic' or 'n1' for {asked}")
        if s.chain is not None:
            _check_chain_of_bases(scene, s)
        return
    if s.links is None and s.loops is None and s.code is None:
        raise scene.error(f"[structure] needs 'links', 'loops' or 'code' for {asked}")


def _check_chain_of_bases(scene: Scene, s: Structure) -> None:
    """A chain with ``loop_classes`` (every base on it): its loops are the classes', and ``dof`` the bases' W by the
    count in their motion spaces, the chain's own in the lower class less (x − h)·K_x (:func:`synth.class_variants`)."""
    from synth import Chain, SynthesisError, split_classes

    try:
        chain = Chain.parse(s.chain)
    except SynthesisError as exc:  # (it came out without the scene's name)
        raise scene.error(f"[structure] key 'chain': {str(exc).rstrip('.')}") from None
    try:
        h, _, x, k_x = split_classes(s.loop_classes)
    except SynthesisError as exc:
        raise scene.error(f"[structure] {str(exc).rstrip('.')}") from None
    loops = sum(s.loop_classes.values())
    if chain.loops != loops:
        raise scene.error(f"[structure] key 'chain' has {chain.loops} loop{'s' * (chain.loops != 1)} and "
                          f"'loop_classes' asks for {loops}")
    _refuse_another_dof(scene, s, dataclasses.replace(chain, h=h, classes=None).dof - (x - h) * k_x, "its bases have")


def _refuse_another_dof(scene: Scene, s: Structure, dof: int, whose: str, mend: str = "") -> None:
    """Refuses a ``dof`` other than ``dof``, the W by the count of the chain given or of the bases on it."""
    if s.dof is not None and s.dof != dof:
        raise scene.error(f"[structure] key 'dof' asks for W = {s.dof} and {whose} W = {dof} by the count: for "
                          f"{_asked(scene)} the chain is taken as it is{mend}")


def _left_unused(scene: Scene, s: Structure, compute: str) -> dict[str, str]:
    """The ``[structure]`` keys that ``compute`` declares but leaves unused with the others given, each with the
    sentence that refuses it when no other computation asked uses it."""
    from synth import not_for_the_subject

    if compute == "analysis" and s.chain is not None:
        return {name: str(not_for_the_subject(f"key '{name}' beside 'chain'", "chain"))
                for name in (("v", "loop_classes", "f") if s.f else ("v", "loop_classes"))}
    # every computation takes the motion spaces from loop_classes, as 'codes' and 'chains --loop-classes' do
    unused = {}
    if s.loop_classes is not None:  # (synth.synthesis.classes is loaded for the classes only: it loads chains and nauty)
        from synth import h_beside_classes

        unused["h"] = str(h_beside_classes("keys 'h'", "'loop_classes'"))
    if compute == "codes":
        return unused
    if compute == "analysis":
        return unused | ({"v": str(not_for_the_subject("key 'v' beside 'code'", "code"))} if s.code is not None else {})
    drawing = scene.tables.get("drawing")
    if compute == "drawing" and not (drawing and drawing.mechanisms):  # ('cylinders' can narrow a query's chains)
        unused["input_link"] = ("key 'input_link' is for mechanisms and [drawing] draws the chains (mechanisms = true "
                                "draws the mechanisms)")
    if s.loop_classes is not None and s.chain is not None:
        return unused | {name: f"key '{name}' selects the chains of a query, and 'chain' with 'loop_classes' lays "
                               "every base on the one chain given" for name in _QUERY_KEYS if name not in _BASE_KEYS}
    if s.loop_classes is not None:
        return unused | {name: f"key '{name}' goes with 'prismatic', which 'loop_classes' does not take"
                         for name in ("idle_joints", "cylinders")}
    if s.chain is None and s.loops is not None and (s.links is not None or s.code is not None):
        fixed = "'links'" if s.links is not None else "'code'"
        unused["loops"] = f"key 'loops' is fixed by {fixed}: give one of them"
    return unused


#: the query keys that 'chain' with 'loop_classes' reads (rigid_subchains) or refuses in its own words
_BASE_KEYS = ("rigid_subchains", "loops", "n1", "prismatic")


def _refuse_unused(scene: Scene, s: Structure) -> None:
    """Refuses a ``[structure]`` key that every computation asked that declares it leaves unused with the others
    given (the analysis of a chain its ``loop_classes``, a query's chains ``loops`` beside ``links``, …), in the
    first one's words; ``Structure`` refuses a key that none of them declares."""
    for name in sorted(s.given(), key=list(Structure.model_fields).index):
        users = [c for c in scene.compute if c in Structure.model_fields[name].json_schema_extra["used_by"]]
        reasons = [_left_unused(scene, s, c).get(name) for c in users]
        if users and all(reasons):
            raise scene.error(f"[structure] for {_named(users)}, {reasons[0]}")


#: [structure] keys that select the chains of a query: a chain given by hand contradicts them
_QUERY_KEYS = ("links", "loops", "code", "v", "n1", "max_multiplicity", "require", "cranks", "rigid_subchains",
               "fractionated", "planar_only", "prismatic", "idle_joints", "cylinders")


def _check_given_chain(scene: Scene, s: Structure) -> None:
    """A chain given by hand (``chain`` without ``loop_classes``) is listed, fixed and drawn as ``chains --chain C``
    and ``mechanisms --chain C`` take it: a structure (W < 0) has no mechanisms, and ``input_link`` is refused for a
    truss (W = 0) and for a chain whose W by the count misleads (:func:`synth.count_defect`), in the CLI's words."""
    from synth import SynthesisError, not_a_mechanisms_chain, truss_has_no_input

    selecting = [name for name in _QUERY_KEYS if name in s.given()]
    if selecting:
        raise scene.error(f"[structure] key '{selecting[0]}' selects the chains of a query and contradicts 'chain' "
                          f"(the one chain given) for {_asked(scene)}")
    try:
        chain = _given_chain(s)
    except SynthesisError as exc:
        raise scene.error(str(exc).rstrip(".")) from None
    _refuse_another_dof(scene, s, chain.dof, "the chain has", " (its analysis says how to mend it)")
    drawing = scene.tables.get("drawing")
    if "mechanisms" not in scene.compute and not ("drawing" in scene.compute and drawing and drawing.mechanisms):
        return
    if chain.dof < 0:
        raise scene.error(str(not_a_mechanisms_chain(chain, chain.dof)))
    if s.input_link:
        defect = _count_defect(chain)
        if defect is not None or chain.dof == 0:
            raise scene.error(str(truss_has_no_input(f"the chain {chain.compact()} has", "the key 'input_link'",
                                                     defect)))


def _given_chain(s: Structure):
    """The chain ``[structure]`` gives by hand for chains, mechanisms and drawings (``chain`` without
    ``loop_classes``), read as ``chains --chain C`` reads it; None for a query."""
    if s.chain is None or s.loop_classes is not None:
        return None
    from synth.exchange import read_chain

    return read_chain(s.chain, None if s.h == 3 else s.h, source="[structure] key 'chain'").chain


def _count_defect(chain):
    """:func:`synth.count_defect` of a chain given by hand, or None beyond the exact test's 24 non-binary links
    (its mechanisms are then counted by its W, as ``mechanisms --chain`` lists them)."""
    from synth import MalformedChain, count_defect

    try:
        return count_defect(chain)
    except MalformedChain:
        return None


def _check_classes_of_chain(scene: Scene, s: Structure) -> None:
    """The analysis takes a chain's loop classes from its text (a base after ``|``): where ``loop_classes`` serve the
    codes or the chains, a chain that names classes must name those, and a chain without them must have a base to
    name (a class above 3; the analysis finds wedge loops, class 2, itself)."""
    from synth import Chain, SynthesisError

    try:
        chain = Chain.parse(s.chain)
    except SynthesisError:
        return  # (refused in the chain's own words by the analysis and the chains' checks)
    named = chain.loop_classes if chain.classes is not None else None
    if named != s.loop_classes and (named is not None or max(s.loop_classes) > 3):
        raise scene.error(f"[structure] for the analysis, 'chain' has loop classes {chain.loop_classes} and "
                          f"'loop_classes' gives {s.loop_classes}: the analysis takes a chain's classes from its "
                          "text, a base written after '|' ('… | h5: 0 1 2 3', docs/exchange.md)")


#: [expect] keys of the analysis that only a code or counts give, and those only a chain gives.
_CODE_ONLY = frozenset({"simple_joint_equivalents", "criterion_holds", "defect", "formulas_agree"})
_CHAIN_ONLY = frozenset({"standard_code", "subchain_defect", "planar", "fractionated", "worst_subchain_mobility",
                         "connected"})


def _check_analysis(scene: Scene) -> None:
    s = scene.tables["structure"]
    _refuse_unused(scene, s)
    given = [k for k in ("code", "counts", "chain") if getattr(s, k) is not None]
    if len(given) != 1:
        raise scene.error(f"[structure] needs exactly one of 'code', 'counts' or 'chain' for the analysis, "
                          f"not {given or 'none'}")
    if s.v is not None and not isinstance(s.v, int):
        raise scene.error(f"[structure] key 'v' must be one whole number for the analysis, not {s.v!r}")
    if s.chain is not None and s.loop_classes is not None:  # loop_classes serve another computation: the same system
        _check_classes_of_chain(scene, s)
    for name in scene.expect:
        if name in _CODE_ONLY and s.chain is not None:
            raise scene.error(f"[expect] key '{name}' belongs to the analysis of a code or counts, "
                              "but [structure] gives a chain")
        if name in _CHAIN_ONLY and s.chain is None:
            raise scene.error(f"[expect] key '{name}' belongs to the analysis of a chain, but [structure] gives no 'chain'")
        if name in {"defect", "criterion_holds"} and s.dof is None:
            raise scene.error(f"[expect] key '{name}' needs 'dof' (the required W) in [structure]")


# --------------------------------------------------------------------------- comparisons
def _same_codes(expected: list, actual: list, rel_tol: float) -> tuple[bool, str]:
    want = _canonical(expected)
    missing = [c for c in want if c not in set(actual)]
    extra = [c for c in actual if c not in set(want)]
    parts = ([f"missing {', '.join(missing)}"] if missing else []) + ([f"unexpected {', '.join(extra)}"] if extra else [])
    return not parts, "; ".join(parts)


def _codes_include(expected: list, actual: list, rel_tol: float) -> tuple[bool, str]:
    missing = [c for c in _canonical(expected) if c not in set(actual)]
    return not missing, f"missing {', '.join(missing)}"


def _codes_exclude(expected: list, actual: list, rel_tol: float) -> tuple[bool, str]:
    present = [c for c in _canonical(expected) if c in set(actual)]
    return not present, f"found {', '.join(present)}"


def _same_code(expected: str, actual: str, rel_tol: float) -> tuple[bool, str]:
    """The standard code, without what follows it in a chain's analysis (' P2', ' K3=4 K5=1')."""
    return _canonical([expected]) == _canonical([_split_suffix(actual)[0]]), f"the run gave {actual!r}"


def _chains_include(expected: list, actual: list, rel_tol: float) -> tuple[bool, str]:
    """Every chain named (a joint list, loop classes included) is among the chains listed, up to numbering."""
    from synth import Chain

    listed = {ch["certificate"] for ch in actual}
    missing = [text for text in expected if Chain.parse(text).certificate not in listed]
    return not missing, f"not listed: {'; '.join(missing)}"


def _split_suffix(code: str) -> tuple[str, str]:
    """A code with what follows it (' P2', ' K3=4 K5=1'): the code and that suffix."""
    head, _, tail = code.partition(" ")
    return head, (" " + tail) if tail else ""


def _codes_table(expected: dict, actual: dict, rel_tol: float) -> tuple[bool, str]:
    want = {_canonical([_split_suffix(c)[0]])[0] + _split_suffix(c)[1]: n for c, n in expected.items()}
    got = {_canonical([_split_suffix(c)[0]])[0] + _split_suffix(c)[1]: n for c, n in actual.items()}
    diff = [f"{c}: expected {want.get(c, 0)}, got {got.get(c, 0)}" for c in sorted(set(want) | set(got))
            if want.get(c, 0) != got.get(c, 0)]
    return not diff, "; ".join(diff)


# --------------------------------------------------------------------------- results
@dataclass(frozen=True)
class CodeList(Row):
    """``codes``: the standard codes of the structure, how many, per K, their sizes and largest link."""

    codes: tuple[str, ...]
    count: int
    by_loops: dict[str, int]
    links: tuple[int, ...]
    i_max: int


@dataclass(frozen=True)
class ChainCount(Row):
    """``count``: the chains of the structure, by code (with its suffixes), by v, non-planar, fractionated."""

    count: int
    by_code: dict[str, int]
    by_v: dict[str, int]
    nonplanar: int
    fractionated: int


@dataclass(frozen=True)
class ListedChain(Row):
    """One chain of a listing: its code, joint list and certificate."""

    code: str
    joints: str
    certificate: str


@dataclass(frozen=True)
class ChainListing(ChainCount):
    """``chains``: the counts and every chain."""

    chains: tuple[ListedChain, ...] = ()


@dataclass(frozen=True)
class MechanismCount(Row):
    """``mechanisms``: the mechanisms of the chains (fixed link, and input link if asked) by code, and how many
    of them are trusses on a frame (W = 0: statically determinate, nothing moves)."""

    count: int
    by_code: dict[str, int]
    input_link: bool
    trusses: int
    count_defect: dict | None = None  # a chain given by hand whose W by the count misleads: synth.CountDefect's fields
    row_keys = ("count", "by_code", "input_link", "trusses", "count_defect?")


@dataclass(frozen=True)
class CodeAnalysis(Row):
    """``analysis`` of a code or of counts: the analysis and whether every formula gives one W."""

    analysis: Any
    row_keys = ("*analysis", "formulas_agree")

    @property
    def formulas_agree(self) -> bool:
        return len(set(self.analysis.formulas.values())) == 1


@dataclass(frozen=True)
class Sheet(Row):
    """``drawing``: the file written and how many of the items it shows, or why none was written."""

    files: tuple[str, ...]
    skipped: str | None = None
    items: int | None = None
    of: int | None = None
    row_keys = ("files", "skipped?", "items?", "of?")


# --------------------------------------------------------------------------- computations
def _codes(run: Run) -> CodeList:
    from synth import number_synthesis  # CP-SAT counting model only

    s = run.scene.tables["structure"]
    codes = number_synthesis(
        s.dof, loops=s.loops, links=s.links, loop_classes=s.loop_classes, h=s.h, f=s.f, v=s.v, n1=0 if s.n1 is None else s.n1,
        max_link_degree=s.max_link_degree, require=s.require, max_multiplicity=s.max_multiplicity,
        compositions=s.compositions)
    by_loops: dict[str, int] = {}
    for c in codes:
        by_loops[str(c.loops)] = by_loops.get(str(c.loops), 0) + 1
    return CodeList(tuple(str(c) for c in codes), len(codes), by_loops, tuple(sorted({c.links for c in codes})),
                    max((c.max_degree for c in codes), default=0))


def _chain_list(run: Run) -> list:
    """The chains of the structure, found once per run (count, chains, mechanisms and drawing share them)."""

    def make() -> list:
        from synth import type_synthesis  # graph models: only for chain queries

        s = run.scene.tables["structure"]
        if s.loop_classes is not None:
            return _heterogeneous(s, run.workers)
        given = _given_chain(s)
        if given is not None:  # in its canonical numbering, as 'chains --chain C' lists it
            return [given.relabel(given.canonical_numbering())]
        query = _query(s)
        _refuse_large(query, run.workers)
        return list(type_synthesis(query, workers=run.workers))

    return run.shared("chains", make)


def _heterogeneous(s: Structure, workers: int) -> list:
    """The heterogeneous chains of a ``[structure]`` with ``loop_classes``: every base on its
    ``chain`` (read as a chain of the lower class, its own classes dropped), or the query."""
    from dataclasses import replace

    from synth import Chain, class_variants, heterogeneous_synthesis, skeleton_query, split_classes

    h, _, x, k_x = split_classes(s.loop_classes)
    if s.chain is not None:  # (its loops checked against the classes before the run)
        return class_variants(replace(Chain.parse(s.chain), h=h, classes=None), x, k_x, rigid_subchains=s.rigid_subchains)
    selection = dict(code=s.code, v=s.v, require=s.require, cranks=s.cranks, fractionated=s.fractionated,
                     planar_only=s.planar_only, max_multiplicity=s.max_multiplicity, rigid_subchains=s.rigid_subchains)
    links = int(s.links) if s.links is not None else None
    _refuse_large(skeleton_query(s.dof, s.loop_classes, links=links, **selection), workers)
    return list(heterogeneous_synthesis(s.dof, s.loop_classes, links=links, workers=workers, **selection))


def _query(s: Structure):
    """The chain query of a ``[structure]`` table."""
    from synth import ChainQuery

    return ChainQuery.of(s.dof, int(s.links) if s.links is not None else None,
                         loops=int(s.loops) if s.loops is not None and s.links is None and s.code is None else None,
                         v=s.v, code=s.code, rigid_subchains=s.rigid_subchains, fractionated=s.fractionated,
                         planar_only=s.planar_only, require=s.require, cranks=s.cranks, h=s.h, n1=s.n1,
                         max_multiplicity=s.max_multiplicity, prismatic=s.prismatic, idle_joints=s.idle_joints,
                         cylinders=s.cylinders)


_SCENE_CHAINS = 200_000  # a scene holds its chains in memory to check and report them
_SCENE_SECONDS = 3600.0


def _refuse_large(query, workers: int) -> None:
    """A scene's chains are listed and held in memory: a structure estimated beyond 200 000 chains or an
    hour is refused before any work (``mechsynth chains --count`` counts such queries in flat memory)."""
    import math

    from synth import QueryTooLarge, describe_seconds, estimate, magnitude, worth_sizing

    if query.prismatic is not None or not worth_sizing(query):
        return
    found = estimate(query, work="list")
    if found is None:
        return
    wall = found.log10_seconds - math.log10(max(workers, 1))
    if found.chains > _SCENE_CHAINS or wall > math.log10(_SCENE_SECONDS):
        raise QueryTooLarge(
            f"{query.links} links: about {magnitude(found.chains, found.log10_chains)} chains, "
            f"{describe_seconds(10 ** wall if wall < 300 else math.inf, wall)} on {workers} worker"
            f"{'s' * (workers > 1)} (extrapolated from the {found.basis}), more than a scene lists "
            f"({magnitude(_SCENE_CHAINS)} chains, an hour); count them with 'mechsynth chains --count'")


def _mechanism_list(run: Run) -> list:
    def make() -> list:
        from synth import mechanisms_of

        s = run.scene.tables["structure"]
        cylinders = () if s.loop_classes is not None or s.chain is not None else _query(s).cylinders
        return [m for ch in _chain_list(run) for m in mechanisms_of(ch, input_link=s.input_link, cylinders=cylinders)]

    return run.shared("mechanisms", make)


def _count(run: Run) -> ChainCount:
    chains = _chain_list(run)
    by_code: dict[str, int] = {}
    by_v: dict[str, int] = {}
    for ch in chains:
        name = str(ch.code) + ch.kind_suffix + ch.class_suffix
        by_code[name] = by_code.get(name, 0) + 1
        by_v[str(ch.v)] = by_v.get(str(ch.v), 0) + 1
    return ChainCount(len(chains), by_code, dict(sorted(by_v.items(), key=lambda kv: int(kv[0]))),
                      sum(1 for ch in chains if not ch.is_planar()), sum(1 for ch in chains if ch.is_fractionated()))


def _chains(run: Run) -> ChainListing:
    counted = _count(run)
    listed = tuple(ListedChain(str(ch.code) + ch.class_suffix, ch.compact(), ch.certificate) for ch in _chain_list(run))
    return ChainListing(counted.count, counted.by_code, counted.by_v, counted.nonplanar, counted.fractionated, listed)


def _mechanisms(run: Run) -> MechanismCount:
    mechs = _mechanism_list(run)
    by_code: dict[str, int] = {}
    for m in mechs:
        by_code[str(m.chain.code)] = by_code.get(str(m.chain.code), 0) + 1
    trusses = sum(m.chain.dof == 0 for m in mechs)  # (type synthesis's chains and bases pass the exact test)
    s = run.scene.tables["structure"]
    given = _given_chain(s)
    defect = None if given is None else _count_defect(given)  # a chain given by hand: is its W by the count true?
    return MechanismCount(len(mechs), by_code, s.input_link, trusses,
                          None if defect is None else dataclasses.asdict(defect))


def _analysis(run: Run) -> Row:
    s = run.scene.tables["structure"]
    if s.chain is not None:
        from synth import analyze_chain

        return analyze_chain(s.chain, dof=s.dof, h=s.h)
    from synth import analyze  # pure counting: no solver

    common = dict(dof=s.dof, h=s.h, f=s.f, loop_classes=s.loop_classes)
    if s.code is not None:
        return CodeAnalysis(analyze(s.code, **common))
    return CodeAnalysis(analyze(counts=s.counts, v=s.v or 0, **common))


def _drawing(run: Run) -> Sheet:
    scene = run.scene
    opts = scene.tables.get("drawing") or Drawing()
    name = opts.out or f"{scene.name}.svg"
    out = run.picture(name)
    if out is None:
        return Sheet((), skipped=f"no --out DIR given to write {name}")
    items = _mechanism_list(run) if opts.mechanisms else _chain_list(run)
    chosen = items[: opts.limit]
    from synth.draw import draw_sheet

    draw_sheet(chosen, out, columns=opts.columns, title=opts.title or scene.description, labels=opts.labels)
    return Sheet((str(out),), items=len(chosen), of=len(items))


# --------------------------------------------------------------------------- readable summaries
def _list(items, limit: int = 12) -> str:
    items = list(items)
    text = " ".join(str(i) for i in items[:limit])
    return text + (f" … (+{len(items) - limit})" if len(items) > limit else "")


def table_text(d: dict, limit: int = 12) -> str:
    """``k: v, …`` of a result table, shortened after ``limit`` items."""
    items = [f"{k}: {v}" for k, v in d.items()]
    return ", ".join(items[:limit]) + (f", … (+{len(items) - limit})" if len(items) > limit else "")


def _report_codes(r: dict) -> list[str]:
    return [f"{r['count']} codes: {_list(r['codes'])}", f"per K: {table_text(r['by_loops'])}; i_max = {r['i_max']}"]


def _report_chains(r: dict) -> list[str]:
    lines = [f"{r['count']} chain{'s' * (r['count'] != 1)}: {table_text(r['by_code'])}",
             f"by v: {table_text(r['by_v'])}; non-planar {r['nonplanar']}; fractionated {r['fractionated']}"]
    lines += [f"  {ch['code']:<12} {ch['joints']}" for ch in r.get("chains", [])[:10]]
    if len(r.get("chains", [])) > 10:
        lines.append(f"  … (+{len(r['chains']) - 10} chains; --format json lists all)")
    return lines


def _report_mechanisms(r: dict) -> list[str]:
    """What the mechanisms are, as ``mechsynth mechanisms`` says it: mechanisms and trusses on a frame, or
    what a chain given by hand is where its count misleads (its words, then the count by code).

    >>> _report_mechanisms({"count": 7, "trusses": 7, "by_code": {"32/0": 5, "401/0": 2}})  # dof = 0, links = 5
    ['7 trusses on a frame (W = 0: statically determinate, nothing moves): 32/0: 5, 401/0: 2']
    >>> _report_mechanisms({"count": 4, "trusses": 0, "by_code": {"42/0": 4}, "count_defect": {  # a triangle's four-bar
    ...     "dof": 1, "moves": 1, "kind": "rigid sub-chain", "worst_mobility": 0}})
    ["4 degenerate mechanisms: W = 1, but a sub-chain is rigid (W(S) = 0), one link in effect ('mechsynth analyze' says where)", 'by code: 42/0: 4']
    """
    from synth import CountDefect, mechanisms_summary

    defect = r.get("count_defect")
    line = mechanisms_summary(r["count"], r["trusses"], defect=defect and CountDefect(**defect))
    if defect:
        return [line, f"by code: {table_text(r['by_code'])}"]
    return [f"{line}: {table_text(r['by_code'])}"]


def _report_analysis(r: dict) -> list[str]:
    keys = ["code", "links", "loops", "complexity", "v", "dof", "defect", "criterion_holds", "subchain_defect"]
    lines = [", ".join(f"{k} = {r[k]}" for k in keys if r.get(k) is not None)]
    if r.get("formulas"):
        lines.append("W by formula: " + table_text(r["formulas"]))
    if r.get("advice"):
        lines.append(r["advice"])
    return lines


def _report_drawing(r: dict) -> list[str]:
    if r.get("skipped"):
        return [f"not drawn: {r['skipped']}"]
    return [f"wrote {r['files'][0]} ({r['items']} of {r['of']} items)"]


# --------------------------------------------------------------------------- the kinds
_CHAIN_COUNTS = {
    "count": Expectation(Whole),
    "by_code": Expectation(CodeTable, compare=_codes_table),
    "count_by_v": Expectation(WholeTable, ("by_v",), compare.table),
    "count_nonplanar": Expectation(Whole, ("nonplanar",)),
    "count_fractionated": Expectation(Whole, ("fractionated",)),
}
_CHAIN_LISTS = {**_CHAIN_COUNTS, "chains_include": Expectation(
    Annotated[list[StrictStr], expect("a list of joint lists such as [\"0-1 1-2 2-3 3-0\"]")], ("chains",),
    _chains_include)}

FAMILY.kind(ComputeKind(
    "codes", "number synthesis: every standard code n2n3…/v for the structure", "structure", _codes,
    expect={
        "codes": Expectation(Codes, compare=_same_codes),
        "codes_include": Expectation(Codes, ("codes",), _codes_include),
        "codes_exclude": Expectation(Codes, ("codes",), _codes_exclude),
        "code_count": Expectation(Whole, ("count",)),
        "code_count_by_loops": Expectation(WholeTable, ("by_loops",), compare.table),
        "code_links": Expectation(Wholes, ("links",)),
        "i_max": Expectation(Whole),
    },
    check=_check_codes, report=_report_codes))
FAMILY.kind(ComputeKind(
    "count", "type synthesis: the number of chains, by code, by v, non-planar and fractionated", "structure",
    _count, expect=_CHAIN_COUNTS, check=_check_chains, report=_report_chains))
FAMILY.kind(ComputeKind(
    "chains", "type synthesis: the chains themselves (joint lists and certificates) and their counts", "structure",
    _chains, expect=_CHAIN_LISTS, check=_check_chains, report=_report_chains))
FAMILY.kind(ComputeKind(
    "mechanisms", "chains with a fixed link (and input link) up to symmetry", "structure", _mechanisms,
    expect={"mechanisms": Expectation(Whole, ("count",)),
            "mechanisms_by_code": Expectation(CodeTable, ("by_code",), _codes_table)},
    check=_check_chains, report=_report_mechanisms))
FAMILY.kind(ComputeKind(
    "analysis", "W, K, Y, D of a code, of explicit counts or of a chain", "structure", _analysis,
    expect={
        **{k: Expectation(Int) for k in ("dof", "loops", "complexity", "defect", "worst_subchain_mobility")},
        **{k: Expectation(Whole) for k in ("links", "joints", "v", "simple_joint_equivalents")},
        **{k: Expectation(Flag) for k in ("criterion_holds", "formulas_agree", "standard_code", "planar",
                                          "fractionated", "connected")},
        "code": Expectation(CodeText, compare=_same_code),
        "subchain_defect": Expectation(Text),
    },
    check=_check_analysis, report=_report_analysis))
FAMILY.kind(ComputeKind(
    "drawing", "an atlas sheet of the chains or mechanisms, written to --out", "structure", _drawing,
    expect={"drawn": Expectation(Whole, ("items",))}, check=_check_chains, report=_report_drawing,
    reads=("drawing",)))
