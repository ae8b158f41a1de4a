"""Output folders with figures, as the command line writes them: the data files of :mod:`rodimpact.io` and the
figures of :mod:`rodimpact.plotting` in one folder, written atomically.

io writes data only and plotting only draws; neither imports the other (docs/architecture.md, layers). This
module sits above both and puts them together for ``rodimpact simulate``, ``sweep``, ``synthesize``, ``design``,
``shpb predict`` and ``shpb reduce`` and for :func:`rodimpact.examples.run_example`. Every folder is written into a
temporary folder and moved into place at the end (:class:`rodimpact.io.results.AtomicFolder`: an existing folder is replaced only with
``overwrite=True`` and only if rodimpact wrote it), so its ``summary.json`` lists the figures too. A result's
data alone: :func:`rodimpact.save`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Optional, Sequence

from .io import design_spec, model_sweep, shpb_reduction_spec, shpb_spec, synthesis_spec
from .io.results import AtomicFolder, simulation_summary, write_simulation_files, write_summary
from .plotting import design as design_plots
from .plotting import new_axes, plot_sweep, save_plots
from .plotting import shpb_model as shpb_model_plots
from .plotting import shpb_reduction as shpb_reduction_plots
from .plotting import synthesis as synthesis_plots

#: The plot file of a sweep folder.
SWEEP_PLOT_FILE = "sweep.png"
#: Resolution of the figures of a synthesis, design or sweep folder, dots per inch.
DPI = 120
Job = tuple[str, Callable[[Any], Any]]
"""A figure to write: its file name and a function that draws it on a given Axes."""


def write_simulation(result: Any, outdir: str | Path, *, model: Any = None, overwrite: bool = False,
                     plots: Sequence[str] = (), csv: bool = True, fields: bool = True,
                     snapshot_times: Optional[Sequence[float]] = None) -> dict[str, Any]:
    """Write the results folder of a simulation: the data files of :func:`rodimpact.io.results.save_simulation`
    (``model``, ``csv``, ``fields`` as there) and the figures ``plots`` names in ``plots/``
    (:func:`rodimpact.plotting.save_plots`, with ``snapshot_times`` for the snapshot plot; a plot that cannot be
    drawn is noted in ``summary.json``). Returns the summary written to ``summary.json`` (with its ``files`` and
    ``notes``), so that a caller need not read it back. Nothing is put in place when an argument is refused."""
    names = [plots] if isinstance(plots, str) else list(plots)
    for i, p in enumerate(names):
        if p in names[:i]:
            raise ValueError(f"plots: {p!r} is listed twice")
    with AtomicFolder(outdir, overwrite) as tmp:
        files, notes = write_simulation_files(result, tmp, model=model, csv=csv, fields=fields)
        if names:
            written, plot_notes = save_plots(result, tmp / "plots", names, snapshot_times=snapshot_times)
            files += [f"plots/{p.name}" for p in written]
            notes += plot_notes
        summary = simulation_summary(result, model, files, notes)
        write_summary(tmp, summary)
    return summary


def write_spec_run(run: Any, spec: Any, outdir: str | Path, *, overwrite: bool = False,
                   plots: bool = True) -> dict[str, Any]:
    """Write the output folder of ``rodimpact synthesize`` or ``rodimpact design``: the data files of the run
    (:func:`rodimpact.io.synthesis_spec.write_files` / :func:`rodimpact.io.design_spec.write_files`),
    ``verification/`` (the direct simulation of the striker, with its ``model.toml``, and its force and profile
    plots), ``plots/`` (not with ``plots=False`` or ``plots = false`` in the spec) and ``summary.json`` (the run's
    summary with the list of files). Returns the summary."""
    synthesis = isinstance(run, synthesis_spec.SynthesisRun)
    module: Any = synthesis_spec if synthesis else design_spec
    plots = plots and spec.plots
    with AtomicFolder(outdir, overwrite) as tmp:
        files = module.write_files(run, spec, tmp)
        if run.verification is not None:
            write_simulation(run.verification.simulation, tmp / "verification", overwrite=True,
                             plots=("forces", "profile") if plots else ())
            files.append("verification/")
        if plots:
            jobs = _synthesis_plots(run) if synthesis else _design_plots(run.result)
            files += [f"plots/{name}" for name in _draw(tmp / "plots", jobs)]
        summary = module.summarize_run(run, spec)
        summary["files"] = files + ["summary.json"]
        return write_summary(tmp, summary)


def write_sweep(ds: Any, data: dict[str, Any], outdir: str | Path, *, overwrite: bool = False,
                plots: bool = True) -> dict[str, Any]:
    """Write the output folder of ``rodimpact sweep``: the table (:func:`rodimpact.io.model_sweep.write_files`),
    ``sweep.png`` (every quantity against every grid key, :func:`rodimpact.plotting.plot_sweep`; not with
    ``plots=False``, and noted instead when it cannot be drawn: the table is the result) and ``summary.json``
    (``data``, :func:`rodimpact.io.model_sweep.summary`, with the list of files). Returns the summary."""
    notes: list[str] = []
    figure = None
    if plots:
        try:
            figure = plot_sweep(ds)
        except (ValueError, ImportError) as exc:
            notes.append(f"plot {SWEEP_PLOT_FILE} skipped: {exc}")
    with AtomicFolder(outdir, overwrite) as tmp:
        files = model_sweep.write_files(ds, data, tmp)
        if figure is not None:
            figure.savefig(tmp / SWEEP_PLOT_FILE, dpi=DPI)
            files.append(SWEEP_PLOT_FILE)
        return write_summary(tmp, {**data, "files": files + ["summary.json"], **({"notes": notes} if notes else {})})


def write_shpb_prediction(run: Any, spec: Any, outdir: str | Path, *, overwrite: bool = False,
                          plots: bool = True) -> dict[str, Any]:
    """Write the output folder of ``rodimpact shpb predict``: the data files of the prediction
    (:func:`rodimpact.io.shpb_spec.write_files`), ``plots/`` (the aligned gauge signals, the specimen's stress-strain
    curve and strain rate of :mod:`rodimpact.plotting.shpb_model`; not with ``plots=False`` or ``plots = false`` in
    the spec) and ``summary.json`` (:func:`rodimpact.io.shpb_spec.summarize_run` with the list of files). Returns
    the summary."""
    p = run.prediction
    jobs: list[Job] = [("signals.png", lambda ax: shpb_model_plots.plot_predicted_signals(p, ax=ax)),
                       ("stress-strain.png", lambda ax: shpb_model_plots.plot_predicted_stress_strain(p, ax=ax)),
                       ("strain-rate.png", lambda ax: shpb_model_plots.plot_predicted_strain_rate(p, ax=ax))]
    with AtomicFolder(outdir, overwrite) as tmp:
        files = shpb_spec.write_files(run, spec, tmp)
        if plots and spec.plots:
            files += [f"plots/{name}" for name in _draw(tmp / "plots", jobs)]
        return write_summary(tmp, {**shpb_spec.summarize_run(run, spec), "files": files + ["summary.json"]})


def write_shpb_reduction(reduction: Any, spec: Any, summary: dict[str, Any], outdir: str | Path, *,
                         overwrite: bool = False, plots: bool = True) -> dict[str, Any]:
    """Write the output folder of ``rodimpact shpb reduce``: the data files
    (:func:`rodimpact.io.shpb_reduction_spec.write_files`: ``reduction.csv``, ``reduction.nc``, ``spec.toml``),
    ``plots/`` (``pulses.png``, ``stress-strain.png``, ``strain-rate.png``, ``equilibrium.png``: the figures of
    :mod:`rodimpact.plotting.shpb_reduction`; not with ``plots=False`` or ``plots = false`` in the spec) and
    ``summary.json`` (``summary`` with the list of files). Returns the summary."""
    with AtomicFolder(outdir, overwrite) as tmp:
        files = shpb_reduction_spec.write_files(reduction, spec, tmp)
        if plots and spec.plots:
            files += [f"plots/{name}" for name in _draw(tmp / "plots", _shpb_plots(reduction))]
        summary["files"] = files + ["summary.json"]
        return write_summary(tmp, summary)


def _shpb_plots(reduction: Any) -> list[Job]:
    """The figures of :mod:`rodimpact.plotting.shpb_reduction` for a split-Hopkinson-bar reduction."""
    return [(f"{name.replace('_', '-')}.png",
             lambda ax, draw=getattr(shpb_reduction_plots, f"plot_{name}"): draw(reduction, ax=ax))
            for name in ("pulses", "stress_strain", "strain_rate", "equilibrium")]


def _synthesis_plots(run: Any) -> list[Job]:
    """The figures of :mod:`rodimpact.plotting.synthesis` for a synthesis run (with its verification and shape)."""
    jobs = [("impedance.png", lambda ax: synthesis_plots.plot_impedance(run.result, ax=ax)),
            ("force.png", lambda ax: synthesis_plots.plot_force(run.result, run.verification, ax=ax)),
            ("existence.png", lambda ax: synthesis_plots.plot_existence(run.result, ax=ax))]
    if run.shape is not None:
        jobs.append(("shape.png", lambda ax: synthesis_plots.plot_shape(run.shape, ax=ax)))
    return jobs


def _design_plots(result: Any) -> list[Job]:
    """The figures of :mod:`rodimpact.plotting.design` for a design result."""
    return [("force.png", lambda ax: design_plots.plot_design_force(result, ax=ax)),
            ("profile.png", lambda ax: design_plots.plot_design_profile(result, ax=ax)),
            ("convergence.png", lambda ax: design_plots.plot_convergence(result, ax=ax))]


def _draw(folder: Path, jobs: list[Job]) -> list[str]:
    """Draw each job on its own pyplot-free figure (headless) into ``folder``; returns the file names."""
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for name, draw in jobs:
        fig, ax = new_axes(None)
        draw(ax)
        fig.savefig(folder / name, dpi=DPI)
        written.append(name)
    return written


def write_identification(result: Any, spec: Any, summary: dict[str, Any], outdir: str | Path, *,
                         overwrite: bool = False, plots: bool = True) -> dict[str, Any]:
    """Write the output folder of ``rodimpact identify``: the data files
    (:func:`rodimpact.io.identify_spec.write_files`: ``profile.csv``, ``identification.nc``, ``spec.toml``),
    ``plots/profile.png`` and ``plots/reflectogram.png`` (beta: with the spec's exponential amplification) or
    ``plots/matched.png`` (:mod:`rodimpact.plotting.identify`; not with ``plots=False`` or ``plots = false`` in
    the spec) and ``summary.json``. Returns the summary."""
    from .io import identify_spec
    from .plotting import identify as identify_plots

    with AtomicFolder(outdir, overwrite) as tmp:
        files = identify_spec.write_files(result, spec, tmp)
        if plots and spec.plots:
            jobs: list[Job] = [("profile.png", lambda ax: identify_plots.plot_identified_profile(result, ax=ax))]
            if "reflectogram" in result.matched:
                rate = spec.values["identify"]["amplification"]
                jobs.append(("reflectogram.png", lambda ax: identify_plots.plot_reflectogram(
                    result, amplification=rate, ax=ax)))
            elif result.matched:
                jobs.append(("matched.png", lambda ax: identify_plots.plot_matched(result, ax=ax)))
            files += [f"plots/{name}" for name in _draw(tmp / "plots", jobs)]
        summary["files"] = files + ["summary.json"]
        return write_summary(tmp, summary)
