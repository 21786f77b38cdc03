//! One test per alarm code of `docs/alarms.md` that the interpreter can raise
//! today, each running a small program through [`Interpreter`] and checking
//! the contract of an alarm:
//!
//! - the code, the 1-based line and the 1-based column of the word the alarm
//!   concerns (the "column" rule of `docs/alarms.md`; the offending word is
//!   never in column 1 unless the rule says so, so the column means something);
//! - the alarm is the last event, the only alarm, and `run` returns it;
//! - no motion event comes from the alarming block;
//! - the interpreter's modal state, position and offsets are what they were
//!   before the alarming block (compared with a run of the program's lines
//!   before the alarming line).
//!
//! Expected columns are counted by hand from the program text in the test.
//! Tests named `regression_…` guard bugs these tests found (see the comment
//! on each): behaviour that once disagreed with the documents.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::collections::HashMap;
use std::io;
use vcnc_interp::{
    Dialect, EndCode, Event, Interpreter, Loc, Machine, NoPrograms, Options, Outcome, ProgramStore,
    State, VecSink,
};
use vcnc_syntax::{Code, Diagnostic, MemSource, TextSource};

// ---------------------------------------------------------------------------
// Harness
// ---------------------------------------------------------------------------

/// Everything a run leaves behind.
struct Run {
    events: Vec<Event>,
    outcome: Outcome,
    state: State,
}

fn run_with(
    machine: &Machine,
    dialect: &str,
    opts: Options,
    program: &[u8],
    store: &mut dyn ProgramStore,
) -> Run {
    let dialect = Dialect::by_name(dialect).expect("dialect");
    let mut sink = VecSink::default();
    let mut interp = Interpreter::new(machine, &dialect, opts);
    let outcome = interp.run(Box::new(MemSource(program.to_vec())), store, &mut sink);
    Run {
        events: sink.0,
        outcome,
        state: *interp.state(),
    }
}

fn run_on(machine: &Machine, program: &str) -> Run {
    run_with(
        machine,
        "syntec",
        Options::default(),
        program.as_bytes(),
        &mut NoPrograms,
    )
}

fn run(program: &str) -> Run {
    run_on(&limited_mill(), program)
}

/// The 3-axis mill with travel limits these tests were written for (the
/// built-in machines have none).
const LIMITED_MILL: &str =
    include_str!("../../../../tests/fixtures/machines/mill_travel_limits.toml");

fn limited_mill() -> Machine {
    Machine::from_toml(LIMITED_MILL).expect("valid test machine")
}

/// The limited mill with some lines of its TOML text replaced.
fn machine_with(edits: &[(&str, &str)]) -> Machine {
    let mut text = LIMITED_MILL.to_string();
    for (from, to) in edits {
        assert!(text.contains(from), "the default machine has no {from:?}");
        text = text.replace(from, to);
    }
    Machine::from_toml(&text).expect("edited machine is valid")
}

fn is_motion(e: &Event) -> bool {
    matches!(
        e,
        Event::Rapid { .. }
            | Event::Feed { .. }
            | Event::Arc { .. }
            | Event::Thread { .. }
            | Event::Skip { .. }
    )
}

fn loc_of(e: &Event) -> Option<&Loc> {
    e.loc()
}

fn motions(events: &[Event]) -> Vec<&Event> {
    events.iter().filter(|e| is_motion(e)).collect()
}

/// Checks the alarm contract except the motion rule and returns the alarm.
fn assert_last_alarm(r: &Run, code: Code, line: u64, column: u32) -> Diagnostic {
    let Some(Event::Alarm(d)) = r.events.last() else {
        panic!("the last event is not an alarm: {:#?}", r.events.last());
    };
    assert_eq!(
        (d.code, d.line, d.column),
        (code, line, column),
        "wrong alarm (code, line, column); message: {}",
        d.message
    );
    assert_eq!(
        r.outcome,
        Outcome::Alarm(d.clone()),
        "run() returns the alarm it emitted"
    );
    let alarms = r
        .events
        .iter()
        .filter(|e| matches!(e, Event::Alarm(_)))
        .count();
    assert_eq!(alarms, 1, "exactly one alarm event");
    assert!(
        !r.events.iter().any(|e| matches!(e, Event::End { .. })),
        "no end event after or before an alarm"
    );
    assert!(
        !d.message.is_empty() && !d.help.is_empty(),
        "an alarm says what is wrong and how to fix it"
    );
    d.clone()
}

/// The alarm contract: code, line, column, last event, and no motion event
/// from the alarming line (the tests put one block on that line, or the
/// alarming block first).
fn assert_alarm(r: &Run, code: Code, line: u64, column: u32) -> Diagnostic {
    let d = assert_last_alarm(r, code, line, column);
    let from_alarm_line = r
        .events
        .iter()
        .filter(|e| is_motion(e))
        .filter(|e| {
            loc_of(e).is_some_and(|l| l.line == d.line && l.file.as_deref() == d.file.as_deref())
        })
        .collect::<Vec<_>>();
    assert!(
        from_alarm_line.is_empty(),
        "motion from the alarming block {}: {from_alarm_line:#?}",
        d.code.as_str()
    );
    d
}

/// Modal state, position and offsets of `after` equal those of `before`.
fn assert_same_state(after: &State, before: &State) {
    assert_eq!(after.modal, before.modal, "modal state after the alarm");
    assert_eq!(after.pos, before.pos, "position after the alarm");
    assert_eq!(after, before, "the whole state after the alarm");
}

/// Runs `program` on `machine` and checks the alarm and that the machine is
/// left exactly as the lines before the alarming line left it (and moved the
/// same way).
fn check_on(machine: &Machine, program: &str, code: Code, line: u64, column: u32) -> Run {
    let r = run_on(machine, program);
    assert_alarm(&r, code, line, column);
    let prefix: String = program
        .lines()
        .take(usize::try_from(line - 1).unwrap())
        .map(|l| format!("{l}\n"))
        .collect();
    let before = run_on(machine, &prefix);
    assert!(
        matches!(before.outcome, Outcome::Ended(_)),
        "the lines before the alarm run cleanly: {:?}",
        before.outcome
    );
    assert_same_state(&r.state, &before.state);
    assert_eq!(
        motions(&r.events),
        motions(&before.events),
        "the alarming block moved"
    );
    r
}

/// [`check_on`] on the default mill.
fn check(program: &str, code: Code, line: u64, column: u32) -> Run {
    check_on(&limited_mill(), program, code, line, column)
}

/// Called programs held in memory: number → (name, text).
#[derive(Default)]
struct MapStore(HashMap<u32, (String, String)>);

impl MapStore {
    fn with(mut self, number: u32, name: &str, text: &str) -> MapStore {
        self.0.insert(number, (name.into(), text.into()));
        self
    }
}

impl ProgramStore for MapStore {
    fn open(&mut self, number: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let (name, text) = self.0.get(&number)?;
        Some(Ok((
            Box::new(MemSource(text.clone().into_bytes())),
            name.clone(),
        )))
    }
}

/// A store whose every program exists but cannot be opened.
struct UnopenableStore;

impl ProgramStore for UnopenableStore {
    fn open(&mut self, _: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        Some(Err(io::Error::new(
            io::ErrorKind::PermissionDenied,
            "permission denied",
        )))
    }
}

/// A program text whose every read fails.
struct BrokenSource;

impl TextSource for BrokenSource {
    fn read_at(&mut self, _: u64, _: &mut [u8]) -> io::Result<usize> {
        Err(io::Error::other("device error"))
    }
}

/// A store whose programs open but cannot be read.
struct UnreadableStore;

impl ProgramStore for UnreadableStore {
    fn open(&mut self, number: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        Some(Ok((Box::new(BrokenSource), format!("O{number:04}.nc"))))
    }
}

// ---------------------------------------------------------------------------
// E1xx — reading the program
// ---------------------------------------------------------------------------

#[test]
fn e101_illegal_character() {
    check("G90 G00 X1.\nG00 X2. @\nM30\n", Code::E101, 2, 9);
    // Columns count characters: the full-width `；` is one column.
    check("G90 G00 X1.\nG00；X2. #\n", Code::E101, 2, 9);
    // A stray non-UTF-8 byte still gets its own column.
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X1.\n  Y2. \xff\n",
        &mut NoPrograms,
    );
    assert_alarm(&r, Code::E101, 2, 7);
    // NUL is not a blank.
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X1.\nG00 \0\n",
        &mut NoPrograms,
    );
    assert_alarm(&r, Code::E101, 2, 5);
}

#[test]
fn e102_malformed_number() {
    check("G00 X1.\nN2 G00 X1.2.3\n", Code::E102, 2, 8);
    check("G00 X1.\nN2 X-\n", Code::E102, 2, 4);
    check("G00 X1.\nN2 X+-1\n", Code::E102, 2, 4);
}

#[test]
fn e103_number_out_of_range() {
    // Ten integer digits.
    check("G00 X1.\nN2 G00 X1234567890\n", Code::E103, 2, 8);
    // Fraction digits beyond the 15th significant one are rounded away,
    // not an alarm: X1.2345678901234567 runs.
    let r = run("G00 X1.\nN2 X1.2345678901234567\nM30\n");
    assert!(matches!(r.outcome, Outcome::Ended(_)), "{:?}", r.outcome);
    // Forty digits.
    check(
        "G00 X1.\nN2 Y1234567890123456789012345678901234567890\n",
        Code::E103,
        2,
        4,
    );
}

#[test]
fn e104_address_without_value() {
    check("G00 X1.\nN2 G X10\n", Code::E104, 2, 4);
    check("G00 X1.\nN2 G00 X1. Y\n", Code::E104, 2, 12);
}

#[test]
fn e105_unterminated_comment() {
    check("G00 X1.\nN2 G00 X1. (open\n", Code::E105, 2, 12);
}

#[test]
fn e106_block_longer_than_4096_bytes() {
    // The second block of line 2 starts after `M09;`, at column 5.
    let program = format!("G00 X1.\nM09;N2{}X1.\nM30\n", " ".repeat(4100));
    check(&program, Code::E106, 2, 5);
}

#[test]
fn e106_line_longer_than_the_64k_reader_buffer() {
    // A physical line the reader cannot hold is reported at its start.
    let program = format!("G00 X1.\n{}\nG00 Y1.\nM30\n", "X1.".repeat(70_000 / 3));
    check(&program, Code::E106, 2, 1);
    // Also when the long line is a comment, and in the fanuc dialect.
    let program = format!("G00 X1.\n({})\nG00 Y1.\nM30\n", "c".repeat(80_000));
    let r = run_with(
        &limited_mill(),
        "fanuc",
        Options::default(),
        program.as_bytes(),
        &mut NoPrograms,
    );
    assert_alarm(&r, Code::E106, 2, 1);
}

#[test]
fn e107_more_than_48_words() {
    // "G00" then 48 × " X1": the 49th word starts at column 4 + 3·47 + 1.
    let program = format!("G00 X1.\nG00{}\n", " X1".repeat(48));
    check(&program, Code::E107, 2, 146);
}

#[test]
fn e108_decimal_point_not_allowed() {
    check("G00 X1.\nN2 G04 P2.5\n", Code::E108, 2, 8);
    check("G00 X1.\nN2 M3.5\n", Code::E108, 2, 4);
    check("G00 X1.\nN2 T1.5\n", Code::E108, 2, 4);
    check("G00 X1.\nN2 M98 P1.\n", Code::E108, 2, 8);
}

#[test]
fn e109_value_out_of_range() {
    check("G00 X1.\nN2 G30 P7 X0\n", Code::E109, 2, 8);
    check("G00 X1.\nN2 T-1\n", Code::E109, 2, 4);
    check("G00 X1.\nN2 S-5\n", Code::E109, 2, 4);
    check("G00 X1.\nN2 M98 P1 L0\n", Code::E109, 2, 11);
    check("G00 X1.\nN2 G01 X2. F-100\n", Code::E109, 2, 12);
    check("G00 X1.\nN2 G04 X-1.\n", Code::E109, 2, 8);
}

// ---------------------------------------------------------------------------
// E2xx — what a block says
// ---------------------------------------------------------------------------

#[test]
fn e201_unknown_g_code() {
    check("G00 X1.\nN2 G12 X1.\n", Code::E201, 2, 4);
    check("G00 X1.\nN2 G59.15\n", Code::E201, 2, 4);
    // G20 is Fanuc's inch code; the hint names the dialect that has it.
    let d = assert_alarm(&run("G00 X1.\nN2 G20\n"), Code::E201, 2, 4);
    assert!(d.help.contains("fanuc"), "help: {}", d.help);
    let r = run_with(
        &limited_mill(),
        "fanuc",
        Options::default(),
        b"G00 X1.\nN2 G70\n",
        &mut NoPrograms,
    );
    let d = assert_alarm(&r, Code::E201, 2, 4);
    assert!(d.help.contains("syntec"), "help: {}", d.help);
}

#[test]
fn e202_unknown_m_code() {
    // Only on a machine that says so; otherwise W105 (tests/warnings.rs).
    let mut strict = limited_mill();
    strict.params.strict_m_codes = true;
    check_on(&strict, "G00 X1.\nN2 M03 M77\n", Code::E202, 2, 8);
}

#[test]
fn e203_word_not_used() {
    check("G00 X1.\nN2 G00 X1. I5.\n", Code::E203, 2, 12);
    check("G00 X1.\nN2 Q3\n", Code::E203, 2, 4);
    // K is no centre word in G17.
    check("G00 X1.\nN2 G17 G02 X2. K1. F100\n", Code::E203, 2, 16);
}

#[test]
fn e204_same_address_twice() {
    check("G00 X1.\nN2 G00 X1. X2.\n", Code::E204, 2, 12);
}

#[test]
fn e205_same_modal_group_with_the_alarm_parameter() {
    let strict = machine_with(&[(
        "same_group_in_block = \"last_wins\"",
        "same_group_in_block = \"alarm\"",
    )]);
    check_on(&strict, "G00 X1.\nN2 G00 G01 X1.\n", Code::E205, 2, 8);
    // Without the parameter the last one wins (Fanuc 0i): G00, a rapid.
    let r = run("N1 G01 G00 X1.\n");
    assert!(
        matches!(r.events.first(), Some(Event::Rapid { .. })),
        "{:?}",
        r.events
    );
    assert_eq!(r.outcome, Outcome::Ended(EndCode::Eof));
}

#[test]
fn e206_same_m_group_twice() {
    check("G00 X1.\nN2 M03 M05\n", Code::E206, 2, 8);
}

#[test]
fn e207_two_g_codes_want_the_axis_words() {
    check("G00 X1.\nN2 G28 G92 X0\n", Code::E207, 2, 8);
}

#[test]
fn e208_g92_with_axes_and_s() {
    check("G00 X1.\nN2 G92 X0 S3000\n", Code::E208, 2, 11);
}

// ---------------------------------------------------------------------------
// E3xx — motion and geometry
// ---------------------------------------------------------------------------

#[test]
fn e301_zero_feed() {
    // No F yet: the motion G word.
    check("G00 X1.\nN2 G01 X10.\n", Code::E301, 2, 4);
    // F0 under modal G01 with no G word: the block's first word.
    check("G01 X1. F100\n  N2 X2. F0\n", Code::E301, 2, 3);
    // Arcs too.
    check("G00 X1.\nN2 G02 X2. R1.\n", Code::E301, 2, 4);
}

#[test]
fn e302_arc_radius_too_small() {
    check("G00 X1.\nN2 G02 X100. R10. F100\n", Code::E302, 2, 14);
}

#[test]
fn e303_arc_end_off_the_circle() {
    check("G00 X1.\nN2 G03 X10. Y0 I3. J0 F100\n", Code::E303, 2, 4);
    // The README's example (manual 1.2.3 with a wrong start point).
    check(
        "G90 G00 X0 Y0\nT1 M06\nG17 G90 G03 X1500 Y4000 I-3000 J-1000 F200; //absolute command\n",
        Code::E303,
        3,
        9,
    );
}

#[test]
fn e304_arc_of_zero_radius() {
    check("G00 X1.\nN2 G02 X1. Y0 I0 J0 F100\n", Code::E304, 2, 4);
}

#[test]
fn e305_arc_without_centre_or_radius() {
    check("G00 X1.\nN2 G02 X10. F100\n", Code::E305, 2, 4);
}

#[test]
fn e306_r_arc_to_its_own_start() {
    check("G00 X1.\nN2 G02 X1. Y0 R5. F100\n", Code::E306, 2, 15);
}

#[test]
fn e307_g29_without_g28() {
    check("G00 X1.\nN2 G29 X0\n", Code::E307, 2, 4);
}

#[test]
fn e308_g53_in_incremental_mode() {
    let r = check("G00 X1.\nN2 G91 G53 X0\n", Code::E308, 2, 8);
    assert!(
        !r.state.modal.incremental,
        "the G91 of the alarming block is rolled back"
    );
}

#[test]
fn e309_m06_without_tool() {
    check("G00 X1.\nN2 M06\n", Code::E309, 2, 4);
}

#[test]
fn e310_g96_without_tool_diameter() {
    // Tool 9 is not in the tool table, so it has no diameter.
    let r = check("T9 M06\nS100 M03\nN3 G96 S120\n", Code::E310, 3, 4);
    assert!(
        !r.state.modal.css,
        "G96 of the alarming block is rolled back"
    );
}

#[test]
fn e311_g33_without_lead() {
    check("G00 X1.\nN2 G33 Z-10.\n", Code::E311, 2, 4);
}

#[test]
fn e312_code_without_the_axis_words_it_needs() {
    for code in ["G28", "G29", "G30", "G31 F100", "G92", "G52", "G10 L2 P1"] {
        check(&format!("G00 X1.\nN2 {code}\n"), Code::E312, 2, 4);
    }
    // G53 is not among them: without axis words it moves nothing (Fanuc
    // and Haas give `G53 G49 M05` no alarm).
    let r = run("G00 X1.\nN2 G53\nM30\n");
    assert!(matches!(r.outcome, Outcome::Ended(_)), "{:?}", r.outcome);
}

/// E329: a G06.2 curve still being defined takes no other command (Syntec
/// 1.2.8; Fanuc: nothing but the definition's blocks until it is complete).
/// A G01 that leaves it, or G05 P0, alarmed nowhere before: the curve was
/// dropped unseen and the next move started from its last control point
/// (review of 2026-12-06).
#[test]
fn regression_e329_a_curve_left_before_its_definition_is_complete() {
    let head = "G17 G90\nG00 X0. Y0. Z0.\nG05 P10000\n\
                G06.2 P3 K0. X0. Y0. Z0. R1. F1000.\nK0. X10. Y10. R1.\n\
                K0. X20. Y0. R1.\nK1. X40. Y7. R1.\nK1.\n";
    check(&format!("{head}N9 G01 X5.\n"), Code::E329, 9, 4);
    check(&format!("{head}N9 G00 X5.\n"), Code::E329, 9, 4);
    check(&format!("{head}N9 G05 P0\n"), Code::E329, 9, 4);
    // Completed, the same G01 is an ordinary move.
    let r = run(&format!("{head}K1.\nK1.\nN11 G01 X5.\nG05 P0\nM30\n"));
    assert!(matches!(r.outcome, Outcome::Ended(_)), "{:?}", r.outcome);
}

// ---------------------------------------------------------------------------
// E343–E348 — the Fanuc lathe's cycles, chamfers and surface speed
// ---------------------------------------------------------------------------

/// Runs a fanuc-lathe program on `machine` (default: its built-in lathe)
/// and checks the alarm, and that the machine is left as the lines before
/// `block_line` (the block that alarms, which may be a cycle whose profile
/// block the alarm points at) left it.
fn check_lathe_on(
    machine: &Machine,
    program: &str,
    code: Code,
    (line, column): (u64, u32),
    block_line: u64,
) -> Run {
    let run = |text: &str| {
        run_with(
            machine,
            "fanuc-lathe",
            Options::default(),
            text.as_bytes(),
            &mut NoPrograms,
        )
    };
    let r = run(program);
    assert_last_alarm(&r, code, line, column);
    let prefix: String = program
        .lines()
        .take(usize::try_from(block_line - 1).unwrap())
        .map(|l| format!("{l}\n"))
        .collect();
    let before = run(&prefix);
    assert!(
        matches!(before.outcome, Outcome::Ended(_)),
        "{:?}",
        before.outcome
    );
    assert_same_state(&r.state, &before.state);
    assert_eq!(
        motions(&r.events),
        motions(&before.events),
        "the alarming block moved"
    );
    r
}

fn check_lathe(program: &str, code: Code, at: (u64, u32), block_line: u64) -> Run {
    check_lathe_on(
        &Dialect::fanuc_lathe().machine(),
        program,
        code,
        at,
        block_line,
    )
}

const LATHE_START: &str = "G97 S1000 M03\nG00 X40. Z2.\nG71 U2. R0.5\n";

#[test]
fn e343_profile_that_cannot_be_cut_points_at_its_block() {
    // Type I (the first block names only X) whose X goes down again.
    let p = format!(
        "{LATHE_START}G71 P10 Q30 U0.4 W0.1 F0.3\nN10 G00 X20.\nG01 Z-10.\nN25 G01 X16. Z-15.\nN30 X40.\nM30\n"
    );
    check_lathe(&p, Code::E343, (7, 5), 4);
    // A profile that turns back along Z, even for type II.
    let p = format!(
        "{LATHE_START}G71 P10 Q30 U0.4 W0.1 F0.3\nN10 G00 X20. Z2.\nG01 Z-10.\nN25 G01 X30. Z-5.\nN30 X40.\nM30\n"
    );
    check_lathe(&p, Code::E343, (7, 5), 4);
}

#[test]
fn e344_word_not_allowed_in_a_profile_block() {
    let p = format!(
        "{LATHE_START}G71 P10 Q30 U0.4 W0.1 F0.3\nN10 G00 X20.\nG01 Z-10. M99\nN30 X40.\nM30\n"
    );
    check_lathe(&p, Code::E344, (6, 11), 4);
}

#[test]
fn e345_profile_end_missing() {
    let p = format!(
        "{LATHE_START}G71 P10 Q30 U0.4 W0.1 F0.3\nN10 G00 X20.\nG01 Z-10.\nN20 X40.\nM30\n"
    );
    check_lathe(&p, Code::E345, (4, 9), 4);
}

#[test]
fn e346_zero_depth_of_cut() {
    check_lathe(
        "G97 S1000 M03\nG00 X40. Z2.\nG71 U0 R1.\n",
        Code::E346,
        (3, 5),
        3,
    );
    // G74 whose peck is zero.
    check_lathe(
        "G97 S1000 M03\nG00 X0. Z2.\nG74 Z-10. Q0 F0.1\n",
        Code::E346,
        (3, 11),
        3,
    );
}

#[test]
fn e347_chamfer_without_a_g01_after_it() {
    let lathe = Dialect::fanuc_lathe().machine();
    let run = |text: &str| {
        run_with(
            &lathe,
            "fanuc-lathe",
            Options::default(),
            text.as_bytes(),
            &mut NoPrograms,
        )
    };
    // The G01 with the chamfer is held (it moves nothing by itself), so the
    // lines before it are the state to compare with: neither it nor the
    // block that alarms moved.
    let before = run("G97 S1000 M03\nG00 X0. Z2.\n");
    for (program, at) in [
        // The next block is a rapid.
        (
            "G97 S1000 M03\nG00 X0. Z2.\nG01 X20. Z0. ,C1. F0.1\nN7 G00 Z5.\n",
            (4, 4),
        ),
        // A chamfer longer than the next line.
        (
            "G97 S1000 M03\nG00 X0. Z2.\nG01 X20. Z0. ,C3. F0.1\nN7 G01 Z-2.\n",
            (4, 4),
        ),
        // The program ends at the corner: the alarm points at the ,C word.
        (
            "G97 S1000 M03\nG00 X0. Z2.\nG01 X20. Z0. ,C1. F0.1\n",
            (3, 14),
        ),
    ] {
        let r = run(program);
        assert_alarm(&r, Code::E347, at.0, at.1);
        assert_eq!(motions(&r.events), motions(&before.events), "{program}");
    }
}

/// Regression (review of 2026-12-06): `,C`/`,R` under G01 in a block
/// without an axis word has no corner to cut: E347 at the word (Fanuc
/// PS0055), as on a block with a G01 and no end point, instead of being
/// dropped unseen.
#[test]
fn regression_e347_a_corner_word_without_a_move() {
    let head = "G97 S1000 M03\nG00 X40. Z2.\nG01 X20. Z0. F0.1\n";
    check_lathe(&format!("{head}N4 ,C1.\n"), Code::E347, (4, 4), 4);
    check_lathe(&format!("{head}N4 G01 ,R1.\n"), Code::E347, (4, 8), 4);
    check_lathe(&format!("{head}N4 M05 ,C1.\n"), Code::E347, (4, 8), 4);
}

/// Regression (review of 2026-12-06): an alarm about a move compensation
/// held is placed on the held block's line, also when the statement being
/// run spans lines (its line map was applied to the held block's offsets:
/// E318 landed on the current statement, 8:1).
#[test]
fn regression_an_alarm_about_a_held_move_is_not_placed_by_the_current_statement() {
    let r = run(
        "%@MACRO\nG10 L12 P1 R5.;\nG00 X-20. Y-20. Z5.;\nG01 Z-1. F100.;\n\
                 G41 D1 X0. Y0.;\nG01 Y50.;\nG01 X50.;\nG01 X40.\n Y50.5;\nY45.;\n\
                 G40 X-20. Y-20.;\nM30;\n",
    );
    assert_last_alarm(&r, Code::E318, 7, 1);
}

/// Regression: an alarm about a move G70 makes along its profile (here
/// over-travel) names the profile block's line and column, not a column
/// of the G70 line.
#[test]
fn regression_g70_alarms_point_at_the_profile_block() {
    let d = Dialect::fanuc_lathe();
    let text = d
        .default_machine
        .replace(
            "letter = \"x\"\n",
            "letter = \"x\"\nmin_mm = -5.0\nmax_mm = 28.0\n",
        )
        .replace("start_mm = { x = 125.0", "start_mm = { x = 25.0");
    let m = Machine::from_toml(&text).unwrap();
    let r = run_with(
        &m,
        "fanuc-lathe",
        Options::default(),
        b"G97 S1000 M03\nG00 X50. Z2.\nG70 P10 Q20\nM30\nN10 G00 X20.\nG01 Z-10. F0.1\nN20 G01 X60.\n",
        &mut NoPrograms,
    );
    // X60. is radius 30, beyond 28: the alarm is at N20's G01 (column 5).
    assert_last_alarm(&r, Code::E501, 7, 5);
}

#[test]
fn e348_surface_speed_at_the_centre_without_a_clamp() {
    let d = Dialect::fanuc_lathe();
    let text = d
        .default_machine
        .replace("max_spindle_rpm = 4000.0", "max_spindle_rpm = 0.0");
    let m = Machine::from_toml(&text).unwrap();
    check_lathe_on(
        &m,
        "G96 S100 M03\nG00 X10. Z2.\nN3 G01 X0. F0.1\n",
        Code::E348,
        (3, 4),
        3,
    );
}

// ---------------------------------------------------------------------------
// E4xx — program flow
// ---------------------------------------------------------------------------

#[test]
fn e210_g92_under_a_rotation() {
    check(
        "G00 X10. Y0.\nG68 X0 Y0 R90.\n  G92 X0 Y0\nM30\n",
        Code::E210,
        3,
        3,
    );
}

#[test]
fn e312_tool_length_on_a_machine_without_z() {
    let lathe = Dialect::lathe().machine();
    let r = run_with(
        &lathe,
        "lathe",
        Options::default(),
        b"G00 X10\n",
        &mut NoPrograms,
    );
    assert!(matches!(r.outcome, Outcome::Ended(_)));
    // The lathe has no G43; on a mill file without Z it alarms E312.
    let xy = Machine::from_toml(
        &LIMITED_MILL
            .replace("[[axes]]\nletter = \"z\"", "[[axes]]\nletter = \"a\"")
            .replace("z = 0.0", "a = 0.0")
            .replace("z = 100.0", "a = 100.0")
            .replace("[tools.1]\nh_mm = 0.0", "[tools.1]\nh_mm = 10.0"),
    )
    .unwrap();
    check_on(&xy, "G00 X1.\nG00 X2. G43 H1\nM30\n", Code::E312, 2, 9);
}

#[test]
fn e315_arc_under_uneven_scaling_or_in_a_tilted_plane() {
    check(
        "G01 X10. Y0. F100.\nG51 X0 Y0 I2. J1.\n  G02 X-10. Y0. I-10.\nM30\n",
        Code::E315,
        3,
        3,
    );
    check(
        "G01 X10. Y0. F100.\nG68 X0 Y0 R30.\nG18\n  G02 X-10. Z0. I-10.\nM30\n",
        Code::E315,
        4,
        3,
    );
}

#[test]
fn e316_scale_factor_zero_or_both_p_and_ijk() {
    check("G00 X1.\nG51 X0 Y0 P0\nM30\n", Code::E316, 2, 11);
    check("G00 X1.\nG51 X0 Y0 P2. I2.\nM30\n", Code::E316, 2, 15);
}

#[test]
fn e503_tool_offset_beyond_the_registers() {
    // The default mill has offsets H0–H200 (offset_registers = 200).
    check("G00 X1.\nG43 H201 Z5.\nM30\n", Code::E503, 2, 5);
    check("G00 X1.\nG10 L10 P201 R5.\nM30\n", Code::E503, 2, 9);
}

#[test]
fn e401_program_not_found() {
    check("G00 X1.\nN2 M98 P1234\n", Code::E401, 2, 8);
    // The store is asked too; it does not have it either.
    let store = &mut MapStore::default().with(10, "O0010.nc", "G00 Y1.\nM99\n");
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X1.\nN2 M98 P11\n",
        store,
    );
    assert_alarm(&r, Code::E401, 2, 8);
}

#[test]
fn e402_sequence_number_not_found() {
    check("G00 X1.\nN2 M99 P50\n", Code::E402, 2, 8);
    check("G00 X1.\nN2 M98 H50\n", Code::E402, 2, 8);
    // N50 exists, but in another program of the file.
    check(
        "O0001\nG00 X1.\nN3 M98 P2 H50\nM30\nO0002\nN40 M99\nO0003\nN50 M99\n",
        Code::E402,
        3,
        11,
    );
}

#[test]
fn e403_self_recursive_subprogram() {
    let m = machine_with(&[("max_call_depth = 10", "max_call_depth = 3")]);
    let program = "O0001\nN1 G91 G00 X1.\nN2 M98 P1\nM30\n";
    let r = run_on(&m, program);
    assert_alarm(&r, Code::E403, 3, 4);
    // The main run and three nested calls moved; the fourth call alarms.
    assert_eq!(motions(&r.events).len(), 4);
    assert_eq!(r.state.pos.get(0), 4.0);
    assert!(r.state.modal.incremental);
}

#[test]
fn e404_block_limit() {
    let m = machine_with(&[("max_executed_blocks = 5000000", "max_executed_blocks = 10")]);
    // The budget is 10 blocks beyond one per byte read: the lines read
    // reach offset 46 (the sub's M99), so 57 blocks run. Block 1 is the
    // call, then each repeat runs X1 and M99: block 58 is repeat 29's X1.
    let program = "O0001\nN1 M98 P2 L1000\nM30\nO0002\n  G91 G00 X1.\nM99\n";
    let r = run_on(&m, program);
    // Line 5 ran before: only the last event is checked, not "no motion
    // from the alarming line".
    assert_last_alarm(&r, Code::E404, 5, 3);
    assert_eq!(motions(&r.events).len(), 28);
}

#[test]
fn a_long_straight_program_never_reaches_the_block_limit() {
    let m = machine_with(&[("max_executed_blocks = 5000000", "max_executed_blocks = 0")]);
    let program: String = (1..=1000).map(|i| format!("N{i} G00 X{i}.\n")).collect();
    let r = run_on(&m, &program);
    assert!(
        matches!(r.outcome, Outcome::Ended(EndCode::Eof)),
        "{:?}",
        r.outcome
    );
    assert_eq!(motions(&r.events).len(), 1000);
}

#[test]
fn m99_in_the_main_program_runs_one_pass_and_warns() {
    // A machine repeats it for ever (bar feeder): vcnc stops after one pass.
    for program in [
        "N1 G91 G00 X1.\nN2 M99\n",
        "G90 G00 X0\nN10 G91 G00 X1.\n  M99 P10\nM30\n",
    ] {
        let r = run(program);
        assert!(
            matches!(r.outcome, Outcome::Ended(EndCode::M99)),
            "{:?}",
            r.outcome
        );
        let warned = r
            .events
            .iter()
            .any(|e| matches!(e, Event::Warning(d) if d.code == Code::W107));
        assert!(warned, "{program}");
        assert_eq!(r.state.pos.get(0), 1.0);
    }
    // M99 P to a later block is a jump, not a repeat.
    let r = run("G90 G00 X0\nM99 P20\nG00 X5.\nN20 G00 X1.\nM30\n");
    assert!(
        matches!(r.outcome, Outcome::Ended(EndCode::M30)),
        "{:?}",
        r.outcome
    );
    assert_eq!(r.state.pos.get(0), 1.0);
}

#[test]
fn e405_repeated_calls() {
    let m = machine_with(&[("max_jumps = 1000000", "max_jumps = 5")]);
    // One call plus repeats: each repeat is a jump.
    let r = run_on(
        &m,
        "O0001\nN1 M98 P2 L10\nM30\nO0002\nG91 G00 X1.\n   M99\n",
    );
    assert_alarm(&r, Code::E405, 6, 4);
}

#[test]
fn e406_subprogram_ends_without_m99_at_end_of_file() {
    let r = run("N1 M98 P2\nN2 M30\nO0002\nN3 G00 X1.\n  N4 G00 Y1.\n");
    // The alarm points at the subprogram's last block, which did run.
    assert_last_alarm(&r, Code::E406, 5, 3);
    assert_eq!(motions(&r.events).len(), 2);
    // The same for a subprogram from the program store: the alarm names its file.
    let store = &mut MapStore::default().with(10, "O0010.nc", "G00 X1.\n  G00 Y1.\n");
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X0\nN2 M98 P10\nM30\n",
        store,
    );
    let d = assert_last_alarm(&r, Code::E406, 2, 3);
    assert_eq!(d.file.as_deref(), Some("O0010.nc"));
}

#[test]
fn e408_called_program_cannot_be_opened() {
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X1.\nN2 M98 P10\n",
        &mut UnopenableStore,
    );
    let d = assert_alarm(&r, Code::E408, 2, 8);
    assert!(d.message.contains("permission denied"), "{}", d.message);
    assert_eq!(d.file, None, "the alarm is in the main program");
}

// ---------------------------------------------------------------------------
// E5xx — the machine
// ---------------------------------------------------------------------------

#[test]
fn e501_over_travel() {
    // The brief's example: the G91 of the alarming block does not stick.
    let r = check("G90 G00 X1.\nN2 G91 G01 X5000. F100\n", Code::E501, 2, 12);
    assert!(
        !r.state.modal.incremental,
        "G90 is still in force after the alarm"
    );
    assert_eq!(r.state.pos.get(0), 1.0);
    // An arc whose end points are inside but whose sweep passes X = 1104:
    // the offending axis (X) is not written, so the G03 word is meant …
    check(
        "N1 G00 Y-999.\nN2 G03 Y999. I100. J999. F100\n",
        Code::E501,
        2,
        4,
    );
    // … and with X written, the X word.
    check(
        "N1 G00 Y-999.\nN2 G03 X0 Y999. I100. J999. F100\n",
        Code::E501,
        2,
        8,
    );
    // No G word in the block: its first word.
    check(
        "N1 G00 Y-999.\nG03 F100\n  N3 Y999. I100. J999.\n",
        Code::E501,
        3,
        3,
    );
    // The intermediate point of G28 counts too.
    check("G00 X1.\nN2 G28 Z600.\n", Code::E501, 2, 8);
}

#[test]
fn e502_reference_point_not_defined() {
    let m = machine_with(&[
        ("p3 = { x = -200.0, y = 150.0, z = 0.0 }\n", ""),
        ("p2 = { x = 200.0, y = 150.0, z = 0.0 }\n", ""),
    ]);
    check_on(&m, "G00 X1.\nN2 G30 P3 X0\n", Code::E502, 2, 8);
    // Without P, G30 means P2: the G30 word.
    check_on(&m, "G00 X1.\nN2 G30 X0\n", Code::E502, 2, 4);
}

#[test]
fn e503_work_offset_number_out_of_range() {
    check("G00 X1.\nN2 G10 L2 P9 X0\n", Code::E503, 2, 11);
    check("G00 X1.\nN2 G10 L2 P0 X0\n", Code::E503, 2, 11);
}

// ---------------------------------------------------------------------------
// Rollback after an alarm
// ---------------------------------------------------------------------------

#[test]
fn an_alarm_leaves_modal_state_position_and_offsets_as_before_the_block() {
    let setup = "G90 G17 G71 G94 G54 G64 S1000 M03\nG00 X10. Y10.\n";
    let m = limited_mill();
    let no_jumps = machine_with(&[("max_jumps = 1000000", "max_jumps = 0")]);
    let cases: &[(&Machine, &str, Code, u32)] = &[
        // Modal codes of every group written in a block that then alarms.
        (&m, "G91 G18 G95 G55 G61 G01 X5000. F100", Code::E501, 25),
        (&m, "G70 G91 G03 X1. I0 J0 F100", Code::E304, 9),
        (&m, "G59.1 G91 G02 X100. R10. F100", Code::E302, 21),
        // Offsets changed by the alarming block (its call or return fails
        // after them) are restored.
        (&m, "G92 X0 Y0 M98 P1234", Code::E401, 15),
        (&m, "G52 X5. Y5. M99 P77", Code::E402, 17),
        (&no_jumps, "G91 G10 L2 P1 X50. M99", Code::E405, 20),
    ];
    for (machine, block, code, column) in cases {
        let program = format!("{setup}{block}\nM30\n");
        let r = check_on(machine, &program, *code, 3, *column);
        assert!(
            !r.state.modal.incremental && !r.state.modal.inch && !r.state.modal.per_rev,
            "{block}"
        );
        assert_eq!(r.state.modal.wcs, 0, "{block}");
    }
}

// ---------------------------------------------------------------------------
// Disagreements with docs/alarms.md and ARCHITECTURE.md (regression tests)
// ---------------------------------------------------------------------------

/// The reader's buffer is 64 KiB and E106 says "line is longer than 64 KiB",
/// but a line of exactly 64 KiB (65536 bytes of short blocks) alarms too:
/// the limit is off by one (the newline must fit in the buffer).
#[test]
fn regression_e106_a_line_of_exactly_64_kib_is_not_longer_than_64_kib() {
    let line = "X1.;".repeat(65_536 / 4);
    assert_eq!(line.len(), 65_536);
    let r = run(&format!("G00 X2.\n{line}\nM30\n"));
    assert_eq!(
        r.outcome,
        Outcome::Ended(EndCode::M30),
        "{:?}",
        r.events.last()
    );
}

/// docs/alarms.md: E304's column is "the G02/G03 word, else the first word",
/// also for R0. The interpreter points at the R word.
#[test]
fn regression_e304_r0_points_at_the_arc_word() {
    check("G00 X1.\nN2 G02 X2. R0 F100\n", Code::E304, 2, 4);
}

/// docs/alarms.md: E310's column is "the G96 word or the S word". With M03 in
/// the block the interpreter points at the M03.
#[test]
fn regression_e310_with_m03_in_the_block_points_at_g96() {
    check("T9 M06\nN2 G96 S100 M03\n", Code::E310, 2, 4);
}

/// docs/alarms.md: E406 points at "the last block's first word" of the
/// subprogram. When the subprogram is ended by `%` or by the next `O` header
/// (rather than by the end of the file) the interpreter points at that `%`
/// or `O` line instead.
#[test]
fn regression_e406_at_percent_or_next_header_points_at_the_last_block() {
    let r = run("N1 M98 P2\nN2 M30\nO0002\nN3 G00 X1.\n  N4 G00 Y1.\n%\n");
    assert_last_alarm(&r, Code::E406, 5, 3);
    let r = run("N1 M98 P2\nN2 M30\nO0002\nN3 G00 X1.\n  N4 G00 Y1.\nO0003\nM99\n");
    assert_last_alarm(&r, Code::E406, 5, 3);
}

/// ARCHITECTURE.md: "the block that raised [an alarm] moves nothing and
/// leaves the modal state and offsets as they were". Program-flow words run
/// last in a block (execute.rs step 8), after its motion has been emitted, so
/// an M98/M99 alarm in a block that also moves leaves that motion behind and
/// the position changed.
#[test]
fn regression_flow_alarms_in_a_moving_block_move_nothing() {
    let main = |block: &str| format!("O0001\nG90 G00 X1.\n{block}\nM30\n");
    // A call to O0002 whose block moves and calls or returns once too often.
    let nested =
        |block: &str| format!("O0001\nG90 G00 X1.\nM98 P2\nM30\nO0002\n{block}\nM99\nO0003\nM99\n");
    let depth = machine_with(&[("max_call_depth = 10", "max_call_depth = 1")]);
    let jumps = machine_with(&[("max_jumps = 1000000", "max_jumps = 1")]);
    let m = limited_mill();
    let cases: Vec<(&Machine, String, Code, u64, u32)> = vec![
        (&m, main("N2 G00 X10. M98 P1234"), Code::E401, 3, 17),
        (&m, main("N2 G00 X10. M99 P50"), Code::E402, 3, 17),
        (&m, main("N2 G01 X10. F100 M98 P1 L0"), Code::E109, 3, 25),
        (&m, main("N2 G01 X10. F100 M98 P1."), Code::E108, 3, 22),
        (&depth, nested("N2 G00 X10. M98 P3"), Code::E403, 6, 13),
        (&jumps, nested("N2 G00 X10. M99"), Code::E405, 6, 13),
    ];
    let mut failures = Vec::new();
    for (machine, program, code, line, column) in &cases {
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let r = run_on(machine, program);
            assert_alarm(&r, *code, *line, *column);
            assert_eq!(r.state.pos.get(0), 1.0, "position after the alarm");
        }));
        if result.is_err() {
            failures.push(code.as_str());
        }
    }
    assert!(
        failures.is_empty(),
        "alarming blocks that moved: {failures:?}"
    );
}

/// docs/alarms.md: E408's column is the P word of the call. When the called
/// program opens but a read fails, the alarm has column 0 (not 1-based) and
/// does not point at the M98's P word.
#[test]
fn regression_e408_read_error_points_at_the_p_word() {
    let r = run_with(
        &limited_mill(),
        "syntec",
        Options::default(),
        b"G00 X1.\nN2 M98 P10\n",
        &mut UnreadableStore,
    );
    let d = assert_alarm(&r, Code::E408, 2, 8);
    assert_eq!(
        d.file, None,
        "the alarm is located at the call in the main program"
    );
}
