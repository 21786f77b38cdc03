//! The HTML viewer page in a real browser: headless Chromium driven through
//! chromedriver over the W3C WebDriver protocol (`webdriver/mod.rs` says
//! why that protocol). `.ci/run` installs both; without them these tests
//! fail and say how to install them.
//!
//! - A manual example: WebGL drew a picture (pixels other than the
//!   background, in several colours); a real click on the slider moves it
//!   to the middle of the planned time and the highlighted program line
//!   changes to that block's; a drag turns the model and the wheel zooms
//!   it; Home goes back to the power-on position.
//! - A square cut under a G52 shift (work X0 Y0 = machine X100 Y50), every
//!   expected figure worked out from the program text: a click on a
//!   segment selects its line, a click on a line lights its segments; the
//!   hover readout gives the line and the point in work and machine
//!   coordinates; the measure tool gives 50.000 mm between the square's
//!   corners (0, 0) and (30, 40); at ×10 playback takes a tenth of the
//!   planned time (which is `vcnc time`'s); `--view xy` opens the page
//!   from the top; `--units in` shows inches.
//! - A lathe page offers the section only and a drag pans it; a page with
//!   a mesh (the material-removal hook) draws it and its toggle hides it;
//!   under G68 R90 the readout's work coordinates are the program's; the
//!   page's time format is `vcnc_core::display::duration`'s.
//! - `plot --stock`: the page carries the simulated stock (hidden at
//!   first) and finished part (shown), each with a toggle that shows and
//!   hides it; without `--stock` the page has no meshes.
//!
//! No page may log a console error. The tests run one at a time (one
//! browser on a shared 2-core machine) and save screenshots in the
//! test's target directory (`target/tmp/browser/*.png`); they print the
//! frame time they measure (no assertion on time: benchmarks hold speed).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

mod webdriver;

use base64::Engine;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use webdriver::Browser;

/// One browser at a time.
static ONE: Mutex<()> = Mutex::new(());

fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    ONE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn shots() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("browser");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn vcnc(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .current_dir(workspace())
        .output()
        .unwrap()
}

/// Plots `program` (text) to `name.html` with `extra` options; the page.
fn page_of(name: &str, program: &str, extra: &[&str]) -> PathBuf {
    let dir = shots();
    let prog = dir.join(format!("{name}.nc"));
    std::fs::write(&prog, program).unwrap();
    let page = dir.join(format!("{name}.html"));
    let mut args = vec!["plot", prog.to_str().unwrap(), "-o", page.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = vcnc(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    page
}

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

fn browser() -> Browser {
    let (chromium, chromedriver) =
        webdriver::tools().unwrap_or_else(|e| panic!("this test fails: {e}"));
    Browser::start(&chromium, &chromedriver)
}

#[test]
fn the_viewer_page_draws_and_its_slider_follows_the_program() {
    let _one = one_at_a_time();
    let out_dir = shots();
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

    let b = browser();
    b.open(&page);
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
    assert_eq!(b.console_errors(), Vec::<String>::new());
}

/// A 30 × 40 mm rectangle at Z −1 under a G52 shift: work X0 Y0 is machine
/// X100 Y50. Line 4 cuts to work (30, 0), line 5 to (30, 40), line 6 to
/// (0, 40), line 7 back to (0, 0).
const SQUARE: &str = "G52 X100. Y50.\nG0 X0. Y0. Z5.\nG1 Z-1. F600.\nG1 X30.\nG1 Y40.\nG1 X0.\nG1 Y0.\nG0 Z5.\nM30\n";

/// The pointer offset from the canvas's centre (what WebDriver actions
/// take) of a machine point.
fn offset_of(b: &Browser, p: [f64; 3]) -> (i64, i64) {
    let v = b.js(&format!(
        "const r = document.getElementById('gl').getBoundingClientRect(); \
         const s = window.vcnc.screenOf({}, {}, {}); \
         return [s[0] - r.width / 2, s[1] - r.height / 2];",
        p[0], p[1], p[2]
    ));
    // Pixel offsets of a view on the screen: far inside i64.
    #[allow(clippy::cast_possible_truncation)]
    let round = |x: &Value| x.as_f64().unwrap().round() as i64;
    (round(&v[0]), round(&v[1]))
}

fn canvas_origin(b: &Browser) -> Value {
    json!({"element-6066-11e4-a52e-4f735466cecf": b.element("#gl")})
}

/// Moves the pointer over a machine point.
fn point_at(b: &Browser, p: [f64; 3]) {
    let (x, y) = offset_of(b, p);
    b.mouse(
        json!([{"type": "pointerMove", "duration": 0, "origin": canvas_origin(b), "x": x, "y": y}]),
    );
}

/// Clicks at a machine point.
fn click_at(b: &Browser, p: [f64; 3]) {
    let (x, y) = offset_of(b, p);
    b.mouse(json!([
        {"type": "pointerMove", "duration": 0, "origin": canvas_origin(b), "x": x, "y": y},
        {"type": "pointerDown", "button": 0},
        {"type": "pointerUp", "button": 0}]));
    std::thread::sleep(Duration::from_millis(100));
}

/// The numbers after `X `, `Y ` and `Z ` on the readout's line that starts
/// with `label`.
fn readout(tip: &str, label: &str) -> [f64; 3] {
    let line = tip
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no {label} in {tip}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let after = |axis: &str| -> f64 {
        let i = words.iter().position(|w| *w == axis).unwrap();
        words[i + 1].parse().unwrap()
    };
    [after("X"), after("Y"), after("Z")]
}

/// The hover readout's text, once it shows.
fn tip_text(b: &Browser) -> String {
    let t0 = Instant::now();
    loop {
        let v = b.js(
            "const t = document.getElementById('tip'); return t.hidden ? null : t.textContent;",
        );
        if let Some(s) = v.as_str() {
            return s.to_string();
        }
        assert!(t0.elapsed() < Duration::from_secs(5), "no readout");
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// How many pixels of the canvas within `r` px of a CSS point are within
/// 60 of `rgb`.
fn pixels_near(b: &Browser, at: (f64, f64), r: i64, rgb: [u8; 3]) -> u64 {
    b.js(&format!(
        "const c = document.getElementById('gl'), k = c.width / c.clientWidth; \
         const t = document.createElement('canvas'); t.width = c.width; t.height = c.height; \
         const g = t.getContext('2d'); g.drawImage(c, 0, 0); \
         const x0 = Math.round(({x} - {r}) * k), y0 = Math.round(({y} - {r}) * k), n = Math.round(2 * {r} * k); \
         const d = g.getImageData(x0, y0, n, n).data; let hits = 0; \
         for (let i = 0; i < d.length; i += 4) \
           if (Math.abs(d[i] - {cr}) + Math.abs(d[i+1] - {cg}) + Math.abs(d[i+2] - {cb}) < 60) hits++; \
         return hits;",
        x = at.0,
        y = at.1,
        cr = rgb[0],
        cg = rgb[1],
        cb = rgb[2]
    ))
    .as_u64()
    .unwrap()
}

/// The measure tool's report between two machine points it is clicked at.
fn measure(b: &Browser, from: [f64; 3], to: [f64; 3]) -> String {
    b.post(
        &format!("/element/{}/click", b.element("#measure")),
        &json!({}),
    );
    click_at(b, from);
    click_at(b, to);
    b.js("return document.getElementById('measureOut').textContent;")
        .as_str()
        .unwrap()
        .to_string()
}

fn screen_of(b: &Browser, p: [f64; 3]) -> (f64, f64) {
    let v = b.js(&format!(
        "return window.vcnc.screenOf({}, {}, {});",
        p[0], p[1], p[2]
    ));
    (v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}

#[test]
fn clicks_select_lines_the_pointer_reads_positions_and_the_measure_tool_measures() {
    let _one = one_at_a_time();
    let page = page_of("square", SQUARE, &["--view", "xy"]);
    let b = browser();
    b.open(&page);
    // --view xy: the page opens looking down Z (screen right X, up Y).
    assert_eq!(
        b.js("return window.vcnc.view();"),
        json!([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    );

    // A click on the middle of the cut to work X30 (machine 115, 50, −1)
    // selects line 4 in the program text.
    click_at(&b, [115.0, 50.0, -1.0]);
    assert_eq!(
        b.js("return window.vcnc.selected();"),
        json!({"file": 0, "line": 4})
    );
    let sel = b.js("const d = document.querySelector('#lines .ln.sel'); return [Number(d.dataset.line), d.textContent];");
    assert_eq!(sel[0], 4);
    assert!(sel[1].as_str().unwrap().ends_with("G1 X30."), "{sel}");

    // The reverse: a click on line 6 lights its segment (work (30, 40) to
    // (0, 40): machine Y 90) in the selection colour.
    let line6 = b.element("#lines .ln[data-line='6']");
    b.post(&format!("/element/{line6}/click"), &json!({}));
    assert_eq!(
        b.js("return window.vcnc.selected();"),
        json!({"file": 0, "line": 6})
    );
    wait_frame(&b);
    let on_line6 = pixels_near(&b, screen_of(&b, [115.0, 90.0, -1.0]), 3, [230, 0, 200]);
    let on_line4 = pixels_near(&b, screen_of(&b, [115.0, 50.0, -1.0]), 3, [230, 0, 200]);
    assert!(on_line6 > 3 && on_line4 == 0, "{on_line6} {on_line4}");
    b.screenshot(&shots().join("select.png"));

    // Hover over the middle of line 5's cut, work (30, 20, −1): the readout
    // names the line and the point in both frames.
    point_at(&b, [130.0, 70.0, -1.0]);
    let tip = tip_text(&b);
    assert!(tip.starts_with("line 5: G1 Y40."), "{tip}");
    let work = readout(&tip, "work");
    let machine = readout(&tip, "machine");
    // The pointer lands on a whole pixel (about 0.05 mm here).
    assert_eq!([work[0], work[2]], [30.0, -1.0], "{tip}");
    assert!((work[1] - 20.0).abs() < 0.2, "{tip}");
    assert_eq!([machine[0], machine[2]], [130.0, -1.0], "{tip}");
    assert!((machine[1] - 70.0).abs() < 0.2, "{tip}");
    assert!(tip.contains("F 600 mm/min"), "{tip}");
    b.screenshot(&shots().join("hover.png"));

    // Measure from work (0, 0) to (30, 40): 50 mm, ΔX 30, ΔY 40.
    let out = measure(&b, [100.0, 50.0, -1.0], [130.0, 90.0, -1.0]);
    assert!(
        out.starts_with("distance 50.000 mm\nΔX 30.000  ΔY 40.000  ΔZ 0.000"),
        "{out}"
    );
    b.screenshot(&shots().join("measure.png"));
    assert_eq!(b.console_errors(), Vec::<String>::new());
}

#[test]
fn playback_at_x10_takes_a_tenth_of_the_planned_time() {
    let _one = one_at_a_time();
    let page = page_of("square_play", SQUARE, &[]);
    // The page's total is the planner's, as `vcnc time` prints it.
    let prog = shots().join("square_play.nc");
    let o = vcnc(&["time", prog.to_str().unwrap(), "--format", "json"]);
    let time: Value = serde_json::from_slice(&o.stdout).unwrap();
    let planned = time["total_s"].as_f64().unwrap();
    assert!(planned > 10.0, "{time}");
    let b = browser();
    b.open(&page);
    let total = b.js("return window.vcnc.totalTime;").as_f64().unwrap();
    assert!((total - planned).abs() < 0.01, "{total} {planned}");

    let ten = b.element("#speed option[value='10']");
    b.post(&format!("/element/{ten}/click"), &json!({}));
    let scrub = b.element("#scrub");
    b.post(
        &format!("/element/{scrub}/value"),
        &json!({"text": "\u{E011}"}),
    );
    assert_eq!(b.js("return window.vcnc.time();"), json!(0));
    b.post(
        &format!("/element/{}/click", b.element("#play")),
        &json!({}),
    );
    let t0 = Instant::now();
    std::thread::sleep(Duration::from_secs_f64(planned / 20.0));
    let half = b.js("return window.vcnc.time();").as_f64().unwrap();
    b.screenshot(&shots().join("playback.png"));
    while b.js("return window.vcnc.playing();") == json!(true) {
        assert!(
            t0.elapsed() < Duration::from_secs(30),
            "playback never ended"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    let stats = b.js("return window.vcnc.playStats;");
    let took = (stats["ended"].as_f64().unwrap() - stats["started"].as_f64().unwrap()) / 1000.0;
    println!("×10 playback of {planned:.2} s took {took:.3} s");
    assert_eq!(stats["speed"], 10);
    assert!(
        took >= planned / 10.0 - 0.05 && took <= planned / 10.0 + 0.5,
        "{took} s for {planned} s"
    );
    // Half-way in wall time, about half-way in planned time.
    assert!(
        half > planned * 0.3 && half < planned * 0.8,
        "{half} of {planned}"
    );
    assert_eq!(
        b.js("return window.vcnc.index() === window.vcnc.count() - 1;"),
        json!(true)
    );
    assert_eq!(b.console_errors(), Vec::<String>::new());
}

#[test]
fn a_lathe_shows_its_section_a_mesh_its_toggle_and_inches_their_unit() {
    let _one = one_at_a_time();
    let dir = shots();
    let lathe = dir.join("lathe.html");
    let o = vcnc(&[
        "plot",
        "examples/fanuc-lathe/01_od_rough_finish.nc",
        "--dialect",
        "fanuc-lathe",
        "-o",
        lathe.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let b = browser();
    b.open(&lathe);
    // The section only: no top, side or iso view; Z across, X up.
    assert_eq!(
        b.js("return [document.getElementById('views').hidden, document.getElementById('latheViews').hidden];"),
        json!([true, false])
    );
    let section = json!([[0, 0, 1], [1, 0, 0], [0, 1, 0]]);
    assert_eq!(b.js("return window.vcnc.view();"), section);
    // A drag pans the section: the picture moves, the view does not turn.
    let before = picture(&b);
    b.mouse(json!([
        {"type": "pointerMove", "duration": 0, "origin": canvas_origin(&b), "x": 0, "y": 0},
        {"type": "pointerDown", "button": 0},
        {"type": "pointerMove", "duration": 200, "origin": "pointer", "x": 80, "y": 30},
        {"type": "pointerUp", "button": 0}]));
    wait_frame(&b);
    assert_ne!(picture(&b), before, "the drag moved the picture");
    assert_eq!(b.js("return window.vcnc.view();"), section);
    b.screenshot(&dir.join("lathe.png"));
    assert_eq!(b.console_errors(), Vec::<String>::new());

    // The material-removal hook: a mesh given to the page is drawn, with a
    // toggle that hides it.
    let mesh_page = dir.join("mesh.html");
    write_mesh_page(&mesh_page);
    b.open(&mesh_page);
    let orange = |b: &Browser| {
        b.js("const c = document.getElementById('gl'); \
              const t = document.createElement('canvas'); t.width = c.width; t.height = c.height; \
              const g = t.getContext('2d'); g.drawImage(c, 0, 0); \
              const d = g.getImageData(0, 0, t.width, t.height).data; let n = 0; \
              for (let i = 0; i < d.length; i += 4) if (d[i] > d[i+1] + 40 && d[i+1] > d[i+2] + 20) n++; \
              return n;")
            .as_u64()
            .unwrap()
    };
    let shown = orange(&b);
    b.screenshot(&dir.join("mesh.png"));
    let toggle = b.element("#meshToggles input");
    b.post(&format!("/element/{toggle}/click"), &json!({}));
    wait_frame(&b);
    let hidden = orange(&b);
    assert!(shown > 5000 && hidden < 50, "{shown} {hidden}");
    assert_eq!(b.console_errors(), Vec::<String>::new());

    // --units in: the readout and the measure in inches (30 mm = 1.1811 in).
    let inch = page_of("square_inch", SQUARE, &["--view", "xy", "--units", "in"]);
    b.open(&inch);
    point_at(&b, [130.0, 70.0, -1.0]);
    let tip = tip_text(&b);
    let work = readout(&tip, "work");
    assert_eq!([work[0], work[2]], [1.1811, -0.0394], "{tip}");
    let out = measure(&b, [100.0, 50.0, -1.0], [130.0, 90.0, -1.0]);
    assert!(out.starts_with("distance 1.9685 in"), "{out}");
    b.screenshot(&dir.join("inch.png"));
    assert_eq!(b.console_errors(), Vec::<String>::new());

    // Under G68 R90 the work coordinates are the program's: the cut of
    // line 6 from program (30, 0) to (30, 40) runs in the machine from
    // (100, 80) to (60, 80) (rotated a quarter turn about work zero, which
    // G52 puts at machine (100, 50)); its middle, program (30, 20), is
    // machine (80, 80).
    let turned = page_of(
        "rotated",
        "G52 X100. Y50.\nG68 X0 Y0 R90.\nG0 X0. Y0. Z5.\nG1 Z-1. F600.\nG1 X30.\nG1 Y40.\nM30\n",
        &["--view", "xy"],
    );
    b.open(&turned);
    point_at(&b, [80.0, 80.0, -1.0]);
    let tip = tip_text(&b);
    assert!(tip.starts_with("line 6: G1 Y40."), "{tip}");
    let work = readout(&tip, "work");
    let machine = readout(&tip, "machine");
    assert_eq!([work[0], work[2]], [30.0, -1.0], "{tip}");
    assert!((work[1] - 20.0).abs() < 0.2, "{tip}");
    assert_eq!([machine[1], machine[2]], [80.0, -1.0], "{tip}");
    assert!((machine[0] - 80.0).abs() < 0.2, "{tip}");
    // The page writes times as vcnc_core::display::duration does.
    assert_eq!(
        b.js("return [59.96, 3599.96, 61.24, 0.04].map(window.vcnc.fmtTime);"),
        json!(["1m 00.0s", "1h 00m 00.0s", "1m 01.2s", "0.0s"])
    );
    assert_eq!(b.console_errors(), Vec::<String>::new());
}

/// Pixels of the canvas whose colour passes `test` (a JS expression of
/// `r`, `g`, `b`).
fn pixels_where(b: &Browser, test: &str) -> u64 {
    b.js(&format!(
        "const c = document.getElementById('gl'); \
         const t = document.createElement('canvas'); t.width = c.width; t.height = c.height; \
         const g2 = t.getContext('2d'); g2.drawImage(c, 0, 0); \
         const d = g2.getImageData(0, 0, t.width, t.height).data; let n = 0; \
         for (let i = 0; i < d.length; i += 4) {{ const r = d[i], g = d[i+1], b = d[i+2]; if ({test}) n++; }} \
         return n;"
    ))
    .as_u64()
    .unwrap()
}

/// Clicks the mesh toggle labelled `name`.
fn toggle_mesh(b: &Browser, name: &str) {
    let labels = b.js("return [...document.querySelectorAll('#meshToggles label')].map((l) => l.textContent.trim());");
    let k = labels
        .as_array()
        .unwrap()
        .iter()
        .position(|l| l == name)
        .unwrap_or_else(|| panic!("no toggle {name}: {labels}"));
    let toggle = b.element(&format!("#meshToggles label:nth-of-type({}) input", k + 1));
    b.post(&format!("/element/{toggle}/click"), &json!({}));
    wait_frame(b);
}

/// A 30 × 20 pocket 4 mm deep with a 10 mm end mill (a Fusion header
/// describes it), in a block the page is asked to simulate.
const POCKET: &str = "(T1 D=10. CR=0. - ZMIN=-4. - flat end mill)\nG21 G90 G17\nT1 M06\n\
    G00 X0. Y0. Z5.\nG01 Z-4. F300\nG01 X30.\nG01 Y20.\nG01 X0.\nG01 Y0.\nG01 X30. Y20.\n\
    G00 Z5.\nM30\n";

#[test]
fn plot_with_a_stock_shows_the_stock_and_the_finished_part_as_toggles() {
    let _one = one_at_a_time();
    let dir = shots();
    let page = page_of(
        "stock",
        POCKET,
        &["--stock", "box:-10,-10,-10,40,30,0", "--view", "iso"],
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(
        html.contains("\"name\":\"stock\""),
        "the stock mesh is in the page"
    );
    assert!(html.contains("\"name\":\"finished part\""));
    let b = browser();
    b.open(&page);
    wait_frame(&b);
    let labels = b.js("return [...document.querySelectorAll('#meshToggles label')].map((l) => [l.textContent.trim(), l.querySelector('input').checked]);");
    assert_eq!(labels, json!([["stock", false], ["finished part", true]]));
    // The legend says what was simulated.
    let legend = b.js("return document.body.innerText;");
    assert!(
        legend.as_str().unwrap().contains("removed"),
        "the legend's material row: {legend}"
    );
    // The part (orange, 215 150 70 shaded) shows; the stock (grey-blue,
    // 150 165 185) does not yet.
    let part = "r > g + 40 && g > b + 20";
    let stock = "b > r + 8 && g > r + 3 && b > g + 3 && b - r < 60";
    let (part_shown, stock_hidden) = (pixels_where(&b, part), pixels_where(&b, stock));
    b.screenshot(&dir.join("stock_part.png"));
    toggle_mesh(&b, "finished part");
    let part_hidden = pixels_where(&b, part);
    toggle_mesh(&b, "stock");
    let stock_shown = pixels_where(&b, stock);
    b.screenshot(&dir.join("stock_block.png"));
    assert!(
        part_shown > 5000 && part_hidden < part_shown / 20,
        "part {part_shown} → {part_hidden}"
    );
    assert!(
        stock_shown > 5000 && stock_hidden < stock_shown / 20,
        "stock {stock_hidden} → {stock_shown}"
    );
    assert_eq!(b.console_errors(), Vec::<String>::new());

    // Without --stock the page is as it was: no meshes, no toggles.
    let plain = page_of("no_stock", POCKET, &["--view", "iso"]);
    let html = std::fs::read_to_string(&plain).unwrap();
    assert!(html.contains(",\"meshes\":[]"));
    b.open(&plain);
    assert_eq!(
        b.js("return document.querySelectorAll('#meshToggles input').length;"),
        json!(0)
    );
    assert_eq!(b.console_errors(), Vec::<String>::new());
}

/// A page of a short cut along X with a 20 mm cube mesh ("stock") under it.
fn write_mesh_page(path: &Path) {
    use vcnc_core::{Event, Feed, Loc, Machine, Pos, Sink};
    use vcnc_plot::{
        ColorBy, FitTo, Legend, Mesh, Page, PlotOptions, PlotSink, Rgb, Space, Theme, View,
    };
    let m = Machine::default_mill();
    let options = PlotOptions {
        space: Space::Volume { resolution: 2048.0 },
        color: ColorBy::Depth,
        max_vertices: 1 << 12,
        max_marks: 100,
        fit: FitTo::All,
    };
    let mut sink = PlotSink::new(&m, options);
    for (line, x) in [(1u64, 0.0), (2, 20.0)] {
        sink.event(&Event::Feed {
            loc: Loc { line, file: None },
            to: Pos([x, 0.0, 20.0, 0.0, 0.0, 0.0]),
            feed: Feed::PerMin(500.0),
            exact_stop: false,
        });
    }
    let plot = sink.into_plot();
    let c = |k: u32| [0, 1, 2].map(|i| if k >> i & 1 == 1 { 20.0 } else { 0.0 });
    let positions: Vec<[f64; 3]> = (0..8).map(c).collect();
    // Two triangles a face, counter-clockwise seen from outside.
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let triangles = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mesh = Mesh {
        name: "stock".into(),
        color: Rgb(230, 140, 40),
        visible: true,
        positions,
        triangles,
    };
    let legend = Legend::default();
    let page = Page {
        theme: Theme::Light,
        color: ColorBy::Depth,
        lathe: false,
        view: View::Iso,
        fit: FitTo::All,
        rapids: true,
        units: vcnc_core::display::DisplayUnits::Mm,
        legend: &legend,
        time_label: "none",
        sources: &[],
        tools: None,
        meshes: std::slice::from_ref(&mesh),
    };
    let mut out = Vec::new();
    vcnc_plot::write_html(&plot, None, &page, &mut out).unwrap();
    std::fs::write(path, out).unwrap();
}
