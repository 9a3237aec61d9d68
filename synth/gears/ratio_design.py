"""Tooth numbers for a wanted speed ratio, in integers, with CP-SAT.

For a mechanism of a 1-DOF train (frame, input, output) the ratio i = ω_in/ω_out is N(z)/D(z),
two polynomials in the tooth numbers (:func:`~synth.gears.mechanisms.speed_ratio`).  The model:

* every wheel: ``min_teeth`` (no undercut; 17 for 20° full-depth teeth) ≤ z, and A ≤ z ≤ B;
* ratio: |N − R·D| ≤ tolerance·|D| with R and the tolerance read as exact fractions;
* internal meshes: the ring has at least ``RING_MARGIN`` more teeth than its pinion;
* coaxial condition, per carrier: the meshes a carrier holds between the same two of its axes
  have one centre distance (one module): z_a + z_b for an external pair, z_ring − z_pinion for
  an internal one — z_ring = z_sun + 2·z_planet for a simple planetary (a gear on no axis of its
  own, a floating sun, counts as turning about the carrier's axis on the frame, or its first);
* with ``planets = k`` equally spaced planets: for every planet meshing a sun (external) and a
  ring (internal) on one carrier, (z_sun + z_ring)/k is a whole number — for a stepped planet
  (wheels z_p1 on the sun, z_p2 on the ring) (z_sun·z_p2 + z_ring·z_p1)/(k·gcd(z_p1, z_p2)); two
  suns or two rings: the difference instead of the sum.

Every design within the tolerance is listed (CP-SAT enumerates them) and the best few are
returned by ratio error, then fewest teeth; if there are more than ``limit`` the query is refused
rather than sampled, so the designs returned are the true best.

Example
-------
>>> from synth.gears import GearTrain
>>> simple = GearTrain.parse("0-1-2 2-3 0~3i 1~3")
>>> best = design(simple, 0, 1, 2, "4", tolerance="0", teeth=(17, 80), best=3)
>>> [(d.teeth["z1"], d.teeth["z3"], d.teeth["z0"], str(d.ratio)) for d in best]
[(17, 17, 51, '4'), (18, 18, 54, '4'), (19, 19, 57, '4')]
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from ..errors import InvalidOption
from .mechanisms import speed_ratio, wheel_names
from .train import GearTrain

__all__ = ["Design", "NoDesign", "design", "parse_fraction", "planet_pairs", "MIN_TEETH", "RING_MARGIN"]

MIN_TEETH = 17  # 20° full-depth involute teeth cut by a rack: fewer are undercut
RING_MARGIN = 10  # an internal pair needs the ring this many teeth above its pinion (tip interference)
_LIMIT = 20_000  # designs within tolerance listed before the query is refused
_BOUND = 1 << 61  # CP-SAT integers


class NoDesign(InvalidOption):
    """No tooth numbers meet the ratio and the conditions (or no planet fits ``--planets``)."""


@dataclass(frozen=True)
class Design:
    """Tooth numbers, the exact ratio they give and its relative error against the target."""

    teeth: dict
    ratio: Fraction
    error: Fraction

    def to_dict(self) -> dict:
        return {"teeth": dict(self.teeth), "ratio": str(self.ratio), "ratio_value": float(self.ratio),
                "error": float(self.error)}


def parse_fraction(text, what: str) -> Fraction:
    """An exact fraction from ``"4.25"``, ``"17/4"`` or ``"1%"``.

    >>> parse_fraction("4.25", "--ratio"), parse_fraction("0.5%", "--tolerance")
    (Fraction(17, 4), Fraction(1, 200))
    """
    s = str(text).strip()
    try:
        if s.endswith("%"):
            return Fraction(s[:-1]) / 100
        return Fraction(s)
    except (ValueError, ZeroDivisionError):
        raise InvalidOption(f"{what} must be a number such as 4.25, 17/4 or 1%, not {text!r}") from None


def _axis_of(train: GearTrain, gear: int, carrier: int, other_axis) -> tuple:
    """The axis about which ``gear`` turns on ``carrier`` (a floating gear: the carrier's axis on
    the frame, or its first axis other than ``other_axis``)."""
    for axis in train.axes:
        if gear in axis and carrier in axis:
            return axis
    own = [a for a in train.axes if carrier in a and a != other_axis]
    on_frame = [a for a in own if train.frame is not None and train.frame in a]
    return (on_frame or own or [("floating", gear)])[0]


def _centre_groups(train: GearTrain) -> dict:
    """Meshes grouped by carrier and the pair of its axes they join."""
    groups: dict = {}
    for k, (a, b, t) in enumerate(train.triples):
        axis_b = next((x for x in train.axes if b in x and t in x), ("floating", b))
        axis_a = _axis_of(train, a, t, axis_b)
        if axis_b[0] == "floating":
            axis_b = _axis_of(train, b, t, axis_a)
        groups.setdefault((t, frozenset((axis_a, axis_b))), []).append(k)
    return groups


def design(train: GearTrain, frame: int, input_link: int, output_link: int, ratio, *, tolerance="1%",
           teeth: tuple[int, int] = (17, 150), min_teeth: int = MIN_TEETH, planets: int | None = None,
           compound=(), best: int = 5, limit: int = _LIMIT) -> list[Design]:
    """The ``best`` designs (tooth numbers) of the mechanism for the speed ratio ``ratio``."""
    from ortools.sat.python import cp_model

    target = parse_fraction(ratio, "--ratio")
    tol = parse_fraction(tolerance, "--tolerance")
    if target == 0:
        raise InvalidOption("a speed ratio of 0 would need an output that never turns")
    if tol < 0:
        raise InvalidOption(f"--tolerance must be ≥ 0, not {tolerance}")
    lo, hi = max(teeth[0], min_teeth), teeth[1]
    if lo > hi:
        raise InvalidOption(f"no tooth number fits {teeth[0]}..{teeth[1]} with at least {min_teeth} teeth "
                            "(fewer are undercut)")
    if planets is not None and planets < 1:
        raise InvalidOption(f"--planets must be a whole number ≥ 1, not {planets}")
    train = GearTrain(train.links, train.axes, train.meshes, train.carriers, train.internal, frame)
    formula = speed_ratio(train, frame, input_link, output_link, compound)
    num, den = dict(formula.numerator), dict(formula.denominator)
    model = cp_model.CpModel()
    z = {w: model.NewIntVar(lo, hi, w) for w in formula.wheels}
    names = wheel_names(train, compound)
    products: dict = {}

    def term(mono):
        if not mono:
            return 1, 1
        if len(mono) == 1 and mono[0][1] == 1:
            return z[mono[0][0]], hi
        if mono not in products:
            factors = [z[x] for x, e in mono for _ in range(e)]
            top = hi ** len(factors)
            if top >= _BOUND:
                raise InvalidOption("these tooth ranges make the ratio's polynomials too large for exact "
                                    "integers: narrow --teeth")
            var = model.NewIntVar(0, top, "·".join(x for x, _ in mono))
            model.AddMultiplicationEquality(var, factors)
            products[mono] = (var, top)
        return products[mono]

    def linear(poly):
        expr, bound = 0, 0
        for mono, c in poly.items():
            var, top = term(mono)
            expr += c * var
            bound += abs(c) * top
        return expr, bound

    n_expr, n_bound = linear(num)
    d_expr, d_bound = linear(den)
    p, q = target.numerator, target.denominator
    a, b = tol.numerator, tol.denominator
    span = max(b * (q * n_bound + abs(p) * d_bound), a * abs(p) * d_bound)
    if span >= _BOUND:
        raise InvalidOption("the ratio and tolerance need integers too large for an exact model: give the "
                            "ratio with fewer digits or narrow --teeth")
    error = model.NewIntVar(-span, span, "error")
    model.Add(error == q * n_expr - p * d_expr)
    abs_error = model.NewIntVar(0, span, "abs_error")
    model.AddAbsEquality(abs_error, error)
    d_var = model.NewIntVar(-d_bound, d_bound, "D")
    model.Add(d_var == d_expr)
    abs_d = model.NewIntVar(1, d_bound, "abs_D")
    model.AddAbsEquality(abs_d, d_var)
    model.Add(b * abs_error <= a * abs(p) * abs_d)  # |N/D − R| ≤ tol·|R|
    for (za, zb), inner in zip(names, train.internal):
        if inner:
            model.Add(z[za] >= z[zb] + RING_MARGIN)
    for members in _centre_groups(train).values():
        sizes = [z[names[k][0]] + (-1 if train.internal[k] else 1) * z[names[k][1]] for k in members]
        for other in sizes[1:]:
            model.Add(other == sizes[0])
    if planets is not None:
        _assembly(model, train, names, z, planets, lo, hi)

    found: list[dict] = []

    class Collect(cp_model.CpSolverSolutionCallback):
        def on_solution_callback(self):
            found.append({w: self.Value(v) for w, v in z.items()})
            if len(found) > limit:
                self.StopSearch()

    solver = cp_model.CpSolver()
    solver.parameters.enumerate_all_solutions = True
    solver.parameters.num_workers = 1
    status = solver.Solve(model, Collect())
    if len(found) > limit:
        raise InvalidOption(f"more than {limit} designs are within the tolerance: tighten --tolerance or narrow "
                            "--teeth to get the best ones")
    if status == cp_model.INFEASIBLE or not found:
        raise NoDesign(f"no tooth numbers in {lo}..{hi} give the ratio {ratio} within {tolerance} under the "
                            "coaxial, assembly and undercut conditions")
    designs = []
    for teeth_of in found:
        exact = formula.evaluate(teeth_of)
        designs.append(Design(dict(sorted(teeth_of.items())), exact, abs(exact - target) / abs(target)))
    designs.sort(key=lambda d: (d.error, sum(d.teeth.values()), tuple(d.teeth.values())))
    return designs[:best]


def planet_pairs(train: GearTrain, names) -> list[tuple[str, str, str, str, int]]:
    """The pairs of meshes that fix where equally spaced planets can go: a planet p turning on
    carrier t about one axis meshes two central gears c1, c2 that turn on t about one other axis.
    Each as (z_c1, z_p1, z_c2, z_p2, ε1·ε2): the wheels, ε = +1 for a sun (external mesh), −1 for a
    ring (internal, the central gear first).

    >>> planet_pairs(GearTrain.parse("0-1-2 2-3 0~3i 1~3"), [("z0", "z3_0"), ("z1", "z3_1")])
    [('z0', 'z3_0', 'z1', 'z3_1', -1)]
    """
    central: dict = {}
    for k, (a, b, t) in enumerate(train.triples):
        for planet, centre, side in ((b, a, 1), (a, b, 0)):
            if train.internal[k] and side == 0:  # the planet would be a ring around its central gear
                continue
            own = next((x for x in train.axes if planet in x and t in x), None)
            if own is None:  # a floating gear is no planet
                continue
            axis = _axis_of(train, centre, t, own)
            sign = -1 if train.internal[k] else 1
            central.setdefault((t, planet, own, axis), []).append((names[k][1 - side], names[k][side], sign))
    out = []
    for meshes in central.values():
        for (c1, p1, e1), (c2, p2, e2) in zip(meshes, meshes[1:]):
            out.append((c1, p1, c2, p2, e1 * e2))
    return out


def _assembly(model, train: GearTrain, names, z, planets: int, lo: int, hi: int) -> None:
    """k equally spaced planets assemble: for every planet meshing two central gears on one carrier,
    (z_c1·z_p2 − ε1ε2·z_c2·z_p1) / (k·gcd(z_p1, z_p2)) is a whole number — (z_sun + z_ring)/k for a
    simple planet, (z_sun·z_p2 + z_ring·z_p1)/(k·gcd(z_p1, z_p2)) for a stepped one (z_p1 meshing the
    sun, z_p2 the ring).  A stepped planet's condition is written with Bézout's identity: the
    quotient by k is j1·z_p1 + j2·z_p2 for some whole j1, j2 (0 ≤ j1 < z_p2 is enough)."""
    pairs = planet_pairs(train, names)
    if not pairs:
        raise NoDesign("--planets needs a planet wheel that meshes a sun and a ring on one carrier")
    for c1, p1, c2, p2, sign in pairs:
        tag = f"{c1}_{c2}"
        if p1 == p2:  # one planet wheel: (z_c1 − ε1ε2·z_c2)/k whole
            turns = model.NewIntVar(-2 * hi, 2 * hi, f"assembly_{tag}")
            model.Add(z[c1] - sign * z[c2] == planets * turns)
            continue
        span = 2 * hi * hi
        top = span // lo + hi
        first, second = model.NewIntVar(0, span, f"{c1}·{p2}"), model.NewIntVar(0, span, f"{c2}·{p1}")
        model.AddMultiplicationEquality(first, [z[c1], z[p2]])
        model.AddMultiplicationEquality(second, [z[c2], z[p1]])
        j1, j2 = model.NewIntVar(0, hi, f"j1_{tag}"), model.NewIntVar(-top, top, f"j2_{tag}")
        u1, u2 = model.NewIntVar(0, hi * hi, f"u1_{tag}"), model.NewIntVar(-top * hi, top * hi, f"u2_{tag}")
        model.AddMultiplicationEquality(u1, [j1, z[p1]])
        model.AddMultiplicationEquality(u2, [j2, z[p2]])
        model.Add(first - sign * second == planets * (u1 + u2))
        model.Add(j1 < z[p2])
