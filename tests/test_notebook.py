"""Notebook output: every result has a ``_repr_html_`` (a table of its key numbers, a small
picture where one says more), a text repr within one screen, and ``.plot()`` where a figure
exists."""

from __future__ import annotations

import math
import re
from html.parser import HTMLParser

import numpy as np
import pytest
from reference_points import JARM_BODY

import eccjump
from eccjump._base.palette import JARM_COLOR, MODE_COLORS

BODY = eccjump.Cylinder(*JARM_BODY)


class Balanced(HTMLParser):
    """Counts open tags, failing on a closing tag that closes nothing open."""

    VOID = frozenset({"br", "rect", "img"})

    def __init__(self) -> None:
        super().__init__()
        self.stack: list[str] = []

    def handle_starttag(self, tag, attrs):
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        pass

    def handle_endtag(self, tag):
        if tag in self.VOID:
            return
        assert self.stack and self.stack[-1] == tag, f"</{tag}> closes {self.stack[-1:]}"
        self.stack.pop()


def results() -> dict[str, object]:
    alpha = np.radians(np.linspace(20.0, 70.0, 12))
    return {
        "Cylinder": BODY,
        "RollResult": eccjump.roll(BODY, 0.7, mu_s=1.0),
        "MotionResult": eccjump.simulate(BODY, 0.7, mu_s=1.0),
        "JarmResult": eccjump.jarm(0.7, *JARM_BODY, 1.0),
        "JarmResult[]": eccjump.jarm([0.7, 0.2], *JARM_BODY, 1.0),
        "Region": eccjump.region(alpha, np.linspace(0.05, 0.4, 10), [0.05, 0.2], 2.0),
        "MotionMap": eccjump.motion_map(alpha, [0.1, 0.3], 0.1, 2.0),
        "StartMap": eccjump.start_map(1.0, [0.0, 4.7], [0.0, 1.0], grid=4),
        "Design": eccjump.design((math.radians(30), math.radians(60)), 1.0, grid=6),
    }


@pytest.fixture(scope="module")
def every() -> dict[str, object]:
    return results()


NAMES = ["Cylinder", "RollResult", "MotionResult", "JarmResult", "JarmResult[]", "Region",
         "MotionMap", "StartMap", "Design"]  # fmt: skip


@pytest.mark.parametrize("name", NAMES)
def test_every_result_has_a_balanced_html_view_and_a_short_text(every, name):
    obj = every[name]
    view = obj._repr_html_()
    parser = Balanced()
    parser.feed(view)
    assert parser.stack == [], f"unclosed {parser.stack}"
    assert view.startswith("<div") and "<table" in view
    text = repr(obj)
    assert len(text.splitlines()) <= 24 and len(text) <= 24 * 100, text[:200]
    assert "#" not in text  # no comment embedded mid-line


def test_the_views_show_the_key_numbers(every):
    r = every["MotionResult"]
    view = r._repr_html_()
    assert f"{math.degrees(r.flights[0].theta_liftoff):.6g} deg" in view
    assert r.status in view
    j = every["JarmResult"]
    assert f"{math.degrees(float(j.theta_J)):.6g} deg" in every["JarmResult"]._repr_html_()
    reg = every["Region"]
    assert f"{reg.fraction():.4g}" in reg._repr_html_()


def test_the_mode_timeline_has_one_bar_per_mode_run(every):
    r = every["MotionResult"]
    bars = re.findall(r"<rect x='[^']*' y='0' [^>]*fill='(#[0-9a-fA-F]{6})'", r._repr_html_())
    runs = 1 + int(np.count_nonzero(np.diff(r.mode)))
    colors = MODE_COLORS  # the one palette (tests/test_plot.py)
    assert len(bars) == runs
    first = eccjump.motion.MODES[int(r.mode[0])]
    assert bars[0] == colors[first]


def test_the_region_picture_is_its_best_slice(every):
    reg = every["Region"]
    k = int(np.argmax(reg.is_jarm.sum(axis=(0, 1))))
    green = reg._repr_html_().count(f"fill='{JARM_COLOR}'")
    assert green == int(reg.is_jarm[:, :, k].sum()) > 0


def test_a_large_map_picture_stays_small():
    reg = eccjump.region(np.linspace(0.3, 1.3, 300), np.linspace(0.05, 0.4, 200), [0.1], 2.0)
    assert len(reg._repr_html_()) < 300_000


@pytest.mark.parametrize("name", ["RollResult", "MotionResult", "Region", "MotionMap", "StartMap"])
def test_plot_methods_give_a_figure(every, name):
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    fig = every[name].plot()
    assert isinstance(fig, Figure) and fig.axes
    plt.close(fig)
