//! `--dialect auto`: one program per dialect, written the way its
//! controllers' programs are (headers, codes, number styles of real posts),
//! with the dialect detection must choose and the evidence it must give;
//! the low-confidence case; the bounded prefix; arbitrary bytes; and E201's
//! hint, which names every dialect that knows a code and how each reads an
//! integer.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use vcnc_interp::Dialect;
use vcnc_interp::detect::{Confidence, Detection, PREFIX_BYTES, detect, g_hint};

/// Detection of `text` as a file called `name`: the dialect, and each of
/// `evidence` among its evidence.
fn chosen(text: &str, name: &str, dialect: &str, evidence: &[&str]) -> Detection {
    let d = detect(text.as_bytes(), Some(name));
    assert_eq!(d.dialect, dialect, "{}", d.describe());
    for e in evidence {
        assert!(
            d.evidence.iter().any(|x| x == e),
            "{e:?} not in {:?}",
            d.evidence
        );
    }
    d
}

#[test]
fn haas_by_its_codes_and_its_header() {
    let d = chosen(
        "%\nO01001 (BRACKET)\n(HAAS VF2)\nG20\nG00 G17 G40 G49 G80 G90\nT1 M06\n\
         G187 P2 E0.002\nG00 G54 X1. Y1. S6000 M03\nG43 H01 Z1.\nG01 Z-0.1 F20.\n\
         G28 G91 Z0.\nG90\nM30\n%\n",
        "O01001.nc",
        "haas",
        &["G187", "\"(HAAS VF2)\" header"],
    );
    assert_eq!(d.confidence, Confidence::High);
    assert_eq!(d.describe(), "auto: G187, \"(HAAS VF2)\" header");
    // M97 (a local subprogram) and a bare G28 (every axis home on a Haas,
    // an alarm on a Fanuc) say Haas without a header.
    chosen(
        "%\nO1\nG20 G90\nG28\nT1 M06\nM97 P100\nM30\nN100 G00 X1. Y1.\nM99\n%\n",
        "o1.nc",
        "haas",
        &["M97"],
    );
}

#[test]
fn fanuc_from_a_fanuc_post() {
    let d = chosen(
        "%\nO1001 (PLATE)\n(T1 D=10. CR=0. - ZMIN=-5. - FLAT END MILL)\nN10 G90 G94 G17\n\
         N15 G21\nN20 G53 G0 Z0.\nN25 T1 M6\nN30 S8000 M3\nN35 G54\nN40 M8\n\
         N45 G0 X-6. Y-6.\nN50 G43 Z15. H1\nN55 G0 Z5.\nN60 G1 Z-2. F300.\nN65 X56.\n\
         N70 G28 G91 Z0.\nN75 G90\nN80 M30\n%\n",
        "1001.nc",
        "fanuc",
        &["G21"],
    );
    assert_eq!(d.confidence, Confidence::High);
    // Tape format: integers in least increments (X25000 is 25 mm).
    chosen(
        "O0001\nG90 G00 X25000 Y10000\nG01 Z-5000 F200\nX50000\nM30\n",
        "O0001",
        "fanuc",
        &["least-increment integers (X25000)"],
    );
}

#[test]
fn syntec_by_its_units_codes_and_its_macro_files() {
    chosen(
        "// bracket, Syntec 900M\nG17 G71 G90 G40;\nG00 X0. Y0.;\nG01 X10. F300.;\nM30;\n",
        "bracket.nc",
        "syntec",
        &["G71"],
    );
    chosen(
        "%@MACRO\n#1 := 10;\nG00 X#1;\nM30;\n",
        "O1000",
        "syntec",
        &["%@MACRO"],
    );
}

#[test]
fn grbl_from_hobby_cam() {
    chosen(
        ";Project 0102\n;Created by Estlcam version 11\nG90\nM03 S24000\n\
         G00 X0.0000 Y0.0000 Z0.0000\nG00 Z2.0000\nG01 Z-1 F300\nG01 X20 Y10 F1000\nM05\n",
        "crown.gcode",
        "grbl",
        &["\";Created by Estlcam version 11\" header"],
    );
    // A `$` line is a grbl system command.
    chosen(
        "$H\nG21 G90\nG0 X10 Y10\nM3 S1000\nG1 X20 F500\nM5\n",
        "job.nc",
        "grbl",
        &["\"$H\" line"],
    );
    // Laser output: M4 with the power on every move, no Z.
    chosen(
        "G21\nG90\nM4 S0\nG0 X10 Y10\nG1 X20 S500 F1000\nG1 Y20 S500\nG1 X10 S500\nG1 Y10 S500\nM5\n",
        "logo.nc",
        "grbl",
        &["laser M4 with S on moves"],
    );
}

#[test]
fn linuxcnc_by_its_words_and_its_extension() {
    chosen(
        "#<depth> = -2\no<hole> sub\n  G81 X#1 Y#2 Z#<depth> R1\no<hole> endsub\n\
         G21 G90\no<hole> call [10] [10]\nM2\n",
        "holes.nc",
        "linuxcnc",
        &["o<name> sub", "#<depth>"],
    );
    // G64 P (a path tolerance) and LinuxCNC's (MSG, …) comments.
    chosen(
        "G21 G64 P0.01\n(MSG, insert the 6 mm cutter)\nM0\nG0 X0 Y0 Z5\nG1 Z-1 F100\nM2\n",
        "part.nc",
        "linuxcnc",
        &["G21 G64 P", "\"(MSG,\" comments"],
    );
    // LinuxCNC's own extension (the documented rule).
    chosen(
        "G21 G90\nG0 X0. Y0.\nG1 X10. F100.\nM2\n",
        "part.ngc",
        "linuxcnc",
        &[".ngc file"],
    );
}

#[test]
fn lathes_by_their_signs() {
    // Fanuc's two-block G71 U R, its turret T0101, G50 S.
    chosen(
        "%\nO0358\nG21 G18 G99\nT0101\nG50 S2500\nG96 S200 M03\nG00 X52. Z2.\n\
         G71 U2. R0.5\nG71 P10 Q20 U0.4 W0.1 F0.25\nN10 G00 X20.\nG01 Z-20.\nX40. Z-30.\n\
         N20 X52.\nG70 P10 Q20\nG28 U0 W0\nM30\n%\n",
        "O0358.nc",
        "fanuc-lathe",
        &["two-block G71 U R"],
    );
    // A Fanuc lathe program in G-code system B: G77 is its turning cycle.
    chosen(
        "%\nO0024\nG21 G90 G95\nG92 S2000\nG97 S500 M03\nG00 X30. Z2.\n\
         G77 X20. Z-20. F0.2\nX16.\nG00 X50. Z50.\nM30\n%\n",
        "O0024.nc",
        "fanuc-lathe",
        &["G77 cycle (Fanuc lathe G-code system B: set gcode_system = \"B\" in the machine file)"],
    );
    // Haas's one-block G71 with D and its G76 with K and D.
    chosen(
        "%\nO2003\nG00 G18 G20 G40 G80 G99\nT101\nG50 S3000\nG96 S900 M03\nG00 X1.6 Z0.1\n\
         G71 P10 Q20 U0.02 W0.01 D.05 F0.008\nN10 G00 X0.5\nG01 Z-1.\nN20 X1.6\n\
         G76 X0.4069 Z-1.5 K0.043 D0.0107 F0.0769\nM30\n%\n",
        "valve.nc",
        "haas-lathe",
        &["one-block G71 with D"],
    );
    // X and Z with A indexing alone (`G0 A180.`), or turning through many
    // angles: a mill's rotary (4th-axis) program, not a lathe's — no lathe
    // dialect has an A axis (the built-in lathes would alarm E203 at the
    // first A word).
    let lathes = ["lathe", "fanuc-lathe", "haas-lathe", "linuxcnc-lathe"];
    for program in [
        &b"G21 G90 G94\nT1 M6\nS6000 M3\nG0 A0.\nG0 X0. Z5.\nG1 Z-2. F200.\nG1 X40.\n\
           G0 Z5.\nG0 A180.\nG0 X0.\nG1 Z-2.\nG1 X40.\nG0 Z25.\nM30\n"[..],
        &b"G21 G90\nG0 X0 A0 Z5\nG1 Z0 F300\nG1 X10 A30\nG1 X20 A60\nG1 X30 A90\n\
           G1 X40 A120\nG1 X50 A150\nG1 X60 A180\nG1 X70 A210\nG0 Z5\nM2\n"[..],
    ] {
        let d = detect(program, Some("wrap.nc"));
        assert!(!lathes.contains(&d.dialect), "{}", d.describe());
    }
    // A few angles beside X or Z are a contour's (Fanuc's direct drawing
    // input): still a lathe program, and the angles are not lengths.
    let d = detect(
        b"O0011\nG00 X42. Z2.\nG01 Z0 F0.2\nX20.\nX30. A150\nZ-30. A180\nX40. A120\nZ-50.\n\
          G00 X100. Z100.\nM30\n",
        Some("dd.nc"),
    );
    assert!(lathes.contains(&d.dialect), "{}", d.describe());
    assert!(
        !d.evidence.iter().any(|e| e.contains("(A")),
        "{}",
        d.describe()
    );
    // Whole degrees beside pointed lengths (`A2` after `X2.3097`): written
    // for a control that reads A2 as 2°, not 0.002°.
    let d = detect(
        b"G90 G20\nM03\nS776\nG00 X1.899 A0 Z1.12\nG01 Z0.2229 F45.0177\nX2.3097 Z0.2014\n\
          G00 Z1.12\nA2\nG01 Z0.2229\nX2.3283 Z0.2071\nG00 Z1.12\nA4\nG01 Z0.2229\nM30\n",
        Some("shaft.nc"),
    );
    assert!(
        d.evidence
            .iter()
            .any(|e| e.contains("whole-unit integers (A")),
        "{}",
        d.describe()
    );
    // LinuxCNC's lathe mode: G18, X and Z only (G7, diameters, the mill
    // mode reads too).
    chosen(
        "G7 G18 G21 ; diameter mode\nT1 M6\nG0 X20 Z2\nG1 Z-10 F100\nX30\nM2\n",
        "turn.nc",
        "linuxcnc-lathe",
        &["X and Z only"],
    );
    // The seed lathe: CR= arcs, whole-unit integers, G70/G71 units.
    chosen(
        "G71\nG00 X40 Z5\nG01 Z-20 F100\nG02 X60 Z-30 CR=10\nG00 X100\nM30\n",
        "turn.nc",
        "lathe",
        &["\"CR=\""],
    );
}

#[test]
fn eia_by_its_pocket_cycles() {
    chosen(
        "G70 G90\nT1 M06\nS1200 M03\nG00 X0 Y0 Z20.\n\
         G78 X50. Y50. Z-3. R2. I34. J26. K9. P1. F300.\nM30\n",
        "pocket.nc",
        "eia",
        &["G78"],
    );
}

/// Conflicting evidence: L repeats a cycle on Haas and LinuxCNC (not on
/// Fanuc), the `%` and O number are industrial, the units and decimals
/// say nothing more — and the two read the cycle differently.
#[test]
fn a_close_call_says_so() {
    let d = detect(
        b"%\nO1\nG20\nG0 X1. Y1.\nG81 X1. Y1. Z-.5 R.1 F10. L2\nG80\nM30\n%\n",
        Some("o1.nc"),
    );
    assert_eq!(d.dialect, "haas", "{}", d.describe());
    assert_eq!(d.confidence, Confidence::Low);
    assert_eq!(d.runner_up, Some("linuxcnc"));
    assert!(
        d.describe().starts_with("auto, low confidence: "),
        "{}",
        d.describe()
    );
    assert!(
        d.describe().ends_with("; next: linuxcnc"),
        "{}",
        d.describe()
    );
}

/// Only the first [`PREFIX_BYTES`] are read: a Haas code further on is not
/// seen, so the cost does not grow with the file, and the answer does not
/// depend on how much of it a reader happened to read.
#[test]
fn only_the_prefix_is_read() {
    let mut text = String::from("%\nO1\nG21 G90\n");
    while text.len() < PREFIX_BYTES + 100 {
        text.push_str("G01 X10.5 Y20.25 F500.\n");
    }
    let before = detect(text.as_bytes(), Some("long.nc"));
    text.push_str("G187 P1\nM30\n");
    let after = detect(text.as_bytes(), Some("long.nc"));
    assert_eq!(before, after);
    assert_eq!(after.dialect, "fanuc", "{}", after.describe());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any bytes: a dialect that exists, the same answer twice.
    #[test]
    fn any_bytes_get_a_dialect(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
        let a = detect(&bytes, Some("x.nc"));
        prop_assert!(Dialect::NAMES.contains(&a.dialect));
        prop_assert_eq!(&a, &detect(&bytes, Some("x.nc")));
    }

    /// G-code-like noise (letters, numbers, comments, `;`, `#`, `[`, `$`).
    #[test]
    fn any_gcode_like_text_gets_a_dialect(
        lines in proptest::collection::vec("[GMXYZIJKRPQLDUWTSFNO%$#<>\\[\\]();:=/ .0-9a-z-]{0,40}", 0..40)
    ) {
        let text = lines.join("\n");
        let a = detect(text.as_bytes(), None);
        prop_assert!(Dialect::NAMES.contains(&a.dialect));
    }
}

#[test]
fn e201_hint_names_every_dialect_that_knows_the_code_and_its_reading() {
    // Syntec does not know G21: Fanuc and Haas read integers as Syntec
    // does; grbl and LinuxCNC read them as whole units, and the hint says
    // so rather than change the program's units unsaid.
    let h = g_hint(&Dialect::syntec(), 21.0);
    assert_eq!(
        h,
        "G21 is a code of fanuc, haas (which read X20 as 0.020 mm, as syntec does) and of grbl, linuxcnc, mach3 (which read X20 as 20 mm): choose by how the program writes lengths, or leave --dialect out and vcnc chooses from the program"
    );
    // grbl has no canned cycles: never sent to fanuc without the warning
    // that its integers would become micrometres.
    let h = g_hint(&Dialect::grbl(), 81.0);
    assert!(h.starts_with("G81 is a code of linuxcnc, mach3 (which read X20 as 20 mm, as grbl does) and of syntec, fanuc, eia, haas (which read X20 as 0.020 mm)"), "{h}");
    // All alike: a plain suggestion.
    assert_eq!(
        g_hint(&Dialect::fanuc(), 70.0),
        "G70 is a code of syntec, eia: run with --dialect syntec, or leave --dialect out and vcnc chooses from the program"
    );
    // A lathe program is pointed at lathes only, of its own `;` family.
    let h = g_hint(&Dialect::lathe(), 18.0);
    assert!(h.starts_with("G18 is a code of "), "{h}");
    assert!(h.contains("fanuc-lathe") && !h.contains("fanuc,"), "{h}");
    assert!(!h.contains("linuxcnc-lathe"), "another `;` family: {h}");
    // Haas's and Mach3's circular pocket, read two ways.
    assert_eq!(
        g_hint(&Dialect::fanuc(), 12.0),
        "G12 is a code of haas (which read X20 as 0.020 mm, as fanuc does) and of mach3 (which read X20 as 20 mm): choose by how the program writes lengths, or leave --dialect out and vcnc chooses from the program"
    );
    // Nobody knows G14.
    assert_eq!(
        g_hint(&Dialect::fanuc(), 14.0),
        "check the code against the controller's G-code list"
    );
}
