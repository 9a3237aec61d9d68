"""Drawings of chains, mechanisms and gear trains, along their seams:

==============  ==================================================================================
``_layout``     where the joints go and each link's polygon (:func:`layout`, :class:`Layout`)
``_render``     chains and mechanisms drawn as a designer draws them: SVG, PNG, PDF and inline SVG
``_gears``      functional schematics of gear trains (shafts, gears on their axes, carriers)
==============  ==================================================================================

Moving mechanisms (a linkage posed, its curves, animations) are drawn by :mod:`synth.motion_draw`.
The names below are loaded on first use.

Example
-------
>>> import tempfile, os
>>> from synth import Chain
>>> from synth.draw import draw_one, draw_train
>>> from synth.gears import GearTrain
>>> folder = tempfile.mkdtemp()
>>> draw_one(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), os.path.join(folder, "watt.svg"))
>>> draw_train(GearTrain.parse("0-1-2 2-3 0~3i 1~3", frame=0), os.path.join(folder, "train.svg"))
>>> sorted(os.listdir(folder))
['train.svg', 'watt.svg']
"""

from .._lazy import lazy_exports

_WHERE = {
    "Layout": "._layout", "layout": "._layout",
    "expand": "._render", "draw_one": "._render", "draw_sheet": "._render", "svg": "._render",
    "svg_inline": "._render", "DrawError": "._render", "SINGLE": "._render", "CELL": "._render",
    "check_size": "._render", "check_pixels": "._render",
    "draw_train": "._gears", "draw_train_sheet": "._gears", "sheet_figure": "._gears", "schematic": "._gears",
    "svg_text": "._gears",
}

__all__ = list(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
