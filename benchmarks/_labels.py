"""Point labels of the benchmark plots that do not cover one another.

Each label goes to the first side of its point, starting from its series' own, where its box
stays inside its axes and covers no labelled point and no label placed before it; with every side
taken it keeps its own.

>>> import matplotlib; matplotlib.use("Agg"); import matplotlib.pyplot as plt
>>> fig, ax = plt.subplots()
>>> a = [ax.annotate(t, (1, 1), xytext=(0, 0), textcoords="offset points") for t in ("one", "two")]
>>> place_labels(fig, [(0, a[0]), (0, a[1])])
>>> a[0].get_position() != a[1].get_position()
True
"""

from __future__ import annotations

#: offsets (points) and alignments around a point: upper left, lower right, lower left, upper right,
#: then the same a line further out
SIDES = [((-4, 5), "right"), ((4, -11), "left"), ((-4, -11), "right"), ((4, 5), "left"),
         ((-4, 14), "right"), ((4, -20), "left"), ((-4, -20), "right"), ((4, 14), "left")]


def place_labels(fig, labels, sides=SIDES) -> None:
    """Move each ``(series index, annotation)`` of ``labels``, in order, to a free side of its point."""
    from matplotlib.transforms import Bbox

    renderer = fig.canvas.get_renderer()
    # the labelled points themselves are taken (a marker is about 8 pixels across)
    placed = [Bbox.from_bounds(*(label.axes.transData.transform(label.xy) - 4), 8, 8) for _, label in labels]

    def put(label, side):
        label.set_position(side[0])
        label.set_horizontalalignment(side[1])
        return label.get_window_extent(renderer)

    def fits(label, side):  # inside its axes, over no point and no label placed before
        box, frame = put(label, side), label.axes.get_window_extent(renderer)
        return frame.contains(box.x0, box.y0) and frame.contains(box.x1, box.y1) and \
            not any(box.overlaps(other) for other in placed)

    for k, label in labels:
        order = sides[k % 4:] + sides[:k % 4]  # from the series' own side among the nearer four
        free = next((side for side in order if fits(label, side)), order[0])
        placed.append(put(label, free))
