"""Simulation results on disk: :func:`save_simulation` writes a folder, :func:`simulation_from_dataset` reads its
result file back into an identical :class:`~rodimpact.SimulationResult` (in Python: :func:`rodimpact.save` and
:func:`rodimpact.load` of :mod:`rodimpact.io.storage`, which save and load every kind of result); :func:`summarize`
gives the key numbers.

Folder layout (all files are written into a temporary folder next to the target and moved into place at the
end, so an interrupted run never leaves half-written results; an existing non-empty folder is only replaced
with ``overwrite=True``, and only if rodimpact wrote it: see :func:`check_output_folder`):

``.rodimpact-output``
    Marks the folder as written by rodimpact and lists what was written (:data:`MARKER`). ``overwrite=True``
    (``--force``) replaces a folder only when it holds this file and nothing that is not listed in it.

``model.toml``
    The model as a self-contained file in SI numbers (written by :func:`rodimpact.io.model.dump_model`);
    ``rodimpact simulate OUTDIR/model.toml`` repeats the run. Missing when the system holds Python callables.
``summary.json``
    :func:`summarize` plus the list of files.
``signals.csv``
    One row per time step (step start time): contact force(s), contact flag(s), outer-end force and velocity,
    probe force, velocity, displacement and strain. Units in the headers (``contact_force [N]``).
``energy.csv``
    Energy samples: kinetic and strain energy and momentum per rod, total energy, work done by the ends,
    loads and friction, external impulse.
``result.nc``
    NetCDF with everything above plus the lattice, the field snapshots N(x), v(x), u(x) and the final state
    (xarray; engine h5netcdf when h5py is installed, else netCDF4, else scipy's NetCDF3 writer), in the layout of
    :meth:`SimulationResult.to_xarray` (:mod:`rodimpact.direct.dataset`: ``probe``, ``junction``, ``end``, ``rod``
    and time coordinates). This is what :func:`simulation_from_dataset` reads (also format 1 and 2 files, which
    named the probes in a JSON attribute); the CSV files are for people and spreadsheets.
``plots/``
    PNG figures (and ``force.gif``): not written here. io writes data only; the command line and the examples
    draw the figures into the same folder (:mod:`rodimpact.output_folders`, above io and plotting).
"""

from __future__ import annotations

import errno
import json
import math
import os
import re
import shutil
import tempfile
import time as _time
import warnings
from pathlib import Path
from typing import Any, Optional, Sequence

import numpy as np

from .._version import __version__
from .._permissions import normal_mode
from .._result_files import netcdf_engine
from .._validate import caller_stacklevel
from ..direct.dataset import (BIT_ROCK_FIELDS, FORMAT_VERSION, JOINT_FIELDS, LUMPED_FIELDS, json_default,
                              result_dataset)
from ..direct.result import (BitRockOutcome, EnergyHistory, FieldSnapshots, JointOutcome, JunctionEvents,
                             LumpedOutcome, Probe, ProbeHistory, SimulationResult, first_within_rounding)
from ..direct.soil_result import soil_from_variables
from ..lattice.discretize import RodDiscretization
from ..lattice.lattice import Lattice
from ._files import write_text_atomic  # noqa: F401  (public here: the CLI writes single files with it)

RESULT_FILE = "result.nc"


class OutputExistsError(FileExistsError):
    """The output folder exists and may not be replaced: it is not empty and overwriting was not requested, or it
    holds files rodimpact did not write, or it is (or contains) the current working folder."""


MARKER = ".rodimpact-output"
"""Name of the file :class:`AtomicFolder` writes into every output folder: line 1 says what wrote the folder, the
other lines list its entries (relative paths, ``/``-separated). ``overwrite=True`` / ``--force`` only replaces a
folder that holds this file and nothing but the entries it lists."""

_MARKER_NOTE = (f"This folder was written by rodimpact (version {__version__}); rodimpact --force / overwrite=True "
                f"may replace it as a whole. Entries written:")


# ============================================================================================ output folders
#: Test-only (not for users; no effect unless set): ``POINT:FILE`` stops a writer at ``POINT`` of the write
#: window of an output folder (``entered``, ``csv``, ``finishing``, ``aside``; see :func:`_test_pause`), so that
#: tests/robustness/test_output_races.py can kill it exactly there.
_TEST_PAUSE = "_RODIMPACT_TEST_PAUSE"


def _test_pause(point: str) -> None:
    """With ``_RODIMPACT_TEST_PAUSE=POINT:FILE`` and ``point == POINT``: create FILE (the sign that the writer is
    inside the window) and wait there until killed. Does nothing otherwise."""
    value = os.environ.get(_TEST_PAUSE)
    if not value:
        return
    where, _, flag = value.partition(":")
    if where != point or not flag:
        return
    with open(flag, "x"):
        pass
    while True:
        _time.sleep(0.5)


def _contains_cwd(folder: Path) -> bool:
    """True if ``folder`` is the current working folder or one of its parents."""
    try:
        cwd = Path.cwd().resolve()
        target = folder.resolve()
    except OSError:
        return False
    return target == cwd or target in cwd.parents


def _entries(folder: Path) -> set[str]:
    """Every file, folder and link below ``folder`` as relative ``/``-separated paths (links are not followed).
    Raises ``OSError`` if part of it cannot be read (so that nothing unseen is ever replaced)."""
    def fail(exc: OSError) -> None:
        raise exc

    out: set[str] = set()
    for root, dirs, files in os.walk(folder, onerror=fail):
        rel = Path(root).relative_to(folder)
        for name in dirs + files:
            out.add((rel / name).as_posix())
    return out


def _written_entries(folder: Path) -> Optional[set[str]]:
    """The entries the marker of ``folder`` lists, or ``None`` when it has no readable marker."""
    try:
        lines = (folder / MARKER).read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return None
    if not lines or not lines[0].startswith("This folder was written by rodimpact"):
        return None
    return {ln for ln in lines[1:] if ln}


def _write_marker(folder: Path, entries: Sequence[str] = ()) -> None:
    (folder / MARKER).write_text("\n".join([_MARKER_NOTE, *sorted(entries)]) + "\n", encoding="utf-8")


def check_output_folder(outdir: str | Path, overwrite: bool) -> Path:
    """Raise :class:`OutputExistsError` unless ``outdir`` may be written: it does not exist, or is an empty folder,
    or -- with ``overwrite`` -- a folder written by rodimpact (it holds the :data:`MARKER` file and no entries
    other than those the marker lists). Never the current working folder or a folder containing it."""
    out = Path(outdir)
    if not (out.exists() or out.is_symlink()):
        return out
    if not out.is_dir():
        raise OutputExistsError(f"{out}: exists and is not a folder; choose another output folder")
    if _contains_cwd(out):
        raise OutputExistsError(f"{out}: is the current working folder or contains it; results are written as a "
                                f"whole folder that replaces the target, so give a new sub-folder, e.g. -o "
                                f"{Path('results') / 'run1'}")
    try:
        if not any(out.iterdir()):
            return out
        written = _written_entries(out)
        if not overwrite:
            if written is None:
                raise OutputExistsError(f"{out}: exists and is not empty, and holds files rodimpact did not write; "
                                        f"choose another output folder (--force only replaces earlier rodimpact "
                                        f"results)")
            raise OutputExistsError(f"{out}: exists and is not empty; choose another output folder or use --force "
                                    f"(overwrite=True) to replace these earlier rodimpact results")
        if written is None:
            raise OutputExistsError(f"{out}: holds files rodimpact did not write (it has no {MARKER} file); --force "
                                    f"(overwrite=True) only replaces earlier rodimpact results, so choose another "
                                    f"output folder")
        extra = sorted(_entries(out) - written - {MARKER})
    except OSError as exc:
        if isinstance(exc, OutputExistsError):
            raise
        raise OutputExistsError(f"{out}: cannot be read ({exc.strerror or exc}: {exc.filename}); choose another "
                                f"output folder") from None
    if extra:
        shown = ", ".join(extra[:5]) + (f" and {len(extra) - 5} more" if len(extra) > 5 else "")
        raise OutputExistsError(f"{out}: holds files rodimpact did not write ({shown}); --force (overwrite=True) "
                                f"only replaces earlier rodimpact results, so move them away or choose another "
                                f"output folder")
    return out


_LOCK_SUFFIX = ".rodimpact-lock"
_TMP_NAME = re.compile(r"\.tmp-[a-z0-9_]{8}$")
_OLD_NAME = re.compile(r"\.old-[a-z0-9_]{8}$")


def _os_lock(fd: int) -> None:
    """Lock the open file ``fd`` exclusively without waiting (``OSError`` if another process holds it). The operating
    system releases the lock when the process ends, however it ends (also on SIGKILL)."""
    if os.name == "nt":  # pragma: no cover - Windows
        import msvcrt

        msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
    else:
        import fcntl

        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)


class OutputClaim:
    """An exclusive claim of the output folder ``target`` by this process, so that two runs can never both write
    it: an operating-system lock on the file ``.NAME.rodimpact-lock`` beside the folder, held until
    :meth:`release` (or the end of the process). A second run that tries to claim the same folder is refused at
    once with :class:`OutputExistsError`. While the claim is held, leftovers of runs that were killed while
    writing ``target`` (hidden ``.NAME.tmp-XXXXXXXX`` folders holding rodimpact's marker) are removed, and a
    previous result that a killed run had moved aside (``.NAME.old-XXXXXXXX``) is put back when ``target`` is
    missing. Claims are re-entrant within a process (:func:`claim_output`)."""

    def __init__(self, target: Path) -> None:
        self.target = target
        self.lock = target.parent / f".{target.name}{_LOCK_SUFFIX}"
        self.count = 0
        self.fd: Optional[int] = None

    def acquire(self) -> None:
        if self.count:
            self.count += 1
            return
        parent = self.target.parent
        try:
            parent.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise OutputExistsError(f"{self.target}: its parent folder {parent} cannot be created "
                                    f"({exc.strerror or exc}); is a file in the way?") from None
        if not parent.is_dir():
            raise OutputExistsError(f"{self.target}: {parent} is not a folder; choose another output folder")
        while True:
            try:
                fd = os.open(self.lock, os.O_RDWR | os.O_CREAT | getattr(os, "O_NOFOLLOW", 0), 0o644)
            except OSError as exc:
                raise OutputExistsError(f"{self.target}: cannot write into {parent} ({exc.strerror or exc}); "
                                        f"choose another output folder") from None
            try:
                _os_lock(fd)
            except OSError as exc:
                os.close(fd)
                if isinstance(exc, (BlockingIOError, PermissionError)) or exc.errno in (errno.EAGAIN, errno.EACCES):
                    raise OutputExistsError(f"{self.target}: another rodimpact run is writing this output folder "
                                            f"now (it holds {self.lock}); wait for it to finish or choose another "
                                            f"output folder") from None
                raise OutputExistsError(f"{self.target}: cannot lock {self.lock} ({exc.strerror or exc}); the file "
                                        f"system offers no locks, so choose an output folder on a local disk") \
                    from None
            try:    # the previous holder may have removed the lock file between our open and our lock: retry
                same = os.path.samestat(os.fstat(fd), os.stat(self.lock, follow_symlinks=False))
            except OSError:
                same = False
            if same:
                break
            os.close(fd)
        self.fd = fd
        self.count = 1
        try:
            self.clean_leftovers()
        except BaseException:
            self.release()
            raise

    def clean_leftovers(self) -> list[Path]:
        """Remove what killed runs into this target left behind (see the class docstring); returns what was
        removed or restored."""
        done = []
        prefix = f".{self.target.name}"
        try:
            entries = list(self.target.parent.iterdir())
        except OSError:
            return done
        for p in entries:
            rest = p.name[len(prefix):] if p.name.startswith(prefix) else ""
            if not rest or p.is_symlink() or not p.is_dir():
                continue
            if _OLD_NAME.fullmatch(rest) and not (self.target.exists() or self.target.is_symlink()) \
                    and _written_entries(p) is not None:
                os.replace(p, self.target)          # killed between moving the old result aside and the new in
                done.append(p)
            elif (_TMP_NAME.fullmatch(rest) or _OLD_NAME.fullmatch(rest)) and (p / MARKER).is_file():
                shutil.rmtree(p, ignore_errors=True)
                done.append(p)
        return done

    def release(self) -> None:
        self.count -= 1
        if self.count > 0 or self.fd is None:
            return
        _CLAIMS.pop(self.target, None)
        try:
            if os.name != "nt":   # remove the lock file while still holding the lock (see acquire's retry)
                os.unlink(self.lock)
        except OSError:
            pass
        finally:
            os.close(self.fd)
            self.fd = None

    def __enter__(self) -> "OutputClaim":
        return self

    def __exit__(self, *exc: Any) -> bool:
        self.release()
        return False


_CLAIMS: dict[Path, OutputClaim] = {}


def _absolute(target: str | Path) -> Path:
    """``target`` as an absolute path with its parent resolved (the target itself may not exist yet)."""
    p = Path(os.path.abspath(target))
    return p.parent.resolve() / p.name


def claim_output(target: str | Path, overwrite: bool = False) -> OutputClaim:
    """Claim the output folder ``target`` for this process (:class:`OutputClaim`; use it as a context manager
    or call ``release()``) after checking that it may be written (:func:`check_output_folder`). Raises
    :class:`OutputExistsError` if another run holds it, if its parent cannot be created, or if the folder may not
    be written. Claiming a folder this process already holds just counts up."""
    path = _absolute(target)
    claim = _CLAIMS.get(path)
    if claim is None:
        claim = _CLAIMS[path] = OutputClaim(path)
    try:
        claim.acquire()
    except BaseException:
        if not claim.count:
            _CLAIMS.pop(path, None)
        raise
    try:
        check_output_folder(target, overwrite)
    except BaseException:
        claim.release()
        raise
    return claim


class AtomicFolder:
    """Context manager: yields a temporary folder; on success it replaces ``target`` in one rename.

    The target is claimed for the whole time (:func:`claim_output`: a second run into the same folder is refused
    at once, leftovers of killed runs are cleaned up). The folder gets a :data:`MARKER` file listing what was
    written, so that a later ``overwrite=True`` can tell rodimpact's results from a user's files
    (:func:`check_output_folder`, checked on entry and again just before the rename).
    """

    def __init__(self, target: str | Path, overwrite: bool = False) -> None:
        self.target = check_output_folder(target, overwrite)
        self.overwrite = overwrite
        self.tmp: Optional[Path] = None
        self.claim: Optional[OutputClaim] = None

    def __enter__(self) -> Path:
        self.claim = claim_output(self.target, self.overwrite)
        try:
            self.tmp = Path(tempfile.mkdtemp(prefix=f".{self.claim.target.name}.tmp-", dir=self.claim.target.parent))
            _write_marker(self.tmp)
            _test_pause("entered")
        except BaseException:
            if self.tmp is not None:
                shutil.rmtree(self.tmp, ignore_errors=True)
            self.claim.release()
            raise
        return self.tmp

    def __exit__(self, exc_type, exc, tb) -> bool:
        assert self.tmp is not None and self.claim is not None
        try:
            self._finish(exc_type)
        finally:
            self.claim.release()
        return False

    def _finish(self, exc_type) -> None:
        assert self.tmp is not None
        if exc_type is not None:
            shutil.rmtree(self.tmp, ignore_errors=True)
            return
        try:
            _write_marker(self.tmp, _entries(self.tmp) - {MARKER})
            check_output_folder(self.target, self.overwrite)    # files may have appeared while we computed
        except OutputExistsError as err:
            self._keep(err)
        except BaseException:
            shutil.rmtree(self.tmp, ignore_errors=True)
            raise
        target = self.target.resolve()
        os.chmod(self.tmp, normal_mode(folder=True))
        _test_pause("finishing")
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=f".{target.name}.old-", dir=target.parent))
            os.rmdir(old)
            os.replace(target, old)
            _test_pause("aside")
            try:
                os.replace(self.tmp, target)
            except BaseException:
                os.replace(old, target)
                raise
            shutil.rmtree(old, ignore_errors=True)
        else:
            try:
                os.replace(self.tmp, target)
            except OSError as exc:    # a folder with files appeared there (written by something else)
                self._keep(OutputExistsError(f"{target}: appeared while rodimpact was working "
                                             f"({exc.strerror or exc})"))

    def _keep(self, err: OutputExistsError) -> None:
        """Keep the finished results beside the target under a new name and raise ``err`` saying where."""
        assert self.tmp is not None
        kept = Path(tempfile.mkdtemp(prefix=f"{self.target.name}-new-", dir=self.tmp.parent))
        os.rmdir(kept)
        os.replace(self.tmp, kept)
        os.chmod(kept, normal_mode(folder=True))
        raise OutputExistsError(f"{err} (it changed while rodimpact was working; the new results are in "
                                f"{kept})") from None


# ============================================================================================ summary
def _rod_label(result: SimulationResult, i: int) -> str:
    sys_ = result.system
    name = sys_.rods[i].name if sys_ is not None else None
    return name if name else f"rod {i}"


def contact_phases(events: JunctionEvents, rel_tol: float = 1e-9) -> list[tuple[int, int]]:
    """Contact phases of one junction as step ranges [start, stop) that transmit force.

    A phase in which the faces touch but the force never exceeds ``rel_tol`` times the largest junction force of
    the run (e.g. two rods at rest against each other after the pulse has passed, where rounding decides the
    contact flag) is no impact and is left out.
    """
    peak = events.max_abs_force_run
    return [(int(a), int(b)) for a, b, m in zip(events.start, events.stop, events.max_abs_force)
            if peak > 0.0 and m > rel_tol * peak]


def summarize(result: SimulationResult) -> dict[str, Any]:
    """Key numbers of a run, JSON-ready (SI units, keys say the unit).

    Per junction (taken at every step, whatever the recording stride): the peak compressive contact force and its
    time (where the force first comes within rounding of the peak, so a plateau is reported where it begins:
    :meth:`~rodimpact.SimulationResult.peak_time`), the first contact phase (start, duration), every separation
    and re-contact time, the total time in contact (phases that carry no force beyond rounding are not counted,
    see :func:`contact_phases`). Per probe: the requested position (``position_m``, from the rod's left end), the
    lattice node actually read (``node_position_m`` in the same coordinate, ``node_index`` into the ``node``
    dimension of ``result.nc``) and the extreme forces among the recorded samples, with the first time each is
    reached (to rounding). ``lattice_report``: how each rod was represented on the lattice
    (:meth:`~rodimpact.Lattice.report`, also ``result.diagnostics["lattice_report"]``). Per rod: initial and final
    energy and rigid-body (centre-of-mass) velocity -- the rebound velocity once the rods have separated. Energy
    transfer: the fraction of rod 0's initial energy it gave away. Energy balance error: max |E - E0 - W| / max E.
    ``bit_rock`` (one entry per outer end with a bit-rock interaction, else empty): the energy into the rock, the
    drilling efficiency (that energy / the striker's initial energy), the penetration per blow (permanent),
    the largest and the final penetration, and whether the bit still presses on the rock at the end
    (:class:`~rodimpact.direct.result.BitRockOutcome`).
    """
    t = result.time
    dt = result.dt
    n = int(result.n_steps)
    out: dict[str, Any] = {"rodimpact_version": __version__, "steps": n, "dt_s": dt,
                           "duration_s": float(n * dt), "elements": int(result.lattice.n_elements),
                           "record_every": int(result.record_every)}
    junctions = []
    for j, ev in enumerate(result.junction_events or ()):
        phases = contact_phases(ev)
        first = phases[0] if phases else None
        junctions.append({
            "index": j, "between": [_rod_label(result, j), _rod_label(result, j + 1)],
            "peak_compressive_force_N": ev.min_force if ev.min_force < 0 else 0.0,
            "peak_time_s": result.peak_time(j) if ev.min_force < 0 else None,
            "first_contact_s": float(first[0] * dt) if first else None,
            "contact_duration_s": float((first[1] - first[0]) * dt) if first else None,
            "total_contact_time_s": float(sum(b - a for a, b in phases) * dt),
            "separation_times_s": [float(b * dt) for a, b in phases if b < n],
            "recontact_times_s": [float(a * dt) for a, b in phases[1:]],
            "in_contact_at_end": bool(phases and phases[-1][1] == n),
        })
    out["junctions"] = junctions
    e = result.energy
    rods = []
    vel = result.rigid_body_velocity
    for i in range(result.lattice.n_rods):
        e_i = e.kinetic[i] + e.strain[i]
        v0 = result.system.velocities[i] if result.system is not None else None
        rods.append({"name": _rod_label(result, i), "initial_velocity_m_s": v0,
                     "final_rigid_body_velocity_m_s": float(vel[i]), "initial_energy_J": float(e_i[0]),
                     "final_energy_J": float(e_i[-1])})
    out["rods"] = rods
    e0 = e.kinetic[0] + e.strain[0]
    out["energy_transfer"] = float((e0[0] - e0[-1]) / e0[0]) if e0[0] > 0 else None
    out["total_energy_J"] = {"initial": float(e.total[0]), "final": float(e.total[-1])}
    out["work_done_on_rods_J"] = {"ends": float(e.work_left[-1] + e.work_right[-1]),
                                  "loads": float(e.work_loads[-1]), "friction": float(e.work_friction[-1]),
                                  "joints": float(e.work_joints[-1]), "soil": float(e.work_soil[-1])}
    out["energy_balance_error"] = float(e.balance_error)
    out["bit_rock"] = [{"end": o.end, "energy_into_rock_J": o.energy, "efficiency": o.efficiency,
                        "striker": _rod_label(result, o.striker), "striker_initial_energy_J": o.striker_energy,
                        "penetration_per_blow_m": o.penetration, "max_penetration_m": o.max_penetration,
                        "final_penetration_m": o.final_penetration, "bit_in_contact_at_end": o.in_contact}
                       for o in result.bit_rock]
    probes = []
    for name, p in result.probes.items():
        # a flat extreme is reported where it begins, not where rounding put its last digit
        kmin = first_within_rounding(p.force, float(np.min(p.force)))
        kmax = first_within_rounding(p.force, float(np.max(p.force)))
        local, _ = result.lattice.nearest_node(p.probe.rod, p.probe.position)     # the node the run read
        probes.append({"name": name, "rod": p.probe.rod, "position_m": p.probe.position,
                       "node_position_m": p.node_position,
                       "node_index": result.lattice.node_index(p.probe.rod, local),
                       "min_force_N": float(p.force[kmin]), "time_of_min_s": float(t[kmin]),
                       "max_force_N": float(p.force[kmax]), "time_of_max_s": float(t[kmax])})
    out["probes"] = probes
    out["lattice_report"] = result.lattice.report()
    d = result.diagnostics
    out["wall_time_s"] = float(d["wall_time_s"]) if "wall_time_s" in d else None
    out["warnings"] = list(d.get("warnings", []))
    return out


def format_summary(summary: dict[str, Any], title: str = "") -> str:
    """A short human-readable text of :func:`summarize` (kN, ms, m/s, J)."""
    lines = [title] if title else []
    lines.append(f"{summary['steps']} steps of dt = {summary['dt_s'] * 1e6:.4g} us "
                 f"({summary['duration_s'] * 1e3:.4g} ms), {summary['elements']} elements"
                 + (f", every {summary['record_every']}th step recorded" if summary.get("record_every", 1) > 1 else "")
                 + (f", {summary['wall_time_s']:.2f} s" if summary.get("wall_time_s") is not None else ""))
    for j in summary["junctions"]:
        a, b = j["between"]
        lines.append(f"contact {a} | {b}:")
        if j["first_contact_s"] is None:
            lines.append("  no contact")
            continue
        lines.append(f"  peak contact force    {j['peak_compressive_force_N'] / 1e3:.4g} kN at "
                     f"{(j['peak_time_s'] or 0.0) * 1e3:.4g} ms")
        dur = j["contact_duration_s"]
        note = " (still in contact at the end)" if not j["separation_times_s"] else ""
        lines.append(f"  contact duration      {dur * 1e3:.4g} ms from {j['first_contact_s'] * 1e3:.4g} ms{note}")
        if j["separation_times_s"]:
            lines.append("  separation at         " + ", ".join(f"{x * 1e3:.4g}" for x in j["separation_times_s"])
                         + " ms")
        lines.append("  re-contact at         " + (", ".join(f"{x * 1e3:.4g}" for x in j["recontact_times_s"])
                                                   + " ms" if j["recontact_times_s"] else "none"))
    for b in summary["bit_rock"]:
        lines.append(f"rock at the {b['end']} end (bit-rock):")
        eff = b["efficiency"]
        lines.append(f"  energy into the rock  {b['energy_into_rock_J']:.4g} J"
                     + ("" if eff is None else f" = {eff * 100:.2f} % of {b['striker']}'s initial energy "
                                               f"(drilling efficiency)"))
        lines.append(f"  penetration per blow  {b['penetration_per_blow_m'] * 1e3:.4g} mm (permanent; largest "
                     f"{b['max_penetration_m'] * 1e3:.4g} mm, at the end {b['final_penetration_m'] * 1e3:.4g} mm)")
        if b["bit_in_contact_at_end"]:
            lines.append("  the bit still presses on the rock at the end: the blow is not over (run longer); the "
                         "energy includes elastic energy the rock will give back")
    et = summary["energy_transfer"]
    if et is not None and summary["junctions"]:
        first = summary["rods"][0]["name"]
        lines.append(f"energy transfer         {et * 100:.2f} % of {first}'s initial energy given away" if et >= 0
                     else f"energy transfer         {first} gained {-et * 100:.2f} % of its initial energy")
    for r in summary["rods"]:
        v0 = r["initial_velocity_m_s"]
        lines.append(f"{r['name']}: velocity {'' if v0 is None else f'{v0:.4g} -> '}"
                     f"{r['final_rigid_body_velocity_m_s']:.4g} m/s (rigid-body), energy "
                     f"{r['initial_energy_J']:.4g} -> {r['final_energy_J']:.4g} J")
    w = summary["work_done_on_rods_J"]
    if any(abs(x) > 0.0 for x in w.values()):
        lines.append("work done on the rods    " + ", ".join(f"{k} {x:.4g} J" for k, x in w.items() if x != 0.0)
                     + " (negative: energy leaves the rods)")
    for p in summary["probes"]:
        node, asked = p["node_position_m"], p["position_m"]
        moved = (f" (read at the node {node * 1e3:.4g} mm from the rod's left end; requested {asked * 1e3:.4g} mm)"
                 if abs(node - asked) > 1e-9 * max(abs(asked), 1e-3) else "")
        lines.append(f"probe {p['name']}: force {p['min_force_N'] / 1e3:.4g} .. {p['max_force_N'] / 1e3:.4g} kN{moved}")
    lines.append(f"energy balance error    {summary['energy_balance_error']:.2e}")
    for w in summary["warnings"]:
        lines.append(f"warning: {w}")
    return "\n".join(lines)


# ============================================================================================ CSV
def _write_csv(path: Path, header: list[str], columns: list[np.ndarray], chunk: int = 8192) -> None:
    """Write the columns as CSV (shortest round-trip float text) in chunks of rows, so that the memory needed does
    not grow with the length of the run."""
    import csv

    with open(path, "w", encoding="utf-8", newline="") as fh:
        csv.writer(fh, lineterminator="\n").writerow(header)
        if _TEST_PAUSE in os.environ:
            fh.flush()
            _test_pause("csv")
        cols = [np.asarray(c, dtype=float) for c in columns]
        n = cols[0].size if cols else 0
        for a in range(0, n, chunk):
            rows = np.column_stack([c[a:a + chunk] for c in cols]).tolist()
            fh.write("\n".join(",".join(map(repr, r)) for r in rows))
            fh.write("\n")


def signal_columns(result: SimulationResult) -> tuple[list[str], list[np.ndarray]]:
    """Header names (with units) and columns of ``signals.csv``."""
    header, cols = ["time [s]"], [result.time]
    n_j = result.junction_force.shape[0]
    for j in range(n_j):
        sfx = "" if n_j == 1 else f"_{j}"
        header += [f"contact_force{sfx} [N]", f"in_contact{sfx} [-]"]
        cols += [result.junction_force[j], result.junction_contact[j].astype(float)]
    for side in ("left", "right"):
        header += [f"{side}_end_force [N]", f"{side}_end_velocity [m/s]"]
        cols += [result.end_force[side], result.end_velocity[side]]
    for name, p in result.probes.items():
        for q, unit in (("force", "N"), ("velocity", "m/s"), ("displacement", "m"), ("strain", "-")):
            header.append(f"{name}.{q} [{unit}]")
            cols.append(getattr(p, q))
    return header, cols


def energy_columns(result: SimulationResult) -> tuple[list[str], list[np.ndarray]]:
    """Header names (with units) and columns of ``energy.csv``."""
    e = result.energy
    header, cols = ["time [s]"], [e.time]
    for i in range(e.kinetic.shape[0]):
        label = _rod_label(result, i)
        header += [f"{label}.kinetic_energy [J]", f"{label}.strain_energy [J]", f"{label}.momentum [N s]"]
        cols += [e.kinetic[i], e.strain[i], e.momentum[i]]
    header += ["total_energy [J]", "work_left_end [J]", "work_right_end [J]", "work_loads [J]",
               "work_friction [J]", "work_joints [J]", "work_soil [J]", "external_impulse [N s]"]
    cols += [e.total, e.work_left, e.work_right, e.work_loads, e.work_friction, e.work_joints, e.work_soil,
             e.impulse]
    return header, cols


# ============================================================================================ JSON
def summary_json(obj: Any) -> str:
    """A summary as JSON text (indented, one trailing newline): numpy values as plain numbers, non-finite
    numbers as ``null`` (JSON has no NaN or infinity)."""
    def clean(o: Any) -> Any:
        if isinstance(o, float) and not math.isfinite(o):
            return None
        if isinstance(o, dict):
            return {k: clean(v) for k, v in o.items()}
        if isinstance(o, list):
            return [clean(v) for v in o]
        return o
    return json.dumps(clean(json.loads(json.dumps(obj, default=json_default))), indent=2) + "\n"


# ============================================================================================ save / load
SUMMARY_FILE = "summary.json"


def write_simulation_files(result: SimulationResult, folder: Path, *, model: Any = None, csv: bool = True,
                           fields: bool = True, engine: Optional[str] = None) -> tuple[list[str], list[str]]:
    """Write the data files of a results folder into ``folder`` (``model.toml``, ``result.nc``, ``signals.csv``,
    ``energy.csv``; layout in this module's docstring). Returns the files written and notes on what was left out
    (a ``model.toml`` that cannot be written). ``model``, ``csv``, ``fields``, ``engine``: as
    :func:`save_simulation`."""
    from .model import ModelWriteError, dump_model, model_from_result

    files: list[str] = []
    notes: list[str] = []
    if model is None and result.system is not None:
        model = model_from_result(result)
    if model is not None:
        try:
            (folder / "model.toml").write_text(dump_model(model), encoding="utf-8")
            files.append("model.toml")
        except ModelWriteError as exc:
            notes.append(f"model.toml not written: {exc}")
    ds = result_dataset(result, fields=fields)
    ds.to_netcdf(folder / RESULT_FILE, engine=engine or netcdf_engine())
    files.append(RESULT_FILE)
    if csv:
        for name, (h, c) in (("signals.csv", signal_columns(result)), ("energy.csv", energy_columns(result))):
            _write_csv(folder / name, h, c)
            files.append(name)
    return files, notes


def simulation_summary(result: SimulationResult, model: Any, files: Sequence[str],
                       notes: Sequence[str]) -> dict[str, Any]:
    """The ``summary.json`` of a results folder: :func:`summarize`, the title of ``model`` (if it has one), the
    ``files`` in the folder (``summary.json`` added) and the ``notes`` on what was left out."""
    summary = summarize(result)
    if model is not None and getattr(model, "title", ""):
        summary["title"] = model.title
    summary["files"] = list(files) + [SUMMARY_FILE]
    summary["notes"] = list(notes)
    return summary


def write_summary(folder: Path, summary: dict[str, Any]) -> dict[str, Any]:
    """Write ``summary`` as ``summary.json`` into ``folder`` (:func:`summary_json`) and return it."""
    (folder / SUMMARY_FILE).write_text(summary_json(summary), encoding="utf-8")
    return summary


def save_simulation(result: SimulationResult, outdir: str | Path, *, model: Any = None, overwrite: bool = False,
                    csv: bool = True, fields: bool = True, engine: Optional[str] = None) -> Path:
    """Write ``result`` to the folder ``outdir`` (layout in this module's docstring: the data files, no figures)
    and return its path (what :func:`rodimpact.save` does with a simulation result).

    ``model`` (a :class:`~rodimpact.io.model.Model`) is written as ``model.toml``; by default one is built
    from the result (:func:`~rodimpact.io.model.model_from_result`). ``csv``: write ``signals.csv`` and
    ``energy.csv``; ``fields``: keep the field snapshots in ``result.nc``. Refuses to replace a non-empty folder
    unless ``overwrite``, and even then refuses a folder holding files rodimpact did not write, or the current
    working folder (:class:`OutputExistsError`, see :func:`check_output_folder`).
    ``engine``: the xarray NetCDF engine (default: h5netcdf with h5py, else netcdf4, else scipy).
    """
    with AtomicFolder(outdir, overwrite) as tmp:
        files, notes = write_simulation_files(result, tmp, model=model, csv=csv, fields=fields, engine=engine)
        write_summary(tmp, simulation_summary(result, model, files, notes))
    return Path(outdir)


def _events(v: dict[str, np.ndarray], n_j: int) -> tuple[JunctionEvents, ...]:
    """The contact events stored in ``result.nc`` (formats 2 and 3)."""
    owner = v.get("phase_junction", np.zeros(0, dtype=np.int32))
    out = []
    for j in range(n_j):
        mine = owner == j
        out.append(JunctionEvents(
            start=v["phase_start"][mine].astype(np.int64) if mine.any() else np.zeros(0, dtype=np.int64),
            stop=v["phase_stop"][mine].astype(np.int64) if mine.any() else np.zeros(0, dtype=np.int64),
            max_abs_force=v["phase_max_abs_force"][mine] if mine.any() else np.zeros(0),
            min_force=float(v["junction_min_force"][j]), min_force_step=int(v["junction_min_force_step"][j]),
            max_abs_force_run=float(v["junction_max_abs_force"][j])))
    return tuple(out)


def simulation_from_dataset(ds: Any, nc: Path) -> SimulationResult:
    """The :class:`~rodimpact.SimulationResult` in ``ds``, the dataset of the result file ``nc`` (the layout of
    :mod:`rodimpact.direct.dataset`, also formats 1 and 2). The system is rebuilt from the ``model.toml`` beside
    ``nc`` (``None`` when there is none). A file of a newer format, or one that lacks part of a result, gives a
    ``ValueError`` naming ``nc``."""
    if int(ds.attrs.get("format_version", 0)) > FORMAT_VERSION:
        raise ValueError(f"{nc}: written by a newer rodimpact (format {ds.attrs['format_version']}); upgrade")
    try:
        return _from_dataset(ds, nc)
    except (KeyError, IndexError, TypeError, json.JSONDecodeError) as exc:
        what = f"no {exc}" if isinstance(exc, KeyError) else "malformed data"
        raise ValueError(f"{nc}: not a complete rodimpact result ({what}); the file is damaged or was not written "
                         f"by rodimpact.save") from None


def _from_dataset(ds: Any, nc: Path) -> SimulationResult:
    from .model import load_model

    folder = nc.parent
    v = {k: ds[k].values for k in ds.variables}
    dt = float(ds.attrs["dt"])
    time = v["time"]
    n_steps = time.size          # recorded samples
    rod_start = v["rod_start"].astype(np.int64)
    n_rods = rod_start.size - 1
    methods = json.loads(ds.attrs["rod_methods"])
    discs = []
    for r in range(n_rods):
        a, b = rod_start[r], rod_start[r + 1]
        discs.append(RodDiscretization(
            impedance=v["impedance"][a:b].copy(), length=v["element_length"][a:b].copy(), n_elements=int(b - a),
            time_scale=float(v["rod_time_scale"][r]), true_length=float(v["rod_true_length"][r]),
            true_mass=float(v["rod_true_mass"][r]), lattice_mass=float(v["rod_lattice_mass"][r]),
            true_travel_time=float(v["rod_true_travel_time"][r]), exact=bool(v["rod_exact"][r]),
            max_boundary_offset=float(v["rod_max_boundary_offset"][r]), method=methods[r]))
    lattice = Lattice(dt, v["impedance"], v["element_length"], rod_start, v["node_x"], v["element_x"], tuple(discs))
    system = None
    if (folder / "model.toml").is_file():
        system = load_model(folder / "model.toml").system
    n_j = n_rods - 1
    jf = v["junction_force"] if "junction_force" in v else np.zeros((0, n_steps))
    jc = (v["junction_contact"] if "junction_contact" in v else np.zeros((0, n_steps))).astype(bool)
    if jf.shape[0] != n_j:
        raise ValueError(f"{nc}: {jf.shape[0]} junction rows for {n_rods} rods; the file is damaged")
    probes: dict[str, ProbeHistory] = {}
    if int(ds.attrs.get("format_version", 0)) >= 3:       # a probe coordinate (absent without probes)
        names = [str(n) for n in ds["probe"].values] if "probe" in ds.coords else []
    else:                                                 # formats 1-2: the names in a JSON attribute
        names = json.loads(ds.attrs["probe_names"])
    for i, name in enumerate(names):
        p = Probe(name, int(v["probe_rod"][i]), float(v["probe_position"][i]))
        probes[name] = ProbeHistory(p, float(v["probe_node_position"][i]), v["probe_force"][i].copy(),
                                    v["probe_velocity"][i].copy(), v["probe_displacement"][i].copy(),
                                    v["probe_strain"][i].copy())
    snapshots = None
    if "snapshot_time" in v:
        snapshots = FieldSnapshots(time=v["snapshot_time"], element_x=lattice.element_x, node_x=lattice.node_x,
                                   element_rod=lattice.element_rod, node_rod=lattice.node_rod,
                                   force=v["force_field"], velocity=v["velocity_field"],
                                   displacement=v["displacement_field"])
    energy = EnergyHistory(time=v["energy_time"], kinetic=v["kinetic_energy"], strain=v["strain_energy"],
                           momentum=v["momentum"], work_left=v["work_left"], work_right=v["work_right"],
                           work_loads=v["work_loads"], work_friction=v["work_friction"],
                           # files written before joints existed have no joint work: zero
                           work_joints=v["work_joints"] if "work_joints" in v else np.zeros_like(v["work_friction"]),
                           work_soil=v["work_soil"] if "work_soil" in v else None,   # files before soil: zero
                           impulse=v["impulse"])
    diagnostics = json.loads(ds.attrs["diagnostics"])
    if system is not None and system.n_rods != n_rods:
        warnings.warn(f"{folder}/model.toml has {system.n_rods} rods but the result has {n_rods}; ignoring the "
                      f"model", stacklevel=caller_stacklevel())
        system = None
    record_every = int(ds.attrs.get("record_every", 1))
    ends = [str(e) for e in ds["bit_rock"].values] if "bit_rock" in ds.coords else []
    bit_rock = tuple(BitRockOutcome(end=end, **{name: (int if name == "striker" else float)(v[f"bit_rock_{name}"][i])
                                               for name in BIT_ROCK_FIELDS}) for i, end in enumerate(ends))
    # files written before the damage work keep JointOutcome's default there (0: no failure law existed)
    joints = tuple(JointOutcome(**{name: (int if name == "junction" else float)(v[f"joint_{name}"][i])
                                   for name in JOINT_FIELDS if f"joint_{name}" in v})
                   for i in range(v["joint_junction"].size)) if "joint_junction" in v else ()
    places = [str(p) for p in ds["lumped"].values] if "lumped" in ds.coords else []
    items = json.loads(ds.attrs.get("lumped_items", "[]"))
    lumped = tuple(LumpedOutcome(place=place, **{name: float(v[f"lumped_{name}"][i]) for name in LUMPED_FIELDS},
                                 velocities=tuple(items[i][0]), max_compressions=tuple(items[i][1]))
                   for i, place in enumerate(places))
    events = _events(v, n_j) if "junction_min_force" in v or n_j == 0 else None   # format 1: rebuilt from histories
    return SimulationResult(
        system=system, lattice=lattice, time=time, junction_force=jf, junction_contact=jc,
        end_force={"left": v["end_force"][0].copy(), "right": v["end_force"][1].copy()},
        end_velocity={"left": v["end_velocity"][0].copy(), "right": v["end_velocity"][1].copy()},
        probes=probes, snapshots=snapshots, energy=energy, final_force=v["final_force"],
        final_velocity=v["final_velocity"], diagnostics=diagnostics, record_every=record_every,
        n_steps=int(ds.attrs.get("steps", n_steps)), junction_events=events, bit_rock=bit_rock, joints=joints,
        lumped=lumped, soil=soil_from_variables(v, ds.coords))
