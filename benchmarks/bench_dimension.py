"""Dimensional synthesis on classical four-bar path problems and on pylinkage's documented examples:
error and CPU time per problem, pylinkage 1.3.0 side by side where it has an example.

Usage: ``python benchmarks/bench_dimension.py [--budget SECONDS] [--seed N] [--only NAME] [--reach R]
[--pylinkage-python PATH]`` — one row per problem (JSON lines on stdout): the sum of squared
errors (the objective the literature reports), the largest and RMS error in the target's units,
the relative error, CPU seconds and candidates evaluated, each constraint's value, and where the
problem was read.  Ours is run as ``mechsynth synthesize`` runs it (the sampled starts included).
Where a source records its own answers (vectors of its four-bar model, :func:`source_model`), the row
gives each one's sum of squared errors as recorded and as the motion layer recomputes it, and says how
our statement of the problem differs from the source's; a problem posed as its source states it also
has our answer judged as the source judges its own (its vector, the source's closed form, bounds and
crank-angle order: :func:`as_the_source_states_it`).  The problems, their sources
and the results are in benchmarks/DIMENSION.md.

``python benchmarks/bench_dimension.py --reliability SEEDS [--budget SECONDS] [--samples N]`` measures how often
the search finds a mechanism's own points again from no guess: for each seed (``0..9``) a crank-rocker
with random dimensions gives ten points without timing (a whole turn), and an offset slider-crank
with random dimensions eight timed points over 300° (the search given ``synth.atlas.sampled_starts``);
a row per seed and case says the relative error
reached and the CPU seconds (the search stops early once the target is met to 1e-11 of its size).

``python benchmarks/bench_dimension.py --table LOG [LOG ...]`` prints the Markdown tables of
benchmarks/DIMENSION.md from such rows (JSON lines, as the runs above write them): one line per
problem, and per reliability case the seeds found; no number in those tables is typed by hand.

pylinkage is not a dependency of the project: its side runs in a virtual environment of its own with
the SciPy extra its synthesis needs, made once with

    python -m venv /tmp/pylinkage-synth
    /tmp/pylinkage-synth/bin/pip install 'pylinkage[scipy]==1.3.0'

(without that interpreter its rows are left out).  Its ``path_generation`` is called exactly as its
README shows, timed in CPU seconds (the import excluded); each of its solutions is then moved through
a whole turn of its crank by its own simulation (20 000 steps) and each target point's distance to
that coupler curve is its error — the nearest point of the curve, whatever the order, which can only
flatter it.  Ours is the distance at the point's own input, in order.
"""

from __future__ import annotations

import argparse
import functools
import json
import math
import subprocess
import sys
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from benchmarks._out import emit  # noqa: E402
from synth import Chain, Mechanism  # noqa: E402
from synth.atlas import sampled_starts  # noqa: E402
from synth.dimension import Constraints, PathTarget, synthesize  # noqa: E402
from synth.motion import Linkage, assemble, motion_range, sweep  # noqa: E402
from tests.dimension.test_synthesize import SLIDER_CRANK, random_crank_rocker  # noqa: E402

FOUR_BAR = Mechanism(Chain.parse("0-1 1-2 2-3 3-0"), frame=0)
DEFAULT_PYLINKAGE = "/tmp/pylinkage-synth/bin/python"

#: The public code the problems below were read from (benchmarks/DIMENSION.md, "The literature").
ECA = "jmejia8/eca-four-bar-mechanisms"
HNMED = "roydes/HNMED-Implementacion-y-Pruebas"
HCDJ = "sy-nguyen-van/DE_Jaya_Synthesis_Four_Bar_Mechanisms"


@dataclass(frozen=True)
class Problem:
    """A classical path problem: the points, their timing, our constraints and where it was read.

    ``records`` are the answers the sources record for the problem as *they* state it: each the vector
    ``(r1, r2, r3, r4, rcx, rcy[, θ0, x0, y0, θ2 at each point])`` of the sources' four-bar model
    (:func:`source_model`), its sum of squared errors, the method and where.  ``differs`` says how
    our statement of the problem differs from the source's, where it does.  ``bounds`` is the source's
    box, where our answer is checked against it (:func:`as_the_source_states_it`): the longest link,
    the coupler point's largest offset in the coupler's frame, and the input pivot's centre and
    half-width."""

    points: list
    inputs: list | None
    constraints: Constraints
    source: str
    pylinkage: bool = False
    records: tuple = ()
    differs: str | None = None
    bounds: dict | None = None


# CE2's five points and their timing, as both sources state them (the crank's angle from the frame line)
ARC = [(3, 3), (2.759, 3.363), (2.372, 3.663), (1.890, 3.862), (1.355, 3.943)]
ARC_TIMING = [math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2]
HNMED_METHOD = "HNMED (hybrid Nelder-Mead and differential evolution)"
ARC_RECORD = {"vector": [2.275311865, 2.085761231, 2.275311865, 2.275311865, 1.503900733, 1.725985126],
              "sum_squared_error": 2.5643900e-4, "method": HNMED_METHOD, "name": "HNMED6",
              "where": f"{HNMED}: Resultados de Experimentos/E/Mejores resultados HNMED6.xlsx, column MCE2"}
# CE1's six points, and the answers the sources record for it: [HNMED]'s best of HNMED6, the five minima of its
# Nelder-Mead variants (experiment A; two of them found twice), and [ECA]'s bestEver
LINE = [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40), (20, 45)]
_MINIMA = f"{HNMED}: Resultados de Experimentos/A/Minimos P1.txt"
LINE_RECORDS = (
    {"vector": [36.20984565222868, 8.5122713957833192, 26.286150530546053, 36.133728484955391, 35.285017928880542,
                15.856251446094324, 3.9425512258184425, -7.5517166964425364, 57.867501834179919, 1.6656403214572555,
                2.4331171195675414, 2.9521145521903884, 3.4537405841629933, 4.0026514475284003, 5.3124518167904986],
     "sum_squared_error": 3.7865323450608567e-29, "method": HNMED_METHOD, "name": "HNMED6",
     "where": f"{HNMED}: Resultados de Experimentos/E/Mejores resultados HNMED6.xlsx, column MCE1"},
    {"vector": [39.35432733966176, 8.738597335076454, 27.91020567579063, 38.41653206619049, 36.576759454887835,
                18.058222622003274, 3.922197401424182, -9.015069651004032, 59.8594568458345, 1.6275724377055465,
                2.42129538238649, 2.93021895068062, 3.4158306289051543, 3.9401612344766854, 5.428565504554411],
     "sum_squared_error": 1e-20, "method": "ECA (Evolutionary Centers Algorithm)", "name": "ECA",
     "where": f"{ECA}: tools.jl bestEver(1) (commits 6ef49b0-5f6fe15; the error written as 1e-20)"},
    {"vector": [30.678548722521839, 7.586679649003891, 27.958699364892709, 29.544623899349318, 44.076107733464056,
                20.242121958133389, 4.213461531964716, -18.616222237141834, 59.178201995688198, 1.780232945487026,
                2.431480107064163, 2.928463126026752, 3.403600051451985, 3.908735043042637, 4.596039076717807],
     "sum_squared_error": 4.964143904374783e-26, "method": "Nelder-Mead NM_RLE1", "name": "NM_RLE1", "where": _MINIMA},
    {"vector": [28.894894002096127, 7.699362924662206, 28.789643790312432, 28.789648347014200, 50.009541789990848,
                19.456595739558054, 4.341350883690305, -24.222221620732952, 59.428637366180538, 1.926846233130806,
                2.470371173894058, 2.923724292683829, 3.359461194819953, 3.812814333970347, 4.356339339329878],
     "sum_squared_error": 1.833186525988796e-25, "method": "Nelder-Mead NM_RLE1", "name": "NM_RLE1",
     "where": _MINIMA},
    {"vector": [58.954789874653642, 10.100561959281467, 22.130174828825229, 48.514150526927558, -22.687379427695106,
                33.037006703955882, 5.952572594126479, 49.737533228753385, 4.591291798616073, 0.822695152391493,
                1.017152238623345, 1.226984550277193, 1.467583986855584, 1.775153505509507, 2.566511912842474],
     "sum_squared_error": 3.155064967649541e-25, "method": "Nelder-Mead NM_RLE2", "name": "NM_RLE2", "where": _MINIMA},
    {"vector": [29.961378038287577, 7.814749260020724, 29.329511473127049, 29.795346154976343, 49.925375596851168,
                19.901163156590947, 4.312498649861119, -24.006244292968709, 59.996496108794844, 1.936533768526645,
                2.480037913641839, 2.932600016581741, 3.368080005161368, 3.822666733609230, 4.372707853323134],
     "sum_squared_error": 6.856652770436199e-25, "method": "Nelder-Mead NM_RL2E", "name": "NM_RL2E",
     "where": _MINIMA},
    {"vector": [36.237821095763053, 8.184926111065355, 28.677920624923544, 35.522573128519056, 40.177509271725945,
                18.480058451459460, 4.032174802373708, -12.806744148539320, 59.943184518757931, 1.756625828974676,
                2.457199566226263, 2.966052653222432, 3.457711443210014, 3.996287284363052, 4.908210932894533],
     "sum_squared_error": 3.056993779912465e-26, "method": "Nelder-Mead NM_RL2E", "name": "NM_RL2E",
     "where": _MINIMA},
)
# Kunjur and Krishnamurty's eighteen points, as [ECA] states them
EIGHTEEN = [(0.5, 1.1), (0.4, 1.1), (0.3, 1.1), (0.2, 1.0), (0.1, 0.9), (0.05, 0.75), (0.02, 0.6), (0, 0.5), (0, 0.4),
            (0.03, 0.3), (0.1, 0.25), (0.15, 0.2), (0.2, 0.3), (0.3, 0.4), (0.4, 0.5), (0.5, 0.7), (0.6, 0.9), (0.6, 1.0)]
EIGHTEEN_CENTRE = tuple(np.mean(EIGHTEEN, axis=0).tolist())  # [ECA] moves the points' mean to the origin
FIXED_FRAME = ("the source fixes the input pivot at the origin and the frame along +x, and times the crank from the "
               "frame line (6 unknowns for 10 equations)")
# [HCDJ]'s Case 4: six points on a half circle (radius 10 about (10, 0)), the crank at 30° … 180° from the frame
# line; its best answer (x_best, reordered (r1 … rcy, θ0, x0, y0) from its (r1 … rcy, x0, y0, θ0))
HALF_CIRCLE = [(0, 0), (1.9098, 5.8779), (6.9098, 9.5106), (13.09, 9.5106), (18.09, 5.8779), (20, 0)]
HALF_CIRCLE_TIMING = [math.radians(30 * k) for k in range(1, 7)]
HALF_CIRCLE_RECORDS = (
    {"vector": [4.9999980e+01, 1.3484315e+00, 1.3484507e+00, 5.0000000e+01, 1.1384434e+01, 4.4424357e+00, 6.2158799e+00,
                1.0194752e+01, -3.6941340e+00],
     "sum_squared_error": 1.2162122, "method": "HCDJ (hybrid-combined differential evolution and Jaya)", "name": "HCDJ",
     "where": f"{HCDJ}: Case4/x_best_HCDJ_Case4.txt, its error in Case4/Records_HCDJ_Case4.txt (best of 50 runs)"},
)
#: [HCDJ]'s Case 4 constraints (Cons4.m): Grashof's condition with the crank the shortest link (so the crank turns)
CRANK_SHORTEST = ("r2 <= r1", "r2 <= r3", "r2 <= r4")
#: the sources' crank-rocker with the frame longest (with the order, their r1 + r2 <= r3 + r4 is the crank turning)
SOURCES_ORDER = ("r2 <= r3 <= r4 <= r1",)

PROBLEMS = {
    "five points on a line, timed": Problem(
        [(20, 20), (20, 25), (20, 30), (20, 35), (20, 40)],
        [math.pi / 6, math.pi / 4, math.pi / 3, 5 * math.pi / 12, math.pi / 2], Constraints(),
        "none read: restated on 28 Nov from later papers' openings (points of CE1, timing of CE2)"),
    "six points on a line, untimed": Problem(
        LINE, None, Constraints(crank=True), f"{ECA}: tools.jl case 1; {HNMED}: Problema_1.m (CE1)",
        records=LINE_RECORDS[:1],
        differs="the source asks r2 <= r3 <= r4 <= r1 and r1 + r2 <= r3 + r4 (a crank-rocker, frame longest); "
                "ours asks only that the crank turns"),
    "six points on a line, untimed, as stated": Problem(
        LINE, None, Constraints(crank=True, order=SOURCES_ORDER),
        f"{ECA}: tools.jl case 1; {HNMED}: Problema_1.m (CE1), bounds in A_Experimentos.m", records=LINE_RECORDS,
        bounds={"link": 60.0, "offset": 60.0, "pivot": (0.0, 0.0, 60.0)},
        differs="the sources' order r2 <= r3 <= r4 <= r1 with the crank turning (with the order, their r1 + r2 <= "
                "r3 + r4); their box (links 0-60; rcx, rcy, x0, y0 within +-60) is checked on the answer, not posed "
                "(our pivots' region would hold the rocker's pivot too, which theirs bounds only through r1, and one "
                "record has it at x = 105); the crank's angles pass the points one way within a turn, where [HNMED] "
                "asks them ascending within 0-2pi from the frame line and [ECA] ascending from the first point's "
                "within a turn (both checked on the answer); any assembly branch, where the sources take the + root "
                "(checked on the answer)"),
    "five timed points on an arc, frame free": Problem(
        ARC, ARC_TIMING, Constraints(crank=True), f"{ECA}: tools.jl case 2; {HNMED}: Problema_2.m (CE2)",
        records=(ARC_RECORD,),
        differs=FIXED_FRAME + "; ours places the frame and the crank's first angle freely (10 unknowns)"),
    "five timed points on an arc, pivots on the x axis": Problem(
        ARC, ARC_TIMING, Constraints(crank=True, pivots=(-1e-3, 50.0, -1e-3, 1e-3)),
        f"{ECA}: tools.jl case 2; {HNMED}: Problema_2.m (CE2)", records=(ARC_RECORD,),
        differs=FIXED_FRAME + "; ours keeps both pivots within 0.001 of the x axis between x = 0 and 50, but the "
                "input pivot may slide along it and the crank's first angle is free (8 unknowns)"),
    "five timed points on an arc, as stated": Problem(
        ARC, ARC_TIMING, Constraints(crank=True, pivot_at={"0-1": (0.0, 0.0)}, frame_angle=0.0, timing="absolute",
                                     order=("r2 <= r3 <= r4 <= r1",)),
        f"{ECA}: tools.jl case 2; {HNMED}: Problema_2.m (CE2)", records=(ARC_RECORD,),
        differs="none: as the sources state it (input pivot at the origin, frame along +x, the crank's absolute "
                "angles, r2 <= r3 <= r4 <= r1; with that order their r1 + r2 <= r3 + r4 is the crank turning fully), "
                "but any assembly branch, where the sources take the + root"),
    "six timed points on a half circle, as stated": Problem(
        HALF_CIRCLE, HALF_CIRCLE_TIMING, Constraints(crank=True, max_length=50.0, timing="absolute", order=CRANK_SHORTEST),
        f"{HCDJ}: Case4/Objf4.m (points, timing, objective), Cons4.m (constraints), "
        "Additional-functions/Mechanisms.m (bounds)", records=HALF_CIRCLE_RECORDS,
        bounds={"link": 50.0, "offset": 50.0, "pivot": (0.0, 0.0, 50.0)},
        differs="as the source states it (the crank's angles from the frame line, the frame's place and direction "
                "free, 9 unknowns; the crank the shortest link and turning, which with that order is its Grashof "
                "test; links at most 50), but any assembly branch, where the source takes one root; its bounds on "
                "rcx, rcy, x0, y0 (+-50) are checked on the answer, not posed"),
    "six timed points on a half circle, no length bound": Problem(
        HALF_CIRCLE, HALF_CIRCLE_TIMING, Constraints(crank=True, timing="absolute", order=CRANK_SHORTEST),
        f"{HCDJ}: Case4/Objf4.m, Cons4.m", records=HALF_CIRCLE_RECORDS,
        differs="the source bounds every link by 50 (its best answers lie on that bound); ours here does not"),
    "ten points of a closed path, untimed": Problem(
        [(20, 10), (17.66, 15.142), (11.736, 17.878), (5, 16.928), (0.60307, 12.736), (0, 6.9519),
         (3.5396, 2.5171), (10, 0.2679), (16.736, 2.1216), (20, 6.5798)], None, Constraints(),
        "none read: restated on 28 Nov from later papers' openings"),
    "eighteen points of a closed path, untimed": Problem(
        EIGHTEEN, None, Constraints(crank=True),
        f"{ECA}: testTrajectories.jl case 12, bounds in experiments.jl",
        differs="the source's box is links 0-5 and offsets and pivot within +-5; ours is 4 target sizes (4.3) "
                "round the points' centre, and asks only that the crank turns"),
    "eighteen points of a closed path, untimed, as stated": Problem(
        EIGHTEEN, None, Constraints(crank=True, order=SOURCES_ORDER),
        f"{ECA}: testTrajectories.jl case 12, bounds in experiments.jl, constraints in tools.jl (grashof)",
        bounds={"link": 5.0, "offset": 5.0, "pivot": (*EIGHTEEN_CENTRE, 5.0)},
        differs="the source's order r2 <= r3 <= r4 <= r1 with the crank turning (with the order, its r1 + r2 <= "
                "r3 + r4); its box (links 0-5; rcx, rcy and the input pivot within +-5 of the points' mean) checked "
                "on the answer, not posed. Not posable: its objective in its last version, the sum of the distances "
                "(ours the sum of their squares, whose minimum its earlier version's root of the sum of squares "
                "shares; our answer's sum of distances is in the row), and its timing, the crank's angles from the "
                "frame line at one unknown total turn T times each point's share of the polygon's length (as coded "
                "the last point's share is 0), counter-clockwise, on the + root: ours passes the points in order at "
                "free angles, either way, on either assembly branch"),
    "eighteen points of a closed path, untimed, transmission 20 deg": Problem(
        EIGHTEEN, None, Constraints(crank=True, min_transmission=math.radians(20)),
        f"{ECA}: testTrajectories.jl case 12, bounds in experiments.jl",
        differs="the source asks only that the crank turns (Grashof's condition, its bound allowed): its best lies on "
                "that bound, where the coupler and rocker fold flat once a turn; ours also asks a transmission angle of "
                "at least 20 deg, a mechanism a designer would build"),
    # pylinkage 1.3.0: its README's example, and its path_generation docstring's
    "pylinkage README: four points, untimed": Problem([(0, 0), (1, 1), (2, 1), (3, 0)], None, Constraints(),
                                                      "pylinkage 1.3.0 README", pylinkage=True),
    "pylinkage docstring: four points, untimed": Problem([(0, 1), (1, 2), (2, 1.5), (3, 0)], None, Constraints(),
                                                         "pylinkage 1.3.0 path_generation docstring", pylinkage=True),
}


def source_model(vector, angles) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The sources' four-bar model in closed form: the fixed pivots, and the crank pin, the coupler's
    far joint and the coupler point at each crank angle.

    The model both sources share: input pivot at (x0, y0), frame of length r1 turned by θ0, crank r2 at
    θ2 from the frame line, coupler r3, rocker r4, the coupler point (rcx, rcy) in the coupler's frame,
    and the coupler's angle θ3 = 2·atan((−B + √(A² + B² − C²)) / (C − A)) with A = 2·r3·(r2·cos θ2 − r1),
    B = 2·r3·r2·sin θ2, C = r1² + r2² + r3² − r4² − 2·r1·r2·cos θ2.  ``vector`` is
    (r1, r2, r3, r4, rcx, rcy) with the frame at the origin along +x, or (…, θ0, x0, y0).

    Returns
    -------
    pivots : array (2, 2)
        The input pivot and the rocker's pivot.
    crank_pins, far_joints, coupler_points : arrays (N, 2)

    Examples
    --------
    >>> pivots, a, b, c = source_model([4, 1, 3, 3, 1.5, 0], [0.0])   # crank along the frame
    >>> b.round(6).tolist(), c.round(6).tolist()
    ([[2.5, 2.598076]], [[1.75, 1.299038]])
    """
    r1, r2, r3, r4, rcx, rcy = vector[:6]
    theta0, x0, y0 = vector[6:9] if len(vector) >= 9 else (0.0, 0.0, 0.0)
    t2 = np.asarray(angles, dtype=float)
    a = 2 * r3 * (r2 * np.cos(t2) - r1)
    b = 2 * r3 * r2 * np.sin(t2)
    c = r1 * r1 + r2 * r2 + r3 * r3 - r4 * r4 - 2 * r1 * r2 * np.cos(t2)
    t3 = 2 * np.arctan((-b + np.sqrt(a * a + b * b - c * c)) / (c - a))
    crank = np.stack((r2 * np.cos(t2), r2 * np.sin(t2)), axis=1)
    far = crank + r3 * np.stack((np.cos(t3), np.sin(t3)), axis=1)
    point = crank + np.stack((rcx * np.cos(t3) - rcy * np.sin(t3), rcx * np.sin(t3) + rcy * np.cos(t3)), axis=1)
    turn = np.array([[math.cos(theta0), -math.sin(theta0)], [math.sin(theta0), math.cos(theta0)]])
    pivots = np.array([[0.0, 0.0], [r1, 0.0]])
    return tuple(v @ turn.T + [x0, y0] for v in (pivots, crank, far, point))


def source_linkage(vector, angle: float) -> Linkage:
    """The sources' four-bar (:func:`source_model`) as a linkage of ours, posed at the crank angle
    ``angle`` from the frame line, its coupler point the tracer "P".

    Examples
    --------
    >>> np.round(source_linkage([4, 1, 3, 3, 1.5, 0], 0.0).tracers["P"][1], 6).tolist()
    [1.75, 1.299038]
    """
    pivots, crank, far, point = source_model(vector, [angle])
    return Linkage(FOUR_BAR, (0,), [pivots[0], pivots[1], crank[0], far[0]], tracers={"P": (2, tuple(point[0]))})


def recorded_by_motion(problem: Problem, record: dict) -> tuple[float, float]:
    """A source's recorded answer, posed at its first point by :func:`source_model` and moved to
    the others by the motion layer: its sum of squared errors against the problem's points, and the
    largest gap between the motion layer's coupler points and the closed form's."""
    vector = record["vector"]
    angles = np.array(vector[9:] if len(vector) > 9 else problem.inputs, dtype=float)
    theta0 = vector[6] if len(vector) >= 9 else 0.0
    point = source_model(vector, angles)[3]
    linkage = source_linkage(vector, angles[0])
    traced = np.array([assemble(linkage, theta0 + t).tracers["P"][1] for t in angles])
    residual = traced - np.array(problem.points, dtype=float)
    return float((residual ** 2).sum()), float(np.abs(traced - point).max())


def source_vector(linkage: Linkage, inputs) -> list[float]:
    """Our four-bar as the sources' vector (r1, r2, r3, r4, rcx, rcy, θ0, x0, y0, θ2 at each point):
    the inverse of :func:`source_model`, the crank's angles taken from the frame line in [0, 2π).

    Examples
    --------
    >>> np.round(source_vector(source_linkage([4, 1, 3, 3, 1.5, 0.5, 0.3, 2.0, -1.0], 0.5), [0.3 + 0.5]), 9).tolist()
    [4.0, 1.0, 3.0, 3.0, 1.5, 0.5, 0.3, 2.0, -1.0, 0.5]
    """
    input_pivot, far_pivot, pin, far = (np.asarray(p, dtype=float) for p in linkage.points)
    frame, coupler = far_pivot - input_pivot, far - pin
    theta0 = math.atan2(frame[1], frame[0]) % (2 * math.pi)
    along = coupler / np.linalg.norm(coupler)
    offset = np.asarray(linkage.tracers["P"][1], dtype=float) - pin
    lengths = [float(np.linalg.norm(v)) for v in (frame, pin - input_pivot, coupler, far - far_pivot)]
    return [*lengths, float(offset @ along), float(along[0] * offset[1] - along[1] * offset[0]), theta0,
            *input_pivot.tolist(), *((np.asarray(inputs, dtype=float) - theta0) % (2 * math.pi)).tolist()]


def as_the_source_states_it(problem: Problem, linkage: Linkage, inputs) -> dict:
    """Our answer judged as the source judges its own: its vector (:func:`source_vector`); the
    coupler points the sources' closed form (the ``+`` root) gives at its crank angles, their sum of
    squared distances to the points, and whether they are ours (the same branch); the sum of our
    points' plain distances ([ECA]'s objective for the eighteen points); the source's box; the crank's
    angles ascending within 0–2π from the frame line ([HNMED]) and within a turn from the first
    point's ([ECA]).

    Examples
    --------
    >>> problem = PROBLEMS["six points on a line, untimed, as stated"]
    >>> record = problem.records[0]["vector"]
    >>> said = as_the_source_states_it(problem, source_linkage(record, record[9]), np.add(record[9:], record[6]))
    >>> said["sum_squared_error"] < 1e-24, said["sources_branch"], said["within_bounds"], said["ascending_hnmed"]
    (True, True, True, True)
    """
    vector = source_vector(linkage, inputs)
    angles = np.array(vector[9:])
    points = np.array(problem.points, dtype=float)
    _, _, _, closed_form = source_model(vector, angles)
    mine = np.array([assemble(linkage, t).tracers["P"][1] for t in inputs])
    distances = np.hypot(*(closed_form - points).T)
    said = {"vector": vector, "sum_squared_error": float(distances @ distances),
            "sum_distances": float(np.hypot(*(mine - points).T).sum()),
            "sources_branch": bool(np.abs(closed_form - mine).max() <= 1e-9 * np.ptp(points, axis=0).max()),
            "ascending_hnmed": bool((np.diff(angles) > 0).all()),
            "ascending_eca": bool((np.diff((angles - angles[0]) % (2 * math.pi)) > 0).all())}
    if problem.bounds is not None:
        bound = problem.bounds
        cx, cy, half = bound["pivot"]
        said["within_bounds"] = bool(max(vector[:4]) <= bound["link"] and max(map(abs, vector[4:6])) <= bound["offset"]
                                     and abs(vector[7] - cx) <= half and abs(vector[8] - cy) <= half)
    return said


# The pylinkage side, run by its own interpreter: path_generation as documented, each solution moved
# through a whole turn of its crank by its own simulation, each target point's distance to that curve.
PYLINKAGE = r"""
import json, math, sys, time
import numpy as np
from pylinkage.synthesis import path_generation

job = json.loads(sys.argv[1])
start = time.process_time()
result = path_generation([tuple(p) for p in job["points"]])
seconds = time.process_time() - start
target = np.array(job["points"], dtype=float)
rows = []
for linkage in result.solutions:
    crank = next(c for c in linkage.components if type(c).__name__ == "Crank")
    names = [c.name for c in linkage.components]
    steps = job["steps"]
    curve = []
    for positions in linkage.step(iterations=steps, dt=2 * math.pi / (steps * abs(crank.angular_velocity))):
        if positions[names.index("P")][0] is None:
            break
        curve.append(positions[names.index("P")])
    c = np.array(curve, dtype=float)
    a, ab = c[:-1], c[1:] - c[:-1]
    w = target[:, None, :] - a[None]
    f = np.clip((w * ab[None]).sum(2) / np.maximum((ab ** 2).sum(1), 1e-300), 0, 1)
    rows.append({"full_turn": len(curve) == steps,
                 "errors": np.sqrt(((w - f[..., None] * ab[None]) ** 2).sum(2)).min(axis=1).tolist()})
print(json.dumps({"seconds": seconds, "solutions": rows}))
"""


def _pylinkage(python: str, points) -> dict | None:
    """pylinkage's answer to the points: CPU seconds, and its first and best solution's errors."""
    done = subprocess.run([python, "-c", PYLINKAGE, json.dumps({"points": points, "steps": 20000})],
                          capture_output=True, text=True, timeout=1800)
    if done.returncode != 0:
        print(f"pylinkage failed: {done.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
        return None
    answer = json.loads(done.stdout)
    errors = [np.array(s["errors"]) for s in answer["solutions"]]
    if not errors:
        return {"pylinkage_cpu_seconds": round(answer["seconds"], 2), "pylinkage_solutions": 0}
    best = min(errors, key=lambda e: float(e.max()))
    size = float(np.hypot(*np.ptp(np.array(points, dtype=float), axis=0)))
    return {"pylinkage_cpu_seconds": round(answer["seconds"], 2), "pylinkage_solutions": len(errors),
            "pylinkage_first_error_max": float(errors[0].max()),
            "pylinkage_first_sum_squared_error": float(errors[0] @ errors[0]),
            "pylinkage_best_error_max": float(best.max()), "pylinkage_best_sum_squared_error": float(best @ best),
            "pylinkage_best_relative_max": float(best.max()) / size}


def random_slider_crank(seed: int) -> Linkage:
    """An offset slider-crank whose crank turns fully, with a point P on its rod, its dimensions drawn
    at random (crank 0.4–0.8, rod 2–3, offset within ±0.3, the point near the rod)."""
    rng = np.random.default_rng(100 + seed)
    while True:
        crank, rod, offset = rng.uniform(0.4, 0.8), rng.uniform(2.0, 3.0), rng.uniform(-0.3, 0.3)
        phi = rng.uniform(0, 2 * math.pi)
        pin = crank * np.array([math.cos(phi), math.sin(phi)])
        block = np.array([pin[0] + math.sqrt(rod * rod - (offset - pin[1]) ** 2), offset])
        at = pin + (block - pin) * rng.uniform(0.2, 0.8) + rng.normal(size=2) * 0.5
        linkage = Linkage(SLIDER_CRANK, (0,), [[0, 0], block, pin, block], {1: (1.0, 0.0)},
                          tracers={"P": (2, tuple(at))})
        if motion_range(linkage).full_rotation:
            return linkage


def reliability(seeds: range, budget: float, samples: int | None = None) -> None:
    """A row per seed and case: the relative error the search reaches from no guess, and its CPU time
    (with ``samples``, the sampled starts take that many crank poses instead of their default)."""
    starts = sampled_starts if samples is None else functools.partial(sampled_starts, samples=samples)
    for seed in seeds:
        rocker = random_crank_rocker(seed)
        slider = random_slider_crank(seed)
        timed = sweep(slider, steps=8, stop=float(slider.pose_inputs[0]) + math.radians(300))
        cases = {"crank-rocker, 10 points, untimed": (FOUR_BAR, PathTarget(sweep(rocker, steps=11).tracers["P"][:10])),
                 "slider-crank, 8 points, timed": (SLIDER_CRANK, PathTarget(timed.tracers["P"], timed.inputs[:, 0]))}
        for case, (mechanism, target) in cases.items():
            result = synthesize(mechanism, target, budget=budget, seed=seed, starts=starts)
            print(json.dumps({"case": case, "seed": seed, "relative_max": result.relative_max,
                              "cpu_seconds": round(result.seconds, 1), "evaluations": result.evaluations,
                              "met": result.met} | ({} if samples is None else {"samples": samples})), flush=True)


def seed_range(text: str) -> range:
    """Seeds "A..B" (or one seed "A") for --reliability."""
    lo, _, hi = text.partition("..")
    try:
        seeds = range(int(lo), int(hi or lo) + 1)
    except ValueError:
        raise argparse.ArgumentTypeError(f"seeds are A..B or A, whole numbers, not {text!r}") from None
    if not seeds:
        raise argparse.ArgumentTypeError(f"the seed range {text!r} is empty")
    return seeds


def whole(text: str) -> int:
    """A whole number of at least 1, for --samples."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a whole number of at least 1, not {text!r}")
    return value


def positive(text: str) -> float:
    """A positive finite number, for --budget and --reach."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"must be a positive number, not {text!r}")
    return value


def run_problem(name: str, *, budget: float, seed: int = 0, reach: float | None = None) -> dict:
    """One row: our synthesis of the problem as the command line runs it (the sampled starts
    included), its errors and CPU time, and the source's record beside it where there is one."""
    problem = PROBLEMS[name]
    target = PathTarget(np.array(problem.points, dtype=float),
                        None if problem.inputs is None else np.array(problem.inputs, dtype=float))
    constraints = replace(problem.constraints, reach=reach)
    result = synthesize(FOUR_BAR, target, constraints=constraints, budget=budget, seed=seed,
                        underdetermined=True, starts=sampled_starts)
    row = {"problem": name, "seed": seed, "budget": budget, "points": len(problem.points),
           "sum_squared_error": float(np.sum(result.errors ** 2)),
           "error_max": result.error_max, "error_rms": result.error_rms, "relative_max": result.relative_max,
           "cpu_seconds": round(result.seconds, 1), "evaluations": result.evaluations, "met": result.met,
           "constraints": result.constraints, "source": problem.source}
    if problem.records:
        row["records"] = [{"name": record["name"], "method": record["method"], "where": record["where"],
                           "recorded": record["sum_squared_error"], "recomputed": recorded_by_motion(problem, record)[0]}
                          for record in problem.records]
    if problem.bounds is not None:
        row["as_the_source_judges"] = as_the_source_states_it(problem, result.linkage, result.inputs)
    if problem.differs is not None:
        row["differs"] = problem.differs
    row["linkage"] = result.linkage.to_dict()
    return row


#: a reliability case counts as found when the answer meets the points to this share of their size
FOUND = 1e-6


def _constraints_said(row: dict) -> str:
    failed = [name for name, c in row["constraints"].items() if not c["met"]]
    return "met" if not failed else "**not met**: " + ", ".join(failed)


def _records_said(row: dict) -> str:
    """The sources' records of a problem's row as our motion layer recomputes them: one in full, several
    each to two digits with its name (rows logged before there could be several hold one, unnamed)."""
    if "recorded_recomputed" in row:
        return f"{row['recorded_recomputed']:.8g}"
    records = row.get("records", [])
    if len(records) == 1:
        return f"{records[0]['recomputed']:.8g}"
    return "; ".join(f"{r['recomputed']:.2g} {r['name']}" for r in records) or "—"


def table(rows: list[tuple[dict, str]]) -> str:
    """The Markdown tables of (row, the log it came from) pairs: a line per problem (our sum of squared errors beside
    the source's record as our motion layer recomputes it, where one is recorded), and a line per
    reliability case (the seeds whose answer meets the points to :data:`FOUND` of their size).

    Examples
    --------
    >>> row = {"problem": "p", "sum_squared_error": 2.5e-4, "error_max": 0.01, "relative_max": 0.005,
    ...        "evaluations": 1234, "cpu_seconds": 30.0, "constraints": {"crank": {"met": True}},
    ...        "recorded_recomputed": 2.56e-4}
    >>> print(table([(row, "x.jsonl")]).splitlines()[2])
    | p | 0.00025 | 0.000256 | 0.01 (0.005) | 1 234 | 30.0 | met | x.jsonl |
    """
    out = []
    problems = [(r, log) for r, log in rows if "problem" in r]
    if problems:
        out += ["| problem | ours: sum of squares | recorded, recomputed by our motion layer | ours: largest error "
                "(relative) | candidates | CPU s | constraints | rows |", "|---|---|---|---|---|---|---|---|"]
        for r, log in problems:
            recorded = _records_said(r)
            candidates = f"{r['evaluations']:,}".replace(",", " ")
            named = r["problem"] + (f", seed {r['seed']}" if "seed" in r else "")  # (rows logged before 29 Nov, dim9b: none)
            out.append(f"| {named} | {r['sum_squared_error']:.8g} | {recorded} | {r['error_max']:.2g} "
                       f"({r['relative_max']:.2g}) | {candidates} | {r['cpu_seconds']:.1f} | {_constraints_said(r)} | {log} |")
    cases = {}
    for r, log in rows:
        if "case" in r:  # (a case's seeds are counted per log: each log is one run of them)
            cases.setdefault((r["case"], log), []).append(r)
    if cases:
        if out:
            out.append("")
        out += ["| case | seeds | found | CPU s of the found (median) | misses (relative max) | rows |",
                "|---|---|---|---|---|---|"]
        for (case, log), runs in cases.items():
            found = [r for r in runs if r["relative_max"] <= FOUND and r["met"]]
            seconds = sorted(r["cpu_seconds"] for r in found)
            spread = (f"{seconds[0]:.1f}–{seconds[-1]:.1f} ({float(np.median(seconds)):.1f})" if seconds else "—")
            misses = ", ".join(f"seed {r['seed']}: {r['relative_max']:.2g}" + ("" if r["met"] else " (a constraint failed)")
                               for r in runs if r not in found) or "none"
            seeds = sorted(r["seed"] for r in runs)
            out.append(f"| {case} | {seeds[0]}–{seeds[-1]} | {len(found)} of {len(runs)} | {spread} | {misses} | {log} |")
    return "\n".join(out)


def read_rows(path: str) -> list[dict]:
    """The JSON rows of a log (one per line; blank lines skipped); exits with status 2 and one sentence on
    stderr where the file cannot be read or holds no rows of this benchmark."""
    try:
        with open(path) as fh:
            rows = [json.loads(line) for line in fh if line.strip()]
        if all(isinstance(row, dict) and ("problem" in row or "case" in row) for row in rows) and rows:
            return rows
        said = f"{path} holds no rows of this benchmark (a problem's or a reliability case's JSON object a line)"
    except OSError as exc:
        said = f"cannot read {path}: {exc.strerror}"
    except json.JSONDecodeError as exc:
        said = f"{path} is not JSON lines ({exc.msg} at line {exc.lineno})"
    print(f"bench_dimension: {said}", file=sys.stderr)
    raise SystemExit(2)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--budget", type=positive, default=60.0, help="CPU seconds per problem (default 60)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--only", choices=sorted(PROBLEMS), help="run this problem alone")
    parser.add_argument("--reach", type=positive, help="the search box in target sizes (default 4)")
    parser.add_argument("--pylinkage-python", default=DEFAULT_PYLINKAGE,
                        help=f"pylinkage's interpreter (default {DEFAULT_PYLINKAGE}; left out if absent)")
    parser.add_argument("--reliability", metavar="A..B", type=seed_range,
                        help="the reliability runs for these seeds instead")
    parser.add_argument("--samples", type=whole, metavar="N",
                        help="with --reliability: the crank poses the sampled starts take (default theirs, 100)")
    parser.add_argument("--table", metavar="LOG", nargs="+",
                        help="print the Markdown tables of these logs' rows instead of running anything")
    args = parser.parse_args()
    if args.samples is not None and args.reliability is None:
        parser.error("--samples sets the reliability runs' sampled starts: give --reliability too")
    if args.table is not None:
        if args.reliability is not None or args.only is not None or args.reach is not None:
            parser.error("--table reads logs and runs nothing: --reliability, --only and --reach do not apply")
        emit(table([(row, Path(path).name) for path in args.table for row in read_rows(path)]))
        return
    if args.reliability is not None:
        if args.only is not None or args.reach is not None:
            parser.error("--reliability runs its own cases in the default box: --only and --reach do not apply")
        reliability(args.reliability, args.budget, args.samples)
        return
    have_pylinkage = Path(args.pylinkage_python).exists()
    for name, problem in PROBLEMS.items():
        if args.only is not None and name != args.only:
            continue
        row = run_problem(name, budget=args.budget, seed=args.seed, reach=args.reach)
        if problem.pylinkage and have_pylinkage:
            row.update(_pylinkage(args.pylinkage_python, problem.points) or {})
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
