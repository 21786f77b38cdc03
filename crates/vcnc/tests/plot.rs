//! `vcnc plot`: SVG snapshots of the manual's example programs, each also
//! checked against the manual's figure, and the bad inputs.
//!
//! How a snapshot was reviewed: the manual's figures give the points of
//! each example (seed 000, sections 1.2.2, 1.2.18, 1.2.20, 1.2.21, 1.2.47).
//! Each test reads the drawn points back out of the SVG — the cut paths'
//! `M`/`L`/`A` end points, or the hole marks' centres — and checks that
//! they are the figure's points under one uniform scale with Y up (to the
//! 0.01 px the writer rounds to), and, for arcs, the direction of each
//! SVG arc against the G02/G03 of its block. The snapshot then holds the
//! rest of the picture (legend, ticks, marks) so that any change shows in
//! review; the PNG renders of the same programs were looked at when the
//! snapshots were accepted.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

/// A fresh directory, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        static N: AtomicUsize = AtomicUsize::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("vcnc-plot-{}-{n}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }
    fn file(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn vcnc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .current_dir(workspace())
        .env("NO_COLOR", "1")
        .output()
        .expect("vcnc runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Plots a workspace program to SVG; returns the SVG.
fn svg_of(program: &str, extra: &[&str]) -> String {
    let dir = TempDir::new("svg");
    let out = dir.file("out.svg");
    let mut args = vec!["plot", program, "-o", out.to_str().unwrap()];
    args.extend_from_slice(extra);
    let o = vcnc(&args);
    assert_eq!(o.status.code(), Some(0), "stderr: {}", stderr(&o));
    std::fs::read_to_string(&out).unwrap()
}

/// The value of `name="…"` in an SVG element.
fn attr<'a>(line: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = line.find(&key)? + key.len();
    let end = line[start..].find('"')? + start;
    Some(&line[start..end])
}

/// One drawn piece: its end point and, for an arc, the SVG sweep flag.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    to: [f64; 2],
    sweep: Option<u8>,
}

/// The pieces of every `<path>` whose stroke width is `width` and that lies
/// left of the legend panel, in order; each path starts with a move.
fn paths(svg: &str, width: &str, dashed: bool) -> Vec<Vec<Piece>> {
    let mut out = Vec::new();
    for line in svg.lines().filter(|l| l.starts_with("<path ")) {
        if attr(line, "stroke-width") != Some(width)
            || attr(line, "stroke-dasharray").is_some() != dashed
        {
            continue;
        }
        let d = attr(line, "d").unwrap();
        let mut pieces = Vec::new();
        let mut rest = d;
        while let Some(c) = rest.chars().next() {
            let end = rest[1..]
                .find(['M', 'L', 'A'])
                .map_or(rest.len(), |i| i + 1);
            let nums: Vec<f64> = rest[1..end]
                .split([' ', ','])
                .filter(|s| !s.is_empty())
                .map(|s| s.parse().unwrap())
                .collect();
            let n = nums.len();
            pieces.push(Piece {
                to: [nums[n - 2], nums[n - 1]],
                sweep: (c == 'A').then(|| u8::from(nums[4] > 0.5)),
            });
            rest = &rest[end..];
        }
        if pieces.iter().all(|p| p.to[0] < 900.0) {
            out.push(pieces);
        }
    }
    out
}

/// Checks that screen points are the plot points `mm` (x, y in mm) under
/// one map `x = x0 + s·u`, `y = y0 − s·v`, fitted on the first point and
/// the farthest one.
fn assert_figure(screen: &[[f64; 2]], mm: &[[f64; 2]]) {
    assert_eq!(screen.len(), mm.len(), "points drawn: {screen:?}");
    let far = (1..mm.len())
        .max_by(|a, b| {
            let d = |i: usize| (mm[i][0] - mm[0][0]).hypot(mm[i][1] - mm[0][1]);
            d(*a).total_cmp(&d(*b))
        })
        .unwrap();
    let s = (screen[far][0] - screen[0][0]).hypot(screen[far][1] - screen[0][1])
        / (mm[far][0] - mm[0][0]).hypot(mm[far][1] - mm[0][1]);
    let (x0, y0) = (screen[0][0] - s * mm[0][0], screen[0][1] + s * mm[0][1]);
    for (p, q) in screen.iter().zip(mm) {
        let want = [x0 + s * q[0], y0 - s * q[1]];
        assert!(
            (p[0] - want[0]).abs() < 0.02 && (p[1] - want[1]).abs() < 0.02,
            "point {q:?} mm is drawn at {p:?}, the figure puts it at {want:?}"
        );
    }
}

fn ends(pieces: &[Piece]) -> Vec<[f64; 2]> {
    pieces.iter().map(|p| p.to).collect()
}

/// 1.2.2 example 2: the profile P0(0,0) P1(0,38) P2(20,45) P3(55,45)
/// P4(55,10) P5(45,0) back to P0, cut at Z-10 (one colour: one depth); the
/// rapids to and from Z10 above P0 are invisible from the top. Absolute
/// and incremental programs draw the same picture.
#[test]
fn svg_of_manual_1_2_2_g01_profile() {
    let svg = svg_of("tests/fixtures/manual/1.2.2_g01_ex2_absolute.nc", &[]);
    let cuts = paths(&svg, "1.5", false);
    assert_eq!(cuts.len(), 1, "one cut path");
    assert_figure(
        &ends(&cuts[0]),
        &[
            [0.0, 0.0],
            [0.0, 38.0],
            [20.0, 45.0],
            [55.0, 45.0],
            [55.0, 10.0],
            [45.0, 0.0],
            [0.0, 0.0],
        ],
    );
    let incremental = svg_of("tests/fixtures/manual/1.2.2_g01_ex2_incremental.nc", &[]);
    assert_eq!(paths(&incremental, "1.5", false), cuts);
    insta::assert_snapshot!(svg);
}

/// 1.2.18 program example: the programmed contour (dashed, thin) is the
/// figure's eight-arc outline A(0,24) B(9,30) C(30,9) D(30,-9) E(9,-30)
/// F(-9,-30) G(-30,-9) H(-30,9) M(-9,30) back to A, the arcs alternating
/// G03 (counter-clockwise: SVG sweep 0 with Y up) and G02 (sweep 1); the
/// tool centre (solid) runs 5 mm inside it (G42 on a clockwise outline),
/// with the same alternation.
#[test]
fn svg_of_manual_1_2_18_cutter_compensation() {
    // D01 = 5 mm, as the manual's example says: the built-in mill's offset
    // memory is empty.
    let svg = svg_of(
        "tests/fixtures/manual/1.2.18_example.nc",
        &["--machine", "tests/fixtures/machines/mill_tools.toml"],
    );
    let contour = paths(&svg, "1", true)
        .into_iter()
        .filter(|p| p.len() > 2)
        .collect::<Vec<_>>();
    assert_eq!(contour.len(), 1, "one programmed contour");
    let outline = &contour[0];
    // The contour starts at the program zero, then A, then the arcs.
    let arcs: Vec<Piece> = outline
        .iter()
        .copied()
        .filter(|p| p.sweep.is_some())
        .collect();
    assert_eq!(
        arcs.iter().map(|p| p.sweep.unwrap()).collect::<Vec<_>>(),
        vec![0, 1, 0, 1, 0, 1, 0, 1, 0],
        "G03 G02 G03 … as programmed"
    );
    let mut pts = vec![outline[1].to];
    pts.extend(ends(&arcs));
    assert_figure(
        &pts,
        &[
            [0.0, 24.0],
            [9.0, 30.0],
            [30.0, 9.0],
            [30.0, -9.0],
            [9.0, -30.0],
            [-9.0, -30.0],
            [-30.0, -9.0],
            [-30.0, 9.0],
            [-9.0, 30.0],
            [0.0, 24.0],
        ],
    );
    let centre: Vec<Piece> = paths(&svg, "1.5", false).concat();
    let centre_arcs: Vec<u8> = centre.iter().filter_map(|p| p.sweep).collect();
    assert_eq!(centre_arcs, vec![0, 1, 0, 1, 0, 1, 0, 1, 0]);
    insta::assert_snapshot!(svg);
}

/// 1.2.20: G51 scales by 0.5 about (125, 90): the figure's program path
/// (50,70) (100,150) arc to (150,150) (200,70) (200,50) (50,50) is drawn
/// at half size towards the centre — (87.5,80) (112.5,120) a G03 half
/// circle of radius 12.5 dipping down to (137.5,120), (162.5,80)
/// (162.5,70) (87.5,70) — after the rapid to (50,50), which G51 leaves.
#[test]
fn svg_of_manual_1_2_20_scaling() {
    let svg = svg_of("tests/fixtures/manual/1.2.20_g51_scaling.nc", &[]);
    let cuts = paths(&svg, "1.5", false);
    assert_eq!(cuts.len(), 1);
    let arcs: Vec<u8> = cuts[0].iter().filter_map(|p| p.sweep).collect();
    assert_eq!(arcs, vec![0], "one G03");
    assert_figure(
        &ends(&cuts[0]),
        &[
            [50.0, 50.0],
            [87.5, 80.0],
            [112.5, 120.0],
            [137.5, 120.0],
            [162.5, 80.0],
            [162.5, 70.0],
            [87.5, 70.0],
        ],
    );
    insta::assert_snapshot!(svg);
}

/// 1.2.21 example 1: the subprogram's shape O(60,75) A(80,75) B(120,75)
/// C(120,105) D(80,95) back to A, then mirrored about X=60 and about
/// Y=55: the figure's (80,35) (120,35) (120,5) (80,15). (The figure prints
/// the X-mirror's far corners as (10,75) and (10,105); mirroring 120 about
/// 60 gives 0, which is what the controller cuts and what is drawn.)
#[test]
fn svg_of_manual_1_2_21_mirror() {
    let svg = svg_of("tests/fixtures/manual/1.2.21_mirror_ex1.nc", &[]);
    let cuts = paths(&svg, "1.5", false);
    assert_eq!(cuts.len(), 3, "three copies of the shape");
    let mut screen = Vec::new();
    for c in &cuts {
        screen.extend(ends(c));
    }
    // O→A→B is one straight line: A merges away (it changes nothing drawn).
    let shape = [
        [60.0, 55.0],
        [60.0, 75.0],
        [120.0, 75.0],
        [120.0, 105.0],
        [80.0, 95.0],
        [80.0, 75.0],
    ];
    let mut mm = shape.to_vec();
    mm.extend(shape.iter().map(|p| [120.0 - p[0], p[1]]));
    mm.extend(shape.iter().map(|p| [p[0], 110.0 - p[1]]));
    // Each copy's cut starts where its positioning rapid ended, at (60,55).
    assert_figure(&screen, &mm);
    insta::assert_snapshot!(svg);
}

/// 1.2.47: G134 drills 6 holes on a circle of r=100 about X200 Y100 (G91
/// from the G92 point, so machine X200 Y100), the first at 20°, then every
/// 60° counter-clockwise; the hole marks sit there, in that order.
#[test]
fn svg_of_manual_1_2_47_circle_of_holes() {
    let svg = svg_of("tests/fixtures/manual/1.2.47_g134.nc", &[]);
    let centres: Vec<[f64; 2]> = svg
        .lines()
        .filter(|l| l.starts_with("<circle ") && attr(l, "r") == Some("4"))
        .map(|l| {
            [
                attr(l, "cx").unwrap().parse().unwrap(),
                attr(l, "cy").unwrap().parse().unwrap(),
            ]
        })
        .filter(|c: &[f64; 2]| c[0] < 900.0)
        .collect();
    let mm: Vec<[f64; 2]> = (0..6)
        .map(|k| {
            let a = (20.0 + 60.0 * f64::from(k)).to_radians();
            [200.0 + 100.0 * a.cos(), 100.0 + 100.0 * a.sin()]
        })
        .collect();
    assert_figure(&centres, &mm);
    assert!(svg.contains(">holes (6)</text>"), "the legend counts them");
    insta::assert_snapshot!(svg);
}

#[test]
fn svg_is_byte_identical_run_to_run() {
    let a = svg_of(
        "tests/fixtures/manual/1.2.18_example.nc",
        &["--theme", "dark", "--view", "iso"],
    );
    let b = svg_of(
        "tests/fixtures/manual/1.2.18_example.nc",
        &["--theme", "dark", "--view", "iso"],
    );
    assert_eq!(a, b);
    assert!(a.contains("fill=\"#12141a\""), "dark background");
}

/// A lathe program is drawn as the XZ half-section: Z across, the
/// diameter axis up, labelled in diameters (the events carry radii).
#[test]
fn a_lathe_program_defaults_to_the_half_section() {
    let svg = svg_of(
        "tests/fixtures/lathe/g01_example.nc",
        &["--dialect", "lathe"],
    );
    assert!(svg.contains("view XZ half-section (lathe)"), "{svg}");
    assert!(svg.contains(">X diameter, mm</text>"));
    // G01 X40 Z20 from X80 Z60: diameter 80 → 40 is radius 40 → 20.
    let cuts = paths(&svg, "1.5", false);
    assert_figure(&ends(&cuts[0]), &[[60.0, 40.0], [20.0, 20.0]]);
}

/// A program that alarms half-way: the plot is written with the path up
/// to the alarm, the alarm is marked and printed, and the exit code is 1.
#[test]
fn a_program_that_alarms_half_way_is_plotted_up_to_the_alarm() {
    let dir = TempDir::new("alarm");
    let prog = dir.write(
        "half.nc",
        "G90 G01 X10. Y0 F500.\nX10. Y10.\nG03 X0 Y20. I-3. J-1.\nX50. Y50.\nM30\n",
    );
    for ext in ["svg", "png", "html"] {
        let out = dir.file(&format!("half.{ext}"));
        let o = vcnc(&["plot", prog.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(1), "{ext}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains("error[E303]"), "{err}");
        assert!(
            err.contains("the plot shows the path up to the alarm"),
            "{err}"
        );
        assert!(
            std::fs::metadata(&out).unwrap().len() > 1000,
            "{ext} written"
        );
    }
    let svg = std::fs::read_to_string(dir.file("half.svg")).unwrap();
    assert!(
        svg.contains(">E303 line 3</text>"),
        "the alarm mark is labelled"
    );
    let cuts = paths(&svg, "1.5", false);
    assert_eq!(cuts.len(), 1);
    // (0,0) → (10,0) → (10,10): nothing after the alarm.
    assert_figure(&ends(&cuts[0]), &[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]);
}

#[test]
fn an_unreadable_program_is_a_usage_error() {
    let dir = TempDir::new("unreadable");
    let out = dir.file("x.svg");
    let o = vcnc(&["plot", "no/such/file.nc", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).starts_with("error: cannot open no/such/file.nc"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists(), "nothing written");
    let o = vcnc(&["plot", "tests", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o), "error: tests is a directory\n");
}

#[test]
fn an_empty_program_plots_its_start_point_and_says_so() {
    let dir = TempDir::new("empty");
    let prog = dir.write("empty.nc", "");
    let out = dir.file("empty.png");
    let o = vcnc(&["plot", prog.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("has no motion: the plot shows only the start point"),
        "{}",
        stderr(&o)
    );
    let png = std::fs::read(&out).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn an_output_of_unknown_kind_or_place_is_a_usage_error() {
    let o = vcnc(&["plot", "examples/bracket.nc", "-o", "out.txt"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("name the output .svg, .png or .html"),
        "{}",
        stderr(&o)
    );
    let o = vcnc(&["plot", "examples/bracket.nc", "-o", "/no/such/dir/out.svg"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).starts_with("error: cannot write /no/such/dir/out.svg"),
        "{}",
        stderr(&o)
    );
    let o = vcnc(&[
        "plot",
        "examples/bracket.nc",
        "-o",
        "x.svg",
        "--size",
        "10x10",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

/// The page carries everything it shows: the program text (base64), the
/// path, the compared program's path; it loads nothing from elsewhere.
#[test]
fn the_page_is_self_contained_and_overlays_the_compared_program() {
    let dir = TempDir::new("html");
    let out = dir.file("p.html");
    let o = vcnc(&[
        "plot",
        "tests/fixtures/manual/1.2.2_g01_ex2_absolute.nc",
        "-o",
        out.to_str().unwrap(),
        "--compare",
        "tests/fixtures/manual/1.2.2_g01_ex2_incremental.nc",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let html = std::fs::read_to_string(&out).unwrap();
    for bad in ["http://", "https://", " src=\"", "<link", "@import"] {
        assert!(!html.contains(bad), "the page refers to {bad}");
    }
    assert!(
        html.contains("\"compareName\":\"tests/fixtures/manual/1.2.2_g01_ex2_incremental.nc\"")
    );
    let text =
        std::fs::read(workspace().join("tests/fixtures/manual/1.2.2_g01_ex2_absolute.nc")).unwrap();
    let b64 = base64_of(&text);
    assert!(html.contains(&format!("id=\"vcnc-src-0\">{b64}</script>")));
}

/// Plain base64 (RFC 4648, padded), written here so that the test does not
/// share the writer's encoder.
fn base64_of(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(char::from(A[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// The page's data object of a workspace program (or a written one).
fn page_data(program: &Path) -> (Option<i32>, serde_json::Value) {
    let dir = TempDir::new("data");
    let out = dir.file("p.html");
    let o = vcnc(&[
        "plot",
        program.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let html = std::fs::read_to_string(&out).unwrap();
    let start = html.find("id=\"vcnc-data\">").unwrap() + "id=\"vcnc-data\">".len();
    let end = start + html[start..].find("</script>").unwrap();
    (
        o.status.code(),
        serde_json::from_str(&html[start..end]).expect("the page's data is JSON"),
    )
}

/// The page carries the marks: the six holes of 1.2.47 and its G92 work
/// origin (machine -500, -100), and the alarm of a program that alarms.
#[test]
fn the_page_carries_holes_origins_and_the_alarm() {
    let (code, d) = page_data(&workspace().join("tests/fixtures/manual/1.2.47_g134.nc"));
    assert_eq!(code, Some(0));
    assert_eq!(d["holeCount"], 6);
    let center = [
        d["center"][0].as_f64().unwrap(),
        d["center"][1].as_f64().unwrap(),
    ];
    let origin = &d["origins"][0][0];
    assert_eq!(
        [
            origin[0].as_f64().unwrap() + center[0],
            origin[1].as_f64().unwrap() + center[1]
        ],
        [-500.0, -100.0]
    );
    assert_eq!(d["alarm"], serde_json::Value::Null);
    let dir = TempDir::new("alarm-page");
    let prog = dir.write("a.nc", "G01 X10. F100.\nG02 X0 Y20. I-3. J-1.\n");
    let (code, d) = page_data(&prog);
    assert_eq!(code, Some(1));
    assert_eq!(d["alarm"]["code"], "E303");
    assert_eq!(d["alarm"]["line"], 2);
}
