"""``eccjump simulate`` and the motion figures (plot.motion, plot.animate_motion).

Most tests run against the fake result of tests/motion_fake.py (only the documented fields of
MotionResult), put in place of ``eccjump.simulate`` so that they neither need nor depend on the
integrator. The last tests run the real ``eccjump.simulate`` when it exists."""

import json
import math
import re
import sys
import types
from dataclasses import replace

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from motion_fake import MODES, energy, fake_result
from reference_points import SLIP_FIRST, SLIP_FIRST_ALPHA, SLIP_FIRST_ARGS, SLIP_FIRST_BODY

from eccjump import Cylinder, plot
from eccjump.cli import main
from eccjump.cli.simulate import state_energy, transition_energies
from eccjump.plot import full_motion

CLI = sys.modules["eccjump.cli.simulate"]

BASE = ["simulate", *SLIP_FIRST_ARGS, "--mu-s", "1"]


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture
def fake(monkeypatch):
    """``simulate`` replaced by one that returns the fake result; the calls (args, kwargs)
    and the results are recorded."""
    calls, results = [], []

    def simulate(body, alpha, **kw):
        calls.append((body, alpha, kw))
        res = fake_result(body.chi, body.km, alpha, with_sol=bool(kw.get("dense_output")))
        results.append(res)
        return res

    # the command's own binding, and the module for `from eccjump.motion import simulate`
    # done later (the gallery script)
    monkeypatch.setattr(CLI, "simulate", simulate)
    mod = types.ModuleType("eccjump.motion")
    mod.simulate = simulate
    monkeypatch.setitem(sys.modules, "eccjump.motion", mod)
    return types.SimpleNamespace(calls=calls, results=results)


def table_rows(out: str) -> list[list[str]]:
    """The transition rows of the table: index, t, theta, from, '->', to, reason, energy."""
    rows = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 8 and parts[0].isdigit() and parts[4] == "->":
            rows.append(parts)
    return rows


# --- the table and the JSON ------------------------------------------------------------------


def test_table_has_one_row_per_transition_with_the_energy_after_it(fake, capsys):
    assert main(BASE) == 0
    out = capsys.readouterr().out
    res = fake.results[0]
    rows = table_rows(out)
    assert [(r[3], r[5], r[6]) for r in rows] == [
        ("-", "ROLL", "start"),
        ("ROLL", "SLIP", "slip"),
        ("SLIP", "SLIP", "reverse"),
        ("SLIP", "FLIGHT", "normal_force"),
        ("FLIGHT", "ROLL", "impact"),
    ]
    for r, tr in zip(rows, res.transitions, strict=True):
        assert float(r[1]) == pytest.approx(tr.t, abs=1e-8)
        assert float(r[2]) == pytest.approx(math.degrees(tr.theta), abs=1e-6)
    # the energy of the point that starts the new segment: after the impact, not before it
    starts = [0, 41, 52, 63, 88]
    assert res.energy[87] != pytest.approx(res.energy[88])
    for r, i in zip(rows, starts, strict=True):
        assert float(r[7]) == pytest.approx(res.energy[i], abs=1e-8)
    assert "t_max: reached t_max = 4.5" in out
    assert "apex = 0.036 R, distance = 2.13 R" in out
    assert f"slip = {res.dissipated_slip:.8g}" in out
    assert f"impacts = {res.dissipated_impacts:.8g}" in out
    assert "lift-off at t = 3 " in out and "landing at t = 3.6 " in out


def test_arguments_reach_simulate_in_radians(fake, capsys):
    args = [*BASE, "--mu-k", "0.8", "--restitution", "0.3", "--rule", "normal_force"]
    args += ["--theta0", "90", "--omega0", "0.5", "--slip0", "-0.1", "--t-max", "20"]
    args += ["--l-max", "50", "--max-transitions", "7"]
    assert main(args) == 0
    body, alpha, kw = fake.calls[0]
    assert (body.chi, body.km) == (0.5, 0.4)
    assert alpha == pytest.approx(math.pi / 6, rel=1e-15)
    assert kw["theta0"] == pytest.approx(math.pi / 2, rel=1e-15)
    want = {"mu_s": 1.0, "mu_k": 0.8, "restitution": 0.3, "rule": "normal_force"}
    want |= {"omega0": 0.5, "slip0": -0.1, "t_max": 20.0, "l_max": 50.0, "max_transitions": 7}
    want |= {"dense_output": False}
    assert {k: kw[k] for k in want} == want
    assert "mu_k = 0.8, e = 0.3, rule = normal_force" in capsys.readouterr().out


def test_defaults_are_the_apis(fake):
    assert main(BASE) == 0
    kw = fake.calls[0][2]
    assert kw["mu_k"] is None and kw["restitution"] == 0.0 and kw["rule"] == "paper"
    assert kw["theta0"] == 0.0 and kw["omega0"] == 0.0 and kw["slip0"] == 0.0
    assert kw["t_max"] == 100.0 and kw["l_max"] == math.inf and kw["max_transitions"] == 100
    assert kw["integrator"] == "RK45"


def test_the_integrator_is_passed_and_recorded(fake, capsys):
    assert main([*BASE, "--integrator", "DOP853", "--json"]) == 0
    assert fake.calls[0][2]["integrator"] == "DOP853"
    assert json.loads(capsys.readouterr().out)["parameters"]["integrator"] == "DOP853"
    assert main([*BASE, "--integrator", "DOP853"]) == 0
    assert re.search(r"^integrator\s+DOP853$", capsys.readouterr().out, re.M)
    with pytest.raises(SystemExit):
        main([*BASE, "--integrator", "dop853"])
    assert "--integrator" in capsys.readouterr().err


def test_json_has_the_transitions_flights_and_ledger(fake, capsys):
    assert main([*BASE, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    res = fake.results[0]
    assert data["status"] == "t_max" and data["message"] == res.message
    assert [(d["from"], d["to"], d["reason"]) for d in data["transitions"]] == [
        (tr.from_mode, tr.to_mode, tr.reason) for tr in res.transitions
    ]
    assert data["transitions"][4]["energy"] == pytest.approx(res.energy[88])
    assert data["transitions"][3]["theta_deg"] == pytest.approx(math.degrees(res.theta[63]))
    (f,) = data["flights"]
    assert f["apex"] == pytest.approx(0.036) and f["distance"] == pytest.approx(2.13)
    assert f["t_liftoff"] == 3.0 and f["t_landing"] == 3.6
    led = data["ledger"]
    assert led["energy0"] == res.energy0
    assert led["dissipated_slip"] == res.dissipated_slip
    assert led["dissipated_impacts"] == res.dissipated_impacts
    assert led["balance"] == pytest.approx(0.0, abs=1e-12)
    assert data["impacts"][0]["outcome"] == "ROLL"
    assert data["parameters"]["alpha_deg"] == 30.0 and data["parameters"]["mu_k"] == 1.0


def test_json_writes_non_finite_numbers_as_null(fake, capsys, monkeypatch):
    def unlanded(body, alpha, **kw):
        res = fake_result(body.chi, body.km, alpha)
        f = replace(res.flights[0], t_landing=math.nan, theta_landing=math.nan)
        return replace(res, flights=(f,))

    monkeypatch.setattr(CLI, "simulate", unlanded)
    assert main([*BASE, "--json"]) == 0
    text = capsys.readouterr().out
    assert "NaN" not in text
    assert json.loads(text)["flights"][0]["t_landing"] is None
    assert main(BASE) == 0
    assert "not landed by the end" in capsys.readouterr().out


def test_energy_from_the_state_where_no_point_matches():
    body, alpha = SLIP_FIRST
    res = fake_result()
    # the transitions moved off the recorded times: the energy comes from their states
    moved = tuple(replace(tr, t=tr.t + 1e-3) for tr in res.transitions)
    got = transition_energies(replace(res, transitions=moved), body, alpha)
    want = [state_energy(body, alpha, tr) for tr in res.transitions]
    assert got == pytest.approx(want, rel=1e-14)
    # and the state's energy is the recorded one (the formula of docs/motion.md)
    assert transition_energies(res, body, alpha) == pytest.approx(want, rel=1e-13)
    tr = res.transitions[3]
    e = energy(0.5, body.Icm, alpha, tr.theta, tr.omega, tr.l, tr.ldot, tr.b, tr.bdot)
    assert state_energy(body, alpha, tr) == pytest.approx(float(e), rel=1e-15)


def test_errors_are_one_line_and_exit_2(fake, monkeypatch, capsys):
    # a wrong animation format is refused before the run
    assert main([*BASE, "--animate", "motion.mp4"]) == 2
    assert ".gif" in capsys.readouterr().err and not fake.calls

    def bad(body, alpha, **kw):
        raise ValueError("mu_s = -1 is outside the allowed range [0, inf)")

    monkeypatch.setattr(CLI, "simulate", bad)
    assert main(BASE) == 2
    err = capsys.readouterr().err
    assert err == "eccjump: error: mu_s = -1 is outside the allowed range [0, inf)\n"
    with pytest.raises(SystemExit):
        main(["simulate", "--alpha", "120", "--chi", "0.5", "--km", "0.4", "--mu-s", "1"])


def test_simulate_is_a_subcommand(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "simulate" in capsys.readouterr().out


# --- the figure and the animation ------------------------------------------------------------


@pytest.mark.slow
def test_figure_and_animation_are_written(fake, tmp_path, capsys):
    png, gif = tmp_path / "motion.png", tmp_path / "motion.gif"
    assert main([*BASE, "--figure", str(png), "--animate", str(gif)]) == 0
    out = capsys.readouterr().out
    assert f"figure: {png}" in out and f"animation: {gif}" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert gif.read_bytes()[:6] == b"GIF89a"
    from PIL import Image

    with Image.open(gif) as im:
        assert 100 <= im.n_frames <= plot.MAX_FRAMES
    # the animation asked for the dense output and used it
    assert fake.calls[0][2]["dense_output"] is True
    assert fake.results[0].calls and max(fake.results[0].calls) >= 100


def test_motion_panels():
    res = fake_result()
    fig = plot.motion(res, body=Cylinder(*SLIP_FIRST_BODY), alpha=SLIP_FIRST_ALPHA)
    axes = fig.axes
    assert len(axes) == 6
    assert all(ax.get_shared_x_axes().joined(axes[0], ax) for ax in axes)
    assert all(ax.get_ylabel() for ax in axes) and "time" in axes[5].get_xlabel()
    lines = {ln.get_gid(): ln for ax in axes for ln in ax.get_lines() if ln.get_gid()}
    want = {
        "theta_dot": res.omega,
        "slip_velocity": res.ldot - res.omega,
        "Fx": res.Fx,
        "Fy": res.Fy,
        "height": res.b - 1.0,
        "energy": res.energy,
        "energy_total": res.energy + res.dissipated,
    }
    for gid, y in want.items():
        np.testing.assert_allclose(lines[gid].get_ydata(), y, rtol=0, atol=1e-14)
    np.testing.assert_allclose(lines["energy_total"].get_ydata(), res.energy0, atol=1e-12)
    assert lines["energy_total"].get_linestyle() == "--"
    legend = [t.get_text() for t in axes[0].get_legend().get_texts()]
    assert legend == ["ROLL", "SLIP", "FLIGHT", "impact"]
    # mode bands: ROLL, SLIP (with its reverse), FLIGHT, ROLL on every panel
    bands = [p for p in axes[2].patches]
    assert len(bands) == 4
    impact_lines = [ln for ln in axes[3].get_lines() if list(ln.get_xdata()) == [3.6, 3.6]]
    assert len(impact_lines) == 1
    assert "30°" in fig._suptitle.get_text() and "t_max" in fig._suptitle.get_text()


def test_motion_draws_into_given_axes_and_needs_six():
    fig, axes = plt.subplots(6, 1, sharex=True)
    assert plot.motion(fake_result(), axes=axes) is fig
    with pytest.raises(ValueError, match="6 axes"):
        plot.motion(fake_result(), axes=axes[:3])


def test_resampled_mode_is_that_of_the_last_transition():
    res = fake_result()
    ts = np.array([0.0, 1.99, 2.0, 2.7, 3.0, 3.3, 3.6, 4.5])
    theta, _l, b, names = full_motion._resample(res, ts)
    assert names == ["ROLL", "ROLL", "SLIP", "SLIP", "FLIGHT", "FLIGHT", "ROLL", "ROLL"]
    np.testing.assert_allclose(theta, np.interp(ts, res.t, res.theta))
    assert b[5] > 1.0 and b[0] == 1.0
    assert set(MODES) == set(plot.MODE_COLORS)


def test_animation_without_dense_output_and_its_frame_count(tmp_path):
    from PIL import Image

    res = fake_result()
    path = plot.animate_motion(
        res, tmp_path / "a.gif", body=Cylinder(*SLIP_FIRST_BODY), alpha=0.5, fps=10, seconds=1.2
    )
    with Image.open(path) as im:
        assert im.n_frames == 12
        assert im.info["duration"] == 100
    with pytest.raises(ValueError, match="body"):
        plot.animate_motion(res, tmp_path / "b.gif")
    with pytest.raises(ValueError, match=r"\.gif"):
        plot.animate_motion(res, tmp_path / "b.mp4", body=Cylinder(*SLIP_FIRST_BODY), alpha=0.5)


# --- the real simulate (runs once eccjump.motion exists) --------------------------------------


def test_real_slip_then_jump(tmp_path, capsys):
    pytest.importorskip("eccjump.motion")
    png = tmp_path / "motion.png"
    assert main([*BASE, "--figure", str(png)]) == 0
    out = capsys.readouterr().out
    rows = table_rows(out)
    assert rows[0][3:7] == ["-", "->", "ROLL", "start"]
    assert any(r[5] == "SLIP" for r in rows), out
    assert any(r[5] == "FLIGHT" for r in rows), out
    assert png.stat().st_size > 20_000


def test_real_animation(tmp_path):
    motion = pytest.importorskip("eccjump.motion")
    body, alpha = SLIP_FIRST
    res = motion.simulate(body, alpha, mu_s=1.0, t_max=8.0, dense_output=True)
    path = plot.animate_motion(res, tmp_path / "m.gif", body=body, alpha=alpha, fps=10, seconds=2)
    assert path.read_bytes()[:6] == b"GIF89a"


# --- the gallery script ----------------------------------------------------------------------


def _gallery_script():
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "docs" / "gallery" / "make_motion_gallery.py"
    spec = importlib.util.spec_from_file_location("make_motion_gallery", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_gallery_script_writes_both_files(fake, tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(full_motion, "MAX_FRAMES", 8)
    gallery = _gallery_script()
    png, gif = gallery.main(tmp_path)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and gif.read_bytes()[:6] == b"GIF89a"
    (_, alpha, kw_full), (_, _, kw) = fake.calls
    assert alpha == pytest.approx(math.radians(30.0)) and kw_full["mu_s"] == 1.0
    # cut a while after the first landing (t = 3.6 + 1 in the fake), or at the run's end (4.5)
    assert kw["t_max"] == 4.5 and kw["dense_output"] is True
    longer = replace(fake.results[0], t=np.r_[fake.results[0].t, 9.0])
    assert gallery.window(longer) == pytest.approx(4.6)
    assert "FLIGHT -> ROLL" in capsys.readouterr().out
