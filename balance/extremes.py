"""True extremes of a function over a box: the best samples, polished by a bounded local search.

Every largest or smallest value :mod:`balance` reports over a workspace or a range (a
residual, a force, a length) comes from here, not from the best of a random sample: the
function is evaluated at the given points (in chunks, so memory stays bounded), the
``starts`` best points of each column and sense are polished by L-BFGS-B inside the box
(gradients by central differences, one vectorised call per gradient), and so is the best
corner of the box (an extreme of a workspace is often at a corner, in a basin too small for
a sample to land in; up to :data:`CORNER_DIMS` free coordinates); the best of the samples,
the corners and the polished points is kept. The result is a local extreme to the
optimiser's tolerance (projected gradient ≤ ``1e-12`` of the function's scale) reached
from the best samples and the best corner; the tests compare it with dense grid searches.

Examples
--------
>>> import numpy as np
>>> f = lambda x: np.sin(3 * x[:, :1]) * np.cos(x[:, 1:])       # one column over a 2-D box
>>> pts = np.random.default_rng(0).uniform([0, 0], [1, 1], (50, 2))
>>> (lo, hi), = box_extremes(f, [0, 0], [1, 1], pts)
>>> round(hi.value, 9), [round(v, 6) for v in hi.at]             # sin(3x)·cos(y): 1 at (π/6, 0)
(1.0, [0.523599, 0.0])
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Callable, Sequence

import numpy as np
from scipy import optimize
from threadpoolctl import threadpool_limits

from mechbase import Row

__all__ = ["Extreme", "box_extremes", "CHUNK", "EXTREMES_NOTE"]

#: how every reported extreme is found, in the words of a result
EXTREMES_NOTE = ("true extremes: the best random samples and the best corner of the box polished by a bounded "
                 "local search (L-BFGS-B, projected gradient ≤ 1e-12 of the scale)")

#: points evaluated at once (bounds the memory of a large sample)
CHUNK = 20_000
#: boxes with at most this many free coordinates also have their 2**d corners searched
CORNER_DIMS = 10
#: best samples kept per start, among which the starts are spread out
CANDIDATES = 10


@dataclass(frozen=True)
class Extreme(Row):
    """The largest or smallest value of a function over a box, and where it is reached.

    Attributes
    ----------
    value : float
        The extreme (polished).
    at : tuple of float
        The point reaching it.
    sampled : float
        The best value among the samples alone (what a sampled search would report).
    """

    value: float
    at: tuple[float, ...]
    sampled: float


def _best_rows(values: np.ndarray, k: int) -> np.ndarray:
    """Indices of the ``k`` largest entries of each column of ``values`` (k × columns)."""
    k = min(k, values.shape[0])
    idx = np.argpartition(-values, k - 1, axis=0)[:k]
    return idx


def box_extremes(f: Callable[[np.ndarray], np.ndarray], lo: Sequence[float], hi: Sequence[float],
                 points: np.ndarray, starts: int = 3, floor: float = 0.0,
                 max_iter: int = 200) -> list[tuple[Extreme, Extreme]]:
    """The smallest and largest value of each column of ``f`` over the box ``[lo, hi]``.

    Parameters
    ----------
    f : callable
        ``f(X)`` with ``X`` of shape (m, d) returns (m, k): k functions at m points; it must be
        defined (and smooth) on the box.
    lo, hi : sequence of float
        The box (``lo ≤ hi`` per coordinate; a coordinate with ``lo == hi`` is held fixed).
    points : ndarray (m, d)
        Where to look first (random samples, a grid); evaluated in chunks of :data:`CHUNK`.
    starts : int
        Best samples of each column and sense polished by L-BFGS-B.
    floor : float
        Columns whose largest ``|f|`` over the samples is at most ``floor`` (rounding noise of
        an exact result) are not polished.
    max_iter : int
        Iterations of each local search.

    Returns
    -------
    list of (Extreme, Extreme)
        ``(min, max)`` per column.
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    pts = np.atleast_2d(np.asarray(points, dtype=float))
    keep = CANDIDATES * starts
    best_max = best_min = None  # (values, rows) kept across chunks
    for s in range(0, len(pts), CHUNK):
        chunk = pts[s:s + CHUNK]
        v = _values(f, chunk)
        for sign in (1, -1):
            rows = _best_rows(sign * v, keep)
            cand_v = np.take_along_axis(v, rows, axis=0)
            cand_x = chunk[rows]  # (k, columns, d)
            kept = best_max if sign == 1 else best_min
            if kept is not None:
                cand_v = np.concatenate([kept[0], cand_v])
                cand_x = np.concatenate([kept[1], cand_x])
            order = _best_rows(sign * cand_v, keep)
            kept = (np.take_along_axis(cand_v, order, axis=0),
                    np.take_along_axis(cand_x, order[..., None], axis=0))
            if sign == 1:
                best_max = kept
            else:
                best_min = kept
    columns = best_max[0].shape[1]
    scale = max(float(np.max(np.abs(best_max[0]))), float(np.max(np.abs(best_min[0]))), 1e-300)
    free = hi > lo
    width = np.where(free, hi - lo, 1.0)
    corners = _corners(lo, hi, free)
    corner_values = _values(f, corners) if len(corners) else np.empty((0, columns))
    out = []
    with threadpool_limits(1, "blas"):  # BLAS threads only spin on these tiny problems (6× slower)
        for c in range(columns):
            out.append(_column_extremes(f, c, best_min, best_max, (corners, corner_values[:, c]), floor, lo, hi,
                                        free, width, scale, max_iter, starts))
    return out


def _corners(lo: np.ndarray, hi: np.ndarray, free: np.ndarray) -> np.ndarray:
    """The 2**d corners of the box over its d free coordinates (none past :data:`CORNER_DIMS`)."""
    idx = np.flatnonzero(free)
    if len(idx) > CORNER_DIMS:
        return np.empty((0, len(lo)))
    bits = (np.arange(2 ** len(idx))[:, None] >> np.arange(len(idx))) & 1
    out = np.repeat(lo[None], len(bits), axis=0)
    out[:, idx] = np.where(bits == 1, hi[idx], lo[idx])
    return out


def _column_extremes(f, c, best_min, best_max, corners, floor, lo, hi, free, width, scale, max_iter, starts):
    """``(min, max)`` of column ``c``: the kept samples, and unless the column is noise, the best corner
    and the polish of both."""
    corner_x, corner_v = corners
    colmax = max(float(np.max(np.abs(best_max[0][:, c]))), float(np.max(np.abs(best_min[0][:, c]))))
    pair = []
    for sign, kept in ((-1, best_min), (1, best_max)):
        vals, xs = kept[0][:, c], kept[1][:, c]
        i0 = int(np.argmax(sign * vals))
        best_v, best_x = float(vals[i0]), xs[i0]
        sampled = best_v
        if colmax > floor and np.any(free):
            x0s = _spread(vals * sign, xs, width, starts)
            if len(corner_v):
                k = int(np.argmax(sign * corner_v))
                x0s.append(corner_x[k])
                if sign * corner_v[k] > sign * best_v:
                    best_v, best_x = float(corner_v[k]), corner_x[k]
            for x0 in x0s:
                v, x = _polish(f, c, sign, x0, lo, hi, free, width, scale, max_iter)
                if sign * v > sign * best_v:
                    best_v, best_x = v, x
        pair.append(Extreme(best_v, tuple(float(t) for t in best_x), sampled))
    return tuple(pair)


def _spread(score: np.ndarray, xs: np.ndarray, width: np.ndarray, starts: int) -> list[np.ndarray]:
    """Up to ``starts`` of the candidates, best first, each at least a tenth of the box from those
    taken (so the starts lie in different basins when the best samples crowd into one)."""
    order = np.argsort(-score)
    taken: list[np.ndarray] = []
    for i in order:
        if all(np.linalg.norm((xs[i] - t) / width) >= 0.1 for t in taken):
            taken.append(xs[i])
        if len(taken) == starts:
            break
    return taken


def _polish(f, c: int, sign: int, x0: np.ndarray, lo, hi, free, width, scale: float, max_iter: int):
    """L-BFGS-B on ``−sign·f_c`` over the free coordinates; returns (value, point)."""
    idx = np.flatnonzero(free)
    h = 1e-7 * width[idx]

    def full(y):
        x = x0.copy()
        x[idx] = y
        return x

    def fun(y):
        x = np.clip(full(y), lo, hi)
        up = np.repeat(x[None], len(idx), axis=0)
        dn = up.copy()
        ar = np.arange(len(idx))
        up[ar, idx] = np.minimum(x[idx] + h, hi[idx])
        dn[ar, idx] = np.maximum(x[idx] - h, lo[idx])
        col = _values(f, np.concatenate([x[None], up, dn]))[:, c]
        step = up[ar, idx] - dn[ar, idx]
        grad = (col[1:1 + len(idx)] - col[1 + len(idx):]) / np.where(step > 0, step, 1.0)
        return -sign * col[0] / scale, -sign * grad / scale

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        sol = optimize.minimize(fun, x0[idx], jac=True, method="L-BFGS-B", bounds=list(zip(lo[idx], hi[idx])),
                                options={"maxiter": max_iter, "ftol": 1e-15, "gtol": 1e-12})
    x = np.clip(full(sol.x), lo, hi)
    return float(_values(f, x[None])[0, c]), x


def _values(f, x: np.ndarray) -> np.ndarray:
    """``f(x)`` as an (m, k) array."""
    v = np.asarray(f(x), dtype=float)
    return v.reshape(len(x), -1)
