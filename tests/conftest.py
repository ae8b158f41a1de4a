"""Shared test settings."""

import os

import matplotlib
from hypothesis import settings

matplotlib.use("Agg")
settings.register_profile("ci", max_examples=25, deadline=None)
settings.register_profile("dev", max_examples=25, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
