"""The ``[slider]`` problem: what it reads from its table, what it prices before it works, and what it hands
to the counter-mass laws and to the mass-matrix check.

The values by hand: a 2 kg link of central inertia 0.1 kg·m² with two 2 kg counter-masses and a designed stroke
of ±0.5 m needs at least C_min = I + (m² + 2mM)·q_max²/(2M) = 0.1 + 12·0.25/4 = 0.85 kg·m²; with C = 1 kg·m² the
laws stay real up to |q| = sqrt(2M(C − I)/(m² + 2mM)) = sqrt(3.6/12) = sqrt(0.3) m.
"""

from __future__ import annotations

import inspect
import math

import pytest

import balance.problems.slider as slider_module
from balance import SchemaError
from balance.budget import TooMuchWork
from balance.devices.countermass import verify_counter_mass
from balance.devices.dynamics import slide_dynamics
from balance.errors import InvalidInput
from balance.problems.slider import DynamicsCheck, SliderProblem, slider_problem

LINK = dict(m=2.0, inertia=0.1, M=2.0, q_max=0.5)


def test_the_stroke_the_constant_and_the_samples_given_reach_the_laws():
    res = SliderProblem(**LINK, stroke=0.4, C=1.0, samples=101).solve().counter_mass
    assert (res.stroke, res.C, res.samples) == (0.4, 1.0, 101)
    assert res.C_min == pytest.approx(0.85, abs=1e-15)
    assert res.law_valid_stroke == pytest.approx(math.sqrt(0.3), abs=1e-15)
    assert res.max_com_error < 1e-12 and res.max_inertia_error < 1e-12  # ±0.4 m is inside ±0.548 m


def test_a_stroke_past_what_the_constant_allows_is_reported():
    """At C = C_min the laws are real up to q_max = 0.5 m exactly; at q = 0.6 m the inertia cannot be kept: the
    roots are clipped at 0, so z1 = z2 = −m·q/(2M) and the inertia passes C by
    I + m·q² + 2M·(m·q/(2M))² − C = 0.1 + 0.72 + 0.36 − 0.85 = 0.33 kg·m² (inside ±0.5 m it is kept)."""
    res = SliderProblem(**LINK, stroke=0.6, samples=201).solve().counter_mass
    assert res.stroke == 0.6 and res.C == pytest.approx(0.85)
    assert res.max_inertia_error == pytest.approx(0.33, rel=1e-9)
    assert any(msg.startswith("the stroke ±0.6 m exceeds ±0.5 m") for msg in res.messages)


def test_a_check_too_large_is_refused_with_its_size_and_a_price_per_point():
    with pytest.raises(TooMuchWork) as ei:
        SliderProblem(**LINK, samples=10**12).solve()
    assert str(ei.value).startswith("checking the laws at 1000000000000 points would take about ")
    # the price of a point is one 64-point check of the laws over 64 (tens of µs and more), never a bare call
    assert ei.value.seconds / 10**12 > 1e-6 and ei.value.limit == 30.0


def test_the_work_limit_given_is_the_one_applied():
    """A limit of a nanosecond refuses even three points; the same problem with the limit lifted is solved."""
    with pytest.raises(TooMuchWork) as ei:
        SliderProblem(**LINK, samples=3, work_limit=1e-9).solve()
    assert ei.value.limit == 1e-9 and str(ei.value).startswith("checking the laws at 3 points would take")
    assert SliderProblem(**LINK, samples=3, work_limit=None).solve().counter_mass.samples == 3


@pytest.mark.parametrize("kwargs, sentence", [
    (dict(stroke=-1.0), "the stroke must be a finite number > 0, not -1.0."),
    (dict(C=0.05), "the inertia constant C must be finite and at least I = 0.1, not 0.05."),
])
def test_a_bad_stroke_or_constant_is_refused_before_the_size_of_the_work(kwargs, sentence):
    """The pricing runs the check itself on 64 points: a bad input is refused in its own words there, not as too
    much work (the samples here would take days)."""
    with pytest.raises(InvalidInput) as ei:
        SliderProblem(**LINK, samples=10**12, **kwargs).solve()
    assert not isinstance(ei.value, TooMuchWork) and str(ei.value) == sentence


def test_a_mass_matrix_check_too_large_is_refused_with_its_size():
    with pytest.raises(TooMuchWork) as ei:
        SliderProblem(**LINK, samples=3, dynamics=DynamicsCheck(samples=10**12)).solve()
    assert str(ei.value).startswith("the mass-matrix check at 1000000000000 configurations would take about ")
    assert ei.value.seconds / 10**12 > 1e-6  # one configuration of Pinocchio's mass matrices, not a bare call


def _recording(monkeypatch, name, calls):
    """Replace the slider module's ``name`` by a call that records its bound arguments and calls the real one."""
    real = getattr(slider_module, name)
    signature = inspect.signature(real)

    def record(*args, **kwargs):
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        calls.append(dict(bound.arguments))
        return real(*args, **kwargs)

    monkeypatch.setattr(slider_module, name, record)


def test_the_work_is_priced_on_64_points_and_one_configuration_of_the_same_problem(monkeypatch):
    priced, laws, dynamics = [], [], []
    _recording(monkeypatch, "ensure_affordable", priced)
    _recording(monkeypatch, "verify_counter_mass", laws)
    _recording(monkeypatch, "slide_dynamics", dynamics)
    check = DynamicsCheck(arm="planar", length=0.7, mass=4.0, samples=5, seed=3)
    res = SliderProblem(**LINK, stroke=0.4, C=1.0, samples=101, dynamics=check, work_limit=600.0).solve()
    assert [(p["what"], p["count"], p["limit"], p["per"]) for p in priced] == [
        ("checking the laws at 101 points", 101, 600.0, 64),
        ("the mass-matrix check at 5 configurations", 5, 600.0, 1.0)]
    same = dict(m=2.0, inertia=0.1, M=2.0, q_max=0.5, stroke=0.4, C=1.0)
    # the price (one 64-point check, timed a few times), then the check
    assert laws[:-1] and all(c == {**same, "samples": 64} for c in laws[:-1]) and laws[-1] == {**same, "samples": 101}
    arm = dict(m=2.0, inertia=0.1, M=2.0, q_max=0.5, kind="planar", length=0.7, parent_mass=4.0, seed=3)
    assert dynamics[:-1] and all(c == {**arm, "samples": 1} for c in dynamics[:-1])
    assert dynamics[-1] == {**arm, "samples": 5}
    assert res.dynamics == slide_dynamics(2.0, 0.1, 2.0, 0.5, "planar", 0.7, 4.0, 5, 3)
    assert res.counter_mass == verify_counter_mass(2.0, 0.1, 2.0, 0.5, 0.4, 1.0, 101)


def test_the_table_is_read_into_the_problem_whole():
    doc = {"slider": {"mass": 2, "inertia": 0.1, "counter_mass": 3, "q_max": 0.5, "stroke": 0.3, "C": 1.2,
                      "samples": 11, "dynamics": {"arm": "planar", "length": 0.6, "mass": 5, "samples": 7, "seed": 9}}}
    pb = slider_problem(doc, "s.toml")
    assert (pb.m, pb.inertia, pb.M, pb.q_max, pb.stroke, pb.C, pb.samples) == (2, 0.1, 3, 0.5, 0.3, 1.2, 11)
    assert pb.dynamics == DynamicsCheck("planar", 0.6, 5, 7, 9)
    bare = slider_problem({"slider": {"mass": 2, "counter_mass": 2, "q_max": 0.5}})
    assert (bare.inertia, bare.stroke, bare.C, bare.samples, bare.dynamics) == (0.0, None, None, 2001, None)


def test_a_table_read_without_a_file_is_named_slider():
    with pytest.raises(SchemaError) as ei:
        slider_problem({"slider": {"mass": "2", "counter_mass": 2, "q_max": 0.5}})
    assert str(ei.value) == "<slider>: [slider] key 'mass' must be a number, not '2'."
