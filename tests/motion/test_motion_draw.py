"""Pictures of moving mechanisms (synth.motion_draw): every writer puts each pin where the solver
put it, animations change between frames, and every mechanism drawn by the atlas becomes a linkage
that moves."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import synth
from synth.motion import read_linkage, sweep
from synth.motion_draw import animate_motion, draw_motion, linkage_from_layout, linkage_svg, motion_svg, player_svg
from synth.structure.chain import Chain, Mechanism

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def four_bar():
    return read_linkage(ROOT / "models" / "motion_four_bar.toml")


def _circles(svg: str) -> list[tuple[float, float, float]]:
    return [tuple(map(float, m)) for m in re.findall(r'<circle cx="([-\d.]+)" cy="([-\d.]+)" r="([\d.]+)"', svg)]


def test_still_picture_puts_every_pin_at_its_pose(four_bar):
    svg = linkage_svg(four_bar, size=400)
    pins = _circles(svg)
    assert len(pins) == 4 + 1  # four pins and the tracer's dot
    width = float(re.search(r'width="(\d+)"', svg).group(1))
    # the pixels are an affine image of the pose: equal distance ratios, y turned downwards
    px = np.array([p[:2] for p in pins[:4]])
    pose = four_bar.points
    scale = np.hypot(*(px[1] - px[0])) / np.hypot(*(pose[1] - pose[0]))
    assert 0 < width <= 400
    for i in range(4):
        for j in range(i):
            assert np.hypot(*(px[i] - px[j])) == pytest.approx(scale * np.hypot(*(pose[i] - pose[j])), abs=0.15)
    assert ">P</text>" in svg and "<title>" in svg


def test_player_frames_follow_the_crank_circle(four_bar):
    motion = sweep(four_bar, steps=73)
    svg = player_svg(motion, size=300, frames=24)
    data = json.loads(re.search(r'data-motion="([^"]+)"', svg).group(1).replace("&quot;", '"'))
    assert data["n"] == 24 and all(len(e) == 24 for e in data["e"])
    # the crank pin (joint 1-2, a moving circle) stays at one distance from the crank's pivot
    pivot = _circles(svg)[0][:2]  # joint 0-1 is drawn first among the pins and never moves
    moving = [e for e in data["e"] if len(e[0]) == 2]  # circles and texts: one point a frame
    distances = [np.ptp([math.dist(pivot, f) for f in e]) for e in moving]
    assert min(distances) < 0.2  # one of them is the crank pin: a circle about the pivot, to the pixel rounding
    assert max(distances) > 10  # and the coupler's pins wander


def test_smil_animation_has_a_value_per_frame(four_bar):
    svg = motion_svg(sweep(four_bar, steps=91), frames=30)
    values = re.findall(r'attributeName="cx" dur="[\d.]+s" repeatCount="indefinite" values="([^"]+)"', svg)
    assert values and all(len(v.split(";")) == 30 for v in values)
    assert len(set(values[-1].split(";"))) > 10  # the frames differ


def test_files_are_checked_and_written(four_bar, tmp_path):
    motion = sweep(four_bar, steps=37)
    with pytest.raises(synth.InvalidOption, match="PNG or SVG"):
        draw_motion(motion, tmp_path / "x.jpg")
    with pytest.raises(synth.InvalidOption, match="2 … 1000"):
        animate_motion(motion, tmp_path / "x.gif", frames=1)
    draw_motion(motion, tmp_path / "c.svg")
    assert (tmp_path / "c.svg").read_text().count("<polyline") >= 3  # pin paths and the coupler curve
    assert animate_motion(motion, tmp_path / "m.gif", frames=8) == 8


@pytest.mark.parametrize("text, frame", [("0-1 1-2 2-3 3-0", 0), ("0-1 1-2 2-3 3=0", 0), ("0-1 1-2 2=3 3-0", 0),
                                         ("0-1 1-2 2-3 3-0 0-4 4-5 5-1", 0), ("0-1 1-2 2-3 3-0 0-4 4-5 5-1", 2)])
def test_a_mechanism_of_the_atlas_moves_from_its_drawing(text, frame):
    linkage = linkage_from_layout(Mechanism(Chain.parse(text), frame))
    motion = sweep(linkage, steps=73)
    assert linkage.dof == 1 and motion.stopped is None
    assert abs(motion.inputs[-1, 0] - motion.inputs[0, 0]) > math.radians(20)
    if linkage.note:
        assert "moved by up to" in linkage.note
    worst = min([min(t["min"], math.pi - t["max"]) for t in motion.transmission.values()], default=math.pi / 2)
    assert worst > math.radians(5)  # not the drawing's locked or folding pose


def test_the_same_mechanism_gets_the_same_linkage():
    m = Mechanism(Chain.parse("0-1 1-2 2-3 3-0 0-4 4-5 5-1"), 0)
    assert linkage_from_layout(m).to_dict() == linkage_from_layout(m).to_dict()


def test_a_linkage_shows_itself_in_a_notebook(four_bar):
    """The facade names linkage_svg as a Linkage's drawing (synth.display.svg_of)."""
    from synth.display import svg_of

    assert svg_of(four_bar) == linkage_svg(four_bar)


@pytest.mark.parametrize("along", [0.0, 7.5, -12.0])
def test_a_sliders_block_is_drawn_where_the_slider_is_wherever_its_joint_lies_on_its_line(along):
    """A prismatic joint's point may be anywhere on its line (the dimensional synthesis leaves it where
    the search put it): the block is drawn at the foot of the slider's pin, the frame is the guide, and
    an offset pin gets an arm to its block."""
    from synth.motion import Linkage
    from synth.motion_draw import _elements, _still

    u = np.array([math.cos(0.4), math.sin(0.4)])
    pin = np.array([3.0, 2.5])  # the slider's pin 2-3, 0.8 off the line through (3, 1.7) along u
    foot = pin - 0.8 * np.array([-u[1], u[0]])
    chain = Chain.parse("0-1 1-2 2-3 3=0")
    at = {(0, 1): [0, 0], (1, 2): [0.6, 0.8], (2, 3): pin, (0, 3): foot + along * u}  # joints by their links
    slide = next(k for k, j in enumerate(chain.joints) if tuple(sorted(j)) == (0, 3))
    slider_crank = Linkage(Mechanism(chain, 0), (0,), [at[tuple(sorted(j))] for j in chain.joints], {slide: tuple(u)})
    joints, angles, tracers = _still(slider_crank)
    elements = _elements(slider_crank, joints, angles, tracers, {})
    block = [e for e in elements if e["tag"] == "polygon" and e["style"].get("fill") == "white"]
    assert len(block) == 1
    assert np.allclose(block[0]["frames"][0].mean(axis=0), foot, atol=1e-9)
    arms = [e["frames"][0] for e in elements if e["tag"] == "polyline" and len(e["frames"][0]) == 2]
    assert any(np.allclose(a, [pin, foot], atol=1e-9) for a in arms)
    guide = [e for e in elements if e["tag"] == "polyline" and e["style"].get("stroke-dasharray") == "5 3"]
    assert len(guide) == 1  # dashed: the frame carries the guide


def test_an_animations_progress_in_a_log_is_no_bar(four_bar, tmp_path, capsys):
    """Where stderr is not a terminal (a log), drawing a GIF writes no tqdm bar ('\\r' redraws) there."""
    assert animate_motion(sweep(four_bar, steps=37), tmp_path / "a.gif", frames=4, progress=True) == 4
    assert "\r" not in capsys.readouterr().err


def test_player_numbers_the_links_moving_with_them_and_hatches_the_ground_pivots(four_bar):
    # the site's page says 'link 0 fixed', 'input joint 0-1' and showed no number; its pivots were a triangle on a
    # line, nothing marked them fixed
    import xml.etree.ElementTree as ET

    svg = player_svg(sweep(four_bar, steps=73), size=300, frames=24)
    root = ET.fromstring(svg)
    data = json.loads(root.get("data-motion"))["e"]
    shapes = list(root)[1:]  # (after the title)

    def frames(el) -> np.ndarray:  # the element's points at every frame, in pixels
        if el.get("data-k") is not None:
            return np.array(data[int(el.get("data-k"))]).reshape(24, -1, 2)
        if el.tag.endswith("text"):
            return np.array([[[float(el.get("x")), float(el.get("y"))]]] * 24)
        return np.array([[list(map(float, p.split(","))) for p in el.get("points").split()]] * 24)

    numbers = {el.text: i for i, el in enumerate(shapes) if el.tag.endswith("text") and el.text.isdigit()}
    assert sorted(numbers) == ["0", "1", "2", "3"]
    pivot = np.array(_circles(svg)[0][:2])  # joint 0-1, the crank's pivot
    for link, i in numbers.items():  # each on a light box, the box around its text at every frame
        box = shapes[i - 1]
        assert box.get("fill") == "white" and box.get("fill-opacity") == "0.8"
        corners, anchor = frames(box), frames(shapes[i])[:, 0]
        assert ((corners.min(axis=1) < anchor) & (anchor < corners.max(axis=1))).all()
    # the crank's number turns with the crank about its pivot: its box's centre keeps its distance (to the pixel
    # rounding) while it goes round; the frame's stands still
    crank = frames(shapes[numbers["1"] - 1]).mean(axis=1)
    reach = np.hypot(*(crank - pivot).T)
    assert np.ptp(reach) < 0.2 and np.ptp(crank, axis=0).min() > reach.mean()
    assert shapes[numbers["0"]].get("data-k") is None
    # under each ground pivot's base line, strokes hatched within its width
    bases = [frames(el)[0] for el in shapes if el.tag.endswith("polyline") and el.get("stroke-width") == "2.4"]
    strokes = [frames(el)[0] for el in shapes if el.tag.endswith("polyline") and el.get("stroke-width") == "1.2"
               and el.get("data-k") is None]
    assert len(bases) == 2
    for base in bases:
        under = [s for s in strokes if base[:, 0].min() - 1 < s[:, 0].min() and s[:, 0].max() < base[:, 0].max() + 1
                 and abs(s[:, 1].min() - base[0, 1]) < 0.2 and s[:, 1].max() > base[0, 1] + 2]
        assert len(under) == 5
