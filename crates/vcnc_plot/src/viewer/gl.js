// vcnc plot viewer, part 2 of 4: colours, WebGL and the camera.
// The path is one static buffer of GL_LINES with a colour per segment, the
// part after the playback position drawn faint. Camera: orthographic,
// turntable about the machine's up axis (Z; a lathe's section does not
// turn), drag to turn, wheel to zoom at the cursor, right-drag or
// shift-drag to pan. A 2D canvas over the WebGL one carries the axis
// triad, the scale bar, the marks where moves leave the view and the
// measure tool's line.

// ---- colours -----------------------------------------------------------
// Set from the first data (`firstLook`); the user's choices after that.
let theme = "light", colorBy = "tool", showCompare = true, showGrid = true, showRapid = true;
// Whether the user picked the colouring (else each new plot's holds).
let colorChosen = false;
function firstLook() {
  theme = D.theme;
  colorBy = D.color;
  // A program of rapids alone shows them whatever --no-rapids says.
  showRapid = D.rapids || D.cutMoves === 0;
}
const pal = () => D.palette[theme];
function ramp(stops, t, steps) {
  if (!isFinite(t)) t = 0.5;
  t = Math.min(1, Math.max(0, t));
  const q = Math.round(t * (steps - 1)) / (steps - 1);
  const x = q * (stops.length - 1), i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
  return [0, 1, 2].map((k) => Math.round(stops[i][k] + (stops[i + 1][k] - stops[i][k]) * f));
}
let depthAxis = 2, depthRange = [0, 0], feedRange = [0, 0];
function range(f) {
  let lo = Infinity, hi = -Infinity;
  for (let i = 1; i < P.n; i++) if (P.kind[i] === 2) { const v = f(i); if (v < lo) lo = v; if (v > hi) hi = v; }
  return lo <= hi ? [lo, hi] : [0, 0];
}
// What the colours of a plot span.
function deriveRanges() {
  depthAxis = D.lathe ? 0 : 2;
  depthRange = range((i) => P.pos[3 * i + depthAxis]);
  feedRange = range((i) => P.feed[i]);
}
const frac = (v, r) => (r[1] - r[0] > 1e-9 ? (v - r[0]) / (r[1] - r[0]) : 0.5);
// Before the first tool change a program that names tools is grey; one
// that never names a tool gets the palette's first colour.
function toolColor(t) {
  const p = pal();
  if (t === 0) return D.tools.length ? p.noTool : p.tools[0];
  return p.tools[(t - 1) % p.tools.length];
}
function segColor(i) {
  const p = pal();
  if (P.kind[i] === 1) return showRapid ? [...p.rapid, 255] : [0, 0, 0, 0];
  let c;
  if (colorBy === "tool") c = toolColor(P.tool[i]);
  else if (colorBy === "feed") c = ramp(p.feed, frac(P.feed[i], feedRange), 16);
  else c = ramp(p.depth, frac((P.pos[3 * i + depthAxis] + P.pos[3 * (i - 1) + depthAxis]) / 2, depthRange), 32);
  return [...c, 255];
}
const SELECT = [230, 0, 200, 255];

// ---- WebGL -------------------------------------------------------------
const canvas = $("gl"), overlay = $("overlay"), ctx2d = overlay.getContext("2d");
// A software renderer (no GPU: SwiftShader, llvmpipe) draws lines about
// three times faster without multisampling, so it gets none.
function softwareGL() {
  const g = document.createElement("canvas").getContext("webgl");
  if (!g) return false;
  const info = g.getExtension("WEBGL_debug_renderer_info");
  const name = String(info ? g.getParameter(info.UNMASKED_RENDERER_WEBGL) : g.getParameter(g.RENDERER));
  const lose = g.getExtension("WEBGL_lose_context");
  if (lose) lose.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}
const software = softwareGL();
// preserveDrawingBuffer: the picture can be read back (screenshots, tests).
const gl = canvas.getContext("webgl", { antialias: !software, preserveDrawingBuffer: true });
const VS = "attribute vec3 a_pos; attribute vec4 a_col; attribute float a_dash;" +
  "uniform mat4 u_mvp; uniform float u_point; varying vec4 v_col; varying float v_dash;" +
  "void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); v_col = a_col; v_dash = a_dash; gl_PointSize = u_point; }";
const PREC = "#ifdef GL_FRAGMENT_PRECISION_HIGH\nprecision highp float;\n#else\nprecision mediump float;\n#endif\n";
const FS = PREC +
  "varying vec4 v_col; varying float v_dash; uniform float u_dash; uniform float u_alpha; uniform float u_round;" +
  "void main() { if (v_dash >= 0.0 && fract(v_dash / u_dash) > 0.55) discard;" +
  " if (u_round > 0.5) { vec2 d = gl_PointCoord - vec2(0.5); if (dot(d, d) > 0.25) discard; }" +
  " gl_FragColor = vec4(v_col.rgb, v_col.a * u_alpha); }";
// Meshes: flat-shaded by a light from the viewer.
const MVS = "attribute vec3 a_pos; attribute vec3 a_nrm; uniform mat4 u_mvp; uniform vec3 u_eye; uniform vec4 u_col; varying vec4 v_col;" +
  "void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); float l = 0.35 + 0.65 * abs(dot(normalize(a_nrm), u_eye)); v_col = vec4(u_col.rgb * l, u_col.a); }";
const MFS = PREC + "varying vec4 v_col; void main() { gl_FragColor = v_col; }";
let prog = null, mprog = null;
const loc = {}, mloc = {};
function shader(type, src) {
  const s = gl.createShader(type);
  gl.shaderSource(s, src);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
  return s;
}
function program(vs, fs, attrs, uniforms, into) {
  const p = gl.createProgram();
  gl.attachShader(p, shader(gl.VERTEX_SHADER, vs));
  gl.attachShader(p, shader(gl.FRAGMENT_SHADER, fs));
  gl.linkProgram(p);
  for (const n of attrs) into[n] = gl.getAttribLocation(p, n);
  for (const n of uniforms) into[n] = gl.getUniformLocation(p, n);
  return p;
}
if (gl) {
  prog = program(VS, FS, ["a_pos", "a_col", "a_dash"], ["u_mvp", "u_point", "u_dash", "u_alpha", "u_round"], loc);
  mprog = program(MVS, MFS, ["a_pos", "a_nrm"], ["u_mvp", "u_eye", "u_col"], mloc);
  gl.enable(gl.BLEND);
  // Keep the canvas opaque: blend colours, never lower its alpha.
  gl.blendFuncSeparate(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA, gl.ONE, gl.ONE_MINUS_SRC_ALPHA);
} else {
  $("nogl").hidden = false;
}

// A buffer of GL_LINES (or points): x y z dash (f32) + rgba (u8), 20 bytes a vertex.
function upload(buf, count) {
  if (!gl) return { count };
  const b = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, b);
  gl.bufferData(gl.ARRAY_BUFFER, buf, gl.STATIC_DRAW);
  return { b, count };
}
function drop(g) { if (gl && g && g.b) gl.deleteBuffer(g.b); }
function lineBuffer(p, color, dashed) {
  let segs = 0;
  const before = new Uint32Array(p.n + 1);
  for (let i = 0; i < p.n; i++) { if (i > 0 && p.kind[i] !== 0) segs++; before[i + 1] = segs; }
  const buf = new ArrayBuffer(segs * 40), f = new Float32Array(buf), u = new Uint8Array(buf);
  let s = 0;
  for (let i = 1; i < p.n; i++) {
    if (p.kind[i] === 0) continue;
    const c = color(i);
    const len = Math.hypot(p.pos[3 * i] - p.pos[3 * i - 3], p.pos[3 * i + 1] - p.pos[3 * i - 2], p.pos[3 * i + 2] - p.pos[3 * i - 1]);
    for (let e = 0; e < 2; e++) {
      const j = i - 1 + e, o = (2 * s + e) * 5;
      f[o] = p.pos[3 * j]; f[o + 1] = p.pos[3 * j + 1]; f[o + 2] = p.pos[3 * j + 2];
      f[o + 3] = dashed && p.kind[i] === 1 ? e * len : -1;
      u.set(c, (o + 4) * 4);
    }
    s++;
  }
  const g = upload(buf, segs * 2);
  g.before = before;
  return g;
}
// Lines from a flat list of [x, y, z] pairs, one colour.
function pairsBuffer(pts, c) {
  const buf = new ArrayBuffer(pts.length * 20), f = new Float32Array(buf), u = new Uint8Array(buf);
  pts.forEach((q, k) => { f.set([q[0], q[1], q[2], -1], k * 5); u.set(c, k * 20 + 16); });
  return upload(buf, pts.length);
}
function pointBuffer(points) {
  const buf = new ArrayBuffer(points.length * 20), f = new Float32Array(buf), u = new Uint8Array(buf);
  points.forEach((q, k) => { f.set([q[0], q[1], q[2], -1], k * 5); u.set(q[3], k * 20 + 16); });
  return upload(buf, points.length);
}
// While the view moves, a large path is drawn from a preview that keeps
// every k-th vertex (at most PREVIEW segments), so that turning and
// zooming stay fluid on a software renderer; the full path is drawn as
// soon as the motion stops.
const PREVIEW = 16384;
function previewBuffer(p, color) {
  const stride = Math.ceil(p.n / PREVIEW);
  const picks = [];
  for (let i = 0; i < p.n; i += stride) picks.push(i);
  if (picks[picks.length - 1] !== p.n - 1) picks.push(p.n - 1);
  const buf = new ArrayBuffer(picks.length * 40), f = new Float32Array(buf), u = new Uint8Array(buf);
  const ends = new Uint32Array(picks.length);
  let s = 0;
  for (let k = 1; k < picks.length; k++) {
    const a = picks[k - 1], b = picks[k];
    let jump = false;
    for (let i = a + 1; i <= b && !jump; i++) jump = p.kind[i] === 0;
    if (jump) continue;
    const c = color(b);
    for (let e = 0; e < 2; e++) {
      const j = e === 0 ? a : b, o = (2 * s + e) * 5;
      f[o] = p.pos[3 * j]; f[o + 1] = p.pos[3 * j + 1]; f[o + 2] = p.pos[3 * j + 2]; f[o + 3] = -1;
      u.set(c, (o + 4) * 4);
    }
    ends[s++] = b;
  }
  const g = upload(buf, s * 2);
  g.ends = ends.subarray(0, s);
  return g;
}
// A mesh as flat-shaded triangles: position and face normal per corner.
function meshBuffer(m) {
  const nt = Math.floor(m.tri.length / 3), f = new Float32Array(nt * 18);
  for (let t = 0; t < nt; t++) {
    const v = [0, 1, 2].map((c) => { const k = m.tri[3 * t + c]; return k < m.n ? [m.pos[3 * k], m.pos[3 * k + 1], m.pos[3 * k + 2]] : [0, 0, 0]; });
    const e1 = [0, 1, 2].map((k) => v[1][k] - v[0][k]), e2 = [0, 1, 2].map((k) => v[2][k] - v[0][k]);
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    for (let c = 0; c < 3; c++) f.set([...v[c], ...n], (3 * t + c) * 6);
  }
  if (!gl) return { count: 0 };
  const b = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, b);
  gl.bufferData(gl.ARRAY_BUFFER, f, gl.STATIC_DRAW);
  return { b, count: nt * 3 };
}
// The twelve edges of a box.
function boxPairs(lo, hi) {
  const c = (k) => [k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]];
  const out = [];
  for (let a = 0; a < 8; a++) for (const bit of [1, 2, 4]) if (!(a & bit)) out.push(c(a), c(a | bit));
  return out;
}
let main = null, preview = null, cmp = null, contour = null, marks = null, origins = null, limits = null;
let meshBufs = [];
function buildMeshes() {
  for (const g of meshBufs) drop(g);
  meshBufs = meshes.map(meshBuffer);
  extent = D.size / 2;
  for (const m of meshes) for (let k = 0; k < m.pos.length; k += 3) extent = Math.max(extent, Math.hypot(m.pos[k], m.pos[k + 1], m.pos[k + 2]));
}
let moving = false, still = 0;
function move() {
  moving = true;
  clearTimeout(still);
  still = setTimeout(() => { moving = false; request(); }, 150);
}
function build() {
  if (!P) return;
  const p = pal();
  for (const g of [main, preview, cmp, contour, marks, origins, limits]) drop(g);
  main = lineBuffer(P, segColor, true);
  preview = main.count / 2 > 2 * PREVIEW ? previewBuffer(P, segColor) : null;
  cmp = K ? lineBuffer(K, (i) => (K.kind[i] === 1 && !showRapid ? [0, 0, 0, 0] : [...p.compare, 200]), true) : null;
  contour = C ? lineBuffer(C, () => [...p.contour, 255], false) : null;
  const pts = [];
  for (let k = 0; k < holes.length; k += 3) pts.push([holes[k], holes[k + 1], holes[k + 2], [...p.hole, 255]]);
  for (const t of toolChanges) pts.push([t[0], t[1], t[2], [...p.toolChange, 255]]);
  pts.push([P.pos[0], P.pos[1], P.pos[2], [...p.start, 255]]);
  if (D.alarm) pts.push([...D.alarm.at, [...p.alarm, 255]]);
  marks = pointBuffer(pts);
  const axes = [];
  const l = D.size * 0.06;
  for (const o of D.origins) {
    const [at, xd, yd] = o;
    const zd = [xd[1] * yd[2] - xd[2] * yd[1], xd[2] * yd[0] - xd[0] * yd[2], xd[0] * yd[1] - xd[1] * yd[0]];
    [[xd, [220, 40, 40, 255]], [yd, [40, 170, 40, 255]], [zd, [40, 90, 220, 255]]].forEach(([d, c]) => {
      axes.push([at[0], at[1], at[2], c], [at[0] + d[0] * l, at[1] + d[1] * l, at[2] + d[2] * l, c]);
    });
  }
  origins = pointBuffer(axes);
  const pairs = D.limits ? boxPairs(D.limits[0], D.limits[1]) : [];
  // A lathe's spindle axis (X = 0) along the part and beyond.
  if (D.lathe) { const x = -D.center[0], [lo, hi] = fitBox("all"), m = D.size; pairs.push([x, 0, lo[2] - m], [x, 0, hi[2] + m]); }
  limits = pairs.length ? pairsBuffer(pairs, [...p.muted, 200]) : null;
}

// ---- camera ------------------------------------------------------------
// R: rows are screen right, up and towards the viewer in machine axes.
const VIEWS = {
  top: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
  front: [[1, 0, 0], [0, 0, 1], [0, -1, 0]],
  side: [[0, 1, 0], [0, 0, 1], [1, 0, 0]],
  iso: [[Math.SQRT1_2, Math.SQRT1_2, 0], [-1 / Math.sqrt(6), 1 / Math.sqrt(6), 2 / Math.sqrt(6)], [1 / Math.sqrt(3), -1 / Math.sqrt(3), 1 / Math.sqrt(3)]],
};
let UP = [0, 0, 1];
let R = VIEWS.iso.map((r) => r.slice());
let scale = 1, pan = [0, 0];
// A lathe's front view is its half-section, and it turns about X.
function deriveViews() {
  VIEWS.front = D.lathe ? [[0, 0, 1], [1, 0, 0], [0, 1, 0]] : [[1, 0, 0], [0, 0, 1], [0, -1, 0]];
  UP = D.lathe ? [1, 0, 0] : [0, 0, 1];
}
// The plot's own view, fitted to it (at the start, and when asked).
function frameView() {
  R = VIEWS[D.lathe ? "front" : D.view].map((r) => r.slice());
  fitTo = D.fit === "all" || !D.cuts ? "all" : "cuts";
  fit();
}
// A new plot under the same camera: its points are relative to its own
// centre, so the pan moves by the centre's shift, and every machine point
// stays where it was on the screen.
function keepCamera(oldCenter) {
  const d = [0, 1, 2].map((k) => D.center[k] - oldCenter[k]);
  pan = [pan[0] + scale * dot(R[0], d), pan[1] + scale * dot(R[1], d)];
  if (fitTo === "cuts" && !D.cuts) fitTo = "all";
  viewChanged();
}
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const dpr = () => window.devicePixelRatio || 1;
// How far anything drawn is from the centre: the depth range of the view
// (set with the meshes' buffers).
let extent = 1;
// The box Fit frames: the cuts (--fit cuts), or everything; a lathe's
// half-section from the spindle axis up.
let fitTo = "cuts";
function fitBox(what) {
  let lo = (what === "cuts" && D.cuts ? D.cuts[0] : D.lo).slice(), hi = (what === "cuts" && D.cuts ? D.cuts[1] : D.hi).slice();
  if (what === "all" && D.limits) { lo = lo.map((v, k) => Math.min(v, D.limits[0][k])); hi = hi.map((v, k) => Math.max(v, D.limits[1][k])); }
  if (what === "all") {
    for (const m of meshes) {
      for (let i = 0; i < m.pos.length; i += 3) for (let k = 0; k < 3; k++) { lo[k] = Math.min(lo[k], m.pos[i + k]); hi[k] = Math.max(hi[k], m.pos[i + k]); }
    }
  }
  if (D.lathe) { lo[0] = Math.min(lo[0], -D.center[0]); hi[0] = Math.max(hi[0], -D.center[0]); }
  if (Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) < 1e-6) { lo = lo.map((v) => v - 5); hi = hi.map((v) => v + 5); }
  return [lo, hi];
}
function fit() {
  if (!P) return;
  const w = canvas.width, h = canvas.height, [lo, hi] = fitBox(fitTo);
  let ulo = Infinity, uhi = -Infinity, vlo = Infinity, vhi = -Infinity;
  for (let k = 0; k < 8; k++) {
    const c = [k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]];
    const u = dot(R[0], c), v = dot(R[1], c);
    ulo = Math.min(ulo, u); uhi = Math.max(uhi, u); vlo = Math.min(vlo, v); vhi = Math.max(vhi, v);
  }
  scale = 0.9 * Math.min(w / Math.max(uhi - ulo, 1e-6), h / Math.max(vhi - vlo, 1e-6));
  if (!isFinite(scale) || scale <= 0) scale = 1;
  pan = [-scale * (ulo + uhi) / 2, -scale * (vlo + vhi) / 2];
  viewChanged();
}
function rotate(axis, a, v) {
  const c = Math.cos(a), s = Math.sin(a), d = dot(axis, v);
  const x = [axis[1] * v[2] - axis[2] * v[1], axis[2] * v[0] - axis[0] * v[2], axis[0] * v[1] - axis[1] * v[0]];
  return [0, 1, 2].map((k) => v[k] * c + x[k] * s + axis[k] * d * (1 - c));
}
function turn(dx, dy) {
  // Turntable: about the machine's up axis, then about the screen's right.
  R = R.map((row) => rotate(UP, -dx * 0.008, row));
  const right = R[0];
  R = [R[0], rotate(right, dy * 0.008, R[1]), rotate(right, dy * 0.008, R[2])];
  viewChanged();
}
// The projection; `depth`: with the depth of each point (meshes), else
// every point at depth 0, so that lines are never cut by the near and far
// planes (they are drawn without a depth test).
function mvp(depth) {
  const w = canvas.width, h = canvas.height, sx = (2 * scale) / w, sy = (2 * scale) / h, z = depth ? 0.99 / Math.max(extent, 1e-6) : 0;
  return new Float32Array([
    R[0][0] * sx, R[1][0] * sy, -R[2][0] * z, 0,
    R[0][1] * sx, R[1][1] * sy, -R[2][1] * z, 0,
    R[0][2] * sx, R[1][2] * sy, -R[2][2] * z, 0,
    (2 * pan[0]) / w, (2 * pan[1]) / h, 0, 1,
  ]);
}
// A point relative to the centre, in CSS pixels of the view.
function project(x, y, z) {
  const w = canvas.width, h = canvas.height, r = dpr();
  return [(w / 2 + scale * (R[0][0] * x + R[0][1] * y + R[0][2] * z) + pan[0]) / r,
    (h / 2 - scale * (R[1][0] * x + R[1][1] * y + R[1][2] * z) - pan[1]) / r];
}

// ---- grid and scale ----------------------------------------------------
// The grid lies in the machine plane that faces the viewer most (XY from
// the top, XZ from the front; a lathe's section: XZ), at the back of the
// frame, with a round step in the display unit about 80 px apart.
function niceStep(x) {
  const mag = Math.pow(10, Math.floor(Math.log10(x))), f = x / mag;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * mag;
}
function gridStep() { return niceStep((80 * dpr()) / scale * UNIT.per) / UNIT.per; }
let gridCache = { key: "", g: null };
function gridBuffer() {
  const nk = D.lathe ? 1 : [0, 1, 2].reduce((b, k) => (Math.abs(R[2][k]) > Math.abs(R[2][b]) ? k : b), 0);
  if (Math.abs(R[2][nk]) < 0.25) return null;
  const [a, b] = [0, 1, 2].filter((k) => k !== nk);
  const [lo] = fitBox(fitTo);
  const c = D.lathe ? 0 : lo[nk];
  const step = gridStep();
  // The view's corners on the grid's plane (a ray along R[2] from each).
  const w = canvas.width, h = canvas.height;
  const amin = [Infinity, Infinity], amax = [-Infinity, -Infinity];
  for (const [sx, sy] of [[-w / 2, -h / 2], [w / 2, -h / 2], [-w / 2, h / 2], [w / 2, h / 2]]) {
    const u = (sx - pan[0]) / scale, v = (sy - pan[1]) / scale;
    const p0 = [0, 1, 2].map((k) => u * R[0][k] + v * R[1][k]);
    const t = (c - p0[nk]) / R[2][nk];
    const p = p0.map((x, k) => x + t * R[2][k]);
    [a, b].forEach((ax, i) => { amin[i] = Math.min(amin[i], p[ax]); amax[i] = Math.max(amax[i], p[ax]); });
  }
  // Grid lines sit on round numbers of machine coordinates.
  const lines0 = [a, b].map((ax, i) => [Math.ceil((amin[i] + D.center[ax]) / step), Math.floor((amax[i] + D.center[ax]) / step)]);
  if (lines0.some(([p, q]) => !(q - p < 400))) return null;
  const key = [nk, c, step, ...lines0.flat(), amin, amax].join(",") + theme;
  if (gridCache.key === key) return gridCache.g;
  const pts = [];
  [a, b].forEach((ax, i) => {
    const other = [a, b][1 - i], j = 1 - i;
    for (let k = lines0[i][0]; k <= lines0[i][1]; k++) {
      const p = [0, 0, 0], q = [0, 0, 0];
      p[nk] = q[nk] = c;
      p[ax] = q[ax] = k * step - D.center[ax];
      p[other] = amin[j]; q[other] = amax[j];
      pts.push(p, q);
    }
  });
  drop(gridCache.g);
  gridCache = { key, g: pairsBuffer(pts, [...pal().grid, 255]) };
  return gridCache.g;
}

// ---- the tool, drawn to size --------------------------------------------
// From the tip (the controlled point less the tool length offset) up: the
// cutting end (flat, ball, bull nose, or the cone of a drill or V
// cutter), the flutes as a cylinder, and a line up to the gauge point; a
// lathe's insert as its nose radius. Without a size, a dot.
function ring(cx, cy, z, r, out, plane) {
  const n = 32;
  for (let k = 0; k < n; k++) {
    const a0 = (2 * Math.PI * k) / n, a1 = (2 * Math.PI * (k + 1)) / n;
    const p = (a) => (plane === "xz" ? [cx + r * Math.cos(a), 0, z + r * Math.sin(a)] : [cx + r * Math.cos(a), cy + r * Math.sin(a), z]);
    out.push(p(a0), p(a1));
  }
}
function toolPairs(i, at) {
  const t = P.tool[i], s = t ? D.toolShapes[t - 1] : null;
  if (!s) return null;
  const f = frameAt(i), tlo = f ? f.tlo : [0, 0, 0];
  const tip = at.map((v, k) => v - tlo[k]);
  const out = [], r = s.d / 2;
  if (D.lathe) {
    ring(tip[0], 0, tip[2], Math.max(s.corner, r * 0.05, 0.05), out, "xz");
    return out;
  }
  const [x, y, z] = tip;
  const flute = s.flute > 0 ? s.flute : 1.5 * s.d;
  let bottom = z;
  if (s.kind === "drill" || s.kind === "vee") {
    const half = ((s.angle > 0 && s.angle < 180 ? s.angle : 118) * Math.PI) / 360;
    bottom = z + r / Math.tan(half);
    for (let k = 0; k < 4; k++) { const a = (k * Math.PI) / 2; out.push([x, y, z], [x + r * Math.cos(a), y + r * Math.sin(a), bottom]); }
  } else {
    const c = Math.min(Math.max(s.corner, 0), r);
    bottom = z + c;
    if (c > 0) {
      // Quarter arcs from the flat (radius r − c) up to the side.
      for (let k = 0; k < 4; k++) {
        const a = (k * Math.PI) / 2, ux = Math.cos(a), uy = Math.sin(a);
        for (let j = 0; j < 8; j++) {
          const q = (b) => [x + ux * (r - c + c * Math.sin(b)), y + uy * (r - c + c * Math.sin(b)), z + c - c * Math.cos(b)];
          out.push(q((j * Math.PI) / 16), q(((j + 1) * Math.PI) / 16));
        }
      }
    }
    if (r - c > 1e-9) ring(x, y, z, r - c, out);
  }
  ring(x, y, bottom, r, out);
  ring(x, y, z + flute, r, out);
  for (let k = 0; k < 4; k++) { const a = (k * Math.PI) / 2; out.push([x + r * Math.cos(a), y + r * Math.sin(a), bottom], [x + r * Math.cos(a), y + r * Math.sin(a), z + flute]); }
  if (at[2] > z + flute) out.push([x, y, z + flute], [x, y, at[2]]);
  return out;
}

// ---- drawing -----------------------------------------------------------
let cur = 0, sel = null, selBuf = null;
// `drawnLoad`: the plot (`vcnc.loads()`) the last frame drew; `drawnAt`:
// when it ended (ms since the epoch, comparable across frames).
const stats = { frames: 0, lastMs: 0, totalMs: 0, drawnLoad: 0, drawnAt: 0 };
function resize() {
  const r = dpr();
  const w = Math.max(1, Math.round(canvas.clientWidth * r)), h = Math.max(1, Math.round(canvas.clientHeight * r));
  if (canvas.width !== w || canvas.height !== h) {
    canvas.width = w; canvas.height = h; overlay.width = w; overlay.height = h;
    return true;
  }
  return false;
}
function bind(g) {
  gl.bindBuffer(gl.ARRAY_BUFFER, g.b);
  gl.enableVertexAttribArray(loc.a_pos);
  gl.vertexAttribPointer(loc.a_pos, 3, gl.FLOAT, false, 20, 0);
  gl.enableVertexAttribArray(loc.a_dash);
  gl.vertexAttribPointer(loc.a_dash, 1, gl.FLOAT, false, 20, 12);
  gl.enableVertexAttribArray(loc.a_col);
  gl.vertexAttribPointer(loc.a_col, 4, gl.UNSIGNED_BYTE, true, 20, 16);
}
function lines_(g, first, count, alpha) {
  if (!g || count <= 0) return;
  bind(g);
  gl.uniform1f(loc.u_alpha, alpha);
  gl.uniform1f(loc.u_round, 0);
  gl.drawArrays(gl.LINES, first, count);
}
function points_(g, size) {
  if (!g || !g.count) return;
  bind(g);
  gl.uniform1f(loc.u_alpha, 1);
  gl.uniform1f(loc.u_round, 1);
  gl.uniform1f(loc.u_point, size * dpr());
  gl.drawArrays(gl.POINTS, 0, g.count);
  gl.uniform1f(loc.u_point, 1);
}
function drawMeshes(m4) {
  if (!meshes.some((m) => m.visible)) return;
  gl.useProgram(mprog);
  gl.enable(gl.DEPTH_TEST);
  gl.clear(gl.DEPTH_BUFFER_BIT);
  gl.uniformMatrix4fv(mloc.u_mvp, false, m4);
  gl.uniform3fv(mloc.u_eye, R[2]);
  gl.disableVertexAttribArray(loc.a_col);
  gl.disableVertexAttribArray(loc.a_dash);
  meshes.forEach((m, k) => {
    const g = meshBufs[k];
    if (!m.visible || !g.count) return;
    gl.bindBuffer(gl.ARRAY_BUFFER, g.b);
    gl.enableVertexAttribArray(mloc.a_pos);
    gl.vertexAttribPointer(mloc.a_pos, 3, gl.FLOAT, false, 24, 0);
    gl.enableVertexAttribArray(mloc.a_nrm);
    gl.vertexAttribPointer(mloc.a_nrm, 3, gl.FLOAT, false, 24, 12);
    gl.uniform4f(mloc.u_col, m.color[0] / 255, m.color[1] / 255, m.color[2] / 255, 0.85);
    gl.drawArrays(gl.TRIANGLES, 0, g.count);
  });
  gl.disableVertexAttribArray(mloc.a_nrm);
  gl.disable(gl.DEPTH_TEST);
  gl.useProgram(prog);
}
function draw() {
  if (!P) return;
  const t0 = performance.now();
  resize();
  if (gl) {
    const bg = pal().bg, m4 = mvp(false);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(bg[0] / 255, bg[1] / 255, bg[2] / 255, 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.useProgram(prog);
    gl.uniformMatrix4fv(loc.u_mvp, false, m4);
    gl.uniform1f(loc.u_dash, (10 * dpr()) / scale);
    gl.uniform1f(loc.u_point, 1);
    // The grid lies behind everything: the meshes cover it.
    const grid = showGrid ? gridBuffer() : null;
    if (grid) lines_(grid, 0, grid.count, 1);
    drawMeshes(mvp(true));
    gl.uniformMatrix4fv(loc.u_mvp, false, m4);
    if (limits) lines_(limits, 0, limits.count, 1);
    if (cmp && showCompare) lines_(cmp, 0, cmp.count, 0.8);
    if (moving && preview) {
      let lo = 0, hi = preview.ends.length;
      while (lo < hi) { const m = (lo + hi) >> 1; if (preview.ends[m] <= cur) lo = m + 1; else hi = m; }
      lines_(preview, 0, 2 * lo, 1);
      lines_(preview, 2 * lo, preview.count - 2 * lo, 0.3);
    } else {
      const done = 2 * main.before[cur + 1];
      lines_(main, 0, done, 1);
      lines_(main, done, main.count - done, 0.3);
    }
    if (contour) lines_(contour, 0, contour.count, 0.9);
    lines_(origins, 0, origins.count, 1);
    if (selBuf) { lines_(selBuf, 0, selBuf.count, 1); points_(selBuf, 4); }
    points_(marks, 7);
    const hp = herePoint(), pairs = toolPairs(cur, hp);
    if (pairs) {
      const g = pairsBuffer(pairs, [...pal().alarm, 255]);
      lines_(g, 0, g.count, 1);
      drop(g);
    }
    const here = pointBuffer([[hp[0], hp[1], hp[2], [...pal().alarm, 255]]]);
    points_(here, pairs ? 5 : 11);
    drop(here);
  }
  drawOverlay();
  const ms = performance.now() - t0;
  stats.frames++; stats.lastMs = ms; stats.totalMs += ms; stats.drawnLoad = loadSerial;
  stats.drawnAt = performance.timeOrigin + performance.now();
}
let pending = false;
function request() {
  if (pending) return;
  pending = true;
  requestAnimationFrame(() => { pending = false; draw(); });
}
// Every change of the camera: the screen positions cached for picking
// are stale, and a frame is due.
let viewSerial = 0;
function viewChanged() { viewSerial++; request(); }
// Lines 1 px wide: the GL line list of the selected line's segments.
function setSelection(s) {
  sel = s;
  drop(selBuf);
  selBuf = null;
  if (s) {
    const pts = [];
    for (let i = 1; i < P.n && pts.length < 400000; i++) {
      if (P.line[i] === s.line && (P.file ? P.file[i] : 0) === s.file && P.kind[i] !== 0 && (showRapid || P.kind[i] !== 1)) {
        pts.push([P.pos[3 * i - 3], P.pos[3 * i - 2], P.pos[3 * i - 1]], [P.pos[3 * i], P.pos[3 * i + 1], P.pos[3 * i + 2]]);
      }
    }
    selBuf = pts.length ? pairsBuffer(pts, SELECT) : null;
  }
  request();
}

// ---- the overlay: triad, scale, exits, measure, hover --------------------
function arrow(x, y, ux, uy, color) {
  ctx2d.fillStyle = color;
  ctx2d.beginPath();
  ctx2d.moveTo(x, y);
  ctx2d.lineTo(x - 10 * ux + 4.5 * uy, y - 10 * uy - 4.5 * ux);
  ctx2d.lineTo(x - 10 * ux - 4.5 * uy, y - 10 * uy + 4.5 * ux);
  ctx2d.closePath();
  ctx2d.fill();
}
const rgb = (c) => "rgb(" + c[0] + "," + c[1] + "," + c[2] + ")";
function drawTriad(W, H) {
  const x = 44, y = H - 44, names = D.lathe ? [0, 2] : [0, 1, 2], colors = ["#d42828", "#28a028", "#2858dc"];
  ctx2d.lineWidth = 2;
  ctx2d.font = "bold 12px system-ui, sans-serif";
  ctx2d.textAlign = "center";
  ctx2d.textBaseline = "middle";
  for (const k of names) {
    const dx = R[0][k] * 30, dy = -R[1][k] * 30;
    ctx2d.strokeStyle = ctx2d.fillStyle = colors[k];
    ctx2d.beginPath(); ctx2d.moveTo(x, y); ctx2d.lineTo(x + dx, y + dy); ctx2d.stroke();
    if (Math.hypot(dx, dy) > 3) ctx2d.fillText(AXES[k], x + dx * 1.35, y + dy * 1.35);
    else ctx2d.fillText(AXES[k] + "·", x + 8, y - 8);
  }
}
function drawScale(W, H) {
  const step = gridStep(), px = (step * scale) / dpr();
  const x1 = W - 16, x0 = x1 - px, y = H - 18;
  ctx2d.strokeStyle = ctx2d.fillStyle = rgb(pal().text);
  ctx2d.lineWidth = 1.5;
  ctx2d.beginPath();
  ctx2d.moveTo(x0, y - 4); ctx2d.lineTo(x0, y); ctx2d.lineTo(x1, y); ctx2d.lineTo(x1, y - 4);
  ctx2d.stroke();
  ctx2d.font = "12px system-ui, sans-serif";
  ctx2d.textAlign = "center";
  ctx2d.textBaseline = "bottom";
  const v = step * UNIT.per, label = (v >= 1 ? String(Math.round(v * 1e6) / 1e6) : v.toPrecision(1)) + " " + UNIT.name;
  ctx2d.fillText((showGrid ? "grid " : "") + label, (x0 + x1) / 2, y - 5);
}
// Moves that leave the view: an arrowhead on the edge where each goes
// out (one per 8 px and heading), as in the flat plots.
function drawExits(W, H) {
  const seen = new Set();
  for (const i of exitSegs) {
    if (P.kind[i] === 1 && !showRapid) continue;
    const a = project(P.pos[3 * i - 3], P.pos[3 * i - 2], P.pos[3 * i - 1]), b = project(P.pos[3 * i], P.pos[3 * i + 1], P.pos[3 * i + 2]);
    const t = clipT(a, b, W, H);
    if (!t || t[1] >= 1) continue;
    const x = a[0] + t[1] * (b[0] - a[0]), y = a[1] + t[1] * (b[1] - a[1]);
    const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
    if (!(len > 0)) continue;
    const ux = (b[0] - a[0]) / len, uy = (b[1] - a[1]) / len;
    const key = Math.floor(x / 8) + "," + Math.floor(y / 8) + "," + Math.round((Math.atan2(uy, ux) * 8) / Math.PI) + "," + P.kind[i];
    if (seen.has(key)) continue;
    seen.add(key);
    arrow(x, y, ux, uy, rgb(P.kind[i] === 1 ? pal().rapid : segColor(i)));
  }
  exitsDrawn = seen.size;
}
// Liang–Barsky against the view [0, W] × [0, H]: the part of a→b inside.
function clipT(a, b, W, H) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  let t0 = 0, t1 = 1;
  for (const [p, q] of [[-dx, a[0]], [dx, W - a[0]], [-dy, a[1]], [dy, H - a[1]]]) {
    if (p === 0) { if (q < 0) return null; } else { const r = q / p; if (p < 0) t0 = Math.max(t0, r); else t1 = Math.min(t1, r); }
  }
  return t0 <= t1 ? [t0, t1] : null;
}
let exitsDrawn = 0;
// A lathe's chuck side: a hatched jaw at the −Z end of the cuts, from the
// spindle axis up to the largest radius cut.
function drawChuck() {
  if (!D.lathe || !D.cuts) return;
  const [lo, hi] = D.cuts, x0 = -D.center[0], z = lo[2];
  const a = project(x0, 0, z), b = project(Math.max(hi[0], x0 + 1e-3), 0, z);
  const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
  if (!(len > 4)) return;
  const ux = (b[0] - a[0]) / len, uy = (b[1] - a[1]) / len;
  // Towards −Z on the screen, away from the part.
  const zq = project(x0, 0, z - 1), zl = Math.hypot(zq[0] - a[0], zq[1] - a[1]) || 1;
  const nx = (zq[0] - a[0]) / zl, ny = (zq[1] - a[1]) / zl;
  const off = 6, w = 10;
  ctx2d.strokeStyle = ctx2d.fillStyle = rgb(pal().muted);
  ctx2d.lineWidth = 1;
  ctx2d.beginPath();
  ctx2d.moveTo(a[0] + nx * off, a[1] + ny * off); ctx2d.lineTo(b[0] + nx * off, b[1] + ny * off);
  for (let d = 0; d + 8 <= len; d += 6) {
    const x = a[0] + ux * d + nx * off, y = a[1] + uy * d + ny * off;
    ctx2d.moveTo(x, y); ctx2d.lineTo(x + nx * w + ux * 8, y + ny * w + uy * 8);
  }
  ctx2d.stroke();
  ctx2d.font = "11px system-ui, sans-serif";
  ctx2d.textAlign = "right";
  ctx2d.textBaseline = "bottom";
  ctx2d.fillText("chuck", b[0] + nx * off, b[1] + ny * off - 4);
}
// The alarm: a ⊗ where the tool stopped, with its code and line.
function drawAlarm() {
  if (!D.alarm) return;
  const [x, y] = project(...D.alarm.at);
  ctx2d.strokeStyle = ctx2d.fillStyle = rgb(pal().alarm);
  ctx2d.lineWidth = 2;
  ctx2d.beginPath();
  ctx2d.arc(x, y, 10, 0, 2 * Math.PI);
  ctx2d.moveTo(x - 6, y - 6); ctx2d.lineTo(x + 6, y + 6);
  ctx2d.moveTo(x - 6, y + 6); ctx2d.lineTo(x + 6, y - 6);
  ctx2d.stroke();
  ctx2d.font = "bold 12px system-ui, sans-serif";
  const label = D.alarm.code + " line " + D.alarm.line, w = ctx2d.measureText(label).width;
  // Beside the mark, on the side where it fits in the view.
  const right = x + 14 + w < overlay.width / dpr();
  ctx2d.textAlign = right ? "left" : "right";
  ctx2d.textBaseline = "bottom";
  ctx2d.fillText(label, right ? x + 14 : x - 14, y - 8);
}
function drawOverlay() {
  const r = dpr(), W = overlay.width / r, H = overlay.height / r;
  ctx2d.setTransform(r, 0, 0, r, 0, 0);
  ctx2d.clearRect(0, 0, W, H);
  drawExits(W, H);
  drawChuck();
  drawAlarm();
  drawTriad(W, H);
  drawScale(W, H);
  drawPicks();
}
