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
def _place(theta, tx, ty, cos, sin, s, link, angle, x, y, rx, ry):
    """Link turned by ``angle`` with its reference point (rx, ry) at (x, y)."""
    c, sn = math.cos(angle), math.sin(angle)
    cos[link], sin[link] = c, sn
    theta[s, link] = angle
    tx[s, link] = x - (c * rx - sn * ry)
    ty[s, link] = y - (sn * rx + c * ry)


@njit(cache=True)
def _between(vx, vy, wx, wy):
    return math.atan2(abs(vx * wy - vy * wx), vx * wx + vy * wy)


@njit(cache=True)
def close_kernel(offsets, in_link, in_prismatic, in_point, in_slide, groups, ints, floats, points, slides,
                 first_link, scale2, theta, tx, ty, g, mu, joints):
    """Fill θ, t (tx, ty), g, μ and every joint's position (carried by its first link) for each
    step's input offsets.  ``ints`` per group: i, j, J1, J2, J3, K1, K2, mesh a, mesh b;
    ``floats``: sign, ratio."""
    steps = offsets.shape[0]
    n_groups = groups.shape[0]
    cos = np.ones(theta.shape[1])  # each link's cos θ, sin θ at the current step (the frame: 1, 0)
    sin = np.zeros(theta.shape[1])
    for s in range(steps):
        for w in range(in_link.shape[0]):
            link = in_link[w]
            if in_prismatic[w]:
                theta[s, link] = 0.0
                cos[link], sin[link] = 1.0, 0.0
                tx[s, link] = offsets[s, w] * in_slide[w, 0]
                ty[s, link] = offsets[s, w] * in_slide[w, 1]
            else:
                px, py = in_point[w, 0], in_point[w, 1]
                _place(theta, tx, ty, cos, sin, s, link, offsets[s, w], px, py, px, py)
        for m in range(n_groups):
            kind = groups[m]
            i, j, k1, k2, k3, h1, h2 = ints[m, 0], ints[m, 1], ints[m, 2], ints[m, 3], ints[m, 4], ints[m, 5], ints[m, 6]
            sign = floats[m, 0]
            if kind == GEAR:
                a, b = ints[m, 7], ints[m, 8]
                ratio = floats[m, 1]
                if i == b:
                    angle = theta[s, h2] + (theta[s, a] - theta[s, h2]) / ratio
                else:
                    angle = theta[s, h2] + ratio * (theta[s, b] - theta[s, h2])
                c1, s1 = cos[h1], sin[h1]
                ax = c1 * points[k1, 0] - s1 * points[k1, 1] + tx[s, h1]
                ay = s1 * points[k1, 0] + c1 * points[k1, 1] + ty[s, h1]
                _place(theta, tx, ty, cos, sin, s, i, angle, ax, ay, points[k1, 0], points[k1, 1])
                g[s, m] = 1.0
                mu[s, m] = np.nan
                continue
            c1, s1 = cos[h1], sin[h1]
            c2, s2 = cos[h2], sin[h2]
            if kind == RRR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                ax = c1 * a0x - s1 * a0y + tx[s, h1]
                ay = s1 * a0x + c1 * a0y + ty[s, h1]
                cx = c2 * c0x - s2 * c0y + tx[s, h2]
                cy = s2 * c0x + c2 * c0y + ty[s, h2]
                li2 = (b0x - a0x) ** 2 + (b0y - a0y) ** 2
                lj2 = (b0x - c0x) ** 2 + (b0y - c0y) ** 2
                dx, dy = cx - ax, cy - ay
                dd = dx * dx + dy * dy
                if dd > 0.0:
                    along = (li2 - lj2 + dd) / (2.0 * dd)
                    h2_ = li2 / dd - along * along
                    g[s, m] = h2_ * dd / li2
                else:
                    along, h2_ = np.nan, -1.0
                    g[s, m] = -1.0
                root = math.sqrt(max(h2_, 0.0)) if g[s, m] >= -ROUNDING else np.nan
                bx = ax + along * dx - sign * root * dy
                by = ay + along * dy + sign * root * dx
                _place(theta, tx, ty, cos, sin, s, i, math.atan2(by - ay, bx - ax) - math.atan2(b0y - a0y, b0x - a0x),
                       ax, ay, a0x, a0y)
                _place(theta, tx, ty, cos, sin, s, j, math.atan2(by - cy, bx - cx) - math.atan2(b0y - c0y, b0x - c0x),
                       cx, cy, c0x, c0y)
                mu[s, m] = _between(ax - bx, ay - by, cx - bx, cy - by)
            elif kind == PRR:
                ux = c1 * slides[k1, 0] - s1 * slides[k1, 1]
                uy = s1 * slides[k1, 0] + c1 * slides[k1, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                basex = c1 * b0x - s1 * b0y + tx[s, h1]
                basey = s1 * b0x + c1 * b0y + ty[s, h1]
                cx = c2 * c0x - s2 * c0y + tx[s, h2]
                cy = s2 * c0x + c2 * c0y + ty[s, h2]
                wx, wy = basex - cx, basey - cy
                bb = ux * wx + uy * wy
                lj2 = (b0x - c0x) ** 2 + (b0y - c0y) ** 2
                disc = bb * bb - (wx * wx + wy * wy) + lj2
                g[s, m] = disc / lj2
                slide = -bb + sign * math.sqrt(max(disc, 0.0)) if g[s, m] >= -ROUNDING else np.nan
                bx, by = basex + slide * ux, basey + slide * uy
                theta[s, i] = theta[s, h1]
                cos[i], sin[i] = c1, s1
                tx[s, i] = tx[s, h1] + slide * ux
                ty[s, i] = ty[s, h1] + slide * uy
                _place(theta, tx, ty, cos, sin, s, j, math.atan2(by - cy, bx - cx) - math.atan2(b0y - c0y, b0x - c0x),
                       cx, cy, c0x, c0y)
                mu[s, m] = _between(bx - cx, by - cy, -uy, ux)
            elif kind == RPR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                u0x, u0y = slides[k3, 0], slides[k3, 1]
                ax = c1 * a0x - s1 * a0y + tx[s, h1]
                ay = s1 * a0x + c1 * a0y + ty[s, h1]
                cx = c2 * c0x - s2 * c0y + tx[s, h2]
                cy = s2 * c0x + c2 * c0y + ty[s, h2]
                dx, dy = cx - ax, cy - ay
                h = u0x * (c0y - a0y) - u0y * (c0x - a0x)
                disc = dx * dx + dy * dy - h * h
                g[s, m] = disc / scale2
                psi = math.atan2(h, sign * math.sqrt(max(disc, 0.0))) if g[s, m] >= -ROUNDING else np.nan
                angle = math.atan2(dy, dx) - math.atan2(u0y, u0x) - psi
                _place(theta, tx, ty, cos, sin, s, i, angle, ax, ay, a0x, a0y)
                _place(theta, tx, ty, cos, sin, s, j, angle, cx, cy, c0x, c0y)
                ca, sa = math.cos(angle), math.sin(angle)
                mu[s, m] = _between(dx, dy, -(sa * u0x + ca * u0y), ca * u0x - sa * u0y)
            else:  # PRP
                u1x = c1 * slides[k1, 0] - s1 * slides[k1, 1]
                u1y = s1 * slides[k1, 0] + c1 * slides[k1, 1]
                u2x = c2 * slides[k2, 0] - s2 * slides[k2, 1]
                u2y = s2 * slides[k2, 0] + c2 * slides[k2, 1]
                b0x, b0y = points[k3, 0], points[k3, 1]
                deltax = (c2 * b0x - s2 * b0y + tx[s, h2]) - (c1 * b0x - s1 * b0y + tx[s, h1])
                deltay = (s2 * b0x + c2 * b0y + ty[s, h2]) - (s1 * b0x + c1 * b0y + ty[s, h1])
                det = u2x * u1y - u2y * u1x
                g[s, m] = det * det
                s1_ = (deltax * (-u2y) - deltay * (-u2x)) / det if det != 0.0 else np.nan
                s2_ = (u1x * deltay - u1y * deltax) / det if det != 0.0 else np.nan
                theta[s, i], theta[s, j] = theta[s, h1], theta[s, h2]
                cos[i], sin[i], cos[j], sin[j] = c1, s1, c2, s2
                tx[s, i] = tx[s, h1] + s1_ * u1x
                ty[s, i] = ty[s, h1] + s1_ * u1y
                tx[s, j] = tx[s, h2] + s2_ * u2x
                ty[s, j] = ty[s, h2] + s2_ * u2y
                mu[s, m] = _between(u1x, u1y, u2x, u2y)
        for k in range(points.shape[0]):
            link = first_link[k]
            c, sn = cos[link], sin[link]
            joints[s, k, 0] = c * points[k, 0] - sn * points[k, 1] + tx[s, link]
            joints[s, k, 1] = sn * points[k, 0] + c * points[k, 1] + ty[s, link]
