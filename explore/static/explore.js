// baranov explore: the page. Dimensions are sliders; every change asks the server for a
// redraw (one request in flight, the latest values win), and every assembly mode is drawn
// in the colour of its identity, which the server keeps while the mode moves continuously.
"use strict";

const PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2",
                 "#7f7f7f", "#bcbd22", "#393b79", "#ad494a"];
const SVG = "http://www.w3.org/2000/svg";
const BUSY_AFTER_MS = 120;   // a redraw slower than this shows "solving…"

const state = {
  document: null, values: {}, frame: null, next_id: 0, method: "numeric", view: null,
  inFlight: false, pending: false, active: null, profile: null, highlighted: null,
  redraws: 0, redrawTimes: [], events: [], waiters: [],
};

function colour(id) { return PALETTE[id % PALETTE.length]; }
function $(id) { return document.getElementById(id); }
function el(tag, attributes = {}, parent = null) {
  const node = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (parent) parent.appendChild(node);
  return node;
}
function html(tag, attributes = {}, text = null, parent = null) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attributes)) node.setAttribute(key, value);
  if (text !== null) node.textContent = text;
  if (parent) parent.appendChild(node);
  return node;
}
function formatted(value) {
  if (value === null || value === undefined) return "";
  const magnitude = Math.abs(value);
  return magnitude !== 0 && (magnitude < 1e-3 || magnitude >= 1e6) ? value.toExponential(4) : String(+value.toPrecision(6));
}

// ---- talking to the server ----------------------------------------------------------
async function post(path, body) {
  const answer = await fetch(path, {method: "POST", headers: {"Content-Type": "application/json"},
                                    body: JSON.stringify(body)});
  if (!answer.ok) {
    let message = answer.statusText;
    try { message = (await answer.json()).error; } catch (error) { /* not JSON */ }
    throw new Error(message);
  }
  return answer;
}

function requestRedraw() {
  if (state.inFlight) { state.pending = true; return; }
  state.inFlight = true;
  state.pending = false;
  const sent = {...state.values};
  const started = performance.now();
  const busy = setTimeout(() => { $("busy").hidden = false; document.body.classList.add("stale"); }, BUSY_AFTER_MS);
  const previous = state.frame && !state.frame.error ?
    {values: state.frame.values, modes: state.frame.modes.map(m => ({id: m.id, joints: m.joints}))} : null;
  post("/api/solve", {values: sent, method: state.method, previous, next_id: state.next_id})
    .then(answer => answer.json())
    .then(frame => {
      frame.values = sent;
      if (frame.error && state.frame && !state.frame.error) frame.previousModes = state.frame.modes;
      showFrame(frame, performance.now() - started);
    })
    .catch(error => showError(error.message))
    .finally(() => {
      clearTimeout(busy);
      $("busy").hidden = true;
      document.body.classList.remove("stale");
      state.inFlight = false;
      if (state.pending) requestRedraw();
      else { const waiters = state.waiters; state.waiters = []; waiters.forEach(resolve => resolve()); }
    });
}

// ---- controls -----------------------------------------------------------------------
function shown(control, value) {   // the number a control's widgets show
  return control.kind === "squared distance" && state.units === "length" ? Math.sqrt(value) : value;
}
function stored(control, value) {  // the value the server gets
  return control.kind === "squared distance" && state.units === "length" ? value * value : value;
}
function label(control) {
  if (control.kind === "squared distance") {
    const [a, b] = control.name.split(",");
    return state.units === "length" ? `|${a}${b}|` : `s${a.slice(1)},${b.slice(1)}`;
  }
  return control.kind === "angle" ? `α ${control.name}` : control.name;
}

function buildControls() {
  const box = $("controls");
  box.textContent = "";
  const groups = new Map();
  for (const control of state.document.controls) {
    const key = control.link ?? (control.kind === "input" ? "inputs" : "actuators");
    if (!groups.has(key)) groups.set(key, []);
    groups.get(key).push(control);
  }
  const ground = state.document.ground;
  for (const [link, controls] of groups) {
    const group = html("div", {class: "link-group", "data-link": link}, null, box);
    html("h3", {}, link === ground ? `${link} (fixed link)` : link, group);
    for (const control of controls) group.appendChild(controlRow(control));
  }
}

function controlRow(control) {
  const row = html("div", {class: "control", "data-name": control.name, title: describe(control)});
  const name = html("label", {}, label(control), row);
  const step = (shown(control, control.high) - shown(control, control.low)) / 1000;
  const range = html("input", {type: "range", min: shown(control, control.low), max: shown(control, control.high),
                               step: step, value: shown(control, state.values[control.name])}, null, row);
  const number = html("input", {type: "number", step: "any", value: formatted(shown(control, state.values[control.name]))},
                      null, row);
  range.addEventListener("input", () => {
    if (control.kind === "input" && state.follow) { state.follow = null; state.highlighted = null; }
    setValue(control.name, stored(control, +range.value), false);
    number.value = formatted(+range.value);
  });
  number.addEventListener("change", () => {
    if (number.value === "" || !isFinite(+number.value)) return;
    setValue(control.name, stored(control, +number.value), false);
    range.value = number.value;
  });
  for (const widget of [name, range, number]) widget.addEventListener("focus", () => activate(control.name));
  name.addEventListener("click", () => activate(control.name));
  return row;
}

function describe(control) {
  const what = {"squared distance": `distance of ${control.name.replace(",", " and ")} on link ${control.link}`,
                "angle": `the slider's axis angle (degrees) on link ${control.link}`,
                "actuator": "the leg's actuated joint", "input": "the driven input"}[control.kind];
  return `${control.name}: ${what}`;
}

function setValue(name, value, updateWidgets = true) {
  state.values[name] = value;
  if (updateWidgets) {
    const control = state.document.controls.find(c => c.name === name);
    const row = document.querySelector(`.control[data-name="${CSS.escape(name)}"]`);
    if (row && control) {
      row.querySelector("input[type=range]").value = shown(control, value);
      row.querySelector("input[type=number]").value = formatted(shown(control, value));
    }
  }
  if (state.active === name) drawProfile();
  requestRedraw();
  return new Promise(resolve => state.waiters.push(resolve));
}

function idle() {
  return state.inFlight || state.pending ? new Promise(resolve => state.waiters.push(resolve)) : Promise.resolve();
}

function activate(name) {
  if (state.active === name) return;
  state.active = name;
  document.querySelectorAll(".control").forEach(row => row.classList.toggle("active", row.dataset.name === name));
  $("profile-box").hidden = false;
  $("profile-name").textContent = label(state.document.controls.find(c => c.name === name));
  $("profile-note").textContent = "(counting…)";
  state.profile = null;
  drawProfile();
  post("/api/profile", {values: state.values, name, samples: 121})
    .then(answer => answer.json())
    .then(profile => { if (state.active === name) { state.profile = profile; drawProfile(); } })
    .catch(error => { $("profile-note").textContent = error.message; });
}

function drawProfile() {
  const svg = $("profile");
  svg.textContent = "";
  const control = state.document.controls.find(c => c.name === state.active);
  if (!control) return;
  const low = shown(control, control.low), high = shown(control, control.high);
  const x = value => 1000 * (shown(control, value) - low) / (high - low);
  svg.setAttribute("viewBox", "0 0 1000 100");
  const profile = state.profile;
  if (profile) {
    const most = Math.max(1, ...profile.counts.filter(c => c !== null));
    const at = profile.values.map(x);   // samples are even in the stored unit, not always in the shown one
    profile.values.forEach((value, k) => {
      const left = k === 0 ? at[0] : (at[k - 1] + at[k]) / 2;
      const right = k === at.length - 1 ? at[k] : (at[k] + at[k + 1]) / 2;
      const count = profile.counts[k], width = Math.max(right - left, 0.5);
      if (count === null) el("rect", {class: "none", x: left, y: 0, width, height: 100}, svg);
      else if (count > 0) el("rect", {class: "count", x: left, y: 100 - 90 * count / most, width, height: 90 * count / most}, svg);
    });
    for (const change of profile.changes) {
      const line = el("line", {class: "change", x1: x(change.value), x2: x(change.value), y1: 0, y2: 100}, svg);
      el("title", {}, line).textContent = `${label(control)} = ${formatted(shown(control, change.value))}: ` +
        `${change.before ?? "no linkage"} → ${change.after ?? "no linkage"} modes`;
    }
    const counts = profile.counts.filter(c => c !== null);
    $("profile-note").textContent = counts.length ? `(${Math.min(...counts)} to ${most} real modes; ` +
      `${profile.changes.length} changes; click to set)` : "(no linkage in this range)";
  }
  el("line", {class: "now", x1: x(state.values[control.name]), x2: x(state.values[control.name]), y1: 0, y2: 100}, svg);
}

// ---- drawing ------------------------------------------------------------------------
function newDrawing(parent, view) {
  const svg = el("svg", {viewBox: `${view[0]} ${-(view[1] + view[3])} ${view[2]} ${view[3]}`,
                         preserveAspectRatio: "xMidYMid meet"}, parent);
  return svg;
}

function drawShapes(svg, shapes, hue, extent, options = {}) {
  const g = el("g", {class: options.className ?? "mode"}, svg);
  for (const link of shapes.links) {
    const points = link.points.map(([x, y]) => `${x},${-y}`).join(" ");
    if (link.ground) {
      if (options.skipGround) continue;
      if (link.points.length === 2) el("polyline", {class: "bar", points, stroke: "#333", "stroke-width": "6px"}, g);
      else el("polygon", {class: "body ground", points}, g);
    } else if (link.points.length === 2) {
      el("polyline", {class: "bar", points, stroke: hue, "stroke-width": "3.5px"}, g);
    } else {
      el("polygon", {class: "body", points, fill: hue, "fill-opacity": 0.18, stroke: hue, "stroke-width": "1.5px"}, g);
    }
  }
  for (const corners of shapes.blocks ?? []) {   // a robot's actuated prismatic joint
    el("polygon", {class: "body", points: corners.map(([x, y]) => `${x},${-y}`).join(" "), fill: "#fff", stroke: hue,
                   "stroke-width": "1.5px"}, g);
  }
  for (const [start, end] of shapes.axes) el("line", {class: "axis", x1: start[0], y1: -start[1], x2: end[0], y2: -end[1]}, g);
  const radius = 0.009 * extent;
  for (const joint of shapes.joints) {
    const [x, y] = joint.point;
    if (joint.slider) el("rect", {class: "joint", x: x - radius, y: -y - radius, width: 2 * radius, height: 2 * radius,
                                  stroke: hue}, g);
    else el("circle", {class: "joint", cx: x, cy: -y, r: radius, stroke: hue}, g);
    if (options.labels) {
      const text = el("text", {class: "label", x: x + 1.6 * radius, y: -y - 1.6 * radius, "font-size": (options.labelSize ?? 0.03) * extent}, g);
      text.textContent = joint.names.join("=");
    }
  }
  return g;
}

function groundShapes(shapes) {   // the fixed link and its joints, drawn once under the modes
  const ground = shapes.links.find(l => l.ground);
  const corners = new Set((ground ? ground.points : []).map(p => p.join(",")));
  return {links: ground ? [ground] : [], axes: [], joints: shapes.joints.filter(j => corners.has(j.point.join(",")))};
}

function render() {
  const frame = state.frame;
  const box = $("drawings");
  box.textContent = "";
  const layout = $("layout").value;
  box.className = layout;
  const view = state.view;
  const extent = Math.max(view[2], view[3]);
  setHatch(extent);
  const modes = frame.error ? (frame.previousModes ?? []) : frame.modes;
  if (layout === "overlay" || modes.length === 0) {
    const svg = newDrawing(box, view);
    svg.id = "drawing";
    drawPaths(svg);
    if (modes.length) drawShapes(svg, groundShapes(modes[0].shapes), "#333", extent, {className: "ground-link", labels: true});
    for (const mode of modes) {
      const g = drawShapes(svg, mode.shapes, colour(mode.id), extent,
                           {skipGround: true, labels: state.highlighted === mode.id});
      g.dataset.id = mode.id;
      if (state.highlighted !== null && state.highlighted !== mode.id) g.classList.add("faded");
    }
    drawGhosts(svg, extent);
  } else {
    for (const mode of modes) {
      const svg = newDrawing(box, view);
      const g = drawShapes(svg, mode.shapes, colour(mode.id), extent, {labels: true, labelSize: 0.05});
      g.dataset.id = mode.id;
      const caption = el("text", {class: "caption", x: view[0] + 0.03 * extent, y: -(view[1] + view[3]) + 0.07 * extent,
                                  "font-size": 0.05 * extent, fill: colour(mode.id)}, svg);
      caption.textContent = `mode ${mode.id + 1} ${mode.signs ? "(" + mode.signs + ")" : ""}`;
    }
  }
  renderLegend(modes);
  if (state.motion) drawMotion();
}

function setHatch(extent) {
  let defs = $("shared-defs");
  if (!defs) {
    const holder = el("svg", {width: 0, height: 0, style: "position:absolute"}, document.body);
    defs = el("defs", {id: "shared-defs"}, holder);
  }
  defs.textContent = "";
  const size = 0.02 * extent;
  const pattern = el("pattern", {id: "hatch", patternUnits: "userSpaceOnUse", width: size, height: size,
                                 patternTransform: "rotate(45)"}, defs);
  el("rect", {width: size, height: size, fill: "#f1f1f1"}, pattern);
  el("line", {x1: 0, y1: 0, x2: 0, y2: size, stroke: "#777", "stroke-width": size / 4}, pattern);
}

function drawGhosts(svg, extent) {
  const recent = state.events.filter(event => performance.now() - event.time < 2500);
  for (const event of recent) {
    for (const configuration of event.configurations) {
      drawShapes(svg, configuration.shapes, "#888", extent, {className: "ghost-mode", skipGround: true});
    }
  }
  svg.querySelectorAll(".ghost-mode .bar, .ghost-mode .body, .ghost-mode .joint").forEach(node => {
    node.setAttribute("class", "ghost");
  });
}

function renderLegend(modes) {
  const legend = $("legend");
  legend.textContent = "";
  for (const mode of [...modes].sort((a, b) => a.id - b.id)) {
    const chip = html("span", {class: "chip", "data-id": mode.id}, null, legend);
    html("span", {class: "swatch", style: `background:${colour(mode.id)}`}, null, chip);
    const values = Object.entries(mode.parameters).map(([name, value]) => `${name} = ${formatted(value)}`).join(", ");
    const pose = mode.pose ? `; platform at (${formatted(mode.pose.position[0])}, ${formatted(mode.pose.position[1])}),` +
      ` ${formatted(mode.pose.angle)}°` : "";
    html("span", {}, `mode ${mode.id + 1}${mode.signs ? " (" + mode.signs + ")" : ""}: ${values}${pose}`, chip);
    chip.addEventListener("mouseenter", () => { state.highlighted = mode.id; render(); });
    chip.addEventListener("mouseleave", () => { state.highlighted = null; render(); });
  }
}

// ---- a moving linkage: its whole motion ------------------------------------------------
function requestTrace() {
  $("motion-note").textContent = "(tracing…)";
  post("/api/trace", {values: state.values})
    .then(answer => answer.json())
    .then(motion => {
      state.motion = motion;
      const input = state.document.controls.find(c => c.name === motion.input);
      $("motion-input").textContent = input ? label(input) : motion.input;
      $("motion-parameter").textContent = motion.parameter;
      $("motion-note").textContent = `(${motion.circuits.length} circuit${motion.circuits.length === 1 ? "" : "s"}, ` +
        `${motion.pieces.length} pieces, ${motion.branch_points} branch points` +
        (motion.loose_ends ? `, ${motion.loose_ends} piece ends not joined)` : ")");
      state.shownPoints = new Set(motion.points);
      state.follow = null;
      pointChoices();
      growView([], motion.pieces.flatMap(piece => Object.values(piece.paths).flat()));
      drawMotion();
      render();
    })
    .catch(error => { $("motion-note").textContent = error.message; });
}

function pointChoices() {   // which points' paths (coupler curves) are drawn
  const box = $("point-choices");
  box.textContent = "";
  for (const name of Object.keys(state.motion.pieces[0]?.paths ?? {})) {
    const choice = html("label", {}, null, box);
    const tick = html("input", {type: "checkbox", value: name}, null, choice);
    tick.checked = state.shownPoints.has(name);
    choice.append(` ${name}`);
    tick.addEventListener("change", () => {
      if (tick.checked) state.shownPoints.add(name); else state.shownPoints.delete(name);
      render();
    });
  }
}

function drawPaths(svg) {   // the chosen points' paths (coupler curves) behind the modes
  if (!state.motion) return;
  for (const piece of state.motion.pieces) {
    for (const [name, path] of Object.entries(piece.paths)) {
      if (state.shownPoints.has(name)) {
        el("polyline", {class: "path", points: path.map(([x, y]) => `${x},${-y}`).join(" ")}, svg);
      }
    }
  }
}

function followedMode() {   // the drawn mode nearest to the followed piece's configuration
  const {piece, index} = state.follow;
  const paths = state.motion.pieces[piece].paths;
  let best = null, distance = Infinity;
  for (const mode of state.frame.modes ?? []) {
    let far = 0;
    for (const [name, at] of Object.entries(mode.joints)) {
      if (paths[name]) far = Math.max(far, Math.hypot(at[0] - paths[name][index][0], at[1] - paths[name][index][1]));
    }
    if (far < distance) { distance = far; best = mode.id; }
  }
  return best;
}

function follow(piece, index) {   // move to a piece's configuration: its input value, its mode highlighted
  state.follow = {piece, index, direction: state.follow?.direction ?? 1};
  return setValue(state.motion.input, state.motion.pieces[piece].inputs[index]);
}

function nearestPiecePoint(event) {
  const box = $("motion").getBoundingClientRect();
  const {x, y} = motionScale();
  let best = null, distance = 15;   // pixels
  state.motion.pieces.forEach((piece, p) => piece.inputs.forEach((value, k) => {
    const dx = (x(value) / 1000) * box.width - (event.clientX - box.left);
    const dy = (y(piece.parameters[k]) / 100) * box.height - (event.clientY - box.top);
    if (Math.hypot(dx, dy) < distance) { distance = Math.hypot(dx, dy); best = [p, k]; }
  }));
  return best;
}

function motionScale() {
  const motion = state.motion;
  const input = state.document.controls.find(c => c.name === motion.input);
  const ys = motion.pieces.flatMap(piece => piece.parameters);
  const low = Math.min(...ys), high = Math.max(...ys), pad = 0.05 * (high - low || 1);
  return {input, x: value => 1000 * (value - input.low) / (input.high - input.low),
          y: value => 100 - 100 * (value - low + pad) / (high - low + 2 * pad)};
}

function drawMotion() {
  const svg = $("motion");
  svg.textContent = "";
  if (!state.motion) return;
  svg.setAttribute("viewBox", "0 0 1000 100");
  const {input, x, y} = motionScale();
  const wraps = state.motion.input_kind === "angle";
  for (const piece of state.motion.pieces) {
    let run = [];
    piece.inputs.forEach((value, k) => {
      if (wraps && k > 0 && Math.abs(value - piece.inputs[k - 1]) > 180) {   // across ±180°: a new run
        el("polyline", {class: "piece", points: run.join(" ")}, svg);
        run = [];
      }
      run.push(`${x(value)},${y(piece.parameters[k])}`);
    });
    if (piece.closed && !wraps) run.push(`${x(piece.inputs[0])},${y(piece.parameters[0])}`);
    el("polyline", {class: "piece", points: run.join(" ")}, svg);
  }
  const now = state.values[input.name];
  el("line", {class: "now", x1: x(now), x2: x(now), y1: 0, y2: 100}, svg);
  if (state.follow) {
    const piece = state.motion.pieces[state.follow.piece];
    el("ellipse", {class: "followed", cx: x(piece.inputs[state.follow.index]), cy: y(piece.parameters[state.follow.index]),
                   rx: 9, ry: 7}, svg);
  }
  const [u, v] = state.motion.parameter_joints;
  for (const mode of (state.frame && state.frame.modes) || []) {
    if (!(u in mode.joints && v in mode.joints)) continue;
    const [a, b] = [mode.joints[u], mode.joints[v]];
    const value = (a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2;
    el("ellipse", {cx: x(now), cy: y(value), rx: 5, ry: 4, fill: colour(mode.id)}, svg);
  }
}

function togglePlay() {
  if (state.playing) { clearInterval(state.playing); state.playing = null; $("play").textContent = "▶ animate"; return; }
  const input = state.document.controls.find(c => c.name === state.motion.input);
  const step = (input.high - input.low) / 240;
  let direction = 1;
  $("play").textContent = "❚❚ stop";
  state.playing = setInterval(() => {
    if (state.inFlight) return;   // one redraw at a time: the animation goes as fast as redraws do
    if (state.follow) {   // along the followed piece, through its folds: the input turns back there
      const piece = state.motion.pieces[state.follow.piece], last = piece.inputs.length - 1;
      let next = state.follow.index + state.follow.direction;
      if (piece.closed) next = (next + last + 1) % (last + 1);
      else if (next < 0 || next > last) { state.follow.direction = -state.follow.direction; next = state.follow.index; }
      follow(state.follow.piece, next);
      return;
    }
    let value = state.values[input.name] + direction * step;
    if (state.motion.input_kind === "angle") value = value > 180 ? value - 360 : value;
    else if (value > input.high || value < input.low) { direction = -direction; value += 2 * direction * step; }
    setValue(input.name, value);
  }, 1000 / 30);
}

// ---- a redraw arrives -----------------------------------------------------------------
function showFrame(frame, milliseconds) {
  state.frame = frame;
  state.next_id = frame.next_id ?? state.next_id;
  growView(frame.modes ?? []);
  state.redraws += 1;
  state.redrawTimes.push(performance.now());
  if (state.redrawTimes.length > 60) state.redrawTimes.shift();
  for (const event of frame.events ?? []) recordEvent(event);
  if (state.follow && state.motion && !frame.error) state.highlighted = followedMode();
  const error = $("error");
  error.hidden = !frame.error;
  error.textContent = frame.error ? `No assembly mode drawn: ${frame.error}` : "";
  const count = frame.error ? null : frame.modes.length;
  $("count").textContent = count === null ? "" : `${count} assembly mode${count === 1 ? "" : "s"}`;
  const certificate = $("certificate");
  certificate.textContent = frame.error ? "" : `· ${frame.certificate}` +
    (count === 0 && frame.complete ? " — the linkage cannot be assembled with these dimensions" : "");
  certificate.className = frame.error ? "" : (frame.complete ? "complete" : "incomplete");
  $("timing").textContent = `solve ${(1000 * (frame.seconds ?? 0)).toFixed(1)} ms, redraw ${milliseconds.toFixed(0)} ms` +
    (fps() ? `, ${fps().toFixed(0)} redraws/s` : "");
  render();
}

function fps() {
  const times = state.redrawTimes.filter(t => performance.now() - t < 1000);
  return times.length > 1 ? (times.length - 1) / ((times[times.length - 1] - times[0]) / 1000) : 0;
}

function recordEvent(event) {
  event.time = performance.now();
  state.events.push(event);
  const control = state.document.controls.find(c => c.name === event.dimension);
  const where = control ? `${label(control)} = ${formatted(shown(control, event.value))}` : "";
  const difference = Math.abs(event.after - event.before);
  const what = event.kind === "merge"
    ? (difference === 1 ? "two modes meet in a double mode" : `${difference} modes meet and leave the real plane`)
    : (difference === 1 ? "a double mode splits in two" : `${difference} modes appear`);
  const item = html("li", {"data-kind": event.kind}, `${where}: ${what} (${event.before} → ${event.after})`);
  $("events").prepend(item);
}

function showError(message) {
  const error = $("error");
  error.hidden = false;
  error.textContent = message;
}

// ---- exports ------------------------------------------------------------------------
async function exportAs(kind) {
  try {
    if (kind === "svg") return download(new Blob([drawingSvg()], {type: "image/svg+xml"}), "explored.svg");
    const route = {"scene": "scene", "modes-json": "modes", "modes-csv": "modes", "png": "png"}[kind];
    const answer = await post(`/api/export/${route}`, {values: state.values, method: state.method,
                                                        format: kind === "modes-csv" ? "csv" : "json"});
    const name = (answer.headers.get("Content-Disposition") || "").match(/filename="([^"]+)"/);
    download(await answer.blob(), name ? name[1] : `explored-${kind}`);
  } catch (error) { showError(`export ${kind}: ${error.message}`); }
}

function drawingSvg() {   // the overlay with every label, as a standalone file
  const holder = document.createElement("div");
  const view = state.view, extent = Math.max(view[2], view[3]);
  const svg = newDrawing(holder, view);
  svg.setAttribute("xmlns", SVG);
  const style = el("style", {}, svg);
  style.textContent = ".bar{fill:none;stroke-linecap:round}.ground{fill:#eee;stroke:#333}.axis{stroke:#555;" +
    "stroke-dasharray:6 4}.joint{fill:#fff}.label{fill:#222}";
  for (const mode of state.frame.modes ?? []) drawShapes(svg, mode.shapes, colour(mode.id), extent, {labels: true});
  return new XMLSerializer().serializeToString(svg);
}

function download(blob, name) {
  const link = html("a", {href: URL.createObjectURL(blob), download: name});
  document.body.appendChild(link);
  link.click();
  link.remove();
}

function boxAround(points, margin) {   // [x, y, width, height] of the points, widened by margin · extent
  const xs = points.map(p => p[0]), ys = points.map(p => p[1]);
  const low = [Math.min(...xs), Math.min(...ys)], high = [Math.max(...xs), Math.max(...ys)];
  const pad = margin * Math.max(high[0] - low[0], high[1] - low[1], 1e-9);
  return [low[0] - pad, low[1] - pad, high[0] - low[0] + 2 * pad, high[1] - low[1] + 2 * pad];
}

function growView(modes, extra = []) {   // never shrinks: the drawing stays still while modes move inside it
  const points = modes.flatMap(mode => Object.values(mode.joints)).concat(extra);
  if (!points.length || !state.view) return;
  const [x, y, width, height] = state.view;
  const outside = points.some(([px, py]) => px < x || py < y || px > x + width || py > y + height);
  if (outside) state.view = boxAround(points.concat([[x, y], [x + width, y + height]]), 0.08);
}

function fitView() {
  const points = (state.frame.modes ?? []).flatMap(mode => Object.values(mode.joints));
  if (!points.length) return;
  state.view = boxAround(points, 0.12);
  render();
}

async function start() {
  state.units = $("units").value;
  const answer = await fetch("/api/document");
  const documentInfo = await answer.json();
  state.document = documentInfo;
  state.method = documentInfo.method;
  state.view = documentInfo.view;
  for (const control of documentInfo.controls) state.values[control.name] = control.value;
  $("title").textContent = documentInfo.title;
  $("kind").textContent = documentInfo.kind === "robot" ? "robot" : `scene, ${documentInfo.controls.length} dimensions`;
  document.title = `${documentInfo.title} — baranov explore`;
  const method = $("method");
  for (const name of documentInfo.methods) html("option", {value: name}, name, method);
  method.value = state.method;
  method.addEventListener("change", () => { state.method = method.value; requestRedraw(); });
  $("layout").addEventListener("change", render);
  $("units").addEventListener("change", () => { state.units = $("units").value; buildControls(); drawProfile(); });
  $("fit").addEventListener("click", fitView);
  $("reset").addEventListener("click", () => {
    for (const control of state.document.controls) state.values[control.name] = control.value;
    buildControls();
    state.follow = null;
    state.highlighted = null;
    requestRedraw();
  });
  $("filter").addEventListener("input", () => {
    const text = $("filter").value.trim().toLowerCase();
    document.querySelectorAll(".control").forEach(row => {
      row.hidden = text !== "" && !(row.dataset.name.toLowerCase().includes(text) ||
                                    row.parentElement.dataset.link.toLowerCase().includes(text));
    });
  });
  document.querySelectorAll("[data-export]").forEach(button =>
    button.addEventListener("click", () => exportAs(button.dataset.export)));
  $("profile").addEventListener("click", event => {
    const control = state.document.controls.find(c => c.name === state.active);
    if (!control) return;
    const box = $("profile").getBoundingClientRect();
    const fraction = (event.clientX - box.left) / box.width;
    const low = shown(control, control.low), high = shown(control, control.high);
    setValue(control.name, stored(control, low + fraction * (high - low)));
  });
  buildControls();
  documentInfo.frame.values = {...state.values};
  showFrame(documentInfo.frame, 0);
  if (documentInfo.mobility > 0) {
    $("motion-box").hidden = false;
    $("trace").addEventListener("click", requestTrace);
    $("play").addEventListener("click", togglePlay);
    $("motion").addEventListener("click", event => {
      if (!state.motion) return;
      const near = nearestPiecePoint(event);
      if (near) { follow(...near); return; }
      state.follow = null;
      state.highlighted = null;
      const input = state.document.controls.find(c => c.name === state.motion.input);
      const box = $("motion").getBoundingClientRect();
      setValue(input.name, input.low + (event.clientX - box.left) / box.width * (input.high - input.low));
    });
    requestTrace();
  }
}

// what the browser tests and the frame-rate script drive
window.explorer = {state, setValue, idle, activate, render, fps, requestTrace, follow, ready: start()};
