//! `--dialect linuxcnc`: the rules rs274's own output cannot show as a
//! full event list (its cutter compensation moves differently from vcnc's
//! Fanuc type A; `path_mode` has no canonical call), checked as
//! equivalences with spellings whose meaning the other tests fix; and the
//! alarms for what the dialect does not read. The rest is compared with
//! rs274 itself (`crates/vcnc/tests/fixtures.rs`,
//! `linuxcnc_dialect_reads_the_programs_rs274_read`).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Outcome};
use vcnc_syntax::Code;

use crate::common;

use common::run_str;

fn run(program: &str) -> (Vec<Event>, Outcome) {
    run_str(&Dialect::linuxcnc(), program)
}

/// The events of a run that ended, but its warnings (whose byte offsets
/// differ between two spellings of a line).
fn ended(program: &str) -> Vec<Event> {
    let (ev, out) = run(program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}\n{program}");
    ev.into_iter()
        .filter(|e| !matches!(e, Event::Warning(_)))
        .collect()
}

/// A run with the block delete switch on.
fn run_with_block_delete(program: &str) -> (Vec<Event>, Outcome) {
    let machine = vcnc_interp::Machine::default_mill();
    let mut sink = vcnc_interp::VecSink::default();
    let opts = vcnc_interp::Options {
        block_delete: true,
        ..vcnc_interp::Options::default()
    };
    let out = vcnc_interp::Interpreter::new(&machine, &Dialect::linuxcnc(), opts)
        .run_str(program, &mut sink);
    (sink.0, out)
}

fn alarm(program: &str) -> (Code, u64, u32) {
    let (ev, out) = run(program);
    let Outcome::Alarm(d) = out else {
        panic!("no alarm: {out:?}\n{program}");
    };
    assert!(
        matches!(ev.last(), Some(Event::Alarm(a)) if *a == d),
        "motion after the alarm"
    );
    (d.code, d.line, d.column)
}

const CONTOUR: &str = "G0 X-10 Y-10 Z5\nG1 Z-1 F300\nG41{D} G1 X0 Y0\nG1 X40\nG1 Y30\n\
                       G1 X0\nG1 Y0\nG40 G1 X-10 Y-10\nG0 Z5\nM5\nM2\n";

/// LinuxCNC: "If D is not given, the diameter of the currently loaded
/// tool is used": after `T3 M6`, `G41` is `G41 D3` (radius 3 mm, against
/// tool 1's 5 mm, both written by G10 L1: the built-in mill has no tools).
#[test]
fn g41_without_d_uses_the_tool_in_the_spindle() {
    let head = "G21 G17 G90 G94\nG10 L1 P1 R5\nG10 L1 P3 R3\nT3 M6\nS2000 M3\n";
    let bare = ended(&format!("{head}{}", CONTOUR.replace("{D}", "")));
    let d3 = ended(&format!("{head}{}", CONTOUR.replace("{D}", " D3")));
    let d1 = ended(&format!("{head}{}", CONTOUR.replace("{D}", " D1")));
    assert_eq!(bare, d3);
    assert_ne!(bare, d1);
}

/// G43 without H: the tool in the spindle (`T2 M6 G43` is `G43 H2`);
/// before any tool change, tool 0: no offset, as G49.
#[test]
fn g43_without_h_uses_the_tool_in_the_spindle() {
    let machine = "G21 G90\nT2 M6\nG43{H}\nG0 X1 Z10\nM2\n";
    let bare = ended(&machine.replace("{H}", ""));
    assert_eq!(bare, ended(&machine.replace("{H}", " H2")));
    let none = ended("G21 G90\nG43\nG0 X1 Z10\nM2\n");
    assert_eq!(none, ended("G21 G90\nG49\nG0 X1 Z10\nM2\n"));
}

/// G61.1 (exact stop) stops at every block end like G61; M60 (pallet
/// change pause) stops like M00.
#[test]
fn g61_1_and_m60_are_exact_stop_and_a_program_stop() {
    let path = "G21 G90 G1 F100\n{G}\nX1\nY1\nM2\n";
    assert_eq!(
        ended(&path.replace("{G}", "G61.1")),
        ended(&path.replace("{G}", "G61"))
    );
    let stop = "G21 G90\nG0 X1\n{M}\nG0 X2\nM2\n";
    assert_eq!(
        ended(&stop.replace("{M}", "M60")),
        ended(&stop.replace("{M}", "M0"))
    );
}

/// Integers are whole units (`X5` is 5 mm) and `;` starts a comment.
#[test]
fn integers_are_whole_units_and_semicolons_comment() {
    assert_eq!(
        ended("G21 G90\nG0 X5 ; five millimetres\nM2\n"),
        ended("G21 G90\nG0 X5.\nM2\n")
    );
}

/// LinuxCNC alarms on a P or Q that no code of the block uses ("P word with
/// no G2 G3 G4 G10 G64 G5 G5.2 G76 G82 G86 G88 G89 … to use it"): G81
/// and G73 take no P, G81 and G82 no Q.
#[test]
fn a_cycle_alarms_on_a_p_or_q_it_does_not_use() {
    let head = "G21 G90\nS1000 M3\nG0 X0 Y0 Z10\n";
    assert_eq!(
        alarm(&format!("{head}G81 X1 Z-5 R2 P1 F100\nM2\n")),
        (Code::E203, 4, 15)
    );
    assert_eq!(
        alarm(&format!("{head}G73 X1 Z-5 R2 Q1 P2 F100\nM2\n")),
        (Code::E203, 4, 18)
    );
    assert_eq!(
        alarm(&format!("{head}G82 X1 Z-5 R2 Q1 P2 F100\nM2\n")),
        (Code::E203, 4, 15)
    );
    // In a later block of the cycle too.
    assert_eq!(
        alarm(&format!("{head}G81 X1 Z-5 R2 F100\nX2 Q1\nM2\n")),
        (Code::E203, 5, 4)
    );
}

/// A dwell kept from a G82 does not make a later G83 dwell (LinuxCNC's G83
/// reads no P); under Fanuc it does (Syntec 1.2.36).
#[test]
fn a_pecking_cycle_never_dwells() {
    let program = "G21 G90\nS1000 M3\nG0 X0 Y0 Z10\nG82 X1 Z-2 R2 P1.5 F100\n\
                   G83 X2 Z-4 R2 Q2\nG80\nM2\n";
    let dwells = |ev: &[Event]| {
        ev.iter()
            .filter(|e| matches!(e, Event::Dwell { .. }))
            .count()
    };
    assert_eq!(dwells(&ended(program)), 1);
    let fanuc = program.replace("P1.5", "P1500").replace("Q2", "Q2.");
    let (ev, out) = run_str(&Dialect::fanuc(), &fanuc);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(dwells(&ev), 2);
}

/// G10 L1 P R Z writes tool P's radius and length; L10–L13 are Fanuc's
/// (LinuxCNC's L10/L11 set the table from the position, not run).
#[test]
fn g10_l1_writes_the_tool_table_and_fanucs_forms_alarm() {
    let set = ended("G21 G90\nG10 L1 P3 R4 Z20\nT3 M6\nG43 H3\nG0 X1 Z10\nM2\n");
    let frame_z = set.iter().find_map(|e| match e {
        Event::Frame { frame, .. } => Some(frame.tool_offset.get(2)),
        _ => None,
    });
    assert_eq!(frame_z, Some(20.0));
    assert_eq!(alarm("G21 G90\nG10 L10 P3 R4\nM2\n"), (Code::E109, 2, 5));
    assert_eq!(alarm("G21 G90\nG10 L1 P3\nM2\n"), (Code::E312, 2, 1));
}

/// O-word statements run along links found once per source (issue #25:
/// the shared compiled statements): a CONTINUE and a BREAK name their
/// loop by label, a false IF jumps to the next ELSEIF to be tested there
/// (an ELSEIF after a branch that ran is skipped), a RETURN inside a
/// REPEAT ends the sub's own passes only (the caller's REPEAT of the same
/// label counts on), and a statement's missing partner alarms when it
/// runs, after its operands. Moves worked out by hand from LinuxCNC's
/// "O Codes".
#[test]
fn o_words_follow_their_links() {
    // #1 = 1: three passes of X+1; 2: CONTINUE; 3: BREAK at once; 4: X+4 ×3.
    let nested = "G21 G91\n#1 = 0\no1 while [#1 LT 4]\n  #1 = [#1 + 1]\n  o2 if [#1 EQ 2]\n    \
                  o1 continue\n  o2 endif\n  o3 repeat [3]\n    o4 if [#1 EQ 3]\n      o3 break\n    \
                  o4 endif\n    G0 X#1\n  o3 endrepeat\no1 endwhile\nM2\n";
    assert_eq!(
        common::xs(&ended(nested)),
        vec![1.0, 2.0, 3.0, 7.0, 11.0, 15.0]
    );
    let branches = "G21 G90\n#2 = 2\no5 if [#2 EQ 1]\n  G0 X10\no5 elseif [#2 EQ 2]\n  G0 X20\n\
                    o5 elseif [#2 EQ 2]\n  G0 X30\no5 else\n  G0 X40\no5 endif\nM2\n";
    assert_eq!(common::xs(&ended(branches)), vec![20.0]);
    let returns = "G21 G91\no<f> sub\n  o1 repeat [5]\n    o2 if [#1 GT 0]\n      \
                   o<f> return [#1 * 10]\n    o2 endif\n  o1 endrepeat\no<f> endsub [0]\n\
                   o1 repeat [2]\n  o<f> call [1]\n  G0 X#<_value>\no1 endrepeat\nM2\n";
    assert_eq!(common::xs(&ended(returns)), vec![10.0, 20.0]);
    // The IF lacks its ENDIF: its vacant operand alarms first (E607 at
    // the operand), a defined one E611 at the statement.
    assert_eq!(alarm("G21\no6 if [#<nope>]\nM2\n"), (Code::E607, 2, 8));
    assert_eq!(alarm("G21\n#2 = 1\no6 if [#2]\nM2\n"), (Code::E611, 3, 1));
}

/// O-word statements that do not pair, or call what the file does not
/// define, alarm at the statement (E611); the other dialects name the
/// dialect that reads them (E604); what the dialect does not read alarms
/// at the construct, with a hint.
#[test]
fn o_words_named_parameters_and_lathe_codes_alarm_where_they_stand() {
    assert_eq!(alarm("G21\no100 sub\nM2\n"), (Code::E611, 2, 1));
    assert_eq!(alarm("G21\nO101 while [1]\nM2\n"), (Code::E611, 2, 1));
    assert_eq!(alarm("G21\no<probe> call [1]\nM2\n"), (Code::E611, 2, 1));
    assert_eq!(alarm("G21\no100 return\nM2\n"), (Code::E611, 2, 1));
    assert_eq!(alarm("G21\nN10 o100 endif\nM2\n").0, Code::E611);
    // A loop that never ends stops at the jump limit, located (a machine
    // with a low limit, to keep the test short).
    let machine = vcnc_interp::Machine::from_toml(
        &vcnc_interp::machine::DEFAULT_MILL_TOML.replace("max_jumps = 1000000", "max_jumps = 1000"),
    )
    .expect("machine");
    let mut sink = vcnc_interp::VecSink::default();
    let out = vcnc_interp::Interpreter::new(&machine, &Dialect::linuxcnc(), Default::default())
        .run_str("G21\no1 while [1]\no1 endwhile\nM2\n", &mut sink);
    assert!(
        matches!(&out, Outcome::Alarm(d) if (d.code, d.line) == (Code::E405, 3)),
        "{out:?}"
    );
    // Labels are local to a subroutine: a BREAK there finds no loop of the
    // caller (rs274: "undefined O-word label").
    assert_eq!(
        alarm(
            "G21\n#1=7\no1 while [1]\no100 sub\no1 break\no100 endsub\no100 call [3]\no1 endwhile\nM2\n"
        ),
        (Code::E611, 5, 1)
    );
    // A subroutine defined twice (rs274: "redefining sub").
    assert_eq!(
        alarm("G21\no100 sub\nG0 X1\no100 endsub\no100 sub\nG0 X2\no100 endsub\no100 call\nM2\n"),
        (Code::E611, 8, 1)
    );
    // A block-deleted call runs when the switch is off.
    assert_eq!(
        common::xs(&ended(
            "G21\n/o100 call [3]\no100 sub\nG0 X#1\no100 endsub\nM2\n"
        )),
        vec![3.0]
    );
    let (_, out) = run_str(&Dialect::fanuc(), "G21\no100 sub\nM30\n");
    assert!(
        matches!(out, Outcome::Alarm(d) if d.code == Code::E604 && d.help.contains("linuxcnc"))
    );
    // rs274 runs G7/G8 in a mill program too: G7 halves X (`G7 G0 X1`
    // goes to X0.5), G8 reads radii again (the moves:
    // `linuxcnc_dialect/g7_g8_in_a_mill_program`).
    assert_eq!(
        common::xs(&ended("G21\nG7 G0 X1\nG8 X1\nM2\n")),
        vec![0.5, 1.0]
    );
    // G33.1 taps with a turning spindle and K in the block, as rs274
    // wants ("Spindle not turning in G33.1", "K word missing with
    // g33/g33.1"); the taps themselves are checked against rs274
    // (`rigid_tapping_g33_1.ngc`).
    assert_eq!(alarm("G21\nG33.1 Z-5 K1\nM2\n"), (Code::E321, 2, 1));
    assert_eq!(
        alarm("G21\nS500 M3\nG33.1 Z-5 K1\nZ-6\nM2\n"),
        (Code::E312, 4, 1)
    );
}

/// LinuxCNC's parameters and expressions (`macros/ngc.rs`; their values
/// against rs274 in `tests/fixtures/linuxcnc_dialect/parameters_and_expressions.ngc`):
/// what rs274 refuses alarms at the word, and the other dialects without
/// macros still say they read none.
#[test]
fn parameters_alarm_where_rs274_refuses_them() {
    // A named parameter read before it is set.
    assert_eq!(alarm("G21\nG0 X#<depth>\nM2\n"), (Code::E607, 2, 5));
    // Parameter numbers 1 to 5602.
    assert_eq!(alarm("G21\n#0 = 1\nM2\n"), (Code::E605, 2, 1));
    assert_eq!(alarm("G21\nG0 X#5603\nM2\n"), (Code::E605, 2, 5));
    assert_eq!(alarm("G21\nG0 X[1/0]\nM2\n"), (Code::E608, 2, 7));
    assert_eq!(alarm("G21\nG0 X[SQRT[-1]]\nM2\n"), (Code::E609, 2, 6));
    assert_eq!(alarm("G21\nG0 X[FOO[1]]\nM2\n"), (Code::E604, 2, 6));
    assert_eq!(alarm("G21\nG0 X[1 + 2\nM2\n"), (Code::E601, 2, 5));
    assert_eq!(alarm("G21\n#1 2\nM2\n"), (Code::E601, 2, 4));
    // The settings of a line apply after it: X reads the old #1 (0), so
    // the first G0 moves Z alone (X0 where the tool is would not move).
    let ev = ended("G21 G90\n#1 = 4 G0 X#1 Z1\nG0 Y#1\nM2\n");
    let ends: Vec<(f64, f64)> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Rapid { to, .. } => Some((to.get(0), to.get(1))),
            _ => None,
        })
        .collect();
    assert_eq!(ends, vec![(0.0, 0.0), (0.0, 4.0)]);
    // The third review: G and M may repeat beside an expression; MOD lands
    // in [0, |b|) and EQ compares within 0.0001 (rs274's values); a
    // computed value beyond 9 digits is E103; `/` settings are skipped
    // under block delete.
    let xs = |p: &str| common::xs(&ended(p));
    assert_eq!(xs("G21 G90\nG0 G91 X[1/2]\nM2\n"), vec![0.5]);
    assert_eq!(
        xs("G21 G90\nG0 X[2 MOD -3]\nG0 X[[0.1 + 0.2] EQ 0.3]\nG0 X[-7 MOD -3]\nM2\n"),
        vec![2.0, 1.0, 2.0]
    );
    assert_eq!(alarm("G21\nG0 X[10 ** 20]\nM2\n"), (Code::E103, 2, 4));
    assert_eq!(alarm("G21\n#1 = [10 ** 400]\nM2\n"), (Code::E609, 2, 1));
    let (ev, _) = run_with_block_delete("G21 G90\n/#1 = 5\nG0 X[#1 + 1]\nM2\n");
    assert_eq!(common::xs(&ev), vec![1.0]);
    // Nesting is bounded (the reader recurses): 3,000 brackets alarm.
    let deep = format!("G21\nG0 X{}1{}\nM2\n", "[".repeat(3000), "]".repeat(3000));
    assert_eq!(alarm(&deep).0, Code::E602);
    // rs274's predefined named parameters are read-only ("Cannot assign
    // to read-only parameter #<_value>"), in any case; a `_` name of the
    // program's own is a global it may set.
    assert_eq!(
        alarm("o<f> sub\no<f> endsub\n#<_value>=5\no<f> call\nG0 X#<_value>\nM2\n"),
        (Code::E606, 3, 1)
    );
    for name in [
        "_value_returned",
        "_X",
        "_feed",
        "_line",
        "_abs_c",
        "_call_level",
    ] {
        assert_eq!(
            alarm(&format!("G21\nG0 X1 #<{name}> = 2\nM2\n")),
            (Code::E606, 2, 7),
            "{name}"
        );
    }
    assert_eq!(
        xs("G21 G90\n#<_abs_u> = 2\n#<_mine> = 3\nG0 X[#<_abs_u> + #<_mine>]\nM2\n"),
        vec![5.0]
    );
    // grbl reads no parameters.
    let (_, out) = run_str(&Dialect::grbl(), "G21\n#1 = 2\nM2\n");
    assert!(matches!(out, Outcome::Alarm(d) if d.code == Code::E101));
}

/// rs274's refusals that are about the cycle's data: zero repeats, a
/// changed cycle that does not write R, the depth and its P or Q again,
/// tool 0 in G10 L1.
#[test]
fn cycle_data_rs274_refuses_alarms_here_too() {
    let head = "G21 G90\nS1000 M3\nG0 X0 Y0 Z10\n";
    // "Cannot do zero repeats of cycle".
    assert_eq!(
        alarm(&format!("{head}G91 G81 X5 Z-5 R-2 L0 F100\nM2\n")),
        (Code::E109, 4, 20)
    );
    // "R clearance plane unspecified in cycle".
    assert_eq!(
        alarm(&format!(
            "{head}G81 X5 Y5 Z-3 R2 F200\nG82 X10 Z-3 P1\nM2\n"
        )),
        (Code::E312, 5, 1)
    );
    // "Z value unspecified in xy plane canned cycle".
    assert_eq!(
        alarm(&format!("{head}G81 X5 Y5 Z-3 R2 F200\nG83 X10 R2 Q1\nM2\n")),
        (Code::E312, 5, 1)
    );
    // "Dwell time P word missing with G86".
    assert_eq!(
        alarm(&format!("{head}G86 X5 Y5 Z-3 R2 F200\nM2\n")),
        (Code::E312, 4, 1)
    );
    // The same code again takes the data over.
    ended(&format!(
        "{head}G82 X5 Y5 Z-3 R2 P1 F200\nG82 X10\nG80\nM2\n"
    ));
    // "P value out of range with G10 L1".
    assert_eq!(alarm("G21\nG10 L1 P0 Z5\nM2\n"), (Code::E109, 2, 8));
}

/// LinuxCNC's own auxiliary M codes (overrides, motion-synchronized and
/// immediate I/O, waits, user M100–M199) pass on as `aux` events with
/// their words; under Fanuc they are unknown and their P unused (E203).
#[test]
fn io_and_user_m_codes_pass_on_with_their_words() {
    let ev = ended(
        "G21 G90\nM62 P1\nG1 X10 F500\nM63 P1\nM66 P0 L3 Q5\nM67 E0 Q2.5\nM48\nM100 P1 Q2\nM2\n",
    );
    let aux: Vec<u32> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Aux { code, .. } => Some(*code),
            _ => None,
        })
        .collect();
    assert_eq!(aux, vec![62, 63, 66, 67, 48, 100]);
    let (_, out) = run_str(&Dialect::fanuc(), "G21 G90\nM62 P1\nM2\n");
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code, d.line, d.column), (Code::E203, 2, 5));
    // M61 (set the tool number) and M70–M73 (modal state) change state
    // vcnc does not keep: unknown, as before.
    assert_eq!(alarm("G21\nM61 Q3\nM2\n"), (Code::E203, 2, 5));
}

/// The second review's findings: a cycle code without axis words alarms
/// (rs274: "All axes missing with motion code") instead of hiding the
/// next block's cycle change; an M code's P/Q in a cycle block is its own;
/// the lexer's O-word alarm wants a blank after the O number (glued, it is
/// a lettered program name) and finds it after a sequence number too; the
/// hint names a dialect that runs the code, not one that lists it as not
/// run; G10 L0 keeps Fanuc's range.
#[test]
fn second_review_findings_stay_fixed() {
    let head = "G21 G90\nS1000 M3\nG0 X0 Y0 Z20\nG81 X0 Y0 Z-5 R2 F100\n";
    assert_eq!(
        alarm(&format!("{head}G82\nG82 X20\nM2\n")),
        (Code::E312, 5, 1)
    );
    let ev = ended(&format!("{head}X10 M62 P1\nX20 M66 P0 L1 Q5\nG80\nM2\n"));
    assert_eq!(
        ev.iter()
            .filter(|e| matches!(e, Event::Hole { .. }))
            .count(),
        3
    );
    let fanuc = |p: &str| {
        let (_, out) = run_str(&Dialect::fanuc(), p);
        match out {
            Outcome::Alarm(d) => (d.code, d.line, d.column, d.message, d.help),
            o => panic!("{o:?}"),
        }
    };
    assert_eq!(fanuc("G21\nO100IF\nM30\n").0, Code::E104);
    assert_eq!(fanuc("G21\nN10 o100 sub\nM30\n").0, Code::E604);
    // G7 runs in LinuxCNC's mill and lathe modes; a mill program is sent
    // to the mill dialect.
    let (code, _, _, _, help) = fanuc("G21\nG7\nM30\n");
    assert_eq!(code, Code::E201);
    assert!(help.contains("--dialect linuxcnc "), "{help}");
    let (_, _, _, _, help) = fanuc("G21\nG33.1 Z-5 K1\nM30\n");
    assert!(
        help.contains("--dialect linuxcnc"),
        "linuxcnc runs G33.1: {help}"
    );
    // A code no dialect runs names none.
    let (_, _, _, _, help) = fanuc("G21\nG43.2 H1\nM30\n");
    assert!(!help.contains("--dialect"), "no dialect runs G43.2: {help}");
    let (code, _, _, message, _) = fanuc("G21\nG10 L0 P1 X1\nM30\n");
    assert_eq!(code, Code::E109);
    assert!(message.contains("2..20"), "{message}");
}

/// `G64 P` is LinuxCNC's blending tolerance: a `smoothing` event with P,
/// which the planner reads as G05.1's E; `G64` alone turns it off (the
/// machine's own corner tolerance); a negative P alarms.
#[test]
fn g64_p_is_a_blending_tolerance_for_the_planner() {
    let ev = ended("G21 G90\nG64 P0.05 Q0.01\nG1 X10 F3000\nG64\nX20\nM2\n");
    let smoothing: Vec<(bool, f64)> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Smoothing {
                on, tolerance_mm, ..
            } => Some((*on, *tolerance_mm)),
            _ => None,
        })
        .collect();
    assert_eq!(smoothing, vec![(true, 0.05), (false, 0.0)]);
    // A bare G64 with nothing on sends nothing.
    let ev = ended("G21 G90 G64 G40\nG1 X1 F100\nM2\n");
    assert!(!ev.iter().any(|e| matches!(e, Event::Smoothing { .. })));
    assert_eq!(alarm("G21\nG64 P-1\nM2\n"), (Code::E109, 2, 5));
    // LinuxCNC 2.9's G64 reads P and Q (the naive-CAM tolerance) only: rs274
    // 2.9 refuses `G64 P0.01 R0.02` with "R word with no g code that uses
    // it", and so does vcnc, at the R.
    assert_eq!(alarm("G21\nG64 P0.01 R0.02\nM2\n"), (Code::E203, 2, 11));
    assert_eq!(alarm("G21\nG64 R0.02\nM2\n"), (Code::E203, 2, 5));
}

/// A store that records every subroutine file asked for, and has one:
/// `mark.ngc`.
#[derive(Default)]
struct SubFiles {
    asked: Vec<String>,
}

impl vcnc_interp::ProgramStore for SubFiles {
    fn open(
        &mut self,
        _: u32,
    ) -> Option<std::io::Result<(Box<dyn vcnc_syntax::TextSource>, String)>> {
        None
    }

    fn open_subroutine(
        &mut self,
        name: &str,
    ) -> Option<std::io::Result<(Box<dyn vcnc_syntax::TextSource>, String)>> {
        self.asked.push(name.to_string());
        let text = match name {
            "mark" => "o<mark> sub\nG0 X#1\no<mark> endsub [#1 * 2]\nM2\n",
            "other" => "o<else> sub\no<else> endsub\n",
            _ => return None,
        };
        Some(Ok((
            Box::new(vcnc_syntax::MemSource(text.as_bytes().to_vec())),
            format!("{name}.ngc"),
        )))
    }
}

fn run_with_files(program: &str) -> (Vec<Event>, Outcome, Vec<String>) {
    let machine = vcnc_interp::Machine::default_mill();
    let mut sink = vcnc_interp::VecSink::default();
    let mut store = SubFiles::default();
    let out = vcnc_interp::Interpreter::new(&machine, &Dialect::linuxcnc(), Default::default())
        .run(
            Box::new(vcnc_syntax::MemSource(program.as_bytes().to_vec())),
            &mut store,
            &mut sink,
        );
    (sink.0, out, store.asked)
}

/// `o<name> call` of a subroutine the program does not define opens
/// `name.ngc` once (a second call reuses it); a name that is no plain
/// file name never reaches the store; a file without the sub alarms.
#[test]
fn subroutine_files_are_asked_for_by_plain_names_only() {
    let (ev, out, asked) = run_with_files("G21\no<mark> call [2]\no<mark> call [#<_value>]\nM2\n");
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(common::xs(&ev), vec![2.0, 4.0]);
    assert_eq!(asked, vec!["mark".to_string()]);
    for name in [
        "../mark",
        "/etc/mark",
        "sub/mark",
        ".mark",
        "c:mark",
        "..\\mark",
    ] {
        let (ev, out, asked) = run_with_files(&format!("G21\no<{name}> call\nG0 X1\nM2\n"));
        assert!(
            matches!(&out, Outcome::Alarm(d) if (d.code, d.line, d.column) == (Code::E611, 2, 1)),
            "{name}: {out:?}"
        );
        assert!(asked.is_empty(), "{name} reached the store: {asked:?}");
        assert!(common::xs(&ev).is_empty());
    }
    let (_, out, _) = run_with_files("G21\no<other> call\nM2\n");
    assert!(
        matches!(&out, Outcome::Alarm(d) if d.code == Code::E611 && d.message.contains("other.ngc defines no")),
        "{out:?}"
    );
    // A missing sub is named as an o-word, `o<name>`, in lower case as
    // rs274 reads it, and the help says the file name is lower case.
    let (_, out, asked) = run_with_files(
        "G21
o<MySub> call
M2
",
    );
    let Outcome::Alarm(d) = &out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code, d.line, d.column), (Code::E611, 2, 1));
    assert!(
        d.message
            .starts_with("o<mysub> call: no o<mysub> sub in this program, and no mysub.ngc"),
        "{}",
        d.message
    );
    assert!(d.help.contains("lower case"), "{}", d.help);
    assert_eq!(asked, vec!["mysub".to_string()]);
}

/// G41.1/G42.1: compensation by the block's D diameter, no register. On
/// the mill `G41.1 D6` is G41 with a tool of radius 3 (rs274 alike:
/// `tests/fixtures/linuxcnc_comp_dynamic`); in lathe mode `G42.1 D0.8 L3`
/// is G42 with a tool of nose radius 0.4 and orientation 3. rs274's
/// refusals alarm here too: no D ("G41.1 with no D word"), L outside the
/// XZ plane ("G41.1 with L word, but plane is not G18").
#[test]
fn dynamic_compensation_takes_the_blocks_diameter_and_orientation() {
    let with_tool = |d: &Dialect, text: &str, tool: vcnc_interp::machine::Tool| {
        let mut machine = d.machine();
        machine.tools.insert(1, tool);
        let mut sink = vcnc_interp::VecSink::default();
        let out =
            vcnc_interp::Interpreter::new(&machine, d, Default::default()).run_str(text, &mut sink);
        assert!(matches!(out, Outcome::Ended(_)), "{out:?}\n{text}");
        sink.0
            .into_iter()
            .filter(|e| !matches!(e, Event::Warning(_)))
            .collect::<Vec<_>>()
    };
    let mill = Dialect::linuxcnc();
    let contour = |c: &str| {
        format!(
            "G21 G17\nG0 X-10 Y-10\n{c} G1 X0 Y0 F100\nG1 X40\nG1 Y30\nG1 X0\nG1 Y0\nG40 G1 X-10 Y-10\nM2\n"
        )
    };
    let radius3 = vcnc_interp::machine::Tool {
        d_mm: 3.0,
        ..Default::default()
    };
    for (dynamic, table) in [
        ("G41.1 D6", "G41 D1"),
        ("G42.1 D6", "G42 D1"),
        ("G41.1 D-6", "G42 D1"),
    ] {
        assert_eq!(
            with_tool(&mill, &contour(dynamic), radius3),
            with_tool(&mill, &contour(table), radius3),
            "{dynamic}"
        );
    }
    let lathe = Dialect::linuxcnc_lathe();
    let turn = |c: &str| {
        format!(
            "G21 G18 G8\nT1 M6\nG0 X30 Z5\n{c} G1 X10 Z0 F100\nG1 Z-20\nG1 X20 Z-30\nG40 G1 X30 Z-30\nM2\n"
        )
    };
    let nose = vcnc_interp::machine::Tool {
        nose_radius_mm: 0.4,
        tip: 3,
        ..Default::default()
    };
    assert_eq!(
        with_tool(&lathe, &turn("G42.1 D0.8 L3"), Default::default()),
        with_tool(&lathe, &turn("G42 D1"), nose)
    );
    assert_eq!(alarm("G21\nG41.1 G1 X1\nM2\n"), (Code::E312, 2, 1));
    assert_eq!(alarm("G21\nG41.1 D6 L3 G1 X1\nM2\n"), (Code::E203, 2, 10));
}

/// rs274 refuses to turn compensation on while it is on, whatever the
/// code, side or diameter ("Cannot turn cutter radius comp on when on",
/// probed with rs274 -g: `G41.1 D8` under G41.1, `G42` under G41, `G41`
/// under G41 with no move between); E320 here, at the code, with no
/// motion after it. Fanuc changes side and offset in offset mode: runs.
#[test]
fn compensation_turned_on_while_on_alarms_as_in_rs274() {
    let on_on = |first: &str, second: &str| {
        format!(
            "G21 G90 G17\nG10 L1 P1 R2\nT1 M6\nG0 X-10 Y-10\n{first} G1 X0 Y0 F100\nX20\n{second} X40\nG40 X50 Y30\nM2\n"
        )
    };
    for (first, second) in [
        ("G41.1 D4", "G41.1 D8"),
        ("G41.1 D4", "G42.1 D4"),
        ("G41", "G42"),
        ("G42 D1", "G42 D1"),
        ("G41", "G41.1 D4"),
    ] {
        let program = on_on(first, second);
        assert_eq!(alarm(&program), (Code::E320, 7, 1), "{program}");
    }
    assert_eq!(
        alarm("G21\nG10 L1 P1 R2\nT1 M6\nG41\nG41\nG40\nM2\n"),
        (Code::E320, 5, 1)
    );
    // After G40 it may start again.
    let (_, out) = run(&on_on("G41", "G40 X30\nG42"));
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let fanuc = on_on("G41 D1", "G42 D1").replace("G10 L1 ", "G10 L12 ");
    let (_, out) = run_str(&Dialect::fanuc(), &fanuc);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
}

/// rs274 refuses any `(` inside a comment ("Nested comment found",
/// probed with rs274 -g: also in a `(msg, …)` and on a line with a
/// parameter setting; a `(` after `;` and two comments side by side
/// pass); E101 at the inner `(`. The Fanuc family reads it as text.
#[test]
fn a_parenthesis_inside_a_comment_alarms_as_in_rs274() {
    assert_eq!(alarm("G0 X1 (T1 (6MM END MILL)\nM2\n"), (Code::E101, 1, 11));
    assert_eq!(alarm("G21\n(msg, a (b)\nM2\n"), (Code::E101, 2, 9));
    assert_eq!(alarm("G21\n#1=2 (a (b)\nM2\n"), (Code::E101, 2, 9));
    assert_eq!(alarm("G21\nG0 X1 (a ( b) (c)\nM2\n"), (Code::E101, 2, 10));
    let xs = |p: &str| common::xs(&ended(p));
    assert_eq!(
        xs("G21\nG0 X1 ; a (b\nG0 X2 (a b) (c)\nM2\n"),
        vec![1.0, 2.0]
    );
    let (_, out) = run_str(&Dialect::fanuc(), "G21\nG0 X1 (T1 (6MM END MILL)\nM30\n");
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
}

/// G2/G3 P, LinuxCNC's number of turns (rs274 -g: `G3 … P2` is
/// `ARC_FEED(…, 2, …)`; P0, P-1: "P value should be 1 or greater with G2
/// or G3"; P1.5: "P value not an integer"): P1 is the plain arc, P n is
/// n − 1 full circles and then the arc (the helix's Z spread over the
/// whole angle: `tests/fixtures/linuxcnc_dialect/multi_turn_arcs`).
#[test]
fn arc_turns_p_runs_full_circles_before_the_arc() {
    let arc = |p: &str| format!("G21 G90 G17\nG0 X100 Y0\nG3 X0 Y100 I-100 J0 {p} F100\nM2\n");
    assert_eq!(ended(&arc("P1")), ended(&arc("")));
    let ends = |p: &str| common::ends(&ended(p), 3);
    let e = ends(&arc("P2"));
    assert_eq!(e.len(), 2, "{e:?}");
    assert!(common::near(e[0], 100.0, 0.0, 0.0), "{e:?}");
    assert!(common::near(e[1], 0.0, 100.0, 0.0), "{e:?}");
    // With Z: a quarter after one circle, 2π of 2.5π: Z at 4/5 of the way.
    let e = ends(&arc("Z-5 P2"));
    assert!(common::near(e[0], 100.0, 0.0, -4.0), "{e:?}");
    assert!(common::near(e[1], 0.0, 100.0, -5.0), "{e:?}");
    // In a modal G3 block too (rs274: ARC_FEED(…, 2, …)).
    let modal = arc("P1").replace("M2\n", "X100 Y0 I0 J-100 P3\nM2\n");
    assert_eq!(common::ends(&ended(&modal), 4).len(), 3);
    for (bad, code) in [
        ("P0", Code::E109),
        ("P-1", Code::E109),
        ("P1.5", Code::E108),
        ("P10001", Code::E109),
    ] {
        assert_eq!(alarm(&arc(bad)).0, code, "{bad}");
    }
}

/// rs274's end-point rule for I/J/K arcs: the ends rs274 2.9 refuses
/// ("Radius to end of arc differs from radius to start"), each just past
/// the edge the fixture `linuxcnc_dialect/arc_end_tolerance` runs on its
/// near side (probed with rs274 -g: 0.0282 mm runs and 0.0284 mm stops on a
/// 1 mm arc; 0.1001 mm inside a 100 mm arc stops, outside it runs, the
/// ratio being of the larger radius; 2.82 mm runs and 2.84 mm stops on a
/// 10,000 mm arc; 0.00284 in stops on a 1 in arc).
#[test]
fn arc_ends_off_the_circle_alarm_past_rs274s_absolute_and_relative_rule() {
    let arc = |units: &str, r: &str, end: &str| {
        format!("{units} G17 G90\nG0 X{r} Y0\nG2 X0 Y{end} I-{r} J0 F100\nM2\n")
    };
    for (units, r, end) in [
        ("G21", "1", "1.0284"),
        ("G21", "100", "99.8999"),
        ("G21", "10000", "10002.84"),
        ("G20", "1", "1.00284"),
    ] {
        assert_eq!(
            alarm(&arc(units, r, end)),
            (Code::E303, 3, 1),
            "{units} R{r} to {end}"
        );
    }
    for (units, r, end) in [
        ("G21", "1", "1.0282"),
        ("G21", "100", "100.1001"),
        ("G21", "10000", "10002.82"),
        ("G20", "1", "1.00282"),
    ] {
        ended(&arc(units, r, end));
    }
}

/// The other dialects keep the machine's `arc_tolerance_mm` (0.01 mm): the
/// Fusion arc rs274 runs is E303 under fanuc.
#[test]
fn other_dialects_keep_the_machine_arc_tolerance() {
    let p = "G21 G17 G90\nG0 X895.5278 Y0\nG3 X0 Y895.5532 I-895.5278 J0 F100\nM30\n";
    let (_, out) = run_str(&Dialect::fanuc(), p);
    assert!(
        matches!(&out, Outcome::Alarm(d) if d.code == Code::E303),
        "{out:?}"
    );
}

/// LinuxCNC's G76 runs in lathe mode (its passes against rs274 in
/// `tests/fixtures/linuxcnc_lathe_cycles`); the mill dialect sends it
/// there, and a block without its words alarms at the code.
#[test]
fn g76_threads_in_lathe_mode_and_alarms_without_its_words() {
    let (_, out) = run("G21\nG76 P1.5 Z-20 I-1 J0.2 K1\nM2\n");
    assert!(
        matches!(&out, Outcome::Alarm(d) if d.code == Code::E201 && d.message.contains("linuxcnc-lathe")),
        "{out:?}"
    );
    let lathe = |p: &str| {
        let (ev, out) = run_str(&Dialect::linuxcnc_lathe(), p);
        (ev, out)
    };
    let head = "G18 G21 G90 G8 G95\nS300 M3\nG0 X12 Z3\n";
    let (ev, out) = lathe(&format!("{head}G76 P1.5 Z-20 I-1 J0.5 K1\nM2\n"));
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    // Depths 0.5 and 1 (R1: J·n): two passes at X 10.5 and 10.
    let threads: Vec<f64> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Thread { to, .. } => Some(to.get(0)),
            _ => None,
        })
        .collect();
    assert_eq!(threads, vec![10.5, 10.0]);
    for (block, code, column) in [
        ("G76 Z-20 I-1 J0.5 K1", Code::E312, 1),
        ("G76 P1.5 I-1 J0.5 K1", Code::E312, 1),
        ("G76 P1.5 Z-20 I0 J0.5 K1", Code::E109, 15),
        ("G76 P1.5 Z-20 I-1 J0.5 K1 X3", Code::E203, 27),
        ("G76 P1.5 Z3 I-1 J0.5 K1", Code::E314, 1),
    ] {
        let (ev, out) = lathe(&format!("{head}{block}\nM2\n"));
        assert!(
            matches!(&out, Outcome::Alarm(d) if (d.code, d.line, d.column) == (code, 4, column)),
            "{block}: {out:?}"
        );
        assert!(
            !ev.iter().any(|e| matches!(e, Event::Thread { .. })),
            "{block}"
        );
    }
}

/// What Fanuc and Haas let pass beside G53 and G49 rs274 refuses: `G49 H0`
/// and `G53 G0 H0 Z0` ("H word with no G43 or G76 to use it": H is a tool
/// number here) and a bare G53 ("Must use g0 or g1 with g53").
#[test]
fn h0_beside_g49_and_a_bare_g53_alarm_as_in_rs274() {
    assert_eq!(alarm("G21\nG49 H0\nM2\n"), (Code::E203, 2, 5));
    assert_eq!(alarm("G21\nG53 G0 H0 Z0\nM2\n"), (Code::E203, 2, 8));
    assert_eq!(alarm("G21\nG53\nM2\n"), (Code::E312, 2, 1));
}

/// LinuxCNC's G70 in lathe mode: the profile is subroutine `o<Q>`; each
/// of P passes goes to the start point (X Z, else where the tool is) and
/// at rapid to the profile's first point, then along it, and the tool
/// stays at its end. rs274 on this program: traverse (11, 2), (5, 0),
/// feed (5, −10), (8, −15), (10, −15), twice (radii). The 40 programs of
/// `tests/fixtures/linuxcnc_lathe` check the single pass against rs274.
#[test]
fn g70_runs_the_profile_subroutine_in_lathe_mode() {
    let program = "G18 G21 G90 G7 G95\nS800 M3\nO100 sub\nG1 X10 Z0\nG1 Z-10\nG1 X16 Z-15\nG1 X20\nO100 endsub\nG0 X22 Z2\nG70 Q100 P2 F0.05\nM2\n";
    let (ev, out) = run_str(&Dialect::linuxcnc_lathe(), program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let ends: Vec<(f64, f64)> = ev
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| (p.get(0), p.get(2)))
        .collect();
    let pass = [
        (11.0, 2.0),
        (5.0, 0.0),
        (5.0, -10.0),
        (8.0, -15.0),
        (10.0, -15.0),
    ];
    let want: Vec<(f64, f64)> = pass.iter().chain(&pass[..]).copied().collect();
    assert_eq!(ends, want);
    // One pass runs at E (0 here): D alone leaves the profile as it is,
    // as rs274 does (`tests/fixtures/linuxcnc_lathe_cycles` checks the
    // offset passes).
    let (ev, out) = run_str(
        &Dialect::linuxcnc_lathe(),
        &program.replace("G70 Q100 P2", "G70 Q100 D0.5"),
    );
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let ends: Vec<(f64, f64)> = ev
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| (p.get(0), p.get(2)))
        .collect();
    assert_eq!(ends, pass);
    let (_, out) = run_str(
        &Dialect::linuxcnc_lathe(),
        &program.replace("G70 Q100 P2", "G70 Q200"),
    );
    assert!(
        matches!(&out, Outcome::Alarm(d) if (d.code, d.line) == (Code::E611, 10)),
        "{out:?}"
    );
}

/// What rs274 2.9 refuses in blocks with the polar words `@` and `^`
/// (each message is rs274's, from `echo | rs274 -g` on the block; the
/// moves it runs are in `tests/fixtures/linuxcnc_dialect/polar_words`):
/// the alarm stands at the word and nothing moves after it.
#[test]
fn polar_words_rs274_refuses_alarm_here_too() {
    let cases: &[(&str, Code, u64, u32)] = &[
        // "Cannot specify both polar coordinate and X word": at the X.
        ("G0 X1 Y1\nG1 @10 X2 F100\nM2\n", Code::E204, 2, 8),
        ("G0 X1 Y1\nG1 ^10 Y2 F100\nM2\n", Code::E204, 2, 8),
        // "Must specify angle in polar coordinate if at the origin".
        ("G1 @10 F100\nM2\n", Code::E312, 1, 4),
        // "Incremental motion with polar coordinates is indeterminate
        // when at the origin", and "G91 motion with ..." for ^ alone.
        ("G91 G1 @1 ^90 F100\nM2\n", Code::E312, 1, 8),
        ("G91 G1 ^90 F100\nM2\n", Code::E312, 1, 8),
        // "Cannot use polar coordinate except in G17 plane": the plane the
        // block starts in (G17 in the block itself does not help).
        ("G0 X1 Y1\nG18\nG1 @1 ^2 F100\nM2\n", Code::E203, 3, 4),
        ("G0 X1 Y1\nG19\nG17 G1 @1 ^2 F100\nM2\n", Code::E203, 3, 8),
        // "Polar coordinates can only be used for motion" (G28, G92), and
        // "Cannot use polar coordinates with G53".
        ("G0 X1\nG28 @1 ^2\nM2\n", Code::E203, 2, 5),
        ("G0 X1\nG92 @1 ^2\nM2\n", Code::E203, 2, 5),
        ("G0 X1\nG53 G0 @1 ^2\nM2\n", Code::E203, 2, 8),
    ];
    for (program, code, line, column) in cases {
        assert_eq!(alarm(program), (*code, *line, *column), "{program}");
    }
    // What rs274 runs from the same points: off the origin, G91 adds to
    // the point's own distance and angle; at the origin under G90 the
    // angle alone is enough (the distance is the current one, 0: a move
    // that does not move, which vcnc drops like every such move).
    let ev = ended("G0 X3 Y4\nG91 G1 @5 F100\nG90 G1 ^90\nG0 X0 Y0\nG1 ^30\nM2\n");
    let ends: Vec<(f64, f64)> = ev
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| {
            (
                (p.get(0) * 1e6).round() / 1e6,
                (p.get(1) * 1e6).round() / 1e6,
            )
        })
        .collect();
    assert_eq!(ends, [(3.0, 4.0), (6.0, 8.0), (0.0, 10.0), (0.0, 0.0)]);
    assert!(matches!(ev.last(), Some(Event::End { .. })), "{ev:?}");
}

/// `@` and `^` are LinuxCNC's: the other dialects read them as the
/// illegal characters they are there, and the lathe (no Y) as words no
/// command uses.
#[test]
fn polar_words_are_linuxcnc_mill_only() {
    for d in [Dialect::grbl(), Dialect::fanuc()] {
        let (_, out) = run_str(&d, "G0 X1\nG0 @1 ^2\nM2\n");
        assert!(
            matches!(&out, Outcome::Alarm(a) if (a.code, a.line, a.column) == (Code::E101, 2, 4)),
            "{}: {out:?}",
            d.name
        );
    }
    let (_, out) = run_str(&Dialect::linuxcnc_lathe(), "G0 X1\nG0 @1 ^2\nM2\n");
    assert!(
        matches!(&out, Outcome::Alarm(a) if (a.code, a.line) == (Code::E203, 2)),
        "{out:?}"
    );
}

/// rs274's G70 reads only the geometry of its `o<Q> sub` (h01 of the
/// review, `rs274 -g`: one SET_FEED_RATE(0.2) before the cycle, none in
/// it): the profile's F words neither feed the cycle nor outlast it.
#[test]
fn g70_ignores_the_profiles_feed_words() {
    let program = "G18 G21 G90 G8 G95\nS500 M3\nO10 sub\nG1 X5 Z0 F0.05\nG1 Z-10 F0.1\n\
                   G1 X10 Z-15\nO10 endsub\nG0 X12 Z2\nF0.2\nG70 Q10\nG1 X14 Z-20\nM2\n";
    let (ev, out) = run_str(&Dialect::linuxcnc_lathe(), program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let feeds: Vec<f64> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Feed {
                feed: vcnc_core::events::Feed::PerRev(f),
                ..
            } => Some(*f),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, [0.2, 0.2, 0.2]);
}

/// What LinuxCNC's roughing cycles G71/G72 refuse, each checked with
/// `rs274 -g` (its words in the test): a depth of cut I of zero ("I must
/// be greater than zero": E346) or below (E109), P or E beside it ("P word
/// with no … to use it": E203), a profile that turns back ("Not
/// monotonic": E343 at that block), two neighbouring parallel lines under
/// an allowance ("Cannot intersect parallel lines": E343), cutter
/// compensation in force ("cannot be used with cutter compensation
/// enabled": E349). Under G91 rs274 2.9.0 reads the cycle block's X Z as
/// absolute and the profile as increments: vcnc refuses that (E349). In
/// the mill dialect the cycles are E201, naming `linuxcnc-lathe`. The
/// moves themselves are rs274's (`tests/fixtures/linuxcnc_lathe_cycles`).
#[test]
fn roughing_cycles_refuse_what_rs274_refuses() {
    let run = |sub: &str, cycle: &str| {
        let program = format!(
            "G18 G21 G90 G8 G95\nS800 M3\nO100 sub\n{sub}\nO100 endsub\nG0 X11 Z2\nF0.1\n{cycle}\nM2\n"
        );
        let (ev, out) = run_str(&Dialect::linuxcnc_lathe(), &program);
        let Outcome::Alarm(d) = out else {
            panic!("no alarm: {out:?}\n{program}");
        };
        assert!(
            matches!(ev.last(), Some(Event::Alarm(a)) if *a == d),
            "motion after the alarm"
        );
        (d.code, d.line)
    };
    let profile = "G1 X5 Z0\nG1 Z-10\nG1 X8 Z-15\nG1 X10";
    assert_eq!(run(profile, "G71 Q100 I0"), (Code::E346, 11));
    assert_eq!(run(profile, "G71 Q100 I-1"), (Code::E109, 11));
    assert_eq!(run(profile, "G71 Q100 P2"), (Code::E203, 11));
    assert_eq!(run(profile, "G72 Q100 E1"), (Code::E203, 11));
    assert_eq!(run(profile, "G71"), (Code::E312, 11));
    assert_eq!(run(profile, "G41 G71 Q100"), (Code::E349, 11));
    assert_eq!(run(profile, "G91 G71 Q100"), (Code::E349, 11));
    // rs274: "G71.0 can only be used in XZ plane (G18)", and G70 alike.
    assert_eq!(run(profile, "G17 G71 Q100"), (Code::E349, 11));
    assert_eq!(run(profile, "G17 G70 Q100"), (Code::E349, 11));
    let back = "G1 X5 Z0\nG1 Z-5\nG1 X7 Z-3\nG1 X9 Z-14";
    assert_eq!(run(back, "G71 Q100 I1"), (Code::E343, 6));
    let parallel = "G1 X5 Z0\nG1 Z-5\nG1 Z-10\nG1 X9 Z-14";
    assert_eq!(run(parallel, "G71 Q100 I1 D0.2"), (Code::E343, 4));
    // Without an allowance nothing is offset: the same profile runs.
    let program = format!(
        "G18 G21 G90 G8 G95\nS800 M3\nO100 sub\n{parallel}\nO100 endsub\nG0 X11 Z2\nF0.1\nG71 Q100 I1\nM2\n"
    );
    let (_, out) = run_str(&Dialect::linuxcnc_lathe(), &program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let (_, out) = run_str(&Dialect::linuxcnc(), "G21\nG71 Q100\nM2\n");
    assert!(
        matches!(&out, Outcome::Alarm(d) if d.code == Code::E201 && d.message.contains("linuxcnc-lathe")),
        "{out:?}"
    );
}

/// Cutter compensation may start on an arc (rs274's entry arc, probed with
/// rs274 -g, tool radius 2 mm: `G0 X0 Y-20` then `G41 G3 X10 Y-10 I0 J10`
/// is ARC_FEED to (8, −10) about (−2.25, −10)): the arc ends r from its
/// programmed end along the radius, about a centre on the line through the
/// programmed centre and end, as far from the start as from the new end;
/// the next block joins as after any arc. Refused as rs274 refuses it: a
/// start within r of the end ("Radius of cutter compensation entry arc is
/// not greater than the tool radius") is E318 at the arc, an arc that
/// cancels compensation E317 ("The move just after exiting cutter
/// compensation mode must be straight"), and so is an entry line not longer
/// than r in the plane. Fanuc keeps E317 (type A's
/// start-up is a line). The moves rs274 makes are also the fixture
/// `tests/fixtures/linuxcnc_dialect/comp_entry_arc`.
#[test]
fn compensation_starts_on_an_entry_arc_as_in_rs274() {
    let entry = |comp: &str, arc: &str| {
        format!("G21 G90 G17\nG10 L1 P1 R2\nT1 M6\nG0 X0 Y-20\n{comp} {arc} F100\nG1 Y10\nM2\n")
    };
    for (comp, arc, end, centre) in [
        ("G41", "G3 X10 Y-10 I0 J10", (8.0, -10.0), (-2.25, -10.0)),
        (
            "G42",
            "G3 X10 Y-10 I0 J10",
            (12.0, -10.0),
            (11.0 / 6.0, -10.0),
        ),
        (
            "G41",
            "G2 X-10 Y-10 I0 J10",
            (-12.0, -10.0),
            (-11.0 / 6.0, -10.0),
        ),
        // G41 alone, the arc the first move after it.
        ("G41\n", "G3 X10 Y-10 I0 J10", (8.0, -10.0), (-2.25, -10.0)),
    ] {
        let program = entry(comp, arc);
        let ev = ended(&program);
        let arcs: Vec<_> = ev
            .iter()
            .filter_map(|e| match e {
                Event::Arc { to, center, .. } => Some((*to, *center)),
                _ => None,
            })
            .collect();
        assert_eq!(arcs.len(), 1, "{program}");
        let (to, c) = arcs[0];
        assert!(common::near(to, end.0, end.1, 0.0), "{to:?}\n{program}");
        assert!(common::near(c, centre.0, centre.1, 0.0), "{c:?}\n{program}");
        // The line after it follows the offset path: X at the new end.
        let line = common::ends(&ev, if comp.ends_with('\n') { 7 } else { 6 });
        assert!(
            common::near(line[0], end.0, 10.0, 0.0),
            "{line:?}\n{program}"
        );
    }
    // An inside corner after it moves the arc's end onto the next offset
    // path, on the entry arc's own circle (rs274: (7.9689, −10.7974)).
    let ev = ended(
        "G21 G90 G17\nG10 L1 P1 R2\nT1 M6\nG0 X0 Y-20\nG41 G3 X10 Y-10 I0 J10 F100\nG1 X0 Y0\nM2\n",
    );
    let to = common::ends(&ev, 5)[0];
    assert!(
        (to.0[0] - 7.968939).abs() < 1e-6 && (to.0[1] + 10.797366).abs() < 1e-6,
        "{to:?}"
    );
    assert!(((to.0[0] + 2.25).hypot(to.0[1] + 10.0) - 10.25).abs() < 1e-9);
    // Start within r of the end; an arc too small for the side (rs274:
    // "Tool radius not less than arc radius with comp"); G40 on an arc.
    let base = "G21 G90 G17\nG10 L1 P1 R2\nT1 M6\nG0 X0 Y-20\n";
    assert_eq!(
        alarm(&format!("{base}G41 G3 X1 Y-19.95 R10 F100\nM2\n")),
        (Code::E318, 5, 5)
    );
    assert_eq!(
        alarm(&format!("{base}G41 G3 X0 Y-17 R1.5 F100\nM2\n")),
        (Code::E318, 5, 5)
    );
    assert_eq!(
        alarm(&format!(
            "{base}G41 G1 Y-10 F100\nG40 G3 X10 Y0 I10 J0\nM2\n"
        )),
        (Code::E317, 6, 5)
    );
    // rs274 takes the first move after G41/G42 for the entry, also one
    // without motion in the plane, and refuses it when it is not longer
    // than r ("Length of cutter compensation entry move is not greater
    // than the tool radius", probed: `G1 Z-1`, `G1 X0 Y-20` from there,
    // `G1 X1 Y-20`); E318 at the move. Longer than r: it runs.
    for entry in [
        "G41\nG1 Z-1 F100",
        "G41\nG1 X0 Y-20 F100",
        "G41\nG1 X1 Y-20 F100",
    ] {
        let program = format!("{base}{entry}\nG1 X10 Y-10\nM2\n");
        assert_eq!(alarm(&program), (Code::E318, 6, 1), "{program}");
    }
    ended(&format!("{base}G41\nG1 X2.1 Y-20 F100\nG1 X10 Y-10\nM2\n"));
    // Fanuc: the start-up must be a line.
    let fanuc =
        "G21 G90 G17\nG10 L12 P1 R2\nT1 M6\nG0 X0 Y-20\nG41 D1 G3 X10 Y-10 I0 J10 F100\nM2\n";
    let (_, out) = run_str(&Dialect::fanuc(), fanuc);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}");
    };
    assert_eq!((d.code, d.line), (Code::E317, 5));
}

/// An empty D register (radius 0, the built-in mill's) offsets nothing:
/// the plunge after G41 and a full-circle entry arc run as programmed, as
/// rs274 runs them with a tool of diameter 0; neither is "an entry not
/// longer than the tool radius" (review 2026-12-06).
#[test]
fn compensation_with_an_empty_register_needs_no_entry_length() {
    for program in [
        "G21 G17 G90 G94\nS1000 M3\nG0 X0 Y-20 Z2\nG41 D1 G1 Z-1 F300\nG1 X10 Y-20\nG40 G1 X20 Y-20\nM2\n",
        "G21 G17 G90 G94\nS1000 M3\nG0 X0 Y-20 Z-1\nG41 D1 G3 X0 Y-20 I0 J10 F300\nG40 G1 X0 Y-30\nM2\n",
    ] {
        let (ev, out) = run_str(&Dialect::linuxcnc(), program);
        assert!(matches!(out, Outcome::Ended(_)), "{out:?}\n{program}");
        let ends: Vec<(f64, f64)> = ev
            .iter()
            .filter_map(|e| match e {
                Event::Feed { to, .. } | Event::Arc { to, .. } => Some((to.get(0), to.get(1))),
                _ => None,
            })
            .collect();
        assert!(
            ends.contains(&(0.0, -20.0)) || ends.contains(&(10.0, -20.0)),
            "{ends:?}"
        );
    }
}

/// An entry arc whose chord is all but square to its end radius has no
/// centre within reach: rs274 refuses it below a cosine of 1e-4 ("Tool
/// radius not less than arc radius with comp"); vcnc cut a loop about a
/// centre 180 km away.
#[test]
fn an_entry_arc_square_to_its_radius_is_refused() {
    let program = "G21 G17 G90 G94\nS1000 M3\nG0 X8.0001 Y-15.99987 Z-1\n\
        G41.1 D4 G3 X10 Y-10 I-8.0001 J5.99987 F300\nG1 X10 Y10\nG40 G1 X10 Y30\nM2\n";
    let (ev, out) = run_str(&Dialect::linuxcnc(), program);
    let Outcome::Alarm(d) = out else {
        panic!("no alarm: {out:?}");
    };
    assert_eq!((d.code, d.line), (Code::E318, 4));
    assert!(matches!(ev.last(), Some(Event::Alarm(_))));
}
