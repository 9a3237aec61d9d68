"""Balance problems: each TOML table read once into a typed problem, solved into a typed result.

=================  =========================================  ===================================
table              problem (``read_problem``)                 result (``problem.solve()``)
=================  =========================================  ===================================
``[arm]``          :class:`~.arm.ArmProblem`                  :class:`~.arm.ArmBalance`
``[spring]``       :class:`~.spring.SpringProblem`            :class:`~.spring.SpringDesign`
``[slider]``       :class:`~.slider.SliderProblem`            :class:`~.slider.SliderBalance`
``[pantograph]``   :class:`~.pantograph.PantographProblem`    :class:`~.pantograph.PantographBalance`
``[compare]``      :class:`~.compare.CompareProblem`          :class:`~.compare.Comparison`
=================  =========================================  ===================================

Every result has ``to_dict()``: the JSON-ready form the CLI and the scene runner write.
``[scene]``, ``[expect]`` and ``[plot]`` belong to the scene runner and are ignored here; any
other unknown table or key is a :class:`~balance.errors.SchemaError` naming the file and the key.

Examples
--------
>>> doc = {"arm": {"links": [{"joint": "revolute", "length": 1.0, "weight": 10.0}]}}
>>> res = read_problem(doc).solve()
>>> res.terms[0].amplitude, res.check.max_residual < 1e-12
(5.0, True)
"""

from __future__ import annotations

from typing import Any, Mapping

from ..errors import SchemaError
from ..schema import OWNED_BY_RUNNER, load_toml
from .arm import ArmBalance, ArmProblem, arm_problem
from .compare import CompareProblem, Comparison, compare_problem
from .pantograph import PantographBalance, PantographProblem, pantograph_problem
from .slider import SliderBalance, SliderProblem, slider_problem
from .spring import SpringDesign, SpringProblem, spring_problem

__all__ = ["read_problem", "load_toml", "READERS", "solve_arm", "solve_spring", "solve_prismatic",
           "solve_pantograph", "solve_compare", "ArmProblem", "SpringProblem", "SliderProblem", "PantographProblem",
           "CompareProblem"]

#: table → the function reading its problem
READERS = {"arm": arm_problem, "spring": spring_problem, "slider": slider_problem, "pantograph": pantograph_problem,
           "compare": compare_problem}


def read_problem(doc: Mapping[str, Any], source: str = "<input>"):
    """The problem of a document holding exactly one balance table."""
    kinds = [k for k in READERS if k in doc]
    if len(kinds) != 1:
        others = [f"[{k}]" for k in doc if k not in OWNED_BY_RUNNER]
        raise SchemaError(f"{source}: a balance problem needs exactly one of the tables [arm], [spring], [slider], "
                          f"[pantograph] or [compare], not {', '.join(others) or 'none'}.")
    return READERS[kinds[0]](doc, source)


def solve_arm(doc: Mapping[str, Any], source: str = "<arm>") -> ArmBalance:
    """Balance the arm of an ``[arm]`` document (:class:`ArmProblem`)."""
    return arm_problem(doc, source).solve()


def solve_spring(doc: Mapping[str, Any], source: str = "<spring>") -> SpringDesign:
    """Fit and design the device of a ``[spring]`` document (:class:`SpringProblem`)."""
    return spring_problem(doc, source).solve()


def solve_prismatic(doc: Mapping[str, Any], source: str = "<slider>") -> SliderBalance:
    """Counter-masses of a ``[slider]`` document (:class:`SliderProblem`)."""
    return slider_problem(doc, source).solve()


def solve_pantograph(doc: Mapping[str, Any], source: str = "<pantograph>") -> PantographBalance:
    """Spring and cylinder force of a ``[pantograph]`` document (:class:`PantographProblem`)."""
    return pantograph_problem(doc, source).solve()


def solve_compare(doc: Mapping[str, Any], source: str = "<compare>") -> Comparison:
    """The strategies side by side for a ``[compare]`` document (:class:`CompareProblem`)."""
    return compare_problem(doc, source).solve()
