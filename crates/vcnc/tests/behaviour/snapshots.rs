//! Snapshots of what a person reads: rendered alarms (stderr) and `check`
//! summaries (stdout), kept in `tests/behaviour/snapshots/` so that a change to the
//! wording or layout shows in review. Each snapshot was read against the
//! program it comes from when it was accepted.

use crate::common::{TempDir, vcnc};
use std::process::Output;

/// What a person reads of a run: exit code, stdout, stderr.
fn shown(o: &Output) -> String {
    format!(
        "exit {}\n--- stdout\n{}--- stderr\n{}",
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Runs `vcnc args…` on a program written to a temporary file; returns
/// exit code, stdout and stderr with the temporary path replaced.
fn vcnc_on(name: &str, program: &str, args: &[&str]) -> String {
    let dir = TempDir::new("snap");
    let file = dir.write(&format!("{name}.nc"), program);
    let path = file.display().to_string();
    let mut all = args.to_vec();
    all.push(&path);
    shown(&vcnc(&all)).replace(&path, &format!("{name}.nc"))
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

/// Runs `vcnc args…` in the repository root on its own files.
fn vcnc_args(args: &[&str]) -> String {
    shown(&vcnc(args))
}

/// `vcnc tools` on a Fusion program of the corpus: the shape from its
/// header comment, the registers of the built-in machine (empty).
#[test]
fn tools_of_a_fusion_program() {
    insta::assert_snapshot!(vcnc_args(&[
        "tools",
        "--dialect",
        "fanuc",
        "corpus/mill-fanuc/jobline-issue-3-fusion-g18.nc",
    ]));
}

/// `vcnc tools --tools mill.tbl`: T1 and T2 from the table (shape and
/// registers), T5 described by nothing, T7 and T12 listed but not used.
#[test]
fn tools_with_a_linuxcnc_table() {
    insta::assert_snapshot!(vcnc_on(
        "tbl",
        "G21 G90 G17\nT1 M6\nG43 H1 Z50.\nT5 M6\nG0 X10.\nT2 M6\nT1 M6\nM30\n",
        &[
            "tools",
            "--dialect",
            "fanuc",
            "--tools",
            "tests/fixtures/tools/mill.tbl"
        ]
    ));
}

/// `vcnc tools --format json` on Carbide Create output (CutViewer lines).
#[test]
fn tools_json_of_carbide_create_output() {
    insta::assert_snapshot!(vcnc_args(&[
        "tools",
        "--dialect",
        "grbl",
        "--format",
        "json",
        "tests/fixtures/tools/carbide_create.nc",
    ]));
}

/// `vcnc check` with `option` naming a file that holds `content`, shown
/// as `shown` (a malformed table or dump: the run never starts).
fn check_with_file(option: &str, shown: &str, content: &str) -> String {
    let dir = TempDir::new("snap-file");
    let path = dir.write(shown, content).display().to_string();
    vcnc_on(shown, "T1 M6\nG0 X1.\nM30\n", &["check", option, &path]).replace(&path, shown)
}

/// A malformed tool table stops before anything runs: exit 2, the file,
/// the line, what is wrong and how to fix it.
#[test]
fn a_malformed_tool_table_is_a_usage_error() {
    insta::assert_snapshot!(check_with_file(
        "--tools",
        "bad.tbl",
        "T1 P1 D6 Z10 ;ok\nT2 P2 D6,35 Z10\n"
    ));
}

/// `vcnc machine --print --machine` on grbl's `$$` with soft limits on.
#[test]
fn machine_print_of_a_grbl_settings_dump() {
    insta::assert_snapshot!(vcnc_args(&[
        "machine",
        "--print",
        "--machine",
        "tests/fixtures/machines/grbl_soft_limits.txt",
    ]));
}

/// The head of `vcnc machine --print --dialect fanuc-lathe`: the embedded
/// file under two lines that say how to use it.
#[test]
fn machine_print_of_the_built_in_lathe() {
    let out = vcnc_args(&["machine", "--print", "--dialect", "fanuc-lathe"]);
    let head: String = out.lines().take(24).map(|l| format!("{l}\n")).collect();
    insta::assert_snapshot!(head);
}

/// A `$$` dump with a value that is not a number: exit 2, file and line.
#[test]
fn a_malformed_grbl_dump_is_a_usage_error() {
    insta::assert_snapshot!(check_with_file(
        "--machine",
        "dump.txt",
        "$100=250.000\n$110=500.000\n$120=ten\n"
    ));
}

/// `vcnc explain`: a code in every dialect (dialects that agree share a
/// line), a code in one dialect, and an address.
#[test]
fn explain_a_code_and_an_address() {
    insta::assert_snapshot!(vcnc_args(&["explain", "G87"]));
    insta::assert_snapshot!(vcnc_args(&["explain", "G43", "--dialect", "linuxcnc"]));
    insta::assert_snapshot!(vcnc_args(&["explain", "H"]));
}
