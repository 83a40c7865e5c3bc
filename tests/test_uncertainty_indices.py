"""uncertainty(..., indices=True): which tolerance matters. The Sobol' estimator against the
exact indices of the Ishigami function and a linear model and against a plain numpy Jansen
estimate on the same design; on eccjump, a fixed parameter has no index, one that cannot
change the verdict has ~0, first <= total, and scipy.stats.sobol_indices on its own samples
agrees within the statistical error; the study's other results are unchanged, the bits the
same for any thread count; files, figure and command line carry the indices."""

from __future__ import annotations

import inspect
import json
import math

import numpy as np
import pytest
from reference_points import JARM, JARM_ARGS

import eccjump
from eccjump.cli import main
from eccjump.studies.uncertainty.indices import GROUPS, cubes, design, sobol_indices
from eccjump.studies.uncertainty.sampling import spread

scipy_stats = pytest.importorskip("scipy.stats")

BODY, ALPHA = JARM
#: The lab's tolerances of the tutorial: about one sample in five is no JARM.
SD = {"alpha": math.radians(2), "chi": 0.02, "km": 0.01, "mu_s": 0.15}


def _saltelli(f, n: int, d: int, seed: int, sampling: str):
    """f at A, B and the AB_i of the study's own design (:func:`design`'s cubes)."""
    a, b = cubes(n, d, seed, sampling)
    ab = []
    for i in range(d):
        m = a.copy()
        m[:, i] = b[:, i]
        ab.append(f(m))
    return f(a), f(b), np.array(ab)


def _ishigami(u):
    x = -math.pi + 2 * math.pi * u
    return np.sin(x[:, 0]) + 7 * np.sin(x[:, 1]) ** 2 + 0.1 * x[:, 2] ** 4 * np.sin(x[:, 0])


def _ishigami_exact():
    """First-order and total indices of Ishigami (a = 7, b = 0.1), from its variance terms."""
    a, b, pi4 = 7.0, 0.1, math.pi**4
    v1 = 0.5 * (1 + b * pi4 / 5) ** 2
    v2 = a * a / 8
    v13 = b * b * pi4 * pi4 * (1 / 18 - 1 / 50)
    v = v1 + v2 + v13
    return np.array([v1, v2, 0.0]) / v, np.array([v1 + v13, v2, v13]) / v


def _plain_jansen(f_a, f_b, f_ab):
    """Jansen's estimators, written out with numpy alone."""
    var = np.var(np.concatenate([f_a, f_b]))
    first = np.array([var - np.mean((f_b - g) ** 2) / 2 for g in f_ab]) / var
    total = np.array([np.mean((f_a - g) ** 2) / 2 for g in f_ab]) / var
    return first, total


@pytest.mark.parametrize("sampling", ["random", "sobol"])
def test_ishigami_indices_are_the_exact_ones_and_plain_jansens(sampling):
    outputs = _saltelli(_ishigami, 2**14, 3, 1, sampling)
    got = sobol_indices(*outputs, ["x1", "x2", "x3"], 0.95, seed=1)
    first, total = _plain_jansen(*outputs)
    exact_first, exact_total = _ishigami_exact()
    for i, ix in enumerate(got.values()):
        assert ix.first.value == pytest.approx(first[i], abs=1e-12)
        assert ix.total.value == pytest.approx(total[i], abs=1e-12)
        # the exact index inside its 95 % interval, give or take a little of its width
        for est, exact in ((ix.first, exact_first[i]), (ix.total, exact_total[i])):
            slack = 0.25 * (est.high - est.low)
            assert est.low - slack <= exact <= est.high + slack, (i, est, exact)
            assert est.high - est.low < 0.06


def test_a_linear_model_has_first_equal_total_equal_its_share_of_the_variance():
    c = np.array([1.0, 2.0, 0.0, 3.0])
    f_a, f_b, f_ab = _saltelli(lambda u: u @ c, 4096, 4, 3, "random")
    got = sobol_indices(f_a, f_b, f_ab, list("abcd"), 0.95, seed=0)
    share = c**2 / np.sum(c**2)
    for i, ix in enumerate(got.values()):
        assert ix.total.value == pytest.approx(share[i], abs=0.03)
        assert ix.first.value == pytest.approx(share[i], abs=0.05)
    assert got["c"].total == (0.0, 0.0, 0.0)  # f(A) == f(AB_c) row by row: exactly 0


def test_bootstrap_groups_bound_the_work_and_agree_with_the_ungrouped_interval():
    # Past GROUPS rows the bootstrap resamples groups of rows: the interval's width stays
    # that of the estimate's error (here against the ungrouped bootstrap of fewer rows,
    # scaled by sqrt(n)).
    n = 4 * GROUPS
    big = sobol_indices(*_saltelli(_ishigami, n, 3, 2, "random"), list("xyz"), 0.95, 0)
    small = sobol_indices(*_saltelli(_ishigami, GROUPS, 3, 2, "random"), list("xyz"), 0.95, 0)
    for k in big:
        w_big = big[k].total.high - big[k].total.low
        w_small = small[k].total.high - small[k].total.low
        assert 0.35 < w_big / w_small < 0.7, (k, w_big, w_small)


def test_no_row_left_is_a_value_error_naming_indices():
    nan = np.full(8, np.nan)
    with pytest.raises(ValueError, match="indices"):
        sobol_indices(nan, nan, nan[None, :], ["chi"], 0.95, 0)
    # invalid="count" with tolerances reaching far out of range: few rows of the design have
    # all d + 2 samples in range (the indices were 1.0 [1.0, 1.0] from a handful of rows)
    wide = {"chi": 0.3, "km": 0.3, "alpha": 0.5}
    with pytest.raises(ValueError, match="indices: only"):
        eccjump.uncertainty(BODY, ALPHA, 1.0, sd=wide, n=256, invalid="count", indices=True)
    counted = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"chi": 0.02, "km": 0.01}, n=256,
                                  invalid="count", indices=True)  # fmt: skip
    assert 0.9 < counted.n_valid / counted.n < 1 and set(counted.indices) == {"chi", "km"}


def test_the_study_is_unchanged_and_the_bits_the_same_for_any_thread_count():
    kw = dict(sd=SD, n=1024, seed=2, sampling="sobol")
    plain = eccjump.uncertainty(BODY, ALPHA, 1.0, **kw)
    assert plain.indices is None
    one = eccjump.uncertainty(BODY, ALPHA, 1.0, indices=True, n_threads=1, **kw)
    two = eccjump.uncertainty(BODY, ALPHA, 1.0, indices=True, n_threads=2, **kw)
    assert one == two and one.indices == two.indices
    assert list(one.indices) == ["chi", "km", "alpha", "mu_s"]  # the cube's order
    # every other field the same bits as without indices
    assert one.p_jarm == plain.p_jarm and one.counts == plain.counts
    for k, v in plain.outcomes.items():
        assert v.tobytes() == one.outcomes[k].tobytes(), k
    for k, v in plain.samples.items():
        assert v.tobytes() == one.samples[k].tobytes(), k


def test_indices_on_eccjump():
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, sd=SD, n=4096, seed=3, indices=True)
    assert 0.6 < u.p_jarm < 0.95
    for name, ix in u.indices.items():
        assert ix.first.low <= ix.total.high, name  # first <= total, within the intervals
        assert ix.first.low <= ix.first.value <= ix.first.high
        assert 0 <= ix.total.low <= ix.total.value <= ix.total.high <= 1.05
    # chi's tolerance matters most here: its total index is far above the others'
    totals = {k: v.total.value for k, v in u.indices.items()}
    assert max(totals, key=totals.get) == "chi"


def test_a_fixed_parameter_has_no_index_and_one_that_hardly_changes_the_verdict_has_zero():
    # mu_s = 3 +- 0.01 is above every friction ratio on the path but those of the few samples
    # whose normal force at the jump is near 0 (the ratio grows without bound there): it
    # decides ~0.1 % of the verdicts. km's sd of 0 fixes it.
    sd = {"alpha": math.radians(2), "chi": 0.02, "km": 0.0, "mu_s": 0.01}
    u = eccjump.uncertainty(BODY, ALPHA, 3.0, sd=sd, n=2048, seed=4, indices=True)
    assert list(u.indices) == ["chi", "alpha", "mu_s"]
    mu = u.indices["mu_s"]
    assert 0 <= mu.total.value < 0.01 and mu.total.high < 0.02
    assert mu.first.low <= 0.0 <= mu.first.high and abs(mu.first.value) < 0.05
    assert u.indices["chi"].total.value > 0.5


def test_nothing_varied_and_a_constant_verdict_give_no_or_zero_indices():
    none = eccjump.uncertainty(BODY, ALPHA, 1.0, n=16, indices=True)
    assert none.indices == {}
    sure = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"alpha": 1e-4}, n=64, indices=True)
    assert sure.p_jarm == 1.0 and sure.indices["alpha"].total == (0.0, 0.0, 0.0)


def test_scipy_sobol_indices_agree_within_the_statistical_error():
    # scipy draws its own samples (independent normals: km held fixed, chi and alpha far from
    # their ranges' ends, so no truncation binds) and estimates the first order by
    # Saltelli 2010, the total by Jansen: the same limits, compared within 4 combined
    # standard errors (each from its 95 % bootstrap interval, as wide as 2 x 1.96 of them).
    sd = {"alpha": math.radians(2), "chi": 0.02, "mu_s": 0.15}
    n = 4096
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, sd=sd, n=n, seed=5, indices=True)
    names = ["chi", "alpha", "mu_s"]  # the cube's order
    nominal = {"chi": BODY.chi, "alpha": ALPHA, "mu_s": 1.0}
    dists = [scipy_stats.norm(nominal[k], sd[k]) for k in names]

    def f(x):
        return np.asarray(eccjump.jarm(x[1], x[0], BODY.km, x[2]).is_jarm, dtype=float)[None]

    # scipy names its generator rng from 1.15, random_state before (the minimum is 1.13)
    gen = np.random.default_rng(9)
    takes_rng = "rng" in inspect.signature(scipy_stats.sobol_indices).parameters
    seeding = {"rng": gen} if takes_rng else {"random_state": gen}
    ref = scipy_stats.sobol_indices(func=f, n=n, dists=dists, **seeding)
    ci = ref.bootstrap(confidence_level=0.95, n_resamples=300)
    for i, name in enumerate(names):
        ours = u.indices[name]
        for est, value, interval in (
            (ours.first, ref.first_order[i], ci.first_order.confidence_interval),
            (ours.total, ref.total_order[i], ci.total_order.confidence_interval),
        ):
            se_ref = (interval.high[i] - interval.low[i]) / (2 * 1.96)
            se_ours = (est.high - est.low) / (2 * 1.96)
            assert abs(est.value - value) < 4 * math.hypot(se_ref, se_ours), (name, est, value)


def test_the_design_maps_ab_columns_as_the_study_maps_its_own():
    # AB_i takes column i from B and every other from A: where i is alpha, chi's values
    # are the study's own, row by row.
    spec = spread({"chi": 0.15, "km": 0.02, "alpha": ALPHA, "mu_s": 1.0, "mu_k": 1.0,
                   "restitution": 0.0, "theta0": 0.0, "omega0": 0.0},
                  {"chi": 0.02, "alpha": 0.03}, None, ("chi", "km", "alpha", "mu_s"))  # fmt: skip
    study = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"chi": 0.02, "alpha": 0.03}, n=32)
    extra = design(spec, 32, 0, "random", "truncate", np.ones(32, dtype=bool))
    assert extra is not None
    cols, valid = extra
    assert cols["chi"].size == 3 * 32 and valid.all()
    ab_alpha = slice(2 * 32, 3 * 32)  # B, AB_chi, AB_alpha
    assert cols["chi"][ab_alpha].tobytes() == study.samples["chi"].tobytes()
    assert cols["alpha"][ab_alpha].tobytes() == cols["alpha"][:32].tobytes()  # from B


def test_a_parameter_that_cannot_change_the_verdict_has_zero_indices():
    # The restitution acts at the first landing, after the lift-off that makes a JARM: it
    # cannot make or unmake one. f(A) == f(AB_restitution) on every row: the total is
    # exactly 0; the first order is 0 within its interval.
    sd = {"chi": 0.02, "restitution": 0.2}
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, sd=sd, n=256, question="motion", indices=True,
                            t_max=10.0)  # fmt: skip
    assert list(u.indices) == ["chi", "restitution"] and 0.05 < u.p_jarm < 0.95
    e = u.indices["restitution"]
    assert e.total == (0.0, 0.0, 0.0)
    assert e.first.low <= 0.0 <= e.first.high
    assert u.indices["chi"].total.value > 0.5


def test_a_bad_indices_is_a_type_error_naming_it():
    with pytest.raises(TypeError, match="indices"):
        eccjump.uncertainty(BODY, ALPHA, 1.0, sd=SD, n=8, indices="yes")


def test_files_and_dict_carry_the_indices(tmp_path):
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"chi": 0.02, "alpha": 0.03}, n=128,
                            indices=True)  # fmt: skip
    d = json.loads(json.dumps(u.to_dict(), allow_nan=False))
    assert d["liftoff_indices"] is None
    assert d["indices"]["chi"]["total"] == list(u.indices["chi"].total)
    u.save(tmp_path / "u.csv")
    assert eccjump.load(tmp_path / "u.csv") == u
    assert "Sobol" in u._repr_html_()
    plain = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"chi": 0.02}, n=16)
    plain.save(tmp_path / "plain.csv")
    assert eccjump.load(tmp_path / "plain.csv").indices is None
    pytest.importorskip("xarray")
    assert json.loads(u.to_xarray().attrs["indices"]) == d["indices"]
    u.save(tmp_path / "u.nc")
    assert eccjump.load(tmp_path / "u.nc") == u


def test_plot_shows_the_indices():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, sd=SD, n=256, indices=True)
    fig = u.plot()
    shown = [ax for ax in fig.axes if ax.get_visible()]
    assert len(shown) == 4 and "tolerance" in shown[-1].get_title()


def test_command_line_prints_the_table(capsys):
    argv = ["uncertainty", *JARM_ARGS, "--mu-s", "1", "--sd", "alpha", "2", "--sd", "chi",
            "0.02", "-n", "256", "-q", "--indices"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    direct = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"alpha": math.radians(2), "chi": 0.02},
                                 n=256, indices=True)  # fmt: skip
    assert "Sobol' indices" in out and "1024 runs" in out
    chi = direct.indices["chi"].total
    assert f"{chi.value:8.3f} [{chi.low:6.3f}, {chi.high:6.3f}]" in out
    assert main([*argv, "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["indices"]["chi"]["total"] == list(chi)
    assert main(argv[:-1]) == 0 and "Sobol" not in capsys.readouterr().out
    motion = [*argv, "--question", "motion", "--t-max", "10", "-n", "16"]
    assert main(motion) == 0 and "indices of the lift-off time" in capsys.readouterr().out


def test_liftoff_time_indices_are_the_shares_of_its_exact_first_order_variance(tmp_path):
    # Small tolerances: the lift-off time is linear in them, t = t0 + sum g_i dx_i, so its
    # first-order and total indices are both g_i^2 var_i / sum_j g_j^2 var_j, g from the
    # exact sensitivities of one simulate (no sampling).
    from eccjump.motion.simulation import SENSITIVITY_PARAMETERS

    sd = {"chi": 0.001, "alpha": math.radians(0.1), "theta0": 0.002}
    kw = {"mu_k": 0.9, "restitution": 0.3}
    u = eccjump.uncertainty(BODY, ALPHA, 1.0, **kw, sd=sd, n=1024, seed=6, question="motion",
                            t_max=20.0, indices=True)  # fmt: skip
    run = eccjump.simulate(BODY, ALPHA, mu_s=1.0, **kw, sensitivities=True, max_transitions=3)
    lift = next(i for i, t in enumerate(run.transitions) if t.to_mode == "FLIGHT")
    g = run.d_transitions[lift, 0]
    terms = {k: (g[SENSITIVITY_PARAMETERS.index(k)] * s) ** 2 for k, s in sd.items()}
    assert u.liftoff_indices is not None and list(u.liftoff_indices) == list(terms)
    for name, ix in u.liftoff_indices.items():
        share = terms[name] / sum(terms.values())
        for est in ix:
            slack = 0.25 * (est.high - est.low)
            assert est.low - slack <= share <= est.high + slack, (name, est, share)
    assert u.liftoff_indices["alpha"].total.low > 0.6  # a test that could fail
    # every sample jumps: P(JARM) does not vary and no tolerance matters for it
    assert u.p_jarm == 1.0 and all(ix.total.value == 0.0 for ix in u.indices.values())
    jarm_only = eccjump.uncertainty(BODY, ALPHA, 1.0, sd={"chi": 0.01}, n=8, indices=True)
    assert jarm_only.liftoff_indices is None
    u.save(tmp_path / "m.csv")
    assert eccjump.load(tmp_path / "m.csv").liftoff_indices == u.liftoff_indices
