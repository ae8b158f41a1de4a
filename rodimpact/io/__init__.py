"""File input/output: measurement-file readers, model files (TOML) and results of every kind on disk
(:func:`save`, :func:`load`). Data only: io never draws (the figures of the command line's output folders come from
:mod:`rodimpact.output_folders`).

Names are imported lazily (PEP 562) so that ``import rodimpact.io.model`` -- and with it the command line --
does not pay for the readers' scipy.signal import, and the readers do not pay for pint and xarray.
"""

from __future__ import annotations

import importlib
from typing import Any

_NAMES = {
    # measurement-file readers
    "hoppybar_bar": "recordings",
    "hoppybar_gains": "recordings",
    "RecordingError": "recordings",
    "read_csv_recording": "recordings",
    "read_hoppybar_input": "recordings",
    "read_lanl_raw": "recordings",
    "read_tdms": "recordings",
    "read_tektronix_csv": "recordings",
    # model files
    "Model": "model",
    "OutputSpec": "model",
    "load_model": "model",
    "loads_model": "model",
    "dump_model": "model",
    "save_model": "model",
    "model_from_result": "model",
    "ModelError": "quantities",
    "ModelWriteError": "model",
    "SafeExpression": "expressions",
    "expression_area": "expressions",
    # results on disk: every kind
    "save": "storage",
    "load": "storage",
    "summarize": "results",
    "format_summary": "results",
    "OutputExistsError": "results",
    "claim_output": "results",
    "save_reduction_csv": "shpb_reduction_spec",
}

__all__ = list(_NAMES)


def __getattr__(name: str) -> Any:
    if name in _NAMES:
        value = getattr(importlib.import_module(f"{__name__}.{_NAMES[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(list(globals()) + __all__)
