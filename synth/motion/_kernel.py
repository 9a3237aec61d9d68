"""The dyads' closed forms compiled (numba): one loop over the steps of a sweep, each step placing
the inputs' links, then each group in solving order (see :mod:`synth.motion._dyads` for the
formulas and the meaning of each group's fields).

Numba compiles the kernel once (cached beside this file, or in numba's user cache).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["RRR", "PRR", "RPR", "PRP", "GEAR", "close_kernel"]

RRR, PRR, RPR, PRP, GEAR = 0, 1, 2, 3, 4
#: a dyad's normalised discriminant this far below 0 is a dead position reached up to rounding
ROUNDING = 1e-12


@njit(cache=True)
def _place(theta, tx, ty, cos, sin, link, angle, x, y, rx, ry):
    """Link turned by ``angle`` with its reference point (rx, ry) at (x, y) (the step's poses)."""
    c, sn = math.cos(angle), math.sin(angle)
    cos[link], sin[link] = c, sn
    theta[link] = angle
    tx[link] = x - (c * rx - sn * ry)
    ty[link] = y - (sn * rx + c * ry)


@njit(cache=True)
def _between(vx, vy, wx, wy):
    return math.atan2(abs(vx * wy - vy * wx), vx * wx + vy * wy)


@njit(cache=True)
def close_kernel(offsets, in_link, in_prismatic, in_point, in_slide, groups, ints, floats, points, slides,
                 carried_link, carried_point, scale2, theta, t_x, t_y, g, mu, carried):
    """Fill θ (S, n) and every carried point's position (S, P, 2) — the joints (each carried by its
    first link), then any tracer points — for each step's input offsets; and, where their arrays
    have a row per step (else none), the links' translations t_x, t_y (S, n), the groups'
    discriminants g and transmission angles μ (S, G).  ``ints`` per group: i, j, J1, J2, J3, K1,
    K2, mesh a, mesh b; ``floats``: sign, ratio."""
    steps, n = offsets.shape[0], theta.shape[1]
    n_groups = groups.shape[0]
    keep_t, keep_g, keep_mu = t_x.shape[0] == steps, g.shape[0] == steps, mu.shape[0] == steps
    # the step's pose of each link: θ, cos θ, sin θ, t (the frame: 0, 1, 0, 0)
    th, cos, sin = np.zeros(n), np.ones(n), np.zeros(n)
    tx, ty = np.zeros(n), np.zeros(n)
    gs = np.empty(n_groups)
    # each group's reference angles in the pose (constant over the sweep)
    ref = np.zeros((n_groups, 2))
    for m in range(n_groups):
        k1, k2, k3 = ints[m, 2], ints[m, 3], ints[m, 4]
        if groups[m] == RRR:
            ref[m, 0] = math.atan2(points[k3, 1] - points[k1, 1], points[k3, 0] - points[k1, 0])
        if groups[m] == RRR or groups[m] == PRR:
            ref[m, 1] = math.atan2(points[k3, 1] - points[k2, 1], points[k3, 0] - points[k2, 0])
        if groups[m] == RPR:
            ref[m, 0] = math.atan2(slides[k3, 1], slides[k3, 0])
    for s in range(steps):
        for w in range(in_link.shape[0]):
            link = in_link[w]
            if in_prismatic[w]:
                th[link] = 0.0
                cos[link], sin[link] = 1.0, 0.0
                tx[link] = offsets[s, w] * in_slide[w, 0]
                ty[link] = offsets[s, w] * in_slide[w, 1]
            else:
                px, py = in_point[w, 0], in_point[w, 1]
                _place(th, tx, ty, cos, sin, link, offsets[s, w], px, py, px, py)
        for m in range(n_groups):
            kind = groups[m]
            i, j, k1, k2, k3, h1, h2 = ints[m, 0], ints[m, 1], ints[m, 2], ints[m, 3], ints[m, 4], ints[m, 5], ints[m, 6]
            sign = floats[m, 0]
            if kind == GEAR:
                a, b = ints[m, 7], ints[m, 8]
                ratio = floats[m, 1]
                if i == b:
                    angle = th[h2] + (th[a] - th[h2]) / ratio
                else:
                    angle = th[h2] + ratio * (th[b] - th[h2])
                c1, s1 = cos[h1], sin[h1]
                ax = c1 * points[k1, 0] - s1 * points[k1, 1] + tx[h1]
                ay = s1 * points[k1, 0] + c1 * points[k1, 1] + ty[h1]
                _place(th, tx, ty, cos, sin, i, angle, ax, ay, points[k1, 0], points[k1, 1])
                gs[m] = 1.0
                if keep_mu:
                    mu[s, m] = np.nan
                continue
            c1, s1 = cos[h1], sin[h1]
            c2, s2 = cos[h2], sin[h2]
            if kind == RRR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                ax = c1 * a0x - s1 * a0y + tx[h1]
                ay = s1 * a0x + c1 * a0y + ty[h1]
                cx = c2 * c0x - s2 * c0y + tx[h2]
                cy = s2 * c0x + c2 * c0y + ty[h2]
                li2 = (b0x - a0x) ** 2 + (b0y - a0y) ** 2
                lj2 = (b0x - c0x) ** 2 + (b0y - c0y) ** 2
                dx, dy = cx - ax, cy - ay
                dd = dx * dx + dy * dy
                if dd > 0.0:
                    along = (li2 - lj2 + dd) / (2.0 * dd)
                    h2_ = li2 / dd - along * along
                    gs[m] = h2_ * dd / li2
                else:
                    along, h2_ = np.nan, -1.0
                    gs[m] = -1.0
                root = math.sqrt(max(h2_, 0.0)) if gs[m] >= -ROUNDING else np.nan
                bx = ax + along * dx - sign * root * dy
                by = ay + along * dy + sign * root * dx
                _place(th, tx, ty, cos, sin, i, math.atan2(by - ay, bx - ax) - ref[m, 0], ax, ay, a0x, a0y)
                _place(th, tx, ty, cos, sin, j, math.atan2(by - cy, bx - cx) - ref[m, 1], cx, cy, c0x, c0y)
                if keep_mu:
                    mu[s, m] = _between(ax - bx, ay - by, cx - bx, cy - by)
            elif kind == PRR:
                ux = c1 * slides[k1, 0] - s1 * slides[k1, 1]
                uy = s1 * slides[k1, 0] + c1 * slides[k1, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                basex = c1 * b0x - s1 * b0y + tx[h1]
                basey = s1 * b0x + c1 * b0y + ty[h1]
                cx = c2 * c0x - s2 * c0y + tx[h2]
                cy = s2 * c0x + c2 * c0y + ty[h2]
                wx, wy = basex - cx, basey - cy
                bb = ux * wx + uy * wy
                lj2 = (b0x - c0x) ** 2 + (b0y - c0y) ** 2
                disc = bb * bb - (wx * wx + wy * wy) + lj2
                gs[m] = disc / lj2
                slide = -bb + sign * math.sqrt(max(disc, 0.0)) if gs[m] >= -ROUNDING else np.nan
                bx, by = basex + slide * ux, basey + slide * uy
                th[i] = th[h1]
                cos[i], sin[i] = c1, s1
                tx[i] = tx[h1] + slide * ux
                ty[i] = ty[h1] + slide * uy
                _place(th, tx, ty, cos, sin, j, math.atan2(by - cy, bx - cx) - ref[m, 1], cx, cy, c0x, c0y)
                if keep_mu:
                    mu[s, m] = _between(bx - cx, by - cy, -uy, ux)
            elif kind == RPR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                u0x, u0y = slides[k3, 0], slides[k3, 1]
                ax = c1 * a0x - s1 * a0y + tx[h1]
                ay = s1 * a0x + c1 * a0y + ty[h1]
                cx = c2 * c0x - s2 * c0y + tx[h2]
                cy = s2 * c0x + c2 * c0y + ty[h2]
                dx, dy = cx - ax, cy - ay
                h = u0x * (c0y - a0y) - u0y * (c0x - a0x)
                disc = dx * dx + dy * dy - h * h
                gs[m] = disc / scale2
                psi = math.atan2(h, sign * math.sqrt(max(disc, 0.0))) if gs[m] >= -ROUNDING else np.nan
                angle = math.atan2(dy, dx) - ref[m, 0] - psi
                _place(th, tx, ty, cos, sin, i, angle, ax, ay, a0x, a0y)
                _place(th, tx, ty, cos, sin, j, angle, cx, cy, c0x, c0y)
                if keep_mu:
                    ca, sa = cos[i], sin[i]
                    mu[s, m] = _between(dx, dy, -(sa * u0x + ca * u0y), ca * u0x - sa * u0y)
            else:  # PRP
                u1x = c1 * slides[k1, 0] - s1 * slides[k1, 1]
                u1y = s1 * slides[k1, 0] + c1 * slides[k1, 1]
                u2x = c2 * slides[k2, 0] - s2 * slides[k2, 1]
                u2y = s2 * slides[k2, 0] + c2 * slides[k2, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                deltax = (c2 * b0x - s2 * b0y + tx[h2]) - (c1 * b0x - s1 * b0y + tx[h1])
                deltay = (s2 * b0x + c2 * b0y + ty[h2]) - (s1 * b0x + c1 * b0y + ty[h1])
                det = u2x * u1y - u2y * u1x
                gs[m] = det * det
                s1_ = (deltax * (-u2y) - deltay * (-u2x)) / det if det != 0.0 else np.nan
                s2_ = (u1x * deltay - u1y * deltax) / det if det != 0.0 else np.nan
                th[i], th[j] = th[h1], th[h2]
                cos[i], sin[i], cos[j], sin[j] = c1, s1, c2, s2
                tx[i] = tx[h1] + s1_ * u1x
                ty[i] = ty[h1] + s1_ * u1y
                tx[j] = tx[h2] + s2_ * u2x
                ty[j] = ty[h2] + s2_ * u2y
                if keep_mu:
                    mu[s, m] = _between(u1x, u1y, u2x, u2y)
        for x in range(n):
            theta[s, x] = th[x]
        if keep_t:
            for x in range(n):
                t_x[s, x] = tx[x]
                t_y[s, x] = ty[x]
        if keep_g:
            for m in range(n_groups):
                g[s, m] = gs[m]
        for k in range(carried_point.shape[0]):
            link = carried_link[k]
            c, sn = cos[link], sin[link]
            carried[s, k, 0] = c * carried_point[k, 0] - sn * carried_point[k, 1] + tx[link]
            carried[s, k, 1] = sn * carried_point[k, 0] + c * carried_point[k, 1] + ty[link]
