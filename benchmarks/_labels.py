"""Point labels of the benchmark plots that do not cover one another.

Each label goes to the first side of its point, starting from its series' own, where its box
covers no label placed before it; with every side taken it keeps its own.

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
    renderer = fig.canvas.get_renderer()
    placed = []
    for k, label in labels:
        own = k % 4  # the series' side among the nearer four
        for offset, align in sides[own:] + sides[:own]:
            label.set_position(offset)
            label.set_horizontalalignment(align)
            box = label.get_window_extent(renderer)
            if not any(box.overlaps(other) for other in placed):
                break
        else:
            label.set_position(sides[own][0])
            label.set_horizontalalignment(sides[own][1])
            box = label.get_window_extent(renderer)
        placed.append(box)
