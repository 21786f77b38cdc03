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

use crate::common::{TempDir, vcnc, vcnc_fed, workspace};
use std::path::{Path, PathBuf};
use std::process::Output;

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
fn an_empty_program_draws_an_empty_frame_with_a_note() {
    let dir = TempDir::new("empty");
    let prog = dir.write("empty.nc", "");
    for ext in ["png", "svg"] {
        let out = dir.file(&format!("empty.{ext}"));
        let o = vcnc(&["plot", prog.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("has no motion: the plot is an empty frame"),
            "{}",
            stderr(&o)
        );
        let bytes = std::fs::read(&out).unwrap();
        if ext == "png" {
            assert_eq!(&bytes[1..4], b"PNG");
        } else {
            let svg = String::from_utf8(bytes).unwrap();
            assert!(svg.contains(">no motion: the program moves nothing</text>"));
        }
    }
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

#[test]
fn a_stock_goes_on_the_page_only_and_a_bad_one_writes_nothing() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("plot_stock");
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("bracket.svg");
    let o = vcnc(&[
        "plot",
        "examples/bracket.nc",
        "--stock",
        "auto",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("write .html"), "{}", stderr(&o));
    assert!(!svg.exists());
    let page = dir.join("bracket.html");
    let o = vcnc(&[
        "plot",
        "examples/bracket.nc",
        "--stock",
        "box:0,0,0,10,10,0",
        "-o",
        page.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("inverted in Z"),
        "the stock's own message: {}",
        stderr(&o)
    );
    assert!(!page.exists(), "nothing is written");
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
    // A short text travels as it is (a long one deflated, `data-z="1"`).
    assert!(html.contains(&format!("id=\"vcnc-src-0\" data-z=\"0\">{b64}</script>")));
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

/// A pocket cut 500 mm from the tool change: the machine starts at
/// 0, 0, 0, changes the tool there, and cuts a 20 mm square at X500 Y500.
const FAR_POCKET: &str = "G90 G17\nT1 M6\nG0 X500. Y500.\nG0 Z5.\nG1 Z-2. F300.\nG1 X520.\nG1 Y520.\nG1 X500.\nG1 Y500.\nG0 Z50.\nG53 G0 Z0.\nG53 X0. Y0.\nM30\n";

/// Whether a pixel is `color` laid over the white background with some
/// coverage of at least a quarter: each channel must say the same coverage
/// (within 0.08), which a blend of any other colour with white does not.
fn is_blend_of(p: [u8; 3], color: [u8; 3]) -> bool {
    let cover: Vec<f64> = (0..3)
        .map(|k| (255.0 - f64::from(p[k])) / (255.0 - f64::from(color[k])))
        .collect();
    let (lo, hi) = cover
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), c| (a.min(*c), b.max(*c)));
    lo >= 0.25 && hi <= 1.05 && hi - lo <= 0.08
}

/// The bounding box of the pixels drawn in `color` in the plot area (left
/// of the legend panel), as a fraction of the plot area's size. A pixel
/// counts when two of its neighbours match too: a line is continuous,
/// while a stray blend where two marks' edges overlap is not.
fn share_of(png: &[u8], color: [u8; 3]) -> f64 {
    let pm = tiny_skia::Pixmap::decode_png(png).unwrap();
    // The legend panel is 300 px wide; the plot area's margins are 56 px
    // left, 16 right, 24 top and 36 bottom (scene.rs).
    let (x0, x1, y0, y1) = (56, pm.width() - 300 - 16, 24, pm.height() - 36);
    let w = pm.width();
    let hits: Vec<bool> = pm
        .pixels()
        .iter()
        .map(|p| {
            let p = p.demultiply();
            is_blend_of([p.red(), p.green(), p.blue()], color)
        })
        .collect();
    let hit = |x: u32, y: u32| hits[(y * w + x) as usize];
    let mut bx: Option<[u32; 4]> = None;
    for y in y0 + 1..y1 - 1 {
        for x in x0 + 1..x1 - 1 {
            if !hit(x, y) {
                continue;
            }
            let neighbours = (0..9)
                .filter(|k| *k != 4 && hit(x + k % 3 - 1, y + k / 3 - 1))
                .count();
            if neighbours >= 2 {
                let b = bx.get_or_insert([x, y, x, y]);
                b[0] = b[0].min(x);
                b[1] = b[1].min(y);
                b[2] = b[2].max(x);
                b[3] = b[3].max(y);
            }
        }
    }
    let [a, b, c, d] = bx.expect("cut pixels");
    f64::from((c - a + 1) * (d - b + 1)) / f64::from((x1 - x0) * (y1 - y0))
}

/// The cuts fill the picture, not the machine: with `--fit cuts` (the
/// default) the cut pixels' box fills at least a fifth of the plot area in
/// the XY and iso views; with `--fit all` the same pocket is a speck (the
/// measure can fail).
#[test]
fn a_pocket_far_from_its_tool_change_fills_the_picture() {
    let dir = TempDir::new("far");
    let prog = dir.write("far.nc", FAR_POCKET);
    // One tool, coloured by tool: every cut in the palette's first colour
    // (theme.rs, light), which nothing else in the plot area uses.
    let t1 = [0x1f, 0x77, 0xb4];
    let mut shares = Vec::new();
    for (view, fit) in [
        ("xy", "cuts"),
        ("iso", "cuts"),
        ("xy", "all"),
        ("iso", "all"),
    ] {
        let out = dir.file(&format!("far-{view}-{fit}.png"));
        let o = vcnc(&[
            "plot",
            prog.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--color",
            "tool",
            "--view",
            view,
            "--fit",
            fit,
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let png = std::fs::read(&out).unwrap();
        let shots = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("plot");
        std::fs::create_dir_all(&shots).unwrap();
        std::fs::write(shots.join(format!("far-{view}-{fit}.png")), &png).unwrap();
        shares.push(share_of(&png, t1));
    }
    assert!(shares[0] >= 0.2, "xy: {shares:?}");
    assert!(shares[1] >= 0.2, "iso: {shares:?}");
    assert!(shares[2] < 0.01 && shares[3] < 0.01, "all: {shares:?}");
}

/// Quick look: `vcnc plot FILE` writes FILE's name with `.html` here and
/// says so; `vcnc plot -` reads the program from standard input.
#[test]
fn without_output_the_page_is_written_here_and_standard_input_plots() {
    let dir = TempDir::new("quick");
    let prog = dir.write("far.nc", FAR_POCKET);
    let here = dir.file("here");
    std::fs::create_dir_all(&here).unwrap();
    let o = vcnc_fed(&here, &["plot", prog.to_str().unwrap()], b"");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(String::from_utf8_lossy(&o.stdout), "wrote far.html\n");
    let html = std::fs::read_to_string(here.join("far.html")).unwrap();
    assert!(html.contains("\"files\":[") && html.contains("far.nc"));

    let o = vcnc_fed(&here, &["plot", "-"], FAR_POCKET.as_bytes());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(String::from_utf8_lossy(&o.stdout), "wrote stdin.html\n");
    let html = std::fs::read_to_string(here.join("stdin.html")).unwrap();
    // The text from standard input is in the page.
    assert!(html.contains(&base64_of(FAR_POCKET.as_bytes())));
    let o = vcnc_fed(&here, &["plot", "-", "-o", "in.svg"], FAR_POCKET.as_bytes());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // The legend names the program read from standard input and the
    // dialect detected for it (decimal points, G53: a Fanuc-family mill).
    assert!(
        std::fs::read_to_string(here.join("in.svg"))
            .unwrap()
            .contains("&lt;stdin&gt; (fanuc)")
    );
}

#[test]
fn a_lathe_without_y_has_only_its_half_section() {
    let o = vcnc(&[
        "plot",
        "examples/fanuc-lathe/01_od_rough_finish.nc",
        "--dialect",
        "fanuc-lathe",
        "--view",
        "iso",
        "-o",
        "never.png",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o),
        "error: --view iso: a lathe without a Y axis is drawn as its XZ half-section (--view xz)\n"
    );
    assert!(!workspace().join("never.png").exists());
}

/// `--no-rapids` hides the rapids of a program that cuts; a program of
/// rapids alone still shows them, and says so.
#[test]
fn no_rapids_hides_rapids_unless_there_is_nothing_else() {
    // Rapids are the only dashed 1 px paths (rapid_stroke in scene.rs).
    let dashed = |svg: &str| {
        svg.matches("stroke-width=\"1\" stroke-dasharray=\"4 3\"")
            .count()
    };
    let cuts = svg_of("tests/fixtures/manual/1.2.18_example.nc", &[]);
    assert!(dashed(&cuts) > 0);
    let hidden = svg_of("tests/fixtures/manual/1.2.18_example.nc", &["--no-rapids"]);
    assert_eq!(dashed(&hidden), 0);
    assert!(hidden.contains(">rapids hidden</text>"));
    let dir = TempDir::new("rapids");
    let prog = dir.write("r.nc", "G0 X10. Y10.\nG0 X20.\nM30\n");
    let out = dir.file("r.svg");
    let o = vcnc(&[
        "plot",
        prog.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--no-rapids",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(dashed(&svg) > 0);
    assert!(svg.contains(">every move is a rapid: rapids are drawn although hidden</text>"));
    assert!(svg.contains(">framed on all moves (no cuts)</text>"));
}

/// `--units in`: ticks, axis names and the legend's figures in inches.
#[test]
fn inches_label_the_ticks_and_the_legend() {
    let svg = svg_of(
        "tests/fixtures/manual/1.2.2_g01_ex2_absolute.nc",
        &["--units", "in"],
    );
    assert!(svg.contains(">X in</text>"), "axis name");
    assert!(svg.contains(">extents (machine in)</text>"));
    // 55 mm of X travel is 2.1654 in.
    assert!(svg.contains(">X 0.0000 .. 2.1654</text>"), "{svg}");
    // 13.2 s planned: the time format is the same in either unit.
    assert!(svg.contains(" planned ("));
}

/// A machine file with travel limits on X, Y and Z: `--fit all` frames
/// their box and draws it dotted; the legend names it.
#[test]
fn travel_limits_are_drawn_as_a_box() {
    let dir = TempDir::new("limits");
    let mill = std::fs::read_to_string(workspace().join("crates/vcnc_core/src/default_mill.toml"))
        .unwrap()
        .replacen(
            "letter = \"x\"\n",
            "letter = \"x\"\nmin_mm = -100.0\nmax_mm = 600.0\n",
            1,
        )
        .replacen(
            "letter = \"y\"\n",
            "letter = \"y\"\nmin_mm = -50.0\nmax_mm = 550.0\n",
            1,
        )
        .replacen(
            "letter = \"z\"\n",
            "letter = \"z\"\nmin_mm = -400.0\nmax_mm = 100.0\n",
            1,
        );
    let machine = dir.write("mill.toml", &mill);
    let prog = dir.write("far.nc", FAR_POCKET);
    let out = dir.file("limits.svg");
    let o = vcnc(&[
        "plot",
        prog.to_str().unwrap(),
        "--machine",
        machine.to_str().unwrap(),
        "--fit",
        "all",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.contains(">travel limits</text>"));
    // The box's dotted edges: the legend's sample and, seen from the top,
    // its four sides (each drawn twice, at Z −400 and Z 100) and its
    // vertical edges (points from the top, not drawn).
    let dotted = svg.matches("stroke-dasharray=\"2 3\"").count();
    assert!(dotted >= 9, "{dotted}");
    // X −100 .. 600 fills the plot area's width: a tick at −100 and at 600.
    assert!(
        svg.contains(">-100</text>") && svg.contains(">600</text>"),
        "ticks"
    );
}
