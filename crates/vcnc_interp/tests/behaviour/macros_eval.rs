//! Expressions of both macro languages: every operator, function, precedence
//! level and null rule, with the expected values worked out by hand in the
//! comments (`docs/macros.md` states the rules these follow).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, VecSink};
use vcnc_syntax::Code;

/// Runs `program` under `dialect`; returns the outcome, the events and the
/// values of `names` afterwards.
fn run(dialect: &str, program: &str, names: &[&str]) -> (Outcome, Vec<Event>, Vec<Option<f64>>) {
    let machine = Machine::default_mill();
    let dialect = Dialect::by_name(dialect).unwrap();
    let mut sink = VecSink::default();
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    let outcome = interp.run_str(program, &mut sink);
    let values = names.iter().map(|n| interp.variable(n)).collect();
    (outcome, sink.0, values)
}

/// The value Macro B gives `expr` (`#1 = expr`).
fn b(expr: &str) -> Option<f64> {
    let (outcome, _, v) = run("fanuc", &format!("#1 = {expr}\nM30\n"), &["#1"]);
    assert!(matches!(outcome, Outcome::Ended(_)), "{expr}: {outcome:?}");
    v[0]
}

/// The value Syntec MACRO gives `expr` (`@1 := expr;`).
fn s(expr: &str) -> Option<f64> {
    let (outcome, _, v) = run(
        "syntec",
        &format!("%@MACRO\n@1 := {expr};\nM30;\n"),
        &["@1"],
    );
    assert!(matches!(outcome, Outcome::Ended(_)), "{expr}: {outcome:?}");
    v[0]
}

/// The alarm code an expression raises (line 2 of the program).
fn b_alarm(expr: &str) -> Code {
    match run("fanuc", &format!("G90\n#1 = {expr}\nM30\n"), &[]).0 {
        Outcome::Alarm(d) => {
            assert_eq!(d.line, 2, "{expr}: {d:?}");
            d.code
        }
        other => panic!("{expr}: no alarm but {other:?}"),
    }
}

fn s_alarm(expr: &str) -> Code {
    match run("syntec", &format!("%@MACRO\n@1 := {expr};\nM30;\n"), &[]).0 {
        Outcome::Alarm(d) => {
            assert_eq!(d.line, 2, "{expr}: {d:?}");
            d.code
        }
        other => panic!("{expr}: no alarm but {other:?}"),
    }
}

fn close(a: Option<f64>, b: f64) -> bool {
    a.is_some_and(|a| (a - b).abs() < 1e-9)
}

#[test]
fn macro_b_arithmetic_and_precedence() {
    assert_eq!(b("1 + 2 * 3"), Some(7.0)); // * before +
    assert_eq!(b("[1 + 2] * 3"), Some(9.0));
    assert_eq!(b("10 / 4"), Some(2.5)); // real division
    assert_eq!(b("8 - 2 - 1"), Some(5.0)); // left to right
    assert_eq!(b("16 / 4 / 2"), Some(2.0));
    assert_eq!(b("-3 * -2"), Some(6.0));
    assert_eq!(b("- - 4"), Some(4.0));
    assert_eq!(b("+5"), Some(5.0));
    assert_eq!(b("10 MOD 3"), Some(1.0));
    assert_eq!(b("-7 MOD 3"), Some(-1.0)); // the dividend's sign
    assert_eq!(b("7.9 MOD 3"), Some(1.0)); // integer portions: 7 MOD 3
    assert_eq!(b("5 AND 3"), Some(1.0)); // 101 & 011
    assert_eq!(b("5 OR 3"), Some(7.0));
    assert_eq!(b("5 XOR 3"), Some(6.0));
    // AND binds like *, OR like +: 2 + [6 AND 3] = 4, 1 OR [2 * 3] = 7.
    assert_eq!(b("2 + 6 AND 3"), Some(4.0));
    assert_eq!(b("1 OR 2 * 3"), Some(7.0));
    // Relational operators are loosest: [1 + 1] EQ 2.
    assert_eq!(b("[1 + 1 EQ 2]"), Some(1.0));
    // Fanuc's trap: 7 EQ [7 AND 1] is 7 EQ 1.
    assert_eq!(b("[7 EQ 7 AND 1]"), Some(0.0));
    assert_eq!(b("[[7 EQ 7] AND 1]"), Some(1.0));
    assert_eq!(b("[2 NE 3]"), Some(1.0));
    assert_eq!(b("[2 GT 3]"), Some(0.0));
    assert_eq!(b("[3 GE 3]"), Some(1.0));
    assert_eq!(b("[2 LT 3]"), Some(1.0));
    assert_eq!(b("[4 LE 3]"), Some(0.0));
    // Keywords glued to their operands.
    assert_eq!(b("[7EQ7]"), Some(1.0));
}

#[test]
fn macro_b_functions_in_degrees() {
    assert!(close(b("SIN[30]"), 0.5));
    assert!(close(b("COS[60]"), 0.5));
    assert_eq!(b("COS[90]"), Some(0.0)); // exact at multiples of 90°
    assert_eq!(b("SIN[180]"), Some(0.0));
    assert!(close(b("TAN[45]"), 1.0));
    assert!(close(b("ASIN[0.5]"), 30.0));
    assert!(close(b("ASIN[-0.5]"), 330.0)); // Fanuc 270°..90°
    assert!(close(b("ACOS[0.5]"), 60.0));
    assert!(close(b("ACOS[-1]"), 180.0));
    assert!(close(b("ATAN[1]"), 45.0));
    assert!(close(b("ATAN[-1]/[-1]"), 225.0)); // two arguments: 0°..360°
    assert!(close(b("ATAN[1,-1]"), 135.0));
    assert!(close(b("ATAN[-1]/[1]"), 315.0));
    assert_eq!(b("SQRT[16]"), Some(4.0));
    assert_eq!(b("ABS[-3.5]"), Some(3.5));
    assert_eq!(b("ROUND[2.5]"), Some(3.0)); // half away from zero
    assert_eq!(b("ROUND[-2.5]"), Some(-3.0));
    assert_eq!(b("ROUND[2.4]"), Some(2.0));
    assert_eq!(b("FIX[1.7]"), Some(1.0));
    assert_eq!(b("FIX[-1.7]"), Some(-1.0)); // toward zero
    assert_eq!(b("FUP[1.2]"), Some(2.0));
    assert_eq!(b("FUP[-1.2]"), Some(-2.0)); // away from zero
    assert_eq!(b("FUP[3]"), Some(3.0));
    assert!(close(b("LN[EXP[1]]"), 1.0));
    assert_eq!(b("EXP[0]"), Some(1.0));
    assert_eq!(b("POW[2,10]"), Some(1024.0));
    assert_eq!(b("POW[-2,3]"), Some(-8.0)); // a whole exponent
    // Functions nest, and take expressions.
    assert!(close(b("SQRT[[3 * 3] + [4 * 4]]"), 5.0));
}

#[test]
fn macro_b_null_rules() {
    // #2 is vacant: a bare reference keeps it, an operation reads it as 0.
    let p = "#2 = #0\n#3 = #2 * 2\n#4 = #2\n#5 = -#2\n#6 = #2 + #2\n\
             #7 = [#2 EQ #0]\n#8 = [#2 EQ 0]\n#9 = [#2 NE 0]\n#10 = [#2 GE #0]\n\
             #11 = [#2 GT 0]\n#12 = [#2 LT 1]\n#13 = SIN[#2]\n#14 = [#0 EQ #0]\nM30\n";
    let (outcome, _, v) = run(
        "fanuc",
        p,
        &[
            "#2", "#3", "#4", "#5", "#6", "#7", "#8", "#9", "#10", "#11", "#12", "#13", "#14",
        ],
    );
    assert!(matches!(outcome, Outcome::Ended(_)), "{outcome:?}");
    let want = [
        None,
        Some(0.0),
        None,
        None,
        Some(0.0),
        Some(1.0), // vacant EQ #0
        Some(0.0), // vacant is not 0
        Some(1.0),
        Some(1.0), // GE reads it as 0: 0 >= 0
        Some(0.0), // 0 > 0
        Some(1.0), // 0 < 1
        Some(0.0),
        Some(1.0),
    ];
    assert_eq!(v, want);
}

#[test]
fn macro_b_vacant_word_is_omitted() {
    // X#2 with #2 vacant is no X word: only Y moves.
    let (outcome, events, _) = run(
        "fanuc",
        "G90 G00 X5. Y1.\n#2 = #0\nX#2 Y7.\nX-#2 Y8.\nM30\n",
        &[],
    );
    assert!(matches!(outcome, Outcome::Ended(_)), "{outcome:?}");
    let ends: Vec<(f64, f64)> = events
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| (p.get(0), p.get(1)))
        .collect();
    assert_eq!(ends, vec![(5.0, 1.0), (5.0, 7.0), (5.0, 8.0)]);
}

#[test]
fn macro_b_errors() {
    assert_eq!(b_alarm("1 / 0"), Code::E608);
    assert_eq!(b_alarm("5 MOD 0"), Code::E608);
    assert_eq!(b_alarm("SQRT[-1]"), Code::E609);
    assert_eq!(b_alarm("LN[0]"), Code::E609);
    assert_eq!(b_alarm("ASIN[2]"), Code::E609);
    assert_eq!(b_alarm("ACOS[-1.5]"), Code::E609);
    assert_eq!(b_alarm("TAN[90]"), Code::E609);
    assert_eq!(b_alarm("ATAN[0]/[0]"), Code::E609);
    assert_eq!(b_alarm("POW[-2,0.5]"), Code::E609);
    assert_eq!(b_alarm("EXP[1000]"), Code::E609); // not finite
    assert_eq!(b_alarm("FOO[1]"), Code::E604);
    assert_eq!(b_alarm("BCD[1]"), Code::E604); // exists, needs the machine
    assert_eq!(b_alarm("[1 + 2"), Code::E601);
    assert_eq!(b_alarm("1 +"), Code::E601);
    assert_eq!(b_alarm("SIN 30"), Code::E601);
    // Five bracket levels (function brackets count) run; six alarm.
    assert_eq!(b("[[[[[1]]]]]"), Some(1.0));
    assert_eq!(b_alarm("[[[[[[1]]]]]]"), Code::E602);
    assert!(close(b("SIN[[[[[30]]]]]"), 0.5));
    assert_eq!(b_alarm("SIN[[[[[[30]]]]]]"), Code::E602);
}

#[test]
fn syntec_long_and_double() {
    assert_eq!(s("1 / 2"), Some(0.0)); // Long / Long truncates
    assert_eq!(s("1. / 2"), Some(0.5));
    assert_eq!(s("1 / 2.0"), Some(0.5));
    assert_eq!(s("(1/2) * 1.0"), Some(0.0)); // the manual's own trap
    assert_eq!(s("(1./2) * 1.0"), Some(0.5));
    assert_eq!(s("-7 / 2"), Some(-3.0)); // toward zero
    assert_eq!(s("7 / -2"), Some(-3.0));
    assert_eq!(s("10 MOD 3"), Some(1.0));
    assert_eq!(s("-7 MOD 3"), Some(-1.0));
    assert_eq!(s("2 + 3 * 4"), Some(14.0));
    assert_eq!(s("(2 + 3) * 4"), Some(20.0));
    assert_eq!(s("[2 + 3] * 4"), Some(20.0));
    assert_eq!(s("7 - 2 - 1"), Some(4.0));
    assert_eq!(s("0xFF AND 0x0F"), Some(15.0));
    assert_eq!(s("0xF0 & 0x3C"), Some(48.0));
    assert_eq!(s("NOT 5"), Some(-6.0)); // -(x+1)
    assert_eq!(s("NOT -1"), Some(0.0));
    assert_eq!(s("-#0"), None);
    // Comparisons give Longs 1/0.
    assert_eq!(s("3 > 2"), Some(1.0));
    assert_eq!(s("3 <= 2"), Some(0.0));
    assert_eq!(s("3 <> 2"), Some(1.0));
}

#[test]
fn syntec_precedence_levels() {
    // < before =: (1 < 2) = 1.
    assert_eq!(s("1 < 2 = 1"), Some(1.0));
    // = before <>: (1 = 1) <> 0.
    assert_eq!(s("1 = 1 <> 0"), Some(1.0));
    // <> before AND: 1 AND (0 <> 0) = 1 AND 0.
    assert_eq!(s("1 AND 0 <> 0"), Some(0.0));
    // AND before XOR before OR: 1 OR (0 AND 0) = 1; (6 XOR 3) OR 8 = 13.
    assert_eq!(s("1 OR 0 AND 0"), Some(1.0));
    assert_eq!(s("6 XOR 3 OR 8"), Some(13.0));
    assert_eq!(s("12 XOR 10 AND 6"), Some(14.0)); // 12 XOR (10 AND 6 = 2)
    // + before <: 1 + 1 < 3.
    assert_eq!(s("1 + 1 < 3"), Some(1.0));
    // Unary minus before *: -2 * 3.
    assert_eq!(s("-2 * 3"), Some(-6.0));
    assert_eq!(s("2 * -3"), Some(-6.0));
}

#[test]
fn syntec_functions() {
    assert_eq!(s("ABS(-2.3)"), Some(2.3));
    assert_eq!(s("ABS(-4)"), Some(4.0));
    assert!(close(s("SIN(90)"), 1.0));
    assert!(close(s("COS(180)"), -1.0));
    assert!(close(s("TAN(45)"), 1.0));
    assert!(close(s("ASIN(-0.5)"), -30.0)); // ±90°
    assert!(close(s("ACOS(-1)"), 180.0));
    assert!(close(s("ATAN(1)"), 45.0));
    assert!(close(s("ATAN2(1, -1)"), 135.0));
    assert!(close(s("ATAN2(-1, -1)"), -135.0)); // ±180°
    assert_eq!(s("SQRT(4)"), Some(2.0));
    assert_eq!(s("POW(16, 0.5)"), Some(4.0));
    assert!(close(s("LN(EXP(2))"), 2.0));
    assert_eq!(s("MAX(10, 20)"), Some(20.0));
    assert_eq!(s("MIN(1.5, 2)"), Some(1.5));
    assert_eq!(s("SIGN(-4)"), Some(-1.0));
    assert_eq!(s("SIGN(0.0)"), Some(0.0));
    assert_eq!(s("ROUND(2.6)"), Some(3.0));
    assert_eq!(s("ROUND(-2.5)"), Some(-3.0));
    assert_eq!(s("CEIL(1.4)"), Some(2.0));
    assert_eq!(s("FLOOR(-1.4)"), Some(-2.0));
    // ROUND gives a Long: ROUND(7.2) / 2 = 7 / 2 = 3.
    assert_eq!(s("ROUND(7.2) / 2"), Some(3.0));
    // STD: a Long in least increments (0.001 mm), a Double as it is.
    assert_eq!(s("STD(100)"), Some(0.1));
    assert_eq!(s("STD(2.5)"), Some(2.5));
    assert_eq!(s("STDAX(1500, X)"), Some(1.5));
    assert_eq!(s("STDAX(90000, A)"), Some(90.0)); // 0.001°
    assert_eq!(s("PARAM(3204)"), None); // no parameter file: vacant
    assert_eq!(s("WAIT()"), None);
}

#[test]
fn syntec_errors() {
    assert_eq!(s_alarm("10. MOD 3"), Code::E610);
    assert_eq!(s_alarm("10 MOD 3.0"), Code::E610);
    assert_eq!(s_alarm("1.5 AND 1"), Code::E610);
    assert_eq!(s_alarm("NOT 1.5"), Code::E610);
    assert_eq!(s_alarm("1 / 0"), Code::E608);
    assert_eq!(s_alarm("1.0 / 0"), Code::E608);
    assert_eq!(s_alarm("POW(-2, 2)"), Code::E609); // negative base (COR-122)
    assert_eq!(s_alarm("ATAN2(0, 0)"), Code::E609);
    assert_eq!(s_alarm("9000000000 * 9000000000 * 9000000000"), Code::E103);
    assert_eq!(s_alarm("900000000 * 900000000 * 900000000"), Code::E609); // Long overflow
    assert_eq!(s_alarm("1 == 1"), Code::E601);
    assert_eq!(s_alarm("READDI(3)"), Code::E604);
    assert_eq!(s_alarm("RANDOM()"), Code::E604);
    assert_eq!(s_alarm("STDAX(1, Q)"), Code::E609);
}

#[test]
fn syntec_vacant_follows_macro_b() {
    let p = "%@MACRO\n#2 := #0;\n@1 := #2 + 1;\n@2 := #2 = #0;\n@3 := #2 = 0;\n@4 := #2 < 1;\n@5 := #2;\nM30;\n";
    let (outcome, _, v) = run("syntec", p, &["@1", "@2", "@3", "@4", "@5"]);
    assert!(matches!(outcome, Outcome::Ended(_)), "{outcome:?}");
    assert_eq!(v, vec![Some(1.0), Some(1.0), Some(0.0), Some(1.0), None]);
}

#[test]
fn values_in_words_read_in_units() {
    // Macro B: a variable is in units (X#1 with #1 = 5 is 5 mm, not 0.005);
    // M#2 is rounded (3.4999 → M03), S#3 too (1000.5 → 1001).
    let p = "#1 = 5\n#2 = 3.4999\n#3 = 1000.5\nG90 G00 X#1 Y[#1 / 2]\nM#2 S#3\nM30\n";
    let (outcome, events, _) = run("fanuc", p, &[]);
    assert!(matches!(outcome, Outcome::Ended(_)), "{outcome:?}");
    let to = events.iter().find_map(Event::motion_end).unwrap();
    assert_eq!((to.get(0), to.get(1)), (5.0, 2.5));
    assert!(
        events
            .iter()
            .any(|e| matches!(e, Event::Spindle { rpm, .. } if *rpm == 1001.0))
    );
    // Syntec: a Long reads like a number without a point (least
    // increments), a Double like one with it.
    let p = "%@MACRO\n#1 := 5;\n#2 := 5.;\nG90 G00 X#1 Y#2;\nM30;\n";
    let (outcome, events, _) = run("syntec", p, &[]);
    assert!(matches!(outcome, Outcome::Ended(_)), "{outcome:?}");
    let to = events.iter().find_map(Event::motion_end).unwrap();
    assert_eq!((to.get(0), to.get(1)), (0.005, 5.0));
}
