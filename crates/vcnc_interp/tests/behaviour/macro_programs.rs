//! Regressions found by the adversarial review of the macros (issue 9):
//! Custom Macro B and Syntec MACRO programs written the way a macro
//! programmer writes them, each test naming what it guards. Expected
//! values are worked out by hand in the comments, from the Fanuc 0i
//! "Custom macro" chapter, the Syntec MACRO specification and
//! `docs/macros.md`.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common;

use common::{Store, alarm_of, ended, run, xs};
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, VecSink};
use vcnc_syntax::{Code, MemSource};

#[test]
fn g66_with_l0_calls_nothing_like_g65_l0() {
    // `G65 P L0` calls nothing (docs/macros.md, Calls); G66 P L0 sets a
    // modal call that runs its program "l times" after each move: zero
    // times. O0070 counts its runs in #100, so after two moves #100 stays
    // vacant, and both moves are the only motion: X5 then X6.
    let o70 = "O0070\n#100 = #100 + 1\nG00 Y9.\nM99\n";
    let p = "G90 G00 X0 Y0\nG66 P70 L0\nX5.\nX6.\nG67\nM30\n";
    let r = run("fanuc", p, Store::default().with(70, o70), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![None]);
    // (The first G00 X0 Y0 does not move: no event.)
    assert_eq!(xs(&r.events), vec![5.0, 6.0]);
    // The same modal call with L2 runs O0070 twice after each of the two
    // moves: #100 = 4.
    let p = "G90 G00 X0 Y0\nG66 P70 L2\nX5.\nX6.\nG67\nM30\n";
    let r = run("fanuc", p, Store::default().with(70, o70), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(4.0)]);
}

#[test]
fn sequence_and_program_numbers_cannot_be_variables() {
    // Fanuc 0i, Custom macro, limitations: "Program numbers, sequence
    // numbers, and optional block skip numbers cannot be referenced using
    // variables" (O#1; N#3 Y200.0; are its examples). The block alarms at
    // the word, and nothing of it runs.
    let r = run("fanuc", "#1 = 5\nN#1 G00 X1.\nM30\n", Store::default(), &[]);
    // Line 2, the N word at column 1.
    assert_eq!(alarm_of(&r), (Code::E601, 2, 1));
    assert!(xs(&r.events).is_empty());
    // In the middle of a block too: `G00 N[#1] X1.` alarms at N, column 5.
    let r = run(
        "fanuc",
        "#1 = 5\nG00 N[#1] X1.\nM30\n",
        Store::default(),
        &[],
    );
    assert_eq!(alarm_of(&r), (Code::E601, 2, 5));
    // O#1 on line 1, column 1.
    let r = run("fanuc", "O#1\nG00 X1.\nM30\n", Store::default(), &[]);
    assert_eq!(alarm_of(&r), (Code::E601, 1, 1));
    // Syntec ISO programs read Macro B: the same rule.
    let r = run("syntec", "G00 X1.\nN#1 X2.\nM30\n", Store::default(), &[]);
    assert_eq!(alarm_of(&r), (Code::E601, 2, 1));
    assert_eq!(xs(&r.events), vec![1.0]);
}

/// End points of the motion events, X, Y and A.
fn xya(events: &[Event]) -> Vec<(f64, f64, f64)> {
    let r = |v: f64| (v * 1e6).round() / 1e6;
    events
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| (r(p.get(0)), r(p.get(1)), r(p.get(3))))
        .collect()
}

#[test]
fn round_in_an_address_rounds_to_the_least_input_increment() {
    // Fanuc 0i, Custom macro, "Rounding function": "When the ROUND
    // function is specified in an NC statement address, the specified
    // value is rounded off according to the least input increment of the
    // address", with the example #1 = 1.2345, #2 = 2.3456 on a 0.001 mm
    // control: X[ROUND[#1]+ROUND[#2]] travels 1.235 + 2.346 = 3.581.
    // In an assignment ROUND stays a whole number: #4 = ROUND[#1] = 1.
    let p = "#1 = 1.2345\n#2 = 2.3456\n#3 = 1.23456\n\
             G90 G00 X[ROUND[#1]] Y[ROUND[-#1]]\n\
             G00 X[ROUND[#1]+ROUND[#2]] A[ROUND[#3]]\n\
             #4 = ROUND[#1]\nG00 X#4\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#4"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(1.0)]);
    assert_eq!(
        xya(&r.events),
        vec![
            // Line 4: 1.2345 → 1.235; -1.2345 → -1.235 (half away from 0).
            (1.235, -1.235, 0.0),
            // Line 5: 1.235 + 2.346; A in 0.001° increments: 1.23456 → 1.235.
            (3.581, -1.235, 1.235),
            // Line 7: X#4 = X1.
            (1.0, -1.235, 1.235),
        ]
    );
    // Under G20 (in a block of its own, as Fanuc wants it) the increment
    // is 0.0001 in: ROUND[1.23456] = 1.2346 in, 31.35884 mm.
    let p = "#3 = 1.23456\nG20\nG90 G00 X[ROUND[#3]]\nM30\n";
    let r = run("fanuc", p, Store::default(), &[]);
    ended(&r);
    assert_eq!(xya(&r.events), vec![(31.35884, 0.0, 0.0)]);
    // The Haas manual's own example (inch): #1 = 1.00333,
    // G0 X[ROUND[#1] + ROUND[#1]] moves to 2.0066 in (50.96764 mm) and
    // A[ROUND[#1] + ROUND[#1]] to 2.006°.
    let p = "#1 = 1.00333\nG20\nG90 G0 X[ROUND[#1] + ROUND[#1]] A[ROUND[#1] + ROUND[#1]]\nM30\n";
    let r = run("haas", p, Store::default(), &[]);
    ended(&r);
    assert_eq!(xya(&r.events), vec![(50.96764, 0.0, 2.006)]);
}

#[test]
fn a_runaway_macro_loop_is_named_in_the_jump_limit_alarm() {
    // With max_jumps = 100 a WHILE loop that never ends stops at E405 on
    // its END (line 3, column 1), and the message must name what a macro
    // programmer wrote — a loop — not only M98/M99 calls and returns, which
    // this program has none of.
    let machine = Machine::from_toml(
        &vcnc_interp::machine::DEFAULT_MILL_TOML.replace("max_jumps = 1000000", "max_jumps = 100"),
    )
    .unwrap();
    let dialect = Dialect::by_name("fanuc").unwrap();
    let mut sink = VecSink::default();
    let p = "#1 = 0\nWHILE [#1 GE 0] DO 1\nEND 1\nM30\n";
    let outcome = Interpreter::new(&machine, &dialect, Options::default()).run(
        Box::new(MemSource(p.as_bytes().to_vec())),
        &mut Store::default(),
        &mut sink,
    );
    let Outcome::Alarm(d) = outcome else {
        panic!("no alarm: {outcome:?}");
    };
    assert_eq!((d.code, d.line, d.column), (Code::E405, 3, 1));
    assert!(d.message.contains("loop"), "{}", d.message);
    assert!(d.help.contains("loop"), "{}", d.help);
}

#[test]
fn a_g_code_beside_g65_alarms_about_the_call_not_the_lathe() {
    // `G65 P10 G01 X1.`: Fanuc passes no G code as an argument, so G01
    // (line 1, column 9) cannot share the call's block: E209. The help
    // must speak of the call, not list the lathe codes of another
    // document.
    let r = run(
        "fanuc",
        "G65 P10 G01 X1.\nM30\n",
        Store::default().with(10, "O0010\nM99\n"),
        &[],
    );
    assert_eq!(alarm_of(&r), (Code::E209, 1, 9));
    let Outcome::Alarm(d) = &r.outcome else {
        unreachable!()
    };
    assert!(!d.help.contains("lathe"), "{}", d.help);
    assert!(d.message.contains("G65"), "{}", d.message);
}

#[test]
fn a_stray_operator_in_a_syntec_macro_file_gets_syntec_advice() {
    // `-1:` is no CASE label (Syntec §4.5: labels are Longs ≥ 0), so line
    // 3 is read as a G-code block starting with `-`: E601 at column 1. The
    // help must not advise Macro B's `X[#1+2.]`: in Syntec MACRO `[ ]`
    // index a variable (`#[#1]`), and an address takes `X(#1 + 2.)`.
    let p = "%@MACRO\nCASE 1 OF\n-1: G00 X1.;\nEND_CASE;\nM30;\n";
    let r = run("syntec", p, Store::default(), &[]);
    assert_eq!(alarm_of(&r), (Code::E601, 3, 1));
    let Outcome::Alarm(d) = &r.outcome else {
        unreachable!()
    };
    assert!(!d.help.contains("X[#1"), "{}", d.help);
}

#[test]
fn goto_finds_a_label_after_a_macro_statement_on_the_same_line() {
    // `;` ends a block (Fanuc's EOB), and docs/macros.md lets statements
    // share a line: `#1 = 1; N20 G00 X2.` holds the block N20. GOTO 20
    // (line 2) skips line 3 and lands on it: the only move is X2, and #1
    // stays vacant because the jump lands after `#1 = 1`.
    let p = "#2 = 0\nGOTO 20\nG00 X1.\n#1 = 1; N20 G00 X2.\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#1"]);
    ended(&r);
    assert_eq!(xs(&r.events), vec![2.0]);
    assert_eq!(r.values, vec![None]);
    // The same with a macro statement as the target: N30 #3 = 3.
    let p = "GOTO 30\n#3 = 1\nG00 X1.; N30 #3 = 3\nG00 X#3\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#3"]);
    ended(&r);
    assert_eq!(xs(&r.events), vec![3.0]);
    // And in a loop that counts to 3 through a label after a statement.
    let p = "#1 = 0\n#9 = 0; N5 #1 = #1 + 1\nIF [#1 LT 3] GOTO 5\nG00 X#1\nM30\n";
    let r = run("fanuc", p, Store::default(), &[]);
    ended(&r);
    assert_eq!(xs(&r.events), vec![3.0]);
}

#[test]
fn program_number_4115_is_the_running_program_also_in_the_main_file() {
    // #4115 is the number of the program that is running (its O). The main
    // program O0555 reads 555; O0013 and O0014, written after it in the
    // same file, read 13 (G65) and 14 (M98); back in the main, 555 again.
    // O0020 comes from the program store and reads 20.
    let p = "O0555\n#101 = #4115\nG65 P13\nM98 P14\nG65 P20\n#104 = #4115\nM30\n\
             O0013\n#102 = #4115\nM99\nO0014\n#103 = #4115\nM99\n";
    let r = run(
        "fanuc",
        p,
        Store::default().with(20, "O0020\n#105 = #4115\nM99\n"),
        &["#101", "#102", "#103", "#104", "#105"],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![Some(555.0), Some(13.0), Some(14.0), Some(555.0), Some(20.0)]
    );
}

#[test]
fn comma_chamfer_and_corner_take_a_variable_or_an_expression() {
    // Fanuc Macro B: a variable or a bracketed expression stands wherever
    // an address takes a value, the comma addresses too. `,R#1` with
    // #1 = 2 rounds the corner at X10 Y0 with R2: the G01 stops at X8
    // (10 − 2), an arc follows to X10 Y2, then the line to Y10: the same
    // motion as `,R2.` written out. `,C[0.5+0.5]` chamfers 1 mm: the line
    // stops at X9, the chamfer goes to X10 Y1.
    let fanuc = Dialect::fanuc();
    let literal = "G90 G21 G17 M3 S1000\nG0 X0 Y0\n#1=2.\nG1 X10. ,R2. F100\nY10.\nM30\n";
    let (want, out) = common::run_str(&fanuc, literal);
    assert!(matches!(out, Outcome::Ended { .. }), "{out:?}");
    for form in [",R#1", ",R[1+1]", ",R #1", ",r#1"] {
        let p = literal.replace(",R2.", form);
        let (got, out) = common::run_str(&fanuc, &p);
        assert!(matches!(out, Outcome::Ended { .. }), "{form}: {out:?}");
        assert_eq!(got, want, "{form}");
    }
    let (events, out) = common::run_str(&fanuc, &literal.replace(",R2.", ",R#1"));
    assert!(matches!(out, Outcome::Ended { .. }));
    let first_cut = events.iter().find_map(|e| match e {
        Event::Feed { to, .. } => Some(*to),
        _ => None,
    });
    assert!(
        common::near(first_cut.unwrap(), 8.0, 0.0, 0.0),
        "{first_cut:?}"
    );

    let chamfer = "G90 G21 G17 M3 S1000\nG0 X0 Y0\nG1 X10. ,C[0.5+0.5] F100\nY10.\nM30\n";
    let (events, out) = common::run_str(&fanuc, chamfer);
    assert!(matches!(out, Outcome::Ended { .. }), "{out:?}");
    let cuts: Vec<_> = events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { to, .. } => Some(*to),
            _ => None,
        })
        .collect();
    assert_eq!(cuts.len(), 3, "{cuts:?}");
    assert!(common::near(cuts[0], 9.0, 0.0, 0.0), "{cuts:?}");
    assert!(common::near(cuts[1], 10.0, 1.0, 0.0), "{cuts:?}");
    assert!(common::near(cuts[2], 10.0, 10.0, 0.0), "{cuts:?}");
}

#[test]
fn fanuc_lathe_comma_chamfer_takes_a_variable() {
    // The review found `,C#1` alarming E101 under fanuc-lathe too: with
    // #1 = 1 it is the chamfer `,C1.` written out (the same events).
    let lathe = Dialect::fanuc_lathe();
    let literal = "G97 S1000 M03\nG00 X0. Z2.\n#1=1.\nG01 X20. Z0. ,C1. F0.1\nG01 Z-10.\nM30\n";
    let (want, out) = common::run_on_its_machine(&lathe, literal);
    assert!(matches!(out, Outcome::Ended { .. }), "{out:?}");
    let (got, out) = common::run_on_its_machine(&lathe, &literal.replace(",C1.", ",C#1"));
    assert!(matches!(out, Outcome::Ended { .. }), "{out:?}");
    assert_eq!(got, want);
}
