//! Whole parts written with macros: a bolt circle drilled by a WHILE loop
//! drills the same holes as the G134 hole pattern, and the same part in
//! Custom Macro B and in the Syntec MACRO language gives the same events.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, VecSink};

fn events(dialect: &str, program: &str) -> Vec<Event> {
    let machine = Machine::default_mill();
    let dialect = Dialect::by_name(dialect).unwrap();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&machine, &dialect, Options::default()).run_str(program, &mut sink);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}\n{program}");
    sink.0
}

/// What an event does, without where it was written: its type, its end
/// point or hole centre (to a nanometre), its feed or speed.
fn shape(events: &[Event]) -> Vec<String> {
    let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
    let p = |p: &vcnc_interp::Pos| format!("{} {} {}", r(p.get(0)), r(p.get(1)), r(p.get(2)));
    events
        .iter()
        .map(|e| match e {
            Event::Hole { cycle, at, .. } => format!("hole {} {}", cycle.as_str(), p(at)),
            Event::Feed { to, feed, .. } => format!("feed {} {feed:?}", p(to)),
            Event::Arc {
                to, center, dir, ..
            } => format!("arc {} {} {dir:?}", p(to), p(center)),
            Event::Spindle { rpm, .. } => format!("spindle {rpm}"),
            e => match e.motion_end() {
                Some(to) => format!("{} {}", e.kind(), p(&to)),
                None => e.kind().to_string(),
            },
        })
        .collect()
}

/// G134: six holes on a circle of radius 40 about 50,30, from 15°.
const PATTERN: &str =
    "S1000 M03\nG90 G00 X0 Y0 Z10.\nG81 Z-5. R2. K0 F200.\nG134 X50. Y30. I40. J15. K6\nG80\nM30\n";

/// The same holes, one G81 block per pass of a WHILE loop.
const WHILE_LOOP: &str = "S1000 M03\nG90 G00 X0 Y0 Z10.\n#1 = 0\nWHILE [#1 LT 6] DO 1\n\
                          #2 = 15 + #1 * 360 / 6\n\
                          G81 X[50 + 40 * COS[#2]] Y[30 + 40 * SIN[#2]] Z-5. R2. F200.\n\
                          #1 = #1 + 1\nEND 1\nG80\nM30\n";

/// The same again in the Syntec MACRO language (Doubles: the decimal
/// points make the words millimetres).
const SYNTEC_FOR: &str = "%@MACRO\nS1000 M03;\nG90 G00 X0. Y0. Z10.;\nFOR #1 := 0 TO 5 DO\n\
                          #2 := 15. + #1 * 360. / 6.;\n\
                          G81 X(50. + 40. * COS(#2)) Y(30. + 40. * SIN(#2)) Z-5. R2. F200.;\n\
                          END_FOR;\nG80;\nM30;\n";

#[test]
fn a_while_loop_drills_the_holes_of_g134() {
    let pattern = shape(&events("fanuc", PATTERN));
    let looped = shape(&events("fanuc", WHILE_LOOP));
    let holes: Vec<&String> = pattern.iter().filter(|s| s.starts_with("hole")).collect();
    assert_eq!(holes.len(), 6);
    // The first hole by hand: 50 + 40·cos 15° = 88.637033, 30 + 40·sin 15° = 40.352762.
    assert_eq!(holes[0], "hole G81 88.637033 40.352762 -5");
    assert_eq!(pattern, looped);
    assert_eq!(pattern, shape(&events("syntec", SYNTEC_FOR)));
}

/// A square faced in three steps down, with a corner arc, in Macro B.
const STEPS_B: &str = "S1200 M03\nG90 G00 X0 Y0 Z5.\n#10 = 1\nWHILE [#10 LE 3] DO 1\n\
                       G01 Z-#10 F100.\nX60. F300.\nY30.\nG03 X40. Y50. R20.\nG01 X0\nY0\n\
                       #10 = #10 + 1\nEND 1\nG00 Z5.\nM30\n";

/// The same part in Syntec MACRO: a FOR loop over Doubles.
const STEPS_SYNTEC: &str = "%@MACRO\nS1200 M03;\nG90 G00 X0. Y0. Z5.;\n\
                            FOR #10 := 1. TO 3. DO\n  G01 Z-#10 F100.;\n  X60. F300.;\n  Y30.;\n\
                            G03 X40. Y50. R20.;\n  G01 X0.;\n  Y0.;\nEND_FOR;\nG00 Z5.;\nM30;\n";

#[test]
fn the_same_part_in_both_languages_gives_the_same_events() {
    let b = shape(&events("fanuc", STEPS_B));
    let s = shape(&events("syntec", STEPS_SYNTEC));
    assert_eq!(b, s);
    // Three passes of six moves, the approach and the retract.
    assert_eq!(
        b.iter()
            .filter(|e| e.starts_with("feed") || e.starts_with("arc"))
            .count(),
        18
    );
    assert!(
        b.contains(&"feed 0 0 -3 PerMin(100.0)".to_string()),
        "{b:?}"
    );
}
