// The eccjump explorer: sliders for a point (α, χ, k_m, μ_s, μ_k, e, θ0, θ̇0, rule), the
// JARM region slice over (χ, α) with the point marked (click to move it), the full motion of
// the point as an animated cylinder on the ramp with its mode timeline, and its numbers;
// given an uncertainty map, also P(JARM) under its tolerances below the region, on the
// same axes.
//
// One module for two hosts, with no dependency and nothing fetched from the internet:
//   - the local page (index.html): mount(el, httpHost()) asks the Python server's /api/…;
//   - the Jupyter widget (anywidget): the default export's render() asks the kernel through
//     the widget's messages (widgetHost), which answer with the same Python function.
// A host is { request(endpoint, query) -> Promise<{status, body}>, initial(), remember(query),
// dispose() }.

const SVG = "http://www.w3.org/2000/svg";
// The colour of each mode: eccjump's one palette (eccjump/_base/palette.py), sent by the
// Python side with the controls and filled in before anything is drawn.
const MODE_COLORS = {};
const REASON_COLORS = {
  JARM: "#1a9641",
  NO_ROOT: "#d9e6f2",
  LIFTOFF_EARLIER: "#74a9cf",
  NORMAL_FORCE_LOST: "#9e9ac8",
  SLIP_BEFORE: "#fde0c0",
  SLIP_AT_JUMP: "#f4a259",
  ROCKS_BACK: "#c7c7c7",
  TURN_LIMIT: "#969696",
  INVALID_PARAMS: "#e4e4e4",
  SOLVER_FAILED: "#000000",
  SLIP: "#fdd0a2",
};
// The controls whose change asks for a new region slice (the others move only the point).
const REGION_KEYS = ["km", "mu_s", "theta0", "omega0", "rule"];
// The controls whose change asks for a new P(JARM) slice (its km_frac is k_m / (1 − χ)).
const UNCERTAINTY_KEYS = ["km", "chi"];
// The requests of a redraw, in the order they are sent.
const ENDPOINTS = ["region", "motion", "uncertainty"];
// Inputs closer together than this make one request (a held arrow key, a drag).
const DEBOUNCE_MS = 25;
// The region map: canvas size and plot area, in canvas pixels.
const MAP = { width: 400, height: 392, x0: 50, y0: 10, w: 336, h: 336 };
// The P(JARM) panel: the region map's plot area, and its colour bar on the right.
const PMAP = { ...MAP, width: 460, bar: { x: 398, w: 12 } };
// matplotlib's viridis at 0, 1/4, 1/2, 3/4, 1 (the colours of P(JARM) in .plot()), and the
// colour of a cell without a valid sample.
const VIRIDIS = ["#440154", "#3b528b", "#21918c", "#5ec962", "#fde725"];
const NO_SAMPLE = "#e4e4e4";
// The contours' colours, as .plot() draws them: the even chance and the 95 % target.
const LEVEL_COLORS = { 0.5: "#ffffff", 0.95: "#e41a1c" };
// The scene: view box, where the axis C sits, pixels per R.
const SCENE = { width: 640, height: 300, cx: 320, cy: 165, scale: 48 };
const TIMELINE = { width: 640, height: 44, x0: 40, w: 580, y0: 6, h: 18 };
let mounts = 0;

// ------------------------------------------------------------------------------------------
// hosts
// ------------------------------------------------------------------------------------------

export function httpHost(base = "") {
  return {
    async request(endpoint, query) {
      const url = `${base}api/${endpoint}?${new URLSearchParams(query)}`;
      let response;
      try {
        response = await fetch(url, { cache: "no-store" });
      } catch (err) {
        return { status: 0, body: { error: "the explorer's server does not answer (stopped?)" } };
      }
      let body;
      try {
        body = await response.json();
      } catch (err) {
        body = { error: `the server answered ${response.status} without data` };
      }
      return { status: response.status, body };
    },
    initial() {
      return Object.fromEntries(new URLSearchParams(window.location.search));
    },
    remember(query) {
      // The address always shows the current point: it can be bookmarked or shared.
      window.history.replaceState(null, "", `?${new URLSearchParams(query)}`);
    },
    dispose() {},
  };
}

export function widgetHost(model) {
  let next = 0;
  const waiting = new Map();
  const onMessage = (msg) => {
    if (msg && msg.kind === "response" && waiting.has(msg.id)) {
      waiting.get(msg.id)({ status: msg.status, body: msg.body });
      waiting.delete(msg.id);
    }
  };
  model.on("msg:custom", onMessage);
  return {
    request(endpoint, query) {
      const id = ++next;
      return new Promise((resolve) => {
        waiting.set(id, resolve);
        model.send({ kind: "request", id, endpoint, query });
      });
    },
    initial() {
      return model.get("params") || {};
    },
    remember(query) {
      model.set("params", query);
      model.save_changes();
    },
    dispose() {
      model.off("msg:custom", onMessage);
      waiting.clear();
    },
  };
}

// ------------------------------------------------------------------------------------------
// small helpers
// ------------------------------------------------------------------------------------------

function decimals(step) {
  const text = String(step);
  return text.includes(".") ? text.split(".")[1].length : 0;
}

function formatted(control, value) {
  const text = Number(value).toFixed(decimals(control.step));
  return control.unit === "°" ? `${text}°` : control.unit ? `${text} ${control.unit}` : text;
}

function fixed(x, digits) {
  return x === null || x === undefined ? "—" : Number(x).toFixed(digits);
}

function element(tag, attrs = {}, text = "") {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
}

function svg(tag, attrs = {}) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  return e;
}

// ------------------------------------------------------------------------------------------
// the controls
// ------------------------------------------------------------------------------------------

function buildControls(box, spec, prefix, start, onChange) {
  const inputs = {};
  const outputs = {};
  const fieldset = element("fieldset", { class: "ej-controls" });
  fieldset.append(element("legend", {}, "Point"));
  for (const c of spec.controls) {
    const id = `${prefix}-${c.key}`;
    const row = element("div", { class: "ej-row" });
    const label = element("label", { for: id, title: c.help }, c.label);
    const input = element("input", {
      type: "range",
      id,
      name: c.key,
      min: c.lo,
      max: c.hi,
      step: c.step,
    });
    input.value = start[c.key];
    const out = element("output", { for: id, "aria-hidden": "true" });
    row.append(label, input, out);
    if (c.key === "mu_k") {
      const tie = element("input", { type: "checkbox", id: `${id}-tie`, name: "tie" });
      tie.checked = start.tie !== "0";
      const tieLabel = element("label", { for: `${id}-tie`, class: "ej-tie" }, "μ_k = μ_s");
      const tieRow = element("div", { class: "ej-row ej-tie-row" });
      tieRow.append(tie, tieLabel);
      fieldset.append(row, tieRow);
      inputs.tie = tie;
      tie.addEventListener("change", () => onChange(["mu_k", "tie"]));
    } else {
      fieldset.append(row);
    }
    inputs[c.key] = input;
    outputs[c.key] = out;
    input.addEventListener("input", () => onChange([c.key]));
  }
  const ruleRow = element("div", { class: "ej-row" });
  const ruleId = `${prefix}-rule`;
  const select = element("select", { id: ruleId, name: "rule" });
  for (const r of spec.rules) select.append(element("option", { value: r }, r.replace("_", " ")));
  select.value = spec.rules.includes(start.rule) ? start.rule : spec.rules[0];
  select.addEventListener("change", () => onChange(["rule"]));
  ruleRow.append(element("label", { for: ruleId }, "lift-off rule"), select);
  fieldset.append(ruleRow);
  inputs.rule = select;
  box.append(fieldset);
  return { inputs, outputs };
}

// ------------------------------------------------------------------------------------------
// the region map
// ------------------------------------------------------------------------------------------

class RegionView {
  constructor(box, onPick) {
    this.title = element("p", { class: "ej-title" }, "JARM region");
    this.canvas = element("canvas", {
      width: MAP.width,
      height: MAP.height,
      class: "ej-map",
      role: "img",
      "aria-label": "JARM region over (χ, α); click to move the point",
    });
    this.legend = element("ul", { class: "ej-legend" });
    this.image = null;
    this.data = null;
    this.point = null;
    box.append(this.title, this.canvas, this.legend);
    this.canvas.addEventListener("click", (ev) => {
      const at = mapPoint(this.canvas, MAP, ev);
      if (at) onPick(...at);
    });
  }

  show(data, spec) {
    this.data = data;
    const n = data.n;
    const off = document.createElement("canvas");
    off.width = n;
    off.height = n;
    const octx = off.getContext("2d");
    const img = octx.createImageData(n, n);
    for (let j = 0; j < n; j++) {
      for (let i = 0; i < n; i++) {
        const name = data.names[data.codes[j * n + i]];
        const hex = REASON_COLORS[name] || "#ff00ff";
        const k = 4 * ((n - 1 - j) * n + i); // alpha grows upwards
        img.data[k] = parseInt(hex.slice(1, 3), 16);
        img.data[k + 1] = parseInt(hex.slice(3, 5), 16);
        img.data[k + 2] = parseInt(hex.slice(5, 7), 16);
        img.data[k + 3] = 255;
      }
    }
    octx.putImageData(img, 0, 0);
    this.image = off;
    const p = data.params;
    this.title.textContent =
      `JARM region at k_m = ${p.km}, μ_s = ${p.mu_s}` +
      (p.theta0 || p.omega0 ? `, θ0 = ${p.theta0}°, θ̇0 = ${p.omega0}` : "") +
      ` (${p.rule.replace("_", " ")} rule): ` +
      `${(100 * data.jarm_fraction).toFixed(1)} % of the valid bodies jump`;
    this.legend.replaceChildren();
    // shares of the valid bodies, as the title's; the invalid corner as a share of the map
    const total = data.n * data.n;
    const valid = total - (data.counts.INVALID_PARAMS || 0);
    for (const [name, count] of Object.entries(data.counts)) {
      const li = element("li");
      const swatch = element("span", { class: "ej-swatch" });
      swatch.style.background = REASON_COLORS[name] || "#ff00ff";
      const what = spec.reasons[name] || "";
      const share =
        name === "INVALID_PARAMS"
          ? `${((100 * count) / total).toFixed(1)} % of the map`
          : `${((100 * count) / Math.max(1, valid)).toFixed(1)} %`;
      li.append(swatch, `${name}: ${what} (${share})`);
      this.legend.append(li);
    }
    this.draw();
  }

  mark(chi, alpha) {
    this.point = [chi, alpha];
    this.draw();
  }

  draw() {
    const ctx = this.canvas.getContext("2d");
    ctx.clearRect(0, 0, MAP.width, MAP.height);
    if (this.image) {
      ctx.imageSmoothingEnabled = false;
      ctx.drawImage(this.image, MAP.x0, MAP.y0, MAP.w, MAP.h);
    }
    drawAxes(ctx);
    if (this.point) drawMark(ctx, ...this.point);
  }
}

// The frame, ticks and labels of a (χ, α) map (MAP's plot area).
function drawAxes(ctx) {
  ctx.strokeStyle = "#444";
  ctx.lineWidth = 1;
  ctx.strokeRect(MAP.x0 + 0.5, MAP.y0 + 0.5, MAP.w, MAP.h);
  ctx.fillStyle = "#222";
  ctx.font = "12px system-ui, sans-serif";
  ctx.textAlign = "center";
  for (const chi of [0, 0.25, 0.5, 0.75, 1]) {
    const x = MAP.x0 + chi * MAP.w;
    ctx.fillRect(x, MAP.y0 + MAP.h, 1, 5);
    ctx.fillText(String(chi), x, MAP.y0 + MAP.h + 17);
  }
  ctx.fillText("χ = d/R", MAP.x0 + MAP.w / 2, MAP.y0 + MAP.h + 33);
  ctx.textAlign = "right";
  for (let a = 0; a <= 90; a += 15) {
    const y = MAP.y0 + MAP.h - (a / 90) * MAP.h;
    ctx.fillRect(MAP.x0 - 5, y, 5, 1);
    ctx.fillText(`${a}°`, MAP.x0 - 8, y + 4);
  }
  ctx.save();
  ctx.translate(12, MAP.y0 + MAP.h / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textAlign = "center";
  ctx.fillText("ramp angle α", 0, 0);
  ctx.restore();
}

// The point's marker: a ring and a cross, visible on any colour.
function drawMark(ctx, chi, alpha) {
  const x = MAP.x0 + chi * MAP.w;
  const y = MAP.y0 + MAP.h - (alpha / 90) * MAP.h;
  ctx.lineWidth = 3;
  ctx.strokeStyle = "#fff";
  ctx.beginPath();
  ctx.arc(x, y, 7, 0, 2 * Math.PI);
  ctx.stroke();
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = "#000";
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(x - 11, y);
  ctx.lineTo(x - 4, y);
  ctx.moveTo(x + 4, y);
  ctx.lineTo(x + 11, y);
  ctx.moveTo(x, y - 11);
  ctx.lineTo(x, y - 4);
  ctx.moveTo(x, y + 4);
  ctx.lineTo(x, y + 11);
  ctx.stroke();
}

// (χ, α in degrees) under a mouse event on a map canvas of size `size` (MAP or PMAP), or
// null outside the plot area.
function mapPoint(canvas, size, ev) {
  const r = canvas.getBoundingClientRect();
  const x = ((ev.clientX - r.left) * size.width) / r.width;
  const y = ((ev.clientY - r.top) * size.height) / r.height;
  const chi = (x - MAP.x0) / MAP.w;
  const alpha = (90 * (MAP.y0 + MAP.h - y)) / MAP.h;
  return chi >= 0 && chi <= 1 && alpha >= 0 && alpha <= 90 ? [chi, alpha] : null;
}

// ------------------------------------------------------------------------------------------
// P(JARM) of an uncertainty map
// ------------------------------------------------------------------------------------------

function viridis(p) {
  const t = Math.min(1, Math.max(0, p)) * (VIRIDIS.length - 1);
  const k = Math.min(VIRIDIS.length - 2, Math.floor(t));
  const f = t - k;
  const rgb = (hex, i) => parseInt(hex.slice(1 + 2 * i, 3 + 2 * i), 16);
  const mix = (i) => Math.round(rgb(VIRIDIS[k], i) * (1 - f) + rgb(VIRIDIS[k + 1], i) * f);
  return `rgb(${mix(0)}, ${mix(1)}, ${mix(2)})`;
}

// The index of the cell of `edges` (ascending) holding x, or -1.
function cellOf(edges, x) {
  for (let i = 0; i + 1 < edges.length; i++) if (x >= edges[i] && x <= edges[i + 1]) return i;
  return -1;
}

class ProbabilityView {
  constructor(box, onPick) {
    this.box = element("div", { class: "ej-prob" });
    this.title = element("p", { class: "ej-title" }, "P(JARM) under tolerances");
    this.canvas = element("canvas", {
      width: PMAP.width,
      height: PMAP.height,
      class: "ej-prob-map",
      role: "img",
      "aria-label": "P(JARM) under the map's tolerances over (χ, α); click to move the point",
    });
    this.readout = element("p", { class: "ej-prob-value" }, "");
    this.note = element("p", { class: "ej-prob-note" });
    this.box.append(this.title, this.canvas, this.readout, this.note);
    this.box.hidden = true; // until a map answers
    box.append(this.box);
    this.data = null;
    this.point = null;
    this.canvas.addEventListener("click", (ev) => {
      const at = mapPoint(this.canvas, PMAP, ev);
      if (at) onPick(...at);
    });
    const hovered = (ev) => this.hover(mapPoint(this.canvas, PMAP, ev));
    this.canvas.addEventListener("mousemove", hovered);
    this.canvas.addEventListener("mouseleave", () => this.hover(null));
  }

  show(data, q) {
    this.data = data;
    this.box.hidden = false;
    const wanted = data.wanted_km_frac === null ? "—" : data.wanted_km_frac.toFixed(3);
    this.title.textContent =
      `P(JARM) under tolerances at km_frac = ${data.km_frac} ` +
      `(the map's slice nearest to k_m / (1 − χ) = ${wanted}), ` +
      `μ_s = ${data.mu_s}, ${data.rule.replace("_", " ")} rule`;
    const differs = Number(q.mu_s) !== data.mu_s || q.rule !== data.rule;
    this.note.textContent =
      `Tolerances: ${data.tolerances}; ${data.n} samples a point. Contours: ` +
      `${data.levels.join(" (white) and ")} (red).` +
      (differs ? " The map's μ_s and rule, not the sliders'." : "");
    this.hover(null);
    this.draw();
  }

  mark(chi, alpha) {
    this.point = [chi, alpha];
    this.draw();
  }

  hover(at) {
    const d = this.data;
    if (!d) return;
    const i = at ? cellOf(d.chi_edges, at[0]) : -1;
    const j = at ? cellOf(d.alpha_edges, at[1]) : -1;
    if (i < 0 || j < 0) {
      this.readout.textContent = "Point at the map for P(JARM) and its interval.";
      return;
    }
    const k = j * (d.chi_edges.length - 1) + i;
    const where = `χ = ${at[0].toFixed(3)}, α = ${at[1].toFixed(1)}°`;
    this.readout.textContent =
      d.p_jarm[k] === null
        ? `${where}: no valid sample`
        : `${where}: P(JARM) = ${d.p_jarm[k].toFixed(3)} ` +
          `[${fixed(d.p_jarm_low[k], 3)}, ${fixed(d.p_jarm_high[k], 3)}] ` +
          `(${Math.round(100 * d.confidence)} % interval)`;
  }

  draw() {
    const ctx = this.canvas.getContext("2d");
    ctx.clearRect(0, 0, PMAP.width, PMAP.height);
    const d = this.data;
    if (d) {
      // whole pixels: neighbouring cells share their edge, with no seam between them
      const X = (chi) => Math.round(MAP.x0 + chi * MAP.w);
      const Y = (a) => Math.round(MAP.y0 + MAP.h - (a / 90) * MAP.h);
      const nx = d.chi_edges.length - 1;
      const ny = d.alpha_edges.length - 1;
      const at = (i, j) => d.p_jarm[j * nx + i];
      for (let j = 0; j < ny; j++) {
        for (let i = 0; i < nx; i++) {
          const p = at(i, j);
          ctx.fillStyle = p === null ? NO_SAMPLE : viridis(p);
          const x0 = X(d.chi_edges[i]);
          const y1 = Y(d.alpha_edges[j + 1]);
          ctx.fillRect(x0, y1, X(d.chi_edges[i + 1]) - x0, Y(d.alpha_edges[j]) - y1);
        }
      }
      // each contour along the cell edges where P(JARM) crosses its level
      for (const level of d.levels) {
        const crosses = (a, b) => a !== null && b !== null && (a >= level) !== (b >= level);
        ctx.strokeStyle = LEVEL_COLORS[level] || "#000";
        ctx.lineWidth = level >= 0.9 ? 2 : 1.5;
        ctx.beginPath();
        for (let j = 0; j < ny; j++) {
          for (let i = 0; i < nx; i++) {
            if (i + 1 < nx && crosses(at(i, j), at(i + 1, j))) {
              ctx.moveTo(X(d.chi_edges[i + 1]), Y(d.alpha_edges[j]));
              ctx.lineTo(X(d.chi_edges[i + 1]), Y(d.alpha_edges[j + 1]));
            }
            if (j + 1 < ny && crosses(at(i, j), at(i, j + 1))) {
              ctx.moveTo(X(d.chi_edges[i]), Y(d.alpha_edges[j + 1]));
              ctx.lineTo(X(d.chi_edges[i + 1]), Y(d.alpha_edges[j + 1]));
            }
          }
        }
        ctx.stroke();
      }
      this.drawBar(d.levels);
    }
    drawAxes(ctx);
    if (this.point) drawMark(ctx, ...this.point);
  }

  drawBar(levels) {
    const ctx = this.canvas.getContext("2d");
    const { x, w } = PMAP.bar;
    for (let y = 0; y < MAP.h; y++) {
      ctx.fillStyle = viridis(1 - y / MAP.h);
      ctx.fillRect(x, MAP.y0 + y, w, 1);
    }
    ctx.strokeStyle = "#444";
    ctx.lineWidth = 1;
    ctx.strokeRect(x + 0.5, MAP.y0 + 0.5, w, MAP.h);
    ctx.fillStyle = "#222";
    ctx.font = "12px system-ui, sans-serif";
    ctx.textAlign = "left";
    for (const p of [0, ...levels, 1]) {
      const y = MAP.y0 + MAP.h - p * MAP.h;
      ctx.fillRect(x + w, y, 4, 1);
      ctx.fillText(String(p), x + w + 6, y + 4);
    }
    ctx.save();
    ctx.translate(PMAP.width - 6, MAP.y0 + MAP.h / 2);
    ctx.rotate(-Math.PI / 2);
    ctx.textAlign = "center";
    ctx.fillText("P(JARM)", 0, 0);
    ctx.restore();
  }
}

// ------------------------------------------------------------------------------------------
// the motion: scene, timeline, playback
// ------------------------------------------------------------------------------------------

class MotionView {
  constructor(box, prefix) {
    this.scene = svg("svg", {
      viewBox: `0 0 ${SCENE.width} ${SCENE.height}`,
      class: "ej-scene",
      role: "img",
      "aria-label": "the cylinder on the ramp",
    });
    this.world = svg("g");
    this.ramp = svg("rect", { class: "ej-ramp", y: 0, height: 6 });
    this.ticks = svg("g", { class: "ej-ticks" });
    this.trail = svg("polyline", { class: "ej-trail", fill: "none" });
    this.wheel = svg("circle", { r: 1, class: "ej-wheel" });
    this.spoke = svg("line", { class: "ej-spoke" });
    this.cm = svg("circle", { r: 0.09, class: "ej-cm" });
    this.axis = svg("circle", { r: 0.04, class: "ej-axis" });
    const parts = [this.ramp, this.ticks, this.trail, this.wheel, this.spoke, this.axis, this.cm];
    this.world.append(...parts);
    const plate = svg("rect", { x: 4, y: 4, width: 330, height: 46, rx: 4, class: "ej-plate" });
    this.clock = svg("text", { x: 12, y: 22, class: "ej-clock" });
    this.modeLabel = svg("text", { x: 12, y: 42, class: "ej-mode" });
    // The mode in dark text after a swatch of its colour: light colours (the palette is made
    // for colour-blind readers) are too pale for text on the plate.
    this.modeSwatch = svg("tspan", {});
    this.modeText = svg("tspan", {});
    this.modeLabel.append(this.modeSwatch, this.modeText);
    const gravity = svg("g", { class: "ej-gravity" });
    gravity.append(
      svg("line", { x1: 610, y1: 16, x2: 610, y2: 46 }),
      svg("path", { d: "M604 40 L610 50 L616 40 Z" }),
    );
    const g = svg("text", { x: 596, y: 34, "text-anchor": "end" });
    g.textContent = "g";
    gravity.append(g);
    this.scene.append(this.world, plate, this.clock, this.modeLabel, gravity);

    this.timeline = svg("svg", {
      viewBox: `0 0 ${TIMELINE.width} ${TIMELINE.height}`,
      class: "ej-timeline",
      role: "img",
      "aria-label": "the modes over time",
    });
    this.bands = svg("g");
    this.axisText = svg("g", { class: "ej-axis-text" });
    this.playhead = svg("line", { class: "ej-playhead", y1: 2, y2: TIMELINE.y0 + TIMELINE.h + 4 });
    this.timeline.append(this.bands, this.axisText, this.playhead);

    const bar = element("div", { class: "ej-playbar" });
    this.play = element("button", { type: "button", class: "ej-play", "aria-pressed": "true" });
    this.play.textContent = "Pause";
    const timeId = `${prefix}-time`;
    this.scrub = element("input", { type: "range", id: timeId, min: 0, max: 1, step: 0.05 });
    this.scrub.value = 0;
    const speedId = `${prefix}-speed`;
    this.speed = element("select", { id: speedId });
    for (const s of [0.5, 1, 2, 4, 8]) this.speed.append(element("option", { value: s }, `${s}×`));
    this.speed.value = "2";
    bar.append(
      this.play,
      element("label", { for: timeId }, "time"),
      this.scrub,
      element("label", { for: speedId }, "speed [√(R/g) per s]"),
      this.speed,
    );
    box.append(this.scene, this.timeline, bar);

    this.data = null;
    this.time = 0;
    this.playing = true;
    this.last = null;
    this.play.addEventListener("click", () => this.toggle());
    // who asks the system for less motion gets a still picture until Play
    if (window.matchMedia?.("(prefers-reduced-motion: reduce)").matches) this.toggle();
    this.scrub.addEventListener("input", () => {
      if (!this.data) return;
      this.time = Number(this.scrub.value);
      this.frame();
    });
    this.timeline.addEventListener("click", (ev) => {
      if (!this.data) return;
      const r = this.timeline.getBoundingClientRect();
      const x = ((ev.clientX - r.left) * TIMELINE.width) / r.width;
      const f = Math.min(1, Math.max(0, (x - TIMELINE.x0) / TIMELINE.w));
      this.time = f * this.data.t_end;
      this.frame();
    });
    this.raf = requestAnimationFrame((now) => this.tick(now));
  }

  toggle() {
    this.playing = !this.playing;
    this.play.textContent = this.playing ? "Pause" : "Play";
    this.play.setAttribute("aria-pressed", String(this.playing));
  }

  show(data, alphaDeg) {
    this.data = data;
    this.alpha = alphaDeg;
    this.time = 0;
    this.scrub.max = data.t_end;
    this.scene.classList.remove("ej-invalid");
    this.bands.replaceChildren();
    this.axisText.replaceChildren();
    const T = data.t_end || 1;
    const x = (t) => TIMELINE.x0 + (t / T) * TIMELINE.w;
    for (const s of data.segments) {
      const band = svg("rect", {
        x: x(s.t_start),
        y: TIMELINE.y0,
        width: Math.max(0.5, x(s.t_end ?? T) - x(s.t_start)),
        height: TIMELINE.h,
        fill: MODE_COLORS[s.mode],
      });
      const title = svg("title");
      title.textContent = `${s.mode} (${s.reason}) from t = ${fixed(s.t_start, 3)}`;
      band.append(title);
      this.bands.append(band);
    }
    const label = (xx, text, anchor) => {
      const e = svg("text", { x: xx, y: TIMELINE.height - 4, "text-anchor": anchor });
      e.textContent = text;
      this.axisText.append(e);
    };
    label(TIMELINE.x0, "t = 0", "start");
    label(TIMELINE.x0 + TIMELINE.w, `${fixed(T, 2)} √(R/g)`, "end");
    let legendX = TIMELINE.x0 + TIMELINE.w / 2 - 110;
    for (const [mode, color] of Object.entries(MODE_COLORS)) {
      const y = TIMELINE.height - 13;
      const sw = svg("rect", { x: legendX, y, width: 10, height: 10, fill: color });
      this.axisText.append(sw);
      label(legendX + 14, mode, "start");
      legendX += 80;
    }
    this.frame();
  }

  invalid() {
    this.data = null;
    this.scene.classList.add("ej-invalid");
    this.bands.replaceChildren();
    this.axisText.replaceChildren();
    this.clock.textContent = "";
    this.modeSwatch.textContent = "";
    this.modeText.textContent = "";
  }

  tick(now) {
    if (this.last !== null && this.playing && this.data) {
      const dt = Math.min(0.1, (now - this.last) / 1000);
      this.time += dt * Number(this.speed.value);
      if (this.time > this.data.t_end + 1) this.time = 0; // a short pause at the end, then again
      this.frame();
    }
    this.last = now;
    this.raf = requestAnimationFrame((t) => this.tick(t));
  }

  frame() {
    const d = this.data;
    if (!d) return;
    const n = d.t.length;
    const t = Math.min(this.time, d.t_end);
    const i = Math.min(n - 1, Math.max(0, Math.round((t / (d.t_end || 1)) * (n - 1))));
    const cx = d.cx[i];
    const S = SCENE.scale;
    this.world.setAttribute(
      "transform",
      `translate(${SCENE.cx} ${SCENE.cy}) rotate(${this.alpha}) scale(${S}) translate(${-cx} 0)`,
    );
    // the ramp and its ticks around the camera (ramp coordinates: x down the ramp, y out of
    // it; SVG's y points into the ramp, hence the minus signs)
    const span = SCENE.width / S;
    this.ramp.setAttribute("x", cx - span);
    this.ramp.setAttribute("width", 2 * span);
    this.ticks.replaceChildren();
    for (let k = Math.floor(cx - span); k <= cx + span; k++) {
      const major = k % 5 === 0;
      this.ticks.append(svg("line", { x1: k, y1: 0, x2: k, y2: major ? 0.35 : 0.18 }));
      if (major) {
        const label = svg("text", { x: k, y: 0.8, "text-anchor": "middle" });
        label.textContent = `${k} R`;
        this.ticks.append(label);
      }
    }
    const from = Math.max(0, i - 90);
    let points = "";
    for (let k = from; k <= i; k++) points += `${d.gx[k]},${-d.gy[k]} `;
    this.trail.setAttribute("points", points);
    const mode = d.modes[d.mode[i]];
    this.wheel.setAttribute("cx", cx);
    this.wheel.setAttribute("cy", -d.cy[i]);
    this.wheel.style.fill = MODE_COLORS[mode];
    this.wheel.style.stroke = MODE_COLORS[mode];
    this.axis.setAttribute("cx", cx);
    this.axis.setAttribute("cy", -d.cy[i]);
    this.spoke.setAttribute("x1", cx);
    this.spoke.setAttribute("y1", -d.cy[i]);
    this.spoke.setAttribute("x2", d.gx[i]);
    this.spoke.setAttribute("y2", -d.gy[i]);
    this.cm.setAttribute("cx", d.gx[i]);
    this.cm.setAttribute("cy", -d.gy[i]);
    this.clock.textContent = `t = ${t.toFixed(2)} √(R/g)   l = ${cx.toFixed(2)} R`;
    const height = d.cy[i] - 1;
    this.modeSwatch.textContent = "■ ";
    this.modeSwatch.style.fill = MODE_COLORS[mode];
    this.modeText.textContent =
      mode === "FLIGHT" ? `${mode}: axis ${height.toFixed(3)} R above contact` : mode;
    const px = TIMELINE.x0 + (t / (d.t_end || 1)) * TIMELINE.w;
    this.playhead.setAttribute("x1", px);
    this.playhead.setAttribute("x2", px);
    if (document.activeElement !== this.scrub) this.scrub.value = t;
    this.scrub.setAttribute("aria-valuetext", `t = ${t.toFixed(2)} √(R/g)`);
  }

  dispose() {
    cancelAnimationFrame(this.raf);
  }
}

// ------------------------------------------------------------------------------------------
// the numbers
// ------------------------------------------------------------------------------------------

const NUMBER_ROWS = [
  ["verdict", "JARM verdict"],
  ["slip", "slip onset"],
  ["liftoff", "lift-off"],
  ["flight", "first flight"],
  ["counts", "flights, impacts"],
  ["sequence", "modes"],
  ["end", "end"],
];

class NumbersView {
  constructor(box) {
    box.append(element("p", { class: "ej-title" }, "Numbers"));
    this.list = element("dl", { class: "ej-numbers" });
    this.cells = {};
    for (const [key, name] of NUMBER_ROWS) {
      const dd = element("dd", { "data-key": key }, "—");
      this.list.append(element("dt", {}, name), dd);
      this.cells[key] = dd;
    }
    this.timing = element("p", { class: "ej-timing", "aria-live": "off" });
    box.append(this.list, this.timing);
  }

  show(d, spec) {
    const n = d.numbers;
    const v = d.verdict;
    this.cells.verdict.textContent =
      `${v.reason}: ${spec.reasons[v.reason] || ""}` +
      (v.is_jarm ? ` at θ_J = ${fixed(v.theta_J_deg, 2)}°` : "");
    this.cells.verdict.className = v.is_jarm ? "ej-jarm" : "";
    this.cells.slip.textContent = n.slip
      ? `t = ${fixed(n.slip.t, 4)} √(R/g), θ = ${fixed(n.slip.theta_deg, 2)}°` +
        (n.slip.reason === "slip" ? "" : ` (after ${n.slip.reason.replace("_", " ")})`)
      : `none until t = ${fixed(d.t_end, 2)} √(R/g)`;
    this.cells.liftoff.textContent = n.liftoff
      ? `t = ${fixed(n.liftoff.t, 4)} √(R/g), θ = ${fixed(n.liftoff.theta_deg, 2)}° ` +
        `(from ${n.liftoff.from}, ${n.liftoff.reason.replace("_", " ")})`
      : `none until t = ${fixed(d.t_end, 2)} √(R/g)`;
    this.cells.flight.textContent = n.flight
      ? `apex ${fixed(n.flight.apex, 4)} R, distance ${fixed(n.flight.distance, 3)} R, ` +
        (n.flight.t_landing === null
          ? "still in flight at the end"
          : `lands at t = ${fixed(n.flight.t_landing, 4)} √(R/g)`)
      : "none";
    const plural = (k, word) => `${k} ${word}${k === 1 ? "" : "s"}`;
    this.cells.counts.textContent =
      `${plural(n.flights, "flight")}, ${plural(n.impacts, "impact")}`;
    this.cells.sequence.textContent =
      n.sequence.join(" → ") +
      (n.more_transitions ? ` → … (${n.more_transitions} more)` : "");
    this.cells.end.textContent = `${d.status} at t = ${fixed(d.t_end, 2)} √(R/g)`;
  }

  clear() {
    for (const dd of Object.values(this.cells)) dd.textContent = "—";
  }
}

// ------------------------------------------------------------------------------------------
// the explorer
// ------------------------------------------------------------------------------------------

// In JupyterLab, keys typed in the explorer must move its controls, not run the notebook's
// command-mode shortcuts (arrows; "d d" deletes the cell). Lumino walks up from the focused
// element and matches each against the shortcuts' selectors (one is
// ".jp-Notebook.jp-mod-commandMode … :focus", which the focused slider itself matches) until
// an element carries data-lm-suppress-shortcuts: so every control carries it.
function suppressNotebookShortcuts(root) {
  root.setAttribute("data-lm-suppress-shortcuts", "true");
  for (const e of root.querySelectorAll("input, select, button")) {
    e.setAttribute("data-lm-suppress-shortcuts", "true");
  }
}

export function mount(el, host) {
  const prefix = `ej${++mounts}`;
  const root = element("div", { class: "ej-root" });
  root.dataset.regionDraws = "0";
  root.dataset.motionDraws = "0";
  root.dataset.uncertaintyDraws = "0";
  root.dataset.settled = "0"; // redraws finished: every input answered and drawn
  const heading = element("p", { class: "ej-status", "aria-live": "polite" }, "Loading…");
  const message = element("div", { class: "ej-message", role: "alert" });
  message.hidden = true;
  const left = element("div", { class: "ej-left" });
  const mapBox = element("section", { class: "ej-map-box", "aria-label": "JARM region" });
  const motionBox = element("section", { class: "ej-motion-box", "aria-label": "motion" });
  const numbersBox = element("section", { class: "ej-numbers-box", "aria-label": "numbers" });
  const views = element("div", { class: "ej-views" });
  views.append(motionBox, mapBox, numbersBox);
  root.append(heading, message, element("div", { class: "ej-body" }));
  root.lastChild.append(left, views);
  el.replaceChildren(root);

  let disposed = false;
  let ui = null;
  // `uncertainty` is asked once at the start; a host without a map answers
  // {available: false}, and the page asks no more (state.noMap)
  const state = {
    need: { region: true, motion: true, uncertainty: true },
    busy: {},
    since: null,
    timer: null,
    noMap: false,
  };

  function query() {
    const q = {};
    for (const c of ui.spec.controls) q[c.key] = ui.inputs[c.key].value;
    q.rule = ui.inputs.rule.value;
    q.tie = ui.inputs.tie.checked ? "1" : "0";
    if (ui.inputs.tie.checked) q.mu_k = q.mu_s;
    return q;
  }

  function refreshOutputs() {
    const tie = ui.inputs.tie.checked;
    ui.inputs.mu_k.disabled = tie;
    if (tie) ui.inputs.mu_k.value = ui.inputs.mu_s.value;
    for (const c of ui.spec.controls) {
      const text = formatted(c, ui.inputs[c.key].value);
      ui.outputs[c.key].textContent = text;
      ui.inputs[c.key].setAttribute("aria-valuetext", text);
    }
  }

  function changed(keys) {
    refreshOutputs();
    if (keys.some((k) => REGION_KEYS.includes(k))) state.need.region = true;
    if (keys.some((k) => UNCERTAINTY_KEYS.includes(k)) && !state.noMap) {
      state.need.uncertainty = true;
    }
    state.need.motion = true;
    if (state.since === null) state.since = performance.now();
    ui.region.mark(Number(ui.inputs.chi.value), Number(ui.inputs.alpha.value));
    ui.prob.mark(Number(ui.inputs.chi.value), Number(ui.inputs.alpha.value));
    clearTimeout(state.timer);
    state.timer = setTimeout(flush, DEBOUNCE_MS);
  }

  function flush() {
    host.remember(query());
    for (const endpoint of ENDPOINTS) {
      if (state.need[endpoint] && !state.busy[endpoint]) run(endpoint);
    }
  }

  async function run(endpoint) {
    state.need[endpoint] = false;
    state.busy[endpoint] = true;
    const q = query();
    const alpha = Number(q.alpha);
    const { status, body } = await host.request(endpoint, q);
    state.busy[endpoint] = false;
    if (disposed) return;
    draw(endpoint, status, body, alpha, q);
    if (state.need[endpoint]) {
      run(endpoint); // the point moved while this one was computed
      return;
    }
    settled();
  }

  function draw(endpoint, status, body, alpha, q) {
    const ok = status === 200;
    if (endpoint === "uncertainty") {
      if (ok && body.available) ui.prob.show(body, q);
      else if (ok) state.noMap = true;
      root.dataset.uncertaintyDraws = String(Number(root.dataset.uncertaintyDraws) + 1);
    } else if (endpoint === "region") {
      if (ok) ui.region.show(body, ui.spec);
      root.dataset.regionDraws = String(Number(root.dataset.regionDraws) + 1);
    } else {
      if (ok) {
        ui.motion.show(body, alpha);
        ui.numbers.show(body, ui.spec);
      } else {
        ui.motion.invalid();
        ui.numbers.clear();
      }
      root.dataset.motionDraws = String(Number(root.dataset.motionDraws) + 1);
    }
    if (ok && endpoint === "motion") message.hidden = true;
    if (!ok) {
      message.textContent = body.error || `request failed (${status})`;
      message.hidden = false;
    }
    state.serverMs = state.serverMs || {};
    if (ok) state.serverMs[endpoint] = body.compute_ms;
  }

  function settled() {
    if (ENDPOINTS.some((e) => state.need[e] || state.busy[e])) return;
    if (state.since === null) return;
    const since = state.since;
    state.since = null;
    requestAnimationFrame(() => {
      const ms = performance.now() - since;
      root.dataset.latencyMs = ms.toFixed(1);
      root.dataset.settled = String(Number(root.dataset.settled) + 1);
      const server = state.serverMs || {};
      ui.numbers.timing.textContent =
        `redraw ${ms.toFixed(0)} ms after the last input ` +
        `(computing: motion ${fixed(server.motion, 1)} ms, region ${fixed(server.region, 1)} ms)`;
    });
  }

  (async () => {
    const { status, body } = await host.request("controls", {});
    if (disposed) return;
    if (status !== 200) {
      heading.textContent = "";
      message.textContent = body.error || "the explorer's server does not answer";
      message.hidden = false;
      return;
    }
    Object.assign(MODE_COLORS, body.mode_colors);
    const start = {};
    for (const c of body.controls) start[c.key] = c.default;
    Object.assign(start, host.initial());
    const { inputs, outputs } = buildControls(left, body, prefix, start, (keys) => changed(keys));
    ui = { spec: body, inputs, outputs };
    ui.motion = new MotionView(motionBox, prefix);
    const pick = (chi, alpha) => {
      for (const [key, value] of [["chi", chi], ["alpha", alpha]]) {
        const c = body.controls.find((x) => x.key === key);
        ui.inputs[key].value = (Math.round(value / c.step) * c.step).toFixed(decimals(c.step));
      }
      changed(["chi", "alpha"]);
    };
    ui.region = new RegionView(mapBox, pick);
    ui.prob = new ProbabilityView(mapBox, (chi, alpha) => pick(chi, alpha));
    ui.numbers = new NumbersView(numbersBox);
    suppressNotebookShortcuts(root);
    heading.textContent =
      "Move a slider (or click the map) to change the point; " +
      "units g = R = M = 1, angles in degrees.";
    root.dataset.ready = "1";
    changed([...REGION_KEYS, ...UNCERTAINTY_KEYS]);
  })();

  return () => {
    disposed = true;
    clearTimeout(state.timer);
    if (ui && ui.motion) ui.motion.dispose();
    host.dispose();
  };
}

// anywidget's entry point: the same explorer, its requests answered by the kernel.
export default {
  render({ model, el }) {
    return mount(el, widgetHost(model));
  },
};
