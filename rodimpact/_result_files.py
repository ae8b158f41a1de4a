"""Writing result files without ever clobbering what a user saved, and reading and writing netCDF files with an
engine that is installed (used by :mod:`rodimpact.io.storage`, :mod:`rodimpact.io.results` and the striker CSV)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any, Callable

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


def _read_engine(path: Path) -> str:
    """An installed xarray engine that reads ``path`` (NetCDF3 files start with b"CDF", NetCDF4 ones are HDF5)."""
    from importlib.util import find_spec

    with open(path, "rb") as fh:
        magic = fh.read(4)
    if magic.startswith(b"CDF"):
        return "scipy"
    if find_spec("h5netcdf") and find_spec("h5py"):
        return "h5netcdf"
    if find_spec("netCDF4"):
        return "netcdf4"
    raise RuntimeError(f"{path}: a NetCDF4 file; reading it needs h5py (pip install h5py) or netCDF4")


def read_netcdf(path: Path) -> Any:
    """The netCDF file ``path`` as an :class:`xarray.Dataset` in memory, with the numbers as stored (no time
    decoding, no masking). A file that is no NetCDF, or a damaged one, gives a ``ValueError`` naming it."""
    import xarray as xr

    try:
        return xr.load_dataset(path, engine=_read_engine(path), decode_times=False, decode_timedelta=False,
                               mask_and_scale=False)
    except PermissionError:
        raise PermissionError(f"{path}: no permission to read it") from None
    except (OSError, ValueError, KeyError, IndexError, TypeError) as exc:
        if isinstance(exc, FileNotFoundError):
            raise FileNotFoundError(f"{path}: no such file") from None
        raise ValueError(f"{path}: not a rodimpact result file (not readable as NetCDF); it is damaged or was not "
                         f"written by rodimpact.save") from None
