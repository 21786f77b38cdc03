// Times the browser's engine (vcnc_web, wasm) under node on one program:
// time() as `vcnc time`, check() without and with the viewer's data (what
// the page runs on each edit). Called by tools/bench/web.sh:
//   node tools/bench/web_engine.cjs PKG/vcnc_web.js PROGRAM.nc
"use strict";
const fs = require("fs");
const [glue, program] = process.argv.slice(2);
const engine = require(require("path").resolve(glue));
const text = fs.readFileSync(program, "utf8");
const settings = { dialect: "fanuc" };
// The engine takes UTF-8 bytes, as the page's worker hands them over
// (encoded in each timed call, as the worker does).
const utf8 = new TextEncoder();
function timed(name, f) {
  for (let run = 1; run <= 3; run++) {
    const t0 = process.hrtime.bigint();
    const r = f();
    const s = Number(process.hrtime.bigint() - t0) / 1e9;
    const rss = Math.round(process.memoryUsage().rss / 1024);
    console.log(`wasm ${name} run ${run}: ${s.toFixed(2)} s, ${rss} KB RSS (node)` + (run === 1 ? `; ${r}` : ""));
  }
}
timed("time", () => "planned " + engine.time(utf8.encode(text), settings).total_s.toFixed(1) + " s");
timed("check", () => "planned " + engine.check(utf8.encode(text), settings, false).summary.planned_s.toFixed(1) + " s");
timed("check + view", () => "view data " + Math.round(engine.check(utf8.encode(text), settings, true).view.length / 1024) + " KiB");
