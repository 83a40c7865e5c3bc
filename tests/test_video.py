"""eccjump.track and ``eccjump track`` / ``eccjump analyze VIDEO`` on videos rendered at test
time from ``simulate`` (``render_video``: H.264 by libx264, motion blur over half a frame,
sensor noise, the two dots on a white end face with a black rim), never stored: the tracked
centroids against the rendered truth (each dot's mean position over its exposure), the frame
times, the scale, the ramp line and the camera's roll, and the verdict with the lift-off.

The stated accuracy, at 1280 x 720 and 240 fps with dots of 0.1 R (8 px across): each
coordinate of a centroid within 0.2 px RMS and 0.6 px at worst (the codec dominates: a
lossless render tracks to 0.02 px), its reported standard error within a factor 3 of that;
the scale from the dots' distance within three of its standard errors; the ramp line within
0.1 deg. The bad videos (not a video, no frames, one dot, one colour) are in the fuzz tests
of files (``test_fuzz_files.py``). About 30 s in all.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from fuzz_cases import MAX_MESSAGE, run_cli_inprocess
from test_analysis_track import BAD_SCENES
from test_limits import interrupted_after

import eccjump
from eccjump.studies.experiment import render_video
from eccjump.studies.experiment.video import is_track_file, is_video

pytest.importorskip("av")

#: The design's JARM body (docs: "A walk through one track") and the paper's Fig. 3b body
#: slipping first (tests/data/slip_240fps.csv's).
JARM = dict(chi=0.10927, km=0.0777, alpha=66.087, radius=0.05, mu_s=1.2, mu_k=0.9,
            marker_angle=0.6)  # fmt: skip
SLIP = dict(chi=0.5, km=0.4, alpha=30.0, radius=0.04, mu_s=0.4, mu_k=0.3, marker_angle=-1.0,
            theta0=3.6, omega0=2.0)  # fmt: skip
FPS = 240.0


def render(path, case: dict, **kw):
    c = dict(case)
    body = eccjump.Cylinder(c.pop("chi"), c.pop("km"))
    return render_video(path, body, math.radians(c.pop("alpha")), **c, **kw)


def analyze(tr, case: dict, marker_radius: float):
    return eccjump.analyze(
        tr, radius=case["radius"], chi=case["chi"], km=case["km"],
        alpha=math.radians(case["alpha"]), marker_radius=marker_radius,
        marker_angle=case["marker_angle"], profile_mu_k=False,
    )  # fmt: skip


@pytest.fixture(scope="module")
def hd(tmp_path_factory):
    """The JARM body filmed at 1280 x 720, tracked with the scale from the marker."""
    clip = render(tmp_path_factory.mktemp("hd") / "jarm.mp4", JARM)
    tr = eccjump.track(clip.path, marker_radius=clip.marker_radius,
                       alpha=math.radians(JARM["alpha"]))  # fmt: skip
    return clip, tr


@pytest.fixture(scope="module")
def slip(tmp_path_factory):
    """The slip-first body at 640 x 360 (dots of 0.2 R, the marker at 0.6 R)."""
    r_m = 0.6 * SLIP["radius"]
    clip = render(tmp_path_factory.mktemp("slip") / "slip.mp4", SLIP, size=(640, 360),
                  marker_radius=r_m, dot_radius=0.2)  # fmt: skip
    return clip, eccjump.track(clip.path, marker_radius=r_m)


def rms(a):
    return float(np.sqrt(np.nanmean(a**2)))


def test_the_centroids_are_within_a_fraction_of_a_pixel(hd):
    clip, tr = hd
    assert tr.n == clip.t.size and tr.lost.size == 0
    for got, want, err in ((tr.axle_px, clip.axle_px, tr.c_err), (tr.marker_px, clip.marker_px,
                                                                   tr.m_err)):  # fmt: skip
        miss = got - want
        assert rms(miss) < 0.2 and np.abs(miss).max() < 0.6, (rms(miss), np.abs(miss).max())
        stated = float(np.median(err)) * tr.scale  # per coordinate [px]
        assert 1 / 3 < rms(miss) / stated < 3, (rms(miss), stated)


def test_the_frame_times_are_the_containers(hd):
    clip, tr = hd
    assert np.array_equal(tr.frame_t, np.arange(clip.t.size) / FPS)  # pts x time_base, exact
    assert np.array_equal(tr.t, tr.frame_t)


def test_the_scale_ramp_line_and_roll(hd):
    clip, tr = hd
    assert abs(tr.scale - clip.scale) <= 3 * tr.scale_err, (tr.scale, clip.scale, tr.scale_err)
    assert tr.scale_err < 1e-3 * tr.scale
    assert abs(math.degrees(tr.ramp_angle) - JARM["alpha"]) < 0.1
    assert abs(math.degrees(tr.roll)) < 0.1


def test_a_jarm_video_with_the_dots_scale_is_not_called_a_slip(hd):
    """Right or undetermined (the issue's target), with the scale from the dots' distance
    (off by 5e-4 to 1e-3): taken as exact, it made this JARM body `slip_first` in 5 of 6
    seeds; the fit now carries the track's length scale, and finds it."""
    clip, tr = hd
    res = analyze(tr, JARM, clip.marker_radius)
    assert res.verdict in ("jarm", "undetermined"), (res.verdict, res.reason, res.evidence)
    assert abs(res.liftoff_t - clip.liftoff_t) < 2 / FPS
    off = clip.scale / tr.scale  # the track's metre in true metres
    assert abs(res.fit.value("length_scale") - off) < 1.5e-3, (res.fit.value("length_scale"), off)


def test_the_design_videos_verdict_is_jarm_with_the_friction_it_was_designed_for(hd):
    """The "done when" of issue 48: the design's body, from its video, with the mu_s the
    design was made for (1.2 +- 0.1 on its sheet) is `jarm`. From the track alone it is
    `undetermined (frame_rate)` at 240 fps: a one-frame slip at the lift-off would not show."""
    clip, tr = hd
    sheet = {"body": {"chi": JARM["chi"], "km": JARM["km"], "radius": JARM["radius"]},
             "alpha_deg": JARM["alpha"], "mu_s": 1.2, "mu_s_err": 0.1}  # fmt: skip
    res = eccjump.analyze(tr, design=sheet, marker_radius=clip.marker_radius,
                          marker_angle=JARM["marker_angle"], profile_mu_k=False)  # fmt: skip
    assert res.verdict == "jarm", (res.verdict, res.reason, res.evidence)
    assert abs(res.liftoff_t - clip.liftoff_t) < 2 / FPS
    assert any("(from the design sheet)" in e for e in res.evidence)


def test_a_slip_first_video_is_slip_first(slip):
    clip, tr = slip
    assert rms(tr.axle_px - clip.axle_px) < 0.3 and rms(tr.marker_px - clip.marker_px) < 0.3
    res = analyze(tr, SLIP, clip.marker_radius)
    assert res.verdict == "slip_first", (res.verdict, res.reason, res.evidence)
    assert abs(res.liftoff_t - clip.liftoff_t) < 2 / FPS
    first_slip = clip.transitions_si()[0]
    assert first_slip[1] == "SLIP" and abs(res.slips[0].t1 - first_slip[0]) < 2 / FPS


def test_colours_pick_the_dots(slip):
    """Named colours override the straight-path rule: naming the marker's dot (blue) the
    axle's swaps them (a user's choice), a colour no dot has is refused naming the option."""
    clip, tr = slip
    assert tr.axle_color != tr.marker_color
    swapped = eccjump.track(clip.path, marker_radius=clip.marker_radius, axle_color="blue")
    assert np.allclose(swapped.axle_px, tr.marker_px, equal_nan=True)
    same = eccjump.track(clip.path, marker_radius=clip.marker_radius, axle_color="#dc1e1e",
                         marker_color=(30, 70, 220))  # fmt: skip
    assert np.array_equal(same.axle_px, tr.axle_px, equal_nan=True)
    with pytest.raises(ValueError, match=r"^marker_color: no dot of colour #f5cb14") as info:
        eccjump.track(clip.path, marker_radius=clip.marker_radius, marker_color="#f5cb14")
    assert len(str(info.value)) <= MAX_MESSAGE


@pytest.mark.parametrize(
    ("name", "value", "error"),
    [*BAD_SCENES, ("roll", 3.0, ValueError), ("roll", "3 deg", TypeError),
     ("fps", "240", TypeError), ("shutter", 2.0, ValueError)],
)  # fmt: skip
def test_render_video_names_a_bad_input(tmp_path, name, value, error):
    """Each bad input of the scene or the camera: its own error, naming it, and no file."""
    with pytest.raises(error) as info:
        render_video(tmp_path / "v.mp4", eccjump.Cylinder(0.1, 0.3), 0.3, mu_s=1.0,
                     duration=0.1, **{name: value})  # fmt: skip
    msg = str(info.value)
    assert msg.startswith(name) and len(msg) < 200 and "\n" not in msg, msg
    assert not list(tmp_path.iterdir())


def test_dots_too_small_to_track_are_not_rendered(tmp_path):
    """The Fig. 3b body slides from rest for 3 s: a 1280 x 720 frame that shows the whole
    run draws its dots 0.5 px in radius, which the tracker cannot find ("no moving dot").
    The renderer says so, naming the parameter, and writes nothing."""
    target = tmp_path / "tiny.mp4"
    with pytest.raises(ValueError, match=r"^dot_radius: the dots would be 0\.5\d* px") as info:
        render(target, dict(SLIP, omega0=0.0))
    assert len(str(info.value)) <= MAX_MESSAGE and not target.exists()


def test_a_rolled_camera_and_a_wait_before_the_release(tmp_path):
    """The roll is measured against alpha; the still frames before the release are left out,
    the track starting at the first frame after it (the model starts at the first frame
    with omega0 >= 0: from the last still frame, a release up to a frame later cannot be
    expressed, and a 0.57 s wait failed the fit at chi2_red 34)."""
    clip = render(tmp_path / "rolled.mp4", JARM, size=(640, 360), marker_radius=0.035,
                  dot_radius=0.2, roll=math.radians(2.0), wait=0.1)  # fmt: skip
    tr = eccjump.track(clip.path, marker_radius=0.035, alpha=math.radians(JARM["alpha"]))
    assert abs(math.degrees(tr.roll) - 2.0) < 0.1, math.degrees(tr.roll)
    release = -clip.t_shift  # the video's time of the release
    assert release < tr.t[0] <= release + 5 / FPS, (tr.t[0], release)  # late is harmless
    assert tr.release_t == tr.t[0] and tr.lost.size == round(tr.t[0] * FPS)


def test_a_wait_before_the_release_is_cut_where_the_fit_can_start(tmp_path):
    """Held still for 0.57 s, then released (a one-second clip): the track starts after the
    release and the fit passes its gate (it failed at chi2_red 34 from the last still frame,
    half a frame before the release), from rolling: its start's slip is not fitted."""
    clip = render(tmp_path / "wait.mp4", JARM, wait=0.57)
    tr = eccjump.track(clip.path, marker_radius=clip.marker_radius,
                       alpha=math.radians(JARM["alpha"]))  # fmt: skip
    assert -clip.t_shift < tr.t[0] <= -clip.t_shift + 5 / FPS
    res = analyze(tr, JARM, clip.marker_radius)
    assert res.reason != "model" and res.fit.chi2_reduced < 2.0, (res.reason, res.evidence)
    assert abs(res.liftoff_t - clip.liftoff_t) < 2 / FPS
    # rolling from its release: no slip at the start (a free slip0 fitted the codec's errors)
    assert res.verdict != "slip_first" and "slip0" not in res.parameters(), res.evidence


def _hide_marker(clip, target, frames) -> None:
    """Re-encode ``clip`` with the marker's dot painted over (white) in ``frames``."""
    import av

    with av.open(str(clip.path)) as src, av.open(str(target), "w") as out:
        stream = out.add_stream("libx264", rate=240)
        stream.width, stream.height, stream.pix_fmt = 640, 360, "yuv420p"
        stream.options = {"crf": "12", "threads": "1"}
        for k, frame in enumerate(src.decode(video=0)):
            rgb = frame.to_ndarray(format="rgb24")
            if k in frames:
                x, y = np.rint(clip.marker_px[k]).astype(int)
                rgb[y - 6 : y + 7, x - 6 : x + 7] = 245
            new = av.VideoFrame.from_ndarray(rgb, format="rgb24")
            new.pts = k
            out.mux(stream.encode(new))
        out.mux(stream.encode())


def test_a_lost_dot_is_a_gap_not_a_guess(slip, tmp_path):
    """A dot hidden in some frames: those frames are left out of the track, the others are
    tracked as before."""
    clip, tr = slip
    hidden = [30, 31, 32, 60]
    _hide_marker(clip, tmp_path / "hidden.mp4", hidden)
    gaps = eccjump.track(tmp_path / "hidden.mp4", marker_radius=clip.marker_radius)
    assert list(gaps.lost) == hidden and np.isnan(gaps.marker_px[hidden]).all()
    assert np.isfinite(gaps.axle_px[hidden]).all()  # the axle's dot is still found there
    assert np.array_equal(gaps.t, np.delete(tr.frame_t, hidden))
    assert rms(gaps.marker_px - clip.marker_px) < 0.3
    assert "4 (30-32, 60) left out" in repr(gaps)


@pytest.mark.skipif(os.name != "posix", reason="needs POSIX signals")
def test_tracking_honours_ctrl_c_within_a_second(hd):
    clip, _ = hd
    code = textwrap.dedent(
        f"""
        import eccjump
        print("start", flush=True)
        try:  # 1280 x 720, about 1.5 s
            eccjump.track({str(clip.path)!r}, marker_radius=0.04)
            print("finished")
        except KeyboardInterrupt:
            print("interrupted", flush=True)
        """
    )
    assert interrupted_after(code, 0.3) < 1.0


# --- the command line --------------------------------------------------------------------


def test_eccjump_track_writes_what_analyze_reads(slip, tmp_path):
    clip, tr = slip
    out = tmp_path / "track.csv"
    r_m = str(clip.marker_radius)
    code, stdout, err = run_cli_inprocess(["track", str(clip.path), "-o", str(out),
                                           "--marker-radius", r_m])  # fmt: skip
    assert code == 0, err
    assert is_track_file(out) and f"track: {out}" in stdout and "Traceback" not in err
    back = eccjump.studies.experiment.read_track(out)
    assert np.array_equal(back.t, np.round(tr.t, 10)) and np.allclose(back.c, tr.c, atol=1e-8)
    # its own file is replaced without --overwrite; the user's is not, even a CSV
    code, _, err = run_cli_inprocess(["track", str(clip.path), "-o", str(out), "--marker-radius",
                                      r_m, "--json"])  # fmt: skip
    assert code == 0, err
    mine = tmp_path / "mine.csv"
    mine.write_text("t,xc,yc,xm,ym\n")
    code, _, err = run_cli_inprocess(["track", str(clip.path), "-o", str(mine),
                                      "--marker-radius", r_m])  # fmt: skip
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and "--overwrite" in lines[0], err
    assert mine.read_text() == "t,xc,yc,xm,ym\n"


def test_eccjump_analyze_takes_the_video(slip, tmp_path):
    clip, _ = slip
    figure = tmp_path / "slip.png"
    argv = ["analyze", str(clip.path), "--radius", str(SLIP["radius"]), "--chi", "0.5",
            "--km", "0.4", "--alpha", "30", "--marker-radius", str(clip.marker_radius),
            "--marker-angle", str(math.degrees(SLIP["marker_angle"])), "--json",
            "--figure", str(figure)]  # fmt: skip
    code, stdout, err = run_cli_inprocess(argv)
    assert code == 0, err
    report = json.loads(stdout)
    assert report["verdict"] == "slip_first" and report["video"]["tracked"] == clip.t.size
    assert report["video"]["source"] == "slip.mp4" and figure.stat().st_size > 10_000
    code, _, err = run_cli_inprocess([*argv[:-5], "--marker-radius", "0"])
    assert code == 2 and err.startswith("eccjump: error: --marker-radius"), err


def test_a_video_is_known_by_its_suffix_or_its_first_bytes(slip, tmp_path):
    clip, _ = slip
    renamed = tmp_path / "clip.data"
    renamed.write_bytes(clip.path.read_bytes())
    assert is_video(clip.path) and is_video(renamed) and is_video(tmp_path / "x.MOV")
    text = tmp_path / "track.csv"
    text.write_text("t,xc,yc,xm,ym\n")
    assert not is_video(text) and not is_video("-") and not is_video(tmp_path)


def test_pyav_is_imported_only_to_read_a_video_and_named_when_missing(slip, monkeypatch, tmp_path):
    code = "import sys, eccjump; print('av' in sys.modules, 'scipy' in sys.modules)"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert p.stdout.split() == ["False", "False"]
    clip, _ = slip
    monkeypatch.setitem(sys.modules, "av", None)  # as if PyAV were not installed
    with pytest.raises(ImportError, match=r"^av is needed for reading videos: pip install "
                       r"eccjump\[video\]$"):  # fmt: skip
        eccjump.track(clip.path, marker_radius=clip.marker_radius)
    out = tmp_path / "t.csv"
    code, _, err = run_cli_inprocess(["track", str(clip.path), "-o", str(out), "--marker-radius",
                                      "0.024"])  # fmt: skip
    assert code == 1 and "eccjump[video]" in err and len(err.splitlines()) == 1, err
    assert not out.exists()
