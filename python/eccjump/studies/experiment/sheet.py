"""The inputs an ``eccjump design --json`` sheet gives the analysis: the body (χ, km), the
radius R [m] when the design was made in metres, the ramp angle, and the static friction
the design was made for (``friction.measured_friction``)."""

from __future__ import annotations

import json
import math
import os
from typing import Any

from eccjump._base.checks import short
from eccjump._base.userfiles import read_text


def design_inputs(design: str | os.PathLike[str] | dict[str, Any]) -> dict[str, float]:
    """{"χ", "km", "α" [rad], and "radius" [m], "mu_s" and "mu_s_err" where the sheet has
    them} from a design sheet (a path to its JSON, or the dict of ``Design.to_dict()``)."""
    if isinstance(design, str | os.PathLike):
        text = read_text("design", design)  # the guard of every user's file
        try:
            sheet = json.loads(text)
        except (ValueError, RecursionError):  # an int of 5000 digits; [[[[... nested deep
            raise ValueError(f"design: {str(design)[-80:]} is not a JSON design sheet") from None
    elif isinstance(design, dict):
        sheet = design
    else:
        raise TypeError(f"design must be a path or a dict, not {type(design).__name__}")
    body = sheet.get("body") if isinstance(sheet, dict) else None
    if not isinstance(body, dict) or "chi" not in body or "km" not in body:
        raise ValueError("design: the sheet has no body with chi and km (eccjump design --json)")
    out = {"chi": _number(body["chi"], "chi"), "km": _number(body["km"], "km")}
    if body.get("radius") is not None:
        out["radius"] = _number(body["radius"], "radius")
    if sheet.get("alpha_deg") is not None:
        out["alpha"] = math.radians(_number(sheet["alpha_deg"], "alpha_deg"))
    for name in ("mu_s", "mu_s_err"):  # the friction the body was designed for
        if sheet.get(name) is not None:
            out[name] = _number(sheet[name], name)
    return out


def _number(value: Any, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"design: {name} in the sheet is not a number: {str(value)[:30]}")
    try:
        return float(value)
    except OverflowError:
        raise ValueError(f"design: {name} in the sheet is beyond float64: {short(value)}") from None
