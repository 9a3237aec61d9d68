#!/usr/bin/env python3
"""Mutation testing of the core with mutmut: one module at a time, each with its fast tests.

Usage (from the repository root; needs ``pip install '.[mutation]'`` or ``pip install mutmut``)::

    nice -n 19 python tools/mutation.py                 # every module below
    nice -n 19 python tools/mutation.py mobility chain  # some of them
    python tools/mutation.py --list                     # the modules and their tests
    nice -n 19 python tools/mutation.py --write-docs    # and put the scores in docs/mutation.md

Each module is mutated in its own copy of the working tree under ``--work``
(default ``/tmp/mechsynth-mutation``), never in the checkout; the copy gets a
``[tool.mutmut]`` table that mutates only that module and runs only its test
subset, so a run stays within reach of 2 cores.  A mutant is *killed* when a
test fails; *survived* and *no tests* count against the module.  Survivors that
cannot change any result (equivalent mutants) are listed, with the reason, in
``tools/mutation_equivalent.toml`` and matched by the changed source line, not by
mutmut's numbering, so the list survives edits elsewhere in the file.

Score per module = killed / (total − equivalent); a mutant that makes a test hang (mutmut's
timeout) counts as killed.  Goal: at least 90 %.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

#: the slowest cases of the synthesis tests, left out of the mutation runs (minutes per surviving mutant)
_HEAVY = ("not W2-n9 and not W1-n8-v4 and not W3-n8-v2 and not 6856 and not 12-938 and not 3-10-98 "
          "and not ctrl_c and not twelve")
#: a module's docstring examples in the balance and synth suites (the module's name and "]" follow)
_BALANCE_DOC = "tests/balance/test_docstrings.py::test_docstring_examples["
_SYNTH_DOC = "tests/test_doctests.py::test_docstring_examples["
#: the tests of reading and writing chains (not the 10-link atlas round trip: a minute per mutant)
_IDENTIFY_LIGHT = "not row[10] and not a_large_code"
_EXCHANGE = ["tests/exchange/test_formats.py", "tests/exchange/test_dot_strength.py", "tests/exchange/test_graphs_strength.py",
             "tests/exchange/test_every_property_round_trips.py", "tests/exchange/test_identify_source_strength.py",
             "tests/exchange/test_entry_strength.py", "tests/exchange/test_lists_strength.py",
             "tests/exchange/test_matrices_strength.py", "tests/exchange/test_read_write_strength.py",
             "tests/exchange/test_identify_round_trip.py", "tests/cli/test_chain_or_counts.py",
             "tests/cli/test_identify_commands.py", "-k", _IDENTIFY_LIGHT]
#: the tests of the spring fits: every method, device and refusal (not the timing and model-file cases)
_FIT = ["tests/balance/test_fit_driver_strength.py", "tests/balance/test_fit_result_strength.py",
        "tests/balance/test_fit_vs_oracle.py", "tests/balance/test_fit.py", "tests/balance/test_devices.py",
        "tests/balance/test_slider_devices.py", "-k", "not under_100_ms and not model_matches"]
#: the motion tests that judge some motion modules only (the sweep's link poses and grids, the linkage's files)
_MOTION_MORE = {"_sweep": ("tests/motion/test_link_poses.py", "tests/motion/test_grid.py", "tests/motion/test_sweep_strength.py"),
                "__init__": ("tests/motion/test_link_poses.py", "tests/motion/test_grid.py")}
#: the atlas tests without the module fixtures of test_atlas.py (the 201 units of grid_small.toml) and Dask
_ATLAS_LIGHT = ("not per_cell and not mechanism_counts_one_dof and not rerun_does_nothing and not sigkill and not dask "
                "and not where_filters and not summary_table and not unreachable")
#: module key -> (file to mutate, test selection); the tests are the fast ones that judge it
MODULES: dict[str, tuple[str, list[str]]] = {
    "mobility": ("synth/structure/subchains.py", ["tests/structure/test_subchains_vs_oracle.py",
                                       "tests/test_doctests.py::test_docstring_examples[synth.structure.subchains]"]),
    "chain": ("synth/structure/chain.py", ["tests/synthesis/test_mechanisms_vs_oracle.py", "tests/structure/test_chain_vs_oracle.py",
                                 "tests/test_doctests.py::test_docstring_examples[synth.structure.chain]"]),
    "type_synthesis": ("synth/synthesis/type_synthesis.py", ["tests/synthesis/test_mechanisms_vs_oracle.py", "tests/synthesis/test_units.py",
                                                    "tests/synthesis/test_chains_vs_oracle.py", "tests/synthesis/test_type_synthesis.py",
                                                    # counts with checkpoints and progress; the query refusals
                                                    # (not the Dask cluster tests: a mutant there waits for
                                                    # mutmut's timeout with both cores idle)
                                                    "tests/execution/test_large_queries.py", "tests/cli/test_contract.py",
                                                    "tests/cli/test_query_refusals.py",
                                                    "tests/test_doctests.py::test_docstring_examples[synth.synthesis.type_synthesis]",
                                                    "-k", _HEAVY + " and not dask"]),
    # stages A and B on every path (search and listing, compiled kernels, CP-SAT models) against the oracle's
    # chains of at most 8 links (not the engine-wide test files: minutes per mutant, the same paths)
    "stage_a": ("synth/synthesis/stage_a.py", ["tests/synthesis/test_stages_strength.py",
                                               _SYNTH_DOC + "synth.synthesis.stage_a]"]),
    "stage_b": ("synth/synthesis/stage_b.py", ["tests/synthesis/test_stages_strength.py",
                                               _SYNTH_DOC + "synth.synthesis.stage_b]"]),
    "number_synthesis": ("synth/synthesis/number_synthesis.py", ["tests/synthesis/test_number_synthesis_vs_oracle.py",
                                                        "tests/synthesis/test_number_synthesis.py",
                                                        "-k", "not test_agrees_with_brute_force["]),
    # joint kinds: counts, generic mobility, idle joints against the R/P oracle (its fast cases)
    "kinds": ("synth/structure/kinds.py", ["tests/structure/test_kinds_vs_oracle.py",
                                           "tests/synthesis/test_joint_kinds_round_trip.py",
                                           "tests/test_doctests.py::test_docstring_examples[synth.structure.kinds]"]),
    # (the -k keeps the fast cases of the first two files; the doctests and variants_vs_oracle are all in)
    "variants": ("synth/synthesis/variants.py", ["tests/synthesis/test_rp_chains_vs_oracle.py",
                                                 "tests/synthesis/test_prismatic_vs_oracle.py",
                                                 "tests/synthesis/test_variants_vs_oracle.py",
                                                 "tests/test_doctests.py::test_docstring_examples[synth.synthesis.variants]",
                                                 "-k", "(counts_by_prismatic_pairs and not 7) or the_same_chains or "
                                                       "variant_counts or wedge_lever or all_prismatic or refusal or "
                                                       "docstring_examples or variants_vs_oracle"]),
    "springs": ("balance/devices/springs.py", ["tests/balance/test_springs.py", "tests/balance/test_fit_vs_oracle.py"]),
    # the fit's problem: errors, scale, limits and refusals against values found without it (4 CPU s clean; the
    # fits of test_fit.py and test_fit_vs_oracle.py took 14 minutes clean on the loaded machine)
    "fit": ("balance/devices/fit/problem.py", ["tests/balance/test_fit_problem_strength.py",
                                               "tests/balance/test_fit_driver_strength.py",
                                               _BALANCE_DOC + "balance.devices.fit.problem]"]),
    "countermass": ("balance/devices/countermass.py", ["tests/balance/test_countermass.py",
                                               "tests/balance/test_countermass_vs_oracle.py"]),
    # the counterweights alone and in `balance arm` (not test_compare.py: its fixtures solve two arms,
    # half a minute per mutant; its counterweight test has a lighter twin in test_compare_strength.py)
    "counterweights": ("balance/devices/counterweights.py", [
        "tests/balance/test_compare_strength.py", "tests/balance/test_arm.py::test_counterweights_balance_example1",
        "tests/balance/test_arm.py::test_counterweights_refused_for_prismatic",
        _BALANCE_DOC + "balance.devices.counterweights]"]),
    "potential": ("balance/model/potential.py", ["tests/balance/test_potential_strength.py",
                                                 "tests/balance/test_arm.py",
                                                 _BALANCE_DOC + "balance.model.potential]"]),
    # (of test_compare.py only the small arms: its module fixtures solve example 1 and the UR5e, 20 minutes clean)
    "compare": ("balance/problems/compare.py", ["tests/balance/test_compare_strength.py", *(
        "tests/balance/test_compare.py::test_" + name for name in (
            "exact_springs_on_a_planar_two_link_arm_leave_nothing", "the_payload_is_a_range_and_the_devices_are_tuned_for_its_middle",
            "bad_input_one_sentence", "an_arm_without_gravity_torque_has_nothing_to_balance",
            "arm_payload_table_for_toml_and_urdf_arms", "one_reader_of_compare_tables_with_the_command_lines_options_over_them",
            "the_ur5e_urdf_is_written_from_the_published_numbers")),
        _BALANCE_DOC + "balance.problems.compare]"]),
    "dynamics": ("balance/devices/dynamics.py", ["tests/balance/test_dynamics.py", "tests/balance/test_dynamics_strength.py",
                                                 _BALANCE_DOC + "balance.devices.dynamics]"]),
    "pantograph": ("balance/model/pantograph.py", ["tests/balance/test_pantograph.py",
                                                   _BALANCE_DOC + "balance.model.pantograph]"]),
    "extremes": ("balance/extremes.py", ["tests/balance/test_extremes_strength.py", "tests/balance/test_extremes.py",
                                         _BALANCE_DOC + "balance.extremes]"]),
    "budget": ("balance/budget.py", ["tests/balance/test_budget.py", _BALANCE_DOC + "balance.budget]"]),
    "code": ("synth/structure/code.py", ["tests/structure/test_code.py", "tests/structure/test_code_strength.py",
                                         _SYNTH_DOC + "synth.structure.code]"]),
    "query": ("synth/structure/query.py", ["tests/structure/test_query_strength.py",
                                           "tests/cli/test_query_refusals.py", _SYNTH_DOC + "synth.structure.query]"]),
    # every --where field and operator against the rows' own values on a small atlas (not test_atlas.py: its
    # module fixture runs a grid of 201 units, a minute per mutant)
    "atlas_queries": ("synth/atlas/queries.py", ["tests/atlas/test_queries_strength.py", _SYNTH_DOC + "synth.atlas.queries]"]),
    # reading and writing chains: every format's round trip, identify's, the chain given on the command line
    **{key: (f"synth/exchange/{name}.py", _EXCHANGE + [_SYNTH_DOC + f"synth.exchange.{name}]".replace(".__init__", "")])
       for key, name in (("exchange", "__init__"), ("exchange_dot", "_dot"), ("exchange_entry", "_entry"),
                         ("exchange_graphs", "_graphs"), ("exchange_lists", "_lists"),
                         ("exchange_matrices", "_matrices"), ("exchange_identify", "identify"))},
    # a chain's id, code, place in its listing (sized first), symmetry and classical names
    "identify": ("synth/analysis/identify.py", ["tests/analysis/test_identify_strength.py",
                                                "tests/exchange/test_identify_round_trip.py",
                                                "tests/cli/test_identify_commands.py",
                                                _SYNTH_DOC + "synth.analysis.identify]", "-k", _IDENTIFY_LIGHT]),
    # analyze of a code or counts: every formula by hand, the defect's advice, the seeds' worked examples
    "analysis_codes": ("synth/analysis/codes.py", ["tests/analysis/test_codes_strength.py",
                                                   "tests/analysis/test_worked_examples.py",
                                                   _SYNTH_DOC + "synth.analysis.codes]"]),
    # analyze of a chain: every field and advice by hand, the lever analogue of gear chains, loop classes
    "analysis_chains": ("synth/analysis/chains.py", ["tests/analysis/test_chains_strength.py",
                                                     "tests/gears/test_lever_analogue_vs_oracle.py",
                                                     "tests/cli/test_chain_or_counts.py", "tests/cli/test_loop_classes.py",
                                                     _SYNTH_DOC + "synth.analysis.chains]"]),
    # classical names of chains and inversions, checked against their definitions on renumbered chains
    "analysis_classical": ("synth/analysis/classical.py", ["tests/analysis/test_classical.py",
                                                           _SYNTH_DOC + "synth.analysis.classical]"]),
    # the repairs of a chain or code, each checked on a chain; the redundant meshes of gear chains
    "analysis_repair": ("synth/analysis/repair.py", ["tests/analysis/test_repair_strength.py", "tests/analysis/test_repair_vs_oracle.py",
                                                     "tests/gears/test_lever_analogue_vs_oracle.py",
                                                     _SYNTH_DOC + "synth.analysis.repair]"]),
    # a set of chains compared with a listing: matched, missing, extra and why
    "analysis_compare": ("synth/analysis/compare.py", ["tests/analysis/test_compare_strength.py", "tests/analysis/test_compare.py",
                                                       "tests/exchange/test_every_property_round_trips.py",
                                                       _SYNTH_DOC + "synth.analysis.compare]"]),
    # linkages moved: poses, dyads, the system of loop equations, the linkage, its sweeps (closed forms, the
    # independent solver, branches, rates, link poses, a grid); the kernel is compiled (numba): no mutant
    **{f"motion_{name.strip('_')}": (f"synth/motion/{name}.py", [
        "tests/motion/test_errors.py", "tests/motion/test_closed_forms.py", "tests/motion/test_oracle.py",
        "tests/motion/test_branches.py", "tests/motion/test_rates.py", "tests/motion/test_pose_strength.py",
        "tests/motion/test_linkage_strength.py", "tests/motion/test_dyads_strength.py",
        "tests/motion/test_system_strength.py", *_MOTION_MORE.get(name, ()),
        _SYNTH_DOC + f"synth.motion.{name}]".replace(".__init__", "")])
       for name in ("_pose", "_dyads", "_system", "_linkage", "_kernel", "_sweep", "__init__")},
    # dimensional synthesis: targets read and checked, the problem's placement and errors, the search on exact
    # targets known by construction (not the CLI's and the executors' tests: Ctrl-C, Dask, seconds per mutant)
    # (the targets by their own tests alone: the searches add half a minute per mutant and reach nothing more of them)
    **{f"dimension_{name.strip('_')}": (f"synth/dimension/{name}.py", [
        "tests/dimension/test_targets.py", "tests/dimension/test_targets_strength.py",
        *(() if name == "_target" else ("tests/dimension/test_problem_strength.py", "tests/dimension/test_search_strength.py",
                                        "tests/dimension/test_placement.py", "tests/dimension/test_synthesize.py")),
        _SYNTH_DOC + f"synth.dimension.{name}]".replace(".__init__", "")])
       for name in ("_target", "_problem", "__init__")},
    # (the search by its cheap cases: in the mutation copy the searches for a four-bar's coupler points, for a
    # constraint no candidate meets and the docstring's run to their budgets, minutes a mutant; the docstring's
    # function generation is Freudenstein's case of test_synthesize.py, which stays)
    "dimension_search": ("synth/dimension/_search.py", [
        "tests/dimension/test_targets.py", "tests/dimension/test_targets_strength.py",
        "tests/dimension/test_problem_strength.py", "tests/dimension/test_search_strength.py",
        "tests/dimension/test_search_evaluate_strength.py", "tests/dimension/test_placement.py",
        "tests/dimension/test_synthesize.py", "-k", "not coupler_points and not no_candidate"]),
    # gear trains: the text form and its chain, planetary trains, enumeration against brute force (not its
    # 7- and 8-link cases, half a minute each), ratios and designs that can be built; each module's strength
    # file (not the random trains against their geometry, the CLI listings and the 5-link kinds' design:
    # 10 to 20 s each, a minute per mutant; lighter cases of each stay)
    **{f"gears_{name}": (f"synth/gears/{name}.py", [
        "tests/test_gear_trains.py", "tests/gears/test_planetary_vs_oracle.py", "tests/gears/test_lever_analogue_vs_oracle.py",
        "tests/gears/test_nine_link_readings.py", "tests/gears/test_buildable_designs.py",
        f"tests/gears/test_{name}_strength.py", _SYNTH_DOC + f"synth.gears.{name}]",
        "-k", "not ctrl_c and not 7] and not -8- and not three_axes and not random_ and not cli_count_and_listing "
              "and not over_a_size and not five_links_are_buildable"])
       for name in ("train", "planetary", "enumeration", "ratios", "ratio_design")},
    # (the enumerator: the counts against brute force, the nine-link readings, its strength file; not the
    # planetary, lever-analogue and design files, which list no train)
    "gears_enumeration": ("synth/gears/enumeration.py", [
        "tests/test_gear_trains.py", "tests/gears/test_nine_link_readings.py", "tests/gears/test_enumeration_strength.py",
        _SYNTH_DOC + "synth.gears.enumeration]",
        "-k", "not ctrl_c and not 7] and not -8- and not three_axes and not cli_ and not design"]),
    # (the ratio designer: its strength file, the designs that can be built and the designs of test_gear_trains.py;
    # not the listings and readings of trains, which never call it, nor the three-axes brute force, 12 s a mutant)
    "gears_ratio_design": ("synth/gears/ratio_design.py", [
        "tests/gears/test_ratio_design_strength.py", "tests/gears/test_buildable_designs.py", "tests/test_gear_trains.py",
        _SYNTH_DOC + "synth.gears.ratio_design]", "-k", "(design or strength or clearance or docstring or free_mesh_kinds) "
                                                        "and not three_axes and not five_links_are_buildable and not ctrl_c"]),
    # (the source's planetary layout: only these tests reach it; the others' clean run would cost minutes)
    "gears_planetary": ("synth/gears/planetary.py", [
        "tests/gears/test_planetary_vs_oracle.py", "tests/gears/test_lever_analogue_vs_oracle.py",
        "tests/gears/test_planetary_strength.py", _SYNTH_DOC + "synth.gears.planetary]", "-k", "not random_"]),
    "tradeoff": ("balance/devices/tradeoff.py", ["tests/balance/test_tradeoff_strength.py", "tests/balance/test_devices.py",
                                                 _BALANCE_DOC + "balance.devices.tradeoff]",
                                                 "-k", "bound or pareto or sensitivity or docstring or strength"]),
    # the parameters every query shares, the errors' sentences, the schema of scene files
    "params": ("synth/structure/_params.py", ["tests/structure/test_params.py", "tests/structure/test_query_strength.py", "tests/cli/test_query_refusals.py",
                                              _SYNTH_DOC + "synth.structure._params]"]),
    # (not tests/cli/test_bad_inputs.py: every error reaches these functions, minutes per mutant)
    "synth_errors": ("synth/errors.py", ["tests/test_errors.py", "tests/structure/test_query_strength.py", "tests/cli/test_query_refusals.py",
                                         _SYNTH_DOC + "synth.errors]"]),
    "synth_schema": ("synth/schema.py", ["tests/scenes/test_require_schema.py", "tests/scenes/test_scenes.py",
                                         _SYNTH_DOC + "synth.schema]", "-k",
                                         "malformed_scene or impossible_expectation or contradicted or copy_change "
                                         "or command_line_mistakes or docstring or require_schema"]),
    # (not tests/balance/test_cli.py: every command reaches parse, minutes per mutant; its refusals of files
    # are the sentences test_schema_strength.py asserts)
    "balance_schema": ("balance/schema.py", ["tests/balance/test_schema_strength.py", "tests/balance/test_arm.py",
                                             _BALANCE_DOC + "balance.schema]"]),
    # the spring devices' fit: its methods, exact devices, driver and result, the slider devices' problem; each
    # judged by its fast strength file (2-4 CPU s clean; the fits of _FIT took 14 minutes clean on the loaded
    # machine), the methods de and nelder_mead (scored with _FIT) and kinds (no function) by _FIT
    **{f"fit_{name}": (f"balance/devices/fit/{name}.py", [*files, _BALANCE_DOC + f"balance.devices.fit.{name}]"])
       for name, files in (
           ("slider_problem", ["tests/balance/test_fit_slider_problem_strength.py"]),
           ("exact", ["tests/balance/test_fit_exact_strength.py"]),
           ("driver", ["tests/balance/test_fit_driver_strength.py"]),
           ("result", ["tests/balance/test_fit_result_strength.py"]),
           ("trf", ["tests/balance/test_fit_methods_strength.py", "tests/balance/test_fit_driver_strength.py"]),
           ("slsqp", ["tests/balance/test_fit_methods_strength.py", "tests/balance/test_fit_driver_strength.py"]),
           *((name, _FIT) for name in ("kinds", "de", "nelder_mead")))},
    "sliders": ("balance/devices/sliders.py", ["tests/balance/test_slider_devices.py",
                                               _BALANCE_DOC + "balance.devices.sliders]"]),
    # the helical spring's design (wire, coils, buckling) and the arm's transmissions (drive forms)
    "helical": ("balance/devices/helical.py", ["tests/balance/test_devices.py", "tests/balance/test_slider_devices.py",
                                               _BALANCE_DOC + "balance.devices.helical]", "-k",
                                               "wire or designed or buckling or refusal or helical or compression_lever or docstring"]),
    # the planar arm from TOML: links, loads, the gravity potential (terms against hand sums, moments against
    # finite differences) and the counterweights' sub-arms
    "arm_model": ("balance/model/arm.py", ["tests/balance/test_arm.py", "tests/balance/test_arm_model_strength.py",
                                           "tests/balance/test_potential_strength.py",
                                           "tests/balance/test_compare_strength.py", _BALANCE_DOC + "balance.model.arm]"]),
    # arms from URDF (Pinocchio the independent check) and the URDF written from DH parameters
    "urdf": ("balance/model/urdf.py", ["tests/balance/test_urdf.py", "tests/balance/test_urdf_strength.py",
                                       "tests/balance/test_compare.py::test_the_ur5e_urdf_is_written_from_the_published_numbers",
                                       _BALANCE_DOC + "balance.model.urdf]"]),
    # the [arm], [pantograph], [slider] and [spring] problems, read and solved
    "problems_arm": ("balance/problems/arm.py", ["tests/balance/test_arm.py", "tests/balance/test_arm_problem_strength.py",
                                                _BALANCE_DOC + "balance.problems.arm]"]),
    "problems_pantograph": ("balance/problems/pantograph.py", ["tests/balance/test_pantograph.py",
                                                               "tests/balance/test_pantograph_problem_strength.py",
                                                               _BALANCE_DOC + "balance.problems.pantograph]"]),
    "problems_slider": ("balance/problems/slider.py", ["tests/balance/test_slider_problem_strength.py",
                                                       "tests/balance/test_countermass.py", "tests/balance/test_dynamics.py",
                                                       "tests/balance/test_packages_strength.py",
                                                       _BALANCE_DOC + "balance.problems.slider]"]),
    # (its strength file and the spring problems of the device tests; not test_fit.py and the rest of
    # test_devices.py and test_slider_devices.py: 24 CPU s, the fits' own modules are judged by them)
    "problems_spring": ("balance/problems/spring.py", ["tests/balance/test_spring_problem_strength.py",
                                                       "tests/balance/test_devices.py::test_unguided_long_spring_warns_about_buckling",
                                                       "tests/balance/test_devices.py::test_bound_warnings_say_which_bound_to_move",
                                                       "tests/balance/test_devices.py::test_pareto_front_is_nondominated_and_contains_better_devices",
                                                       "tests/balance/test_slider_devices.py::test_sensitivity_moves_the_rod_and_refits_the_same_device",
                                                       "tests/balance/test_slider_devices.py::test_helical_spring_for_a_slider_device_works_between_its_lengths",
                                                       _BALANCE_DOC + "balance.problems.spring]"]),
    # the package's lazily loaded names, the problems' readers, the fit's names
    "balance_init": ("balance/__init__.py", ["tests/balance/test_packages_strength.py", _BALANCE_DOC + "balance]"]),
    "problems_init": ("balance/problems/__init__.py", ["tests/balance/test_packages_strength.py",
                                                       _BALANCE_DOC + "balance.problems]"]),
    "fit_init": ("balance/devices/fit/__init__.py", ["tests/balance/test_packages_strength.py",
                                                     _BALANCE_DOC + "balance.devices.fit]"]),
    # the figures: each curve's data, the labels, markers and captions read back from the saved figure
    "plots": ("balance/plots.py", ["tests/balance/test_plots_strength.py", _BALANCE_DOC + "balance.plots]"]),
    # the atlas file: its schema, version checks, refusals and run lock (not test_atlas.py's 201-unit grid: a
    # minute per mutant)
    "atlas_database": ("synth/atlas/database.py", ["tests/atlas/test_database_strength.py", "tests/atlas/test_atlas.py",
                                                   "tests/atlas/test_grid.py::test_docstring_examples", "-k", _ATLAS_LIGHT]),
    # grid files: cells by hand from n = W + 1 + (h − 1)·K, every key's part, every refusal's sentence
    "atlas_grid": ("synth/atlas/grid.py", ["tests/atlas/test_grid_strength.py", "tests/atlas/test_grid.py"]),
    # grid runs: every column of the rows by hand on a few links, stopped runs, the sizing from estimates by hand
    "atlas_runs": ("synth/atlas/runs.py", ["tests/atlas/test_runs_strength.py", "tests/atlas/test_database_strength.py",
                                           "tests/atlas/test_atlas.py",
                                           "tests/atlas/test_grid.py::test_docstring_examples", "-k", _ATLAS_LIGHT]),
    # the atlas search: descriptors, alignment, refusals, a stored curve moved and mirrored found exactly, the
    # starts sampled for a mechanism (not the recoveries of random cranks and the commands, half a minute of
    # polishing each; not its doctest either, whose search polishes for 5 CPU s: minutes a mutant when loaded)
    "atlas_search": ("synth/atlas/search.py", ["tests/atlas/test_search_strength.py", "tests/atlas/test_curve_search.py",
                                               "-k", "not found_again and not command"]),
    # the curve index: every stored curve swept again, its settings, resumption and refusals (not the searches'
    # recoveries and commands, which read the index and take half a minute each)
    "atlas_curves": ("synth/atlas/curves.py", ["tests/atlas/test_search_strength.py", "tests/atlas/test_curve_search.py",
                                               _SYNTH_DOC + "synth.atlas.curves]", "-k",
                                               "not found_again and not command and not alignment_finds"]),
    # gear cells of an atlas: units, ranks, rows and rotation representatives on hand-built databases, one 6-link run
    "atlas_trains": ("synth/atlas/trains.py", ["tests/atlas/test_trains_strength.py", _SYNTH_DOC + "synth.atlas.trains]"]),
    # the atlas's web site: every code's entry, page, card and lookup by hand, moving pages, refusals (not
    # test_site.py and test_site_motion.py: their atlases of 1- and 2-DOF chains up to 8 links are drawn anew for
    # every mutant, minutes on the loaded machine)
    "atlas_site": ("synth/atlas/site.py", ["tests/atlas/test_site_strength.py", _SYNTH_DOC + "synth.atlas.site]"]),
    # where links and joints go, and the marks drawn there: each mark by kind where it stands, the layouts of the
    # 8-link chains (not the drawings of every planar chain, the commands and the measured drawings: minutes a
    # mutant on the loaded machine)
    **{f"draw_{name.strip('_')}": (f"synth/draw/{name}.py", ["tests/test_draw_strength.py", "tests/test_draw.py",
                                                            _SYNTH_DOC + f"synth.draw.{name}]",
                                                            "-k", "not every_planar_chain and not cli and not sheet_png "
                                                                  "and not jupyter and not prismatic_variants"])
       for name in ("_layout", "_render")},
    # gear schematics: axis heights, shaft levels, bars to their pitch points, rings, arms, hatching, numbers,
    # legend and sheets by hand, read from the artists (not the gears command's tests: subprocesses, minutes)
    "draw_gears": ("synth/draw/_gears.py", ["tests/gears/test_draw_gears_strength.py", _SYNTH_DOC + "synth.draw._gears]"]),
    # pictures of moving mechanisms: each element where the pose and the sweep put it, its style by kind, the
    # SVG, SMIL and player texts, the files and refusals, linkages from the atlas's drawings
    "motion_draw": ("synth/motion_draw.py", ["tests/motion/test_motion_draw_strength.py", "tests/motion/test_motion_draw.py",
                                             _SYNTH_DOC + "synth.motion_draw]"]),
    "transmission": ("balance/devices/transmission.py", ["tests/balance/test_transmission.py",
                                                         _BALANCE_DOC + "balance.devices.transmission]"]),
    # synthesis internals: the bound of the codes before a model, the size estimate and its refusals (the
    # estimate's test counts real sizes: its 14-link case is left out, minutes a mutant), heterogeneous chains
    "sizing": ("synth/synthesis/_sizing.py", ["tests/synthesis/test_sizing_strength.py", "tests/synthesis/test_sizing.py", _SYNTH_DOC + "synth.synthesis._sizing]"]),
    "estimate": ("synth/synthesis/estimate.py", [
        "tests/synthesis/test_estimate_strength.py", "tests/execution/test_large_queries.py",
        "tests/synthesis/test_classes_vs_oracle.py", _SYNTH_DOC + "synth.synthesis.estimate]",
        "-k", "estimate_strength or giant or long_query or large_listing or model_too_large or size_note "
              "or docstring"]),
    "classes": ("synth/synthesis/classes.py", ["tests/synthesis/test_classes_strength.py",
                                               "tests/synthesis/test_classes_vs_oracle.py",
                                               _SYNTH_DOC + "synth.synthesis.classes]"]),
    "cpsat": ("synth/synthesis/_cpsat.py", ["tests/synthesis/test_cpsat_api.py", "tests/synthesis/test_cpsat_strength.py",
                                            _SYNTH_DOC + "synth.synthesis._cpsat]"]),
    # execution: checkpoints of counts, the store of results, sizes in words, the scheduler's address, the
    # pools and pipelines (inline and in pool processes), Ctrl-C in a search (not the tests that signal a
    # child process and wait for it: mutmut does not see which function a child reaches)
    "checkpoint": ("synth/execution/checkpoint.py", ["tests/execution/test_large_queries.py",
                                                     "tests/execution/test_checkpoint_strength.py",
                                                     _SYNTH_DOC + "synth.execution.checkpoint]", "-k", "checkpoint and not sigkill"]),
    # (of test_memo.py only the cases in this process: the others run synthesis in child processes, 100 CPU s,
    # and call no function of the module in the process whose calls mutmut maps to tests)
    "memo": ("synth/execution/memo.py", ["tests/execution/test_memo_strength.py", "tests/execution/test_memo.py",
                                         _SYNTH_DOC + "synth.execution.memo]",
                                         "-k", "not warm_run and not damaged_store and not cannot_be_written "
                                               "and not asked_again"]),
    "sizes": ("synth/execution/sizes.py", ["tests/test_small_modules_strength.py",
                                           _SYNTH_DOC + "synth.execution.sizes]"]),
    "scheduler": ("synth/execution/scheduler.py", ["tests/execution/test_scheduler_strength.py",
                                                   "tests/execution/test_large_queries.py",
                                                   _SYNTH_DOC + "synth.execution.scheduler]",
                                                   "-k", "scheduler or endpoint"]),
    # (the pipeline on a clock given by hand, Dask stood in for, a pool of two workers on tiny work: 2 CPU s; not
    # test_large_queries.py, whose counts add 20 CPU s and reach nothing of the module the others do not)
    "executor": ("synth/execution/executor.py", ["tests/execution/test_executor_strength.py",
                                                 "tests/execution/test_executor.py",
                                                 _SYNTH_DOC + "synth.execution.executor]", "-k", "not map_on_a_dask_cluster"]),
    "interrupt": ("synth/execution/interrupt.py", ["tests/execution/test_interrupt_strength.py",
                                                   "tests/execution/test_interrupt.py",
                                                   _SYNTH_DOC + "synth.execution.interrupt]",
                                                   "-k", "strength or extension or after_a_handled or docstring"]),
    "sqlite_files": ("synth/execution/sqlite_files.py", ["tests/test_small_modules_strength.py",
                                                         _SYNTH_DOC + "synth.execution.sqlite_files]"]),
    # small structure modules and the package's start-up paths (not synth/__init__.py: no function, so mutmut
    # makes no mutant of it; its names are checked by tests/test_small_modules_strength.py)
    "disjoint": ("synth/structure/disjoint.py", ["tests/test_small_modules_strength.py",
                                                 _SYNTH_DOC + "synth.structure.disjoint]"]),
    "blas": ("synth/structure/_blas.py", ["tests/test_small_modules_strength.py",
                                          _SYNTH_DOC + "synth.structure._blas]"]),
    "joints": ("synth/structure/joints.py", ["tests/structure/test_joint_kinds_table.py",
                                             _SYNTH_DOC + "synth.structure.joints]"]),
    "lazy": ("synth/_lazy.py", ["tests/test_small_modules_strength.py", _SYNTH_DOC + "synth._lazy]"]),
    # stage A's compiled search: its @njit functions are not mutated (mutmut skips decorated functions), only
    # new_state, the size of the search's state; judged by the kernel against the CP-SAT model's multigraphs
    "stage_a_kernel": ("synth/synthesis/_stage_a_kernel.py", ["tests/synthesis/test_kernels.py",
                                                              _SYNTH_DOC + "synth.synthesis._stage_a_kernel]",
                                                              "-k", "(stage_a_kernel or docstring) and " + _HEAVY]),
    "display": ("synth/display.py", ["tests/test_small_modules_strength.py", _SYNTH_DOC + "synth.display]"]),
}

#: the packages pyproject.toml installs (a new one is copied without an edit here), the data and the tests
_PACKAGES = [name.rstrip("*") for name in
             tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]["packages"]["find"]["include"]]
COPY = _PACKAGES + ["models", "benchmarks", "tests", "pyproject.toml"]
EQUIVALENT = ROOT / "tools" / "mutation_equivalent.toml"
DOC = ROOT / "docs" / "mutation.md"
BEGIN, END = "<!-- mutation-scores:begin -->", "<!-- mutation-scores:end -->"


def _selection(key: str) -> list[str]:
    """The pytest arguments that choose the tests judging ``key`` (test files that no longer exist left out)."""
    return [t for t in MODULES[key][1] if not t.startswith("tests/") or (ROOT / t.split("::")[0]).exists()]


def _prepare(key: str, work: Path) -> Path:
    path, tests = MODULES[key][0], _selection(key)
    where = work / key
    shutil.rmtree(where, ignore_errors=True)
    where.mkdir(parents=True)
    ignore = shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis", "mutants")
    for name in COPY:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, where / name, ignore=ignore)
        else:
            shutil.copy2(src, where / name)
    package = path.split("/")[0]
    config = {
        "source_paths": [f"{package}/"],
        "only_mutate": [path],
        "also_copy": [f"{d}/" for d in COPY if (ROOT / d).is_dir() and d not in (package, "tests")],
        "pytest_add_cli_args_test_selection": tests,
        "pytest_add_cli_args": ["-p", "no:cacheprovider", "-q", "-x"],
        # a mutant is stopped (and counted as caught) past 2 × 3 × (60 s + the CPU time of its tests on
        # the clean code): mutmut's default multiplier 15 gave a looping mutant of stage B 25 CPU minutes;
        # the 60 s because the clean run's times are those of a warm cache (a test reading an oracle an
        # earlier test computed) and a mutant's tests start with empty caches (_CONFTEST)
        "timeout_multiplier": 3.0,
        "timeout_constant": 60.0,
    }
    lines = ["", "[tool.mutmut]"] + [f"{k} = {json.dumps(v)}" for k, v in config.items()]
    _conftest_for_mutants(where)
    with open(where / "pyproject.toml", "a") as fh:
        fh.write("\n".join(lines) + "\n")
    return where


#: appended to the copy's tests/conftest.py
_CONFTEST = """

# --- added by tools/mutation.py ---
# Synthesis with the default worker count runs its units in pool processes, where mutmut does not see
# which test reaches which function: in the copy, one core means inline runs.
os.cpu_count = lambda: 1


_LRU_CACHES = []


def pytest_collection_finish(session):
    # mutmut runs each mutant's tests in a fork of the process that ran them on the unmutated code:
    # every lru_cache there (brute-force oracles of the tests, fits, the engine's own memos) would
    # hand the mutant's tests the unmutated results.  And within one session a test that reads what
    # an earlier test cached never calls the code that made it, so mutmut's map of which tests reach
    # which function would miss it.  So every test starts with all of them empty.
    import functools
    import gc

    _LRU_CACHES[:] = [c for c in gc.get_objects() if isinstance(c, functools._lru_cache_wrapper)]


def pytest_runtest_setup(item):
    for cached in _LRU_CACHES:
        cached.cache_clear()
"""


def _conftest_for_mutants(where: Path) -> None:
    """Append ``_CONFTEST`` to the copy's tests/conftest.py (inline synthesis, empty caches per session)."""
    with open(where / "tests" / "conftest.py", "a") as fh:
        fh.write(_CONFTEST)


def _retest(key: str, work: Path, children: int, env: dict, only: list[str] | None = None) -> None:
    """Run the survivors of the last run of ``key`` again, against the checkout's present tests
    (mutmut finds the new tests and which functions they reach); the module must be unchanged."""
    where, path = work / key, MODULES[key][0]
    if not (where / "mutants").exists():
        raise SystemExit(f"mutation.py: no earlier run of {key} under {work}; run it in full first")
    if (ROOT / path).read_bytes() != (where / path).read_bytes():
        raise SystemExit(f"mutation.py: {path} changed since its run under {work}; run {key} in full")
    shutil.rmtree(where / "tests")
    shutil.copytree(ROOT / "tests", where / "tests", ignore=shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis"))
    _conftest_for_mutants(where)
    config = (where / "pyproject.toml").read_text()
    if "process_isolation" in config:  # a run made with the fork server (see _CONFTEST): fork again
        config = re.sub(r"\nprocess_isolation = .*\n", "\n", config)
    if "timeout_constant" not in config:  # a run made before the caches were emptied (see _prepare)
        config += "timeout_constant = 60.0\n"
    # the present selection: a test file added for the survivors is run too
    config = re.sub(r"\npytest_add_cli_args_test_selection = .*\n",
                    lambda _: f"\npytest_add_cli_args_test_selection = {json.dumps(_selection(key))}\n", config)
    (where / "pyproject.toml").write_text(config)
    # which tests reach which function, from the present tests (mutmut would map only the new ones)
    (where / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    listing = subprocess.run(["mutmut", "results"], cwd=where, env=env, capture_output=True, text=True).stdout
    # (and the timeouts: with a time limit set before it allowed for empty caches, one may be false)
    names = [m.split(":")[0].strip() for m in listing.splitlines()
             if ":" in m and m.split(":")[1].strip() in ("survived", "no tests", "suspicious", "timeout")]
    known = {(e["function"], e["before"], e["after"]) for e in _equivalents(key)}
    names = [n for n, diff in _diffs(where, path, names).items()
             if diff not in known and (not only or diff[0] in only)]  # (equivalents stay so)
    if names:
        proc = subprocess.run(["mutmut", "run", "--max-children", str(children), *names], cwd=where, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        (where / "again.log").write_text(proc.stdout)
        if not (where / "mutants" / "mutmut-stats.json").exists():  # the unmutated code failed its tests
            raise SystemExit(f"mutation.py: the tests of {key} fail on the unmutated copy under {where}, so no "
                             f"survivor was run again (see {where / 'again.log'}); run {key} in full")


_DIFFS = """
import json, sys
from mutmut.mutation.diff_apply import get_diff_for_mutant
path, names = sys.argv[1], sys.argv[2:]
print(json.dumps({n: get_diff_for_mutant(n, path=path) for n in names}))
"""


def _diffs(where: Path, path: str, names: list[str]) -> dict[str, tuple[str, str, str]]:
    """(function, original line, mutated line) of each mutant, from mutmut's own diff (one process)."""
    if not names:
        return {}
    out = subprocess.run([sys.executable, "-c", _DIFFS, path, *names], cwd=where, capture_output=True, text=True,
                         check=True).stdout
    result = {}
    for name, diff in json.loads(out).items():
        lines = diff.splitlines()
        before = [x[1:].strip() for x in lines if x.startswith("-") and not x.startswith("---")]
        after = [x[1:].strip() for x in lines if x.startswith("+") and not x.startswith("+++")]
        function = re.sub(r"__mutmut_\d+$", "", name.rsplit(".", 1)[-1])  # x_func or xǁClassǁmethod
        function = function[2:] if function.startswith("x_") else function.removeprefix("xǁ").replace("ǁ", ".")
        result[name] = (function, " / ".join(before), " / ".join(after))
    return result


def _equivalents(key: str) -> list[dict]:
    if not EQUIVALENT.exists():
        return []
    data = tomllib.loads(EQUIVALENT.read_text())
    return [e for e in data.get("equivalent", []) if e["module"] == key]


def _sampled(where: Path, key: str, size: int, seed: int, env: dict) -> list[str]:
    """Names of a random sample of ``size`` of the module's mutants: mutmut makes them (and its
    test statistics) on a first call with a name that matches none, which it then refuses."""
    subprocess.run(["mutmut", "run", "no-mutant-has-this-name"], cwd=where, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    meta = where / "mutants" / (MODULES[key][0] + ".meta")
    if not meta.exists():
        raise SystemExit(f"mutmut made no mutants of {key}")
    names = sorted(json.loads(meta.read_text())["exit_code_by_key"])
    return sorted(random.Random(seed).sample(names, min(size, len(names))))


def run_module(key: str, work: Path, children: int, mode: str = "run", sample: int | None = None,
               seed: int = 16, only: list[str] | None = None) -> dict:
    """Mutate one module in a fresh copy (``"run"``; all its mutants, or a random ``sample`` of
    them), run the survivors of the copy a run left again with the present tests (``"again"``),
    or only read that copy (``"collect"``)."""
    where = _prepare(key, work) if mode == "run" else work / key
    start = time.monotonic()
    env = dict(os.environ, PYTHONPATH="")  # the copy, not the checkout, is what the tests import
    if mode == "run":
        names = _sampled(where, key, sample, seed, env) if sample else []
        (where / "sample.json").write_text(json.dumps({"sample": sample, "seed": seed}))
        proc = subprocess.run(["mutmut", "run", "--max-children", str(children), *names], cwd=where, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if proc.returncode != 0 and not (where / "mutants" / "mutmut-stats.json").exists():
            raise SystemExit(f"mutmut failed on {key}: {proc.stderr.strip().splitlines()[-1:]}")
        meta = json.loads((where / "mutants" / (MODULES[key][0] + ".meta")).read_text())["exit_code_by_key"]
        if names and all(meta.get(n) is None for n in names):
            raise SystemExit(f"mutmut ran none of the sampled mutants of {key} (exit {proc.returncode}: "
                             f"{proc.stderr.strip().splitlines()[-1:]}); run them by name in {where}: "
                             f"mutmut run NAME …")
    elif mode == "again":
        _retest(key, work, children, env, only)
    minutes = (time.monotonic() - start) / 60 if mode == "run" else None  # (a full run's time only)
    subprocess.run(["mutmut", "export-cicd-stats"], cwd=where, capture_output=True)
    stats = json.loads((where / "mutants" / "mutmut-cicd-stats.json").read_text())
    listing = subprocess.run(["mutmut", "results", "--all", "true"], cwd=where, capture_output=True, text=True).stdout
    # a mutant that makes a test hang (timeout) is detected: the suite would never pass with it
    alive = [(m.split(":")[0].strip(), m.split(":")[1].strip()) for m in listing.splitlines()
             if ":" in m and m.split(":")[1].strip() in ("survived", "no tests", "suspicious")]
    known = _equivalents(key)
    survivors, equivalent = [], []
    diffs = _diffs(where, MODULES[key][0], [name for name, _ in alive])
    for name, status in alive:
        function, before, after = diffs[name]
        match = next((e for e in known if e["function"] == function and e["before"] == before
                      and e["after"] == after), None)
        row = {"name": name, "status": status, "function": function, "before": before, "after": after}
        if match and status == "survived":
            equivalent.append({**row, "reason": match["reason"]})
        else:
            survivors.append(row)
    total = stats["total"] - stats.get("skipped", 0)
    # mutmut reads a SIGKILL as a "segfault"; its fork server also SIGKILLs mutants that pass when run
    # alone (seen on stage B), so such a mutant is not judged: counted as not run, never as killed
    killed = stats["killed"] + stats.get("timeout", 0)
    checked = killed + stats["survived"] + stats.get("no_tests", 0) + stats.get("suspicious", 0)
    judged = checked - len(equivalent)
    return {"module": key, "file": MODULES[key][0], "date": _dt.date.today().isoformat(),
            "total": total, "not_checked": total - checked,
            "killed": killed, "equivalent": equivalent, "survivors": survivors,
            "minutes": None if minutes is None else round(minutes, 1),
            **json.loads((where / "sample.json").read_text() if (where / "sample.json").exists() else "{}"),
            "score": killed / judged if judged else 1.0}


def _markdown(results: list[dict]) -> str:
    out = [f"mutmut {_mutmut_version()}, `nice -n 19 python tools/mutation.py`, 2 cores shared with other "
           "work; each row from the run of its date (mutants not run: the run was stopped, or tested a seeded "
           "random sample of them, named in the row).", "",
           "| module | run | mutants | killed | equivalent | survived | not run | score | minutes |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        run = r.get("date", "—") + (f", random {r['sample']} (seed {r['seed']})" if r.get("sample") else "")
        out.append(f"| `{r['file']}` | {run} | {r['total']} | {r['killed']} | {len(r['equivalent'])} | "
                   f"{len(r['survivors'])} | {r.get('not_checked', 0)} | {100 * r['score']:.1f} % | {r['minutes'] if r['minutes'] is not None else '—'} |")
    for r in results:
        if r["survivors"]:
            out += ["", f"Surviving in `{r['file']}`:", ""]
            out += [f"- `{s['function']}`: `{s['before']}` → `{s['after']}` ({s['status']})" for s in r["survivors"]]
        if r["equivalent"]:
            out += ["", f"Equivalent in `{r['file']}`:", ""]
            out += [f"- `{s['function']}`: `{s['before']}` → `{s['after']}` — {s['reason']}" for s in r["equivalent"]]
    return "\n".join(out) + "\n"


def _merged(old: str, new: str) -> str:
    """The score block ``new`` (from :func:`_markdown`) with the rows and mutant lists of the modules it does
    not cover kept from the block ``old``: a run of some modules leaves the other modules' scores as they were."""
    def parts(text: str) -> tuple[list[str], dict[str, str], dict[tuple[str, str], list[str]]]:
        lines = text.rstrip("\n").split("\n")
        rows = {line.split("`")[1]: line for line in lines if line.startswith("| `")}
        lists: dict[tuple[str, str], list[str]] = {}
        key = None
        for line in lines:
            head = re.fullmatch(r"(Surviving|Equivalent) in `([^`]+)`:", line)
            if head:
                key = (head[2], head[1])
                lists[key] = []
            elif key and line.startswith("- "):
                lists[key].append(line)
            elif line:
                key = None
        return lines[:4], rows, lists

    intro, new_rows, new_lists = parts(new)
    _, old_rows, old_lists = parts(old)
    files = list(old_rows) + [f for f in new_rows if f not in old_rows]
    out = intro + [new_rows.get(f, old_rows.get(f)) for f in files]
    for f in files:
        lists = new_lists if f in new_rows else old_lists
        for kind in ("Surviving", "Equivalent"):
            if lists.get((f, kind)):
                out += ["", f"{kind} in `{f}`:", ""] + lists[(f, kind)]
    return "\n".join(out) + "\n"


def _mutmut_version() -> str:
    try:
        from importlib.metadata import version

        return version("mutmut")
    except Exception:  # noqa: BLE001 - only for the report line
        return "?"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("modules", nargs="*", help=f"module keys (default all): {', '.join(MODULES)}")
    parser.add_argument("--work", type=Path, default=Path("/tmp/mechsynth-mutation"), help="where the copies go")
    parser.add_argument("--children", type=int, default=2, help="parallel mutants (default 2)")
    parser.add_argument("--write-docs", action="store_true", help="put the scores into docs/mutation.md")
    parser.add_argument("--json", type=Path, help="also write the results as JSON")
    parser.add_argument("--list", action="store_true", help="list the modules and their tests")
    parser.add_argument("--collect", action="store_true",
                        help="no run: read the results a finished (or stopped) run left under --work")
    parser.add_argument("--sample", type=int, metavar="N",
                        help="test a random sample of N mutants of each module (the others count as not run)")
    parser.add_argument("--seed", type=int, default=16, help="seed of --sample (default 16)")
    parser.add_argument("--again", action="store_true",
                        help="run only the survivors of the last run under --work again, with the present tests "
                             "(the module itself unchanged)")
    parser.add_argument("--only", metavar="FUNC,…", help="with --again: only the survivors in these functions")
    parser.add_argument("--from-json", type=Path, nargs="+", metavar="FILE",
                        help="no run: report the results saved by earlier --json runs (the last one per module)")
    args = parser.parse_args(argv)
    if args.list:
        for key, (path, tests) in MODULES.items():
            print(f"{key:18} {path:30} {' '.join(tests)}")
        return 0
    if shutil.which("mutmut") is None and not args.from_json:  # --collect needs it too (results, diffs)
        print("mutation.py: mutmut is not installed (pip install '.[mutation]')", file=sys.stderr)
        return 2
    if args.sample is not None and (args.sample < 1 or args.collect or args.again or args.from_json):
        print("mutation.py: --sample N (N ≥ 1) makes a new run: not with --collect, --again or --from-json",
              file=sys.stderr)
        return 2
    if args.only and not args.again:
        print("mutation.py: --only chooses among the survivors that --again runs: give --again too", file=sys.stderr)
        return 2
    if args.collect and args.again:
        print("mutation.py: --collect reads a run and --again runs its survivors: give one of them", file=sys.stderr)
        return 2
    unknown = [m for m in args.modules if m not in MODULES]
    if unknown:
        print(f"mutation.py: unknown module(s) {', '.join(unknown)}; known: {', '.join(MODULES)}", file=sys.stderr)
        return 2
    results = []
    if args.from_json:
        saved = {r["module"]: r for f in args.from_json for r in json.loads(f.read_text())}
        results = [saved[k] for k in MODULES if k in saved]
    for key in [] if args.from_json else (args.modules or list(MODULES)):
        print(f"mutating {MODULES[key][0]} …", file=sys.stderr, flush=True)
        r = run_module(key, args.work, args.children, "collect" if args.collect else "again" if args.again else "run",
                       args.sample, args.seed, args.only.split(",") if args.only else None)
        print(f"  {r['killed']}/{r['total']} killed, {len(r['equivalent'])} equivalent, "
              f"{len(r['survivors'])} surviving: {100 * r['score']:.1f} % ({str(r['minutes']) + ' min' if r['minutes'] is not None else 'survivors run again' if args.again else 'collected'})", file=sys.stderr)
        results.append(r)
        if args.json:  # after every module, so a stopped run keeps what it finished
            args.json.write_text(json.dumps(results, indent=1))
    text = _markdown(results)
    print(text)
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))
    if args.write_docs:
        doc = DOC.read_text()
        head, rest = doc.split(BEGIN, 1)
        before, tail = rest.split(END, 1)
        DOC.write_text(f"{head}{BEGIN}\n{_merged(before, text)}{END}{tail}")
    return 0 if all(r["score"] >= 0.9 for r in results) else 1


if __name__ == "__main__":
    raise SystemExit(main())
