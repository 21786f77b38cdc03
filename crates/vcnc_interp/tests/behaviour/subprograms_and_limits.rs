//! Regression tests for what an adversarial review found (each test names
//! the bug it guards). Expected values are worked out from the manuals and
//! docs/dialects.md, not copied from vcnc's output.
#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::collections::HashMap;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, ProgramStore, VecSink};
use vcnc_syntax::{Code, MemSource, TextSource};

struct Store(HashMap<u32, &'static str>);

impl ProgramStore for Store {
    fn open(&mut self, n: u32) -> Option<std::io::Result<(Box<dyn TextSource>, String)>> {
        let text = self.0.get(&n)?;
        Some(Ok((
            Box::new(MemSource(text.as_bytes().to_vec())),
            format!("O{n:04}.nc"),
        )))
    }
}

fn run_with(
    dialect: &Dialect,
    machine: &Machine,
    program: &str,
    store: &[(u32, &'static str)],
) -> (Vec<Event>, Outcome) {
    let mut sink = VecSink::default();
    let mut store = Store(store.iter().copied().collect());
    let out = Interpreter::new(machine, dialect, Options::default()).run(
        Box::new(MemSource(program.as_bytes().to_vec())),
        &mut store,
        &mut sink,
    );
    (sink.0, out)
}

fn run(dialect: &Dialect, program: &str) -> (Vec<Event>, Outcome) {
    run_with(dialect, &dialect.machine(), program, &[])
}

/// (x, y or z, …) of every move, rounded to 1e-6.
fn ends(events: &[Event], axes: usize) -> Vec<Vec<f64>> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Rapid { to, .. }
            | Event::Feed { to, .. }
            | Event::Arc { to, .. }
            | Event::Thread { to, .. } => {
                Some((0..axes).map(|i| (to.get(i) * 1e6).round() / 1e6).collect())
            }
            _ => None,
        })
        .collect()
}

fn alarm(out: &Outcome) -> (Code, u64, u32) {
    match out {
        Outcome::Alarm(d) => (d.code, d.line, d.column),
        other => panic!("expected an alarm, got {other:?}"),
    }
}

#[test]
fn tape_format_main_returns_to_its_sequence_number() {
    // `%` first, no O number: M99 P20 in O0010 returns to N20 of the main.
    let p = "%\nG91 G01 F100\nM98 P10\nX5.\nN20 Y5.\nM30\nO0010\nX1.\nM99 P20\n%\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    assert_eq!(ends(&ev, 3), vec![vec![1.0, 0.0, 0.0], vec![1.0, 5.0, 0.0]]);
}

#[test]
fn tape_format_main_restarts_on_m99() {
    // Manual chapter 2: M99 in a main program runs it again; a machine
    // would for ever, so vcnc runs one pass and warns (W107).
    let d = Dialect::syntec();
    let (ev, out) = run_with(&d, &d.machine(), "%\nG91 G01 F100 X1.\nM99\n%\n", &[]);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M99));
    assert_eq!(ends(&ev, 1), vec![vec![1.0]]);
    assert!(
        ev.iter()
            .any(|e| matches!(e, Event::Warning(w) if w.code == Code::W107))
    );
}

#[test]
fn repeats_of_a_tape_format_subprogram_file() {
    let (ev, out) = run_with(
        &Dialect::syntec(),
        &Dialect::syntec().machine(),
        "G00 X0\nM98 P11 L2\nM30\n",
        &[(11, "%\nG91 G01 X1. F100\nG90\nM99\n%\n")],
    );
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    // `G00 X0` from X0 does not move: no event.
    assert_eq!(ends(&ev, 1), vec![vec![1.0], vec![2.0]]);
}

#[test]
fn m98_h_into_a_file_with_a_tape_mark_and_header() {
    let (ev, out) = run_with(
        &Dialect::syntec(),
        &Dialect::syntec().machine(),
        "M98 P10 H50\nM30\n",
        &[(10, "%\nO0010\nG91 G01 X1. F100\nN50 Y1.\nM99\n%\n")],
    );
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    // Starts at N50 with the main program's modes (G00, G90): a rapid to Y1.
    assert_eq!(ends(&ev, 2), vec![vec![0.0, 1.0]]);
}

#[test]
fn lathe_g26_q1_runs_the_body_once() {
    let p = "G00 X100 Z100\nN10 G01 U-2 F100\nW-1\nW-1\nG26 L10 Q1\nG01 W-5\nM30\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let last = ends(&ev, 2).pop().unwrap();
    assert_eq!(last, vec![49.0, 93.0]);
}

#[test]
fn lathe_g26_without_its_label_alarms_at_l_after_the_body_ran_once() {
    // No N20 in the program: the G26 has no head, so it alarms when it
    // runs (E402 at its L word), after the blocks before it moved.
    let p = "G00 X100 Z100\nN10 G01 W-1 F100\nG26 L20 Q2\nM30\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(alarm(&out), (Code::E402, 3, 5));
    // G00 from the home position (Z150) moves X, then Z (dog-leg).
    assert_eq!(
        ends(&ev, 2),
        vec![vec![50.0, 150.0], vec![50.0, 100.0], vec![50.0, 99.0]]
    );
}

#[test]
fn lathe_g26_loops_back_to_the_first_block_with_its_label() {
    // Two N10: the sequence search from the program's start finds the
    // first, so both W moves repeat (Z 99, 97, then 96, 94).
    let p = "G00 X100 Z100\nN10 G01 W-1 F100\nN10 W-2\nG26 L10 Q2\nM30\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let z: Vec<f64> = ends(&ev, 2).iter().map(|e| e[1]).collect();
    assert_eq!(z, vec![150.0, 100.0, 99.0, 97.0, 96.0, 94.0]);
}

#[test]
fn lathe_g26_loops_nest_and_an_inner_loop_counts_again_each_pass() {
    // The inner G26 runs N20 twice on each of the outer loop's two passes:
    // six W-1 moves in all.
    let p = "G00 X100 Z100\nN10 G01 W-1 F100\nN20 W-1\nG26 L20 Q2\nG26 L10 Q2\nM30\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let z: Vec<f64> = ends(&ev, 2).iter().map(|e| e[1]).collect();
    assert_eq!(z, vec![150.0, 100.0, 99.0, 98.0, 97.0, 96.0, 95.0, 94.0]);
}

#[test]
fn lathe_g26_in_a_g20_subroutine_loops_within_it() {
    // G20 L50 calls N50 until G24; its G26 L50 Q2 runs the W-1 twice.
    let p = "G00 X100 Z100\nG20 L50\nM30\nN50 G01 W-1 F100\nG26 L50 Q2\nG24\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let z: Vec<f64> = ends(&ev, 2).iter().map(|e| e[1]).collect();
    assert_eq!(z, vec![150.0, 100.0, 99.0, 98.0]);
}

#[test]
fn lathe_g81_with_a_tiny_i_alarms_instead_of_exhausting_memory() {
    let (_, out) = run(
        &Dialect::lathe(),
        "G00 X200 Z100\nG81 X0 Z50 R0 I-0.00001 K0 F100\nM30\n",
    );
    assert_eq!(alarm(&out), (Code::E314, 2, 15));
}

#[test]
fn g33_with_a_zero_lead_alarms() {
    let (_, out) = run(&Dialect::syntec(), "S1000 M03\nG33 Z-10. F0\nM30\n");
    assert_eq!(alarm(&out), (Code::E311, 2, 1));
}

#[test]
fn g97_alone_keeps_the_speed_g96_gave() {
    // T2's D is 5 mm (G10 L12): 1000·130/(π·10) = 4138.03 rpm, kept by
    // G97 without S.
    let d = Dialect::syntec();
    let m = d.machine();
    let mut sink = VecSink::default();
    let mut i = Interpreter::new(&m, &d, Options::default());
    i.run_str(
        "G10 L12 P2 R5.\nT2 M06\nG96 S130 M03\nG97\nM30\n",
        &mut sink,
    );
    assert!(
        (i.state().s_value - 4138.0285).abs() < 1e-3,
        "{}",
        i.state().s_value
    );
    let spindle_events = sink
        .0
        .iter()
        .filter(|e| matches!(e, Event::Spindle { .. }))
        .count();
    assert_eq!(
        spindle_events, 1,
        "G97 alone changes nothing the spindle does"
    );
}

#[test]
fn g96_speed_follows_a_tool_change() {
    // T2's D is 5 mm, T3's 3 mm (G10 L12): 1000·130/(π·6) = 6897 rpm,
    // clamped by G92 S5000.
    let (ev, _) = run(
        &Dialect::syntec(),
        "G10 L12 P2 R5.\nG10 L12 P3 R3.\nT2 M06\nG92 S5000\nG96 S130 M03\nT3 M06\nM30\n",
    );
    let rpms: Vec<f64> = ev
        .iter()
        .filter_map(|e| {
            if let Event::Spindle { rpm, .. } = e {
                Some((rpm * 1e3).round() / 1e3)
            } else {
                None
            }
        })
        .collect();
    assert_eq!(rpms, vec![4138.029, 5000.0]);
}

#[test]
fn lathe_g92_takes_absolute_words_only() {
    let (_, out) = run(&Dialect::lathe(), "G92 X20 W5\nM30\n");
    assert_eq!(alarm(&out), (Code::E203, 1, 9));
}

#[test]
fn over_travel_points_at_an_incremental_word() {
    let m = Machine::from_toml(include_str!(
        "../../../../tests/fixtures/machines/lathe_travel_limits.toml"
    ))
    .unwrap();
    let (_, out) = run_with(&Dialect::lathe(), &m, "N1 G01 F100 U1000\n", &[]);
    assert_eq!(alarm(&out), (Code::E501, 1, 13));
}

#[test]
fn a_chord_longer_than_2r_by_more_than_the_tolerance_alarms() {
    // Chord 10.015 against 2R = 10: 0.015 beyond, tolerance 0.01.
    let (_, out) = run(&Dialect::syntec(), "G01 F100 X0 Y0\nG02 X10.015 R5.\nM30\n");
    assert_eq!(alarm(&out), (Code::E302, 2, 13));
    let (_, ok) = run(&Dialect::syntec(), "G01 F100 X0 Y0\nG02 X10.005 R5.\nM30\n");
    assert_eq!(ok, Outcome::Ended(vcnc_interp::EndCode::M30));
}

#[test]
fn mill_dwell_is_at_most_9999_999_s() {
    let (_, out) = run(&Dialect::syntec(), "G04 X10000.\nM30\n");
    assert_eq!(alarm(&out), (Code::E109, 1, 5));
}

#[test]
fn an_empty_program_ends_on_line_1() {
    let (ev, out) = run(&Dialect::syntec(), "");
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::Eof));
    // W106: no M30; then the end, both on line 1.
    assert!(
        matches!(&ev[..], [Event::Warning(w), Event::End { loc, .. }] if loc.line == 1 && w.code == Code::W106),
        "{ev:?}"
    );
}

// --- second review ---

#[test]
fn m99_p_searches_the_caller_from_its_program_start() {
    // O0010 is entered at N20; O0011's M99 P10 must find N10, which comes
    // before the entry point (docs: searches start at the program start).
    let p = "G91 G01 F100\nM98 P10 H20\nM30\nO0010\nN10 Y1.\nM99\nN20 X1.\nM98 P11\nM99\nO0011\nZ1.\nM99 P10\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    assert_eq!(
        ends(&ev, 3),
        vec![
            vec![1.0, 0.0, 0.0],
            vec![1.0, 0.0, 1.0],
            vec![1.0, 1.0, 1.0]
        ]
    );
}

#[test]
fn lathe_g20_inside_a_subroutine_finds_an_earlier_label() {
    let p = "G00 X100 Z100\nG20 L10\nM30\nN5 G01 W-1 F100\nG24\nN10 G20 L5\nG01 W-2\nG24\n";
    let (ev, out) = run(&Dialect::lathe(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    assert_eq!(ends(&ev, 2).last().unwrap(), &vec![50.0, 97.0]);
}

#[test]
fn e406_after_a_nested_return_points_at_the_callers_last_block() {
    let p = "M98 P10\nM30\nO0010\nG91 G01 F100\nM98 P20\nO0020\nX1.\nM99\n";
    let (_, out) = run(&Dialect::syntec(), p);
    assert_eq!(alarm(&out), (Code::E406, 5, 1));
}

#[test]
fn the_end_of_a_main_program_after_a_call_is_on_the_mains_last_block() {
    let (ev, out) = run(
        &Dialect::syntec(),
        "G91 G01 F100\nM98 P10\n%\nO0010\nX1.\nY1.\nM99\n",
    );
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::Eof));
    assert!(
        matches!(ev.last(), Some(Event::End { loc, .. }) if loc.line == 2 && loc.file.is_none())
    );
}

#[test]
fn g331_never_cuts_deeper_than_the_thread() {
    // R0.03 over 20 passes rounds to 0.002 per pass (diameter): passes 16-19
    // would reach 0.032-0.038 without the clamp. Radius depth at most 0.015.
    let (ev, out) = run(
        &Dialect::lathe(),
        "G0 X30 Z0 S500 M03\nG331 Z-10 X0 I2 K2 R0.03 P20\nM30\n",
    );
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let deepest = ev
        .iter()
        .filter_map(|e| {
            if let Event::Thread { to, .. } = e {
                Some(to.get(0))
            } else {
                None
            }
        })
        .fold(f64::INFINITY, f64::min);
    assert!((deepest - 14.985).abs() < 1e-9, "{deepest}");
}

#[test]
fn e401_help_names_the_file_to_add() {
    let (_, out) = run(&Dialect::syntec(), "M98 P77\nM30\n");
    match out {
        Outcome::Alarm(d) => assert!(d.help.contains("O0077.nc"), "{}", d.help),
        other => panic!("{other:?}"),
    }
}

#[test]
fn labels_passed_by_one_search_are_found_by_the_next_and_duplicates_resolve_to_the_first() {
    // The first search (H3) passes N1 and N2 and stops at N3; H1 and H2 are
    // answered from what it saw; N2 appears twice and the first one (from
    // the program start) is the one found.
    let p = "G91 G01 F100\nM98 H3\nM98 H1\nM98 H2\nM30\nN1 X1.\nM99\nN2 Y1.\nM99\nN3 Z1.\nM99\nN2 Y5.\nM99\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    assert_eq!(
        ends(&ev, 3),
        vec![
            vec![0.0, 0.0, 1.0],
            vec![1.0, 0.0, 1.0],
            vec![1.0, 1.0, 1.0]
        ]
    );
}

/// Regression (found by a random program): a called program that ends right
/// after its header ran no block, so its E406 had no place (line 0). It is
/// located at the call.
#[test]
fn an_empty_subprogram_alarms_at_its_call() {
    let (_, out) = run(&Dialect::syntec(), "G00 X1.\n  M98 P2\nM30\nO0002\n");
    assert_eq!(alarm(&out), (Code::E406, 2, 3));
}

/// The warnings of a run.
fn warnings(events: &[Event]) -> Vec<&vcnc_syntax::Diagnostic> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Warning(d) => Some(d),
            _ => None,
        })
        .collect()
}

#[test]
fn a_tiny_peck_over_a_deep_hole_alarms_instead_of_holding_millions_of_moves() {
    // (1 + 1000) / 0.001 = 1,001,000 pecks in one block: beyond 100,000.
    let p = "S1000 M03\nG00 X0 Y0 Z10.\nG83 X0 Y0 Z-1000. R1. Q0.001 F100.\nM30\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(alarm(&out), (Code::E326, 3, 1));
    assert!(!ev.iter().any(|e| matches!(e, Event::Hole { .. })));
    // 11 pecks × 9999 holes = 109,989: also beyond.
    let p = "S1000 M03\nG00 X0 Y0 Z10.\nG91 G73 X0.1 Z-11. R-9. Q1. K9999 F100.\nM30\n";
    let (_, out) = run(&Dialect::syntec(), p);
    assert_eq!(alarm(&out), (Code::E326, 3, 5));
    // 10 pecks × 9999 holes = 99,990 runs.
    let p = "S1000 M03\nG00 X0 Y0 Z10.\nG91 G73 X0.1 Z-10. R-9. Q1. K9999 F100.\nM30\n";
    let (_, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
}

#[test]
fn a_loop_around_a_block_of_many_holes_meets_the_block_limit_as_soon() {
    // Each pass of the subprogram drills 100 holes (4 moves each): counted
    // by its events, a budget of 5000 stops it after a dozen passes, not
    // after thousands.
    let machine = Machine::from_toml(&vcnc_interp::machine::DEFAULT_MILL_TOML.replace(
        "max_executed_blocks = 5000000",
        "max_executed_blocks = 5000",
    ))
    .unwrap();
    let (ev, out) = run_with(
        &Dialect::syntec(),
        &machine,
        "S1000 M03\nG00 X0 Y0 Z10.\nM98 P2 L9999\nM30\n",
        &[(2, "G91 G81 X1. Z-2. R-8. K100 F100.\nG90 G80\nM99\n")],
    );
    assert_eq!(alarm(&out).0, Code::E404);
    let holes = ev
        .iter()
        .filter(|e| matches!(e, Event::Hole { .. }))
        .count();
    assert!(holes < 2000, "{holes} holes before the limit");
}

#[test]
fn k0_stores_tapping_data_with_the_spindle_stopped() {
    // K0 drills nothing, so the spindle need not turn yet (no E321); the
    // holes after M03 tap.
    let p = "G00 X0 Y0 Z10.\nG84 Z-5. R2. K0 F100.\nS500 M03\nX5.\nG80\nM30\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    assert_eq!(
        ev.iter()
            .filter(|e| matches!(e, Event::Hole { .. }))
            .count(),
        1
    );
}

#[test]
fn g88_feeding_per_revolution_alarms_at_its_cycle_word() {
    // 1.2.41: the way out is G01 with the spindle stopped: under G95 that
    // cannot move.
    let p = "G95 S1000 M03\nG00 X0 Y0 Z10.\nF0.1\n  G88 X10. Y10. Z-5. R2. P1.\nM30\n";
    let (ev, out) = run(&Dialect::fanuc(), p);
    assert_eq!(alarm(&out), (Code::E342, 4, 3));
    assert!(!ev.iter().any(|e| matches!(e, Event::Hole { .. })));
}

#[test]
fn a_group_01_code_beside_a_cycle_code_cancels_it() {
    // 1.2.31 condition 4: G00 wins, so R is read by nothing (E203) instead
    // of a rapid to the hole bottom.
    let p = "S1000 M03\nG00 X0 Y0 Z10.\nG00 G81 X5. Y5. Z-2. R1. F100.\nM30\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(alarm(&out), (Code::E203, 3, 22));
    assert_eq!(ends(&ev, 3), vec![vec![0.0, 0.0, 10.0]]);
    // Without cycle words it is an ordinary rapid, and the cycle is off.
    let p = "S1000 M03\nG81 X0 Y0 Z-2. R1. F100.\nG00 G81 X5. Y5. Z3.\nX6.\nM30\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let tail: Vec<_> = ends(&ev, 3).into_iter().rev().take(2).collect();
    assert_eq!(tail, vec![vec![6.0, 5.0, 3.0], vec![5.0, 5.0, 3.0]]);
}

#[test]
fn eia_g82_needs_its_dwell_and_eia_arcs_take_r() {
    let p = "G71 G90\nG00 X0 Y0 Z5.\nG82 X5. Y5. Z-2. R1. F100.\nM30\n";
    let (_, out) = run(&Dialect::eia(), p);
    assert_eq!(alarm(&out), (Code::E312, 3, 1));
    // R = 5 from (0,0) to (10,0) clockwise: the centre is (5,0).
    let p = "G71 G90\nG00 X0 Y0 Z0\nG02 X10. Y0 R5. F100.\nM30\n";
    let (ev, out) = run(&Dialect::eia(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let center = ev.iter().find_map(|e| match e {
        Event::Arc { center, .. } => Some((center.get(0), center.get(1))),
        _ => None,
    });
    assert_eq!(center, Some((5.0, 0.0)));
}

#[test]
fn w101_covers_arc_and_cycle_lengths_but_not_dwell_times() {
    // A pointed program: I5000 of an arc is 5 mm, Q2000 of a peck 2 mm
    // (both as meant, but written without a point); G04 X2 is a time.
    let p = "G00 X0 Y0 Z10.\nG02 X10. Y0 I5000 F100.\nS1000 M03\nG83 X5. Y5. Z-2. R1. Q2000 F100.\nG80\nG04 X2\nM30\n";
    let (ev, out) = run(&Dialect::syntec(), p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let w: Vec<_> = warnings(&ev)
        .iter()
        .filter(|d| d.code == Code::W101)
        .map(|d| (d.line, d.column))
        .collect();
    assert_eq!(w, vec![(2, 13), (4, 22)]);
}

#[test]
fn w101_names_degrees_for_a_rotary_word() {
    let (ev, _) = run(&Dialect::fanuc(), "G00 X1. Y0\nG00 A90\nM30\n");
    let w = warnings(&ev);
    let w101 = w.iter().find(|d| d.code == Code::W101).expect("a W101");
    assert!(w101.message.contains("0.09°"), "{}", w101.message);
}

#[test]
fn g93_warns_on_a_clamped_rate_and_never_feeds_zero() {
    // grbl G93: 10 mm at F1000 is 10,000 mm/min, above the built-in
    // maximum; F itself is no rate and does not warn at the F word.
    let d = Dialect::grbl();
    let max = d.machine().max_feed_mm_per_min();
    let p = format!(
        "G21 G90 G93\nG01 X10 F{}\nG01 X10 F5\nM30\n",
        max / 10.0 * 2.0
    );
    let (ev, out) = run(&d, &p);
    assert_eq!(out, Outcome::Ended(vcnc_interp::EndCode::M30));
    let w: Vec<_> = warnings(&ev)
        .iter()
        .filter(|d| d.code == Code::W102)
        .map(|d| d.line)
        .collect();
    assert_eq!(w, vec![2]);
    let feeds: Vec<f64> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Feed {
                feed: vcnc_interp::Feed::PerMin(f),
                ..
            } => Some(*f),
            _ => None,
        })
        .collect();
    assert!(feeds.iter().all(|f| *f > 0.0), "{feeds:?}");
}
