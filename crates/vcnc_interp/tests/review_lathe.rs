//! Regressions found by the adversarial review of `--dialect fanuc-lathe`
//! (issue 11). Each test names the Fanuc lathe behaviour it guards; the
//! expected values are worked out by hand in the comments, from the Fanuc
//! 0i-TF reading documented in docs/dialects.md.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, EndCode, Event, Interpreter, Options, Outcome, VecSink};

const X: usize = 0;
const Z: usize = 1;

fn run(program: &str) -> (Vec<Event>, Outcome) {
    let d = Dialect::fanuc_lathe();
    let m = d.machine();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&m, &d, Options::default()).run_str(program, &mut sink);
    (sink.0, out)
}

/// The feed moves' end points (X radius, Z) of the given source line.
fn feeds_of_line(events: &[Event], line: u64) -> Vec<(f64, f64)> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { loc, to, .. } if loc.line == line => Some((to.get(X), to.get(Z))),
            _ => None,
        })
        .collect()
}

/// A profile written after M30 (Fanuc practice: the main program calls the
/// cycles, the finished shape sits at the end of the file) does not follow
/// the G71 block, so the program goes on after the G71 block: G70 on line 5
/// finishes along the profile and M30 on line 6 ends the run. Jumping
/// after N20 instead would skip G70 and M30 and fall off the end.
#[test]
fn profile_after_m30_resumes_after_the_cycle_block() {
    let program = "M03 S500\n\
                   G00 X50. Z2.\n\
                   G71 U1. R0.5\n\
                   G71 P10 Q20 U0.4 W0.1 F0.2\n\
                   G70 P10 Q20\n\
                   M30\n\
                   N10 G00 X30.\n\
                   G01 Z-10. F0.1\n\
                   N20 X50.\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
    // G70 cuts the profile's own blocks (lines 8 and 9) exactly: from
    // X30 (radius 15) along Z to -10, then out to X50 (radius 25).
    let finish: Vec<_> = [8, 9]
        .iter()
        .flat_map(|&l| feeds_of_line(&events, l))
        .collect();
    let want = [(15.0, -10.0), (25.0, -10.0)];
    assert_eq!(finish.len(), 2, "{finish:?}");
    for (got, want) in finish.iter().zip(want) {
        assert!((got.0 - want.0).abs() < 1e-9 && (got.1 - want.1).abs() < 1e-9);
    }
}
