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
  plans: [], report: null, overlays: [], selected: 0,
  mode: "edit", fingers: [], verdict: null,
  seq: 0, job: null, checkSeq: 0,
  view: null, drag: null, invalid: false, maxUpload: 8 << 20, anim: null,
  history: [],       // earlier accepted outlines of this part, for undo
};

// ------------------------------------------------------------------ server

async function request(method, url, body, raw) {
  const opts = { method, headers: {} };
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

const sleep = (ms) => new Promise((ok) => setTimeout(ok, ms));
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

// a quick test while dragging (the server's Polygon check is the authority)
function selfCrossing(part) {
  const E = edges(part);
  for (let i = 0; i < E.length; i++) {
    for (let j = i + 1; j < E.length; j++) {
      const ei = E[i], ej = E[j];
      if (ei.ring === ej.ring) {
        const n = rings(part)[ei.ring].length;
        if (Math.abs(ei.i - ej.i) <= 1 || Math.abs(ei.i - ej.i) === n - 1) continue;
      }
      if (segmentsCross(ei.a, ei.b, ej.a, ej.b)) return true;
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
             size: b.size };
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

function render() {
  if (!S.part || !S.view) return;
  svg.textContent = "";
  const defs = el("defs");
  const mk = el("marker", { id: "arrow", viewBox: "0 0 10 10", refX: 9, refY: 5,
                            markerWidth: 6, markerHeight: 6, orient: "auto-start-reverse" }, defs);
  el("path", { d: "M0,0L10,5L0,10z", fill: "#333" }, mk);
  el("rect", { x: 0, y: 0, width: S.view.W, height: S.view.H, fill: "#fff" });
  el("path", { d: ringPath(S.part), "fill-rule": "evenodd", fill: "#e0e0e0",
               stroke: S.invalid ? "#d00" : "#404040", "stroke-width": S.invalid ? 2 : 1.2,
               id: "part-path" });
  const E = edges(S.part);
  if (E.length <= 80) {
    const g = el("g", { class: "labels", "font-size": 10, fill: "#777",
                        "text-anchor": "middle", "dominant-baseline": "middle" });
    const off = 0.03 * S.view.size;
    E.forEach((e, k) => {
      const m = X([(e.a[0] + e.b[0]) / 2 + off * e.n[0], (e.a[1] + e.b[1]) / 2 + off * e.n[1]]);
      el("text", { x: m[0], y: m[1] }, g).textContent = String(k);
    });
  }
  const plan = S.dragging ? null : S.plans[S.selected];
  if (plan && $("overlay").checked) drawOverlay(S.overlays[S.selected]);
  if (plan) (plan.gripper === "parallel_jaw" ? drawJaw : drawPlan)(plan);
  el("text", { x: 12, y: 22, "font-size": 13, fill: "#333", id: "caption" }).textContent =
    plan ? caption(plan) : (S.part.name || "");
  drawFingers();
  if (S.mode === "edit") {
    const g = el("g", { class: "handle" });
    rings(S.part).forEach((r, ring) => r.forEach((p, i) => {
      const q = X(p);
      el("circle", { cx: q[0], cy: q[1], r: 5, class: "vertex", "data-ring": ring,
                     "data-index": i }, g);
    }));
  }
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
  for (const t of plan.theta_rad) {
    const d = [Math.cos(t) * reach, Math.sin(t) * reach], m = P(c, 0);
    const a = X([m[0] - d[0], m[1] - d[1]]), b = X([m[0] + d[0], m[1] + d[1]]);
    el("line", { x1: a[0], y1: a[1], x2: b[0], y2: b[1], stroke: "#2ca02c",
                 "stroke-dasharray": "6 4", class: "fan" }, g);
  }
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
  if (g !== "4" && g !== "3g") o.mu = num("mu", "mu");
  if (g === "jaw") {
    o.stroke = [num("stroke0", "stroke"), num("stroke1", "stroke")];
    o.pad = num("pad", "pad width");
    o.certify = $("certify").checked;
  } else {
    o.along_boundary = $("along").checked;
    o.rank_by = $("rank").value;
  }
  return o;
}

function partBody(part) {
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
  const sent = clone(S.part);
  busy(true, "planning…");
  $("progress").removeAttribute("value");
  let ans;
  try {
    ans = await request("POST", "/api/plan", { part: partBody(sent), options: opts, replaces });
    if (S.good && JSON.stringify(S.good) !== JSON.stringify(sent)) {
      S.history.push(S.good);
      if (S.history.length > 100) S.history.shift();
    }
    S.good = sent;
    $("undo").disabled = !S.history.length;
    while (seq === S.seq && ans.state === "running") {
      S.job = ans.job;
      const [done, total] = ans.progress;
      if (total > 0) { $("progress").max = total; $("progress").value = done; }
      $("statustext").textContent = total > 0 ? `planning… ${done} / ${total}` : "planning…";
      await sleep(100);
      ans = await request("GET", `/api/jobs/${ans.job}`);
    }
  } catch (e) {
    if (seq !== S.seq) return;
    busy(false);
    S.job = null;
    if (e.field === "part") {
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
  S.selected = 0;
  const list = $("plans");
  list.textContent = "";
  const units = ans.report.units;
  S.plans.forEach((p, k) => {
    const li = document.createElement("li");
    li.dataset.rank = String(p.rank);
    if (p.gripper === "parallel_jaw") {
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
    li.addEventListener("click", () => select(k));
    list.appendChild(li);
  });
  select(0);
  document.body.dataset.planSeq = String(Number(document.body.dataset.planSeq) + 1);
}

function select(k) {
  S.selected = k;
  [...$("plans").children].forEach((li, i) => li.classList.toggle("selected", i === k));
  render();
}

// ------------------------------------------------------------------ fingers by hand

async function runCheck() {
  stopEscape();
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
  if (!S.history.length) return;
  S.part = S.history.pop();
  S.good = clone(S.part);
  $("undo").disabled = !S.history.length;
  S.invalid = false;
  message("");
  changed();
}

function setPart(part, note) {
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
  if (ev.button !== 0 || !S.part) return;
  const t = ev.target;
  if (S.mode === "edit" && t.classList.contains("vertex")) {
    if (ev.shiftKey) { deleteVertex(+t.dataset.ring, +t.dataset.index); return; }
    S.drag = { kind: "vertex", ring: +t.dataset.ring, index: +t.dataset.index, moved: false };
  } else if (S.mode === "fingers" && t.classList.contains("finger")) {
    S.drag = { kind: "finger", index: +t.dataset.finger, moved: false };
  } else if (S.mode === "fingers") {
    addFinger(toWorld(...eventPoint(ev)));
    return;
  } else {
    return;
  }
  svg.setPointerCapture(ev.pointerId);
  ev.preventDefault();
});

svg.addEventListener("pointermove", (ev) => {
  if (!S.drag) return;
  const p = toWorld(...eventPoint(ev));
  S.drag.moved = true;
  if (S.drag.kind === "vertex") {
    S.dragging = true;
    rings(S.part)[S.drag.ring][S.drag.index] = p;
    S.invalid = selfCrossing(S.part);
  } else {
    const near = nearestOnBoundary(S.part, p);
    S.fingers[S.drag.index] = { point: near.point, edge: near.edge };
  }
  render();
});

svg.addEventListener("pointerup", () => {
  const d = S.drag;
  S.drag = null;
  S.dragging = false;
  if (!d) return;
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
  if (selfCrossing(S.part)) {
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
  copy.querySelectorAll(".handle").forEach((n) => n.remove());
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

async function loadFile(file) {
  if (file.size > S.maxUpload) {
    message(`${file.name} is too large (${file.size} bytes; at most ${S.maxUpload})`);
    return;
  }
  try {
    const part = await request("POST", `/api/part?name=${encodeURIComponent(file.name)}`,
      await file.arrayBuffer(), true);
    setPart(part, (part.notes || []).join("; "));
  } catch (e) {
    message(`${e.message} (kept the current part)`);
  }
}

async function init() {
  const st = await request("GET", "/api/state");
  S.maxUpload = st.max_upload;
  for (const name of st.demos) {
    const o = document.createElement("option");
    o.value = name; o.textContent = name;
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
    try { setPart(await request("GET", `/api/demo/${$("demo").value}`)); } catch (e) {
      message(e.message);
    }
  });
  $("file").addEventListener("change", () => {
    const f = $("file").files[0];
    if (f) loadFile(f);
    $("file").value = "";
  });
  for (const id of ["mu", "margin", "top", "stroke0", "stroke1", "pad", "rank", "along",
                    "certify"]) {
    $(id).addEventListener("change", () => { schedulePlan(); runCheck(); });
  }
  $("gripper").addEventListener("change", () => {
    document.body.dataset.gripper = $("gripper").value;
    schedulePlan(); runCheck();
  });
  $("overlay").addEventListener("change", render);
  $("mode-edit").addEventListener("change", () => setMode("edit"));
  $("mode-fingers").addEventListener("change", () => setMode("fingers"));
  $("fit").addEventListener("click", () => { fit(); render(); });
  $("undo").addEventListener("click", undo);
  document.addEventListener("keydown", (ev) => {
    if ((ev.ctrlKey || ev.metaKey) && ev.key === "z" && ev.target.tagName !== "INPUT") {
      ev.preventDefault();
      undo();
    }
  });
  $("clear-fingers").addEventListener("click", () => { S.fingers = []; render(); runCheck(); });
  $("cancel").addEventListener("click", () => {
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
  window.addEventListener("resize", () => { fit(); render(); });
  setPart(st.part);
}

// for tests and the console: the state and the mapping from part to screen
window.explorer = { state: S, toScreen: (p) => X(p), figureSVG, options, selfCrossing, render };

init().catch((e) => message(`cannot start: ${e.message}`));
