"""Progress lines on a terminal, the relative-improvement stopping criterion, and the convergence plot's
explanation of its runs (issue 20, item 5)."""

import io
import sys
import warnings

import numpy as np
import pytest

import rodimpact as ri
from rodimpact.plotting.design import plot_convergence

DT = 2e-6


def _half_sine(progress=None, **search):
    bar = ri.Rod.from_impedance([6e4] * 8, DT)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -5e4 * np.sin(np.pi * t / 40e-6), duration=40e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        return ri.design(target, ri.System.struck(bar, far_end="nonreflecting"), 8.0, n=10, dt=DT,
                         limits=ri.StrikerLimits(impedance_bounds=(5e3, 2e5)), search=ri.SearchOptions(**search),
                         progress=progress)


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_lines_go_to_stderr_on_a_terminal_only(monkeypatch):
    term = _Terminal()
    monkeypatch.setattr(sys, "stderr", term)
    d = _half_sine(max_iterations=20, starts=2)
    lines = [ln for ln in term.getvalue().splitlines() if ln.startswith("design:")]
    assert lines, "no progress on a terminal"
    assert all("iteration" in ln and "misfit" in ln and "best so far" in ln for ln in lines)
    best = float(lines[-1].split("best so far ")[1].split()[0])
    assert best == pytest.approx(d.misfit, rel=1e-5)
    pipe = io.StringIO()                      # not a terminal: silent unless asked
    monkeypatch.setattr(sys, "stderr", pipe)
    _half_sine(max_iterations=5, starts=1)
    assert pipe.getvalue() == ""
    _half_sine(max_iterations=5, starts=1, progress=True)
    assert "best so far" in pipe.getvalue()


def test_a_looser_improvement_criterion_stops_earlier():
    """With improvement = 0 only the iteration limit and L-BFGS-B's own ftol stop; a run whose best value has
    improved by less than 1e-2 (relative) over 10 iterations stops there."""
    z_bar = ri.STEEL.impedance(np.pi / 4 * 0.02 ** 2)
    bar = ri.Rod.from_impedance([z_bar] * 8, 100e-6 / 60)
    target = ri.inverse.ForceTarget.from_callable(lambda t: -80e3 * np.sin(np.pi * t / 100e-6), duration=100e-6)
    kw = dict(struck=ri.System.struck(bar, far_end="nonreflecting"), striker_velocity=12.0, n=30, dt=100e-6 / 60,
              limits=ri.StrikerLimits(diameter_bounds=(0.005, 0.06)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ri.SynthesisWarning)
        full = ri.design(target, search=ri.SearchOptions(improvement=0.0, max_iterations=150, starts=1), **kw)
        early = ri.design(target, search=ri.SearchOptions(improvement=1e-2, max_iterations=150, starts=1), **kw)
    assert early.iterations < full.iterations
    h = np.asarray(early.convergence[0])
    best = np.minimum.accumulate(h)
    assert best[-11] - best[-1] <= 1e-2 * best[-11]          # the criterion held where it stopped
    assert early.diagnostics["optimizer_message"].startswith("CONVERGED: the best objective improved")
    with pytest.raises(ValueError, match="SearchOptions.improvement"):
        ri.SearchOptions(improvement=-1.0)
    with pytest.raises(TypeError, match="SearchOptions.improvement"):
        ri.SearchOptions(improvement="1e-3")


def test_the_convergence_plot_says_why_there_are_more_runs_than_starts():
    d = _half_sine(max_iterations=20, starts=2)
    n_runs, n_starts = len(d.convergence), len(d.diagnostics["starts"])
    assert n_runs > n_starts
    ax = plot_convergence(d)
    assert f"{n_runs} runs from {n_starts} starts" in ax.get_title()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("levels" in t for t in labels) and any("free profile" in t for t in labels)
