//! Block atomicity, one way for every block: a block that alarms leaves the
//! state, the offset tables and the event stream exactly as the blocks
//! before it left them. Checked on random programs made of blocks that
//! change every kind of state (modal codes, F, thread lead, offsets, tool
//! data, transforms, spindle, tool) and blocks that alarm in their middle,
//! by comparing each run that alarms with a run of the lines before the
//! alarm.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, State, Tables, VecSink};

/// Blocks that change state, and blocks that alarm after changing some.
const BLOCKS: &[&str] = &[
    "G00 X12. Y7.",
    "G01 X-3. Y4. F300.",
    "G91 G01 X2. Z-1. F250.",
    "G90",
    "G02 X10. Y0. R5. F200.",
    "G92 X1. Y2.",
    "G52 X5. Y-5.",
    "G55 X1.",
    "G54",
    "G10 L2 P2 X3. Y4. Z5.",
    "G10 L10 P1 R-12.5",
    "G10 L12 P2 R3.",
    "G43 H1 Z5.",
    "G44 H2",
    "G49",
    "G51 X1. Y1. P2.",
    "G50",
    "G68 X0. Y0. R30.",
    "G69",
    "G51.1 X4.",
    "G50.1",
    "G16 X10. Y45.",
    "G15",
    "G21 G33 Z-1. F1.5",
    "S1200 M03",
    "M05",
    "T2 M06",
    "G04 X0.5",
    "G61",
    "G64",
    // These alarm part-way: after their modal codes or F have been read.
    "G91 G01 X5000. F7.",
    "G33 Z-100000. F7.",
    "G01 X1. F-1.",
    "G43 H999 Z1.",
    "G51 X0. P0.",
    "G02 X1. Y1. I0. J0.05 F100.",
    "G10 L10 P1 R5. G55 X99999.",
    "G68 R45. G51 P2.",
    "G92 X1. M98 P9999",
    // Plain moves that alarm after their motion code, F or polar point
    // changed (they save only those, see `MoveUndo`).
    "G01 Y2. F0.",
    "X5000. F7.",
    "X9000. Y30.",
];

fn run(machine: &Machine, program: &str) -> Run {
    let d = Dialect::fanuc();
    let mut sink = VecSink::default();
    let mut interp = Interpreter::new(machine, &d, Options::default());
    let out = interp.run_str(program, &mut sink);
    (sink.0, out, *interp.state(), interp.tables().clone())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn an_alarming_block_changes_nothing(picks in proptest::collection::vec(0..BLOCKS.len(), 1..25)) {
        // Travel limits, so that over-travel is among the alarms.
        let machine = Machine::from_toml(include_str!(
            "../../../../tests/fixtures/machines/mill_travel_limits.toml"
        ))
        .unwrap();
        let lines: Vec<&str> = picks.iter().map(|&i| BLOCKS[i]).collect();
        let program = lines.join("\n") + "\n";
        let (events, outcome, state, tables) = run(&machine, &program);
        let Outcome::Alarm(d) = outcome else {
            return Ok(());
        };
        let before = usize::try_from(d.line).unwrap() - 1;
        let prefix = lines[..before].join("\n") + "\n";
        let (p_events, p_outcome, p_state, p_tables) = run(&machine, &prefix);
        // The prefix ends at the end of its file: it warns that it has no
        // M30 (W106), the alarmed run never got there.
        let p_events: Vec<Event> = p_events
            .into_iter()
            .filter(|e| !matches!(e, Event::Warning(d) if d.code == vcnc_syntax::Code::W106))
            .collect();
        prop_assert!(matches!(p_outcome, Outcome::Ended(_)), "{:?}", p_outcome);
        prop_assert_eq!(state, p_state, "state after the alarm in:\n{}", program);
        prop_assert_eq!(tables, p_tables, "tables after the alarm in:\n{}", program);
        // Same events, but for the alarm and the prefix's end of file.
        prop_assert_eq!(&events[..events.len() - 1], &p_events[..p_events.len() - 1]);
    }
}

/// Blocks cut under G41, among them plain moves that alarm once the
/// compensation stage has handed its held move on (over-travel of the move
/// released, of the corner, a zero feed, a reversal the tool cannot follow):
/// such blocks undo the stage through its mark instead of a copy.
const COMP_BLOCKS: &[&str] = &[
    "X20. Y0.",
    "X20. Y20.",
    "X0. Y20.",
    "X0. Y0.",
    "X35. Y5.",
    "G91 X4. Y-3.",
    "G90",
    "Z-2.",
    "Z1.",
    "M08",
    "G04 X0.1",
    "F250.",
    "G02 X10. Y10. R30.",
    "G00 X15. Y12.",
    "G01 X30. Y30.",
    // These alarm part-way.
    "X995. Y0.",
    "X0. Y998.5",
    "X5000. F7.",
    "G01 Y2. F0.",
    "X20.0001 Y0.",
    "G91 X0.5 Y0. G90",
    "G91 X-0.5 Y0. G90",
];

/// A block that alarms without changing anything (program 9999 does not
/// exist), so that a program stops where a prefix ends without the end of
/// program releasing the move held by the compensation.
const STOP: &str = "M98 P9999";

/// What a run leaves: its events, how it ended, the state and the tables.
type Run = (Vec<Event>, Outcome, State, Tables);

/// Finds the first of `lines` that alarms itself (an alarm can name the
/// block of the move the compensation held before it) and compares the
/// run up to it with the run of the lines before it, each followed by
/// [`STOP`]: the same state, tables and events but for the alarm. Debug
/// builds also check, after every alarm of a plain move, that its undo
/// restored the state and the compensation stage exactly.
fn alarm_changes_nothing(run: impl Fn(&str) -> Run, lines: &[&str]) -> Result<(), TestCaseError> {
    let stopped = |n: usize| {
        let mut text = lines[..n].join("\n");
        text.push('\n');
        text.push_str(STOP);
        text.push('\n');
        run(&text)
    };
    let Some(trigger) = (1..=lines.len())
        .find(|&n| matches!(&stopped(n).1, Outcome::Alarm(d) if d.line != n as u64 + 1))
    else {
        return Ok(());
    };
    let (events, _, state, tables) = stopped(trigger);
    let (p_events, _, p_state, p_tables) = stopped(trigger - 1);
    let program = lines[..trigger].join("\n");
    prop_assert_eq!(state, p_state, "state after the alarm in:\n{}", program);
    prop_assert_eq!(tables, p_tables, "tables after the alarm in:\n{}", program);
    prop_assert_eq!(&events[..events.len() - 1], &p_events[..p_events.len() - 1]);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn an_alarming_block_under_compensation_changes_nothing(
        picks in proptest::collection::vec(0..COMP_BLOCKS.len(), 1..25),
    ) {
        let machine = Machine::from_toml(include_str!(
            "../../../../tests/fixtures/machines/mill_travel_limits.toml"
        ))
        .unwrap();
        let mut lines = vec!["G10 L12 P1 R2.", "G00 X-10. Y-10.", "G41 D1 G01 X0. Y0. F300."];
        lines.extend(picks.iter().map(|&i| COMP_BLOCKS[i]));
        lines.push("M30");
        alarm_changes_nothing(|text| run(&machine, text), &lines)?;
    }
}

/// Blocks turned under G42 with a tool nose (fanuc-lathe: the radius and
/// the imaginary tip come from the T offset, and the compensated points are
/// shifted from the nose centre to the tip before they leave), among them
/// plain moves that alarm after the stage handed its held move on.
const NOSE_BLOCKS: &[&str] = &[
    "X40. Z-10.",
    "Z-20.",
    "X60.",
    "X50. Z-30.",
    "U2. W-3.",
    "W-5.",
    "G00 X70. Z-25.",
    "G01 X30. Z-40.",
    "G02 X80. Z-45. R8.",
    "M08",
    "G04 U0.1",
    "F0.3",
    "T0202",
    // These alarm part-way.
    "X301. Z-30.",
    "X299.5",
    "Z-299.8",
    "G01 Z-5. F0.",
    "X40.0001 Z-10.",
    "W0.5",
    "W-0.5",
];

/// The built-in fanuc-lathe with travel limits: X radius -5..150, Z -300..250.
fn lathe_with_limits() -> Machine {
    let text = include_str!("../../../vcnc_core/src/default_fanuc_lathe.toml")
        .replace(
            "letter = \"x\"\n",
            "letter = \"x\"\nmin_mm = -5.0\nmax_mm = 150.0\n",
        )
        .replace(
            "letter = \"z\"\n",
            "letter = \"z\"\nmin_mm = -300.0\nmax_mm = 250.0\n",
        );
    // Without the limits the over-travel blocks would not alarm.
    assert_eq!(text.matches("max_mm = ").count(), 2, "{text}");
    Machine::from_toml(&text).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn an_alarming_block_under_nose_radius_compensation_changes_nothing(
        picks in proptest::collection::vec(0..NOSE_BLOCKS.len(), 1..25),
    ) {
        let machine = lathe_with_limits();
        let d = Dialect::fanuc_lathe();
        let run = |text: &str| {
            let mut sink = VecSink::default();
            let mut interp = Interpreter::new(&machine, &d, Options::default());
            let out = interp.run_str(text, &mut sink);
            (sink.0, out, *interp.state(), interp.tables().clone())
        };
        let mut lines = vec!["T0101", "M03 S800", "G00 X60. Z5.", "G42 G01 X50. Z2. F0.2"];
        lines.extend(picks.iter().map(|&i| NOSE_BLOCKS[i]));
        lines.push("M30");
        alarm_changes_nothing(run, &lines)?;
    }
}
