//! The offline page of `tools/build-web.sh` in headless Chromium: how long
//! a large program takes to open — from handing the text to the editor to
//! its diagnostics and summary on screen, and to the viewer's first frame
//! of its path — and how long a keystroke at its end takes to be checked
//! again.
//!
//! `VCNC_WEB_PAGE=target/web/vcnc.html VCNC_WEB_PROGRAM=prog.nc cargo
//! bench -p vcnc --bench web_page`; `tools/bench/web.sh` runs it on the
//! surfacing program. A benchmark, not a test: it prints figures and
//! asserts nothing about time. It also times a page built before the
//! viewer kept its camera (2026-12-06: each plot a new page in the
//! iframe), so a before/after comparison needs no other bench.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark reports by panicking

#[path = "../tests/webdriver/mod.rs"]
mod webdriver;

use serde_json::json;
use std::time::{Duration, Instant};

fn wait(b: &webdriver::Browser, cond: &str, what: &str) {
    let t0 = Instant::now();
    while b.js(&format!(
        "try {{ return !!({cond}); }} catch (e) {{ return false; }}"
    )) != json!(true)
    {
        assert!(t0.elapsed() < Duration::from_secs(300), "{what}: never");
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn main() {
    let (Some(page), Some(program)) = (
        std::env::var_os("VCNC_WEB_PAGE"),
        std::env::var_os("VCNC_WEB_PROGRAM"),
    ) else {
        println!("web_page: set VCNC_WEB_PAGE (tools/build-web.sh) and VCNC_WEB_PROGRAM");
        return;
    };
    let page = std::path::PathBuf::from(page).canonicalize().unwrap();
    let text = std::fs::read_to_string(program).unwrap();
    let (chromium, chromedriver) = webdriver::tools().unwrap_or_else(|e| panic!("{e}"));
    let b = webdriver::Browser::start(&chromium, &chromedriver);
    b.post(
        "/url",
        &json!({"url": format!("file://{}", page.display())}),
    );
    wait(
        &b,
        "window.vcncApp && vcncApp.applied > 0",
        "the example is checked",
    );
    wait(
        &b,
        "(() => { const w = document.getElementById('viewer').contentWindow; \
           return w.vcnc && w.vcnc.stats.frames > 0; })()",
        "the example is drawn",
    );
    // The page's warm-up run (web/src/engine.wjs) has ended, as it has
    // for a user a second after the page opened.
    wait(&b, "vcncApp.warmed !== null", "the warm-up ends");
    println!(
        "warm-up: {}",
        b.js("return vcncApp.warmed === undefined ? null : vcncApp.warmed;")
    );
    // The viewer's first frame of the new plot: the plot it draws
    // (`stats.drawnLoad`) past the example's; an older page replaced the
    // viewer's page instead.
    let before = b.js(
        "const w = document.getElementById('viewer').contentWindow; w.__old = true; \
         return w.vcnc && w.vcnc.loads ? w.vcnc.loads() : 0;",
    );
    let t0 = Instant::now();
    b.post(
        "/execute/sync",
        &json!({"script": "vcncApp.setText(arguments[0], null);", "args": [text]}),
    );
    let handed = t0.elapsed();
    wait(
        &b,
        "vcncApp.lastChecked === vcncApp.text()",
        "the program is checked",
    );
    let checked = t0.elapsed();
    wait(
        &b,
        &format!(
            "(() => {{ const w = document.getElementById('viewer').contentWindow; \
               return w.vcnc && (w.vcnc.loads ? w.vcnc.stats.drawnLoad > {before} \
                 : !w.__old && w.vcnc.stats.frames > 0); }})()"
        ),
        "the viewer draws",
    );
    let drawn = t0.elapsed();
    // In the page's own clock: from the edit (the editor holding the
    // text) to the end of the viewer's first frame of it.
    let in_page = b.js(
        "const w = document.getElementById('viewer').contentWindow; const c = vcncApp.lastLatency(); \
         return c && c.editedAt && w.vcnc.stats.drawnAt ? Math.round(w.vcnc.stats.drawnAt - c.editedAt) : null;",
    );
    let check = b.js("return vcncApp.lastLatency();");
    let lines = b.js("return vcncApp.editor.state.doc.lines;");
    println!(
        "{lines} lines: text handed to the editor in {handed:.2?}; checked and on screen after {checked:.2?} ({check}); the viewer's first frame after {drawn:.2?} ({in_page} ms after the edit, in the page)"
    );
    // A keystroke at the end: checked again.
    b.js("const v = vcncApp.editor; v.dispatch({changes: {from: v.state.doc.length, insert: ' '}}); return 0;");
    wait(
        &b,
        "vcncApp.lastChecked === vcncApp.text()",
        "the edit is checked",
    );
    println!(
        "a keystroke at the end: {}",
        b.js("return vcncApp.lastLatency();")
    );
}
