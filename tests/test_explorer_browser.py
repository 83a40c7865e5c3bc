"""The explorer in a real browser: Playwright drives Debian's headless Chromium
(``apt-get install chromium-headless-shell``; ``playwright install`` cannot download browsers
here) against ``ExplorerServer`` on a free port. The sliders are moved by keyboard, the map
is clicked, and the numbers and the pictures must change.

The time from an input to its redraw is measured and printed (``pytest -s``), never asserted:
the project has no timing asserts. Skipped, with the reason, without playwright or Chromium.

``python tests/test_explorer_browser.py DIR`` writes the screenshots of the docs to DIR
(docs/explorer).
"""

from __future__ import annotations

import os
import shutil
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from eccjump.explorer.server import ExplorerServer

pytestmark = pytest.mark.slow

sync_api = pytest.importorskip(
    "playwright.sync_api", reason="the browser test needs playwright: pip install playwright"
)


def chromium() -> str | None:
    """Debian's headless Chromium (or $ECCJUMP_CHROMIUM)."""
    return os.environ.get("ECCJUMP_CHROMIUM") or next(
        filter(None, map(shutil.which, ("chromium-headless-shell", "chromium"))), None
    )


if chromium() is None:
    pytest.skip(
        "no Chromium: apt-get install chromium-headless-shell (or set ECCJUMP_CHROMIUM)",
        allow_module_level=True,
    )

ROOT = ".ej-root"
#: The region map's plot area in canvas pixels (MAP in explorer.js).
MAP = {"width": 400, "height": 392, "x0": 50, "y0": 10, "w": 336, "h": 336}


@pytest.fixture(scope="module")
def browser() -> Iterator[Any]:
    with ExplorerServer(0) as server, sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=chromium())
        b.explorer_url = server.url
        yield b
        b.close()


@pytest.fixture
def page(browser: Any) -> Iterator[Any]:
    pg = browser.new_page(viewport={"width": 1280, "height": 900})
    errors: list[str] = []
    pg.on("pageerror", lambda err: errors.append(str(err)))
    pg.goto(browser.explorer_url)
    wait_settled(pg, 0)
    yield pg
    pg.close()
    assert not errors, errors


# --- helpers --------------------------------------------------------------------------------


def state(pg: Any) -> dict[str, Any]:
    return pg.eval_on_selector(
        ROOT,
        """e => ({settled: +e.dataset.settled, region: +e.dataset.regionDraws,
                  motion: +e.dataset.motionDraws, latency: +e.dataset.latencyMs})""",
    )


def wait_settled(pg: Any, before: int) -> dict[str, Any]:
    pg.wait_for_function(
        "n => +(document.querySelector('.ej-root')?.dataset.settled ?? 0) > n", arg=before
    )
    return state(pg)


def picture(pg: Any) -> dict[str, str]:
    """What is drawn: the map's pixels, the mode timeline, the numbers, the message."""
    return pg.evaluate(
        """() => ({
        map: document.querySelector('.ej-map').toDataURL(),
        timeline: document.querySelector('.ej-timeline').innerHTML,
        numbers: document.querySelector('.ej-numbers').innerText,
        message: document.querySelector('.ej-message').hidden ? ''
                 : document.querySelector('.ej-message').innerText,
        })"""
    )


def number(pg: Any, key: str) -> str:
    return pg.inner_text(f'.ej-numbers dd[data-key="{key}"]')


def value(pg: Any, key: str) -> str:
    return pg.inner_text(f'output[for$="-{key}"]')


LATENCIES: list[tuple[str, float, float]] = []


def act(pg: Any, what: str, action: Any) -> tuple[dict[str, str], dict[str, Any]]:
    """Do ``action``, wait until the page has answered and drawn it; log the time from the
    input to the redraw (the page's own measure, and the test's round trip)."""
    before = state(pg)["settled"]
    start = time.perf_counter()
    action()
    after = wait_settled(pg, before)
    LATENCIES.append((what, after["latency"], 1e3 * (time.perf_counter() - start)))
    print(f"redraw after {what}: {after['latency']:.0f} ms in the page, "
          f"{LATENCIES[-1][2]:.0f} ms seen by the test")  # fmt: skip
    return picture(pg), after


# --- the tests ------------------------------------------------------------------------------


def test_first_view_shows_the_readme_jump(page):
    assert number(page, "verdict").startswith("JARM")
    assert "θ = 334.34°" in number(page, "liftoff")
    assert "JARM" in page.inner_text(".ej-legend")
    assert value(page, "alpha") == "40.0°" and value(page, "omega0") == "0.00 √(g/R)"
    blank = page.evaluate(
        "() => { const c = document.createElement('canvas'); c.width = 400; c.height = 392;"
        " return c.toDataURL(); }"
    )
    assert picture(page)["map"] != blank
    assert page.locator(".ej-prob").is_hidden()  # no uncertainty map given: no such panel


def test_every_control_has_a_name_and_a_visible_value(page):
    controls = page.evaluate(
        """() => [...document.querySelectorAll('.ej-controls input, .ej-controls select')]
        .map(e => ({type: e.type, name: e.labels.length ? e.labels[0].innerText :
                    e.getAttribute('aria-label'),
                    shown: e.type === 'range' ?
                      document.querySelector(`output[for="${e.id}"]`).innerText : 'n/a'}))"""
    )
    ranges = [c for c in controls if c["type"] == "range"]
    assert len(ranges) == 9 and all(c["name"] for c in controls)
    assert all(c["shown"] for c in ranges)
    # and each is reachable by the keyboard
    page.focus(".ej-controls input[type=range]")
    for _ in range(3):
        page.keyboard.press("Tab")
    assert page.evaluate("document.activeElement.closest('.ej-controls') !== null")


def test_arrow_key_moves_alpha_and_redraws_the_motion(page):
    first = picture(page)
    regions = state(page)["region"]
    page.focus('input[name="alpha"]')
    shown, after = act(page, "ArrowRight on alpha", lambda: page.keyboard.press("ArrowRight"))
    assert value(page, "alpha") == "40.5°"
    assert shown["numbers"] != first["numbers"] and shown["timeline"] != first["timeline"]
    assert "θ = 334.34°" not in number(page, "liftoff")
    assert after["region"] == regions  # alpha moves the point on the map, not the map
    assert shown["map"] != first["map"]  # ... but the marker moved


def test_page_up_on_km_redraws_the_region(page):
    first = picture(page)
    page.focus('input[name="km"]')
    shown, _ = act(page, "PageUp on km", lambda: page.keyboard.press("PageUp"))
    assert float(value(page, "km")) > 0.02
    assert shown["map"] != first["map"] and shown["numbers"] != first["numbers"]
    assert f"k_m = {float(value(page, 'km')):g}" in page.inner_text(".ej-map-box .ej-title")


def test_held_arrow_keys_end_on_the_last_value(page):
    page.focus('input[name="mu_s"]')

    def hold() -> None:
        for _ in range(6):
            page.keyboard.press("ArrowLeft")

    act(page, "6 x ArrowLeft on mu_s", hold)
    page.wait_for_timeout(100)  # a stale answer must not follow the last one
    assert value(page, "mu_s") == "0.70"
    assert "μ_s = 0.7 " in page.inner_text(".ej-map-box .ej-title")


def test_click_on_the_map_moves_the_point(page):
    first = picture(page)
    box = page.locator(".ej-map").bounding_box()
    scale = box["width"] / MAP["width"]
    x = (MAP["x0"] + 0.5 * MAP["w"]) * scale
    y = (MAP["y0"] + MAP["h"] * (1 - 30 / 90)) * scale
    shown, _ = act(page, "click on the map", lambda: page.mouse.click(box["x"] + x, box["y"] + y))
    assert value(page, "alpha") == "30.0°" and value(page, "chi") == "0.50"
    assert shown["map"] != first["map"] and shown["numbers"] != first["numbers"]


def test_a_body_that_does_not_exist_is_a_clear_message(page):
    page.focus('input[name="km"]')
    shown, _ = act(page, "End on km", lambda: page.keyboard.press("End"))
    assert shown["message"].startswith("No such body: k_m = 1 is above 1 − χ = 0.85")
    assert "Traceback" not in page.inner_text("body")
    assert page.locator(".ej-scene.ej-invalid").count() == 1
    shown, _ = act(page, "Home on km", lambda: page.keyboard.press("Home"))
    assert "km = 0" in shown["message"]  # simulate refuses k_m = 0, and says why
    shown, _ = act(page, "ArrowRight on km", lambda: page.keyboard.press("ArrowRight"))
    assert shown["message"] == "" and page.locator(".ej-scene.ej-invalid").count() == 0


def test_rule_select_and_tie_by_keyboard(page):
    first = picture(page)
    page.focus('select[name="rule"]')
    shown, _ = act(page, "ArrowDown on the rule", lambda: page.keyboard.press("ArrowDown"))
    assert page.input_value('select[name="rule"]') == "normal_force"
    assert "normal force rule" in page.inner_text(".ej-map-box .ej-title")
    assert shown["map"] != first["map"]
    assert page.is_disabled('input[name="mu_k"]')
    page.focus('input[name="tie"]')
    act(page, "Space on the tie", lambda: page.keyboard.press("Space"))
    assert page.is_enabled('input[name="mu_k"]')
    page.focus('input[name="mu_k"]')
    act(page, "PageDown on mu_k", lambda: page.keyboard.press("PageDown"))
    assert float(value(page, "mu_k")) < 1.0


def test_the_animation_runs_and_pauses(page):
    clock = page.locator(".ej-clock")
    page.wait_for_function(
        "() => !document.querySelector('.ej-clock').textContent.startsWith('t = 0.00')"
    )
    page.click(".ej-play")
    assert page.get_attribute(".ej-play", "aria-pressed") == "false"
    paused = clock.text_content()
    page.wait_for_timeout(150)
    assert clock.text_content() == paused
    page.focus(".ej-playbar input[type=range]")
    page.keyboard.press("End")
    assert clock.text_content().startswith("t = 15.00")


def test_reduced_motion_starts_paused(browser):
    pg = browser.new_page(reduced_motion="reduce")
    pg.goto(browser.explorer_url)
    wait_settled(pg, 0)
    assert pg.get_attribute(".ej-play", "aria-pressed") == "false"
    assert pg.locator(".ej-clock").text_content().startswith("t = 0.00")
    pg.close()


WIDGET_PAGE = """<!doctype html><html><head><link rel="stylesheet" href="explorer.css"></head>
<body><div id="w"></div><script type="module">
import widget from "./explorer.js";
// anywidget's model, its messages answered over HTTP by the same api.handle as the kernel's
const handlers = [];
window.saved = [];
const params = {alpha: "30", chi: "0.5", km: "0.4", t_max: "9", tie: "1", rule: "paper"};
const model = {
  get: (key) => key === "params" ? params : undefined,
  set: (key, value) => window.saved.push(value),
  save_changes: () => {},
  on: (name, fn) => handlers.push(fn),
  off: () => {},
  send: async (msg) => {
    const r = await fetch(`api/${msg.endpoint}?${new URLSearchParams(msg.query)}`);
    const body = await r.json();
    handlers.forEach((fn) => fn({kind: "response", id: msg.id, status: r.status, body}));
  },
};
widget.render({model, el: document.getElementById("w")});
</script></body></html>"""


def test_the_widget_front_end_talks_through_its_model(browser):
    pg = browser.new_page()
    pg.route(
        browser.explorer_url + "widget.html",
        lambda route: route.fulfill(body=WIDGET_PAGE, content_type="text/html"),
    )
    pg.goto(browser.explorer_url + "widget.html")
    wait_settled(pg, 0)
    assert value(pg, "alpha") == "30.0°"  # the start came from the model
    # JupyterLab runs its notebook shortcuts for keys typed in a focused element unless it
    # carries data-lm-suppress-shortcuts (an arrow key would not move the slider)
    assert pg.evaluate(
        "[...document.querySelectorAll('.ej-root input, .ej-root select, .ej-root button')]"
        ".every(e => e.dataset.lmSuppressShortcuts === 'true')"
    )
    assert "θ = 325.17°" in number(pg, "liftoff")  # the Fig. 3b body, which slips first
    pg.focus('input[name="chi"]')
    act(pg, "ArrowLeft on chi (widget)", lambda: pg.keyboard.press("ArrowLeft"))
    assert pg.evaluate("window.saved.at(-1).chi") == "0.49"
    pg.close()


def test_the_p_jarm_panel_of_an_uncertainty_map(browser):
    """Given a map, the page draws its P(JARM) below the region, on the same axes, says the
    value under the cursor and moves the point on a click."""
    import numpy as np

    import eccjump

    alpha, chi = np.radians([30.0, 40.0, 50.0]), np.array([0.1, 0.15, 0.2, 0.3])
    m = eccjump.uncertainty_map(alpha, chi, [0.0, 0.1], 1.0, sd={"alpha": 0.004}, n=100)
    with ExplorerServer(0, uncertainty=m) as server:
        pg = browser.new_page(viewport={"width": 1280, "height": 1100})
        pg.goto(server.url)
        wait_settled(pg, 0)
        assert pg.locator(".ej-prob").is_visible()
        assert "km_frac = 0 " in pg.inner_text(".ej-prob .ej-title")
        box = pg.locator(".ej-prob-map").bounding_box()
        scale = box["width"] / 460  # PMAP.width
        at = (MAP["x0"] + 0.15 * MAP["w"]) * scale, (MAP["y0"] + MAP["h"] * (1 - 40 / 90)) * scale
        pg.mouse.move(box["x"] + at[0], box["y"] + at[1])
        shown = f"P(JARM) = {m.p_jarm[1, 1, 0]:.3f} [{m.p_jarm_low[1, 1, 0]:.3f}, "
        assert shown in pg.inner_text(".ej-prob-value")
        pixels = pg.evaluate("document.querySelector('.ej-prob-map').toDataURL()")
        act(
            pg,
            "click on the P(JARM) map",
            lambda: pg.mouse.click(box["x"] + at[0], box["y"] + at[1] + 30),
        )
        assert value(pg, "alpha") != "40.0°"
        assert pg.evaluate("document.querySelector('.ej-prob-map').toDataURL()") != pixels
        pg.close()


def test_zz_log_the_redraw_times():
    """Not a check: the times of this run, in one place (``pytest -s`` shows them)."""
    if LATENCIES:
        page_ms = sorted(x[1] for x in LATENCIES)
        print(f"\nredraws: {len(page_ms)}, page-measured median {page_ms[len(page_ms) // 2]:.0f} "
              f"ms, max {page_ms[-1]:.0f} ms")  # fmt: skip


def test_the_page_draws_the_modes_in_eccjumps_one_palette(page):
    """The timeline's bands and legend and the scene's mode swatch take their colours from
    eccjump._base.palette (sent with the controls), the same as the figures and the notebook
    views; the mode's name stays dark text (the palette's colours are too pale for text)."""
    from eccjump._base.palette import MODE_COLORS

    fills = page.evaluate(
        "() => [...document.querySelectorAll('.ej-timeline rect')].map(r => r.getAttribute('fill'))"
    )
    assert set(MODE_COLORS.values()) <= set(fills)
    assert set(fills) <= set(MODE_COLORS.values()) | {None}
    swatch, text = page.evaluate(
        """() => [...document.querySelectorAll('.ej-mode tspan')]
        .map(t => getComputedStyle(t).fill)"""
    )
    rgb = {"rgb({}, {}, {})".format(*(int(c[i : i + 2], 16) for i in (1, 3, 5))): m
           for m, c in MODE_COLORS.items()}  # fmt: skip
    assert swatch in rgb and text == "rgb(0, 0, 0)"


# --- screenshots for the docs ---------------------------------------------------------------


def screenshots(folder: Path) -> None:
    """Two PNGs for docs/explorer.md: the first view, and the Fig. 3b body on its map."""
    folder.mkdir(parents=True, exist_ok=True)
    with ExplorerServer(0) as server, sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=chromium())
        pg = b.new_page(viewport={"width": 1260, "height": 700})
        for name, query, at in (
            ("explorer.png", "", 4.6),
            ("explorer-slip.png", "?alpha=30&chi=0.5&km=0.4&t_max=9&tie=1", 6.2),
        ):
            pg.goto(server.url + query)
            wait_settled(pg, 0)
            pg.click(".ej-play")  # pause, then show the moment ``at``
            pg.evaluate(
                "t => { const s = document.querySelector('.ej-playbar input[type=range]');"
                " s.value = t; s.dispatchEvent(new Event('input')); }",
                at,
            )
            pg.screenshot(path=str(folder / name), full_page=True)
            _smaller(folder / name)
        b.close()


def _smaller(png: Path) -> None:
    """256 colours instead of true colour: a third of the size, the same picture."""
    try:
        from PIL import Image
    except ImportError:
        return
    with Image.open(png) as img:
        small = img.convert("RGB").quantize(256, method=Image.Quantize.MEDIANCUT)
    small.save(png, optimize=True)


if __name__ == "__main__":
    screenshots(Path(sys.argv[1] if len(sys.argv) > 1 else "docs/explorer"))
