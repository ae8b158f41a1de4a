"""File permissions for files written through a temporary file (``tempfile.mkstemp`` creates them 0o600)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional


def umask() -> int:
    """The process umask (read without changing it where /proc allows, else set and restored at once)."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def normal_mode(existing: Optional[Path] = None, folder: bool = False) -> int:
    """Permissions for a new file or folder as open()/mkdir() would give them (0o666 / 0o777 less the umask), or
    those of the file it replaces."""
    if existing is not None:
        try:
            return existing.stat().st_mode & 0o7777
        except OSError:
            pass
    return (0o777 if folder else 0o666) & ~umask()
