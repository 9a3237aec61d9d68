"""Arms from URDF through Pinocchio, and Pinocchio's gravity as the independent check.

Reading: Pinocchio builds the rigid-body model (revolute, continuous and prismatic
joints; fixed joints merged). Gravity is ``−g·z`` of the URDF's base frame.

Decomposition: each body's height is a product of one rotation per joint, so the gravity
potential of a revolute arm is a trigonometric polynomial of degree at most one in every
joint angle, ``U(q) = Σ_k c_k·e^{i k·q}`` with ``k ∈ {−1, 0, 1}ⁿ``. Sampling ``U`` on the grid
``q_j ∈ {0, 2π/3, 4π/3}`` (``3ⁿ`` potential evaluations) and a discrete Fourier transform give
every ``c_k`` exactly (to rounding); ``k`` and ``−k`` pair into ``2|c_k|·cos(k·q + arg c_k)``, a
harmonic term of the linear form ``k·q``. A prismatic joint enters affinely (each body's
position once), so ``U`` is sampled at the slide's mid-stroke and one unit beyond, and its
coefficient ``q`` is replaced by ``k·sin(q/k)`` (the gear-ratio substitution of
:mod:`balance.model.arm`, accuracy ``ε`` over the stroke): ``q·e^{iφ} ≈ (k/2i)·(e^{i(φ+γ)} − e^{i(φ−γ)})``.

Check: :func:`pinocchio_check` compares the project's gravity forces (its own arm model or
the harmonic terms) with ``pinocchio.computeGeneralizedGravity`` at random configurations.
A TOML arm is checked through :func:`arm_to_urdf`, which writes it as URDF.
"""

from __future__ import annotations

import contextlib
import itertools
import math
import os
import sys
from dataclasses import dataclass

import numpy as np

from mechbase import Row

from ..errors import InvalidArm, SchemaError
from .arm import Arm, ArmModel, Coordinate, gear_ratio_for_accuracy
from .potential import HarmonicTerm, merge_terms, terms_forces

__all__ = ["UrdfArm", "load_urdf", "validate_urdf", "arm_to_urdf", "pinocchio_model", "pinocchio_gravity",
           "pinocchio_check", "PinocchioCheck", "URDF_JOINT_TYPES", "MAX_REVOLUTE", "DHLink", "urdf_from_dh"]

#: the decomposition's grid holds 3ⁿ complex numbers: beyond 16 revolute joints (0.7 GB) it is refused
MAX_REVOLUTE = 16
_G = 9.80665


def _pin():
    try:
        import pinocchio
    except ImportError:  # pragma: no cover - pin is a dependency
        raise InvalidArm("reading URDF needs Pinocchio: python -m pip install pin.") from None
    return pinocchio


@contextlib.contextmanager
def _quiet_stderr():
    """Silence file descriptor 2 (C++ libraries print there, bypassing sys.stderr)."""
    fd = 2
    try:
        sys.stderr.flush()
        saved = os.dup(fd)
    except OSError:
        yield
        return
    try:
        with open(os.devnull, "w") as null:
            os.dup2(null.fileno(), fd)
        yield
    finally:
        os.dup2(saved, fd)
        os.close(saved)


#: URDF joint types an arm may have (fixed joints are merged into their parent link)
URDF_JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed")


def _numbers(element, attribute: str, count: int, default: str, what: str) -> np.ndarray:
    text = default if element is None else element.get(attribute, default)
    words = "a finite number" if count == 1 else f"{count} finite numbers"
    try:
        values = np.array([float(v) for v in text.split()])
    except ValueError:
        raise InvalidArm(f"{what} must be {words}, not {text!r}.") from None
    if values.size != count or not np.all(np.isfinite(values)):
        raise InvalidArm(f"{what} must be {words}, not {text!r}.")
    return values


def _check_inertial(link) -> None:
    name = link.get("name")
    inertial = link.find("inertial")
    if inertial is None:
        return  # a massless link (a frame)
    _numbers(inertial.find("origin"), "xyz", 3, "0 0 0", f"the centre of mass of link '{name}'")
    _numbers(inertial.find("origin"), "rpy", 3, "0 0 0", f"the inertia frame of link '{name}'")
    mass_el = inertial.find("mass")
    mass = _numbers(mass_el, "value", 1, "0", f"the mass of link '{name}'")[0]
    if mass < 0:
        raise InvalidArm(f"link '{name}' has the negative mass {mass:g} kg.")
    el = inertial.find("inertia")
    keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    vals = {}
    for k in keys:
        vals[k] = _numbers(el, k, 1, "0", f"the inertia {k} of link '{name}'")[0]
    inertia = np.array([[vals["ixx"], vals["ixy"], vals["ixz"]],
                        [vals["ixy"], vals["iyy"], vals["iyz"]],
                        [vals["ixz"], vals["iyz"], vals["izz"]]])
    eig = np.linalg.eigvalsh(inertia)
    tol = 1e-9 * max(float(np.max(np.abs(eig))), 1e-300)
    if eig[0] < -tol:  # a body's principal moments are ≥ 0 (all 0 for a point mass)
        raise InvalidArm(
            f"link '{name}' has an inertia with a negative principal moment ({', '.join(f'{v:.4g}' for v in eig)} "
            "kg·m²): it must be positive semi-definite.")


def validate_urdf(text: str) -> None:
    """Refuse a URDF no arm can be read from, in one sentence naming the link or joint.

    Checked before Pinocchio sees the file (it accepts several of these silently): every
    number finite; masses ≥ 0 (0, or no ``<inertial>``, is a massless frame); inertia matrices
    positive semi-definite (a point mass has zero inertia); joint types among :data:`URDF_JOINT_TYPES`; parents and children that exist,
    no joint whose parent is its own child, no link that is the child of two joints, one root
    link and no loop; finite non-zero axes; limits ``lower < upper`` on revolute and prismatic
    joints.

    Examples
    --------
    >>> validate_urdf('<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="continuous">'
    ...               '<parent link="a"/><child link="b"/></joint></robot>')
    >>> validate_urdf('<robot name="r"><link name="a"/><joint name="j" type="continuous">'
    ...               '<parent link="a"/><child link="a"/></joint></robot>')
    Traceback (most recent call last):
    ...
    balance.errors.InvalidArm: joint 'j' has the link 'a' as both its parent and its child.
    """
    import xml.etree.ElementTree as ET

    try:
        root = ET.fromstring(text)
    except ET.ParseError as exc:
        raise SchemaError(f"not a URDF file: the XML does not parse ({exc}).") from None
    if root.tag != "robot":
        raise SchemaError(f"not a URDF file: its root element is <{root.tag}>, not <robot>.")
    links = root.findall("link")
    names = [ln.get("name") for ln in links]
    if not links:
        raise InvalidArm("the URDF has no link.")
    for n in names:
        if not n:
            raise InvalidArm("a URDF link has no name.")
        if names.count(n) > 1:
            raise InvalidArm(f"two URDF links are named '{n}'.")
    for ln in links:
        _check_inertial(ln)
    parent_of: dict[str, str] = {}
    joint_names: set[str] = set()
    for j in root.findall("joint"):
        name, kind = j.get("name"), j.get("type")
        if not name:
            raise InvalidArm("a URDF joint has no name.")
        if name in joint_names:
            raise InvalidArm(f"two URDF joints are named '{name}'.")
        joint_names.add(name)
        if kind not in URDF_JOINT_TYPES:
            raise InvalidArm(f"joint '{name}' is of type {kind!r}, which an arm cannot have here; "
                             "use revolute, continuous, prismatic or fixed joints.")
        parent = (j.find("parent").get("link") if j.find("parent") is not None else None)
        child = (j.find("child").get("link") if j.find("child") is not None else None)
        for role, link in (("parent", parent), ("child", child)):
            if link is None:
                raise InvalidArm(f"joint '{name}' names no {role} link.")
            if link not in names:
                raise InvalidArm(f"joint '{name}' has the {role} link '{link}', which the URDF does not define.")
        if parent == child:
            raise InvalidArm(f"joint '{name}' has the link '{parent}' as both its parent and its child.")
        if child in parent_of:
            raise InvalidArm(f"link '{child}' is the child of two joints ('{parent_of[child]}' and '{name}'): "
                             "an arm is a tree.")
        parent_of[child] = name
        _numbers(j.find("origin"), "xyz", 3, "0 0 0", f"the origin of joint '{name}'")
        _numbers(j.find("origin"), "rpy", 3, "0 0 0", f"the orientation of joint '{name}'")
        if kind != "fixed":
            axis = _numbers(j.find("axis"), "xyz", 3, "1 0 0", f"the axis of joint '{name}'")
            if not np.linalg.norm(axis) > 0:
                raise InvalidArm(f"joint '{name}' has the zero axis; give its direction.")
        if kind in ("revolute", "prismatic"):
            lim = j.find("limit")
            if lim is None:
                raise InvalidArm(f"joint '{name}' is {kind} and needs a <limit lower=… upper=…>.")
            lo = _numbers(lim, "lower", 1, "0", f"the lower limit of joint '{name}'")[0]
            hi = _numbers(lim, "upper", 1, "0", f"the upper limit of joint '{name}'")[0]
            if not lo < hi:
                raise InvalidArm(f"joint '{name}' has the limits lower {lo:g} ≥ upper {hi:g}; give lower < upper.")
    joints_by_child = {c: j for c, j in parent_of.items()}
    roots = [n for n in names if n not in joints_by_child]
    if len(roots) != 1:
        if not roots:
            raise InvalidArm("every URDF link is the child of a joint: the joints close a loop, and an arm is a tree.")
        raise InvalidArm(f"the URDF has {len(roots)} root links ({', '.join(roots[:4])}): an arm is one tree "
                         "rooted at its base.")
    child_links: dict[str, list[str]] = {}
    for j in root.findall("joint"):
        child_links.setdefault(j.find("parent").get("link"), []).append(j.find("child").get("link"))
    seen, todo = {roots[0]}, [roots[0]]
    while todo:
        for c in child_links.get(todo.pop(), []):
            if c not in seen:
                seen.add(c)
                todo.append(c)
    if len(seen) != len(names):
        lost = sorted(set(names) - seen)
        raise InvalidArm(f"the links {', '.join(lost[:4])} hang in a loop of joints, not from the base "
                         f"'{roots[0]}': an arm is a tree.")


def pinocchio_model(urdf_text: str, g: float = _G):
    """A fixed-base Pinocchio model from URDF text (checked by :func:`validate_urdf`), gravity ``−g·z``."""
    validate_urdf(urdf_text)
    pin = _pin()
    try:
        with _quiet_stderr():  # the URDF parser writes its own diagnostics to stderr
            model = pin.buildModelFromXML(urdf_text)
    except (RuntimeError, ValueError) as exc:
        raise SchemaError(f"not a URDF Pinocchio can read ({str(exc).splitlines()[0][:120]}).") from None
    model.gravity.linear = np.array([0.0, 0.0, -g])
    return model


#: Pinocchio's joint models a URDF's revolute, continuous and prismatic joints become
_REVOLUTE = {"JointModelRX", "JointModelRY", "JointModelRZ", "JointModelRevoluteUnaligned"}
_UNBOUNDED = {"JointModelRUBX", "JointModelRUBY", "JointModelRUBZ", "JointModelRevoluteUnboundedUnaligned"}
_PRISMATIC = {"JointModelPX", "JointModelPY", "JointModelPZ", "JointModelPrismaticUnaligned"}


def _tool0(model):
    for f in model.frames:
        if f.name == "tool0":
            joint = f.parentJoint if hasattr(f, "parentJoint") else f.parent
            if joint > 0:
                return int(joint), tuple(float(v) for v in f.placement.translation)
    return None


class UrdfArm(ArmModel):
    """A serial (or tree) arm read from URDF: one coordinate per joint (continuous joints as an angle).

    Gravity comes from Pinocchio (``potential``, ``gravity_forces``); the harmonic terms from
    sampling its potential (see the module docstring).

    Parameters
    ----------
    model : pinocchio.Model
        A fixed-base model (:func:`pinocchio_model`).
    name : str
    accuracy : float
        ``ε`` of every slide's ``γ = q/k`` substitution (:func:`~balance.model.arm.gear_ratio_for_accuracy`).
    drive_matrix : array, optional
        ``D`` with ``q = D·ψ`` (default: a drive at each joint).
    """

    def __init__(self, model, name: str = "urdf arm", accuracy: float = 1e-3, drive_matrix=None,
                 payload_point: tuple[int, tuple[float, float, float]] | None = None):
        self.model, self.name, self.accuracy = model, name, accuracy
        #: where a payload sits: (Pinocchio joint index, position in that joint's frame); default the frame
        #: "tool0" when the URDF has one (the flange, by ROS convention), else the last joint's origin
        self.payload_point = payload_point or _tool0(model) or (model.njoints - 1, (0.0, 0.0, 0.0))
        self.drive_matrix = None if drive_matrix is None else np.asarray(drive_matrix, dtype=float)
        coords = []
        for j in range(1, model.njoints):
            jm = model.joints[j]
            short, label = jm.shortname(), model.names[j]
            lo, hi = float(model.lowerPositionLimit[jm.idx_q]), float(model.upperPositionLimit[jm.idx_q])
            if short in _UNBOUNDED:
                coords.append(Coordinate(label, "revolute", (-math.pi, math.pi)))
            elif short in _REVOLUTE:
                lim = (max(lo, -math.pi), min(hi, math.pi)) if lo < hi else (-math.pi, math.pi)
                coords.append(Coordinate(label, "revolute", lim))
            elif short in _PRISMATIC:
                if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                    raise InvalidArm(f"URDF joint '{label}' is prismatic and needs finite limits lower < upper.")
                coords.append(Coordinate(label, "prismatic", (lo, hi), hi - lo,
                                         gear_ratio_for_accuracy(hi - lo, accuracy)))
            else:
                raise InvalidArm(f"URDF joint '{label}' is of a kind balance cannot take ({short}); "
                                 "use revolute, continuous or prismatic joints.")
        if not coords:
            raise InvalidArm("the URDF has no movable joint.")
        self.coordinates = tuple(coords)
        if self.drive_matrix is not None and (self.drive_matrix.shape != (self.n, self.n)
                                              or abs(np.linalg.det(self.drive_matrix)) < 1e-12):
            raise InvalidArm(f"the drive matrix must be a non-singular {self.n}×{self.n} matrix for this URDF arm.")
        self._data = model.createData()

    @property
    def kinds(self) -> list[str]:
        return [c.joint for c in self.coordinates]

    def copy(self, model=None) -> "UrdfArm":
        """The same arm (a copy of its model, or ``model``)."""
        return UrdfArm(self.model.copy() if model is None else model, self.name, self.accuracy, self.drive_matrix,
                       self.payload_point)

    def with_payload_at(self, link: str | None = None, at=(0.0, 0.0, 0.0)) -> "UrdfArm":
        """The same arm with its payload point on ``link`` (a URDF link name; default the last) at ``at`` (m,
        in that link's frame)."""
        pin = _pin()
        if link is None:
            return UrdfArm(self.model, self.name, self.accuracy, self.drive_matrix, (self.model.njoints - 1, tuple(at)))
        for f in self.model.frames:
            if f.name == link and f.type in (pin.FrameType.BODY, pin.FrameType.FIXED_JOINT, pin.FrameType.OP_FRAME):
                joint = f.parentJoint if hasattr(f, "parentJoint") else f.parent
                if joint == 0:
                    raise InvalidArm(f"the payload's link '{link}' is the base: it does not move.")
                point = f.placement.act(np.asarray(at, dtype=float))
                return UrdfArm(self.model, self.name, self.accuracy, self.drive_matrix,
                               (int(joint), tuple(float(v) for v in point)))
        names = sorted({f.name for f in self.model.frames if f.type == pin.FrameType.BODY})
        raise InvalidArm(f"the URDF has no link '{link}' to carry the payload (links: {', '.join(names)}).")

    def with_payload(self, mass: float, g: float | None = None) -> "UrdfArm":
        """The same arm carrying a point mass of ``mass`` kg at its payload point."""
        if mass == 0:
            return self
        pin = _pin()
        model = self.model.copy()
        joint, at = self.payload_point
        model.inertias[joint] = model.inertias[joint] + pin.Inertia(float(mass), np.asarray(at, dtype=float),
                                                                     np.zeros((3, 3)))
        return self.copy(model)

    def mass_matrix(self, q: np.ndarray) -> np.ndarray:
        """The joint-space mass matrix ``M(q)`` (composite rigid-body algorithm), (n, n) or (m, n, n)."""
        pin = _pin()
        qq = np.atleast_2d(q)
        out = []
        for c in self.configs(qq):
            m = pin.crba(self.model, self._data, c)
            out.append(np.triu(m) + np.triu(m, 1).T)
        out = np.array(out)
        return out[0] if np.ndim(q) == 1 else out

    def link_name(self, j: int) -> str:
        """The name of the link joint ``j`` (0-based) moves: the first URDF link it carries."""
        pin = _pin()
        for f in self.model.frames:
            parent = f.parentJoint if hasattr(f, "parentJoint") else f.parent
            if f.type == pin.FrameType.BODY and parent == j + 1:
                return f.name
        return self.coordinates[j].name

    @property
    def g(self) -> float:
        """The magnitude of the model's gravity (m/s²)."""
        return float(np.linalg.norm(self.model.gravity.linear))

    def config(self, q: np.ndarray) -> np.ndarray:
        """Pinocchio's configuration vector for joint coordinates ``q`` (n,)."""
        return self.configs(np.atleast_2d(q))[0]

    def configs(self, q: np.ndarray) -> np.ndarray:
        """Pinocchio's configuration vectors for joint coordinates ``q`` (m, n), shape (m, nq)."""
        if not hasattr(self, "_layout"):
            pin = _pin()
            one = [(j - 1, self.model.joints[j].idx_q) for j in range(1, self.model.njoints)
                   if self.model.joints[j].nq == 1]
            two = [(j - 1, self.model.joints[j].idx_q) for j in range(1, self.model.njoints)
                   if self.model.joints[j].nq == 2]
            self._layout = (np.asarray(pin.neutral(self.model)), one, two)
        neutral, one, two = self._layout
        q = np.asarray(q, dtype=float)
        out = np.tile(neutral, (len(q), 1))
        for j, i in one:
            out[:, i] = q[:, j]
        for j, i in two:
            out[:, i], out[:, i + 1] = np.cos(q[:, j]), np.sin(q[:, j])
        return out

    def potential(self, q: np.ndarray) -> np.ndarray:
        pin = _pin()
        qq = np.atleast_2d(q)
        u = np.array([pin.computePotentialEnergy(self.model, self._data, c) for c in self.configs(qq)])
        return u[0] if np.ndim(q) == 1 else u

    def gravity_forces(self, q: np.ndarray) -> np.ndarray:
        """``−∂U/∂q`` from Pinocchio's generalised gravity."""
        pin = _pin()
        qq = np.atleast_2d(q)
        g = np.array([pin.computeGeneralizedGravity(self.model, self._data, c) for c in self.configs(qq)])
        return -(g[0] if np.ndim(q) == 1 else g)

    def approx_potential_error_bounds(self) -> np.ndarray:
        """Upper bounds of ``|Q_exact − Q_terms|`` per joint from the ``γ = q/k`` substitution.

        The potential is ``U0(θ) + Σ_slides q_j·B_j(θ)`` with ``B_j`` the weight carried by slide
        ``j`` times the vertical component of its axis (a function of the rotations before it):
        replacing ``q_j`` by ``k·sin(q_j/k)`` changes the slide's force by at most
        ``W_j·(1 − cos γ_max)`` and each revolute joint before it by ``W_j·(s/2)·(1 − sin γ_max/γ_max)``.
        """
        pin = _pin()
        data = self.model.createData()
        pin.computeSubtreeMasses(self.model, data)
        g = float(np.linalg.norm(self.model.gravity.linear))
        bounds = np.zeros(self.n)
        for j, ln in enumerate(self.coordinates):
            if ln.joint != "prismatic":
                continue
            weight = g * float(data.mass[j + 1])
            half = ln.stroke / 2
            gm = half / ln.gear_ratio
            bounds[j] += weight * (1 - math.cos(gm))
            i = self.model.parents[j + 1]
            while i > 0:
                if self.kinds[i - 1] == "revolute":
                    bounds[i - 1] += weight * half * (1 - math.sin(gm) / gm)
                i = self.model.parents[i]
        return bounds

    # ------------------------------------------------------- harmonic terms
    def ensure_decomposable(self, limit: float | None) -> float:
        """Refuse a decomposition whose grid would not fit in memory, or (``limit`` s) take too long.

        Returns the estimated seconds (``3ʳ·2ᵖ`` potential evaluations, r revolute joints, p slides).
        """
        from ..budget import ensure_affordable

        rev = sum(c.joint == "revolute" for c in self.coordinates)
        pri = self.n - rev
        if rev > MAX_REVOLUTE:
            raise InvalidArm(f"the URDF arm has {rev} revolute joints; the exact decomposition samples 3ⁿ "
                             f"configurations and stops at {MAX_REVOLUTE} (its grid would fill memory).")
        q = self.sample(4)
        return ensure_affordable(f"decomposing the potential of {rev} revolute joints and {pri} slides "
                                 f"({3 ** rev * 2 ** pri} evaluations)", 3 ** rev * 2 ** pri,
                                 lambda: self.potential(q), limit, per=len(q))

    def harmonic_terms(self) -> list[HarmonicTerm]:
        """Exact harmonic terms for revolute joints (DFT on the 3-point grid), ``γ = q/k`` for slides."""
        rev = [i for i, c in enumerate(self.coordinates) if c.joint == "revolute"]
        pri = [i for i, c in enumerate(self.coordinates) if c.joint == "prismatic"]
        self.ensure_decomposable(None)
        mids = {i: 0.5 * sum(self.coordinates[i].limits) for i in pri}
        nodes = 2 * math.pi * np.arange(3) / 3
        phasors: list[tuple[complex, np.ndarray]] = []
        # U at slide offsets 0/1 from mid-stroke → affine coefficients by inclusion-exclusion
        corner_values = {}
        shape, size = (3,) * len(rev), 3 ** len(rev)
        for corner in itertools.product((0, 1), repeat=len(pri)):
            flat = np.empty(size)
            for start in range(0, size, 4096):  # the grid in C order, a chunk of configurations at a time
                ids = np.arange(start, min(start + 4096, size))
                q = np.zeros((len(ids), self.n))
                if rev:
                    q[:, rev] = nodes[np.stack(np.unravel_index(ids, shape), axis=1)]
                for j, c in zip(pri, corner):
                    q[:, j] = mids[j] + c
                flat[start:start + len(ids)] = self.potential(q)
            corner_values[corner] = flat.reshape(shape)
        for subset in itertools.product((0, 1), repeat=len(pri)):
            grid = sum((-1) ** (sum(subset) - sum(t)) * corner_values[t]
                       for t in itertools.product((0, 1), repeat=len(pri)) if all(a <= b for a, b in zip(t, subset)))
            coef = np.fft.fftn(grid) / grid.size if rev else np.asarray(grid, dtype=complex)
            tol = 1e-13 * max(float(np.max(np.abs(coef))), 1e-300)  # DFT rounding: parts below it are zero
            coef = np.where(np.abs(coef.real) < tol, 0, coef.real) + 1j * np.where(np.abs(coef.imag) < tol, 0, coef.imag)
            for idx in itertools.product(range(3), repeat=len(rev)):
                c = complex(coef[idx]) if rev else complex(coef)
                if c == 0:
                    continue
                form = np.zeros(self.n)
                for j, t in zip(rev, idx):
                    form[j] = (0, 1, -1)[t]  # bin t holds the coefficient of e^{i·f·q} with f ≡ t (mod 3)
                slides = [j for j, b in zip(pri, subset) if b]
                for signs in itertools.product((1, -1), repeat=len(slides)):
                    z, f = c, form.copy()
                    for j, s in zip(slides, signs):
                        k = self.coordinates[j].gear_ratio
                        z *= s * k / 2j * np.exp(-1j * s * mids[j] / k)
                        f[j] += s / k
                    phasors.append((z, f))
        return merge_terms(phasors)


def load_urdf(path: str, accuracy: float = 1e-3, g: float = _G, drive_matrix=None, name: str | None = None) -> UrdfArm:
    """Read a URDF file into a :class:`UrdfArm` (one sentence naming the file on any failure).

    Examples
    --------
    >>> arm = load_urdf("models/arm_base_drives.urdf")
    >>> arm.n, [c.joint for c in arm.coordinates]
    (4, ['revolute', 'revolute', 'revolute', 'revolute'])
    """
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except FileNotFoundError:
        raise SchemaError(f"{path}: no such URDF file.") from None
    except (IsADirectoryError, UnicodeDecodeError):
        raise SchemaError(f"{path}: not a URDF text file.") from None
    except OSError as exc:
        raise SchemaError(f"{path}: cannot be read ({exc.strerror}).") from None
    try:
        model = pinocchio_model(text, g)
        return UrdfArm(model, name or os.path.basename(path), accuracy, drive_matrix)
    except (SchemaError, InvalidArm) as exc:
        raise type(exc)(f"{path}: {exc}") from None


# ----------------------------------------------------------------------------- TOML arms
def _f(v) -> str:
    return repr(float(v))


def _point_inertia(points: list[tuple[float, np.ndarray]]) -> tuple[float, np.ndarray, np.ndarray]:
    mass = sum(m for m, _ in points)
    if mass == 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    com = sum(m * p for m, p in points) / mass
    inertia = sum(m * (np.dot(p - com, p - com) * np.eye(3) - np.outer(p - com, p - com)) for m, p in points)
    return mass, com, inertia


def arm_to_urdf(arm: Arm, g: float = _G) -> str:
    """URDF of a planar :class:`~balance.model.arm.Arm`: plane x–z (x forward, z up), in-plane joints
    about ``−y`` (counter-clockwise seen with x to the right), turntables about ``z``; point
    weights become point masses ``G/g``."""
    u0 = np.array([0.0, 0.0, 1.0]) if arm.zero == "vertical" else np.array([1.0, 0.0, 0.0])
    nrm = np.array([-1.0, 0.0, 0.0]) if arm.zero == "vertical" else np.array([0.0, 0.0, 1.0])
    masses: dict[int, list] = {i: [] for i in range(arm.n)}
    for link, w, s, t in arm.masses():
        if w == 0:
            continue
        if arm.links[link].joint == "vertical":
            p = np.array([-t, 0.0, s])
        else:
            p = s * u0 + t * nrm
        masses[link].append((w / g, p))
    out = [f'<robot name="{arm.name}">', '  <link name="base"/>']
    parent, along = "base", np.zeros(3)
    for i, ln in enumerate(arm.links):
        m, com, inertia = _point_inertia(masses[i])
        ixx, iyy, izz = inertia[0, 0], inertia[1, 1], inertia[2, 2]
        ixy, ixz, iyz = inertia[0, 1], inertia[0, 2], inertia[1, 2]
        out.append(f'  <link name="link{i + 1}"><inertial><origin xyz="{_f(com[0])} {_f(com[1])} {_f(com[2])}"/>'
                   f'<mass value="{_f(m)}"/><inertia ixx="{_f(ixx)}" ixy="{_f(ixy)}" ixz="{_f(ixz)}" iyy="{_f(iyy)}" '
                   f'iyz="{_f(iyz)}" izz="{_f(izz)}"/></inertial></link>')
        lo, hi = ln.limits
        if ln.joint == "vertical":
            axis, kind, rpy = "0 0 1", "revolute", 0.0
        elif ln.joint == "revolute":
            axis, kind, rpy = "0 -1 0", "revolute", ln.offset
        else:
            axis, kind, rpy = " ".join(repr(float(v)) for v in u0), "prismatic", ln.offset
        out.append(f'  <joint name="joint{i + 1}" type="{kind}"><parent link="{parent}"/><child link="link{i + 1}"/>'
                   f'<origin xyz="{_f(along[0])} {_f(along[1])} {_f(along[2])}" rpy="0 {_f(-rpy)} 0"/><axis xyz="{axis}"/>'
                   f'<limit lower="{_f(lo)}" upper="{_f(hi)}" effort="1000" velocity="10"/></joint>')
        parent = f"link{i + 1}"
        along = ln.length * (np.array([0.0, 0.0, 1.0]) if ln.joint == "vertical" else u0)
    out.append("</robot>")
    return "\n".join(out)


@dataclass(frozen=True)
class PinocchioCheck(Row):
    """An arm's balance recomputed with Pinocchio's generalised gravity (the independent check).

    Attributes
    ----------
    samples, seed : int
        The random configurations (seeded) …
    worst_configurations : int
        … and the worst configurations of the arm's own check, evaluated too.
    pinocchio : str
        Pinocchio's version.
    max_gravity_force : float
        The scale of the relative residual (N·m or N).
    max_residual, relative_residual : float
        ``|Q_Pinocchio + Q_devices|`` at those configurations, and over the scale.
    max_residual_at_worst : float or None
        The same at the worst configurations only.
    gravity_agreement : float or None
        A TOML arm's own gravity forces against Pinocchio's, relative to the scale.
    """

    samples: int
    seed: int
    worst_configurations: int
    pinocchio: str
    max_gravity_force: float
    max_residual: float
    relative_residual: float
    max_residual_at_worst: float | None = None
    gravity_agreement: float | None = None

    row_keys = ("samples", "seed", "worst_configurations", "pinocchio", "max_gravity_force", "max_residual",
                "relative_residual", "max_residual_at_worst?", "gravity_agreement?")


def pinocchio_gravity(arm: ArmModel, g: float = _G) -> "UrdfArm":
    """The arm as Pinocchio sees it: itself for a URDF arm, its URDF (:func:`arm_to_urdf`) otherwise."""
    return arm if isinstance(arm, UrdfArm) else UrdfArm(pinocchio_model(arm_to_urdf(arm, g), g), arm.name)


@dataclass(frozen=True)
class DHLink:
    """One row of standard Denavit–Hartenberg parameters and the link it moves.

    The joint turns by ``θ`` about ``z`` of the previous frame; the link's frame follows by
    ``Rz(θ)·Tz(d)·Tx(a)·Rx(α)``. ``mass`` (kg) sits at ``com`` (m, in the link's DH frame).
    """

    name: str
    a: float
    d: float
    alpha: float
    mass: float
    com: tuple[float, float, float]
    limits: tuple[float, float] = (-2 * math.pi, 2 * math.pi)


def urdf_from_dh(name: str, links: list[DHLink], source: str = "") -> str:
    """URDF of a revolute serial arm given by standard DH parameters, point masses at the centres.

    Each URDF link's frame is the joint's (``z`` its axis, turned by ``θ``); the next joint sits at
    ``(a, 0, d)`` with ``rpy = (α, 0, 0)`` from it, and a fixed ``tool0`` frame closes the chain at the
    last DH frame (the flange). ``source`` goes into a comment.

    Examples
    --------
    >>> text = urdf_from_dh("two", [DHLink("l1", 0.5, 0.0, 0.0, 2.0, (-0.25, 0.0, 0.0)),
    ...                             DHLink("l2", 0.4, 0.0, 0.0, 1.0, (-0.2, 0.0, 0.0))])
    >>> validate_urdf(text); text.count("<joint ")
    3
    """
    out = ['<?xml version="1.0"?>']
    if source:
        out.append(f"<!-- {source} -->")
    out += [f'<robot name="{name}">', '  <link name="base_link"/>']
    parent, a, d, alpha = "base_link", 0.0, 0.0, 0.0
    for i, ln in enumerate(links, start=1):
        c = np.array([ln.a, 0.0, ln.d]) + _rot_x(ln.alpha) @ np.asarray(ln.com, dtype=float)
        out.append(f'  <joint name="joint{i}" type="revolute"><parent link="{parent}"/><child link="{ln.name}"/>'
                   f'<origin xyz="{_f(a)} 0 {_f(d)}" rpy="{_f(alpha)} 0 0"/><axis xyz="0 0 1"/>'
                   f'<limit lower="{_f(ln.limits[0])}" upper="{_f(ln.limits[1])}" effort="150" velocity="3.14"/></joint>')
        out.append(f'  <link name="{ln.name}"><inertial><origin xyz="{_f(c[0])} {_f(c[1])} {_f(c[2])}"/>'
                   f'<mass value="{_f(ln.mass)}"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>'
                   '</inertial></link>')
        parent, a, d, alpha = ln.name, ln.a, ln.d, ln.alpha
    out.append(f'  <joint name="flange" type="fixed"><parent link="{parent}"/><child link="tool0"/>'
               f'<origin xyz="{_f(a)} 0 {_f(d)}" rpy="{_f(alpha)} 0 0"/></joint>')
    out += ['  <link name="tool0"/>', "</robot>"]
    return "\n".join(out) + "\n"


def _rot_x(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def pinocchio_check(arm: ArmModel, terms, samples: int = 1000, seed: int = 0, g: float = _G, worst=(),
                    scale: float = 0.0) -> PinocchioCheck:
    """Residuals of the devices ``terms`` against Pinocchio's generalised gravity at ``samples`` random
    configurations and at the configurations ``worst`` (the worst ones the arm's own check found).

    The relative residual divides by ``scale`` (the largest gravity force over the workspace), or
    by the largest Pinocchio finds at these configurations when that is larger.

    Examples
    --------
    >>> from balance.model.arm import Link
    >>> arm = Arm((Link("l", "revolute", 1.0, 10.0, 0.5),))
    >>> pinocchio_check(arm, arm.harmonic_terms(), samples=20).relative_residual < 1e-14
    True
    """
    pa = pinocchio_gravity(arm, g)
    q = arm.sample(samples, seed)
    if len(worst):
        q = np.concatenate([q, np.asarray(worst, dtype=float).reshape(-1, arm.n)])
    qg = pa.gravity_forces(q)
    scale = max(float(np.max(np.abs(qg))), scale) or 1.0
    res = np.abs(qg - terms_forces(terms, q))
    return PinocchioCheck(
        samples=samples, seed=seed, worst_configurations=len(worst), pinocchio=_pin().__version__,
        max_gravity_force=scale, max_residual=float(np.max(res)), relative_residual=float(np.max(res)) / scale,
        max_residual_at_worst=float(np.max(res[samples:])) if len(worst) else None,
        gravity_agreement=None if pa is arm else float(np.max(np.abs(arm.gravity_forces(q) - qg))) / scale,
    )
