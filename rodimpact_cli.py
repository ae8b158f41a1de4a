"""Entry point of the ``rodimpact`` command.

It lives outside the ``rodimpact`` package so that it can catch Ctrl-C (and SIGTERM) while the package and its
dependencies (numpy, numba, xarray, ...) are still being imported: the command then exits with a one-line message
instead of a traceback. Everything else is :func:`rodimpact.cli.main`.
"""

from __future__ import annotations

import signal
import sys


def _terminate(signum, frame):
    raise KeyboardInterrupt


def main() -> int:
    """Import :mod:`rodimpact.cli` and run it; an interrupt during the imports ends quietly (exit 130 / 143)."""
    try:
        if hasattr(signal, "SIGTERM"):
            signal.signal(signal.SIGTERM, _terminate)
        from rodimpact.cli import main as cli_main
    except KeyboardInterrupt:
        print("rodimpact: interrupted while starting; nothing was written", file=sys.stderr)
        return 130
    return cli_main()


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
