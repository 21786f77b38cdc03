//! The Z-map against a slow, independent reference on random programs:
//! the tool stamped at points every 0.02 mm along the path the events
//! describe (its own arc and profile arithmetic, nothing of vcnc_sim's),
//! evaluated at each cell centre.
//!
//! Stamping can only miss what lies between its samples, so it bounds
//! the exact envelope from both sides: above by the stamps themselves,
//! below by the stamps of a tool lowered by half the spacing and widened
//! by it. Every cell of the Z-map must lie between the two (to f32's
//! rounding): that is the grid's error bound at the cell centres, where
//! the Z-map samples the envelope.

use proptest::prelude::*;
use std::fmt::Write;
use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_core::{Event, Sink, ToolKind, VecSink};
use vcnc_interp::{Dialect, Interpreter, Options};
use vcnc_sim::{Part, SimOptions, Simulation, StockOrigin, StockSpec};

const RES: f64 = 0.25;
const STEP: f64 = 0.02;

#[derive(Debug, Clone, Copy)]
enum Kind {
    Flat,
    Ball,
    Bull(f64),
    Drill(f64),
}

/// The bottom's height above the tip at radius `r` of a tool of radius
/// `big_r`, written out again from the shapes' definitions.
fn profile(kind: Kind, big_r: f64, r: f64) -> f64 {
    let r = r.clamp(0.0, big_r);
    match kind {
        Kind::Flat => 0.0,
        Kind::Ball => big_r - (big_r * big_r - r * r).sqrt(),
        Kind::Bull(c) => {
            let q = (r - (big_r - c)).max(0.0);
            c - (c * c - q * q).max(0.0).sqrt()
        }
        Kind::Drill(angle) => r / (angle.to_radians() / 2.0).tan(),
    }
}

/// The tip's positions every `STEP` along the events' moves.
fn samples(events: &[Event]) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    let mut at = [0.0f64; 3];
    let xyz = |p: &vcnc_core::Pos| [p.get(0), p.get(1), p.get(2)];
    let axes = PlaneAxes {
        a: 0,
        b: 1,
        n: Some(2),
    };
    let mut from = vcnc_core::Pos::default();
    for e in events {
        match e {
            Event::Rapid { to, .. } | Event::Feed { to, .. } => {
                let b = xyz(to);
                let len =
                    ((b[0] - at[0]).powi(2) + (b[1] - at[1]).powi(2) + (b[2] - at[2]).powi(2))
                        .sqrt();
                let n = (len / STEP).ceil().max(1.0) as usize;
                for k in 0..=n {
                    let t = k as f64 / n as f64;
                    out.push([
                        at[0] + (b[0] - at[0]) * t,
                        at[1] + (b[1] - at[1]) * t,
                        at[2] + (b[2] - at[2]) * t,
                    ]);
                }
                at = b;
                from = *to;
            }
            Event::Arc {
                to, center, dir, ..
            } => {
                let arc = ArcPath::new(from, *to, *center, axes, *dir);
                let n = (arc.length() / STEP).ceil().max(1.0) as usize;
                for k in 0..=n {
                    out.push(xyz(&arc.point_at(k as f64 / n as f64)));
                }
                at = xyz(to);
                from = *to;
            }
            _ => {}
        }
    }
    out
}

/// A random program on the 20 × 20 stock: plunges, level lines and arcs,
/// ramps.
fn program(moves: &[(u8, f64, f64, f64)], depth: f64) -> String {
    let mut p = String::from("G21 G90 G17\nT1 M06\nG00 X10 Y10 Z3\n");
    let _ = writeln!(p, "G01 Z{depth:.4} F500");
    let (mut x, mut y, mut z) = (10.0f64, 10.0f64, depth);
    for &(kind, a, b, c) in moves {
        match kind % 6 {
            0 => {
                x = 2.0 + 16.0 * a;
                y = 2.0 + 16.0 * b;
                let _ = writeln!(p, "G01 X{x:.4} Y{y:.4}");
            }
            1 => {
                x = 2.0 + 16.0 * a;
                y = 2.0 + 16.0 * b;
                z = (z + (c - 0.5) * 3.0).clamp(-5.0, 0.5);
                let _ = writeln!(p, "G01 X{x:.4} Y{y:.4} Z{z:.4}");
            }
            2 => {
                // An arc about a centre 1..5 mm away, sweeping ±(0.3..5) rad.
                let r = 1.0 + 4.0 * a;
                let ang0 = std::f64::consts::TAU * b;
                let (cx, cy) = (x - r * ang0.cos(), y - r * ang0.sin());
                let sweep = (0.3 + 4.7 * c) * if kind < 6 { 1.0 } else { -1.0 };
                let (ex, ey) = (cx + r * (ang0 + sweep).cos(), cy + r * (ang0 + sweep).sin());
                let code = if sweep > 0.0 { "G03" } else { "G02" };
                let _ = writeln!(p, "{code} X{ex:.4} Y{ey:.4} I{:.4} J{:.4}", cx - x, cy - y);
                x = ex;
                y = ey;
            }
            4 => {
                // Along X, level or ramping (a raster's move: one distance
                // from the line per row, the Z-map's own path).
                x = 2.0 + 16.0 * a;
                z = (z + (c - 0.5) * 3.0 * b).clamp(-5.0, 0.5);
                let _ = writeln!(p, "G01 X{x:.4} Z{z:.4}");
            }
            5 => {
                y = 2.0 + 16.0 * a;
                z = (z + (c - 0.5) * 3.0 * b).clamp(-5.0, 0.5);
                let _ = writeln!(p, "G01 Y{y:.4} Z{z:.4}");
            }
            _ => {
                z = -5.0 * a;
                let _ = writeln!(
                    p,
                    "G00 Z3\nG00 X{:.4} Y{:.4}\nG01 Z{z:.4}",
                    2.0 + 16.0 * b,
                    2.0 + 16.0 * c
                );
                x = 2.0 + 16.0 * b;
                y = 2.0 + 16.0 * c;
            }
        }
    }
    p.push_str("G00 Z5\nM30\n");
    p
}

fn check(kind: Kind, radius: f64, moves: &[(u8, f64, f64, f64)], depth: f64) {
    let text = program(moves, depth);
    let d = Dialect::fanuc();
    let m = d.machine();
    let mut events = VecSink::default();
    Interpreter::new(&m, &d, Options::default()).run_str(&text, &mut events);
    let tool_kind = match kind {
        Kind::Flat => ToolKind::Flat,
        Kind::Ball => ToolKind::Ball,
        Kind::Bull(c) => ToolKind::Bull {
            corner_radius_mm: c,
        },
        Kind::Drill(a) => ToolKind::Drill { point_angle_deg: a },
    };
    let tools = crate::harness::library(&[crate::harness::tool(1, tool_kind, 2.0 * radius)]);
    let options = SimOptions {
        stock: StockSpec::parse("box:0,0,-6,20,20,0").unwrap(),
        stock_origin: StockOrigin::Option,
        resolution_mm: Some(RES),
        lathe: false,
        workers: 3,
        replay: None,
    };
    let mut sim = Simulation::new(&m, &tools, None, options).unwrap();
    sim.take_events(&mut events.0.clone());
    let f = sim.finish_run().unwrap();
    let Part::Mill(map, _) = &f.part else {
        panic!("no Z-map")
    };
    // The two stamped bounds at every cell centre.
    let n = map.nx * map.ny;
    let (mut upper, mut lower) = (vec![f64::INFINITY; n], vec![f64::INFINITY; n]);
    let h = STEP / 2.0;
    for s in samples(&events.0) {
        let reach = radius + h;
        let (i0, i1) = (
            ((s[0] - reach) / RES - 0.5).ceil().max(0.0) as usize,
            ((s[0] + reach) / RES - 0.5)
                .floor()
                .min(map.nx as f64 - 1.0),
        );
        let (j0, j1) = (
            ((s[1] - reach) / RES - 0.5).ceil().max(0.0) as usize,
            ((s[1] + reach) / RES - 0.5)
                .floor()
                .min(map.ny as f64 - 1.0),
        );
        if i1 < 0.0 || j1 < 0.0 {
            continue;
        }
        for j in j0..=j1 as usize {
            for i in i0..=i1 as usize {
                let (cx, cy) = ((i as f64 + 0.5) * RES, (j as f64 + 0.5) * RES);
                let rho = (cx - s[0]).hypot(cy - s[1]);
                let k = j * map.nx + i;
                if rho <= radius {
                    upper[k] = upper[k].min(s[2] + profile(kind, radius, rho));
                }
                if rho <= radius + h {
                    lower[k] = lower[k].min(s[2] - h + profile(kind, radius, (rho - h).max(0.0)));
                }
            }
        }
    }
    let clamp = |v: f64| v.clamp(-6.0, 0.0);
    for j in 0..map.ny {
        for i in 0..map.nx {
            let k = j * map.nx + i;
            let got = f64::from(map.height(i, j));
            let (lo, hi) = (clamp(lower[k]), clamp(upper[k]));
            assert!(
                got >= lo - 1e-4 && got <= hi + 1e-4,
                "cell ({i}, {j}): {got} not in [{lo}, {hi}]\n{text}"
            );
        }
    }
}

fn moves() -> impl Strategy<Value = Vec<(u8, f64, f64, f64)>> {
    prop::collection::vec((0u8..12, 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64), 1..9)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    #[test]
    fn flat_end_mills_match_the_stamped_reference(m in moves(), d in -4.0..-0.5f64, r in 0.8..3.0f64) {
        check(Kind::Flat, r, &m, d);
    }

    #[test]
    fn ball_end_mills_match_the_stamped_reference(m in moves(), d in -4.0..-0.5f64, r in 0.8..3.0f64) {
        check(Kind::Ball, r, &m, d);
    }

    #[test]
    fn bull_and_drill_points_match_the_stamped_reference(m in moves(), d in -4.0..-0.5f64, r in 1.0..3.0f64, c in 0.2..0.9f64, a in 90.0..140.0f64) {
        check(Kind::Bull(c * r), r, &m, d);
        check(Kind::Drill(a), r, &m, d);
    }
}
