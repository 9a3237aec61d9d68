"""Tooth numbers for a wanted speed ratio, in integers, with CP-SAT.

For a mechanism of a 1-DOF train (frame, input, output) the ratio i = ω_in/ω_out is N(z)/D(z),
two polynomials in the tooth numbers (:func:`~synth.gears.ratios.speed_ratio`).  The model:

* every wheel: ``min_teeth`` (no undercut; 17 for 20° full-depth teeth) ≤ z, and A ≤ z ≤ B;
* ratio: |N − R·D| ≤ tolerance·|R·D|, a relative error |i − R| ≤ tolerance·|R| (below 100 %: the ratio keeps
  its sign), with R and the tolerance read as exact fractions;
* internal meshes: the ring has at least ``RING_MARGIN`` more teeth than its pinion;
* coaxial condition, per carrier: the meshes a carrier holds between the same two of its axes
  have one centre distance (one module): z_a + z_b for an external pair, z_ring − z_pinion for
  an internal one — z_ring = z_sun + 2·z_planet for a simple planetary (a gear on no axis of its
  own, a floating sun, counts as turning about the carrier's axis on the frame, or its first);
* with ``planets = k`` equally spaced planets: for every planet meshing a sun (external) and a
  ring (internal) on one carrier, (z_sun + z_ring)/k is a whole number — for a stepped planet
  (wheels z_p1 on the sun, z_p2 on the ring) (z_sun·z_p2 + z_ring·z_p1)/(k·gcd(z_p1, z_p2)); two
  suns or two rings: the difference instead of the sum.

With ``kinds="free"`` each mesh is external or internal (either gear the ring) as the solver
chooses: the Willis equations carry a sign per mesh, one formula for every choice.

The designs returned are the true best by ratio error, then fewest teeth, then tooth numbers in
order — found level by level, not sampled: the least error is reached by solving again and again
with "error below the last one found" (each solve minimising the error's numerator); the designs
of that error are taken by increasing tooth sum (CP-SAT minimises it) and, within a sum, by their
tooth numbers in order (each wheel minimised in turn, the design found then excluded); the
search goes on above that error until ``best`` are found.

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

from mechbase import Row

from ..errors import InvalidOption, option
from .ratios import speed_ratio, wheel_names
from .train import GearTrain

__all__ = ["Design", "NoDesign", "RatioUnreached", "design", "parse_fraction", "ratio_and_tolerance", "planet_pairs", "carrier_cycles", "planet_clearance",
           "MIN_TEETH", "RING_MARGIN"]

MIN_TEETH = 17  # 20° full-depth involute teeth cut by a rack: fewer are undercut
RING_MARGIN = 10  # an internal pair needs the ring this many teeth above its pinion (tip interference)
_BOUND = 1 << 61  # CP-SAT integers


class NoDesign(InvalidOption):
    """The train cannot be designed as asked (e.g. it has no planet for ``planets``)."""


class RatioUnreached(NoDesign):
    """The search ran and no tooth numbers of the range meet the ratio and the conditions: a valid
    question without an answer (the command line's exit status 1, not a refusal)."""


@dataclass(frozen=True)
class Design(Row):
    """Tooth numbers, the exact ratio they give and its relative error against the target."""

    teeth: dict
    ratio: Fraction
    error: Fraction
    train: GearTrain | None = None  # with kinds="free": the train with the mesh kinds chosen

    row_keys = ("teeth", "ratio=ratio_text", "ratio_value", "error=error_value", "train=train_text?")

    @property
    def ratio_text(self) -> str:
        """The exact ratio, ``17/4``."""
        return str(self.ratio)

    @property
    def ratio_value(self) -> float:
        return float(self.ratio)

    @property
    def error_value(self) -> float:
        return float(self.error)

    @property
    def train_text(self) -> str | None:
        """The train with its chosen mesh kinds as a joint list (None: the kinds were given)."""
        return None if self.train is None else self.train.compact()


def parse_fraction(text, what: str) -> Fraction:
    """An exact fraction from ``"4.25"``, ``"17/4"`` or ``"1%"``.

    >>> parse_fraction("4.25", "the speed ratio"), parse_fraction("0.5%", "the tolerance")
    (Fraction(17, 4), Fraction(1, 200))
    """
    s = str(text).strip()
    try:
        if s.endswith("%"):
            return Fraction(s[:-1]) / 100
        return Fraction(s)
    except (ValueError, ZeroDivisionError):
        raise InvalidOption(f"{what} must be a number such as 4.25, 17/4 or 1%, not {text!r}") from None


def ratio_and_tolerance(ratio, tolerance) -> tuple[Fraction, Fraction]:
    """The speed ratio and its tolerance as exact fractions, refused where meaningless.

    The tolerance is the ratio's relative error allowed, |i − R| ≤ tolerance·|R|: 0 ≤ tolerance < 100 %
    (at 100 % any ratio of the same sign up to 2R would do; beyond it one of the other sign, the output
    turning the wrong way).

    >>> ratio_and_tolerance("17/4", "0.5%")
    (Fraction(17, 4), Fraction(1, 200))
    """
    target = parse_fraction(ratio, "the speed ratio")
    tol = parse_fraction(tolerance, "the tolerance")
    if target == 0:
        raise InvalidOption("a speed ratio of 0 would need an output that never turns")
    if not 0 <= tol < 1:
        raise InvalidOption(f"the tolerance is the ratio's relative error allowed, 0 … 100 % (exclusive), not "
                            f"{tolerance}" + (" (at 100 % or more, a ratio twice the one asked, or of the other "
                                               "sign, would pass)" if tol >= 1 else ""))
    return target, tol


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
           compound=(), best: int = 5, kinds: str = "given",
           beat: tuple[Fraction, int] | None = None) -> list[Design]:
    """The ``best`` designs (tooth numbers) of the mechanism for the speed ratio ``ratio``.

    ``kinds``: "given" (the train's own internal and external meshes) or "free" (each mesh as the
    solver chooses).  ``beat``: (error, tooth sum) — only designs of a smaller error, or of that
    error and at most that sum (a search over many mechanisms passes the worst design it keeps).
    Raises :class:`RatioUnreached` when none qualifies, :class:`NoDesign` when the train cannot be
    designed as asked.
    """
    target, tol = ratio_and_tolerance(ratio, tolerance)
    if teeth[0] < 1:
        raise InvalidOption(f"a gear has at least 1 tooth: the tooth range {teeth[0]}..{teeth[1]} starts below 1")
    lo, hi = max(teeth[0], min_teeth), teeth[1]
    if lo > hi:
        raise InvalidOption(f"no tooth number fits {teeth[0]}..{teeth[1]} with at least {min_teeth} teeth "
                            "(fewer are undercut)")
    if planets is not None and planets < 1:
        raise InvalidOption(f"the number of planets must be a whole number ≥ 1, not {planets}")
    if kinds not in ("given", "free"):
        raise InvalidOption(f"mesh kinds are given or free, not {kinds!r}")
    train = GearTrain(train.links, train.axes, train.meshes, train.carriers, train.internal, frame)
    model = _DesignModel(train, frame, input_link, output_link, target, tol, (lo, hi), planets, compound,
                         kinds == "free", beat)
    found = model.best(best)
    if not found:
        raise RatioUnreached(f"no tooth numbers in {lo}..{hi} give the ratio {ratio} within {tolerance} under the "
                       "coaxial, assembly and undercut conditions")
    return found


class _DesignModel:
    """The CP-SAT model of one mechanism and the level-by-level search of its best designs."""

    def __init__(self, train, frame, input_link, output_link, target, tol, teeth, planets, compound, free, beat):
        from ortools.sat.python import cp_model

        self.cp = cp_model
        self.train, self.target, self.compound, self.free = train, target, tuple(compound), free
        self.mechanism = (frame, input_link, output_link)
        lo, hi = self.teeth = teeth
        self.formula = speed_ratio(train, frame, input_link, output_link, compound, signs=free)
        num, den = dict(self.formula.numerator), dict(self.formula.denominator)
        model = self.model = cp_model.CpModel()
        wheels = [w for w in self.formula.wheels if w.startswith("z")]
        z = self.z = {w: model.new_int_var(lo, hi, w) for w in wheels}
        names = wheel_names(train, compound)
        self.kind = self._kinds(len(names)) if free else None
        sign = {f"s{k}": v for k, v in enumerate(self.kind["sign"])} if free else {}
        products: dict = {}

        def term(mono):
            if not mono:
                return 1, 1
            if len(mono) == 1 and mono[0][1] == 1:
                return (z | sign)[mono[0][0]], (hi if mono[0][0] in z else 1)
            if mono not in products:
                factors = [(z | sign)[x] for x, e in mono for _ in range(e)]
                top = hi ** sum(e for x, e in mono if x in z)
                if top >= _BOUND:
                    raise InvalidOption("these tooth ranges make the ratio's polynomials too large for exact "
                                        f"integers: narrow {option('teeth', 'A..B')}")
                var = model.new_int_var(-top if any(x in sign for x, _ in mono) else 0, top, "·".join(x for x, _ in mono))
                model.add_multiplication_equality(var, factors)
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
        if span >= _BOUND or span * d_bound >= _BOUND:
            raise InvalidOption("the ratio and tolerance need integers too large for an exact model: give the "
                                f"ratio with fewer digits or narrow {option('teeth', 'A..B')}")
        error = model.new_int_var(-span, span, "error")
        model.add(error == q * n_expr - p * d_expr)
        self.E = model.new_int_var(0, span, "abs_error")  # error of a design: E / (|p|·A)
        model.add_abs_equality(self.E, error)
        d_var = model.new_int_var(-d_bound, d_bound, "D")
        model.add(d_var == d_expr)
        self.A = model.new_int_var(1, d_bound, "abs_D")
        model.add_abs_equality(self.A, d_var)
        n_var = model.new_int_var(-n_bound, n_bound, "N")
        model.add(n_var == n_expr)
        model.add(n_var != 0)  # the input turns the output: a finite, non-zero ratio
        model.add(b * self.E <= a * abs(p) * self.A)  # |N/D − R| ≤ tol·|R|
        self.S = sum(z.values())
        if beat is not None:  # a smaller error, or the same and no more teeth
            self._error_is(model, "<=", beat[0])
            better = model.new_bool_var("better")
            self._error_is(model, "<", beat[0]).only_enforce_if(better)
            model.add(self.S <= beat[1]).only_enforce_if(better.negated())
        centre = self._centres(names)
        self._one_kind_per_wheel(names)
        _carrier_geometry(model, train, centre)
        if planets is not None:
            _assembly(model, train, names, z, planets, lo, hi, self.kind)
            _planets_clear(model, train, names, z, centre, planets, lo, hi, self.kind)

    # ---------------------------------------------------------------- mesh kinds chosen
    def _kinds(self, meshes: int) -> dict:
        """Per mesh three literals — external, first gear the ring, second gear the ring — and its sign."""
        model, out = self.model, {"external": [], "ring_first": [], "ring_second": [], "sign": []}
        for k in range(meshes):
            lits = [model.new_bool_var(f"{what}{k}") for what in ("ext", "ring_a", "ring_b")]
            model.add_exactly_one(lits)
            s = model.new_int_var_from_domain(self.cp.Domain.from_values([-1, 1]), f"s{k}")
            model.add(s == 1).only_enforce_if(lits[0])
            model.add(s == -1).only_enforce_if(lits[0].negated())
            for key, lit in zip(("external", "ring_first", "ring_second"), lits):
                out[key].append(lit)
            out["sign"].append(s)
        return out

    def _centres(self, names) -> list:
        """Per mesh its centre distance in half modules, 2a/m: z_a + z_b for an external pair,
        z_ring − z_pinion for an internal one (a ring at least ``RING_MARGIN`` teeth above its
        pinion), for the kinds given or whichever the solver chooses."""
        model, z, kind = self.model, self.z, self.kind
        if kind is None:
            for (za, zb), inner in zip(names, self.train.internal):
                if inner:
                    model.add(z[za] >= z[zb] + RING_MARGIN)
            return [z[za] - z[zb] if inner else z[za] + z[zb] for (za, zb), inner in zip(names, self.train.internal)]
        hi = self.teeth[1]
        centre = []
        for k, (za, zb) in enumerate(names):
            c = model.new_int_var(RING_MARGIN, 2 * hi, f"centre{k}")
            model.add(c == z[za] + z[zb]).only_enforce_if(kind["external"][k])
            model.add(c == z[za] - z[zb]).only_enforce_if(kind["ring_first"][k])
            model.add(c == z[zb] - z[za]).only_enforce_if(kind["ring_second"][k])
            model.add(z[za] >= z[zb] + RING_MARGIN).only_enforce_if(kind["ring_first"][k])
            model.add(z[zb] >= z[za] + RING_MARGIN).only_enforce_if(kind["ring_second"][k])
            centre.append(c)
        return centre

    def _one_kind_per_wheel(self, names) -> None:
        """A wheel in several meshes is the ring of all of them or of none: one toothed rim is
        internal or external (a link with a wheel of each kind is a compound link, ``compound``)."""
        meshes_of: dict = {}
        for k, pair in enumerate(names):
            for side, wheel in enumerate(pair):
                meshes_of.setdefault(wheel, []).append((k, side))
        for wheel, where in meshes_of.items():
            if self.kind is None:
                rings = [self.train.internal[k] and side == 0 for k, side in where]
                if any(rings) and not all(rings):
                    (k1, _), (k2, _) = (where[rings.index(True)], where[rings.index(False)])
                    a, b = self.train.meshes[k1]
                    c, d = self.train.meshes[k2]
                    raise NoDesign(f"wheel {wheel} is the ring of mesh {a}~{b}i and an external gear of mesh {c}~{d}: "
                                   f"one rim has internal or external teeth; list link {wheel[1:].split('_')[0]} "
                                   "with --compound to give it a wheel per mesh")
                continue
            lits = [self.kind["ring_first" if side == 0 else "ring_second"][k] for k, side in where]
            for other in lits[1:]:
                self.model.add(other == lits[0])

    # ---------------------------------------------------------------- the search
    def _error_is(self, model, relation: str, error: Fraction):
        """Constrain a design's error E/(|p|·A) against ``error`` = u/v: E·v ``relation`` u·|p|·A."""
        u, v, p = error.numerator, error.denominator, abs(self.target.numerator)
        left, right = v * self.E, u * p * self.A
        return model.add({"<": left < right, "<=": left <= right, "==": left == right, ">": left > right}[relation])

    def _solve(self, model, minimise=None):
        """Solve ``model`` (minimising ``minimise``); Ctrl-C stops the search within milliseconds."""
        from ..execution.interrupt import solve_stoppably

        solver = self.cp.CpSolver()
        solver.parameters.num_workers = 1
        solver.parameters.catch_sigint_signal = False  # Ctrl-C belongs to the caller (KeyboardInterrupt)
        if minimise is not None:
            model.minimize(minimise)
        status = solve_stoppably(solver, model)
        if status not in (self.cp.OPTIMAL, self.cp.FEASIBLE):
            return None
        return solver

    def _error(self, solver) -> Fraction:
        return Fraction(solver.value(self.E), abs(self.target.numerator) * solver.value(self.A))

    def _least_error(self, above: Fraction | None) -> Fraction | None:
        """The least error of the designs whose error is above ``above`` (None: any), or None."""
        least = None
        while True:
            model = self.model.clone()
            if above is not None:
                self._error_is(model, ">", above)
            if least is not None:
                self._error_is(model, "<", least)
            solver = self._solve(model, minimise=self.E)
            if solver is None:
                return least
            least = self._error(solver)

    def _least_design(self, model):
        """The design of ``model`` with the least tooth numbers in order (wheel by wheel), then the
        least mesh kinds; None if there is none."""
        model = model.clone()
        order = [self.z[w] for w in sorted(self.z)]
        if self.kind:
            order += [lit for pair in zip(self.kind["ring_first"], self.kind["ring_second"]) for lit in pair]
        solver = None
        for var in order:
            solver = self._solve(model, minimise=var)
            if solver is None:
                return None
            value = int(solver.value(var))
            model.clear_objective()
            model.add(var == value)
        solver = solver or self._solve(model)
        teeth = {w: int(solver.value(v)) for w, v in self.z.items()}
        rings = (tuple((solver.value(a), solver.value(b)) for a, b in zip(self.kind["ring_first"],
                                                                          self.kind["ring_second"]))
                 if self.kind else None)
        return teeth, rings

    def _exclude(self, model, teeth: dict, rings) -> None:
        """No design equal to this one (some tooth number or mesh kind differs)."""
        differs = []
        for w, value in teeth.items():
            b = model.new_bool_var("")
            model.add(self.z[w] != value).only_enforce_if(b)
            differs.append(b)
        for k, (first, second) in enumerate(rings or ()):
            for lit, value in ((self.kind["ring_first"][k], first), (self.kind["ring_second"][k], second)):
                differs.append(lit.negated() if value else lit)
        model.add_bool_or(differs)

    def best(self, count: int) -> list[Design]:
        out: list[Design] = []
        above = None
        while len(out) < count:
            error = self._least_error(above)
            if error is None:
                break
            level = self.model.clone()
            self._error_is(level, "==", error)
            total = None
            while len(out) < count:
                model = level.clone()
                if total is not None:
                    model.add(self.S > total)
                solver = self._solve(model, minimise=self.S)
                if solver is None:
                    break
                total = int(solver.objective_value)
                model = level.clone()
                model.add(self.S == total)
                while len(out) < count:
                    found = self._least_design(model)
                    if found is None:
                        break
                    out.append(self._design(*found))
                    self._exclude(model, *found)
            above = error
        return out

    def _design(self, teeth: dict, rings) -> Design:
        if rings is None:
            return Design(dict(sorted(teeth.items())), self.formula.evaluate(teeth),
                          abs(self.formula.evaluate(teeth) - self.target) / abs(self.target))
        t = self.train
        meshes = [(b, a) if second else (a, b) for (a, b), (first, second) in zip(t.meshes, rings)]
        variant = GearTrain(t.links, t.axes, meshes, t.carriers, [bool(f or s) for f, s in rings], t.frame)
        exact = speed_ratio(variant, *self.mechanism, self.compound).evaluate(teeth)
        return Design(dict(sorted(teeth.items())), exact, abs(exact - self.target) / abs(self.target), variant)


def carrier_cycles(train: GearTrain) -> list[tuple[int, list[list[int]]]]:
    """Per carrier, the cycles its centre distances close: each cycle as the lists of meshes (one
    group of meshes per side, a side joining two axes of the carrier) around a cycle of its axes.

    A carrier holds its axes at fixed places; the centre distances of the meshes between them
    must close every such cycle in the plane: each at most the sum of the others (for three
    axes, the triangle inequality).  Those inequalities place the axes exactly when their graph
    is series–parallel (no four axes joined pairwise through other axes); a carrier whose axes
    are not is refused (:class:`NoDesign`) — the first such trains have 8 links.

    >>> carrier_cycles(GearTrain.parse("0-1-4 0-2 0-3 1~2 2~3 4~3i", frame=1))
    [(0, [[0], [1], [2]])]
    """
    import networkx as nx
    from networkx.algorithms.approximation import treewidth_min_degree

    graphs: dict = {}
    for (t, ends), members in _centre_groups(train).items():
        if len(ends) == 2:
            graphs.setdefault(t, nx.Graph()).add_edge(*sorted(ends, key=repr), meshes=members)
    out = []
    for t, graph in graphs.items():
        if treewidth_min_degree(graph)[0] > 2:  # exact up to 2: a vertex of degree ≤ 2 is always there to remove
            raise NoDesign(f"carrier {t} holds four axes at mutually fixed distances (a complete quadrilateral of "
                           "meshes): whether they lie in one plane is not modelled; carry fewer meshes on it")
        for cycle in sorted(nx.simple_cycles(graph), key=lambda c: (len(c), sorted(map(repr, c)))):
            sides = zip(cycle, cycle[1:] + cycle[:1])
            out.append((t, [graph.edges[u, v]["meshes"] for u, v in sides]))
    return out


def _carrier_geometry(model, train: GearTrain, centre: list) -> None:
    """The meshes a carrier holds between the same two axes share one centre distance, and the
    distances around every cycle of its axes close (each side at most the sum of the others)."""
    for members in _centre_groups(train).values():
        for k in members[1:]:
            model.add(centre[k] == centre[members[0]])
    for _, sides in carrier_cycles(train):
        lengths = [centre[group[0]] for group in sides]
        for j, side in enumerate(lengths):
            model.add(side <= sum(lengths[:j] + lengths[j + 1:]))


def planet_clearance(planets: int, planet_teeth: int) -> int:
    """The least centre distance 2a/m (z_sun + z_planet, or z_ring − z_planet) at which ``planets``
    equally spaced planets of ``planet_teeth`` teeth clear each other: neighbours stand
    2a·sin(π/k) apart and a planet's tip circle has the diameter m(z_planet + 2), so
    (2a/m)·sin(π/k) > z_planet + 2.  Exact (sin² π/k is rational for k = 2, 3, 4, 6; otherwise
    irrational, so the bound is never met with equality).

    >>> planet_clearance(3, 17), planet_clearance(6, 20)   # 3: 19/sin 60° = 21.9…; 6: 22/(1/2) = 44
    (22, 45)
    """
    import math

    if planets < 2:
        return 0  # one planet has no neighbour
    exact = {2: Fraction(1), 3: Fraction(3, 4), 4: Fraction(1, 2), 6: Fraction(1, 4)}.get(planets)
    tip = planet_teeth + 2
    if exact is None:
        return math.floor(tip / math.sin(math.pi / planets)) + 1
    least = math.isqrt(int(tip * tip / exact))  # D² sin² > tip²
    while least * least * exact <= tip * tip:
        least += 1
    return least


def _planets_clear(model, train: GearTrain, names, z, centre, planets: int, lo: int, hi: int, kind=None) -> None:
    """k equally spaced planets clear each other: per planet wheel, its mesh's centre distance at
    least :func:`planet_clearance` of its teeth (a table over lo..hi)."""
    if planets < 2:
        return
    table = [planet_clearance(planets, v) for v in range(lo, hi + 1)]
    done = set()
    for c1, p1, k1, s1, c2, p2, k2, s2 in _planet_meshes(train, names):
        for planet, k, side in ((p1, k1, s1), (p2, k2, s2)):
            if kind is None and train.internal[k] and side == 0:
                continue  # the planet is the ring: no planet pair
            if (planet, k) in done:
                continue
            done.add((planet, k))
            index = model.new_int_var(0, hi - lo, f"clear_index_{planet}_{k}")
            model.add(index == z[planet] - lo)
            least = model.new_int_var(min(table), max(table), f"clear_{planet}_{k}")
            model.add_element(index, table, least)
            rule = model.add(centre[k] >= least)
            if kind is not None:
                rule.only_enforce_if(kind["ring_first" if side == 0 else "ring_second"][k].negated())


def _planet_meshes(train: GearTrain, names) -> list[tuple]:
    """Pairs of meshes (k1, k2) in which one planet p, turning on carrier t about one axis, meshes
    two central gears c1, c2 that turn on t about one other axis: (c1, p1, k1, side1, c2, p2, k2,
    side2) with the wheels' names and the planet's side in each mesh (0: its first gear)."""
    central: dict = {}
    for k, (a, b, t) in enumerate(train.triples):
        for planet, centre, side in ((b, a, 1), (a, b, 0)):
            own = next((x for x in train.axes if planet in x and t in x), None)
            if own is None:  # a floating gear is no planet
                continue
            axis = _axis_of(train, centre, t, own)
            central.setdefault((t, planet, own, axis), []).append((names[k][1 - side], names[k][side], k, side))
    return [first + second for meshes in central.values() for first, second in zip(meshes, meshes[1:])]


def planet_pairs(train: GearTrain, names) -> list[tuple[str, str, str, str, int]]:
    """The pairs of meshes that fix where equally spaced planets can go: a planet p turning on
    carrier t about one axis meshes two central gears c1, c2 that turn on t about one other axis
    (a planet that would be a ring around its central gear does not count).  Each as (z_c1, z_p1,
    z_c2, z_p2, ε1·ε2): the wheels, ε = +1 for a sun (external mesh), −1 for a ring (internal).

    >>> planet_pairs(GearTrain.parse("0-1-2 2-3 0~3i 1~3"), [("z0", "z3_0"), ("z1", "z3_1")])
    [('z0', 'z3_0', 'z1', 'z3_1', -1)]
    """
    inner = train.internal
    return [(c1, p1, c2, p2, (-1 if inner[k1] else 1) * (-1 if inner[k2] else 1))
            for c1, p1, k1, s1, c2, p2, k2, s2 in _planet_meshes(train, names)
            if not (inner[k1] and s1 == 0) and not (inner[k2] and s2 == 0)]


def _assembly(model, train: GearTrain, names, z, planets: int, lo: int, hi: int, kind=None) -> None:
    """k equally spaced planets assemble: for every planet meshing two central gears on one carrier,
    (z_c1·z_p2 − ε1ε2·z_c2·z_p1) / (k·gcd(z_p1, z_p2)) is a whole number — (z_sun + z_ring)/k for a
    simple planet, (z_sun·z_p2 + z_ring·z_p1)/(k·gcd(z_p1, z_p2)) for a stepped one (z_p1 meshing the
    sun, z_p2 the ring).  A stepped planet's condition is written with Bézout's identity: the
    quotient by k is j1·z_p1 + j2·z_p2 for some whole j1, j2 (0 ≤ j1 < z_p2 is enough).  With mesh
    kinds chosen by the solver (``kind``), ε is each mesh's sign and a pair counts unless its
    planet is the ring."""
    if kind is None:
        pairs = [(c1, p1, c2, p2, sign, []) for c1, p1, c2, p2, sign in planet_pairs(train, names)]
    else:
        pairs = []
        for c1, p1, k1, s1, c2, p2, k2, s2 in _planet_meshes(train, names):
            sign = model.new_int_var(-1, 1, f"sign_{c1}_{c2}")
            model.add_multiplication_equality(sign, [kind["sign"][k1], kind["sign"][k2]])
            not_ring = [kind["ring_first" if s == 0 else "ring_second"][k].negated() for k, s in ((k1, s1), (k2, s2))]
            pairs.append((c1, p1, c2, p2, sign, not_ring))
    if not pairs:
        raise NoDesign("equally spaced planets need a planet wheel that meshes a sun and a ring on one carrier, "
                       "and this train has none")
    span = 2 * hi * hi
    for c1, p1, c2, p2, sign, when in pairs:
        tag = f"{c1}_{c2}"
        if isinstance(sign, int):
            second = z[c2] if p1 == p2 else None
            signed = sign
        else:  # ε1ε2·z_c2 (·z_p1) as a product
            second = model.new_int_var(-span, span, f"signed_{tag}")
            model.add_multiplication_equality(second, [sign, z[c2]] + ([] if p1 == p2 else [z[p1]]))
            signed = 1
        if p1 == p2:  # one planet wheel: (z_c1 − ε1ε2·z_c2)/k whole
            turns = model.new_int_var(-2 * hi, 2 * hi, f"assembly_{tag}")
            model.add(z[c1] - signed * second == planets * turns).only_enforce_if(when)
            continue
        top = span // lo + hi
        first = model.new_int_var(0, span, f"{c1}·{p2}")
        model.add_multiplication_equality(first, [z[c1], z[p2]])
        if second is None:
            second = model.new_int_var(0, span, f"{c2}·{p1}")
            model.add_multiplication_equality(second, [z[c2], z[p1]])
        j1, j2 = model.new_int_var(0, hi, f"j1_{tag}"), model.new_int_var(-top, top, f"j2_{tag}")
        u1, u2 = model.new_int_var(0, hi * hi, f"u1_{tag}"), model.new_int_var(-top * hi, top * hi, f"u2_{tag}")
        model.add_multiplication_equality(u1, [j1, z[p1]])
        model.add_multiplication_equality(u2, [j2, z[p2]])
        model.add(first - signed * second == planets * (u1 + u2)).only_enforce_if(when)
        model.add(j1 < z[p2])
