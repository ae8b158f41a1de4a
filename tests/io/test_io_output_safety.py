"""Nothing a user saved is lost: overwrite=True only replaces folders rodimpact wrote (marker file), never the
current working folder; written files get normal permissions; damaged or foreign result files give clear errors;
folders where a CSV file is expected and oversized impedance-level rods are refused with the key path."""

import os
import stat

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.io.model import loads_model
from rodimpact.io import load, save
from rodimpact.io.results import MARKER, AtomicFolder, OutputExistsError, write_text_atomic


def small_result():
    rods = [ri.Rod.from_impedance([4e4] * 10, dt=1e-6), ri.Rod.from_impedance([6e4] * 30, dt=1e-6)]
    return ri.simulate(rods, velocities=[2.0, 0.0], steps=60)


def mode(p):
    return stat.S_IMODE(os.stat(p).st_mode)


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    yield
    os.umask(old)


# ------------------------------------------------------------------------------------------- overwrite rule
def test_overwrite_never_replaces_a_folder_rodimpact_did_not_write(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "notes.txt").write_text("keep")
    (out / "model.toml").write_text("# mine")
    with pytest.raises(OutputExistsError, match=r"out: holds files rodimpact did not write.*only replaces earlier "
                                                 r"rodimpact results"):
        save(small_result(), out, overwrite=True)
    assert sorted(os.listdir(out)) == ["model.toml", "notes.txt"]
    assert sorted(os.listdir(tmp_path)) == ["out"]                         # no temporary folders left


def test_overwrite_replaces_earlier_results_but_not_files_added_to_them(tmp_path):
    res = small_result()
    out = tmp_path / "out"
    save(res, out)
    assert MARKER in os.listdir(out)
    assert (out / MARKER).read_text().startswith("This folder was written by rodimpact")
    save(res, out, overwrite=True)                                          # earlier results: replaced
    (out / "my-analysis.txt").write_text("keep")
    with pytest.raises(OutputExistsError, match=r"holds files rodimpact did not write \(my-analysis.txt\)"):
        save(res, out, overwrite=True)
    assert (out / "my-analysis.txt").read_text() == "keep"
    (out / "my-analysis.txt").unlink()
    save(res, out, overwrite=True)
    assert load(out).n_steps == 60


def test_the_current_folder_or_a_parent_of_it_is_never_an_output_folder(tmp_path, monkeypatch):
    res = small_result()
    work = tmp_path / "work"
    work.mkdir()
    (work / "notes.txt").write_text("keep")
    monkeypatch.chdir(work)
    for target in (".", str(work), ".."):
        with pytest.raises(OutputExistsError, match="current working folder"):
            save(res, target, overwrite=True)
    assert os.listdir(work) == ["notes.txt"]
    empty = tmp_path / "empty"
    empty.mkdir()
    monkeypatch.chdir(empty)
    with pytest.raises(OutputExistsError, match="current working folder"):
        save(res, ".")
    assert os.listdir(empty) == [] and sorted(os.listdir(tmp_path)) == ["empty", "work"]
    save(res, "sub")                                                       # a new sub-folder is fine
    assert (empty / "sub" / "result.nc").is_file()


def test_save_into_a_fresh_atomic_folder_with_overwrite_still_works(tmp_path):
    """rodimpact.examples.run_example saves into the temporary folder itself (it holds only the marker)."""
    res = small_result()
    with AtomicFolder(tmp_path / "out") as tmp:
        save(res, tmp, overwrite=True)
        save(res, tmp / "sub", overwrite=True)
    assert {"result.nc", "summary.json", "sub", MARKER} <= set(os.listdir(tmp_path / "out"))
    assert (tmp_path / "out" / "sub" / MARKER).is_file()
    save(res, tmp_path / "out", overwrite=True)                            # the marker lists sub/ too


def test_a_folder_changing_during_the_run_keeps_both_the_files_and_the_new_results(tmp_path):
    out = tmp_path / "out"
    with pytest.raises(OutputExistsError, match="changed while rodimpact was working; the new results are in"):
        with AtomicFolder(out) as tmp:
            (tmp / "a.txt").write_text("new")
            out.mkdir()
            (out / "b.txt").write_text("user")
    assert (out / "b.txt").read_text() == "user"
    kept = [p for p in tmp_path.iterdir() if p.name.startswith("out-new-")]
    assert len(kept) == 1 and (kept[0] / "a.txt").read_text() == "new"


# ------------------------------------------------------------------------------------------- permissions
def test_written_files_and_folders_get_normal_permissions(tmp_path, umask_022):
    write_text_atomic(tmp_path / "a.txt", "x")
    assert mode(tmp_path / "a.txt") == 0o644
    os.chmod(tmp_path / "a.txt", 0o640)
    write_text_atomic(tmp_path / "a.txt", "y")                              # a replaced file keeps its mode
    assert mode(tmp_path / "a.txt") == 0o640
    save(small_result(), tmp_path / "out")
    assert mode(tmp_path / "out") == 0o755 and mode(tmp_path / "out" / "summary.json") == 0o644
    with pytest.raises(IsADirectoryError, match="is a folder, not a file"):
        write_text_atomic(tmp_path / "out", "x")


# ------------------------------------------------------------------------------------------- damaged results
def test_load_of_a_damaged_or_foreign_result_file_says_so(tmp_path):
    out = tmp_path / "out"
    save(small_result(), out)
    (out / "result.nc").write_bytes(b"\x89HDF\r\n\x1a\n" + b"garbage" * 10)
    with pytest.raises(ValueError, match=r"result.nc: not a rodimpact result file .*damaged"):
        load(out)
    (out / "result.nc").write_text("time,force\n0,1\n")
    with pytest.raises(ValueError, match=r"result.nc: not a rodimpact result file"):
        load(out)
    import xarray as xr

    xr.Dataset({"x": ("a", np.arange(3.0))}).to_netcdf(out / "result.nc", engine="scipy")
    with pytest.raises(ValueError, match=r"result.nc: not a complete rodimpact result"):
        load(out)


def test_load_of_missing_or_foreign_files(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.nc: no such file or folder"):
        load(tmp_path / "missing.nc")
    (tmp_path / "afile.txt").write_text("hello\n")
    with pytest.raises(ValueError, match="afile.txt: not a rodimpact result file"):
        load(tmp_path / "afile.txt")
    (tmp_path / "h5.nc").write_bytes(b"\x89HDF\r\n\x1a\n" + b"\0" * 40)
    with pytest.raises(ValueError, match="h5.nc: not a rodimpact result file"):
        load(tmp_path / "h5.nc")
    with pytest.raises(FileNotFoundError, match="no result here"):
        load(tmp_path)


# ------------------------------------------------------------------------------------------- model files
SEG_FILE = """
[[rods]]
[[rods.segments]]
shape = "table"
file = "{file}"

[simulation]
steps = 10
"""


def test_a_folder_given_as_a_profile_csv_file_names_the_key(tmp_path):
    (tmp_path / "sub").mkdir()
    for f in (".", "sub"):
        with pytest.raises(ri.io.ModelError, match=r"rods\[0\]\.segments\[0\]\.file: '.*' is a folder, not a CSV "
                                                    r"file"):
            loads_model(SEG_FILE.format(file=f), base_dir=tmp_path)


def test_huge_impedance_level_run_is_refused_before_allocating():
    text = """
[[rods]]
[rods.elements]
dt = "1 us"
runs = [{ impedance = "40 kN s/m", count = 10 }, { impedance = "50 kN s/m", count = 100000000000 }]

[simulation]
steps = 10
"""
    with pytest.raises(ValueError, match=r"rods\[0\]\.elements\.runs\[1\]\.count: 100,000,000,010 elements .*GiB"):
        loads_model(text)
    small = loads_model(text.replace("100000000000", "20"))
    assert small.system.rods[0].native.impedance.size == 30
