"""Shaking-force and gravity balancing of a dimensioned 1-DOF linkage by counterweights.

The linkage reaches this package as its moving links (:class:`~balance.model.linkage.LinkBody`:
joints, mass, centre) and a callable giving every link's pose and its derivatives at input values
(the application moves the linkage; ``balance`` never imports ``synth``).  Counterweights on the
chosen links (default: those pivoted on the frame) are fitted to make the total first moment M(q)
constant (:mod:`balance.devices.link_counterweights`); before and after, the centre of mass's largest
excursion, the shaking force's largest amplitude per ω² and the gravity potential's variation are true
extremes over the input's range (:func:`balance.extremes.box_extremes`).

Examples
--------
>>> import numpy as np
>>> from balance.model.linkage import LinkBody
>>> crank = LinkBody(1, (("0-1", (0.0, 0.0)), ("1-2", (1.0, 0.0))), 2.0, (0.5, 0.0), "0-1")
>>> def motion(q):                                   # a lone crank turning about the origin
...     z = np.zeros((len(q), 2, 2))
...     return np.c_[0 * q, q], z, np.c_[0 * q, 1 + 0 * q], z, np.zeros((len(q), 2)), z
>>> res = LinkageProblem("crank", 2, (crank,), motion, "0-1", (0.0, 2 * np.pi)).solve()
>>> round(res.before.shaking_force, 9), res.full_balance, round(res.counterweights[0].mass, 9)
(1.0, True, 1.0)
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from mechbase import Row

from ..budget import WORK_LIMIT, ensure_affordable
from ..devices.link_counterweights import LinkCounterweight, fit_counterweights
from ..errors import InvalidInput
from ..extremes import EXTREMES_NOTE, box_extremes
from ..model.linkage import LinkBody, Motion, body_arrays, first_moment, moment_rate

__all__ = ["LinkageProblem", "LinkageBalance", "BalanceState"]

#: full balance: what is left of the first moment's excursion, relative to the linkage's own, is rounding
FULL_BALANCE = 1e-9
#: the samples of the input a solve takes (the fit needs more equations than unknowns; memory bounds the most)
MIN_SAMPLES, MAX_SAMPLES = 9, 100_000
#: input pairs sampled for the centre of mass's largest excursion (a 2-D search)
PAIRS = 2000
#: the work of a solve, in moves of the linkage over its samples (measured: 5–20 on the models' linkages)
MOVES = 25


@dataclass(frozen=True)
class BalanceState(Row):
    """How unbalanced the linkage is with one set of masses, over the input's range.

    Attributes
    ----------
    total_mass : float
        kg.
    moment_excursion : float
        The largest distance between two values of the first moment M over the range (kg·m).
    com_excursion : float
        The same of the centre of mass, M / total mass (m).
    shaking_force : float or None
        The largest |M''|: the shaking force's amplitude per ω² of the input (N per (rad/s)², or per
        (m/s)² for a prismatic input) at a constant input speed; None where the range ends at a dead
        position (unbounded there).
    shaking_force_at : float or None
        The input where it is reached (rad or m).
    potential_variation : float
        The largest less the smallest gravity potential −g·M over the range (J).
    shaking_moment : float or None
        The largest |dH/dt| per ω² at a constant input speed, H the links' angular momentum about the input
        joint's point (N·m per (rad/s)², or per (m/s)²); None at dead ends or where a link's inertia is not
        known.  Reported, not minimised by the counterweights.
    shaking_moment_at : float or None
        The input where it is reached.
    """

    total_mass: float
    moment_excursion: float
    com_excursion: float
    shaking_force: float | None
    shaking_force_at: float | None
    potential_variation: float
    shaking_moment: float | None = None
    shaking_moment_at: float | None = None


@dataclass(frozen=True)
class LinkageBalance(Row):
    """Counterweights found for a linkage, and its unbalance before and after (true extremes).

    ``carried``: the counterweights the links carried already (counted in ``before``); ``residual_share``:
    the first moment's largest excursion after, relative to that of the links alone (no counterweight)."""

    name: str
    input: str
    input_kind: str
    input_range: tuple[float, float]
    links: tuple[LinkBody, ...]
    carried: tuple[LinkBody, ...]
    on: tuple[int, ...]
    counterweights: tuple[LinkCounterweight, ...]
    before: BalanceState
    after: BalanceState
    full_balance: bool
    residual_share: float
    notes: tuple[str, ...]
    problem: "LinkageProblem" = field(repr=False, compare=False)

    kind: ClassVar[str] = "linkage"
    extremes: ClassVar[str] = EXTREMES_NOTE
    row_keys = ("kind", "name", "input", "input_kind", "input_range", "shaking_force_unit", "links", "carried", "on",
                "counterweights", "added_mass", "before", "after", "full_balance", "residual_share", "notes",
                "extremes")

    @property
    def added_mass(self) -> float:
        return float(sum(c.mass for c in self.counterweights))

    @property
    def shaking_force_unit(self) -> str:
        return "N per (rad/s)²" if self.input_kind == "revolute" else "N per (m/s)²"

    def bodies(self, balanced: bool) -> tuple[LinkBody, ...]:
        """The links and the counterweights they carried, with the counterweights found (point masses) or
        without."""
        found = tuple(LinkBody(c.link, (), c.mass, c.at, None, 0.0) for c in self.counterweights if balanced)
        return self.links + self.carried + found

    def masses(self, balanced: bool) -> tuple[np.ndarray, np.ndarray]:
        """Mass (n,) and first moment (n, 2) per link (the counterweights it carried included), with the
        counterweights found or without."""
        return body_arrays(self.bodies(balanced), self.problem.links)


@dataclass(frozen=True)
class LinkageProblem:
    """A linkage of ``links`` links (the moving ones in ``bodies``, with their masses) moved by ``motion``
    (input values → (θ, t, θ', t', θ'', t'')) over ``input_range``; counterweights on the links ``on``
    (default: those pivoted on the frame), of mass ``counter_mass`` or at ``counter_radius`` from their
    pivot if given; gravity ``gravity`` (m/s², default −y).  ``carried``: counterweights the links already
    carry (a linkage balanced before: each a point mass, its ``centre`` where it sits in the pose), counted
    in the unbalance before and in the fit.  ``moment_about``: the point of the shaking moment.
    ``dead_ends``: the range ends at dead positions (the shaking force and moment per ω² are unbounded
    there and not reported)."""

    name: str
    links: int
    bodies: tuple[LinkBody, ...]
    motion: Motion
    input: str
    input_range: tuple[float, float]
    input_kind: str = "revolute"
    dead_ends: bool = False
    on: tuple[int, ...] | None = None
    counter_mass: float | None = None
    counter_radius: float | None = None
    gravity: tuple[float, float] = (0.0, -9.81)
    samples: int = 361
    carried: tuple[LinkBody, ...] = ()
    moment_about: tuple[float, float] = (0.0, 0.0)
    work_limit: float | None = WORK_LIMIT

    def solve(self) -> LinkageBalance:
        lo, hi = self.input_range
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise InvalidInput(f"the input's range must be two finite numbers, low below high, not {lo:g}..{hi:g}.")
        if not MIN_SAMPLES <= self.samples <= MAX_SAMPLES:
            raise InvalidInput(f"the samples of the input must be {MIN_SAMPLES} … {MAX_SAMPLES:,}, not {self.samples}.")
        if not all(math.isfinite(g) for g in self.gravity):
            raise InvalidInput("gravity must be two finite numbers [gx, gy] (m/s²).")
        on = self._on()
        turn = self.input_kind == "revolute" and math.isclose(hi - lo, 2 * math.pi, rel_tol=1e-12)
        qs = np.linspace(lo, hi, self.samples, endpoint=not turn)  # a whole turn: each input once
        start = time.process_time()
        sampled = self.motion(qs)
        ensure_affordable(f"the fit and the searches for the largest values (about {MOVES} moves of the linkage over "
                          f"its {self.samples} samples)", MOVES, time.process_time() - start, self.work_limit)
        weights = fit_counterweights(self.bodies + self.carried, on, sampled, self.links, self.counter_mass,
                                     self.counter_radius)
        draft = LinkageBalance(self.name, self.input, self.input_kind, (lo, hi), self.bodies, self.carried,
                               tuple(b.link for b in on), weights, None, None, False, 0.0, (), self)
        before = self._state(draft.bodies(False), qs)
        own = self._state(self.bodies, qs) if self.carried else before  # no counterweight
        floor = 1e-12 * max(own.moment_excursion, own.shaking_force or 0.0, 1e-300)
        after = self._state(draft.bodies(True), qs, floor)
        share = after.moment_excursion / own.moment_excursion if own.moment_excursion > 0 else 0.0
        full = share <= FULL_BALANCE
        return LinkageBalance(self.name, self.input, self.input_kind, (lo, hi), self.bodies, self.carried, draft.on,
                              weights,
                              before, after, full, share, self._notes(full, share, draft.on, sampled), self)

    def _on(self) -> list[LinkBody]:
        """The bodies that get a counterweight."""
        by_link = {b.link: b for b in self.bodies}
        if self.on is None:
            on = [b for b in self.bodies if b.pivot is not None]
            if not on:
                raise InvalidInput("no moving link is pivoted on the frame: name the links to carry counterweights "
                                   "(--on, or 'on' in the table).")
            return on
        for link in self.on:
            if link not in by_link:
                raise InvalidInput(f"link {link} cannot carry a counterweight: it is the frame or no link of the "
                                   f"linkage (the moving links are {', '.join(str(k) for k in sorted(by_link))}).")
        if len(set(self.on)) != len(self.on):
            raise InvalidInput("a link is named twice in the links to carry counterweights.")
        return [by_link[k] for k in self.on]

    def _state(self, bodies: tuple[LinkBody, ...], qs: np.ndarray, floor: float = 0.0) -> BalanceState:
        """The unbalance with these bodies: each largest value polished from the samples ``qs``."""
        lo, hi = self.input_range
        gravity = np.asarray(self.gravity, dtype=float)
        mass, moment = body_arrays(bodies, self.links)
        turning = not self.dead_ends and all(b.inertia is not None for b in bodies)

        def per_input(x):
            motion = self.motion(x[:, 0])
            columns = [-(first_moment(mass, moment, motion) @ gravity)]
            if not self.dead_ends:
                columns.append(np.hypot(*first_moment(mass, moment, motion, order=2).T))
            if turning:
                columns.append(np.abs(moment_rate(bodies, motion, self.moment_about)))
            return np.stack(columns, axis=1)

        def spread(x):
            motion = self.motion(x.reshape(-1))
            m = first_moment(mass, moment, motion).reshape(len(x), 2, 2)
            return np.hypot(*(m[:, 0] - m[:, 1]).T)

        found = box_extremes(per_input, [lo], [hi], qs[:, None], floor=floor)
        (v_min, v_max) = found[0]
        force, force_at = (None, None) if self.dead_ends else (found[1][1].value, found[1][1].at[0])
        turn, turn_at = (found[-1][1].value, found[-1][1].at[0]) if turning else (None, None)
        pairs = np.random.default_rng(0).uniform(lo, hi, (PAIRS, 2))
        (_, widest), = box_extremes(spread, [lo, lo], [hi, hi], pairs, floor=floor)
        total = float(mass.sum())
        return BalanceState(total, widest.value, widest.value / total if total > 0 else 0.0, force, force_at,
                            v_max.value - v_min.value, turn, turn_at)

    def _notes(self, full: bool, share: float, on: tuple[int, ...], sampled: tuple) -> tuple[str, ...]:
        notes = []
        if self.carried:
            notes.append("the links carry counterweights already (" + ", ".join(
                f"{b.mass:.6g} kg on link {b.link}" for b in self.carried) + "), counted before; what is left is "
                "measured against the links without any")
        unknown = [str(b.link) for b in self.bodies if b.inertia is None]
        if unknown and not self.dead_ends:
            notes.append(f"the shaking moment is not reported: link{'s' * (len(unknown) > 1)} {', '.join(unknown)} "
                         "give no inertia (kg·m² about the centre: 'inertia' beside its mass, or --density)")
        if self.dead_ends:
            notes.append("the range ends at dead positions, where the links' rates per unit input rate are unbounded: "
                         "the shaking force and moment per ω² are not reported (give a range inside the limits)")
        if not full:
            links = ", ".join(map(str, on))
            notes.append(f"not fully balanced: counterweights on link{'s' * (len(on) > 1)} {links} leave "
                         f"{100 * share:.3g}% of the first moment's excursion; what is left is no combination of "
                         "those links' rotations (add counterweights on other links, floating ones included)")
            rates, moves = sampled[2], sampled[3]
            sliding = [b.link for b in self.bodies if b.mass > 0 and np.nanmax(np.abs(rates[:, b.link])) <= 1e-12
                       and np.nanmax(np.abs(moves[:, b.link])) > 0]
            if sliding:
                notes.append(f"link{'s' * (len(sliding) > 1)} {', '.join(map(str, sliding))} translate"
                             f"{'s' * (len(sliding) == 1)} without turning (a slider): a counterweight cannot "
                             "follow a mass along a guide")
        return tuple(notes)
