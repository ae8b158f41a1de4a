"""Results on disk, one way for every kind: :func:`save` writes a result, :func:`load` reads it back.

============  ===============================================  ================================================
kind          ``save(result, path)`` writes                    ``load(path)`` returns
============  ===============================================  ================================================
simulation    a folder (:mod:`rodimpact.io.results`: model,    the :class:`~rodimpact.SimulationResult`, its
              ``result.nc``, CSV files, ``summary.json``)      system rebuilt from ``model.toml``
synthesis     one netCDF file (:meth:`SynthesisResult          the :class:`~rodimpact.SynthesisResult`, without
              .to_xarray`)                                     the struck system (it cannot ``verify()``)
design        one netCDF file (:meth:`DesignResult.to_xarray`)  the :class:`~rodimpact.DesignResult`, likewise
sweep         one netCDF file (the ``xarray.Dataset`` of        that ``xarray.Dataset``
              :func:`rodimpact.sweep`)
shpb          one netCDF file (:meth:`ShpbReduction             the :class:`~rodimpact.shpb.ShpbReduction`
reduction     .to_xarray`: a split-Hopkinson-bar reduction)
identifi-     one netCDF file (:meth:`IdentificationResult      the :class:`~rodimpact.identify.
cation        .to_xarray`), or with a ``.csv`` path the         IdentificationResult` (from a CSV: without the
              profile table (:mod:`rodimpact.io.                matched signals)
              identification`)
============  ===============================================  ================================================

This module owns the reading and writing; the result classes own their layout (``to_xarray`` and
``from_xarray``) and know nothing about files (docs/architecture.md, layers). Nothing a user saved is replaced
silently: an existing file or non-empty folder is refused unless ``overwrite=True`` (and a folder only if
rodimpact wrote it), and every file or folder is written under a temporary name and moved into place when
complete. :func:`load` recognises the kind: a folder by the result file it holds (the output folders of
``rodimpact simulate``, ``synthesize``, ``design``, ``sweep`` and ``shpb reduce``), a single file by its attributes.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Optional, Union

from .._moved import moved
from .._result_files import netcdf_engine, read_netcdf, write_new_file
from ..design.result import DesignResult
from ..direct.result import SimulationResult
from ..inverse.result import SynthesisResult
from .results import RESULT_FILE, save_simulation, simulation_from_dataset

if TYPE_CHECKING:
    import xarray

    from ..identify.result import IdentificationResult
    from ..shpb.result import ShpbReduction

Result = Union[SimulationResult, SynthesisResult, DesignResult, "ShpbReduction", "IdentificationResult",
               "xarray.Dataset"]
"""What :func:`save` takes and :func:`load` returns (the ``xarray.Dataset`` of a sweep)."""

#: The file that holds each kind of result in an output folder.
FOLDER_FILES = {"simulation": RESULT_FILE, "synthesis": "synthesis.nc", "design": "design.nc", "sweep": "sweep.nc",
                "shpb reduction": "reduction.nc", "identification": "identification.nc"}
#: The attributes by which :func:`load` recognises the kind of a netCDF file (every file rodimpact wrote has them).
KIND_ATTRIBUTES = {"simulation": ("format_version", "rod_methods"), "synthesis": ("n_requested", "impact_force_n0"),
                   "design": ("objective", "constraint_report"), "sweep": ("points", "runner"),
                   "shpb reduction": ("specimen_length", "pass_limit"), "identification": ("anomalies", "toe_band")}
#: What :func:`save` no longer takes, and where it went: io writes data files only (docs/architecture.md, layers).
FIGURES_MOVED = {
    "plots": "plots: rodimpact.save writes the data files only; the folder with figures, as the command line "
             "writes it, is rodimpact.output_folders.write_simulation(result, outdir, plots=[...]) (or draw them "
             "with rodimpact.plotting.save_plots)",
    "snapshot_times": "snapshot_times: a setting of the snapshot plot; give it to "
                      "rodimpact.output_folders.write_simulation(result, outdir, plots=['snapshots'], "
                      "snapshot_times=[...])",
}


@moved(FIGURES_MOVED)
def save(result: Result, path: str | Path, *, overwrite: bool = False, engine: Optional[str] = None,
         model: Any = None, csv: Optional[bool] = None, fields: Optional[bool] = None) -> Path:
    """Write ``result`` (a simulation, synthesis or design result, a split-Hopkinson-bar reduction, or the dataset
    of :func:`rodimpact.sweep`) to
    ``path`` and return the path: a folder for a simulation, one netCDF file otherwise (this module's docstring).

    An existing file, or a non-empty folder, is refused (``FileExistsError``; :class:`OutputExistsError` for a
    folder) unless ``overwrite=True``; even then a folder holding files rodimpact did not write is never replaced.
    ``engine``: the xarray netCDF engine (default: h5netcdf with h5py, else netcdf4, else scipy).

    Only for a simulation's folder: ``model`` (written as ``model.toml``; by default one is built from the
    result), ``csv`` (write ``signals.csv`` and ``energy.csv``, default ``True``) and ``fields`` (keep the field
    snapshots, default ``True``): :func:`rodimpact.io.results.save_simulation`.
    """
    if isinstance(result, SimulationResult):
        return save_simulation(result, path, model=model, overwrite=overwrite, csv=True if csv is None else csv,
                               fields=True if fields is None else fields, engine=engine)
    given = [name for name, value in (("model", model), ("csv", csv), ("fields", fields)) if value is not None]
    if Path(path).suffix.lower() == ".csv":
        from .identification import save_identification_csv

        if given:
            raise TypeError(f"{given[0]}: an option of a simulation's results folder, not of a CSV table")
        return save_identification_csv(result, path, overwrite=overwrite)
    ds = _dataset(result)
    if given:
        raise TypeError(f"{given[0]}: an option of a simulation's results folder; a {kind_of(ds.attrs)} result is "
                        f"saved as one netCDF file")
    return write_new_file(path, lambda tmp: ds.to_netcdf(tmp, engine=engine or netcdf_engine()), overwrite)


def load(path: str | Path) -> Result:
    """Read a result written by :func:`save` (or the output folder of ``rodimpact simulate``, ``synthesize``,
    ``design``, ``sweep`` or ``shpb reduce``, or the result file in it) back: identical arrays, of the kind it was saved as (this
    module's docstring). A path that holds no rodimpact result gives a ``FileNotFoundError`` or a ``ValueError``
    that names it."""
    p = Path(path)
    if p.is_dir():
        for kind, name in FOLDER_FILES.items():
            if (p / name).is_file():
                return _from_file(p / name, kind)
        raise FileNotFoundError(f"{p}: no result here (none of {', '.join(FOLDER_FILES.values())}); is this a folder "
                                f"written by rodimpact (simulate, synthesize, design, sweep, shpb reduce) or rodimpact.save?")
    if not p.exists():
        raise FileNotFoundError(f"{p}: no such file or folder")
    if p.suffix.lower() == ".csv":
        from .identification import read_identification_csv

        return read_identification_csv(p)
    return _from_file(p)


def kind_of(attrs: Mapping[str, Any]) -> Optional[str]:
    """The kind of result a dataset with these attributes holds (:data:`KIND_ATTRIBUTES`), or ``None``."""
    return next((k for k, names in KIND_ATTRIBUTES.items() if all(n in attrs for n in names)), None)


def _from_file(p: Path, kind: Optional[str] = None) -> Result:
    """The result in the netCDF file ``p``: of ``kind`` (known from its name in an output folder) or of the kind
    its attributes show."""
    ds = read_netcdf(p)
    found = kind_of(ds.attrs)
    kind = kind or found
    if kind is None:
        raise ValueError(f"{p}: a netCDF file, but no rodimpact result (simulation, synthesis, design, sweep, "
                         f"shpb reduction or identification); "
                         f"it was not written by rodimpact.save")
    if kind == "simulation":            # also the files of formats 1 and 2, with their own checks
        return simulation_from_dataset(ds, p)
    if found != kind:
        raise _incomplete(p, kind, f"it holds a {found} result" if found else "another netCDF file")
    if kind == "sweep":
        import xarray as xr

        return xr.decode_cf(ds, decode_times=False, decode_timedelta=False)
    try:
        return _result_class(kind).from_xarray(ds)
    except (KeyError, IndexError, TypeError, ValueError) as exc:
        raise _incomplete(p, kind, f"no {exc}" if isinstance(exc, KeyError) else "malformed data") from None


def _result_class(kind: str) -> Any:
    """The class that reads a result of ``kind`` from its dataset (the reduction's imported on use: the
    split-Hopkinson-bar package loads scipy.integrate and the Kolsky-bar model)."""
    if kind == "shpb reduction":
        from ..shpb.result import ShpbReduction

        return ShpbReduction
    if kind == "identification":
        from ..identify.result import IdentificationResult

        return IdentificationResult
    return SynthesisResult if kind == "synthesis" else DesignResult


def _incomplete(p: Path, kind: str, what: str) -> ValueError:
    """The error for a file that does not hold the complete ``kind`` of result it should."""
    return ValueError(f"{p}: not a complete rodimpact {kind} result ({what}); the file is damaged or was not "
                      f"written by rodimpact.save")


def _dataset(result: Any) -> "xarray.Dataset":
    """The dataset a synthesis, design, sweep or split-Hopkinson-bar result is saved as; anything else is refused
    naming its type."""
    import xarray as xr

    if isinstance(result, (SynthesisResult, DesignResult)):
        return result.to_xarray()
    if isinstance(result, xr.Dataset) and kind_of(result.attrs) == "sweep":
        return result
    from ..shpb.result import ShpbReduction      # loaded already if result is one (only a wrong type pays for it)

    if isinstance(result, ShpbReduction):
        return result.to_xarray()
    from ..identify.result import IdentificationResult

    if isinstance(result, IdentificationResult):
        return result.to_xarray()
    what = ("an xarray.Dataset that rodimpact.sweep did not make (save it with its to_netcdf)"
            if isinstance(result, xr.Dataset) else type(result).__name__)
    raise TypeError(f"result: must be a SimulationResult, SynthesisResult, DesignResult, ShpbReduction, "
                    f"IdentificationResult or the "
                    f"xarray.Dataset of rodimpact.sweep, got {what}")
