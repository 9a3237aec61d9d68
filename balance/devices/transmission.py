"""Gear trains that form each device shaft's angle ``φ_k`` from the drive shafts.

A harmonic term's linear form over the drive shafts, ``φ = Σ a_j·ψ_j``, is built from
three elements (ratios ``i = ω_in/ω_out``, negative when the stage reverses):

- a **gear stage** (reducer, or spur pair) of ratio ``i``: ``ω_out = ω_in/i``;
- a **differential** (bevel gears, equal side gears): ``ω_side1 + ω_side2 = 2·ω_carrier``,
  used with the carrier and one side gear as inputs and the other side gear as output,
  ``ω_out = 2·ω_carrier − ω_side``.

A single-shaft form is one stage of ratio ``1/a`` (none when ``a = 1``: the crank sits on
the shaft). Otherwise the first positive term drives the carrier of a differential
through a reducer of ratio ``2/a``, the next term drives a side gear through a stage of
ratio ``−1/a_j``, and each further term adds a differential whose carrier takes the
previous output through a reducer of ratio 2. For the arm with base drives this gives
the textbook's train: ``φ_k = ψ_{k+1} − ψ1`` by a differential whose carrier is driven
from shaft ``ψ_{k+1}`` through a reducer of ratio 2 and whose side gear is driven from
shaft ``ψ1`` through a spur stage of ratio 1.

:func:`compose` multiplies the ratios back into the linear form: the check.

Examples
--------
>>> train = design_train([-1.0, 1.0, 0.0], ["ψ1", "ψ2", "ψ3"], "φ1")
>>> [(s.element, s.ratio) for s in train]
[('reducer', 2.0), ('spur stage', 1.0), ('differential', None)]
>>> compose(train, ["ψ1", "ψ2", "ψ3"])
[-1.0, 1.0, 0.0]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from mechbase import Row

__all__ = ["GearElement", "GearTrain", "design_train", "compose", "transmissions"]


@dataclass(frozen=True)
class GearElement(Row):
    """One element of a train: a gear stage, a differential, or the crank on the shaft itself.

    Attributes
    ----------
    element : {"reducer", "spur stage", "step-up stage", "differential", "shaft"}
    output : str
        The shaft it drives.
    input : str or None
        A stage's (or the shaft's) input shaft.
    ratio : float or None
        A stage's ``i = ω_in/ω_out`` (negative when it reverses); None for a differential.
    carrier, side : str or None
        A differential's inputs: ``ω_out = 2·ω_carrier − ω_side``.
    """

    element: str
    output: str
    input: str | None = None
    ratio: float | None = None
    carrier: str | None = None
    side: str | None = None

    @property
    def reverses(self) -> bool:
        return self.ratio is not None and self.ratio < 0

    @property
    def row_keys(self) -> tuple[str, ...]:
        """The row: a differential's two inputs, or a stage's input."""
        if self.element == "differential":
            return ("element", "carrier", "side", "output", "ratio", "reverses")
        return ("element", "input", "output", "ratio", "reverses")


@dataclass(frozen=True)
class GearTrain(Row):
    """The train forming one device shaft ``shaft = Σ form_j·ψ_j``, with the form it composes back to."""

    term: int
    shaft: str
    form: tuple[float, ...]
    train: tuple[GearElement, ...]
    composed_form: tuple[float, ...]

    row_keys = ("term", "shaft", "form", "train", "differentials", "composed_form", "error")

    @property
    def differentials(self) -> int:
        return sum(el.element == "differential" for el in self.train)

    @property
    def error(self) -> float:
        """The largest coefficient error of the composed form."""
        return float(np.max(np.abs(np.subtract(self.composed_form, self.form)))) if self.form else 0.0



def _stage(src: str, dst: str, ratio: float) -> GearElement:
    kind = "spur stage" if abs(abs(ratio) - 1) <= 1e-12 else ("reducer" if abs(ratio) > 1 else "step-up stage")
    return GearElement(kind, dst, src, float(ratio))


def design_train(form: Sequence[float], shafts: Sequence[str], name: str, tol: float = 1e-12) -> list[GearElement]:
    """Stages and differentials forming ``name = Σ form_j·shafts_j``; see the module docstring."""
    terms = [(j, float(a)) for j, a in enumerate(form) if abs(a) > tol]
    if not terms:
        return []
    terms.sort(key=lambda t: t[1] <= 0)  # a positive term first: it drives the carrier
    (j0, a0), rest = terms[0], terms[1:]
    if not rest:
        if abs(a0 - 1) <= tol:
            return [GearElement("shaft", name, shafts[j0], 1.0)]
        return [_stage(shafts[j0], name, 1 / a0)]
    out: list[GearElement] = []
    carrier_src, carrier_ratio = shafts[j0], 2 / a0
    for n, (j, a) in enumerate(rest):
        last = n == len(rest) - 1
        c_in = f"{name}.c{n + 1}"
        s_in = f"{name}.s{n + 1}"
        dst = name if last else f"{name}.{n + 1}"
        out.append(_stage(carrier_src, c_in, carrier_ratio))
        out.append(_stage(shafts[j], s_in, -1 / a))
        out.append(GearElement("differential", dst, carrier=c_in, side=s_in))
        carrier_src, carrier_ratio = dst, 2.0
    return out


def compose(train: Sequence[GearElement], shafts: Sequence[str]) -> list[float]:
    """The linear form a train realises, by propagating each drive shaft's unit motion."""
    n = len(shafts)
    speed = {s: np.eye(n)[j] for j, s in enumerate(shafts)}
    last = None
    for el in train:
        if el.element == "differential":
            speed[el.output] = 2 * speed[el.carrier] - speed[el.side]
        else:
            speed[el.output] = speed[el.input] / el.ratio
        last = el.output
    if last is None:
        return [0.0] * n
    return [float(v) for v in speed[last]]


def transmissions(drive_forms: Sequence[Sequence[float]], shafts: Sequence[str]) -> list[GearTrain]:
    """A train per term with the form it composes back to."""
    out = []
    for k, form in enumerate(drive_forms):
        name = f"φ{k + 1}"
        train = design_train(form, shafts, name)
        out.append(GearTrain(k, name, tuple(float(v) for v in form), tuple(train), tuple(compose(train, shafts))))
    return out
