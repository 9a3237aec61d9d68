"""Mechanisms of a gear train (frame, input, output up to symmetry) and their speed ratios.

Each mesh (a, b) with carrier t gives a Willis equation in the angular speeds ω:

    z_a (ω_a − ω_t) = ∓ z_b (ω_b − ω_t)       (external mesh −, internal mesh +)

with z the tooth numbers of the two wheels.  A link is one wheel (one tooth number ``z<link>``)
unless it is named *compound*: then it carries a wheel per mesh, ``z<link>_<mate>``.  With the
frame at rest and the input turning, a 1-DOF train's equations fix every speed, and the speed
ratio i = ω_input / ω_output is a quotient of two polynomials in the tooth numbers (Cramer's
rule on the Willis equations, exact).

Example
-------
>>> from synth.gears import GearTrain
>>> simple = GearTrain.parse("0-1-2 2-3 0~3i 1~3")  # ring 0 fixed, sun 1, carrier 2, planet 3
>>> formula = speed_ratio(simple, frame=0, input_link=1, output_link=2)
>>> formula.text
'(z0 + z1)/z1'
>>> formula.evaluate({"z0": 72, "z1": 24, "z3": 24})
Fraction(4, 1)
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from fractions import Fraction

from mechbase import Row

from ..errors import InvalidOption
from .train import GearTrain

__all__ = ["RatioFormula", "GearMechanism", "wheel_names", "willis_rows", "speed_ratio", "mechanisms"]

Poly = dict  # {monomial: int}, a monomial a sorted tuple of (wheel, power)


def _mono(*names: str) -> tuple:
    power: dict[str, int] = {}
    for x in names:
        power[x] = power.get(x, 0) + 1
    return tuple(sorted(power.items()))


def _add(p: Poly, q: Poly, sign: int = 1) -> Poly:
    out = dict(p)
    for m, c in q.items():
        out[m] = out.get(m, 0) + sign * c
        if out[m] == 0:
            del out[m]
    return out


def _mul(p: Poly, q: Poly) -> Poly:
    out: Poly = {}
    for m1, c1 in p.items():
        for m2, c2 in q.items():
            power = dict(m1)
            for x, e in m2:
                power[x] = power.get(x, 0) + e
            m = tuple(sorted(power.items()))
            out[m] = out.get(m, 0) + c1 * c2
            if out[m] == 0:
                del out[m]
    return out


def _evaluate(p: Poly, teeth: dict) -> int:
    total = 0
    for m, c in p.items():
        term = c
        for x, e in m:
            term *= teeth[x] ** e
        total += term
    return total


def _det(matrix: list[list[Poly]]) -> Poly:
    """Determinant of a square matrix of polynomials (sum over permutations by column subsets)."""
    k = len(matrix)
    table: dict[int, Poly] = {0: {(): 1}}
    for mask in sorted(range(1, 1 << k), key=lambda m: bin(m).count("1")):
        row = bin(mask).count("1") - 1
        total: Poly = {}
        for c in range(k):
            if not mask >> c & 1 or not matrix[row][c]:
                continue
            prev = mask ^ (1 << c)
            if not table.get(prev):
                continue
            sign = -1 if bin(prev >> (c + 1)).count("1") % 2 else 1
            total = _add(total, _mul(matrix[row][c], table[prev]), sign)
        table[mask] = total
    return table[(1 << k) - 1]


def _text(p: Poly) -> str:
    terms = []
    for m, c in sorted(p.items(), key=lambda mc: (-sum(e for _, e in mc[0]), mc[0])):
        body = "·".join(x if e == 1 else f"{x}^{e}" for x, e in m)
        mag = abs(c)
        word = body if mag == 1 and body else (f"{mag}·{body}" if body else str(mag))
        terms.append(("- " if c < 0 else "+ ") + word)
    if not terms:
        return "0"
    out = " ".join(terms)
    return out[2:] if out.startswith("+ ") else "-" + out[2:]


def wheel_names(train: GearTrain, compound=()) -> list[tuple[str, str]]:
    """Per mesh, the tooth-number names of its two wheels.

    >>> wheel_names(GearTrain.parse("0-1-2 2-3 0~3i 1~3"), compound=[3])
    [('z0', 'z3_0'), ('z1', 'z3_1')]
    """
    compound = set(compound)
    out = []
    for a, b in train.meshes:
        out.append(tuple(f"z{x}_{y}" if x in compound else f"z{x}" for x, y in ((a, b), (b, a))))
    return out


def willis_rows(train: GearTrain, compound=(), signs: bool = False) -> list[dict[int, Poly]]:
    """Per mesh, the coefficients of the speeds in its Willis equation (each a polynomial).  With
    ``signs`` the kind of mesh k is left open as a symbol ``s<k>`` (+1 external, −1 internal).

    >>> willis_rows(GearTrain.parse("0-1 1-2 0~2"), signs=True)[0][2]
    {(('s0', 1), ('z2', 1)): 1}
    """
    rows = []
    for k, ((a, b, t), inner, (za, zb)) in enumerate(zip(train.triples, train.internal, wheel_names(train, compound))):
        # z_a(ω_a − ω_t) + s·z_b(ω_b − ω_t) = 0
        zs = {_mono(zb, f"s{k}"): 1} if signs else {_mono(zb): -1 if inner else 1}
        row = {a: {_mono(za): 1}, b: zs}
        row[t] = _add({_mono(za): -1}, {m: -c for m, c in zs.items()})
        rows.append(row)
    return rows


def _fold_signs(p: Poly) -> Poly:
    """s² = 1 for every sign symbol ``s<k>``."""
    out: Poly = {}
    for m, c in p.items():
        mono = tuple((x, e % 2 if x.startswith("s") else e) for x, e in m)
        mono = tuple((x, e) for x, e in mono if e)
        out[mono] = out.get(mono, 0) + c
        if out[mono] == 0:
            del out[mono]
    return out


@dataclass(frozen=True)
class RatioFormula:
    """i = ω_input / ω_output = numerator / denominator, polynomials in the tooth numbers."""

    numerator: tuple
    denominator: tuple
    wheels: tuple[str, ...]

    @property
    def text(self) -> str:
        num, den = dict(self.numerator), dict(self.denominator)
        wrap = lambda p: _text(p) if len(p) == 1 and "·" not in _text(p) else f"({_text(p)})"  # noqa: E731
        if den == {(): 1}:
            return _text(num)
        return f"{wrap(num)}/{wrap(den)}"

    def evaluate(self, teeth: dict) -> Fraction:
        """The exact ratio for given tooth numbers (``{"z0": 72, …}``)."""
        missing = [w for w in self.wheels if w not in teeth]
        if missing:
            raise InvalidOption(f"no tooth number given for wheel {missing[0]}")
        den = _evaluate(dict(self.denominator), teeth)
        if den == 0:
            raise InvalidOption("the output does not turn with these tooth numbers (ratio infinite)")
        return Fraction(_evaluate(dict(self.numerator), teeth), den)


def _simplify(num: Poly, den: Poly) -> tuple[Poly, Poly]:
    """Divide out the integer content and the monomial factor common to both; denominator's
    first coefficient positive."""
    from math import gcd

    content = 0
    for c in list(num.values()) + list(den.values()):
        content = gcd(content, c)
    common = None
    for m in list(num) + list(den):
        power = dict(m)
        common = power if common is None else {x: min(e, power.get(x, 0)) for x, e in common.items() if x in power}
    common = {x: e for x, e in (common or {}).items() if e > 0}

    def reduce(p):
        out = {}
        for m, c in p.items():
            power = dict(m)
            for x, e in common.items():
                power[x] -= e
            out[tuple(sorted((x, e) for x, e in power.items() if e))] = c // content
        return out

    num, den = reduce(num), reduce(den)
    lead = den[min(den, key=lambda m: (-sum(e for _, e in m), m))]
    if lead < 0:
        num, den = {m: -c for m, c in num.items()}, {m: -c for m, c in den.items()}
    return num, den


def _independent_rows(rows, columns, wheels) -> list[int]:
    """A largest set of Willis rows independent on ``columns`` (exact rank at random tooth numbers)."""
    rng = random.Random(1)
    teeth = {w: rng.randint(20, 10**6) for w in wheels}
    chosen, basis = [], []
    for k, row in enumerate(rows):
        vec = [Fraction(_evaluate(row.get(c, {}), teeth)) for c in columns]
        for pivot, b in basis:
            if vec[pivot]:
                f = vec[pivot] / b[pivot]
                vec = [x - f * y for x, y in zip(vec, b)]
        lead = next((i for i, x in enumerate(vec) if x), None)
        if lead is not None:
            basis.append((lead, vec))
            chosen.append(k)
    return chosen


def speed_ratio(train: GearTrain, frame: int, input_link: int, output_link: int, compound=(),
                signs: bool = False) -> RatioFormula:
    """i = ω_input/ω_output with the frame at rest, as a formula in the tooth numbers (and with
    ``signs`` in the kinds of the meshes, ``s<k>`` = +1 external, −1 internal: one formula for
    every choice of internal meshes).

    Raises InvalidOption when the input does not drive the train to one motion (its speed leaves
    other speeds free) or the output stands still for every choice of tooth numbers.
    """
    links = {frame, input_link, output_link}
    if len(links) != 3 or not all(0 <= x < train.links for x in links):
        raise InvalidOption("the frame, the input and the output must be three different links of the train")
    rows = willis_rows(train, compound, signs)
    wheels = sorted({w for pair in wheel_names(train, compound) for w in pair})
    wheels += [f"s{k}" for k in range(len(train.meshes))] if signs else []
    unknown = [x for x in range(train.links) if x not in (frame, input_link)]
    chosen = _independent_rows(rows, unknown, wheels)
    if len(chosen) < len(unknown):
        raise InvalidOption(f"with link {frame} fixed, driving link {input_link} leaves the train free to move "
                            "(more than one degree of freedom)")
    every = _independent_rows(rows, unknown + [input_link], wheels)
    if len(every) > len(unknown):
        raise InvalidOption(f"with link {frame} fixed the train cannot turn (its Willis equations lock it)")
    matrix = [[rows[k].get(c, {}) for c in unknown] for k in chosen]
    rhs = [{m: -v for m, v in rows[k].get(input_link, {}).items()} for k in chosen]
    column = unknown.index(output_link)
    replaced = [row[:column] + [r] + row[column + 1:] for row, r in zip(matrix, rhs)]
    den, num = _det(replaced), _det(matrix)  # ω_out = det(replaced)/det(matrix), ω_in = 1
    if signs:
        den, num = _fold_signs(den), _fold_signs(num)
    if not den:
        raise InvalidOption(f"output link {output_link} stands still whatever the tooth numbers")
    num, den = _simplify(num, den)
    return RatioFormula(tuple(sorted(num.items())), tuple(sorted(den.items())), tuple(wheels))


@dataclass(frozen=True)
class GearMechanism(Row):
    """A train with a fixed link and, for F = 1, an input and an output shaft turning on the frame."""

    train: GearTrain
    frame: int
    input_link: int | None = None
    output_link: int | None = None
    ratio: RatioFormula | None = None

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The train's row, its frame, the input and output shafts when chosen, and the ratio's formula."""
        shafts = ("input_link", "output_link") if self.input_link is not None else ()
        return ("*train", "frame", *shafts, "ratio=ratio_text?")

    @property
    def ratio_text(self) -> str | None:
        return None if self.ratio is None else self.ratio.text


def _shafts(train: GearTrain, frame: int) -> list[int]:
    """Links that turn about an axis of the frame (input and output shafts)."""
    return sorted({x for axis in train.axes if frame in axis for x in axis if x != frame})


def mechanisms(train: GearTrain, input_output: bool = False, compound=()) -> list[GearMechanism]:
    """Frames up to the train's symmetry, and with ``input_output`` every (input, output) pair of
    frame shafts up to the symmetry that fixes the frame, each with its speed ratio (F = 1).

    >>> [(m.frame, m.input_link, m.output_link, m.ratio.text) for m in
    ...  mechanisms(GearTrain.parse("0-1-2 2-3 0~3i 1~3"), input_output=True)][:3]
    [(0, 1, 2, '(z0 + z1)/z1'), (0, 2, 1, 'z1/(z0 + z1)'), (1, 0, 2, '(z0 + z1)/z0')]
    """
    _, orbits = train.automorphisms()
    frames = sorted({min(x for x in range(train.links) if orbits[x] == orbits[f]) for f in range(train.links)})
    out = []
    for f in frames:
        if not input_output:
            out.append(GearMechanism(train, f))
            continue
        if train.dof != 1:
            raise InvalidOption(f"input and output fix the speed ratio of a 1-DOF train; this one has F = {train.dof}")
        seen = set()
        for i in _shafts(train, f):
            for o in _shafts(train, f):
                if o == i:
                    continue
                key = _mechanism_key(train, f, i, o)
                if key in seen:
                    continue
                seen.add(key)
                try:
                    ratio = speed_ratio(train, f, i, o, compound)
                except InvalidOption:
                    continue
                out.append(GearMechanism(train, f, i, o, ratio))
    return out


def _mechanism_key(train: GearTrain, frame: int, i: int, o: int) -> bytes:
    import pynauty

    return pynauty.certificate(train._graph(marked=(frame, i, o)))
