"""The resource contract (balance.budget): the estimate, the refusal at the limit and its sentence."""

from __future__ import annotations

import pytest

from balance import budget
from balance.budget import TooMuchWork, duration, ensure_affordable, unit_seconds
from balance.errors import InvalidInput


@pytest.mark.parametrize("seconds, text", [
    (0.4, "0.4 s"), (89, "89 s"), (89.9, "90 s"), (90, "2 min"), (149, "2 min"), (151, "3 min"),
    (5399, "90 min"), (5400, "2 h"), (86399, "24 h"), (86400, "1 day"), (129599, "1 day"),
    (129600, "2 days"), (3e6, "35 days"), (30.0, "30 s"),
])
def test_durations_in_words(seconds, text):
    assert duration(seconds) == text


@pytest.mark.parametrize("seconds, text", [
    (1e-4, "100 µs"), (9.99e-4, "999 µs"), (1e-3, "1 ms"), (2.5e-3, "2.5 ms"), (0.3, "300 ms"), (1.0, "1 s"),
    (12.34, "12.3 s"), (9.994995e-4, "999 µs"), (9.996e-4, "1 ms"), (0.9994995, "999 ms"), (0.9996, "1 s"),
])
def test_short_times(seconds, text):
    assert budget._short(seconds) == text


def test_one_unit_costs_its_fastest_call(monkeypatch):
    clock = iter([0.0, 5.0, 10.0, 12.0, 20.0, 23.0, 30.0, 30.5])  # calls of 5, 2, 3, 0.5 s
    monkeypatch.setattr(budget.time, "perf_counter", lambda: next(clock))
    calls = []
    assert unit_seconds(lambda: calls.append(1)) == 2.0 and len(calls) == 3
    assert unit_seconds(lambda: calls.append(1), repeat=1) == 0.5 and len(calls) == 4


def test_the_estimate_and_the_refusal():
    assert ensure_affordable("x", 10, 1e-4, limit=1.0) == pytest.approx(1e-3, rel=1e-12)
    assert ensure_affordable("x", 10, 3, limit=30) == 30  # an int price; exactly the limit is allowed
    assert ensure_affordable("x", 100, 1.0, limit=1.0, per=100) == 1.0  # one call does 100 units
    assert ensure_affordable("x", 1e12, 1.0, limit=None) == 1e12  # no limit: the estimate only
    assert ensure_affordable("x", 4, lambda: None) < 1e-3  # a timed call
    with pytest.raises(TooMuchWork) as caught:
        ensure_affordable("checking 1e9 configurations", 10**9, 1e-4, limit=30.0, per=2)
    exc = caught.value
    assert isinstance(exc, InvalidInput) and exc.seconds == pytest.approx(5e4) and exc.limit == 30.0
    assert str(exc) == ("checking 1e9 configurations would take about 14 h (50 µs each, measured here), more than "
                        "the 30 s a problem may take unless its limit is lifted")
    with pytest.raises(TooMuchWork, match="about 31 s"):
        ensure_affordable("x", 31, 1.0)  # the default limit, 30 s
    assert budget.WORK_LIMIT == 30.0
