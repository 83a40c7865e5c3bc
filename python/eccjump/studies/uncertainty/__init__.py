"""How sure is a jump? Monte Carlo and quasi-Monte Carlo studies of the JARM and of the
first flight under tolerances on the body, the ramp, the friction and the start.

- :mod:`.sampling`: which parameters vary and how, the unit-cube points and their inverse
  CDFs, the physical ranges;
- :mod:`.questions`: each sample's answer (the JARM classification or the full motion);
- :mod:`.results`: :class:`Uncertainty` and the Wilson interval;
- :mod:`.delta`: the place of the first-order (delta-method) estimate;
- :mod:`.indices`: which tolerance matters, the Sobol' indices (``indices=True``);
- :mod:`.study`: :func:`uncertainty`, which ties them together (:mod:`.scheduled`: its
  ``chunks=`` on Dask);
- :mod:`.map`: :func:`eccjump.uncertainty_map`, P(JARM) over a region grid (:mod:`.grid`: the
  batches; :mod:`.grid_motion`: those of the full motion; :mod:`.map_fields`: its map kinds).
"""

from eccjump.studies.uncertainty.results import Summary, Uncertainty, wilson
from eccjump.studies.uncertainty.study import uncertainty

__all__ = ["Summary", "Uncertainty", "uncertainty", "wilson"]
