"""Prismatic pairs on revolute chains: every assignment up to symmetry that the exact test keeps.

A prismatic (P) pair fixes the relative rotation of its links, so a loop of P pairs only is a
wedge loop that gives one freedom back: a chain with K_2 = k wedge loops has the mobility of
its revolute skeleton plus k (docs/theory.md, "What W means with prismatic pairs").  Type
synthesis builds the skeletons of mobility W − k (with that *slack* in the sub-chain rule)
and :func:`assignments` puts the P pairs on them; :func:`prismatic_variants` does the same for
one given chain, whatever mobility its variants reach.

Example
-------
>>> from synth.structure.chain import Chain
>>> four_bar = Chain.parse("0-1 1-2 2-3 3-0")
>>> [len(prismatic_variants(four_bar, k)) for k in range(5)]     # slider-crank, ..., wedge loop
[1, 1, 2, 0, 1]
>>> [v.dof for v in prismatic_variants(four_bar, 4)]
[2]
"""

from __future__ import annotations

from itertools import combinations

from ..errors import InvalidOption
from ..structure.chain import Chain
from ..structure.joints import PRISMATIC, REVOLUTE
from ..structure.kinds import cycle_rank, motion
from ..structure.subchains import check_subchains
from .stage_a import Conventions

__all__ = ["assignments", "prismatic_variants", "variants_of"]


def _admissible(variant: Chain, rigid: bool, idle: bool, counted: bool = False) -> bool:
    """The exact sub-chain test with joint kinds (no rigid or over-constrained sub-chain, no
    redundant constraint hidden from the count), and no idle joint unless ``idle`` (a truss, W = 0,
    moves nowhere: idleness means nothing there).  ``counted``: the sub-chains' counts are known
    to pass (prismatic pairs without a wedge loop add nothing to a revolute chain that passes),
    so only the hidden redundancy is left to look at: the generic mobility against the count."""
    if counted:
        if motion(variant)[0] != variant.dof:
            return False
    elif not check_subchains(variant, rigid_subchains=rigid).ok:
        return False
    return idle or variant.dof == 0 or not motion(variant)[1]


def _assign(chain: Chain, counts, keep, first=None, *, candidates=None) -> list[Chain]:
    """Every assignment of P pairs (a count in ``counts``) to the simple joints of ``chain`` (or to
    the joints ``candidates``) that ``keep(variant)`` accepts, once per symmetry class
    (certificates with the joint kinds as colours), sorted by certificate.  ``first(pairs)``, a
    cheap test of the P pairs alone, runs before the certificate."""
    simple = [k for k, j in enumerate(chain.joints) if len(j) == 2] if candidates is None else candidates
    seen: dict[str, Chain | None] = {}
    for count in counts:
        for chosen in combinations(simple, count):
            if first is not None and not first([chain.joints[k] for k in chosen]):
                continue
            kinds = [REVOLUTE] * len(chain.joints)
            for k in chosen:
                kinds[k] = PRISMATIC
            variant = Chain.trusted(chain.links, chain.joints, chain.h, kinds)
            certificate = variant.certificate
            if certificate not in seen:
                seen[certificate] = variant if keep(variant) else None
    return [seen[c] for c in sorted(seen) if seen[c] is not None]


def assignments(skeleton: Chain, conv: Conventions) -> list[Chain]:
    """The chains a unit of a query with prismatic pairs gives for one revolute skeleton: every
    assignment of ``conv.prismatic`` P pairs with exactly ``conv.slack`` wedge loops that passes the
    exact test with its joint kinds (so its mobility is the skeleton's plus ``conv.slack``).

    >>> conv = Conventions(slack=1, prismatic=(1, 6))
    >>> [v.compact() for v in assignments(Chain.parse("0-1 1-2 2-0 2-3 3-4 4-0"), conv)]   # Task 3
    ['0=1 0=2 0-4 1=2 2-3 3-4', '0=1 0=2 0-4 1=2 2-3 3=4', '0=1 0=2 0=4 1=2 2-3 3-4']
    """
    lo, hi = conv.prismatic
    candidates = [k for k, j in enumerate(skeleton.joints) if len(j) == 2]
    if conv.cylinders_only:  # every prismatic pair a cylinder: between two binary links
        degree = skeleton.degrees
        candidates = [k for k in candidates if degree[skeleton.joints[k][0]] == degree[skeleton.joints[k][1]] == 2]
    least = max(lo, conv.slack + 2 if conv.slack else 0)
    most = len(candidates) if hi is None else min(hi, len(candidates))
    return _assign(skeleton, range(least, most + 1),
                   lambda v: _admissible(v, conv.rigid_subchains, conv.idle_joints, counted=conv.slack == 0),
                   lambda pairs: cycle_rank(range(skeleton.links), pairs) == conv.slack, candidates=candidates)


def prismatic_variants(chain: Chain, count: int, *, idle: bool = False,
                       rigid_subchains: bool | None = None) -> list[Chain]:
    """Every assignment of ``count`` prismatic pairs to the simple joints of one chain, up to
    symmetry, that passes the exact test with joint kinds; each variant has its own mobility
    (the chain's plus its wedge loops).  Rigid sub-chains are allowed where the variant's W is 0
    (or as ``rigid_subchains`` says); idle joints only with ``idle``.

    >>> watt = Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1")
    >>> len(prismatic_variants(watt, 1)), len(prismatic_variants(watt, 2))
    (3, 8)
    """
    simple = [k for k, j in enumerate(chain.joints) if len(j) == 2]
    if isinstance(count, bool) or not isinstance(count, int) or count < 0:
        raise InvalidOption(f"the number of prismatic pairs must be a whole number ≥ 0, not {count!r}")
    if count > 0 and not simple:
        raise InvalidOption("prismatic pairs go on simple joints and this chain has multiple joints only")
    if count > len(simple):
        raise InvalidOption(f"{count} prismatic pairs asked for, but the chain has only {len(simple)} simple joints")
    if not chain.all_revolute:
        raise InvalidOption(f"the chain has joint kinds already ({chain.compact()}): give its revolute form")
    return _assign(chain, [count], lambda v: _admissible(
        v, v.dof == 0 if rigid_subchains is None else rigid_subchains, idle))


def variants_of(chains, counts: tuple[int, int | None], *, idle: bool = False):
    """Every prismatic variant, with A ≤ P pairs ≤ B for ``counts`` = (A, B), of each chain in turn.

    >>> from synth.structure.kinds import kind_count
    >>> [kind_count(c, "prismatic") for c in variants_of([Chain.parse("0-1 1-2 2-3 3-0")], (0, 9))]
    [0, 1, 2, 2, 4]
    """
    lo, hi = counts
    for chain in chains:
        simple = sum(1 for j in chain.joints if len(j) == 2)
        for k in range(lo, min(simple if hi is None else hi, simple) + 1):
            yield from prismatic_variants(chain, k, idle=idle)
