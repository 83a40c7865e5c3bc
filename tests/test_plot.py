"""The figures layer: each plot function returns a labelled Figure; the CLI writes the files."""

import math
import re
from pathlib import Path

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from reference_points import JARM, JARM_BODY, SLIP_FIRST, SLIP_FIRST_BODY

import eccjump
from eccjump import plot
from eccjump.classification import closed_form, surfaces
from eccjump.cli import main


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _labelled(ax) -> None:
    assert ax.get_xlabel() and ax.get_ylabel() and ax.get_title()


def test_fig3b_data_is_closed_form_mu_and_marks_the_minimum():
    fig = plot.fig3b(*SLIP_FIRST_BODY, mu_s=1.6)
    assert isinstance(fig, matplotlib.figure.Figure)
    ax = fig.axes[0]
    _labelled(ax)
    assert "deg" in ax.get_xlabel()
    assert ax.get_legend() is not None
    line = next(ln for ln in ax.get_lines() if ln.get_gid() == "mu")
    x, y = (np.asarray(v, float) for v in line.get_data())
    ok = np.isfinite(y)
    assert ok.sum() > 0.9 * x.size
    np.testing.assert_allclose(
        y[ok], closed_form.mu(*SLIP_FIRST_BODY, np.radians(x[ok])), rtol=1e-12
    )
    mark = next(ln for ln in ax.get_lines() if ln.get_gid() == "mu_s_min")
    mx, my = (float(np.asarray(v)[0]) for v in mark.get_data())
    m, phi = closed_form.mu_s_min(*SLIP_FIRST_BODY)
    assert my == pytest.approx(float(m), rel=1e-14)
    assert my == pytest.approx(1.3916, abs=1e-4)
    assert mx == pytest.approx(360.0 + math.degrees(float(phi)), abs=1e-9)
    assert mx == pytest.approx(302.49, abs=0.01)
    # the minimum is the minimum of the plotted curve inside the green window
    green = ok & (x > 270.0) & (x < 360.0)
    assert np.min(y[green]) >= my - 1e-12


def test_fig3b_draws_into_a_given_axes():
    fig, ax = plt.subplots()
    assert plot.fig3b(ax=ax, mu_s=None) is fig


def test_fig4_uses_exact_boundaries_and_a_legend_per_turn():
    s = plot.jarm_surfaces(1.0, 1, resolution=8, chi_range=(0.1, 0.5), km_range=(0.0, 0.06))
    assert s.any
    i, j = np.argwhere(s.n_intervals > 0)[0]
    iv = eccjump.alpha_intervals(s.chi[i], s.km[j], 1.0, 1)[0]
    assert (s.lo[i, j], s.hi[i, j]) == pytest.approx(iv[0], abs=1e-11)
    fig = plot.fig4(1.0, surfaces=[s])
    ax = fig.axes[0]
    assert ax.name == "3d"
    assert ax.get_xlabel() and ax.get_ylabel() and ax.get_zlabel()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels and labels[0].startswith("$n = 1$")


def test_the_surfaces_are_computed_below_the_figures_and_still_importable_there():
    for name in ("JarmSurfaces", "jarm_surfaces", "MAX_RESOLUTION"):
        assert getattr(plot, name) is getattr(plot.paper, name) is getattr(surfaces, name)


def test_flood_fill_recovers_intervals_thinner_than_the_scan():
    chi = np.linspace(0.2, 0.45, 6)
    km = np.zeros_like(chi)
    coarse = eccjump.alpha_intervals(chi, km, 0.7, 3, n_scan=20)
    filled = surfaces.grid_intervals(chi, km, 0.7, 3, 90)
    fine = eccjump.alpha_intervals(chi, km, 0.7, 3, n_scan=3000)
    assert sum(map(bool, filled)) >= sum(map(bool, coarse))
    for got, want in zip(filled, fine, strict=True):
        if got:
            assert got[0] == pytest.approx(want[0], abs=1e-10)


def test_fig4_slices_labels_and_legend():
    fig = plot.fig4_slices(1.0, ns=(1,), km_values=(0.02,), chi_values=(0.2,), resolution=12)
    visible = [ax for ax in fig.axes if ax.get_visible()]
    assert len(visible) == 2
    for ax in visible:
        assert ax.get_xlabel() and ax.get_title()
        assert ax.get_ylim() == (0.0, 90.0)
    assert visible[0].get_ylabel() == r"ramp angle $\alpha$ [deg]"
    assert fig.legends and [t.get_text() for t in fig.legends[0].get_texts()] == ["$n = 1$"]


def test_trajectory_panels_and_events():
    res = eccjump.roll(*JARM, mu_s=1.0, dense_output=True)
    fig = plot.trajectory(res)
    assert len(fig.axes) == 4
    for ax in fig.axes:
        _labelled(ax)
        assert ax.get_legend() is not None
    texts = " ".join(t.get_text() for ax in fig.axes for t in ax.get_legend().get_texts())
    assert "lift-off" in texts and "334.344" in texts
    # the ratio panel shows |Fx|/Fy only where Fy > 0
    ratio = fig.axes[3].get_lines()[0].get_ydata()
    assert np.all(np.asarray(ratio, float)[np.isfinite(ratio)] >= 0.0)


def test_trajectory_without_dense_output():
    res = eccjump.roll(*SLIP_FIRST, mu_s=1.0)
    fig = plot.trajectory(res)
    assert "slip" in " ".join(t.get_text() for t in fig.axes[1].get_legend().get_texts())


def test_cli_writes_every_figure(tmp_path, capsys):
    rc = main(
        [
            "figures",
            "-o",
            str(tmp_path),
            "--resolution",
            "6",
            "--slice-resolution",
            "10",
            "--dpi",
            "40",
        ]
    )
    assert rc == 0
    out = capsys.readouterr().out
    for name in ("fig3b", "fig4a", "fig4b", "fig4_slices", "trajectory"):
        path = tmp_path / f"{name}.png"
        assert path.stat().st_size > 1000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert str(path) in out


def test_region_map_figure_and_map_cli_figure(tmp_path):
    import numpy as np

    from eccjump import plot, region
    from eccjump.cli import main

    reg = region(
        mu_s=1.0,
        alpha=np.radians(np.linspace(5, 85, 12)),
        chi=np.linspace(0.02, 0.6, 10),
        km_frac=np.linspace(0, 0.1, 4),
    )
    fig = plot.region_map(reg)
    ax = fig.axes[0]
    assert "alpha" in ax.get_ylabel() and "chi" in ax.get_xlabel()
    assert fig.legends, "turn legend"
    out, png = tmp_path / "m.npz", tmp_path / "m.png"
    assert (
        main(["map", "--mu-s", "1", "--grid", "8", "-q", "-o", str(out), "--figure", str(png)]) == 0
    )
    assert png.stat().st_size > 10_000


def test_every_first_flight_gets_its_frames():
    """A flight of a few hundredths of the run still gets FLIGHT_FRAMES frames (evenly
    spaced frames alone would skip the first flight of this run, 0.0071 R high)."""
    from eccjump.plot.full_motion import FLIGHT_FRAMES, MAX_FRAMES, _frame_times

    r = eccjump.simulate(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    ts = _frame_times(float(r.t[0]), float(r.t[-1]), MAX_FRAMES, r.flights)
    assert ts.size <= MAX_FRAMES and np.all(np.diff(ts) > 0)
    assert ts[0] == r.t[0] and ts[-1] == r.t[-1]
    for f in r.flights[:3]:
        inside = np.count_nonzero((ts >= f.t_liftoff) & (ts <= f.t_landing))
        assert inside >= FLIGHT_FRAMES
    even = np.linspace(r.t[0], r.t[-1], MAX_FRAMES)
    first = r.flights[0]
    assert np.count_nonzero((even >= first.t_liftoff) & (even <= first.t_landing)) <= 2


# --- every result's .plot(): ax= draws its main panel, fig= the full figure -----------------


def _results() -> dict:
    """One small result of every kind with a ``.plot()``."""
    from test_analysis import _stored

    body, slip_first = eccjump.Cylinder(*JARM_BODY), eccjump.Cylinder(*SLIP_FIRST_BODY)
    chi, alpha = np.linspace(0.05, 0.9, 8), np.radians([10.0, 30.0, 50.0])
    return {
        "roll": eccjump.roll(*JARM, mu_s=1.0),
        "motion": eccjump.simulate(slip_first, math.radians(30), mu_s=1.0, t_max=9),
        "jarm": eccjump.jarm(np.radians(np.linspace(20, 50, 12)), *JARM_BODY, 1.0),
        "region": eccjump.region(
            mu_s=1.0, alpha=np.radians(np.linspace(1, 60, 8)), chi=chi, km_frac=[0.05, 0.2]
        ),
        "motion_map": eccjump.motion_map(alpha, [0.2, 0.6], [0.1, 0.5], 1.0),
        "start_map": eccjump.start_map(1.0, [0.0, 4.7], [0.0, 1.0], grid=3),
        "uncertainty": eccjump.uncertainty(body, JARM[1], 1.0, sd={"mu_s": 0.05}, n=64),
        "design": eccjump.design((math.radians(10), math.radians(40)), 0.6, 0.1, grid=8),
        "analysis": _stored("jarm_240fps")[1],
    }


@pytest.fixture(scope="module")
def results() -> dict:
    return _results()


KINDS = ("roll", "motion", "jarm", "region", "motion_map", "start_map", "uncertainty",
         "design", "analysis")  # fmt: skip


def test_every_result_kind_is_plotted_through_the_one_table(results):
    assert set(KINDS) == set(results)
    assert {type(r) for r in results.values()} <= set(plot.compose.PLOTS)
    assert len(plot.compose.PLOTS) == len(KINDS)


@pytest.mark.parametrize("kind", KINDS)
def test_plot_ax_draws_the_main_panel_into_the_given_axes_and_returns_it(results, kind):
    fig, (left, right) = plt.subplots(1, 2)
    right.plot([0, 1], [0, 1])
    assert results[kind].plot(ax=left) is left
    assert left.has_data() and left.get_xlabel() and left.get_ylabel()
    assert right.get_xlabel() == "" and len(right.get_lines()) == 1  # the other is untouched
    assert fig.axes == [left, right]  # no axes added


@pytest.mark.parametrize("kind", KINDS)
def test_plot_fig_draws_the_full_figure_into_the_given_subfigure(results, kind):
    root = plt.figure()
    one, other = root.subfigures(1, 2)
    assert results[kind].plot(fig=one) is root
    assert one.axes and not other.axes
    assert all(a.get_figure() is one for a in root.axes)
    assert isinstance(results[kind].plot(), matplotlib.figure.Figure)


def test_two_results_compose_into_one_figure(results):
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.5))
    results["roll"].plot(ax=a)
    results["region"].plot(ax=b, km_frac=0.2)
    assert fig.axes == [a, b]
    assert "0.2" in b.get_title() and a.get_lines()[0].get_gid() == "theta"


@pytest.mark.parametrize(
    ("kwargs", "error", "name"),
    [
        ({"ax": "axes"}, TypeError, "ax"),
        ({"ax": 3}, TypeError, "ax"),
        ({"fig": []}, TypeError, "fig"),
        ({"fig": "fig"}, TypeError, "fig"),
    ],
)
def test_bad_ax_or_fig_names_the_parameter(results, kwargs, error, name):
    with pytest.raises(error, match=rf"^{name} must be"):
        results["roll"].plot(**kwargs)


def test_ax_and_fig_together_and_a_used_fig_are_refused(results):
    fig, ax = plt.subplots()
    with pytest.raises(TypeError, match=r"ax=.*fig=.*not both"):
        results["jarm"].plot(ax=ax, fig=plt.figure())
    with pytest.raises(ValueError, match=r"^fig must be empty \(it holds 1 axes\)"):
        results["jarm"].plot(fig=fig)
    assert fig.axes == [ax]


def test_jarm_plot_panels_are_the_results_fields(results):
    r = results["jarm"]
    fig = r.plot(x=np.degrees(np.linspace(20, 50, 12)), xlabel="alpha [deg]", mu_s=1.0)
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines() if ln.get_gid()}
    jarm = np.asarray(r.is_jarm)
    np.testing.assert_array_equal(lines["theta_J"].get_ydata(), np.degrees(r.theta_J[jarm]))
    for name in ("Fx_J", "Fy_J", "max_ratio", "min_Fy"):
        np.testing.assert_array_equal(lines[name].get_ydata(), getattr(r, name))
    assert fig.axes[2].get_xlabel() == "alpha [deg]"
    with pytest.raises(ValueError, match=r"^x must be .* shape \(12,\)"):
        r.plot(x=[1.0, 2.0])


def test_region_panel_draws_the_slice_asked_for(results):
    reg = results["region"]
    _, ax = plt.subplots()
    reg.plot(ax=ax, km_frac=0.06)  # nearest on the grid: 0.05
    mesh = ax.collections[0].get_array()
    cat = np.where(reg.result.is_jarm[:, :, 0], reg.result.n[:, :, 0], np.nan)
    np.testing.assert_array_equal(np.ma.filled(mesh, np.nan).reshape(cat.shape), cat)
    with pytest.raises(ValueError, match=r"^km_frac"):
        reg.plot(ax=ax, km_frac=math.nan)


def test_design_plot_marks_the_design_and_its_margins(results):
    d = results["design"]
    _, ax = plt.subplots()
    d.plot(ax=ax, resolution=20)
    star = next(ln for ln in ax.get_lines() if ln.get_gid() == "design")
    assert star.get_xdata()[0] == d.body.chi
    assert star.get_ydata()[0] == pytest.approx(math.degrees(d.alpha))
    labels = " ".join(t.get_text() for t in ax.get_legend().get_texts())
    assert "margin" in labels and "rod" in labels
    with pytest.raises(ValueError, match=r"^resolution"):
        d.plot(ax=ax, resolution=10**6)


# --- one mode palette: figures, notebook views and the explorer ------------------------------


def test_one_mode_palette_in_figures_reprs_and_the_explorer(results):
    """The palette is defined once (eccjump._base.palette); the figures, the notebook views
    and the explorer's page all draw the modes in its colours."""
    from matplotlib.colors import to_hex

    from eccjump._base import html, palette
    from eccjump.explorer import api

    colors = palette.MODE_COLORS
    assert plot.MODE_COLORS is html.MODE_COLORS is colors
    assert set(colors) == {"ROLL", "SLIP", "FLIGHT"} and len(set(colors.values())) == 3
    # the figure's bands
    run = results["motion"]
    _, ax = plt.subplots()
    run.plot(ax=ax)
    bands = {to_hex(p.get_facecolor(), keep_alpha=False) for p in ax.patches}
    assert bands == {c.lower() for c in colors.values()}  # this run rolls, slips and flies
    # the notebook view's timeline
    svg = run._repr_html_()
    assert all(f"fill='{c}'" in svg for c in colors.values())
    # the explorer: the page takes its colours from the server, and has none of its own
    status, spec = api.handle("controls", {})
    assert status == 200 and spec["mode_colors"] == colors
    script = (Path(api.__file__).parent / "static" / "explorer.js").read_text()
    assert re.search(r"const MODE_COLORS = \{\};", script)
    assert "Object.assign(MODE_COLORS, body.mode_colors)" in script
    assert not re.search(r"MODE_COLORS\s*=\s*\{[^}]*#", script)


def test_the_mode_palette_is_told_apart_by_colour_blind_readers():
    """Okabe and Ito's colours: under simulated protanopia, deuteranopia and tritanopia
    (Machado et al. 2009, severity 1, on linear RGB) every pair stays apart."""
    from matplotlib.colors import to_rgb

    from eccjump._base.palette import MODE_COLORS

    machado = {
        "protan": [[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                   [-0.003882, -0.048116, 1.051998]],
        "deutan": [[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                   [-0.011820, 0.042940, 0.968881]],
        "tritan": [[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                   [0.004733, 0.691367, 0.303900]],
    }  # fmt: skip
    lin = {m: np.asarray(to_rgb(c)) ** 2.2 for m, c in MODE_COLORS.items()}
    for matrix in machado.values():
        seen = {m: np.clip(np.asarray(matrix) @ v, 0, 1) ** (1 / 2.2) for m, v in lin.items()}
        names = list(seen)
        for i, a in enumerate(names):
            for b in names[i + 1 :]:
                assert np.linalg.norm(seen[a] - seen[b]) > 0.2, (a, b)  # 0.12 for #0072B2
