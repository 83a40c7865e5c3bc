"""The figures layer: each plot function returns a labelled Figure; the CLI writes the files."""

import math

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
