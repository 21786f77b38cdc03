//! CLI tests of `vcnc time` and `vcnc run --format trace`: the split adds up
//! to the total, the plan is never faster than distance/feed, the trace has
//! one row per period and ends at rest, and alarms set the exit code.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

fn vcnc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(args)
        .current_dir(workspace())
        .output()
        .expect("vcnc runs")
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

#[test]
fn time_json_splits_add_up_to_the_total() {
    let o = vcnc(&["time", "examples/bracket.nc", "--format", "json"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let v: Value = serde_json::from_str(text.trim()).unwrap();
    let parts = [
        "cutting_s",
        "rapid_s",
        "dwell_s",
        "tool_change_s",
        "spindle_s",
        "in_position_s",
    ];
    let sum: f64 = parts.iter().map(|k| f(&v, k)).sum();
    assert!((sum - f(&v, "total_s")).abs() < 1e-5, "{v}");
    let per_tool: f64 = v["per_tool"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| f(t, "seconds"))
        .sum();
    assert!((per_tool - f(&v, "total_s")).abs() < 1e-5);
    // Acceleration only ever adds time to the cutting and rapid moves.
    let moving = f(&v, "cutting_s") + f(&v, "rapid_s") + f(&v, "dwell_s");
    assert!(moving >= f(&v, "distance_feed_s"), "{v}");
    assert_eq!(v["result"], "M30");
    assert_eq!(v["dwell_s"], 0.5);
}

#[test]
fn time_takes_many_files_and_an_alarm_sets_the_exit_code() {
    let o = vcnc(&[
        "time",
        "examples/bracket.nc",
        "tests/fixtures/manual/1.2.3_arc_ex1_absolute.nc",
        "--format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let text = String::from_utf8(o.stdout).unwrap();
    let lines: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[1]["result"], "alarm");
    assert_eq!(lines[1]["alarm"], "E303");
}

#[test]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // a small positive count
fn a_trace_has_one_row_per_period_and_ends_at_rest() {
    let t = vcnc(&["time", "examples/bracket.nc", "--format", "json"]);
    let v: Value = serde_json::from_str(String::from_utf8(t.stdout).unwrap().trim()).unwrap();
    let total = f(&v, "total_s");
    let o = vcnc(&[
        "run",
        "examples/bracket.nc",
        "--format",
        "trace",
        "--period",
        "0.01",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let mut lines = text.lines();
    // The built-in mill has rotary A, B, C: their columns stay 0 here.
    assert_eq!(
        lines.next(),
        Some("t,x,y,z,a,b,c,vx,vy,vz,va,vb,vc,ax,ay,az,aa,ab,ac,speed,line")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let expected = (total / 0.01).ceil() as usize + 1;
    assert!(
        rows.len().abs_diff(expected) <= 1,
        "{} {expected}",
        rows.len()
    );
    let last = rows.last().unwrap();
    assert!((last[0] - total).abs() < 1e-5);
    assert_eq!(last[10], 0.0);
    // The rapid rate of the built-in mill: 400 mm/s on X and Y, 250 on Z.
    for r in &rows {
        assert!(
            r[4].abs() <= 400.0 + 1e-6 && r[5].abs() <= 400.0 + 1e-6 && r[6].abs() <= 250.0 + 1e-6
        );
    }
}

/// `--profile` picks the planner's profile; the built-in mill's own is
/// `filter` (trapezoids through a moving average after interpolation),
/// which only adds its run-out to the trapezoid plan, at each stop.
#[test]
fn time_takes_each_profile_and_the_mill_filters_by_default() {
    let total = |args: &[&str]| {
        let mut all = vec!["time", "examples/bracket.nc", "--format", "json"];
        all.extend_from_slice(args);
        let o = vcnc(&all);
        assert_eq!(o.status.code(), Some(0));
        let v: Value = serde_json::from_str(String::from_utf8(o.stdout).unwrap().trim()).unwrap();
        f(&v, "total_s")
    };
    let default = total(&[]);
    let filter = total(&["--profile", "filter"]);
    let trapezoid = total(&["--profile", "trapezoid"]);
    let jerk = total(&["--profile", "jerk"]);
    assert_eq!(default, filter);
    assert!(trapezoid < filter, "{trapezoid} {filter}");
    assert!(filter != jerk, "{filter} {jerk}");
    let o = vcnc(&["time", "examples/bracket.nc", "--profile", "filter"]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("(generic mill, filter profile)"), "{text}");
}
