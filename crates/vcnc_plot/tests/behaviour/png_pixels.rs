//! The PNG back-plot checked pixel by pixel: a rapid and two cuts are
//! drawn, the PNG is encoded and decoded again, and the rapid colour and
//! the cut colour (or their anti-aliased blends with the background) must
//! appear along their segments and nowhere else in the plot area (the
//! legend panel shows samples of both, so it is left out).
//!
//! The expected places come from the scene's own plot-to-screen map; the
//! map itself is checked independently: the rapid along +X must be
//! horizontal and the cut along +Y must go up the screen from its right end.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report
#![allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // pixel indices near the picture

use tiny_skia::Pixmap;
use vcnc_core::display::DisplayUnits;
use vcnc_core::{Event, Feed, Loc, Machine, Pos, Sink};
use vcnc_plot::scene::PANEL_W;
use vcnc_plot::theme::{DEPTH_STEPS, Theme, palette, ramp};
use vcnc_plot::{ColorBy, FitTo, Legend, Look, PlotOptions, PlotSink, Projection, Space, View};

const W: u32 = 600;
const H: u32 = 400;

fn at(x: f64, y: f64) -> Pos {
    Pos([x, y, -2.0, 0.0, 0.0, 0.0])
}

fn loc(line: u64) -> Loc {
    Loc { line, file: None }
}

/// Distance from `q` to the segment `a`–`b`, px.
fn dist(q: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = (((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / len2).clamp(0.0, 1.0);
    (q[0] - a[0] - t * dx).hypot(q[1] - a[1] - t * dy)
}

/// Whether pixel `p` is colour `c` laid over the background `bg` with an
/// anti-aliasing coverage of at least a third: `p = bg + α·(c − bg)` to
/// within a few levels. Other colours, and their blends with the
/// background (grid, text, marks), are off that line.
fn tint(p: [u8; 3], c: vcnc_plot::Rgb, bg: vcnc_plot::Rgb) -> bool {
    let d = [
        f64::from(c.0) - f64::from(bg.0),
        f64::from(c.1) - f64::from(bg.1),
        f64::from(c.2) - f64::from(bg.2),
    ];
    let q = [
        f64::from(p[0]) - f64::from(bg.0),
        f64::from(p[1]) - f64::from(bg.1),
        f64::from(p[2]) - f64::from(bg.2),
    ];
    let alpha =
        (q[0] * d[0] + q[1] * d[1] + q[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    let off = (0..3)
        .map(|k| (q[k] - alpha * d[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    (0.33..=1.1).contains(&alpha) && off < 20.0
}

fn pixel(pm: &Pixmap, x: u32, y: u32) -> [u8; 3] {
    let p = pm.pixel(x, y).unwrap().demultiply();
    [p.red(), p.green(), p.blue()]
}

#[test]
fn rapid_and_cut_colours_appear_where_the_path_goes_and_nowhere_else() {
    let machine = Machine::default_mill();
    let projection = Projection::new(View::Xy, false);
    let look = Look {
        theme: Theme::Light,
        color: ColorBy::Depth,
        width_px: W,
        height_px: H,
        // The rapid is part of what this test checks: frame everything.
        fit: FitTo::All,
        rapids: true,
        units: DisplayUnits::Mm,
    };
    let (width_px, height_px) = vcnc_plot::plot_area(W, H);
    let mut sink = PlotSink::new(
        &machine,
        PlotOptions {
            space: Space::Flat {
                projection,
                width_px,
                height_px,
            },
            color: ColorBy::Depth,
            max_vertices: 1000,
            max_marks: 1000,
            fit: FitTo::All,
        },
    );
    // The machine starts at 0,0,0: a rapid to (0, 0, -2) is invisible from
    // the top, then a rapid along X and two cuts at one depth.
    let moves = [
        Event::Rapid {
            loc: loc(1),
            to: at(0.0, 0.0),
            exact_stop: false,
        },
        Event::Rapid {
            loc: loc(2),
            to: at(100.0, 0.0),
            exact_stop: false,
        },
        Event::Feed {
            loc: loc(3),
            to: at(100.0, 60.0),
            feed: Feed::PerMin(500.0),
            exact_stop: false,
        },
        Event::Feed {
            loc: loc(4),
            to: at(40.0, 60.0),
            feed: Feed::PerMin(500.0),
            exact_stop: false,
        },
    ];
    for e in &moves {
        sink.event(e);
    }
    let plot = sink.into_plot();
    let scene = vcnc_plot::scene(&plot, None, &projection, &look, &Legend::default());
    let mut png = Vec::new();
    vcnc_plot::write_png(&scene, &mut png).unwrap();
    let pm = Pixmap::decode_png(&png).unwrap();
    assert_eq!((pm.width(), pm.height()), (W, H));

    let pal = palette(Theme::Light);
    // One depth only: the cuts take the middle of the depth ramp.
    let cut = ramp(&pal.depth, 0.5, DEPTH_STEPS);
    let xy = |x: f64, y: f64| scene.fit.xy([x, y, -2.0]);
    let rapid_seg = (xy(0.0, 0.0), xy(100.0, 0.0));
    let cut_segs = [
        (xy(100.0, 0.0), xy(100.0, 60.0)),
        (xy(100.0, 60.0), xy(40.0, 60.0)),
    ];

    // The map: +X runs right along one row, +Y runs up the screen.
    assert!((rapid_seg.0[1] - rapid_seg.1[1]).abs() < 1e-9);
    assert!(rapid_seg.1[0] - rapid_seg.0[0] > 200.0, "{rapid_seg:?}");
    assert!(
        cut_segs[0].1[1] < cut_segs[0].0[1] - 100.0,
        "{:?}",
        cut_segs[0]
    );

    let (mut rapid_px, mut cut_px) = (0, 0);
    let legend_x = f64::from(W) - PANEL_W;
    for y in 0..H {
        for x in 0..W {
            let q = [f64::from(x) + 0.5, f64::from(y) + 0.5];
            if q[0] >= legend_x {
                continue;
            }
            let p = pixel(&pm, x, y);
            if tint(p, pal.rapid, pal.background) {
                rapid_px += 1;
                let d = dist(q, rapid_seg.0, rapid_seg.1);
                assert!(d < 2.0, "rapid colour at {x},{y}, {d:.1} px off the rapid");
            }
            if tint(p, cut, pal.background) {
                cut_px += 1;
                let d = cut_segs
                    .iter()
                    .map(|(a, b)| dist(q, *a, *b))
                    .fold(f64::INFINITY, f64::min);
                assert!(d < 2.5, "cut colour at {x},{y}, {d:.1} px off the cuts");
            }
        }
    }
    // Dashed: 4 of every 7 px of the rapid are drawn, on one or two rows.
    let rapid_len = rapid_seg.1[0] - rapid_seg.0[0];
    assert!(
        f64::from(rapid_px) > 0.4 * rapid_len,
        "{rapid_px} rapid pixels over {rapid_len:.0} px"
    );
    // Solid, 1.5 px wide: every step along the cuts is covered.
    for (a, b) in cut_segs {
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let mut hits = 0;
        let n = 50;
        for k in 1..n {
            let t = f64::from(k) / f64::from(n);
            let q = [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
            let found = (-1..=1).any(|dy: i32| {
                (-1..=1).any(|dx: i32| {
                    let (px, py) = (q[0].floor() as i32 + dx, q[1].floor() as i32 + dy);
                    tint(pixel(&pm, px as u32, py as u32), cut, pal.background)
                })
            });
            hits += u32::from(found);
        }
        assert!(
            hits >= n - 2,
            "cut from {a:?} to {b:?} ({len:.0} px): {hits} of {} samples",
            n - 1
        );
    }
    assert!(cut_px > 0);
}
