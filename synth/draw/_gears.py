"""Functional schematics of gear trains, as transmission designers draw them (matplotlib, Agg).

Shafts are horizontal lines: the main axis (the frame's, or the one with most links) at the
bottom, each other axis above the axis of the carrier that holds it.  Links on one axis are
concentric shafts, drawn a little apart.  A gear is a vertical bar on its shaft reaching to the
pitch point of its mesh; an internal gear (a ring) reaches past its pinion and turns back, a
bracket open towards the axis; a carrier is an arm from its own shaft up to the axis it holds;
the frame is hatched.  Each link has its own colour and its number at its shaft's left end (the numbers of
concentric shafts a text line apart).
With tooth numbers, bar heights follow the pitch radii.

Example
-------
>>> import tempfile, os
>>> from synth.gears import GearTrain
>>> out = os.path.join(tempfile.mkdtemp(), "simple.svg")
>>> draw_train(GearTrain.parse("0-1-2 2-3 0~3i 1~3", frame=0), out)
>>> os.path.getsize(out) > 0
True
"""

from __future__ import annotations

from pathlib import Path

from mechbase import save_figure

from ..errors import InvalidOption
from ..gears.train import GearTrain

__all__ = ["draw_train", "draw_train_sheet", "sheet_figure", "schematic", "svg_text"]

_FORMATS = (".svg", ".png", ".pdf")
_GAP = 0.16  # between concentric shafts
_LINE = 1.35  # a link number's line, in its font's size (the digits' box and a little room)
_PLATE = {"facecolor": "white", "edgecolor": "none", "pad": 0.6, "alpha": 0.85}  # a tooth number over the lines


def _axis_heights(train: GearTrain) -> dict[int, float]:
    """Height of each axis: the main axis at 0, an axis held by a carrier one step above it."""
    axes = train.axes
    if not axes:
        return {}
    main = max(range(len(axes)), key=lambda k: (train.frame is not None and train.frame in axes[k], len(axes[k]), -k))
    height = {main: 0.0}
    frontier = [main]
    while frontier:
        nxt = []
        for k in frontier:
            siblings = 0
            for x in axes[k]:
                for j, other in enumerate(axes):
                    if j not in height and x in other:  # axes held side by side: staggered
                        height[j] = height[k] + 2.0 + 0.9 * siblings
                        siblings += 1
                        nxt.append(j)
        frontier = nxt
    for k in range(len(axes)):  # axes of another tree component (a floating part)
        height.setdefault(k, 2.0 * (k + 1))
    return height


def schematic(train: GearTrain, teeth: dict | None = None, compound=()) -> dict:
    """Geometry of the schematic: shafts, gear bars, carrier arms (plain data, for drawing and tests).

    The meshes of one wheel on one carrier share a column: the wheel is drawn once, centred on its
    shaft, with the gears it meshes below it (external) or a ring over it (internal).

    >>> s = schematic(GearTrain.parse("0-1-2 2-3 0~3i 1~3"))
    >>> sorted(s["shafts"]), len(s["gears"]), len(s["arms"])
    ([0, 1, 2, 3], 3, 1)
    """
    heights = _axis_heights(train)
    own_axis: dict[int, int] = {}
    level: dict[int, float] = {}
    for k, axis in enumerate(train.axes):
        for x in axis:
            if x not in own_axis or heights[k] < heights[own_axis[x]]:
                own_axis[x] = k
    for k, axis in enumerate(train.axes):  # concentric shafts; the frame outermost (lowest)
        members = sorted((x for x in axis if own_axis[x] == k), key=lambda x: (x == train.frame, x))
        for rank, x in enumerate(members):
            level[x] = heights[k] - _GAP * rank
    for x in range(train.links):  # a floating gear (a link on no axis meshes) turns about its carrier's lowest axis
        if x not in level:
            carrier = next(t for (a, b), t in zip(train.meshes, train.carriers) if x in (a, b))
            level[x] = level.get(carrier, 0.0) + _GAP
    compound = set(compound)

    def tooth(x, mate):
        if not teeth:
            return None
        return teeth.get(f"z{x}_{mate}", teeth.get(f"z{x}"))

    def label(x, mate):
        """``z<link>=teeth`` (``z<link>_<mate>`` for a wheel of a compound link), or None."""
        name = f"z{x}_{mate}" if f"z{x}_{mate}" in (teeth or {}) else f"z{x}"
        return f"{name}={teeth[name]}" if teeth and name in teeth else None

    columns: dict = {}  # (upper wheel, carrier) -> meshes
    for k, ((a, b), t) in enumerate(zip(train.meshes, train.carriers)):
        high = b if level[b] >= level[a] else a
        key = (high, t) if high not in compound else (high, t, k)
        columns.setdefault(key, []).append(k)
    gears, arms, span = [], [], {x: [] for x in range(train.links)}
    for c, (key, members) in enumerate(columns.items()):
        x = 1.0 + sum(1.0 + 0.3 * len(m) for m in list(columns.values())[:c])
        high, t = key[0], key[1]
        radius = None
        for k in members:
            a, b = train.meshes[k]
            low = a if high == b else b
            d = abs(level[high] - level[low]) or 1.0
            zh, zl = tooth(high, low), tooth(low, high)
            if zh and zl:
                r = d * zh / (zl - zh if train.internal[k] else zl + zh)
            else:
                r = 0.4 * d
            radius = r if radius is None else min(radius, r)
        width = 0.18 + 0.3 * (len(members) - 1)  # a wheel meshing several gears side by side
        gears.append({"link": high, "x": x + (width - 0.18) / 2, "from": level[high] - radius,
                      "to": level[high] + radius, "ring": False, "width": width,
                      "label": label(high, sum(train.meshes[members[0]]) - high)})
        span[high].append(x)
        for j, k in enumerate(members):
            a, b = train.meshes[k]
            low = a if high == b else b
            at = x + 0.3 * j
            if train.internal[k]:  # a ring over the wheel
                gears.append({"link": low, "x": at, "from": level[low], "to": level[high] + radius, "ring": True,
                              "label": label(low, high)})
            else:
                gears.append({"link": low, "x": at, "from": level[low], "to": level[high] - radius, "ring": False,
                              "label": label(low, high)})
            span[low].append(at)
        if level[high] > level[t] + 1e-9:
            arm_x = x - 0.5
            arms.append({"link": t, "x": arm_x, "from": level[t], "to": level[high]})
            span[t].append(arm_x)
            span[high].append(arm_x)
    shafts = {}
    for x in range(train.links):
        xs = span[x] or [0.5]
        shafts[x] = {"y": level[x], "from": min(xs) - 0.3, "to": max(xs) + 0.3}
    return {"shafts": shafts, "gears": gears, "arms": arms}


def _draw_on(ax, train: GearTrain, teeth, compound, title: str, fontsize: float = 9) -> None:
    import matplotlib.pyplot as plt

    geometry = schematic(train, teeth, compound)
    colours = plt.get_cmap("tab10").colors
    colour_of = lambda x: "black" if x == train.frame else colours[x % 10]  # noqa: E731
    shafts = geometry["shafts"]
    left = min(shaft["from"] for shaft in shafts.values())
    for x, shaft in shafts.items():
        ax.plot([shaft["from"], shaft["to"]], [shaft["y"]] * 2, color=colour_of(x), lw=2.2, solid_capstyle="butt")
        if x == train.frame:  # hatched ground under the frame's shaft
            x0, x1 = shaft["from"], shaft["to"]
            ax.plot([x0, x1], [shaft["y"] - 0.12] * 2, color="black", lw=1)
            for i in range(int((x1 - x0) / 0.15) + 1):
                t = x0 + i * 0.15
                ax.plot([t, t - 0.1], [shaft["y"] - 0.12, shaft["y"] - 0.24], color="black", lw=0.8)
    for arm in geometry["arms"]:
        ax.plot([arm["x"]] * 2, [arm["from"], arm["to"]], color=colour_of(arm["link"]), lw=2.2)
    for gear in geometry["gears"]:
        colour, x, y0, y1 = colour_of(gear["link"]), gear["x"], gear["from"], gear["to"]
        if gear["ring"]:  # a bracket over the wheel it meshes: internal teeth
            ax.plot([x + 0.3, x + 0.3, x - 0.12], [y0, y1 + 0.06, y1 + 0.06], color=colour, lw=2.2)
            ax.add_patch(plt.Rectangle((x - 0.12, y1 + 0.06), 0.42, 0.14, facecolor=colour, edgecolor=colour))
            if gear.get("label"):
                ax.text(x + 0.36, y1 + 0.13, gear["label"], fontsize=fontsize - 1, color=colour, ha="left",
                        va="center", bbox=_PLATE)
        else:
            w = gear.get("width", 0.18)
            ax.add_patch(plt.Rectangle((x - w / 2, min(y0, y1)), w, abs(y1 - y0), facecolor=colour,
                                       edgecolor=colour, alpha=0.85))
            if gear.get("label"):
                ax.text(x + max(w / 2, 0.3) + 0.08, (y0 + y1) / 2, gear["label"], fontsize=fontsize - 1, color=colour,
                        ha="left", va="center", bbox=_PLATE)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title(title, fontsize=fontsize)
    ax.margins(0.08)
    line = _text_line(ax, fontsize + 1)  # (the drawing's scale known: the numbers are placed last)
    for x, at, y in _label_places(shafts, left, line):  # link numbers in a column left of every shaft
        ax.text(at, y, str(x), ha="right", va="center", fontsize=fontsize + 1, color=colour_of(x), fontweight="bold")
        ax.plot([at + 0.04, shafts[x]["from"]], [y, shafts[x]["y"]], color=colour_of(x), lw=0.6, ls=":")


def _text_line(ax, points: float) -> float:
    """The height of a line of text of ``points`` in the data units of ``ax`` (equal aspect) as drawn so far, with
    room for the limits the numbers' leaders add."""
    ax.autoscale_view()
    box = ax.get_window_extent()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    per_pixel = max((x1 - x0) / box.width, (y1 - y0) / box.height)
    return _LINE * points * ax.figure.dpi / 72 * per_pixel


def _label_places(shafts: dict, left: float, line: float) -> list[tuple[int, float, float]]:
    """(link, x, y) of each link number, in a column left of every shaft: each at its shaft's height, and
    the numbers of shafts nearer than a text ``line`` (concentric shafts) spread a line apart about their
    shafts' mean height (radially, as the shafts of an axis stand), a dotted leader to each shaft.

    >>> _label_places({0: {"y": 0.0}, 1: {"y": 0.1}, 2: {"y": 2.0}}, 1.0, 0.5)   # 0 and 1 concentric
    [(0, 0.8, -0.2), (1, 0.8, 0.3), (2, 0.8, 2.0)]
    """
    groups: list[list[int]] = []  # runs of numbers a line apart, from the lowest up
    lowest = lambda group: sum(shafts[x]["y"] for x in group) / len(group) - line * (len(group) - 1) / 2  # noqa: E731
    for x in sorted(shafts, key=lambda x: (shafts[x]["y"], x)):
        groups.append([x])
        while len(groups) > 1 and lowest(groups[-1]) < lowest(groups[-2]) + line * len(groups[-2]) - 1e-12:
            above = groups.pop()
            groups[-1] += above  # too near the run below: one run
    return [(x, left - 0.2, lowest(group) + line * k) for group in groups for k, x in enumerate(group)]


def _legend(fig, frame: bool, fontsize: float = 8) -> None:
    """What the symbols mean, under the drawings."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Line2D([], [], color="grey", lw=2.2, label="shaft (its link's number on the left)"),
               Patch(facecolor="grey", alpha=0.85, label="gear wheel (bar: its pitch diameter)"),
               Line2D([], [], color="grey", lw=2.2, marker="_", markersize=10, label="ring gear (bracket over its pinion)"),
               Line2D([], [], color="grey", lw=2.2, marker="|", markersize=10, ls="none", label="carrier arm")]
    if frame:
        handles.append(Line2D([], [], color="black", lw=2.2, label="frame (black, hatched)"))
    fig.legend(handles=handles, loc="lower center", ncol=3 if len(handles) > 4 else 2, fontsize=fontsize,
               frameon=False, bbox_to_anchor=(0.5, 0.0))


def _caption(train: GearTrain) -> str:
    return train.compact() + (f"  (frame {train.frame})" if train.frame is not None else "")


def _target(path) -> Path:
    path = Path(path)
    if path.suffix.lower() not in _FORMATS:
        raise InvalidOption(f"a drawing is written as {', '.join(_FORMATS)}, not {path.suffix or 'no extension'}")
    return path


def _save(fig, path: Path, dpi: int) -> None:
    import matplotlib.pyplot as plt

    try:
        save_figure(fig, path, bbox_inches="tight", dpi=dpi)
    except OSError as exc:
        raise InvalidOption(f"cannot write {path}: {exc.strerror}") from None
    finally:
        plt.close(fig)


def draw_train(train: GearTrain, path, *, teeth: dict | None = None, compound=(), title: str | None = None,
               size: float = 6.0) -> None:
    """Write the functional schematic of one train to ``path`` (.svg, .png or .pdf), with a legend;
    with ``teeth`` (a design) each wheel is labelled with its tooth number."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = _target(path)
    fig, ax = plt.subplots(figsize=(size, size * 0.75 + 0.6))
    _draw_on(ax, train, teeth, compound, title or _caption(train))
    fig.subplots_adjust(bottom=0.6 / (size * 0.75 + 0.6) + 0.04)
    _legend(fig, train.frame is not None)
    _save(fig, path, 110)


def draw_train_sheet(trains, path, *, columns: int = 4, limit: int = 48, titles=None) -> int:
    """Several schematics on one sheet, each captioned (each line wrapped to its cell) and a legend under
    them; more than ``limit`` trains are refused (a sheet never drops trains silently).
    Returns how many were drawn."""
    path = _target(path)
    trains = list(trains)
    if len(trains) > limit:
        raise InvalidOption(f"{len(trains)} trains are more than the {limit} a sheet holds here: select fewer")
    if not trains:
        return 0
    _save(sheet_figure(trains, columns=columns, titles=titles), path, 90)
    return len(trains)


def sheet_figure(trains, *, columns: int = 4, titles=None):
    """The matplotlib figure of a sheet of schematics (:func:`draw_train_sheet` writes it).

    >>> fig = sheet_figure([GearTrain.parse("0-1-2 2-3 0~3i 1~3"), GearTrain.parse("0-1 0-2 1~2")])
    >>> [ax.get_title() for ax in fig.axes]
    ['1: 0-1-2 2-3 0~3i 1~3', '2: 0-1 0-2 1~2']
    """
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    columns = min(columns, len(trains))
    rows = -(-len(trains) // columns)
    width, height, foot = 3.6, 3.4, 0.5  # inches: a cell, and the legend's strip
    fig, axes = plt.subplots(rows, columns, figsize=(width * columns, height * rows + foot), squeeze=False,
                             layout="constrained")
    for k, ax in enumerate(axes.flat):
        if k < len(trains):  # captions wrap at 11 characters an inch (at 8 points about 15 fit)
            title = titles[k] if titles else f"{k + 1}: {_caption(trains[k])}"
            title = "\n".join(textwrap.fill(line, int(width * 11)) for line in title.splitlines())  # its own breaks kept
            _draw_on(ax, trains[k], None, (), title, fontsize=8)
        else:
            fig.delaxes(ax)
    share = foot / (height * rows + foot)
    fig.get_layout_engine().set(h_pad=0.15, w_pad=0.1, rect=(0, share, 1, 1 - share))
    _legend(fig, any(t.frame is not None for t in trains))
    return fig


def svg_text(train: GearTrain, *, size: float = 2.6) -> str:
    """The schematic of one train as an ``<svg>`` element (no title; ``size`` inches wide), for
    web pages that show many trains inline; the same drawing as :func:`draw_train`, deterministic.

    >>> svg_text(GearTrain.parse("0-1-2 2-3 0~3i 1~3", frame=0)).startswith("<svg")
    True
    """
    import io

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(size, size * 0.75))
    _draw_on(ax, train, None, (), "")
    buffer = io.StringIO()
    try:
        save_figure(fig, buffer, fmt="svg", bbox_inches="tight")
    finally:
        plt.close(fig)
    text = buffer.getvalue()
    return text[text.index("<svg"):]
