"""``eccjump.uncertainty``: how sure is a jump when the body, the ramp and the friction are
known only within tolerances? A Monte Carlo (or quasi-Monte Carlo) study over the
samples of :mod:`.sampling`, each answered by :mod:`.questions`."""

from __future__ import annotations

from typing import Literal

import numpy as np

from eccjump._base.body import Cylinder
from eccjump._base.checks import Integrator, Rule, flag, optional_real, real, rule_name, text
from eccjump._base.docs import fill
from eccjump._base.progress import Progress, checked, reporting
from eccjump._base.sizes import check_fits, uncertainty_bytes
from eccjump._base.units import ramp_angle
from eccjump.classification.fields import JARM
from eccjump.motion.fields import MOTION
from eccjump.motion.options import MotionOptions
from eccjump.studies.uncertainty.delta import delta_method
from eccjump.studies.uncertainty.indices import design, evaluate_all, study_indices
from eccjump.studies.uncertainty.questions import jumps, outcome_counts, ran
from eccjump.studies.uncertainty.results import (
    QUANTITIES,
    Summary,
    Uncertainty,
    check_confidence,
    wilson,
)
from eccjump.studies.uncertainty.sampling import (
    PARAMETERS,
    Invalid,
    Sampling,
    draw,
    options,
    spread,
)
from eccjump.studies.uncertainty.scheduled import chunk_size, evaluate_scheduled

#: The parameters the JARM question can vary: :func:`eccjump.jarm` takes one start (theta0,
#: omega0) for all its points, and neither mu_k nor e enters the classification.
JARM_PARAMETERS = ("chi", "km", "alpha", "mu_s")

Question = Literal["jarm", "motion"]


@fill
def uncertainty(
    body: Cylinder,
    alpha: float,
    mu_s: float,
    *,
    mu_k: float | None = None,
    restitution: float = 0.0,
    theta0: float = 0.0,
    omega0: float = 0.0,
    sd: dict[str, float] | None = None,
    bounds: dict[str, tuple[float, float]] | None = None,
    n: int = 10_000,
    seed: int = 0,
    sampling: Sampling = "random",
    question: Question = "jarm",
    invalid: Invalid = "truncate",
    confidence: float = 0.95,
    indices: bool = False,
    rule: Rule = "paper",
    t_max: float = 100.0,
    max_transitions: int = 100,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    integrator: Integrator = "RK45",
    n_threads: int = 0,
    chunks: int | None = None,
    progress: bool | Progress | None = None,
) -> Uncertainty:
    """The probability of a JARM, of each outcome, and the spread of the lift-off and the
    first flight, when the inputs vary within tolerances.

    The nominal point is ``body`` on a ramp of angle ``alpha`` with friction ``mu_s`` (and
    ``mu_k``, ``restitution``, the start ``theta0``, ``omega0``); ``sd`` gives normal
    standard deviations and ``bounds`` uniform ranges (lo, hi), by parameter name among
    χ, km (the body's k_m), α, μ_s, μ_k, restitution, theta0 and omega0. ``n``
    samples are drawn (pseudo-random, or scrambled Sobol' with ``sampling="sobol"``) and
    each is classified by :func:`eccjump.jarm` (``question="jarm"``, the closed form) or run
    to its first landing by :func:`eccjump.motion_points` (``question="motion"``).

    The argument order is :func:`eccjump.simulate`'s -- the body, then the ramp, then
    ``mu_s`` -- with ``mu_s`` positional as in :func:`eccjump.jarm`,
    :func:`eccjump.motion_map` and :func:`eccjump.design` (``mu_s=`` works too); every
    option is keyword-only, named and defaulted as in ``simulate`` and ``motion_map``.

    Samples outside the physical range (χ outside [0, 1], k_m > 1 - χ, μ < 0,
    μ_k > μ_s, e outside [0, 1], α outside [0, π/2]) follow ``invalid``:
    ``"truncate"`` (default) conditions each distribution on its range by the inverse CDF of
    the truncated distribution (k_m's range is that of the sample's own χ, μ_k's that of
    its μ_s): no sample is redrawn, so the result is the same for any thread count and the
    Sobol' structure is kept; ``"count"`` keeps the distributions as given and counts the
    samples outside as invalid. Invalid samples count in no probability; ``n_valid`` and
    ``p_invalid`` report them. The samples, and so every result, are bit-identical for any
    ``n_threads``.

    Parameters
    ----------
    body : Cylinder
        The nominal body (χ, km).
    alpha : float
        Nominal ramp angle [rad], in [0, π/2] (``math.radians`` for degrees).
    mu_s : float
        Nominal static friction coefficient, in [0, inf).
    mu_k : float or None, default None
        Nominal kinetic friction coefficient, in [0, μ_s]; None: each sample's μ_k is its
        μ_s (if μ_k varies, around the nominal μ_s).
    restitution : float, default 0.0
        Nominal Stronge coefficient of restitution, in [0, 1].
    theta0 : float, default 0.0
        Nominal initial angle [rad].
    omega0 : float, default 0.0
        Nominal initial angular velocity [√(g/R) rad].
    sd : dict of str to float or None, default None
        Normal standard deviations (≥ 0, in the parameter's unit) by parameter name; 0:
        the parameter is fixed.
    bounds : dict of str to (float, float) or None, default None
        Uniform ranges (lo ≤ hi, absolute values in the parameter's unit) by parameter
        name. A parameter is in ``sd`` or in ``bounds``, not both.
    n : int, default 10_000
        Samples, 1 ... 10**8.
    seed : int, default 0
        Seed of numpy's PCG64 stream or of the Sobol' scrambling, ≥ 0.
    sampling : {"random", "sobol"}, default "random"
        Pseudo-random points, or the first n points of Owen-scrambled Sobol'
        (``scipy.stats.qmc.Sobol``; best for n a power of 2; normals by the inverse CDF).
    question : {"jarm", "motion"}, default "jarm"
        ``"jarm"``: the JARM classification by the closed forms (10**5 samples take well
        under a second; it can vary χ, km, α and μ_s); ``"motion"``: the full motion
        to the first landing (every parameter; the sequences of modes, the first flight).
    invalid : {"truncate", "count"}, default "truncate"
        How samples outside the physical range are treated (see above).
    confidence : float, default 0.95
        Level of the Wilson intervals, in (0, 1 - 1e-15] (closer to 1 the two-sided normal
        quantile is infinite in floating point), and of the indices' bootstrap intervals.
    indices : bool, default False
        Also estimate which tolerance matters: the first-order and total Sobol' indices of
        the JARM indicator for each varied parameter, by Saltelli's design (the study's n
        samples, n more, and n per varied parameter: **n (d + 2) runs** for d varied
        parameters) and Jansen's estimators, with bootstrap intervals
        (:mod:`eccjump.studies.uncertainty.indices`: how the k_m ≤ 1 − χ truncation is
        treated; fewer than half the design's rows in range is a ValueError). The study's
        other results are the same bits either way.
    %(rule_rolling)s
    t_max, max_transitions, rtol, atol, integrator
        The full motion's options (``question="motion"``), as in :func:`eccjump.motion_map`.
    %(n_threads)s
    chunks : int or None, default None
        None computes here. Otherwise samples per chunk (1 ... 10**8): the chunks are dask
        tasks computed by the current scheduler (a ``dask.distributed`` cluster when a
        ``Client`` is active; ``pip install "eccjump[dask]"``), with ``n_threads`` threads
        each; the result is bit-identical for any chunk size, scheduler or worker count.
    progress : bool, callable or None, default None
        Progress of the work, in valid samples: None or False, none; True, a bar on stderr
        (tqdm); a callable, called as ``progress(done, total)`` after each chunk of them
        (anything else is a TypeError before any work). The result is the same either way.
        Not with ``chunks`` (a ValueError: dask reports its tasks' progress).

    Returns
    -------
    Uncertainty
        ``p_jarm`` with its Wilson interval ``p_jarm_ci`` (for Sobol' samples the random
        sampling interval: conservative), ``counts``/``probabilities`` of each outcome, the
        ``distributions`` of the lift-off angle (and, for "motion", its time, the flight
        time, apex and distance), the samples and outcomes, and ``delta``, the first-order
        estimate from the exact derivatives at the nominal point (question "jarm"), and
        with ``indices=True`` the Sobol' ``indices`` by parameter (``.first``, ``.total``,
        each ``.value``, ``.low``, ``.high``), for "motion" also ``liftoff_indices``, those
        of the first lift-off's time.

    Raises
    ------
    ValueError
        For an unknown parameter name, a negative or non-finite sd, bounds with lo > hi, a
        parameter varied that the question does not use, n < 1, a nominal value outside
        its range, or no valid sample at all; the message names the parameter with its
        unit and range.
    TypeError
        If ``body`` is not a Cylinder or an argument has the wrong type.
    ImportError
        Without scipy (``pip install "eccjump[analysis]"``).

    See Also
    --------
    jarm : the classification of one point.
    motion_points : the full motion at given points.
    design : the most robust body and angle.

    Examples
    --------
    The paper's JARM point with a 1 degree tolerance on the ramp and 0.01 on χ:

    >>> import math
    >>> import eccjump
    >>> body = eccjump.Cylinder(chi=0.15, km=0.02)
    >>> u = eccjump.uncertainty(
    ...     body, math.radians(40), 1.0, sd={"alpha": math.radians(1), "chi": 0.01}, n=4096
    ... )
    >>> print(f"P(JARM) = {u.p_jarm:.3f}, 95 % [{u.p_jarm_ci[0]:.3f}, {u.p_jarm_ci[1]:.3f}]")
    P(JARM) = 0.978, 95 % [0.973, 0.982]
    """
    if not isinstance(body, Cylinder):
        raise TypeError(f"body must be a Cylinder, not {type(body).__name__}")
    alpha_, mu_s_ = ramp_angle("alpha", alpha), real("mu_s", mu_s)
    mu_k_ = optional_real("mu_k", mu_k)
    nominal = {
        "chi": body.chi,
        "km": body.km,
        "alpha": alpha_,
        "mu_s": mu_s_,
        "mu_k": mu_s_ if mu_k_ is None else mu_k_,
        "restitution": real("restitution", restitution),
        "theta0": real("theta0", theta0),
        "omega0": real("omega0", omega0),
    }
    q = text("question", question)
    if q not in ("jarm", "motion"):
        raise ValueError(f"question must be 'jarm' or 'motion', not {q!r}"[:200])
    allowed = JARM_PARAMETERS if q == "jarm" else PARAMETERS
    spec = spread(nominal, sd, bounds, allowed, mu_k_follows=mu_k_ is None)
    size, seed_, how, policy = options(n, seed, sampling, invalid)
    level = check_confidence(confidence)
    sobol = flag("indices", indices)
    if checked(progress) and chunks is not None:
        raise ValueError("progress needs chunks=None (dask reports the progress of its tasks)")
    per_chunk = None if chunks is None else chunk_size(chunks)
    opts = _question_options(q, rule, t_max, max_transitions, rtol, atol, integrator, n_threads)
    per_sample = (JARM if q == "jarm" else MOTION).bytes_per_point()
    runs = size * (len(spec.varied) + 2) if sobol else size  # Saltelli's design
    need = uncertainty_bytes(runs, len(spec.varied), per_sample)
    check_fits("uncertainty", size, need, "n", "samples")
    cols, valid = draw(spec, size, seed_, how, policy)
    extra = design(spec, size, seed_, how, policy, valid) if sobol else None
    if per_chunk is not None:  # each sample is answered from its own values: same bits
        outcomes = evaluate_scheduled(q, cols, valid, opts, per_chunk)
        answered = None
        if extra is not None:
            answered = (evaluate_scheduled(q, extra[0], extra[1], opts, per_chunk), extra[1])
    else:
        with reporting(progress, "sample") as report:
            outcomes, answered = evaluate_all(q, (cols, valid), extra, opts, report)
    found = liftoff = None
    if sobol:  # each row of the design drops what the core refused itself (study_indices)
        found, liftoff = study_indices(q, spec.varied, (outcomes, valid), answered, level, seed_)
    valid &= ran(q, outcomes)  # k_m = 0 has no full motion (simulate needs k_m > 0)
    n_valid = int(valid.sum())
    if n_valid == 0:  # no probability to give: an error, not NaN
        raise ValueError(
            "sd, bounds: no sample lies in the physical range (chi in [0, 1], km <= 1 - chi, "
            "mu_k <= mu_s, ...); narrow them or use invalid='truncate'"
        )
    k = int(jumps(q, outcomes)[valid].sum())
    return Uncertainty(
        question=q,
        sampling=how,
        invalid=policy,
        n=size,
        seed=seed_,
        confidence=level,
        nominal=nominal,
        sd=spec.sd,
        bounds=spec.bounds,
        samples={p: cols[p] for p in spec.varied},
        valid=valid,
        outcomes=outcomes,
        n_valid=n_valid,
        p_jarm=k / n_valid,
        p_jarm_ci=wilson(k, n_valid, level),
        counts=outcome_counts(q, outcomes, valid),
        distributions={
            name: Summary.of(np.where(valid, outcomes[name], np.nan))
            for name in QUANTITIES
            if name in outcomes
        },
        delta=delta_method(spec, q, rule_name(rule), opts),
        indices=found,
        liftoff_indices=liftoff,
    )


def _question_options(
    question: str,
    rule: Rule,
    t_max: float,
    max_transitions: int,
    rtol: float,
    atol: float,
    integrator: Integrator,
    n_threads: int,
) -> dict[str, object]:
    """The keyword options of the question's function. The full motion's options are checked
    whatever the question (by the one path of every entry point of the full motion), so that
    a bad one is an error even where the closed form does not use it."""
    opts = MotionOptions(
        rule=rule,
        t_max=t_max,
        max_transitions=max_transitions,
        rtol=rtol,
        atol=atol,
        integrator=integrator,
    )
    opts.to_core(n_threads)
    if question == "jarm":
        return {"rule": opts.rule, "n_threads": n_threads}
    return {**opts.keywords(), "n_threads": n_threads}


__all__ = ["JARM_PARAMETERS", "Question", "uncertainty"]
