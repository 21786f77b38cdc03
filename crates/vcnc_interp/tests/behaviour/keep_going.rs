//! `Options::keep_going`: after an alarm the run goes on with the next
//! block, the state as it was before the alarmed one, so that an editor
//! (the language server) or `vcnc check --keep-going` shows every mistake
//! of a program at once. Expected positions are worked out from the
//! programs by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common::Store;
use vcnc_interp::{Dialect, Event, Interpreter, MAX_ALARMS, Machine, Options, Outcome, VecSink};
use vcnc_syntax::Code;

fn run(program: &str) -> (Vec<Event>, Outcome) {
    run_in(&Dialect::fanuc(), program)
}

fn run_in(dialect: &Dialect, program: &str) -> (Vec<Event>, Outcome) {
    let machine = Machine::default_mill();
    let opts = Options {
        keep_going: true,
        ..Options::default()
    };
    let mut sink = VecSink::default();
    let out = Interpreter::new(&machine, dialect, opts).run_str(program, &mut sink);
    (sink.0, out)
}

fn alarms(events: &[Event]) -> Vec<(Code, u64)> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Alarm(d) => Some((d.code, d.line)),
            _ => None,
        })
        .collect()
}

/// The X of every feed, in order.
fn feed_xs(events: &[Event]) -> Vec<f64> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { to, .. } => Some(to.get(0)),
            _ => None,
        })
        .collect()
}

#[test]
fn three_mistakes_give_three_alarms_and_the_program_runs_on() {
    // Line 3: an arc whose end is off its circle (E303); line 5: a
    // negative dwell (E109); line 6: G0 with a word G0 does not read (E203).
    let program = "G21 G90 G17 S1000 M03\nG01 X10. F100.\nG02 X20. Y0 I-99. J0\nG01 X30.\nG04 X-1.\nG00 X5. Q2.\nG01 X40.\nM30\n";
    let (events, out) = run(program);
    assert_eq!(
        alarms(&events),
        vec![(Code::E303, 3), (Code::E109, 5), (Code::E203, 6)]
    );
    // The alarmed blocks move nothing; the others move from where the
    // last good block left the tool.
    assert_eq!(feed_xs(&events), vec![10.0, 30.0, 40.0]);
    assert!(matches!(events.last(), Some(Event::End { .. })));
    // The run's outcome is its first alarm: it is not a clean run.
    match out {
        Outcome::Alarm(d) => assert_eq!((d.code, d.line), (Code::E303, 3)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_alarmed_block_leaves_the_modes_as_they_were() {
    // G91 in a block that alarms (an unknown G code) does not take effect:
    // the next X15. is absolute, to X15, not 15 more (to 25).
    let program = "G21 G90 S1000 M03\nG01 X10. F100.\nG91 G999 X5.\nG01 X15.\nM30\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events), vec![(Code::E201, 3)]);
    assert_eq!(feed_xs(&events), vec![10.0, 15.0]);
}

#[test]
fn runaway_limits_still_end_the_run() {
    // A GOTO loop without end: E405 (jumps) ends it even under keep-going.
    let program = "N1 #1=[#1+1]\nGOTO 1\nM30\n";
    let mut machine = Machine::default_mill();
    machine.limits.max_jumps = 1000;
    let dialect = Dialect::fanuc();
    let opts = Options {
        keep_going: true,
        ..Options::default()
    };
    let mut sink = VecSink::default();
    let out = Interpreter::new(&machine, &dialect, opts).run_str(program, &mut sink);
    match out {
        Outcome::Alarm(d) => assert!(matches!(d.code, Code::E404 | Code::E405), "{d:?}"),
        other => panic!("{other:?}"),
    }
    assert!(!matches!(sink.0.last(), Some(Event::End { .. })));
}

#[test]
fn a_flood_of_alarms_stops_at_the_limit() {
    let bad = "G999\n".repeat(MAX_ALARMS as usize + 50);
    let (events, out) = run(&format!("{bad}M30\n"));
    // The limit's alarms as events, and the next one as the run's end.
    assert_eq!(alarms(&events).len(), MAX_ALARMS as usize + 1);
    assert!(matches!(out, Outcome::Alarm(_)));
}

#[test]
fn a_bad_macro_statement_does_not_stall_the_line() {
    // An unreadable statement, then a good block on the next line.
    let program = "#1=[1+\nG01 X7. F100.\nM30\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events).len(), 1);
    assert_eq!(feed_xs(&events), vec![7.0]);
}

#[test]
fn without_keep_going_the_first_alarm_ends_the_run() {
    let machine = Machine::default_mill();
    let dialect = Dialect::fanuc();
    let mut sink = VecSink::default();
    let out = Interpreter::new(&machine, &dialect, Options::default())
        .run_str("G999\nG01 X1. F1.\nM30\n", &mut sink);
    assert!(matches!(out, Outcome::Alarm(_)));
    assert_eq!(alarms(&sink.0).len(), 1);
    assert!(feed_xs(&sink.0).is_empty());
}

/// A corner round that cannot be made (R20 on 10 mm lines, E347 at the
/// block after it) leaves its G01 to run straight to the corner: the next
/// blocks read as written, no stale corner alarms them again, and M30 ends
/// the run (before, every later block alarmed E347 and nothing moved).
#[test]
fn a_corner_that_cannot_be_made_runs_its_g01_straight_and_the_program_goes_on() {
    let program =
        "G90 G21 G17 M3 S1000\nG0 X0 Y0\nG1 X10. Y0 ,R20. F100\nG1 X10. Y10.\nX20.\nM30\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events), vec![(Code::E347, 4)]);
    // Line 3's G01 straight to (10, 0); line 4 skipped; line 5 on to X20.
    let feeds: Vec<(u64, f64, f64)> = events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { loc, to, .. } => Some((loc.line, to.get(0), to.get(1))),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, vec![(3, 10.0, 0.0), (5, 20.0, 0.0)]);
    assert!(matches!(events.last(), Some(Event::End { .. })));
}

#[test]
fn a_linuxcnc_line_that_alarms_on_a_later_pass_skips_that_line_only() {
    // Line 4 divides by 2 - #1: on the second pass (#1 = 2) by zero
    // (E608). The line has been run once already, so this pass runs it
    // from the statement cache; its alarm must still be that of a line
    // (the run goes on with the next line) and the third pass moves to
    // 10 / (2 - 3) = -10.
    let program = "#1 = 0\no100 while [#1 LT 3]\n#1 = [#1 + 1]\nG1 X[10 / [2 - #1]] F100\no100 endwhile\nM2\n";
    let (events, _) = run_in(&Dialect::linuxcnc(), program);
    assert_eq!(alarms(&events), vec![(Code::E608, 4)]);
    assert_eq!(feed_xs(&events), vec![10.0, -10.0]);
    assert!(matches!(events.last(), Some(Event::End { .. })));
}

/// An alarm inside G70's finishing pass drops the G70 block, and the run
/// goes on after it — not where reading the profile left the program
/// (review of 2026-12-06: the run ended at the G70 with W106, or replayed
/// the profile until the alarm cap).
#[test]
fn an_alarm_in_a_profile_cycle_goes_on_after_the_cycle_block() {
    let lathe = Dialect::fanuc_lathe();
    // G70 alone: its profile's G01 has no feed (E301 at line 9).
    let program = "O0001\nG21 G18 G99\nT0101\nG97 S500 M03\nG00 X80. Z2.\nG70 P10 Q20\nM30\n\
                   N10 G00 X20.\nG01 Z-20.\nN20 G01 X82.\n";
    let (events, out) = run_in(&lathe, program);
    assert_eq!(alarms(&events), vec![(Code::E301, 9)]);
    assert!(ends_with_m30(&events), "{out:?}");
    // G71 whose profile starts inside the stock (E343), then the same
    // profile run as blocks and by G70: each alarm once, then M30.
    let program = "O0001\nG21 G18 G99\nT0101\nG97 S500 M03\nG00 X80. Z2.\nG71 U2. R0.5\n\
                   G71 P10 Q20 U0.4 W0.1 F0.25\nN10 G00 X20.\nG01 Z-20.\nN20 G01 X82.\n\
                   G70 P10 Q20\nM30\n";
    let (events, out) = run_in(&lathe, program);
    assert_eq!(
        alarms(&events),
        vec![
            (Code::E343, 8),
            (Code::E301, 9),
            (Code::E301, 10),
            (Code::E301, 9)
        ]
    );
    assert!(ends_with_m30(&events), "{out:?}");
}

/// Whether the run reached its M30 (the last event).
fn ends_with_m30(events: &[Event]) -> bool {
    matches!(
        events.last(),
        Some(Event::End {
            code: vcnc_interp::EndCode::M30,
            ..
        })
    )
}

/// A Syntec `%@MACRO` program goes on after an alarmed statement like any
/// other (review of 2026-12-06: the first alarm ended the run, so the
/// editor showed one mistake of such a program).
#[test]
fn a_macro_file_goes_on_after_an_alarmed_statement() {
    let program = "%@MACRO\nG00 X0. Y0. Z0.;\nG02 X10. Y0. R0.;\nG01 X5. F100.;\n\
                   G02 X10. Y0. R0.;\nG01 X7.;\nM30;\n";
    let (events, _) = run_in(&Dialect::syntec(), program);
    assert_eq!(alarms(&events).len(), 2, "{events:#?}");
    assert_eq!(
        alarms(&events).iter().map(|a| a.1).collect::<Vec<_>>(),
        vec![3, 5]
    );
    assert_eq!(feed_xs(&events), vec![5.0, 7.0]);
    assert!(matches!(events.last(), Some(Event::End { .. })));
}

/// A G06.2 curve keeps what its blocks before an alarmed one gave: the
/// next blocks go on defining it (review of 2026-12-06: the curve was
/// dropped at the first alarm and each later block alarmed again).
#[test]
fn a_curve_being_defined_survives_an_alarmed_block() {
    let program = "G90 G17\nG00 X0. Y0. Z0.\nG05 P10000\nG06.2 P4 K0. X0. Y0. Z0. R1. F1000.\n\
                   K0. X10. Y10. R1.\nK0. X20. Y0. R1.\nK0. X30. Y10. R1.\nK1.\nK0.5\nK1.\nK1.\n\
                   K1.\nG05 P0\nM30\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events), vec![(Code::E329, 9)]);
    assert_eq!(
        events
            .iter()
            .filter(|e| matches!(e, Event::Nurbs { .. }))
            .count(),
        1,
        "{events:#?}"
    );
    assert!(ends_with_m30(&events));
}

/// After an alarm a G01 held for its `,R` runs straight to its corner;
/// when that move cannot be made either (here an over-cut under G41), its
/// alarm is reported too instead of the move vanishing (review of
/// 2026-12-06).
#[test]
fn a_released_corner_that_cannot_move_is_reported() {
    let program = "G21 G17 G90 G54\nS1000 M03\nG10 L12 P1 R3.\nG00 X-20. Y-20. Z1.\n\
                   G01 Z-1. F100.\nG41 D1 X0. Y0.\nG01 Y50.\nX50.\nG01 X0. ,R1.\nG00 Z5.\n\
                   G40 X-20. Y-20.\nM30\n";
    let (events, _) = run(program);
    let found = alarms(&events);
    assert_eq!(found.first(), Some(&(Code::E347, 10)), "{found:?}");
    assert_eq!(found.get(1).map(|a| a.1), Some(9), "{found:?}");
}

/// Runs `program` under `dialect`, its subprograms from `store`, with or
/// without keep-going.
fn run_with(
    dialect: &Dialect,
    program: &str,
    store: Store,
    keep_going: bool,
) -> (Vec<Event>, Outcome) {
    let machine = dialect.machine();
    let opts = Options {
        keep_going,
        ..Options::default()
    };
    let mut sink = VecSink::default();
    let mut store = store;
    let out = Interpreter::new(&machine, dialect, opts).run(
        Box::new(vcnc_syntax::MemSource(program.as_bytes().to_vec())),
        &mut store,
        &mut sink,
    );
    (sink.0, out)
}

/// The line of every feed, in order.
fn feed_lines(events: &[Event]) -> Vec<u64> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { loc, .. } => Some(loc.line),
            _ => None,
        })
        .collect()
}

/// An M99 that alarms (here E347: the block after a held `,C` must be a
/// G01) still returns to the caller once its alarm is reported, so the
/// caller's remaining blocks are checked too (review of 2026-12-06: the
/// subprogram was left without a return, E406 ended the run). Without
/// keep-going the first alarm still ends the run there.
#[test]
fn an_alarmed_m99_still_returns_to_the_caller() {
    let lathe = Dialect::fanuc_lathe();
    let main = "O0001\nG21 G18 G99\nT0101\nG97 S500 M03\nG00 X80. Z2.\nG01 X20. Z0. F0.2\n\
                M98 P2000\nG01 X60.\nG01 Z-30.\nM98 P3000\nG01 X70. Z-50.\nG00 X100. Z100.\nM30\n";
    let store = || {
        Store::default()
            .with(2000, "O2000\nG01 Z-10.\nG01 Z-20. ,C50.\nM99\n")
            .with(3000, "O3000\nG01 X64. ,R1.\nM99\n")
    };
    let (events, _) = run_with(&lathe, main, store(), true);
    // One alarm per mistake, each at its subprogram's M99 (O2000 line 4,
    // O3000 line 3), and no E406.
    assert_eq!(alarms(&events), vec![(Code::E347, 4), (Code::E347, 3)]);
    // The held G01s run straight (O2000 line 3, O3000 line 2), and each
    // return goes on with the caller's next block: lines 8, 9 and 11.
    assert_eq!(feed_lines(&events), vec![6, 2, 3, 8, 9, 2, 11]);
    assert!(ends_with_m30(&events));

    let (events, out) = run_with(&lathe, main, store(), false);
    assert_eq!(alarms(&events), vec![(Code::E347, 4)]);
    assert_eq!(feed_lines(&events), vec![6, 2]);
    assert!(matches!(out, Outcome::Alarm(d) if d.code == Code::E347));
}

/// An M30 in a block that alarms still ends the program after its alarm
/// (the text after it is not run, as on the machine).
#[test]
fn an_alarmed_m30_still_ends_the_program() {
    let program = "G21 G90 S1000 M03\nG01 X10. F100.\nG01 X20. Q1. M30\nG01 X30.\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events), vec![(Code::E203, 3)]);
    assert_eq!(feed_xs(&events), vec![10.0]);
    assert!(ends_with_m30(&events));
}

/// When the alarmed block's own return cannot be made either (M99 P of a
/// sequence the caller lacks), the run goes on with the next block as
/// after any alarm, and that return's alarm is not reported twice.
#[test]
fn an_alarmed_m99_whose_return_fails_goes_on_with_the_next_block() {
    let main = "G21 G90 S1000 M03\nG01 X1. F100.\nM98 P2000\nG01 X9.\nM30\n";
    let store = Store::default().with(2000, "O2000\nG01 X5. Q1. M99 P999\nG01 X7.\nM99\n");
    let (events, _) = run_with(&Dialect::fanuc(), main, store, true);
    assert_eq!(alarms(&events), vec![(Code::E203, 2)]);
    assert_eq!(feed_xs(&events), vec![1.0, 7.0, 9.0]);
    assert!(ends_with_m30(&events));
}

/// The same when the failed return searched the block's own program (an
/// M99 P of the main program): the search walked the reader to the end of
/// the text, and the run still goes on right after the alarmed block —
/// with the next block of its own line when one follows (review 4,
/// finding 1: it ended at the end of the text, with a false W106).
#[test]
fn an_alarmed_m99_whose_search_fails_goes_on_right_after_the_block() {
    let program =
        "G21 G90 S1000 M03\nG01 X10. F100.\nG01 X20. Q5. M99 P3; G01 X30.\nG01 X99.\nM30\n";
    let (events, _) = run(program);
    assert_eq!(alarms(&events), vec![(Code::E203, 3)]);
    assert_eq!(feed_xs(&events), vec![10.0, 30.0, 99.0]);
    assert!(ends_with_m30(&events));
}

/// A LinuxCNC O-word whose condition cannot be evaluated reads as false
/// after its alarm: an `if` goes to its next branch, a `while` or `repeat`
/// past its end, a `do`'s closing `while` out of the loop — once, on both
/// the statement's first pass and its cached ones (review 4, finding 4: a
/// `while [1/0]` fell into its body and met its alarm again at each pass,
/// up to the alarm limit, and the rest of the program went unchecked).
#[test]
fn an_o_word_condition_that_alarms_reads_as_false() {
    let program = "G21 G90 S1000 M03\nG1 X1 F100\n\
                   o12 if [1/0]\n  G1 X3\no12 elseif [1]\n  G1 X5\no12 else\n  G1 X6\no12 endif\n\
                   o13 repeat [1/0]\n  G1 X7\no13 endrepeat\n\
                   o14 do\n  G1 X8\no14 while [1/0]\n\
                   o15 repeat [2]\n  o16 while [#<_vacant>]\n    G1 X9\n  o16 endwhile\no15 endrepeat\n\
                   G1 X4\nM2\n";
    let (events, _) = run_in(&Dialect::linuxcnc(), program);
    // The second pass of o15 runs o16 from the statement cache.
    let codes: Vec<u64> = alarms(&events).iter().map(|a| a.1).collect();
    assert_eq!(codes, vec![3, 10, 15, 17, 17]);
    assert_eq!(feed_xs(&events), vec![1.0, 5.0, 8.0, 4.0]);
    assert!(matches!(events.last(), Some(Event::End { .. })));
}

/// Macro B the same: a WHILE or IF whose condition cannot be evaluated
/// reads as false after its alarm (past END, or no jump), and a statement
/// that alarms on a later pass of a loop — run from the statement cache —
/// is reported and skipped like on its first (review 4: the cached
/// statement's alarm ended the run under keep-going, with no `end` and the
/// rest of the program unchecked).
#[test]
fn a_macro_b_condition_or_a_cached_statement_that_alarms_goes_on() {
    let program = "G21 G90 S1000 M03\nG01 X1. F100\n\
                   WHILE [[1/0] GT 0] DO1\nG01 X3.\nEND1\n\
                   #1=0\nWHILE [#1 LT 3] DO2\n#2=1/[#1-1]\n#1=#1+1\nEND2\n\
                   IF [[1/0] GT 0] GOTO 99\nG01 X4.\nN99 G01 X5.\nM30\n";
    let (events, _) = run(program);
    // Line 8 alarms on the loop's second pass (#1 = 1), from the cache.
    assert_eq!(
        alarms(&events),
        vec![(Code::E608, 3), (Code::E608, 8), (Code::E608, 11)]
    );
    assert_eq!(feed_xs(&events), vec![1.0, 4.0, 5.0]);
    assert!(ends_with_m30(&events));
}
