"""The static friction measured apart from the track (a tilt test, or the ``mu_s`` and
``mu_s_err`` an ``eccjump design`` sheet was made for), as evidence beside the track's.

Why it is needed: a track that rolls up to its lift-off bounds μ_s only from below (what
the rolling needs). A slip of one frame just before the lift-off needs μ_s just below that
need, and then the body slips with almost the friction it had: the positions move by
micrometres, and no frame rate or noise level can exclude it (the design's JARM body at
240 fps: χ² −0.7 to 5 against the 9 needed). A measured μ_s can. Such a slip needs μ_s at
most ``mu_slip``, and a measurement μ ± σ (normal) makes that less likely by
((μ − mu_slip)/σ)², a χ² of one degree of freedom added to the track's. A rolling
that needs more than the measured μ_s pays ((need − μ)/σ)² the same way.

The penalty against a slip is taken at the rolling's need, the largest μ_s a slip can
have at the fitted start: it errs low, and a verdict that rests on it errs towards
``undetermined``. The measurement is trusted as given: a
μ_s measured too high makes a slip look unlikely, and the evidence says that the verdict
rests on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from eccjump.studies.experiment.fit import (
    Fit,
    Setup,
    fitted_needs,
    slip_frames,
)
from eccjump.studies.experiment.inputs import in_range
from eccjump.studies.experiment.one_frame import (
    OneFrameSlip,
    one_frame_slip,
    slipping_mu_s,
)
from eccjump.studies.experiment.reconstruction import Reconstruction
from eccjump.studies.experiment.track import Track

#: What ``weigh`` works on: the setup, the track and its reconstruction.
Scene = tuple[Setup, Track, Reconstruction]


@dataclass(frozen=True)
class MeasuredFriction:
    """μ_s measured apart from the track: ``value`` ± ``err`` (one standard deviation,
    normal) and where it came from (``"given"`` or ``"design"``)."""

    value: float
    err: float
    source: str

    def against_slip(self, mu_slip: float) -> float:
        """How much less likely (a χ²) the measurement makes a run that slips only
        with μ_s at most ``mu_slip``: 0 if the measured value is below it."""
        return (max(self.value - mu_slip, 0.0) / self.err) ** 2

    def against_rolling(self, needs: float) -> float:
        """The same for a rolling that needs μ_s of at least ``needs`` (inf: no finite μ_s
        holds it)."""
        if not math.isfinite(needs):
            return math.inf
        return (max(needs - self.value, 0.0) / self.err) ** 2

    @property
    def shown(self) -> str:
        """The value and its error as the report prints them."""
        return f"{self.value:.3g} +- {self.err:.2g}"

    def text(self) -> str:
        where = " (from the design sheet)" if self.source == "design" else ""
        return f"mu_s = {self.shown}{where}"

    def as_dict(self) -> dict[str, Any]:
        return {"value": self.value, "err": self.err, "source": self.source}


def measured_friction(
    mu_s: float | None, mu_s_err: float | None, sheet: dict[str, float]
) -> tuple[MeasuredFriction | None, tuple[str, ...]]:
    """The measured μ_s from ``mu_s`` and ``mu_s_err`` (both or neither), else from a
    design sheet that gives an uncertainty (one of 0 is no measurement: a note says so);
    None where there is none. ValueError naming the parameter for a bad value."""
    if mu_s is None and mu_s_err is None:
        value, err = sheet.get("mu_s"), sheet.get("mu_s_err")
        if value is None or err is None:
            return None, ()
        if not err > 0:
            return None, (
                "the design sheet's mu_s has no uncertainty (mu_s_err 0): not used as a "
                "measurement; give mu_s and mu_s_err to use it",
            )
        given = " (from design)"
        measured = MeasuredFriction(
            in_range("mu_s", value, given), in_range("mu_s_err", err, given), "design"
        )
        return measured, (
            f"the design sheet's mu_s = {measured.shown} is taken as the measured static "
            "friction (give mu_s and mu_s_err to override it)",
        )
    if mu_s is None or mu_s_err is None:
        missing = "mu_s" if mu_s is None else "mu_s_err"
        raise ValueError(
            f"{missing} is needed too: a measured static friction (mu_s) and its standard "
            "deviation (mu_s_err) come together"
        )
    measured = MeasuredFriction(in_range("mu_s", mu_s), in_range("mu_s_err", mu_s_err), "given")
    if measured.err < measured.value:
        return measured, ()
    return measured, (
        f"mu_s_err = {measured.err:.3g} is not below mu_s = {measured.value:.3g}: the "
        "measurement says little (a standard deviation, not a percentage?)",
    )


def weigh(
    friction: MeasuredFriction,
    fits: tuple[Fit, Fit | None],
    one: OneFrameSlip | None,
    scene: Scene,
    significant: float,
) -> tuple[Fit, Fit | None, float, tuple[str, ...]]:
    """The free and slip-forbidden fits to judge from, what a slip of one frame would cost
    the track and the measured μ_s together (``one``: the track's part, where the free fit
    rolls), and the evidence of that.

    A slip needs μ_s below what the rolling needs: a measured μ_s above that weighs
    against every slip (against the largest μ_s found to slip a frame, if higher: the
    penalty errs low). A free fit that slips where the track does not ask for it (below
    ``significant``, the slip test's threshold) gives way to the rolling fit when the
    measurement makes its slip less likely than the rolling by more than the slip gains on
    the track; that margin then bounds the one-frame test too (its slip is one of a frame
    or more). A slip the track asks for stays (a slip the data ask for is never jarm):
    where the measurement makes it unlikely, the evidence says so."""
    best, jarm_fit = fits
    setup, track, rec = scene
    frames = slip_frames(best, setup, track)
    if frames < 1.0 or jarm_fit is None:
        if one is None:
            return best, jarm_fit, math.nan, ()
        total, line = _one_frame_with(friction, one, jarm_fit or best, scene)
        return best, jarm_fit, total, (line,)
    needs = fitted_needs(jarm_fit, setup, track)
    found = slipping_mu_s(best, setup, track, rec)  # at the free fit's own start
    on_track = 2.0 * (jarm_fit.cost - best.cost) / best.variance_factor
    if on_track >= significant:  # a slip the track asks for
        return best, jarm_fit, math.nan, _contradicted(friction, found, frames, significant)
    mu_slip = max(found, needs) if math.isfinite(found) else needs
    by = friction.against_slip(mu_slip) - friction.against_rolling(needs) - on_track
    if not by > 0:
        return best, jarm_fit, math.nan, ()
    total, line = _one_frame_with(
        friction, one_frame_slip(jarm_fit, setup, track, rec), jarm_fit, scene
    )
    return (
        jarm_fit,
        None,
        min(by, total),
        (
            f"the free fit's slip of {frames:.1f} frames needs mu_s < {mu_slip:.3g}; with "
            f"the measured {friction.text()} the fit that rolls is better by chi2 = {by:.3g}",
            line,
        ),
    )


def _contradicted(
    friction: MeasuredFriction, mu_slip: float, frames: float, significant: float
) -> tuple[str, ...]:
    """The evidence where the measured μ_s makes unlikely (at least ``significant``) a
    slip the track asks for, which needs μ_s below ``mu_slip``: none where it does not."""
    against = friction.against_slip(mu_slip) if math.isfinite(mu_slip) else 0.0
    if against < significant:
        return ()
    return (
        f"the track's slip of {frames:.1f} frames needs mu_s < {mu_slip:.3g}, which the "
        f"measured {friction.text()} makes unlikely (chi2 = {against:.3g}): check the "
        "friction measurement",
    )


def _one_frame_with(
    friction: MeasuredFriction, one: OneFrameSlip, rolling: Fit, scene: Scene
) -> tuple[float, str]:
    """What a slip of one frame costs the ``rolling`` fit and the measured μ_s together:
    the track's χ² (``one_frame.one_frame_slip``) plus what the measurement says against
    a μ_s below the rolling's need, less what it says against that need; and the
    sentence."""
    if not math.isfinite(one.mu_s):
        return math.nan, "no lowered mu_s gives a run that slips a frame and lifts off"
    needs = fitted_needs(rolling, *scene[:2])
    against = friction.against_slip(max(one.mu_s, needs)) - friction.against_rolling(needs)
    whose = "the slip-forbidden fit's rolling" if rolling.jarm_only else "the fitted rolling"
    return one.cost + against, (
        f"a slip of one frame before the lift-off needs mu_s below what {whose} needs, "
        f"{needs:.3g}: the measured {friction.text()} weighs chi2 = {against:.3g} against "
        f"it, the track {one.cost:.2g}"
    )
