// fcgrasp explorer: the 3-D view of a solid part (a mesh), drawn with WebGL by hand (no
// library). The page's app.js calls Solid3D.show(part), Solid3D.draw(plan) and
// Solid3D.hide(); the mouse orbits (drag) and zooms (wheel) about the part's centre.
"use strict";

const Solid3D = (() => {
  const canvas = document.getElementById("view3d");
  const V = { gl: null, prog: null, part: null, plan: null, yaw: 0.7, pitch: 0.45,
              dist: 1, mesh: null, drag: null, matrix: null, eye: [0, 0, 1],
              error: null };

  // ---------------------------------------------------------------- small 3-D algebra
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const crossV = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                            a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => { const n = Math.hypot(...a) || 1; return mul(a, 1 / n); };

  // column-major 4x4 matrices, as WebGL takes them
  function perspective(fovy, aspect, near, far) {
    const f = 1 / Math.tan(fovy / 2), d = near - far;
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / d, -1,
            0, 0, (2 * far * near) / d, 0];
  }
  function lookAt(eye, at, up) {
    const z = unit(sub(eye, at)), x = unit(crossV(up, z)), y = crossV(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
            -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }
  function times(a, b) {
    const out = new Array(16).fill(0);
    for (let c = 0; c < 4; c++) {
      for (let r = 0; r < 4; r++) {
        for (let k = 0; k < 4; k++) out[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
      }
    }
    return out;
  }
  const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16) / 255);

  // ---------------------------------------------------------------- WebGL
  const VERT = `attribute vec3 p; attribute vec3 n; attribute vec3 c;
    uniform mat4 m; uniform vec3 eye; uniform float lit;
    varying vec3 col;
    void main() {
      gl_Position = m * vec4(p, 1.0);
      gl_PointSize = 9.0;
      float d = abs(dot(normalize(n + vec3(1e-9)), normalize(eye - p)));
      col = lit > 0.5 ? c * (0.35 + 0.65 * d) : c;
    }`;
  const FRAG = `precision mediump float; varying vec3 col;
    void main() { gl_FragColor = vec4(col, 1.0); }`;

  function context() {
    if (V.gl || V.error) return V.gl;
    const gl = canvas.getContext("webgl", { preserveDrawingBuffer: true, antialias: true });
    if (!gl) { V.error = "this browser has no WebGL: the solid cannot be drawn"; return null; }
    const shader = (type, src) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    };
    const prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, VERT));
    gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, FRAG));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    V.gl = gl; V.prog = prog;
    return gl;
  }

  // one buffer of interleaved (position, normal, colour) rows
  function buffer(rows) {
    const gl = V.gl, b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(rows.flat()), gl.STATIC_DRAW);
    return { b, count: rows.length };
  }

  function drawBuffer(buf, mode, lit) {
    const gl = V.gl, prog = V.prog;
    gl.bindBuffer(gl.ARRAY_BUFFER, buf.b);
    [["p", 0], ["n", 3], ["c", 6]].forEach(([name, off]) => {
      const at = gl.getAttribLocation(prog, name);
      gl.enableVertexAttribArray(at);
      gl.vertexAttribPointer(at, 3, gl.FLOAT, false, 36, off * 4);
    });
    gl.uniform1f(gl.getUniformLocation(prog, "lit"), lit ? 1 : 0);
    gl.drawArrays(mode, 0, buf.count);
  }

  // the part's triangles, each with its own normal (flat shading)
  function meshRows(part) {
    const grey = [0.78, 0.78, 0.8], rows = [];
    for (const [i, j, k] of part.faces) {
      const a = part.vertices[i], b = part.vertices[j], c = part.vertices[k];
      const n = unit(crossV(sub(b, a), sub(c, a)));
      rows.push([...a, ...n, ...grey], [...b, ...n, ...grey], [...c, ...n, ...grey]);
    }
    return rows;
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
  function planRows(plan) {
    const lift = V.part.size * 2e-3, tri = [], pts = [], lines = [];
    plan.regions.forEach((poly, k) => {
      const col = rgb(COLORS[k % COLORS.length]);
      const n = mul(plan.normals[k], -1);        // inward: the finger pushes along it
      const up = (p) => add(p, mul(n, -lift));
      if (plan.surface_triangles) {              // a region across a curved surface
        for (const t of plan.surface_triangles[k]) {
          for (const p of t) tri.push([...up(p), ...n, ...col]);
        }
      } else {
        for (const t of triangulate(poly, n)) {
          for (const i of t) tri.push([...up(poly[i]), ...n, ...col]);
        }
      }
      const c = plan.centers[k];
      pts.push([...up(c), 0, 0, 0, 0.1, 0.1, 0.1]);
      const tail = add(c, mul(n, -0.3 * V.part.size));
      lines.push([...tail, 0, 0, 0, ...col], [...up(c), 0, 0, 0, ...col]);
    });
    return { tri, pts, lines };
  }

  function resize() {
    const r = canvas.parentElement.getBoundingClientRect();
    const W = Math.max(Math.round(r.width), 100), H = Math.max(Math.round(r.height), 100);
    if (canvas.width !== W || canvas.height !== H) { canvas.width = W; canvas.height = H; }
  }

  function render() {
    const gl = context();
    if (!gl || !V.part) return;
    resize();
    const W = canvas.width, H = canvas.height;
    const center = V.part.center, R = V.part.size / 2;
    const dir = [Math.cos(V.pitch) * Math.cos(V.yaw), Math.cos(V.pitch) * Math.sin(V.yaw),
                 Math.sin(V.pitch)];
    const d = 3 * R * V.dist;
    V.eye = add(center, mul(dir, d));
    V.matrix = times(perspective(Math.PI / 4, W / H, Math.max(d - 2 * R, d * 1e-3), d + 2 * R),
                     lookAt(V.eye, center, [0, 0, 1]));
    gl.viewport(0, 0, W, H);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.useProgram(V.prog);
    gl.uniformMatrix4fv(gl.getUniformLocation(V.prog, "m"), false, new Float32Array(V.matrix));
    gl.uniform3fv(gl.getUniformLocation(V.prog, "eye"), new Float32Array(V.eye));
    if (!V.mesh) V.mesh = buffer(meshRows(V.part));
    drawBuffer(V.mesh, gl.TRIANGLES, true);
    if (V.plan) {
      const { tri, pts, lines } = planRows(V.plan);
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(-2, -2);
      const bufs = [[buffer(tri), gl.TRIANGLES, true], [buffer(lines), gl.LINES, false],
                    [buffer(pts), gl.POINTS, false]];
      for (const [b, mode, lit] of bufs) drawBuffer(b, mode, lit);
      gl.disable(gl.POLYGON_OFFSET_FILL);
      for (const [b] of bufs) gl.deleteBuffer(b.b);
    }
  }

  // a point of the part on the canvas (pixels from the top left) and its depth
  function project(p) {
    const m = V.matrix, v = [p[0], p[1], p[2], 1];
    const o = [0, 1, 2, 3].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r]);
    return [(o[0] / o[3] + 1) / 2 * canvas.width, (1 - o[1] / o[3]) / 2 * canvas.height,
            o[2] / o[3]];
  }

  function pixel(x, y) {
    const gl = V.gl, px = new Uint8Array(4);
    gl.readPixels(Math.round(x), canvas.height - 1 - Math.round(y), 1, 1, gl.RGBA,
                  gl.UNSIGNED_BYTE, px);
    return Array.from(px);
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
      V.part = part; V.plan = null;
      if (V.mesh && V.gl) V.gl.deleteBuffer(V.mesh.b);
      V.mesh = null;
      canvas.hidden = false;
      context();
      render();
      return V.error;
    },
    hide() { V.part = null; V.plan = null; canvas.hidden = true; },
    draw(plan) { V.plan = plan || null; render(); },
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
    state: () => ({ yaw: V.yaw, pitch: V.pitch, dist: V.dist, eye: V.eye, error: V.error }),
    project,
    pixel,
    triangulate,
  };
})();
