"""Type synthesis: every non-isomorphic chain (and mechanism) for W, n and v.

Work is split into independent *units* (one code's branch-multigraph enumeration,
then one branch multigraph's binary-link distribution), run inline or on a
process pool; the output order is fixed by (code, multigraph certificate, chain
certificate), so it does not depend on the number of workers.

Example
-------
>>> sum(1 for _ in type_synthesis(1, 8, workers=1))
16
>>> count_chains(1, 6, v=(0, 2), workers=1)["by_code"]
{'42/0': 2, '51/1': 1, '60/2': 1}
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass

from ..execution.executor import process_pool, run_plan
from .number_synthesis import number_synthesis, parse_range, parse_requirements
from ._realise import Contracted, Conventions, contracted_graphs, count_realised, realise
from ..structure.chain import Chain, Mechanism
from ..structure.code import Code
from ..structure._params import check_motion_space
from ..errors import ImpossibleParameters, InvalidOption, QueryTooLarge

__all__ = ["Conventions", "Unit", "plan_codes", "plan_units", "plan_many", "type_synthesis", "count_chains", "count_mechanisms", "mechanisms", "mechanisms_of", "run_unit"]


# Stages A and B write one sub-chain condition per set of branch vertices: 2^m of them;
# m = 18 gives 262 144, the most a model is allowed to hold.
_MAX_BRANCH = 18
# A query runs inline for this long before it starts a pool, if no code has more branch
# vertices than _INLINE_BRANCH (stage A of such a code takes milliseconds: 8 at 12 links).
_INLINE_SECONDS = 0.25
_INLINE_BRANCH = 8


def _branch_vertices(code: Code) -> int:
    """Links with 3+ joints and multiple joints: the vertices of the branch multigraph H."""
    return code.links - code.count(2) + sum(code.composition or ())


@dataclass(frozen=True)
class Unit:
    """One independent piece of work: the chains of ``code`` whose branch multigraph is ``contracted``.

    ``contracted`` is None for a code without branch vertices (the single loop).
    """

    code: Code
    contracted: Contracted | None
    conventions: Conventions

    @property
    def key(self) -> str:
        """Stable name of the unit (code, multigraph certificate and, where h ≠ 3, the motion
        space), used by atlases and checkpoints to resume."""
        space = "" if self.conventions.h == 3 else f"|h{self.conventions.h}"
        return f"{self.code}|{self.contracted.certificate if self.contracted else 'loop'}{space}"


def _conventions(dof: int, rigid_subchains: bool | None, fractionated: bool, planar_only: bool,
                 cranks: Mapping | Iterable[str] | None, h: int = 3) -> Conventions:
    if rigid_subchains is None:
        rigid_subchains = dof == 0
    return Conventions(bool(rigid_subchains), bool(fractionated), bool(planar_only), _parse_cranks(cranks), h)


def _parse_cranks(cranks: Mapping | Iterable[str] | None) -> tuple[tuple[int, int], ...]:
    """``{5: 5}`` or ``["5=5"]``: a link with 5 joints carrying at least 5 cranks."""
    if not cranks:
        return ()
    pairs = cranks.items() if isinstance(cranks, Mapping) else (str(c).split("=", 1) for c in cranks)
    out = []
    for pair in pairs:
        try:
            i, c = (int(x) for x in pair)
        except (TypeError, ValueError):
            text = "=".join(map(str, pair))
            raise InvalidOption(f"cranks are written I=C (a link with I joints carrying C cranks), not {text!r}") from None
        if i < 1 or c < 1 or c > i:
            raise ImpossibleParameters(f"a link with {i} joints cannot carry {c} cranks")
        out.append((i, c))
    return tuple(sorted(out))


def _with_crank_links(require, conv: Conventions):
    """A crank requirement needs a link with I joints: say so to number synthesis too."""
    if not conv.cranks:
        return require
    from .number_synthesis import parse_requirements

    merged = parse_requirements(require)
    for i, c in conv.cranks:
        lo, hi = merged.get(i, (0, None))
        if hi == 0:
            raise ImpossibleParameters(f"cranks {i}={c} need a link with {i} joints, but the requirement n{i} = 0 "
                                       "forbids one")
        merged[i] = (max(lo, 1), hi)
    return merged


def plan_codes(
    dof: int,
    links: int | None = None,
    *,
    v: int | tuple | str | None = None,
    code: Code | str | None = None,
    fractionated: bool = True,
    rigid_subchains: bool = False,
    require: Mapping | Iterable[str] | None = None,
    h: int = 3,
    n1: int | tuple | str = 0,
    max_multiplicity: int | None = None,
) -> list[Code]:
    """The codes (with joint composition) a chain query covers, in output order.

    A link of a non-fractionated closed part carries at most K+1 joints, of a fractionated
    one at most 2K, and an open chain's link at most n1 more (each further joint leads to a
    branch with a single-joint link of its own); a non-degenerate closed chain with W = 1 is
    never fractionated (its parts would each need W ≥ 1).

    >>> [str(c) for c in plan_codes(1, 8)]
    ['440/0', '521/0', '602/0']
    >>> [str(c) for c in plan_codes(4, 7, n1=2, v=2)]  # the robot arm of two grippers: 2|5/2 as two joint compositions
    ['2|5/0-1', '2|5/2']
    """
    if max_multiplicity is None and (rigid_subchains or fractionated and not (dof == 1 and n1 in (0, None))):
        # the limit theorem (a joint of order ≤ K closed, ≤ K + W open) holds for chains that are neither
        # fractionated nor degenerate (a non-degenerate closed 1-DOF chain is never fractionated);
        # other conventions have chains beyond it (a 4-link joint carrying two 4-link loops: W = 3, K = 2)
        max_multiplicity = (links if code is None else Code.parse(code).links if isinstance(code, str) else code.links)
    if code is not None:
        code = Code.parse(code) if isinstance(code, str) else code
        _check_code_against(code, v, require)
        if n1 not in (0, None) and parse_range(n1, "n1") != (code.n1, code.n1):
            raise ImpossibleParameters(f"code {code} has n1 = {code.n1}, not the requested n1 = {n1}")
        if code.dof(h) != dof:
            raise ImpossibleParameters(f"code {code} gives W = {code.dof(h)} with h = {h}, not the requested W = {dof}")
        if links is not None and code.links != links:
            raise ImpossibleParameters(f"code {code} has {code.links} links, not {links}")
        exact = {i: (code.count(i), code.count(i)) for i in range(2, code.max_degree + 1)}
        codes = number_synthesis(dof, links=code.links, v=code.v, compositions=True, h=h, n1=code.n1,
                                 max_link_degree=max(code.max_degree, 2), require=exact,
                                 max_multiplicity=max_multiplicity)
        return [c for c in codes if code.composition is None or c.composition == code.composition]
    if links is None:
        raise InvalidOption("give the number of links (or a code)")
    rng = parse_range(0 if v is None else v, "v")
    n1_lo, n1_hi = parse_range(0 if n1 is None else n1, "n1")
    n1_hi = links if n1_hi is None else n1_hi
    K = max(0, (links - dof - 1) // (h - 1))
    closed, why = (2 * K, "2K, fractionated chains included") if fractionated and (dof >= 2 or rigid_subchains) \
        else (K + 1, "K+1")
    imax = closed + n1_hi
    if n1_hi:
        why += f", and {n1_hi} more for single-joint links"
    for i, (lo, _) in parse_requirements(require).items():
        if i > imax and lo > 0 and K >= 1:
            raise ImpossibleParameters(
                f"no chain with W = {dof} and {links} links has a link with {i} joints: with K = {K} loops a link "
                f"carries at most {imax} ({why})")
    return number_synthesis(dof, links=links, v=rng, compositions=True, max_link_degree=max(imax, K + 1),
                            require=require, h=h, n1=(n1_lo, n1_hi), max_multiplicity=max_multiplicity)


def _check_code_against(code: Code, v, require) -> None:
    """Refuse a code that contradicts the other options of the same query (``v``, requirements)."""
    if v is not None:
        lo, hi = parse_range(v, "v")
        if not lo <= code.v <= (code.v if hi is None else hi):
            shown = f"{lo}" if lo == hi else f"{lo}..{'' if hi is None else hi}"
            raise ImpossibleParameters(f"code {code} has v = {code.v}, outside the requested v = {shown}")
    for i, (lo, hi) in parse_requirements(require).items():
        n_i = code.count(i)
        if n_i < lo or (hi is not None and n_i > hi):
            shown = f"{lo}" if lo == hi else f"{lo}..{'' if hi is None else hi}"
            raise ImpossibleParameters(
                f"code {code} has {n_i} link(s) with {i} joints, but the requirement asks for n{i} = {shown}")


def _stage_a(args) -> list[Unit]:
    code, conv = args
    if code.count(2) == code.links and code.v == 0:  # a single loop of binary links
        return [Unit(code, None, conv)]
    return [Unit(code, h, conv) for h in contracted_graphs(code, conv)]


def run_unit(unit: Unit, stats: dict | None = None) -> list[Chain]:
    """The chains of one unit, sorted by certificate (deterministic)."""
    if unit.contracted is None:
        n = unit.code.links
        return [Chain(n, tuple((i, (i + 1) % n) for i in range(n)), h=unit.conventions.h)] if n >= 3 else []
    return realise(unit.code, unit.contracted, unit.conventions, stats)


def _validate(dof, links, workers):
    if isinstance(dof, bool) or not isinstance(dof, int) or dof < 0:
        raise ImpossibleParameters(f"the degree of freedom W must be 0 or more, not {dof!r}")
    if links is not None and (isinstance(links, bool) or not isinstance(links, int) or links < 1):
        raise ImpossibleParameters(f"the number of links must be 1 or more, not {links!r}")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InvalidOption(f"workers must be a whole number ≥ 1, not {workers!r}")


def plan_units(
    dof: int,
    links: int | None = None,
    *,
    v: int | tuple | str | None = None,
    code: Code | str | None = None,
    rigid_subchains: bool | None = None,
    fractionated: bool = True,
    planar_only: bool = False,
    require: Mapping | Iterable[str] | None = None,
    cranks: Mapping | Iterable[str] | None = None,
    h: int = 3,
    n1: int | tuple | str = 0,
    max_multiplicity: int | None = None,
    workers: int | None = 1,
) -> list[Unit]:
    """The independent work units of a chain query, in output order.

    Stage A (one CP-SAT model per code) runs inline, or on ``workers`` processes.
    ``run_unit(u)`` for every unit, concatenated, equals ``list(type_synthesis(...))``.

    >>> units = plan_units(1, 8); [u.key.split("|")[0] for u in units]
    ['440/0', '440/0', '521/0', '602/0']
    >>> sum(len(run_unit(u)) for u in units)
    16
    """
    _validate(dof, links, workers)
    query = dict(dof=dof, links=links, v=v, code=code, rigid_subchains=rigid_subchains, fractionated=fractionated,
                 planar_only=planar_only, require=require, cranks=cranks, h=h, n1=n1,
                 max_multiplicity=max_multiplicity)
    workers = workers or os.cpu_count() or 1
    if workers == 1:
        return plan_many([query])[0]
    pool = process_pool(workers)
    try:
        return plan_many([query], pool=pool)[0]
    finally:
        pool.terminate()
        pool.join()


def plan_many(queries: Iterable[Mapping], *, pool=None, skip_impossible: bool = False) -> list[list[Unit]]:
    """:func:`plan_units` for several queries at once: stage A of all their codes in one batch.

    ``queries`` are keyword dictionaries of :func:`plan_units` (with ``dof`` and ``links``);
    ``pool`` is an optional ``multiprocessing`` pool that runs stage A; with
    ``skip_impossible`` a query the counting equations rule out gets no units instead of
    raising :class:`ImpossibleParameters`.

    >>> [len(units) for units in plan_many([dict(dof=1, links=8), dict(dof=1, links=9)], skip_impossible=True)]
    [4, 0]
    """
    queries = list(queries)
    jobs, owners = [], []
    for index, query in enumerate(queries):
        codes, conv = _codes_of(query, skip_impossible)
        jobs += [(c, conv) for c in codes]
        owners += [index] * len(codes)
    plans: list[list[Unit]] = [[] for _ in queries]
    batches = pool.imap(_stage_a, jobs) if pool is not None else map(_stage_a, jobs)
    for owner, batch in zip(owners, batches):
        plans[owner].extend(batch)
    return plans


def _codes_of(query: Mapping, skip_impossible: bool = False) -> tuple[list[Code], Conventions]:
    """Number synthesis of one chain query: its codes (in output order) and conventions."""
    q = dict(query)
    dof, links = q.pop("dof"), q.pop("links", None)
    h = q.pop("h", 3)
    check_motion_space(h, lowest=2)  # h = 1 (elastic couplings) has no chains to build
    conv = _conventions(dof, q.pop("rigid_subchains", None), q.get("fractionated", True),
                        q.pop("planar_only", False), q.pop("cranks", None), h)
    try:
        codes = plan_codes(dof, links, v=q.pop("v", None), code=q.pop("code", None),
                           fractionated=q.pop("fractionated", True), rigid_subchains=conv.rigid_subchains,
                           require=_with_crank_links(q.pop("require", None), conv), h=h, n1=q.pop("n1", 0),
                           max_multiplicity=q.pop("max_multiplicity", None))
    except ImpossibleParameters:
        if not skip_impossible:
            raise
        codes = []
    if q:
        raise InvalidOption(f"unknown option(s) for a chain query: {', '.join(sorted(q))}")
    for code in codes:
        branch = _branch_vertices(code)
        if branch > _MAX_BRANCH:
            raise QueryTooLarge(f"code {code} has {branch} branch vertices (links with 3+ joints and multiple "
                                f"joints); its branch-multigraph model would need 2^{branch} sub-chain conditions, "
                                f"more than this engine builds (at most {_MAX_BRANCH} branch vertices)")
    return codes, conv


def type_synthesis(
    dof: int,
    links: int | None = None,
    *,
    v: int | tuple | str | None = None,
    code: Code | str | None = None,
    rigid_subchains: bool | None = None,
    fractionated: bool = True,
    planar_only: bool = False,
    require: Mapping | Iterable[str] | None = None,
    cranks: Mapping | Iterable[str] | None = None,
    h: int = 3,
    n1: int | tuple | str = 0,
    max_multiplicity: int | None = None,
    workers: int | None = None,
    progress: bool = False,
) -> Iterator[Chain]:
    """Every non-isomorphic chain with mobility ``dof`` and ``links`` links, in motion space ``h``.

    Parameters
    ----------
    dof : int
        W (0 for trusses).
    links : int
        n, the frame included (or give ``code``).
    v : int or range
        Multiple-joint count(s), default 0 (simple joints) or, with ``code``, the code's own; ``(0, 4)`` or ``"0..4"`` for a range.
    code : Code or str, optional
        Only this code (with or without composition).
    rigid_subchains : bool, optional
        Allow rigid sub-chains (W(S) ≥ 0); default True for W = 0, else False (non-degenerate).
    fractionated : bool
        Keep chains that a link or joint splits in two (default True).
    planar_only : bool
        Keep only chains with planar graphs.
    require : design constraints ``"I=N"`` etc. on the link assortment (see number_synthesis).
    cranks : mapping I -> C or strings ``"I=C"``
        Required sub-structure: a link with I joints carrying at least C cranks (binary links
        jointed to it), a constraint of the CP-SAT model (e.g. ``{5: 5}``: five parallel cranks
        on a 5-joint frame).
    h : int
        Motion space of the loops, 2 … 6 (default 3: planar and spherical; 6 general spatial).
    n1 : int or range
        Single-joint links (open chains: robot arms, grippers); default 0 (closed chains).
    max_multiplicity : int, optional
        Most links on one joint; default the limit theorem's K + 1 (closed) or K + W + 1 (open) for
        chains that are neither fractionated nor degenerate (where it holds), else no limit.
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
    _validate(dof, links, workers)
    query = dict(dof=dof, links=links, v=v, code=code, rigid_subchains=rigid_subchains, fractionated=fractionated,
                 planar_only=planar_only, require=require, cranks=cranks, h=h, n1=n1,
                 max_multiplicity=max_multiplicity)
    codes, conv = _codes_of(query)
    for _, unit, chains in _map_units(run_unit, codes, conv, workers, progress):
        if unit is not None:
            yield from chains


def _map_units(work, codes: list[Code], conv: Conventions, workers: int | None, progress: bool, *,
               client=None, skip_code=None, skip_unit=None, ordered: bool = True) -> Iterator[tuple]:
    """``(code index, unit, work(unit))`` for every unit of ``codes``, then ``(index, None, units)``
    when a code is complete: inline for a small query, else streamed to a process pool (or a
    Dask ``client``) with a bounded number of tasks in flight (see :mod:`synth.execution.executor`);
    in plan order, or as units finish with ``ordered=False``.

    ``work`` returns the unit's chains or a (code, count) pair; the progress bar adds up either.
    """
    workers = workers or os.cpu_count() or 1
    bar = None
    if progress and sys.stderr.isatty():  # tqdm shows nothing elsewhere: do not even import it
        from tqdm import tqdm

        bar = tqdm(total=len(codes), unit=" codes", file=sys.stderr, leave=False)
    try:
        found = 0
        # stage A of one code grows steeply with its branch vertices (12 at 16 links: minutes):
        # a plan with such codes goes to the pool at once, a smaller one starts inline
        inline = _INLINE_SECONDS if max(map(_branch_vertices, codes), default=0) <= _INLINE_BRANCH else 0.0
        for event in run_plan([(c, conv) for c in codes], _stage_a, work, workers=workers, client=client,
                              skip_item=skip_code, skip_unit=skip_unit, inline_seconds=inline, ordered=ordered):
            if bar is not None:
                if event[1] is None:
                    bar.update(1)
                else:
                    found += event[2][1] if isinstance(event[2], tuple) else len(event[2])
                    bar.set_postfix(chains=found, refresh=False)
            yield event
    finally:
        if bar is not None:
            bar.close()


def _count_unit(unit: Unit) -> tuple[str, int]:
    """(code, number of chains) of one unit: counted where it is computed (every chain of a unit has its code),
    without building the chains where stage B's solutions are already one per chain."""
    if unit.contracted is None:
        return str(unit.code), len(run_unit(unit))
    return str(unit.code), count_realised(unit.code, unit.contracted, unit.conventions)


def _count_unit_mechanisms(unit: Unit, input_link: bool = False) -> tuple[str, int]:
    return str(unit.code), sum(len(mechanisms_of(c, input_link=input_link)) for c in run_unit(unit))


def _count_unit_mechanisms_with_input(unit: Unit) -> tuple[str, int]:
    return _count_unit_mechanisms(unit, input_link=True)


def _identity(what: str, codes: list[Code], conv: Conventions) -> str:
    """What a count computes, as a digest: the same codes and conventions give the same units."""
    import hashlib

    text = repr((what, [str(c) for c in codes], conv))
    return hashlib.sha256(text.encode()).hexdigest()


def _describe(what: str, query: Mapping) -> str:
    words = [what] + [f"{k}={v}" for k, v in query.items() if v not in (None, (), [], {}, False)]
    return " ".join(words).replace("'", "")


def _count(work, what: str, query: dict, workers, progress, checkpoint, scheduler, timeout, log) -> dict:
    """Counts by code of ``work`` over the units of ``query``, resumable and on Dask if asked."""
    from contextlib import ExitStack

    _validate(query["dof"], query.get("links"), workers)
    codes, conv = _codes_of(query)
    names = [str(c) for c in codes]
    totals = dict.fromkeys(names, 0)
    with ExitStack() as stack:
        ck = None
        if checkpoint is not None:
            from ..execution.checkpoint import Checkpoint

            ck = stack.enter_context(Checkpoint(checkpoint, _identity(what, codes, conv), _describe(what, query),
                                                log=log))
            for name, n in ck.codes.items():
                totals[name] += n
            for name, n in ck.units.values():
                totals[name] += n
        client = None
        if scheduler is not None:
            from ..execution.scheduler import connect

            client = connect(scheduler, timeout)
            stack.callback(client.close)
        events = _map_units(work, codes, conv, workers, progress, client=client,
                            skip_code=(lambda i: names[i] in ck.codes) if ck else None,
                            skip_unit=(lambda u: u.key in ck.units) if ck else None, ordered=False)
        for index, unit, result in events:
            if unit is None:
                if ck is not None:
                    ck.finish_code(names[index], totals[names[index]], units=result)
                continue
            name, n = result
            totals[name] += n
            if ck is not None:
                ck.add_unit(unit.key, name, n)
    by_code = {name: n for name, n in totals.items() if n}
    return {"count": sum(by_code.values()), "by_code": by_code}


def count_chains(dof: int, links: int | None = None, *, workers: int | None = None, progress: bool = False,
                 checkpoint=None, scheduler: str | None = None, timeout: float = 5.0, log=None,
                 **selection) -> dict:
    """``{"count": N, "by_code": {code: count}}`` for the chains of :func:`type_synthesis`.

    Chains are counted by the processes that find them, so memory stays flat however many there are.
    With ``checkpoint`` (a file path) finished units are committed as they finish and a rerun
    with the same file resumes (see :mod:`synth.execution.checkpoint`); with ``scheduler`` (a Dask
    address such as ``tcp://host:8786``) the units run on that cluster.

    >>> count_chains(1, 8, workers=1)
    {'count': 16, 'by_code': {'440/0': 9, '521/0': 5, '602/0': 2}}
    """
    return _count(_count_unit, "chains", dict(dof=dof, links=links, **selection), workers, progress, checkpoint,
                  scheduler, timeout, log)


def count_mechanisms(dof: int, links: int | None = None, *, input_link: bool = False, workers: int | None = None,
                     progress: bool = False, checkpoint=None, scheduler: str | None = None, timeout: float = 5.0,
                     log=None, **selection) -> dict:
    """``{"count": N, "by_code": {code: count}}`` for the mechanisms of :func:`mechanisms` (options as
    :func:`count_chains`).

    >>> count_mechanisms(1, 8, workers=1)["count"]
    71
    """
    work = _count_unit_mechanisms_with_input if input_link else _count_unit_mechanisms
    what = "mechanisms with input link" if input_link else "mechanisms"
    return _count(work, what, dict(dof=dof, links=links, **selection), workers, progress, checkpoint, scheduler,
                  timeout, log)


def mechanisms_of(chain: Chain, *, input_link: bool = False) -> list[Mechanism]:
    """Distinct mechanisms of one chain: a fixed link per automorphism orbit (and input links).

    >>> [m.frame for m in mechanisms_of(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"))]  # Watt I and II
    [0, 2]
    """
    out = []
    for orbit in chain.link_orbits:
        frame = orbit[0]
        if not input_link:
            out.append(Mechanism(chain, frame))
            continue
        orbits = chain.automorphisms([frame])[2]
        neighbours = sorted({x for j in chain.joints if frame in j for x in j if x != frame})
        reps: dict[int, int] = {}
        for x in neighbours:
            reps.setdefault(orbits[x], x)
        out += [Mechanism(chain, frame, x) for x in sorted(reps.values())]
    return out


def mechanisms(dof: int, links: int | None = None, *, input_link: bool = False, **kwargs) -> Iterator[Mechanism]:
    """Every mechanism (chain + fixed link, optionally + input link) up to symmetry.

    >>> sum(1 for _ in mechanisms(1, 6, workers=1))
    5
    """
    for chain in type_synthesis(dof, links, **kwargs):
        yield from mechanisms_of(chain, input_link=input_link)
