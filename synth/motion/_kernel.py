"""The dyads' closed forms compiled (numba): one loop over the steps of a sweep, each step placing
the inputs' links, then each group in solving order (see :mod:`synth.motion._dyads` for the
formulas and the meaning of each group's fields).

A link's rotation is carried as its cosine and sine, never as an angle: an RRR dyad's links turn by
the rotation that takes each link's pose vector (outer pin to middle pin) to the one just found,
(v₀·v, v₀ × v)/|v₀|², so a dyad costs one square root and no trigonometric function.  A revolute
input's cosine and sine come, where asked (a sweep's points), from a rotation recurrence where the
inputs are equally spaced, re-anchored on the exact cos and sin every ``ANCHOR`` steps (the rounding
it gathers stays below 1e-14 rad); elsewhere (the search for a branch's ends, where the sign of a
discriminant near 0 matters) from cos and sin at every step.  Angles are computed only where asked for (or where a gear needs them: a mesh turns
its gear by a ratio of angles).

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
#: a revolute input's cosine and sine are computed exactly every this many steps, rotated in between
ANCHOR = 64


@njit(cache=True, inline="always")
def _place(cos, sin, tx, ty, link, c, sn, x, y, rx, ry):
    """Link turned by the rotation (c, sn) with its reference point (rx, ry) at (x, y)."""
    cos[link], sin[link] = c, sn
    tx[link] = x - (c * rx - sn * ry)
    ty[link] = y - (sn * rx + c * ry)


@njit(cache=True, inline="always")
def _turn(vx, vy, v0x, v0y, inv_l2, normalise):
    """The rotation (cos, sin) taking v₀ to v, for |v| = |v₀| (renormalised where ``normalise``:
    a dyad closed at a dead position within rounding, where |v| differs from |v₀| by ~1e-12)."""
    c = (v0x * vx + v0y * vy) * inv_l2
    sn = (v0x * vy - v0y * vx) * inv_l2
    if normalise:
        r = math.sqrt(c * c + sn * sn)
        c, sn = c / r, sn / r
    return c, sn


@njit(cache=True, inline="always")
def _between(vx, vy, wx, wy):
    return math.atan2(abs(vx * wy - vy * wx), vx * wx + vy * wy)


@njit(cache=True)
def close_kernel(offsets, recurrence, in_link, in_prismatic, in_point, in_slide, groups, ints, floats, points, slides,
                 carried_link, carried_point, scale2, theta, t_x, t_y, g, mu, carried):
    """Fill every carried point's position (S, P, 2) — the joints (each carried by its first link),
    then any tracer points — for each step's input offsets (S, W); and, where their arrays have a
    row per step (else none), the links' rotations θ (S, n, rad, modulo a turn) and translations
    t_x, t_y (S, n), the groups' discriminants g and transmission angles μ (S, G).  ``recurrence``:
    revolute inputs turned by the rotation recurrence between anchors (else cos and sin each step).  ``ints`` per
    group: i, j, J1, J2, J3, K1, K2, mesh a, mesh b; ``floats``: sign, ratio."""
    steps, n, n_in = offsets.shape[0], theta.shape[1], in_link.shape[0]
    n_groups = groups.shape[0]
    keep_theta, keep_t = theta.shape[0] == steps, t_x.shape[0] == steps
    keep_g, keep_mu = g.shape[0] == steps, mu.shape[0] == steps
    angles = keep_theta  # a link's angle is needed: asked for, or by a gear's ratio
    for m in range(n_groups):
        if groups[m] == GEAR:
            angles = True
    # the step's pose of each link: θ, cos θ, sin θ, t (the frame: 0, 1, 0, 0)
    th, cos, sin = np.zeros(n), np.ones(n), np.zeros(n)
    tx, ty = np.zeros(n), np.zeros(n)
    gs = np.empty(n_groups)
    # each group's constants in the pose: squared lengths (and their inverses), pose vectors
    const = np.zeros((n_groups, 6))
    for m in range(n_groups):
        k1, k2, k3 = ints[m, 2], ints[m, 3], ints[m, 4]
        if groups[m] == RRR or groups[m] == PRR:
            vx, vy = points[k3, 0] - points[k2, 0], points[k3, 1] - points[k2, 1]
            const[m, 0], const[m, 1], const[m, 2] = vx * vx + vy * vy, vx, vy
        if groups[m] == RRR:
            vx, vy = points[k3, 0] - points[k1, 0], points[k3, 1] - points[k1, 1]
            const[m, 3], const[m, 4], const[m, 5] = vx * vx + vy * vy, vx, vy
        if groups[m] == RPR:
            const[m, 0] = slides[k3, 0] * (points[k2, 1] - points[k1, 1]) - slides[k3, 1] * (points[k2, 0] - points[k1, 0])
    # each revolute input's rotation recurrence: the step it was anchored at, its value there, the
    # spacing, and the rotation by the spacing
    anchor = np.full(n_in, -ANCHOR)
    every = ANCHOR if recurrence else 1
    base, spacing, c_step, s_step = np.zeros(n_in), np.zeros(n_in), np.ones(n_in), np.zeros(n_in)
    for s in range(steps):
        for w in range(n_in):
            link, x = in_link[w], offsets[s, w]
            if in_prismatic[w]:
                th[link] = 0.0
                cos[link], sin[link] = 1.0, 0.0
                tx[link] = x * in_slide[w, 0]
                ty[link] = x * in_slide[w, 1]
                continue
            k = s - anchor[w]
            along = base[w] + k * spacing[w]
            if k < every and abs(x - along) <= 4e-16 * (abs(x) + abs(along)):
                c0, s0 = cos[link], sin[link]
                c, sn = c0 * c_step[w] - s0 * s_step[w], s0 * c_step[w] + c0 * s_step[w]
            else:  # anchored on the exact value; the next steps rotate on by this step's spacing
                c, sn = math.cos(x), math.sin(x)
                anchor[w], base[w] = s, x
                spacing[w] = offsets[s + 1, w] - x if s + 1 < steps else 0.0
                c_step[w], s_step[w] = math.cos(spacing[w]), math.sin(spacing[w])
            th[link] = x
            px, py = in_point[w, 0], in_point[w, 1]
            _place(cos, sin, tx, ty, link, c, sn, px, py, px, py)
        for m in range(n_groups):
            kind = groups[m]
            i, j, k1, k2, k3, h1, h2 = ints[m, 0], ints[m, 1], ints[m, 2], ints[m, 3], ints[m, 4], ints[m, 5], ints[m, 6]
            sign = floats[m, 0]
            c1, s1 = cos[h1], sin[h1]
            c2, s2 = cos[h2], sin[h2]
            if kind == GEAR:
                a, b = ints[m, 7], ints[m, 8]
                ratio = floats[m, 1]
                if i == b:
                    angle = th[h2] + (th[a] - th[h2]) / ratio
                else:
                    angle = th[h2] + ratio * (th[b] - th[h2])
                ax = c1 * points[k1, 0] - s1 * points[k1, 1] + tx[h1]
                ay = s1 * points[k1, 0] + c1 * points[k1, 1] + ty[h1]
                _place(cos, sin, tx, ty, i, math.cos(angle), math.sin(angle), ax, ay, points[k1, 0], points[k1, 1])
                th[i] = angle
                gs[m] = 1.0
                if keep_mu:
                    mu[s, m] = np.nan
                continue
            if kind == RRR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                ax = c1 * a0x - s1 * a0y + tx[h1]
                ay = s1 * a0x + c1 * a0y + ty[h1]
                cx = c2 * c0x - s2 * c0y + tx[h2]
                cy = s2 * c0x + c2 * c0y + ty[h2]
                lj2, li2 = const[m, 0], const[m, 3]
                dx, dy = cx - ax, cy - ay
                dd = dx * dx + dy * dy
                if dd > 0.0:
                    inv = 1.0 / dd
                    along = 0.5 + 0.5 * (li2 - lj2) * inv
                    h2_ = li2 * inv - along * along
                    gs[m] = h2_ * dd / li2
                else:
                    along, h2_ = np.nan, -1.0
                    gs[m] = -1.0
                root = math.sqrt(max(h2_, 0.0)) if gs[m] >= -ROUNDING else np.nan
                bx = ax + along * dx - sign * root * dy
                by = ay + along * dy + sign * root * dx
                ci, si = _turn(bx - ax, by - ay, const[m, 4], const[m, 5], 1.0 / li2, h2_ < 0.0)
                cj, sj = _turn(bx - cx, by - cy, const[m, 1], const[m, 2], 1.0 / lj2, h2_ < 0.0)
                _place(cos, sin, tx, ty, i, ci, si, ax, ay, a0x, a0y)
                _place(cos, sin, tx, ty, j, cj, sj, cx, cy, c0x, c0y)
                if angles:
                    th[i], th[j] = math.atan2(si, ci), math.atan2(sj, cj)
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
                lj2 = const[m, 0]
                disc = bb * bb - (wx * wx + wy * wy) + lj2
                gs[m] = disc / lj2
                slide = -bb + sign * math.sqrt(max(disc, 0.0)) if gs[m] >= -ROUNDING else np.nan
                bx, by = basex + slide * ux, basey + slide * uy
                th[i] = th[h1]
                cos[i], sin[i] = c1, s1
                tx[i] = tx[h1] + slide * ux
                ty[i] = ty[h1] + slide * uy
                cj, sj = _turn(bx - cx, by - cy, const[m, 1], const[m, 2], 1.0 / lj2, disc < 0.0)
                _place(cos, sin, tx, ty, j, cj, sj, cx, cy, c0x, c0y)
                if angles:
                    th[j] = math.atan2(sj, cj)
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
                h = const[m, 0]
                disc = dx * dx + dy * dy - h * h
                gs[m] = disc / scale2
                root = sign * math.sqrt(max(disc, 0.0)) if gs[m] >= -ROUNDING else np.nan
                # the guide's rotation: arg(C − A) − arg u₀ − atan2(h, root), as a product of unit complexes
                pr, pi = dx * u0x + dy * u0y, dy * u0x - dx * u0y
                qr, qi = pr * root + pi * h, pi * root - pr * h
                norm = math.sqrt(qr * qr + qi * qi)
                ca, sa = qr / norm, qi / norm
                _place(cos, sin, tx, ty, i, ca, sa, ax, ay, a0x, a0y)
                _place(cos, sin, tx, ty, j, ca, sa, cx, cy, c0x, c0y)
                if angles:
                    th[i] = th[j] = math.atan2(sa, ca)
                if keep_mu:
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
        if keep_theta:
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
