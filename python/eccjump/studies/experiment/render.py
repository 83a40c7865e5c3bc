"""A video of what ``eccjump.simulate`` predicts, filmed as a lab camera would (the tests of
``eccjump.track`` and the tutorial start from one; useful to rehearse an experiment's
analysis before filming it): the body's end face -- a white disc with a black rim and two
coloured dots, one on the axle and one at ``marker_radius`` -- rolling down a grey ramp.

What makes it a camera's: motion blur (each frame averages the body over its exposure,
``shutter`` frames long, centred on the frame's time; the run starts as the first exposure
opens, or ``wait`` seconds later: ``RenderedVideo.t_shift``), sensor
noise (Gaussian, ``noise`` grey levels), a camera rolled by ``roll``, and H.264 compression
(libx264, 4:2:0 chroma, ``crf``). The truth returned beside the file is each dot's centroid in
each frame (its mean position over the exposure, which is what a centroid of a blurred dot
measures) and the simulated run. Writing needs PyAV (``pip install eccjump[video]``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump._base.checks import flag, integer, real
from eccjump._base.checks import path as path_arg
from eccjump._base.optional import require
from eccjump._base.overwrite import check_overwrite, never
from eccjump.maps import store
from eccjump.motion.simulation import MotionResult
from eccjump.studies.experiment.inputs import between
from eccjump.studies.experiment.synthetic import MAX_FPS, lab_points, scene_inputs, simulated_run
from eccjump.studies.experiment.video import _color

#: The scene's grey levels: background, ramp, the face, its rim.
BACKGROUND, RAMP, FACE, RIM = 175.0, 80.0, 245.0, 20.0
#: The rim's width and a dot's radius, in units of R.
RIM_WIDTH, DOT_RADIUS = 0.08, 0.1
#: Sub-frames averaged over one exposure (the motion blur).
SUBFRAMES = 8
#: The smallest dot radius [px] rendered: the tracker followed dots of 1.7 px in every frame
#: of a 640 x 360 video and lost 77 of 240 frames at 1.3 px (4:2:0 chroma halves a dot's
#: colour resolution).
MIN_DOT_PX = 1.5
#: The frame's margin around the body's path [px].
MARGIN = 12
#: x264's speed preset.
PRESET = "ultrafast"


@dataclass(frozen=True, eq=False)
class RenderedVideo:
    """A rendered video and its truth: the file, the frame times ``t`` [s], each dot's
    centroid per frame in image pixels (``axle_px``, ``marker_px``: column, row from the
    top-left pixel's centre), the scale [px/m], the setup (R, the marker, α [rad], the
    camera's roll [rad]) and the simulated run with its time unit [s]; the run's time [s]
    is the video's + ``t_shift`` (half an exposure, less the wait before the release)."""

    path: Path
    t: NDArray[np.float64]
    axle_px: NDArray[np.float64]
    marker_px: NDArray[np.float64]
    scale: float
    radius: float
    marker_radius: float
    marker_angle: float
    alpha: float
    roll: float
    motion: MotionResult
    time_unit: float
    t_shift: float

    @property
    def liftoff_t(self) -> float:
        """The first lift-off in the video's time [s] (NaN without one)."""
        f = self.motion.flights
        return f[0].t_liftoff * self.time_unit - self.t_shift if f else math.nan

    def transitions_si(self) -> list[tuple[float, str, str]]:
        """(t [s], to_mode, reason) of every transition within the video, in its time."""
        end = float(self.t[-1])
        out = [(tr.t * self.time_unit - self.t_shift, tr.to_mode, tr.reason)
               for tr in self.motion.transitions[1:]]  # fmt: skip
        return [x for x in out if x[0] <= end]


@dataclass(frozen=True)
class _Camera:
    """Lab metres to image pixels: turned clockwise by ``roll`` about the lab origin (a ramp
    descending to the right looks steeper by ``roll``), scaled by ``scale`` [px/m], rows
    growing downwards, shifted by ``offset`` [px]."""

    roll: float
    scale: float
    offset: NDArray[np.float64]
    size: tuple[int, int]

    def pixels(self, p: NDArray[np.float64]) -> NDArray[np.float64]:
        cr, sr = math.cos(self.roll), -math.sin(self.roll)
        x = cr * p[:, 0] - sr * p[:, 1]
        y = sr * p[:, 0] + cr * p[:, 1]
        return self.offset + self.scale * np.column_stack([x, -y])


def render_video(
    path: str | os.PathLike[str],
    body: Cylinder,
    alpha: float,
    *,
    mu_s: float,
    mu_k: float | None = None,
    restitution: float = 0.0,
    theta0: float = 0.0,
    omega0: float = 0.0,
    radius: float = 0.05,
    g: float = 9.81,
    fps: float = 240.0,
    duration: float | None = None,
    size: tuple[int, int] = (1280, 720),
    marker_radius: float | None = None,
    marker_angle: float = 0.0,
    axle_color: str | None = "red",
    marker_color: str | None = "blue",
    dot_radius: float = DOT_RADIUS,
    shutter: float = 0.5,
    wait: float = 0.0,
    noise: float = 2.0,
    roll: float = 0.0,
    crf: int = 18,
    seed: int = 0,
    overwrite: bool = False,
) -> RenderedVideo:
    """Film what ``eccjump.simulate`` predicts into an MP4, as a lab camera would.

    Simulates ``body`` on a ramp of angle ``alpha`` (the inputs of :func:`synthetic_track`)
    and films its end face (a white disc with a black rim, a dot on the axle and one on the
    marker) on a grey ramp descending to the right across the frame, which shows the whole
    run: motion blur over each exposure, sensor noise, a rolled camera and H.264 compression
    (libx264, 4:2:0 chroma). Writing needs PyAV (``pip install eccjump[video]``).

    Parameters
    ----------
    path : str or path
        The MP4 file to write (H.264); a file already there is replaced only with
        ``overwrite``.
    body : Cylinder
        The body, with km > 0 (as :func:`eccjump.simulate` takes it).
    alpha : float
        The ramp angle [rad], in [0, π/2].
    mu_s : float
        Static friction coefficient, in [0, inf).
    mu_k : float or None, default None
        Kinetic friction coefficient, in [0, μ_s]; None: μ_k = μ_s.
    restitution : float, default 0.0
        Stronge's energetic coefficient of restitution e, in [0, 1].
    theta0 : float, default 0.0
        Initial angle [rad], |theta0| ≤ 2π 1e6.
    omega0 : float, default 0.0
        Initial angular velocity [√(g/R) rad], |omega0| ≤ 1e6; it must be 0 when ``wait``
        > 0.
    radius : float, default 0.05
        R [m], the body's radius, in [1e-4, 10].
    g : float, default 9.81
        Gravity [m/s²], in [0.01, 100].
    fps : float, default 240.0
        The frame rate [1/s], in [1, 1e5].
    duration : float or None, default None
        The run filmed after its release [s] (the last exposure ends by then; the video adds
        the ``wait`` before it); None: to the first landing and half a flight more, or 3 s
        without a flight. The run it needs, ``duration`` / √(R/g) + 2, must be in (0, 1e6]
        (``simulate``'s ``t_max``).
    size : (int, int), default (1280, 720)
        The frame's (width, height) [px], each an even int in [16, 4096] (4:2:0 chroma).
    marker_radius : float or None, default None
        The marker dot's distance from the axle [m]; None: 0.8 R. Both dots must lie on the
        white face, apart: 2 ``dot_radius`` R < ``marker_radius`` ≤ 0.92 R − ``dot_radius`` R.
    marker_angle : float, default 0.0
        The marker's angle from the direction axle -> centre of mass [rad], measured like θ
        (towards the direction of rolling), in [−2π, 2π].
    axle_color : str, (r, g, b) or None, default "red"
        The axle dot's colour: a name (``"red"``, ``"orange"``, ``"yellow"``, ``"green"``,
        ``"cyan"``, ``"blue"``, ``"purple"``, ``"magenta"``), ``"#rrggbb"`` or three ints in
        0..255, saturated enough for a dot (a chroma of at least 50); None leaves the dot out.
    marker_color : str, (r, g, b) or None, default "blue"
        The marker dot's colour, as ``axle_color``; None leaves the dot out.
    dot_radius : float, default 0.1
        A dot's radius [R], > 0 and bounded by ``marker_radius`` as above. In the frame a dot
        must be at least 1.5 px in radius (``MIN_DOT_PX``): dots a few pixels across are what
        the tracker needs, and a long run in a small frame shrinks them.
    shutter : float, default 0.5
        The exposure [frames], in [0, 1], centred on each frame's time: the motion blur
        (0: none).
    wait : float, default 0.0
        How long the body is held at rest before its release [s], in [0, 60]; ``omega0``
        must then be 0.
    noise : float, default 2.0
        The sensor's Gaussian noise [8-bit grey levels], in [0, 50].
    roll : float, default 0.0
        The camera's roll [rad], clockwise, in [−π/2, π/2]: the ramp shows at α + roll.
    crf : int, default 18
        x264's quality (its constant rate factor), an int in [0, 51]: 0 lossless, 51 worst.
    seed : int, default 0
        The seed of the sensor noise (``numpy.random.default_rng``), an int ≥ 0.
    overwrite : bool, default False
        Replace a regular file at ``path`` (anything else there is never replaced). True or
        False, nothing else.

    Returns
    -------
    RenderedVideo
        The file and its truth: the frame times ``t`` [s], each dot's centroid per frame in
        image pixels (``axle_px``, ``marker_px``: its mean position over the exposure, what
        the centroid of a blurred dot measures), the ``scale`` [px/m], the setup and the
        simulated run (``motion``, its ``time_unit`` [s]; the run's time is the video's +
        ``t_shift``), with ``liftoff_t`` and ``transitions_si()`` in the video's time.

    Raises
    ------
    ValueError
        For a parameter outside its range, dots that would not both fit on the face or would
        be too small, or a colour that is no colour or too pale; the message names it.
    FileExistsError
        If ``path`` holds a file and ``overwrite`` is False, or holds anything but a regular
        file (the error is also a ValueError).
    TypeError
        If ``body`` is not a Cylinder or a parameter has the wrong type.
    ImportError
        Without PyAV (``pip install eccjump[video]``).
    """
    av = require("av", purpose="writing videos", extra="video")
    target = Path(path_arg("path", path))
    check_overwrite(target, overwrite=flag("overwrite", overwrite), option="overwrite=True",
                    ours=never, what="a rendered video", name="path")  # fmt: skip
    radius, g, r_m, marker_angle = scene_inputs(radius, g, marker_radius, marker_angle)
    roll = between("roll", roll, -math.pi / 2, math.pi / 2, "rad")
    seed = integer("seed", seed)
    _check_camera(radius, r_m, dot_radius, fps, shutter, wait, omega0, noise, crf)
    run, unit, horizon = simulated_run(
        body, alpha, mu_s=mu_s, mu_k=mu_k, restitution=restitution, theta0=theta0,
        omega0=omega0, radius=radius, g=g, duration=duration,
    )  # fmt: skip
    shift = 0.5 * shutter / fps - wait  # the run's time minus the video's
    t = np.arange(int((horizon * unit - shift - shutter / fps) * fps) + 1) / fps
    # the sub-frames of each exposure, centred on the frame's time (in the run's time)
    offsets = ((np.arange(SUBFRAMES) + 0.5) / SUBFRAMES - 0.5) * shutter / fps
    sub = np.clip((t[:, None] + shift + offsets[None, :]).ravel() / unit, 0.0, None)
    c, m, _ = lab_points(run, sub, alpha, 1, radius, r_m, marker_angle)
    camera = _frame(c, radius, roll, _size(size))
    dot_px = dot_radius * radius * camera.scale
    if dot_px < MIN_DOT_PX:  # the whole run fills the frame
        raise ValueError(
            f"dot_radius: the dots would be {dot_px:.2g} px in radius"
            f" (a frame that shows the whole run; the tracker needs {MIN_DOT_PX:g}): a shorter "
            "duration, a larger size or a larger dot_radius"
        )
    c_px, m_px = camera.pixels(c), camera.pixels(m)
    colors = [None if k is None else _color(n, k) for n, k in
              (("axle_color", axle_color), ("marker_color", marker_color))]  # fmt: skip
    scene = _Scene(camera, radius, dot_radius, alpha, c[0], colors, noise,
                   np.random.default_rng(seed))  # fmt: skip
    per_frame = zip(np.split(c_px, t.size), np.split(m_px, t.size), strict=True)
    frames = (scene.frame(ck, mk) for ck, mk in per_frame)
    tmp = store.temp_sibling(target)
    try:
        _encode(av, tmp, fps, crf, camera.size, frames)
        store.install(tmp, target)
    finally:
        store.remove(tmp)
    return RenderedVideo(
        path=target,
        t=t,
        axle_px=c_px.reshape(t.size, SUBFRAMES, 2).mean(axis=1),
        marker_px=m_px.reshape(t.size, SUBFRAMES, 2).mean(axis=1),
        scale=camera.scale,
        radius=radius,
        marker_radius=r_m,
        marker_angle=marker_angle,
        alpha=alpha,
        roll=roll,
        motion=run,
        time_unit=unit,
        t_shift=shift,
    )


def _check_camera(
    radius: float,
    r_m: float,
    dot_radius: float,
    fps: float,
    shutter: float,
    wait: float,
    omega0: float,
    noise: float,
    crf: int,
) -> None:
    """ValueError naming the parameter for a camera or a face that cannot be rendered."""
    dot = real("dot_radius", dot_radius) * radius
    if not (dot > 0 and 2 * dot < r_m <= (1 - RIM_WIDTH) * radius - dot):
        raise ValueError(
            "marker_radius, dot_radius: both dots must lie on the white face, apart: "
            f"2 dot_radius R < marker_radius <= {1 - RIM_WIDTH:g} R - dot_radius R"
        )
    between("fps", fps, 1.0, MAX_FPS, "1/s")
    between("shutter", shutter, 0.0, 1.0, "frames")
    between("wait", wait, 0.0, 60.0, "s")
    between("noise", noise, 0.0, 50.0, "grey levels")
    if wait and omega0:
        raise ValueError("wait: a body held before its release starts with omega0 = 0")
    if not (isinstance(crf, int) and 0 <= crf <= 51):
        raise ValueError(f"crf must be an int in [0, 51] (x264's quality), got {crf!r}")


def _frame(c: NDArray[np.float64], radius: float, roll: float, size: tuple[int, int]) -> _Camera:
    """The camera that shows the whole path of the body (its disc) inside the margin,
    centred in the frame."""
    q = _Camera(roll, 1.0, np.zeros(2), size).pixels(c)  # rotated metres, rows down
    span = np.ptp(q, axis=0) + 2.2 * radius
    w, h = size
    scale = float(min((w - 2 * MARGIN) / span[0], (h - 2 * MARGIN) / span[1]))
    mid = (q.min(axis=0) + q.max(axis=0)) / 2
    return _Camera(roll, scale, np.array([(w - 1) / 2, (h - 1) / 2]) - scale * mid, size)


def _size(size: object) -> tuple[int, int]:
    """(width, height), each even (4:2:0 chroma) and in [16, 4096]."""
    if isinstance(size, tuple | list) and len(size) == 2:
        w, h = size
        if all(isinstance(v, int) and 16 <= v <= 4096 and v % 2 == 0 for v in (w, h)):
            return int(w), int(h)
    raise ValueError(f"size must be (width, height), even ints in [16, 4096], got {size!r}")


class _Scene:
    """The static background (grey, the ramp below its surface line) and the body drawn on
    it, frame by frame."""

    def __init__(
        self,
        camera: _Camera,
        radius: float,
        dot_radius: float,
        alpha: float,
        c0: NDArray[np.float64],
        colors: list[tuple[int, int, int] | None],
        noise: float,
        rng: np.random.Generator,
    ) -> None:
        w, h = camera.size
        self.r = radius * camera.scale
        self.dot = dot_radius * self.r
        self.colors = [None if k is None else np.array(k, dtype=np.float64) for k in colors]
        self.noise, self.rng = noise, rng
        # the ramp's surface: the line R below the axle's contact line, in pixels
        normal = np.array([math.sin(alpha), math.cos(alpha)])
        down = np.array([math.cos(alpha), -math.sin(alpha)])
        a, b = camera.pixels(np.array([c0 - radius * normal, c0 - radius * normal + down]))
        d = (b - a) / np.hypot(*(b - a))
        ys, xs = np.mgrid[0:h, 0:w]
        below = (xs - a[0]) * d[1] - (ys - a[1]) * d[0]  # > 0 below the line (rows down)
        ramp = np.clip(below + 0.5, 0.0, 1.0)
        self.clean = (BACKGROUND * (1 - ramp) + RAMP * ramp)[:, :, None].repeat(3, axis=2)
        pad = 32
        self.grain = np.clip(
            np.pad(self.clean, ((0, pad), (0, pad), (0, 0)), mode="edge")
            + rng.normal(0.0, noise, (h + pad, w + pad, 3)),
            0,
            255,
        ).astype(np.uint8)
        self.pad = pad

    def frame(self, c: NDArray[np.float64], m: NDArray[np.float64]) -> NDArray[np.uint8]:
        """One frame: the body averaged over the sub-frame positions ``c``, ``m`` [px]."""
        h, w, _ = self.clean.shape
        dy, dx = self.rng.integers(0, self.pad, 2)
        out = self.grain[dy : dy + h, dx : dx + w].copy()  # the background's noise, shifted
        reach = self.r + 2
        x0, y0 = (np.floor(c.min(axis=0) - reach)).astype(int).clip(0)
        x1, y1 = np.ceil(c.max(axis=0) + reach).astype(int) + 1
        x1, y1 = min(x1, w), min(y1, h)
        ys, xs = np.mgrid[y0:y1, x0:x1].astype(np.float64)
        bg = self.clean[y0:y1, x0:x1]
        acc = np.zeros_like(bg)
        for ck, mk in zip(c, m, strict=True):
            acc += self._body(xs, ys, bg, ck, mk)
        acc /= len(c)
        acc += self.rng.normal(0.0, self.noise, acc.shape)
        out[y0:y1, x0:x1] = np.clip(np.rint(acc), 0, 255).astype(np.uint8)
        return out

    def _body(
        self,
        xs: NDArray[np.float64],
        ys: NDArray[np.float64],
        bg: NDArray[np.float64],
        c: NDArray[np.float64],
        m: NDArray[np.float64],
    ) -> NDArray[np.float64]:
        """The body at one sub-frame over the background ``bg`` of the pixels (xs, ys)."""
        r = self.r
        d = np.hypot(xs - c[0], ys - c[1])[:, :, None]
        disc = np.clip(r + 0.5 - d, 0.0, 1.0)
        face = np.clip(r * (1 - RIM_WIDTH) + 0.5 - d, 0.0, 1.0)
        img = bg * (1 - disc) + RIM * (disc - face) + FACE * face
        for centre, color in zip((c, m), self.colors, strict=True):
            if color is None:
                continue
            dd = np.hypot(xs - centre[0], ys - centre[1])[:, :, None]
            dot = np.clip(self.dot + 0.5 - dd, 0.0, 1.0)
            img = img * (1 - dot) + color * dot
        return img


def _encode(
    av: Any, path: Path, fps: float, crf: int, size: tuple[int, int], frames: Iterable[Any]
) -> None:
    """Write the RGB frames as H.264 (yuv420p) in an MP4 at ``fps``."""
    from fractions import Fraction

    with av.open(os.fspath(path), mode="w", format="mp4") as out:
        stream = out.add_stream("libx264", rate=Fraction(fps).limit_denominator(10**6))
        stream.width, stream.height = size
        stream.pix_fmt = "yuv420p"
        # one thread: x264's output then depends on nothing but its input (same bits anywhere)
        stream.options = {"crf": str(int(crf)), "preset": PRESET, "threads": "1"}
        for k, rgb in enumerate(frames):
            frame = av.VideoFrame.from_ndarray(rgb, format="rgb24")
            frame.pts = k
            for packet in stream.encode(frame):
                out.mux(packet)
        for packet in stream.encode():
            out.mux(packet)


__all__ = ["RenderedVideo", "render_video"]
