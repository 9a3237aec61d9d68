"""synth: structural synthesis of mechanisms after Pozhbelko's universal theory of structure.

Chains of links and joints — revolute, prismatic and gear-mesh joints, multiple joints, loops in
any motion space h = 2 … 6, open chains — are counted (number synthesis: standard codes from the
counting equations, CP-SAT), built (type synthesis: every non-isomorphic chain that passes the
exact sub-chain test, nauty certificates), turned into mechanisms, analysed and repaired, stored in
SQLite atlases and drawn.  The package is laid out by pipeline stage:

=============  ==========================================================================
``structure``  the core types (:class:`Code`, :class:`Chain`, :class:`Mechanism`,
               :class:`ChainQuery`), joint kinds and the exact sub-chain test
``synthesis``  number synthesis and type synthesis (stages A and B), prismatic assignments, size estimates
``execution``  running units inline, on a pool or on Dask; checkpoints; progress; sizes and times in words
``atlas``      grid files, SQLite atlases, the ``--where`` language, the static web site
``analysis``   analysis of codes and chains, directed repair, identification, atlas comparison
``exchange``   chains read and written in other tools' formats (GraphML, GML, DOT, edge lists, matrices)
``gears``      gear trains: the planetary-train atlas, speed ratios, tooth design
``motion``     dimensioned mechanisms moved: positions, velocities, ranges, dead positions
``draw``       drawings of chains and mechanisms
=============  ==========================================================================

The names below are the public interface (the command line uses nothing else); they are loaded
on first use, so ``import synth`` (and a balancing scene run through ``mechsynth``) loads neither
OR-Tools, nauty nor networkx.

Example
-------
>>> import synth
>>> [str(c) for c in synth.number_synthesis(1, loops=2)]
['42/0', '51/1', '60/2']
>>> synth.count_chains(1, 8, workers=1)["count"]
16
>>> synth.analyze_chain("0=1 1=2 2=0 2-3 3-4 4-0").dof   # Task 3: a wedge loop and a lever loop
1
"""

from ._lazy import lazy_exports

from .errors import *  # noqa: F401,F403
from .errors import __all__ as _errors_all

#: public name -> module (relative to synth) that defines it
_WHERE = {
    # core types, joint kinds, the exact sub-chain test
    "Code": ".structure.code", "Chain": ".structure.chain", "Mechanism": ".structure.chain",
    "JOINT_KINDS": ".structure.joints", "JointKind": ".structure.joints", "chain_id": ".structure.chain",
    "ChainQuery": ".structure.query", "parse_range": ".structure.query", "parse_requirements": ".structure.query",
    "check_motion_space": ".structure._params", "Require": ".schema",
    "structural_mobility": ".structure.kinds", "generic_mobility": ".structure.kinds",
    "redundant_constraints": ".structure.kinds", "idle_joints": ".structure.kinds", "wedge_loops": ".structure.kinds",
    "prismatic_roles": ".structure.kinds", "lever_analogue": ".structure.kinds",
    "SubchainReport": ".structure.subchains", "check_subchains": ".structure.subchains",
    "subchain_mobility": ".structure.subchains",
    # a chain fixed by a link: a mechanism, a truss, or a chain whose count misleads, and the words for each
    "count_defect": ".structure.trusses", "CountDefect": ".structure.trusses",
    "truss_has_no_input": ".structure.trusses", "on_a_frame": ".structure.trusses", "TRUSS_NOTE": ".structure.trusses",
    "mechanisms_summary": ".structure.trusses", "not_a_mechanisms_chain": ".structure.trusses",
    # number and type synthesis, mechanisms
    "number_synthesis": ".synthesis.number_synthesis", "iter_codes": ".synthesis.number_synthesis",
    "MAX_CODES": ".synthesis.number_synthesis", "CodeQuery": ".synthesis.number_synthesis",
    "Conventions": ".synthesis.type_synthesis", "Unit": ".synthesis.type_synthesis", "Counts": ".synthesis.type_synthesis",
    "type_synthesis": ".synthesis.type_synthesis", "count_chains": ".synthesis.type_synthesis",
    "count_mechanisms": ".synthesis.type_synthesis", "mechanisms": ".synthesis.type_synthesis",
    "mechanisms_of": ".synthesis.type_synthesis", "plan_codes": ".synthesis.type_synthesis",
    "plan_units": ".synthesis.type_synthesis", "plan_many": ".synthesis.type_synthesis",
    "run_unit": ".synthesis.type_synthesis", "count_unit": ".synthesis.type_synthesis",
    "count_by_code": ".synthesis.type_synthesis",
    "prismatic_variants": ".synthesis.variants", "variants_of": ".synthesis.variants",
    "split_classes": ".synthesis.classes", "h_beside_classes": ".synthesis.classes", "class_variants": ".synthesis.classes",
    "heterogeneous_synthesis": ".synthesis.classes", "skeleton_query": ".synthesis.classes",
    "size_note": ".synthesis.classes", "class_loops": ".structure.kinds",
    # how large a query is
    "Estimate": ".synthesis.estimate", "estimate": ".synthesis.estimate", "size_check": ".synthesis.estimate",
    "worth_sizing": ".synthesis.estimate", "TABLE_ROWS": ".synthesis.estimate",
    "describe_estimate": ".synthesis.estimate", "NOTE_SECONDS": ".synthesis.estimate",
    "time_to_go_from": ".synthesis.estimate",
    "describe_seconds": ".execution.sizes", "magnitude": ".execution.sizes",
    # a long run's progress (a bar on a terminal, a line a minute in a log) and its checkpoint read back
    "Progress": ".execution.progress", "Every": ".execution.progress",
    "read_checkpoint": ".execution.checkpoint", "CheckpointState": ".execution.checkpoint",
    "PLAN_FORMAT": ".execution.checkpoint", "count_identity": ".synthesis.type_synthesis", "plan_jobs": ".synthesis.type_synthesis",
    # analysis and repair
    "Analysis": ".analysis.codes", "analyze": ".analysis.codes", "mobility": ".analysis.codes",
    "not_for_the_subject": ".analysis.codes",
    "ChainAnalysis": ".analysis.chains", "analyze_chain": ".analysis.chains",
    "chain_repairs": ".analysis.repair", "code_repairs": ".analysis.repair", "Repair": ".analysis.repair",
    "ChainRepair": ".analysis.repair",
    # the source's planetary layout through its lever analogue
    "planetary_row": ".gears.planetary", "planetary_rows": ".gears.planetary",
    "planetary_table": ".gears.planetary",
    # identifying any chain, comparing atlases
    "identify": ".exchange.identify", "identify_all": ".exchange.identify", "compare": ".analysis.compare",
    # motion of dimensioned mechanisms
    "Linkage": ".motion._linkage", "read_linkage": ".motion._linkage", "linkage_from_pose": ".motion._pose",
    "Motion": ".motion._sweep", "MotionRange": ".motion._sweep", "sweep": ".motion._sweep",
    "sweep_grid": ".motion._sweep", "motion_range": ".motion._sweep", "refine_extreme": ".motion._sweep",
    # drawings of moving mechanisms (chains, mechanisms and gear trains: synth.draw)
    "linkage_from_layout": ".motion_draw", "draw_motion": ".motion_draw", "animate_motion": ".motion_draw",
    "draw_linkage": ".motion_draw", "draw_motion_sheet": ".motion_draw",
}

__all__ = [*_WHERE, *_errors_all]


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)

# the facade stands above every floor: it names the drawings the values at the ground show in a notebook
from .display import register_drawing as _register_drawing  # noqa: E402

for _kind in ("Chain", "Mechanism"):
    _register_drawing(_kind, "synth.draw:svg")
_register_drawing("Linkage", "synth.motion_draw:linkage_svg")  # a dimensioned mechanism in its pose
