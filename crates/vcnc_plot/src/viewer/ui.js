// vcnc plot viewer, part 4 of 4: the program text (drawn only where it is
// visible, searchable), the legend, playback on the planned time, the
// controls, and the start. Selecting a line (a click in the text, or on a
// segment in the view) lights its segments; the playback position lights
// its line.

// ---- program text --------------------------------------------------------
const LH = 16;
const pane = $("source"), lines = $("lines");
async function decodeSource(i) {
  const el = $("vcnc-src-" + i);
  if (!el) return null;
  let raw = bytes(el.textContent.trim());
  if (el.dataset.z === "1") raw = await inflate(raw);
  return textSource(new TextDecoder("utf-8").decode(raw));
}
// A program text; where its lines start is found when first needed (a
// hidden text pane never needs it until the readout shows a line).
function textSource(text) {
  let starts = null;
  return {
    text,
    lower: null,
    get starts() {
      if (!starts) {
        starts = [0];
        for (let k = text.indexOf("\n"); k !== -1; k = text.indexOf("\n", k + 1)) starts.push(k + 1);
        if (starts.length > 1 && starts[starts.length - 1] === text.length) starts.pop();
      }
      return starts;
    },
  };
}
let sources = [];
const source = (i) => sources[i] || null;
function lineText(s, i) {
  const a = s.starts[i], b = i + 1 < s.starts.length ? s.starts[i + 1] : s.text.length;
  return s.text.slice(a, b).replace(/\r?\n$/, "");
}
let curFile = -1, curLine = 0;
function renderLines() {
  const s = source(curFile);
  // Hidden (embedded: the parent shows the text), nothing to draw.
  if (!s || !pane.clientHeight) { lines.textContent = ""; return; }
  const height = s.starts.length * LH + "px";
  if (lines.style.height !== height) lines.style.height = height;
  const first = Math.max(0, Math.floor(pane.scrollTop / LH) - 5);
  const last = Math.min(s.starts.length, first + Math.ceil(pane.clientHeight / LH) + 10);
  const frag = document.createDocumentFragment();
  const selLine = sel && sel.file === curFile ? sel.line : 0;
  const found = findState.file === curFile ? findState.line : 0;
  for (let i = first; i < last; i++) {
    const d = document.createElement("div");
    d.className = "ln" + (i + 1 === curLine ? " cur" : "") + (i + 1 === selLine ? " sel" : "") + (i + 1 === found ? " found" : "");
    d.style.top = i * LH + "px";
    d.dataset.line = String(i + 1);
    const b = document.createElement("b");
    b.textContent = String(i + 1);
    d.appendChild(b);
    d.appendChild(document.createTextNode(lineText(s, i)));
    frag.appendChild(d);
  }
  lines.replaceChildren(frag);
}
function showFile(i) {
  if (i === curFile) return;
  curFile = i;
  if (!source(i)) lines.style.height = "0px";
  $("srcname").textContent = D.files[i] !== undefined ? D.files[i] : "(program text not included)";
}
function scrollTo(line) {
  const top = (line - 1) * LH;
  if (line > 0 && (top < pane.scrollTop + 2 * LH || top > pane.scrollTop + pane.clientHeight - 3 * LH)) {
    pane.scrollTop = Math.max(0, top - pane.clientHeight / 2);
  }
}
// The playback position's line.
function highlight(file, line) {
  showFile(file);
  curLine = line;
  scrollTo(line);
  renderLines();
}
// A selected line: lit in the text and its segments lit in the view.
// Embedded in the web app (docs/web.md), the page tells the app which
// line a click selected, and the app selects lines from its editor
// (`quiet`: the app asked, so it is not told back).
const embedded = window.parent !== window;
function selectLine(file, line, quiet) {
  showFile(file);
  setSelection(line > 0 ? { file, line } : null);
  scrollTo(line);
  renderLines();
  if (embedded && !quiet) window.parent.postMessage({ vcnc: "selected", file, line }, "*");
}
if (embedded) {
  window.addEventListener("message", (e) => {
    const m = e.data;
    if (e.source !== window.parent || !m || m.vcnc !== "select") return;
    // Before the first plot: kept for it.
    if (!loaded) sel = m.line > 0 ? { file: m.file | 0, line: m.line | 0 } : null;
    else selectLine(m.file | 0, m.line | 0, true);
  });
}
pane.addEventListener("scroll", () => requestAnimationFrame(renderLines));
lines.addEventListener("click", (e) => {
  const d = e.target.closest(".ln");
  if (d) selectLine(curFile, Number(d.dataset.line));
});
// A double click runs the program to the line's first block.
lines.addEventListener("dblclick", (e) => {
  const d = e.target.closest(".ln");
  if (!d) return;
  const want = Number(d.dataset.line);
  for (let i = 0; i < P.n; i++) {
    if (P.line[i] === want && (P.file ? P.file[i] : 0) === curFile) { setIndex(i); return; }
  }
});

// ---- search --------------------------------------------------------------
const findState = { query: "", file: -1, hits: [], at: -1, line: 0 };
function findAll() {
  const q = $("findText").value.toLowerCase(), s = source(curFile);
  findState.query = q; findState.file = curFile; findState.hits = []; findState.at = -1; findState.line = 0;
  if (!q || !s) return;
  if (!s.lower) s.lower = s.text.toLowerCase();
  let lastLine = -1;
  for (let k = s.lower.indexOf(q); k !== -1 && findState.hits.length < 100000; k = s.lower.indexOf(q, k + q.length)) {
    let lo = 0, hi = s.starts.length;
    while (lo < hi) { const m = (lo + hi) >> 1; if (s.starts[m] <= k) lo = m + 1; else hi = m; }
    if (lo !== lastLine) { findState.hits.push(lo); lastLine = lo; }
  }
}
function findStep(dir) {
  if (findState.query !== $("findText").value.toLowerCase() || findState.file !== curFile) findAll();
  const n = findState.hits.length;
  if (!n) { $("findCount").textContent = findState.query ? "0/0" : ""; renderLines(); return; }
  const from = sel && sel.file === curFile ? sel.line : curLine;
  let at;
  if (findState.at < 0) {
    at = findState.hits.findIndex((l) => (dir > 0 ? l > from : l >= from));
    if (at < 0) at = dir > 0 ? 0 : n - 1;
    if (dir < 0) at = (at - 1 + n) % n;
  } else {
    at = (findState.at + dir + n) % n;
  }
  findState.at = at;
  findState.line = findState.hits[at];
  $("findCount").textContent = at + 1 + "/" + n + (n >= 100000 ? "+" : "");
  selectLine(curFile, findState.line);
}
$("findText").addEventListener("keydown", (e) => { if (e.key === "Enter") { e.preventDefault(); findStep(e.shiftKey ? -1 : 1); } });
$("findText").addEventListener("input", () => { findAll(); $("findCount").textContent = findState.query ? "0/" + findState.hits.length : ""; renderLines(); });
$("findNext").addEventListener("click", () => findStep(1));
$("findPrev").addEventListener("click", () => findStep(-1));

// ---- legend --------------------------------------------------------------
function esc(s) { const d = document.createElement("div"); d.textContent = s; return d.innerHTML; }
function sw(c) { return '<span class="sw" style="background:rgb(' + c.join(",") + ')"></span>'; }
function legend() {
  if (!P) return;
  const p = pal();
  let h = "";
  const frameNote = D.cuts ? "the view fits the cuts (Fit: " + fitTo + ")" : "no cuts: the view fits all moves";
  h += '<div class="muted">' + esc(frameNote) + "</div>";
  h += "<div>" + (showRapid ? sw(p.rapid) + "rapid (dashed)" : '<span class="muted">rapids hidden</span>') + "</div>";
  if (colorBy === "tool") {
    const used = new Set();
    for (let i = 1; i < P.n; i++) if (P.kind[i] === 2) used.add(P.tool[i]);
    [...used].sort((a, b) => a - b).slice(0, 16).forEach((t) => { h += "<div>" + sw(toolColor(t)) + esc(toolName(t)) + "</div>"; });
  } else if (colorBy === "depth") {
    const v = (r) => (D.lathe ? "X⌀ " + fmtLen(2 * (r + D.center[0])) : "Z " + fmtLen(r + D.center[2])) + " " + UNIT.name;
    h += "<div>" + sw(ramp(p.depth, 0, 32)) + v(depthRange[0]) + " (deep)</div>";
    h += "<div>" + sw(ramp(p.depth, 1, 32)) + v(depthRange[1]) + " (high)</div>";
  } else {
    h += "<div>" + sw(ramp(p.feed, 0, 16)) + "F " + fmtFeed(feedRange[0]) + "</div><div>" + sw(ramp(p.feed, 1, 16)) + "F " + fmtFeed(feedRange[1]) + "</div>";
  }
  if (C) h += "<div>" + sw(p.contour) + "programmed contour</div>";
  if (K) h += "<div>" + sw(p.compare) + "compare: " + esc(D.compareName) + "</div>";
  if (D.holeCount) h += "<div>" + sw(p.hole) + "holes (" + D.holeCount + ")</div>";
  if (toolChanges.length) h += "<div>" + sw(p.toolChange) + "tool changes</div>";
  if (D.limits) h += "<div>" + sw(p.muted) + "travel limits</div>";
  if (exitSegs.length) h += "<div>" + sw(p.rapid) + "▶ a move leaves the view</div>";
  h += "<div>" + sw(p.start) + "start</div>";
  h += "<div>" + sw(SELECT) + "selected line</div><table>";
  for (const [k, v] of D.rows) h += "<tr><td>" + esc(k) + "</td><td>" + esc(v) + "</td></tr>";
  h += "</table>";
  if (D.moves === 0) h += '<div class="note">no motion: the program moves nothing</div>';
  else if (D.cutMoves === 0 && !D.rapids) h += '<div class="note">every move is a rapid: rapids are shown although hidden</div>';
  if (!D.framesComplete) h += '<div class="muted">work coordinates are known up to the 65,536th frame change</div>';
  if (D.alarm) h += '<div class="alarm">alarm ' + esc(D.alarm.code) + " line " + D.alarm.line + ": " + esc(D.alarm.message) + "</div>";
  $("legend").innerHTML = h;
}

// ---- playback on the planned time ----------------------------------------
// The slider is the program's planned time (10,000 steps); playing moves
// it at ×1, ×10 or ×100 the machine's speed, so ×10 takes a tenth of the
// planned time. Without times (none known) it steps through the vertices.
const scrub = $("scrub"), speedSel = $("speed");
let timed = false;
const STEPS = 10000;
let curT = 0;
// The last vertex reached at time t.
function indexAtTime(t) {
  if (t <= 0) return 0;
  let lo = 0, hi = P.n;
  while (lo < hi) { const m = (lo + hi) >> 1; if (P.time[m] <= t) lo = m + 1; else hi = m; }
  return Math.max(0, lo - 1);
}
// Where the tool is: on the way from the last vertex reached to the next.
function herePoint() {
  const i = cur, j = Math.min(P.n - 1, i + 1);
  let f = 0;
  if (timed && j > i && P.kind[j] !== 0 && P.time[j] > P.time[i]) f = Math.min(1, Math.max(0, (curT - P.time[i]) / (P.time[j] - P.time[i])));
  return [0, 1, 2].map((k) => lerp(P.pos[3 * i + k], P.pos[3 * j + k], f));
}
function update() {
  // The block running: the one whose move is in progress, else the last.
  const run = timed && cur + 1 < P.n && curT > P.time[cur] ? cur + 1 : cur;
  const f = P.file ? P.file[run] : 0;
  // Line 0: the power-on position, before any block; nothing is lit.
  highlight(f, P.line[run]);
  const hp = herePoint(), m = hp.map((v, k) => v + D.center[k]);
  $("info").textContent = (P.line[run] ? "line " + P.line[run] + (f ? " of " + D.files[f] : "") : "power-on position") +
    " | " + toolName(P.tool[run]) + " | machine " + fmtPoint(m);
  $("clock").textContent = timed ? fmtTime(curT) + " / " + fmtTime(D.totalTime) + " " + D.timeLabel : "vertex " + cur + " / " + (P.n - 1);
  request();
}
function setTime(t) {
  curT = Math.max(0, Math.min(D.totalTime, t));
  cur = indexAtTime(curT);
  scrub.value = String(Math.round((STEPS * curT) / D.totalTime));
  update();
}
function setIndex(i) {
  cur = Math.max(0, Math.min(P.n - 1, i));
  if (timed) { curT = P.time[cur]; scrub.value = String(Math.round((STEPS * curT) / D.totalTime)); } else scrub.value = String(cur);
  update();
}
scrub.addEventListener("input", () => {
  stop();
  const v = Number(scrub.value);
  if (timed) setTime((v / STEPS) * D.totalTime); else setIndex(v);
});
// Arrow keys on the slider step block by block.
scrub.addEventListener("keydown", (e) => {
  if (e.key === "ArrowLeft" || e.key === "ArrowDown") { e.preventDefault(); stepBlock(-1); }
  if (e.key === "ArrowRight" || e.key === "ArrowUp") { e.preventDefault(); stepBlock(1); }
});
let playing = false, playStart = 0, playFrom = 0;
const playStats = { started: 0, ended: 0, from: 0, to: 0, speed: 0 };
function stop() {
  if (!playing) return;
  playing = false;
  $("play").textContent = "play";
}
function frame(now) {
  if (!playing) return;
  const speed = Number(speedSel.value);
  const t = playFrom + ((now - playStart) / 1000) * speed;
  if (!timed) {
    setIndex(cur + Math.max(1, Math.round(P.n / 600)));
    if (cur >= P.n - 1) { stop(); playStats.ended = now; }
  } else if (t >= D.totalTime) {
    setTime(D.totalTime);
    stop();
    playStats.ended = now;
    playStats.to = D.totalTime;
    return;
  } else {
    setTime(t);
  }
  if (playing) requestAnimationFrame(frame);
}
function play() {
  if (!loaded) return;
  if (playing) { stop(); return; }
  if (timed ? curT >= D.totalTime : cur >= P.n - 1) setIndex(0);
  playing = true;
  $("play").textContent = "pause";
  playFrom = timed ? curT : 0;
  playStart = performance.now();
  Object.assign(playStats, { started: playStart, ended: 0, from: playFrom, to: 0, speed: Number(speedSel.value) });
  requestAnimationFrame(frame);
}
speedSel.addEventListener("change", () => { if (playing) { playFrom = curT; playStart = performance.now(); playStats.speed = Number(speedSel.value); } });
$("play").addEventListener("click", play);
const same = (i, j) => P.line[i] === P.line[j] && (P.file ? P.file[i] === P.file[j] : true);
function stepBlock(dir) {
  stop();
  let i = cur + dir;
  while (i > 0 && i < P.n - 1 && same(i, cur)) i += dir;
  setIndex(i);
}
function stepTool(dir) {
  stop();
  let i = cur;
  if (dir > 0) {
    while (i < P.n - 1 && P.tool[i] === P.tool[cur]) i++;
  } else {
    // Back to the start of this tool's run; from there, of the one before.
    if (i > 0 && P.tool[i - 1] !== P.tool[i]) i--;
    const t = P.tool[i];
    while (i > 0 && P.tool[i - 1] === t) i--;
  }
  setIndex(i);
}
$("prevBlock").addEventListener("click", () => stepBlock(-1));
$("nextBlock").addEventListener("click", () => stepBlock(1));
$("prevTool").addEventListener("click", () => stepTool(-1));
$("nextTool").addEventListener("click", () => stepTool(1));

// ---- controls ------------------------------------------------------------
for (const b of document.querySelectorAll("[data-view]")) {
  b.addEventListener("click", () => { R = VIEWS[b.dataset.view].map((r) => r.slice()); fit(); });
}
$("fit").addEventListener("click", fit);
const fitSel = $("fitTo");
fitSel.addEventListener("change", () => { fitTo = fitSel.value; fit(); legend(); });
const colorSel = $("color");
colorSel.addEventListener("change", () => { colorBy = colorSel.value; colorChosen = true; build(); legend(); request(); });
const rapidBox = $("showRapid");
rapidBox.addEventListener("change", (e) => { showRapid = e.target.checked; build(); if (sel) setSelection(sel); legend(); viewChanged(); });
$("showGrid").addEventListener("change", (e) => { showGrid = e.target.checked; request(); });
$("showCompare").addEventListener("change", (e) => { showCompare = e.target.checked; request(); });
// One toggle a mesh; what the user chose stays for the next plot's mesh
// of the same name.
function meshControls() {
  const box = $("meshToggles");
  box.replaceChildren();
  meshes.forEach((m) => {
    const l = document.createElement("label"), c = document.createElement("input");
    c.type = "checkbox"; c.checked = m.visible; c.dataset.mesh = m.name;
    c.addEventListener("change", () => { m.visible = c.checked; meshShown.set(m.name, c.checked); request(); });
    l.append(c, " " + m.name);
    box.append(l, " ");
  });
}
// The controls that follow the plot.
function plotControls() {
  $("views").hidden = !!D.lathe;
  $("latheViews").hidden = !D.lathe;
  fitSel.value = fitTo;
  fitSel.disabled = !D.cuts;
  colorSel.value = colorBy;
  if (D.cutMoves === 0) showRapid = true;
  rapidBox.checked = showRapid;
  rapidBox.disabled = D.cutMoves === 0;
  $("cmpLabel").hidden = !K;
  meshControls();
}
$("measure").addEventListener("click", () => setMeasuring(!measuring));
$("theme").addEventListener("click", () => {
  theme = theme === "dark" ? "light" : "dark";
  document.body.className = theme;
  gridCache.key = "";
  build(); if (sel) setSelection(sel); legend(); request();
});
document.addEventListener("keydown", (e) => {
  if (e.target.closest && e.target.closest("input, select, textarea")) return;
  if (e.key === " ") { e.preventDefault(); play(); }
  if (e.key === "Escape") { setMeasuring(false); setSelection(null); renderLines(); }
});
// Drag to turn (a lathe's section pans instead), right-drag or shift-drag
// to pan, wheel to zoom; a click without a drag picks.
let drag = null;
canvas.addEventListener("pointerdown", (e) => {
  drag = { x: e.clientX, y: e.clientY, x0: e.clientX, y0: e.clientY, pan: e.button === 2 || e.shiftKey || D.lathe, moved: false };
  canvas.setPointerCapture(e.pointerId);
  canvas.style.cursor = "grabbing";
});
canvas.addEventListener("pointermove", (e) => {
  const r = canvas.getBoundingClientRect();
  if (!drag) { queueHover(e.clientX - r.left, e.clientY - r.top); return; }
  const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
  drag.x = e.clientX; drag.y = e.clientY;
  if (!drag.moved && Math.hypot(e.clientX - drag.x0, e.clientY - drag.y0) < 4) return;
  drag.moved = true;
  tip.hidden = true;
  move();
  if (drag.pan) { pan = [pan[0] + dx * dpr(), pan[1] - dy * dpr()]; viewChanged(); } else turn(dx, dy);
});
canvas.addEventListener("pointerup", (e) => {
  const r = canvas.getBoundingClientRect(), clicked = drag && !drag.moved && e.button === 0;
  drag = null;
  canvas.style.cursor = "";
  if (!clicked) return;
  const x = e.clientX - r.left, y = e.clientY - r.top;
  if (measuring) { pick(x, y); return; }
  const hit = nearest(x, y, 8);
  if (hit) selectLine(P.file ? P.file[hit.i] : 0, P.line[hit.i]);
  else { setSelection(null); renderLines(); }
});
canvas.addEventListener("pointercancel", () => { drag = null; canvas.style.cursor = ""; });
canvas.addEventListener("pointerleave", () => queueHover(null));
canvas.addEventListener("contextmenu", (e) => e.preventDefault());
canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  const r = canvas.getBoundingClientRect();
  const sx = (e.clientX - r.left) * dpr() - canvas.width / 2, sy = canvas.height / 2 - (e.clientY - r.top) * dpr();
  const k = Math.exp(-e.deltaY * 0.0015);
  pan = [sx - (sx - pan[0]) * k, sy - (sy - pan[1]) * k];
  scale *= k;
  move();
  viewChanged();
}, { passive: false });
// A resize fits the view again, but an embedded one keeps its camera (the
// app's panels change its size as results come; the centre stays put).
window.addEventListener("resize", () => { if (!loaded) return; if (resize() && !embedded) fit(); viewChanged(); });

// ---- start, and each new plot ----------------------------------------------
// `frame`: fit the view to the plot (the first one always), else the
// camera stays where it is. Loads run one at a time; a plot that arrives
// while one loads waits, and only the latest is loaded.
let loaded = false, loadSerial = 0, plotSerial = 0;
async function load(data, texts, frame) {
  const first = !loaded, oldCenter = D && loaded ? D.center : null, wasLathe = loaded && !!D.lathe;
  stop();
  D = data;
  await decodeData();
  sources = texts ? texts.map((t) => (t === null ? null : textSource(t))) : await Promise.all(D.files.map((_, i) => decodeSource(i)));
  curFile = -1;
  findState.file = -1;
  deriveUnits();
  deriveViews();
  if (first) firstLook();
  else if (!colorChosen) colorBy = D.color;
  deriveRanges();
  buildMeshes();
  timed = !!P.time && D.totalTime > 0;
  scrub.max = String(timed ? STEPS : Math.max(0, P.n - 1));
  $("title").textContent = D.title;
  document.body.className = theme;
  gridCache.key = "";
  resize();
  // A lathe's section and a mill's views do not share a camera.
  if (first || frame || !oldCenter || wasLathe !== !!D.lathe) frameView(); else keepCamera(oldCenter);
  deriveExits();
  plotControls();
  build();
  if (sel) setSelection(sel.line > 0 ? sel : null);
  if (measuring) setMeasuring(true);
  legend();
  showFile(0);
  setIndex(P.n - 1);
  if (timed) setTime(D.totalTime);
  loaded = true;
  loadSerial++;
}
// Meshes posted apart (the web app's simulated part): placed and drawn.
async function loadMeshes(data) {
  const m = data ? JSON.parse(data) : null;
  extraMeshes = m ? await decodeMeshes(m.meshes, m.center) : [];
  if (!loaded) return;
  placeMeshes();
  buildMeshes();
  meshControls();
  legend();
  request();
}
let queue = Promise.resolve(), latest = 0;
function enqueue(f) {
  queue = queue.then(f).catch((e) => { $("nogl").hidden = false; $("nogl").textContent = "The viewer could not draw this plot: " + e.message; });
  return queue;
}
if (embedded) {
  window.addEventListener("message", (e) => {
    const m = e.data;
    if (e.source !== window.parent || !m) return;
    if (m.vcnc === "data") {
      const mine = ++latest;
      enqueue(async () => {
        if (mine !== latest) return;
        await load(JSON.parse(m.data), [m.text === undefined ? null : m.text], !!m.frame);
        plotSerial = m.serial | 0;
      });
    } else if (m.vcnc === "meshes") {
      enqueue(() => loadMeshes(m.data));
    }
  });
}
if (D) await load(D, null, true);
// For tests and benchmarks: state, and a synchronous frame timer.
window.vcnc = {
  stats,
  playStats,
  get totalTime() { return D ? D.totalTime : 0; },
  // Plots loaded so far (embedded: one per posted plot).
  loads: () => loadSerial,
  // Embedded: the serial the parent gave the plot shown.
  plotSerial: () => plotSerial,
  // The camera: rows of R, scale (device px per mm) and pan (device px).
  camera: () => ({ R: R.map((r) => r.slice()), scale, pan: pan.slice() }),
  setCamera(c) { R = c.R.map((r) => r.slice()); scale = c.scale; pan = c.pan.slice(); viewChanged(); },
  // Meshes drawn: name, visible, triangles.
  meshes: () => meshes.map((m) => ({ name: m.name, visible: m.visible, triangles: Math.floor(m.tri.length / 3) })),
  index: () => cur,
  count: () => P.n,
  currentLine: () => curLine,
  selected: () => (sel ? { file: sel.file, line: sel.line } : null),
  setIndex,
  setTime,
  time: () => curT,
  view: () => R.map((r) => r.slice()),
  play,
  playing: () => playing,
  exits: () => exitsDrawn,
  measure: () => (picks.length === 2 ? Math.hypot(...[0, 1, 2].map((k) => picks[1].p[k] - picks[0].p[k])) : null),
  // CSS pixels, from the view's top left, of a machine point.
  screenOf: (x, y, z) => project(x - D.center[0], y - D.center[1], z - D.center[2]),
  vertex: (i) => ({ at: [P.abs[3 * i], P.abs[3 * i + 1], P.abs[3 * i + 2]], line: P.line[i], kind: P.kind[i], time: P.time ? P.time[i] : 0 }),
  // The page's time format, to hold it to vcnc_core::display::duration.
  fmtTime,
  // The segment under a CSS point of the view (what hover and clicks use).
  nearestAt: (x, y) => nearest(x, y, 10),
  webgl: !!gl,
  software,
  // Mean ms of n synchronous frames; `whileMoving`: as drawn during a drag.
  bench(n, whileMoving) {
    const was = moving;
    moving = !!whileMoving;
    const t0 = performance.now();
    for (let k = 0; k < n; k++) { draw(); if (gl) gl.finish(); }
    moving = was;
    if (gl) gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
    return (performance.now() - t0) / n;
  },
};
