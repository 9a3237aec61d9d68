"""``python -m mechsynth …`` is the ``mechsynth`` command."""

from .cli import main

raise SystemExit(main())
