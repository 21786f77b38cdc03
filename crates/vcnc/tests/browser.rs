//! The HTML viewer page in a real browser: headless Chromium driven through
//! chromedriver over the W3C WebDriver protocol (`webdriver/mod.rs` says
//! why that protocol). `.ci/run` installs both; without them this test
//! fails and says how to install them.
//!
//! The test plots a manual example to HTML, opens the file, checks that
//! WebGL drew a picture (pixels other than the background, in several
//! colours), clicks the slider (a real click, which moves it to the
//! middle) and checks that the highlighted program line changed to the
//! line of the block at that point, drags and scrolls the wheel on the
//! canvas and checks that the picture turned and zoomed, then presses Home
//! and checks the start.
//! It saves a screenshot (slider in the middle) in the test's target
//! directory (`target/tmp/browser/viewer.png`) and prints the
//! frame time it measured (no assertion on time: benchmarks hold speed).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod webdriver;

use base64::Engine;
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

/// The highlighted line of the program text, if any.
fn highlighted(b: &Browser) -> Value {
    b.js("const d = document.querySelector('#lines .ln.cur'); \
          return d ? [Number(d.dataset.line), d.textContent] : null;")
}

/// A fingerprint of the canvas's picture.
fn picture(b: &Browser) -> Value {
    b.js("const d = document.getElementById('gl').toDataURL(); \
          let h = 0; for (let i = 0; i < d.length; i++) h = (h * 31 + d.charCodeAt(i)) | 0; \
          return [d.length, h];")
}

/// Waits until the page has drawn the frame it asked for (and the full
/// path again after a motion: 150 ms after it stops).
fn wait_frame(b: &Browser) {
    std::thread::sleep(Duration::from_millis(400));
    b.js("return window.vcnc.stats.frames;");
}

/// Pixels of the canvas that differ from its background, and how many
/// distinct colours they have.
fn drawn(b: &Browser) -> (u64, u64) {
    let v = b.js(
        "const c = document.getElementById('gl'); \
         const t = document.createElement('canvas'); t.width = c.width; t.height = c.height; \
         const g = t.getContext('2d'); g.drawImage(c, 0, 0); \
         const d = g.getImageData(0, 0, t.width, t.height).data; \
         const bg = [d[0], d[1], d[2]]; let n = 0; const colours = new Set(); \
         for (let i = 0; i < d.length; i += 4) { \
           if (Math.abs(d[i] - bg[0]) + Math.abs(d[i+1] - bg[1]) + Math.abs(d[i+2] - bg[2]) > 60) { \
             n++; colours.add((d[i] >> 4) + ',' + (d[i+1] >> 4) + ',' + (d[i+2] >> 4)); } } \
         return [n, colours.size];",
    );
    (v[0].as_u64().unwrap(), v[1].as_u64().unwrap())
}

#[test]
fn the_viewer_page_draws_and_its_slider_follows_the_program() {
    let (chromium, chromedriver) =
        webdriver::tools().unwrap_or_else(|e| panic!("this test fails: {e}"));

    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("browser");
    std::fs::create_dir_all(&out_dir).unwrap();
    let page = out_dir.join("1.2.18_example.html");
    let program = workspace().join("tests/fixtures/manual/1.2.18_example.nc");
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args([
            "plot",
            program.to_str().unwrap(),
            "-o",
            page.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let source = std::fs::read_to_string(&program).unwrap();
    let source_line = |n: u64| {
        source
            .lines()
            .nth(usize::try_from(n).unwrap() - 1)
            .unwrap()
            .to_string()
    };

    let b = Browser::start(&chromium, &chromedriver);
    b.post(
        "/url",
        &json!({"url": format!("file://{}", page.display())}),
    );
    let t0 = Instant::now();
    while b.js("return !!(window.vcnc && window.vcnc.stats.frames > 0);") != json!(true) {
        assert!(
            t0.elapsed() < Duration::from_secs(20),
            "the page never drew a frame"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    assert_eq!(
        b.js("return window.vcnc.webgl;"),
        json!(true),
        "WebGL is available"
    );

    // A picture: the path, the contour, the marks — not a blank canvas.
    let (pixels, colours) = drawn(&b);
    assert!(pixels > 2000, "only {pixels} pixels drawn");
    assert!(colours >= 3, "only {colours} colours drawn");

    // Loaded at the end of the program: the last block that moved.
    let end = highlighted(&b);
    let end_line = end[0].as_u64().unwrap();
    assert!(
        end[1].as_str().unwrap().ends_with(&source_line(end_line)),
        "{end}"
    );

    // A click on the slider moves it to the middle of the program.
    let scrub = b.element("#scrub");
    b.post(&format!("/element/{scrub}/click"), &json!({}));
    let mid = highlighted(&b);
    let mid_line = mid[0].as_u64().unwrap();
    assert_ne!(
        mid_line, end_line,
        "the highlighted line follows the slider"
    );
    assert!(
        mid[1].as_str().unwrap().ends_with(&source_line(mid_line)),
        "{mid}"
    );
    let index = b.js("return window.vcnc.index();").as_u64().unwrap();
    let count = b.js("return window.vcnc.count();").as_u64().unwrap();
    assert!(
        index > 0 && index < count - 1,
        "slider at {index} of {count}"
    );
    // Half-way through the eight arcs of the outline (N006-N014).
    assert!(
        (7..=14).contains(&mid_line),
        "line {mid_line} is not in the outline"
    );
    let (pixels_mid, _) = drawn(&b);
    assert!(pixels_mid > 1000, "the page still draws: {pixels_mid}");
    let shot = b.get("/screenshot")["value"].as_str().unwrap().to_string();
    let png = base64::engine::general_purpose::STANDARD
        .decode(shot)
        .unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let shot_path = out_dir.join("viewer.png");
    std::fs::write(&shot_path, png).unwrap();

    // A drag turns the model and the wheel zooms it: the picture changes.
    let canvas = b.element("#gl");
    let before = picture(&b);
    let drag = json!({"actions": [{"type": "pointer", "id": "mouse",
        "parameters": {"pointerType": "mouse"}, "actions": [
            {"type": "pointerMove", "duration": 0, "origin": {"element-6066-11e4-a52e-4f735466cecf": canvas}, "x": 0, "y": 0},
            {"type": "pointerDown", "button": 0},
            {"type": "pointerMove", "duration": 200, "origin": "pointer", "x": 120, "y": 40},
            {"type": "pointerUp", "button": 0}]}]});
    b.post("/actions", &drag);
    wait_frame(&b);
    let turned = picture(&b);
    assert_ne!(turned, before, "dragging turns the model");
    let wheel = json!({"actions": [{"type": "wheel", "id": "wheel", "actions": [
        {"type": "scroll", "x": 0, "y": 0, "deltaX": 0, "deltaY": -400, "duration": 0,
         "origin": {"element-6066-11e4-a52e-4f735466cecf": canvas}}]}]});
    b.post("/actions", &wheel);
    wait_frame(&b);
    assert_ne!(picture(&b), turned, "the wheel zooms");

    // Home: back to the power-on position, before any block.
    b.post(
        &format!("/element/{scrub}/value"),
        &json!({"text": "\u{E011}"}),
    );
    assert_eq!(b.js("return window.vcnc.index();"), json!(0));
    assert_eq!(highlighted(&b), Value::Null, "no block has run yet");

    let frame_ms = b.js("return window.vcnc.bench(10);").as_f64().unwrap();
    println!("screenshot: {}", shot_path.display());
    println!("frame time after loading: {frame_ms:.2} ms");
    assert!(frame_ms.is_finite() && frame_ms > 0.0);
}
