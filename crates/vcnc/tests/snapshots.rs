//! Snapshots of what a person reads: rendered alarms (stderr) and `check`
//! summaries (stdout), kept in `tests/snapshots/` so that a change to the
//! wording or layout shows in review. Each snapshot was read against the
//! program it comes from when it was accepted.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

/// Runs `vcnc args…` on a program written to a temporary file; returns
/// exit code, stdout and stderr with the temporary path replaced.
fn vcnc_on(name: &str, program: &str, args: &[&str]) -> String {
    let dir = std::env::temp_dir().join(format!("vcnc_snap_{}_{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.nc"));
    std::fs::write(&file, program).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .arg(&file)
        .current_dir(workspace())
        .env("NO_COLOR", "1")
        .output()
        .expect("vcnc runs");
    let shown = file.display().to_string();
    let text = format!(
        "exit {}\n--- stdout\n{}--- stderr\n{}",
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
    text.replace(&shown, &format!("{name}.nc"))
}

#[test]
fn alarm_arc_end_off_the_circle() {
    insta::assert_snapshot!(vcnc_on(
        "arc",
        "G90 G00 X5.5 Y4.\nG17 G90 G03 X1.5 Y4. I-3. J-1. F200.;\nM30\n",
        &["check"]
    ));
}

#[test]
fn alarm_over_travel_points_at_the_axis_word() {
    insta::assert_snapshot!(vcnc_on(
        "travel",
        "S1000 M03\nG00 X10. Y10.\nG01 X20. Y1200. F500.\nM30\n",
        &[
            "check",
            "--machine",
            "tests/fixtures/machines/mill_travel_limits.toml"
        ]
    ));
}

#[test]
fn alarm_scale_factor_zero() {
    insta::assert_snapshot!(vcnc_on(
        "scale",
        "G00 X10. Y10.\nG51 X0. Y0. P0\nM30\n",
        &["check"]
    ));
}

/// Under Syntec, G21 is no code: the hint names the dialects that know it
/// and how each reads an integer. (Without `--dialect` the program runs:
/// detection reads G21 as a Fanuc-family program's.)
#[test]
fn alarm_unknown_code_names_the_dialect_that_has_it() {
    insta::assert_snapshot!(vcnc_on(
        "g21",
        "G21 G00 X1.\nM30\n",
        &["check", "--dialect", "syntec"]
    ));
}

#[test]
fn check_summary_with_tool_length_and_rotation() {
    insta::assert_snapshot!(vcnc_on(
        "frames",
        "T1 M06\nS1000 M03\nG00 X0. Y0. Z20.\nG43 H1 Z10.\nG68 X0. Y0. R90.\nG01 X10. Y0. F300.\nG02 X0. Y-10. R10.\nG69 G49\nG00 Z50.\nM30\n",
        &["check"]
    ));
}

#[test]
fn check_summary_of_a_lathe_program() {
    insta::assert_snapshot!(vcnc_on(
        "lathe",
        "G0 X45 Z130\nG81 X40 Z100 R15 I-3 K-1 F100\nM02\n",
        &["check", "--dialect", "lathe"]
    ));
}

#[test]
fn warnings_are_rendered_and_counted() {
    // A point-less length among pointed ones (under Syntec's least
    // increments: detection would read it in whole units), a cut with the
    // spindle stopped, an unknown M code and no program end.
    insta::assert_snapshot!(vcnc_on(
        "warn",
        "G90 G00 X10. Y10.\nG01 X20 F500.\nM31\n",
        &["check", "--dialect", "syntec"]
    ));
}

/// The trap: a grbl program (no decimal points) forced through
/// Fanuc is a 0.020 mm half circle; W109 says so and names the readings
/// in whole units. Without `--dialect` it is read as grbl, 20 mm.
#[test]
fn whole_units_under_least_increments_warn() {
    let program = "G21 G90\nM3 S1000\nG0 X0 Y0\nG2 X20 Y0 I10 J0 F100\nM30\n";
    insta::assert_snapshot!(vcnc_on("trap", program, &["check", "--dialect", "fanuc"]));
    insta::assert_snapshot!(vcnc_on("trap", program, &["check"]));
}
