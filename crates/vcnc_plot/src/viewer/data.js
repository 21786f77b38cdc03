// vcnc plot viewer, part 1 of 4: the data and how figures are written.
// The four parts (data.js, gl.js, pick.js, ui.js) run as one async
// function in the page (viewer.html), sharing its scope; hand-written, no
// libraries, no network.
//
// The data (html.rs, encode.rs) is one JSON object whose tables are
// base64 of deflated columns of LEB128 varints; the browser inflates them
// with its own DecompressionStream. Positions are whole quanta (0.1 µm)
// relative to D.center: decoded once into a Float32Array relative to the
// centre (for WebGL) and a Float64Array of machine coordinates (for the
// readouts).
//
// Embedded (the web app, docs/web.md) the page starts with no data
// (`null`) and its parent posts the data of each new plot; everything
// below that depends on the data is (re)made by `decodeData` and the
// `derive*` functions of the other parts, so the page, its camera and its
// controls stay while the plot changes.
const $ = (id) => document.getElementById(id);
let D = JSON.parse($("vcnc-data").textContent);

function bytes(s) {
  const bin = atob(s || "");
  const n = bin.length;
  const u = new Uint8Array(n);
  for (let i = 0; i < n; i++) u[i] = bin.charCodeAt(i);
  return u;
}
async function inflate(u8) {
  if (typeof DecompressionStream === "undefined") throw new Error("this browser cannot inflate the page's data (DecompressionStream is missing)");
  const stream = new Blob([u8]).stream().pipeThrough(new DecompressionStream("deflate-raw"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// A table: its inflated bytes and where each column lies in them.
async function table(t) {
  if (!t) return null;
  const u8 = await inflate(bytes(t.z));
  const cols = {};
  let off = 0;
  for (const [name, len] of t.cols) { cols[name] = [off, off + len]; off += len; }
  return { n: t.n, u8, cols };
}
// Calls f(value) for each unsigned varint of a column (exact to 2^53).
function eachVarint(tb, name, f) {
  const span = tb.cols[name];
  if (!span) return false;
  const u8 = tb.u8;
  let i = span[0];
  const end = span[1];
  while (i < end) {
    let v = 0, m = 1, c;
    do { c = u8[i++]; v += (c & 127) * m; m *= 128; } while (c & 128 && i < end);
    f(v);
  }
  return true;
}
const unzig = (u) => (u % 2 === 0 ? u / 2 : -(u + 1) / 2);
function unsignedCol(tb, name, T) {
  const out = new T(tb.n);
  let k = 0;
  return eachVarint(tb, name, (v) => { if (k < tb.n) out[k++] = v; }) ? out : null;
}
// Running sums of a column of signed deltas, times `scale`.
function deltaCol(tb, name, scale, T) {
  const out = new T(tb.n);
  let k = 0, acc = 0;
  return eachVarint(tb, name, (v) => { acc += unzig(v); if (k < tb.n) out[k++] = acc * scale; }) ? out : null;
}
// Positions: relative to the centre (f32, for WebGL) and absolute (f64).
let Q = 1e-4, centerQ = [0, 0, 0];
function positions(tb) {
  const rel = new Float32Array(3 * tb.n), abs = new Float64Array(3 * tb.n);
  const acc = [0, 0, 0];
  let k = 0;
  eachVarint(tb, "pos", (v) => {
    const a = k % 3;
    acc[a] += unzig(v);
    if (k < 3 * tb.n) { rel[k] = acc[a] * Q; abs[k] = (centerQ[a] + acc[a]) * Q; }
    k++;
  });
  return { rel, abs };
}
async function path(t, attrs) {
  const tb = await table(t);
  if (!tb) return null;
  const p = positions(tb);
  // The kind column is one byte per vertex (0 jump, 1 rapid, 2 cut).
  const ks = tb.cols.kind;
  const out = { n: tb.n, pos: p.rel, abs: p.abs, kind: tb.u8.slice(ks[0], ks[1]) };
  if (attrs) {
    out.tool = unsignedCol(tb, "tool", Uint16Array);
    out.line = deltaCol(tb, "line", 1, Uint32Array);
    out.file = unsignedCol(tb, "file", Uint16Array);
    out.time = deltaCol(tb, "time", 1e-4, Float64Array);
    out.feed = deltaCol(tb, "feed", 1e-3, Float32Array);
  }
  return out;
}
let P = null, C = null, K = null, H = null, TC = null, holes = new Float32Array(0);
let toolChanges = [], meshes = [], frames = [];
// Meshes posted apart from the data ({vcnc: "meshes"}: the web app's
// simulated stock and part), each with positions relative to its own
// centre; placed relative to D.center by `placeMeshes`.
let extraMeshes = [];
// Which meshes show, by name, as the user left the toggles.
const meshShown = new Map();
async function decodeMeshes(list, center) {
  const out = [];
  for (const m of list || []) {
    const tb = await table(m.table);
    const tri = unsignedCol({ n: 3 * m.tris, u8: tb.u8, cols: tb.cols }, "tri", Uint32Array);
    out.push({ name: m.name, color: m.color, visible: m.visible, rel: positions(tb).rel, center, tri, n: tb.n });
  }
  return out;
}
// Every mesh relative to D.center (f32), with the visibility the user chose.
function placeMeshes() {
  meshes = [...D.meshesDecoded, ...extraMeshes].map((m) => {
    const d = m.center.map((c, k) => c - D.center[k]);
    const pos = new Float32Array(m.rel.length);
    for (let i = 0; i < pos.length; i += 3) { pos[i] = m.rel[i] + d[0]; pos[i + 1] = m.rel[i + 1] + d[1]; pos[i + 2] = m.rel[i + 2] + d[2]; }
    const visible = meshShown.has(m.name) ? meshShown.get(m.name) : m.visible;
    return { name: m.name, color: m.color, visible, pos, tri: m.tri, n: m.n };
  });
}
async function decodeData() {
  Q = D.quantum;
  centerQ = D.center.map((c) => Math.round(c / Q));
  [P, C, K, H, TC] = await Promise.all([
    path(D.path, true), path(D.contour, false), path(D.compare, false), table(D.holes), table(D.toolChanges),
  ]);
  // Times travel as f32 seconds: the last vertex may round a hair past the
  // total, which must still reach it.
  if (P.time && P.n) D.totalTime = Math.max(D.totalTime, P.time[P.n - 1]);
  holes = H ? positions(H).rel : new Float32Array(0);
  toolChanges = [];
  if (TC) {
    const at = positions(TC).rel, tool = unsignedCol(TC, "tool", Float64Array), line = deltaCol(TC, "line", 1, Float64Array);
    for (let i = 0; i < TC.n; i++) toolChanges.push([at[3 * i], at[3 * i + 1], at[3 * i + 2], tool[i], line[i]]);
  }
  D.meshesDecoded = await decodeMeshes(D.meshes, D.center);
  placeMeshes();
  deriveFrames();
}

// ---- figures as people read them ------------------------------------------
// One time format everywhere (vcnc_core::display::duration): 41.7s,
// 1m 02.3s, 1h 00m 00.0s, rounded to the tenth before it is split.
function fmtTime(s) {
  const total = Math.round(Math.max(0, s) * 10) / 10;
  const h = Math.floor(total / 3600), m = Math.floor((total - h * 3600) / 60);
  const sec = total - h * 3600 - m * 60;
  const ss = sec.toFixed(1);
  if (h > 0) return h + "h " + String(m).padStart(2, "0") + "m " + ss.padStart(4, "0") + "s";
  if (m > 0) return m + "m " + ss.padStart(4, "0") + "s";
  return ss + "s";
}
// Lengths in the page's unit (--units; vcnc_core::display::DisplayUnits).
let UNIT = { name: "mm", per: 1, dec: 3 };
function deriveUnits() { UNIT = D.units === "in" ? { name: "in", per: 1 / 25.4, dec: 4 } : { name: "mm", per: 1, dec: 3 }; }
const fmtLen = (mm) => (mm * UNIT.per).toFixed(UNIT.dec);
const fmtFeed = (mmMin) => (mmMin * UNIT.per).toFixed(UNIT.name === "in" ? 1 : 0) + " " + UNIT.name + "/min";
const AXES = ["X", "Y", "Z"];
// A point in machine (or work) coordinates; a lathe's X is a diameter.
function fmtPoint(p) {
  const parts = [];
  for (let k = 0; k < 3; k++) {
    if (D.lathe && k === 1) continue;
    parts.push(D.lathe && k === 0 ? "X⌀" + fmtLen(2 * p[0]) : AXES[k] + " " + fmtLen(p[k]));
  }
  return parts.join(" ");
}
function toolName(t) {
  if (!t) return "no tool";
  const s = D.toolShapes[t - 1];
  return "T" + D.tools[t - 1] + (s ? " ⌀" + fmtLen(s.d) + " " + s.kind : "");
}

// ---- work coordinates ------------------------------------------------------
// machine = linear · work + origin + tool_offset (docs/events.md), so
// work = linear⁻¹ · (machine − origin − tool_offset).
function inverse3(m) {
  const [a, b, c] = m, det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  if (!isFinite(det) || Math.abs(det) < 1e-12) return null;
  const r = (i, j) => {
    const m2 = m.filter((_, k) => k !== j).map((row) => row.filter((_, k) => k !== i));
    return ((i + j) % 2 ? -1 : 1) * (m2[0][0] * m2[1][1] - m2[0][1] * m2[1][0]) / det;
  };
  return [0, 1, 2].map((i) => [0, 1, 2].map((j) => r(i, j)));
}
function deriveFrames() {
  frames = D.frames.map(([o, lin, tlo]) => ({
    origin: o.map((v, k) => v + D.center[k]), inv: lin ? inverse3(lin) : null, singular: !!lin && !inverse3(lin), tlo,
  }));
}
// The frame in force at vertex i (runs in vertex order).
function frameAt(i) {
  const runs = D.frameRuns;
  let lo = 0, hi = runs.length;
  while (lo < hi) { const m = (lo + hi) >> 1; if (runs[m][0] <= i) lo = m + 1; else hi = m; }
  return lo > 0 ? frames[runs[lo - 1][1]] : null;
}
// Work coordinates of machine point p at vertex i (null when unknown).
function workOf(p, i) {
  const f = frameAt(i);
  if (!f) return p.slice();
  if (f.singular) return null;
  const d = [0, 1, 2].map((k) => p[k] - f.origin[k] - f.tlo[k]);
  return f.inv ? [0, 1, 2].map((r) => f.inv[r][0] * d[0] + f.inv[r][1] * d[1] + f.inv[r][2] * d[2]) : d;
}
