"""An :class:`~eccjump.Analysis` taken elsewhere: as a labelled ``xarray.Dataset`` (the data
of the track, what was reconstructed from it and the fitted model, frame by frame, with
units; the verdict and its numbers as attributes). Saving and reading back:
:mod:`eccjump.maps.results` (the whole analysis, the track and both fits included)."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

import numpy as np

from eccjump.maps import results
from eccjump.studies.experiment.figure import NAMES

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

#: The reconstruction's series along ``frame``: (long name, units).
RECONSTRUCTED = {
    "theta": ("angle of the marker from the ramp normal", "rad"),
    "l": ("position of C along the ramp from its first frame", "m"),
    "b": ("height of C above the ramp (R in contact)", "m"),
    "s": ("slip displacement l - R (theta - theta[0])", "m"),
    "omega": ("angular velocity, smoothed", "rad/s"),
    "ldot": ("speed of C along the ramp, smoothed", "m/s"),
    "bdot": ("rate of b, smoothed", "m/s"),
    "slip": ("slip velocity ldot - R omega, smoothed", "m/s"),
}
_ERRORS = ("theta", "s", "omega", "ldot", "bdot", "slip")


def analysis_dataset(a: Any) -> xr.Dataset:
    """The analysis ``a`` as a dataset (:meth:`eccjump.Analysis.to_xarray`)."""
    rec = a.rec
    data: dict[str, Any] = {}
    for k, (long_name, units) in RECONSTRUCTED.items():
        data[k] = ("frame", getattr(rec, k), {"long_name": long_name, "units": units})
        if k in _ERRORS:
            err = {"long_name": f"standard error of {k}", "units": units}
            data[f"{k}_err"] = ("frame", getattr(rec, f"{k}_err"), err)
    data |= _track_vars(a) | _model_vars(a)
    slips = [tuple(vars(s).values()) for s in a.slips]
    data |= results.records_of(
        "slip_interval", slips, ("t1", "t2", "t1_err", "t2_err", "frames"), _slip
    )
    coords = {
        "t": ("frame", rec.t, {"long_name": "time of the frame", "units": "s"}),
        "xy": ("xy", np.array(["x", "y"]), {"long_name": "lab axis", "units": "1"}),
    }
    return results.dataset(a, data, coords, _attrs(a))


def _slip(name: str) -> dict[str, str]:
    return {"units": "1" if name == "frames" else "s"}


def _track_vars(a: Any) -> dict[str, Any]:
    mode = {
        "long_name": "mode seen in the track",
        "flag_values": np.arange(len(NAMES), dtype=np.int8),
        "flag_meanings": " ".join(NAMES),
    }
    return {
        "c": (("frame", "xy"), a.track.c, {"long_name": "axle position in the lab", "units": "m"}),
        "m": (
            ("frame", "xy"),
            a.track.m,
            {"long_name": "marker position in the lab", "units": "m"},
        ),
        "observed_mode": ("frame", a.observed.mode, mode),
    }


def _model_vars(a: Any) -> dict[str, Any]:
    """The fitted model at the frames (its dimensionless states in SI units)."""
    y, radius, unit = a.fit.states, a.setup.radius, a.setup.time_unit
    return {
        "model_theta": ("frame", y[0], {"long_name": "theta of the fitted model", "units": "rad"}),
        "model_b": ("frame", y[4] * radius, {"long_name": "b of the fitted model", "units": "m"}),
        "model_slip": (
            "frame",
            (y[3] - y[1]) * radius / unit,
            {"long_name": "slip velocity of the fitted model", "units": "m/s"},
        ),
    }


def _attrs(a: Any) -> dict[str, Any]:
    names = ("verdict", "reason", "liftoff_t", "liftoff_err", "delta_chi2", "mu_s_needed")
    out = {k: getattr(a, k) for k in (*names, "seconds")}
    out |= {"mu_k_lo": a.mu_k_interval[0], "mu_k_hi": a.mu_k_interval[1]}
    out |= {"evidence": "\n".join(a.evidence), "notes": "\n".join(a.notes)}
    out["summary"] = json.dumps(a.to_dict(), ensure_ascii=False)
    return out
