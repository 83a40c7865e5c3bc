"""eccjump.uncertainty_map (P(JARM) under tolerances over a region grid) and
uncertainty(..., chunks=): an independent Monte Carlo loop over ``jarm`` with the same unit-cube
points, common random numbers, the same bits for any chunking and scheduler, the files, the
picture, bad input and the command line."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_points import JARM_ALPHA, JARM_BODY

import eccjump
from eccjump.cli import main
from eccjump.studies.uncertainty.sampling import unit_cube

stats = pytest.importorskip("scipy.stats")

ALPHA = np.radians([39.0, 40.0, 41.0])
CHI = np.array([0.14, 0.15])
KM_FRAC = np.array([JARM_BODY[1] / (1 - JARM_BODY[0]), 0.05])
#: Tolerances wide enough that P(JARM) lies inside (0, 1) on the grid.
SD = {"alpha": math.radians(0.5), "chi": 0.01}
BOUNDS = {"mu_s": (-0.1, 0.05)}
N = 400


@pytest.fixture(scope="module")
def umap() -> eccjump.UncertaintyMap:
    return eccjump.uncertainty_map(ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N, seed=7)


def test_plain_monte_carlo_loop_over_jarm_gives_the_map(umap):
    """The same unit-cube points mapped by scipy's inverse CDFs here, one ``jarm`` call per
    sample: the count of JARMs at three grid points is the map's, exactly."""
    cube = unit_cube(N, 3, 7, "random")  # columns: chi, alpha, mu_s (the cube's order)
    for i, j, k in [(1, 1, 0), (0, 0, 1), (2, 1, 1)]:
        chi0, alpha0 = CHI[j], ALPHA[i]
        km = KM_FRAC[k] * (1 - chi0)
        s = SD["chi"]
        chi = stats.truncnorm.ppf(cube[:, 0], -chi0 / s, (1 - chi0) / s, loc=chi0, scale=s)
        s = SD["alpha"]
        top = (math.pi / 2 - alpha0) / s
        alpha = stats.truncnorm.ppf(cube[:, 1], -alpha0 / s, top, loc=alpha0, scale=s)
        mu = 0.9 + cube[:, 2] * 0.15
        hits = valid = 0
        for a, c, m in zip(alpha, chi, mu, strict=True):
            if km > 1 - c:  # km held, chi moved: outside the physical range
                continue
            valid += 1
            hits += bool(eccjump.jarm(float(a), float(c), km, float(m)).is_jarm)
        assert 0 < hits < valid
        assert int(umap.n_valid[i, j, k]) == valid
        assert umap.p_jarm[i, j, k] == hits / valid
        lo, hi = eccjump.studies.uncertainty.wilson(hits, valid)
        assert (umap.p_jarm_low[i, j, k], umap.p_jarm_high[i, j, k]) == (lo, hi)


def test_a_grid_point_is_uncertainty_there(umap):
    """At a grid point the map holds what ``uncertainty`` gives (bounds as offsets)."""
    i, j, k = 1, 0, 1
    body = eccjump.Cylinder(CHI[j], KM_FRAC[k] * (1 - CHI[j]))
    u = eccjump.uncertainty(body, ALPHA[i], 1.0, sd=SD, bounds={"mu_s": (0.9, 1.05)}, n=N, seed=7)
    assert umap.p_jarm[i, j, k] == u.p_jarm
    assert (umap.p_jarm_low[i, j, k], umap.p_jarm_high[i, j, k]) == u.p_jarm_ci
    for name, count in u.counts.items():
        if name != "JARM":
            assert umap.fields[f"p_{name.lower()}"][i, j, k] == count / u.n_valid
    shares = sum(v for f, v in umap.fields.items() if f.startswith("p_") and "jarm_" not in f)
    np.testing.assert_allclose(shares, 1.0, rtol=1e-12)


@settings(max_examples=8, deadline=None)
@given(
    st.lists(st.integers(0, 2), min_size=1, max_size=3, unique=True),
    st.lists(st.integers(0, 1), min_size=1, max_size=2, unique=True),
    st.sampled_from(["random", "sobol"]),
)
def test_common_random_numbers_a_point_ignores_the_rest_of_the_grid(ia, ic, sampling):
    kw = {"sd": SD, "bounds": BOUNDS, "n": 64, "seed": 3, "sampling": sampling}
    full = eccjump.uncertainty_map(ALPHA, CHI, KM_FRAC, 1.0, **kw)
    ia, ic = sorted(ia), sorted(ic)
    part = eccjump.uncertainty_map(ALPHA[ia], CHI[ic], KM_FRAC[1:], 1.0, **kw)
    for name, values in part.fields.items():
        want = full.fields[name][np.ix_(ia, ic, [1])]
        assert values.tobytes() == want.tobytes(), name


def test_blocks_of_samples_change_no_bit(monkeypatch, umap):
    """One grid point's samples split over several core calls: the same counts."""
    from eccjump.studies.uncertainty import grid

    monkeypatch.setattr(grid, "BLOCK", 150)  # fewer than n: a point in three parts
    again = eccjump.uncertainty_map(ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N, seed=7)
    assert again == umap


@pytest.mark.parametrize("chunks", [1, (2, 1, -1), {"chi": 1}])
def test_chunks_bit_identical(umap, chunks):
    pytest.importorskip("dask.array")
    lazy = eccjump.uncertainty_map(
        ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N, seed=7, chunks=chunks, n_threads=1
    )
    assert lazy.lazy and "lazy" in repr(lazy)
    assert lazy.compute(scheduler="threads") == umap
    assert lazy.compute(scheduler="sync") == umap


def test_uncertainty_chunks_bit_identical():
    pytest.importorskip("dask")
    body = eccjump.Cylinder(*JARM_BODY)
    kw = {"sd": {"alpha": math.radians(2), "chi": 0.02}, "n": 3000, "seed": 5}
    here = eccjump.uncertainty(body, math.radians(40), 1.0, **kw)
    assert 0 < here.p_jarm < 1
    for chunks, scheduler in [(1000, "threads"), (777, "sync"), (3000, "processes")]:
        import dask

        with dask.config.set(scheduler=scheduler):
            there = eccjump.uncertainty(body, math.radians(40), 1.0, chunks=chunks, **kw)
        assert there == here
    with pytest.raises(ValueError, match="chunks"):
        eccjump.uncertainty(body, 0.7, 1.0, chunks=0, **kw)
    with pytest.raises(ValueError, match="progress"):
        eccjump.uncertainty(body, 0.7, 1.0, chunks=10, progress=True, **kw)


@pytest.mark.parametrize("suffix", [".npz", ".nc"])
def test_saved_and_loaded(umap, tmp_path, suffix):
    if suffix == ".nc":
        pytest.importorskip("xarray")
    path = umap.save(tmp_path / f"u{suffix}")
    back = eccjump.load(path)
    assert isinstance(back, eccjump.UncertaintyMap) and back == umap
    assert eccjump.maps.load(path) == umap
    if suffix == ".nc":
        ds = umap.to_xarray()
        assert (
            ds["p_jarm"].dims == ("alpha", "chi", "km_frac") and ds.attrs["kind"] == "uncertainty"
        )


def test_a_damaged_map_is_refused(umap, tmp_path):
    """The kind's own rule: P(JARM) lies in its interval (no writer writes what a loader
    refuses: the check of both)."""
    lay = umap.to_layout()
    dims, p, attrs = lay["data_vars"]["p_jarm_low"]
    bad = p.copy()
    bad[0, 0, 0] = 1.0  # above p_jarm
    lay["data_vars"]["p_jarm_low"] = (dims, bad, attrs)
    with pytest.raises(ValueError, match="p_jarm"):
        eccjump.maps.save(lay, tmp_path / "bad.npz")


def test_a_grid_point_out_of_range_has_no_valid_sample(tmp_path):
    """A ramp angle past pi/2 is an invalid point, as in a region (its samples, truncated to
    the range, would be those of a point inside); the map is saved and read back."""
    with pytest.warns(UserWarning, match="alpha"):
        m = eccjump.uncertainty_map([0.7, 2.0], [0.15], [0.1], 1.0, sd={"alpha": 0.3}, n=50)
    assert m.n_valid.ravel().tolist() == [50, 0]
    assert np.isnan(m.p_jarm[1]).all() and np.isnan(m.p_jarm_low[1]).all()
    assert eccjump.load(m.save(tmp_path / "m.npz")) == m


def test_plot_draws_the_contours(umap):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    fig = umap.plot(km_index=0)
    ax = fig.axes[0]
    assert "P(JARM)" in ax.get_title() and ax.collections
    with pytest.raises(ValueError, match="km_index"):
        umap.plot(km_index=5)


def test_plot_composes_into_the_callers_axes_and_figure(umap):
    """The plots' convention (issue 49): ``ax=`` draws the panel into the given Axes and
    returns them, ``fig=`` the figure into the given empty Figure; a wrong ax is a
    TypeError naming it."""
    plt = pytest.importorskip("matplotlib.pyplot")
    _, (left, right) = plt.subplots(1, 2)
    assert umap.plot(ax=right) is right and right.collections and not left.collections
    assert "P(JARM)" in right.get_title()
    empty = plt.figure()
    assert umap.plot(fig=empty) is empty and empty.axes
    with pytest.raises(TypeError, match=r"^ax must be"):
        umap.plot(ax="left")
    plt.close("all")


@pytest.mark.parametrize(
    ("kwargs", "error", "name"),
    [
        ({"question": "flight"}, ValueError, "question"),
        ({"method": "taylor"}, ValueError, "method"),
        ({"method": "delta", "question": "motion"}, ValueError, "method"),
        ({"method": 2}, TypeError, "method"),
        ({"question": "motion", "sd": {"restitution": 0.1}}, ValueError, "restitution"),
        ({"sd": {"restitution": 0.1}}, ValueError, "restitution"),
        ({"sd": {"alpha": -1.0}}, ValueError, "sd"),
        ({"km": 0.1}, TypeError, "km"),
        ({"n": 0}, ValueError, "n"),
        ({"chi": [0.1, 1.5]}, ValueError, "chi"),
        ({"mu_s": -1.0}, ValueError, "mu_s"),
        ({"rule": "other"}, ValueError, "rule"),
        ({"chunks": 1, "progress": True}, ValueError, "progress"),
        ({"progress": 3}, TypeError, "progress"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, error, name):
    kw = {"alpha": ALPHA, "chi": CHI, "km_frac": KM_FRAC, "mu_s": 1.0, "sd": SD, "n": 8, **kwargs}
    with pytest.raises(error, match=name) as err:
        eccjump.uncertainty_map(**kw)
    assert len(str(err.value)) < 200


@pytest.mark.parametrize("question", ["jarm", "motion"])
def test_absurd_request_is_a_memory_error(question):
    axis = np.linspace(0.0, 1.0, 2000)
    with pytest.raises(MemoryError, match="uncertainty_map"):
        eccjump.uncertainty_map(
            np.radians(axis * 90), axis, axis, 1.0, sd=SD, n=10**8, question=question
        )


def test_command_line_writes_the_map(tmp_path, capsys):
    out = tmp_path / "u.npz"
    argv = ["map", "--kind", "uncertainty", "--mu-s", "1", "--sd", "alpha=0.5,chi=0.01",
            "--samples", str(N), "--seed", "7", "--alpha-min", "39", "--alpha-max", "41",
            "--n-alpha", "3", "--chi-min", "0.14", "--chi-max", "0.15", "--n-chi", "2",
            "--km-frac-min", str(KM_FRAC[0]), "--km-frac-max", "0.05", "--n-km-frac", "2",
            "-q", "-o", str(out)]  # fmt: skip
    pytest.importorskip("matplotlib")
    assert main([*argv, "--figure", str(tmp_path / "u.png")]) == 0
    assert (tmp_path / "u.png").stat().st_size > 0
    back = eccjump.load(out)
    want = eccjump.uncertainty_map(back.alpha, back.chi, back.km_frac, 1.0, sd=SD, n=N, seed=7)
    assert back == want
    assert "P(JARM)" in capsys.readouterr().out
    assert main([*argv[:-2], "-o", str(tmp_path / "x.npz"), "--route", "ode"]) == 2


def test_local_cluster_of_two_processes_bit_identical(umap, monkeypatch):
    """The tutorial's LocalCluster: both chunked calls on two worker processes."""
    distributed = pytest.importorskip("distributed")
    from pathlib import Path

    # Worker processes must import this eccjump (e.g. from a source tree on PYTHONPATH).
    monkeypatch.setenv("PYTHONPATH", str(Path(eccjump.__file__).parents[1]))
    body = eccjump.Cylinder(*JARM_BODY)
    here = eccjump.uncertainty(body, math.radians(40), 1.0, sd=SD, n=2000, seed=2)
    with (
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        lazy = eccjump.uncertainty_map(
            ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N, seed=7, chunks=(1, 1, -1),
            n_threads=1,
        )  # fmt: skip
        assert lazy.compute() == umap  # the client is the default scheduler
        there = eccjump.uncertainty(body, math.radians(40), 1.0, sd=SD, n=2000, seed=2, chunks=300)
        assert there == here
        assert len(client.scheduler_info()["workers"]) == 2


# --------------------------------------------------------------------------------------------
# question="motion": the full motion's first flight at every grid point
# --------------------------------------------------------------------------------------------

N_MOTION = 96


@pytest.fixture(scope="module")
def mmap() -> eccjump.UncertaintyMap:
    return eccjump.uncertainty_map(
        ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N_MOTION, seed=5, question="motion"
    )


@pytest.mark.parametrize(("i", "j", "k"), [(0, 1, 0), (2, 0, 1)])
def test_motion_grid_point_is_uncertainty_motion_there(mmap, i, j, k):
    """At a grid point the motion map holds what ``uncertainty(question="motion")`` gives
    with the same samples: P(JARM) of the full motion, its interval, the shares that fly
    and slip first, and the quantiles of the first flight, to the bit."""
    body = eccjump.Cylinder(CHI[j], KM_FRAC[k] * (1 - CHI[j]))
    u = eccjump.uncertainty(
        body, ALPHA[i], 1.0, sd=SD, bounds={"mu_s": (0.9, 1.05)}, n=N_MOTION, seed=5,
        question="motion",
    )  # fmt: skip
    at = {name: v[i, j, k] for name, v in mmap.fields.items()}
    assert (at["n_valid"], at["p_jarm"]) == (u.n_valid, u.p_jarm)
    assert (at["p_jarm_low"], at["p_jarm_high"]) == u.p_jarm_ci
    flies = np.isfinite(u.outcomes["liftoff_t"][u.valid]).sum()
    assert at["p_flies"] == flies / u.n_valid > 0
    assert at["p_slipped_first"] == u.outcomes["slipped_first"][u.valid].sum() / u.n_valid
    for q in ("liftoff_t", "flight_time", "distance"):
        s = u.distributions[q]
        assert (at[f"{q}_median"], at[f"{q}_q025"], at[f"{q}_q975"]) == (s.median, s.q025, s.q975)
    assert 0 < at["liftoff_t_q025"] <= at["liftoff_t_median"] <= at["liftoff_t_q975"]


def test_motion_map_files_chunks_and_picture(mmap, tmp_path):
    """A motion map is saved and loaded as its own kind, chunked by dask to the same bits,
    and drawn as every uncertainty map."""
    assert isinstance(mmap, eccjump.UncertaintyMotionMap) and mmap.question == "motion"
    assert "UncertaintyMotionMap(3 x 2 x 2 grid" in repr(mmap)
    back = eccjump.load(mmap.save(tmp_path / "m.npz"))
    assert isinstance(back, eccjump.UncertaintyMotionMap) and back == mmap
    assert back.attrs()["kind"] == "uncertainty_motion"
    pytest.importorskip("dask")
    lazy = eccjump.uncertainty_map(
        ALPHA, CHI, KM_FRAC, 1.0, sd=SD, bounds=BOUNDS, n=N_MOTION, seed=5, question="motion",
        chunks=(2, 1, 1),
    )  # fmt: skip
    assert lazy.lazy and lazy.compute() == mmap
    pytest.importorskip("matplotlib")
    assert mmap.plot().axes


# --------------------------------------------------------------------------------------------
# method="delta": the first-order P(JARM) over the grid, from the exact derivatives
# --------------------------------------------------------------------------------------------

#: Small tolerances: the verdict is the sign of a smooth margin (tests/test_uncertainty.py).
SMALL = {"alpha": math.radians(0.3), "chi": 0.002, "km": 0.001, "mu_s": 0.005}


def test_delta_map_agrees_with_sampling_away_from_the_boundary():
    """mu_s a little above the friction the JARM point's jump needs, small tolerances: on a
    grid around it P(JARM) runs from 0.2 to 0.87; where the first order gives it (the nominal
    point a JARM), it is the sampled map's within its interval and the curvature's 0.02, and
    at a grid point it is ``uncertainty``'s delta there, to the bit."""
    alpha = JARM_ALPHA + np.radians([-0.3, 0.0, 0.3])
    chi = JARM_BODY[0] + np.array([-0.002, 0.0, 0.002])
    frac = np.array([JARM_BODY[1] / (1 - JARM_BODY[0])])
    r = eccjump.jarm(JARM_ALPHA, *JARM_BODY, 1.0)
    mu = float(-r.Fx_J / r.Fy_J) + 0.004
    first = eccjump.uncertainty_map(alpha, chi, frac, mu, sd=SMALL, method="delta")
    assert isinstance(first, eccjump.UncertaintyDeltaMap) and first.n == 0
    sampled = eccjump.uncertainty_map(alpha, chi, frac, mu, sd=SMALL, n=20_000, seed=3)
    given = first.delta_status == 0
    assert given.sum() == 6 and np.isnan(first.p_jarm[~given]).all()
    p = first.p_jarm[given]
    lo, hi = sampled.p_jarm_low[given], sampled.p_jarm_high[given]
    assert ((lo - 0.02 <= p) & (p <= hi + 0.02)).all(), (p, sampled.p_jarm[given])
    assert np.ptp(sampled.p_jarm[given]) > 0.3  # the check spans the transition
    # Where the nominal point is no JARM (a verdict change) sampling still finds JARMs.
    assert (first.delta_status[~given] == 1).all()
    assert ((sampled.p_jarm[~given] > 0.1) & (sampled.p_jarm[~given] < 0.5)).all()
    body = eccjump.Cylinder(JARM_BODY[0], JARM_BODY[1])
    u = eccjump.uncertainty(body, alpha[1], mu, sd=SMALL, n=8)
    assert u.delta is not None and u.delta.p_jarm == first.p_jarm[1, 1, 0]
    assert u.delta.theta_J_sd == first.theta_J_sd[1, 1, 0]


def test_delta_map_says_where_it_fails():
    """NaN and a status where the linearisation fails at the nominal point: a kink (an
    earlier friction ratio decides: chi 0.15, k_m 0.005 at 40 deg), k_m = 0 (one-sided
    derivatives) under a tolerance on k_m, a point outside the physical range, a nominal
    point that is no JARM (a verdict change), the classical rule."""
    from eccjump.studies.uncertainty.delta import Status

    frac = [0.0, 0.005 / 0.85, JARM_BODY[1] / 0.85]
    with pytest.warns(UserWarning, match="alpha"):
        m = eccjump.uncertainty_map([JARM_ALPHA, 1.6], [0.15], frac, 1.0, sd=SMALL, method="delta")
    want = [[Status.SINGULAR, Status.KINK, Status.ESTIMATE], [Status.INVALID] * 3]
    assert m.delta_status[:, 0, :].tolist() == want
    assert np.isnan(m.p_jarm[m.delta_status != 0]).all() and m.p_jarm[0, 0, 2] > 0.99
    assert np.isfinite(m.theta_J_sd[0, 0, 1:]).all()  # the lift-off's spread is still given
    for mu_s, rule, status in [(0.05, "paper", Status.NO_JARM), (1.0, "normal_force", 4)]:
        one = eccjump.uncertainty_map([JARM_ALPHA], [0.15], frac[2:], mu_s, sd=SMALL,
                                      method="delta", rule=rule)  # fmt: skip
        assert one.delta_status.item() == status and np.isnan(one.p_jarm.item())


def test_delta_map_flags_a_kink_the_tolerances_reach():
    """The lab's tolerances at the JARM point reach samples that slip before the jump (an
    earlier friction ratio: a kink the margin cannot see): the first order says 0.997,
    sampling 0.79 (tests/test_uncertainty.py). The map gives the value, flagged REACHES,
    because a probe at 2 sd along an input slips before the jump; with small tolerances the
    same point is an ESTIMATE."""
    lab = {"alpha": math.radians(2), "chi": 0.02, "km": 0.01, "mu_s": 0.15}
    frac = [JARM_BODY[1] / (1 - JARM_BODY[0])]
    wide = eccjump.uncertainty_map([JARM_ALPHA], [JARM_BODY[0]], frac, 1.0, sd=lab,
                                   method="delta")  # fmt: skip
    sampled = eccjump.uncertainty_map([JARM_ALPHA], [JARM_BODY[0]], frac, 1.0, sd=lab, n=4000)
    assert wide.delta_status.item() == 6 and wide.p_jarm.item() - sampled.p_jarm.item() > 0.15
    small = eccjump.uncertainty_map([JARM_ALPHA], [JARM_BODY[0]], frac, 1.0, sd=SMALL,
                                    method="delta")  # fmt: skip
    assert small.delta_status.item() == 0


def test_delta_map_files_chunks_and_repr(tmp_path):
    kw = {"sd": SMALL, "method": "delta"}
    m = eccjump.uncertainty_map(ALPHA, CHI, KM_FRAC, 1.0, **kw)
    assert "first order (delta method)" in repr(m)
    back = eccjump.load(m.save(tmp_path / "d.nc"))
    assert isinstance(back, eccjump.UncertaintyDeltaMap) and back == m
    pytest.importorskip("dask")
    assert eccjump.uncertainty_map(ALPHA, CHI, KM_FRAC, 1.0, chunks=(1, 2, 1), **kw).compute() == m
