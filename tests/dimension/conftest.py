"""Fixtures of the dimension tests: the benchmark scripts' problems, loaded as modules."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


def _benchmark(name: str):
    """The script benchmarks/NAME.py loaded as a module (registered while in use: its dataclasses look their
    module up), removed again after the tests of a module."""
    spec = importlib.util.spec_from_file_location(name, BENCHMARKS / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    yield module
    del sys.modules[spec.name]


@pytest.fixture(scope="module")
def bench():
    """benchmarks/bench_dimension.py: the classical path problems (``PROBLEMS``, ``EIGHTEEN``, …)."""
    yield from _benchmark("bench_dimension")


@pytest.fixture(scope="module")
def hcdj():
    """benchmarks/hcdj_ten_points.py: [HCDJ]'s ten points, their weights, bound and the source's closed form."""
    yield from _benchmark("hcdj_ten_points")


@pytest.fixture(scope="module")
def slider_bench():
    """benchmarks/bench_slider_function.py: random offset slider-cranks' functions, their closed form."""
    yield from _benchmark("bench_slider_function")


@pytest.fixture(scope="module")
def motion_poses():
    """benchmarks/bench_motion_poses.py: random four-bars and slider-cranks and their coupler poses."""
    yield from _benchmark("bench_motion_poses")
