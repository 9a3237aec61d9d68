"""CLI commands for chains and mechanisms (type synthesis)."""


def add_commands(sub) -> None:
    """Mount ``chains`` and ``mechanisms`` on the ``mechsynth`` parser."""
