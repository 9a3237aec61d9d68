"""The command groups of ``mechsynth``: each module mounts its sub-commands with ``add_commands(sub)``."""
