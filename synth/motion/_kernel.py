"""The dyads' closed forms compiled (numba), each step placing the inputs' links, then each group in
solving order (see :mod:`synth.motion._dyads` for the formulas and the meaning of each group's
fields).

The steps are taken ``BLOCK`` at a time, stage by stage (the inputs, then each group, then the
points carried), each stage one loop over the block's steps that the compiler turns into vector
instructions.  A link's rotation is carried as its cosine and sine, never as an angle: an RRR
dyad's links turn by the rotation that takes each link's pose vector (outer pin to middle pin) to
the one just found, (v₀·v, v₀ × v)/|v₀|², so a dyad costs one square root and no trigonometric
function.  Where asked (a sweep's many steps), a revolute input's cosine and sine over a block of
equally spaced inputs are the exact ones of the block's first input turned by a table of the
rotations by 0, 1, … spacings (two roundings, no accumulation); elsewhere (the search for a
branch's ends, where the sign of a discriminant near 0 matters) cos and sin of each input.  Angles
are computed only where asked for, or where a gear needs them (a mesh turns its gear by a ratio
of angles).

Numba compiles the kernel once (cached beside this file, or in numba's user cache).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["RRR", "PRR", "RPR", "PRP", "RPP", "GEAR", "close_kernel"]

RRR, PRR, RPR, PRP, RPP, GEAR = 0, 1, 2, 3, 5, 4
#: a dyad's normalised discriminant this far below 0 is a dead position reached up to rounding
ROUNDING = 1e-12
#: steps computed together, stage by stage
BLOCK = 64


@njit(cache=True, inline="always", error_model="numpy")
def _place(cos, sin, tx, ty, link, b, c, sn, x, y, rx, ry):
    """Link turned by the rotation (c, sn) with its reference point (rx, ry) at (x, y), at step b."""
    cos[link, b], sin[link, b] = c, sn
    tx[link, b] = x - (c * rx - sn * ry)
    ty[link, b] = y - (sn * rx + c * ry)


@njit(cache=True, inline="always", error_model="numpy")
def _turn(vx, vy, v0x, v0y, inv_l2, normalise):
    """The rotation (cos, sin) taking v₀ to v, for |v| = |v₀| (renormalised where ``normalise``:
    a dyad closed at a dead position within rounding, where |v| differs from |v₀| by ~1e-12)."""
    c = (v0x * vx + v0y * vy) * inv_l2
    sn = (v0x * vy - v0y * vx) * inv_l2
    if normalise:
        r = math.sqrt(c * c + sn * sn)
        c, sn = c / r, sn / r
    return c, sn


@njit(cache=True, inline="always", error_model="numpy")
def _at(cos, sin, tx, ty, link, b, x, y, moved=True):
    """The point (x, y) of the pose carried by ``link`` at step b (a direction where not ``moved``)."""
    c, sn = cos[link, b], sin[link, b]
    if moved:
        return c * x - sn * y + tx[link, b], sn * x + c * y + ty[link, b]
    return c * x - sn * y, sn * x + c * y


@njit(cache=True, inline="always", error_model="numpy")
def _between(vx, vy, wx, wy):
    return math.atan2(abs(vx * wy - vy * wx), vx * wx + vy * wy)


@njit(cache=True, inline="always", error_model="numpy")
def _between_slides(cos, sin, tx, ty, b, slides, link1, k1, link2, k2):
    """The angle between slide k1 carried by link1 and slide k2 carried by link2 at step b."""
    u1x, u1y = _at(cos, sin, tx, ty, link1, b, slides[k1, 0], slides[k1, 1], False)
    u2x, u2y = _at(cos, sin, tx, ty, link2, b, slides[k2, 0], slides[k2, 1], False)
    return _between(u1x, u1y, u2x, u2y)


@njit(cache=True, error_model="numpy")
def close_kernel(offsets, spaced, in_link, in_prismatic, in_point, in_slide, groups, ints, floats, points, slides,
                 carried_link, carried_point, scale2, theta, t_x, t_y, g, mu, carried):
    """Fill every carried point's position (S, P, 2) — the joints (each carried by its first link),
    then any tracer points — for each step's input offsets (S, W); and, where their arrays have a
    row per step (else none), the links' rotations θ (S, n, rad, modulo a turn) and translations
    t_x, t_y (S, n), the groups' discriminants g and transmission angles μ (S, G).  ``ints`` per
    group: i, j, J1, J2, J3, K1, K2, mesh a, mesh b; ``floats``: sign, ratio.  ``spaced``: turn
    revolute inputs by the table of rotations where a block's inputs are equally spaced."""
    steps, n, n_in, n_groups = offsets.shape[0], theta.shape[1], in_link.shape[0], groups.shape[0]
    keep_theta, keep_t = theta.shape[0] == steps, t_x.shape[0] == steps
    keep_g, keep_mu = g.shape[0] == steps, mu.shape[0] == steps
    angles = keep_theta  # a link's angle is needed: asked for, or by a gear's ratio
    for m in range(n_groups):
        if groups[m] == GEAR:
            angles = True
    # each link's pose at each step of the block: θ, cos θ, sin θ, t (the frame: 0, 1, 0, 0)
    th, cos, sin = np.zeros((n, BLOCK)), np.ones((n, BLOCK)), np.zeros((n, BLOCK))
    tx, ty = np.zeros((n, BLOCK)), np.zeros((n, BLOCK))
    gs = np.empty((n_groups, BLOCK))
    # each group's constants in the pose: squared lengths and their inverses, pose vectors
    const = np.zeros((n_groups, 8))
    for m in range(n_groups):
        k1, k2, k3 = ints[m, 2], ints[m, 3], ints[m, 4]
        if groups[m] == RRR or groups[m] == PRR:
            vx, vy = points[k3, 0] - points[k2, 0], points[k3, 1] - points[k2, 1]
            const[m, 0], const[m, 1], const[m, 2], const[m, 3] = vx * vx + vy * vy, 1 / (vx * vx + vy * vy), vx, vy
        if groups[m] == RRR:
            vx, vy = points[k3, 0] - points[k1, 0], points[k3, 1] - points[k1, 1]
            const[m, 4], const[m, 5], const[m, 6], const[m, 7] = vx * vx + vy * vy, 1 / (vx * vx + vy * vy), vx, vy
        if groups[m] == RPR:
            const[m, 0] = slides[k3, 0] * (points[k2, 1] - points[k1, 1]) - slides[k3, 1] * (points[k2, 0] - points[k1, 0])
    inv_scale2 = 1.0 / scale2
    # each input's spacing over the sweep and the rotations by 0, 1, … BLOCK − 1 spacings
    spacing = np.zeros(n_in)
    turn_c, turn_s = np.ones((n_in, BLOCK)), np.zeros((n_in, BLOCK))
    for w in range(n_in):
        if spaced and steps > 1:
            spacing[w] = (offsets[steps - 1, w] - offsets[0, w]) / (steps - 1)
        for b in range(BLOCK):
            turn_c[w, b], turn_s[w, b] = math.cos(b * spacing[w]), math.sin(b * spacing[w])
    for s0 in range(0, steps, BLOCK):
        nb = min(BLOCK, steps - s0)
        for w in range(n_in):
            link = in_link[w]
            if in_prismatic[w]:
                for b in range(nb):
                    x = offsets[s0 + b, w]
                    th[link, b] = 0.0
                    cos[link, b], sin[link, b] = 1.0, 0.0
                    tx[link, b] = x * in_slide[w, 0]
                    ty[link, b] = x * in_slide[w, 1]
                continue
            px, py = in_point[w, 0], in_point[w, 1]
            x0, dx = offsets[s0, w], spacing[w]
            equal = spaced
            for b in range(nb):  # (the rotation taken for x0 + b·dx: off by at most 2e-15 (1 + |x|) rad)
                x = offsets[s0 + b, w]
                equal = equal and abs(x - (x0 + b * dx)) <= 2e-15 * (1.0 + abs(x))
            c0, s0_ = math.cos(x0), math.sin(x0)
            if equal:
                for b in range(nb):
                    c, sn = c0 * turn_c[w, b] - s0_ * turn_s[w, b], s0_ * turn_c[w, b] + c0 * turn_s[w, b]
                    _place(cos, sin, tx, ty, link, b, c, sn, px, py, px, py)
            else:
                for b in range(nb):
                    x = offsets[s0 + b, w]
                    _place(cos, sin, tx, ty, link, b, math.cos(x), math.sin(x), px, py, px, py)
            for b in range(nb):
                th[link, b] = offsets[s0 + b, w]
        for m in range(n_groups):
            kind = groups[m]
            i, j, k1, k2, k3, h1, h2 = ints[m, 0], ints[m, 1], ints[m, 2], ints[m, 3], ints[m, 4], ints[m, 5], ints[m, 6]
            sign = floats[m, 0]
            if kind == GEAR:
                a, b_ = ints[m, 7], ints[m, 8]
                ratio = floats[m, 1]
                a0x, a0y = points[k1, 0], points[k1, 1]
                for b in range(nb):
                    if i == b_:
                        angle = th[h2, b] + (th[a, b] - th[h2, b]) / ratio
                    else:
                        angle = th[h2, b] + ratio * (th[b_, b] - th[h2, b])
                    ax, ay = _at(cos, sin, tx, ty, h1, b, a0x, a0y)
                    _place(cos, sin, tx, ty, i, b, math.cos(angle), math.sin(angle), ax, ay, a0x, a0y)
                    th[i, b] = angle
                    gs[m, b] = 1.0
                    if keep_mu:
                        mu[s0 + b, m] = np.nan
            elif kind == RRR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                lj2, inv_lj2, vjx, vjy = const[m, 0], const[m, 1], const[m, 2], const[m, 3]
                li2, inv_li2, vix, viy = const[m, 4], const[m, 5], const[m, 6], const[m, 7]
                for b in range(nb):
                    ax, ay = _at(cos, sin, tx, ty, h1, b, a0x, a0y)
                    cx, cy = _at(cos, sin, tx, ty, h2, b, c0x, c0y)
                    dx, dy = cx - ax, cy - ay
                    dd = dx * dx + dy * dy
                    inv = 1.0 / dd  # (dd = 0: NaN below, and g = −1)
                    along = 0.5 + 0.5 * (li2 - lj2) * inv
                    h2_ = li2 * inv - along * along
                    gm = h2_ * dd * inv_li2 if dd > 0.0 else -1.0
                    gs[m, b] = gm
                    root = math.sqrt(max(h2_, 0.0)) if gm >= -ROUNDING else np.nan
                    bx = ax + along * dx - sign * root * dy
                    by = ay + along * dy + sign * root * dx
                    ci, si = _turn(bx - ax, by - ay, vix, viy, inv_li2, h2_ < 0.0)
                    cj, sj = _turn(bx - cx, by - cy, vjx, vjy, inv_lj2, h2_ < 0.0)
                    _place(cos, sin, tx, ty, i, b, ci, si, ax, ay, a0x, a0y)
                    _place(cos, sin, tx, ty, j, b, cj, sj, cx, cy, c0x, c0y)
                if keep_mu:  # the angle at the middle pin B between B A and B C
                    b0x, b0y = points[k3, 0], points[k3, 1]
                    for b in range(nb):
                        bx, by = _at(cos, sin, tx, ty, i, b, b0x, b0y)
                        ax, ay = _at(cos, sin, tx, ty, i, b, a0x, a0y)
                        cx, cy = _at(cos, sin, tx, ty, j, b, c0x, c0y)
                        mu[s0 + b, m] = _between(ax - bx, ay - by, cx - bx, cy - by)
            elif kind == PRR:
                b0x, b0y = points[k3, 0], points[k3, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                u0x, u0y = slides[k1, 0], slides[k1, 1]
                lj2, inv_lj2, vjx, vjy = const[m, 0], const[m, 1], const[m, 2], const[m, 3]
                for b in range(nb):
                    ux, uy = _at(cos, sin, tx, ty, h1, b, u0x, u0y, False)
                    basex, basey = _at(cos, sin, tx, ty, h1, b, b0x, b0y)
                    cx, cy = _at(cos, sin, tx, ty, h2, b, c0x, c0y)
                    wx, wy = basex - cx, basey - cy
                    bb = ux * wx + uy * wy
                    disc = bb * bb - (wx * wx + wy * wy) + lj2
                    gs[m, b] = disc * inv_lj2
                    slide = -bb + sign * math.sqrt(max(disc, 0.0)) if gs[m, b] >= -ROUNDING else np.nan
                    bx, by = basex + slide * ux, basey + slide * uy
                    cos[i, b], sin[i, b] = cos[h1, b], sin[h1, b]
                    tx[i, b] = tx[h1, b] + slide * ux
                    ty[i, b] = ty[h1, b] + slide * uy
                    cj, sj = _turn(bx - cx, by - cy, vjx, vjy, inv_lj2, disc < 0.0)
                    _place(cos, sin, tx, ty, j, b, cj, sj, cx, cy, c0x, c0y)
                if keep_mu:  # between the rod C B and the slide's normal
                    for b in range(nb):
                        bx, by = _at(cos, sin, tx, ty, i, b, b0x, b0y)
                        cx, cy = _at(cos, sin, tx, ty, j, b, c0x, c0y)
                        ux, uy = _at(cos, sin, tx, ty, i, b, u0x, u0y, False)
                        mu[s0 + b, m] = _between(bx - cx, by - cy, -uy, ux)
            elif kind == RPR:
                a0x, a0y = points[k1, 0], points[k1, 1]
                c0x, c0y = points[k2, 0], points[k2, 1]
                u0x, u0y = slides[k3, 0], slides[k3, 1]
                h = const[m, 0]
                for b in range(nb):
                    ax, ay = _at(cos, sin, tx, ty, h1, b, a0x, a0y)
                    cx, cy = _at(cos, sin, tx, ty, h2, b, c0x, c0y)
                    dx, dy = cx - ax, cy - ay
                    disc = dx * dx + dy * dy - h * h
                    gs[m, b] = disc * inv_scale2
                    root = sign * math.sqrt(max(disc, 0.0)) if gs[m, b] >= -ROUNDING else np.nan
                    # the guide's rotation arg(C − A) − arg u₀ − atan2(h, root), a product of complexes
                    pr, pi = dx * u0x + dy * u0y, dy * u0x - dx * u0y
                    qr, qi = pr * root + pi * h, pi * root - pr * h
                    norm = math.sqrt(qr * qr + qi * qi)
                    ca, sa = qr / norm, qi / norm
                    _place(cos, sin, tx, ty, i, b, ca, sa, ax, ay, a0x, a0y)
                    _place(cos, sin, tx, ty, j, b, ca, sa, cx, cy, c0x, c0y)
                if keep_mu:  # between A C and the guide's normal
                    for b in range(nb):
                        ax, ay = _at(cos, sin, tx, ty, i, b, a0x, a0y)
                        cx, cy = _at(cos, sin, tx, ty, j, b, c0x, c0y)
                        ux, uy = _at(cos, sin, tx, ty, i, b, u0x, u0y, False)
                        mu[s0 + b, m] = _between(cx - ax, cy - ay, -uy, ux)
            elif kind == RPP:  # i turns about A with j, j slides on h2's line, i on j's: both turn with h2
                a0x, a0y = points[k1, 0], points[k1, 1]
                for b in range(nb):
                    c2, s2 = cos[h2, b], sin[h2, b]
                    ax, ay = _at(cos, sin, tx, ty, h1, b, a0x, a0y)
                    _place(cos, sin, tx, ty, i, b, c2, s2, ax, ay, a0x, a0y)
                    # the directions of the outer slide and of the middle one
                    u2x, u2y = _at(cos, sin, tx, ty, h2, b, slides[k2, 0], slides[k2, 1], False)
                    u3x, u3y = _at(cos, sin, tx, ty, h2, b, slides[k3, 0], slides[k3, 1], False)
                    # t_j = t_h2 + s₂u₂ = t_i + s₃u₃: s₂ = (t_i − t_h2) × u₃ / (u₂ × u₃)
                    det = u2x * u3y - u2y * u3x
                    gs[m, b] = det * det
                    along = ((tx[i, b] - tx[h2, b]) * u3y - (ty[i, b] - ty[h2, b]) * u3x) / det if det != 0.0 else np.nan
                    cos[j, b], sin[j, b] = c2, s2
                    tx[j, b] = tx[h2, b] + along * u2x
                    ty[j, b] = ty[h2, b] + along * u2y
                if keep_mu:  # between the two slides
                    for b in range(nb):
                        mu[s0 + b, m] = _between_slides(cos, sin, tx, ty, b, slides, j, k2, j, k3)
            else:  # PRP
                b0x, b0y = points[k3, 0], points[k3, 1]
                for b in range(nb):
                    c1, s1, c2, s2 = cos[h1, b], sin[h1, b], cos[h2, b], sin[h2, b]
                    u1x, u1y = _at(cos, sin, tx, ty, h1, b, slides[k1, 0], slides[k1, 1], False)
                    u2x, u2y = _at(cos, sin, tx, ty, h2, b, slides[k2, 0], slides[k2, 1], False)
                    b2x, b2y = _at(cos, sin, tx, ty, h2, b, b0x, b0y)
                    b1x, b1y = _at(cos, sin, tx, ty, h1, b, b0x, b0y)
                    deltax, deltay = b2x - b1x, b2y - b1y
                    det = u2x * u1y - u2y * u1x
                    gs[m, b] = det * det
                    s1_ = (deltax * (-u2y) - deltay * (-u2x)) / det if det != 0.0 else np.nan
                    s2_ = (u1x * deltay - u1y * deltax) / det if det != 0.0 else np.nan
                    cos[i, b], sin[i, b], cos[j, b], sin[j, b] = c1, s1, c2, s2
                    tx[i, b] = tx[h1, b] + s1_ * u1x
                    ty[i, b] = ty[h1, b] + s1_ * u1y
                    tx[j, b] = tx[h2, b] + s2_ * u2x
                    ty[j, b] = ty[h2, b] + s2_ * u2y
                if keep_mu:  # between the two slides
                    for b in range(nb):
                        mu[s0 + b, m] = _between_slides(cos, sin, tx, ty, b, slides, i, k1, j, k2)
            if angles and kind != GEAR:  # the angles of the group's links: a slider's is its guide's
                for b in range(nb):
                    th[i, b] = (th[h1, b] if kind == PRR or kind == PRP else th[h2, b] if kind == RPP
                                else math.atan2(sin[i, b], cos[i, b]))
                    th[j, b] = th[h2, b] if kind == PRP or kind == RPP else math.atan2(sin[j, b], cos[j, b])
        for b in range(nb):
            if keep_theta:
                for x in range(n):
                    theta[s0 + b, x] = th[x, b]
            if keep_t:
                for x in range(n):
                    t_x[s0 + b, x] = tx[x, b]
                    t_y[s0 + b, x] = ty[x, b]
            if keep_g:
                for m in range(n_groups):
                    g[s0 + b, m] = gs[m, b]
        for k in range(carried_point.shape[0]):
            link, px, py = carried_link[k], carried_point[k, 0], carried_point[k, 1]
            for b in range(nb):
                c, sn = cos[link, b], sin[link, b]
                carried[s0 + b, k, 0] = c * px - sn * py + tx[link, b]
                carried[s0 + b, k, 1] = sn * px + c * py + ty[link, b]
