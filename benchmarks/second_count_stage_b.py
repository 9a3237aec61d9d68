"""Stage B of the two counts of issue 41, unit by unit and alternating, in CPU seconds (time.process_time).

``python benchmarks/second_count_stage_b.py 16``: every unit of the 1-DOF chains of that many links
is built once by stage A, then counted by the first count (``stage_b.count_realised``: the tight
programme in maximum-adjacency order) and by the second (``stage_b.count_reversed``, ``--method
tight-reverse``), the order of the two swapped from unit to unit and between two rounds, so that
the load of a shared machine falls on both alike.  Prints each round's totals and the dearest units.
"""
import sys, time
import numpy as np
import synth
from synth.synthesis import stage_a, stage_b
links = int(sys.argv[1])
t = time.process_time()
units = [u for u in synth.plan_units(dof=1, links=links, workers=1) if u.contracted is not None]
print("stage A", round(time.process_time() - t, 1), "CPU s,", len(units), "units", flush=True)
for u in units[:50]:  # compile / warm both
    a = (u.code, u.contracted, u.conventions); stage_b.count_realised(*a); stage_b.count_reversed(*a)
first = second = 0.0; n1 = n2 = 0; worst = []
for rnd in range(2):
    for i, u in enumerate(units):
        a = (u.code, u.contracted, u.conventions)
        order = (0, 1) if (i + rnd) % 2 == 0 else (1, 0)
        for m in order:
            t = time.process_time()
            x = stage_b.count_realised(*a) if m == 0 else stage_b.count_reversed(*a)
            dt = time.process_time() - t
            if m == 0: first += dt; n1 += x
            else: second += dt; n2 += x
            if m == 1: worst.append((dt, u.key))
    print(f"round {rnd}: first {first:.2f} CPU s, second {second:.2f} CPU s, chains {n1} {n2}", flush=True)
print("dearest second-count units:", sorted(worst)[-5:])
