"""Every reproducer listed under "Why" in issue 13, each with the named error it must give now.

Inputs that used to hang, exhaust memory or end in an uncaught exception (``OverflowError``,
``ZeroDivisionError``, ``RecursionError``, ``TypeError: unhashable``) must fail quickly with a
:class:`~rodimpact.io.quantities.ModelError` (a ``ValueError``) that starts with the file's key path.
"""

from __future__ import annotations

import io
import math
import os
import re
import signal
import subprocess
import sys
import time
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

import rodimpact as ri
from rodimpact import cli
from rodimpact.direct import guards
from rodimpact.io import preflight
from rodimpact.io import synthesis_spec
from rodimpact.io.model import loads_model
from rodimpact.io.quantities import ModelError
from rodimpact.io.recordings import read_lanl_raw, read_tdms
from rodimpact.io.templates import TEMPLATES
from rodimpact.output_folders import write_simulation

from robust_inputs import DT_LINE, ROOT, small_model

MODEL = small_model("t")


def fails(text: str, pattern: str, base_dir: Path | None = None, *, seconds: float = 5.0) -> str:
    """Load ``text``; it must raise a ModelError matching ``pattern`` (a regex searched from the start)."""
    t0 = time.perf_counter()
    with pytest.raises(ModelError) as info:
        loads_model(text, base_dir=base_dir)
    assert time.perf_counter() - t0 < seconds * 20   # generous: a hang would take minutes (pint: forever)
    msg = str(info.value)
    assert re.match(pattern, msg), msg
    return msg


# ------------------------------------------------------------------------------------------------ hangs
def test_exponent_towers_are_refused_before_pint_sees_them():
    fails(MODEL.replace('length = "0.1 m"', 'length = "10**10**10 m"'),
          r"rods\[0\]\.segments\[0\]\.length: \"10\*\*10\*\*10 m\": a power \(\*\*\) may only raise a unit")
    fails(MODEL.replace("[simulation]", '[parameters]\nA = "10**10**10 m"\n[simulation]'),
          r"parameters\.A: \"10\*\*10\*\*10 m\": a power")
    fails(MODEL.replace('length = "0.1 m"', 'length = "0.1 m**2**3**4"'),
          r"rods\[0\]\.segments\[0\]\.length: .*no towers")
    fails(MODEL.replace('length = "0.1 m"', 'length = "0.1 m^99"'),
          r"rods\[0\]\.segments\[0\]\.length: .*exponent of at most 12")
    # unit powers stay allowed
    m = loads_model(MODEL.replace('diameter = "40 mm"', 'diameter = "0.04 m^1"', 1))
    assert m.system.rods[0].segments[0].diameter == 0.04


def test_a_quantity_string_of_100000_letters_is_refused_at_once():
    msg = fails(MODEL.replace('length = "0.1 m"', f'length = "{"m" * 100_000}"'),
                r"rods\[0\]\.segments\[0\]\.length: a quantity string may have at most 200 characters, got 100,000")
    assert len(msg) < 300                                     # the string is not echoed


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="FIFOs are a POSIX feature")
def test_a_fifo_as_table_file_force_file_or_model_file_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "pipe.csv")
    text = MODEL.replace('shape = "cylinder"\nlength = "0.1 m"\ndiameter = "40 mm"',
                         'shape = "table"\nfile = "pipe.csv"', 1)
    fails(text, r"rods\[0\]\.segments\[0\]\.file: '.*pipe.csv' is not a regular file", tmp_path)
    text = MODEL + '[ends]\nright = { type = "force", force = { file = "pipe.csv" } }\n'
    fails(text, r"ends\.right\.force\.file: '.*pipe.csv' is not a regular file", tmp_path)
    with pytest.raises(ModelError, match=r"pipe.csv: '.*pipe.csv' is not a regular file"):
        ri.load_model(tmp_path / "pipe.csv")


# ------------------------------------------------------------------------------------------------ memory
@pytest.mark.skipif(not Path("/dev/zero").exists(), reason="no /dev/zero on this platform")
@pytest.mark.parametrize("device", ["/dev/zero", "/dev/urandom"])
def test_devices_as_table_or_force_files_are_refused_before_reading(device):
    text = MODEL.replace('shape = "cylinder"\nlength = "0.1 m"\ndiameter = "40 mm"',
                         f'shape = "table"\nfile = "{device}"', 1)
    fails(text, rf"rods\[0\]\.segments\[0\]\.file: '{device}' is not a regular file")
    fails(MODEL + f'[ends]\nleft = {{ type = "force", force = {{ file = "{device}" }} }}\n',
          rf"ends\.left\.force\.file: '{device}' is not a regular file")


def test_a_file_above_the_size_limit_is_refused_and_the_limit_can_be_lifted(tmp_path, monkeypatch):
    (tmp_path / "big.csv").write_text("time,force\n" + "0,0\n" * 200_000)      # 11 + 4 x 200,000 bytes
    text = MODEL + '[ends]\nleft = { type = "force", force = { file = "big.csv" } }\n'
    monkeypatch.setenv("RODIMPACT_MAX_INPUT_MB", "0.5")
    fails(text, r"ends\.left\.force\.file: '.*big.csv' has 800,011 bytes, more than the limit of 524,288 for a "
                r"CSV file; set RODIMPACT_MAX_INPUT_MB", tmp_path)
    monkeypatch.setenv("RODIMPACT_MAX_INPUT_MB", "2")
    assert loads_model(text, base_dir=tmp_path).system.left is not None


def _big_snapshot_model() -> str:
    # 12,802 elements x 41,404 steps with a snapshot at every step: the 12.7 GB case
    return MODEL.replace('length = "0.4 m"', 'length = "66.25 m"').replace(
        'steps = 150\n', 'steps = 41404\n').replace(DT_LINE, 'dt = "1 us"\nallow_discretization_error = true').replace(
        "snapshot_count = 5", "snapshot_every = 1")


def test_snapshots_at_every_step_are_refused_before_the_run(monkeypatch):
    monkeypatch.setattr(guards, "available_memory", lambda: 8.0 * 2**30)      # a laptop with 8 GiB free
    model = loads_model(_big_snapshot_model())
    n_el = int(round(sum(r.total_travel_time for r in model.system.rods) / model.time_step))
    assert 12_700 < n_el < 12_900
    t0 = time.perf_counter()
    with pytest.raises(ModelError, match=r"output\.snapshot_every: the run would need about (1[0-9]|2[0-9])\.?\d* GiB "
                                         r"of memory .*snapshots .* more than the 8 GiB available now; fewer "
                                         r"snapshots"):
        model.simulate()
    assert time.perf_counter() - t0 < 60                       # refused up front, not after 41,404 steps
    # the command line refuses it as well, before the run, naming the key
    with pytest.raises(ModelError, match=r"output\.snapshot_count: the run would need"):
        preflight.check_run(model, Path("."), ())


def test_the_output_of_a_long_run_is_counted_before_it_starts(monkeypatch, tmp_path):
    """A 10 s bar shot wrote a 471 MB CSV that no check counted: the CLI's pre-run check estimates the files
    (about 24 bytes per CSV value) and refuses them when the disk is too small."""
    text = MODEL.replace('steps = 150\n', 'duration = "10 s"\n').replace(DT_LINE, 'dt = "2 us"')
    model = loads_model(text)
    assert model.n_steps == 5_000_000
    # signals.csv: time, contact force and flag, force and velocity of both ends = 7 columns x 24 bytes x 5e6 rows
    # = 0.782 GiB; result.nc: the 6 histories and the time, 8 bytes each = 0.261 GiB
    monkeypatch.setattr(guards, "free_disk", lambda folder: 200e6)
    with pytest.raises(ModelError, match=r"output: the results would take about 1\.04 GiB on disk \(result\.nc "
                                         r"0\.261 GiB, signals\.csv 0\.782 GiB\), more than the 191 MiB free at"):
        preflight.check_run(model, tmp_path / "out", (), max_element_updates=math.inf)


def test_writing_the_csv_does_not_hold_the_whole_text_in_memory(tmp_path):
    from rodimpact.io.results import _write_csv

    n = 150_000
    cols = [np.linspace(0, 1, n) * (k + 1) / 7 for k in range(7)]
    tracemalloc.start()
    _write_csv(tmp_path / "s.csv", [f"c{k}" for k in range(7)], cols)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    size = (tmp_path / "s.csv").stat().st_size
    assert size > 20e6                                        # ~ 1 million values of ~ 20 characters
    assert peak < 0.4 * size, (peak, size)     # chunks of rows only; holding the text (as before) takes > 1x the file
    first = (tmp_path / "s.csv").read_text().splitlines()[:3]
    assert first[0] == "c0,c1,c2,c3,c4,c5,c6"
    assert [float(x) for x in first[2].split(",")] == [float(c[1]) for c in cols]


def test_a_run_of_4e13_element_updates_is_refused_up_front():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(2.0, 0.04)])]
    n_el = 2.2 / ri.STEEL.wave_speed / 1e-10                  # 4.25 million elements, 1e7 steps
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"duration: the run needs 4,25\d,\d{3} elements x 10,000,000 steps = "
                                         r"4\.25e\+13 element updates, more than the limit of 1e\+11 \(roughly "
                                         r"4\.92 days at 1e8 updates per second\); .* lift the limit with "
                                         r"max_element_updates= \(command line: --max-element-updates\)"):
        ri.simulate(rods, [5.0, 0.0], duration=1e-3, dt=1e-10)
    assert time.perf_counter() - t0 < 120                      # not the days the run would take
    assert 4.2e6 < n_el < 4.3e6


def test_the_default_limit_refuses_and_the_option_lifts_it():
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(2.0, 0.04)])]
    with pytest.raises(ValueError, match=r"duration: the run needs .* more than the limit of 1e\+11 \(roughly "
                                         r"22 min at 1e8 updates per second\)"):
        ri.simulate(ri.Problem.of(rods, [5.0, 0.0], steps=1_500_000_000, elements=(1, 80)))
    with pytest.raises(ValueError, match=r"max_element_updates: must be a number > 0"):
        ri.simulate(rods, [5.0, 0.0], steps=10, max_element_updates=-1)
    res = ri.simulate(ri.Problem.of(rods, [5.0, 0.0], steps=40, elements=(1, 80)),
                      max_element_updates=88 * 40)   # exactly at it
    assert res.n_steps == 40
    with pytest.raises(ValueError, match=r"duration: the run needs 88 elements x 41 steps = 3\.61e\+03"):
        ri.simulate(ri.Problem.of(rods, [5.0, 0.0], steps=41, elements=(1, 80)), max_element_updates=88 * 40)


def test_max_element_updates_on_the_command_line(tmp_path, capsys):
    (tmp_path / "m.toml").write_text(small_model("t"))
    # 10 + 40 elements (1 cm each) x 150 steps = 7,500 element updates
    assert cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(tmp_path / "a"), "--quiet",
                     "--max-element-updates", "7499"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("rodimpact: error: simulation.duration: the run needs 50 elements x 150 steps = 7.5e+03 "
                          "element updates, more than the limit of 7.5e+03"), err
    assert err.rstrip().endswith("or lift the limit with --max-element-updates") and not (tmp_path / "a").exists()
    assert cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(tmp_path / "b"), "--quiet",
                     "--max-element-updates", "7500"]) == 0
    assert cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(tmp_path / "c"), "--quiet",
                     "--max-element-updates", "inf"]) == 0

def test_long_runs_report_progress_without_a_terminal(capsys):
    rods = [ri.Rod([ri.Cylinder(0.2, 0.04)]), ri.Rod([ri.Cylinder(2.0, 0.04)])]
    ri.simulate(ri.Problem.of(rods, [5.0, 0.0], steps=1000, elements=(1, 80)), progress=True)
    lines = capsys.readouterr().err.splitlines()               # pytest's stderr is no terminal
    assert lines and lines[-1].startswith("simulate: 100% (1,000 of 1,000 steps, "), lines
    stream = io.StringIO()
    bar = guards.Progress(10, stream)
    for _ in range(10):
        bar.update(1)
    assert [ln.split("%")[0] for ln in stream.getvalue().splitlines()] == \
        [f"simulate: {10 * k:3d}" for k in range(1, 11)]
    assert guards.progress(None, 10**5, 10**5) is not None          # 1e10 updates: long, reported by default
    assert guards.progress(None, 10**3, 10**3) is None


# ------------------------------------------------------------------------------------------------ uncaught
def test_overflowing_numbers_give_named_errors():
    fails(MODEL.replace('length = "0.1 m"', 'length = "10**400 m"'), r"rods\[0\]\.segments\[0\]\.length: ")
    fails(MODEL.replace('length = "0.1 m"', 'length = "1e400 m"'),
          r"rods\[0\]\.segments\[0\]\.length: must be finite, got \"1e400 m\"")
    fails(MODEL.replace('length = "0.1 m"', "length = 1" + "0" * 400), r"rods\[0\]\.segments\[0\]\.length: must be "
                                                                      r"finite, got an integer of about 401 digits")
    fails(MODEL.replace('diameter = "40 mm"', "diameter = 1e200", 1),
          r"rods\[0\]\.segments\[0\]: Cylinder: the cross-section area must be finite and > 0")
    fails(MODEL.replace('velocity = "5 m/s"', "velocity = " + "9" * 5000),
          r"model: not valid TOML: ValueError: Exceeds the limit")


def test_a_run_length_at_the_float_limit_and_a_denormal_element_length():
    elements = ('[[rods]]\nvelocity = "5 m/s"\n[rods.elements]\nelement_length = "5 mm"\n'
                'runs = [{ impedance = 1.0, length = 1.797e308 }]\n[simulation]\nduration = "1 ms"\n')
    fails(elements, r"rods\[0\]\.elements\.runs\[0\]\.length: 1\.797e\+308 m is inf elements .* far too many")
    fails(elements.replace("length = 1.797e308", "length = 1.0").replace('"5 mm"', "5e-324"),
          r"rods\[0\]\.elements\.element_length: gives an element travel time of 0 s")
    # two rods of 1.797e308 m each: the sum overflows, so the run refuses (before allocating), naming the key
    huge = loads_model(MODEL.replace('length = "0.1 m"', "length = 1.797e308")
                       .replace('length = "0.4 m"', "length = 1.797e308"))
    with pytest.raises(ModelError, match=r"^simulation\.dt: .* lattice elements .* more than this machine's memory"):
        huge.simulate()
    with pytest.raises(ModelError, match=r"^simulation\.dt: the rods would need inf elements"):
        preflight.check_run(huge, Path("."), ())


@pytest.mark.parametrize("nested", ["[" * 500 + "]" * 500, "{a = " * 500 + "1" + "}" * 500])
def test_arrays_and_inline_tables_nested_500_deep(nested):
    fails(MODEL + f"[[probes]]\nname = {nested}\n", r"model: arrays or tables nested too deeply \(at most 32")


def test_nesting_below_the_parser_limit_names_the_key_path():
    fails(MODEL + "[[probes]]\nname = " + "[" * 40 + "]" * 40 + "\n",
          r"probes\[0\]\.name(\[0\])+: arrays or tables nested too deeply")


@pytest.mark.parametrize("text, pattern", [
    (MODEL.replace('shape = "cylinder"', "shape = []", 1),
     r"rods\[0\]\.segments\[0\]\.shape: expected a string, one of 'cylinder'.*; got \[\]"),
    (MODEL + "[ends]\nleft = { type = {} }\n", r"ends\.left\.type: expected a string, one of 'free'.*; got \{\}"),
    (MODEL + "[[junctions]]\ntype = 3\n", r"junctions\[0\]\.type: expected a string"),
])
def test_discriminators_must_be_strings(text, pattern):
    fails(text, pattern)


def test_duplicate_plot_names_are_refused_before_the_run(tmp_path):
    fails(MODEL.replace("plots = []", 'plots = ["forces", "energy", "forces"]'),
          r"output\.plots\[2\]: 'forces' is listed twice")
    res = ri.simulate([ri.Rod([ri.Cylinder(0.1, 0.04)]), ri.Rod([ri.Cylinder(0.2, 0.04)])], [1.0, 0.0], steps=20)
    with pytest.raises(ValueError, match="plots: 'xt' is listed twice"):
        write_simulation(res, tmp_path / "out", plots=["xt", "xt"])
    assert not (tmp_path / "out").exists()


def test_an_output_folder_below_a_file_is_refused_before_the_run(tmp_path, monkeypatch, capsys):
    (tmp_path / "m.toml").write_text(MODEL)
    (tmp_path / "existing_file").write_text("x")
    ran = []
    monkeypatch.setattr("rodimpact.io.model.Model.simulate", lambda *a, **k: ran.append(1))
    code = cli.main(["simulate", str(tmp_path / "m.toml"), "-o", str(tmp_path / "existing_file" / "sub")])
    assert code == 2 and not ran
    assert re.search(r"error: .*existing_file/sub: its parent folder .*existing_file cannot be created",
                     capsys.readouterr().err)


# ------------------------------------------------------------------------------------------------ key paths
def test_run_time_errors_name_the_model_keys_not_the_api_arguments():
    text = MODEL.replace('name = "bar"\n', 'name = "bar"\ninitial = { force = [1.0, 2.0, 3.0] }\n')
    model = loads_model(text)
    with pytest.raises(ModelError, match=r"^rods\[1\]\.initial\.force: needs one value per lattice element"):
        model.simulate()
    model = loads_model(MODEL.replace(DT_LINE, DT_LINE + '\nenergy_every = 1\nbackend = "numpy"')
                        .replace("steps = 150", "steps = 3_000_000"))
    with pytest.raises(ModelError, match=r"^simulation\.energy_every: 1 gives"):
        model.simulate()


def test_synthesis_errors_name_the_spec_keys():
    spec = synthesis_spec.loads_spec(synthesis_spec.TEMPLATE.replace('dt = "1.93 us"', "# no dt"))
    with pytest.raises(ModelError, match=r"^synthesis\.dt: give the time step"):
        spec.synthesize()
    spec = synthesis_spec.loads_spec(synthesis_spec.TEMPLATE.replace("elements = 100", "elements = 1000000000000"))
    with pytest.raises(ModelError, match=r"^striker\.elements: "):
        spec.synthesize()


# ------------------------------------------------------------------------------------------------ readers
LANL = ROOT / "tests" / "data" / "hoppybar" / "LANLstandard-Cu" / "20061201_1148HE_CuOFE_273K.raw"


def test_a_truncated_lanl_file_is_an_error_naming_the_file(tmp_path):
    data = LANL.read_bytes()
    assert read_lanl_raw(LANL).time.size == 5000
    cut = tmp_path / "cut.raw"
    cut.write_bytes(data[:len(data) * 1581 // 5003 + 7])              # cut inside a data line, as a copy might
    assert not cut.read_bytes().endswith(b"\n")
    with pytest.raises(ValueError, match=r"cut\.raw, line \d+: the file ends in the middle of this line: it is "
                                         r"truncated"):
        read_lanl_raw(cut)


def test_a_tdms_file_with_nan_names_the_file(tmp_path):
    from nptdms import ChannelObject, TdmsWriter

    path = tmp_path / "nan.tdms"
    values = np.array([0.0, 1.0, np.nan, 3.0])
    with TdmsWriter(str(path)) as w:
        w.write_segment([ChannelObject("g", "ch", values, properties={"wf_increment": 1e-6})])
    with pytest.raises(ValueError, match=r"nan\.tdms: channel 'ch' contains a non-finite value at sample 2"):
        read_tdms(path)


def test_a_file_that_is_no_csv_is_never_echoed(tmp_path):
    secret = "root:x:0:0:root:/root:/bin/bash-SECRET-LINE"
    (tmp_path / "passwd").write_text(secret + "\ndaemon:x:1:1\n")
    for text in (MODEL + '[ends]\nleft = { type = "force", force = { file = "passwd" } }\n',
                 MODEL.replace('shape = "cylinder"\nlength = "0.1 m"\ndiameter = "40 mm"',
                               'shape = "table"\nfile = "passwd"', 1)):
        msg = fails(text, r"(ends\.left\.force|rods\[0\]\.segments\[0\])\.file: ", tmp_path)
        assert "SECRET" not in msg and "/bin/bash" not in msg and "daemon" not in msg, msg
    (tmp_path / "units.csv").write_text("time [SECRET],force\n0,0\n")
    msg = fails(MODEL + '[ends]\nleft = { type = "force", force = { file = "units.csv" } }\n',
                r"ends\.left\.force\.file: .*units\.csv, column 1: the unit in its header is not a time unit", tmp_path)
    assert "SECRET" not in msg


# ------------------------------------------------------------------------------------------------ signals
@pytest.mark.skipif(os.name != "posix", reason="POSIX signals (a SIGINT disposition inherited through exec)")
@pytest.mark.parametrize("runner", ["default", "ignores SIGINT"])
def test_ctrl_c_during_the_imports_ends_without_a_traceback(runner):
    """The ``rodimpact`` command's entry point (rodimpact_cli) catches an interrupt while numpy, numba and the
    package are still being imported.

    The child sends itself SIGINT from inside the import of ``rodimpact.cli`` (single-threaded then: nothing else
    imported yet), so the signal arrives inside the imports however slow they are, and its stdout proves it was
    sent there. It starts with SIGINT at its default disposition, as a command started from a terminal: a process
    inherits an ignored SIGINT, and Python then never raises KeyboardInterrupt, so a test run in the background
    of a non-interactive shell (``pytest ... &``, nohup) saw the child exit 0 (issue 20, item 21). The
    ``ignores SIGINT`` case is such a runner."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    code = ("import signal, os, sys, builtins\n"
            "real = builtins.__import__\n"
            "def slow(name, *a, **k):\n"
            "    if name == 'rodimpact.cli':\n"
            "        print('SIGINT sent inside the import of rodimpact.cli', flush=True)\n"
            "        os.kill(os.getpid(), signal.SIGINT)\n"      # Ctrl-C arrives while the CLI is imported
            "    return real(name, *a, **k)\n"
            "builtins.__import__ = slow\n"
            "import rodimpact_cli\n"
            "sys.argv = ['rodimpact', '--version']\n"
            "raise SystemExit(rodimpact_cli.main())\n")
    old = signal.signal(signal.SIGINT, signal.SIG_IGN) if runner != "default" else None
    try:
        p = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120,
                           preexec_fn=_sigint_as_from_a_terminal)
    finally:
        if old is not None:
            signal.signal(signal.SIGINT, old)
    assert p.stdout == "SIGINT sent inside the import of rodimpact.cli\n", (p.stdout, p.stderr)
    assert p.returncode == 130, p.stderr
    assert "Traceback" not in p.stderr
    assert p.stderr.strip() == "rodimpact: interrupted while starting; nothing was written"


def _sigint_as_from_a_terminal() -> None:
    """In the child before it runs Python: SIGINT at its default disposition (as a terminal's foreground job has
    it), whatever the test runner inherited."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_plot_memory_is_counted_before_the_run(monkeypatch, tmp_path):
    """Plots of every recorded step hold their points in matplotlib (about 64 bytes each): a 5-million-step run
    whose histories fit but whose plots do not is refused before it starts, naming output.plots."""
    text = MODEL.replace('steps = 150\n', 'duration = "10 s"\n').replace(DT_LINE, 'dt = "2 us"')
    model = loads_model(text)
    monkeypatch.setattr(guards, "free_disk", lambda folder: 1e12)
    monkeypatch.setattr(guards, "available_memory", lambda: 1.5 * 2**30)
    preflight.check_run(model, tmp_path / "out", (), max_element_updates=math.inf)       # no plots: it fits
    with pytest.raises(ModelError, match=r"^output\.plots: the run would need about .* GiB of memory .*plots "):
        preflight.check_run(model, tmp_path / "out", ("forces",), max_element_updates=math.inf)
