"""From a lab video to a track (``eccjump.track``): the two coloured dots on the body's end face
found in every frame, their sub-pixel centroids with a standard error, the frame times from
the container, the scale, and the ramp line with the camera's roll, as a :class:`VideoTrack`
that ``eccjump.analyze`` takes like any track (the site's page "Analysing an experiment").

The scene: the end face carries two small dots of saturated, distinct colours, one on the
axle and one at ``marker_radius`` from it; the rest of the scene is mostly unsaturated (a
white face, a black rim, a grey ramp). How they are found, and why:

* A dot is a compact blob of high **chroma** (max - min of R, G, B), not of HSV saturation:
  saturation divides by the brightness and blows up the noise of dark pixels (the rim),
  while chroma is near 0 on white, grey and black alike.
* Its centroid weighs each pixel by its chroma above a floor, over the blob's connected
  pixels at full resolution. A blob symmetric about its centre (a disc, or a disc smeared by
  motion blur) has its centroid there; under blur that is the dot's mean position over the
  exposure (docs: a timing claim finer than a frame must say so). The standard error follows
  from the chroma noise sigma_C (the spread of the chroma inside and around the dot):
  var(x) = sigma_C² sum (x_i - x)² / W², W the summed weight. That ignores the codec's
  correlation of neighbouring pixels, so the errors are then scaled up to the centroids'
  actual scatter along their paths, when that is larger (the spread of third differences of
  consecutive frames). The analysis estimates the noise from the track itself as well.
* The two dots are the two colours whose blobs **move together** (their distance stays the
  same: two points of one rigid body) and move at all (a coloured object of the scene does
  not). The **axle's** dot is the one whose path is a straight line (the rolling line); the
  marker's turns about it. ``axle_color`` / ``marker_color`` pick them by colour where the
  scene is cluttered.
* A dot that is not found where its path leads, cut by the frame's edge, smaller than half
  its usual size (partly hidden), or not at the other dot's distance, is **lost** in that
  frame: the frame is left out of the track (a gap, not a guess; the analysis works on the
  frames' actual times).
* Frames where the body waits before its release are left out (``release.release_frame``:
  the track starts at the first frame after the release, erring late, never early).

Work and memory are bounded: frames are decoded one at a time and only the blobs of each are
kept (at most :data:`MAX_BLOBS`); at most ``track.MAX_FRAMES`` frames between ``start`` and
``end`` and :data:`MAX_PIXELS` pixels a frame; Ctrl-C stops between two frames. Reading needs
PyAV and scipy (``pip install eccjump[video]``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import flag, real, short
from eccjump._base.checks import path as path_arg
from eccjump._base.docs import fill
from eccjump._base.optional import require
from eccjump._base.overwrite import check_overwrite
from eccjump._base.userfiles import open_binary
from eccjump.maps import store
from eccjump.studies.experiment.inputs import in_range
from eccjump.studies.experiment.release import REACH, release_frame
from eccjump.studies.experiment.track import MAX_FRAMES, MIN_FRAMES, Track

#: A colour: a name of :data:`COLORS`, ``"#rrggbb"``, or (r, g, b) in 0..255.
Color = str | Sequence[int]

#: The colour names ``axle_color`` and ``marker_color`` take (the renderer paints these).
COLORS: dict[str, tuple[int, int, int]] = {
    "red": (220, 30, 30),
    "orange": (245, 130, 20),
    "yellow": (235, 215, 20),
    "green": (30, 160, 60),
    "cyan": (20, 190, 210),
    "blue": (30, 70, 220),
    "purple": (130, 40, 200),
    "magenta": (215, 30, 190),
}
#: The least chroma a colour of a dot may have (the length of its (Cb, Cr) offset from grey,
#: in 8-bit levels; pure red has 120, a pale pink 20): a paler one drowns in the scene.
MIN_COLOR_CHROMA = 50
#: Chroma that makes a sample part of a dot, and the floor of the centroid's weights: far
#: above the noise of a white, grey or black scene (a level or two), below a dot's (60-120).
DETECT_CHROMA, WEIGHT_CHROMA = 30.0, 12.0
#: A dot's size bounds in chroma samples (2 x 2 pixels each in 4:2:0 video): at least
#: MIN_AREA, at most MAX_AREA of the frame.
MIN_AREA, MAX_AREA = 3, 0.02
#: The fewest of its bounding box's pixels a compact blob fills (a smeared disc fills ~0.6).
MIN_FILL = 0.3
#: The most blobs kept per frame (the largest): a bound on the memory of a cluttered scene.
MAX_BLOBS = 24
#: The window of a centroid: the dot's samples and this many rings around them.
WINDOW = 1
#: The most pixels of a frame (4096 x 4096).
MAX_PIXELS = 4096 * 4096
#: Blobs within this hue [deg] of each other are one colour; a named colour matches a dot's
#: within COLOR_MATCH.
HUE_GAP, COLOR_MATCH = 25.0, 40.0
#: Two dots move together if their distance spreads by less than this fraction of itself.
RIGID = 0.08
#: A path is the straight one if the other's residual about its line is this many times its.
STRAIGHTER = 2.0
#: A frame's luma (H, W) and chroma offsets Cb, Cr (H/2, W/2).
Planes = tuple[NDArray[np.uint8], NDArray[np.float32], NDArray[np.float32]]
#: The columns of a blob row (internal): centroid, its standard errors, area, hue, weight.
_X, _Y, _SX, _SY, _AREA, _HUE, _W = range(7)


@dataclass(frozen=True, eq=False, repr=False)
class VideoTrack(Track):
    """A :class:`Track` read from a video by :func:`track`, with what the tracking found.

    ``t``, ``c``, ``m`` (lab metres: x right, y up, the camera's axes) hold the frames where
    both dots were found; ``c_err`` and ``m_err`` (n, 2) their standard errors [m]. Every
    decoded frame: ``frame_t`` [s] and the dots' image positions ``axle_px``, ``marker_px``
    (N, 2; column, row from the top-left pixel's centre; NaN where lost). ``scale`` [px/m]
    and how it was set (``scale_from``); ``ramp_angle`` [rad] (the axle's rolling line in the
    image, below the horizontal in the direction of motion) with its standard error, and
    ``roll`` [rad] = ramp_angle - α when α was given (else NaN: a level camera shows
    the ramp at α); the dots' colours found (``#rrggbb``); ``release_t`` [s], the first
    frame kept when a wait before the release was left out (else NaN). ``scale_err``
    [px/m] is the scale's standard error from the spread of the dots' distance (0 when
    ``scale`` was given; the error of ``marker_radius`` itself adds to it): a scale off by
    a fraction e makes rolling look like a slip of e times the distance rolled.
    """

    c_err: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 2)))
    m_err: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 2)))
    frame_t: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    axle_px: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 2)))
    marker_px: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 2)))
    size: tuple[int, int] = (0, 0)
    scale: float = math.nan
    scale_err: float = 0.0
    scale_from: str = ""
    ramp_angle: float = math.nan
    ramp_angle_err: float = math.nan
    roll: float = math.nan
    axle_color: str = ""
    marker_color: str = ""
    release_t: float = math.nan

    @property
    def lost(self) -> NDArray[np.intp]:
        """The decoded frames left out of the track (a dot lost, or a wait before release)."""
        kept = np.isin(self.frame_t, self.t)
        return np.flatnonzero(~kept)

    def summary(self) -> list[str]:
        """The tracking's report, one line each (the command line prints it)."""
        n_all = self.frame_t.size
        lines = [
            f"{self.source}: {n_all} frames at {1 / self.dt:.4g} fps, {self.size[0]}x"
            f"{self.size[1]} px; {self.n} tracked, {_spans(self.lost)} left out",
            f"dots: axle {self.axle_color}, marker {self.marker_color}; centroid error "
            f"median {np.median(np.hypot(*self.c_err.T)) * self.scale:.2g} px (axle)",
            f"scale {self.scale:.6g} +- {self.scale_err:.2g} px/m ({self.scale_from})",
            f"ramp line at {math.degrees(self.ramp_angle):.3f} +- "
            f"{math.degrees(self.ramp_angle_err):.3f} deg in the image"
            + (
                f"; camera roll {math.degrees(self.roll):+.3f} deg against alpha"
                if math.isfinite(self.roll)
                else ""
            ),
        ]
        if math.isfinite(self.release_t):
            lines.append(
                f"the body waits until t = {self.release_t:.4f} s: earlier frames left out"
            )
        return lines

    def __repr__(self) -> str:
        return "VideoTrack(" + "; ".join(self.summary()) + ")"

    def to_dict(self) -> dict[str, Any]:
        """The tracking's report, JSON-ready (angles in degrees, NaN as None)."""

        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {
            "source": self.source,
            "frames": int(self.frame_t.size),
            "tracked": self.n,
            "left_out": [int(k) for k in self.lost],
            "fps": 1.0 / self.dt,
            "size": list(self.size),
            "scale": self.scale,
            "scale_err": self.scale_err,
            "scale_from": self.scale_from,
            "centroid_err_px": float(np.median(np.hypot(*self.c_err.T)) * self.scale),
            "ramp_angle_deg": math.degrees(self.ramp_angle),
            "ramp_angle_err_deg": math.degrees(self.ramp_angle_err),
            "roll_deg": num(math.degrees(self.roll)),
            "axle_color": self.axle_color,
            "marker_color": self.marker_color,
            "release_t": num(self.release_t),
        }

    def save(self, path: str | os.PathLike[str], *, overwrite: bool = False) -> Path:
        """Write the track as a CSV that ``eccjump analyze`` and :func:`eccjump.analyze`
        read: ``#`` lines with :meth:`summary`, then ``t,xc,yc,xm,ym`` [s, m] and the
        standard errors ``xc_err,yc_err,xm_err,ym_err`` [m] of the tracked frames. The file
        appears whole or not at all; one already at ``path`` is replaced if it is a track
        this method wrote (its first line says so), else only with ``overwrite=True``
        (ValueError naming ``path`` otherwise)."""
        target = Path(path_arg("path", path))
        check_overwrite(
            target,
            overwrite=flag("overwrite", overwrite),
            option="overwrite=True",
            ours=is_track_file,
            what="a track of eccjump track",
            name="path",
        )
        tmp = store.temp_sibling(target)
        try:
            tmp.write_text(self.csv(), encoding="utf-8")
            store.install(tmp, target)
        except OSError as err:  # the user's path, not the temporary one
            raise OSError(err.errno, err.strerror or str(err), str(target)) from err
        finally:
            store.remove(tmp)
        return target

    def csv(self) -> str:
        """The text :meth:`save` writes."""
        head = [HEADER + line for line in self.summary()]
        head.append("t,xc,yc,xm,ym,xc_err,yc_err,xm_err,ym_err")
        table = np.column_stack([self.t, self.c, self.m, self.c_err, self.m_err])
        rows = (
            f"{r[0]:.10f}," + ",".join(f"{v:.8f}" for v in r[1:5]) + ","
            + ",".join(f"{v:.2e}" for v in r[5:])
            for r in table
        )  # fmt: skip
        return "\n".join([*head, *rows]) + "\n"


#: The first line of a track file that :meth:`VideoTrack.save` writes.
HEADER = "# eccjump track: "


def is_track_file(path: Path) -> bool:
    """Whether the regular file ``path`` is a track :meth:`VideoTrack.save` wrote (by its
    first bytes: the overwrite policy recognises a writer's own files by content)."""
    try:
        with open(path, "rb") as f:
            return f.read(len(HEADER)) == HEADER.encode()
    except OSError:
        return False


def _spans(frames: NDArray[np.intp]) -> str:
    """Frame numbers as ranges: "none", "3", "3-5, 9"."""
    if frames.size == 0:
        return "none"
    cuts = np.flatnonzero(np.diff(frames) > 1) + 1
    parts = [f"{g[0]}" if g.size == 1 else f"{g[0]}-{g[-1]}" for g in np.split(frames, cuts)]
    text = ", ".join(parts[:6]) + (", ..." if len(parts) > 6 else "")
    return f"{frames.size} ({text})"


@fill
def track(
    video: str | os.PathLike[str],
    *,
    marker_radius: float | None = None,
    scale: float | None = None,
    axle_color: Color | None = None,
    marker_color: Color | None = None,
    alpha: float | None = None,
    start: float | None = None,
    end: float | None = None,
    progress: Callable[[int, int], object] | None = None,
) -> VideoTrack:
    """Track the axle's and the marker's dots through a video of the experiment.

    Parameters
    ----------
    video : str or path
        A video file FFmpeg reads (MP4, MOV, MKV, AVI, ...; a regular file).
    marker_radius : float or None
        The marker dot's distance from the axle's [m], in (0, 20]: sets the scale from the
        dots' median distance in the image. One of ``marker_radius`` and ``scale`` is due.
    scale : float or None
        Pixels per metre, in [1, 1e9] (wins over ``marker_radius``).
    axle_color, marker_color : str, (r, g, b) or None
        The dots' colours: a name (``"red"``, ``"orange"``, ``"yellow"``, ``"green"``,
        ``"cyan"``, ``"blue"``, ``"purple"``, ``"magenta"``), ``"#rrggbb"`` or three ints in
        0..255. None finds them: the two colours that move together, the axle's the one
        that moves on a straight line.
    alpha : float or None
        The ramp angle [rad], in [0, π/2]: the camera's roll is then reported (the rolling
        line's angle in the image minus α). The track is not rotated.
    start, end : float or None
        Track only the frames between the times start and end [s] of the video (at most
        10,000 frames).
    progress : callable or None
        Called as ``progress(frames_done, frames_expected)`` (the expected count is 0 if
        the container does not say).

    Returns
    -------
    VideoTrack
        A :class:`Track` (``eccjump.analyze`` takes it) with the tracking's findings.

    Raises
    ------
    ValueError
        For a file that is no video, holds no frames, too many or too large ones, shows
        fewer than two moving dots of distinct colours, or no dot of a colour named; and for
        a parameter outside its range. The message names the file or the parameter.
    %(type_error)s
    ImportError
        Without PyAV or scipy (``pip install eccjump[video]``).

    Examples
    --------
    A video of a simulated run (``render_video``: H.264, motion blur, sensor noise), its
    dots tracked to within a fraction of a pixel:

    >>> import math, tempfile, eccjump
    >>> from eccjump.studies.experiment import render_video
    >>> body = eccjump.Cylinder(0.10927, 0.0777)
    >>> clip = render_video(tempfile.mkdtemp() + "/clip.mp4", body, math.radians(66.087),
    ...                     mu_s=1.2, size=(640, 360), marker_radius=0.035, dot_radius=0.2)
    >>> tr = eccjump.track(clip.path, marker_radius=0.035, alpha=math.radians(66.087))
    >>> tr.n == clip.t.size, bool(abs(tr.scale / clip.scale - 1) < 0.01)
    (True, True)
    >>> bool(abs(tr.axle_px - clip.axle_px).max() < 0.5)
    True
    >>> bool(abs(math.degrees(tr.roll)) < 0.2)  # the camera is level
    True
    """
    sc = None if scale is None else in_range("scale", scale)
    r_m = None if marker_radius is None else _marker_radius(marker_radius)
    if sc is None and r_m is None:
        raise ValueError("marker_radius [m] or scale [px/m] is due: the track is in metres")
    a = None if alpha is None else in_range("alpha", alpha)
    colors = (_color("axle_color", axle_color), _color("marker_color", marker_color))
    if colors[0] is not None and colors[0] == colors[1]:
        raise ValueError("axle_color and marker_color name the same colour: the dots differ")
    t0 = -math.inf if start is None else real("start", start)
    t1 = math.inf if end is None else real("end", end)
    if not t0 < t1:
        raise ValueError(f"start = {short(t0)} s must be before end = {short(t1)} s")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable, not {type(progress).__name__}")
    scan = _scan(video, t0, t1, progress)
    return _assemble(scan, colors, r_m, sc, a)


def _marker_radius(value: object) -> float:
    v = real("marker_radius", value)
    if not 0 < v <= 20.0:
        raise ValueError(f"marker_radius = {short(v)} m is outside the allowed range (0, 20] m")
    return v


def _color(name: str, value: object) -> tuple[int, int, int] | None:
    """A colour argument as (r, g, b) in 0..255, saturated enough to be a dot's."""
    if value is None:
        return None
    if isinstance(value, str):
        key = value.strip().lower()
        hexa = key.removeprefix("#")
        if key in COLORS:
            rgb = COLORS[key]
        elif len(hexa) == 6 and all(ch in "0123456789abcdef" for ch in hexa):
            rgb = (int(hexa[:2], 16), int(hexa[2:4], 16), int(hexa[4:], 16))
        else:
            names = ", ".join(COLORS)
            raise ValueError(f"{name}: {short(value)} is not a colour: {names}, or #rrggbb")
    elif isinstance(value, Sequence) and len(value) == 3:
        if not all(isinstance(v, int | np.integer) and not isinstance(v, bool) for v in value):
            raise TypeError(f"{name} must be a name, '#rrggbb' or 3 ints in 0..255")
        rgb = (int(value[0]), int(value[1]), int(value[2]))
        if not all(0 <= v <= 255 for v in rgb):
            raise ValueError(f"{name}: {short(tuple(value))} has a value outside 0..255")
    else:
        raise TypeError(f"{name} must be a name, '#rrggbb' or 3 ints in 0..255, not {short(value)}")
    if math.hypot(*_cbcr(rgb)) < MIN_COLOR_CHROMA:
        raise ValueError(
            f"{name}: {_hex(rgb)} is too pale or grey for a dot (a chroma of at least "
            f"{MIN_COLOR_CHROMA} is due)"
        )
    return rgb


def _hex(rgb: Sequence[float]) -> str:
    return "#" + "".join(f"{round(min(max(float(v), 0.0), 255.0)):02x}" for v in rgb)


def _cbcr(rgb: Sequence[float]) -> tuple[float, float]:
    """The chroma offsets (Cb, Cr) of an (r, g, b) colour (BT.601, full range)."""
    r, g, b = (float(v) for v in rgb)
    return -0.168736 * r - 0.331264 * g + 0.5 * b, 0.5 * r - 0.418688 * g - 0.081312 * b


def _rgb(y: float, cb: float, cr: float) -> tuple[float, float, float]:
    """(r, g, b) of a luma and chroma offsets (BT.601, full range): for the report."""
    return y + 1.402 * cr, y - 0.344136 * cb - 0.714136 * cr, y + 1.772 * cb


def hue(rgb: Sequence[float]) -> float:
    """The hue of an (r, g, b) colour [deg, 0..360): the angle of its chroma offsets, the
    hue the tracker reads from a video's colour planes."""
    cb, cr = _cbcr(rgb)
    return math.degrees(math.atan2(cr, cb)) % 360.0


def _hue_gap(a: NDArray[np.float64] | float, b: float) -> NDArray[np.float64]:
    """The distance of hues on the colour circle [deg]."""
    d = np.abs(np.asarray(a, dtype=np.float64) - b) % 360.0
    return np.minimum(d, 360.0 - d)


#: The suffixes of video files (``eccjump analyze`` takes such a file as a video).
VIDEO_SUFFIXES = frozenset(
    ".mp4 .m4v .mov .qt .mkv .webm .avi .mts .m2ts .ts .3gp .mpg .mpeg .wmv .asf .flv .ogv".split()
)
#: The first bytes of the video containers FFmpeg reads, whatever the file's suffix: (offset,
#: bytes). ISO media (MP4, MOV, 3GP) name their brand at offset 4.
_MAGIC = (
    (4, b"ftyp"), (4, b"moov"), (4, b"mdat"), (0, b"\x1a\x45\xdf\xa3"), (8, b"AVI "),
    (0, b"OggS"), (0, b"FLV"), (0, b"\x00\x00\x01\xba"), (0, b"\x30\x26\xb2\x75"),
)  # fmt: skip


def is_video(path: object) -> bool:
    """Whether ``path`` names a video: by its suffix, or by the first bytes of a regular file
    (a FIFO or a device is not opened: not a video)."""
    if not isinstance(path, str | os.PathLike) or isinstance(os.fspath(path), bytes):
        return False
    if Path(path).suffix.lower() in VIDEO_SUFFIXES:
        return True
    try:
        with open_binary("video", path) as f:
            head = f.read(16)
    except (ValueError, OSError):
        return False
    return any(head[at : at + len(magic)] == magic for at, magic in _MAGIC)


# --- reading: one frame at a time, only the blobs kept -------------------------------------


@dataclass(frozen=True, eq=False)
class _Scan:
    """What the decoding keeps: the file's name, the frame times, each frame's blobs (rows of
    _X ... _W), the frame size and the mean colour of each blob (for the report)."""

    name: str
    t: NDArray[np.float64]
    blobs: list[NDArray[np.float64]]
    colors: list[NDArray[np.float64]]
    size: tuple[int, int]


def _scan(video: object, t0: float, t1: float, progress: Any) -> _Scan:
    av = require("av", purpose="reading videos", extra="video")
    ndimage = require("scipy.ndimage", purpose="tracking videos", extra="video")
    name = _shown(video)
    times: list[float] = []
    blobs: list[NDArray[np.float64]] = []
    colors: list[NDArray[np.float64]] = []
    size = (0, 0)
    with open_binary("video", video) as raw:
        try:
            container = av.open(raw, mode="r")
        except (av.FFmpegError, OSError, ValueError, EOFError) as err:
            raise ValueError(
                f"video: {name} is not a video FFmpeg can read ({_why(err)})"
            ) from None
        with container:
            if not container.streams.video:
                raise ValueError(f"video: {name} has no video frames (no video stream)")
            stream = container.streams.video[0]
            stream.thread_type = "AUTO"
            expected = _expected_frames(stream, t0, t1)
            for t, planes in _frames(av, container, stream, name, t0, t1):
                if len(times) == MAX_FRAMES:
                    raise ValueError(
                        f"video: {name} has more than {MAX_FRAMES:,} frames between start and "
                        "end: give a shorter span (start, end)"
                    )
                size = (planes[0].shape[1], planes[0].shape[0])
                found, tint = _frame_blobs(planes, ndimage)
                times.append(t)
                blobs.append(found)
                colors.append(tint)
                if progress is not None:
                    progress(len(times), max(expected, len(times)))
    if not times:
        raise ValueError(
            f"video: {name} has no video frames" + ("" if t0 == -math.inf else " after start")
        )
    return _Scan(name, np.array(times), blobs, colors, size)


def _shown(video: object) -> str:
    """The file's name for a message (its last 60 characters)."""
    text = os.fspath(video) if isinstance(video, str | os.PathLike) else repr(video)
    text = Path(str(text)).name or str(text)
    return text if len(text) <= 60 else "..." + text[-57:]


def _why(err: BaseException) -> str:
    text = getattr(err, "strerror", None) or str(err) or type(err).__name__
    return text.split(";")[0][:60]


def _expected_frames(stream: Any, t0: float, t1: float) -> int:
    """The frames the container announces (0 if it does not), within [t0, t1]."""
    n = int(stream.frames or 0)
    rate = float(stream.average_rate or 0)
    if rate > 0 and (math.isfinite(t0) or math.isfinite(t1)):
        duration = n / rate if n else math.inf
        span = min(t1, duration) - max(t0, 0.0)
        n = int(span * rate) + 1 if math.isfinite(span) else 0
    return max(n, 0)


def _frames(
    av: Any, container: Any, stream: Any, name: str, t0: float, t1: float
) -> Iterator[tuple[float, Planes]]:
    """(time [s] = pts × time_base, planes) of each frame in [t0, t1], one at a time."""
    if math.isfinite(t0) and t0 > 0 and stream.time_base:
        container.seek(int(t0 / stream.time_base), stream=stream, backward=True)
    last = -math.inf
    k = 0
    try:
        for frame in container.decode(stream):
            k += 1
            if frame.pts is None:
                raise ValueError(f"video: {name}: frame {k - 1} has no time stamp")
            t = float(frame.pts * stream.time_base)
            if t < t0:
                continue
            if t > t1:
                return
            if t <= last:
                raise ValueError(
                    f"video: {name}: frame {k - 1} at t = {t:.6g} s does not follow "
                    f"t = {last:.6g} s (times must increase)"
                )
            if frame.width * frame.height > MAX_PIXELS:
                raise ValueError(
                    f"video: {name}: frames of {frame.width}x{frame.height} px, more than "
                    f"the {MAX_PIXELS:,} pixels allowed"
                )
            last = t
            yield t, _planes(frame)
    except (av.FFmpegError, EOFError) as err:
        raise ValueError(f"video: {name}: cannot decode frame {k} ({_why(err)})") from None


def _planes(frame: Any) -> Planes:
    """The luma (H, W) and the chroma offsets Cb, Cr (each (H/2, W/2), 4:2:0) of a frame,
    in the orientation it is displayed in (a phone's rotation applied). Chroma is read from
    the colour planes, not from RGB: RGB clips where a dot meets white or black, which
    shifts its centroid."""
    if frame.format.name != "yuv420p":
        frame = frame.reformat(format="yuv420p")
    planes = []
    for plane in frame.planes:
        data = np.frombuffer(plane, dtype=np.uint8).reshape(-1, plane.line_size)
        planes.append(data[: plane.height, : plane.width])
    turn = round(float(getattr(frame, "rotation", 0) or 0) / 90.0) % 4
    y, cb, cr = (np.rot90(p, turn) if turn else p for p in planes)
    return y, cb.astype(np.float32) - 128.0, cr.astype(np.float32) - 128.0


def _frame_blobs(planes: Planes, ndimage: Any) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The compact coloured blobs of one frame: rows (_X ... _W) and their mean colours
    (r, g, b)."""
    chroma = np.hypot(planes[1], planes[2])
    labels, n = ndimage.label(chroma >= DETECT_CHROMA)
    rows: list[list[float]] = []
    tints: list[tuple[float, float, float]] = []
    if n:
        sizes = np.bincount(labels.ravel(), minlength=n + 1)[1:]
        slices = ndimage.find_objects(labels)
        for i in np.argsort(sizes)[::-1][: 4 * MAX_BLOBS]:
            got = _blob(planes, chroma, slices[i], labels[slices[i]] == i + 1, ndimage)
            if got is not None:
                rows.append(got[0])
                tints.append(got[1])
    if len(rows) > MAX_BLOBS:
        keep = np.argsort([-r[_W] for r in rows])[:MAX_BLOBS]
        rows, tints = [rows[i] for i in keep], [tints[i] for i in keep]
    return np.array(rows, dtype=np.float64).reshape(-1, 7), np.array(tints).reshape(-1, 3)


def _blob(
    planes: Planes,
    chroma: NDArray[np.float32],
    where: tuple[slice, slice],
    seed: NDArray[np.bool_],
    ndimage: Any,
) -> tuple[list[float], tuple[float, float, float]] | None:
    """One blob's row (in luma pixels) and mean colour, or None if it is cut by the frame's
    edge, too small or large, or not compact. Its pixels: the connected chroma above the
    weights' floor, in a box around the detection grown until it holds them."""
    h, w = chroma.shape
    for pad in (3, 12):
        y0, y1 = where[0].start - pad, where[0].stop + pad
        x0, x1 = where[1].start - pad, where[1].stop + pad
        if y0 < 0 or x0 < 0 or y1 > h or x1 > w:
            return None  # at the frame's edge: cut, its centroid would be biased
        roi = chroma[y0:y1, x0:x1]
        labels, _ = ndimage.label(roi > WEIGHT_CHROMA)
        core = labels[pad : pad + seed.shape[0], pad : pad + seed.shape[1]][seed]
        own = labels == np.bincount(core).argmax()  # the component that holds the detection
        if not (own[0].any() or own[-1].any() or own[:, 0].any() or own[:, -1].any()):
            break
    else:
        return None  # a large coloured region, not a dot
    rows_, cols_ = np.nonzero(own)
    area = rows_.size
    box = (np.ptp(rows_) + 1) * (np.ptp(cols_) + 1)
    if area < MIN_AREA or area > MAX_AREA * h * w or area < MIN_FILL * box:
        return None
    cb_roi, cr_roi = planes[1][y0:y1, x0:x1], planes[2][y0:y1, x0:x1]
    cb, cr = float(cb_roi[own].mean()), float(cr_roi[own].mean())
    x, y, sx, sy, total = _centroid(cb_roi, cr_roi, own, (cb, cr), ndimage)
    luma = float(planes[0][2 * (y0 + rows_), 2 * (x0 + cols_)].mean())
    # a chroma sample covers 2 x 2 luma pixels: its centre is at 2 j + 0.5 in theirs
    row = [2 * (x + x0) + 0.5, 2 * (y + y0) + 0.5, 2 * sx, 2 * sy, float(area),
           math.degrees(math.atan2(cr, cb)) % 360.0, total]  # fmt: skip
    return row, _rgb(luma, cb, cr)


def _centroid(
    cb: NDArray[np.float32],
    cr: NDArray[np.float32],
    own: NDArray[np.bool_],
    colour: tuple[float, float],
    ndimage: Any,
) -> tuple[float, float, float, float, float]:
    """(x, y) of a dot in its box's chroma samples, their standard errors and the summed
    weight. The weight of a sample is its chroma along the dot's own (Cb, Cr) direction:
    linear in the share of the sample the dot covers (white, grey and black have none),
    with zero-mean noise elsewhere, so every sample of a window around the dot counts, none
    cut at a threshold (a cut shifts the centroid of a dot two samples wide towards the
    grid's nearest sample)."""
    u = np.array(colour) / math.hypot(*colour)
    s = (u[0] * cb + u[1] * cr).astype(np.float64)
    window = ndimage.binary_dilation(own, iterations=WINDOW)
    rows_, cols_ = np.nonzero(window)
    wgt = s[window]
    total = float(wgt.sum())
    x, y = float(wgt @ cols_) / total, float(wgt @ rows_) / total
    rest = s[~window]
    sigma = 1.4826 * float(np.median(np.abs(rest - np.median(rest)))) if rest.size > 8 else 1.0
    sigma = max(sigma, 0.5)
    sx = sigma * math.sqrt(float(((cols_ - x) ** 2).sum())) / total
    sy = sigma * math.sqrt(float(((rows_ - y) ** 2).sum())) / total
    return x, y, sx, sy, total


# --- which blobs are the dots ---------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class _Path:
    """One colour followed through the frames: position, standard errors, area (NaN where
    not found) and the hue it was followed by."""

    hue: float
    p: NDArray[np.float64]
    err: NDArray[np.float64]
    area: NDArray[np.float64]
    twins: float  # the share of frames with a second blob of this colour as large

    @property
    def found(self) -> NDArray[np.bool_]:
        return np.isfinite(self.p[:, 0])

    @property
    def moves(self) -> bool:
        p = self.p[self.found]
        size = 2.0 * math.sqrt(float(np.nanmedian(self.area)) / math.pi)
        return p.shape[0] >= 2 and float(np.ptp(p, axis=0).max()) > max(3.0, size)


def _follow(blobs: list[NDArray[np.float64]], target: float) -> _Path:
    """The blob of hue ``target`` in each frame: the one nearest to where its path leads
    (the largest in the first frame, or after it was lost), within a gate of a few dot sizes
    plus its motion; none outside the gate."""
    n = len(blobs)
    p, err, area = np.full((n, 2), np.nan), np.full((n, 2), np.nan), np.full(n, np.nan)
    twins = 0
    sizes: list[float] = []
    last: NDArray[np.float64] | None = None
    vel = np.zeros(2)
    k_last = -1
    for k, rows in enumerate(blobs):
        mine = rows[_hue_gap(rows[:, _HUE], target) <= HUE_GAP] if rows.size else rows
        if mine.shape[0] == 0:
            continue
        big = np.sort(mine[:, _AREA])[::-1]
        twins += int(big.size >= 2 and big[1] >= 0.4 * big[0])
        if last is None:
            pick = int(np.argmax(mine[:, _W]))
        else:
            guess = last + vel * (k - k_last)
            dist = np.hypot(*(mine[:, :2] - guess).T)
            size = 2.0 * math.sqrt(float(np.median(sizes)) / math.pi)
            gate = 3.0 * size + 2.0 * float(np.hypot(*vel)) * (k - k_last) + 4.0
            pick = int(np.argmin(dist))
            if dist[pick] > gate:
                continue
        row = mine[pick]
        p[k], err[k], area[k] = row[[_X, _Y]], row[[_SX, _SY]], row[_AREA]
        sizes.append(float(row[_AREA]))
        if last is not None and k - k_last <= 3:
            vel = (p[k] - last) / (k - k_last)
        last, k_last = p[k].copy(), k
    return _Path(target, p, err, area, twins / max(1, int(np.isfinite(area).sum())))


def _colours(blobs: list[NDArray[np.float64]]) -> list[float]:
    """The hues of the colours that appear in at least a third of the frames, the most
    frequent first: blob hues split where the colour circle has a gap of HUE_GAP."""
    per_frame = [np.unique(np.round(r[:, _HUE])) for r in blobs if r.size]
    if not per_frame:
        return []
    hues = np.sort(np.concatenate(per_frame))
    gaps = np.diff(np.r_[hues, hues[0] + 360.0])
    cuts = np.flatnonzero(gaps > HUE_GAP)
    if cuts.size == 0:
        groups = [hues]
    else:
        rolled = np.roll(hues, -(cuts[-1] + 1))
        bounds = np.flatnonzero(_hue_gap(np.diff(rolled), 0.0) > HUE_GAP) + 1
        groups = np.split(rolled, bounds)
    found = []
    for g in groups:
        angle = np.angle(np.exp(1j * np.radians(g)).mean())
        frames = sum(bool((_hue_gap(f, math.degrees(angle)) <= HUE_GAP).any()) for f in per_frame)
        if frames >= len(blobs) / 3:
            found.append((frames, math.degrees(angle) % 360.0))
    return [h for _, h in sorted(found, reverse=True)]


def _name(h: float) -> str:
    """The nearest colour name of a hue (for messages)."""
    return min(COLORS, key=lambda k: float(_hue_gap(hue(COLORS[k]), h)))


def _pick_dots(
    scan: _Scan, given: tuple[tuple[int, int, int] | None, tuple[int, int, int] | None]
) -> tuple[_Path, _Path]:
    """The axle's and the marker's paths (module docstring)."""
    name = scan.name
    paths = {h: _follow(scan.blobs, h) for h in _colours(scan.blobs)}
    for key, rgb in zip(("axle_color", "marker_color"), given, strict=True):
        if rgb is not None and not any(_hue_gap(h, hue(rgb)) <= COLOR_MATCH for h in paths):
            seen = ", ".join(_name(h) for h in paths) or "none"
            raise ValueError(f"{key}: no dot of colour {_hex(rgb)} in {name}; dots seen: {seen}")
    moving = [p for p in paths.values() if p.moves]
    if len(moving) < 2:
        raise ValueError(_too_few(name, moving))
    fixed = [None if rgb is None else _nearest(moving, hue(rgb)) for rgb in given]
    pair = _rigid_pair(moving, fixed, name)
    if fixed[0] is not None:
        axle = fixed[0]
    elif fixed[1] is not None:
        axle = pair[0] if pair[1] is fixed[1] else pair[1]
    else:
        axle = _straighter(pair, name)
    return axle, pair[1] if axle is pair[0] else pair[0]


def _nearest(paths: list[_Path], h: float) -> _Path:
    return min(paths, key=lambda p: float(_hue_gap(p.hue, h)))


def _too_few(name: str, moving: list[_Path]) -> str:
    if not moving:
        return (
            f"video: {name}: no moving dot of a saturated colour found (two are due, on the "
            "end face: the axle's and the marker's, each 3 px across or more)"
        )
    only = moving[0]
    colour = _name(only.hue)
    if only.twins > 0.5:
        return (
            f"video: {name}: both dots seem to have one colour, {colour}: paint them in "
            "two distinct colours"
        )
    return (
        f"video: {name}: only one moving dot found, {colour}: the marker or the axle's is missing"
    )


def _rigid_pair(moving: list[_Path], fixed: list[_Path | None], name: str) -> tuple[_Path, _Path]:
    """The two paths that keep their distance over most frames (and include the ones the
    colours fixed)."""
    scored: list[tuple[tuple[bool, int, float], _Path, _Path]] = []
    for i, a in enumerate(moving):
        for b in moving[i + 1 :]:
            if any(f is not None and f is not a and f is not b for f in fixed):
                continue
            both = a.found & b.found
            if both.sum() < MIN_FRAMES:
                continue
            d = np.hypot(*(a.p[both] - b.p[both]).T)
            spread = float(np.median(np.abs(d - np.median(d))) / max(np.median(d), 1e-9))
            scored.append(((spread > RIGID, -int(both.sum()), spread), a, b))
    if not scored or min(x[0] for x in scored)[0]:
        colours = ", ".join(_name(p.hue) for p in moving)
        raise ValueError(
            f"video: {name}: no two moving dots keep their distance (seen: {colours}): "
            "are both on the body's end face?"
        )
    _, a, b = min(scored, key=lambda x: x[0])
    return a, b


def _straighter(pair: tuple[_Path, _Path], name: str) -> _Path:
    """The path that is a straight line, by its residual about its own line, over the first
    40 % of the frames where both dots are found and on the move (the body rolls there; a
    wait before the release says nothing)."""
    both = pair[0].found & pair[1].found
    idx = np.flatnonzero(both)
    mid = (pair[0].p[idx] + pair[1].p[idx]) / 2
    moved = np.hypot(*(mid - np.median(mid[:5], axis=0)).T) > 2.0
    idx = idx[int(np.argmax(moved)) :] if moved.any() else idx
    idx = idx[: max(MIN_FRAMES, int(0.4 * idx.size))]
    res = [_line_residual(p.p[idx]) for p in pair]
    if max(res) < STRAIGHTER * min(res):
        raise ValueError(
            f"video: {name}: cannot tell the axle's dot from the marker's (both paths are "
            "about as straight): give axle_color"
        )
    return pair[int(np.argmin(res))]


def _line_residual(p: NDArray[np.float64]) -> float:
    """The RMS distance of points from their total-least-squares line."""
    q = p - p.mean(axis=0)
    return float(np.linalg.svd(q, compute_uv=False)[-1] / math.sqrt(max(len(q), 1)))


# --- the track ------------------------------------------------------------------------------


def _assemble(
    scan: _Scan,
    given: tuple[tuple[int, int, int] | None, tuple[int, int, int] | None],
    marker_radius: float | None,
    scale: float | None,
    alpha: float | None,
) -> VideoTrack:
    axle, marker = _pick_dots(scan, given)
    c_px, m_px = _usable(axle), _usable(marker)
    both = np.isfinite(c_px[:, 0]) & np.isfinite(m_px[:, 0])
    dist = np.hypot(*(c_px - m_px).T)
    d0 = float(np.median(dist[both])) if both.any() else math.nan
    off = both & (np.abs(dist - d0) > max(3.0, 0.15 * d0))  # one of them is not its dot
    c_px[off], m_px[off] = np.nan, np.nan
    both &= ~off
    begin = release_frame(scan.t, c_px, REACH * d0)  # (the dots' distance: a little under R)
    keep = both & (np.arange(both.size) >= begin)
    if keep.sum() < MIN_FRAMES:
        raise ValueError(
            f"video: {scan.name}: both dots found in {int(keep.sum())} frames, fewer than the "
            f"{MIN_FRAMES} a track needs"
        )
    # the statistics of the frames kept: a wait before the release repeats one frame
    d0 = float(np.median(dist[keep]))
    kept = [np.where(keep[:, None], p, np.nan) for p in (c_px, m_px, axle.err, marker.err)]
    widen = _error_scale((kept[0], kept[1]), (kept[2], kept[3]))
    if scale is not None:
        px, px_err, how = scale, 0.0, "given"
    else:
        px = d0 / float(marker_radius)  # type: ignore[arg-type]
        px_err = px * _median_error(dist[keep]) / d0
        how = f"dots {d0:.2f} px apart, marker_radius"
    height = scan.size[1]

    def lab(p: NDArray[np.float64]) -> NDArray[np.float64]:  # image rows grow downwards
        return np.column_stack([p[keep, 0], height - 1 - p[keep, 1]]) / px

    c = lab(c_px)
    ramp, ramp_err = _ramp_line(c, float(np.median(widen * axle.err[keep])) / px)
    return VideoTrack(
        t=scan.t[keep],
        c=c,
        m=lab(m_px),
        source=scan.name,
        c_err=widen * axle.err[keep] / px,
        m_err=widen * marker.err[keep] / px,
        frame_t=scan.t,
        axle_px=c_px,
        marker_px=m_px,
        size=scan.size,
        scale=float(px),
        scale_err=float(px_err),
        scale_from=how,
        ramp_angle=ramp,
        ramp_angle_err=ramp_err,
        roll=math.nan if alpha is None else ramp - alpha,
        axle_color=_mean_colour(scan, axle),
        marker_color=_mean_colour(scan, marker),
        release_t=float(scan.t[begin]) if begin > 0 else math.nan,
    )


def _error_scale(
    paths: tuple[NDArray[np.float64], ...], errs: tuple[NDArray[np.float64], ...]
) -> float:
    """The factor (at least 1) that brings the centroids' standard errors from the pixel
    noise up to their scatter along the paths: the robust spread of third differences of
    four consecutive frames (20 sigma² for independent noise; the smooth motion's share is
    small at a camera's frame rates, and an impact's is an outlier the median ignores). The
    codec correlates neighbouring pixels, which the pixel-noise errors ignore."""
    d3 = np.concatenate([np.diff(p, n=3, axis=0).ravel() for p in paths])
    d3 = d3[np.isfinite(d3)]
    if d3.size < 8:
        return 1.0
    scatter = 1.4826 * float(np.median(np.abs(d3))) / math.sqrt(20.0)
    typical = float(np.nanmedian(np.concatenate([e.ravel() for e in errs])))
    return max(1.0, scatter / typical) if typical > 0 else 1.0


def _ramp_line(c: NDArray[np.float64], noise: float) -> tuple[float, float]:
    """The angle [rad] below the horizontal, in the direction of motion, of the axle's
    rolling line, and its standard error: the straight line through the axle's positions in
    contact (C is R above the ramp there), found from the track's first half and then from
    every frame within 4 noise levels of it (a flight is above it), refitted. The noise is
    the larger of the scatter about the line and the centroids' error ``noise``: still
    frames at the start scatter less than the rolling ones."""
    use = np.arange(c.shape[0]) < max(MIN_FRAMES, c.shape[0] // 2)
    for _ in range(8):
        centre = c[use].mean(axis=0)
        _, _, vt = np.linalg.svd(c[use] - centre, full_matrices=False)
        along, normal = vt[0], vt[1]
        res = (c - centre) @ normal
        sigma = max(1.4826 * float(np.median(np.abs(res[use]))), noise)
        new = np.abs(res) <= 4.0 * sigma
        if (new == use).all() or new.sum() < MIN_FRAMES:
            break
        use = new
    along = along if along @ (c[-1] - c[0]) >= 0 else -along
    s = (c[use] - centre) @ along
    spread = float(((s - s.mean()) ** 2).sum())
    err = sigma / math.sqrt(spread) if spread > 0 else math.inf
    return math.atan2(-along[1], abs(along[0])), err


def _median_error(x: NDArray[np.float64]) -> float:
    """The standard error of the median of a series whose neighbours correlate: that of
    independent normal draws (1.25 sigma / sqrt n) over the effective number of draws
    n (1 - r) / (1 + r), r the lag-one correlation."""
    if x.size < 3:
        return math.inf
    sigma = 1.4826 * float(np.median(np.abs(x - np.median(x))))
    d = x - x.mean()
    r = float(d[1:] @ d[:-1] / (d @ d)) if d @ d > 0 else 0.0
    n_eff = x.size * (1 - max(r, 0.0)) / (1 + max(r, 0.0))
    return 1.2533 * sigma / math.sqrt(max(n_eff, 1.0))


def _usable(path: _Path) -> NDArray[np.float64]:
    """The path's positions, lost where its blob is less than half its median size (partly
    hidden: its centroid would be biased)."""
    p = path.p.copy()
    p[path.area < 0.5 * np.nanmedian(path.area)] = np.nan
    return p


def _mean_colour(scan: _Scan, path: _Path) -> str:
    """The mean colour of the blobs followed by ``path`` (#rrggbb)."""
    tints = [
        c[np.argmin(np.hypot(*(b[:, :2] - p).T))]
        for b, c, p in zip(scan.blobs, scan.colors, path.p, strict=True)
        if np.isfinite(p[0]) and b.size
    ]
    return _hex(np.mean(tints, axis=0)) if tints else ""


__all__ = ["COLORS", "VIDEO_SUFFIXES", "Color", "VideoTrack", "is_track_file", "is_video", "track"]
