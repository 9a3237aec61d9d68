"""The loop-closure equations of a linkage in link poses, their Jacobian and convective terms, and
Newton's method with continuation along the inputs (for groups that do not decompose into dyads).

Unknowns: the pose (t_x, t_y, θ) of every moving link, measured from the linkage's pose (a point p
of a link, placed as in the pose, is at R(θ)·p + t).  Equations:

==========  ====  ======================================================================
joint       rows  equation
==========  ====  ======================================================================
revolute    2     the joint's point carried by its first link = carried by each other link
prismatic   2     θ_a − θ_b = 0; the point carried by b stays on a's sliding line:
                  (R(θ_a)·u) × (p_b − p_a) = 0
mesh        1     θ_a − θ_c − ρ·(θ_b − θ_c) = 0 (c the carrier of both gears' axes)
input       1     revolute: θ_L − (φ − φ_pose) = 0; prismatic: u · (p_L − p_frame) − s = 0
==========  ====  ======================================================================

Every function is vectorised over a leading axis of S configurations.
"""

from __future__ import annotations

import numpy as np

from ..structure.joints import PRISMATIC, REVOLUTE
from ._linkage import Linkage, joint_name

__all__ = ["System", "check_movable"]


def _rotate(theta: np.ndarray, p: np.ndarray) -> np.ndarray:
    """R(θ)·p for θ of shape (S,) and p of shape (2,): shape (S, 2); or θ (S, P) and points p (P, 2):
    shape (S, P, 2)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack((c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1]), axis=-1)


def _perp(v: np.ndarray) -> np.ndarray:
    """v turned by +90°."""
    return np.stack((-v[..., 1], v[..., 0]), axis=-1)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


class System:
    """The closure equations of one linkage (built once, evaluated for many configurations).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> sys = System(lk); sys.size
    9
    >>> theta, t = sys.poses(np.zeros((1, 9)))
    >>> float(abs(sys.residual(theta, t, lk.pose_inputs[None, :])).max())
    0.0
    """

    def __init__(self, linkage: Linkage):
        self.linkage = lk = linkage
        chain, points = lk.chain, lk.points
        self.moving = [x for x in range(chain.links) if x != lk.frame]
        self.column = {x: i for i, x in enumerate(self.moving)}
        self.size = 3 * len(self.moving)
        self.pins = []  # (first link, other link, point)
        self.sliders = []  # (link a, link b, point, direction)
        self.meshes = []  # (a, b, carrier, ratio)
        for k, j in enumerate(chain.joints):
            kind = lk.kind(k)
            if kind == REVOLUTE:
                self.pins += [(j[0], x, points[k]) for x in j[1:]]
            elif kind == PRISMATIC:
                self.sliders.append((j[0], j[1], points[k], np.array(lk.slides[k])))
            else:
                self.meshes.append((j[0], j[1], lk.carrier(k), lk.meshes[k]))
        self.drives = []  # (link, kind, point, direction)
        for i, k in enumerate(lk.inputs):
            self.drives.append((lk.input_link(i), lk.kind(k), points[k], np.array(lk.slides.get(k, (1.0, 0.0)))))
        self.rows = 2 * len(self.pins) + 2 * len(self.sliders) + len(self.meshes) + len(self.drives)
        # the pins' equations at once: each pin's links, point, rows and (θ-)columns (−1: the frame)
        self._pin_a = np.array([a for a, _, _ in self.pins], dtype=int)
        self._pin_b = np.array([b for _, b, _ in self.pins], dtype=int)
        self._pin_p = np.array([p for _, _, p in self.pins], dtype=float).reshape(-1, 2)
        pin_rows = 2 * np.arange(len(self.pins))
        theta_col = np.array([3 * self.column[x] + 2 if x in self.column else -1 for x in range(chain.links)])
        self._pin_ends = np.concatenate((self._pin_a, self._pin_b))  # both ends' points turned in one call
        self._pin_pp = np.concatenate((self._pin_p, self._pin_p))
        self._constant = np.zeros((self.rows, self.size))  # the Jacobian's entries that do not depend on q
        jac = []  # per pin end on a moving link: the end, its pin's x row, its link's θ column, its sign
        for side, (links, sign) in enumerate(((self._pin_a, 1.0), (self._pin_b, -1.0))):
            moving = np.flatnonzero(theta_col[links] >= 0)
            rows, cols = pin_rows[moving], theta_col[links[moving]]
            self._constant[rows, cols - 2] = self._constant[rows + 1, cols - 1] = sign
            jac.append((moving + side * len(self.pins), rows, cols, np.full(len(moving), sign)))
        self._pin_jac = tuple(np.concatenate(parts) for parts in zip(*jac))

    # ------------------------------------------------------------- poses
    def poses(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Per-link rotation θ (S, n) and translation t (S, n, 2) from the unknowns q (S, 3m)."""
        s = q.shape[0]
        n = self.linkage.chain.links
        theta, t = np.zeros((s, n)), np.zeros((s, n, 2))
        cols = np.array(self.moving, dtype=int)
        theta[:, cols] = q[:, 2::3]
        t[:, cols, 0] = q[:, 0::3]
        t[:, cols, 1] = q[:, 1::3]
        return theta, t

    def input_offsets(self, values: np.ndarray) -> np.ndarray:
        """The inputs as the drives' coordinates: rotation from the pose, or displacement (S, W)."""
        return np.asarray(values, dtype=float) - self.linkage.pose_inputs[None, :]

    # ---------------------------------------------------------- equations
    def residual(self, theta, t, values) -> np.ndarray:
        """The closure equations' values (S, rows); ``values`` the inputs (S, W)."""
        count = len(self.pins)
        turned = _rotate(theta[:, self._pin_ends], self._pin_pp)
        pins = turned[:, :count] + t[:, self._pin_a] - turned[:, count:] - t[:, self._pin_b]
        out = list(pins.reshape(len(theta), -1).T)
        for a, b, p, u in self.sliders:
            d = _rotate(theta[:, b], p) + t[:, b] - _rotate(theta[:, a], p) - t[:, a]
            out += [theta[:, a] - theta[:, b], _cross(_rotate(theta[:, a], u), d)]
        for a, b, c, ratio in self.meshes:
            out.append(theta[:, a] - theta[:, c] - ratio * (theta[:, b] - theta[:, c]))
        offsets = self.input_offsets(values)
        for i, (link, kind, p, u) in enumerate(self.drives):
            if kind == REVOLUTE:
                out.append(theta[:, link] - offsets[:, i])
            else:
                out.append((_rotate(theta[:, link], p) + t[:, link] - p) @ u - offsets[:, i])
        return np.stack(out, axis=1)

    def jacobian(self, theta, t) -> np.ndarray:
        """∂(equations)/∂q, shape (S, rows, 3m)."""
        s = theta.shape[0]
        jac = np.repeat(self._constant[None], s, axis=0)
        col = self.column
        ends, rows, cols, sign = self._pin_jac
        turned = _rotate(theta[:, self._pin_ends[ends]], self._pin_pp[ends])  # ∂/∂θ: the point turned by +90°
        jac[:, rows, cols] = -sign * turned[..., 1]
        jac[:, rows + 1, cols] = sign * turned[..., 0]
        row = 2 * len(self.pins)

        def put(r, link, dt, dtheta):  # dt (S, 2) or None, dtheta (S,)
            if link in col:
                c = 3 * col[link]
                if dt is not None:
                    jac[:, r, c], jac[:, r, c + 1] = dt[..., 0], dt[..., 1]
                jac[:, r, c + 2] += dtheta

        one = np.ones(s)
        for a, b, p, u in self.sliders:
            put(row, a, None, one)
            put(row, b, None, -one)
            w = _rotate(theta[:, a], u)
            d = _rotate(theta[:, b], p) + t[:, b] - _rotate(theta[:, a], p) - t[:, a]
            put(row + 1, a, -_perp(w), _cross(_perp(w), d) - _cross(w, _perp(_rotate(theta[:, a], p))))
            put(row + 1, b, _perp(w), _cross(w, _perp(_rotate(theta[:, b], p))))
            row += 2
        for a, b, c, ratio in self.meshes:
            put(row, a, None, one)
            put(row, b, None, -ratio * one)
            put(row, c, None, (ratio - 1) * one)
            row += 1
        for link, kind, p, u in self.drives:
            if kind == REVOLUTE:
                put(row, link, None, one)
            else:
                put(row, link, np.broadcast_to(u, (s, 2)), _perp(_rotate(theta[:, link], p)) @ u)
            row += 1
        return jac

    def rate_column(self) -> np.ndarray:
        """−∂(equations)/∂(inputs), shape (rows, W): the right-hand side of J·q̇ = … per unit input rate."""
        out = np.zeros((self.rows, len(self.drives)))
        for i in range(len(self.drives)):
            out[self.rows - len(self.drives) + i, i] = 1.0
        return out

    def convective(self, theta, t, dtheta, dt) -> np.ndarray:
        """The part of the equations' second time derivative not linear in q̈ (S, rows)."""
        out = []
        for a, b, p in self.pins:
            g = -dtheta[:, a, None] ** 2 * _rotate(theta[:, a], p) + dtheta[:, b, None] ** 2 * _rotate(theta[:, b], p)
            out += list(g.T)
        for a, b, p, u in self.sliders:
            w = _rotate(theta[:, a], u)
            pa, pb = _rotate(theta[:, a], p), _rotate(theta[:, b], p)
            d = pb + t[:, b] - pa - t[:, a]
            dd = dt[:, b] + dtheta[:, b, None] * _perp(pb) - dt[:, a] - dtheta[:, a, None] * _perp(pa)
            gd = -dtheta[:, b, None] ** 2 * pb + dtheta[:, a, None] ** 2 * pa
            out += [np.zeros(len(theta)),
                    _cross(-dtheta[:, a, None] ** 2 * w, d) + 2 * _cross(dtheta[:, a, None] * _perp(w), dd) + _cross(w, gd)]
        for _ in self.meshes:
            out.append(np.zeros(len(theta)))
        for link, kind, p, u in self.drives:
            out.append(np.zeros(len(theta)) if kind == REVOLUTE
                       else (-dtheta[:, link, None] ** 2 * _rotate(theta[:, link], p)) @ u)
        return np.stack(out, axis=1)

    # ------------------------------------------------------------ solves
    def solve_linear(self, jac: np.ndarray, rhs: np.ndarray, regular: np.ndarray | None = None) -> np.ndarray:
        """Solve J·x = rhs per configuration (least squares where the system has more rows than
        unknowns, as with wedge loops whose angle equations repeat); NaN where J is singular.
        ``regular``: where J is known not to be singular (det J ≠ 0), if already found."""
        if self.rows == self.size:
            if regular is None:
                with np.errstate(divide="ignore", invalid="ignore"):  # (an exactly singular J: its det is 0, said below)
                    regular = np.abs(np.linalg.det(jac)) > 0
            ok = regular
            if ok.all():  # (no copies of the regular configurations to make)
                return np.linalg.solve(jac, rhs)
            out = np.full(rhs.shape, np.nan)
            if ok.any():
                out[ok] = np.linalg.solve(jac[ok], rhs[ok])
            return out
        return np.stack([np.linalg.lstsq(jac[i], rhs[i], rcond=None)[0] for i in range(len(jac))])

    def rates(self, theta, t, accelerations: bool = False):
        """Link rates per unit rate of each input: q̇ (S, W, 3m) and, if asked, q̈ (S, W, 3m)
        with that input alone moving at unit rate and no input accelerating."""
        jac = self.jacobian(theta, t)
        w = len(self.drives)
        rhs = np.broadcast_to(self.rate_column(), (len(theta), self.rows, w))
        regular = np.abs(np.linalg.det(jac)) > 0 if accelerations and self.rows == self.size else None
        qd = np.moveaxis(self.solve_linear(jac, np.array(rhs), regular), 2, 1)  # (S, W, 3m)
        if not accelerations:
            return qd, None
        qdd = np.empty_like(qd)
        for i in range(w):
            dtheta, dt = self.poses(qd[:, i])
            gamma = self.convective(theta, t, dtheta, dt)
            qdd[:, i] = self.solve_linear(jac, -gamma[..., None], regular)[..., 0]
        return qd, qdd

    def conditioning(self, theta, t) -> np.ndarray:
        """Smallest over largest singular value of J per configuration (0: singular)."""
        sv = np.linalg.svd(self.jacobian(theta, t), compute_uv=False)
        return sv[:, -1] / np.maximum(sv[:, 0], 1e-300) if self.rows == self.size else \
            sv[:, self.size - 1] / np.maximum(sv[:, 0], 1e-300)

    def newton(self, q: np.ndarray, values: np.ndarray, *, tol: float, iterations: int = 30):
        """Newton's method from q (3m,) at inputs ``values`` (W,): (q, converged, sign of det J)."""
        scale = self.linkage.scale
        for _ in range(iterations):
            theta, t = self.poses(q[None])
            r = self.residual(theta, t, values[None])[0]
            jac = self.jacobian(theta, t)[0]
            if np.abs(r).max() <= tol * scale:
                return q, True, _sign_det(jac, self.rows == self.size)
            try:
                dq = np.linalg.solve(jac, -r) if self.rows == self.size else np.linalg.lstsq(jac, -r, rcond=None)[0]
            except np.linalg.LinAlgError:
                return q, False, 0
            if not np.isfinite(dq).all() or np.abs(dq).max() > 10 * (scale + 1):
                return q, False, 0
            q = q + dq
        return q, False, 0


def _sign_det(jac: np.ndarray, square: bool) -> int:
    if square:
        return int(np.sign(np.linalg.det(jac)))
    return 1


#: J's smallest / largest singular value below this: the pose is locked (or a dead position)
LOCKED = 1e-8


def check_movable(linkage: Linkage) -> str | None:
    """None if the inputs move the linkage out of its pose, else why not (one clause).

    >>> from synth.structure.chain import Chain, Mechanism
    >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3.5, 3]])
    >>> check_movable(lk) is None
    True
    >>> flat = Linkage(lk.mechanism, (0,), [[0, 0], [4, 0], [1, 0], [2, 0]])
    >>> check_movable(flat)
    'its loop-closure equations are singular there: links 2, 3 are aligned in a dead position'
    """
    system = System(linkage)
    theta, t = system.poses(np.zeros((1, system.size)))
    if system.conditioning(theta, t)[0] > LOCKED:
        return None
    from ._dyads import locked_groups  # which dyads are aligned, where the mechanism decomposes

    groups = locked_groups(linkage)
    if groups:
        return ("its loop-closure equations are singular there: links "
                + "; ".join(", ".join(map(str, g)) for g in groups) + " are aligned in a dead position")
    return ("its loop-closure equations are singular there (a group of links aligned in a dead position, "
            f"or a locked sub-chain); input{'s' * (linkage.dof > 1)} "
            + ", ".join(joint_name(linkage.chain, k) for k in linkage.inputs))
