// fcgrasp explorer: the 3-D view of a solid part (a mesh), drawn with three.js (vendored
// from npm: vendor/README.md). The page's app.js calls Solid3D.show(part),
// Solid3D.draw(plan, report) and Solid3D.hide(); the mouse orbits (drag) and zooms
// (wheel) about the part's centre. Beside the part and a plan's regions it draws the
// hand of a pick at its pose (its collision boxes), the table the part rests on, the
// part frame's axes and a scale bar.
import * as THREE from "./vendor/three.module.min.js";

const COLORS = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd"];

const Solid3D = (() => {
  const canvas = document.getElementById("view3d");
  const V = { renderer: null, scene: null, camera: null, part: null, plan: null,
              report: null, yaw: 0.7, pitch: 0.45, dist: 1, mesh: null, extras: null,
              drag: null, eye: [0, 0, 1], error: null, scale: null };

  // ---------------------------------------------------------------- small 3-D algebra
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const unit = (a) => { const n = Math.hypot(...a) || 1; return mul(a, 1 / n); };
  // a unit quaternion (x, y, z, w) as the rows of its rotation
  const rotation = ([x, y, z, w]) => [
    [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
    [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
    [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]];
  const apply = (R, v) => R.map((r) => dot(r, v));
  const transpose = (R) => [0, 1, 2].map((j) => R.map((r) => r[j]));

  function context() {
    if (V.renderer || V.error) return V.renderer;
    try {
      V.renderer = new THREE.WebGLRenderer({ canvas, antialias: true,
                                             preserveDrawingBuffer: true });
    } catch (e) {
      V.error = "this browser has no WebGL: the solid cannot be drawn";
      return null;
    }
    V.renderer.setClearColor(0xffffff, 1);
    V.scene = new THREE.Scene();
    V.camera = new THREE.PerspectiveCamera(45, 1, 0.1, 10);
    V.camera.up.set(0, 0, 1);
    // a soft light everywhere and a lamp at the eye: a face turned to the camera is
    // brightest, one seen edge-on darkest
    V.scene.add(new THREE.AmbientLight(0xffffff, 1.1));
    V.lamp = new THREE.DirectionalLight(0xffffff, 2.2);
    V.scene.add(V.lamp);
    V.scene.add(V.lamp.target);
    return V.renderer;
  }

  function dispose(obj) {
    if (!obj) return;
    V.scene.remove(obj);
    obj.traverse((o) => {
      if (o.geometry) o.geometry.dispose();
      if (o.material) o.material.dispose();
    });
  }

  function geometry(points, normals) {
    const g = new THREE.BufferGeometry();
    g.setAttribute("position", new THREE.Float32BufferAttribute(points.flat(), 3));
    if (normals) g.setAttribute("normal", new THREE.Float32BufferAttribute(normals.flat(), 3));
    return g;
  }

  // the part's triangles, each with its own normal (flat shading)
  function partMesh(part) {
    const pts = [];
    for (const [i, j, k] of part.faces) pts.push(part.vertices[i], part.vertices[j], part.vertices[k]);
    const g = geometry(pts);
    g.computeVertexNormals();
    return new THREE.Mesh(g, new THREE.MeshLambertMaterial({ color: 0xc7c7cc,
                                                             side: THREE.DoubleSide }));
  }

  // triangles (index triples) of a simple polygon in its plane of normal n, by ear
  // clipping (a jaw's region can be an L: not convex)
  function triangulate(poly, n) {
    const ax = [0, 1, 2].reduce((a, b) => (Math.abs(n[b]) > Math.abs(n[a]) ? b : a), 0);
    const [u, v] = [[1, 2], [2, 0], [0, 1]][ax];
    const q = poly.map((p) => [p[u], p[v]]);
    const area = q.reduce((a, p, i) => {
      const r = q[(i + 1) % q.length];
      return a + p[0] * r[1] - r[0] * p[1];
    }, 0);
    const turn = (a, b, c) => ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) *
      Math.sign(area);
    const inside = (p, a, b, c) => turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
    const idx = q.map((_, i) => i), out = [];
    let guard = 0;
    while (idx.length > 3 && guard++ < 10000) {
      let cut = false;
      for (let k = 0; k < idx.length; k++) {
        const i = idx[(k + idx.length - 1) % idx.length], j = idx[k], l = idx[(k + 1) % idx.length];
        if (turn(q[i], q[j], q[l]) <= 0) continue;            // a reflex or flat corner
        if (idx.some((m) => m !== i && m !== j && m !== l && inside(q[m], q[i], q[j], q[l]))) {
          continue;
        }
        out.push([i, j, l]);
        idx.splice(k, 1);
        cut = true;
        break;
      }
      if (!cut) break;                                          // degenerate: stop
    }
    if (idx.length === 3) out.push(idx.slice());
    return out;
  }

  // a plan's regions (polygons on facets, triangulated, or a region's own triangles on a
  // curved surface; lifted off the surface along the outward normal), the contact
  // centres, and each finger's approach
  function planGroup(plan) {
    const group = new THREE.Group(), lift = V.part.size * 2e-3;
    plan.regions.forEach((poly, k) => {
      const col = new THREE.Color(COLORS[k % COLORS.length]);
      const n = mul(plan.normals[k], -1);        // inward: the finger pushes along it
      const up = (p) => add(p, mul(n, -lift));
      const tri = [];
      if (plan.surface_triangles) {              // a region across a curved surface
        for (const t of plan.surface_triangles[k]) for (const p of t) tri.push(up(p));
      } else {
        for (const t of triangulate(poly, n)) for (const i of t) tri.push(up(poly[i]));
      }
      const out = mul(n, -1);
      const mat = new THREE.MeshLambertMaterial({ color: col, side: THREE.DoubleSide,
                                                  polygonOffset: true,
                                                  polygonOffsetFactor: -2,
                                                  polygonOffsetUnits: -2 });
      group.add(new THREE.Mesh(geometry(tri, tri.map(() => out)), mat));
      const c = plan.centers[k];
      const tail = add(c, mul(n, -0.3 * V.part.size));
      group.add(new THREE.Line(geometry([tail, up(c)]),
                               new THREE.LineBasicMaterial({ color: col })));
      const dot3 = new THREE.Mesh(new THREE.SphereGeometry(V.part.size * 6e-3, 12, 8),
                                  new THREE.MeshBasicMaterial({ color: 0x1a1a1a }));
      dot3.position.set(...up(c));
      group.add(dot3);
    });
    return group;
  }

  // the hand of a jaw's pick at its pose (the report's boxes in the tool frame at its
  // largest opening, the fingers moved to the grasp's opening): palm dashed grey,
  // fingers dark, each a translucent box with its edges
  function handGroup(plan, hand) {
    const group = new THREE.Group();
    if (!plan.pose || !hand || !hand.boxes) return group;
    const R = rotation(plan.pose.orientation), p = plan.pose.position;
    const opening = typeof plan.opening === "number" ? plan.opening : hand.opening;
    const nPalm = hand.boxes.length - 2 * (hand.finger_boxes || 0);
    hand.boxes.forEach((b, k) => {
      const side = k < nPalm ? 0 : (k < nPalm + hand.finger_boxes ? 1 : -1);
      const centre = [...b.centre];
      centre[1] += side * (opening - hand.opening) / 2;
      const where = add(p, apply(R, centre));
      const Rb = R.map((r) => [0, 1, 2].map((j) => dot(r, [b.rotation[0][j], b.rotation[1][j],
                                                          b.rotation[2][j]])));
      const m = new THREE.Matrix4().set(Rb[0][0], Rb[0][1], Rb[0][2], where[0],
                                        Rb[1][0], Rb[1][1], Rb[1][2], where[1],
                                        Rb[2][0], Rb[2][1], Rb[2][2], where[2], 0, 0, 0, 1);
      const box = new THREE.BoxGeometry(...b.size);
      const colour = side === 0 ? 0x8c8c8c : 0x444444;
      const solid = new THREE.Mesh(box, new THREE.MeshLambertMaterial({
        color: colour, transparent: true, opacity: 0.35, depthWrite: false }));
      const edges = new THREE.LineSegments(new THREE.EdgesGeometry(box),
                                           new THREE.LineBasicMaterial({ color: colour }));
      for (const o of [solid, edges]) {
        o.matrixAutoUpdate = false;
        o.matrix.copy(m);
        o.name = "hand-box";
        group.add(o);
      }
    });
    return group;
  }

  // the table under a part resting on it (the scene's table is the plane z = 0 of the
  // world; the part's pose on it, `part_pose`, takes the part frame there): a square
  // twice the part's size with its outline, seen from above and below
  function tableMesh(scene) {
    if (!scene || !scene.table) return null;
    const pose = scene.part_pose || { position: [0, 0, 0], orientation: [0, 0, 0, 1] };
    const Rt = transpose(rotation(pose.orientation));
    const n = apply(Rt, scene.table.normal);                 // in the part frame
    const point = apply(Rt, sub(scene.table.point, pose.position));
    const c = V.part.center, h = dot(sub(c, point), n);
    const foot = sub(c, mul(n, h));
    const a = unit(Math.abs(n[2]) < 0.9 ? [-n[1], n[0], 0] : [1, 0, -n[0] / (n[2] || 1)]);
    const b = [n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]];
    const s = V.part.size, q = (u, v) => add(foot, add(mul(a, u * s), mul(b, v * s)));
    const tri = [q(-1, -1), q(1, -1), q(1, 1), q(-1, -1), q(1, 1), q(-1, 1)];
    const group = new THREE.Group();
    const mesh = new THREE.Mesh(geometry(tri, tri.map(() => n)), new THREE.MeshLambertMaterial({
      color: 0xc8a878, transparent: true, opacity: 0.3, side: THREE.DoubleSide,
      depthWrite: false }));
    mesh.name = "table";
    const rim = [q(-1, -1), q(1, -1), q(1, -1), q(1, 1), q(1, 1), q(-1, 1), q(-1, 1), q(-1, -1)];
    group.add(mesh, new THREE.LineSegments(geometry(rim),
                                           new THREE.LineBasicMaterial({ color: 0x8a6d45 })));
    return group;
  }

  // the part frame's axes (x red, y green, z blue) beside the part, off its corner so
  // that they hide no region, and a scale bar of a round length along x under it, its
  // length written over the canvas
  function frameGroup() {
    const group = new THREE.Group(), size = V.part.size;
    const lo = V.lo;
    const axes = new THREE.AxesHelper(size / 4);
    axes.position.set(lo[0] - 0.12 * size, lo[1] - 0.12 * size, lo[2]);
    axes.name = "axes";
    group.add(axes);
    const want = size / 3, p10 = 10 ** Math.floor(Math.log10(want));
    const len = [5, 2, 1].map((m) => m * p10).find((v) => v <= want) || p10;
    const y = lo[1] - 0.08 * size, z = lo[2];
    const bar = [[lo[0], y, z], [lo[0] + len, y, z], [lo[0], y - 0.02 * size, z],
                 [lo[0], y + 0.02 * size, z], [lo[0] + len, y - 0.02 * size, z],
                 [lo[0] + len, y + 0.02 * size, z]];
    const line = new THREE.LineSegments(geometry(bar),
                                        new THREE.LineBasicMaterial({ color: 0x222222 }));
    line.name = "scale";
    group.add(line);
    V.scale = { length: len, units: V.part.units || "" };
    let label = document.getElementById("scale3d");
    if (!label) {
      label = document.createElement("div");
      label.id = "scale3d";
      canvas.parentElement.appendChild(label);
    }
    label.textContent = `scale bar ${len} ${V.scale.units}; axes x red, y green, z blue`;
    label.hidden = false;
    return group;
  }

  function resize() {
    const r = canvas.parentElement.getBoundingClientRect();
    const W = Math.max(Math.round(r.width), 100), H = Math.max(Math.round(r.height), 100);
    if (canvas.width !== W || canvas.height !== H) V.renderer.setSize(W, H, false);
  }

  function render() {
    if (!context() || !V.part) return;
    resize();
    const W = canvas.width, H = canvas.height;
    const center = V.part.center, R = V.part.size / 2;
    const dir = [Math.cos(V.pitch) * Math.cos(V.yaw), Math.cos(V.pitch) * Math.sin(V.yaw),
                 Math.sin(V.pitch)];
    const d = 3 * R * V.dist;
    V.eye = add(center, mul(dir, d));
    const cam = V.camera;
    cam.aspect = W / H;
    cam.near = Math.max(d - 2 * R, d * 1e-3);
    cam.far = d + 2 * R;
    cam.position.set(...V.eye);
    cam.lookAt(...center);
    cam.updateProjectionMatrix();
    cam.updateMatrixWorld();
    V.lamp.position.set(...V.eye);
    V.lamp.target.position.set(...center);
    if (!V.mesh) { V.mesh = partMesh(V.part); V.scene.add(V.mesh); }
    dispose(V.extras);
    V.extras = new THREE.Group();
    if (V.plan) {
      V.extras.add(planGroup(V.plan));
      if (V.report) V.extras.add(handGroup(V.plan, V.report.hand));
    }
    const table = V.report ? tableMesh(V.report.scene) : null;
    if (table) V.extras.add(table);
    V.extras.add(frameGroup());
    V.scene.add(V.extras);
    V.renderer.render(V.scene, cam);
  }

  // a point of the part on the canvas (pixels from the top left) and its depth
  function project(p) {
    const v = new THREE.Vector3(...p).project(V.camera);
    return [(v.x + 1) / 2 * canvas.width, (1 - v.y) / 2 * canvas.height, v.z];
  }

  function pixel(x, y) {
    const gl = V.renderer.getContext(), px = new Uint8Array(4);
    gl.readPixels(Math.round(x), canvas.height - 1 - Math.round(y), 1, 1, gl.RGBA,
                  gl.UNSIGNED_BYTE, px);
    return Array.from(px);
  }

  // the names of what is drawn besides the part (for tests): hand boxes, table, axes
  function drawn() {
    const names = [];
    if (V.extras) V.extras.traverse((o) => { if (o.name) names.push(o.name); });
    return names;
  }

  canvas.addEventListener("pointerdown", (ev) => {
    V.drag = { x: ev.clientX, y: ev.clientY, yaw: V.yaw, pitch: V.pitch };
    canvas.setPointerCapture(ev.pointerId);
  });
  canvas.addEventListener("pointermove", (ev) => {
    if (!V.drag) return;
    V.yaw = V.drag.yaw - (ev.clientX - V.drag.x) * 0.01;
    V.pitch = Math.max(-1.5, Math.min(1.5, V.drag.pitch + (ev.clientY - V.drag.y) * 0.01));
    render();
  });
  canvas.addEventListener("pointerup", () => { V.drag = null; });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    V.dist = Math.max(0.2, Math.min(10, V.dist * Math.exp(ev.deltaY * 0.001)));
    render();
  }, { passive: false });

  return {
    show(part) {
      V.part = part; V.plan = null; V.report = null;
      V.lo = part.vertices.reduce((m, v) => m.map((x, i) => Math.min(x, v[i])),
                                  [Infinity, Infinity, Infinity]);
      if (context() && V.mesh) { dispose(V.mesh); }
      V.mesh = null;
      canvas.hidden = false;
      render();
      return V.error;
    },
    hide() {
      V.part = null; V.plan = null; V.report = null; canvas.hidden = true;
      const label = document.getElementById("scale3d");
      if (label) label.hidden = true;
    },
    draw(plan, report) { V.plan = plan || null; V.report = report || null; render(); },
    fit() { V.yaw = 0.7; V.pitch = 0.45; V.dist = 1; render(); },
    // look at a plan from where most of its regions face the camera: among each
    // region's outward normal and the bisectors of two of them (turned a little
    // upwards), the direction that sees the most regions, then the most squarely
    aim(plan) {
      const out = plan.normals.map((n) => [...n]);     // the report's: outward
      const cands = [...out];
      out.forEach((a, i) => out.slice(i + 1).forEach((b) => {
        const m = add(a, b);
        if (Math.hypot(...m) > 1e-6) cands.push(m);
      }));
      let best = null;
      for (const c of cands) {
        const d = unit(add(unit(c), [0, 0, 0.35]));
        const cos = out.map((o) => dot(d, o));
        const score = [cos.filter((v) => v > 0.2).length, cos.reduce((a, v) => a + v, 0)];
        if (!best || score[0] > best.score[0] ||
            (score[0] === best.score[0] && score[1] > best.score[1] + 1e-9)) {
          best = { d, score };
        }
      }
      if (!best) return false;
      V.yaw = Math.atan2(best.d[1], best.d[0]);
      V.pitch = Math.asin(Math.max(-1, Math.min(1, best.d[2])));
      render();
      return true;
    },
    render,
    // for tests and the console
    state: () => ({ yaw: V.yaw, pitch: V.pitch, dist: V.dist, eye: V.eye, error: V.error,
                    scale: V.scale, drawn: drawn(), library: `three.js r${THREE.REVISION}` }),
    project,
    pixel,
    triangulate,
    rotation,
  };
})();

window.Solid3D = Solid3D;
