"""The small helpers every floor leans on, each against values worked out by hand or a slow method:
sizes and durations in words (every unit's boundary on both sides), the read-only SQLite address,
the pair of finite numbers every point and pair of limits is read by, union–find against a breadth-first search, one BLAS thread, lazy exports and notebook drawings.
"""

from __future__ import annotations

import math
import random
import sqlite3
import sys
import types

import numpy as np
import pytest

from mechbase.pairs import finite_pair
from synth._lazy import lazy_exports
from synth.display import register_drawing, svg_of
from synth.execution.sizes import describe_seconds, magnitude
from synth.execution.sqlite_files import read_only_uri
from synth.structure.disjoint import DisjointSets

DAY = 86400
YEAR = 365.25 * DAY


@pytest.mark.parametrize("seconds, words", [
    (0, "0 s"), (42.4, "42 s"), (119.4, "119 s"),          # seconds below two minutes
    (120, "2 min"), (5400, "90 min"), (7199, "120 min"),    # minutes below two hours
    (7200, "2.0 h"), (9000, "2.5 h"), (144184, "40.1 h"), (2 * DAY - 1, "48.0 h"),  # hours below two days
    (2 * DAY, "2.0 days"), (3e5, "3.5 days"), (8644407, "100.1 days"), (365 * DAY - 1, "365.0 days"),
    (365 * DAY, "1 year"), (1.4 * YEAR, "1 year"), (2 * YEAR, "2 years"),
    (100.5006 * YEAR, "101 years"), (9999 * YEAR, "9999 years"), (1e4 * YEAR, "1e+04 years"),
    (12345 * YEAR, "1.2e+04 years"),
])
def test_a_duration_is_written_in_its_largest_sensible_unit(seconds, words):
    assert describe_seconds(seconds) == words


def test_a_duration_beyond_floating_point_is_written_from_its_logarithm():
    # 10^2000 s = 10^(2000 − log10 31 557 600) years = 10^1992.5009 years = 3.17e+1992
    assert describe_seconds(math.inf, 2000.0) == "3.2e+1992 years"
    assert describe_seconds(math.inf) == "more than 1e+308 years"  # no logarithm given: unknown
    # a Julian year of 365.25 days of 86 400 s: 1.050005e+2000 years is written 1.1e+2000 (a year 1e-5 longer: 1e+2000)
    assert describe_seconds(math.inf, 2000 + math.log10(1.050005) + math.log10(365.25 * 86400)) == "1.1e+2000 years"


@pytest.mark.parametrize("count, words", [
    (0, "0"), (6856.4, "6 856"), (6856.6, "6 857"), (1_234_567, "1 234 567"), (9_999_999, "9 999 999"),
    (1e7, "1e+07"), (1_535_380_884, "1.5e+09"), (3e40, "3e+40"),
])
def test_a_count_is_written_with_spaces_or_in_powers_of_ten(count, words):
    assert magnitude(count) == words


@pytest.mark.parametrize("log10, words", [
    (2400.3, "2e+2400"),      # 10^0.3 = 1.995
    (5.5, "3.2e+5"),          # 10^0.5 = 3.162
    (7.0, "1e+7"),
    (2.99999, "1e+3"),        # 10^0.99999 = 9.99977: rounds to 10, written as 1e+3, not 10e+2
    (1000.96, "9.1e+1000"),   # 10^0.96 = 9.12: below the rounding step
    (4.98, "9.5e+4"),         # 10^0.98 = 9.55: rounds to 9.5 or 9.6 at one decimal, not to 10
    (2.9987, "1e+3"),         # 10^0.9987 = 9.970: 10.0 at one decimal (at two it would be 9.97, written 10e+2)
])
def test_a_count_beyond_floating_point_is_written_from_its_logarithm(log10, words):
    assert magnitude(math.inf, log10) == words


def test_an_infinite_count_without_its_logarithm_is_more_than_the_largest_float():
    assert magnitude(math.inf) == "more than 1e+308"


def test_the_read_only_address_reads_the_file_and_creates_nothing_beside_it(tmp_path, monkeypatch):
    path = tmp_path / "atlas.sqlite"
    with sqlite3.connect(path) as db:
        db.execute("create table t (x)")
        db.execute("insert into t values (7)")
    db.close()
    monkeypatch.chdir(tmp_path)
    relative = read_only_uri(path.relative_to(tmp_path))  # a relative path becomes an absolute file URI
    assert relative == f"file://{path}?mode=ro&immutable=1"
    reader = sqlite3.connect(relative, uri=True)
    assert reader.execute("select x from t").fetchall() == [(7,)]
    with pytest.raises(sqlite3.OperationalError, match="readonly"):
        reader.execute("insert into t values (8)")
    reader.close()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.sqlite"]


def test_a_file_with_a_write_ahead_log_is_read_as_a_live_file(tmp_path):
    path = tmp_path / "count.sqlite"
    writer = sqlite3.connect(path)
    writer.execute("pragma journal_mode=wal")
    writer.execute("create table t (x)")
    writer.execute("insert into t values (1)")
    writer.commit()  # the row is in the -wal file, not yet in the database file
    assert (tmp_path / "count.sqlite-wal").exists()
    uri = read_only_uri(path)
    assert uri == f"{path.as_uri()}?mode=ro"
    reader = sqlite3.connect(uri, uri=True)
    assert reader.execute("select x from t").fetchall() == [(1,)]  # (immutable would not see the log)
    reader.close()
    writer.close()


def _components(items, pairs):
    """The connected components by breadth-first search (the slow method)."""
    neighbours = {x: set() for x in items}
    for a, b in pairs:
        neighbours[a].add(b)
        neighbours[b].add(a)
    seen, parts = set(), []
    for x in items:
        if x in seen:
            continue
        part, todo = set(), [x]
        while todo:
            y = todo.pop()
            if y not in part:
                part.add(y)
                todo.extend(neighbours[y] - part)
        seen |= part
        parts.append(frozenset(part))
    return parts


class _Refused(Exception):
    pass


@pytest.mark.parametrize("value, pair", [
    ([1, 2.5], (1.0, 2.5)), ((-3, 0), (-3.0, 0.0)), (np.array([0.25, 1e300]), (0.25, 1e300)),
    (("1.5", " -2 "), (1.5, -2.0)), (iter([4, 5]), (4.0, 5.0)), ((np.float32(0.5), np.int64(7)), (0.5, 7.0)),
])
def test_a_pair_of_finite_numbers_is_read_as_two_floats(value, pair):
    got = finite_pair(value, error=_Refused, malformed="two numbers", not_finite="not finite")
    assert got == pair and all(type(v) is float for v in got)


@pytest.mark.parametrize("value, sentence", [
    ("12", "two numbers"), (b"12", "two numbers"), ({1: 2, 3: 4}, "two numbers"),  # "12" is no point (1, 2)
    (None, "two numbers"), (3, "two numbers"), ([1], "two numbers"), ([1, 2, 3], "two numbers"),
    ([True, 0], "two numbers"), ([0, False], "two numbers"), ([0, "x"], "two numbers"), ([0, None], "two numbers"),
    ([1j, 0], "two numbers"), (np.zeros((2, 2)), "two numbers"),
    ([math.nan, 0], "not finite"), ([0, -math.inf], "not finite"), (["inf", 0], "not finite"),
])
def test_anything_but_two_finite_numbers_raises_the_callers_error_with_its_sentence(value, sentence):
    with pytest.raises(_Refused) as raised:
        finite_pair(value, error=_Refused, malformed="two numbers", not_finite="not finite")
    assert str(raised.value) == sentence
    with pytest.raises(_Refused) as raised:  # one sentence serves both faults where the caller gives one
        finite_pair(value, error=_Refused, malformed="two finite numbers")
    assert str(raised.value) == "two finite numbers"


@pytest.mark.parametrize("seed", range(20))
def test_union_find_joins_what_a_breadth_first_search_connects(seed):
    rng = random.Random(seed)
    items = list(range(rng.randint(1, 40)))
    pairs = [(rng.choice(items), rng.choice(items)) for _ in range(rng.randint(0, 40))]
    sets = DisjointSets(reversed(items))  # the order of the items does not name the sets
    joined_before = []
    for a, b in pairs:
        before = {frozenset(p) for p in _components(items, joined_before)}
        apart = not any(a in p and b in p for p in before)
        assert sets.union(a, b) is apart
        joined_before.append((a, b))
    parts = _components(items, pairs)
    assert sets.roots() == {min(p) for p in parts}
    for part in parts:
        assert {sets.find(x) for x in part} == {min(part)}


def test_find_halves_the_path_it_walks():
    # a path 4 → 3 → 2 → 1 → 0 built by hand: find(4) points every other link two steps up
    sets = DisjointSets(range(5))
    sets._root.update({1: 0, 2: 1, 3: 2, 4: 3})
    assert sets.find(4) == 0
    assert sets._root == {0: 0, 1: 0, 2: 0, 3: 2, 4: 2}


def test_single_threaded_limits_blas_to_one_thread_and_gives_the_setting_back():
    threadpoolctl = pytest.importorskip("threadpoolctl")
    import numpy as np  # noqa: F401 - loads the BLAS library

    from synth.structure._blas import single_threaded

    def blas_threads():
        return {i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"}

    with threadpoolctl.threadpool_limits(limits=2, user_api="blas"):
        if blas_threads() != {2}:
            pytest.skip("this BLAS cannot run on two threads")
        with single_threaded():
            assert blas_threads() == {1}
        assert blas_threads() == {2}


@pytest.fixture
def package(monkeypatch):
    """A package ``demo_pkg`` with one submodule, made in memory."""
    pkg = types.ModuleType("demo_pkg")
    pkg.__path__ = []
    pkg.__all__ = ["b_name", "c_eager", "a_name"]
    pkg.c_eager = "defined at import"
    sub = types.ModuleType("demo_pkg.sub")
    sub.a_name = "from sub"
    pkg.b_name = "own"
    monkeypatch.setitem(sys.modules, "demo_pkg", pkg)
    monkeypatch.setitem(sys.modules, "demo_pkg.sub", sub)
    pkg.__getattr__, pkg.__dir__ = lazy_exports("demo_pkg", {"a_name": ".sub", "b_name": ""})
    return pkg


def test_a_lazy_name_is_loaded_from_its_module_and_kept(package):
    assert "a_name" not in vars(package)
    assert package.__getattr__("a_name") == "from sub"
    assert vars(package)["a_name"] == "from sub"  # kept: the next access does not go through __getattr__
    assert package.__getattr__("b_name") == "own"  # "" names the package itself


def test_an_unknown_lazy_name_is_an_attribute_error_naming_it(package):
    with pytest.raises(AttributeError, match=r"^module 'demo_pkg' has no attribute 'c_name'$"):
        package.__getattr__("c_name")


def test_the_lazy_listing_is_the_sorted_public_names(package):
    assert package.__dir__() == ["a_name", "b_name", "c_eager"]  # what the package lists, lazy or not
    del package.__all__
    assert package.__dir__() == ["a_name", "b_name"]  # without __all__: the names it exports


def test_synth_exports_every_name_it_lists():
    import synth

    assert dir(synth) == sorted(synth.__all__)
    assert synth.ChainQuery.__module__ == "synth.structure.query"
    assert synth.describe_seconds(5400) == "90 min"
    with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
        synth.no_such_name  # noqa: B018


class _Plain:
    pass


class _Derived(_Plain):
    pass


def _draw(value):
    return f"<svg>{type(value).__name__}</svg>"


def _draw_derived(value):
    return "<svg>its own</svg>"


def test_a_value_is_drawn_by_the_function_of_its_class_or_a_base_class(monkeypatch):
    from synth import display

    monkeypatch.setattr(display, "_DRAWINGS", dict(display._DRAWINGS))
    register_drawing("_Plain", f"{__name__}:_draw")
    assert svg_of(_Derived()) == "<svg>_Derived</svg>"  # the base class's function, given the value itself
    register_drawing("_Derived", f"{__name__}:_draw_derived")
    assert svg_of(_Derived()) == "<svg>its own</svg>"  # its own class first
    assert svg_of(_Plain()) == "<svg>_Plain</svg>"


def test_a_value_without_a_drawing_is_a_type_error_naming_its_class():
    with pytest.raises(TypeError, match=r"^no drawing is registered for a _Plain$"):
        svg_of(_Plain())
