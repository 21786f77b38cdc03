// vcnc plot viewer: hand-written WebGL 1, no libraries, no network.
// The data (see html.rs) is decoded once into typed arrays; the path is
// drawn as GL_LINES with one colour per segment, the part after the
// slider's position faint. Camera: orthographic, turntable about the
// machine's up axis (Z; X on a lathe), drag to turn, wheel to zoom at the
// cursor, right-drag or shift-drag to pan.
"use strict";
(function () {
  const $ = (id) => document.getElementById(id);
  const D = JSON.parse($("vcnc-data").textContent);

  function bytes(s) {
    const bin = atob(s || "");
    const n = bin.length;
    const u = new Uint8Array(n);
    for (let i = 0; i < n; i++) u[i] = bin.charCodeAt(i);
    return u.buffer;
  }
  function arr(T, s) { return s === undefined || s === null ? null : new T(bytes(s)); }
  function path(p) {
    if (!p) return null;
    return {
      n: p.n, pos: arr(Float32Array, p.pos), kind: arr(Uint8Array, p.kind),
      tool: arr(Uint16Array, p.tool), line: arr(Uint32Array, p.line),
      file: arr(Uint16Array, p.file), time: arr(Float32Array, p.time),
      feed: arr(Float32Array, p.feed),
    };
  }
  const P = path(D.path), C = path(D.contour), K = path(D.compare);
  const holes = arr(Float32Array, D.holes);
  let theme = D.theme, colorBy = D.color, showRapid = true, showCompare = true;
  const pal = () => D.palette[theme];

  // ---- program text, drawn only where it is visible ----------------------
  const LH = 16;
  const pane = $("source"), lines = $("lines");
  const sources = [];
  let curFile = -1, curLine = 0;
  function source(i) {
    if (sources[i] !== undefined) return sources[i];
    const el = $("vcnc-src-" + i);
    let s = null;
    if (el) {
      const text = new TextDecoder("utf-8").decode(new Uint8Array(bytes(el.textContent.trim())));
      const starts = [0];
      for (let k = text.indexOf("\n"); k !== -1; k = text.indexOf("\n", k + 1)) starts.push(k + 1);
      if (starts.length > 1 && starts[starts.length - 1] === text.length) starts.pop();
      s = { text, starts };
    }
    sources[i] = s;
    return s;
  }
  function lineText(s, i) {
    const a = s.starts[i], b = i + 1 < s.starts.length ? s.starts[i + 1] : s.text.length;
    return s.text.slice(a, b).replace(/\r?\n$/, "");
  }
  function renderLines() {
    const s = source(curFile);
    if (!s) { lines.textContent = ""; return; }
    const first = Math.max(0, Math.floor(pane.scrollTop / LH) - 5);
    const last = Math.min(s.starts.length, first + Math.ceil(pane.clientHeight / LH) + 10);
    const frag = document.createDocumentFragment();
    for (let i = first; i < last; i++) {
      const d = document.createElement("div");
      d.className = i + 1 === curLine ? "ln cur" : "ln";
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
    curFile = i;
    const s = source(i);
    lines.style.height = (s ? s.starts.length : 0) * LH + "px";
    $("srcname").textContent = D.files[i] !== undefined ? D.files[i] : "(program text not included)";
  }
  function highlight(file, line) {
    if (file !== curFile) showFile(file);
    curLine = line;
    const top = (line - 1) * LH;
    if (line > 0 && (top < pane.scrollTop + 2 * LH || top > pane.scrollTop + pane.clientHeight - 3 * LH)) {
      pane.scrollTop = Math.max(0, top - pane.clientHeight / 2);
    }
    renderLines();
  }
  pane.addEventListener("scroll", () => requestAnimationFrame(renderLines));
  lines.addEventListener("click", (e) => {
    const d = e.target.closest(".ln");
    if (!d) return;
    const want = Number(d.dataset.line);
    for (let i = 0; i < P.n; i++) {
      if (P.line[i] === want && (P.file ? P.file[i] : 0) === curFile) { setIndex(i); return; }
    }
  });

  // ---- colours -----------------------------------------------------------
  function ramp(stops, t, steps) {
    if (!isFinite(t)) t = 0.5;
    t = Math.min(1, Math.max(0, t));
    const q = Math.round(t * (steps - 1)) / (steps - 1);
    const x = q * (stops.length - 1), i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
    return [0, 1, 2].map((k) => Math.round(stops[i][k] + (stops[i + 1][k] - stops[i][k]) * f));
  }
  const depthAxis = D.lathe ? 0 : 2;
  function range(f) {
    let lo = Infinity, hi = -Infinity;
    for (let i = 1; i < P.n; i++) if (P.kind[i] === 2) { const v = f(i); if (v < lo) lo = v; if (v > hi) hi = v; }
    return lo <= hi ? [lo, hi] : [0, 0];
  }
  const depthRange = range((i) => P.pos[3 * i + depthAxis]);
  const feedRange = range((i) => P.feed[i]);
  const frac = (v, r) => (r[1] - r[0] > 1e-9 ? (v - r[0]) / (r[1] - r[0]) : 0.5);
  function toolColor(t) { const p = pal(); return t === 0 ? p.noTool : p.tools[(t - 1) % p.tools.length]; }
  function segColor(i) {
    const p = pal();
    if (P.kind[i] === 1) return showRapid ? [...p.rapid, 255] : [0, 0, 0, 0];
    let c;
    if (colorBy === "tool") c = toolColor(P.tool[i]);
    else if (colorBy === "feed") c = ramp(p.feed, frac(P.feed[i], feedRange), 16);
    else c = ramp(p.depth, frac((P.pos[3 * i + depthAxis] + P.pos[3 * (i - 1) + depthAxis]) / 2, depthRange), 32);
    return [...c, 255];
  }

  // ---- WebGL -------------------------------------------------------------
  const canvas = $("gl");
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
  const FS = "#ifdef GL_FRAGMENT_PRECISION_HIGH\nprecision highp float;\n#else\nprecision mediump float;\n#endif\n" +
    "varying vec4 v_col; varying float v_dash; uniform float u_dash; uniform float u_alpha; uniform float u_round;" +
    "void main() { if (v_dash >= 0.0 && fract(v_dash / u_dash) > 0.55) discard;" +
    " if (u_round > 0.5) { vec2 d = gl_PointCoord - vec2(0.5); if (dot(d, d) > 0.25) discard; }" +
    " gl_FragColor = vec4(v_col.rgb, v_col.a * u_alpha); }";
  let prog = null, loc = {};
  function shader(type, src) {
    const s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  if (gl) {
    prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, VS));
    gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, FS));
    gl.linkProgram(prog);
    gl.useProgram(prog);
    for (const n of ["a_pos", "a_col", "a_dash"]) loc[n] = gl.getAttribLocation(prog, n);
    for (const n of ["u_mvp", "u_point", "u_dash", "u_alpha", "u_round"]) loc[n] = gl.getUniformLocation(prog, n);
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
  let main = null, preview = null, cmp = null, contour = null, marks = null, origins = null;
  let moving = false, still = 0;
  function move() {
    moving = true;
    clearTimeout(still);
    still = setTimeout(() => { moving = false; request(); }, 150);
  }
  function build() {
    const p = pal();
    main = lineBuffer(P, segColor, true);
    preview = main.count / 2 > 2 * PREVIEW ? previewBuffer(P, segColor) : null;
    if (K) cmp = lineBuffer(K, () => [...p.compare, 200], true);
    if (C) contour = lineBuffer(C, () => [...p.contour, 255], false);
    const pts = [];
    for (let k = 0; holes && k < holes.length; k += 3) pts.push([holes[k], holes[k + 1], holes[k + 2], [...p.hole, 255]]);
    for (const t of D.toolChanges) pts.push([t[0], t[1], t[2], [...p.toolChange, 255]]);
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
  }

  // ---- camera ------------------------------------------------------------
  // R: rows are screen right, up and towards the viewer in machine axes.
  const VIEWS = {
    top: [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
    front: D.lathe ? [[0, 0, 1], [1, 0, 0], [0, 1, 0]] : [[1, 0, 0], [0, 0, 1], [0, -1, 0]],
    side: [[0, 1, 0], [0, 0, 1], [1, 0, 0]],
    iso: [[Math.SQRT1_2, Math.SQRT1_2, 0], [-1 / Math.sqrt(6), 1 / Math.sqrt(6), 2 / Math.sqrt(6)], [1 / Math.sqrt(3), -1 / Math.sqrt(3), 1 / Math.sqrt(3)]],
  };
  const UP = D.lathe ? [1, 0, 0] : [0, 0, 1];
  let R = VIEWS[D.lathe ? "front" : "iso"].map((r) => r.slice());
  let scale = 1, pan = [0, 0];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  function fit() {
    const w = canvas.width, h = canvas.height;
    let ulo = Infinity, uhi = -Infinity, vlo = Infinity, vhi = -Infinity;
    for (let k = 0; k < 8; k++) {
      const c = [k & 1 ? D.hi[0] : D.lo[0], k & 2 ? D.hi[1] : D.lo[1], k & 4 ? D.hi[2] : D.lo[2]];
      const u = dot(R[0], c), v = dot(R[1], c);
      ulo = Math.min(ulo, u); uhi = Math.max(uhi, u); vlo = Math.min(vlo, v); vhi = Math.max(vhi, v);
    }
    scale = 0.9 * Math.min(w / Math.max(uhi - ulo, 1e-6), h / Math.max(vhi - vlo, 1e-6));
    if (!isFinite(scale) || scale <= 0) scale = 1;
    pan = [-scale * (ulo + uhi) / 2, -scale * (vlo + vhi) / 2];
    request();
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
    request();
  }
  function mvp() {
    const w = canvas.width, h = canvas.height, sx = (2 * scale) / w, sy = (2 * scale) / h, z = 1 / D.size;
    return new Float32Array([
      R[0][0] * sx, R[1][0] * sy, -R[2][0] * z, 0,
      R[0][1] * sx, R[1][1] * sy, -R[2][1] * z, 0,
      R[0][2] * sx, R[1][2] * sy, -R[2][2] * z, 0,
      (2 * pan[0]) / w, (2 * pan[1]) / h, 0, 1,
    ]);
  }

  // ---- drawing -----------------------------------------------------------
  let cur = 0;
  const stats = { frames: 0, lastMs: 0, totalMs: 0 };
  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; return true; }
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
  function draw() {
    const t0 = performance.now();
    if (!gl) return;
    resize();
    const bg = pal().bg;
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(bg[0] / 255, bg[1] / 255, bg[2] / 255, 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
    gl.uniformMatrix4fv(loc.u_mvp, false, mvp());
    gl.uniform1f(loc.u_dash, (10 * (window.devicePixelRatio || 1)) / scale);
    gl.uniform1f(loc.u_point, 1);
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
    bind(marks);
    gl.uniform1f(loc.u_alpha, 1);
    gl.uniform1f(loc.u_round, 1);
    gl.uniform1f(loc.u_point, 7 * (window.devicePixelRatio || 1));
    gl.drawArrays(gl.POINTS, 0, marks.count);
    const here = pointBuffer([[P.pos[3 * cur], P.pos[3 * cur + 1], P.pos[3 * cur + 2], [...pal().alarm, 255]]]);
    bind(here);
    gl.uniform1f(loc.u_point, 11 * (window.devicePixelRatio || 1));
    gl.drawArrays(gl.POINTS, 0, 1);
    gl.deleteBuffer(here.b);
    const ms = performance.now() - t0;
    stats.frames++; stats.lastMs = ms; stats.totalMs += ms;
  }
  let pending = false;
  function request() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => { pending = false; draw(); });
  }
  window.addEventListener("resize", () => { if (resize()) fit(); request(); });

  // ---- slider, text, info ------------------------------------------------
  const scrub = $("scrub"), by = $("by");
  const fmtTime = (s) => (s >= 60 ? Math.floor(s / 60) + "m " + (s % 60).toFixed(1) + "s" : s.toFixed(1) + "s");
  function indexAtTime(t) {
    let lo = 0, hi = P.n - 1;
    while (lo < hi) { const m = (lo + hi) >> 1; if (P.time[m] < t) lo = m + 1; else hi = m; }
    return lo;
  }
  function setIndex(i) {
    cur = Math.max(0, Math.min(P.n - 1, i));
    scrub.value = String(by.value === "time" ? Math.round((1000 * P.time[cur]) / Math.max(D.totalTime, 1e-9)) : cur);
    update();
  }
  function update() {
    const f = P.file ? P.file[cur] : 0;
    // Line 0: the power-on position, before any block; nothing is lit.
    highlight(f, P.line[cur]);
    const t = P.tool[cur];
    const pos = [0, 1, 2].map((k) => (P.pos[3 * cur + k] + D.center[k]).toFixed(3));
    // A lathe's X is a radius in the data and a diameter to its programmer.
    if (D.lathe) pos[0] = "dia " + (2 * Number(pos[0])).toFixed(3);
    $("info").textContent =
      (P.line[cur] ? "line " + P.line[cur] + (f ? " of " + D.files[f] : "") : "power-on position") + " | " + (t ? "T" + D.tools[t - 1] : "no tool") +
      " | X " + pos[0] + " Y " + pos[1] + " Z " + pos[2] +
      " | " + fmtTime(P.time[cur]) + " of " + fmtTime(D.totalTime) + " (" + D.timeLabel + ")";
    request();
  }
  function setupScrub() {
    if (by.value === "time") { scrub.max = "1000"; } else { scrub.max = String(Math.max(0, P.n - 1)); }
    setIndex(cur);
  }
  scrub.addEventListener("input", () => {
    const v = Number(scrub.value);
    cur = by.value === "time" ? indexAtTime((v / 1000) * D.totalTime) : v;
    update();
  });
  by.addEventListener("change", setupScrub);
  let playing = false;
  $("play").addEventListener("click", () => {
    playing = !playing;
    $("play").textContent = playing ? "pause" : "play";
    if (playing && cur >= P.n - 1) setIndex(0);
    const step = () => {
      if (!playing) return;
      setIndex(cur + Math.max(1, Math.round(P.n / 600)));
      if (cur >= P.n - 1) { playing = false; $("play").textContent = "play"; return; }
      requestAnimationFrame(step);
    };
    requestAnimationFrame(step);
  });

  // ---- legend ------------------------------------------------------------
  function esc(s) { const d = document.createElement("div"); d.textContent = s; return d.innerHTML; }
  function sw(c) { return '<span class="sw" style="background:rgb(' + c.join(",") + ')"></span>'; }
  function legend() {
    const p = pal();
    let h = "<div>" + sw(p.rapid) + "rapid (dashed)</div>";
    if (colorBy === "tool") {
      const used = new Set();
      for (let i = 1; i < P.n; i++) if (P.kind[i] === 2) used.add(P.tool[i]);
      [...used].sort((a, b) => a - b).slice(0, 16).forEach((t) => { h += "<div>" + sw(toolColor(t)) + (t ? "T" + D.tools[t - 1] : "no tool") + "</div>"; });
    } else if (colorBy === "depth") {
      h += "<div>" + sw(ramp(p.depth, 0, 32)) + (D.lathe ? "X dia " + (2 * (depthRange[0] + D.center[0])).toFixed(3) : "Z " + (depthRange[0] + D.center[2]).toFixed(3)) + " (deep)</div>";
      h += "<div>" + sw(ramp(p.depth, 1, 32)) + (D.lathe ? "X dia " + (2 * (depthRange[1] + D.center[0])).toFixed(3) : "Z " + (depthRange[1] + D.center[2]).toFixed(3)) + " (high)</div>";
    } else {
      h += "<div>" + sw(ramp(p.feed, 0, 16)) + "F " + feedRange[0].toFixed(0) + "</div><div>" + sw(ramp(p.feed, 1, 16)) + "F " + feedRange[1].toFixed(0) + " mm/min</div>";
    }
    if (C) h += "<div>" + sw(p.contour) + "programmed contour</div>";
    if (K) h += "<div>" + sw(p.compare) + "compare: " + esc(D.compareName) + "</div>";
    if (D.holeCount) h += "<div>" + sw(p.hole) + "holes (" + D.holeCount + ")</div>";
    if (D.toolChanges.length) h += "<div>" + sw(p.toolChange) + "tool changes</div>";
    h += "<div>" + sw(p.start) + "start</div><table>";
    for (const [k, v] of D.rows) h += "<tr><td>" + esc(k) + "</td><td>" + esc(v) + "</td></tr>";
    h += "</table>";
    if (D.alarm) h += '<div class="alarm">alarm ' + esc(D.alarm.code) + " line " + D.alarm.line + ": " + esc(D.alarm.message) + "</div>";
    $("legend").innerHTML = h;
  }

  // ---- controls ----------------------------------------------------------
  for (const b of document.querySelectorAll("[data-view]")) {
    b.addEventListener("click", () => { R = VIEWS[b.dataset.view].map((r) => r.slice()); fit(); });
  }
  $("fit").addEventListener("click", fit);
  const colorSel = $("color");
  colorSel.value = colorBy;
  colorSel.addEventListener("change", () => { colorBy = colorSel.value; build(); legend(); request(); });
  $("showRapid").addEventListener("change", (e) => { showRapid = e.target.checked; build(); request(); });
  if (K) $("cmpLabel").hidden = false;
  $("showCompare").addEventListener("change", (e) => { showCompare = e.target.checked; request(); });
  $("theme").addEventListener("click", () => {
    theme = theme === "dark" ? "light" : "dark";
    document.body.className = theme;
    build(); legend(); request();
  });
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
    canvas.setPointerCapture(e.pointerId);
    canvas.style.cursor = "grabbing";
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dpr = window.devicePixelRatio || 1, dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    move();
    if (drag.pan) { pan = [pan[0] + dx * dpr, pan[1] - dy * dpr]; request(); } else turn(dx, dy);
  });
  const endDrag = () => { drag = null; canvas.style.cursor = "grab"; };
  canvas.addEventListener("pointerup", endDrag);
  canvas.addEventListener("pointercancel", endDrag);
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const dpr = window.devicePixelRatio || 1, r = canvas.getBoundingClientRect();
    const sx = (e.clientX - r.left) * dpr - canvas.width / 2, sy = canvas.height / 2 - (e.clientY - r.top) * dpr;
    const k = Math.exp(-e.deltaY * 0.0015);
    pan = [sx - (sx - pan[0]) * k, sy - (sy - pan[1]) * k];
    scale *= k;
    move();
    request();
  }, { passive: false });

  // ---- start -------------------------------------------------------------
  $("title").textContent = D.title;
  document.body.className = theme;
  build();
  legend();
  resize();
  fit();
  showFile(0);
  setupScrub();
  setIndex(P.n - 1);
  // For tests and benchmarks: state and a synchronous frame timer.
  window.vcnc = {
    stats,
    index: () => cur,
    count: () => P.n,
    currentLine: () => curLine,
    setIndex,
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
})();
