"""What a mechanism must do: a path (with or without timing), a function (input–output pairs) or
a motion (poses of a body); read from CSV or JSON and checked once, here.

Angles are radians in Python; a file says its unit in its column's name (``input`` in radians or
length, ``input_deg`` in degrees).
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from mechbase.files import read_text

from ..errors import BadTarget

__all__ = ["PathTarget", "FunctionTarget", "MotionTarget", "read_target"]

#: what a function's input or output measures: an angle (rad) or a slider's displacement (a length)
MEASURES = ("angle", "displacement")
#: two target points closer than this × the target's size are one point (a duplicate)
DUPLICATE = 1e-9


def _array(values, columns: int | None, what: str) -> np.ndarray:
    """A float array of rows (``columns`` each, or 1-D when None), finite, refused in one sentence."""
    try:
        out = np.array(values, dtype=float)
    except (TypeError, ValueError):
        raise BadTarget(f"the {what} must be numbers") from None
    if out.size == 0:
        raise BadTarget(f"the target has no {what}")
    if out.ndim != (2 if columns else 1) or (columns and out.shape[1] != columns):
        raise BadTarget(f"the {what} must be {'rows of ' + str(columns) + ' numbers' if columns else 'a list of numbers'}, "
                        f"not an array of shape {out.shape}")
    bad = np.flatnonzero(~np.isfinite(out.reshape(len(out), -1)).all(axis=1))
    if bad.size:
        raise BadTarget(f"the {what} are not all finite numbers: row {int(bad[0]) + 1} is {out[bad[0]].tolist()}")
    out.flags.writeable = False
    return out


def _size(points: np.ndarray) -> float:
    """The diagonal of the points' bounding box."""
    return float(np.hypot(*np.ptp(points, axis=0)))


def _no_duplicates(rows: np.ndarray, scale: float, what: str) -> None:
    if len(rows) < 2:
        raise BadTarget(f"the target has {len(rows)} {what[:-1]}: give at least 2")
    gap = np.abs(rows[:, None, :] - rows[None, :, :]).max(axis=2)
    gap[np.diag_indices(len(rows))] = np.inf
    i, j = np.unravel_index(int(np.argmin(gap)), gap.shape)
    if gap[i, j] <= DUPLICATE * max(scale, 1e-300):
        i, j = sorted((int(i), int(j)))
        raise BadTarget(f"{what} {i + 1} and {j + 1} are the same ({rows[i].tolist()}): give each once (one that "
                        f"counts twice: give it a weight of 2)")


def _weights(values, count: int, what: str) -> np.ndarray | None:
    """The per-point weights of a target (None: every point counts once), each finite and ≥ 0, not all 0."""
    if values is None:
        return None
    weights = _array(values, None, "weights")
    if len(weights) != count:
        raise BadTarget(f"the target gives {len(weights)} weights for {count} {what}: give one per row")
    bad = np.flatnonzero(weights < 0)
    if bad.size:
        raise BadTarget(f"a weight must be 0 or more: row {int(bad[0]) + 1} has {weights[bad[0]]:g}")
    if not weights.any():
        raise BadTarget("the weights are all 0: no point would count")
    return weights


def _monotonic(values: np.ndarray, what: str) -> None:
    sign = np.sign(np.diff(values))
    wrong = np.flatnonzero(sign != (sign[0] or 1.0))
    if wrong.size:
        k = int(wrong[0])
        raise BadTarget(f"the {what} must increase (or decrease) from row to row, but rows {k + 1} and {k + 2} "
                        f"go {values[k]:.9g} → {values[k + 1]:.9g}")


@dataclass(frozen=True, eq=False)
class PathTarget:
    """Points a tracer point must pass, in order, optionally at prescribed input values (timing).

    Parameters
    ----------
    points : array (N, 2)
        The points, in the order the tracer passes them.
    inputs : array (N,), optional
        Prescribed timing: the input's value at each point (rad for a revolute input, length for a
        prismatic one), strictly increasing or decreasing.  Only differences count: the input's
        value at the first point is an unknown of the synthesis (the crank's angle there is free).
        None: no timing — the inputs are unknowns too, kept in the points' order.
    weights : array (N,), optional
        How much each point counts: the synthesis minimises the sum of weight × squared distance (a
        point of weight 2 counts as the point given twice; 0 ignores it).  Finite, ≥ 0, not all 0;
        None: 1 each.

    Examples
    --------
    >>> t = PathTarget([[0, 0], [1, 0], [1, 1]], inputs=[0.0, 0.5, 1.0])
    >>> t.size, t.kind
    (1.4142135623730951, 'path')
    >>> PathTarget([[0, 0], [1, 0], [1, 1]], weights=[2, 1, 1]).weights.tolist()
    [2.0, 1.0, 1.0]
    """

    points: np.ndarray
    inputs: np.ndarray | None = None
    weights: np.ndarray | None = None
    kind = "path"

    def __post_init__(self):
        points = _array(self.points, 2, "points")
        _no_duplicates(points, _size(points), "points")
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "weights", _weights(self.weights, len(points), "points"))
        if self.inputs is not None:
            inputs = _array(self.inputs, None, "input values")
            if len(inputs) != len(points):
                raise BadTarget(f"the timing gives {len(inputs)} input values for {len(points)} points")
            _monotonic(inputs, "input values")
            object.__setattr__(self, "inputs", inputs)

    @property
    def size(self) -> float:
        """The target's size: the diagonal of its points' bounding box (errors are relative to it)."""
        return _size(self.points)

    def __len__(self) -> int:
        return len(self.points)


@dataclass(frozen=True, eq=False)
class FunctionTarget:
    """Input–output pairs a mechanism must generate: the output's angle or displacement at each
    input angle or displacement.

    Angles against angles (two links pivoted on the frame): both (rad) are measured from the frame
    line, the line from the input's pivot to the output's pivot, anticlockwise (Freudenstein's
    convention).  A displacement is a slider's, on a prismatic pair with the frame, against the
    angle of a link pivoted there: it is the position of the slider's pin (its revolute joint) along
    the slider's line, in the direction the line is drawn, measured from the foot of the pivot on
    the line (the crank's pivot of a slider-crank: s = r cos θ + √(l² − (r sin θ − e)²)); the angle
    is measured from that direction, anticlockwise.  Only one side may be a displacement.  The
    output link is a link jointed to the frame (``output_link``; by default the only other one).

    Parameters
    ----------
    inputs, outputs : array (N,)
        Input values (strictly monotonic) and the output values wanted there.
    output_link : int, optional
        The output link (a rocker, crank or slider on the frame).
    weights : array (N,), optional
        How much each pair counts (weight × squared error), as a path's points' weights.
    input_is, output_is : "angle" or "displacement"
        What each column measures (rad, or the target's length unit); at most one a displacement.
    origin : "pivot" or "free"
        Where a displacement is measured from: the pivot's foot on the slider's line, or a point of the
        line the synthesis chooses (the pivot's place along the line an unknown, so that the target's
        own zero — a first position, a machine's datum — is taken as it is).

    Examples
    --------
    >>> FunctionTarget([0.5, 1.0, 1.5], [1.2, 1.4, 1.7]).size
    1.0
    >>> FunctionTarget([0.5, 1.0, 1.5], [3.25, 2.75, 2.5], output_is="displacement").size   # the displacements' range
    0.75
    """

    inputs: np.ndarray
    outputs: np.ndarray
    output_link: int | None = None
    weights: np.ndarray | None = None
    input_is: str = "angle"
    output_is: str = "angle"
    origin: str = "pivot"
    kind = "function"

    def __post_init__(self):
        inputs = _array(self.inputs, None, "input values")
        outputs = _array(self.outputs, None, "output values")
        if len(inputs) != len(outputs):
            raise BadTarget(f"the function gives {len(inputs)} input values and {len(outputs)} output values")
        if len(inputs) < 2:
            raise BadTarget(f"the target has {len(inputs)} pair: give at least 2")
        _monotonic(inputs, "input values")
        object.__setattr__(self, "inputs", inputs)
        object.__setattr__(self, "outputs", outputs)
        object.__setattr__(self, "weights", _weights(self.weights, len(inputs), "pairs"))
        for side in ("input_is", "output_is"):
            if getattr(self, side) not in MEASURES:
                raise BadTarget(f"{side} is 'angle' or 'displacement', not {getattr(self, side)!r}")
        if self.input_is == self.output_is == "displacement":
            raise BadTarget("function generation relates two angles or an angle and a displacement: two "
                            "displacements are not offered")
        if self.origin not in ("pivot", "free"):
            raise BadTarget(f"a displacement's origin is 'pivot' or 'free', not {self.origin!r}")
        if self.origin == "free" and self.input_is == self.output_is:
            raise BadTarget("a free origin is a displacement's: this function relates two angles")

    @property
    def size(self) -> float:
        """What the errors are relative to: 1 for angles (rad); the outputs' range for displacements
        (their largest absolute value where they are all equal)."""
        if self.output_is == "angle":
            return 1.0
        return float(np.ptp(self.outputs)) or float(np.abs(self.outputs).max()) or 1.0

    def __len__(self) -> int:
        return len(self.inputs)


@dataclass(frozen=True, eq=False)
class MotionTarget:
    """Poses a body (the tracer's link) must take: its tracer point's position and its angle.

    Only differences of the angles count (the body's reference line is free), so the first pose's
    angle is the body's angle in the returned pose.  No timing: the inputs are unknowns.

    Parameters
    ----------
    poses : array (N, 3)
        x, y and angle (rad) of the body at each pose, in the order it passes them.
    weights : array (N,), optional
        How much each pose counts (weight × its squared position and angle errors), as a path's
        points' weights.

    Examples
    --------
    >>> MotionTarget([[0, 0, 0], [1, 0, 0.2], [1, 1, 0.5]]).size
    1.4142135623730951
    """

    poses: np.ndarray
    weights: np.ndarray | None = None
    kind = "motion"

    def __post_init__(self):
        poses = _array(self.poses, 3, "poses")
        _no_duplicates(poses, _size(poses[:, :2]) or 1.0, "poses")
        object.__setattr__(self, "poses", poses)
        object.__setattr__(self, "weights", _weights(self.weights, len(poses), "poses"))

    @property
    def points(self) -> np.ndarray:
        return self.poses[:, :2]

    @property
    def size(self) -> float:
        """The diagonal of the bounding box of the poses' points (1 if they are all one point)."""
        return _size(self.points) or 1.0

    def __len__(self) -> int:
        return len(self.poses)


#: the columns of each kind of target file (a ``_deg`` column is in degrees)
COLUMNS = {
    ("x", "y"): "path", ("x", "y", "input"): "path", ("x", "y", "input_deg"): "path",
    ("input", "output"): "function", ("input_deg", "output_deg"): "function",
    ("input", "output_displacement"): "function", ("input_deg", "output_displacement"): "function",
    ("input_displacement", "output"): "function", ("input_displacement", "output_deg"): "function",
    ("x", "y", "angle"): "motion", ("x", "y", "angle_deg"): "motion",
}


def _rows(path: Path) -> tuple[list[str], list[list]]:
    """The header and the rows of a CSV or JSON target file."""
    text = read_text(path, error=BadTarget, what="target file")
    if not text.strip():
        raise BadTarget(f"the target file {path.name} is empty")
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise BadTarget(f"{path.name}: not valid JSON ({exc.msg} at line {exc.lineno})") from None
        if not (isinstance(data, list) and data and all(isinstance(r, dict) for r in data)):
            raise BadTarget(f"{path.name} must hold a list of rows, each an object such as {{\"x\": 0, \"y\": 1}}")
        header = list(data[0])
        if any(list(r) != header for r in data):
            raise BadTarget(f"{path.name}: every row must have the same keys as the first ({', '.join(header)})")
        return header, [[r[c] for c in header] for r in data]
    lines = [row for row in csv.reader(io.StringIO(text)) if row and any(c.strip() for c in row)]
    header = [c.strip().lower() for c in lines[0]]
    body = lines[1:]
    for n, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise BadTarget(f"{path.name} line {n} has {len(row)} values for the {len(header)} columns "
                            f"{', '.join(header)}")
    return header, body


def read_target(path: str | Path, *, output_link: int | None = None, origin: str = "pivot"):
    """Read a target from a CSV file (a header row, then one row per point) or a JSON list of rows.

    The columns say the kind: ``x,y`` a path without timing; ``x,y,input`` (or ``input_deg``) a
    path with timing; ``input,output`` (or ``input_deg,output_deg``) a function of angles,
    ``input_deg,output_displacement`` a slider's displacement against an angle and
    ``input_displacement,output_deg`` an angle against a slider's (each angle also in rad without
    ``_deg``); ``x,y,angle`` (or ``angle_deg``) a motion.  ``origin`` is a slider function's (see
    :class:`FunctionTarget`).  Any of them may end with a ``weight`` column: how much each row
    counts (the target's ``weights``).

    Raises
    ------
    BadTarget
        One sentence: no such file, an empty one, unknown columns, a value that is not a finite
        number, duplicate points, a timing that is not monotonic, a negative weight or all weights 0.

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "t.csv")
    >>> _ = open(path, "w").write("x,y,input_deg\\n0,0,0\\n1,0,30\\n1,1,60\\n")
    >>> read_target(path).inputs.round(6).tolist()
    [0.0, 0.523599, 1.047198]
    """
    path = Path(path)
    if path.suffix.lower() not in (".csv", ".json"):
        raise BadTarget(f"a target file is .csv or .json, not {path.name!r}")
    header, body = _rows(path)
    weighted = header[-1:] == ["weight"]
    kind = COLUMNS.get(tuple(header[:-1] if weighted else header))
    if kind is None:
        raise BadTarget(f"{path.name} has the columns {', '.join(header) or 'none'}; a target's are x,y (a path), "
                        "x,y,input (timed path), input,output (a function; input_displacement or "
                        "output_displacement for a slider's side) or x,y,angle (a motion), an angle column named "
                        "*_deg in degrees, and last an optional weight column")
    if not body:
        raise BadTarget(f"the target file {path.name} has a header but no rows")
    try:
        values = np.array([[float(v) for v in row] for row in body])
    except (TypeError, ValueError):
        bad = next(v for row in body for v in row if not _is_number(v))
        raise BadTarget(f"{path.name}: {bad!r} is not a number") from None
    if "input_deg" in header:  # checked as written, so that a refusal quotes the file's degrees
        _monotonic(values[:, header.index("input_deg")], "input_deg values")
    for c, name in enumerate(header):
        if name.endswith("_deg"):
            values[:, c] = np.radians(values[:, c])
    weights = values[:, -1] if weighted else None
    values = values[:, :-1] if weighted else values
    if kind == "path":
        return PathTarget(values[:, :2], values[:, 2] if values.shape[1] == 3 else None, weights)
    if kind == "function":
        measures = ["displacement" if name.endswith("_displacement") else "angle" for name in header[:2]]
        return FunctionTarget(values[:, 0], values[:, 1], output_link, weights, *measures, origin)
    return MotionTarget(values, weights)


def _is_number(v) -> bool:
    try:
        float(v)
        return True
    except (TypeError, ValueError):
        return False
