"use strict";
// NAME.html's script: draws the mechanism at a row of the sweep (the JSON in #sweep), plays the sweep,
// traces the chosen points and moves a cursor over every plot panel.  Model coordinates are kept as
// they are: one transform scales them to the view (VIEW units across) and flips y, so a pair's cx and
// cy are its x and y at the row; the labels are placed in the view's units (a browser caps font sizes,
// which a mechanism a million millimetres across would reach in model units).
(function () {
  const D = JSON.parse(document.getElementById("sweep").textContent);
  const NS = "http://www.w3.org/2000/svg";
  const COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#ff7f0e"];
  const SWEEP_SECONDS = 6;  // one sweep at speed 1
  const svg = document.getElementById("mechanism");
  const slider = document.getElementById("row");
  const play = document.getElementById("play");
  const speed = document.getElementById("speed");
  const readout = document.getElementById("readout");

  function make(tag, attrs, parent) {
    const el = document.createElementNS(NS, tag);
    for (const key in attrs) el.setAttribute(key, attrs[key]);
    if (parent) parent.appendChild(el);
    return el;
  }

  // the view: the box of every place over the sweep, padded
  const [x0, y0, x1, y1] = D.box;
  const span = Math.max(x1 - x0, y1 - y0, 1e-9);
  const pad = 0.08 * span;
  const VIEW = 1000, k = VIEW / (span + 2 * pad);
  const left = x0 - pad, top = y1 + pad;  // the view's corner in model coordinates
  svg.setAttribute("viewBox", [0, 0, (x1 - x0 + 2 * pad) * k, (y1 - y0 + 2 * pad) * k].join(" "));
  svg.setAttribute("preserveAspectRatio", "xMidYMid meet");
  const LABEL_PX = 12;  // the pairs' names, in screen pixels
  const unit = span / 60;  // the size of a pair's mark, in model units
  const world = make("g", {transform: "matrix(" + [k, 0, 0, -k, -left * k, top * k].join(",") + ")"}, svg);
  const traces = make("g", {id: "trace-layer"}, world);
  const links = make("g", {id: "link-layer"}, world);
  const marks = make("g", {id: "pair-layer"}, world);
  const labels = make("g", {id: "label-layer", "font-family": "Helvetica, Arial, sans-serif"}, svg);
  function fit() {  // the drawing's height follows the mechanism's shape, within reason; labels stay 12 px
    const w = (x1 - x0 + 2 * pad) * k, h = (y1 - y0 + 2 * pad) * k;
    const height = Math.max(220, Math.min(520, svg.clientWidth * h / w));
    svg.style.height = height.toFixed(0) + "px";
    const pixels = Math.min(svg.clientWidth / w, height / h);  // per view unit (meet)
    labels.setAttribute("font-size", String(LABEL_PX / pixels));
  }
  fit();
  window.addEventListener("resize", fit);

  const traceOf = {};
  let colour = 0;
  for (const name in D.places) {
    const [xs, ys] = D.places[name];
    let d = "", pen = false;
    for (let k = 0; k < D.rows; k++) {
      if (xs[k] === null || ys[k] === null) { pen = false; continue; }
      d += (pen ? "L" : "M") + xs[k] + " " + ys[k];
      pen = true;
    }
    traceOf[name] = make("path", {d: d, fill: "none", stroke: COLOURS[colour++ % COLOURS.length],
      "stroke-width": "1.6", "vector-effect": "non-scaling-stroke", "data-name": name, visibility: "hidden"}, traces);
  }
  const linkEls = D.links.map(function (link, k) {
    const fixed = link.fixed;
    const c = fixed ? "#6b7280" : COLOURS[k % COLOURS.length];
    const el = make(link.members.length > 2 ? "polygon" : "polyline", {
      fill: link.members.length > 2 ? c : "none", "fill-opacity": "0.14", stroke: c, "stroke-width": fixed ? "2" : "4",
      "stroke-linejoin": "round", "stroke-linecap": "round", "vector-effect": "non-scaling-stroke",
      "stroke-dasharray": fixed ? "7 4" : "none", class: "link", "data-name": link.name}, links);
    return [link, el];
  });
  const pivots = new Set(D.pivots), points = new Set(D.points);
  const sliders = new Map(D.sliders.map(function (s) { return [s.name, s]; }));
  for (const s of D.sliders) {  // a guide fixed to the frame: its line over the slider's travel, drawn once
    if (!s.fixed) continue;
    const [xs, ys] = D.places[s.name];
    const ux = Math.cos(s.axis), uy = Math.sin(s.axis);
    let low = Infinity, high = -Infinity, across = 0;
    for (let k = 0; k < D.rows; k++) {
      if (xs[k] === null || ys[k] === null) continue;
      const t = xs[k] * ux + ys[k] * uy;
      low = Math.min(low, t); high = Math.max(high, t);
      across = -xs[k] * uy + ys[k] * ux;
    }
    if (low > high) continue;
    low -= 2 * unit; high += 2 * unit;
    make("path", {d: "M" + (low * ux - across * uy) + " " + (low * uy + across * ux) + "L" + (high * ux - across * uy) + " " +
      (high * uy + across * ux), stroke: "#374151", "stroke-width": "1.5", "vector-effect": "non-scaling-stroke",
      class: "guide"}, links);
  }
  for (const name of D.pivots) {  // ground hatch under each fixed pivot, drawn once
    const [xs, ys] = D.places[name];
    const x = xs[0], y = ys[0];
    make("path", {d: "M" + (x - 1.6 * unit) + " " + (y - 1.4 * unit) + "L" + (x + 1.6 * unit) + " " + (y - 1.4 * unit),
      stroke: "#374151", "stroke-width": "1.5", "vector-effect": "non-scaling-stroke"}, links);
    make("path", {d: "M" + x + " " + y + "L" + (x - unit) + " " + (y - 1.4 * unit) + "L" + (x + unit) + " " + (y - 1.4 * unit) + "Z",
      fill: "#e5e7eb", stroke: "#374151", "stroke-width": "1", "vector-effect": "non-scaling-stroke"}, links);
  }
  const markOf = {}, labelOf = {};
  for (const name in D.places) {
    if (sliders.has(name)) {
      make("rect", {width: 3 * unit, height: 2 * unit, fill: "#fff", stroke: "#111827", "stroke-width": "1.5",
        "vector-effect": "non-scaling-stroke", class: "slider", "data-for": name}, marks);
    }
    const r = points.has(name) ? 0.45 * unit : 0.7 * unit;
    markOf[name] = make("circle", {r: r, fill: pivots.has(name) ? "#374151" : points.has(name) ? "#111827" : "#fff",
      stroke: "#111827", "stroke-width": "1.5", "vector-effect": "non-scaling-stroke", class: "pair", "data-name": name}, marks);
    labelOf[name] = make("text", {fill: "#111827"}, labels);
    labelOf[name].textContent = name;
  }
  const sliderEls = Array.from(marks.querySelectorAll("rect.slider"));

  // a cursor line on every plot panel
  const cursors = Array.from(document.querySelectorAll("#plots g.panel")).map(function (g) {
    const top = +g.dataset.top, height = +g.dataset.height;
    return [g, make("line", {class: "cursor", y1: top, y2: top + height, x1: -10, x2: -10}, g)];
  });

  function statusText(code) {
    if (code === 0) return "<span class=ok>regular</span>";
    const step = Math.floor(Math.abs(code) / 10), reason = Math.abs(code) % 10;
    if (code < 0) return "<span class=warn>near a singular position at step " + step + "</span>";
    const why = {1: "the chain cannot close", 2: "the resolver did not converge", 3: "singular position (rates nan)",
      5: "input refused", 6: "the iteration does not contract"}[reason] || "reason " + reason;
    return "<span class=" + (reason === 3 ? "warn" : "bad") + ">status " + code + ": step " + step + ", " + why + "</span>";
  }

  function fmt(v) { return v === null ? "–" : (Math.abs(v) >= 1e5 || (v !== 0 && Math.abs(v) < 1e-3) ? v.toExponential(4) : v.toFixed(3)); }

  function show(row) {
    row = Math.max(0, Math.min(D.rows - 1, row | 0));
    document.body.dataset.row = String(row);  // the page's row; D.index[row] is the file's
    if (+slider.value !== row) slider.value = String(row);
    const at = {};
    for (const name in D.places) {
      const [xs, ys] = D.places[name];
      const x = xs[row], y = ys[row];
      const el = markOf[name];
      if (x === null || y === null) {
        el.setAttribute("visibility", "hidden");
        labelOf[name].setAttribute("visibility", "hidden");
        continue;
      }
      at[name] = [x, y];
      el.setAttribute("visibility", "visible");
      el.setAttribute("cx", String(x));
      el.setAttribute("cy", String(y));
      labelOf[name].setAttribute("visibility", "visible");
      labelOf[name].setAttribute("x", ((x - left + 0.9 * unit) * k).toFixed(2));
      labelOf[name].setAttribute("y", ((top - y - 0.9 * unit) * k).toFixed(2));
    }
    for (const rect of sliderEls) {
      const p = at[rect.dataset.for];
      rect.setAttribute("visibility", p ? "visible" : "hidden");
      if (!p) continue;
      const s = sliders.get(rect.dataset.for);
      rect.setAttribute("x", String(p[0] - 1.5 * unit));
      rect.setAttribute("y", String(p[1] - unit));
      let axis = s.axis;  // a moving guide turns the axis with it (two places fixed in the guide)
      if (!s.fixed && s.guide.length === 2 && at[s.guide[0]] && at[s.guide[1]]) {
        const [a, b] = [at[s.guide[0]], at[s.guide[1]]];
        axis += Math.atan2(b[1] - a[1], b[0] - a[0]) - s.turn;
      }
      if (s.fixed || s.guide.length === 2) rect.setAttribute("transform", "rotate(" + (axis * 180 / Math.PI) + " " + p[0] + " " + p[1] + ")");
    }
    for (const [link, el] of linkEls) {
      const pts = link.members.filter(function (n) { return at[n]; }).map(function (n) { return at[n].join(","); });
      el.setAttribute("points", pts.join(" "));
      el.setAttribute("visibility", pts.length === link.members.length ? "visible" : "hidden");
    }
    for (const [g, line] of cursors) {
      const a = +g.dataset.x0, b = +g.dataset.x1, left = +g.dataset.left, width = +g.dataset.width;
      const px = left + (D.x[row] - a) / (b - a) * width;
      line.setAttribute("x1", px.toFixed(2));
      line.setAttribute("x2", px.toFixed(2));
    }
    const inputs = D.inputs.map(function (i) { return "<b>" + i.column + "</b> = " + fmt(i.values[row]) + " " + i.unit; });
    const values = Array.from(document.querySelectorAll("#traces input:checked")).map(function (box) {
      const p = at[box.value];
      return "<tr><th>" + box.value + "</th><td>" + (p ? fmt(p[0]) : "–") + "</td><td>" + (p ? fmt(p[1]) : "–") + "</td></tr>";
    });
    readout.innerHTML = "row " + D.index[row] + " of " + D.index[D.rows - 1] + " · " + inputs.join(" · ") + "<br>" +
      statusText(D.status[row]) + (values.length ? "<table class=values><tr><th></th><th>x (" + D.unit + ")</th><th>y (" +
      D.unit + ")</th></tr>" + values.join("") + "</table>" : "");
  }

  function traced() {
    for (const box of document.querySelectorAll("#traces input")) {
      traceOf[box.value].setAttribute("visibility", box.checked ? "visible" : "hidden");
    }
  }

  let timer = null, clock = 0, position = 0;
  function tick() {
    const now = performance.now();
    position += (now - clock) / 1000 * (+speed.value) * (D.rows - 1) / SWEEP_SECONDS;
    clock = now;
    if (position > D.rows - 1) position = position % (D.rows - 1);
    show(Math.floor(position));
  }
  function toggle() {
    if (timer === null) {
      position = +slider.value;
      clock = performance.now();
      timer = setInterval(tick, 30);
      play.textContent = "Pause";
      play.classList.add("playing");
    } else {
      clearInterval(timer);
      timer = null;
      play.textContent = "Play";
      play.classList.remove("playing");
    }
  }

  play.addEventListener("click", toggle);
  slider.addEventListener("input", function () { position = +slider.value; show(+slider.value); });
  document.getElementById("traces").addEventListener("change", function () { traced(); show(+slider.value); });
  document.addEventListener("keydown", function (e) {
    if (e.target === slider) return;
    if (e.key === " ") { e.preventDefault(); toggle(); }
    else if (e.key === "ArrowRight") show(+slider.value + 1);
    else if (e.key === "ArrowLeft") show(+slider.value - 1);
  });
  traced();
  show(0);
})();
