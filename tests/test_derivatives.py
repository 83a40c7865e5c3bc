"""The exact derivatives of ``jarm(..., derivatives=True)`` with respect to (alpha, chi, km):

(a) against sympy: the lift-off function, the forces and the implicit derivatives built and
    differentiated symbolically, evaluated at the core's theta_J (~1e-12);
(b) against an independent route: theta_J as the root of the lift-off function in mpmath at
    50 digits, central differences with step 1e-8 (1e-7, the issue's bar);
(c) a hypothesis property over jumping points: central differences of the classification
    itself, and the ODE route's derivatives;
(d) the flagged non-differentiable case: a double root of the lift-off function.

Both lift-off rules; under the classical rule theta_J is where the friction cone is reached
(mu_s Fy - |Fx| = 0, sliding inconsistent), or where Fy = 0.
"""

from __future__ import annotations

import functools
import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from properties import reach_rate
from reference_points import JARM_ALPHA, JARM_BODY

import eccjump
from eccjump import _core
from eccjump.classification.fields import DERIVATIVES

FIELDS = ("d_theta_J", "d_Fx_J", "d_Fy_J", "d_mu_J")
RULES = ("paper", "normal_force")


@functools.cache
def pool(rule: str, mu_s: float = 1.0) -> tuple[tuple[float, float, float], ...]:
    """JARM points (alpha, chi, km) of a coarse map, every 7th."""
    m = eccjump.region(
        np.radians(np.linspace(2, 88, 44)),
        np.linspace(0.03, 0.95, 24),
        np.linspace(0, 0.95, 20),
        mu_s,
        rule=rule,
    )
    a, c, f = np.meshgrid(m.alpha, m.chi, m.km_frac, indexing="ij")
    j = m.is_jarm
    pts = zip(a[j], c[j], (f * (1 - c))[j], strict=True)
    return tuple((float(x), float(y), float(z)) for x, y, z in pts)[::7]


def some(rule: str, k: int) -> list[tuple[float, float, float]]:
    """k points of the pool, spread over it; half with km > 0 (under the classical rule most
    jumps have km = 0, where Fx and Fy vanish together)."""
    p = pool(rule)
    inner = [q for q in p if q[2] > 0]
    pick = [inner[i] for i in np.linspace(0, len(inner) - 1, k // 2).astype(int)]
    return pick + [p[i] for i in np.linspace(0, len(p) - 1, k - k // 2).astype(int)]


def vanishing(rule: str, km: float, fy_j: float) -> str:
    """What vanishes at theta_J: the lift-off function (paper), else the friction margin, or
    Fy where km = 0 and Fy_J = 0 (the contact force then points at the centre of mass, and
    both forces vanish together; where Fy_J > 0 the cone decided, km = 0 or not)."""
    if rule == "paper":
        return "lift"
    return "fy" if km == 0 and abs(fy_j) < 1e-9 else "margin"


def km_columns(km: float) -> list[int]:
    """The columns (alpha, chi, km) with a two-sided derivative: at km = 0 the km column is
    one-sided (km < 0 is no body) and NaN."""
    return [0, 1] if km == 0 else [0, 1, 2]


def test_the_pools_hold_enough_jumps():
    assert len(pool("paper")) > 30 and len(pool("normal_force")) > 30


# --- (a) sympy -------------------------------------------------------------------------------


@functools.cache
def symbolic(root: str):
    """The derivatives of theta_J, Fx_J, Fy_J, mu_J as mpmath functions of (theta, alpha,
    chi, km, theta0, omega0, mu_s, sigma), built with sympy from the physics notes."""
    th, a, x, k, t0, w0, mu, sig = sp.symbols("theta alpha chi km theta0 omega0 mu_s sigma")
    ic = k + x**2 / (1 - k)
    ip = ic + 1 + 2 * x * sp.cos(th)
    k0 = (ic + 1 + 2 * x * sp.cos(t0)) * w0**2 / 2
    w2 = 2 * (k0 + (th - t0) * sp.sin(a) + x * (sp.cos(a + t0) - sp.cos(a + th))) / ip
    thdd = (x * w2 * sp.sin(th) + x * sp.sin(a + th) + sp.sin(a)) / ip
    lift = x * w2 * sp.cos(th) - sp.cos(a)
    fx = -sp.sin(a) - x * w2 * sp.sin(th) + (1 + x * sp.cos(th)) * thdd
    fy = sp.cos(a) - x * w2 * sp.cos(th) - x * thdd * sp.sin(th)
    g = {"lift": lift, "fy": fy, "margin": mu * fy - sig * fx}[root]
    params = (a, x, k)
    # d/dtheta of g is along rolling: w2 depends on theta explicitly.
    dth = [-sp.diff(g, p) / sp.diff(g, th) for p in params]
    dfx = [sp.diff(fx, th) * d + sp.diff(fx, p) for d, p in zip(dth, params, strict=True)]
    dfy = [sp.diff(fy, th) * d + sp.diff(fy, p) for d, p in zip(dth, params, strict=True)]
    dmu = [-(u * fy - fx * v) / fy**2 for u, v in zip(dfx, dfy, strict=True)]
    if root == "fy":  # mu_J = -Fx_J/Fy_J is 0/0 there: the core gives NaN
        dmu = [sp.nan] * 3
    args = (th, a, x, k, t0, w0, mu, sig)
    return [sp.lambdify(args, e, "mpmath") for e in (dth, dfx, dfy, dmu, fx)]


def sympy_values(rule, point, theta_j, fy_j, mu_s=1.0, start=(0.0, 0.0)):
    with mpmath.workdps(30):
        *derivs, fx = symbolic(vanishing(rule, point[2], fy_j))
        args = [mpmath.mpf(v) for v in (theta_j, *point, *start, mu_s)]
        sigma = mpmath.sign(fx(*args, 1))
        out = [np.array([float(v) for v in f(*args, sigma)]) for f in derivs]
    for row in out if point[2] == 0 else ():
        row[2] = np.nan
    return out


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("start", [(0.0, 0.0), (-0.2, 0.1)])
def test_agree_with_sympy(rule, start):
    checked = 0
    for point in some(rule, 12):
        r = eccjump.jarm(*point, 1.0, rule=rule, theta0=start[0], omega0=start[1], derivatives=True)
        if not r.is_jarm:  # from the moving start some pool points no longer jump
            continue
        checked += 1
        expected = sympy_values(rule, point, float(r.theta_J), float(r.Fy_J), start=start)
        # The forces' total derivatives cancel terms |dtheta_J| times their size; mu_J's
        # combine them over Fy (and vanish on the classical friction root, mu_J = mu_s).
        cancel = 1.0 + np.nanmax(np.abs(expected[0]))
        fx, fy = float(r.Fx_J), float(r.Fy_J)
        size = [np.nanmax(np.abs(w)) if np.isfinite(w).any() else 0.0 for w in expected]
        if vanishing(rule, point[2], fy) != "fy":  # else mu_J's derivatives are NaN
            size[3] = max(size[3], (size[1] + abs(fx / fy) * size[2]) / abs(fy))
        for name, want, big in zip(FIELDS, expected, size, strict=True):
            got = getattr(r, name)
            tol = 1e-12 * cancel * big + 1e-14 * cancel  # exact zeros: Fy on its own root
            assert np.allclose(got, want, rtol=0, atol=tol, equal_nan=True), (
                f"{name} at {point}: {got} vs {want}"
            )
    assert checked >= 6


# --- (b) mpmath root and central differences -------------------------------------------------


def rolling(theta, alpha, chi, km, start):
    """theta'^2, L, Fx, Fy along pure rolling from ``start``, in mpmath (the physics notes)."""
    t0, w0 = start
    ic = km + chi**2 / (1 - km)
    ip = ic + 1 + 2 * chi * mpmath.cos(theta)
    k0 = (ic + 1 + 2 * chi * mpmath.cos(t0)) * w0**2 / 2
    gain = (theta - t0) * mpmath.sin(alpha) + chi * (
        mpmath.cos(alpha + t0) - mpmath.cos(alpha + theta)
    )
    w2 = 2 * (k0 + gain) / ip
    thdd = (chi * w2 * mpmath.sin(theta) + chi * mpmath.sin(alpha + theta) + mpmath.sin(alpha)) / ip
    lift = chi * w2 * mpmath.cos(theta) - mpmath.cos(alpha)
    fx = -mpmath.sin(alpha) - chi * w2 * mpmath.sin(theta) + (1 + chi * mpmath.cos(theta)) * thdd
    fy = mpmath.cos(alpha) - chi * w2 * mpmath.cos(theta) - chi * thdd * mpmath.sin(theta)
    return w2, lift, fx, fy


def jump_at(p, guess, root, mu_s, sigma, start):
    """(theta_J, Fx_J, Fy_J, mu_J) at parameters p, theta_J the root of ``root`` (see
    :func:`vanishing`) near ``guess``."""

    def g(theta):
        _, lift, fx, fy = rolling(theta, *p, start)
        return {"lift": lift, "fy": fy, "margin": mu_s * fy - sigma * fx}[root]

    theta = mpmath.findroot(g, mpmath.mpf(guess), tol=mpmath.mpf(10) ** -45)
    _, _, fx, fy = rolling(theta, *p, start)
    return [theta, fx, fy, -fx / fy]


def central_differences(point, theta_j, fy_j, rule, mu_s=1.0, start=(0.0, 0.0)):
    """Each field's derivatives (rows: theta_J, Fx, Fy, mu; columns: alpha, chi, km)."""
    with mpmath.workdps(50):
        p0 = [mpmath.mpf(v) for v in point]
        st = tuple(mpmath.mpf(v) for v in start)
        sigma = mpmath.sign(rolling(mpmath.mpf(theta_j), *p0, st)[2])
        h = mpmath.mpf("1e-8")
        root = vanishing(rule, point[2], fy_j)
        out = np.empty((4, 3))
        for i in range(3):
            up, down = list(p0), list(p0)
            up[i] += h
            down[i] -= h
            hi = jump_at(up, theta_j, root, mu_s, sigma, st)
            lo = jump_at(down, theta_j, root, mu_s, sigma, st)
            out[:, i] = [float((u - d) / (2 * h)) for u, d in zip(hi, lo, strict=True)]
        return out


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("method", ["closed_form", "ode"])
def test_agree_with_high_precision_central_differences(rule, method):
    start = (0.3, 0.2)
    checked = 0
    for point in some(rule, 5):
        r = eccjump.jarm(*point, 1.0, rule=rule, derivatives=True, method=method, rtol=1e-13,
                         atol=1e-15, theta0=start[0], omega0=start[1])  # fmt: skip
        if not r.is_jarm:
            continue
        checked += 1
        fd = central_differences(point, float(r.theta_J), float(r.Fy_J), rule, start=start)
        got = np.array([getattr(r, name) for name in FIELDS])
        if point[2] == 0:  # one-sided in km: NaN
            assert np.isnan(got[:, 2]).all()
        cols = km_columns(point[2])
        got, fd = got[:, cols], fd[:, cols]
        if vanishing(rule, point[2], float(r.Fy_J)) == "fy":  # mu_J = -Fx_J/Fy_J is 0/0: NaN
            assert np.isnan(got[3]).all()
            got, fd = got[:3], fd[:3]
        tol = 1e-7 * np.maximum(1.0, np.abs(fd))
        assert (np.abs(got - fd) <= tol).all(), f"{point}: {got} vs {fd}"
    assert checked >= 3


def test_the_paper_example_is_pinned():
    # alpha = 40 deg, chi = 0.15, km = 0.02 (the README's point): the values of (b).
    point = (JARM_ALPHA, *JARM_BODY)
    r = eccjump.jarm(*point, 1.0, derivatives=True)
    fd = central_differences(point, float(r.theta_J), float(r.Fy_J), "paper")
    assert np.allclose(r.d_theta_J, fd[0], rtol=1e-9)
    assert np.allclose(r.d_theta_J, [-3.58866512, -8.87374639, 1.38116331], rtol=1e-8)
    assert np.allclose(r.d_mu_J, fd[3], rtol=1e-9)


# --- (c) a property over jumping points ------------------------------------------------------

NEAR_JUMPS = st.tuples(
    st.sampled_from(RULES),
    st.integers(0, 10**6),
    st.tuples(*[st.floats(-1.0, 1.0)] * 3),
)


def near_jump(draw) -> tuple[str, tuple[float, float, float]]:
    """A pool point of the rule moved by up to 1e-3 of its values (inside the valid range)."""
    rule, i, (u, v, w) = draw
    p = pool(rule)
    a, c, k = p[i % len(p)]
    c = min(c * (1 + 1e-3 * v), 1.0)
    return rule, (a * (1 + 1e-3 * u), c, min(k * (1 + 1e-3 * w), 1 - c))


def jumps(draw) -> bool:
    rule, point = near_jump(draw)
    return bool(eccjump.jarm(*point, 1.0, rule=rule).is_jarm)


@settings(max_examples=40)
@given(NEAR_JUMPS)
def test_derivatives_are_the_slopes_of_the_classification(draw):
    rule, point = near_jump(draw)
    r = eccjump.jarm(*point, 1.0, rule=rule, derivatives=True)
    assume(r.is_jarm)
    assert not r.d_singular
    cols = km_columns(point[2])
    assert all(np.isfinite(getattr(r, name)[cols]).all() for name in FIELDS[:3])
    assert np.isnan(r.d_theta_J[2]) == (point[2] == 0)
    # mu_J = -Fx_J/Fy_J is 0/0 where both vanish (classical rule, km = 0): NaN there only.
    assert np.isfinite(r.d_mu_J[cols]).all() == (vanishing(rule, point[2], float(r.Fy_J)) != "fy")
    # Jumps many turns away are strongly curved in alpha (d3 theta_J up to ~1e12): central
    # differences at h and h/2, Richardson-extrapolated (error O(h^4)).
    h = 1e-7

    def difference(i: int, step: float) -> dict[str, float]:
        up, down = list(point), list(point)
        up[i] += step
        down[i] -= step
        hi, lo = (eccjump.jarm(*q, 1.0, rule=rule) for q in (up, down))
        assume(hi.is_jarm and lo.is_jarm and hi.n == lo.n == r.n)
        return {
            f: (float(getattr(hi, f)) - float(getattr(lo, f))) / (2 * step)
            for f in ("theta_J", "Fy_J")
        }

    for i in cols:
        coarse, fine = difference(i, h), difference(i, h / 2)
        for name, field in (("d_theta_J", "theta_J"), ("d_Fy_J", "Fy_J")):
            fd = (4 * fine[field] - coarse[field]) / 3
            exact = float(getattr(r, name)[i])
            assert abs(exact - fd) <= 1e-5 * max(1.0, abs(exact)), (name, i, exact, fd)
    ode = eccjump.jarm(*point, 1.0, rule=rule, derivatives=True, method="ode", rtol=1e-12)
    assert np.allclose(ode.d_theta_J, r.d_theta_J, rtol=1e-6, atol=1e-8, equal_nan=True)


def test_the_property_reaches_its_assertion():
    assert reach_rate(NEAR_JUMPS, jumps) >= 0.9


# --- (d) the non-differentiable case ---------------------------------------------------------


def double_root(chi: str, km: str, guess: tuple[float, float]) -> tuple[float, float]:
    """(alpha*, theta*) where the lift-off function from rest touches 0: L = dL/dtheta = 0."""
    with mpmath.workdps(50):
        c, k = mpmath.mpf(chi), mpmath.mpf(km)

        def lift(theta, alpha):
            return rolling(theta, alpha, c, k, (0, 0))[1]

        def slope(theta, alpha):
            return mpmath.diff(lambda t: lift(t, alpha), theta)

        theta, alpha = mpmath.findroot(
            lambda t, a: (lift(t, a), slope(t, a)), (mpmath.mpf(guess[1]), mpmath.mpf(guess[0]))
        )
        return float(alpha), float(theta)


def test_a_double_root_of_the_lift_off_function_is_flagged():
    # On the paper's body the maximum of L past 2 pi touches 0 near alpha = 34.9 deg.
    alpha, theta = double_root(*map(str, JARM_BODY), (math.radians(35), 6.5125))
    arrays = [np.array([v]) for v in (alpha, *JARM_BODY, 1.0, theta)]
    *derivs, singular = _core.jarm_derivatives(*arrays, rule="paper", theta0=0.0, omega0=0.0)
    assert singular.tolist() == [True]
    assert all(np.isnan(d).all() for d in derivs)
    # A little away from it theta_J is a simple root: not flagged, finite, large.
    arrays[-1] = np.array([theta - 1e-4])
    *derivs, singular = _core.jarm_derivatives(*arrays, rule="paper", theta0=0.0, omega0=0.0)
    assert singular.tolist() == [False] and np.abs(derivs[0]).max() > 100
    # There F_y < 0 (F_y = -chi theta'^2 sin^2 theta / (2 cos theta) at any double root):
    # the body has lost contact before, so no JARM is ever a double root (paper's rule).
    with mpmath.workdps(30):
        assert rolling(mpmath.mpf(theta), alpha, *JARM_BODY, (0, 0))[3] < 0
    r = eccjump.jarm(alpha, *JARM_BODY, 1.0, derivatives=True)
    assert not r.is_jarm and not r.d_singular


def test_no_jump_means_nan_and_no_flag():
    r = eccjump.jarm(np.radians([30, 40, 60]), [0.5, 0.15, 0.15], [0.4, 0.02, 0.02], 1.0,
                     derivatives=True)  # fmt: skip
    assert r.d_theta_J.shape == (3, 3) and r.d_singular.shape == (3,)
    assert np.isnan(r.d_theta_J[[0, 2]]).all() and np.isfinite(r.d_theta_J[1]).all()
    assert not r.d_singular.any()


def test_forces_derivatives_only_where_the_forces_are():
    # SLIP_AT_JUMP reports theta_J (the paper's root after a slip) but no forces.
    r = eccjump.jarm(np.radians(np.linspace(5, 85, 60)), 0.6, 0.1, 1.0, derivatives=True)
    slip_at_jump = r.reason == eccjump.Reason.SLIP_AT_JUMP
    assert slip_at_jump.any()
    assert np.isfinite(r.d_theta_J[slip_at_jump]).all()
    for name in ("d_Fx_J", "d_Fy_J", "d_mu_J"):
        assert np.isnan(getattr(r, name)[~r.is_jarm]).all()


# --- the API ---------------------------------------------------------------------------------


def test_without_derivatives_the_fields_are_none():
    r = eccjump.jarm(0.7, *JARM_BODY, 1.0)
    assert all(getattr(r, name) is None for name in DERIVATIVES) and r.derivatives() == {}


def test_shapes_broadcast_with_a_trailing_axis():
    r = eccjump.jarm(np.radians([[38, 40, 42]]), [[0.15], [0.16]], 0.02, 1.0, derivatives=True)
    assert r.theta_J.shape == (2, 3)
    assert all(getattr(r, name).shape == (2, 3, 3) for name in FIELDS)
    assert r.d_singular.shape == (2, 3) and r.d_singular.dtype == np.bool_


def test_the_turn_restriction_and_threads_do_not_change_them():
    a = np.radians(np.linspace(30, 50, 40))
    one = eccjump.jarm(a, *JARM_BODY, 1.0, derivatives=True, n_threads=1)
    two = eccjump.jarm(a, *JARM_BODY, 1.0, derivatives=True, n_threads=2)
    assert one == two


def test_region_derivatives_are_the_points_derivatives():
    m = eccjump.region(np.radians(np.linspace(36, 44, 9)), [0.14, 0.15, 0.16], [0.0, 0.02 / 0.85],
                       1.0, derivatives=True)  # fmt: skip
    a, c, f = np.meshgrid(m.alpha, m.chi, m.km_frac, indexing="ij")
    r = eccjump.jarm(a, c, f * (1 - c), 1.0, derivatives=True)
    assert m.result.is_jarm.any()
    for name in DERIVATIVES:
        assert np.array_equal(getattr(m.result, name), getattr(r, name), equal_nan=True)


def test_region_refuses_derivatives_with_chunks():
    with pytest.raises(ValueError, match="derivatives=True needs chunks=None"):
        eccjump.region([0.6, 0.7], [0.15], [0.1], 1.0, chunks=1, derivatives=True)


def test_derivatives_must_be_a_bool():
    with pytest.raises(TypeError, match="derivatives must be True or False"):
        eccjump.jarm(0.7, *JARM_BODY, 1.0, derivatives="yes")  # type: ignore[arg-type]


@pytest.mark.parametrize("suffix", ["npz", "nc", "zarr"])
def test_a_map_with_derivatives_goes_to_xarray_and_files_and_back(tmp_path, suffix):
    pytest.importorskip("xarray")
    if suffix == "zarr":
        pytest.importorskip("zarr")
    m = eccjump.region(np.radians([38, 40, 42]), [0.15, 0.3], [0.0, 0.1], 1.0, derivatives=True)
    ds = m.to_xarray()
    assert ds.d_theta_J.dims == ("alpha", "chi", "km_frac", "wrt")
    assert list(ds.wrt.values) == ["alpha", "chi", "km"]
    assert ds.d_singular.dims == ("alpha", "chi", "km_frac")
    assert float(ds.d_theta_J.sel(wrt="chi")[1, 0, 0]) == m.result.d_theta_J[1, 0, 0, 1]
    path = tmp_path / f"m.{suffix}"
    eccjump.maps.save(m, path)
    back = eccjump.load_map(path)
    assert back == m and back.result.d_theta_J is not None
    plain = eccjump.region(np.radians([38, 40, 42]), [0.15, 0.3], [0.0, 0.1], 1.0)
    assert "wrt" not in plain.to_xarray().dims


def test_a_swept_dataset_carries_them():
    pytest.importorskip("xarray")
    ds = eccjump.region_dataset(np.radians([38, 40]), [0.15], [0.02 / 0.85], mu_s=[0.7, 1.0],
                                derivatives=True)  # fmt: skip
    assert ds.d_theta_J.dims == ("mu_s", "alpha", "chi", "km_frac", "wrt")
