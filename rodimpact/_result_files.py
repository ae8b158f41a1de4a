"""Writing result files without ever clobbering what a user saved, and the netCDF engine to write them with
(shared by the synthesis and design results)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Callable

from ._permissions import normal_mode


def write_new_file(path: str | Path, write: Callable[[Path], None], overwrite: bool = False) -> Path:
    """Call ``write(tmp)`` on a temporary file next to ``path`` and move it into place atomically.

    An existing ``path`` is refused (``FileExistsError`` naming it) unless ``overwrite=True``; an interrupted
    write leaves no half-written file behind.
    """
    path = Path(path)
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path}: exists; choose another file name or pass overwrite=True to replace it")
    if not path.parent.is_dir():
        raise FileNotFoundError(f"{path.parent}: no such folder to write {path.name} into")
    mode = normal_mode(path if path.is_file() else None)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        write(Path(tmp))
        os.chmod(tmp, mode)      # mkstemp's 0o600 -> what open() would have given
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def netcdf_engine() -> str:
    """An xarray netCDF engine that is installed: h5netcdf (needs h5py), netCDF4 or scipy (NetCDF3)."""
    from importlib.util import find_spec

    if find_spec("h5netcdf") and find_spec("h5py"):
        return "h5netcdf"
    if find_spec("netCDF4"):
        return "netcdf4"
    return "scipy"
