"""From a lab video to a verdict: read a tracked experiment (axle and marker), reconstruct
theta, l, b in the ramp frame, detect and time slip, lift-off and landing, fit the model
(``eccjump.simulate``) and say whether the body jumped straight out of pure rolling
(``docs/analysis.md``). The fit needs scipy (``pip install eccjump[analysis]``).
"""

from eccjump.experiment.reconstruct import Reconstruction, reconstruct
from eccjump.experiment.track import Track, read_track, track_from_arrays

__all__ = ["Reconstruction", "Track", "read_track", "reconstruct", "track_from_arrays"]
