"""The suite's hypothesis settings (tests/conftest.py): derandomised unless a profile is chosen explicitly."""

import os

from hypothesis import settings


def test_default_profile_is_derandomized():
    if os.environ.get("HYPOTHESIS_PROFILE", "ci") in ("", "ci"):
        assert settings.default.derandomize
        assert settings.default.max_examples == 25
    else:
        assert settings.default is settings.get_profile(os.environ["HYPOTHESIS_PROFILE"])


def test_explore_profile_runs_more_random_examples():
    explore = settings.get_profile("explore")
    assert explore.max_examples >= 1000 and not explore.derandomize
