"""scripts/validate_shpb.py on the LANL copper shot: the prediction from the measured incident pulse meets the goal of
issue 22 (NRMSE <= 10 % for the reflected and the transmitted gauge signal), and docs/validation-shpb.md holds the
numbers this run gives (the page is current). The mini-Kolsky shot reads from the repository's excerpts alone; its
rows with failure are this run's, and their failure strain lies on the fitted flow curve."""

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("validate_shpb", ROOT / "scripts" / "validate_shpb.py")
validate_shpb = importlib.util.module_from_spec(_spec)
sys.modules["validate_shpb"] = validate_shpb             # its dataclasses look their module up there
_spec.loader.exec_module(validate_shpb)


@pytest.fixture(scope="module")
def lanl():
    return validate_shpb.validate_lanl()


def test_lanl_prediction_meets_the_nrmse_goal(lanl):
    p = lanl.prediction
    assert p.reflected <= validate_shpb.NRMSE_GOAL and p.transmitted <= validate_shpb.NRMSE_GOAL
    assert p.incident < 0.01                        # the drive reproduces the measured incident pulse
    assert not p.warnings


def test_lanl_fit_is_made_in_equilibrium_and_describes_the_data(lanl):
    eq, fit = lanl.reduction.equilibrium, lanl.fit
    assert fit.span == (eq.equilibrium_time, eq.loading_end)
    assert fit.rms < 0.03 * lanl.reduction.flow_stress(0.15, "3-wave", true=True)
    assert 0.0 < fit.a < 150e6                       # annealed copper yields low
    assert fit.elastic_fraction == 0.0


def test_the_page_holds_the_numbers_of_this_run(lanl):
    page = (ROOT / "docs" / "validation-shpb.md").read_text(encoding="utf-8")
    f, p = lanl.fit, lanl.prediction
    assert f"A = {validate_shpb.mpa(f.a)}, B = {validate_shpb.mpa(f.b)}, n = {f.n:.3f}" in page
    assert f"| reflected (incident-bar gauge) | {100 * p.reflected:.1f} % |" in page
    assert f"| transmitted | {100 * p.transmitted:.1f} % |" in page
    for row in validate_shpb.reduction_rows(lanl):
        assert row in page


def test_the_pmma_record_unloads_faster_than_any_pmma_modulus_allows():
    # the page's explanation of the PMMA misfit: the reduced stress falls at the end of the pulse along a slope far
    # above PMMA's moduli (3.3 GPa quasi-static, about 6 GPa at the highest rates), and the page says so
    shot = validate_shpb.mini_shot()
    red = validate_shpb.reduce_shot(shot.signals, shot.incident_bar, shot.transmitted_bar, shot.specimen)
    u = validate_shpb.unloading(red)
    assert u.peak_stress > 2.0 * u.end_stress > 0.0 and u.peak_strain > u.end_strain
    assert u.modulus > 5.0 * max(e for e, _ in validate_shpb.PMMA_VARIANTS)
    page = (ROOT / "docs" / "validation-shpb.md").read_text(encoding="utf-8")
    assert validate_shpb.unloading_note(shot, red) in page


def test_mini_kolsky_shot_reads_from_the_repository():
    shot = validate_shpb.mini_shot()
    assert shot.signals.time.size == 2250 and np.isclose(shot.signals.dt, 40e-9)
    assert np.min(shot.signals.transmitted) < -1e-3                 # the transmitted pulse is in the excerpt


def test_the_pmma_failure_rows_are_this_runs_and_eps_f_lies_on_the_fitted_curve():
    # the failure strain: the fitted Johnson-Cook flow stress at eps_f and the loading part's mean rate equals the
    # largest 3-wave true stress (checked here with the compiled law's own flow stress, an independent evaluation);
    # the page holds the rows this run gives
    from rodimpact.direct.joints import flow_stress

    intact, ff, runs = validate_shpb.validate_failure()
    law = validate_shpb.johnson_cook(intact.shot, intact.fit.a, intact.fit.b, intact.fit.n)
    stress = flow_stress.py_func(law.code, law.kernel(), ff.failure_strain, ff.rate)
    assert stress == pytest.approx(ff.peak_stress, rel=1e-9)
    assert ff.softening_strain == pytest.approx(ff.rate * ff.collapse, rel=1e-12)
    page = (ROOT / "docs" / "validation-shpb.md").read_text(encoding="utf-8")
    for row in validate_shpb.failure_section(intact, ff, runs):
        assert row in page


def test_the_least_squares_failure_fit_is_this_runs_and_lowers_the_transmitted_misfit():
    # the fit minimises the transmitted misfit from a grid of starts; the rule-based headline pair is one point of
    # the same objective, so a fit that ends above it has missed that basin (a multi-start search that failed);
    # the page holds the row this run gives
    match = validate_shpb.match_failure()
    _, _, runs = validate_shpb.validate_failure()
    assert match.prediction.transmitted <= runs[0].prediction.transmitted * (1 + 1e-9)
    assert 1 <= match.reached <= match.starts == len(validate_shpb.FAILURE_STARTS)
    page = (ROOT / "docs" / "validation-shpb.md").read_text(encoding="utf-8")
    for row in validate_shpb.match_section(match):
        assert row in page
