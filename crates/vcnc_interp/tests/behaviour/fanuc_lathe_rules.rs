//! Regressions found by the adversarial review of `--dialect fanuc-lathe`
//! (issue 11). Each test names the Fanuc lathe behaviour it guards; the
//! expected values are worked out by hand in the comments, from the Fanuc
//! 0i-TF reading documented in docs/dialects.md.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common;
use vcnc_interp::{Dialect, EndCode, Event, Outcome};

const X: usize = 0;
const Z: usize = 1;

fn run(program: &str) -> (Vec<Event>, Outcome) {
    common::run_on_its_machine(&Dialect::fanuc_lathe(), program)
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

/// The alarm that ended a run.
fn alarm(out: &Outcome) -> &vcnc_syntax::Diagnostic {
    match out {
        Outcome::Alarm(d) => d,
        other => panic!("expected an alarm, got {other:?}"),
    }
}

/// E342's help must name the Fanuc lathe's feed-per-minute code G98: the
/// mill's G94 is the facing cycle here, so following the old advice would
/// run a cycle instead of changing the feed mode.
#[test]
fn per_rev_feed_with_spindle_stopped_suggests_g98() {
    let (_, out) = run("G00 X50. Z2.\nG01 Z-10. F0.2\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E342", 2, 1));
    assert!(d.help.contains("G98"), "{}", d.help);
    assert!(!d.help.contains("G94"), "{}", d.help);
}

/// A thread cannot feed per minute: E342 on a G92 thread suggests
/// starting the spindle only.
#[test]
fn thread_with_spindle_stopped_does_not_suggest_feed_per_minute() {
    let (_, out) = run("G00 X40. Z5.\nG92 X38. Z-20. F1.5\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E342", 2, 1));
    assert!(!d.help.contains("per minute"), "{}", d.help);
}

/// G76 without a lead is E311; the message must not speak of G33, a code
/// this dialect does not have (its threads are G32, G76 and G92).
#[test]
fn thread_without_lead_does_not_name_g33() {
    let (_, out) = run("M03 S500\nG00 X50. Z2.\nG76 X40. Z-5. P2000 Q500\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E311", 3, 1));
    assert!(!d.message.contains("G33"), "{}", d.message);
}

/// A negative depth of cut in G71's first block (Fanuc writes Δd without a
/// sign) alarms at the U word (line 3, column 5) with a message that says
/// so; it used to read "the depth of cut -2 is zero".
#[test]
fn negative_g71_depth_says_negative_not_zero() {
    let (events, out) =
        run("M03 S500\nG00 X50. Z2.\nG71 U-2. R0.5\nG71 P1 Q2 F.2\nN1 G0 X30.\nN2 G1 Z-10.\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E109", 3, 5));
    assert!(!d.message.contains("zero"), "{}", d.message);
    // Nothing of line 3 or later moved.
    assert!(!events.iter().any(|e| matches!(e,
        Event::Rapid { loc, .. } | Event::Feed { loc, .. } if loc.line >= 3)));
}

/// Fanuc 0i-T forbids in a profile (ns..nf) only one-shot G codes other
/// than G04, group 01 codes other than G00–G03, G20/G21 and M98/M99; the
/// usual layout starts nose radius compensation in the profile's first
/// block (`N10 G00 G42 X30.`) and cancels it in the last, and G70 applies
/// it. G71 roughs without it.
///
/// Tool 1: nose radius 0.8, tip 3 (the tip is (-r, -r) from the nose
/// centre in (Z, X radius)). Profile from A (X50 Z2: radius 25): G42 G00
/// to radius 15, Z-10, G40 out to radius 25.
/// - G42 (tool on +X of a -Z move): on Z-10 the centre runs at radius
///   15.8 and the tip at 15.8 - 0.8 = 15.0: the programmed line, whose
///   end is the inside corner with the face N20 (Z-10 radius 15 -> 25):
///   the face's offset line is Z -10 + 0.8 (+Z of a +X move), so the
///   centre stops at Z-9.2 and the tip at Z-9.2 - 0.8 = -10.0.
///
/// So G70's feed on line 6 ends at (15.0, -10.0), as without
/// compensation: a sharp-tip path on axis-parallel lines.
#[test]
fn g41_g42_g40_in_a_profile_are_applied_by_g70() {
    let program = "M03 S500\n\
                   T0101\n\
                   G00 X50. Z2.\n\
                   G71 P10 Q20 U0.4 W0.1 D1000 F0.2\n\
                   N10 G00 G42 X30.\n\
                   G01 Z-10.\n\
                   N20 G40 X50.\n\
                   G70 P10 Q20\n\
                   M30\n";
    let (events, out) = run(program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
    let z_cut = feeds_of_line(&events, 6);
    assert_eq!(z_cut.len(), 1, "{z_cut:?}");
    assert!((z_cut[0].0 - 15.0).abs() < 1e-6, "{z_cut:?}");
    assert!((z_cut[0].1 + 10.0).abs() < 1e-6, "{z_cut:?}");
    // The G40 block (line 7) ends at its programmed point: radius 25, Z-10.
    let out_cut = feeds_of_line(&events, 7);
    let last = out_cut.last().copied().unwrap();
    assert!(
        (last.0 - 25.0).abs() < 1e-6 && (last.1 + 10.0).abs() < 1e-6,
        "{out_cut:?}"
    );
}

/// An arc cannot start compensation: G42 on a G02 profile block is E317 at
/// the arc's G word (line 6, column 1), as in a program.
#[test]
fn g42_on_a_profile_arc_is_e317() {
    let program = "M03 S500\n\
                   T0101\n\
                   G00 X50. Z2.\n\
                   G70 P10 Q20\n\
                   N10 G00 X30.\n\
                   G02 G42 X40. Z-5. R5.\n\
                   N20 G01 X50.\n\
                   M30\n";
    let (_, out) = run(program);
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E317", 6, 1));
}

/// R of G73 is the number of passes in the first block only (Fanuc 0i-T:
/// `G73 U W R; G73 P Q U W F;`). In the second block nothing reads it, so
/// it is E203 at the R word (line 4, column 22), as for G71 and G72,
/// rather than a pass count silently ignored.
#[test]
fn r_in_g73_second_block_is_e203() {
    let program = "M03 S500\n\
                   G00 X50. Z2.\n\
                   G73 U2. W1. R3\n\
                   G73 P10 Q20 U0.4 F.2 R5\n\
                   N10 G00 X30.\n\
                   G01 Z-10.\n\
                   N20 X50.\n\
                   M30\n";
    let (events, out) = run(program);
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E203", 4, 22));
    assert!(!events.iter().any(|e| matches!(e,
        Event::Rapid { loc, .. } | Event::Feed { loc, .. } if loc.line >= 4)));
}

/// Coordinate setting and the spindle clamp are G50 on a Fanuc lathe (G92
/// is the threading cycle): `G50 X100. S2000` is E208 at the S word (line
/// 2, column 11) and a bare `G50` is E312, both naming G50, not G92.
#[test]
fn g50_alarms_name_g50() {
    let (_, out) = run("G00 X50. Z2.\nG50 X100. S2000\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E208", 2, 11));
    assert!(
        d.message.contains("G50") && !d.message.contains("G92"),
        "{}",
        d.message
    );
    assert!(!d.help.contains("G92"), "{}", d.help);
    let (_, out) = run("G00 X50. Z2.\nG50\nM30\n");
    let d = alarm(&out);
    assert_eq!((d.code.as_str(), d.line, d.column), ("E312", 2, 1));
    assert!(
        d.message.contains("G50") && !d.message.contains("G92"),
        "{}",
        d.message
    );
}

/// A chamfer or corner R of zero or below is wrong in its own block: E347
/// at the `,C`/`,R` word (line 5, column 6, the comma), not at the next
/// block, and nothing of line 5 moves.
#[test]
fn non_positive_chamfer_alarms_at_its_word() {
    for corner in [",C-1.", ",C0", ",R0", ",R-2."] {
        let program =
            format!("M03 S500\nG00 X50. Z2.\nG01 X30. F.2\nZ-5.\nX40. {corner}\nZ-20.\nM30\n");
        let (events, out) = run(&program);
        let d = alarm(&out);
        assert_eq!(
            (d.code.as_str(), d.line, d.column),
            ("E347", 5, 6),
            "{corner}"
        );
        assert!(!events.iter().any(|e| matches!(e,
            Event::Rapid { loc, .. } | Event::Feed { loc, .. } | Event::Arc { loc, .. } if loc.line >= 5)));
    }
}
