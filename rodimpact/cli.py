"""The ``rodimpact`` command line: thin wrappers around the Python API (output folders with figures:
:mod:`rodimpact.output_folders`).

Commands: ``simulate MODEL.toml``, ``sweep MODEL.toml``, ``init [simulate|synthesize|design|shpb|identify|drive]``,
``examples [list|run|show|copy]``, ``synthesize SPEC.toml``, ``design SPEC.toml``, ``shpb predict SPEC.toml``,
``shpb reduce RECORDING...``, ``identify RECORD... --spec SPEC.toml``, ``drive SPEC.toml``,
``docs [TOPIC]`` and ``--version``; see docs/cli.md.

Python warnings raised while a command runs are printed once each, as ``warning: <message>`` on stderr (never with
``--quiet``), without the source location that Python's default display adds.

Exit codes: 0 success, 2 bad input (model file, arguments, existing output; the message says what and where),
1 internal error (a bug: please report it with the traceback shown by ``RODIMPACT_DEBUG=1``), 130 interrupted
(Ctrl-C), 143 terminated (SIGTERM, handled like Ctrl-C). The output folder is claimed for the whole command
(:func:`rodimpact.io.results.claim_output`); limits and guarantees: docs/security.md.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import threading
import traceback
import warnings
from contextlib import nullcontext
from pathlib import Path
from typing import Any, Callable, Optional, Sequence

from ._version import __version__

EXIT_OK, EXIT_INTERNAL, EXIT_INPUT = 0, 1, 2
#: ``synthesize``: the exact striker does not exist over the requested span; the part that exists is reported
#: (and written, with an output folder). docs/cli.md, "Exit codes".
EXIT_NO_EXACT = 3


class InputError(Exception):
    """Bad input: reported as ``rodimpact: error: ...`` with exit code 2."""


# ============================================================================================ helpers
def _err(msg: str) -> None:
    print(f"rodimpact: error: {msg}", file=sys.stderr)


def _input_phase(fn: Callable[[], Any]) -> Any:
    """Run ``fn``; ValueError/TypeError (bad model, bad settings) become :class:`InputError`."""
    try:
        return fn()
    except (ValueError, TypeError) as exc:
        raise InputError(str(exc)) from exc


def _progress(args: argparse.Namespace) -> Optional[bool]:
    """Progress on stderr for long runs (a bar on a terminal, else a line every 10 %; the solver decides what is
    long), never with --quiet."""
    return False if args.quiet else None


class WarningLines:
    """Python warnings of one command on stderr: each distinct message once, as ``warning: <message>`` (no source
    location), and none with ``--quiet``. Installed as ``warnings.showwarning`` while the command runs."""

    def __init__(self, quiet: bool) -> None:
        self.quiet, self.seen, self.lock = quiet, set(), threading.Lock()

    def show(self, text: str) -> None:
        with self.lock:               # sweeps warn from worker threads
            new = text not in self.seen
            self.seen.add(text)
        if new and not self.quiet:
            print(f"warning: {text}", file=sys.stderr, flush=True)

    def showwarning(self, message: Any, category: Any, filename: str, lineno: int, file: Any = None,
                    line: Any = None) -> None:
        self.show(str(message))


def _report(summary: dict, text: str, args: argparse.Namespace, extra: str = "",
            warned: Sequence[str] = ()) -> None:
    """Print the summary (``text``, or JSON with --json; nothing with --quiet) and the warnings it lists,
    ``warned`` (on stderr, once each: :class:`WarningLines`)."""
    from .io.results import summary_json

    for w in warned:
        args.warning_lines.show(w)
    if args.json:
        print(summary_json(summary), end="")
    elif not args.quiet:
        print(text)
        if extra:
            print(extra)


def _without_warnings(summary: dict) -> dict:
    """``summary`` for the text on stdout: its warnings go to stderr (:func:`_report`)."""
    return {**summary, "warnings": []}


def _output(args: argparse.Namespace, default: str) -> Optional[Path]:
    """The output folder (``-o``, else ``results/<default>``), or ``None`` when nothing is written: with
    --no-output, and with --json unless -o names a folder."""
    if args.no_output or (args.json and args.output is None):
        return None
    return Path(args.output) if args.output else Path("results") / default


def _overrides(args: argparse.Namespace) -> dict[str, Any]:
    """The ``--set KEY=VALUE`` options as key path -> value (TOML values or plain text)."""
    from .io.overrides import parse_assignment, parse_value

    out: dict[str, Any] = {}
    for item in args.set or ():
        key, text = _input_phase(lambda: parse_assignment(item))
        if key in out:
            raise InputError(f"--set {key}: given twice")
        out[key] = parse_value(text)
    return out


def _claim_out(path: Optional[Path], force: bool):
    """Claim the output folder before any work is done, for the whole command (a context manager; nothing to
    claim for ``None``): refused when another run is writing it, when its parent cannot be created
    (``-o some_file/sub``), when it is non-empty without --force, holds files rodimpact did not write, or is the
    current working folder (see :func:`rodimpact.io.results.claim_output`)."""
    from .io.results import OutputExistsError, claim_output

    if path is None:
        return nullcontext()
    try:
        return claim_output(path, force)
    except OutputExistsError as exc:
        raise InputError(str(exc)) from None


def _file_target(output: Optional[str], default: str) -> Path:
    """The file ``-o`` names: ``default`` in the current folder without ``-o``, or inside ``output`` when that is
    an existing folder or ends in a path separator (``-o newdir/``)."""
    if output is None:
        return Path(default)
    seps = tuple(s for s in (os.sep, os.altsep) if s)
    if output.endswith(seps) or Path(output).is_dir():
        return Path(output) / default
    return Path(output)


def _write_file(path: Path, text: str, force: bool, what: str = "file") -> None:
    """Write a text file for the user: refuse to replace one without --force, never write over a folder, and
    turn file-system errors into input errors naming the path."""
    from .io.results import write_text_atomic

    if path.is_dir():
        raise InputError(f"{path}: is a folder, not a {what}; give a file name with -o")
    if (path.exists() or path.is_symlink()) and not force:
        raise InputError(f"{path}: exists; choose another file with -o or use --force to replace it")
    try:
        write_text_atomic(path, text)
    except OSError as exc:
        raise InputError(f"{path}: cannot be written ({exc.strerror or exc})") from None


# ============================================================================================ simulate
def cmd_simulate(args: argparse.Namespace) -> int:
    from .io.preflight import check_run
    from .io.model import load_model
    from .io.results import format_summary, summarize
    from .output_folders import write_simulation

    model_path = Path(args.model)
    out = _output(args, model_path.stem)
    with _claim_out(out, args.force):
        model = _input_phase(lambda: load_model(model_path, _overrides(args)))
        plots = () if args.no_plots else model.output.plots
        _input_phase(lambda: check_run(model, out, plots, args.max_element_updates))
        result = _input_phase(lambda: model.simulate(progress=_progress(args),
                                                     max_element_updates=args.max_element_updates))
        if out is not None:
            summary = write_simulation(result, out, model=model, overwrite=args.force, plots=plots,
                                       csv=model.output.csv, fields=model.output.fields,
                                       snapshot_times=list(model.output.snapshot_times) or None)
    computed = summarize(result)
    text = format_summary(_without_warnings(computed), model.title or model_path.name)
    if out is None:
        _report({**computed, "title": model.title} if model.title else computed, text, args,
                warned=computed["warnings"])
        return EXIT_OK
    notes = "".join(f"note: {n}\n" for n in summary.get("notes", []))
    _report(summary, text, args, f"{notes}results written to {out}", computed["warnings"])
    return EXIT_OK


# ============================================================================================ sweep
def cmd_sweep(args: argparse.Namespace) -> int:
    from .io.model_sweep import check_model_grid_size, format_sweep, parse_grid, summary, sweep_model
    from .output_folders import write_sweep

    model_path = Path(args.model)
    grid = _input_phase(lambda: parse_grid(args.grid))
    _input_phase(lambda: check_model_grid_size([len(v) for v in grid.values()], "--grid"))
    overrides = _overrides(args)
    out = _output(args, f"{model_path.stem}-sweep")
    with _claim_out(out, args.force):
        ds = _input_phase(lambda: sweep_model(model_path, grid, overrides, workers=args.workers,
                                              progress=_progress(args), max_element_updates=args.max_element_updates))
        data = summary(ds, model_path, overrides)
        if out is not None:
            write_sweep(ds, data, out, overwrite=args.force, plots=not args.no_plots)
    title = f"sweep of {model_path.name}: {data['points']} runs ({data['runner']}), {data['wall_time_s']:.2f} s"
    _report(data, format_sweep(ds, title), args, f"table written to {out / 'sweep.csv'}" if out else "")
    return EXIT_OK


# ============================================================================================ init
def cmd_init(args: argparse.Namespace) -> int:
    kind = args.kind
    templates = _templates()
    if kind not in templates:
        raise InputError(f"init: no template {kind!r}; available: {', '.join(templates)}")
    text, default = templates[kind]
    path = _file_target(args.output, default)
    _write_file(path, text, args.force, "model file" if kind == "simulate" else "spec file")
    if not args.quiet:
        cmd = {"synthesize": "synthesize", "design": "design", "shpb": "shpb predict",
               "identify": "identify RECORD.csv --spec", "drive": "drive"}.get(kind, "simulate")
        print(f"wrote {path}; edit it, then run:  rodimpact {cmd} {path}")
    return EXIT_OK


def _templates() -> dict[str, tuple[str, str]]:
    from .io import synthesis_spec
    from .io.templates import TEMPLATES

    from .io import design_spec, identify_spec, pile_spec, shpb_spec

    return {**TEMPLATES, "synthesize": (synthesis_spec.TEMPLATE, "synthesis.toml"),
            "design": (design_spec.TEMPLATE, "design.toml"), "shpb": (shpb_spec.TEMPLATE, "shpb.toml"),
            "identify": (identify_spec.TEMPLATE, "identify.toml"), "drive": (pile_spec.TEMPLATE, "drive.toml")}


# ============================================================================================ examples
def cmd_examples(args: argparse.Namespace) -> int:
    from .examples import EXAMPLES, example, load_example, model_text, run_example

    action = args.action or "list"
    if action == "list":
        if args.json:
            print(json.dumps([{"name": e.name, "title": e.title, "models": list(e.models)}
                              for e in EXAMPLES.values()], indent=2))
            return EXIT_OK
        width = max(len(n) for n in EXAMPLES)
        for e in EXAMPLES.values():
            print(f"{e.name:<{width}}  {e.title}")
        print("\nrun one with:  rodimpact examples run NAME -o OUTDIR")
        return EXIT_OK
    if not args.name:
        raise InputError(f"examples {action}: give an example name ({', '.join(EXAMPLES)})")
    ex = _input_phase(lambda: example(args.name))
    if args.set and action != "run":
        raise InputError(f"--set: sets keys of the models an example runs; only with 'examples run', not "
                         f"'examples {action}' (copy the model and edit it, or run it with --set)")
    if action == "show":
        for f in ex.models:
            if len(ex.models) > 1:
                print(f"# ===== {f}")
            print(model_text(f))
        return EXIT_OK
    if action == "copy":
        if len(ex.models) == 1:
            targets = [_file_target(args.output, ex.models[0])]
        else:                       # several files: -o names a folder
            targets = [Path(args.output or ".") / f for f in ex.models]
            if args.output is not None and Path(args.output).exists() and not Path(args.output).is_dir():
                raise InputError(f"{args.output}: is a file; example {ex.name!r} has {len(ex.models)} model files, "
                                 f"so -o names a folder to copy them into")
        for t in targets:
            if t.is_dir():
                raise InputError(f"{t}: is a folder, not a model file; give a file name with -o")
            if (t.exists() or t.is_symlink()) and not args.force:
                raise InputError(f"{t}: exists; use --force to replace it")
        for f, t in zip(ex.models, targets):
            _write_file(t, model_text(f), True)
            if not args.quiet:
                print(f"wrote {t}")
        return EXIT_OK
    # run
    from .io.results import format_summary, summarize

    overrides = _overrides(args)
    models = [_input_phase(lambda i=i: load_example(ex.name, i, overrides)) for i in range(len(ex.models))]
    out = _output(args, ex.name)
    if out is None:
        runs = [(f, m.simulate(progress=_progress(args))) for f, m in zip(ex.models, models)]
    else:
        with _claim_out(out, args.force):
            runs = [(f, r) for f, r, _ in run_example(ex.name, out, overwrite=args.force, plots=not args.no_plots,
                                                      progress=_progress(args), overrides=overrides)]
    summaries = {Path(f).stem: summarize(r) for f, r in runs}
    text = "\n\n".join(format_summary(_without_warnings(s), f"{ex.title}" + (f" -- {k}" if len(runs) > 1 else ""))
                       for k, s in summaries.items())
    _report(summaries if len(runs) > 1 else next(iter(summaries.values())), text, args,
            f"results written to {out}" if out else "", [w for s in summaries.values() for w in s["warnings"]])
    return EXIT_OK


# ============================================================================================ synthesize
def cmd_synthesize(args: argparse.Namespace) -> int:
    from .io import synthesis_spec

    return _run_spec(args, synthesis_spec)


def _run_spec(args: argparse.Namespace, module: Any, prepare: Any = None, write: Any = None) -> int:
    """Load a spec with ``module.load_spec``, ``run`` it, write the output folder with ``write`` (default
    :func:`rodimpact.output_folders.write_spec_run`) and report (synthesize, design, shpb predict);
    ``prepare(spec)``, if given, adjusts the loaded spec from command-line flags."""
    from .output_folders import write_spec_run

    write = write or write_spec_run
    spec_path = Path(args.spec)
    out = _output(args, spec_path.stem)
    with _claim_out(out, args.force):
        spec = _input_phase(lambda: module.load_spec(spec_path, _overrides(args)))
        if prepare is not None:
            prepare(spec)
        result = _input_phase(lambda: module.run(spec))
        summary = (module.summarize_run(result, spec) if out is None
                   else write(result, spec, out, overwrite=args.force, plots=not args.no_plots))
    _report(summary, module.format_summary(_without_warnings(summary), spec), args,
            f"results written to {out}" if out else "", summary["warnings"])
    return EXIT_NO_EXACT if summary.get("feasible") is False else EXIT_OK


# ============================================================================================ design
def cmd_design(args: argparse.Namespace) -> int:
    from .io import design_spec

    def prepare(spec: Any) -> None:
        # progress lines on stderr: --progress always, --no-progress (or --quiet) never, else on a terminal
        progress = args.progress if args.progress is not None else (False if getattr(args, "quiet", False)
                                                                     else None)
        spec.kwargs["progress"] = progress

    return _run_spec(args, design_spec, prepare)


# ============================================================================================ shpb
def cmd_shpb_predict(args: argparse.Namespace) -> int:
    from .io import shpb_spec
    from .output_folders import write_shpb_prediction

    return _run_spec(args, shpb_spec, write=write_shpb_prediction)


def cmd_shpb_reduce(args: argparse.Namespace) -> int:
    from .io import shpb_reduction_spec as spec_io
    from .output_folders import write_shpb_reduction

    overrides: dict[str, Any] = {}
    for role in ("incident_bar", "transmitted_bar"):
        if args.bridge is not None:
            overrides[f"{role}.bridge"] = args.bridge
        if args.polarity is not None:
            overrides[f"{role}.polarity"] = args.polarity
    if args.dispersion:
        overrides["reduction.dispersion"] = True
    overrides.update(_overrides(args))
    named = args.recording[0] if args.recording else args.spec
    out = _output(args, f"{Path(named).stem if named else 'shot'}-shpb")
    with _claim_out(out, args.force):
        spec = _input_phase(lambda: spec_io.load_spec(args.spec, overrides))
        shot = _input_phase(lambda: spec_io.read_shot(spec, args.recording))
        reduction = _input_phase(lambda: spec_io.run(spec, shot))
        summary = spec_io.summarize_run(reduction, spec, shot)
        if out is not None:
            write_shpb_reduction(reduction, spec, summary, out, overwrite=args.force, plots=not args.no_plots)
    _report(summary, spec_io.format_summary(summary), args, f"results written to {out}" if out else "",
            summary["warnings"])
    return EXIT_OK


def _add_shpb_parser(sub: Any, output_flags: Callable[..., None], set_flag: Callable[..., None]) -> None:
    """``rodimpact shpb VERB``: the split-Hopkinson (Kolsky) bar's commands, one sub-parser per verb."""
    h = sub.add_parser("shpb", help="split-Hopkinson (Kolsky) bar: predict the gauge signals of a test, reduce a "
                                    "recorded shot",
                       description="Split-Hopkinson (Kolsky) pressure bar. 'predict SPEC.toml': the gauge signals "
                                   "and the specimen's stress, strain and strain rate of a test (rodimpact init shpb "
                                   "writes a template). 'reduce RECORDING...': a recorded shot's 1-, 2- and 3-wave "
                                   "stress, strain and strain rate and its force equilibrium.")
    verbs = h.add_subparsers(dest="verb", metavar="VERB", required=True)
    p = verbs.add_parser("predict", help="predict the gauge signals and the specimen's histories",
                         description="Predict the gauge signals and the specimen's stress, strain and strain rate "
                                     "of the Kolsky-bar test SPEC.toml describes and write them (CSV, NetCDF), plots "
                                     "and a summary to OUTDIR.")
    p.add_argument("spec", metavar="SPEC.toml", help="Kolsky-bar specification")
    output_flags(p, "SPEC-NAME")
    set_flag(p, "spec")
    p.set_defaults(func=cmd_shpb_predict)
    r = verbs.add_parser("reduce", help="reduce a recorded shot: stress-strain, strain rate, equilibrium",
                         description="Reduce a recorded split-Hopkinson-bar shot: find the pulse windows, move the "
                                     "pulses to the specimen faces, compute the 1-, 2- and 3-wave stress, strain and "
                                     "strain rate (compression positive) and the equilibrium ratio R(t); write "
                                     "reduction.csv, reduction.nc, plots and summary.json to OUTDIR.")
    r.add_argument("recording", nargs="*", metavar="RECORDING",
                   help="a LANL .raw file (its sheet gives bars, gauges and specimen), Tektronix .csv files (one "
                        "per channel) or a .tdms file; or name them in the spec (recording.files)")
    r.add_argument("--spec", metavar="SPEC.toml", help="bars, gauges, specimen, channels and settings the recording "
                                                       "lacks (keys: rodimpact docs shpb-reduce)")
    r.add_argument("--bridge", metavar="NAME", help="bridge circuit of both bars' gauges (quarter, half-axial, ...; "
                                                    "the LANL sheets do not record it)")
    r.add_argument("--polarity", type=int, choices=(1, -1), help="-1 if the recorder shows compression as positive "
                                                                "voltage (both bars)")
    r.add_argument("--dispersion", action="store_true", help="undo the Pochhammer-Chree dispersion between gauges "
                                                             "and specimen")
    output_flags(r, "RECORDING-shpb")
    set_flag(r, "spec")
    r.set_defaults(func=cmd_shpb_reduce)


# ============================================================================================ identify
def cmd_identify(args: argparse.Namespace) -> int:
    from .io import identify_spec as spec_io
    from .output_folders import write_identification

    named = args.record[0] if args.record else args.spec
    out = _output(args, f"{Path(named).stem if named else 'record'}-identify")
    with _claim_out(out, args.force):
        spec = _input_phase(lambda: spec_io.load_spec(args.spec, _overrides(args)))
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            # the matching method's progress lines on stderr when it is a terminal (never with --quiet)
            lines = None if args.quiet or not sys.stderr.isatty() else (lambda m: print(m, file=sys.stderr))
            result = _input_phase(lambda: spec_io.run(spec, args.record, progress=lines))
        files = list(args.record) or [str(spec.base / f) for f in spec.values["record"]["files"] or ()]
        summary = spec_io.summarize(result, spec, files)
        summary["warnings"] = list(dict.fromkeys(summary["warnings"] + [str(w.message) for w in caught]))
        if out is not None:
            write_identification(result, spec, summary, out, overwrite=args.force, plots=not args.no_plots)
    _report(summary, spec_io.format_summary(summary), args, f"results written to {out}" if out else "",
            summary["warnings"])
    return EXIT_OK


# ============================================================================================ drive
def cmd_drive(args: argparse.Namespace) -> int:
    from .io import pile_spec
    from .output_folders import write_pile_run

    def prepare(spec: Any) -> None:
        if args.units is not None:
            object.__setattr__(spec, "units", args.units)

    return _run_spec(args, pile_spec, prepare, write=write_pile_run)


def _add_drive_parser(sub: Any, output_flags: Callable[..., None], set_flag: Callable[..., None]) -> None:
    """``rodimpact drive SPEC.toml``: pile driving."""
    p = sub.add_parser("drive", help="pile driving: one blow, bearing graph, drivability, inspector's chart",
                       description="Drive a pile as SPEC.toml describes (rodimpact init drive writes a template): one "
                                   "blow (permanent set, blow count, stress envelopes, transferred energy), a bearing "
                                   "graph, drivability over depth or an inspector's chart; writes CSV files, plots "
                                   "and summary.json to OUTDIR.")
    p.add_argument("spec", metavar="SPEC.toml", help="pile-driving specification")
    p.add_argument("--units", choices=("si", "us"), default=None,
                   help="units of the printed summary: si (default) or us (kips, ft, blows/ft)")
    output_flags(p, "SPEC-NAME")
    set_flag(p, "spec")
    p.set_defaults(func=cmd_drive)


# ============================================================================================ docs
def _doc_topics() -> dict[str, tuple[str, Callable[[], str]]]:
    """Topic -> (description, function generating the page): the pages are generated from the schemas the
    files are validated with, so the installed package always has them, matching its own code."""
    from .io import design_spec, identify_spec, pile_spec, schema, shpb_reduction_spec, shpb_spec, synthesis_spec

    return {"model": ("every key of a model file (docs/model-reference.md)", schema.reference_markdown),
            "synthesis": ("every key of a synthesis spec (docs/cli.md)", synthesis_spec.spec_reference_markdown),
            "design": ("every key of a design spec (docs/cli.md)", design_spec.spec_reference_markdown),
            "shpb": ("every key of a Kolsky-bar spec (docs/cli.md)", shpb_spec.spec_reference_markdown),
            "shpb-reduce": ("every key of a split-Hopkinson-bar reduction spec (docs/cli.md)",
                            shpb_reduction_spec.spec_reference_markdown),
            "identify": ("every key of an identification spec (docs/identification.md)",
                         identify_spec.spec_reference_markdown),
            "drive": ("every key of a pile-driving spec (docs/pile-driving.md)", pile_spec.spec_reference_markdown)}


def cmd_docs(args: argparse.Namespace) -> int:
    topics = _doc_topics()
    if args.topic is None:
        width = max(map(len, topics))
        for name, (what, _) in topics.items():
            print(f"{name:<{width}}  {what}")
        print("\nprint one with:  rodimpact docs TOPIC")
        return EXIT_OK
    if args.topic not in topics:
        raise InputError(f"docs: no topic {args.topic!r}; topics: {', '.join(topics)}")
    text = topics[args.topic][1]()
    print(text, end="" if text.endswith("\n") else "\n")
    return EXIT_OK


# ============================================================================================ parser
def build_parser() -> argparse.ArgumentParser:
    """The argument parser (also used by docs/cli.md)."""
    p = argparse.ArgumentParser(
        prog="rodimpact", description="Longitudinal impact of non-uniform elastic rods: simulate impacts from "
                                      "model files, run the thesis examples, synthesize strikers.",
        epilog="Exit codes: 0 ok, 2 bad input, 1 internal error. Model keys: rodimpact docs model.")
    p.add_argument("--version", action="version", version=f"rodimpact {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")

    def output_flags(sp: argparse.ArgumentParser, what: str, plots: bool = True) -> None:
        where = sp.add_mutually_exclusive_group()
        where.add_argument("-o", "--output", metavar="OUTDIR", help=f"output folder (default: results/{what})")
        where.add_argument("--no-output", action="store_true", help="write nothing; print the summary only")
        sp.add_argument("--force", action="store_true", help="replace an existing output folder written by "
                                                             "rodimpact (never one holding other files)")
        sp.add_argument("--quiet", action="store_true", help="print nothing but errors")
        sp.add_argument("--json", action="store_true", help="print the summary as JSON on stdout (and nothing "
                                                            "else); writes the output folder only with -o")
        if plots:
            sp.add_argument("--no-plots", action="store_true", help="write no plots (faster)")

    def set_flag(sp: argparse.ArgumentParser, what: str) -> None:
        sp.add_argument("--set", action="append", metavar="KEY=VALUE",
                        help=f"set a key of the {what} before it is validated, e.g. --set rods.piston.velocity="
                             f"'5 m/s' or --set 'rods[1].segments[0].length=2 m' (repeatable)")

    def limit_flag(sp: argparse.ArgumentParser) -> None:
        sp.add_argument("--max-element-updates", type=float, metavar="N", default=None,
                        help="refuse runs of more than N element updates (elements x steps; default 1e11, about 17 "
                             "min at 1e8 updates/s; inf: no limit); see docs/security.md")

    s = sub.add_parser("simulate", help="run a model file and write results, plots and a summary",
                       description="Run MODEL.toml and write results, plots and summary.json to OUTDIR.")
    s.add_argument("model", metavar="MODEL.toml", help="model file (rodimpact init simulate writes a template)")
    output_flags(s, "MODEL-NAME")
    set_flag(s, "model file")
    limit_flag(s)
    s.set_defaults(func=cmd_simulate)

    w = sub.add_parser("sweep", help="run a model file over a grid of key values and write one table",
                       description="Run MODEL.toml at every combination of the --grid values and write one table "
                                   "of the first contact's peak force, contact time, energy transfer and striker "
                                   "velocity (sweep.csv, sweep.nc, summary.json) and a plot of each quantity "
                                   "against each grid key (sweep.png) to OUTDIR.")
    w.add_argument("model", metavar="MODEL.toml", help="model file")
    w.add_argument("--grid", action="append", required=True, metavar="KEY=V1,V2,...",
                   help="a key of the model file and the values to sweep, e.g. --grid rods.piston.velocity=4,5,6 "
                        "or --grid 'simulation.dt=0.5 us,1 us' (repeatable: all combinations are run)")
    output_flags(w, "MODEL-NAME-sweep")
    set_flag(w, "model file")
    w.add_argument("--workers", type=int, metavar="N", default=None, help="parallel runs (default: the CPUs)")
    limit_flag(w)
    w.set_defaults(func=cmd_sweep)

    i = sub.add_parser("init", help="write a commented template that runs as it is",
                       description="Write a fully commented template model (simulate), synthesis spec "
                                   "(synthesize), design spec (design), Kolsky-bar spec (shpb), identification "
                                   "spec (identify) or pile-driving spec (drive) that runs as it is.")
    i.add_argument("kind", nargs="?", default="simulate",
                   help="simulate (default), synthesize, design, shpb, identify or drive")
    i.add_argument("-o", "--output", metavar="FILE", help="file to write (default: model.toml / synthesis.toml; "
                                                          "an existing folder or a name ending in / means "
                                                          "that file inside it)")
    i.add_argument("--force", action="store_true", help="replace an existing file")
    i.add_argument("--quiet", action="store_true", help="print nothing but errors")
    i.set_defaults(func=cmd_init)

    e = sub.add_parser("examples", help="list, run, show or copy the built-in thesis examples",
                       description="Built-in examples from the thesis. 'list' (default) names them; "
                                   "'run NAME' writes results and plots; 'show NAME' prints the model file; "
                                   "'copy NAME' copies it for editing.")
    e.add_argument("action", nargs="?", choices=("list", "run", "show", "copy"), help="what to do (default list)")
    e.add_argument("name", nargs="?", help="example name (see 'rodimpact examples list')")
    output_flags(e, "NAME")
    set_flag(e, "example's model files (examples run)")
    e.set_defaults(func=cmd_examples)

    y = sub.add_parser("synthesize", help="find the striker impedance that produces a prescribed force",
                       description="Solve the inverse problem described by SPEC.toml (rodimpact init synthesize "
                                   "writes a template) and write the striker profile, report and plots.")
    y.add_argument("spec", metavar="SPEC.toml", help="synthesis specification")
    output_flags(y, "SPEC-NAME")
    set_flag(y, "spec")
    y.set_defaults(func=cmd_synthesize)

    g = sub.add_parser("design", help="find the best striker under constraints when no exact one exists",
                       description="Design the striker described by SPEC.toml (rodimpact init design writes a "
                                   "template): best match to a target force or best drilling efficiency inside "
                                   "diameter, mass and step limits; writes the profile, plots and a summary.")
    g.add_argument("spec", metavar="SPEC.toml", help="design specification")
    g.add_argument("--progress", dest="progress", action="store_const", const=True, default=None,
                   help="print progress lines (run, iteration, objective, best so far) to stderr; default: only "
                        "when stderr is a terminal")
    g.add_argument("--no-progress", dest="progress", action="store_const", const=False,
                   help="never print progress lines")
    output_flags(g, "SPEC-NAME")
    set_flag(g, "spec")
    g.set_defaults(func=cmd_design)

    _add_shpb_parser(sub, output_flags, set_flag)
    n = sub.add_parser("identify", help="identify the impedance profile of a pile, rod or striker from a record",
                       description="Identify the impedance profile below the measured face from a head record "
                                   "(CSV of time, force, velocity; several files are blows, averaged) or a striker "
                                   "from a LANL shot's incident pulse: regularised signal matching with bands, layer "
                                   "peeling, beta reflectors or striker identification (docs/identification.md; keys: rodimpact docs identify; "
                                   "rodimpact init identify writes a template). Writes profile.csv, "
                                   "identification.nc, plots and summary.json to OUTDIR.")
    n.add_argument("record", nargs="*", metavar="RECORD", help="CSV head record(s) or one LANL .raw shot; or name "
                                                               "them in the spec (record.files)")
    n.add_argument("--spec", metavar="SPEC.toml", help="method, rod and record settings")
    output_flags(n, "RECORD-identify")
    set_flag(n, "spec")
    n.set_defaults(func=cmd_identify)
    _add_drive_parser(sub, output_flags, set_flag)

    d = sub.add_parser("docs", help="print reference pages of this installation (model-file keys, ...)",
                       description="Print a reference page as Markdown, generated by the installed rodimpact from "
                                   "the schema it validates files with; without TOPIC, list the topics.")
    d.add_argument("topic", nargs="?", help="model, synthesis, design, shpb, shpb-reduce, identify or drive")
    d.set_defaults(func=cmd_docs)
    return p


def _is_output_exists(exc: BaseException) -> bool:
    from .io.results import OutputExistsError

    return isinstance(exc, OutputExistsError)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Entry point of the ``rodimpact`` command; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "func", None) is None:
        parser.print_help()
        return EXIT_INPUT
    restore_sigterm = _handle_sigterm()
    args.warning_lines = WarningLines(getattr(args, "quiet", False))
    try:
        with warnings.catch_warnings():         # the filters stay as they are (Python's: no DeprecationWarning)
            warnings.showwarning = args.warning_lines.showwarning
            return args.func(args)
    except InputError as exc:
        _err(str(exc))
        return EXIT_INPUT
    except Terminated:
        _err("terminated; no partial results were written")
        return 128 + 15
    except KeyboardInterrupt:
        _err("interrupted; no partial results were written")
        return 130
    except Exception as exc:  # a bug: say so, keep the traceback available
        if _is_output_exists(exc):      # raised late: the output folder changed while we computed
            _err(str(exc))
            return EXIT_INPUT
        if os.environ.get("RODIMPACT_DEBUG"):
            traceback.print_exc()
        _err(f"internal error: {type(exc).__name__}: {exc}\n(this is a bug in rodimpact; set RODIMPACT_DEBUG=1 "
             f"to see the traceback and please report it)")
        return EXIT_INTERNAL
    finally:
        restore_sigterm()


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived: unwound like Ctrl-C, so that temporary output is removed and nothing half-written stays."""


def _raise_terminated(signum: int, frame: Any) -> None:
    raise Terminated()


def _handle_sigterm() -> Callable[[], None]:
    """Handle SIGTERM like SIGINT; returns a function that restores the previous handler (a no-op where signals
    cannot be set, e.g. outside the main thread)."""
    if not hasattr(signal, "SIGTERM") or threading.current_thread() is not threading.main_thread():
        return lambda: None
    try:
        old = signal.signal(signal.SIGTERM, _raise_terminated)
    except (ValueError, OSError):
        return lambda: None
    return lambda: signal.signal(signal.SIGTERM, old if old is not None else signal.SIG_DFL)


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
