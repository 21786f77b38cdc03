//! One test per warning code (W101–W109, `docs/alarms.md`): the code, its
//! line and column, that the run goes on, and where a warning must stay
//! silent. Columns are counted by hand from the program text.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, EndCode, Event, Interpreter, Machine, Options, Outcome, VecSink};
use vcnc_syntax::{Code, Diagnostic};

fn run_in(machine: &Machine, dialect: Dialect, program: &str) -> (Vec<Event>, Outcome) {
    let mut sink = VecSink::default();
    let out = Interpreter::new(machine, &dialect, Options::default()).run_str(program, &mut sink);
    (sink.0, out)
}

fn run(program: &str) -> (Vec<Event>, Outcome) {
    run_in(&Machine::default_mill(), Dialect::syntec(), program)
}

fn warnings(events: &[Event]) -> Vec<&Diagnostic> {
    events
        .iter()
        .filter_map(|e| match e {
            Event::Warning(d) => Some(d),
            _ => None,
        })
        .collect()
}

/// (code, line, column) of every warning.
fn places(events: &[Event]) -> Vec<(Code, u64, u32)> {
    warnings(events)
        .iter()
        .map(|d| (d.code, d.line, d.column))
        .collect()
}

#[test]
fn w101_a_length_without_a_point_among_points() {
    let (ev, out) = run("S1000 M03\nG00 X10. Y10.\nG01 X35 F500.\nY20.\nM30\n");
    assert!(matches!(out, Outcome::Ended(EndCode::M30)));
    assert_eq!(places(&ev), vec![(Code::W101, 3, 5)]);
    // X35 is 0.035 mm, as the warning says.
    let w = warnings(&ev)[0];
    assert!(w.message.contains("0.035 mm"), "{}", w.message);
}

#[test]
fn w101_is_given_for_an_early_point_less_word_once_points_appear() {
    // The trap is seen at line 3; the warning names line 2.
    let (ev, _) = run("S1000 M03\nG00 X10 Y0\nG01 X20. F500.\nM30\n");
    assert_eq!(places(&ev), vec![(Code::W101, 2, 5)]);
}

#[test]
fn w101_stays_silent_on_a_consistent_program() {
    // Tape format throughout, zeros, and whole-unit dialects never warn.
    let (ev, _) = run("S1000 M03\nG00 X10000 Y5000\nG01 X20000 F500\nX0 Y0\nM30\n");
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
    let (ev, _) = run("S1000 M03\nG00 X10. Y0\nG01 X20. Y0 F500.\nM30\n");
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
    let (ev, _) = run_in(
        &Machine::default_mill(),
        Dialect::grbl(),
        "M3 S1000\nG0 X10. Y10\nG1 X35 F500\nM30\n",
    );
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
}

#[test]
fn w101_stops_after_ten() {
    let mut p = String::from("S1000 M03\nG00 X1.\n");
    for i in 1..=20 {
        p += &format!("G01 X{i} F500.\n");
    }
    p += "M30\n";
    let (ev, _) = run(&p);
    assert_eq!(places(&ev).len(), 10);
}

#[test]
fn w102_a_feed_above_the_maximum_is_clamped() {
    let (ev, _) = run("S1000 M03\nG01 X10. F20000.\nM30\n");
    assert_eq!(places(&ev), vec![(Code::W102, 2, 10)]);
    let feed = ev.iter().find_map(|e| match e {
        Event::Feed { feed, .. } => Some(*feed),
        _ => None,
    });
    assert_eq!(feed, Some(vcnc_interp::Feed::PerMin(10_000.0)));
}

#[test]
fn w103_a_spindle_speed_above_the_maximum_is_clamped() {
    // The built-in machines have no spindle limit: a machine file gives it.
    let (ev, _) = run("G00 X1.\n  S20000 M03\nM30\n");
    assert!(places(&ev).is_empty());
    let mut m = Machine::default_mill();
    m.params.max_spindle_rpm = 12_000.0;
    let (ev, _) = run_in(&m, Dialect::syntec(), "G00 X1.\n  S20000 M03\nM30\n");
    assert_eq!(places(&ev), vec![(Code::W103, 2, 3)]);
    let rpm = ev.iter().find_map(|e| match e {
        Event::Spindle { rpm, .. } => Some(*rpm),
        _ => None,
    });
    assert_eq!(rpm, Some(12_000.0));
}

#[test]
fn w104_once_until_the_spindle_turns_again() {
    let program = "G01 X1. F100.\nX2.\nS100 M03\nX3.\nM05\n  G02 X4. R1.\nX5.\nM30\n";
    let (ev, _) = run(program);
    assert_eq!(
        places(&ev),
        vec![(Code::W104, 1, 1), (Code::W104, 6, 3)],
        "line 2 and 7 are in the same stretch as lines 1 and 6"
    );
}

#[test]
fn w105_an_unknown_m_code_is_ignored() {
    let (ev, out) = run("G00 X1.\nN2 M03 S100 M77\nM30\n");
    assert!(matches!(out, Outcome::Ended(EndCode::M30)));
    assert_eq!(places(&ev), vec![(Code::W105, 2, 13)]);
    // A machine that lists it passes it through instead.
    let mut m = Machine::default_mill();
    m.m_codes.insert(77, "pallet clamp".into());
    let (ev, _) = run_in(&m, Dialect::syntec(), "G00 X1.\nN2 M03 S100 M77\nM30\n");
    assert!(places(&ev).is_empty());
    assert!(ev.iter().any(|e| matches!(e, Event::Aux { code: 77, .. })));
}

#[test]
fn w106_no_program_end() {
    let (ev, out) = run("G00 X1.\n  G00 Y1.\n");
    assert!(matches!(out, Outcome::Ended(EndCode::Eof)));
    assert_eq!(places(&ev), vec![(Code::W106, 2, 3)]);
    // The warning comes before the `end` event.
    assert!(matches!(ev.last(), Some(Event::End { .. })));
}

#[test]
fn w107_m99_in_the_main_program_runs_one_pass() {
    let (ev, out) = run("G91 G00 X1.\n  M99\n");
    assert_eq!(out, Outcome::Ended(EndCode::M99));
    assert_eq!(places(&ev), vec![(Code::W107, 2, 3)]);
}

#[test]
fn a_block_that_alarms_drops_its_warnings() {
    // W102 on the F word, then E303 in the same block: no warning remains.
    let (ev, out) = run("G00 X1.\nG02 X10. Y0 I-3. J-1. F20000.\nM30\n");
    assert!(matches!(out, Outcome::Alarm(_)));
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
}

/// The trap: a grbl program (no decimal points, whole millimetres)
/// under fanuc draws a half circle from X0 to X20 read as 0.020 mm. The
/// end points lie within 0.020 mm: W109 at X20 (line 3, column 5), before
/// `end`, naming the whole-unit readings.
#[test]
fn w109_no_points_and_a_part_under_a_millimetre() {
    let program = "S1000 M03\nG00 X0 Y0\nG02 X20 Y0 I10 J0 F100\nM30\n";
    let (ev, out) = run_in(&Machine::default_mill(), Dialect::fanuc(), program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)));
    assert_eq!(places(&ev), vec![(Code::W109, 3, 5)]);
    let w = warnings(&ev)[0];
    // The longest length is X20 (I10 is half of it), read as 0.020 mm.
    assert!(
        w.message.contains("the longest, X20, is 0.0200 mm"),
        "{}",
        w.message
    );
    for reading in [
        "--dialect grbl",
        "--dialect linuxcnc",
        "decimal_input = \"calculator\"",
    ] {
        assert!(w.help.contains(reading), "{}", w.help);
    }
    let n = ev.len();
    assert!(matches!(ev[n - 2], Event::Warning(_)) && matches!(ev[n - 1], Event::End { .. }));
    // The same at the end of the file (no M30): W106 and W109.
    let (ev, _) = run_in(
        &Machine::default_mill(),
        Dialect::fanuc(),
        "S1000 M03\nG00 X0 Y0\nG01 X20 F100\n",
    );
    assert_eq!(places(&ev), vec![(Code::W106, 3, 1), (Code::W109, 3, 5)]);
}

#[test]
fn w109_stays_silent_where_the_reading_is_whole_units_or_the_part_is_large() {
    let program = "S1000 M03\nG00 X0 Y0\nG02 X20 Y0 I10 J0 F100\nM30\n";
    // Whole units: grbl, and Fanuc with calculator-type input.
    let (ev, _) = run_in(&Machine::default_mill(), Dialect::grbl(), program);
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
    let mut calculator = Machine::default_mill();
    calculator.params.decimal_input = vcnc_interp::machine::DecimalInput::Calculator;
    let (ev, _) = run_in(&calculator, Dialect::fanuc(), program);
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
    // Tape format whose part spans 20 mm (X20000 is 20 mm).
    let (ev, _) = run_in(
        &Machine::default_mill(),
        Dialect::fanuc(),
        "S1000 M03\nG00 X0 Y0\nG01 X20000 F100\nM30\n",
    );
    assert!(places(&ev).is_empty(), "{:?}", places(&ev));
    // A point anywhere: W101's business, not W109's.
    let (ev, _) = run_in(
        &Machine::default_mill(),
        Dialect::fanuc(),
        "S1000 M03\nG00 X0 Y0\nG01 X20 F100\nY1.\nM30\n",
    );
    assert_eq!(places(&ev), vec![(Code::W101, 3, 5)]);
}

/// On a lathe the power-on position (far from the part) is left out, and
/// the help names the lathes that read whole units.
#[test]
fn w109_on_a_lathe_leaves_the_power_on_position_out() {
    let (ev, _) = run_in(
        &Machine::from_toml(vcnc_interp::machine::DEFAULT_FANUC_LATHE_TOML).unwrap(),
        Dialect::fanuc_lathe(),
        "G21 G18\nM03 S1200\nG0 X21 Z92\nG1 X16 Z92 F280\nG1 X26 Z86\nM30\n",
    );
    assert_eq!(places(&ev), vec![(Code::W109, 3, 4)]);
    let w = warnings(&ev)[0];
    assert!(
        w.help
            .contains("--dialect lathe or --dialect linuxcnc-lathe"),
        "{}",
        w.help
    );
}

/// W108: the built-in mill's offset memory is empty, so G41 D1 offsets by 0
/// (warned once per register, at the G41/G42 word) and the cut is the
/// programmed path; D0 is the zero register by definition and stays silent.
#[test]
fn w108_compensation_with_an_empty_register() {
    let program = "S1000 M03\nG00 X-10. Y-10.\nG01 G41 D1 X0 Y0 F500.\nX20.\nG40 X30. Y-10.\n\
                   G42 D1 G01 X0 Y0\nG40 X-10.\nG41 D2 X0\nG40 X-10.\nG41 D0 X0\nG40 X-10.\nM30\n";
    let (ev, out) = run(program);
    assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
    assert_eq!(
        places(&ev),
        vec![(Code::W108, 3, 5), (Code::W108, 8, 1)],
        "{:?}",
        warnings(&ev)
    );
    assert!(warnings(&ev)[0].message.contains("G41 D1 = 0"));
    // Nothing is offset: the cut ends where the program says.
    let feeds: Vec<(f64, f64)> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Feed { to, .. } => Some((to.get(0), to.get(1))),
            _ => None,
        })
        .take(3)
        .collect();
    assert_eq!(feeds, vec![(0.0, 0.0), (20.0, 0.0), (30.0, -10.0)]);
}

/// W108 for G43/G44 with an H register that holds 0; a filled register
/// (written by G10 L10) and G49 stay silent.
#[test]
fn w108_tool_length_with_an_empty_register() {
    let (ev, _) =
        run("G10 L10 P2 R50.\nG43 H1 Z10.\nG49\nG44 H3 Z10.\nG43 H2 Z10.\nG49 Z20.\nM30\n");
    assert_eq!(
        places(&ev),
        vec![(Code::W108, 2, 1), (Code::W108, 4, 1)],
        "{:?}",
        warnings(&ev)
    );
    assert!(warnings(&ev)[1].message.contains("G44 H3 = 0"));
}

/// W108 stays silent when the register holds a radius, and names the tool
/// nose on a lathe whose turret offset has none.
#[test]
fn w108_names_the_nose_radius_on_a_lathe_and_is_silent_with_tools() {
    let mut mill = Machine::default_mill();
    mill.tools.entry(1).or_default().d_mm = 5.0;
    let (ev, _) = run_in(
        &mill,
        Dialect::syntec(),
        "S1000 M03\nG00 X-10. Y-10.\nG01 G41 D1 X0 Y0 F500.\nX20.\nG40 X30.\nM30\n",
    );
    assert!(places(&ev).is_empty(), "{:?}", warnings(&ev));
    let lathe = Dialect::fanuc_lathe();
    let (ev, out) = run_in(
        &lathe.machine(),
        Dialect::fanuc_lathe(),
        "T0101\nS500 M03\nG00 X40. Z2.\nG42 G01 X40. Z0 F0.2\nZ-20.\nG40 G00 X60.\nM30\n",
    );
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(places(&ev), vec![(Code::W108, 4, 1)]);
    let w = warnings(&ev)[0];
    assert!(
        w.message.contains("nose radius of 0 (offset 1)"),
        "{}",
        w.message
    );
}

#[test]
fn w110_fanuc_and_haas_ignore_g53_in_incremental_mode() {
    // Fanuc 0i: "when an incremental command is specified, the G53 command
    // is ignored". The block does not move; Syntec keeps its alarm (E308).
    for dialect in [Dialect::fanuc(), Dialect::haas()] {
        let program = "G00 X5. Z10.\nG91 G00 X1.\nG53 G49 Z0.\nM30\n";
        let (ev, out) = run_in(&Machine::default_mill(), dialect, program);
        assert!(matches!(out, Outcome::Ended(EndCode::M30)), "{out:?}");
        assert_eq!(places(&ev), vec![(Code::W110, 3, 1)]);
        let moves_on_3 = ev
            .iter()
            .filter(|e| matches!(e, Event::Rapid { loc, .. } if loc.line == 3))
            .count();
        assert_eq!(moves_on_3, 0);
    }
    let (_, out) = run("G91\nG53 Z0.\nM30\n");
    assert!(
        matches!(out, Outcome::Alarm(ref d) if d.code == Code::E308),
        "{out:?}"
    );
}

/// W110 says what happens: G53's axis words make no machine move, but an
/// H0 in the block still cancels the length offset (50 mm), so Z moves
/// 50 mm down in machine coordinates on that line (Fanuc: "the G53 command
/// is ignored", the rest of the block is not).
#[test]
fn w110_names_what_still_acts_in_an_ignored_g53_block() {
    let p = "G90 G21 G17\nG10 L10 P1 R50.\nG43 H1 G0 Z10.\nG91 G53 G0 H0 Z0.\nM30\n";
    let (events, out) = crate::common::run_str(&Dialect::fanuc(), p);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let w = events
        .iter()
        .find_map(|e| match e {
            Event::Warning(d) if d.code == Code::W110 => Some(d),
            _ => None,
        })
        .expect("W110");
    assert!(w.message.contains("H0"), "{}", w.message);
    assert!(!w.message.contains("does not move"), "{}", w.message);
}
