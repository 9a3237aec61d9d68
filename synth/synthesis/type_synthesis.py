"""Type synthesis: every non-isomorphic chain (and mechanism) of a :class:`~synth.structure.query.ChainQuery`.

Work is split into independent *units* (one code's branch-multigraph enumeration,
then one branch multigraph's binary-link distribution), run inline or on a
process pool; the output order is fixed by (code, multigraph certificate, chain
certificate), so it does not depend on the number of workers.

With prismatic pairs, the chains of mobility W are the assignments of prismatic pairs with
K_2 = k wedge loops to the revolute chains of mobility W − k (docs/theory.md, "What W means
with prismatic pairs"): each k is a set of units whose skeletons allow sub-chains down to
W(S) = 1 − k (stage A and B with that *slack*), and each unit assigns the pairs to its
skeletons and keeps the chains that pass the exact test with their joint kinds.

Example
-------
>>> sum(1 for _ in type_synthesis(1, 8, workers=1))
16
>>> count_chains(1, 6, v=(0, 2), workers=1)["by_code"]
{'42/0': 2, '51/1': 1, '60/2': 1}
>>> for c in type_synthesis(1, 5, prismatic="1..6", workers=1):   # Task 3: a wedge loop and a lever loop
...     print(c.compact(), c.dof)
0=2 0=3 1=2 1=3 2-4 3-4 1
0=1 0=2 1=2 1-4 2-3 3-4 1
0=3 0=4 1=2 1-4 2-3 3=4 1
0=1 0=3 1=2 1=3 2-4 3-4 1
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import dataclass, field, fields
from pathlib import Path

from mechbase import Row

from ..errors import ImpossibleParameters, InvalidOption, QueryTooLarge
from ..execution.executor import Executor, run_plan
from ..execution.memo import keep, recall
from ..execution.progress import Progress
from ..structure.chain import Chain, Mechanism
from ..structure.code import Code
from ..structure.query import ChainQuery, parse_requirements
from .stage_a import BranchFacts, Contracted, Conventions, Vertex, contracted_graphs, contracted_stream, needs_solver, uses_kernel
from .stage_b import count_orbits, count_realised, count_reversed, load_kernel, realise
from .number_synthesis import number_synthesis

__all__ = ["Conventions", "Unit", "Counts", "plan_codes", "plan_units", "plan_many", "plan_jobs", "type_synthesis",
           "count_chains", "COUNT_METHODS", "count_mechanisms", "mechanisms", "mechanisms_of", "run_unit", "count_unit", "count_by_code", "job_units",
           "count_identity"]


# Stages A and B write one sub-chain condition per set of branch vertices: 2^m of them;
# m = 18 gives 262 144, the most a model is allowed to hold.
_MAX_BRANCH = 18
# A query runs inline for this long before it starts a pool, if no code has more branch
# vertices than _INLINE_BRANCH (stage A of such a code takes milliseconds: 8 at 12 links).
# A pool of two starts in about 15 ms: 0.25 -> 0.05 s made planar 12 links (0.3 CPU s) 0.43 -> 0.37 s
# wall on 2 workers, and queries that end sooner (10 links: 0.2 s with start-up) pay nothing.
_INLINE_SECONDS = 0.05
_INLINE_BRANCH = 8
# A count holds at most this many units of a code at a time in any process: a code with more is
# written by the worker of its stage A to a temporary file, this many at a time, and read back as
# it is worked on (synth.execution.spill).  4 096 units of 20 links are about 2.5 MB pickled, 10 MB
# held.  The environment variable MECHSYNTH_UNIT_WINDOW sets another (tests: a tiny one).
UNIT_WINDOW = 4096


def _branch_vertices(code: Code) -> int:
    """Links with 3+ joints and multiple joints: the vertices of the branch multigraph H."""
    return code.links - code.count(2) + sum(code.composition or ())


@dataclass(frozen=True)
class Unit:
    """One independent piece of work: the chains of ``code`` whose branch multigraph is ``contracted``
    (with prismatic pairs: their assignments to those revolute skeletons).

    ``contracted`` is None for a code without branch vertices (the single loop).
    """

    code: Code
    contracted: Contracted | None
    conventions: Conventions

    @property
    def key(self) -> str:
        """Stable name of the unit (code, multigraph certificate, the motion space where h ≠ 3 and
        the prismatic pairs where asked), used by atlases and checkpoints to resume."""
        conv = self.conventions
        space = "" if conv.h == 3 else f"|h{conv.h}"
        if conv.prismatic is not None:
            lo, hi = conv.prismatic
            space += f"|P{lo}..{'' if hi is None else hi}" + ("i" if conv.idle_joints else "")
        return f"{self.code}|{self.contracted.certificate if self.contracted else 'loop'}{space}"


def _conventions(query: ChainQuery, slack: int = 0) -> Conventions:
    return Conventions(query.rigid, query.fractionated, query.planar_only, query.cranks, query.h, slack=slack,
                       prismatic=query.prismatic, idle_joints=query.idle_joints, cylinders_only=query.cylinders_only)


def _with_crank_links(query: ChainQuery):
    """The requirements on the link assortment, with a link with I joints for each crank requirement."""
    merged = parse_requirements(query.require)
    for i, c in query.cranks:
        lo, hi = merged.get(i, (0, None))
        if hi == 0:
            raise ImpossibleParameters(f"cranks {i}={c} need a link with {i} joints, but the requirement n{i} = 0 "
                                       "forbids one")
        merged[i] = (max(lo, 1), hi)
    return merged


def plan_codes(query: ChainQuery | int | None = None, links: int | None = None, *, slack: int = 0,
               **options) -> list[Code]:
    """The codes (with joint composition) a chain query covers, in output order; with ``slack``
    k, the codes of its revolute skeletons of mobility W − k (k wedge loops to come).

    A link of a non-fractionated closed part carries at most K+1 joints, of a fractionated
    one at most 2K, and an open chain's link at most n1 more (each further joint leads to a
    branch with a single-joint link of its own); a non-degenerate closed chain with W = 1 is
    never fractionated (its parts would each need W ≥ 1), with prismatic pairs too.

    >>> [str(c) for c in plan_codes(1, 8)]
    ['440/0', '521/0', '602/0']
    >>> [str(c) for c in plan_codes(4, 7, n1=2, v=2)]  # the robot arm of two grippers: 2|5/2 as two joint compositions
    ['2|5/0-1', '2|5/2']
    >>> [str(c) for c in plan_codes(1, 5, prismatic="0..", slack=1)]  # Task 3's truss skeleton
    ['32/0']
    """
    query = ChainQuery.of(query, links, **options)
    dof, code, h = query.dof, query.code, query.h
    n1 = query.n1 if query.n1 is not None else ((code.n1, code.n1) if code else (0, 0))
    max_multiplicity = query.max_multiplicity
    if max_multiplicity is None and (query.rigid or slack or query.fractionated and not (dof == 1 and n1 == (0, 0))):
        # the limit theorem (a joint of order ≤ K closed, ≤ K + W open) holds for chains that are neither
        # fractionated nor degenerate (a non-degenerate closed 1-DOF chain is never fractionated);
        # other conventions have chains beyond it (a 4-link joint carrying two 4-link loops: W = 3, K = 2)
        max_multiplicity = query.links
    if code is not None:
        exact = {i: (code.count(i), code.count(i)) for i in range(2, code.max_degree + 1)}
        codes = number_synthesis(dof, links=code.links, v=code.v, compositions=True, h=h, n1=code.n1, f=slack,
                                 max_link_degree=max(code.max_degree, 2), require=exact,
                                 max_multiplicity=max_multiplicity)
        return [c for c in codes if code.composition is None or c.composition == code.composition]
    v = query.v or (0, 0)
    n1_hi = query.links if n1[1] is None else n1[1]
    K = max(0, (query.links - (dof - slack) - 1) // (h - 1))
    closed, why = (2 * K, "2K, fractionated chains included") if query.fractionated and (dof >= 2 or query.rigid) \
        else (K + 1, "K+1")
    imax = closed + n1_hi
    if n1_hi:
        why += f", and {n1_hi} more for single-joint links"
    require = _with_crank_links(query)
    for i, (lo, _) in require.items():
        if i > imax and lo > 0 and K >= 1:
            raise ImpossibleParameters(
                f"no chain with W = {dof} and {query.links} links has a link with {i} joints: with K = {K} loops a "
                f"link carries at most {imax} ({why})")
    return number_synthesis(dof, links=query.links, v=v, compositions=True, max_link_degree=max(imax, K + 1), f=slack,
                            require=require, h=h, n1=(n1[0], n1_hi), max_multiplicity=max_multiplicity)


def job_units(job: tuple[Code, Conventions]) -> list[Unit]:
    """Stage A of one job of :func:`plan_jobs`: its units, one per branch multigraph.

    >>> [len(job_units(job)) for job in plan_jobs(ChainQuery(1, 8))]
    [2, 1, 1]
    """
    code, conv = job
    if code.count(2) == code.links and code.v == 0:  # a single loop of binary links
        return [Unit(code, None, conv)]
    return [Unit(code, graph, conv) for graph in contracted_graphs(code, conv)]


def unit_window() -> int:
    """The units of a code a count holds at a time (:data:`UNIT_WINDOW`, or the environment's
    ``MECHSYNTH_UNIT_WINDOW``, a whole number ≥ 1).

    >>> unit_window()
    4096
    """
    text = os.environ.get("MECHSYNTH_UNIT_WINDOW")
    if text is None:
        return UNIT_WINDOW
    if not text.isdigit() or int(text) < 1:
        raise InvalidOption(f"MECHSYNTH_UNIT_WINDOW must be a whole number ≥ 1, not {text!r}")
    return int(text)


@dataclass(frozen=True)
class _StreamedUnits:
    """Stage A of one job for a count (a picklable expand function): its units in the order found
    (:func:`~synth.synthesis.stage_a.contracted_stream`), a list when there are at most ``window``
    of them, else spilled to a file in ``directory`` ``window`` at a time (:func:`spill`).

    With ``plan`` (the identity of a checkpoint's plan), ``directory`` is the checkpoint's folder of
    kept units: every code's units are written there whatever their number (:func:`write_kept`, one
    file a code, :meth:`path`), and a code whose complete file is there already is read back from it
    instead of running stage A again (a count resumed after a kill).
    """

    directory: str
    window: int
    plan: str | None = None

    def path(self, code: Code) -> str:
        """The file of ``code``'s kept units (its name made safe for a file, and told apart by a digest)."""
        import hashlib

        name = str(code)
        safe = "".join(ch if ch.isalnum() or ch in "-." else "_" for ch in name)
        return os.path.join(self.directory, f"{safe}-{hashlib.sha256(name.encode()).hexdigest()[:8]}.units")

    def __call__(self, job: tuple[Code, Conventions]):
        from ..execution.spill import read_kept, spill, write_kept

        code, conv = job
        if code.count(2) == code.links and code.v == 0:  # a single loop of binary links
            return [Unit(code, None, conv)]
        if self.plan is None:
            return spill(_stage_a(code, conv), self.directory, chunk=self.window)
        label = f"{self.plan}|{code}|{conv!r}|{_UNIT_LAYOUT}"
        kept = read_kept(self.path(code), label)
        return kept if kept is not None else write_kept(_stage_a(code, conv), self.path(code), chunk=self.window,
                                                        label=label)


# what a kept unit is pickled as: a file kept by an engine whose units had other fields is not read
_UNIT_LAYOUT = ",".join(f"{cls.__name__}({' '.join(names)})" for cls, names in
                        [(Unit, [f.name for f in fields(Unit)]), (Contracted, [f.name for f in fields(Contracted)]),
                         (Vertex, Vertex._fields)])


def _stage_a(code: Code, conv: Conventions) -> Iterator[Unit]:
    """The units of ``code`` as stage A finds them (begun at the first one asked for)."""
    for graph in contracted_stream(code, conv):
        yield Unit(code, graph, conv)


def run_unit(unit: Unit, stats: dict | None = None) -> list[Chain]:
    """The chains of one unit, sorted by certificate (deterministic), each in its canonical labelling
    (:meth:`Chain.canonical`: the numbering the atlas stores, so one id has one numbering everywhere)."""
    conv = unit.conventions
    if unit.contracted is None:
        n = unit.code.links
        found = [Chain(n, tuple((i, (i + 1) % n) for i in range(n)), h=conv.h)] if n >= 3 else []
    else:
        found = realise(unit.code, unit.contracted, conv, stats)
    if conv.prismatic is not None:
        from .variants import assignments

        found = [c for skeleton in found for c in assignments(skeleton, conv)]
    return [c.canonical() for c in found]


def _check_workers(workers):
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidOption(f"workers must be a whole number ≥ 1, not {workers!r}")


def plan_units(query: ChainQuery | int | None = None, links: int | None = None, *, workers: int | None = 1,
               **options) -> list[Unit]:
    """The independent work units of a chain query, in output order.

    Stage A (one CP-SAT model per code) runs inline, or on ``workers`` processes.
    ``run_unit(u)`` for every unit, concatenated, equals ``list(type_synthesis(...))``.

    >>> units = plan_units(1, 8); [u.key.split("|")[0] for u in units]
    ['440/0', '440/0', '521/0', '602/0']
    >>> sum(len(run_unit(u)) for u in units)
    16
    """
    query = ChainQuery.of(query, links, **options)
    _check_workers(workers)
    with Executor(workers or os.cpu_count() or 1) as executor:
        return plan_many([query], executor=executor)[0]


def plan_many(queries, *, executor: Executor | None = None, skip_impossible: bool = False) -> list[list[Unit]]:
    """:func:`plan_units` for several queries at once: stage A of all their codes in one batch.

    ``queries`` are :class:`ChainQuery` objects (or keyword dictionaries of one); ``executor``
    runs stage A (default: inline); with ``skip_impossible`` a query the counting equations rule
    out gets no units instead of raising :class:`ImpossibleParameters`.

    >>> [len(units) for units in plan_many([dict(dof=1, links=8), dict(dof=1, links=9)], skip_impossible=True)]
    [4, 0]
    """
    jobs, owners = [], []
    queries = list(queries)
    for index, query in enumerate(queries):
        try:
            query = query if isinstance(query, ChainQuery) else ChainQuery.of(**query)
            found = plan_jobs(query)
        except ImpossibleParameters:
            if not skip_impossible:
                raise
            found = []
        jobs += found
        owners += [index] * len(found)
    plans: list[list[Unit]] = [[] for _ in queries]
    batches = (executor or Executor()).map(job_units, jobs)
    for owner, batch in zip(owners, batches):
        plans[owner].extend(batch)
    return plans


def plan_jobs(query: ChainQuery) -> list[tuple[Code, Conventions]]:
    """Number synthesis of one query: (code, conventions) of each stage-A job, in output order
    (with prismatic pairs, the skeletons of 0, 1, 2 … wedge loops in turn).

    >>> [(str(c), conv.slack) for c, conv in plan_jobs(ChainQuery(1, 6, prismatic=(0, 3)))]
    [('42/0', 0)]
    """
    slacks = query.skeleton_slacks()
    if not slacks:
        raise ImpossibleParameters(
            f"no chain with W = {query.dof} has {query.links} links for any number of wedge loops K_2: "
            f"n = W + 1 + 2K − K_2 needs K_2 ≤ K, and a wedge loop needs three prismatic pairs")
    jobs = []
    for slack in slacks:
        conv = _conventions(query, slack)
        try:
            codes = plan_codes(query, slack=slack)
        except ImpossibleParameters:
            if len(slacks) == 1:
                raise
            continue
        for code in codes:
            branch = _branch_vertices(code)
            if branch > _MAX_BRANCH:
                raise QueryTooLarge(f"code {code} has {branch} branch vertices (links with 3+ joints and multiple "
                                    f"joints); its branch-multigraph model would need 2^{branch} sub-chain conditions, "
                                    f"more than this engine builds (at most {_MAX_BRANCH} branch vertices)")
        jobs += [(c, conv) for c in codes]
    return jobs


def type_synthesis(query: ChainQuery | int | None = None, links: int | None = None, *, workers: int | None = None,
                   progress: bool = False, **options) -> Iterator[Chain]:
    """Every non-isomorphic chain of a query: mobility ``dof``, ``links`` links, motion space ``h``.

    Parameters
    ----------
    query : ChainQuery or int
        The query, or W (0 for trusses) with ``links`` and the options of :class:`ChainQuery`
        (``v``, ``code``, ``h``, ``n1``, ``require``, ``cranks``, ``max_multiplicity``,
        ``rigid_subchains``, ``fractionated``, ``planar_only``, ``prismatic``, ``idle_joints``).
    links : int, optional
        n, the frame included (or give ``code``).
    workers : int, optional
        Processes; default all cores; 1 runs inline.
    progress : bool
        A progress bar on stderr.

    Yields
    ------
    Chain
        In deterministic order: code, branch multigraph, certificate.

    Notes
    -----
    Stage A (one CP-SAT model per code) and stage B (one per branch multigraph) are
    independent units; the sub-chain test is exact and nauty removes duplicates.
    """
    query = ChainQuery.of(query, links, **options)
    _check_workers(workers)
    for _, unit, chains in _map_units(run_unit, plan_jobs(query), workers, progress):
        if unit is not None:
            branch = BranchFacts(unit.contracted.edges if unit.contracted else ())  # (a single loop: no edge)
            for chain in chains:  # planarity and fractionation, asked of a chain, decided once on its H
                object.__setattr__(chain, "_branch", branch)
            yield from chains


def _map_units(work, jobs: list[tuple[Code, Conventions]], workers: int | None, progress: bool, *,
               client=None, skip_code=None, skip_unit=None, ordered: bool = True,
               expected: tuple[str, float] | None = None, kept: tuple | None = None,
               before: dict | None = None) -> Iterator[tuple]:
    """``(job index, unit, work(unit))`` for every unit of the stage-A ``jobs`` (code, conventions),
    then ``(index, None, units)`` when a job is complete: inline for a small query, else streamed to
    a process pool (or a Dask ``client``) with a bounded number of tasks in flight (see
    :mod:`synth.execution.executor`); in plan order, or as units finish with ``ordered=False``.

    ``work`` returns the unit's chains or its counts by code; the progress (a bar on a terminal, a
    line a minute in a log: :class:`~synth.execution.progress.Progress`) adds up either, and with
    ``expected`` (a counter and the total an estimate expects of it: :func:`~synth.synthesis.estimate.time_to_go_from`)
    reckons the time to go from that counter's share; ``before``
    (``{"units": …, "chains": …}``, what a resumed run's checkpoint or the store already holds) starts its totals,
    the codes skipped counted as done, so the line reads the whole count's and its time to go this run's rate.
    Unordered on this machine (a count), a code's units are never held whole: stage A hands them on
    as found, through a temporary folder when they are more than :func:`unit_window`; with ``kept``
    (a checkpoint's folder of kept units and the identity of its plan) through that folder instead,
    one file a code read back by a resumed run (:class:`_StreamedUnits`), each removed once the
    caller has taken its code's completion, and the folder once the run is through.
    """
    from contextlib import ExitStack

    # stage A of one code grows steeply with its branch vertices (12 at 16 links: minutes):
    # a plan with such codes goes to the pool at once, a smaller one starts inline
    to_run = [job for i, job in enumerate(jobs) if not (skip_code and skip_code(i))]
    bar = Progress(len(jobs), "codes", desc="mechsynth", before={"steps": len(jobs) - len(to_run), **(before or {})},
                   expected=expected) if progress else None
    try:
        inline = _INLINE_SECONDS if max((_branch_vertices(c) for c, _ in to_run), default=0) <= _INLINE_BRANCH else 0.0
        if any(uses_kernel(c, conv) for c, conv in to_run):
            load_kernel()  # once, here: the workers forked later inherit it
        if any(needs_solver(c, conv) for c, conv in to_run):
            from . import _cpsat  # noqa: F401 - likewise the solver (≈ 0.3 s), and outside the inline phase's clock
        with ExitStack() as stack:
            expand = job_units
            keeping = kept is not None and not ordered and client is None
            if keeping:
                expand = _StreamedUnits(str(kept[0]), unit_window(), kept[1])
            elif not ordered and client is None:  # (a Dask worker elsewhere could not write to this machine's folder)
                import tempfile

                folder = stack.enter_context(tempfile.TemporaryDirectory(prefix="mechsynth-units-"))
                expand = _StreamedUnits(folder, unit_window())
            # (entered last, left first: the pool ends before its folder is removed)
            executor = stack.enter_context(Executor(workers or os.cpu_count() or 1, client))
            for event in run_plan(jobs, expand, work, executor=executor, skip_item=skip_code, skip_unit=skip_unit,
                                  inline_seconds=inline, ordered=ordered):
                if bar is not None:
                    if event[1] is None:
                        bar.update(1)
                    else:
                        found = sum(event[2].values()) if isinstance(event[2], dict) else len(event[2])
                        bar.update(0, units=1, chains=found)
                yield event
                if keeping and event[1] is None:  # the caller has committed the code complete
                    Path(expand.path(jobs[event[0]][0])).unlink(missing_ok=True)
        if keeping:
            _remove_kept_folder(kept[0])
    finally:
        if bar is not None:
            bar.close()


def kept_units_folder(checkpoint, *, make: bool = True) -> Path:
    """The folder beside ``checkpoint`` (``FILE.units``) where a count keeps each code's units until the
    code is complete, made if missing (with ``make``); what a killed run was writing there (``*.part``)
    is removed.

    Raises :class:`~synth.execution.checkpoint.CheckpointError` when that name is taken by a file (with
    ``make=False``, that is all it does: the count asks before it opens the checkpoint).

    >>> import tempfile
    >>> folder = kept_units_folder(Path(tempfile.mkdtemp()) / "c16.sqlite"); folder.name, folder.is_dir()
    ('c16.sqlite.units', True)
    """
    from ..execution.checkpoint import CheckpointError

    folder = Path(f"{checkpoint}.units")
    if folder.exists() and not folder.is_dir():
        raise CheckpointError(f"the checkpoint {checkpoint} keeps its units in the folder {folder}, but that is a "
                              "file: move it away or give another checkpoint")
    if not make:
        return folder
    try:
        folder.mkdir(exist_ok=True)
    except OSError as exc:
        raise CheckpointError(f"cannot make the folder {folder} for the checkpoint's units ({exc.strerror})") from None
    for part in folder.glob("*.units.*.part"):
        part.unlink(missing_ok=True)
    return folder


def _remove_kept_folder(folder: Path) -> None:
    """Delete a count's folder of kept units once the count is through: its files (codes complete
    whose file a kill left behind) and the folder; a folder holding anything else is left."""
    for path in folder.glob("*.units"):
        path.unlink(missing_ok=True)
    try:
        folder.rmdir()
    except OSError:
        pass


def count_by_code(items) -> dict[str, int]:
    """Counts of chains (or mechanisms) by code, joint kinds included, in the order met.

    >>> count_by_code([Chain.parse("0-1 1-2 2-3 3-0"), Chain.parse("0=1 1-2 2-3 3-0")])
    {'4/0': 1, '4/0 P1': 1}
    """
    out: dict[str, int] = {}
    for item in items:
        chain = item.chain if isinstance(item, Mechanism) else item
        name = str(chain.code) + chain.kind_suffix + chain.class_suffix
        out[name] = out.get(name, 0) + 1
    return out


# How a count finds each unit's chains: "listing" as stage B lists them (one lex-least placement per
# orbit, or the chains compared), "orbits" by Burnside's lemma over the automorphisms of H
# (stage_b.count_orbits, where it applies; docs/theory.md, "Counting by orbits"), "tight-reverse" by the
# second count of issue 41 (stage_b.count_reversed: the programme over the bundles in reverse, another
# reading of the group, the bundles' ways listed; docs/theory.md, "A second count").
COUNT_METHODS = ("listing", "orbits", "tight-reverse")


def count_unit(unit: Unit, method: str = "listing", stats: dict | None = None) -> dict[str, int]:
    """Counts by code of one unit's chains (``'42/0 P2'`` with prismatic pairs): counted where they
    are computed, without building the chains where stage B's solutions are already one per chain;
    what ``count_chains`` runs on each unit, on any scheduler.  ``method`` is one of
    :data:`COUNT_METHODS` (all give the same counts); ``stats`` gathers stage B's figures as
    :func:`run_unit`'s does (``"tight"``: the unit was counted without visiting its placements).

    >>> [count_unit(u) for u in plan_units(1, 6)], [count_unit(u, "tight-reverse") for u in plan_units(1, 6)]
    ([{'42/0': 2}], [{'42/0': 2}])
    """
    if unit.contracted is None or unit.conventions.prismatic is not None:
        return count_by_code(run_unit(unit, stats))
    count = {"orbits": count_orbits, "tight-reverse": count_reversed}.get(method, count_realised)
    n = count(unit.code, unit.contracted, unit.conventions, stats)
    return {str(unit.code): n} if n else {}


class _UnitCount(dict):
    """One unit's counts by code, ``by_search``: why it was counted by the search where counting by
    orbits was asked for (a key of :data:`~synth.synthesis.stage_b.BY_SEARCH`), else None; and ``shared``:
    whether the second count (tight-reverse) counted it by the first count's own path."""

    def __init__(self, counts: dict[str, int], by_search: str | None = None, shared: bool = False):
        super().__init__(counts)
        self.by_search, self.shared = by_search, shared


@dataclass(frozen=True)
class _ChainCount:
    """The chains of one unit counted by ``method`` (a picklable work function), with why the unit
    was counted by the search if it was (:class:`_UnitCount`)."""

    method: str

    def __call__(self, unit: Unit) -> _UnitCount:
        stats: dict = {}
        counts = count_unit(unit, self.method, stats)
        return _UnitCount(counts, next((key.removeprefix("by_search_") for key in stats
                                        if key.startswith("by_search_")), None), bool(stats.get("shared")))


def _check_method(method: str, query: ChainQuery) -> None:
    """Refuse an unknown counting method, and counting by orbits where some chain needs a rule or a check
    Burnside's count over patterns does not make (prismatic pairs, cranks, two empty parallel strings, which
    with h = 2 and rigid sub-chains allowed is also two joints on the same links)."""
    if method not in COUNT_METHODS:
        raise InvalidOption(f"the counting method is one of {', '.join(COUNT_METHODS)}, not {method!r}")
    if method == "orbits":
        why = ("chains with prismatic pairs are counted from their revolute skeletons' listings" if query.prismatic
               is not None else "a crank requirement is checked on each chain" if query.cranks else
               "with h = 2 and rigid sub-chains allowed two strings between the same links may both be empty"
               if query.h + (0 if query.rigid else 1) <= 2 else None)
        if why:
            raise InvalidOption(f"these chains cannot be counted by orbits ({why}): use the listing method")
    if method == "tight-reverse":
        why = ("chains with prismatic pairs are counted from their revolute skeletons' listings" if query.prismatic
               is not None else "a crank requirement is checked on each chain" if query.cranks else None)
        if why:
            raise InvalidOption(f"the second count (tight-reverse) does not cover these chains ({why}): use the "
                                f"listing method")


@dataclass(frozen=True)
class _MechanismCount:
    """The mechanisms of one unit's chains, counted by code (a picklable work function)."""

    input_link: bool = False
    cylinders: tuple = ()

    def __call__(self, unit: Unit, stats: dict | None = None) -> dict[str, int]:
        return count_by_code(m for c in run_unit(unit, stats) for m in mechanisms_of(c, input_link=self.input_link,
                                                                                   cylinders=self.cylinders))


@dataclass(frozen=True)
class Counts(Row):
    """How many chains (or mechanisms) a query has: in all and by code (``'42/0 P2'`` with
    prismatic pairs), in the order of the plan.  ``counts["count"]`` reads its JSON form.

    >>> c = count_chains(1, 8, workers=1); c.count, c.by_code["440/0"], c["count"]
    (16, 9, 16)
    """

    count: int
    by_code: dict
    #: the units of work this call ran (not those a checkpoint or the store of earlier runs gave); this and
    #: ``by_search`` say how the count was made, not what it is: neither is in the row nor compared
    units_run: int = field(default=0, compare=False)
    #: of those, the units counted by the search where counting by orbits was asked for, by the key of
    #: :data:`~synth.synthesis.stage_b.BY_SEARCH` that says why
    by_search: dict = field(default_factory=dict, compare=False)
    #: of those, the units the second count (tight-reverse) counted by the first count's own path
    #: (:func:`~synth.synthesis.stage_b.count_reversed`): no independent check of the first count
    shared_units: int = field(default=0, compare=False)

    row_keys = ("count", "by_code")

    def __getitem__(self, key: str):
        return self.to_dict()[key]

    @property
    def by_search_note(self) -> str | None:
        """One sentence on the units counted by the search instead of by orbits, or None if none was.

        >>> print(Counts(9, {"6301/0": 9}, 4, {"group": 1}).by_search_note)  # doctest: +ELLIPSIS
        1 of the 4 units run was counted by the search, not by orbits (...): 1 because the permutations ... to list
        """
        if not self.by_search:
            return None
        from .stage_b import BY_SEARCH

        why = "; ".join(f"{n} because {BY_SEARCH[key]}" for key, n in self.by_search.items())
        searched = sum(self.by_search.values())
        return (f"{searched} of the {self.units_run} units run {'was' if searched == 1 else 'were'} counted by the search, not by "
                f"orbits (the same counts, found as the listing finds them): {why}")

    @property
    def shared_note(self) -> str | None:
        """One sentence on the units of a second count that were counted by the first count's path, or None.

        >>> print(Counts(9, {"6301/0": 9}, 4, shared_units=1).shared_note)  # doctest: +ELLIPSIS
        1 of the 4 units run was counted by the first count's own path (...), not independently of it
        """
        if not self.shared_units:
            return None
        return (f"{self.shared_units} of the {self.units_run} units run {'was' if self.shared_units == 1 else 'were'} "
                f"counted by the first count's own path (neither the reversed programme nor the count by orbits applies "
                f"to them), not independently of it")


def _identity(what: str, jobs: list[tuple[Code, Conventions]]) -> str:
    """What a count computes, as a digest: the same codes and conventions give the same units."""
    import hashlib

    text = repr((what, [(str(c), conv) for c, conv in jobs]))
    return hashlib.sha256(text.encode()).hexdigest()


def _describe(what: str, query: ChainQuery) -> str:
    return " ".join([what] + [f"{k}={v}" for k, v in query.to_dict().items()]).replace("'", "")


def count_identity(query: ChainQuery, what: str = "chains") -> tuple[str, str]:
    """The plan's digest and the query in words that a checkpoint of this count is written with
    (``what``: ``"chains"``, ``"chains by orbits"``, ``"mechanisms"``, ``"mechanisms with input link"``),
    so a checkpoint can be matched to its query and plan without running it.

    >>> digest, words = count_identity(ChainQuery(1, 8)); len(digest), words
    (64, 'chains dof=1 links=8')
    """
    return _identity(what, plan_jobs(query)), _describe(what, query)


def _count(work, what: str, query: ChainQuery, workers, progress, checkpoint, scheduler, timeout, log,
           remember: bool = False, expected: tuple[str, float] | None = None) -> Counts:
    """Counts by code of ``work`` over the units of ``query``, resumable and on Dask if asked; with
    ``remember``, each code's counts read from the store of earlier runs, or kept there once found."""
    from contextlib import ExitStack, closing

    from ..execution.interrupt import ending_signals_unwind

    _check_workers(workers)
    if query.prismatic is not None and (checkpoint is not None or scheduler is not None):
        raise InvalidOption("chains with prismatic pairs are counted on this machine, without a checkpoint or a "
                            "scheduler")
    if remember and (checkpoint is not None or scheduler is not None):
        raise InvalidOption("counts are kept between runs only for a count on this machine without a checkpoint: "
                            "a checkpoint or a scheduler says where to work, and every unit is run")
    jobs = plan_jobs(query)
    names = [str(c) for c, _ in jobs]
    totals: dict[str, int] = {}
    stored = {i: found for i, job in enumerate(jobs) if remember
              for found in [recall("counts", repr((what, *job)))] if found is not None}
    for found in stored.values():
        for name, n in found.items():
            totals[name] = totals.get(name, 0) + n
    found_now: dict[int, dict[str, int]] = {}  # counts of the codes run here (with ``remember``)
    units_run, by_search, shared = 0, {}, 0  # the units run here, those counted by the search instead of by orbits,
    # and those a second count counted by the first count's path
    with ExitStack() as stack:
        # a kill (SIGTERM, SIGHUP) unwinds the count before it ends the process, as Ctrl-C does: its pool ended,
        # its temporary folder of units removed (the command has its own handler; a script calling this has none)
        stack.enter_context(ending_signals_unwind())
        client = None
        if scheduler is not None:  # (before the checkpoint: an unreachable scheduler leaves no file behind)
            from ..execution.scheduler import connect

            client = connect(scheduler, timeout)
            stack.callback(client.close)
        ck = None
        if checkpoint is not None:
            from ..execution.checkpoint import Checkpoint

            identity = _identity(what, jobs)
            if client is None:  # (before the checkpoint is opened: a refusal leaves no new file)
                kept_units_folder(checkpoint, make=False)
            ck = stack.enter_context(Checkpoint(checkpoint, identity, _describe(what, query), log=log))
            for name, n in list(ck.codes.items()) + list(ck.unit_counts.items()):
                totals[name] = totals.get(name, 0) + n
        events = stack.enter_context(closing(_map_units(
            work, jobs, workers, progress, client=client,
            skip_code=(lambda i: names[i] in ck.codes) if ck else stored.__contains__,
            skip_unit=(lambda u: ck.has_unit(u.key)) if ck else None, ordered=False, expected=expected,
            before={"units": ck.resumed_units if ck else 0, "chains": sum(totals.values())},
            kept=(kept_units_folder(checkpoint), identity) if ck and client is None else None)))
        for index, unit, result in events:
            if unit is None:
                if ck is not None:
                    ck.finish_code(names[index], totals.get(names[index], 0), units=result)
                if remember:  # every unit of the code ran here: its counts are whole
                    keep("counts", repr((what, *jobs[index])), found_now.pop(index, {}))
                continue
            units_run += 1
            why = getattr(result, "by_search", None)  # (a count by orbits says where it counted by the search)
            if why is not None:
                by_search[why] = by_search.get(why, 0) + 1
            shared += getattr(result, "shared", False)
            for name, n in result.items():
                totals[name] = totals.get(name, 0) + n
                if remember:
                    found_now.setdefault(index, {})[name] = found_now.get(index, {}).get(name, 0) + n
            if ck is not None:
                ck.add_unit(unit.key, names[index], result.get(names[index], 0), shared=getattr(result, "shared", False))
    order = {name: i for i, name in enumerate(dict.fromkeys(names))}
    def place(name: str):  # plan order of the code, then its numbers of prismatic pairs and meshes
        code, *kinds = name.split(" ")
        return order.get(code, 0), [(k[0], int(k[1:])) for k in kinds]

    by_code = {name: totals[name] for name in sorted(totals, key=place) if totals[name]}
    return Counts(sum(by_code.values()), by_code, units_run, dict(sorted(by_search.items())), shared)


def count_chains(query: ChainQuery | int | None = None, links: int | None = None, *, workers: int | None = None,
                 progress: bool = False, checkpoint=None, scheduler: str | None = None, timeout: float = 5.0,
                 log=None, remember: bool = False, method: str = "listing",
                 expected: tuple[str, float] | None = None, **options) -> Counts:
    """How many chains :func:`type_synthesis` gives, in all and by code (:class:`Counts`).

    Chains are counted by the processes that find them, so memory stays flat however many there are.
    With ``checkpoint`` (a file path) finished units are committed as they finish and a rerun
    with the same file resumes (see :mod:`synth.execution.checkpoint`); with ``scheduler`` (a Dask
    address such as ``tcp://host:8786``) the units run on that cluster.  With ``remember`` (what the
    command line does), each code's counts are kept in the store of solver results
    (:mod:`synth.execution.memo`) once found, and a later count of the same code reads them
    instead of running its units (not with a checkpoint or a scheduler, which ask for the units run).
    ``method`` (:data:`COUNT_METHODS`): ``"listing"`` counts what stage B lists; ``"orbits"``
    counts each unit by Burnside's lemma where that applies (simple joints, no crank requirement,
    the group of H listed whole) and as the listing does elsewhere (the result's ``by_search`` says
    how many units, and why); ``"tight-reverse"`` is a second
    count sharing as little of the listing's arithmetic as can be arranged (simple joints only,
    :func:`~synth.synthesis.stage_b.count_reversed`); all give the same counts, each kept apart in
    the store and in a checkpoint.
    ``expected``: a counter and the total an estimate expects of it (``("units", 8.5e6)``:
    :func:`~synth.synthesis.estimate.time_to_go_from`), from whose share the progress reckons the time to go.

    >>> count_chains(1, 8, workers=1).to_dict()
    {'count': 16, 'by_code': {'440/0': 9, '521/0': 5, '602/0': 2}}
    >>> count_chains(1, 10, workers=1, method="orbits").count
    230
    >>> count_chains(1, 4, prismatic="0..4", workers=1)["by_code"]   # the all-prismatic loop has W = 2
    {'4/0': 1, '4/0 P1': 1, '4/0 P2': 2}
    """
    query = ChainQuery.of(query, links, **options)
    _check_method(method, query)
    # the store and a checkpoint keep each method's counts apart: a count by one never stands for the other
    work, what = (count_unit, "chains") if method == "listing" else (_ChainCount(method), f"chains by {method}")
    return _count(work, what, query, workers, progress, checkpoint, scheduler, timeout, log, remember, expected)


def count_mechanisms(query: ChainQuery | int | None = None, links: int | None = None, *, input_link: bool = False,
                     workers: int | None = None, progress: bool = False, checkpoint=None,
                     scheduler: str | None = None, timeout: float = 5.0, log=None, **options) -> Counts:
    """How many mechanisms :func:`mechanisms` gives, in all and by code (options as :func:`count_chains`).

    >>> count_mechanisms(1, 8, workers=1)["count"]
    71
    """
    query = ChainQuery.of(query, links, **options)
    _no_input_of_trusses(query, input_link)
    what = "mechanisms with input link" if input_link else "mechanisms"
    return _count(_MechanismCount(input_link, query.cylinders), what, query, workers, progress, checkpoint,
                  scheduler, timeout, log)


def _no_input_of_trusses(query: ChainQuery, input_link: bool) -> None:
    """Refuse input links of a query whose chains have W = 0: trusses on a frame, nothing to drive."""
    if input_link and query.dof == 0:
        from ..structure.trusses import truss_has_no_input

        raise truss_has_no_input("the chains of this query have")


def mechanisms_of(chain: Chain, *, input_link: bool = False, cylinders=()) -> list[Mechanism]:
    """Distinct mechanisms of one chain: a fixed link per automorphism orbit (and input links);
    with ``cylinders`` (``(("floating", (1, 1)), …)``, see :class:`ChainQuery`) only those whose
    prismatic pairs are of those kinds.

    ``input_link`` of a chain of W = 0 by the count raises :class:`InvalidOption`, as the command line
    refuses ``--input-link``: fixed by a link such a chain is a truss and nothing moves (or, given by hand,
    its count misleads and an input link is chosen by the count).  The mechanisms without an input link
    would be a silent answer to another question, which a caller mixing chains of W = 0 and W ≥ 1 asks
    by ``input_link=chain.dof != 0``.

    >>> [m.frame for m in mechanisms_of(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"))]  # Watt I and II
    [0, 2]
    >>> [m.frame for m in mechanisms_of(Chain.parse("0-1 1-2 2=3 3-0"), cylinders=["swinging=1"])]
    [0]
    >>> mechanisms_of(Chain.parse("0-3 0-4 1-3 1-4 2-3 2-4"), input_link=True)
    Traceback (most recent call last):
    synth.errors.InvalidOption: the chain 0-3 0-4 1-3 1-4 2-3 2-4 has W = 0 by the count: on a frame a truss is a statically determinate structure, it does not move, so input_link has no link to drive (list them without it)
    """
    from ..structure.kinds import prismatic_roles
    from ..structure.query import parse_cylinders

    if input_link and chain.dof == 0:  # (the sub-chain test only on the way out: it costs a listing nothing)
        from ..structure.trusses import count_defect, truss_has_no_input

        raise truss_has_no_input(f"the chain {chain.compact()} has", defect=count_defect(chain))
    wanted = parse_cylinders(cylinders)
    out = []
    for orbit in chain.link_orbits:
        frame = orbit[0]
        if not input_link:
            found = [Mechanism(chain, frame)]
        else:
            orbits = chain.automorphisms([frame])[2]
            neighbours = sorted({x for j in chain.joints if frame in j for x in j if x != frame})
            reps: dict[int, int] = {}
            for x in neighbours:
                reps.setdefault(orbits[x], x)
            found = [Mechanism(chain, frame, x) for x in sorted(reps.values())]
        if wanted:
            roles = prismatic_roles(chain, frame)
            if not all(lo <= roles[kind] <= (roles[kind] if hi is None else hi) for kind, (lo, hi) in wanted):
                continue
        out += found
    return out


def mechanisms(query: ChainQuery | int | None = None, links: int | None = None, *, input_link: bool = False,
               workers: int | None = None, progress: bool = False, **options) -> Iterator[Mechanism]:
    """Every mechanism (chain + fixed link, optionally + input link) up to symmetry; with
    ``cylinders`` in the query, those whose prismatic pairs are guides, swinging or floating
    cylinders as asked.

    >>> sum(1 for _ in mechanisms(1, 6, workers=1))
    5
    """
    query = ChainQuery.of(query, links, **options)
    _no_input_of_trusses(query, input_link)
    for chain in type_synthesis(query, workers=workers, progress=progress):
        yield from mechanisms_of(chain, input_link=input_link, cylinders=query.cylinders)
