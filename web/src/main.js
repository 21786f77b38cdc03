// The vcnc page (docs/web.md): a CodeMirror 6 editor on the left; on the
// right the viewer of `vcnc plot` (crates/vcnc_plot, loaded once in an
// iframe and sent each new plot, so its camera stays) above the summary
// panel. The engine (crates/vcnc_web, wasm) runs in a worker:
//
//   edit ─▶ 30 ms quiet ─▶ worker busy? terminate it, start another
//        ─▶ check(text, settings) ─▶ diagnostics (lint), summary, dialect
//                                     and its evidence, the viewer's data
//        ─▶ (simulate) sim ─▶ removed volume, collisions, the finished
//                             part's mesh to the viewer
//
// A result is applied only when it answers the latest request. A worker
// that traps (a Rust panic) is replaced and the page says so. Nothing here
// makes a network request: the wasm, its glue and this script are inlined.
import { EditorState, Compartment, StateEffect } from "@codemirror/state";
import {
  EditorView, keymap, lineNumbers, highlightActiveLine, highlightActiveLineGutter,
  drawSelection, highlightSpecialChars,
} from "@codemirror/view";
import { defaultKeymap, history, historyKeymap } from "@codemirror/commands";
import { search, searchKeymap, highlightSelectionMatches } from "@codemirror/search";
import { syntaxHighlighting, indentOnInput } from "@codemirror/language";
import { setDiagnostics, lintGutter, lintKeymap } from "@codemirror/lint";
import { WASM, GLUE } from "vcnc-engine";
import WORKER from "./engine.wjs";
import { gcodeLanguage, gcodeHighlight } from "./gcode.js";

const $ = (id) => document.getElementById(id);
const QUIET_MS = 30;
// Programs longer than this do not travel in the address (it would be
// megabytes long); the link button says so.
const MAX_LINK_BYTES = 2 << 20;

function showError(text) {
  const b = $("banner");
  b.textContent = text;
  b.hidden = !text;
}
window.addEventListener("error", (e) => showError("error: " + e.message));
window.addEventListener("unhandledrejection", (e) => showError("error: " + (e.reason && e.reason.message || e.reason)));

// ---- the engine in a worker ------------------------------------------------
function base64Bytes(s) {
  const bin = atob(s);
  const u = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
  return u;
}
const workerUrl = URL.createObjectURL(new Blob([GLUE, "\n", WORKER], { type: "text/javascript" }));
const modulePromise = WebAssembly.compile(base64Bytes(WASM));

class Engine {
  constructor(onCrash) {
    this.onCrash = onCrash;
    this.nextId = 1;
    this.pending = new Map();
    this.restarts = 0;
    this.spawn();
  }
  spawn() {
    this.worker = new Worker(workerUrl, { name: "vcnc-engine" });
    this.ready = modulePromise.then((module) => new Promise((resolve, reject) => {
      this.worker.onmessage = (e) => {
        if (e.data.type === "ready") { this.worker.onmessage = (ev) => this.answer(ev.data); resolve(); } else reject(new Error(e.data.message));
      };
      this.worker.onerror = (e) => { e.preventDefault(); this.crashed(e.message || "the worker failed"); };
      this.worker.postMessage({ type: "init", module });
    }));
  }
  get busy() { return this.pending.size > 0; }
  answer(m) {
    const p = this.pending.get(m.id);
    if (m.type === "panic") { this.crashed(m.message); return; }
    if (!p) return;
    this.pending.delete(m.id);
    if (m.type === "result") p.resolve({ result: m.result, ms: m.ms }); else p.reject(new Error(m.message));
  }
  // Ends the run in flight: its requests are rejected as cancelled.
  cancel() {
    if (!this.busy) return;
    this.worker.terminate();
    for (const p of this.pending.values()) p.reject(Object.assign(new Error("cancelled"), { cancelled: true }));
    this.pending.clear();
    this.spawn();
  }
  crashed(message) {
    this.worker.terminate();
    for (const p of this.pending.values()) p.reject(Object.assign(new Error("the engine stopped: " + message), { crashed: true }));
    this.pending.clear();
    this.restarts++;
    this.spawn();
    this.onCrash(message);
  }
  async request(type, text, settings) {
    await this.ready;
    const id = this.nextId++;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject });
      this.worker.postMessage({ type, id, text, settings });
    });
  }
}
const engine = new Engine((message) => showError(
  "The engine stopped on this program (a bug in vcnc: " + message + "). It was restarted; edit the program to check it again."));

// ---- settings: dialect, machine, tools ---------------------------------------
const setup = { dialect: "auto", file_name: null, machine: null, machineName: null, tools: null, tools_name: null };
function settings() {
  return {
    dialect: setup.dialect, file_name: setup.file_name, machine: setup.machine,
    tools: setup.tools, tools_name: setup.tools_name,
  };
}
function showLoaded() {
  const parts = [];
  if (setup.machineName) parts.push("machine: " + setup.machineName);
  if (setup.tools_name) parts.push("tools: " + setup.tools_name);
  $("loaded").textContent = parts.join(", ");
}

// ---- the editor ----------------------------------------------------------------
const language = new Compartment();
const app = {
  gen: 0, applied: 0, result: null, checks: [], restarts: () => engine.restarts,
  selectedFromView: null,
  // A new program (opened, dropped, set): its first plot is framed; an
  // edit keeps the camera.
  frameNext: true,
  // The warm-up run's ms (or why it did not run); null until it ends.
  warmed: null,
};
const editor = new EditorView({
  parent: $("editor"),
  state: EditorState.create({
    doc: "",
    extensions: [
      lineNumbers(), highlightActiveLineGutter(), highlightSpecialChars(), history(), drawSelection(),
      indentOnInput(), highlightActiveLine(), highlightSelectionMatches(), search({ top: true }),
      lintGutter(), language.of(gcodeLanguage("fanuc")), syntaxHighlighting(gcodeHighlight),
      keymap.of([...defaultKeymap, ...historyKeymap, ...searchKeymap, ...lintKeymap]),
      EditorView.updateListener.of((u) => {
        if (u.docChanged) scheduleCheck();
        if (u.selectionSet || u.docChanged) cursorMoved();
      }),
    ],
  }),
});

let timer = 0, editedAt = 0;
function scheduleCheck() {
  editedAt = performance.now();
  clearTimeout(timer);
  // An edit makes the run in flight worthless: end it now.
  engine.cancel();
  timer = setTimeout(runCheck, QUIET_MS);
  app.gen++;
}
async function runCheck() {
  const gen = ++app.gen;
  const text = editor.state.doc.toString();
  const frame = app.frameNext;
  const started = performance.now();
  $("status").textContent = "checking…";
  let answer;
  try {
    answer = await engine.request("check", text, settings());
  } catch (e) {
    if (e.cancelled) return;
    if (gen === app.gen) $("status").textContent = e.message;
    if (!e.crashed && gen === app.gen) showError(e.message);
    return;
  }
  if (gen !== app.gen) return;
  app.frameNext = app.frameNext && !frame;
  apply(answer.result, text, frame);
  const now = performance.now();
  app.checks.push({
    lines: editor.state.doc.lines, engineMs: answer.ms, roundTripMs: now - started, sinceEditMs: editedAt ? now - editedAt : null,
    // The edit, in ms since the epoch (the viewer's frames say when they end in the same clock).
    editedAt: performance.timeOrigin + editedAt,
  });
  if (app.checks.length > 50) app.checks.shift();
  app.applied = gen;
  app.lastChecked = text;
  updateLink(text);
  if ($("simOn").checked) simulate(gen, text);
  else if (app.meshesShown) { postViewer({ vcnc: "meshes", data: null }); app.meshesShown = false; }
}

// Material removal after the check, when asked for (it costs more than a
// check: a survey pass for the automatic stock, then the cuts).
async function simulate(gen, text) {
  const row = $("simRow");
  if (row) row.textContent = "simulating…";
  let answer;
  try {
    answer = await engine.request("sim", text, Object.assign(settings(), { stock: $("stock").value }));
  } catch (e) {
    if (e.cancelled || gen !== app.gen) return;
    app.sim = { error: e.message };
    if ($("simRow")) $("simRow").textContent = e.message;
    return;
  }
  if (gen !== app.gen) return;
  const r = answer.result;
  app.sim = r;
  app.simmed = gen;
  // The stock and the finished part, drawn in the view.
  postViewer({ vcnc: "meshes", data: r.meshes || null });
  app.meshesShown = !!r.meshes;
  const pct = r.stock_mm3 > 0 ? (100 * r.removed_mm3 / r.stock_mm3).toFixed(1) : "0";
  let h = '<span id="removed" data-mm3="' + r.removed_mm3 + '">removed ' + r.removed_mm3.toFixed(3) + " mm³ of " + r.stock_mm3.toFixed(3) + " mm³ (" + pct + " %)</span>\n" +
    esc(r.stock) + "\n" + (r.collision_total ? '<span class="bad">' + r.collision_total + " collision(s)</span>" : "no collision");
  for (const c of r.collisions.slice(0, 20)) h += "\nline " + c.line + ": " + esc(c.kind) + ": " + esc(c.message);
  for (const n of r.notes) h += '\n<span class="warn">' + esc(n) + "</span>";
  if ($("simRow")) $("simRow").innerHTML = h;
}

// ---- results -------------------------------------------------------------------
function apply(r, text, frame) {
  app.result = r;
  showError("");
  const doc = editor.state.doc;
  const diags = [];
  for (const d of r.diagnostics) {
    if (d.file || d.line < 1 || d.line > doc.lines) {
      diags.push({ from: 0, to: 0, severity: d.severity, source: d.code, message: message(d) });
      continue;
    }
    const line = doc.line(d.line);
    const from = Math.min(line.from + d.from, line.to), to = Math.min(line.from + Math.max(d.to, d.from), line.to);
    diags.push({ from, to, severity: d.severity, source: d.code, message: message(d) });
  }
  editor.dispatch(setDiagnostics(editor.state, diags));
  const name = r.dialect.name;
  editor.dispatch({ effects: language.reconfigure(gcodeLanguage(name)) });
  $("evidence").textContent = setup.dialect === "auto"
    ? "auto: " + name + " — " + (r.dialect.evidence.join(", ") || "no evidence, the default") + " (" + r.dialect.confidence + ")"
    : name + " (chosen)";
  $("evidence").title = r.dialect.why;
  $("evidence").dataset.dialect = name;
  summary(r);
  showPlot(r.view, text, frame);
  const a = r.summary.alarms, w = r.summary.warnings;
  $("status").textContent = doc.lines + " lines, " + name + ": " + (a ? a + " alarm(s)" : "no alarm") + ", " + w + " warning(s); planned " + r.summary.planned;
}
function message(d) {
  let m = d.code + ": " + d.message;
  if (d.file) m = "in " + d.file + ", line " + d.line + ": " + m;
  if (d.help) m += "\nhelp: " + d.help;
  if (d.after_alarm) m += "\n(after an earlier alarm: the run went on with the state as it was before that block)";
  return m;
}
function esc(s) { const d = document.createElement("div"); d.textContent = s; return d.innerHTML; }
function summary(r) {
  const s = r.summary;
  const rows = [
    ["result", s.alarms ? '<span class="bad">' + esc(s.result) + "</span>" : esc(s.result)],
    ["planned time", '<span id="plannedTime" data-seconds="' + s.planned_s + '">' + esc(s.planned) + "</span> (distance/feed " + s.dist_feed_s.toFixed(1) + " s)"],
    ["distance", "rapid " + s.rapid_mm.toFixed(3) + " mm, cutting " + s.cut_mm.toFixed(3) + " mm"],
  ];
  if (s.extents) {
    const ax = Object.keys(s.extents.min);
    rows.push(["extents (machine mm)", ax.map((k) => k.toUpperCase() + " " + s.extents.min[k].toFixed(3) + " .. " + s.extents.max[k].toFixed(3)).join("\n")]);
  } else rows.push(["extents", "no motion"]);
  rows.push(["tools", s.tools.length ? s.tools.map((t) => "T" + t.number + (t.diameter_mm != null ? " ⌀" + t.diameter_mm.toFixed(3) : "")).join("  ") : "none"]);
  if (s.holes) rows.push(["holes", String(s.holes)]);
  rows.push(["diagnostics", '<span class="' + (s.alarms ? "bad" : "") + '">' + s.alarms + " alarm(s)</span>, <span class=\"" + (s.warnings ? "warn" : "") + '">' + s.warnings + " warning(s)</span>"]);
  rows.push(["machine", esc(s.machine)]);
  rows.push(["material removal", $("simOn").checked ? '<span id="simRow">simulating…</span>' : "off (tick simulate)"]);
  $("summary").innerHTML = "<table>" + rows.map(([k, v]) => "<tr><td>" + esc(k) + "</td><td>" + v + "</td></tr>").join("") + "</table>";
}

// ---- the viewer, linked with the editor ------------------------------------------
// The viewer page (vcnc_plot::write_viewer, without its text pane: the
// editor is the text) is loaded once; each plot is posted to it as data
// with the text (for its readout), and it keeps its camera unless the
// plot is a new program's. A plot that comes while the viewer loads waits
// for it; only the latest is kept.
let viewerLoaded = false, viewerWaiting = [];
function postViewer(m) {
  if (!viewerLoaded) {
    if (m.vcnc === "data") viewerWaiting = viewerWaiting.filter((w) => w.vcnc !== "data");
    if (m.vcnc === "meshes") viewerWaiting = viewerWaiting.filter((w) => w.vcnc !== "meshes");
    viewerWaiting.push(m);
    return;
  }
  $("viewer").contentWindow.postMessage(m, "*");
}
function showPlot(data, text, frame) {
  if (!data) return;
  app.plotSerial = (app.plotSerial || 0) + 1;
  postViewer({ vcnc: "data", data, text, frame: frame || app.plotSerial === 1, serial: app.plotSerial });
}
// Asked for before the first check (an edit cancels what the worker runs).
async function loadViewer() {
  const { result } = await engine.request("viewer", "", null);
  $("viewer").addEventListener("load", () => {
    viewerLoaded = true;
    const w = $("viewer").contentWindow;
    if (lastCursorLine) w.postMessage({ vcnc: "select", file: 0, line: lastCursorLine }, "*");
    for (const m of viewerWaiting) w.postMessage(m, "*");
    viewerWaiting = [];
  }, { once: true });
  $("viewer").srcdoc = result;
}
// A click on a path segment selects its line in the editor.
window.addEventListener("message", (e) => {
  const m = e.data;
  if (!m || m.vcnc !== "selected" || e.source !== $("viewer").contentWindow) return;
  if (m.file !== 0 || !(m.line >= 1) || m.line > editor.state.doc.lines) return;
  const line = editor.state.doc.line(m.line);
  app.selectedFromView = m.line;
  editor.dispatch({ selection: { anchor: line.from, head: line.to }, scrollIntoView: true });
  editor.focus();
});
// The cursor's line lights its segments in the view.
let lastCursorLine = 0;
function cursorMoved() {
  const line = editor.state.doc.lineAt(editor.state.selection.main.head).number;
  if (line === lastCursorLine) return;
  lastCursorLine = line;
  if (line === app.selectedFromView) return;
  app.selectedFromView = null;
  const w = $("viewer").contentWindow;
  if (w && viewerLoaded) w.postMessage({ vcnc: "select", file: 0, line }, "*");
}

// ---- files: open, drop, machine, tools, save ----------------------------------------
function setText(text, fileName) {
  setup.file_name = fileName || null;
  app.frameNext = true;
  editor.dispatch({ changes: { from: 0, to: editor.state.doc.length, insert: text } });
}
// A program's bytes as text: UTF-8 where it is, else Latin-1 (old
// controllers' files), so that every byte shows and is checked.
function decode(buf) {
  try { return new TextDecoder("utf-8", { fatal: true }).decode(buf); } catch { return new TextDecoder("latin1").decode(buf); }
}
async function openFile(file, as) {
  const text = decode(await file.arrayBuffer());
  const kind = as || kindOf(file.name, text);
  if (kind === "machine") { setup.machine = text; setup.machineName = file.name; showLoaded(); scheduleCheck(); }
  else if (kind === "tools") { setup.tools = text; setup.tools_name = file.name; showLoaded(); scheduleCheck(); }
  else setText(text, file.name);
}
function kindOf(name, text) {
  const n = name.toLowerCase();
  if (n.endsWith(".toml")) return "machine";
  if (n.endsWith(".tbl") || n.endsWith(".csv")) return "tools";
  if (/^\s*\$\d+\s*=/.test(text)) return "machine";
  return "program";
}
$("openProgram").addEventListener("change", (e) => { const f = e.target.files[0]; if (f) openFile(f, "program"); e.target.value = ""; });
$("openMachine").addEventListener("change", (e) => { const f = e.target.files[0]; if (f) openFile(f, "machine"); e.target.value = ""; });
$("openTools").addEventListener("change", (e) => { const f = e.target.files[0]; if (f) openFile(f, "tools"); e.target.value = ""; });
$("clearSetup").addEventListener("click", () => {
  Object.assign(setup, { machine: null, machineName: null, tools: null, tools_name: null });
  showLoaded();
  scheduleCheck();
});
let dragDepth = 0;
window.addEventListener("dragenter", (e) => { e.preventDefault(); dragDepth++; $("dropHint").hidden = false; });
window.addEventListener("dragleave", () => { if (--dragDepth <= 0) { dragDepth = 0; $("dropHint").hidden = true; } });
window.addEventListener("dragover", (e) => e.preventDefault());
window.addEventListener("drop", (e) => {
  e.preventDefault();
  dragDepth = 0;
  $("dropHint").hidden = true;
  for (const f of e.dataTransfer.files) openFile(f);
}, true);
$("saveFlat").addEventListener("click", async () => {
  try {
    const { result } = await engine.request("flatten", editor.state.doc.toString(), settings());
    if (result.alarm) showError("The program alarms (" + result.alarm.code + " at line " + result.alarm.line + "): the flattened program stops there.");
    const a = document.createElement("a");
    a.href = URL.createObjectURL(new Blob([result.gcode], { type: "text/plain" }));
    a.download = (setup.file_name || "program").replace(/\.[^.]*$/, "") + "-flat.nc";
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  } catch (e) {
    if (!e.cancelled) showError(e.message);
  }
});
$("simOn").addEventListener("change", scheduleCheck);
$("stock").addEventListener("change", scheduleCheck);
$("dialect").addEventListener("change", (e) => { setup.dialect = e.target.value; scheduleCheck(); });

// ---- the program in the address: #p=<base64url(deflate-raw)>&dialect=NAME ----------------
async function pipe(bytes, stream) {
  return new Uint8Array(await new Response(new Blob([bytes]).stream().pipeThrough(stream)).arrayBuffer());
}
function b64url(u8) {
  let s = "";
  for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode.apply(null, u8.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}
function unb64url(s) {
  const b = s.replace(/-/g, "+").replace(/_/g, "/");
  return base64Bytes(b + "===".slice((b.length + 3) % 4));
}
async function linkOf(text) {
  const z = await pipe(new TextEncoder().encode(text), new CompressionStream("deflate-raw"));
  return "#p=" + b64url(z) + (setup.dialect !== "auto" ? "&dialect=" + encodeURIComponent(setup.dialect) : "");
}
let linking = false;
async function updateLink(text) {
  if (!linking) return;
  if (text.length > MAX_LINK_BYTES) { showError("This program is too long to travel in a link (over 2 MB)."); return; }
  window.history.replaceState(null, "", await linkOf(text));
}
$("share").addEventListener("click", async () => {
  linking = true;
  await updateLink(editor.state.doc.toString());
  $("share").textContent = "link ✓ (in the address)";
});
async function fromFragment() {
  const f = new URLSearchParams(location.hash.slice(1));
  const d = f.get("dialect");
  if (d) setup.dialect = d.toLowerCase();
  const p = f.get("p");
  if (!p) return null;
  linking = true;
  const bytes = await pipe(unb64url(p), new DecompressionStream("deflate-raw"));
  return new TextDecoder().decode(bytes);
}

// ---- start ---------------------------------------------------------------------------
const EXAMPLE = "%\nO1000 (a square pocket corner and a drilled hole)\nG21 G17 G40 G49 G80 G90\nT1 M06\nG54 G00 X0 Y0 S3000 M03\nG43 H1 Z10.\nG01 Z-2. F200.\nX40.\nY30.\nG02 X30. Y40. R10.\nG01 X0\nY0\nG00 Z10.\nG81 X20. Y20. Z-8. R2. F150.\nG80\nG00 Z50.\nM30\n%\n";
async function start() {
  let text = null;
  try { text = await fromFragment(); } catch (e) { showError("The link's program could not be read: " + e.message); }
  try {
    const { result } = await engine.request("dialects", "", null);
    for (const name of result) {
      const o = document.createElement("option");
      o.value = o.textContent = name;
      $("dialect").appendChild(o);
    }
  } catch (e) {
    showError(e.message);
  }
  try { await loadViewer(); } catch (e) { showError("The viewer did not start: " + e.message); }
  $("dialect").value = setup.dialect;
  if ($("dialect").value !== setup.dialect) { showError("unknown dialect " + setup.dialect + " in the link: auto"); setup.dialect = "auto"; $("dialect").value = "auto"; }
  setText(text === null ? EXAMPLE : text, null);
  warmUp();
}
// Once the first text is checked, a warm-up run while the page is idle
// (engine.wjs says why); an edit meanwhile cancels it like any run.
async function warmUp() {
  for (let i = 0; !app.applied && i < 200; i++) await new Promise((r) => setTimeout(r, 50));
  if (!app.applied || engine.busy) { app.warmed = "skipped"; return; }
  try {
    const t0 = performance.now();
    await engine.request("warmup", "", null);
    app.warmed = performance.now() - t0;
  } catch (e) {
    app.warmed = e.cancelled ? "cancelled" : e.message;
  }
}
start();
window.vcncApp = Object.assign(app, {
  editor,
  setText,
  text: () => editor.state.doc.toString(),
  engine,
  settings,
  linkOf,
  // Milliseconds from the last keystroke to its result on screen.
  lastLatency: () => (app.checks.length ? app.checks[app.checks.length - 1] : null),
});
