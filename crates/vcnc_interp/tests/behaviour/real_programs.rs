//! Constructs that real programs of the corpus (`corpus/`) use and a
//! controller of their dialect accepts; each test names the program that
//! showed it and works out the expected motion by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Outcome};

use crate::common;

use common::{run_str as run, xs};

/// `:0097` heads `corpus/mill-fanuc/gcodeworkshop-FANUC0M.nc` and
/// `:0100( FLANGE OP.2 )` the Fanuc 0T lathe program beside it: in ISO
/// code the colon is the program number's O, on the mill, the Haas mill
/// and the Fanuc lathe. The program then runs as `O0097` would: one rapid
/// to X1. (a radius of 0.5 on the lathe, which reads X as a diameter).
#[test]
fn a_colon_is_the_program_numbers_o_in_the_fanuc_dialects() {
    let program = ":0097 (FANUC 0M)\nG0 X1.\nM30\n";
    for dialect in [Dialect::fanuc(), Dialect::haas(), Dialect::fanuc_lathe()] {
        let (ev, out) = run(&dialect, program);
        assert!(
            matches!(out, Outcome::Ended(_)),
            "{}: {out:?}",
            dialect.name
        );
        let x = if dialect.name == "fanuc-lathe" {
            0.5
        } else {
            1.0
        };
        assert_eq!(xs(&ev), vec![x], "{}", dialect.name);
        let o = run(&dialect, &program.replacen(':', "O", 1)).0;
        assert_eq!(ev, o, "{}", dialect.name);
    }
    // Syntec's manual does not name it: still an illegal character.
    let (ev, out) = run(&Dialect::syntec(), program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line, d.column), ("E101", 1, 1));
    assert!(!ev.iter().any(|e| matches!(e, Event::Rapid { .. })));
}

/// Ends of the feeds (drilling-axis levels) and the holes' X, in order.
fn feeds_and_holes(ev: &[Event]) -> Vec<String> {
    ev.iter()
        .filter_map(|e| match e {
            Event::Hole { at, .. } => Some(format!("hole X{}", at.get(0))),
            Event::Feed { to, .. } => Some(format!("Z{}", to.get(2))),
            _ => None,
        })
        .collect()
}

/// `N460 G91 X.480 L6` inside a G82/G83 in `corpus/mill-haas/cadekiely-o78244.nc`:
/// on a Haas, L repeats the cycle block (incrementally under G91), where
/// Fanuc writes K. Three G81 holes 1 mm apart from X0, each a feed from R
/// (10 − 8 = 2) to Z = 2 − 5 = −3.
#[test]
fn haas_repeats_a_cycle_block_by_l() {
    let program = "G0 X0 Y0 Z10.\nS1000 M3\nG91 G81 X1. Y0 Z-5. R-8. F100. L3\nG80\nM30\n";
    let (ev, out) = run(&Dialect::haas(), program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(
        feeds_and_holes(&ev),
        ["hole X1", "Z-3", "hole X2", "Z-3", "hole X3", "Z-3"]
    );
    // An M98 beside a hole takes its L: the call repeats, the hole not (the
    // hole at X5, then O2000's G91 X1. twice in the cycle: X6, X7).
    let call = "G0 X0 Y0 Z10.\nS1000 M3\nG81 X0 Z-3. R2. F100.\nX5. M98 P2000 L2\nG80\nM30\n\
                O2000\nG91 X1.\nG90\nM99\n";
    let (ev, out) = run(&Dialect::haas(), call);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let holes: Vec<String> = feeds_and_holes(&ev)
        .into_iter()
        .filter(|h| h.starts_with("hole"))
        .collect();
    assert_eq!(holes, ["hole X0", "hole X5", "hole X6", "hole X7"]);
    // K is Fanuc's repeat count, and in G81 no Haas word.
    let (_, out) = run(&Dialect::haas(), &program.replace("L3", "K3"));
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line), ("E203", 3));
}

/// Haas G83 I J K (the manual: "the first pass will cut in by I, each
/// succeeding cut will be reduced by amount J, and the minimum cutting
/// depth is K"): from R 2 to Z −10 with I4 J1 K1.5 the pecks are 4, 3, 2,
/// 1.5 and 1.5 mm, ending at −2, −5, −7, −8.5 and −10; the next hole keeps
/// them. A later block may change them; all three go together.
#[test]
fn haas_g83_pecks_less_each_time_by_i_j_k() {
    let program = "G0 X0 Y0 Z10.\nS1000 M3\nG83 X1. Y1. Z-10. R2. I4. J1. K1.5 F100.\nX5.\n\
                   X6. I3. J1. K1.\nG80\nM30\n";
    let (ev, out) = run(&Dialect::haas(), program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let pecks = ["Z-2", "Z-5", "Z-7", "Z-8.5", "Z-10"];
    let mut expected = vec!["hole X1"];
    expected.extend(pecks);
    expected.push("hole X5");
    expected.extend(pecks);
    // 3, 2, 1, 1, 1, 1 mm: −1, −3, −4, −5, … −10.
    expected.extend([
        "hole X6", "Z-1", "Z-3", "Z-4", "Z-5", "Z-6", "Z-7", "Z-8", "Z-9", "Z-10",
    ]);
    assert_eq!(feeds_and_holes(&ev), expected);
    let (_, out) = run(&Dialect::haas(), &program.replace(" K1.5", ""));
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line), ("E312", 3));
    // A Q in a later block replaces them (2 mm each from R 2); in their own
    // block I, J, K win (the manual's "different operating mode").
    let later = "G0 X0 Y0 Z10.\nS1000 M3\nG83 X0 Z-10. R2. I6. J1. K1. F100.\nX5. Q2.\n\
                 X6. Q2. I6. J1. K1.\nG80\nM30\n";
    let (ev, out) = run(&Dialect::haas(), later);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let reduced = ["Z-4", "Z-9", "Z-10"];
    let mut expected = vec!["hole X0"];
    expected.extend(reduced);
    expected.extend(["hole X5", "Z0", "Z-2", "Z-4", "Z-6", "Z-8", "Z-10"]);
    expected.push("hole X6");
    expected.extend(reduced);
    assert_eq!(feeds_and_holes(&ev), expected);
    // With J0 the pecks stay I long: a tiny K is no reason to count
    // millions of pecks (E326).
    let (ev, out) = run(
        &Dialect::haas(),
        "G0 X0 Y0 Z10.\nS1000 M3\nG83 X0 Z-10. R2. I4. J0 K0.0001 F100.\nM30\n",
    );
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(feeds_and_holes(&ev), ["hole X0", "Z-2", "Z-6", "Z-10"]);
}

/// `G04 P3. (WAIT FOR TAILSTOCK)` (`corpus/lathe-haas/cadekiely-O58214.nc`):
/// on a Haas a P with a point is seconds, without one milliseconds; Fanuc
/// and Syntec keep P whole milliseconds and alarm E108 on the point.
#[test]
fn haas_reads_a_dwell_p_with_a_point_as_seconds() {
    let dwells = |ev: &[Event]| -> Vec<f64> {
        ev.iter()
            .filter_map(|e| match e {
                Event::Dwell { seconds, .. } => Some(*seconds),
                _ => None,
            })
            .collect()
    };
    let (ev, out) = run(&Dialect::haas(), "G04 P3.\nG04 P250\nM30\n");
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(dwells(&ev), [3.0, 0.25]);
    for dialect in [Dialect::fanuc(), Dialect::syntec()] {
        let (_, out) = run(&dialect, "G04 P3.\nM30\n");
        let Outcome::Alarm(d) = out else {
            panic!("{out:?}")
        };
        assert_eq!(d.code.as_str(), "E108", "{}", dialect.name);
    }
}

/// `N40 IF [ #5405 GE 6000 ] THEN #3000= 15 ( TOOL LIFE EXPIRED )`
/// (`corpus/mill-haas/gcodeworkshop-HAAS.nc`): Haas's tool-life timers,
/// #5401–#6000, read 0 on a machine whose tools have not cut yet (or what
/// the program wrote there), so the check passes and the program goes on
/// to its rapid. Fanuc has no such variables: E605.
#[test]
fn haas_tool_life_timers_read_zero() {
    // X is #5999 + 1 so that the rapid moves (from the origin) and shows.
    let program =
        "IF [#5405 GE 6000] THEN #3000=15 (TOOL LIFE EXPIRED)\n#1=#5999\nG0 X[#1+1.]\nM30\n";
    let (ev, out) = run(&Dialect::haas(), program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(xs(&ev), vec![1.0]);
    // A program may set a limit or reset a counter, and reads it back.
    let (ev, out) = run(&Dialect::haas(), "#5701=7.\nG0 X#5701\nG0 X#5702\nM30\n");
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(xs(&ev), vec![7.0, 0.0]);
    let (_, out) = run(&Dialect::fanuc(), program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line), ("E605", 1));
}

/// The one-block G74/G75/G76 of Haas lathes and Fanuc's FS15 tape format
/// (`G75 X.800 Z-.325 I0.1 K0.2 F0.0002` in
/// `corpus/lathe-haas/cadekiely-Lathe-L8-Ex1.nc`, `G76 X0.2 Z-0.25 K0.044
/// D0.01 F0.05` in the thumbscrew program): I, K, D spell the two-block
/// form's P, Q, R for G74/G75, and K, D, I its P (height), Q (first depth),
/// R (taper) for G76, whose A is the tool angle. Each one-block program
/// moves exactly as its two-block twin (same first block, same modal
/// values).
#[test]
fn one_block_g74_g75_g76_move_as_their_two_block_forms() {
    let lathe = Dialect::fanuc_lathe();
    let start = "G21 G18 G99 T0101\nS500 M03\nG00 X40. Z2.\n";
    let pairs = [
        (
            "G75 R0.5\nG75 X20. Z-10. P2000 Q3000 R0.1 F0.1\n",
            "G75 R0.5\nG75 X20. Z-10. I2. K3. D0.1 F0.1\n",
        ),
        (
            "G74 R0.5\nG00 X10. Z2.\nG74 X0 Z-15. P2500 Q4000 F0.1\n",
            "G74 R0.5\nG00 X10. Z2.\nG74 X0 Z-15. I2.5 K4. F0.1\n",
        ),
        (
            "G76 P010060 Q50 R0.01\nG76 X36. Z-20. P1200 Q400 F2.\n",
            "G76 P010060 Q50 R0.01\nG76 X36. Z-20. K1.2 D0.4 F2.\n",
        ),
        (
            "G76 P010060 Q50 R0.01\nG76 X36. Z-20. R-0.5 P1200 Q400 F2.\n",
            "G76 P010030 Q50 R0.01\nG76 X36. Z-20. I-0.5 K1.2 D0.4 A60 F2.\n",
        ),
    ];
    for (two, one) in pairs {
        let (a, out_a) = run(&lathe, &format!("{start}{two}M30\n"));
        let (b, out_b) = run(&lathe, &format!("{start}{one}M30\n"));
        assert!(matches!(out_a, Outcome::Ended(_)), "{two}: {out_a:?}");
        assert!(matches!(out_b, Outcome::Ended(_)), "{one}: {out_b:?}");
        let moves = |ev: &[Event]| -> Vec<String> {
            ev.iter()
                .filter_map(|e| {
                    e.motion_end()
                        .map(|p| format!("{:.6} {:.6}", p.get(0), p.get(2)))
                })
                .collect()
        };
        assert!(moves(&a).len() > 4, "{two}");
        assert_eq!(moves(&a), moves(&b), "{one}");
    }
    // Haas's Q in the one-block G76 is the thread's start angle: the
    // spindle's phase, not the path.
    let (a, _) = run(
        &lathe,
        &format!("{start}G76 X36. Z-20. K1.2 D0.4 F2.\nM30\n"),
    );
    let (b, out) = run(
        &lathe,
        &format!("{start}G76 X36. Z-20. K1.2 D0.4 Q180000 F2.\nM30\n"),
    );
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    assert_eq!(xs(&a), xs(&b));
    // Both spellings in one block, the two-block words beside K/D, the
    // one-block words in a first block (no X/Z) and the one-block words in
    // a two-block second block alarm, naming the two forms; so does an
    // infeed other than P1.
    for (bad, code, says) in [
        ("G75 X20. Z-10. P2000 I2. K3. F0.1\n", "E203", "same value"),
        (
            "G76 X36. Z-20. K1.2 D0.4 R0.1 F2.\n",
            "E203",
            "two-block form",
        ),
        ("G76 K1.2 D0.4 F2.\n", "E203", "one-block form"),
        ("G75 R0.5 I2. K3. D0.1\n", "E203", "one-block form"),
        (
            "G76 X36. Z-20. P1200 Q400 A60 F2.\n",
            "E203",
            "one-block form",
        ),
        ("G76 X36. Z-20. K1.2 D0.4 P2 F2.\n", "E314", "only P1"),
        ("G76 X36. Z-20. K-1.2 D0.4 F2.\n", "E109", "more than 0"),
    ] {
        let (_, out) = run(&lathe, &format!("{start}{bad}M30\n"));
        let Outcome::Alarm(d) = out else {
            panic!("{bad}: {out:?}")
        };
        assert_eq!((d.code.as_str(), d.line), (code, 4), "{bad}: {d:?}");
        assert!(d.message.contains(says), "{bad}: {}", d.message);
    }
}

/// `--dialect haas-lathe`: the Fanuc lathe with the Haas rules the mill
/// has. `G04 P3. (WAIT FOR TAILSTOCK)` (`corpus/lathe-haas/cadekiely-O58214.nc`)
/// waits 3 s, the tool-life variables read 0; under fanuc-lathe both
/// alarm (E108, E605). The lathe's own reading stays: X is a diameter.
#[test]
fn the_haas_lathe_dialect_is_the_fanuc_lathe_with_haas_rules() {
    let program = "G04 P3.\nG00 X[#5401 + 20.] Z2.\nM30\n";
    let haas = Dialect::by_name("haas-lathe").expect("haas-lathe");
    let (ev, out) = run(&haas, program);
    assert!(matches!(out, Outcome::Ended(_)), "{out:?}");
    let dwell: Vec<f64> = ev
        .iter()
        .filter_map(|e| match e {
            Event::Dwell { seconds, .. } => Some(*seconds),
            _ => None,
        })
        .collect();
    assert_eq!(dwell, [3.0]);
    assert_eq!(xs(&ev), vec![10.0]);
    let (_, out) = run(&Dialect::fanuc_lathe(), program);
    let Outcome::Alarm(d) = out else {
        panic!("{out:?}")
    };
    assert_eq!((d.code.as_str(), d.line), ("E108", 1));
}
