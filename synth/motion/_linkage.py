"""The dimensioned mechanism: a chain with its frame, inputs, one assembled pose, sliding directions,
gear ratios and tracer points; its reading from dicts, JSON and TOML files.

Every link is the rigid body through its joints' positions in the given pose.  A link's motion is
written as a rotation θ about the origin followed by a translation t, both measured from that pose:
a point p of the link (as placed in the pose) is at R(θ)·p + t.  The frame has θ = 0, t = 0.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from mechbase.files import read_text
from mechbase.pairs import finite_pair
from mechbase.toml import read_toml_text

from ..display import svg_of
from ..errors import BadPose, LockedMechanism, MalformedChain, MotionError, UnknownJoint, WrongInputs
from ..structure.chain import Chain, Mechanism, joint_links
from ..structure.joints import MESH, PRISMATIC, REVOLUTE

__all__ = ["Linkage", "read_linkage", "joint_name"]

#: two joints of one link closer than this (relative to the mechanism's size) are one point
COINCIDENT = 1e-9


def joint_name(chain: Chain, k: int) -> str:
    """The written form of joint ``k``: its links joined by its kind's sign.

    >>> joint_name(Chain.parse("0-1 1=2 2-3 3-0"), 2)
    '1=2'
    """
    kind = chain.kinds[k]
    return kind.symbol.join(map(str, chain.joints[k]))


def _joint_index(chain: Chain, key, what: str) -> int:
    """The joint a user names by its links (``"1-2"``, ``"2=1"``, ``[1, 2]``) or by its index."""
    try:
        return chain.joint_index(key, what)
    except UnknownJoint as exc:
        raise MotionError(str(exc)) from None


def _input_joint(chain: Chain, frame: int, key) -> tuple[int, int | None]:
    """An input named by its joint, or by the frame and the link it drives inside a multiple joint
    (``"0-3"`` in the joint ``0-1-3``): (joint, driven link or None for the joint's other link)."""
    try:
        return _joint_index(chain, key, "'inputs'"), None
    except MotionError:
        if not isinstance(key, str):
            raise
        links = set(joint_links(key) or ())
        holding = [k for k, j in enumerate(chain.joints) if links <= set(j)]
        if len(links) != 2 or frame not in links or len(holding) != 1:
            raise
        return holding[0], (links - {frame}).pop()


def _pair(value, what: str) -> tuple[float, float]:
    """Two finite numbers: ``what`` (a position, a direction, two radii) as a pose gives it."""
    return finite_pair(value, error=BadPose, malformed=f"{what} must be two numbers [x, y], not {value!r}",
                       not_finite=f"{what} is not finite: {value!r}")


@dataclass(frozen=True, eq=False)
class Linkage:
    """A dimensioned planar mechanism: chain, frame, input joints and one assembled pose.

    Parameters
    ----------
    mechanism : Mechanism
        The chain with its joint kinds and its frame.
    inputs : tuple of int
        Indices into ``mechanism.chain.joints`` of the W input joints, each a revolute or
        prismatic joint of the frame and one moving link.
    points : ndarray, shape (J, 2)
        Every joint's position in the pose (a multiple joint is one point; a prismatic joint's
        point is any point of its sliding line; a mesh's point is the pitch point).
    slides : dict int -> (float, float)
        Sliding direction of each prismatic joint in the pose (normalised to unit length).
    meshes : dict int -> float
        Speed ratio ρ of each gear mesh a~b relative to its carrier c (the link carrying both
        axes): θ_a − θ_c = ρ·(θ_b − θ_c).  Left out, it follows from the pose: ρ = −r_b/r_a
        with the pitch radii from the mesh point to each gear's axis (positive for a ring).
    tracers : dict str -> (int, (float, float))
        Named points fixed to links, as placed in the pose.
    note : str or None
        What was changed to make the pose move (set by :func:`linkage_from_pose` with
        ``nudge=True``), else None.
    driven : tuple of int, optional
        The link each input drives relative to the frame; needed only where an input is a multiple
        joint of the frame (a planetary train's central axis ``0-1-2-3``), else the joint's other link.

    Raises
    ------
    BadPose, WrongInputs, LockedMechanism
        One sentence saying what is wrong.

    Examples
    --------
    >>> from synth.structure.chain import Chain, Mechanism
    >>> m = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
    >>> four_bar = Linkage(m, (0,), np.array([[0, 0], [4, 0], [1, 0], [3, 2]]))  # joints 0-1 0-3 1-2 2-3
    >>> four_bar.dof, round(four_bar.lengths()[2], 6)
    (1, 2.828427)
    """

    mechanism: Mechanism
    inputs: tuple[int, ...]
    points: np.ndarray
    slides: dict = field(default_factory=dict)
    meshes: dict = field(default_factory=dict)
    tracers: dict = field(default_factory=dict)
    note: str | None = None
    driven: tuple[int, ...] | None = None

    def __post_init__(self):
        chain = self.chain
        if chain.h != 3:
            raise MotionError(f"a linkage moves in the plane (h = 3), not in motion space h = {chain.h}")
        try:
            points = np.array(self.points, dtype=float)
        except (TypeError, ValueError):
            raise BadPose("the joint positions must be numbers, one [x, y] per joint") from None
        if points.shape != (len(chain.joints), 2):
            raise BadPose(f"the pose needs one [x, y] per joint ({len(chain.joints)}), not an array of shape {points.shape}")
        bad = np.flatnonzero(~np.isfinite(points).all(axis=1))
        if bad.size:
            raise BadPose(f"joint {joint_name(chain, int(bad[0]))} has a position that is not finite: {points[bad[0]].tolist()}")
        points.flags.writeable = False
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "inputs", tuple(int(k) for k in self.inputs))
        self._set_driven()
        self._check_inputs()
        self._check_links()
        object.__setattr__(self, "slides", self._checked_slides())
        object.__setattr__(self, "meshes", self._checked_meshes())
        object.__setattr__(self, "tracers", self._checked_tracers())

    # ------------------------------------------------------------------ checks
    def _set_driven(self) -> None:
        chain, frame = self.chain, self.frame
        if len(self.inputs) != max(chain.dof, 0) and chain.dof > 0:
            return  # (_check_inputs says so)
        for k in self.inputs:
            if not 0 <= k < len(chain.joints):
                raise WrongInputs(f"input joint {k} is not a joint of the chain (0 … {len(chain.joints) - 1})")
        if self.driven is None:
            driven = []
            for k in self.inputs:
                j = chain.joints[k]
                if len(j) != 2 or frame not in j:
                    raise WrongInputs(f"input joint {joint_name(chain, k)} must join the frame (link {frame}) to one "
                                      "moving link, or name the link it drives")
                driven.append(j[1] if j[0] == frame else j[0])
            object.__setattr__(self, "driven", tuple(driven))
        else:
            driven = tuple(int(x) for x in self.driven)
            if len(driven) != len(self.inputs):
                raise WrongInputs(f"{len(driven)} driven links given for {len(self.inputs)} inputs")
            for k, x in zip(self.inputs, driven):
                if frame not in chain.joints[k] or x not in chain.joints[k] or x == frame:
                    raise WrongInputs(f"input joint {joint_name(chain, k)} does not join the frame (link {frame}) "
                                      f"to link {x}")
            object.__setattr__(self, "driven", driven)

    def _check_inputs(self) -> None:
        chain = self.chain
        w = chain.dof
        if w <= 0:
            raise LockedMechanism(f"the chain {chain.compact()} is rigid (W = {w}): nothing can move it")
        if len(self.inputs) != w:
            raise WrongInputs(f"this mechanism has W = {w} and needs {w} input joint{'s' * (w > 1)} on the frame, "
                              f"not {len(self.inputs)}")
        if len(set(zip(self.inputs, self.driven))) != len(self.inputs):
            raise WrongInputs("an input joint is named twice")
        for k in self.inputs:
            if not 0 <= k < len(chain.joints):
                raise WrongInputs(f"input joint {k} is not a joint of the chain (0 … {len(chain.joints) - 1})")
            name = joint_name(chain, k)
            if self.kind(k) == MESH:
                raise WrongInputs(f"input joint {name} is a gear mesh: drive a revolute or prismatic joint of the frame")
        driven = [self.input_link(i) for i in range(w)]
        if len(set(driven)) != len(driven):
            raise WrongInputs(f"two inputs drive link {driven[0]}: each input must drive its own link")

    def _check_links(self) -> None:
        """A link whose pins are all at one point has no length (pins of different links on one
        axis, as a planetary train's shafts on its frame, are allowed where the link has others)."""
        scale = self.scale
        for link in range(self.chain.links):
            pins = [k for k in self.joints_of(link) if self.kind(k) == REVOLUTE]
            if len(pins) >= 2 and all(np.hypot(*(self.points[k] - self.points[pins[0]])) <= COINCIDENT * scale
                                      for k in pins[1:]):
                raise BadPose(f"joints {joint_name(self.chain, pins[0])} and {joint_name(self.chain, pins[1])} of link "
                              f"{link} are at the same point: a link's pins must be apart (a zero-length link)")

    def _checked_slides(self) -> dict:
        chain, out = self.chain, {}
        given = dict(self.slides)
        for k in given:
            if not (isinstance(k, int) and 0 <= k < len(chain.joints) and self.kind(k) == PRISMATIC):
                raise BadPose(f"a sliding direction is given for joint {k!r}, which is not a prismatic joint")
        for k in range(len(chain.joints)):
            if self.kind(k) != PRISMATIC:
                continue
            if k not in given:
                raise BadPose(f"prismatic joint {joint_name(chain, k)} needs its sliding direction")
            x, y = _pair(given[k], f"the sliding direction of joint {joint_name(chain, k)}")
            norm = math.hypot(x, y)
            if norm == 0:
                raise BadPose(f"the sliding direction of joint {joint_name(chain, k)} has zero length")
            out[k] = (x / norm, y / norm)
        return out

    def carrier(self, k: int) -> int:
        """The link that carries the axes of both gears of mesh ``k`` (revolute joints to each).

        The frame is preferred where several links do."""
        a, b = self.chain.joints[k]
        def pinned(x):
            return {y for m in self.joints_of(x) if self.kind(m) == REVOLUTE for y in self.chain.joints[m] if y != x}
        common = sorted(pinned(a) & pinned(b), key=lambda c: (c != self.frame, c))
        if not common:
            raise BadPose(f"gear mesh {joint_name(self.chain, k)} needs a link carrying both gears' axes (a carrier)")
        return common[0]

    def axis(self, gear: int, carrier: int) -> int:
        """The revolute joint of ``gear`` and ``carrier`` (the gear's axis)."""
        return next(m for m in self.joints_of(gear) if self.kind(m) == REVOLUTE and carrier in self.chain.joints[m])

    def _checked_meshes(self) -> dict:
        chain, out = self.chain, {}
        given = dict(self.meshes)
        for k in given:
            if not (isinstance(k, int) and 0 <= k < len(chain.joints) and self.kind(k) == MESH):
                raise BadPose(f"a gear ratio is given for joint {k!r}, which is not a gear mesh")
        for k in range(len(chain.joints)):
            if self.kind(k) != MESH:
                continue
            name = joint_name(chain, k)
            c = self.carrier(k)
            if k in given:
                value = given[k]
                if isinstance(value, (list, tuple)):
                    ra, rb = _pair(value, f"the pitch radii of mesh {name}")
                    if ra == 0 or rb == 0:
                        raise BadPose(f"a pitch radius of mesh {name} is zero")
                    value = -rb / ra
                try:
                    ratio = float(value)
                except (TypeError, ValueError):
                    raise BadPose(f"the ratio of mesh {name} must be a number or a pair of pitch radii, not {value!r}") from None
                if not math.isfinite(ratio) or ratio == 0:
                    raise BadPose(f"the ratio of mesh {name} must be finite and not zero, not {value!r}")
            else:
                a, b = chain.joints[k]
                pa = self.points[k] - self.points[self.axis(a, c)]
                pb = self.points[k] - self.points[self.axis(b, c)]
                ra, rb = math.hypot(*pa), math.hypot(*pb)
                if ra <= COINCIDENT * self.scale or rb <= COINCIDENT * self.scale:
                    raise BadPose(f"the pitch point of mesh {name} is on a gear's axis: give the ratio or move the point")
                ratio = (rb / ra) * (1.0 if float(pa @ pb) > 0 else -1.0)
            out[k] = ratio
        return out

    def _checked_tracers(self) -> dict:
        out = {}
        for name, value in dict(self.tracers).items():
            try:
                link, at = value
                link = int(link)
            except (TypeError, ValueError):
                raise BadPose(f"tracer {name!r} must be (link, [x, y]), not {value!r}") from None
            if not 0 <= link < self.chain.links:
                raise BadPose(f"tracer {name!r} is on link {link}, which is not a link of the chain")
            out[str(name)] = (link, _pair(at, f"the position of tracer {name!r}"))
        return out

    # ---------------------------------------------------------------- views
    @property
    def chain(self) -> Chain:
        return self.mechanism.chain

    @property
    def frame(self) -> int:
        return self.mechanism.frame

    @property
    def dof(self) -> int:
        """W: the number of inputs."""
        return len(self.inputs)

    def kind(self, k: int) -> str:
        """Kind of joint ``k``: revolute, prismatic or mesh."""
        return self.chain.kinds[k]

    def joints_of(self, link: int) -> tuple[int, ...]:
        """Indices of the joints on ``link``."""
        return self._joints_by_link[link]

    @cached_property
    def _joints_by_link(self) -> tuple[tuple[int, ...], ...]:
        out = [[] for _ in range(self.chain.links)]
        for k, j in enumerate(self.chain.joints):
            for x in j:
                out[x].append(k)
        return tuple(map(tuple, out))

    @cached_property
    def scale(self) -> float:
        """The mechanism's size: the largest side of the box around its joints (1 if they are all one point)."""
        span = float(np.ptp(self.points, axis=0).max()) if len(self.points) else 0.0
        return span if span > 0 else 1.0

    def input_link(self, i: int) -> int:
        """The moving link driven by input ``i``."""
        return self.driven[i]

    def input_reference(self, i: int) -> int | None:
        """For a revolute input, the joint of the driven link whose direction from the input joint is
        the input angle; None for a prismatic input (its input is the displacement from the pose)."""
        k = self.inputs[i]
        if self.kind(k) != REVOLUTE:
            return None
        link = self.input_link(i)
        others = [m for m in self.joints_of(link) if m != k]
        far = [m for m in others if np.hypot(*(self.points[m] - self.points[k])) > COINCIDENT * self.scale]
        return (far or others)[0]

    @cached_property
    def pose_inputs(self) -> np.ndarray:
        """The input values of the pose: a revolute input's angle (rad, of the line from the input
        joint to :meth:`input_reference`, from the x axis), a prismatic input's displacement (0)."""
        out = []
        for i, k in enumerate(self.inputs):
            ref = self.input_reference(i)
            if ref is None:
                out.append(0.0)
            else:
                d = self.points[ref] - self.points[k]
                out.append(math.atan2(d[1], d[0]))
        return np.array(out)

    def lengths(self) -> dict[int, float]:
        """Length of each link with exactly two revolute joints (the distance between its pins)."""
        out = {}
        for link in range(self.chain.links):
            pins = [k for k in self.joints_of(link) if self.kind(k) == REVOLUTE]
            if len(pins) == 2:
                out[link] = float(np.hypot(*(self.points[pins[0]] - self.points[pins[1]])))
        return out

    # ------------------------------------------------------------------ I/O
    def to_dict(self) -> dict:
        """A JSON-able object, read back by :meth:`from_dict`.

        >>> from synth.structure.chain import Chain, Mechanism
        >>> lk = Linkage(Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), 0), (0,), [[0, 0], [4, 0], [1, 0], [3, 2]])
        >>> Linkage.from_dict(lk.to_dict()).to_dict() == lk.to_dict()
        True
        """
        chain = self.chain
        d = {
            "chain": chain.compact(),
            "frame": self.frame,
            "inputs": [joint_name(chain, k) if len(chain.joints[k]) == 2 else f"{self.frame}-{x}"
                       for k, x in zip(self.inputs, self.driven)],
            "points": {joint_name(chain, k): [float(x), float(y)] for k, (x, y) in enumerate(self.points)},
        }
        if self.slides:
            d["slides"] = {joint_name(chain, k): list(v) for k, v in self.slides.items()}
        if self.meshes:
            d["meshes"] = {joint_name(chain, k): v for k, v in self.meshes.items()}
        if self.tracers:
            d["tracers"] = {name: {"link": link, "at": list(at)} for name, (link, at) in self.tracers.items()}
        if self.note:
            d["note"] = self.note
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "Linkage":
        """Read the object written by :meth:`to_dict` (a scene's ``[linkage]`` table).

        ``chain`` is a joint list (``"0-1 1=2 2-3 3-0"``) or a chain object; ``points`` maps each
        joint, written by its links, to [x, y]; ``inputs`` lists the input joints by their links;
        ``slides`` and ``meshes`` map joints to a direction [x, y] and to a ratio or a pair of
        pitch radii (negative for a ring gear); ``tracers`` maps names to ``{link, at}``.

        >>> lk = Linkage.from_dict({"chain": "0-1 1-2 2-3 3-0", "frame": 0, "inputs": ["0-1"],
        ...     "points": {"0-1": [0, 0], "1-2": [1, 0], "2-3": [3, 2], "0-3": [4, 0]},
        ...     "tracers": {"P": {"link": 2, "at": [2, 3]}}})
        >>> lk.inputs, lk.tracers
        ((0,), {'P': (2, (2.0, 3.0))})
        """
        if not isinstance(d, dict):
            raise MotionError("a linkage must be an object (a table) with 'chain', 'frame', 'inputs' and 'points'")
        unknown = sorted(set(d) - {"chain", "frame", "inputs", "points", "slides", "meshes", "tracers", "note"})
        if unknown:
            raise MotionError(f"a linkage has no entry {unknown[0]!r} (it has chain, frame, inputs, points, slides, "
                              "meshes, tracers)")
        for key in ("chain", "frame", "inputs", "points"):
            if key not in d:
                raise MotionError(f"a linkage needs {key!r}")
        try:
            raw = d["chain"]
            chain = Chain.parse(raw) if isinstance(raw, str) else Chain.from_dict(
                raw if isinstance(raw, dict) else {"joints": raw})
        except MalformedChain as exc:
            raise MotionError(f"the linkage's chain cannot be read: {exc}") from None
        frame = d["frame"]
        if isinstance(frame, bool) or not isinstance(frame, int) or not 0 <= frame < chain.links:
            raise MotionError(f"'frame' must be a link number 0 … {chain.links - 1}, not {frame!r}")
        inputs = d["inputs"]
        if isinstance(inputs, (str, int)):
            inputs = [inputs]
        if not isinstance(inputs, list):
            raise MotionError("'inputs' must be a list of joints, e.g. ['0-1']")
        picked, driven = [], []
        for key in inputs:
            k, link = _input_joint(chain, frame, key)
            picked.append(k)
            driven.append(link)
        inputs = tuple(picked)
        points = d["points"]
        if not isinstance(points, dict):
            raise MotionError("'points' must map each joint to its position, e.g. {'0-1': [0, 0]}")
        table = {}
        for key, value in points.items():
            k = _joint_index(chain, key, "'points'")
            if k in table:
                raise MotionError(f"'points' gives joint {joint_name(chain, k)} twice")
            table[k] = _pair(value, f"the position of joint {key}")
        missing = [joint_name(chain, k) for k in range(len(chain.joints)) if k not in table]
        if missing:
            raise BadPose(f"joint{'s' * (len(missing) > 1)} {', '.join(missing)} {'have' if len(missing) > 1 else 'has'} "
                          "no position in 'points'")

        def keyed(name):
            value = d.get(name, {})
            if not isinstance(value, dict):
                raise MotionError(f"'{name}' must map joints to values")
            return {_joint_index(chain, key, f"'{name}'"): v for key, v in value.items()}

        tracers = d.get("tracers", {})
        if not isinstance(tracers, dict) or not all(isinstance(v, dict) and set(v) == {"link", "at"}
                                                   for v in tracers.values()):
            raise MotionError("'tracers' must map each name to {link = L, at = [x, y]}")
        mechanism = Mechanism(chain, frame)
        return cls(mechanism, inputs, np.array([table[k] for k in range(len(chain.joints))]), keyed("slides"),
                   keyed("meshes"), {name: (v["link"], v["at"]) for name, v in tracers.items()}, d.get("note"),
                   None if None in driven else tuple(driven))

    def _repr_svg_(self) -> str:
        """The drawing Jupyter shows: the linkage in its pose (the drawing registered for it)."""
        return svg_of(self)

    def to_json(self) -> str:
        return json.dumps(self.to_dict())


def read_linkage(path: str | Path, row: int | None = None) -> Linkage:
    """Read a linkage from a ``.toml`` or ``.json`` file: the object of :meth:`Linkage.from_dict`,
    at the top level or under a ``linkage`` key (a scene's ``[linkage]`` table); or row ``row`` (1-based,
    the table's rank) of the rows of an atlas search (``dimension --db … --format json`` or ``jsonl``),
    each of which carries its linkage.

    Raises
    ------
    MotionError
        One sentence: the file cannot be read, its content is not a linkage, it holds several rows and
        ``row`` is not given (or not one of them), or ``row`` is given for a file of one linkage.

    >>> import tempfile, os
    >>> with tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False) as f:
    ...     _ = f.write('[linkage]\\nchain = "0-1 1-2 2-3 3-0"\\nframe = 0\\ninputs = ["0-1"]\\n'
    ...                 '[linkage.points]\\n"0-1" = [0, 0]\\n"1-2" = [1, 0]\\n"2-3" = [3, 2]\\n"0-3" = [4, 0]\\n')
    >>> read_linkage(f.name).dof
    1
    >>> os.unlink(f.name)
    """
    path = Path(path)
    data = _rows_or_linkage(path)
    if isinstance(data, list) and data and all(isinstance(one, dict) for one in data):
        data = _row_of(data, row, path.name)
    elif row is not None:
        raise MotionError(f"--row picks one of the rows of an atlas search ('dimension --db … --format json'), and "
                          f"{path.name} holds one linkage: give it without --row")
    if isinstance(data, dict) and "linkage" in data:
        data = data["linkage"]
    elif isinstance(data, dict) and "error_max" in data and not isinstance(data.get("points"), dict):
        # one row of 'dimension' without its linkage (a jsonl row of one mechanism carried none before 30 Nov 2026)
        raise MotionError(f"{path.name} is a row of 'mechsynth dimension' without its linkage: its '--format json' or "
                          "'jsonl' gives each answer with its linkage, '--save FILE' the best one's")
    elif isinstance(data, dict) and not {"chain", "frame", "inputs", "points"} & set(data):  # an arm, a grid, …
        raise MotionError(f"{path.name} holds no linkage: a linkage file has a [linkage] table, or chain, frame, "
                          f"inputs and points at its top; this one holds {', '.join(data) or 'nothing'}")
    try:
        return Linkage.from_dict(data)
    except MotionError as exc:  # the same sentence, naming the file
        raise type(exc)(f"{path.name}: {exc.args[0]}") from None


def _rows_or_linkage(path: Path):
    """The parsed content of a linkage file: a TOML or JSON document, or the rows of a ``.jsonl`` file."""
    suffix = path.suffix.lower()
    if suffix == ".csv":
        raise MotionError(f"{path.name} is a csv file, whose rows carry no linkage: the rows of 'dimension … --format "
                          "json' or 'jsonl' carry each linkage (--row K picks one), a linkage file is .toml or .json")
    if suffix not in (".toml", ".json", ".jsonl"):
        raise MotionError(f"a linkage file is .toml or .json (or the .json/.jsonl rows of an atlas search), not "
                          f"{path.name!r}")
    text = read_text(path, error=MotionError, what="linkage file")
    if suffix == ".toml":
        return read_toml_text(text, error=MotionError, source=path.name)
    lines = [(n, line) for n, line in enumerate(text.splitlines(), 1) if line.strip()] if suffix == ".jsonl" \
        else [(1, text)]
    parsed = []
    for n, line in lines:
        try:
            parsed.append(json.loads(line))
        except json.JSONDecodeError as exc:
            raise MotionError(f"{path.name}: not valid JSON ({exc.msg} at line {exc.lineno + n - 1}).") from None
    return parsed if suffix == ".jsonl" else parsed[0]


def _row_of(rows: list[dict], row: int | None, name: str) -> dict:
    """Row ``row`` (1-based, as the table ranks them) of an atlas search's rows, refused in one sentence
    where it is not given for several rows or is not one of them."""
    if not all("linkage" in one or "error_max" in one for one in rows):  # another command's rows
        raise MotionError(f"{name} holds {len(rows)} row{'s' * (len(rows) != 1)} of another kind, not a linkage: a "
                          "linkage file has a [linkage] table, or chain, frame, inputs and points at its top")
    if row is None and len(rows) > 1:
        raise MotionError(f"{name} holds {len(rows)} rows, not one linkage: pick one with --row K (1 to {len(rows)}, "
                          "as the table ranks them)" if all("linkage" in one for one in rows) else
                          f"{name} holds {len(rows)} rows of 'mechsynth dimension' without their linkages: its "
                          "'--format json' or 'jsonl' gives each row with its linkage")
    if row is not None and not 1 <= row <= len(rows):
        raise MotionError(f"--row {row} is not a row of {name}: it holds row{'s 1 to ' if len(rows) > 1 else ' '}"
                          f"{len(rows)}")
    return rows[0 if row is None else row - 1]

