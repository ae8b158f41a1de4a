"""Shared test settings.

Hypothesis profiles (choose with the environment variable ``HYPOTHESIS_PROFILE``):

* ``ci`` (the default, always loaded unless another profile is named): 25 examples per property,
  ``derandomize=True`` -- the examples follow from the test itself, so every run (CI, a colleague's machine,
  the mutation check in ``scripts/mutation_check.py``) tests the same cases and a failure reproduces;
  no deadline (compiled kernels are built on first use);
* ``explore``: 1000 examples per property, random seeds, for a longer hunt for counter-examples before a
  release or after changing a kernel (``HYPOTHESIS_PROFILE=explore pytest tests/direct tests/inverse``);
  a failure prints the ``@reproduce_failure`` blob and is stored in the local example database;
* ``dev``: 25 random examples (the old default).
"""

import os

import matplotlib
from hypothesis import HealthCheck, settings

matplotlib.use("Agg")
# Hypothesis loads its own "ci" profile (derandomised, no database) when the environment variable CI is set;
# ours are based on hypothesis's "default" profile so that they mean the same thing on CI and off it.
_BASE = settings.get_profile("default")
settings.register_profile(
    "ci", _BASE, max_examples=25, deadline=None, derandomize=True, database=None, print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile("explore", _BASE, max_examples=1000, deadline=None, print_blob=True)
settings.register_profile("dev", _BASE, max_examples=25, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE") or "ci")
