//! Canned cycles and hole patterns beyond the hand-worked fixtures: random
//! G81/G83 chains checked against a model written here, the frame and
//! compensation interplay, bounds, and the alarms of `docs/cycles-spec.md`
//! §10 (each with no motion of its block).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, Pos, VecSink};
use vcnc_syntax::Code;

fn run_in(dialect: Dialect, program: &str) -> (Vec<Event>, Outcome) {
    let m = Machine::default_mill();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &dialect, Options::default()).run_str(program, &mut sink);
    (sink.0, out)
}

fn run(program: &str) -> (Vec<Event>, Outcome) {
    run_in(Dialect::fanuc(), program)
}

fn holes(events: &[Event]) -> Vec<Pos> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Hole { at, .. } => Some(*at),
            _ => None,
        })
        .collect()
}

fn alarm(out: &Outcome) -> Option<(Code, u64, u32)> {
    match out {
        Outcome::Alarm(d) => Some((d.code, d.line, d.column)),
        _ => None,
    }
}

/// The events of one source line (an alarm carries no `loc`).
fn line_events(events: &[Event], line: u64) -> usize {
    events
        .iter()
        .filter(|e| e.loc().is_some_and(|l| l.line == line))
        .count()
}

fn close(a: Pos, x: f64, y: f64, z: f64) -> bool {
    (a.get(0) - x).abs() < 1e-6 && (a.get(1) - y).abs() < 1e-6 && (a.get(2) - z).abs() < 1e-6
}

#[test]
fn bad_cycle_words_alarm_where_they_are_and_the_block_moves_nothing() {
    let cases: &[(&str, Code, u64, u32)] = &[
        // K out of range, K with a point.
        ("G0 Z10\nG81 X1 Y1 Z-5. R2. F100 K-1\n", Code::E109, 2, 25),
        ("G0 Z10\nG81 X1 Y1 Z-5. R2. F100 K2.5\n", Code::E108, 2, 25),
        // The plane cannot change under a cycle.
        (
            "G0 Z10\nG81 X1 Y1 Z-5. R2. F100\nG18 X5.\n",
            Code::E324,
            3,
            1,
        ),
        // R alone does not drill, so it is not stored: an unused word.
        ("G0 Z10\nG81 X1 Y1 Z-5. R2. F100\nR1.\n", Code::E203, 3, 1),
        // A hole bottom above R, under G91 (Z from R).
        ("G0 Z10\nG91 G81 X1 Y1 Z5. R-2. F100\n", Code::E323, 2, 15),
        // Tapping backwards.
        (
            "S500 M04\nG0 Z10\nG84 X1 Y1 Z-5. R2. F100\n",
            Code::E321,
            3,
            1,
        ),
        // G74 needs M04.
        (
            "S500 M03\nG0 Z10\nG74 X1 Y1 Z-5. R2. F100\n",
            Code::E321,
            3,
            1,
        ),
        // A pattern of more than 10,000 holes.
        (
            "G0 Z10\nG81 Z-5. R2. F100 K0\nG137.1 X0 Y0 I1. P200 J1. K100\n",
            Code::E326,
            3,
            1,
        ),
        // G134 K0 and G135 K0.
        (
            "G0 Z10\nG81 Z-5. R2. F100 K0\nG134 X0 Y0 I10. K0\n",
            Code::E109,
            3,
            17,
        ),
        (
            "G0 Z10\nG81 Z-5. R2. F100 K0\nG135 X0 Y0 I10. K0\n",
            Code::E109,
            3,
            17,
        ),
        // No feed.
        ("G0 Z10\nG81 X1 Y1 Z-5. R2.\n", Code::E301, 2, 1),
    ];
    for (program, code, line, column) in cases {
        let (events, out) = run(program);
        assert_eq!(alarm(&out), Some((*code, *line, *column)), "{program}");
        // Only the alarm event carries the failing line.
        let moved = events
            .iter()
            .filter(|e| !matches!(e, Event::Alarm(_)))
            .filter(|e| e.loc().is_some_and(|l| l.line == *line))
            .count();
        assert_eq!(moved, 0, "{program}: events of the failing block");
    }
}

#[test]
fn a_k_block_that_fails_at_a_later_hole_emits_none_of_its_holes() {
    // Hole 3 of 4 is beyond X +1000 (the travel): the whole block alarms.
    let m = Machine::from_toml(include_str!(
        "../../../../tests/fixtures/machines/mill_travel_limits.toml"
    ))
    .unwrap();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &Dialect::fanuc(), Options::default())
        .run_str("G0 Z10\nG91 G81 X400. Z-5. R-8. F100 K4\n", &mut sink);
    let events = sink.0;
    assert_eq!(alarm(&out).map(|a| a.0), Some(Code::E501));
    assert_eq!(line_events(&events, 2), 0, "no event of the block");
}

#[test]
fn cancelling_a_cycle_that_is_not_active_is_a_no_op() {
    let (events, out) = run("G80\nG0 G80 G98 X5. Z5.\nM30\n");
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert!(holes(&events).is_empty());
}

#[test]
fn rotated_scaled_and_offset_holes_land_where_the_frame_puts_them() {
    // G54 at (100, 50, 0), rotation 90° about the program origin, then a
    // G81 line of holes along program X.
    let program = "G10 L2 P1 X100. Y50. Z0\nG54 G0 X0 Y0 Z10.\nG68 X0 Y0 R90.\n\
                   G81 X10. Y0 Z-5. R2. F100\nX20.\nG80 G69\nM30\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let h = holes(&events);
    assert_eq!(h.len(), 2);
    assert!(close(h[0], 100.0, 60.0, -5.0), "{:?}", h[0]);
    assert!(close(h[1], 100.0, 70.0, -5.0), "{:?}", h[1]);
}

#[test]
fn compensation_is_suspended_for_holes_and_starts_again_afterwards() {
    // D1 = 5 mm, written by the program: the built-in mill has no tools.
    let program = "G10 L12 P1 R5.\nG0 X-20. Y0 Z10.\nG41 D1 G1 X0 Y0 F500\nY20.\n\
                   G81 X30. Y30. Z-5. R2. F100\nG80\nG1 X50. Y20. F500\nG40 X60. Y0\nM30\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let h = holes(&events);
    assert_eq!(h.len(), 1);
    // The hole is where the program says, not offset by the radius.
    assert!(close(h[0], 30.0, 30.0, -5.0), "{:?}", h[0]);
    // Before the hole the held move ended square to its path: r = 5 left
    // of the move north along X0, so at X-5 Y20.
    let before: Vec<Pos> = events
        .iter()
        .take_while(|e| !matches!(e, Event::Hole { .. }))
        .filter_map(|e| match e {
            Event::Feed { to, .. } | Event::Rapid { to, .. } => Some(*to),
            _ => None,
        })
        .collect();
    let last = *before.last().expect("moves before the hole");
    assert!(close(last, -5.0, 20.0, 10.0), "{last:?}");
}

#[test]
fn the_eia_dialect_has_no_k_and_no_g98() {
    let eia = || Dialect::eia();
    let (_, out) = run_in(eia(), "G0 Z10\nG81 X1 Y1 Z-5 F100 K2\n");
    assert_eq!(alarm(&out).map(|a| a.0), Some(Code::E203));
    let (_, out) = run_in(eia(), "G98\n");
    assert_eq!(alarm(&out).map(|a| a.0), Some(Code::E201));
}

#[test]
fn a_pocket_with_no_tool_loaded_says_so() {
    // Regression: the alarm spoke of "the pocket's tool … diameter 0.0000 mm".
    let program = "S1000 M03\nG0 Z10.\nG79 X0 Y0 Z-5. I20. F300.\n";
    let (_, out) = run_in(Dialect::eia(), program);
    let Outcome::Alarm(d) = out else {
        panic!("no alarm: {out:?}")
    };
    assert_eq!((d.code, d.line), (Code::E325, 3));
    assert!(d.message.contains("no tool is loaded"), "{}", d.message);
    // A tool whose radius register is empty is named.
    let (_, out) = run_in(Dialect::eia(), &format!("T7 M06\n{program}"));
    let Outcome::Alarm(d) = out else {
        panic!("no alarm: {out:?}")
    };
    assert!(
        d.message.contains("T7") && d.message.contains("no radius"),
        "{}",
        d.message
    );
}

#[test]
fn a_pocket_too_large_for_its_block_alarms_before_it_moves() {
    // 0.1 mm of tool over a 1,900 mm pocket in 0.001 mm passes.
    let program = "G0 Z10.\nG78 X0 Y0 Z-5. I1900. J1900. Q0.001 F300.\n";
    let mut m = Machine::default_mill();
    m.tools.entry(1).or_default().d_mm = 0.05;
    let d = Dialect::eia();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &d, Options::default())
        .run_str(&format!("T1 M06\n{program}"), &mut sink);
    assert_eq!(alarm(&out).map(|a| a.0), Some(Code::E326));
}

/// A G81/G83 chain as the generator below writes it: G90 positions, one
/// depth and R, optional G99 and K (under G91 only).
#[derive(Debug, Clone)]
struct Chain {
    peck: Option<f64>,
    r: f64,
    depth: f64,
    holes: Vec<(f64, f64)>,
    g99: bool,
}

fn chain() -> impl Strategy<Value = Chain> {
    (
        prop::option::of(0.5f64..4.0),
        0.0f64..5.0,
        1.0f64..20.0,
        prop::collection::vec((-200.0f64..200.0, -200.0f64..200.0), 1..6),
        any::<bool>(),
    )
        .prop_map(|(peck, r, depth, holes, g99)| Chain {
            peck,
            r,
            depth,
            holes,
            g99,
        })
}

fn n4(v: f64) -> String {
    format!("{v:.4}")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Every hole is drilled where the program says, to the depth it says;
    /// the tool never goes below a hole's bottom, feeds only between R and
    /// the bottom, and is back at the return level after each hole.
    #[test]
    fn random_drilling_chains_follow_the_model(c in chain()) {
        let initial = 10.0 + c.r;
        let r_level = c.r;
        let bottom = c.r - c.depth;
        let code = if c.peck.is_some() { "G83" } else { "G81" };
        let mut p = format!("G0 X0 Y0 Z{}\n{} {} ", n4(initial), if c.g99 { "G99" } else { "G98" }, code);
        let (x0, y0) = c.holes[0];
        p += &format!("X{} Y{} Z{} R{} F200.", n4(x0), n4(y0), n4(bottom), n4(r_level));
        if let Some(q) = c.peck {
            p += &format!(" Q{}", n4(q));
        }
        p += "\n";
        for &(x, y) in &c.holes[1..] {
            p += &format!("X{} Y{}\n", n4(x), n4(y));
        }
        p += "G80\nM30\n";
        let (events, out) = run(&p);
        prop_assert!(matches!(out, Outcome::Ended(_)), "{:?}\n{}", out, p);
        let h = holes(&events);
        prop_assert_eq!(h.len(), c.holes.len());
        let ret = if c.g99 { r_level } else { initial };
        let round = |v: f64| (v * 1e4).round() / 1e4;
        for (at, &(x, y)) in h.iter().zip(&c.holes) {
            prop_assert!(close(*at, round(x), round(y), round(bottom)), "{:?} vs {},{}", at, x, y);
        }
        // Per hole: the moves between its `hole` event and the next.
        let mut i = 0;
        let mut deepest = f64::INFINITY;
        let mut last_z = initial;
        for e in &events {
            match e {
                Event::Hole { .. } => {
                    if i > 0 {
                        prop_assert!((last_z - round(ret)).abs() < 1e-6, "hole {} ends at {}", i, last_z);
                        prop_assert!((deepest - round(bottom)).abs() < 1e-6);
                    }
                    i += 1;
                    deepest = f64::INFINITY;
                }
                Event::Feed { to, .. } => {
                    let z = to.get(2);
                    prop_assert!(z >= round(bottom) - 1e-6 && z <= round(r_level) + 1e-6, "feed at {}", z);
                    deepest = deepest.min(z);
                    last_z = z;
                }
                Event::Rapid { to, .. } => {
                    prop_assert!(to.get(2) >= round(bottom) - 1e-6);
                    last_z = to.get(2);
                }
                _ => {}
            }
        }
        prop_assert!((deepest - round(bottom)).abs() < 1e-6);
        prop_assert!((last_z - round(ret)).abs() < 1e-6);
    }
}
