"""From a lab video to a verdict: track the axle's and the marker's dots through the video
(``eccjump.track``, module ``video``; ``render_video`` films a simulated run) or read a
tracked experiment (axle and marker, module ``track``), reconstruct
θ, l, b in the ramp frame, detect and time slip, lift-off and landing, fit the model
(``eccjump.simulate``) and say whether the body jumped straight out of pure rolling
(the site's page "Analysing an experiment"). The fit needs scipy
(``pip install eccjump[analysis]``).
"""

from eccjump.studies.experiment.analysis import Analysis, analyze
from eccjump.studies.experiment.reconstruction import Reconstruction, reconstruct
from eccjump.studies.experiment.render import RenderedVideo, render_video
from eccjump.studies.experiment.synthetic import SyntheticTrack, synthetic_track
from eccjump.studies.experiment.track import Track, read_track, track_from_arrays
from eccjump.studies.experiment.verdict import VERDICTS
from eccjump.studies.experiment.video import VideoTrack

__all__ = [
    "VERDICTS",
    "Analysis",
    "Reconstruction",
    "RenderedVideo",
    "SyntheticTrack",
    "Track",
    "VideoTrack",
    "analyze",
    "read_track",
    "reconstruct",
    "render_video",
    "synthetic_track",
    "track_from_arrays",
]
