// vcnc plot viewer, part 3 of 4: what is under the pointer. The path's
// screen positions are projected once per camera change (orthographic, so
// a point's parameter along a segment is the same on the screen as in the
// machine), and the nearest segment to the pointer is found by a linear
// scan with a box test first: a few milliseconds for 500,000 segments.
// Hovering shows the readout; a click selects the segment's program line;
// in measure mode two clicks pick points (snapped to a vertex within
// 10 px, else to the nearest point of a segment) and the distance between
// them is shown.

let screen = { serial: -1, w: 0, h: 0, xy: null };
function screenXY() {
  if (screen.serial === viewSerial && screen.w === canvas.width && screen.h === canvas.height) return screen.xy;
  const xy = new Float32Array(2 * P.n);
  const r = dpr(), w = canvas.width, h = canvas.height;
  const a = R[0].map((v) => (scale * v) / r), b = R[1].map((v) => (scale * v) / r);
  const x0 = (w / 2 + pan[0]) / r, y0 = (h / 2 - pan[1]) / r;
  for (let i = 0; i < P.n; i++) {
    const x = P.pos[3 * i], y = P.pos[3 * i + 1], z = P.pos[3 * i + 2];
    xy[2 * i] = x0 + a[0] * x + a[1] * y + a[2] * z;
    xy[2 * i + 1] = y0 - (b[0] * x + b[1] * y + b[2] * z);
  }
  screen = { serial: viewSerial, w, h, xy };
  return xy;
}
// The drawn segment nearest to (x, y) (CSS px of the view) within
// `maxPx`: its vertex index, the parameter along it and the distance.
function nearest(x, y, maxPx) {
  if (!P) return null;
  const xy = screenXY();
  let best = -1, bd = maxPx * maxPx, bt = 0;
  for (let i = 1; i < P.n; i++) {
    const k = P.kind[i];
    if (k === 0 || (k === 1 && !showRapid)) continue;
    const ax = xy[2 * i - 2], ay = xy[2 * i - 1], bx = xy[2 * i], by = xy[2 * i + 1];
    if ((ax < x - maxPx && bx < x - maxPx) || (ax > x + maxPx && bx > x + maxPx) ||
      (ay < y - maxPx && by < y - maxPx) || (ay > y + maxPx && by > y + maxPx)) continue;
    const dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    const t = len2 > 0 ? Math.min(1, Math.max(0, ((x - ax) * dx + (y - ay) * dy) / len2)) : 1;
    const ex = ax + t * dx - x, ey = ay + t * dy - y, d2 = ex * ex + ey * ey;
    if (d2 <= bd) { best = i; bd = d2; bt = t; }
  }
  return best < 0 ? null : { i: best, t: bt, d: Math.sqrt(bd) };
}
const lerp = (a, b, t) => a + t * (b - a);
// Machine coordinates at parameter t of the segment that ends at vertex i.
function pointAt(i, t) {
  return [0, 1, 2].map((k) => lerp(P.abs[3 * (i - 1) + k], P.abs[3 * i + k], t));
}
function timeAt(i, t) { return P.time ? lerp(P.time[i - 1], P.time[i], t) : 0; }

// ---- hover readout -------------------------------------------------------
const tip = $("tip");
function readout(hit) {
  const i = hit.i, f = P.file ? P.file[i] : 0, line = P.line[i];
  const m = pointAt(i, hit.t), w = workOf(m, i);
  const s = source(f);
  let head = "line " + line + (f ? " of " + D.files[f] : "");
  if (s && line > 0 && line <= s.starts.length) {
    const t = lineText(s, line - 1).trim();
    head += ": " + (t.length > 48 ? t.slice(0, 47) + "…" : t);
  }
  const move = P.kind[i] === 1 ? "rapid" : "F " + fmtFeed(P.feed[i]);
  return [
    head,
    "work     " + (w ? fmtPoint(w) : "(frame not kept)") + (D.framesComplete ? "" : " ?"),
    "machine  " + fmtPoint(m),
    move + " · " + toolName(P.tool[i]) + " · " + fmtTime(timeAt(i, hit.t)) + " of " + fmtTime(D.totalTime),
  ].join("\n");
}
let hoverAt = null, hovered = null, hoverQueued = false;
function hover() {
  hoverQueued = false;
  if (!hoverAt || measuring) { tip.hidden = true; hovered = null; drawOverlay(); return; }
  const [x, y] = hoverAt;
  hovered = nearest(x, y, 10);
  if (!hovered) { tip.hidden = true; drawOverlay(); return; }
  tip.textContent = readout(hovered);
  tip.hidden = false;
  const view = $("view"), W = view.clientWidth, H = view.clientHeight;
  const tw = tip.offsetWidth, th = tip.offsetHeight;
  tip.style.left = Math.max(4, Math.min(W - tw - 4, x + 16)) + "px";
  tip.style.top = Math.max(4, Math.min(H - th - 4, y + 16)) + "px";
  drawOverlay();
}
function queueHover(x, y) {
  hoverAt = x === null ? null : [x, y];
  if (!hoverQueued) { hoverQueued = true; requestAnimationFrame(hover); }
}

// ---- measure -------------------------------------------------------------
let measuring = false, picks = [];
// A picked point: a vertex within 10 px, else the nearest point of a
// segment within 10 px; null elsewhere (a click in empty space has no
// depth to measure from).
function snap(x, y) {
  const hit = nearest(x, y, 10);
  if (!hit) return null;
  const xy = screenXY(), i = hit.i;
  for (const j of [i - 1, i]) {
    if (Math.hypot(xy[2 * j] - x, xy[2 * j + 1] - y) <= 10) return { p: [P.abs[3 * j], P.abs[3 * j + 1], P.abs[3 * j + 2]], i: Math.max(j, 1) };
  }
  return { p: pointAt(i, hit.t), i };
}
function measureText() {
  if (picks.length < 2) return picks.length ? "measure: pick the second point" : "measure: pick a point of the path";
  const [a, b] = picks.map((q) => q.p), d = [0, 1, 2].map((k) => b[k] - a[k]);
  const dist = Math.hypot(d[0], d[1], d[2]);
  const parts = D.lathe ? ["ΔX⌀ " + fmtLen(2 * d[0]), "ΔZ " + fmtLen(d[2])] : [0, 1, 2].map((k) => "Δ" + AXES[k] + " " + fmtLen(d[k]));
  return "distance " + fmtLen(dist) + " " + UNIT.name + "\n" + parts.join("  ") + "\nfrom " + fmtPoint(a) + "\nto   " + fmtPoint(b);
}
function pick(x, y) {
  const q = snap(x, y);
  if (!q) return;
  if (picks.length >= 2) picks = [];
  picks.push(q);
  $("measureOut").textContent = measureText();
  drawOverlay();
}
function setMeasuring(on) {
  measuring = on;
  picks = [];
  $("measure").classList.toggle("on", on);
  $("view").classList.toggle("measuring", on);
  $("measureOut").hidden = !on;
  $("measureOut").textContent = measureText();
  tip.hidden = true;
  drawOverlay();
}
function drawPicks() {
  const rel = (p) => project(p[0] - D.center[0], p[1] - D.center[1], p[2] - D.center[2]);
  if (hovered && !measuring) {
    const m = rel(pointAt(hovered.i, hovered.t));
    ctx2d.strokeStyle = rgb(pal().text);
    ctx2d.lineWidth = 1.5;
    ctx2d.beginPath(); ctx2d.arc(m[0], m[1], 5, 0, 2 * Math.PI); ctx2d.stroke();
  }
  if (!measuring || !picks.length) return;
  const pts = picks.map((q) => rel(q.p));
  ctx2d.strokeStyle = ctx2d.fillStyle = "rgb(230,0,200)";
  ctx2d.lineWidth = 1.5;
  if (pts.length === 2) { ctx2d.beginPath(); ctx2d.moveTo(...pts[0]); ctx2d.lineTo(...pts[1]); ctx2d.stroke(); }
  for (const p of pts) { ctx2d.beginPath(); ctx2d.arc(p[0], p[1], 4, 0, 2 * Math.PI); ctx2d.fill(); }
}

// ---- moves that leave the frame ------------------------------------------
// Segments with one end in the frame of the cuts and the other outside
// (at most 4096, rapids first): where the view cuts them, an arrowhead.
let exitSegs = [];
function deriveExits() {
  const out = [], [lo, hi] = fitBox("cuts"), pad = 0.02 * D.size;
  const inside = (i) => [0, 1, 2].every((k) => P.pos[3 * i + k] >= lo[k] - pad && P.pos[3 * i + k] <= hi[k] + pad);
  for (const want of [1, 2]) {
    for (let i = 1; i < P.n && out.length < 4096; i++) {
      if (P.kind[i] === want && inside(i - 1) !== inside(i)) out.push(i);
    }
  }
  exitSegs = out;
}
