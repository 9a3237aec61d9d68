"""The one base of every error the project raises on purpose.

Each engine's errors (``synth.SynthesisError``, ``balance.BalanceError``) derive from
:class:`ProjectError`, whose message is one sentence a designer understands; the application
prints it and exits with status 2.

>>> issubclass(ProjectError, Exception)
True
"""

from __future__ import annotations

__all__ = ["ProjectError"]


class ProjectError(Exception):
    """An error whose message is one sentence for a designer (what is wrong, and where)."""
