// fcgrasp explorer: the page of `fcgrasp serve`. Plain JavaScript, no build step.
// The server plans (POST /api/plan, the same function as `fcgrasp plan`) and checks
// (POST /api/check, theorem 6.1); this page draws, edits and never blocks: plans run as
// jobs that it polls, a newer request cancels the older one.
"use strict";

const COLORS = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd"];
const SVGNS = "http://www.w3.org/2000/svg";
const $ = (id) => document.getElementById(id);
const svg = $("view");

const S = {
  part: null,        // {outer, holes, units, name}: what is drawn and edited
  good: null,        // the last part the server accepted
  plans: [], report: null, overlays: [], selected: 0, stressSeq: 0,
  mode: "edit", fingers: [], verdict: null,
  seq: 0, job: null, checkSeq: 0,
  view: null, drag: null, invalid: false, maxUpload: 8 << 20, anim: null,
  history: [],       // earlier accepted outlines of this part, for undo
  solid: null,       // a solid part (a mesh): {source, vertices, faces, units, ...}
};

// ------------------------------------------------------------------ server

// the session token the server wrote into this page: every API call carries it
const TOKEN = document.querySelector('meta[name="fcgrasp-token"]').content;

async function request(method, url, body, raw) {
  const opts = { method, headers: { "X-Fcgrasp-Token": TOKEN } };
  if (body !== undefined) {
    if (raw) { opts.body = body; } else {
      opts.body = JSON.stringify(body);
      opts.headers["Content-Type"] = "application/json";
    }
  }
  const r = await fetch(url, opts);
  let data;
  try { data = await r.json(); } catch (e) { data = { error: `the server answered ${r.status}` }; }
  if (!r.ok) {
    const err = new Error(data.error || `the server answered ${r.status}`);
    err.field = data.field; err.status = r.status;
    throw err;
  }
  return data;
}

const clone = (x) => JSON.parse(JSON.stringify(x));

function message(text, note) {
  const m = $("message");
  m.textContent = text || "";
  m.className = note ? "note" : "";
}

// ------------------------------------------------------------------ geometry

function rings(part) { return [part.outer, ...(part.holes || [])]; }

function signedArea(r) {
  let a = 0;
  for (let i = 0; i < r.length; i++) {
    const p = r[i], q = r[(i + 1) % r.length];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return a / 2;
}

// every edge in the server's numbering: outer ring first, then each hole
function edges(part) {
  const out = [];
  rings(part).forEach((r, ring) => {
    const ccw = signedArea(r) > 0;
    // outward from the material: right of a ccw outer ring, into a hole
    const sgn = (ring === 0) === ccw ? 1 : -1;
    r.forEach((p, i) => {
      const q = r[(i + 1) % r.length];
      const dx = q[0] - p[0], dy = q[1] - p[1], L = Math.hypot(dx, dy) || 1;
      out.push({ a: p, b: q, ring, i, n: [sgn * dy / L, -sgn * dx / L], len: L });
    });
  });
  return out;
}

function bounds(part) {
  const xs = part.outer.map((p) => p[0]), ys = part.outer.map((p) => p[1]);
  const minx = Math.min(...xs), maxx = Math.max(...xs);
  const miny = Math.min(...ys), maxy = Math.max(...ys);
  return { minx, miny, w: maxx - minx, h: maxy - miny, size: Math.hypot(maxx - minx, maxy - miny) };
}

function cross(o, a, b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

function segmentsCross(p, q, r, s) {
  const d1 = cross(r, s, p), d2 = cross(r, s, q), d3 = cross(p, q, r), d4 = cross(p, q, s);
  return ((d1 > 0) !== (d2 > 0)) && ((d3 > 0) !== (d4 > 0)) && d1 && d2 && d3 && d4;
}

// the edges that meet vertex (ring, index) against every other edge: a drag or a
// deletion changes only those, and the rest of the outline was good (O(n) per frame; a
// quick test, the server's Polygon check is the authority)
function crossesAt(part, ring, index) {
  const R = rings(part), r = R[ring], n = r.length;
  const moved = [[(index - 1 + n) % n, index], [index, (index + 1) % n]];
  for (const [i0, i1] of moved) {
    const p = r[i0], q = r[i1];
    for (let g = 0; g < R.length; g++) {
      const s = R[g], m = s.length;
      for (let j = 0; j < m; j++) {
        if (g === ring && (j === i0 || j === i1 || (j + 1) % m === i0)) continue;
        if (segmentsCross(p, q, s[j], s[(j + 1) % m])) return true;
      }
    }
  }
  return false;
}

function nearestOnBoundary(part, p) {
  let best = null;
  edges(part).forEach((e, k) => {
    const dx = e.b[0] - e.a[0], dy = e.b[1] - e.a[1];
    const L2 = dx * dx + dy * dy || 1;
    let t = ((p[0] - e.a[0]) * dx + (p[1] - e.a[1]) * dy) / L2;
    t = Math.max(0, Math.min(1, t));
    const q = [e.a[0] + t * dx, e.a[1] + t * dy];
    const d = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (!best || d < best.d) best = { d, point: q, edge: k, t, e };
  });
  return best;
}

// ------------------------------------------------------------------ view

function fit() {
  const r = svg.getBoundingClientRect();
  const W = Math.max(r.width, 100), H = Math.max(r.height, 100);
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  const b = bounds(S.part), m = 50;
  const s = Math.min((W - 2 * m) / (b.w || 1), (H - 2 * m) / (b.h || 1));
  S.view = { s, W, H, ox: (W - s * b.w) / 2 - s * b.minx, oy: (H + s * b.h) / 2 + s * b.miny,
             size: b.size, fit: s };
}

// zoom by `factor` about the screen point (x, y): the part's point under it stays put
function zoomAt(x, y, factor) {
  const v = S.view;
  const f = Math.min(Math.max(factor, v.fit / 20 / v.s), (v.fit * 1e4) / v.s);
  v.ox = x - (x - v.ox) * f;
  v.oy = y - (y - v.oy) * f;
  v.s *= f;
  render();
}

const X = (p) => [S.view.ox + S.view.s * p[0], S.view.oy - S.view.s * p[1]];
const toWorld = (x, y) => [(x - S.view.ox) / S.view.s, (S.view.oy - y) / S.view.s];

function eventPoint(ev) {
  const pt = svg.createSVGPoint();
  pt.x = ev.clientX; pt.y = ev.clientY;
  const q = pt.matrixTransform(svg.getScreenCTM().inverse());
  return [q.x, q.y];
}

function el(tag, attrs, parent) {
  const e = document.createElementNS(SVGNS, tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  (parent || svg).appendChild(e);
  return e;
}

const pts = (line) => line.map((p) => X(p).map((v) => v.toFixed(2)).join(",")).join(" ");
const fmt = (v) => (v === null || v === undefined ? "-" : Number(v).toPrecision(3));

function ringPath(part) {
  return rings(part).map((r) => "M" + r.map((p) => X(p).map((v) => v.toFixed(2)).join(","))
    .join("L") + "Z").join(" ");
}

function rot(n, a) {
  return [n[0] * Math.cos(a) - n[1] * Math.sin(a), n[0] * Math.sin(a) + n[1] * Math.cos(a)];
}

// a finger's push: the V of its friction cone (half-angle atan(mu)), or an arrow when
// frictionless; drawn outside the part, where the finger is
function drawPush(g, c, n, mu, color) {
  const L = 0.07 * S.view.size;
  if (mu > 0) {
    const a = Math.atan(mu), at = X(c);
    for (const sg of [1, -1]) {
      const d = rot(n, sg * a), end = X([c[0] + L * d[0], c[1] + L * d[1]]);
      el("line", { x1: at[0], y1: at[1], x2: end[0], y2: end[1], stroke: color || "#000",
                   "stroke-width": 1.4, class: "vee" }, g);
    }
  } else {
    const tip = X(c), tail = X([c[0] + L * n[0], c[1] + L * n[1]]);
    el("line", { x1: tail[0], y1: tail[1], x2: tip[0], y2: tip[1], stroke: color || "#000",
                 "stroke-width": 1.4, "marker-end": "url(#arrow)", class: "vee" }, g);
  }
}

// ------------------------------------------------------------------ handles, numbers, scale

//: screen pixels between two vertex handles, at least: a curve's vertices get handles
//: only where the zoom spreads them (or under the pointer), never a chain of beads
const HANDLE_GAP = 22;

const inView = (q, pad) => q[0] >= -pad && q[1] >= -pad && q[0] <= S.view.W + pad &&
  q[1] <= S.view.H + pad;

//: a vertex is a corner where the outline turns by more than this (radians) between the
//: points HANDLE_GAP pixels before and after it: noise and flattened curves are not
const CORNER = (25 * Math.PI) / 180;

// the outline's turn at each vertex of ring r on the screen (points q), measured between
// the chords to the vertices about HANDLE_GAP pixels back and ahead (at most 64 steps)
function screenTurns(q) {
  const n = q.length, out = new Float64Array(n);
  const far = (i, step) => {
    let j = i;
    for (let k = 0; k < Math.min(64, n - 1); k++) {
      j = (j + step + n) % n;
      if (Math.hypot(q[j][0] - q[i][0], q[j][1] - q[i][1]) >= HANDLE_GAP) break;
    }
    return q[j];
  };
  for (let i = 0; i < n; i++) out[i] = turnAt(far(i, -1), q[i], far(i, 1));
  return out;
}

// the turn (radians, 0 to pi) of the path a -> p -> b at p
function turnAt(a, p, b) {
  const u = [p[0] - a[0], p[1] - a[1]], w = [b[0] - p[0], b[1] - p[1]];
  return Math.abs(Math.atan2(u[0] * w[1] - u[1] * w[0], u[0] * w[0] + u[1] * w[1]));
}

// the outline's turn at vertex i of ring r
const turn = (r, i) => turnAt(r[(i - 1 + r.length) % r.length], r[i], r[(i + 1) % r.length]);

// spatial hashing of the screen: a cell's key, and the list of what a map holds in it
const cellKey = (cx, cy) => `${cx},${cy}`;
function bucket(map, key) {
  if (!map.has(key)) map.set(key, []);
  return map.get(key);
}

// the vertices that get a handle: the corners, and every vertex whose edges are
// HANDLE_GAP pixels long on the screen (all of a curve's, zoomed in far enough); sharpest
// first, each at least HANDLE_GAP pixels from the handles taken before it
function handleVertices() {
  const cand = [];
  rings(S.part).forEach((r, ring) => {
    const q = r.map(X), turns = screenTurns(q), n = r.length;
    const len = (i, j) => Math.hypot(q[j][0] - q[i][0], q[j][1] - q[i][1]);
    for (let i = 0; i < n; i++) {
      if (!inView(q[i], HANDLE_GAP)) continue;
      const spread = Math.min(len((i - 1 + n) % n, i), len(i, (i + 1) % n)) >= HANDLE_GAP;
      // sharpest first: on the screen's scale, then at the vertex itself (a corner's
      // neighbours turn as much on the screen's scale, not at themselves)
      if (turns[i] >= CORNER || spread) {
        cand.push({ ring, i, q: q[i], turn: turns[i] + turn(r, i) });
      }
    }
  });
  cand.sort((a, b) => b.turn - a.turn);
  const grid = new Map(), out = [];
  for (const c of cand) {
    const cx = Math.floor(c.q[0] / HANDLE_GAP), cy = Math.floor(c.q[1] / HANDLE_GAP);
    let free = true;
    for (let dx = -1; dx <= 1 && free; dx++) {
      for (let dy = -1; dy <= 1 && free; dy++) {
        for (const o of grid.get(cellKey(cx + dx, cy + dy)) || []) {
          if (Math.hypot(o.q[0] - c.q[0], o.q[1] - c.q[1]) < HANDLE_GAP) { free = false; break; }
        }
      }
    }
    if (!free) continue;
    out.push(c);
    bucket(grid, cellKey(cx, cy)).push(c);
  }
  return out;
}

function drawHandle(g, ring, i, extra) {
  const q = X(rings(S.part)[ring][i]);
  el("circle", { cx: q[0], cy: q[1], r: 5, class: "vertex" + (extra ? " " + extra : ""),
                 "data-ring": ring, "data-index": i }, g);
}

function segmentHitsBox(p, q, b) {
  // Liang-Barsky: does segment pq meet the box b = [x0, y0, x1, y1]?
  let t0 = 0, t1 = 1;
  const d = [q[0] - p[0], q[1] - p[1]];
  for (const [num, den] of [[p[0] - b[0], -d[0]], [b[2] - p[0], d[0]],
                            [p[1] - b[1], -d[1]], [b[3] - p[1], d[1]]]) {
    if (den === 0) { if (num < 0) return false; continue; }
    const t = num / den;
    if (den < 0) { if (t > t1) return false; if (t > t0) t0 = t; } else {
      if (t < t0) return false; if (t < t1) t1 = t;
    }
  }
  return true;
}

// what a number must not cover besides the outline: the selected plan's regions (bold:
// their segments padded) and its fingers' V's, as screen segments [a, b, pad]
function planSegments(plan) {
  const out = [];
  if (!plan || plan.gripper === "parallel_jaw") return out;
  for (const reg of plan.regions) {
    for (let i = 0; i + 1 < reg.length; i++) out.push([X(reg[i]), X(reg[i + 1]), 5]);
  }
  const mu = plan.contact_type === "friction" ? plan.mu : 0, L = 0.07 * S.view.size;
  plan.contacts.forEach((c, i) => {
    const n = plan.normals[i];
    for (const sg of mu > 0 ? [1, -1] : [0]) {
      const d = rot(n, sg * Math.atan(mu));
      out.push([X(c), X([c[0] + L * d[0], c[1] + L * d[1]]), 2]);
    }
  });
  return out;
}

// edge numbers, placed: each off its edge's middle on the outward side, longest edges on
// the screen first, kept only where its box meets no other number, no edge and nothing
// of the plan drawn
function edgeLabels(plan) {
  const E = edges(S.part), cell = 32, segs = new Map(), out = [];
  const cells = (b, fn) => {
    for (let cx = Math.floor(b[0] / cell); cx <= Math.floor(b[2] / cell); cx++) {
      for (let cy = Math.floor(b[1] / cell); cy <= Math.floor(b[3] / cell); cy++) {
        fn(cellKey(cx, cy));
      }
    }
  };
  const scr = E.map((e) => [X(e.a), X(e.b), 0]).concat(planSegments(plan));
  scr.forEach(([a, b, pad], k) => {
    if (!inView(a, 100) && !inView(b, 100)) return;
    if (Math.abs(a[0] - b[0]) + Math.abs(a[1] - b[1]) > 4 * Math.max(S.view.W, S.view.H)) return;
    cells([Math.min(a[0], b[0]) - pad, Math.min(a[1], b[1]) - pad, Math.max(a[0], b[0]) + pad,
           Math.max(a[1], b[1]) + pad], (c) => bucket(segs, c).push(k));
  });
  const placed = new Map();
  const order = E.map((e, k) => k).sort((i, j) => E[j].len - E[i].len);
  const fits = (box) => {
    if (box[0] < 0 || box[1] < 0 || box[2] > S.view.W || box[3] > S.view.H) return false;
    let free = true;
    cells(box, (c2) => {
      if (!free) return;
      for (const o of placed.get(c2) || []) {
        if (o[0] < box[2] && box[0] < o[2] && o[1] < box[3] && box[1] < o[3]) { free = false; return; }
      }
      for (const j of segs.get(c2) || []) {
        const [a, b, pad] = scr[j];
        if (segmentHitsBox(a, b, [box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad])) {
          free = false; return;
        }
      }
    });
    return free;
  };
  for (const k of order) {
    const e = E[k], [a, b] = scr[k];
    const w = 6.2 * String(k).length + 3, h = 12, n = [e.n[0], -e.n[1]];  // y down on screen
    const base = 3 + Math.abs(n[0]) * w / 2 + Math.abs(n[1]) * h / 2;
    // the middle first, then off along the edge (an edge under a region), then further out
    for (const [t, more] of [[0.5, 0], [0.3, 0], [0.7, 0], [0.15, 0], [0.85, 0], [0.5, 10],
                             [0.3, 10], [0.7, 10]]) {
      const at = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
      if (!inView(at, -4)) continue;
      const c = [at[0] + (base + more) * n[0], at[1] + (base + more) * n[1]];
      const box = [c[0] - w / 2, c[1] - h / 2, c[0] + w / 2, c[1] + h / 2];
      if (!fits(box)) continue;
      out.push({ k, c });
      cells(box, (c2) => bucket(placed, c2).push(box));
      break;
    }
  }
  return out;
}

// a scale bar of a round length (1, 2 or 5 times a power of ten) 60-150 pixels long
function drawScaleBar() {
  const most = 150 / S.view.s, p = 10 ** Math.floor(Math.log10(most));
  const L = [5, 2, 1].map((k) => k * p).find((v) => v <= most * (1 + 1e-9));
  const px = L * S.view.s, x0 = 16, y0 = S.view.H - 18;
  const g = el("g", { id: "scalebar", "data-length": L, "data-pixels": px.toFixed(3) });
  el("rect", { x: x0 - 6, y: y0 - 18, width: px + 12, height: 26, fill: "#fff",
               "fill-opacity": 0.8 }, g);
  el("path", { d: `M${x0},${y0 - 5}V${y0}H${x0 + px}V${y0 - 5}`, fill: "none", stroke: "#222",
               "stroke-width": 1.5 }, g);
  const units = S.report ? S.report.units : S.part.units || "";
  el("text", { x: x0 + px / 2, y: y0 - 7, "font-size": 11, fill: "#222",
               "text-anchor": "middle" }, g).textContent = `${+L.toPrecision(1)} ${units}`;
}

function render() {
  if (S.solid) { Solid3D.draw(S.plans[S.selected], S.report); return; }
  if (!S.part || !S.view) return;
  svg.textContent = "";
  const defs = el("defs");
  const mk = el("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 9, refY: 5,
                            markerWidth: 6, markerHeight: 6, orient: "auto-start-reverse" }, defs);
  el("path", { d: "M0,0L10,5L0,10z", fill: "#333" }, mk);
  el("rect", { x: 0, y: 0, width: S.view.W, height: S.view.H, fill: "#fff", id: "background" });
  el("path", { d: ringPath(S.part), "fill-rule": "evenodd", fill: "#e0e0e0",
               stroke: S.invalid ? "#d00" : "#404040", "stroke-width": S.invalid ? 2 : 1.2,
               id: "part-path" });
  // the handles under the plan (which lets the pointer through): regions stay visible
  if (S.mode === "edit") {
    const g = el("g", { class: "handle" });
    for (const h of handleVertices()) drawHandle(g, h.ring, h.i);
  }
  const plan = S.dragging ? null : S.plans[S.selected];
  if ($("edgenums").checked && !S.dragging) {
    const g = el("g", { class: "labels", "font-size": 10, fill: "#666",
                        "text-anchor": "middle", "dominant-baseline": "central" });
    for (const { k, c } of edgeLabels(plan)) {
      el("text", { x: c[0].toFixed(1), y: c[1].toFixed(1), "data-edge": k }, g).textContent =
        String(k);
    }
  }
  if (plan && $("overlay").checked) drawOverlay(S.overlays[S.selected]);
  if (plan) (plan.gripper === "parallel_jaw" ? drawJaw : drawPlan)(plan);
  el("text", { x: 12, y: 22, "font-size": 13, fill: "#333", id: "caption" }).textContent =
    plan ? caption(plan) : (S.part.name || "");
  drawFingers();
  drawScaleBar();
  el("g", { id: "hover", class: "handle" });
  el("text", { x: S.view.W - 12, y: S.view.H - 12, "font-size": 11, fill: "#555",
               "text-anchor": "end", id: "readout" });
  showHover();
}

// the pointer's place in the part's units and the edge under it; in edit mode, a handle
// on the vertex under the pointer where none is drawn (curves, seen from afar)
function showHover() {
  const g = $("hover"), t = $("readout");
  if (!g || !S.pointer) return;
  g.textContent = "";
  const p = toWorld(...S.pointer), u = S.part.units || "";
  const near = nearestOnBoundary(S.part, p);
  const onEdge = near && near.d * S.view.s <= 8;
  t.textContent = `x ${fmt(p[0])}, y ${fmt(p[1])} ${u}` + (onEdge ? `, edge ${near.edge}` : "");
  if (S.mode !== "edit" || S.drag || !onEdge) return;
  const r = rings(S.part)[near.e.ring], n = r.length;
  const i = near.t < 0.5 ? near.e.i : (near.e.i + 1) % n, q = X(r[i]);
  if (Math.hypot(q[0] - S.pointer[0], q[1] - S.pointer[1]) > 10) return;
  if (svg.querySelector(`.handle circle[data-ring="${near.e.ring}"][data-index="${i}"]`)) return;
  drawHandle(g, near.e.ring, i, "hover");
}

function caption(plan) {
  const u = S.report ? S.report.units : "";
  if (plan.gripper === "parallel_jaw") {
    return `rank ${plan.rank}: parallel jaw, box ${fmt(plan.measure)} ${u}, mu = ${plan.mu}`;
  }
  const mu = plan.contact_type === "friction" ? `mu = ${plan.mu}` : "frictionless";
  return `rank ${plan.rank}: edges ${plan.edges.join(", ")}, min region ` +
    `${fmt(plan.min_region_length)} ${u}, ${mu}`;
}

function drawPlan(plan) {
  const g = el("g", { id: "plan", "data-rank": plan.rank });
  const mu = plan.contact_type === "friction" ? plan.mu : 0;
  plan.regions.forEach((reg, i) => {
    el("polyline", { points: pts(reg), fill: "none", stroke: COLORS[i % 4], "stroke-width": 7,
                     "stroke-linecap": "butt", "stroke-linejoin": "round", class: "region",
                     "data-finger": i }, g);
  });
  plan.contacts.forEach((c, i) => drawPush(g, c, plan.normals[i], mu, "#000"));
  if (plan.gravity) {
    const c = plan.gravity.center, d = plan.gravity.direction, L = 0.1 * S.view.size;
    const a = X(c), b = X([c[0] + L * d[0], c[1] + L * d[1]]);
    el("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: "#333", "stroke-width": 1.6,
                 "marker-end": "url(#arrow)", class: "gravity" }, g);
  }
}

function drawJaw(plan) {
  const g = el("g", { id: "plan", "data-rank": plan.rank });
  const [theta, c] = plan.centre, cen = plan.centroid;
  const u = [Math.cos(theta), Math.sin(theta)], n = [-u[1], u[0]];
  const half = plan.pad_width / 2;
  let reach = 0;
  for (const p of S.part.outer) {
    reach = Math.max(reach, Math.abs((p[0] - cen[0]) * u[0] + (p[1] - cen[1]) * u[1]));
  }
  reach += 0.1 * S.view.size;
  const P = (a, b) => [cen[0] + a * n[0] + b * u[0], cen[1] + a * n[1] + b * u[1]];
  const lo = plan.offset[0] - half, hi = plan.offset[1] + half;
  el("polygon", { points: pts([P(lo, -reach), P(hi, -reach), P(hi, reach), P(lo, reach)]),
                  fill: "#1f77b4", "fill-opacity": 0.12, class: "strip" }, g);
  const thick = 0.03 * S.view.size;
  ["a", "b"].forEach((k, i) => {
    const stop = plan.contacts[k].stop;
    const sgn = (i === 0 ? 1 : -1) * (plan.mode === "internal" ? -1 : 1);
    el("polygon", { points: pts([P(c - half, stop), P(c + half, stop),
                                 P(c + half, stop + sgn * thick), P(c - half, stop + sgn * thick)]),
                    fill: "#555", stroke: "#000", class: "pad", "data-pad": k }, g);
    for (const p of plan.contacts[k].points) {
      const q = X(p);
      el("circle", { cx: q[0], cy: q[1], r: 3.5, fill: "#d62728", class: "jaw-contact" }, g);
    }
  });
  if (plan.pose && S.report && S.report.hand) drawHand(plan, S.report.hand, g);
  for (const t of plan.theta_rad) {
    const d = [Math.cos(t) * reach, Math.sin(t) * reach], m = P(c, 0);
    const a = X([m[0] - d[0], m[1] - d[1]]), b = X([m[0] + d[0], m[1] + d[1]]);
    el("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: "#2ca02c",
                 "stroke-dasharray": "6 4", class: "fan" }, g);
  }
}

// a real hand seen from above at the box's centre pose (the report's hand: its boxes in
// the tool frame at its largest opening; the fingers moved to the grasp's opening)
function drawHand(plan, hand, g) {
  const p = plan.pose.position;
  // the rotation's first two rows: the plane's x and y of each tool axis
  const R = Solid3D.rotation(plan.pose.orientation);
  const opening = plan.contacts.a.stop - plan.contacts.b.stop;
  const nPalm = hand.boxes.length - 2 * hand.finger_boxes;
  hand.boxes.forEach((b, k) => {
    const side = k < nPalm ? 0 : (k < nPalm + hand.finger_boxes ? 1 : -1);
    const dy = side * (opening - hand.opening) / 2;
    const corners = [];
    for (const sx of [-1, 1]) for (const sy of [-1, 1]) for (const sz of [-1, 1]) {
      const l = [sx * b.size[0] / 2, sy * b.size[1] / 2, sz * b.size[2] / 2];
      const c = [0, 1, 2].map((i) => b.centre[i] + b.rotation[i][0] * l[0] +
                 b.rotation[i][1] * l[1] + b.rotation[i][2] * l[2]);
      c[1] += dy;
      corners.push(X([p[0] + R[0][0] * c[0] + R[0][1] * c[1] + R[0][2] * c[2],
                      p[1] + R[1][0] * c[0] + R[1][1] * c[1] + R[1][2] * c[2]]));
    }
    el("polygon", { points: hull(corners).map((q) => q.join(",")).join(" "), fill: "none",
                    stroke: side === 0 ? "#777" : "#333", "stroke-width": 1,
                    "stroke-dasharray": side === 0 ? "4 3" : "", class: "hand-box" }, g);
  });
}

// the convex hull of screen points (monotone chain)
function hull(points) {
  const q = points.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const half = (list) => {
    const h = [];
    for (const r of list) {
      while (h.length >= 2 && cross(h[h.length - 2], h[h.length - 1], r) <= 0) h.pop();
      h.push(r);
    }
    h.pop();
    return h;
  };
  return half(q).concat(half(q.slice().reverse()));
}

function drawOverlay(ov) {
  if (!ov) return;
  const g = el("g", { id: "overlay", class: "overlay" });
  el("text", { x: 12, y: 40, "font-size": 12, fill: "#555" }, g).textContent =
    ov.kind === "e'" ? "grasp set: the restricted edges e'1, e'2 (theorem 6.3), orange"
      : "grasp set: the parallelograms Pi12, Pi34 (purple) and the two-sided sector C " +
        "(brown) of algorithm 6.1";
  for (const p of ov.polygons) {
    el("polygon", { points: pts(p), fill: "#9467bd", "fill-opacity": 0.18, stroke: "#9467bd",
                    class: "pi" }, g);
  }
  for (const s of ov.segments) {
    el("polyline", { points: pts(s), fill: "none", stroke: "#ff7f0e", "stroke-width": 13,
                     "stroke-opacity": 0.35, "stroke-linecap": "round", class: "eprime" }, g);
  }
  for (const c of ov.cones) {
    const R = 0.25 * S.view.size;
    for (const sg of [1, -1]) {
      const a0 = c.angle - c.half, a1 = c.angle + c.half;
      const p0 = [c.apex[0] + sg * R * Math.cos(a0), c.apex[1] + sg * R * Math.sin(a0)];
      const p1 = [c.apex[0] + sg * R * Math.cos(a1), c.apex[1] + sg * R * Math.sin(a1)];
      el("polygon", { points: pts([c.apex, p0, p1]), fill: "#8c564b", "fill-opacity": 0.2,
                      stroke: "#8c564b", class: "cone" }, g);
    }
  }
}

function fingerMu() {
  const g = $("gripper").value;
  return g === "4" || g === "3g" ? 0 : Number($("mu").value);
}

function drawFingers() {
  const g = el("g", { id: "fingers" });
  const E = edges(S.part), mu = fingerMu();
  S.fingers.forEach((f, k) => {
    const e = E[f.edge];
    if (e) drawPush(g, f.point, e.n, mu, "#111");
    const q = X(f.point);
    el("circle", { cx: q[0], cy: q[1], r: 6, class: "finger", "data-finger": k }, g);
  });
  el("path", { id: "ghost", d: "", fill: "none", stroke: "#d62728", "stroke-width": 1.5,
               "stroke-dasharray": "5 3" });
}

// ------------------------------------------------------------------ plans

function options() {
  const g = $("gripper").value;
  const num = (id, name) => {
    const v = Number($(id).value);
    if ($(id).value === "" || !Number.isFinite(v)) throw new Error(`${name} must be a number`);
    return v;
  };
  const o = { gripper: g, margin: num("margin", "margin"), top: Math.round(num("top", "plans")) };
  o.distinct = $("distinct").checked ? 0.5 : 0;
  o.time_limit = num("timelimit", "time limit");
  if ((g === "3" || g === "4") && !S.solid && $("bound").checked) o.bound = true;
  if (g !== "4" && g !== "3g") o.mu = num("mu", "mu");
  if (g === "jaw") {
    o.stroke = [num("stroke0", "stroke"), num("stroke1", "stroke")];
    o.pad = num("pad", "pad width");
    o.certify = $("certify").checked;
    if ($("hand").value) {
      o.hand = $("hand").value;
      o.table = $("table").checked;
      if (!S.solid) {
        o.thickness = num("thickness", "plate thickness");
        // the hand lying in the plate's plane, its palm on one side of the pads' strip
        o.in_plane = $("inplane").checked;
      }
    }
  } else {
    o.along_boundary = $("along").checked;
    o.rank_by = $("rank").value;
  }
  return o;
}

function partBody(part) {
  if (part.solid) {          // the server reads a built-in solid again by its name
    const demo = part.source.startsWith("demo:");
    return { solid: true, source: part.source, units: part.units,
             vertices: demo ? [] : part.vertices, faces: demo ? [] : part.faces };
  }
  return { outer: part.outer, holes: part.holes || [], units: part.units };
}

function schedulePlan(delay) {
  clearTimeout(S.planTimer);
  S.planTimer = setTimeout(runPlan, delay === undefined ? 120 : delay);
}

function busy(on, text) {
  document.body.dataset.busy = on ? "1" : "0";
  $("statustext").textContent = text || "";
  $("cancel").hidden = !on;
  $("progress").hidden = !on;
}

async function runPlan() {
  let opts;
  try { opts = options(); } catch (e) { message(e.message); return; }
  const seq = ++S.seq;
  const replaces = S.job;            // the previous plan, stale now: the server kills it
  S.job = null;
  const sent = S.solid || clone(S.part);
  busy(true, "planning…");
  $("progress").removeAttribute("value");
  let ans;
  try {
    ans = await request("POST", "/api/plan", { part: partBody(sent), options: opts, replaces });
    if (!S.solid && S.good && JSON.stringify(S.good) !== JSON.stringify(sent)) {
      S.history.push(S.good);
      if (S.history.length > 100) S.history.shift();
    }
    if (!S.solid) S.good = sent;
    $("undo").disabled = !S.history.length;
    while (seq === S.seq && ans.state === "running") {
      S.job = ans.job;
      const [done, total] = ans.progress;
      if (total > 0) { $("progress").max = total; $("progress").value = done; }
      $("statustext").textContent = total > 0 ? `planning… ${done} / ${total}` : "planning…";
      // a long poll: the answer comes the moment the plan ends (or after 0.1 s, to
      // show the progress)
      ans = await request("GET", `/api/jobs/${ans.job}?wait=0.1`);
    }
  } catch (e) {
    if (seq !== S.seq) return;
    busy(false);
    S.job = null;
    if (e.field === "part" && !S.solid) {
      revert(`${e.message}: kept the last good outline`);
    } else {
      message(e.message);
    }
    return;
  }
  if (seq !== S.seq) return;
  S.job = null;
  busy(false, ans.state === "done" ? `planned in ${(ans.seconds * 1000).toFixed(0)} ms` : ans.state);
  if (ans.state === "error") { message(ans.error); return; }
  if (ans.state !== "done") return;
  message(ans.report.reason ? `no grasp: ${ans.report.reason}` : "", true);
  accept(ans);
}

function cancelJob(id) {
  request("DELETE", `/api/jobs/${id}`).catch(() => {});
}

function accept(ans) {
  S.report = ans.report;
  S.plans = ans.report.grasps;
  S.overlays = ans.overlays;
  S.moveit = ans.moveit || null;          // a parallel gripper's plans as MoveIt grasps
  $("export-moveit").disabled = !S.moveit;
  $("stress").disabled = !S.plans.length;
  $("stresstext").textContent = "";
  $("stressgif").hidden = true;
  S.selected = 0;
  const list = $("plans");
  list.textContent = "";
  const units = ans.report.units;
  S.plans.forEach((p, k) => {
    const li = document.createElement("li");
    li.dataset.rank = String(p.rank);
    if (S.solid) {
      li.dataset.facets = p.facets.join(",");
      li.dataset.radius = String(p.radius);
      li.textContent = `${p.rank}. facets ${p.facets.join(", ")}: ` +
        (p.contact_type === "jaw"
          ? `pads' area ${fmt(p.area)} ${units}², opening ${fmt(p.opening)}`
          : `region radius ${fmt(p.radius)} ${units}, ${p.contact_type}`);
    } else if (p.gripper === "parallel_jaw") {
      li.dataset.measure = String(p.measure);
      li.textContent = `${p.rank}. box ${fmt(p.measure)} ${units}: closing ` +
        `${p.theta_deg[0].toFixed(1)}–${p.theta_deg[1].toFixed(1)}°, offset ` +
        `${fmt(p.offset[0])}…${fmt(p.offset[1])}, ${p.mode}${p.certified ? ", proved" : ""}`;
    } else {
      li.dataset.edges = p.edges.join(",");
      li.dataset.min = String(p.min_region_length);
      li.textContent = `${p.rank}. edges ${p.edges.join(", ")}: min region ` +
        `${fmt(p.min_region_length)} ${units}, ${p.mode}`;
    }
    if (p.similar && p.similar.length) {
      li.dataset.similar = String(p.similar.length);
      li.textContent += ` (and ${p.similar.length} like it)`;
    }
    li.addEventListener("click", () => select(k));
    list.appendChild(li);
  });
  $("optimum").textContent = optimumText(ans.report);
  $("incomplete").textContent = incompleteText(ans.report) || fewerText(ans.report);
  if (S.solid && !S.solid.aimed && S.plans.length) {
    S.solid.aimed = true;                  // the first plans of a solid: face the best
    Solid3D.aim(S.plans[0]);
  }
  select(0);
  document.body.dataset.planSeq = String(Number(document.body.dataset.planSeq) + 1);
}

// the proved upper bound of --bound (the report's "optimality"), as fcgrasp plan prints it
function optimumText(report) {
  const b = report.optimality;
  if (!b) return "";
  if (b.upper_bound === null) return "optimum: no upper bound proved within the search's budget";
  const best = Math.max(0, ...report.grasps.map((g) => g.min_region_length));
  const g4 = (v) => String(Number(Number(v).toPrecision(4)));   // Python's :.4g
  return `optimum: no regions of ${report.parameters.fingers} fingers each ` +
    `${g4(b.upper_bound)} ${report.units} long or more hold (proved over ${b.nodes} boxes ` +
    `of positions); the best plan's ${g4(best)} is within ${(100 * b.gap).toFixed(1)} % of that`;
}

// a search stopped early (the report's "gap"), as fcgrasp plan prints it
function incompleteText(report) {
  const g = report.gap;
  if (report.complete !== false || !g) return "";
  const why = {time_limit: "at its time limit (--time-limit)",
               max_memory: "at its memory budget (--max-memory)",
               depth: "at the most plans a distinct search reads"}[g.stopped_by] || "early";
  const g4 = (v) => String(Number(Number(v).toPrecision(4)));   // Python's :.4g
  const atMost = g.bound === null ? null
    : `${g.measure || "smallest region"} of at most ${g4(g.bound)} ${report.units}`;
  if (g.exact === false)
    return `search stopped ${why}: ${g.found} of ${report.parameters.top} plans, each proved ` +
      `to hold; a complete search may rank others first` +
      (atMost === null ? "" : `, each with a ${atMost}`);
  const rest = atMost === null ? "no bound on the rest was proved"
    : `every further distinct alternative has a ${atMost}`;
  return `search stopped ${why}: ${g.found} of ${report.parameters.top} plans proved, ` +
    `exact; ${rest}`;
}

// a complete search with fewer plans than asked: why, as fcgrasp plan prints it
function fewerText(report) {
  const top = (report.parameters || {}).top, found = (report.grasps || []).length;
  if (report.complete === false || top == null || !(found > 0 && found < top)) return "";
  const d = report.parameters.distinct;
  if (d)
    return `${found} of ${top} plans: every other plan that holds is the same alternative ` +
      `as one of these (--distinct ${d}; the JSON's "similar" lists them, --distinct 0 ` +
      `every plan)`;
  return `${found} of ${top} plans: the search found no other plan that holds`;
}

function select(k) {
  S.selected = k;
  [...$("plans").children].forEach((li, i) => li.classList.toggle("selected", i === k));
  render();
}

// ------------------------------------------------------------------ fingers by hand

// the selected plan shaken in MuJoCo (the server's /api/stress: fcgrasp simulate on a
// few of its grasps), the result and the animation of one shown under the button
async function runStress() {
  const plan = S.plans[S.selected];
  if (!plan) return;
  const seq = ++S.stressSeq;
  $("stresstext").textContent = "shaking…";
  $("stressgif").hidden = true;
  let ans;
  try {
    ans = await request("POST", "/api/stress", { part: partBody(S.part), plan });
  } catch (e) {
    if (seq === S.stressSeq) $("stresstext").textContent = e.message;
    return;
  }
  if (seq !== S.stressSeq) return;
  const worst = ans.worst_ratio === null ? "no slip up to three times it"
    : `the least slip at ${ans.worst_ratio.toFixed(2)} times it`;
  $("stresstext").textContent = `plan ${ans.rank}: ${ans.held} of ${ans.runs} grasps held ` +
    `to their certified payload; ${worst}`;
  document.body.dataset.stressHeld = String(ans.held);
  if (ans.gif) {
    $("stressgif").src = `data:image/gif;base64,${ans.gif}`;
    $("stressgif").hidden = false;
  }
}

async function runCheck() {
  stopEscape();
  if (S.solid) { $("verdict").textContent = ""; return; }
  const seq = ++S.checkSeq;
  const v = $("verdict");
  if (!S.fingers.length) {
    v.textContent = ""; v.className = ""; v.dataset.closure = "";
    return;
  }
  const g = $("gripper").value, mu = fingerMu();
  const contacts = S.fingers.map((f) => (mu > 0
    ? { point: f.point, edge: f.edge, type: "friction", mu }
    : { point: f.point, edge: f.edge, type: "frictionless" }));
  const body = { part: partBody(S.part), contacts };
  if (g === "3g") body.gravity = { direction: [0, -1] };
  let ans;
  try { ans = await request("POST", "/api/check", body); } catch (e) {
    if (seq === S.checkSeq) message(e.message);
    return;
  }
  if (seq !== S.checkSeq) return;
  S.verdict = ans;
  v.className = ans.force_closure ? "ok" : "bad";
  v.dataset.closure = ans.force_closure ? "yes" : "no";
  v.textContent = ans.force_closure
    ? `${S.fingers.length} fingers: force closure`
    : `${S.fingers.length} fingers: ${ans.verdict}`;
  document.body.dataset.checkSeq = String(seq);
  if (!ans.force_closure && ans.escape_twist) startEscape(ans);
}

// the escape motion, animated: the part's outline moved along the escape twist
function startEscape(ans) {
  const [w, vx, vy] = ans.escape_twist;
  const size = S.view.size, t0 = performance.now();
  let amount;
  if (ans.rotation_center) {
    const c = ans.rotation_center;
    let far = 0;
    for (const p of S.part.outer) far = Math.max(far, Math.hypot(p[0] - c[0], p[1] - c[1]));
    amount = Math.sign(w) * Math.min(0.35, (0.12 * size) / (far || 1));
  } else {
    amount = (0.12 * size) / (Math.hypot(vx, vy) || 1);
  }
  const d = ringPath(S.part);
  const step = (now) => {
    const ghost = $("ghost");
    if (!ghost) return;
    const t = ((now - t0) % 1600) / 1600;
    ghost.setAttribute("d", d);
    if (ans.rotation_center) {
      const c = X(ans.rotation_center), deg = (-amount * t * 180) / Math.PI;
      ghost.setAttribute("transform", `rotate(${deg.toFixed(3)} ${c[0]} ${c[1]})`);
    } else {
      const k = amount * t * S.view.s;
      ghost.setAttribute("transform", `translate(${(k * vx).toFixed(2)} ${(-k * vy).toFixed(2)})`);
    }
    S.anim = requestAnimationFrame(step);
  };
  S.anim = requestAnimationFrame(step);
}

function stopEscape() {
  if (S.anim) cancelAnimationFrame(S.anim);
  S.anim = null;
  const ghost = $("ghost");
  if (ghost) ghost.setAttribute("d", "");
}

// ------------------------------------------------------------------ editing

function undo() {
  if (S.solid || !S.history.length) return;      // a solid is not edited
  S.part = S.history.pop();
  S.good = clone(S.part);
  $("undo").disabled = !S.history.length;
  S.invalid = false;
  message("");
  changed();
}

// a solid part: the 3-D view, its grippers (two soft fingers, three fingers with
// friction, the jaw), no editing
function setSolid(part, note) {
  S.solid = part;
  S.history = [];
  document.body.dataset.solid = "1";
  svg.style.display = "none";
  for (const o of $("gripper").options) o.disabled = !S.solidGrippers.includes(o.value);
  if ($("gripper").selectedOptions[0].disabled) {
    $("gripper").value = "2";
    document.body.dataset.gripper = "2";
  }
  S.fingers = []; S.plans = []; S.overlays = []; S.report = null;
  $("plans").textContent = "";
  $("undo").disabled = true;
  $("verdict").textContent = "";
  $("partinfo").textContent = `${part.name || "solid"}: ${part.triangles} triangles, ` +
    `${part.facets} facets, units ${part.units}`;
  const error = Solid3D.show(part);
  message(error || note || "", !error);
  schedulePlan(0);
}

function setPart(part, note) {
  sizeJaw(part.size);
  if (part.solid) { setSolid(part, note); return; }
  if (S.solid) {
    S.solid = null;
    document.body.dataset.solid = "0";
    svg.style.display = "";
    for (const o of $("gripper").options) o.disabled = false;
    Solid3D.hide();
  }
  S.part = { outer: part.outer, holes: part.holes || [], units: part.units, name: part.name };
  S.good = clone(S.part);
  S.history = [];
  $("undo").disabled = true;
  S.fingers = [];
  S.plans = []; S.overlays = []; S.report = null;
  $("plans").textContent = "";
  runCheck();
  $("partinfo").textContent = `${part.name || "part"}: ${edges(S.part).length} edges, ` +
    `${(part.holes || []).length} holes, units ${part.units}`;
  message(note || "", true);
  fit();
  render();
  schedulePlan(0);
}

function revert(text) {
  S.part = clone(S.good);
  S.invalid = false;
  message(text);
  render();
}

function changed() {
  S.fingers = [];
  runCheck();
  S.plans = []; S.overlays = [];
  render();
  schedulePlan();
}

svg.addEventListener("pointerdown", (ev) => {
  if (!S.part || (ev.button !== 0 && ev.button !== 1)) return;
  const t = ev.target, here = eventPoint(ev);
  if (ev.button === 1) {
    S.drag = { kind: "pan", from: here, ox: S.view.ox, oy: S.view.oy, moved: false };
  } else if (S.mode === "edit" && t.classList.contains("vertex")) {
    if (ev.shiftKey) { deleteVertex(+t.dataset.ring, +t.dataset.index); return; }
    S.drag = { kind: "vertex", ring: +t.dataset.ring, index: +t.dataset.index, moved: false };
  } else if (S.mode === "fingers" && t.classList.contains("finger")) {
    S.drag = { kind: "finger", index: +t.dataset.finger, moved: false };
  } else if (S.mode === "fingers" && nearOutline(here)) {
    addFinger(toWorld(...here));
    return;
  } else {
    // the background: drag to pan (a click in finger mode says where fingers go)
    S.drag = { kind: "pan", from: here, ox: S.view.ox, oy: S.view.oy, moved: false };
  }
  svg.setPointerCapture(ev.pointerId);
  ev.preventDefault();
});

function nearOutline(q) {
  const near = nearestOnBoundary(S.part, toWorld(...q));
  return near && near.d * S.view.s <= 15;
}

// one frame of a vertex drag: the vertex moved, the outline checked where it changed
function dragVertex(ring, index, p) {
  S.dragging = true;
  rings(S.part)[ring][index] = p;
  S.invalid = crossesAt(S.part, ring, index);
  render();
}

svg.addEventListener("pointermove", (ev) => {
  const here = eventPoint(ev);
  S.pointer = here;
  if (!S.drag) { showHover(); return; }
  const p = toWorld(...here), d = S.drag;
  if (d.kind === "pan") {
    if (!d.moved && Math.hypot(here[0] - d.from[0], here[1] - d.from[1]) < 3) return;
    d.moved = true;
    S.view.ox = d.ox + here[0] - d.from[0];
    S.view.oy = d.oy + here[1] - d.from[1];
    render();
    return;
  }
  d.moved = true;
  if (d.kind === "vertex") {
    dragVertex(d.ring, d.index, p);
  } else {
    const near = nearestOnBoundary(S.part, p);
    S.fingers[d.index] = { point: near.point, edge: near.edge };
    render();
  }
});

svg.addEventListener("pointerleave", () => {
  S.pointer = null;
  if ($("hover")) { $("hover").textContent = ""; $("readout").textContent = ""; }
});

svg.addEventListener("wheel", (ev) => {
  if (!S.part || !S.view) return;
  ev.preventDefault();
  const [x, y] = eventPoint(ev);
  const step = ev.deltaMode === 1 ? 33 * ev.deltaY : ev.deltaMode === 2 ? 500 * ev.deltaY
    : ev.deltaY;
  zoomAt(x, y, Math.exp(-step * 0.0015));
}, { passive: false });

svg.addEventListener("pointerup", () => {
  const d = S.drag;
  S.drag = null;
  S.dragging = false;
  if (!d) return;
  if (d.kind === "pan") {
    if (!d.moved && S.mode === "fingers") message("click on the outline to place a finger", true);
    return;
  }
  if (d.kind === "vertex") {
    if (!d.moved) { render(); return; }
    if (S.invalid) { revert("the outline crossed itself: kept the last good outline"); return; }
    changed();
  } else if (!d.moved) {
    S.fingers.splice(d.index, 1);
    render();
    runCheck();
  } else {
    render();
    runCheck();
  }
});

svg.addEventListener("dblclick", (ev) => {
  if (S.mode !== "edit" || !S.part) return;
  const p = toWorld(...eventPoint(ev));
  const near = nearestOnBoundary(S.part, p);
  if (!near || near.d * S.view.s > 12 || near.t < 0.02 || near.t > 0.98) return;
  rings(S.part)[near.e.ring].splice(near.e.i + 1, 0, near.point);
  changed();
});

svg.addEventListener("contextmenu", (ev) => {
  if (S.mode === "edit" && ev.target.classList.contains("vertex")) {
    ev.preventDefault();
    deleteVertex(+ev.target.dataset.ring, +ev.target.dataset.index);
  }
});

function deleteVertex(ring, index) {
  const r = rings(S.part)[ring];
  if (r.length <= 3) { message("a ring keeps at least three vertices"); return; }
  r.splice(index, 1);
  if (crossesAt(S.part, ring, index % r.length)) {
    revert("deleting that vertex makes the outline cross itself: kept the last good outline");
    return;
  }
  changed();
}

function addFinger(p) {
  const near = nearestOnBoundary(S.part, p);
  if (!near || near.d * S.view.s > 15) {
    message("click on the outline to place a finger", true);
    return;
  }
  if (S.fingers.length >= 4) { message("at most four fingers: click one to take it away"); return; }
  S.fingers.push({ point: near.point, edge: near.edge });
  render();
  runCheck();
}

// ------------------------------------------------------------------ controls

function download(name, type, text) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

function figureSVG() {
  const copy = svg.cloneNode(true);
  copy.querySelectorAll(".handle, #readout").forEach((n) => n.remove());
  copy.setAttribute("xmlns", SVGNS);
  copy.setAttribute("width", S.view.W);
  copy.setAttribute("height", S.view.H);
  copy.removeAttribute("id");
  return new XMLSerializer().serializeToString(copy);
}

function setMode(mode) {
  S.mode = mode;
  render();
}

// the file loaded last: another of its parts, or other units, reads it again
async function loadFile(file, which) {
  if (file.size > S.maxUpload) {
    message(`${file.name} is too large (${file.size} bytes; at most ${S.maxUpload})`);
    return;
  }
  let url = `/api/part?name=${encodeURIComponent(file.name)}` +
    `&units=${encodeURIComponent($("units").value)}`;
  if (which !== undefined) url += `&part=${encodeURIComponent(which)}`;
  try {
    const part = await request("POST", url, await file.arrayBuffer(), true);
    S.file = file;
    showParts(part);
    setPart(part, (part.notes || []).join("; "));
  } catch (e) {
    message(`${e.message} (kept the current part)`);
  }
}

// the parts of the file loaded (as fcgrasp parts lists them), the one shown selected
function showParts(part) {
  const pick = $("partpick");
  pick.textContent = "";
  const parts = part.parts || [];
  for (const p of parts) {
    const o = document.createElement("option");
    o.value = String(p.index);
    o.disabled = !p.usable;
    o.textContent = `${p.index}: ${p.id || "-"}${p.layer ? ` (layer ${p.layer})` : ""}, ` +
      `${p.edges === null ? "not usable" : `${p.edges} edges`}, area ${fmt(p.area)}`;
    pick.appendChild(o);
  }
  pick.value = String(part.part);
  document.body.dataset.parts = parts.length > 1 ? "many" : "one";
}

// the jaw's stroke and pads sized to the part, until the user sets them
function sizeJaw(size) {
  if (S.jawEdited || !(size > 0)) return;
  const round = (v) => Number(v.toPrecision(2));
  $("stroke0").value = String(round(0.05 * size));
  $("stroke1").value = String(round(1.5 * size));
  $("pad").value = String(round(0.1 * size));
}

async function init() {
  // the 3-D view is an ES module on three.js (vendor/): loaded before any part is shown
  await import("/static/solid3d.js");
  const st = await request("GET", "/api/state");
  S.maxUpload = st.max_upload;
  for (const name of st.demos) {
    const o = document.createElement("option");
    o.value = name; o.textContent = name;
    $("demo").appendChild(o);
  }
  S.solidGrippers = st.solid_grippers;
  for (const name of st.solids) {
    const o = document.createElement("option");
    o.value = name; o.textContent = `${name} (solid)`;
    $("demo").appendChild(o);
  }
  for (const m of st.measures) {
    const o = document.createElement("option");
    o.value = m; o.textContent = m.replace(/_/g, " ");
    $("rank").appendChild(o);
  }
  document.body.dataset.gripper = $("gripper").value;
  $("demo").addEventListener("change", async () => {
    if (!$("demo").value) return;
    S.file = null;                       // a built-in part: no file's parts to pick
    document.body.dataset.parts = "one";
    try { setPart(await request("GET", `/api/demo/${$("demo").value}`)); } catch (e) {
      message(e.message);
    }
  });
  $("file").addEventListener("change", () => {
    const f = $("file").files[0];
    if (f) loadFile(f);
    $("file").value = "";
  });
  $("partpick").addEventListener("change", () => {
    if (S.file) loadFile(S.file, $("partpick").value);
  });
  $("units").addEventListener("change", () => {
    if (S.file) loadFile(S.file, $("partpick").value || undefined);
  });
  for (const id of ["stroke0", "stroke1", "pad"]) {
    for (const ev of ["input", "change"]) {
      $(id).addEventListener(ev, () => { S.jawEdited = true; });
    }
  }
  for (const id of ["mu", "margin", "top", "stroke0", "stroke1", "pad", "rank", "along",
                    "certify", "distinct", "bound", "timelimit", "hand", "table",
                    "thickness", "inplane"]) {
    $(id).addEventListener("change", () => { schedulePlan(); runCheck(); });
  }
  $("gripper").addEventListener("change", () => {
    document.body.dataset.gripper = $("gripper").value;
    // each gripper's default (fcgrasp.plan's distinct=None): distinct alternatives (a
    // jaw's mirror and neighbouring boxes merged, fingers' plans shifted by an edge)
    $("distinct").checked = true;
    schedulePlan(); runCheck();
  });
  $("overlay").addEventListener("change", render);
  $("edgenums").addEventListener("change", render);
  $("mode-edit").addEventListener("change", () => setMode("edit"));
  $("mode-fingers").addEventListener("change", () => setMode("fingers"));
  $("fit").addEventListener("click", () => {
    if (S.solid) {
      Solid3D.fit();
      if (S.plans[S.selected]) Solid3D.aim(S.plans[S.selected]);
      return;
    }
    fit(); render();
  });
  $("undo").addEventListener("click", undo);
  document.addEventListener("keydown", (ev) => {
    if ((ev.ctrlKey || ev.metaKey) && ev.key === "z" && ev.target.tagName !== "INPUT") {
      ev.preventDefault();
      undo();
    }
  });
  $("clear-fingers").addEventListener("click", () => { S.fingers = []; render(); runCheck(); });
  $("cancel").addEventListener("click", () => {
    clearTimeout(S.planTimer);       // a plan scheduled but not yet sent is cancelled too
    S.seq++;
    if (S.job) cancelJob(S.job);
    S.job = null;
    busy(false, "cancelled");
  });
  $("export-json").addEventListener("click", () => {
    if (!S.report) { message("no plan to export yet"); return; }
    download("fcgrasp-plan.json", "application/json", JSON.stringify(S.report, null, 2) + "\n");
  });
  $("export-svg").addEventListener("click", () => {
    download("fcgrasp-plan.svg", "image/svg+xml", figureSVG());
  });
  $("stress").addEventListener("click", runStress);
  $("export-moveit").addEventListener("click", () => {
    if (!S.moveit) { message("MoveIt grasps are a jaw's or two fingers' plans"); return; }
    download("fcgrasp-grasps.json", "application/json", JSON.stringify(S.moveit, null, 1) + "\n");
  });
  $("export-png").addEventListener("click", () => {       // a solid's 3-D view as it is
    $("view3d").toBlob((blob) => download("fcgrasp-view.png", "image/png", blob));
  });
  window.addEventListener("resize", () => { if (!S.solid) fit(); render(); });
  setPart(st.part);
}

// for tests and the console: the state and the mapping from part to screen
window.explorer = { state: S, toScreen: (p) => X(p), toPart: (x, y) => toWorld(x, y), figureSVG,
                    options, crossesAt, dragVertex, zoomAt, render,
                    get solid3d() { return window.Solid3D; } };

init().catch((e) => message(`cannot start: ${e.message}`));
