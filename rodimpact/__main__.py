"""``python -m rodimpact``: the command line (see :mod:`rodimpact.cli`)."""

from .cli import main

raise SystemExit(main())
