//! Macro statements and calls: loops, branches, jumps, G65/G66/G67,
//! extended G-code and M-code macros, locals per call level, system
//! variables, kept variables and the unset-variable report. Expected values
//! are worked out by hand in the comments.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use crate::common;

use common::{Store, ended, run, run_on};
use std::collections::BTreeMap;
use vcnc_interp::{Dialect, EndCode, Event, Interpreter, Machine, Options, Outcome, VecSink};
use vcnc_syntax::Code;
use vcnc_syntax::macros::Value;

/// End points of the motion events, X and Y.
fn xy(events: &[Event]) -> Vec<(f64, f64)> {
    events
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| {
            (
                (p.get(0) * 1e6).round() / 1e6,
                (p.get(1) * 1e6).round() / 1e6,
            )
        })
        .collect()
}

fn messages(events: &[Event]) -> Vec<(String, bool)> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Message { text, stop, .. } => Some((text.to_string(), *stop)),
            _ => None,
        })
        .collect()
}

#[test]
fn macro_b_while_loops_nest() {
    // Outer 3 times, inner 2 times: #3 counts 6 inner passes.
    let p = "#1 = 0\n#3 = 0\nWHILE [#1 LT 3] DO 1\n#2 = 0\nWHILE [#2 LT 2] DO 2\n\
             #3 = #3 + 1\n#2 = #2 + 1\nEND 2\n#1 = #1 + 1\nEND 1\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#1", "#2", "#3"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(3.0), Some(2.0), Some(6.0)]);
}

#[test]
fn macro_b_loop_with_a_false_condition_skips_its_body() {
    let p = "#1 = 5\nWHILE [#1 LT 3] DO 1\n#2 = 99\nEND 1\n#3 = 1\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#2", "#3"]);
    ended(&r);
    assert_eq!(r.values, vec![None, Some(1.0)]);
}

#[test]
fn macro_b_if_goto_then_and_computed_goto() {
    // IF GOTO skips N20; IF THEN assigns; GOTO #5 jumps to N40; GOTO [#5+10] to N50.
    let p = "#1 = 1\nIF [#1 EQ 1] GOTO 30\nN20 #2 = 20\nN30 #3 = 30\nIF [#1 GT 0] THEN #4 = 4\n\
             IF [#1 GT 5] THEN #6 = 6\n#5 = 40\nGOTO #5\n#7 = 7\nN40 GOTO [#5 + 10]\n#8 = 8\nN50 #9 = 9\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default(),
        &["#2", "#3", "#4", "#6", "#7", "#8", "#9"],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![None, Some(30.0), Some(4.0), None, None, None, Some(9.0)]
    );
}

#[test]
fn macro_b_do_without_while_runs_until_a_goto_leaves() {
    let p = "#1 = 0\nDO 1\n#1 = #1 + 1\nIF [#1 GE 4] GOTO 100\nEND 1\nN100 M30\n";
    let r = run("fanuc", p, Store::default(), &["#1"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(4.0)]);
}

#[test]
fn macro_b_goto_jumps_inside_a_loop_body() {
    // The corpus's bolt circle jumps from the loop body to a label later in
    // the same body: allowed. Passes 0..2: the first goes to N30.
    let p = "#1 = 0\n#2 = 0\nWHILE [#1 LT 3] DO 1\nIF [#1 EQ 0] GOTO 30\n#2 = #2 + 10\nGOTO 40\n\
             N30 #2 = #2 + 1\nN40 #1 = #1 + 1\nEND 1\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#2"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(21.0)]);
}

#[test]
fn macro_b_moves_in_a_loop() {
    let p =
        "G90 G01 F100.\n#1 = 1\nWHILE [#1 LE 3] DO 1\nX[#1 * 10] Y-#1\n#1 = #1 + 1\nEND 1\nM30\n";
    let r = run("fanuc", p, Store::default(), &[]);
    ended(&r);
    assert_eq!(
        xy(&r.events),
        vec![(10.0, -1.0), (20.0, -2.0), (30.0, -3.0)]
    );
}

#[test]
fn syntec_if_elseif_else() {
    for (x, want) in [(1, 10.0), (3, 20.0), (9, 30.0)] {
        let p = format!(
            "%@MACRO\n#1 := {x};\nIF #1 = 1 THEN\n  @1 := 10;\nELSEIF (#1 >= 2) AND (#1 <= 5) THEN\n  @1 := 20;\nELSE\n  @1 := 30;\nEND_IF;\nM30;\n"
        );
        let r = run("syntec", &p, Store::default(), &["@1"]);
        ended(&r);
        assert_eq!(r.values, vec![Some(want)], "#1 = {x}");
    }
}

#[test]
fn syntec_case() {
    for (x, want) in [(1, 1.0), (4, 3.0), (5, 3.0), (7, 9.0)] {
        let p = format!(
            "%@MACRO\n#1 := {x};\nCASE #1 OF\n1:\n  @1 := 1;\n2:\n  @1 := 2;\n3, 4, 5:\n  @1 := 3;\nELSE\n  @1 := 9;\nEND_CASE;\nM30;\n"
        );
        let r = run("syntec", &p, Store::default(), &["@1"]);
        ended(&r);
        assert_eq!(r.values, vec![Some(want)], "#1 = {x}");
    }
}

#[test]
fn syntec_loops() {
    // FOR 0..3 BY 1.0: #7 = 0+1+2+3 = 6 (Doubles: the step is 1.0).
    // FOR 10 down to 1 BY -3: 10, 7, 4, 1 → #8 = 22.
    // WHILE: #14 counts to 5.  REPEAT: at least once, #15 = 1.
    // FOR with EXIT at 4: #16 = 1+2+3 = 6, and #17 = 4 after the loop.
    let p = "%@MACRO\n#7 := 0;\nFOR #6 := 0 TO 3 BY 1.0 DO\n  #7 := #7 + #6;\nEND_FOR;\n\
             #8 := 0;\nFOR #9 := 10 TO 1 BY -3 DO\n  #8 := #8 + #9;\nEND_FOR;\n\
             #14 := 0;\nWHILE #14 < 5 DO\n  #14 := #14 + 1;\nEND_WHILE;\n\
             #15 := 0;\nREPEAT\n  #15 := #15 + 1;\nUNTIL #15 > 0 END_REPEAT;\n\
             #16 := 0;\nFOR #17 := 1 TO 10 DO\n  IF #17 = 4 THEN\n    EXIT;\n  END_IF;\n  #16 := #16 + #17;\nEND_FOR;\nM30;\n";
    let r = run(
        "syntec",
        p,
        Store::default(),
        &["#6", "#7", "#8", "#14", "#15", "#16", "#17"],
    );
    ended(&r);
    // After FOR 0 TO 3 the counter stepped past the end: 4.
    assert_eq!(
        r.values,
        vec![
            Some(4.0),
            Some(6.0),
            Some(22.0),
            Some(5.0),
            Some(1.0),
            Some(6.0),
            Some(4.0)
        ]
    );
}

#[test]
fn syntec_goto_labels_comments_and_joined_lines() {
    // A statement without `;` joins the next line (the manual's §4.13); a
    // (* *) comment spans lines; GOTO #2 jumps to N10.
    let p = "%@MACRO\n(* a comment\n   over lines *)\n#1 := 1 +\n  2;  // 3\n#2 := 10;\nGOTO #2;\n@1 := 99;\nN10;\n@2 := #1;\nM30;\n";
    let r = run("syntec", p, Store::default(), &["@1", "@2"]);
    ended(&r);
    assert_eq!(r.values, vec![None, Some(3.0)]);
}

#[test]
fn syntec_g_code_with_expressions() {
    let p = "%@MACRO\n#1 := 3.0;\nG90 G01 X(1.0 + 3.0) Y30.0 / 2.0 F100.;\nG01 X(4.0 * #1);\nG#10;\nM30;\n";
    // #10 is vacant: `G#10;` is an empty block.
    let r = run("syntec", p, Store::default(), &[]);
    ended(&r);
    assert_eq!(xy(&r.events), vec![(4.0, 15.0), (12.0, 15.0)]);
}

#[test]
fn syntec_messages_stack_and_alarm() {
    let p = "%@MACRO\nPUSH(5);\nPUSH(6);\n#1 := PUSH(7);\n#2 := STKTOP[0];\n#3 := STKTOP[2];\n#4 := POP();\n#5 := STKTOP[9];\n\
             MSG(\"HELLO\");\nMSG(100, \"DRILL\");\nWAIT();\nSLEEP();\n@1 := #1 + #2 + #3 + #4;\nM30;\n";
    let r = run("syntec", p, Store::default(), &["@1", "#5"]);
    ended(&r);
    // 7 + 7 + 5 + 7.
    assert_eq!(r.values, vec![Some(26.0), None]);
    assert_eq!(
        messages(&r.events),
        vec![("HELLO".into(), false), ("100: DRILL".into(), false)]
    );
    let r = run(
        "syntec",
        "%@MACRO\nALARM(301, \"NO TOOL\");\nM30;\n",
        Store::default(),
        &[],
    );
    match r.outcome {
        Outcome::Alarm(d) => {
            assert_eq!((d.code, d.line, d.column), (Code::E612, 2, 1));
            assert!(
                d.message.contains("301") && d.message.contains("NO TOOL"),
                "{}",
                d.message
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn g65_arguments_land_in_their_locals() {
    // Every argument letter to its local, and P/L are the call's.
    let sub = "O9000\n#100 = #1\n#101 = #2\n#102 = #3\n#103 = #4\n#104 = #5\n#105 = #6\n#106 = #7\n\
               #107 = #8\n#108 = #9\n#109 = #11\n#110 = #13\n#111 = #17\n#112 = #18\n#113 = #19\n\
               #114 = #20\n#115 = #21\n#116 = #22\n#117 = #23\n#118 = #24\n#119 = #25\n#120 = #26\n\
               #121 = #10\n#122 = #12\n#123 = #16\nM99\n";
    let p = "G65 P9000 A1. B2. C3. I4. J5. K6. D7. E8. F9. H11. M13. Q17. R18. S19. T20. U21. V22. W23. X24. Y25. Z26.\nM30\n";
    let names: Vec<String> = (100..=123).map(|n| format!("#{n}")).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    let r = run("fanuc", p, Store::default().with(9000, sub), &names);
    ended(&r);
    let want: Vec<Option<f64>> = [
        1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 13, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26,
    ]
    .iter()
    .map(|v| Some(f64::from(*v)))
    .chain([None, None, None])
    .collect();
    assert_eq!(r.values, want);
}

#[test]
fn g65_values_without_a_point_are_least_increments_on_fanuc() {
    // X10 is 0.010 mm, D7 is 7 (D counts), F100 is 100.
    let sub = "O9001\n#100 = #24\n#101 = #7\n#102 = #9\nM99\n";
    let r = run(
        "fanuc",
        "G65 P9001 X10 D7 F100\nM30\n",
        Store::default().with(9001, sub),
        &["#100", "#101", "#102"],
    );
    ended(&r);
    assert_eq!(r.values, vec![Some(0.01), Some(7.0), Some(100.0)]);
}

/// Per address: E is no length on a Fanuc mill, so `E41` passes 41 and a
/// macro's `G#8` is G41 (regression: it read 0.041 and stopped at G0.041);
/// Q and R are lengths, A an angle.
#[test]
fn g65_argument_units_follow_each_address() {
    let sub = "O9000\n#100 = #8\n#101 = #17\n#102 = #18\n#103 = #1\nG#8 D1\nG40\nM99\n";
    let r = run(
        "fanuc",
        "G65 P9000 E41 Q2500 R500 A90000\nM30\n",
        Store::default().with(9000, sub),
        &["#100", "#101", "#102", "#103"],
    );
    ended(&r);
    assert_eq!(r.values, vec![Some(41.0), Some(2.5), Some(0.5), Some(90.0)]);
}

#[test]
fn locals_per_level_g65_isolates_m98_shares() {
    // G65: the callee's #1 is its A; the caller's #1 stays 100.
    // M98: the callee writes the caller's #1.
    let sub = "O9002\n#100 = #1\n#1 = 200\nM99\n";
    let p = "#1 = 100\nG65 P9002 A5.\n#101 = #1\nM98 P9002\n#102 = #1\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default().with(9002, sub),
        &["#100", "#101", "#102"],
    );
    ended(&r);
    // After M98 #100 is the caller's #1 (100).
    assert_eq!(r.values, vec![Some(100.0), Some(100.0), Some(200.0)]);
}

#[test]
fn g65_repeats_l_times_and_l0_does_not_call() {
    let sub = "O9003\n#100 = #100 + 1\nM99\n";
    let p = "#100 = 0\nG65 P9003 L4\nG65 P9003 L0\nM30\n";
    let r = run("fanuc", p, Store::default().with(9003, sub), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(4.0)]);
}

#[test]
fn g66_calls_after_each_move_block_until_g67() {
    // The macro counts its calls and moves Z down and up: it runs after the
    // two move blocks, not after the G66 block, the assignment or G67, and
    // its own moves do not call again.
    let sub = "O9004\n#100 = #100 + 1\nG91 G00 Z-#26\nZ#26\nG90\nM99\n";
    let p = "#100 = 0\nG90 G00 X0 Y0 Z10.\nG66 P9004 Z2.\nX10.\n#1 = 1\nY10.\nG67\nX0\nM30\n";
    let r = run("fanuc", p, Store::default().with(9004, sub), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(2.0)]);
    let z: Vec<f64> = r
        .events
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| p.get(2))
        .collect();
    assert_eq!(z, vec![10.0, 10.0, 8.0, 10.0, 10.0, 8.0, 10.0, 10.0]);
}

#[test]
fn syntec_g66_shares_its_locals_until_g67() {
    // Syntec: one set of locals from G66 to G67: #27 counts across calls.
    let sub = "%@MACRO\n#27 := #27 + 1;\n@1 := #27;\nM99;\n";
    let p = "G90 G00 X0\nG66 P9005\nX1.\nX2.\nX3.\nG67\nM30\n";
    let r = run("syntec", p, Store::default().with(9005, sub), &["@1"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(3.0)]);
    // Fanuc starts each call afresh: #27 is a common there, so use #10.
    let sub = "O9006\n#10 = #10 + 1\n#100 = #10\nM99\n";
    let p = "G90 G00 X0\nG66 P9006\nX1.\nX2.\nX3.\nG67\nM30\n";
    let r = run("fanuc", p, Store::default().with(9006, sub), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(1.0)]);
}

#[test]
fn syntec_getarg_and_extended_g_code_macro() {
    // G200 X10. Y5. P3 calls the file G0200: X → #24, P → #16 (Syntec), and
    // GETARG(X) reads the argument even after #24 changed.
    let g200 =
        "%@MACRO\n#24 := 0;\n@1 := GETARG(X);\n@2 := #25;\n@3 := #16;\n@4 := GETARG(Q);\nM99;\n";
    let p = "G200 X10. Y5. P3\nM30\n";
    let r = run(
        "syntec",
        p,
        Store::default().named("G0200", g200),
        &["@1", "@2", "@3", "@4"],
    );
    ended(&r);
    assert_eq!(r.values, vec![Some(10.0), Some(5.0), Some(3.0), None]);
    // Without the file, G200 is an unknown G code.
    let r = run("syntec", p, Store::default(), &[]);
    assert!(
        matches!(r.outcome, Outcome::Alarm(ref d) if d.code == Code::E201),
        "{:?}",
        r.outcome
    );
}

#[test]
fn machine_registered_m_code_macro() {
    let toml =
        vcnc_core::machine::DEFAULT_MILL_TOML.to_string() + "\n[m_macros]\n123 = \"M0123\"\n";
    let machine = Machine::from_toml(&toml).unwrap();
    let m123 = "O0123\n#100 = #24 + #13\nM99\n";
    let r = run_on(
        &machine,
        "fanuc",
        "M123 X2.\nM30\n",
        Store::default().named("M0123", m123),
        &["#100"],
    );
    ended(&r);
    // #13 is vacant (the M code is the call, not an argument): 2 + 0.
    assert_eq!(r.values, vec![Some(2.0)]);
}

#[test]
fn m99_in_a_main_program_that_counts_loops() {
    // Without variables one pass (W107); with a counter it loops until its
    // own condition ends it.
    let p = "#100 = #100 + 1\nIF [#100 GE 3] GOTO 99\nM99\nN99 M30\n";
    let r = run("fanuc", p, Store::default(), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(3.0)]);
    assert!(matches!(r.outcome, Outcome::Ended(EndCode::M30)));
}

#[test]
fn system_variables_positions_modal_and_words() {
    // After G20 moves, #5001 reads in inches; #5021 (machine) too.
    let p = "G20 G90 G01 X1. Y2. F10.\n#100 = #5001\n#101 = #5002\n#102 = #5021\n\
             #103 = #4001\n#104 = #4003\n#105 = #4006\n#106 = #4109\nG91\n#107 = #4003\n\
             T5 M06\n#108 = #4120\n#109 = #4014\nG21\n#110 = #5001\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default(),
        &[
            "#100", "#101", "#102", "#103", "#104", "#105", "#106", "#107", "#108", "#109", "#110",
        ],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![
            Some(1.0),
            Some(2.0),
            Some(1.0),
            Some(1.0),
            Some(90.0),
            Some(20.0),
            Some(10.0),
            Some(91.0),
            Some(5.0),
            Some(54.0),
            Some(25.4)
        ]
    );
}

#[test]
fn tool_and_work_offset_variables() {
    // Write H1 geometry and wear through #11001/#10001 (memory C), read
    // them back through #2201/#2001; set G55's X to 100 through #5241 and
    // move in G55.
    let p = "#11001 = 12.5\n#10001 = -0.5\n#100 = #2201\n#101 = #2001\n#13002 = 3.\n#102 = #13002\n\
             #5241 = 100.\n#103 = #5241\nG55 G90 G00 X10. Y0\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default(),
        &["#100", "#101", "#102", "#103"],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![Some(12.5), Some(-0.5), Some(3.0), Some(100.0)]
    );
    assert_eq!(xy(&r.events), vec![(110.0, 0.0)]);
}

#[test]
fn message_variable_stops_with_the_comment() {
    let r = run(
        "fanuc",
        "#3006 = 1 (LOAD PART)\nM30\n",
        Store::default(),
        &[],
    );
    ended(&r);
    assert_eq!(messages(&r.events), vec![("LOAD PART".into(), true)]);
    let r = run(
        "fanuc",
        "G90\n#3000 = 7 (TOOL BROKEN)\nM30\n",
        Store::default(),
        &[],
    );
    match r.outcome {
        Outcome::Alarm(d) => {
            assert_eq!((d.code, d.line, d.column), (Code::E612, 2, 1));
            assert!(d.message.contains("TOOL BROKEN"), "{}", d.message);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn clock_and_parts_count_are_plain_cells() {
    let p = "#3001 = 0\n#3901 = #3901 + 1\n#100 = #3001\n#101 = #3901\nM30\n";
    let r = run("fanuc", p, Store::default(), &["#100", "#101"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(0.0), Some(1.0)]);
}

#[test]
fn kept_variables_survive_between_runs() {
    let machine = Machine::default_mill();
    let dialect = Dialect::fanuc();
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    let mut before = BTreeMap::new();
    before.insert("#500".to_string(), Value::Double(41.0));
    interp.restore_variables(&before).unwrap();
    let out = interp.run_str("#500 = #500 + 1\n#100 = 5\nM30\n", &mut VecSink::default());
    assert!(matches!(out, Outcome::Ended(_)));
    let kept = interp.kept_variables();
    assert_eq!(kept.get("#500"), Some(&Value::Double(42.0)));
    // #100 is common but not kept.
    assert_eq!(kept.get("#100"), None);
    let mut bad = BTreeMap::new();
    bad.insert("#100".to_string(), Value::Double(1.0));
    assert!(interp.restore_variables(&bad).is_err());
}

#[test]
fn unset_variables_are_reported_once_before_the_end() {
    // #101 is read and never set; #102 is read before it is set (listed:
    // it was set afterwards? no, commons set later are dropped); #24 in
    // the macro was not passed.
    let sub = "O9007\n#100 = #24\nM99\n";
    let p = "#1 = #101\n#2 = #102\n#102 = 1\nG65 P9007\nM30\n";
    let r = run("fanuc", p, Store::default().with(9007, sub), &[]);
    ended(&r);
    let report: Vec<(String, u64)> = r
        .events
        .iter()
        .filter_map(|e| match e {
            Event::UnsetVariables { variables, .. } => Some(
                variables
                    .iter()
                    .map(|v| (v.name.to_string(), v.line))
                    .collect::<Vec<_>>(),
            ),
            _ => None,
        })
        .flatten()
        .collect();
    assert_eq!(report, vec![("#101".into(), 1), ("#24".into(), 2)]);
    // It comes right before the end event.
    let n = r.events.len();
    assert!(matches!(r.events[n - 2], Event::UnsetVariables { .. }));
    assert!(matches!(r.events[n - 1], Event::End { .. }));
}

#[test]
fn macro_b_statements_share_a_line_and_take_block_delete() {
    // `;` ends a block: three statements on one line; `/` skips one under
    // block delete (off here: it runs).
    let p = "#1 = 1; #2 = #1 + 1 ; #3 = #2 * 2\n/#4 = 9\n#[#1 + 9] = 5\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default(),
        &["#1", "#2", "#3", "#4", "#10"],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![Some(1.0), Some(2.0), Some(4.0), Some(9.0), Some(5.0)]
    );
}

#[test]
fn g65_arguments_may_be_expressions() {
    let sub = "O9008\n#100 = #24 + #25\nM99\n";
    let p = "#1 = 2.\nG65 P9008 X#1 Y[#1 * 3]\nM30\n";
    let r = run("fanuc", p, Store::default().with(9008, sub), &["#100"]);
    ended(&r);
    assert_eq!(r.values, vec![Some(8.0)]);
}

#[test]
fn syntec_indirect_variables_spellings_and_labels() {
    // @[#1] and #[#1 + 1] write indirectly; `=` assigns like `:=`; ENDIF,
    // ENDWHILE, ENDFOR and ENDCASE are accepted; a case label may carry a
    // statement on its line; ELSEIF chains.
    let p = "%@MACRO\n#1 := 5;\n@[#1] := 50;\n#[#1 + 1] := 60;\n#7 = 70;\n\
             IF #1 = 1 THEN\n@1 := 1;\nELSEIF #1 = 2 THEN\n@1 := 2;\nELSEIF #1 = 5 THEN\n@1 := 5;\nELSE\n@1 := 9;\nENDIF;\n\
             #8 := 0;\nWHILE #8 < 3 DO\n#8 := #8 + 1;\nENDWHILE;\n\
             FOR #9 := 1 TO 2 DO\nENDFOR;\n\
             CASE #1 OF\n5: @2 := 55;\nELSE\n@2 := 0;\nENDCASE;\nM30;\n";
    let r = run(
        "syntec",
        p,
        Store::default(),
        &["@5", "#6", "#7", "@1", "#8", "#9", "@2"],
    );
    ended(&r);
    assert_eq!(
        r.values,
        vec![
            Some(50.0),
            Some(60.0),
            Some(70.0),
            Some(5.0),
            Some(3.0),
            Some(3.0),
            Some(55.0)
        ]
    );
}

#[test]
fn syntec_long_registers_hold_longs() {
    // @401–@655 mirror PLC R registers: a Double written there is truncated.
    let p = "%@MACRO\n@401 := 7.9;\n@1 := @401 / 2;\nM30;\n";
    let r = run("syntec", p, Store::default(), &["@401", "@1"]);
    ended(&r);
    // 7 / 2 = 3 (Long division).
    assert_eq!(r.values, vec![Some(7.0), Some(3.0)]);
}

#[test]
fn syntec_m98_shares_locals_and_m198_too() {
    // The corpus's CALL_RUN programs: M98 and M198 subprograms write the
    // caller's #27, G65 gets its own.
    let sub = "%@MACRO\n#27 := 200;\nM99;\n";
    for (call, want) in [
        ("M98 P2001", 200.0),
        ("M198 P2001", 200.0),
        ("G65 P2001", 100.0),
    ] {
        let p = format!("%@MACRO\n#27 := 100;\n{call};\n@1 := #27;\nM30;\n");
        let r = run("syntec", &p, Store::default().with(2001, sub), &["@1"]);
        ended(&r);
        assert_eq!(r.values, vec![Some(want)], "{call}");
    }
}

/// Motion end points (X radius, Z) of a fanuc-lathe run.
fn xz(events: &[Event]) -> Vec<(f64, f64)> {
    xy(events)
}

#[test]
fn fanuc_lathe_profiles_read_variables_when_the_cycle_runs() {
    // #1 = 40 (diameter) is set after the profile is written but before
    // G70 reads it: the finishing pass goes to X20 (radius) at Z2, along
    // Z to -20, out to X25 (X50 diameter), and back to the start (25, 2).
    let p = "G50 S2000\nT0101\nG97 S500 M03\nG00 X50. Z2.\n#1 = 40.\n\
             G70 P10 Q20 F0.2\nM30\nN10 G00 X#1\nG01 Z-20.\nN20 X50.\n";
    let d = Dialect::fanuc_lathe();
    let r = run_on(&d.machine(), "fanuc-lathe", p, Store::default(), &[]);
    ended(&r);
    let pts = xz(&r.events);
    let want = [(25.0, 2.0), (20.0, 2.0), (20.0, -20.0), (25.0, -20.0)];
    let at = pts
        .windows(4)
        .position(|w| w == want)
        .unwrap_or_else(|| panic!("{pts:?}"));
    assert_eq!(pts[at + 4], (25.0, 2.0), "{pts:?}");
}

#[test]
fn fanuc_lathe_macro_statements_cannot_stand_in_a_profile() {
    let p = "G50 S2000\nT0101\nG97 S500 M03\nG00 X50. Z2.\n\
             G70 P10 Q20 F0.2\nM30\nN10 G00 X40.\n#2 = 1\nN20 X50.\n";
    let d = Dialect::fanuc_lathe();
    let r = run_on(&d.machine(), "fanuc-lathe", p, Store::default(), &[]);
    let Outcome::Alarm(a) = &r.outcome else {
        panic!("{:?}", r.outcome)
    };
    assert_eq!((a.code, a.line, a.column), (Code::E344, 8, 1), "{a:?}");
}

#[test]
fn fanuc_lathe_runs_g65_and_while() {
    // O0010 turns diameter #24 (X) to length #26 (Z), then faces out 1 mm; the main
    // program calls it for diameters 40, 36, 32.
    let sub = "O0010\nG00 X#24\nG01 Z#26 F0.2\nX[#24 + 2.]\nG00 Z2.\nM99\n";
    let p = "G50 S2000\nT0101\nG97 S500 M03\nG00 X50. Z2.\n#1 = 40.\n\
             WHILE [#1 GE 32.] DO 1\nG65 P10 X#1 Z-10.\n#1 = #1 - 4.\nEND 1\nM30\n";
    let d = Dialect::fanuc_lathe();
    let r = run_on(
        &d.machine(),
        "fanuc-lathe",
        p,
        Store::default().with(10, sub),
        &[],
    );
    ended(&r);
    let feeds: Vec<f64> = r
        .events
        .iter()
        .filter_map(|e| match e {
            Event::Feed { to, .. } if (to.get(1) + 10.0).abs() < 1e-9 => Some(to.get(0)),
            _ => None,
        })
        .collect();
    // Each call: in along Z at radius #24/2, then out to (#24 + 2)/2.
    assert_eq!(feeds, vec![20.0, 21.0, 18.0, 19.0, 16.0, 17.0]);
}

/// Fanuc's abbreviations of custom macro words (the first two letters):
/// `WH[#1GT0]DO1` … `EN1` loops (regression: "END 1 has no DO 1"), AT, RO,
/// SQ, GO, TH, and the operators XO, AN, MO.
#[test]
fn macro_b_words_abbreviated_to_two_letters() {
    let p = "#1=3\n#5=0\nWH[#1GT0]DO1\n#5=#5+#1\n#1=#1-1\nEN1\n#2=AT[1]/[1]\n\
             #3=RO[SQ[16.4]]\nIF[#2EQ45.]GO10\n#6=99\nN10 IF[#3NE4]TH#6=1\n\
             IF[#3EQ4]TH#7=[6XO3]+[6AN3]+[7MO4]\nM30\n";
    let r = run(
        "fanuc",
        p,
        Store::default(),
        &["#1", "#5", "#2", "#3", "#6", "#7"],
    );
    ended(&r);
    // 3+2+1 = 6; ATAN 45°; ROUND(√16.4 = 4.05) = 4; GO10 skips #6=99 and
    // #3 is 4 so TH#6 does not run; 6 XOR 3 = 5, 6 AND 3 = 2, 7 MOD 4 = 3.
    assert_eq!(
        r.values,
        vec![
            Some(0.0),
            Some(6.0),
            Some(45.0),
            Some(4.0),
            None,
            Some(10.0)
        ]
    );
}

/// A line meant to open a loop that cannot be read is reported itself, not
/// as a later "END 1 has no DO 1".
#[test]
fn an_unreadable_loop_head_is_reported_at_its_line() {
    let p = "#1=3\nWX[#1GT0]DO1\n#1=#1-1\nEND1\nM30\n";
    let r = run("fanuc", p, Store::default(), &[]);
    let Outcome::Alarm(d) = &r.outcome else {
        panic!("no alarm: {:?}", r.outcome)
    };
    assert_eq!(d.line, 2, "{d:?}");
}
