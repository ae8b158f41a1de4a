"""The command line never deletes what a user saved: --force only replaces folders rodimpact wrote and is checked
before any work; folders given where a file is expected, `-o dir/` and missing spec keys give clear exit-2
errors; written files get normal permissions."""

import os
import stat
import subprocess
import sys

import pytest

from rodimpact import cli
from rodimpact.io.results import MARKER

RODIMPACT = [sys.executable, "-m", "rodimpact"]


def main_in_process(args, cwd, capsys, monkeypatch):
    monkeypatch.chdir(cwd)
    try:
        code = cli.main(list(args))
    except SystemExit as exc:
        code = exc.code
    cap = capsys.readouterr()
    return code, cap.out, cap.err


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    yield
    os.umask(old)


def test_simulate_force_into_the_current_folder_deletes_nothing(tmp_path):
    """The reviewer's reproduction: init, a notes file, then simulate -o . --force."""
    env = {k: v for k, v in os.environ.items() if k != "RODIMPACT_DEBUG"}
    sh = (f"{sys.executable} -m rodimpact init -o model.toml --quiet && echo keep > notes.txt && "
          f"{sys.executable} -m rodimpact simulate model.toml -o . --force --quiet --no-plots")
    p = subprocess.run(sh, shell=True, cwd=tmp_path, capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 2, (p.stdout, p.stderr)
    assert p.stderr.startswith("rodimpact: error: .: is the current working folder"), p.stderr
    assert sorted(os.listdir(tmp_path)) == ["model.toml", "notes.txt"]
    assert (tmp_path / "notes.txt").read_text() == "keep\n"


def test_force_refuses_a_user_folder_before_simulating(tmp_path, capsys, monkeypatch):
    code, _, _ = main_in_process(["init", "-o", "model.toml", "--quiet"], tmp_path, capsys, monkeypatch)
    assert code == 0
    user = tmp_path / "data"
    user.mkdir()
    (user / "measurement.csv").write_text("1,2\n")
    import rodimpact.io.model as model_mod

    def no_simulation(*a, **k):
        raise AssertionError("the output folder must be checked before the model is even loaded")

    monkeypatch.setattr(model_mod, "load_model", no_simulation)
    code, _, err = main_in_process(["simulate", "model.toml", "-o", "data", "--force", "--quiet"], tmp_path,
                                   capsys, monkeypatch)
    assert code == 2 and err.startswith("rodimpact: error: data: holds files rodimpact did not write")
    assert "--force" in err and "only replaces earlier rodimpact results" in err
    assert os.listdir(user) == ["measurement.csv"]


def test_force_replaces_results_rodimpact_wrote(tmp_path, capsys, monkeypatch):
    main_in_process(["init", "-o", "model.toml", "--quiet"], tmp_path, capsys, monkeypatch)
    args = ["simulate", "model.toml", "-o", "out", "--quiet", "--no-plots"]
    assert main_in_process(args, tmp_path, capsys, monkeypatch)[0] == 0
    assert (tmp_path / "out" / MARKER).is_file()
    assert main_in_process(args + ["--force"], tmp_path, capsys, monkeypatch)[0] == 0
    (tmp_path / "out" / "notes.txt").write_text("mine")
    code, _, err = main_in_process(args + ["--force"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "out: holds files rodimpact did not write (notes.txt)" in err
    assert (tmp_path / "out" / "notes.txt").read_text() == "mine"


def test_examples_run_and_synthesize_respect_the_rule(tmp_path, capsys, monkeypatch):
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine" / "keep.txt").write_text("keep")
    code, _, err = main_in_process(["examples", "run", "first-example", "-o", "mine", "--force", "--quiet"],
                                   tmp_path, capsys, monkeypatch)
    assert code == 2 and "mine: holds files rodimpact did not write" in err
    code, _, err = main_in_process(["examples", "run", "first-example", "-o", ".", "--force", "--quiet"],
                                   tmp_path, capsys, monkeypatch)
    assert code == 2 and "current working folder" in err
    main_in_process(["init", "synthesize", "--quiet"], tmp_path, capsys, monkeypatch)
    code, _, err = main_in_process(["synthesize", "synthesis.toml", "-o", "mine", "--force", "--quiet"],
                                   tmp_path, capsys, monkeypatch)
    assert code == 2 and "mine: holds files rodimpact did not write" in err
    assert os.listdir(tmp_path / "mine") == ["keep.txt"]


# ------------------------------------------------------------------------------------------- files, not folders
def test_init_into_a_folder_writes_the_default_file_name(tmp_path, capsys, monkeypatch):
    (tmp_path / "existing_dir").mkdir()
    code, out, err = main_in_process(["init", "-o", "existing_dir", "--force"], tmp_path, capsys, monkeypatch)
    assert code == 0, err
    assert (tmp_path / "existing_dir" / "model.toml").is_file()
    code, _, _ = main_in_process(["init", "-o", "newdir/", "--quiet"], tmp_path, capsys, monkeypatch)
    assert code == 0 and (tmp_path / "newdir" / "model.toml").is_file()
    (tmp_path / "d2" / "model.toml").mkdir(parents=True)
    code, _, err = main_in_process(["init", "-o", "d2", "--force"], tmp_path, capsys, monkeypatch)
    assert code == 2 and err.startswith(f"rodimpact: error: {os.path.join('d2', 'model.toml')}: is a folder")
    (tmp_path / "plain").write_text("x")
    code, _, err = main_in_process(["init", "-o", "plain/model.toml"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "cannot be written" in err and "internal" not in err


def test_examples_copy_into_a_new_folder_with_trailing_slash(tmp_path, capsys, monkeypatch):
    code, _, err = main_in_process(["examples", "copy", "test-rig", "-o", "newdir/", "--quiet"], tmp_path, capsys,
                                   monkeypatch)
    assert code == 0, err
    assert (tmp_path / "newdir").is_dir() and (tmp_path / "newdir" / "test-rig.toml").is_file()
    code, _, err = main_in_process(["examples", "copy", "test-rig", "-o", "newdir", "--quiet"], tmp_path, capsys,
                                   monkeypatch)
    assert code == 2 and "test-rig.toml: exists" in err
    (tmp_path / "newdir" / "test-rig.toml").unlink()
    (tmp_path / "newdir" / "test-rig.toml").mkdir()
    code, _, err = main_in_process(["examples", "copy", "test-rig", "-o", "newdir", "--force"], tmp_path, capsys,
                                   monkeypatch)
    assert code == 2 and "is a folder, not a model file" in err
    code, _, _ = main_in_process(["examples", "copy", "test-rig", "-o", "rig.toml", "--quiet"], tmp_path, capsys,
                                 monkeypatch)
    assert code == 0 and (tmp_path / "rig.toml").is_file()


def test_written_files_have_normal_permissions(tmp_path, capsys, monkeypatch, umask_022):
    main_in_process(["init", "-o", "model.toml", "--quiet"], tmp_path, capsys, monkeypatch)
    main_in_process(["examples", "copy", "test-rig", "--quiet"], tmp_path, capsys, monkeypatch)
    for f in ("model.toml", "test-rig.toml"):
        assert stat.S_IMODE(os.stat(tmp_path / f).st_mode) == 0o644, f
    main_in_process(["init", "synthesize", "--quiet"], tmp_path, capsys, monkeypatch)
    code, _, err = main_in_process(["synthesize", "synthesis.toml", "-o", "syn", "--quiet", "--no-plots"],
                                   tmp_path, capsys, monkeypatch)
    assert code == 0, err
    assert stat.S_IMODE(os.stat(tmp_path / "syn").st_mode) == 0o755
    for f in ("striker.csv", "synthesis.nc", "summary.json", "verification/result.nc"):
        assert stat.S_IMODE(os.stat(tmp_path / "syn" / f).st_mode) == 0o644, f


# ------------------------------------------------------------------------------------------- synthesis specs
SPEC = """
[striker]
velocity = "6 m/s"
elements = 10

[target]
{target}

[[struck]]
[[struck.segments]]
shape = "cylinder"
length = "1 m"
diameter = "50 mm"
"""


@pytest.mark.parametrize("target, message", [
    ('type = "samples"', "target.time: missing"),
    ('type = "samples"\ntime = ["0 ms", "1 ms"]', "target.force: missing"),
    ('type = "windows"', "target.values: missing"),
    ('type = "file"\nfile = "."', "target.file: '.' is a folder, not a CSV file"),
])
def test_spec_target_errors_name_the_key(tmp_path, capsys, monkeypatch, target, message):
    (tmp_path / "s.toml").write_text(SPEC.format(target=target))
    code, _, err = main_in_process(["synthesize", "s.toml", "-o", "out"], tmp_path, capsys, monkeypatch)
    assert code == 2 and err.startswith(f"rodimpact: error: {message}"), err
    assert not (tmp_path / "out").exists()


def test_model_segment_file_that_is_a_folder_exits_2(tmp_path, capsys, monkeypatch):
    (tmp_path / "m.toml").write_text('[[rods]]\n[[rods.segments]]\nshape = "table"\nfile = "."\n\n'
                                     '[simulation]\nsteps = 10\n')
    code, _, err = main_in_process(["simulate", "m.toml", "-o", "out"], tmp_path, capsys, monkeypatch)
    assert code == 2 and "rods[0].segments[0].file: '.' is a folder, not a CSV file" in err, err
