//! Bad input to the macro front ends: token soup of Syntec `%@MACRO` files
//! and of Custom Macro B blocks (`#`, `[`, `]`, `:=`, keywords half
//! written, comments left open). Every run must end or alarm — no panic, no
//! hang, a bounded number of events — and an alarm must name a line and a
//! column inside the program. The machine's runaway limits are small so
//! that loops the soup builds stop quickly.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use proptest::sample::select;
use std::sync::LazyLock;
use std::sync::mpsc;
use std::time::Duration;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, NoPrograms, Options, Outcome, VecSink};
use vcnc_syntax::MemSource;

const TIME_LIMIT: Duration = Duration::from_secs(20);
const MAX_BLOCKS: u64 = 2000;

static MACHINE: LazyLock<Machine> = LazyLock::new(|| {
    let text = vcnc_interp::machine::DEFAULT_MILL_TOML
        .replace("max_jumps = 1000000", "max_jumps = 50")
        .replace(
            "max_executed_blocks = 5000000",
            &format!("max_executed_blocks = {MAX_BLOCKS}"),
        )
        .replace("max_call_depth = 10", "max_call_depth = 4");
    Machine::from_toml(&text).unwrap()
});
static SYNTEC: LazyLock<Dialect> = LazyLock::new(Dialect::syntec);
static FANUC: LazyLock<Dialect> = LazyLock::new(Dialect::fanuc);

fn run(dialect: &'static Dialect, program: String) -> (Outcome, Vec<Event>) {
    let (tx, rx) = mpsc::channel();
    let text = program.clone();
    let handle = std::thread::spawn(move || {
        let mut sink = VecSink::default();
        let outcome = Interpreter::new(&MACHINE, dialect, Options::default()).run(
            Box::new(MemSource(text.into_bytes())),
            &mut NoPrograms,
            &mut sink,
        );
        let _ = tx.send((outcome, sink.0));
    });
    match rx.recv_timeout(TIME_LIMIT) {
        Ok(r) => {
            handle.join().unwrap();
            r
        }
        Err(mpsc::RecvTimeoutError::Timeout) => panic!("hang on {program:?}"),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let _ = handle.join();
            panic!("panic on {program:?}")
        }
    }
}

fn well_formed(program: &str, outcome: &Outcome, events: &[Event]) -> Result<(), String> {
    let n = events.len();
    // A statement makes at most a handful of events; the block budget bounds them.
    if n == 0 || n as u64 > 16 * (MAX_BLOCKS + 64) {
        return Err(format!("{n} events"));
    }
    match (outcome, &events[n - 1]) {
        (Outcome::Ended(a), Event::End { code, .. }) if a == code => {}
        (Outcome::Alarm(a), Event::Alarm(d)) if a == d => {
            let lines: Vec<&str> = program.split('\n').collect();
            let line = usize::try_from(d.line).unwrap_or(0);
            let width = lines.get(line.wrapping_sub(1)).map(|l| l.chars().count());
            match width {
                Some(w) if d.column >= 1 && d.column as usize <= w + 1 => {}
                _ => {
                    return Err(format!(
                        "alarm {} at line {} column {}",
                        d.code.as_str(),
                        d.line,
                        d.column
                    ));
                }
            }
        }
        (o, e) => return Err(format!("outcome {o:?}, last event {e:?}")),
    }
    Ok(())
}

const SYNTEC_TOKENS: &[&str] = &[
    "#1",
    "#2",
    "#[#1]",
    "@1",
    "@[2]",
    ":=",
    "=",
    "<>",
    "<",
    ">=",
    "+",
    "-",
    "*",
    "/",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "(",
    ")",
    "[",
    "]",
    ";",
    ";",
    ";",
    "\n",
    "\n",
    "1",
    "2.5",
    "0",
    "10",
    "0x1F",
    "IF",
    "THEN",
    "ELSEIF",
    "ELSE",
    "END_IF",
    "CASE",
    "OF",
    "1:",
    "2, 3:",
    "END_CASE",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "WHILE",
    "END_WHILE",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "EXIT",
    "GOTO",
    "N10",
    "N10;",
    "G01",
    "G00",
    "X",
    "Y10.",
    "Z(#1)",
    "F100.",
    "M30",
    "M99",
    "M98 P1",
    "G65 P1",
    "G66 P1",
    "G67",
    "G200",
    "(*",
    "*)",
    "//",
    "\"text\"",
    "MSG(",
    "ALARM(",
    "PUSH(",
    "POP()",
    "STKTOP[",
    "SIN(",
    "SQRT(",
    "STD(",
    "GETARG(",
    "MOVL",
    "%",
    ",",
];

const MACRO_B_TOKENS: &[&str] = &[
    "#1",
    "#2",
    "#[",
    "#0",
    "#3000",
    "#5001",
    "=",
    "[",
    "]",
    "+",
    "-",
    "*",
    "/",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "EQ",
    "NE",
    "LT",
    "GE",
    "1",
    "2.5",
    "0",
    "10",
    "\n",
    "\n",
    "\n",
    ";",
    "IF",
    "GOTO",
    "THEN",
    "WHILE",
    "DO",
    "DO1",
    "END",
    "END1",
    "DO4",
    "N10",
    "N5",
    "G01",
    "G00",
    "X",
    "Y",
    "X#1",
    "Y-#2",
    "Z[#1]",
    "F100.",
    "M30",
    "M99",
    "G65 P1",
    "G66 P9",
    "G67",
    "(",
    ")",
    "(MSG)",
    "SIN[",
    "ATAN[1]/[",
    "POW[",
    "#3006=1",
    "/",
];

fn soup(tokens: &'static [&'static str], prefix: &'static str) -> impl Strategy<Value = String> {
    proptest::collection::vec((select(tokens), select(&[" ", "", ""][..])), 0..80).prop_map(
        move |ts| {
            let mut s = String::from(prefix);
            for (t, sep) in ts {
                s.push_str(t);
                s.push_str(sep);
            }
            s
        },
    )
}

/// Whole statements, mostly valid, so that runs get past the syntax check
/// into loops, calls and jumps.
const SYNTEC_STATEMENTS: &[&str] = &[
    "#1 := #1 + 1;",
    "#2 := #1 * 2.5;",
    "@1 := @1 + #1;",
    "#[#1 + 2] := 3;",
    "IF #1 > 2 THEN",
    "ELSEIF #1 = 1 THEN",
    "ELSE",
    "END_IF;",
    "CASE #1 OF",
    "1:",
    "2, 3:",
    "END_CASE;",
    "FOR #3 := 1 TO 3 DO",
    "END_FOR;",
    "WHILE #1 < 5 DO",
    "END_WHILE;",
    "REPEAT",
    "UNTIL #1 > 3 END_REPEAT;",
    "EXIT;",
    "GOTO 10;",
    "GOTO #1;",
    "N10;",
    "N1 #1 := 0;",
    "G91 G01 X1. F100.;",
    "G00 X(#1) Y#2;",
    "G01 X#1;",
    "MSG(\"hi\");",
    "PUSH(#1);",
    "#4 := POP();",
    "M99;",
    "M30;",
    "G65 P1 X1.;",
    "#5 := 1 / #9;",
    "#6 := SQRT(#1 - 3);",
    "(* note *)",
    "// note",
];

const MACRO_B_STATEMENTS: &[&str] = &[
    "#1 = #1 + 1",
    "#2 = #1 * 2.5",
    "#[#1 + 2] = 3",
    "WHILE [#1 LT 4] DO 1",
    "END 1",
    "WHILE [#2 LT 4] DO 2",
    "END 2",
    "DO 3",
    "END 3",
    "IF [#1 GT 2] GOTO 10",
    "IF [#1 EQ 1] THEN #3 = 5",
    "GOTO 10",
    "GOTO #1",
    "N10 #4 = 0",
    "N1",
    "G91 G01 X1. F100.",
    "G00 X#1 Y-#2",
    "G01 X[#1 * 2]",
    "#3006 = 1 (STOP)",
    "M99",
    "M30",
    "G65 P1 X1.",
    "G66 P1",
    "G67",
    "#5 = 1 / #9",
    "#6 = SQRT[#1 - 3]",
];

fn statements(
    list: &'static [&'static str],
    prefix: &'static str,
) -> impl Strategy<Value = String> {
    proptest::collection::vec(select(list), 0..40).prop_map(move |ts| {
        let mut s = String::from(prefix);
        for t in ts {
            s.push_str(t);
            s.push('\n');
        }
        s
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 384, max_shrink_iters: 1024, ..ProptestConfig::default() })]

    #[test]
    fn plausible_syntec_programs_end_or_alarm(p in statements(SYNTEC_STATEMENTS, "%@MACRO\n")) {
        let (outcome, events) = run(&SYNTEC, p.clone());
        if let Err(why) = well_formed(&p, &outcome, &events) {
            return Err(TestCaseError::fail(format!("{why}\nprogram: {p:?}")));
        }
    }

    #[test]
    fn plausible_macro_b_programs_end_or_alarm(p in statements(MACRO_B_STATEMENTS, ""), fanuc: bool) {
        let dialect = if fanuc { &*FANUC } else { &*SYNTEC };
        let (outcome, events) = run(dialect, p.clone());
        if let Err(why) = well_formed(&p, &outcome, &events) {
            return Err(TestCaseError::fail(format!("{why}\nprogram: {p:?}")));
        }
    }

    #[test]
    fn syntec_macro_soup_ends_or_alarms(p in soup(SYNTEC_TOKENS, "%@MACRO\n")) {
        let (outcome, events) = run(&SYNTEC, p.clone());
        if let Err(why) = well_formed(&p, &outcome, &events) {
            return Err(TestCaseError::fail(format!("{why}\nprogram: {p:?}")));
        }
    }

    #[test]
    fn macro_b_soup_ends_or_alarms(p in soup(MACRO_B_TOKENS, ""), fanuc: bool) {
        let dialect = if fanuc { &*FANUC } else { &*SYNTEC };
        let (outcome, events) = run(dialect, p.clone());
        if let Err(why) = well_formed(&p, &outcome, &events) {
            return Err(TestCaseError::fail(format!("{why}\nprogram: {p:?}")));
        }
    }
}

#[test]
fn long_loops_of_statements_stay_bounded() {
    // A loop that would run for ever: the block budget ends it, with a few
    // events at most, whatever the language.
    let (outcome, events) = run(
        &FANUC,
        "#1 = 0\nWHILE [1 EQ 1] DO 1\n#1 = #1 + 1\nEND 1\n".into(),
    );
    assert!(matches!(outcome, Outcome::Alarm(_)));
    assert!(events.len() < 4);
    let (outcome, _) = run(
        &SYNTEC,
        "%@MACRO\nREPEAT\n@1 := @1 + 1;\nUNTIL 0 END_REPEAT;\n".into(),
    );
    assert!(matches!(outcome, Outcome::Alarm(_)));
}
