"""Structural analysis of a code or of explicit counts: W by every formula, K, Y, D, advice.

Example
-------
>>> a = analyze("64200/0", dof=1)
>>> (a.dof, a.loops, a.defect, a.criterion_holds)
(1, 5, 0, True)
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from mechbase import Row

from ..structure import check_dof, check_extra_mobility, check_motion_space
from ..structure.code import Code
from ..errors import ImpossibleParameters, InvalidOption

__all__ = ["Analysis", "analyze", "mobility", "not_for_the_subject"]


def not_for_the_subject(option: str, subject: str) -> InvalidOption:
    """The refusal of ``option`` (``--v``, ``--f``, ``--loop-classes``, or a scene's key so named) that the analysis
    of ``subject``, ``"chain"`` or ``"code"``, would ignore: a chain carries its links, joints, v and loop classes
    (a base of a higher class is written in its text after ``|``), a code its v.

    >>> print(not_for_the_subject("--loop-classes", "chain"))
    --loop-classes does not apply to a chain (it describes codes and counts): write a base of a higher class in the chain's text after '|' ('… | h5: 0 1 2 3', docs/exchange.md)
    >>> print(not_for_the_subject("--v", "code"))
    --v goes with explicit counts: a code carries its own v
    """
    if subject == "code":
        return InvalidOption(f"{option} goes with explicit counts: a code carries its own v")
    base = (": write a base of a higher class in the chain's text after '|' ('… | h5: 0 1 2 3', docs/exchange.md)"
            if "classes" in option else "")
    return InvalidOption(f"{option} does not apply to a chain (it describes codes and counts){base}")


def mobility(links: int, loops: int, *, h: int = 3, f: int = 0, loop_classes: Mapping[int, int] | None = None) -> int:
    """Pozhbelko (2a)/(2b): W = (n − 1) − Σ_h (h − 1)·K_h + f.

    >>> mobility(6, 1, h=5)   # Bricard / toroidal six-bar
    1
    >>> mobility(6, 1, h=6)   # the classical formula's "paradoxical" answer
    0
    """
    if loop_classes:
        return links - 1 - sum((int(hh) - 1) * int(k) for hh, k in loop_classes.items()) + f
    return links - 1 - (h - 1) * loops + f


@dataclass(frozen=True)
class Analysis(Row):
    """What the counting theory says about one code.

    ``formulas`` holds W computed by each applicable formula of docs/theory.md (they agree,
    and the tests check it); ``defect`` is D = W(counts) − W(required) and ``advice`` a
    sentence on how to reach D = 0 when it is not.
    """

    code: str
    links: int
    loops: int
    complexity: int
    joints: int
    simple_joint_equivalents: int
    v: int
    h: int
    f: int
    dof: int
    formulas: dict = field(default_factory=dict)
    required_dof: int | None = None
    defect: int | None = None
    criterion_holds: bool | None = None
    advice: str = ""

#: elementary edits of a chain and what each does to W = 3(n − 1) − 2p (planar): the advice names only these
RAISE_W = ("remove {k} binary link(s) with both their joints, or insert {k} binary link(s) into joints "
           "(a joint a–b becomes a–x–b); each raises W by 1")
LOWER_W = ("add {k} binary link(s), each jointed to two links already there, or take {k} binary link(s) out of "
           "their strings (a–x–b becomes a–b); each lowers W by 1")


def _advice(defect: int) -> str:
    """What to change for D = 0, in the edits of :mod:`synth.analysis.repair` (the repairs list such edits,
    each checked on a chain).

    >>> _advice(-1).split("; ")[1]
    'remove 1 binary link(s) with both their joints, or insert 1 binary link(s) into joints (a joint a–b becomes a–x–b)'
    """
    if defect == 0:
        return "D = 0: the counts have no redundant constraints for the required W."
    if defect > 0:
        return (f"D = {defect} > 0: the counts give {defect} degree(s) of freedom too many; "
                + LOWER_W.format(k=defect) + ".")
    return (f"D = {defect} < 0: the counts carry {-defect} redundant constraint(s); " + RAISE_W.format(k=-defect)
            + ".")


def analyze(
    code: Code | str | None = None,
    *,
    counts: Mapping[int, int] | None = None,
    v: int = 0,
    dof: int | None = None,
    h: int = 3,
    f: int = 0,
    loop_classes: Mapping[int, int] | None = None,
) -> Analysis:
    """Analyse a code (``"6301/0"``) or explicit counts ``{1: n1, 2: n2, …}`` with ``v``.

    Parameters
    ----------
    code : Code or str, optional
        The standard code; alternatively ``counts`` and ``v``.
    dof : int, optional
        Required W: the defect D and the criterion (W + 1) + 2K = n are computed for it.
    h, f, loop_classes :
        Motion space, extra pair mobility, heterogeneous loop classes.

    Examples
    --------
    >>> analyze(counts={1: 2, 2: 5}, v=2).dof          # open robot chain
    4
    >>> analyze(counts={2: 4}, f=1).dof                # loop with one 2-DOF pair
    2
    """
    if (code is None) == (counts is None):
        raise InvalidOption("give a code or explicit counts, not both or neither")
    if code is None:
        counts = {int(i): int(c) for i, c in counts.items()}  # (keys and counts as numbers or their text)
        if any(i < 1 or c < 0 for i, c in counts.items()):
            raise ImpossibleParameters("counts are n_i ≥ 0 for links with i ≥ 1 joints")
        top = max((i for i, c in counts.items() if c), default=2)
        assortment = tuple(counts.get(i, 0) for i in range(2, top + 1))
        code = Code(assortment, int(v), None, counts.get(1, 0))
    elif isinstance(code, str):
        code = Code.parse(code)
    check_motion_space(h), check_extra_mobility(f)
    if dof is not None:
        check_dof(dof)
    n, K = code.links, code.loops
    if n == 0:
        raise ImpossibleParameters(f"code {code} counts no link: a chain has links")
    if K < 0:
        raise ImpossibleParameters(f"code {code} has fewer joints than a connected chain of {n} links needs")
    if loop_classes and sum(int(k) for k in loop_classes.values()) != K:
        raise ImpossibleParameters(
            f"the loop classes add up to {sum(loop_classes.values())} loops but code {code} has K = {K}"
        )
    W = mobility(n, K, h=h, f=f, loop_classes=loop_classes)
    formulas = {"general (2a/2b)": W}
    if h == 3 and not loop_classes:
        p = code.simple_joint_equivalents
        formulas["Grübler 3(n−1)−2p+f"] = 3 * (n - 1) - 2 * p + f
        formulas["VIP assortment (2c)"] = (
            2 * code.n1 + code.count(2) - sum((i - 3) * code.count(i) for i in range(4, code.max_degree + 1))
            - code.v - 3 + f
        )
        if K == 1 and code.n1 == 0 and code.v == 0:
            formulas["single loop n2−h+f"] = code.count(2) - h + f
    result = dict(
        code=str(code), links=n, loops=K, complexity=K - 1, joints=code.joints,
        simple_joint_equivalents=code.simple_joint_equivalents, v=code.v, h=h, f=f, dof=W, formulas=formulas,
    )
    if dof is not None:
        D = W - dof
        result.update(required_dof=dof, defect=D, advice=_advice(D))
        if h == 3 and not loop_classes:
            result["criterion_holds"] = (dof + 1) + 2 * K == n + f
    return Analysis(**result)
