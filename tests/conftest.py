"""Test configuration: hypothesis runs derandomized by default, so that a run of the suite is
reproducible (CI never fails on a new random example). Set HYPOTHESIS_PROFILE=explore for a
randomized, longer search when looking for counterexamples."""

import os

from hypothesis import settings

settings.register_profile("default", derandomize=True, database=None, deadline=None)
settings.register_profile("explore", max_examples=500, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))


def pytest_collection_modifyitems(config, items):
    """The campaigns (minutes each) run only when a ``-m`` names them (``pytest -m campaign``).
    Here, not in addopts: a ``-m`` on the command line replaces the one in addopts, so
    ``pytest -m "not slow"``, the quick check, would run them all."""
    if "campaign" in (config.getoption("markexpr") or ""):
        return
    campaigns = [item for item in items if item.get_closest_marker("campaign")]
    if campaigns:
        config.hook.pytest_deselected(items=campaigns)
        items[:] = [item for item in items if not item.get_closest_marker("campaign")]
