"""Tools for testing code built on eccjump: hypothesis strategies of valid inputs
(:mod:`eccjump.testing.strategies`) and assertions about results
(:func:`assert_ledger_closes`, :func:`assert_maps_equal`), as ``xarray.testing`` does for
xarray. Needs hypothesis (``pip install "eccjump[testing]"``); ``import eccjump`` never
imports this package.

Examples
--------
>>> import eccjump
>>> from hypothesis import given, settings
>>> from eccjump.testing import strategies
>>> @settings(max_examples=20, deadline=None)
... @given(strategies.bodies(), strategies.ramps(), strategies.frictions())
... def test_every_point_has_a_verdict(body, alpha, friction):
...     r = eccjump.jarm(alpha, body.chi, body.km, friction.mu_s)
...     assert eccjump.Reason(int(r.reason)) is not eccjump.Reason.INVALID_PARAMS
>>> test_every_point_has_a_verdict()
"""

from eccjump._base import optional

optional.require("hypothesis", purpose="eccjump.testing", extra="testing")

from eccjump.testing import strategies  # noqa: E402  (after the check of the extra)
from eccjump.testing.assertions import (  # noqa: E402
    assert_ledger_closes,
    assert_maps_equal,
    ledger_scale,
)

__all__ = ["assert_ledger_closes", "assert_maps_equal", "ledger_scale", "strategies"]
