"""What each sample answers: the JARM classification (:func:`eccjump.jarm`, closed form) or
the full motion to the first landing (:func:`eccjump.motion_points`), computed in chunks so
that a caller can show progress. Each sample is computed from its own values alone, so the
chunking and the thread count change no bit."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.progress import Progress
from eccjump.classification.classify import jarm
from eccjump.classification.fields import Reason
from eccjump.motion.fields import DTYPES, FIELDS, FILL, INVALID, sequence_name
from eccjump.motion.points import motion_points

#: Samples per core call: about 0.05 s of closed form, 1 s of full motion on 2 cores.
CHUNK = {"jarm": 1 << 17, "motion": 1 << 14}

#: The fields of a JARM sample, with their fill values for an invalid one.
JARM_FILL: dict[str, Any] = {
    "is_jarm": False,
    "reason": np.uint8(Reason.INVALID_PARAMS),
    "liftoff_theta": np.nan,
    "Fy_J": np.nan,
    "max_ratio": np.nan,
}

#: The dtype of each outcome field of a question, in the order of ``Uncertainty.outcomes``.
OUTCOME_DTYPES: dict[str, dict[str, np.dtype]] = {
    "jarm": {k: np.asarray(v).dtype for k, v in JARM_FILL.items()},
    "motion": {k: np.dtype(DTYPES[k]) for k in FIELDS},
}


def _empty(fill: Mapping[str, Any], dtypes: Mapping[str, Any], n: int) -> dict[str, NDArray[Any]]:
    return {k: np.full(n, v, dtype=dtypes[k]) for k, v in fill.items()}


def _jarm_chunk(cols: Mapping[str, NDArray], opts: Mapping[str, Any]) -> dict[str, NDArray]:
    r = jarm(cols["alpha"], cols["chi"], cols["km"], cols["mu_s"], **opts)
    is_jarm = np.asarray(r.is_jarm)
    return {
        "is_jarm": is_jarm,
        "reason": np.asarray(r.reason, dtype=np.uint8),
        "liftoff_theta": np.where(is_jarm, r.theta_J, np.nan),
        "Fy_J": np.asarray(r.Fy_J),
        "max_ratio": np.asarray(r.max_ratio),
    }


def _motion_chunk(cols: Mapping[str, NDArray], opts: Mapping[str, Any]) -> dict[str, NDArray]:
    p = motion_points(
        cols["alpha"],
        cols["chi"],
        cols["km"],
        cols["mu_s"],
        mu_k=cols["mu_k"],
        restitution=cols["restitution"],
        theta0=cols["theta0"],
        omega0=cols["omega0"],
        **opts,
    )
    return p.as_dict()


def evaluate(
    question: str,
    cols: Mapping[str, NDArray[np.float64]],
    valid: NDArray[np.bool_],
    opts: Mapping[str, Any],
    progress: Progress | None = None,
) -> dict[str, NDArray[Any]]:
    """The outcome fields of every sample (the fill values where it is invalid), the valid
    ones computed in chunks of :data:`CHUNK`, ``progress(done, total)`` after each."""
    n = valid.size
    if question == "jarm":
        dtypes = {k: np.asarray(v).dtype for k, v in JARM_FILL.items()}
        out, chunk = _empty(JARM_FILL, dtypes, n), _jarm_chunk
    else:
        out, chunk = _empty(FILL, DTYPES, n), _motion_chunk
    idx = np.flatnonzero(valid)
    step = CHUNK[question]
    for i0 in range(0, idx.size, step):
        part = idx[i0 : i0 + step]
        got = chunk({k: np.ascontiguousarray(v[part]) for k, v in cols.items()}, opts)
        for k, v in got.items():
            out[k][part] = v
        if progress is not None:
            progress(min(i0 + step, idx.size), idx.size)
    return out


def ran(question: str, outcomes: Mapping[str, NDArray[Any]]) -> NDArray[np.bool_]:
    """Whether the question could be answered at each sample (the core found its values
    valid: not k_m = 0 for the full motion, for instance)."""
    if question == "jarm":
        return outcomes["reason"] != Reason.INVALID_PARAMS
    return outcomes["status"] != INVALID


def jumps(question: str, outcomes: Mapping[str, NDArray[Any]]) -> NDArray[np.bool_]:
    """Whether each sample is a JARM."""
    return outcomes["is_jarm" if question == "jarm" else "jarm"]


def outcome_counts(
    question: str, outcomes: Mapping[str, NDArray[Any]], valid: NDArray[np.bool_]
) -> dict[str, int]:
    """The valid samples of each outcome, most frequent first: by Reason name ("jarm") or
    by sequence of modes ("motion")."""
    key = outcomes["reason"] if question == "jarm" else outcomes["sequence"]
    codes, counts = np.unique(key[valid], return_counts=True)
    order = np.argsort(-counts, kind="stable")
    name = (lambda c: Reason(c).name) if question == "jarm" else sequence_name
    return {name(int(codes[i])): int(counts[i]) for i in order}


__all__ = ["CHUNK", "JARM_FILL", "OUTCOME_DTYPES", "evaluate", "jumps", "outcome_counts", "ran"]
