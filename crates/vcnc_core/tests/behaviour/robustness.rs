//! Hostile input for the text files `vcnc_core` reads besides programs:
//! tool tables (`--tools`), CAM comments and grbl `$$` dumps
//! (`--machine`). None may panic; a refused file names a line that exists;
//! what is kept stays bounded however large the file.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_core::grbl_settings;
use vcnc_core::tooling::{from_comments, read_table};

/// Runs every reader on `text`; checks that an error names a real line.
fn read_all(text: &str) {
    let lines = u32::try_from(text.lines().count()).unwrap_or(u32::MAX);
    match read_table(text, "t.tbl") {
        Ok(lib) => {
            assert!(!lib.tools.is_empty());
            assert!(lib.tools.len() <= 10_000);
            for t in lib.tools.values() {
                assert!(t.diameter_mm.is_finite() && t.diameter_mm >= 0.0, "{t:?}");
            }
        }
        Err(e) => assert!(e.line <= lines, "line {} of {lines}: {e}", e.line),
    }
    let lib = from_comments(text);
    assert!(lib.tools.len() <= 10_000 && lib.offsets.is_empty());
    for t in lib.tools.values() {
        assert!(t.diameter_mm.is_finite() && t.diameter_mm >= 0.0, "{t:?}");
    }
    if let Err(e) = grbl_settings::machine(text, "dump.txt") {
        assert!(e.line <= lines, "line {} of {lines}: {e}", e.line);
    }
}

#[test]
fn hostile_tables_and_dumps_are_refused_or_read() {
    let long = "T1 D".to_string() + &"9".repeat(100_000);
    let many: String = (1..=10_001).map(|n| format!("T{n} D1\n")).collect();
    let many_csv: String = std::iter::once("tool,diameter\n".to_string())
        .chain((1..=10_001).map(|n| format!("{n},1\n")))
        .collect();
    let cases: Vec<String> = vec![
        String::new(),
        "\u{feff}T1 D6\r\n".into(),
        "T1 D6\0\n".into(),
        "T99999999999999999999 D1\n".into(),
        "T1 D1e-400\n".into(),
        "T1 D+-5\n".into(),
        "T1 D.\n".into(),
        "T1 Q-1\n".into(),
        "T1 D6 T2\n".into(),
        "T\n".into(),
        ";;;;\n;\n".into(),
        "tool,diameter\n".into(),
        "tool,diameter\n1,\n".into(),
        "tool,diameter\n,,,,,\n".into(),
        "tool,diameter,corner_radius\n1,0,0\n2,1e308,0\n".into(),
        "tool\n1\n".into(),
        long.clone(),
        many,
        many_csv,
        "(T1 D=1e308 CR=0. - x)\n(T2 D=-5 CR=0)\n(T3 D=NaN)\n".into(),
        "(TOOL/MILL,1,2,3,4,5,6,7)\n(TOOL/MILL,)\n(TOOL/MILL,-1,0,0,0)\nM6T1\n".into(),
        "(TOOL/MILL,1,0,1e300,89.9999)\nT1\n".into(),
        "((((((T1 D=6. CR=0. - flat end mill\n".into(),
        "(Required tools:)\n".repeat(1000),
        "(Tools used in this file: )\n(99999999999 = End Mill {6 mm})\n(1 = {} {} {})\n".into(),
        "(T1|||||||)\n(TOOL - DIA. - )\n(TOOL -  99999999999999 DIA. - 1)\n".into(),
        "$$\n".into(),
        "$100=\n".into(),
        "$=5\n".into(),
        "$100=1e7\n$110=1e8\n".into(),
        format!("$100={}\n", "1".repeat(300)),
        "Grbl 1.1h\n$110=500\n$111=500\n$112=500\n$120=10\n$121=10\n$122=10\n$130=-5\n".into(),
        (0..3000).map(|n| format!("${n}=1\n")).collect(),
    ];
    for c in &cases {
        read_all(c);
    }
    // A table that lists too many tools stops with a line, not memory.
    let e = read_table(&cases[17], "many.tbl").unwrap_err();
    assert_eq!(e.line, 10_001, "{e}");
    assert!(
        read_table(&long, "long.tbl")
            .unwrap_err()
            .message
            .contains("bytes long")
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Arbitrary bytes, read as text the way the CLI reads a file.
    #[test]
    fn arbitrary_text_never_panics(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        read_all(&String::from_utf8_lossy(&bytes));
    }

    /// Lines built from the words these files use, in any order.
    #[test]
    fn shuffled_table_words_never_panic(words in proptest::collection::vec(
        prop_oneof![
            Just("T1"), Just("T0"), Just("D6"), Just("D-1"), Just("Z1e3"), Just("Q9"),
            Just("Q10"), Just(";c"), Just("\n"), Just(","), Just("tool"), Just("diameter"),
            Just("units"), Just("in"), Just("$110=5"), Just("$120=1"), Just("("), Just(")"),
            Just("TOOL/MILL,"), Just("T1 D="), Just("CR="), Just(" - "), Just("1/4\""),
            Just("{6 mm}"), Just("="), Just("|"), Just("DIA. -"), Just("M6T2"),
        ],
        0..80,
    )) {
        read_all(&words.join(" "));
    }
}
