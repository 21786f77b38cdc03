//! Property tests of the programmable transforms (G51 scaling, G51.1
//! mirror, G68 rotation) on random programs of lines and arcs, checked
//! against a small independent implementation of the same maths here:
//!
//! - rotating a program by θ about a centre rotates every event by θ;
//! - scaling by k about a centre scales every point (so every length) by k;
//! - a mirror and a scale of −1 about the same axis cancel (mirror twice);
//! - any composition of scaling, rotation and mirror, undone by its inverse
//!   here, gives back the untransformed program's events.
//!
//! Every program starts with an absolute move, so that the tool's position
//! before the transform does not matter (an increment after a frame change
//! starts from the machine position, as on Fanuc).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_interp::{ArcDir, Dialect, Event, Interpreter, Machine, Options, Outcome, Pos, VecSink};

/// A machine without practical travel limits.
fn machine() -> Machine {
    let text = vcnc_interp::machine::DEFAULT_MILL_TOML
        .replace("min_mm = -1000.0", "min_mm = -100000.0")
        .replace("max_mm = 1000.0", "max_mm = 100000.0")
        .replace("min_mm = -500.0", "min_mm = -100000.0")
        .replace("max_mm = 500.0", "max_mm = 100000.0");
    Machine::from_toml(&text).unwrap()
}

fn run(program: &str) -> Vec<Event> {
    let m = machine();
    let d = Dialect::fanuc();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &d, Options::default()).run_str(program, &mut sink);
    assert!(
        matches!(out, Outcome::Ended(_)),
        "{out:?}\nprogram:\n{program}"
    );
    sink.0
        .into_iter()
        .filter(|e| !matches!(e, Event::Frame { .. }))
        .collect()
}

/// One step of a random program, in program coordinates.
#[derive(Debug, Clone)]
enum Step {
    Line {
        x: f64,
        y: f64,
        z: f64,
        inc: bool,
    },
    Arc {
        dx: f64,
        dy: f64,
        sweep_deg: f64,
        cw: bool,
    },
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        (
            -50.0..50.0f64,
            -50.0..50.0f64,
            -20.0..20.0f64,
            any::<bool>()
        )
            .prop_map(|(x, y, z, inc)| Step::Line { x, y, z, inc }),
        (
            -30.0..30.0f64,
            -30.0..30.0f64,
            10.0..300.0f64,
            any::<bool>()
        )
            .prop_map(|(dx, dy, sweep_deg, cw)| Step::Arc {
                dx,
                dy,
                sweep_deg,
                cw
            }),
    ]
}

/// The program text of `steps`, and the program positions it visits.
fn program(steps: &[Step]) -> String {
    // The setup goes before F500; the absolute G01 after it puts the
    // programmed point where the new frame says it is.
    // The G00 goes elsewhere, so that the plain program's G01 moves too (a
    // move that would not move reports no event).
    let mut text = String::from("G21 G17 G90 G00 X0. Y0. Z10.\nF500.\nG01 X10. Y5. Z2.\n");
    let (mut x, mut y) = (10.0f64, 5.0f64);
    for s in steps {
        match *s {
            Step::Line { x: a, y: b, z, inc } => {
                if inc {
                    text.push_str(&format!("G91 G01 X{a:.4} Y{b:.4} Z{z:.4}\nG90\n"));
                    x += (a * 1e4).round() / 1e4;
                    y += (b * 1e4).round() / 1e4;
                } else {
                    text.push_str(&format!("G01 X{a:.4} Y{b:.4} Z{z:.4}\n"));
                    x = (a * 1e4).round() / 1e4;
                    y = (b * 1e4).round() / 1e4;
                }
            }
            Step::Arc {
                dx,
                dy,
                sweep_deg,
                cw,
            } => {
                let (dx, dy) = ((dx * 1e4).round() / 1e4, (dy * 1e4).round() / 1e4);
                if dx.hypot(dy) < 1.0 {
                    continue;
                }
                let (cx, cy) = (x + dx, y + dy);
                let r = dx.hypot(dy);
                let a0 = (-dy).atan2(-dx);
                let a1 = a0 + sweep_deg.to_radians() * if cw { -1.0 } else { 1.0 };
                let (ex, ey) = (cx + r * a1.cos(), cy + r * a1.sin());
                let code = if cw { "G02" } else { "G03" };
                text.push_str(&format!("{code} X{ex:.4} Y{ey:.4} I{dx:.4} J{dy:.4}\n"));
                x = (ex * 1e4).round() / 1e4;
                y = (ey * 1e4).round() / 1e4;
            }
        }
    }
    text.push_str("M30\n");
    text
}

/// The same program with `setup` placed after its first (absolute) move.
fn with_setup(program: &str, setup: &str) -> String {
    let (first, rest) = program.split_once("F500.\n").unwrap();
    format!("{first}{setup}\nF500.\n{rest}")
}

/// An affine map of X, Y, Z written here, independently of the interpreter.
#[derive(Debug, Clone, Copy)]
struct Map {
    m: [[f64; 3]; 3],
    t: [f64; 3],
}

impl Map {
    fn apply(&self, p: Pos) -> Pos {
        let mut q = p;
        for r in 0..3 {
            q.0[r] = self.t[r] + (0..3).map(|c| self.m[r][c] * p.0[c]).sum::<f64>();
        }
        q
    }
    fn det_xy(&self) -> f64 {
        self.m[0][0] * self.m[1][1] - self.m[0][1] * self.m[1][0]
    }
    fn rotation(deg: f64, cx: f64, cy: f64) -> Map {
        let (s, c) = deg.to_radians().sin_cos();
        Map {
            m: [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
            t: [cx - c * cx + s * cy, cy - s * cx - c * cy, 0.0],
        }
    }
    fn scaling(k: f64, c: [f64; 3]) -> Map {
        Map {
            m: [[k, 0.0, 0.0], [0.0, k, 0.0], [0.0, 0.0, k]],
            t: [c[0] * (1.0 - k), c[1] * (1.0 - k), c[2] * (1.0 - k)],
        }
    }
    fn mirror_x(a: f64) -> Map {
        Map {
            m: [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            t: [2.0 * a, 0.0, 0.0],
        }
    }
    /// `self ∘ inner`.
    fn after(&self, inner: &Map) -> Map {
        let mut out = Map {
            m: [[0.0; 3]; 3],
            t: self.t,
        };
        for r in 0..3 {
            for c in 0..3 {
                out.m[r][c] = (0..3).map(|k| self.m[r][k] * inner.m[k][c]).sum();
                out.t[r] += self.m[r][c] * inner.t[c];
            }
        }
        out
    }
}

fn close(a: Pos, b: Pos) -> bool {
    (0..3).all(|i| (a.0[i] - b.0[i]).abs() < 1e-6)
}

/// Events of the transformed program equal the plain program's events
/// mapped by `map` (arcs reverse when the map mirrors the plane).
fn same_under(plain: &[Event], transformed: &[Event], map: &Map) -> Result<(), TestCaseError> {
    prop_assert_eq!(plain.len(), transformed.len());
    let flip = map.det_xy() < 0.0;
    for (a, b) in plain.iter().zip(transformed) {
        match (a, b) {
            (Event::Feed { to: p, .. }, Event::Feed { to: q, .. })
            | (Event::Rapid { to: p, .. }, Event::Rapid { to: q, .. }) => {
                prop_assert!(close(map.apply(*p), *q), "{a:?} vs {b:?}");
            }
            (
                Event::Arc {
                    to: p,
                    center: c,
                    dir: d1,
                    ..
                },
                Event::Arc {
                    to: q,
                    center: c2,
                    dir: d2,
                    ..
                },
            ) => {
                prop_assert!(close(map.apply(*p), *q), "{a:?} vs {b:?}");
                let mc = map.apply(*c);
                prop_assert!(
                    (mc.0[0] - c2.0[0]).abs() < 1e-6 && (mc.0[1] - c2.0[1]).abs() < 1e-6,
                    "centre {a:?} vs {b:?}"
                );
                let expected = if flip {
                    if *d1 == ArcDir::Cw {
                        ArcDir::Ccw
                    } else {
                        ArcDir::Cw
                    }
                } else {
                    *d1
                };
                prop_assert_eq!(expected, *d2);
            }
            (x, y) => prop_assert_eq!(x.kind(), y.kind()),
        }
    }
    Ok(())
}

/// Drops the first move (from the power-on point, which no transform touches).
fn after_first_move(events: Vec<Event>) -> Vec<Event> {
    events.into_iter().skip(1).collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn rotation_rotates_every_event(
        steps in proptest::collection::vec(step(), 1..12),
        deg in -360.0..360.0f64,
        cx in -40.0..40.0f64,
        cy in -40.0..40.0f64,
    ) {
        let (deg, cx, cy) = ((deg * 1e3).round() / 1e3, (cx * 1e3).round() / 1e3, (cy * 1e3).round() / 1e3);
        let p = program(&steps);
        let plain = after_first_move(run(&p));
        let rotated = after_first_move(run(&with_setup(&p, &format!("G68 X{cx:.3} Y{cy:.3} R{deg:.3}"))));
        same_under(&plain, &rotated, &Map::rotation(deg, cx, cy))?;
    }

    #[test]
    fn scaling_scales_every_point(
        steps in proptest::collection::vec(step(), 1..12),
        k in 0.1..5.0f64,
        c in proptest::array::uniform3(-40.0..40.0f64),
    ) {
        let k = (k * 1e3).round() / 1e3;
        let c = c.map(|v| (v * 1e3).round() / 1e3);
        let p = program(&steps);
        let plain = after_first_move(run(&p));
        let setup = format!("G51 X{:.3} Y{:.3} Z{:.3} P{k:.3}", c[0], c[1], c[2]);
        let scaled = after_first_move(run(&with_setup(&p, &setup)));
        same_under(&plain, &scaled, &Map::scaling(k, c))?;
    }

    #[test]
    fn mirror_twice_is_the_identity(
        steps in proptest::collection::vec(step(), 1..12),
        a in -40.0..40.0f64,
    ) {
        let a = (a * 1e3).round() / 1e3;
        let p = program(&steps);
        let plain = after_first_move(run(&p));
        // A mirror about x = a, and a scale of −1 on X about the same axis.
        let setup = format!("G51.1 X{a:.3}\nG51 X{a:.3} I-1. J1. K1.");
        let twice = after_first_move(run(&with_setup(&p, &setup)));
        same_under(&plain, &twice, &Map::scaling(1.0, [0.0; 3]))?;
    }

    #[test]
    fn a_composition_undone_by_its_inverse_gives_the_program_back(
        steps in proptest::collection::vec(step(), 1..10),
        k in 0.2..4.0f64,
        deg in -180.0..180.0f64,
        a in -30.0..30.0f64,
        c in proptest::array::uniform3(-30.0..30.0f64),
    ) {
        let (k, deg, a) = ((k * 1e3).round() / 1e3, (deg * 1e3).round() / 1e3, (a * 1e3).round() / 1e3);
        let c = c.map(|v| (v * 1e3).round() / 1e3);
        let p = program(&steps);
        let plain = after_first_move(run(&p));
        // Nested frames: the later command acts first on the program point.
        let setup = format!(
            "G51.1 X{a:.3}\nG51 X{:.3} Y{:.3} Z{:.3} P{k:.3}\nG68 X{:.3} Y{:.3} R{deg:.3}",
            c[0], c[1], c[2], c[1], c[0]
        );
        let map = Map::mirror_x(a)
            .after(&Map::scaling(k, c))
            .after(&Map::rotation(deg, c[1], c[0]));
        let transformed = after_first_move(run(&with_setup(&p, &setup)));
        same_under(&plain, &transformed, &map)?;
    }
}

#[test]
fn a_cancelled_mirror_leaves_increments_moving_from_the_machine_position() {
    // Syntec 1.2.21's note: after G50.1 away from the axis, an increment
    // moves from where the tool is, not from the mirrored-back position.
    let events = run("G00 X10. Y0.\nG51.1 X0.\nG00 X20.\nG50.1\nG91 G00 X5.\nM30\n");
    let ends: Vec<f64> = events
        .iter()
        .filter_map(|e| match e {
            Event::Rapid { to, .. } => Some(to.0[0]),
            _ => None,
        })
        .collect();
    assert_eq!(ends, vec![10.0, -20.0, -15.0]);
}
