"""The final polish meets the half circle's record ([HCDJ] Case 4): polished from the record, with the row's
constraints (the crank the shortest link and turning, links at most 50), ours ends at or below its error,
on the bound of 50 and on Grashof's bound — re-checked by the motion layer and by the source's closed form —
whether the record is posed at its first point or beyond the dead position at θ2 = 0 (the points lie at
30°–180°), from where the dyads must close across that dead position to reach the points.

Before the link-length bound and the crank's turn were held as inequalities of the final polish (and its
gradient taken by central differences), the same polish ended at 1.2163819, 1.4e-4 above the record; before
the final polish posed the answer at its first point, from the pose at −10° it ended at 1.2163974."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from synth.dimension import PathTarget, synthesize
from synth.motion import motion_range

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_dimension import HALF_CIRCLE_RECORDS, PROBLEMS, as_the_source_states_it, source_linkage  # noqa: E402

ROW = PROBLEMS["six timed points on a half circle, as stated"]
#: the record's error as the source prints it (Case4/Records_HCDJ_Case4.txt)
PRINTED = 1.2162122


@pytest.mark.parametrize("pose", [ROW.inputs[0], math.radians(-10.0)],
                         ids=["at the first point", "beyond the dead position"])
def test_the_polish_from_the_record_reaches_its_error_on_both_bounds(pose):
    vector = list(HALF_CIRCLE_RECORDS[0]["vector"])
    vector[0] += 8.0e-7  # as printed the record exceeds Grashof's condition by 8.0e-7: its crank would not turn
    start = source_linkage(vector, pose)  # (the crank at the angle pose from the frame line)
    target = PathTarget(np.array(ROW.points, dtype=float), np.array(ROW.inputs, dtype=float))
    result = synthesize(start, target, constraints=ROW.constraints, polish_only=True, budget=30, underdetermined=True)
    assert result.met, result.failed()
    ours = float(np.sum(result.errors ** 2))
    assert ours <= PRINTED
    assert motion_range(result.linkage).full_rotation
    # the source's own closed form at our crank angles: the same points (its branch), the same error, its box
    said = as_the_source_states_it(ROW, result.linkage, result.inputs)
    assert said["sources_branch"] and said["within_bounds"]
    assert abs(said["sum_squared_error"] - ours) <= 1e-9 * ours
    r1, r2, r3, r4 = said["vector"][:4]
    shortest, longest = min(r1, r2, r3, r4), max(r1, r2, r3, r4)
    assert shortest == r2 and longest <= 50.0 * (1 + 1e-9)
    assert longest >= 50.0 * (1 - 1e-8)  # on the bound, not the search's margin of 1e-4 inside it
    grashof = r1 + r2 + r3 + r4 - 2 * (shortest + longest)  # p + q - (s + l): >= 0 where the crank turns
    assert -1e-9 * longest <= grashof <= 1e-6 * longest  # on Grashof's bound, as the record
