"""balance/extremes.py on functions whose extremes are known by hand: samples spread over several
chunks, a column of rounding noise, a held coordinate, extremes inside the box and on its corners,
functions of a large and of a small scale, and the spreading of the local searches' starts."""

from __future__ import annotations

import numpy as np
import pytest

from balance.extremes import CANDIDATES, CHUNK, Extreme, _best_rows, _spread, box_extremes


def test_best_rows_are_the_largest_of_each_column():
    v = np.array([[1.0, 9.0], [5.0, 2.0], [3.0, 7.0], [4.0, 8.0]])
    rows = _best_rows(v, 2)
    assert rows.shape == (2, 2)
    assert set(rows[:, 0]) == {1, 3} and set(rows[:, 1]) == {0, 3}
    assert sorted(_best_rows(v, 10)[:, 0]) == [0, 1, 2, 3]  # more than there are: all of them


def test_the_samples_of_every_chunk_count():
    """No polishing (``floor`` above every value): the result is the best sample, wherever it lies."""
    n = 2 * CHUNK + 5000
    pts = np.random.default_rng(1).uniform(0, 1, (n, 1))
    pts[CHUNK + 17] = 0.999999       # the largest x: in the second chunk
    pts[2 * CHUNK + 99] = 1e-7      # the smallest: in the third
    (lo, hi), = box_extremes(lambda x: x, [0.0], [1.0], pts, floor=10.0)
    assert hi.value == hi.sampled == 0.999999 and hi.at == (0.999999,)
    assert lo.value == lo.sampled == 1e-7 and lo.at == (1e-7,)
    (lo, hi), = box_extremes(lambda x: -x, [0.0], [1.0], pts, floor=10.0)
    assert (hi.value, lo.value) == (-1e-7, -0.999999)


def test_every_column_has_its_own_extremes_and_points():
    f = lambda x: np.column_stack([x[:, 0], -x[:, 0] + 2 * x[:, 1], x[:, 0] * x[:, 1]])  # noqa: E731
    pts = np.random.default_rng(2).uniform([0, 0], [1, 2], (40, 2))
    (a, b, c) = box_extremes(f, [0.0, 0.0], [1.0, 2.0], pts)
    assert (a[0].value, a[1].value) == pytest.approx((0.0, 1.0), abs=1e-12)
    assert (b[0].value, b[1].value) == pytest.approx((-1.0, 4.0), abs=1e-12)
    assert b[0].at == pytest.approx((1.0, 0.0), abs=1e-12) and b[1].at == pytest.approx((0.0, 2.0), abs=1e-12)
    assert (c[0].value, c[1].value) == pytest.approx((0.0, 2.0), abs=1e-12)
    assert c[1].at == pytest.approx((1.0, 2.0), abs=1e-12)


def test_an_interior_peak_between_the_samples():
    """−((x − 0.3)² + 4(y − 0.7)²): largest 0 at (0.3, 0.7); smallest at the corner (1, 0)."""
    f = lambda x: -((x[:, 0] - 0.3) ** 2 + 4 * (x[:, 1] - 0.7) ** 2)  # noqa: E731
    pts = np.random.default_rng(4).uniform(0, 1, (30, 2))
    (lo, hi), = box_extremes(f, [0.0, 0.0], [1.0, 1.0], pts)
    assert hi.value == pytest.approx(0.0, abs=1e-12) and hi.at == pytest.approx((0.3, 0.7), abs=1e-6)
    assert hi.sampled < -1e-4 and hi.sampled == f(pts).max()
    assert lo.value == pytest.approx(-(0.49 + 4 * 0.49), rel=1e-12) and lo.at == pytest.approx((1.0, 0.0))
    assert lo.sampled == f(pts).min()


@pytest.mark.parametrize("scale", [1e-13, 1e-6, 1.0, 1e6])
def test_the_scale_of_the_function_does_not_matter(scale):
    f = lambda x: scale * np.sin(x[:, :1] * 2) * np.cos(x[:, 1:] - 0.4)  # noqa: E731
    pts = np.random.default_rng(5).uniform([0, 0], [1.5, 1], (25, 2))
    (lo, hi), = box_extremes(f, [0.0, 0.0], [1.5, 1.0], pts)
    assert hi.value == pytest.approx(scale, rel=1e-11)
    assert hi.at == pytest.approx((np.pi / 4, 0.4), abs=1e-5)
    assert lo.value == pytest.approx(0.0, abs=1e-12 * scale) and lo.at[0] == 0.0  # sin 2x ≥ 0 on the box


def test_a_column_of_rounding_noise_is_not_polished():
    f = lambda x: np.column_stack([1e-14 * np.sin(5 * x[:, 0]), np.sin(5 * x[:, 0])])  # noqa: E731
    pts = np.linspace(0, 1, 7)[:, None]
    (noise, signal) = box_extremes(f, [0.0], [1.0], pts, floor=1e-12)
    assert noise[1].value == noise[1].sampled == f(pts)[:, 0].max()
    assert noise[0].value == noise[0].sampled == f(pts)[:, 0].min()
    assert signal[1].value == pytest.approx(1.0, abs=1e-12) and signal[0].value == pytest.approx(-1.0, abs=1e-12)
    (_, exact), = box_extremes(lambda x: f(x)[:, 1:], [0.0], [1.0], pts, floor=f(pts)[:, 1].max())
    assert exact.value == exact.sampled  # the floor is a bound on |f|, inclusive


def test_a_held_coordinate_stays_where_it_is():
    f = lambda x: -(x[:, 0] - 0.25) ** 2 + x[:, 1]  # noqa: E731
    pts = np.column_stack([np.linspace(0, 1, 9), np.full(9, 0.5)])
    (lo, hi), = box_extremes(f, [0.0, 0.5], [1.0, 0.5], pts)
    assert hi.value == pytest.approx(0.5, abs=1e-12) and hi.at == pytest.approx((0.25, 0.5), abs=1e-6)
    assert hi.at[1] == 0.5 and lo.at == (1.0, 0.5)
    (lo, hi), = box_extremes(f, [0.3, 0.5], [0.3, 0.5], np.array([[0.3, 0.5]]))  # a box of one point
    assert hi.value == hi.sampled == lo.value == pytest.approx(0.5 - 0.05 ** 2)


def test_the_starts_are_spread_over_the_box():
    """The best candidates crowd near 0.5; the starts skip those closer than a tenth of the box."""
    xs = np.array([[0.50], [0.51], [0.52], [0.9], [0.1], [0.65]])
    score = np.array([6.0, 5.0, 4.0, 3.0, 2.0, 1.0])
    starts = _spread(score, xs, np.array([1.0]), 3)
    assert [float(s[0]) for s in starts] == [0.5, 0.9, 0.1]
    assert [float(s[0]) for s in _spread(score, xs, np.array([1.0]), 10)] == [0.5, 0.9, 0.1, 0.65]
    assert [float(s[0]) for s in _spread(score, xs, np.array([0.05]), 3)] == [0.5, 0.51, 0.52]  # in widths


def test_a_second_basin_is_found_from_a_spread_start():
    """Two peaks, the samples crowd on the lower one: the higher one is reached from a second start.
    The higher peak is narrow, so the best corner (x = 0) lies in the lower peak's basin too."""
    f = lambda x: np.exp(-((x[:, :1] - 0.2) / 0.05) ** 2) + 1.5 * np.exp(-((x[:, :1] - 0.8) / 0.02) ** 2)  # noqa
    pts = np.concatenate([np.linspace(0.18, 0.22, 5), [0.77]])[:, None]  # all of them candidates
    (_, hi), = box_extremes(f, [0.0], [1.0], pts, starts=2)
    assert hi.value == pytest.approx(1.5, rel=1e-9) and hi.at == pytest.approx((0.8,), abs=1e-6)
    (_, one), = box_extremes(f, [0.0], [1.0], pts, starts=1)  # one start: the lower peak only
    assert one.value == pytest.approx(1.0, rel=1e-9) and len(pts) < CANDIDATES


def test_extreme_as_a_dict():
    e = Extreme(2.5, (0.1, 0.2), 2.0)
    assert e.to_dict() == {"value": 2.5, "at": [0.1, 0.2], "sampled": 2.0}


def test_a_held_coordinate_does_not_stop_the_starts_spreading():
    """The two peaks of the test above with a second coordinate held: still found from a second start."""
    def f(x):
        return np.exp(-((x[:, :1] - 0.2) / 0.05) ** 2) + 1.5 * np.exp(-((x[:, :1] - 0.8) / 0.05) ** 2) + x[:, 1:]
    pts = np.column_stack([np.concatenate([np.linspace(0.18, 0.22, 10), [0.7]]), np.full(11, 0.25)])
    (_, hi), = box_extremes(f, [0.0, 0.25], [1.0, 0.25], pts, starts=2)
    assert hi.value == pytest.approx(1.75, rel=1e-9) and hi.at == pytest.approx((0.8, 0.25), abs=1e-6)


def test_the_local_search_stops_after_max_iter():
    """Rosenbrock's valley (largest 0 at (1, 1)): one iteration from a far sample does not get there."""
    f = lambda x: -((1 - x[:, :1]) ** 2 + 100 * (x[:, 1:] - x[:, :1] ** 2) ** 2)  # noqa: E731
    pts = np.array([[-1.5, 2.0], [-1.6, 2.0]])
    (_, one), = box_extremes(f, [-2.0, -2.0], [2.0, 2.0], pts, starts=1, max_iter=1)
    (_, full), = box_extremes(f, [-2.0, -2.0], [2.0, 2.0], pts, starts=1)
    assert full.value == pytest.approx(0.0, abs=1e-8) and full.at == pytest.approx((1.0, 1.0), abs=1e-4)
    assert one.sampled < one.value < -1e-2


def test_a_corner_extreme_in_a_basin_no_sample_reaches():
    """A broad well of depth 0.9 over the whole box, deepest at the centre, and a narrow one of depth 1
    at the corner (1, 1): every sample and every local search from one lies in the broad well, so only
    the corner finds the smallest value, about −1.4 at (1, 1) (a mutant study found a workspace force
    whose least value sat at such a corner)."""
    def f(x):
        broad = 0.9 * np.exp(-((x - 0.5) ** 2).sum(axis=1) / 0.5)
        narrow = np.exp(-((x - 1.0) ** 2).sum(axis=1) / 1e-4)
        return -(broad + narrow)
    pts = np.random.default_rng(0).uniform(0, 1, (200, 2))
    assert f(pts).min() > -0.91                       # no sample near the corner's well
    (lo, hi), = box_extremes(f, [0.0, 0.0], [1.0, 1.0], pts)
    # by symmetry the least value lies on the diagonal x = y = t, a hair inside the corner (the broad
    # well pulls it in): a dense search over t, independent of the engine
    t = np.linspace(0.99, 1.0, 100_001)
    diag = f(np.column_stack([t, t]))
    assert lo.value == pytest.approx(diag.min(), abs=1e-9)
    assert lo.at == pytest.approx((t[diag.argmin()],) * 2, abs=1e-6) and lo.value < -1.33
    assert lo.sampled == f(pts).min()                 # what the samples alone would have said


def test_a_box_of_many_free_coordinates_is_not_cornered():
    """Past CORNER_DIMS free coordinates the 2**d corners are not evaluated (f counts its points)."""
    from balance.extremes import CORNER_DIMS
    seen = []

    def f(x):
        seen.append(len(x))
        return x.sum(axis=1)
    d = CORNER_DIMS + 1
    pts = np.random.default_rng(1).uniform(0, 1, (50, d))
    box_extremes(f, np.zeros(d), np.ones(d), pts, floor=1e9)
    assert seen == [50]
    seen.clear()
    box_extremes(f, np.zeros(CORNER_DIMS), np.ones(CORNER_DIMS), pts[:, :CORNER_DIMS], floor=1e9)
    assert seen == [50, 2 ** CORNER_DIMS]
