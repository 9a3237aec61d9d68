"""Shared fixtures of the balance tests; puts the repository root on sys.path."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

MODELS = ROOT / "models"


@pytest.fixture
def model():
    """Load ``models/NAME.toml`` as a dict."""
    import tomllib

    def load(name: str) -> dict:
        with open(MODELS / f"{name}.toml", "rb") as fh:
            return tomllib.load(fh)

    return load
