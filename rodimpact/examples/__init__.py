"""Built-in example models from the thesis (model files shipped inside the package).

``rodimpact examples`` lists them, ``rodimpact examples run NAME -o OUTDIR`` runs one and writes its results and
plots, ``rodimpact examples copy NAME`` copies its model file for editing. Numbers the thesis text gives are kept;
dimensions it does not give are chosen and marked in each file's header comment and in ``examples/README.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any, Mapping, Optional

from ..io.model import Model, loads_model


@dataclass(frozen=True)
class Example:
    """A built-in example: one or more model files (run into sub-folders when there are several) and an
    optional comparison plot of their total energies (thesis Fig. 3.9)."""

    name: str
    title: str
    models: tuple[str, ...]
    labels: tuple[str, ...] = ()
    compare_energy: bool = False


EXAMPLES: dict[str, Example] = {e.name: e for e in (
    Example("first-example", "Thesis first example: stepped striker on a uniform rod (Fig. 3.5, Tab. 3.1)",
            ("first-example.toml",)),
    Example("complex-example", "Thesis complex example: varying geometry and material, bearings with friction "
                               "(Fig. 3.7, Tab. 3.2, Fig. 3.8)", ("complex-example.toml",)),
    Example("complex-example-energy", "Thesis complex example over 100 round trips, with and without friction "
                                      "(Fig. 3.9)",
            ("complex-example-friction.toml", "complex-example-no-friction.toml"),
            labels=("with friction (mu = 0.3)", "without friction"), compare_energy=True),
    Example("test-rig", "Thesis test rig (chapter 5): piston 1 (40/50/40 mm) hits a 50 mm x 1800 mm rod at "
                        "4.60 m/s; strain gauges at 110, 900, 1690 mm", ("test-rig.toml",)),
    Example("percussion-drilling", "Percussion drilling (Fig. 4.9, Tab. 4.5): piston, shank adapter, coupling "
                                   "sleeve, rod, bit with linear increase, bit-rock spring",
            ("percussion-drilling.toml",)),
)}


def _unknown(name: str) -> ValueError:
    return ValueError(f"examples: no example named {name!r}; available: {', '.join(EXAMPLES)}")


def example(name: str) -> Example:
    """The example called ``name``."""
    if name not in EXAMPLES:
        raise _unknown(name)
    return EXAMPLES[name]


def model_text(file: str) -> str:
    """The text of a shipped model file (works from an installed wheel)."""
    return resources.files(__name__).joinpath(file).read_text(encoding="utf-8")


def load_example(name: str, index: int = 0, overrides: Optional[Mapping[str, Any]] = None) -> Model:
    """The ``index``-th model of example ``name`` as a :class:`~rodimpact.io.model.Model`; ``overrides``: key path
    -> value set before the model is validated, as in :func:`rodimpact.io.model.load_model`."""
    ex = example(name)
    return loads_model(model_text(ex.models[index]), name=f"{name}:{ex.models[index]}", overrides=overrides)


def run_example(name: str, outdir: str | Path, *, overwrite: bool = False, plots: bool = True,
                progress: Optional[bool] = False,
                overrides: Optional[Mapping[str, Any]] = None) -> list[tuple[str, Any, Path]]:
    """Run every model of example ``name`` and write results and plots to ``outdir`` (sub-folders named after the
    model files when there are several, plus ``energy-comparison.png``). Returns (model file, result, folder)
    per model. The whole folder is written atomically and never replaces existing results unless ``overwrite``;
    even then only a folder rodimpact wrote (:func:`rodimpact.io.results.check_output_folder`). ``overrides``
    are set in every model of the example (:func:`load_example`)."""
    from ..io.results import AtomicFolder
    from ..output_folders import write_simulation
    from ..plotting import plot_energy_comparison

    ex = example(name)
    out = []
    with AtomicFolder(outdir, overwrite) as tmp:
        models = [load_example(name, i, overrides) for i in range(len(ex.models))]    # all checked first
        for file, model in zip(ex.models, models):
            result = model.simulate(progress=progress)
            # into the fresh temporary folder itself (it holds only AtomicFolder's marker) or a new sub-folder
            sub = tmp if len(ex.models) == 1 else tmp / Path(file).stem
            write_simulation(result, sub, model=model, overwrite=True, plots=model.output.plots if plots else (),
                             csv=model.output.csv, fields=model.output.fields,
                             snapshot_times=list(model.output.snapshot_times) or None)
            out.append((file, result, sub))
        if ex.compare_energy and plots:
            rod = out[0][1].system.rods[-1]
            ax = plot_energy_comparison([r for _, r, _ in out], list(ex.labels),
                                        round_trip_time=2.0 * rod.total_travel_time)
            ax.figure.savefig(tmp / "energy-comparison.png", dpi=120)
    final = Path(outdir)
    return [(f, r, final if len(ex.models) == 1 else final / Path(f).stem) for f, r, _ in out]
