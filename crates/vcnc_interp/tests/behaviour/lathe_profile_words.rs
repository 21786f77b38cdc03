//! The words a Fanuc lathe allows in a G70–G73 profile (the blocks N P …
//! N Q), after the 0i-TF operator's manual (multiple repetitive cycles):
//! one-shot G codes other than G04, group-01 codes other than G00–G03,
//! G20/G21 and M98/M99 may not be written there; F, S and T there are
//! ignored by the roughing cycles G71–G73 (which cut with the cycle
//! block's F) and are G70's. vcnc reads the other words the same way: the
//! roughing ignores G04, M codes, T, S, F, G96/G97 and G98/G99 in the
//! profile, and G70 runs them in order along the finishing pass, leaving
//! the modes they set as ordinary blocks would.
//!
//! Every expected trace below is worked out by hand in its comment.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common;
use std::f64::consts::PI;
use vcnc_interp::{Dialect, EndCode, Event, Feed, Outcome, SpindleDir};

const X: usize = 0;
const Z: usize = 1;

fn run(program: &str) -> (Vec<Event>, Outcome) {
    common::run_on_its_machine(&Dialect::fanuc_lathe(), program)
}

fn feed_text(f: &Feed) -> String {
    match f {
        Feed::PerMin(v) => format!("{v:.3}/min"),
        Feed::PerRev(v) => format!("{v:.3}/rev"),
    }
}

/// The events as short lines: `line kind values`, positions (X radius, Z).
fn trace(events: &[Event]) -> Vec<String> {
    events
        .iter()
        .filter_map(|e| {
            Some(match e {
                Event::Rapid { loc, to, .. } => {
                    format!("{} rapid {:.3} {:.3}", loc.line, to.get(X), to.get(Z))
                }
                Event::Feed { loc, to, feed, .. } => format!(
                    "{} feed {:.3} {:.3} {}",
                    loc.line,
                    to.get(X),
                    to.get(Z),
                    feed_text(feed)
                ),
                Event::Dwell { loc, seconds } => format!("{} dwell {seconds:.3}", loc.line),
                Event::Coolant { loc, on } => format!("{} coolant {on}", loc.line),
                Event::ToolChange { loc, tool } => format!("{} tool {tool}", loc.line),
                Event::Spindle { loc, dir, rpm, .. } => {
                    format!("{} spindle {dir:?} {rpm:.3}", loc.line)
                }
                Event::End { loc, .. } => format!("{} end", loc.line),
                _ => return None,
            })
        })
        .collect()
}

/// The rpm of 150 m/min on a diameter of `d_mm`: 1000·S / (π·D).
fn css(d_mm: f64) -> String {
    format!("{:.3}", 150_000.0 / (PI * d_mm))
}

/// G70 runs M08, G04, G98 with F, G96 with S, M09 and T in the order of
/// their blocks, each with its own line, and what they set stays after the
/// G70 as after ordinary blocks.
///
/// A = (X44 Z2) = radius 22. The profile (after M30):
/// - line 7 `N10 G00 X20. M08`: coolant on, then the rapid to radius 10.
/// - line 8 `G01 Z-15. F0.1`: G99 is in force: 0.1 mm/rev to Z-15.
/// - line 9 `G04 X0.5`: a dwell of 0.5 s, no move.
/// - line 10 `G98 F200.`: feed per minute, 200 mm/min; no event.
/// - line 11 `T0202`: turret station 2 (offset register 2 has zero X/Z
///   offsets on the built-in machine, so positions stay).
/// - line 12 `G01 X30.`: to radius 15 at 200 mm/min.
/// - line 13 `G96 S150`: the spindle runs, so it changes at once on the
///   work diameter under the tool, 30 mm: 150000/(π·30) = 1591.549 rpm.
/// - line 14 `N40 X44. M09`: coolant off (M codes come before the motion),
///   then the speed for the move's end point, ⌀44: 1085.156 rpm, then the
///   feed to radius 22 at 200 mm/min.
///
/// Then the G00 back to A (line 3): already at X44, only Z moves, ⌀44: no
/// new speed. Line 4 `G01 X50. Z5.` runs in the modes G70 left: G96 S150
/// (⌀50: 954.930 rpm, announced before the move) and G98 F200 — a
/// roughing-only reading would give 0.1 mm/rev and 1000 rpm here.
#[test]
fn g70_runs_the_profile_words_in_order_and_keeps_their_modes() {
    let program = "G97 S1000 M03\n\
                   G00 X44. Z2.\n\
                   G70 P10 Q40\n\
                   G01 X50. Z5.\n\
                   M30\n\
                   (the profile)\n\
                   N10 G00 X20. M08\n\
                   G01 Z-15. F0.1\n\
                   G04 X0.5\n\
                   G98 F200.\n\
                   T0202\n\
                   G01 X30.\n\
                   G96 S150\n\
                   N40 X44. M09\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
    let got = trace(&events);
    let want = vec![
        "1 spindle Cw 1000.000".to_string(),
        "2 rapid 22.000 2.000".into(),
        "7 coolant true".into(),
        "7 rapid 10.000 2.000".into(),
        "8 feed 10.000 -15.000 0.100/rev".into(),
        "9 dwell 0.500".into(),
        "11 tool 2".into(),
        "12 feed 15.000 -15.000 200.000/min".into(),
        format!("13 spindle Cw {}", css(30.0)),
        "14 coolant false".into(),
        format!("14 spindle Cw {}", css(44.0)),
        "14 feed 22.000 -15.000 200.000/min".into(),
        "3 rapid 22.000 2.000".into(),
        format!("4 spindle Cw {}", css(50.0)),
        "4 feed 25.000 5.000 200.000/min".into(),
    ];
    let n = want.len();
    assert_eq!(got[..n.min(got.len())], want[..], "{got:#?}");
    assert!(got.last().is_some_and(|l| l == "5 end"), "{got:#?}");
}

/// A profile block that only dwells or changes modes makes no move of its
/// own and must not end the profile's geometry: G70's path is the same as
/// without it. Here G04 P250 (whole milliseconds: 0.25 s) sits between the
/// two cuts of line 6 and line 8.
#[test]
fn g70_dwell_in_the_profile_is_not_a_move() {
    let program = "G97 S800 M03\n\
                   G00 X40. Z2.\n\
                   G70 P10 Q20\n\
                   M30\n\
                   N10 G00 X30.\n\
                   G01 Z-10. F0.2\n\
                   G04 P250\n\
                   N20 X40.\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
    let got = trace(&events);
    let want = [
        "1 spindle Cw 800.000",
        "2 rapid 20.000 2.000",
        "5 rapid 15.000 2.000",
        "6 feed 15.000 -10.000 0.200/rev",
        "7 dwell 0.250",
        "8 feed 20.000 -10.000 0.200/rev",
        "3 rapid 20.000 2.000",
        "4 end",
    ];
    assert_eq!(got, want, "{got:#?}");
}

/// The profile of the roughing tests: M08, G04, T, G98 G96 S F and F in
/// its blocks (`with_words`), or blank comment lines in their place, so
/// that both programs have the same line numbers.
fn rough_program(cycle: &str, with_words: bool) -> String {
    let words = |w: &'static str| if with_words { w } else { "()" };
    format!(
        "G97 S1000 M03\n\
         G00 X40. Z2.\n\
         {cycle}\n\
         G01 X45. Z5.\n\
         M30\n\
         N10 G00 X30. {}\n\
         {}\n\
         {}\n\
         {}\n\
         G01 Z-10. {}\n\
         N20 X40. {}\n",
        words("M08"),
        words("G04 X1."),
        words("T0202"),
        words("G98 G96 S200 F500."),
        words("F0.1"),
        words("M09"),
    )
}

/// G71 and G73 rough with the cycle block's F and ignore G04, M08,
/// M09, T, G98, G96, S and F in the profile: their events are those of the
/// same profile without those words, none of them is a dwell, coolant,
/// tool change or spindle event, every roughing feed is the cycle's
/// 0.3 mm/rev, and after the cycle (lines 3–4) the G01 of line 5 still
/// feeds at G99 F0.3 with the spindle at 1000 rpm (no spindle event
/// after line 1): the roughing changed no mode. (G72
/// reads the profile through the same code as G71.)
#[test]
fn roughing_ignores_the_profile_words() {
    let cycles = [
        "G71 U2. R0.5\nG71 P10 Q20 U0.4 W0.1 F0.3",
        "G73 U4. W0. R2\nG73 P10 Q20 U0.4 W0.1 F0.3",
    ];
    for cycle in cycles {
        let with = rough_program(cycle, true);
        let without = rough_program(cycle, false);
        let (ev_with, out_with) = run(&with);
        let (ev_without, out_without) = run(&without);
        assert!(
            matches!(out_with, Outcome::Ended(EndCode::M30)),
            "{cycle}: {out_with:?}"
        );
        assert!(matches!(out_without, Outcome::Ended(EndCode::M30)));
        assert_eq!(trace(&ev_with), trace(&ev_without), "{cycle}");
        let mut feeds = 0;
        for e in &ev_with {
            match e {
                Event::Dwell { .. } | Event::Coolant { .. } | Event::ToolChange { .. } => {
                    panic!("{cycle}: {e:?}")
                }
                Event::Spindle { loc, dir, rpm, .. } => {
                    assert_eq!(
                        (loc.line, *dir, *rpm),
                        (1, SpindleDir::Cw, 1000.0),
                        "{cycle}"
                    )
                }
                Event::Feed { feed, .. } => {
                    feeds += 1;
                    assert_eq!(*feed, Feed::PerRev(0.3), "{cycle}");
                }
                _ => {}
            }
        }
        assert!(feeds > 1, "{cycle}");
        assert!(
            ev_with
                .iter()
                .any(|e| matches!(e, Event::Feed { loc, .. } if loc.line == 5)),
            "{cycle}"
        );
    }
}

/// What stays forbidden in a profile: E344 at the word, in the profile
/// block's own line (line 6) and column (1-based).
#[test]
fn forbidden_profile_words_are_e344_at_the_word() {
    let cases = [
        ("G01 Z-10. M99", 11),      // M99 (program flow)
        ("G01 Z-10. M98 P100", 11), // M98
        ("G20 G01 Z-10.", 1),       // G20 (group 06)
        ("G28 U0.", 1),             // a one-shot code other than G04
        ("G32 Z-10. F1.5", 1),      // group 01 other than G00–G03
        ("G01 Z-10. P5", 11),       // P belongs to G04 only
        ("G01 Z-10. M30", 11),      // a program end inside the cycle
    ];
    for cycle in ["G71 P10 Q20 U0.4 W0.1 D1000 F0.3", "G70 P10 Q20"] {
        for (block, column) in cases {
            let program =
                format!("M03 S500\nG00 X40. Z2.\n{cycle}\nM30\nN10 G00 X30.\n{block}\nN20 X40.\n");
            let (_, out) = run(&program);
            let Outcome::Alarm(d) = out else {
                panic!("{block}: {out:?}")
            };
            assert_eq!(
                (d.code.as_str(), d.line, d.column),
                ("E344", 6, column),
                "{cycle} / {block}: {}",
                d.message
            );
        }
    }
}

/// E343 for a profile that never reaches the stock: `G71 P1 Q1` whose one
/// block `N1 G0 X30.` is only the approach from A (X50): there is no
/// shape below A to cut. The message must say that, not that the profile
/// "lies on both sides of the start point" (it lies on neither). The
/// alarm is at the profile's block: line 4, column 4 (the G0).
#[test]
fn a_profile_of_only_its_approach_says_so() {
    let program = "M03 S500\nG00 X50. Z2.\nG71 P1 Q1 U0.4 W0.1 D1000 F0.2\nN1 G0 X30.\nM30\n";
    let (_, out) = run(program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line, d.column), ("E343", 4, 4));
    assert!(!d.message.contains("both sides"), "{}", d.message);
    assert!(
        d.message.contains("never reaches the stock"),
        "{}",
        d.message
    );
    assert!(d.message.contains("only its first block"), "{}", d.message);
    // A shape that runs on A's own level (X50 from A at X50, then along Z)
    // never reaches the stock either; the alarm is at the first block's
    // G0 (line 4, column 4) and says so.
    let program =
        "M03 S500\nG00 X50. Z2.\nG71 P1 Q2 U0.4 W0.1 D1000 F0.2\nN1 G0 X50.\nN2 G1 Z-10.\nM30\n";
    let (_, out) = run(program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line, d.column), ("E343", 4, 4));
    assert!(d.message.contains("start point's level"), "{}", d.message);
}
