"""Test configuration: hypothesis runs derandomized by default, so that a run of the suite is
reproducible (CI never fails on a new random example). Set HYPOTHESIS_PROFILE=explore for a
randomized, longer search when looking for counterexamples."""

import os

from hypothesis import settings

settings.register_profile("default", derandomize=True, database=None, deadline=None)
settings.register_profile("explore", max_examples=500, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))
