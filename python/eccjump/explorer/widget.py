"""``eccjump.explore()``: the explorer as a Jupyter widget (anywidget).

The widget runs the page's own script (``static/explorer.js``); its requests travel as the
widget's messages to the kernel, which answers them with :func:`api.handle`, the function
behind the local server. So the widget needs no port and no server, and works wherever the
notebook runs (JupyterLab, Notebook, VS Code, a remote or hosted kernel), where an iframe of a
server on the kernel's machine would not load.
"""

from __future__ import annotations

import functools
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from eccjump._base.checks import Rule, optional_real, real
from eccjump._base.units import FOR_DEGREES
from eccjump.explorer import api, controls
from eccjump.explorer.probability import checked_map
from eccjump.motion.options import MotionOptions

if TYPE_CHECKING:
    import anywidget

    from eccjump.studies.uncertainty.map import UncertaintyMap

STATIC = Path(__file__).parent / "static"


@functools.cache
def widget_class() -> type[anywidget.AnyWidget]:
    """The widget's class, made at first use (anywidget is an optional extra)."""
    try:
        import anywidget
        import traitlets
    except ImportError as err:
        raise ImportError("eccjump.explore needs anywidget: pip install eccjump[explore]") from err

    class Explorer(anywidget.AnyWidget):
        """The eccjump explorer; ``params`` holds the current point (the sliders' units:
        degrees, and strings as in a URL), kept in step with the sliders."""

        _esm = STATIC / "explorer.js"
        _css = STATIC / "explorer.css"
        params = traitlets.Dict().tag(sync=True)

        def __init__(self, uncertainty_map: UncertaintyMap | None = None, **kwargs: Any) -> None:
            super().__init__(**kwargs)
            # the P(JARM) panel's map stays in the kernel: the page asks for its slices
            self._uncertainty_map = uncertainty_map
            self.on_msg(self._answer)

        def _answer(self, _widget: object, content: object, _buffers: object) -> None:
            if not isinstance(content, dict) or content.get("kind") != "request":
                return
            query = content.get("query")
            query = {str(k): str(v) for k, v in query.items()} if isinstance(query, dict) else {}
            endpoint = str(content.get("endpoint"))
            status, body = api.handle(endpoint, query, self._uncertainty_map)
            self.send({"kind": "response", "id": content.get("id"), "status": status, "body": body})

    return Explorer


def explore(
    *,
    alpha: float = math.radians(40.0),
    chi: float = 0.15,
    km: float = 0.02,
    mu_s: float = 1.0,
    mu_k: float | None = None,
    restitution: float = 0.0,
    theta0: float = 0.0,
    omega0: float = 0.0,
    rule: Rule = "paper",
    t_max: float = 15.0,
    uncertainty: UncertaintyMap | str | os.PathLike | None = None,
) -> anywidget.AnyWidget:
    """The interactive explorer in a Jupyter notebook, starting at the given point.

    Sliders for every parameter below; the JARM region slice over (χ, α) at the current
    km and μ_s, the point marked (click the map to move it); the full motion of the point
    (:func:`eccjump.simulate`) as an animated cylinder on the ramp with its mode timeline; and its
    numbers (lift-off angle and time, slip onset, flight apex and distance). The same
    explorer runs as a local web page with ``eccjump explore`` (the user guide's page "The
    explorer"). The sliders show angles in degrees; here they are in radians, as everywhere
    in the Python API.

    Parameters
    ----------
    alpha : float, default radians(40)
        Ramp angle [rad], in [0, π/2].
    chi : float, default 0.15
        Offset of the centre of mass d/R, in [0, 1].
    km : float, default 0.02
        Shell mass fraction, in [0, 1]; a body needs km ≤ 1 - χ, and the explorer says so
        when it is not one.
    mu_s : float, default 1.0
        Static friction coefficient, in [0, 3].
    mu_k : float or None, default None
        Kinetic friction coefficient, in [0, 3]; None ties it to μ_s (a tick box unties it).
    restitution : float, default 0.0
        Energetic coefficient of restitution e of the landings, in [0, 1].
    theta0 : float, default 0.0
        Start angle [rad], in [-π, π].
    omega0 : float, default 0.0
        Start rate [√(g/R) rad], in [0, 3].
    rule : {"paper", "normal_force"}, default "paper"
        The lift-off rule from rolling.
    t_max : float, default 15.0
        Duration of the motion [√(R/g)], in [2, 60].
    uncertainty : UncertaintyMap, str, os.PathLike or None, default None
        A map of P(JARM) under tolerances (:func:`eccjump.uncertainty_map`), or the path of
        its file: shown beside the JARM region on the map's km_frac slice nearest to the
        current k_m / (1 − χ), with its 0.5 and 0.95 contours and the value under the
        cursor. None: no such panel.

    Returns
    -------
    anywidget.AnyWidget
        The explorer: display it (the last expression of a cell). Its ``params`` trait (the
        sliders' values as strings, angles in degrees) follows the sliders.

    Raises
    ------
    ValueError
        For a value outside its slider's range; the message names it, its range and unit.
        For an ``uncertainty`` file that is no uncertainty map (a map of another kind is
        named).
    TypeError
        For a value of a wrong type (a bool, a string, None where a number is due).
    OSError
        For an ``uncertainty`` file that cannot be read.
    ImportError
        Without anywidget: ``pip install "eccjump[explore]"``.

    See Also
    --------
    simulate : the full motion the explorer animates.
    region : JARM maps on any grid.

    Examples
    --------
    The paper's Fig. 3b body on a 30° ramp, in a notebook:

    >>> import math
    >>> import eccjump
    >>> w = eccjump.explore(alpha=math.radians(30), chi=0.5, km=0.4)  # doctest: +SKIP
    >>> w  # doctest: +SKIP

    A start outside the sliders' ranges is refused before anything is shown:

    >>> eccjump.explore(alpha=2.0)
    Traceback (most recent call last):
    ValueError: alpha = 2 rad is outside the explorer's range [0, 1.5708] rad (math.radians(...)
    """
    point = {
        "alpha": math.degrees(real("alpha", alpha)),
        "chi": real("chi", chi),
        "km": real("km", km),
        "mu_s": real("mu_s", mu_s),
        "mu_k": optional_real("mu_k", mu_k),
        "restitution": real("restitution", restitution),
        "theta0": math.degrees(real("theta0", theta0)),
        "omega0": real("omega0", omega0),
    }
    # The run's options, their types checked as simulate checks them; the sliders' ranges
    # below.
    run = MotionOptions(rule=rule, t_max=t_max)
    point["t_max"] = run.t_max
    controls.rule_checked(run.rule)
    for key, value in point.items():
        if value is not None:
            _in_range(key, value)
    tie = point["mu_k"] is None
    params = {k: repr(v) for k, v in point.items() if v is not None}
    params.update(rule=run.rule, tie="1" if tie else "0")
    umap = None if uncertainty is None else checked_map(uncertainty, "uncertainty")
    return widget_class()(umap, params=params)


def _in_range(key: str, value: float) -> None:
    """The slider's range check, its message in the Python API's units (radians)."""
    try:
        controls.checked(key, value)
    except ValueError:
        if key not in controls.ANGLES:
            raise
        c = controls.BY_KEY[key]
        raise ValueError(
            f"{key} = {math.radians(value):g} rad is outside the explorer's range "
            f"[{math.radians(c.lo):g}, {math.radians(c.hi):g}] rad ({FOR_DEGREES})"
        ) from None
