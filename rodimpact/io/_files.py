"""Reading input files safely (regular files only, with a size limit) and writing text files atomically.

Model files, synthesis specs, the CSV tables and force files they name, and gauge recordings are read through
:func:`read_bytes_limited`: a folder, FIFO, socket or device (``/dev/zero``, ``/dev/urandom``) is refused before
anything is read (the file is opened without blocking and checked with ``fstat``), and a file larger than
:func:`max_input_bytes` is refused with a message saying how to lift the limit.
"""

from __future__ import annotations

import os
import stat
import tempfile
from pathlib import Path

from .._permissions import normal_mode
from .quantities import ModelError

#: Largest model, spec or table file read, bytes; the environment variable ``RODIMPACT_MAX_INPUT_MB`` (MiB) lifts it.
MAX_INPUT_BYTES = 64 * 2**20


def max_input_bytes() -> int:
    """The input file size limit in bytes: :data:`MAX_INPUT_BYTES`, or ``RODIMPACT_MAX_INPUT_MB`` MiB if set."""
    text = os.environ.get("RODIMPACT_MAX_INPUT_MB", "").strip()
    try:
        return int(float(text) * 2**20) if text else MAX_INPUT_BYTES
    except (ValueError, OverflowError):
        raise ModelError(f"RODIMPACT_MAX_INPUT_MB: expected a number of MiB, got {text[:40]!r}") from None


def read_bytes_limited(path: Path, label: str, kind: str) -> bytes:
    """The bytes of ``path`` after checking it is a regular file (not a folder, FIFO, socket or device such as
    /dev/zero: opened without blocking and checked before reading) of at most :func:`max_input_bytes` bytes; every
    failure is a :class:`ModelError` starting with ``label`` (the key path, or the file itself)."""
    name = repr(str(path))
    who = "" if label == str(path) else f" {name}"
    limit = max_input_bytes()
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0) | getattr(os, "O_NOCTTY", 0)
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise ModelError(f"{label}: no such {kind}{who}") from None
    except IsADirectoryError:
        raise ModelError(f"{label}: " + ("is" if not who else f"{name} is") + f" a folder, not a {kind}") from None
    except PermissionError:
        raise ModelError(f"{label}: no permission to read {name}") from None
    except OSError as exc:
        raise ModelError(f"{label}: cannot read {name} ({exc.strerror or exc})") from None
    try:
        st = os.fstat(fd)
        if stat.S_ISDIR(st.st_mode):
            raise ModelError(f"{label}: " + ("is" if not who else f"{name} is") + f" a folder, not a {kind}")
        if not stat.S_ISREG(st.st_mode):
            raise ModelError(f"{label}: {name} is not a regular file (a device, pipe or socket); expected a {kind}")
        if st.st_size > limit:
            raise ModelError(f"{label}: {name} has {st.st_size:,} bytes, more than the limit of {limit:,} for a "
                             f"{kind}; set RODIMPACT_MAX_INPUT_MB to read larger files")
        if hasattr(os, "set_blocking"):
            os.set_blocking(fd, True)
        chunks, total = [], 0
        while True:
            chunk = os.read(fd, min(1 << 20, limit + 1 - total))
            if not chunk:
                break
            chunks.append(chunk)
            total += len(chunk)
            if total > limit:      # the file grew while we read it
                raise ModelError(f"{label}: {name} has more than {limit:,} bytes, the limit for a {kind}; set "
                                 f"RODIMPACT_MAX_INPUT_MB to read larger files")
        return b"".join(chunks)
    except OSError as exc:
        raise ModelError(f"{label}: cannot read {name} ({exc.strerror or exc})") from None
    finally:
        os.close(fd)


def write_text_atomic(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file in the same folder and an atomic rename.

    The file gets normal permissions (0o666 less the umask, or those of the file it replaces), not the 0o600 of a
    temporary file. ``path`` may not be a folder (:class:`IsADirectoryError` naming it).
    """
    p = Path(path)
    if p.is_dir():
        raise IsADirectoryError(f"{p}: is a folder, not a file; give a file name")
    p.parent.mkdir(parents=True, exist_ok=True)
    mode = normal_mode(p if p.is_file() else None)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        os.chmod(tmp, mode)
        os.replace(tmp, p)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
