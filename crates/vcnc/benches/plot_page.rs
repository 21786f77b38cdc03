//! The viewer page in headless Chromium: how long a page takes to load
//! (inflate and decode its tables and program text, build the vertex
//! buffer, draw the first frame), how long a frame takes after loading,
//! how long a slider move takes, and how long finding the segment under
//! the pointer takes after the view changed.
//!
//! `VCNC_PLOT_PAGE=out.html cargo bench -p vcnc --bench plot_page`;
//! `tools/bench/plot.sh` makes a 1,000,000-block page and runs this. A
//! benchmark, not a test: it prints figures and asserts nothing about time.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a benchmark reports by panicking

#[path = "../tests/webdriver/mod.rs"]
mod webdriver;

use serde_json::json;
use std::time::{Duration, Instant};

fn main() {
    let Some(page) = std::env::var_os("VCNC_PLOT_PAGE") else {
        println!("plot_page: set VCNC_PLOT_PAGE to an HTML plot (tools/bench/plot.sh makes one)");
        return;
    };
    let page = std::path::PathBuf::from(page).canonicalize().unwrap();
    let (chromium, chromedriver) = webdriver::tools().unwrap_or_else(|e| panic!("{e}"));
    let b = webdriver::Browser::start(&chromium, &chromedriver);
    let t0 = Instant::now();
    b.post(
        "/url",
        &json!({"url": format!("file://{}", page.display())}),
    );
    while b.js("return !!(window.vcnc && window.vcnc.stats.frames > 0);") != json!(true) {
        assert!(
            t0.elapsed() < Duration::from_secs(120),
            "the page never drew"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    let load = t0.elapsed();
    let n = b.js("return window.vcnc.count();");
    let webgl = b.js("return window.vcnc.webgl;");
    let frame_ms = b.js("return window.vcnc.bench(20);").as_f64().unwrap();
    let moving_ms = b
        .js("return window.vcnc.bench(20, true);")
        .as_f64()
        .unwrap();
    let scrub_ms = b
        .js("const t = performance.now(); \
             for (let k = 1; k <= 20; k++) { window.vcnc.setIndex(Math.floor(window.vcnc.count() * k / 21)); window.vcnc.bench(1); } \
             return (performance.now() - t) / 20;")
        .as_f64()
        .unwrap();
    // A pick as hover and clicks make it, after a turn of the view (the
    // path's screen positions are projected again, then scanned).
    let pick_ms = b
        .js(
            "const c = document.getElementById('gl'), w = c.clientWidth, h = c.clientHeight; \
             const t = performance.now(); \
             for (let k = 0; k < 10; k++) { window.vcnc.setIndex(window.vcnc.count() - 1 - k); \
               document.querySelector('[data-view=\"' + ['top', 'iso'][k % 2] + '\"]').click(); \
               window.vcnc.nearestAt(w * (0.3 + 0.04 * k), h / 2); } \
             return (performance.now() - t) / 10;",
        )
        .as_f64()
        .unwrap();
    let size = std::fs::metadata(&page).unwrap().len();
    println!(
        "page        {} ({:.1} MB, {n} vertices, WebGL {webgl})",
        page.display(),
        size as f64 / 1e6
    );
    println!(
        "load        {:.2} s (navigation to first frame)",
        load.as_secs_f64()
    );
    println!("frame       {frame_ms:.1} ms (mean of 20 redraws, GPU finished)");
    println!("drag frame  {moving_ms:.1} ms (the preview drawn while the view moves)");
    println!("slider move {scrub_ms:.1} ms (text pane and a redraw, mean of 20)");
    println!(
        "pick        {pick_ms:.1} ms (a view change, then the segment under the pointer, mean of 10)"
    );
}
