//! Macro alarms and limits, each with its code, line and column (counted by
//! hand in the program text), and the guarantees around them: structure
//! errors are found before a program's statements run, runaway loops stop
//! on the machine's limits, and nothing of the alarming statement happens.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::collections::HashMap;
use std::io;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, ProgramStore, VecSink};
use vcnc_syntax::{Code, MemSource, TextSource};

#[derive(Default)]
struct Store(HashMap<u32, String>);

impl ProgramStore for Store {
    fn open(&mut self, n: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let text = self.0.get(&n)?.clone();
        Some(Ok((
            Box::new(MemSource(text.into_bytes())),
            format!("O{n:04}.nc"),
        )))
    }
}

fn run_on(machine: &Machine, dialect: &str, program: &str, store: Store) -> (Outcome, Vec<Event>) {
    let dialect = Dialect::by_name(dialect).unwrap();
    let mut sink = VecSink::default();
    let mut store = store;
    let outcome = Interpreter::new(machine, &dialect, Options::default()).run(
        Box::new(MemSource(program.as_bytes().to_vec())),
        &mut store,
        &mut sink,
    );
    (outcome, sink.0)
}

/// The alarm of `program`: (code, line, column), checked to be the last
/// event.
fn alarm_on(
    machine: &Machine,
    dialect: &str,
    program: &str,
    store: Store,
) -> (Code, u64, u32, Vec<Event>) {
    let (outcome, events) = run_on(machine, dialect, program, store);
    let Outcome::Alarm(d) = outcome else {
        panic!("no alarm: {outcome:?}\n{events:?}");
    };
    assert!(matches!(events.last(), Some(Event::Alarm(a)) if *a == d));
    (d.code, d.line, d.column, events)
}

fn alarm(dialect: &str, program: &str) -> (Code, u64, u32) {
    let (c, l, col, _) = alarm_on(&Machine::default_mill(), dialect, program, Store::default());
    (c, l, col)
}

fn small_limits(jumps: u64, blocks: u64, depth: u32) -> Machine {
    let text = vcnc_core::machine::DEFAULT_MILL_TOML.replace(
        "[limits]",
        &format!("[limits]\nmax_jumps = {jumps}\nmax_executed_blocks = {blocks}\nmax_call_depth = {depth}\n[ignored]"),
    );
    // The default file's own limit keys follow: keep only ours.
    let mut out = String::new();
    let mut skip = false;
    for line in text.lines() {
        if line == "[ignored]" {
            skip = true;
            continue;
        }
        if skip && line.starts_with('[') {
            skip = false;
        }
        if !skip {
            out.push_str(line);
            out.push('\n');
        }
    }
    Machine::from_toml(&out).unwrap()
}

fn motions(events: &[Event]) -> usize {
    events.iter().filter(|e| e.motion_end().is_some()).count()
}

#[test]
fn division_by_zero_points_at_the_operator() {
    // `#1 = 5 / #2`: the / is byte 7, column 8.
    assert_eq!(
        alarm("fanuc", "#2 = 0\n#1 = 5 / #2\nM30\n"),
        (Code::E608, 2, 8)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\n#1 := 5 / 0;\nM30;\n"),
        (Code::E608, 2, 9)
    );
}

#[test]
fn vacant_where_a_number_is_required() {
    // GOTO #5 with #5 vacant: the expression at column 6.
    assert_eq!(alarm("fanuc", "G90\nGOTO #5\nM30\n"), (Code::E607, 2, 6));
    // #[#9] with #9 vacant.
    assert_eq!(alarm("fanuc", "G90\n#1 = #[#9]\nM30\n"), (Code::E607, 2, 6));
    assert_eq!(
        alarm(
            "syntec",
            "%@MACRO\nCASE #3 OF\n1:\n#1 := 1;\nEND_CASE;\nM30;\n"
        ),
        (Code::E607, 2, 6)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\nFOR #1 := 1 TO #8 DO\nEND_FOR;\nM30;\n"),
        (Code::E607, 2, 16)
    );
}

#[test]
fn variables_that_do_not_exist_or_are_read_only() {
    assert_eq!(alarm("fanuc", "G90\n#1 = #34\nM30\n"), (Code::E605, 2, 6));
    assert_eq!(alarm("fanuc", "G90\n#1 = #1010\nM30\n"), (Code::E605, 2, 6));
    assert_eq!(alarm("fanuc", "G90\n#1 = @3\nM30\n"), (Code::E601, 2, 6));
    assert_eq!(alarm("fanuc", "G90\n#0 = 1\nM30\n"), (Code::E606, 2, 1));
    assert_eq!(alarm("fanuc", "G90\n#5001 = 1\nM30\n"), (Code::E606, 2, 1));
    assert_eq!(alarm("fanuc", "G90\n#4001 = 1\nM30\n"), (Code::E606, 2, 1));
    assert_eq!(
        alarm("fanuc", "G90\n#1 = #2201.5\nM30\n"),
        (Code::E601, 2, 6)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\n#1 := @70000;\nM30;\n"),
        (Code::E605, 2, 7)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\n#4001 := 1;\nM30;\n"),
        (Code::E606, 2, 1)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\n#1000 := 1;\nM30;\n"),
        (Code::E606, 2, 1)
    );
}

#[test]
fn syntax_errors_point_at_the_token() {
    // `X#1+2`: the + at byte 7.
    assert_eq!(alarm("fanuc", "G90\nG01 X#1+2\nM30\n"), (Code::E601, 2, 8));
    // A missing ]: at the [ left open.
    assert_eq!(
        alarm("fanuc", "G90\n#1 = [1 + 2\nM30\n"),
        (Code::E601, 2, 6)
    );
    assert_eq!(
        alarm("fanuc", "G90\nIF [#1 EQ 1] GOTOX\nM30\n"),
        (Code::E601, 2, 14)
    );
    assert_eq!(alarm("fanuc", "G90\nG01 X#\nM30\n"), (Code::E601, 2, 6));
    // Syntec: the missing THEN of a statement that spans two lines is on
    // line 3.
    assert_eq!(
        alarm("syntec", "%@MACRO\nIF #1 > 0 +\n 1 ;\nM30;\n"),
        (Code::E601, 3, 4)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\nMOVL X10.;\nM30;\n"),
        (Code::E604, 2, 1)
    );
    assert_eq!(
        alarm("syntec", "%@MACRO\nG01 X1=5.;\nM30;\n"),
        (Code::E601, 2, 5)
    );
    // A (* comment the file never closes.
    assert_eq!(
        alarm("syntec", "%@MACRO\n#1 := 1;\n(* open\nM30;\n"),
        (Code::E105, 3, 1)
    );
}

#[test]
fn syntax_errors_stop_syntec_files_before_they_move() {
    // The structure scan parses the whole %@MACRO file first: no motion.
    let (code, line, col, events) = alarm_on(
        &Machine::default_mill(),
        "syntec",
        "%@MACRO\nG00 X10.;\n#1 := ;\nM30;\n",
        Store::default(),
    );
    assert_eq!((code, line, col), (Code::E601, 3, 7));
    assert_eq!(motions(&events), 0);
}

#[test]
fn loops_that_do_not_pair_are_found_before_they_run() {
    // END 2 without DO 2, found when the first macro statement runs: the
    // G00 before it moved, the one after did not.
    let (code, line, col, events) = alarm_on(
        &Machine::default_mill(),
        "fanuc",
        "G00 X1.\n#1 = 0\nG00 X2.\nWHILE [#1 LT 2] DO 1\nEND 2\nM30\n",
        Store::default(),
    );
    assert_eq!((code, line, col), (Code::E611, 5, 1));
    assert_eq!(motions(&events), 1);
    // Overlapping loops: END 1 while DO 2 is open.
    let p = "#1 = 0\nWHILE [#1 LT 2] DO 1\nWHILE [#1 LT 2] DO 2\nEND 1\nEND 2\nM30\n";
    assert_eq!(alarm("fanuc", p), (Code::E611, 4, 1));
    // DO 1 inside DO 1.
    let p = "#1 = 0\nDO 1\nDO 1\nEND 1\nEND 1\nM30\n";
    assert_eq!(alarm("fanuc", p), (Code::E611, 3, 1));
    // Four nested loops.
    let p = "#1 = 0\nDO 1\nDO 2\nDO 3\nDO 4\nM30\n";
    assert_eq!(alarm("fanuc", p), (Code::E611, 5, 4));
    let p = "#1 = 0\nDO 1\nDO 2\nDO 3\nWHILE [1] DO 2\nM30\n";
    assert_eq!(alarm("fanuc", p), (Code::E611, 5, 1));
    // A DO without END: at the DO, with N10 its label first.
    assert_eq!(
        alarm("fanuc", "#1 = 0\nN10 DO 1\nM30\n"),
        (Code::E611, 2, 1)
    );
}

#[test]
fn syntec_structures_that_do_not_pair() {
    let cases: [(&str, u64, u32); 7] = [
        ("%@MACRO\nG00 X1.;\nIF #1 = 0 THEN\n#2 := 1;\nM30;\n", 3, 1),
        ("%@MACRO\nEND_IF;\nM30;\n", 2, 1),
        ("%@MACRO\nIF 1 THEN\nELSE\nELSE\nEND_IF;\nM30;\n", 4, 1),
        ("%@MACRO\nEXIT;\nM30;\n", 2, 1),
        ("%@MACRO\nFOR #1 := 1 TO 2 DO\nEND_WHILE;\nM30;\n", 3, 1),
        ("%@MACRO\nCASE 1 OF\nEND_IF;\nM30;\n", 3, 1),
        ("%@MACRO\n2:\nM30;\n", 2, 1),
    ];
    for (p, line, col) in cases {
        let (code, l, c, events) =
            alarm_on(&Machine::default_mill(), "syntec", p, Store::default());
        assert_eq!((code, l, c), (Code::E611, line, col), "{p}");
        assert_eq!(motions(&events), 0, "{p}");
    }
    // Eleven nested IFs.
    let mut p = String::from("%@MACRO\n");
    for _ in 0..11 {
        p.push_str("IF 1 THEN\n");
    }
    assert_eq!(alarm("syntec", &p), (Code::E611, 12, 1));
}

#[test]
fn a_loop_that_never_ends_stops_on_the_jump_limit() {
    let machine = small_limits(1000, 5_000_000, 10);
    let (code, line, col, _) = alarm_on(
        &machine,
        "fanuc",
        "#1 = 0\nWHILE [#1 GE 0] DO 1\n#1 = #1 + 1\nEND 1\nM30\n",
        Store::default(),
    );
    assert_eq!((code, line, col), (Code::E405, 4, 1));
    let (code, line, _, _) = alarm_on(
        &machine,
        "syntec",
        "%@MACRO\nWHILE 1 DO\nEND_WHILE;\nM30;\n",
        Store::default(),
    );
    assert_eq!((code, line), (Code::E405, 3));
    let (code, _, _, _) = alarm_on(&machine, "fanuc", "N10 #1 = 1\nGOTO 10\n", Store::default());
    assert_eq!(code, Code::E405);
}

#[test]
fn a_loop_that_never_ends_stops_on_the_block_limit() {
    // 1000 blocks beyond the text read: the WHILE's body runs about 500 times.
    let machine = small_limits(1_000_000, 1000, 10);
    let (code, line, _, _) = alarm_on(
        &machine,
        "fanuc",
        "#1 = 0\nWHILE [#1 GE 0] DO 1\n#1 = #1 + 1\nEND 1\nM30\n",
        Store::default(),
    );
    assert_eq!(code, Code::E404);
    assert!((2..=4).contains(&line));
}

#[test]
fn recursion_stops_on_the_call_depth() {
    let mut store = Store::default();
    store.0.insert(9010, "O9010\nG65 P9010\nM99\n".into());
    let (code, line, col, _) = alarm_on(
        &small_limits(1_000_000, 5_000_000, 4),
        "fanuc",
        "G65 P9010\nM30\n",
        store,
    );
    // The call that would go one level too deep: line 2 of O9010, its P word.
    assert_eq!((code, line, col), (Code::E403, 2, 5));
}

#[test]
fn a_goto_to_a_missing_label() {
    assert_eq!(alarm("fanuc", "G90\nGOTO 77\nM30\n"), (Code::E402, 2, 6));
    assert_eq!(
        alarm("syntec", "%@MACRO\nGOTO 77;\nM30;\n"),
        (Code::E402, 2, 6)
    );
}

#[test]
fn a_goto_into_a_loop_alarms_in_the_program_that_holds_it() {
    // O0077 jumps within its own loop (allowed: N5 and the GOTO are both
    // inside DO 1) and returns; the main program's GOTO 10 then enters its
    // own loop from outside: E614 at line 2, column 1 of the main program.
    let o77 =
        "O0077\n#1 = 0\nWHILE [#1 LT 2] DO 1\n#1 = #1 + 1\nIF [#1 EQ 1] GOTO 5\nN5 END 1\nM99\n";
    let main = "G65 P77\nGOTO 10\nWHILE [#1 LT 1] DO 1\nN10 #1 = 1\nEND 1\nM30\n";
    let mut store = Store::default();
    store.0.insert(77, o77.to_string());
    let (code, line, col, _) = alarm_on(&Machine::default_mill(), "fanuc", main, store);
    assert_eq!((code, line, col), (Code::E614, 2, 1));
    // In the called program: line 3 of O0077 jumps into the loop of its
    // lines 4-6.
    let o77 = "O0077\n#1 = 0\nGOTO 5\nWHILE [#1 LT 2] DO 1\nN5 #1 = #1 + 1\nEND 1\nM99\n";
    let mut store = Store::default();
    store.0.insert(77, o77.to_string());
    let (code, line, col, events) =
        alarm_on(&Machine::default_mill(), "fanuc", "G65 P77\nM30\n", store);
    assert_eq!((code, line, col), (Code::E614, 3, 1));
    let Some(Event::Alarm(d)) = events.last() else {
        panic!("no alarm event");
    };
    assert_eq!(d.file.as_deref(), Some("O0077.nc"));
}

#[test]
fn calls_that_fail() {
    assert_eq!(alarm("fanuc", "G90\nG65 X1.\nM30\n"), (Code::E312, 2, 1));
    assert_eq!(alarm("fanuc", "G90\nG65 P77\nM30\n"), (Code::E401, 2, 5));
    assert_eq!(
        alarm("fanuc", "G90\nG65 P77 X1. X2.\nM30\n"),
        (Code::E204, 2, 13)
    );
    assert_eq!(
        alarm("fanuc", "G90\nG65 P77 G01\nM30\n"),
        (Code::E209, 2, 9)
    );
}

#[test]
fn the_stack_is_bounded() {
    let p = "%@MACRO\nWHILE 1 DO\nPUSH(1);\nEND_WHILE;\nM30;\n";
    assert_eq!(alarm("syntec", p), (Code::E613, 3, 1));
}

#[test]
fn an_alarming_statement_changes_nothing() {
    // The assignment that divides by zero leaves #1 as it was, and the
    // block after it never runs.
    let machine = Machine::default_mill();
    let dialect = Dialect::fanuc();
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    let mut sink = VecSink::default();
    let out = interp.run_str("#1 = 7\n#1 = 1 / 0\n#2 = 1\nM30\n", &mut sink);
    assert!(matches!(out, Outcome::Alarm(ref d) if d.code == Code::E608));
    assert_eq!(interp.variable("#1"), Some(7.0));
    assert_eq!(interp.variable("#2"), None);
}

#[test]
fn statements_that_never_end_alarm() {
    // 70 lines of `+` without `;`: more than 64 lines.
    let mut p = String::from("%@MACRO\n#1 := 1\n");
    for _ in 0..70 {
        p.push_str("+ 1\n");
    }
    let (code, line, _) = alarm("syntec", &p);
    assert_eq!((code, line), (Code::E603, 2));
}
