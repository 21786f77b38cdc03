//! The offline page of `tools/build-web.sh` (docs/web.md) in headless
//! Chromium, driven over WebDriver by the browser test's client
//! (`webdriver/mod.rs`). The test builds the page itself (the script
//! installs what is missing; `tools/install-test-deps.sh` installs it
//! ahead on CI), or takes `VCNC_WEB_PAGE`.
//!
//! One session walks through what a user does, each expectation from an
//! oracle outside the page: the CLI (`vcnc check --keep-going --format
//! json` for where the alarm is, `vcnc time --format json` for the planned
//! time) or the program text itself (which line a segment belongs to).
//! - the page loads its example and checks it;
//! - a program typed with a mistake shows the diagnostic at the CLI's line
//!   and column, with the hint on hover; typing the fix removes it;
//! - a Haas program loaded through the file input is read as haas, with
//!   the detector's evidence shown; a file dropped on the editor replaces
//!   the text once and its name counts for detection;
//! - a click on a segment of the 3D view selects its line in the editor,
//!   and the editor's line lights its segments in the view;
//! - the summary's planned time is `vcnc time`'s, and the volume the
//!   simulation removes is `vcnc sim`'s; the finished part shows in the
//!   view as a mesh, the stock as a hidden one with its toggle, and they
//!   go when simulate is unticked;
//! - the view keeps its camera across edits (a drag turns it, an edit
//!   draws the new path under the same camera: a machine point stays at
//!   its pixel), and a new program is framed again;
//! - a binary file and an endless loop end in located alarms, the page
//!   stays up;
//! - a `#p=` link brings the program and its dialect back;
//! - a 10,000-line program re-checks after a keystroke (the latency is
//!   printed, not asserted: benchmarks hold speed);
//! - no console error and no network request, in the page or the viewer.
//!
//! Screenshots go to the test's target directory (`target/tmp/web/`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod webdriver;

use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};
use webdriver::Browser;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("web");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The page: `VCNC_WEB_PAGE`, else built now by tools/build-web.sh.
fn page() -> PathBuf {
    if let Some(p) = std::env::var_os("VCNC_WEB_PAGE") {
        return PathBuf::from(p);
    }
    let root = workspace();
    let o = Command::new("bash")
        .arg(root.join("tools/build-web.sh"))
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "tools/build-web.sh failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    root.join("target/web/vcnc.html")
}

fn vcnc_json(args: &[&str]) -> Value {
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .output()
        .unwrap();
    serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("{e}: {}", String::from_utf8_lossy(&o.stdout)))
}

/// Waits until `cond` (a JS expression) is true in the page.
fn wait_for(b: &Browser, cond: &str, what: &str) {
    let t0 = Instant::now();
    loop {
        if b.js(&format!(
            "try {{ return !!({cond}); }} catch (e) {{ return false; }}"
        )) == json!(true)
        {
            return;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "{what}: never true: {cond}; banner {:?}, status {:?}, console {:?}, diagnostics {:?}",
            b.js("return document.getElementById('banner').textContent;"),
            b.js("return document.getElementById('status').textContent;"),
            b.console_errors(),
            b.js("return JSON.stringify(window.vcncApp && vcncApp.result && vcncApp.result.diagnostics) + ' ' + document.querySelector('.cm-content').innerHTML.slice(0, 2000);")
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Replaces the editor's text and waits for its check.
fn set_text(b: &Browser, text: &str) {
    let before = b.js("return vcncApp.applied;");
    b.post(
        "/execute/sync",
        &json!({"script": "vcncApp.setText(arguments[0], null);", "args": [text]}),
    );
    wait_for(
        b,
        &format!("vcncApp.applied > {before} && vcncApp.text() === vcncApp.lastChecked"),
        "the text is checked",
    );
}

/// Types `keys` into the editor at the end of line `line`, as a user does.
fn type_at_end_of_line(b: &Browser, line: u32, keys: &str) {
    b.js(&format!(
        "const v = vcncApp.editor; const l = v.state.doc.line({line}); \
         v.dispatch({{selection: {{anchor: l.to}}}}); v.focus(); return 0;"
    ));
    let content = b.element(".cm-content");
    b.post(&format!("/element/{content}/value"), &json!({"text": keys}));
}

fn shot(b: &Browser, name: &str) {
    b.screenshot(&out_dir().join(format!("{name}.png")));
}

/// Waits until the viewer has drawn the plot of the latest check.
fn viewer_ready(b: &Browser) {
    wait_for(
        b,
        "(() => { const w = document.getElementById('viewer').contentWindow; \
           return w.vcnc && w.vcnc.plotSerial() === vcncApp.plotSerial \
             && w.vcnc.stats.drawnLoad === w.vcnc.loads(); })()",
        "the viewer draws the latest plot",
    );
}

/// The viewer's camera, as its test hook gives it.
fn camera(b: &Browser) -> Value {
    b.js("return document.getElementById('viewer').contentWindow.vcnc.camera();")
}

#[test]
fn the_page_checks_times_and_draws_as_you_type() {
    let page = page();
    let (chromium, chromedriver) =
        webdriver::tools().unwrap_or_else(|e| panic!("this test fails: {e}"));
    let b = Browser::start(&chromium, &chromedriver);
    let url = format!("file://{}", page.display());
    b.post("/url", &json!({"url": url}));
    wait_for(
        &b,
        "window.vcncApp && vcncApp.applied > 0",
        "the example is checked",
    );
    viewer_ready(&b);
    shot(&b, "1-loaded");

    // A mistake: a cut with no feed rate. Where the CLI puts the alarm.
    let dir = out_dir();
    let wrong = "G90 G00 X0 Y0\nG01 X10.\nM30\n";
    std::fs::write(dir.join("wrong.nc"), wrong).unwrap();
    let cli = vcnc_json(&[
        "check",
        dir.join("wrong.nc").to_str().unwrap(),
        "--keep-going",
        "--format",
        "json",
    ]);
    let alarm = &cli["files"][0]["alarm"];
    assert_eq!(alarm["code"], "E301", "{cli}");
    set_text(&b, "G90 G00 X0 Y0\nG01 X10.\n");
    type_at_end_of_line(&b, 2, "\nM30");
    wait_for(
        &b,
        "vcncApp.text().includes('\\nM30') && vcncApp.lastChecked === vcncApp.text() \
         && document.querySelector('.cm-lintRange-error')",
        "the diagnostic is underlined",
    );
    let d = b.js(
        "const d = vcncApp.result.diagnostics[0]; const v = vcncApp.editor; \
         const el = document.querySelector('.cm-lintRange-error'); \
         const pos = v.posAtDOM(el); const line = v.state.doc.lineAt(pos); \
         return [d.code, d.line, d.column, line.number, pos - line.from + 1, el.textContent];",
    );
    assert_eq!(d[0], alarm["code"], "{d}");
    assert_eq!(d[1], alarm["line"], "{d}");
    assert_eq!(d[2], alarm["column"], "{d}");
    // The underline is on that line, from that column.
    assert_eq!(d[3], alarm["line"], "{d}");
    assert_eq!(d[4], alarm["column"], "{d}");
    assert_eq!(d[5], "G01", "{d}");
    // The hint on hover.
    let el = b.element(".cm-lintRange-error");
    b.mouse(json!([
        {"type": "pointerMove", "origin": {"element-6066-11e4-a52e-4f735466cecf": el}, "x": 0, "y": 0},
    ]));
    wait_for(
        &b,
        "document.querySelector('.cm-tooltip-lint') && \
         document.querySelector('.cm-tooltip-lint').textContent.includes('F300')",
        "the hint shows on hover",
    );
    shot(&b, "2-diagnostic");
    // The fix: the feed typed in; the alarm goes (the spindle's warning
    // stays: it never started).
    type_at_end_of_line(&b, 2, " F100.");
    wait_for(
        &b,
        "vcncApp.text().includes('X10. F100.') && vcncApp.lastChecked === vcncApp.text() \
         && !vcncApp.result.diagnostics.some((d) => d.severity === 'error') \
         && !document.querySelector('.cm-lintRange-error')",
        "the diagnostic goes",
    );
    shot(&b, "3-fixed");

    // A Haas program through the file input: haas, with its evidence.
    let haas = "%\nO1000 (HAAS VF2 SQUARE)\nG20 G17 G40 G80 G90\nT1 M06\nG54 G00 X0 Y0 S2000 M03\n\
                G43 H1 Z1.\nG01 Z-0.1 F20.\nX2.\nY1.5\nX0\nY0\nG00 Z1.\nG187 P1\nM30\n%\n";
    let haas_file = dir.join("square.nc");
    std::fs::write(&haas_file, haas).unwrap();
    let input = b.element("#openProgram");
    b.post(
        &format!("/element/{input}/value"),
        &json!({"text": haas_file.to_str().unwrap()}),
    );
    wait_for(
        &b,
        "vcncApp.text().includes('HAAS VF2') && vcncApp.lastChecked === vcncApp.text() \
         && document.getElementById('evidence').dataset.dialect === 'haas'",
        "the Haas program is read as haas",
    );
    let evidence = b.js("return document.getElementById('evidence').textContent;");
    let cli_time = vcnc_json(&["time", haas_file.to_str().unwrap(), "--format", "json"]);
    assert_eq!(cli_time["dialect"], "haas", "{cli_time}");
    for e in cli_time["dialect_evidence"].as_array().unwrap() {
        assert!(
            evidence.as_str().unwrap().contains(e.as_str().unwrap()),
            "{evidence} lacks {e}"
        );
    }
    // The summary's planned time is `vcnc time`'s (printed to 1 µs).
    let planned = b.js("return Number(document.getElementById('plannedTime').dataset.seconds);");
    let (page_s, cli_s) = (
        planned.as_f64().unwrap(),
        cli_time["total_s"].as_f64().unwrap(),
    );
    assert!(cli_s > 0.0);
    assert!(
        (page_s - cli_s).abs() < 1e-6,
        "page {page_s} s, vcnc time {cli_s} s"
    );
    // Material removal: what `vcnc sim` removes from the automatic stock.
    b.js("document.getElementById('simOn').click(); return 0;");
    wait_for(
        &b,
        "vcncApp.simmed === vcncApp.applied && document.getElementById('removed')",
        "the simulation reports",
    );
    let cli_sim = vcnc_json(&["sim", haas_file.to_str().unwrap(), "--format", "json"]);
    let removed = b.js("return Number(document.getElementById('removed').dataset.mm3);");
    let (page_mm3, cli_mm3) = (
        removed.as_f64().unwrap(),
        cli_sim["removed_mm3"].as_f64().unwrap(),
    );
    assert!(cli_mm3 > 0.0, "{cli_sim}");
    assert!(
        (page_mm3 - cli_mm3).abs() <= 1e-9 * cli_mm3,
        "page {page_mm3} mm³, vcnc sim {cli_mm3} mm³"
    );
    // The finished part in the view (the stock hidden, with its toggle).
    wait_for(
        &b,
        "JSON.stringify(document.getElementById('viewer').contentWindow.vcnc.meshes().map((m) => [m.name, m.visible])) \
           === '[[\"stock\",false],[\"finished part\",true]]'",
        "the stock and the finished part are in the view",
    );
    let meshes = b.js("return document.getElementById('viewer').contentWindow.vcnc.meshes();");
    assert!(meshes[1]["triangles"].as_u64().unwrap() > 12, "{meshes}");
    shot(&b, "4a-part");
    b.js(
        "document.getElementById('viewer').contentWindow.document.querySelector('[data-mesh=\"stock\"]').click(); return 0;",
    );
    assert_eq!(
        b.js("return document.getElementById('viewer').contentWindow.vcnc.meshes()[0].visible;"),
        json!(true),
        "the stock's toggle shows it"
    );
    b.js("document.getElementById('simOn').click(); return 0;");
    viewer_ready(&b);
    wait_for(
        &b,
        "document.getElementById('viewer').contentWindow.vcnc.meshes().length === 0",
        "unticked, the meshes go",
    );
    b.js("document.getElementById('viewer').contentWindow.vcnc.setIndex(0); return 0;");
    std::thread::sleep(Duration::from_millis(400));
    shot(&b, "4-haas");

    // A click on the cut X2. → Y1.5 (line 9 of the text) selects line 9.
    let at = b.js(
        "const f = document.getElementById('viewer'); const w = f.contentWindow; \
         const r = f.getBoundingClientRect(); const v = w.document.getElementById('view').getBoundingClientRect(); \
         const p = w.vcnc.screenOf(2 * 25.4, 0.75 * 25.4, -0.1 * 25.4); \
         return [Math.round(r.left + v.left + p[0]), Math.round(r.top + v.top + p[1])];",
    );
    let (x, y) = (at[0].as_i64().unwrap(), at[1].as_i64().unwrap());
    b.mouse(json!([
        {"type": "pointerMove", "origin": "viewport", "x": x, "y": y},
        {"type": "pointerDown", "button": 0},
        {"type": "pointerUp", "button": 0},
    ]));
    wait_for(
        &b,
        "vcncApp.editor.state.doc.lineAt(vcncApp.editor.state.selection.main.head).number === 9",
        "a click on the segment selects line 9",
    );
    let selected = b.js(
        "const v = vcncApp.editor; const s = v.state.selection.main; return v.state.sliceDoc(s.from, s.to);",
    );
    assert_eq!(selected, "Y1.5");
    // The editor's line lights its segments in the view.
    b.js(
        "const v = vcncApp.editor; v.dispatch({selection: {anchor: v.state.doc.line(10).from}}); return 0;",
    );
    wait_for(
        &b,
        "JSON.stringify(document.getElementById('viewer').contentWindow.vcnc.selected()) === '{\"file\":0,\"line\":10}'",
        "the cursor's line is selected in the view",
    );
    shot(&b, "5-linked");

    // The camera stays across an edit. A drag turns the view.
    let view = b.js(
        "const f = document.getElementById('viewer'); const r = f.getBoundingClientRect(); \
         const v = f.contentWindow.document.getElementById('view').getBoundingClientRect(); \
         return [Math.round(r.left + v.left + v.width / 2), Math.round(r.top + v.top + v.height / 3)];",
    );
    let (cx, cy) = (view[0].as_i64().unwrap(), view[1].as_i64().unwrap());
    let fitted = camera(&b);
    b.mouse(json!([
        {"type": "pointerMove", "origin": "viewport", "x": cx, "y": cy},
        {"type": "pointerDown", "button": 0},
        {"type": "pointerMove", "origin": "viewport", "x": cx + 60, "y": cy + 25, "duration": 100},
        {"type": "pointerUp", "button": 0},
    ]));
    let turned = camera(&b);
    assert_ne!(turned["R"], fitted["R"], "the drag turns the view");
    // The same machine point (the corner X2. Y1.5 Z-0.1 in inches) on
    // the screen before and after the edit.
    let corner = "return document.getElementById('viewer').contentWindow.vcnc.screenOf(2 * 25.4, 1.5 * 25.4, -0.1 * 25.4);";
    let at_before = b.js(corner);
    let loads = b.js("return document.getElementById('viewer').contentWindow.vcnc.loads();");
    // The edit: line 11 "Y0" becomes "Y-1." (backspace, then typed).
    type_at_end_of_line(&b, 11, "\u{E003}-1.");
    wait_for(
        &b,
        "vcncApp.text().includes('\\nY-1.\\n') && vcncApp.lastChecked === vcncApp.text()",
        "the edit is checked",
    );
    viewer_ready(&b);
    let after = camera(&b);
    assert!(
        b.js("return document.getElementById('viewer').contentWindow.vcnc.loads();")
            .as_u64()
            > loads.as_u64(),
        "the edit's plot is loaded"
    );
    assert_eq!(after["R"], turned["R"], "the view's rotation stays");
    assert_eq!(after["scale"], turned["scale"], "the zoom stays");
    let at_after = b.js(corner);
    for k in 0..2 {
        let (a, z) = (
            at_before[k].as_f64().unwrap(),
            at_after[k].as_f64().unwrap(),
        );
        assert!(
            (a - z).abs() < 0.01,
            "the corner moved on screen: {at_before} → {at_after}"
        );
    }
    // The new path is drawn: a vertex at Y-1. (inches) ends the edited line.
    let new_vertex = b.js(
        "const w = document.getElementById('viewer').contentWindow.vcnc; \
         for (let i = 0; i < w.count(); i++) { const v = w.vertex(i); \
           if (v.line === 11 && Math.abs(v.at[1] + 25.4) < 1e-6) return true; } return false;",
    );
    assert_eq!(new_vertex, json!(true), "the edited move is in the view");
    shot(&b, "5b-camera-kept");
    // The summary growing (as it does with simulate) shrinks the view:
    // the camera stays.
    let h0 = b.js("return document.getElementById('viewer').contentWindow.innerHeight;");
    b.js("document.getElementById('summary').style.minHeight = '320px'; return 0;");
    wait_for(
        &b,
        &format!("document.getElementById('viewer').contentWindow.innerHeight < {h0}"),
        "the view shrinks",
    );
    std::thread::sleep(Duration::from_millis(300));
    let resized = camera(&b);
    assert_eq!(resized["R"], after["R"], "a resize keeps the rotation");
    assert_eq!(resized["scale"], after["scale"], "a resize keeps the zoom");
    assert_eq!(resized["pan"], after["pan"], "a resize keeps the pan");
    b.js("document.getElementById('summary').style.minHeight = ''; return 0;");

    // Bad input: a binary file and an endless loop end in located alarms.
    let binary: Vec<u8> = (0u8..=255).cycle().take(4096).collect();
    let bin_file = dir.join("binary.nc");
    std::fs::write(&bin_file, &binary).unwrap();
    b.post(
        &format!("/element/{input}/value"),
        &json!({"text": bin_file.to_str().unwrap()}),
    );
    wait_for(
        &b,
        "vcncApp.lastChecked === vcncApp.text() && vcncApp.text().length > 1000 \
         && vcncApp.result.diagnostics.some((d) => d.severity === 'error' && d.line >= 1)",
        "a binary file alarms at a line",
    );
    set_text(&b, "#1=0\nWHILE [#1 LT 1] DO1\nG00 X1.\nEND1\nM30\n");
    // A new program is framed again: the view is back to its first turn.
    viewer_ready(&b);
    assert_eq!(camera(&b)["R"], fitted["R"], "a new program is framed");
    let endless = b.js("return vcncApp.result.diagnostics.filter((d) => d.severity === 'error').map((d) => [d.code, d.line]);");
    assert!(!endless.as_array().unwrap().is_empty(), "{endless}");
    assert_eq!(
        b.js("return document.getElementById('banner').hidden;"),
        json!(true),
        "no engine error"
    );
    shot(&b, "6-endless");

    // A program dropped on the editor replaces the text (once), and its
    // name is the detector's: an .ngc file reads as linuxcnc.
    b.js(
        "const dt = new DataTransfer(); \
         dt.items.add(new File(['G21 G90\\nG0 X1 Y2\\nG1 X3 F100\\nM2\\n'], 'drop.ngc')); \
         const t = document.querySelector('.cm-content'); \
         t.dispatchEvent(new DragEvent('drop', {dataTransfer: dt, bubbles: true, cancelable: true})); return 0;",
    );
    wait_for(
        &b,
        "vcncApp.text() === 'G21 G90\\nG0 X1 Y2\\nG1 X3 F100\\nM2\\n' && vcncApp.lastChecked === vcncApp.text() \
         && document.getElementById('evidence').dataset.dialect === 'linuxcnc'",
        "the dropped program is read, by its name, as linuxcnc",
    );

    // A worker that traps (a Rust panic) is replaced, the page says so,
    // and the next edit is checked by the new one.
    b.js("vcncApp.engine.request('trap', '', null).catch(() => {}); return 0;");
    wait_for(
        &b,
        "vcncApp.restarts() === 1 && !document.getElementById('banner').hidden \
         && document.getElementById('banner').textContent.includes('restarted')",
        "the trapped worker is replaced and the page says so",
    );
    shot(&b, "6b-worker-restarted");
    set_text(&b, "G00 X1.\nG01 X2. F100.\nM30\n");
    assert_eq!(
        b.js("return document.getElementById('banner').hidden;"),
        json!(true),
        "the next check clears the message"
    );

    // A link carries the program and its dialect.
    let program = "G90 G00 X5. Y5.\nG01 X15. F300.\nM30\n";
    set_text(&b, program);
    b.js("const s = document.getElementById('dialect'); s.value = 'grbl'; s.dispatchEvent(new Event('change')); return 0;");
    let link = b.post(
        "/execute/async",
        &json!({"script": "vcncApp.linkOf(vcncApp.text()).then(arguments[arguments.length - 1]);", "args": []}),
    )["value"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        link.starts_with("#p=") && link.ends_with("&dialect=grbl"),
        "{link}"
    );
    b.post("/url", &json!({"url": format!("{url}{link}")}));
    // A change of the fragment alone does not load the page again.
    b.js("location.reload(); return 0;");
    wait_for(
        &b,
        "window.vcncApp && vcncApp.applied > 0 && vcncApp.text() === 'G90 G00 X5. Y5.\\nG01 X15. F300.\\nM30\\n'",
        "the link's program is loaded",
    );
    assert_eq!(
        b.js("return document.getElementById('dialect').value;"),
        "grbl"
    );
    assert_eq!(
        b.js("return document.getElementById('evidence').dataset.dialect;"),
        "grbl"
    );

    // 10,000 lines: one keystroke to its result on screen.
    let mut big = String::new();
    for i in 0..10_000 {
        big.push_str(&format!("G01 X{}. Y{}. F500.\n", i % 100, (i / 100) % 100));
    }
    set_text(&b, &big);
    type_at_end_of_line(&b, 10_000, " ");
    wait_for(
        &b,
        "vcncApp.lastChecked === vcncApp.text() && vcncApp.text().endsWith(' \\n')",
        "the 10,000-line program is checked again",
    );
    let latency = b.js("return vcncApp.lastLatency();");
    println!("10,000-line re-check after a keystroke: {latency}");
    viewer_ready(&b);
    shot(&b, "7-10000-lines");

    // Nothing was fetched, here or in the viewer; no console errors.
    let resources = b.js(
        "const w = document.getElementById('viewer').contentWindow; \
         return performance.getEntriesByType('resource').map((e) => e.name) \
           .concat(w.performance.getEntriesByType('resource').map((e) => e.name));",
    );
    assert_eq!(resources, json!([]), "network requests");
    assert_eq!(b.console_errors(), Vec::<String>::new());
}
