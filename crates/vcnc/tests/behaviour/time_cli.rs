//! CLI tests of `vcnc time` and `vcnc run --format trace`: the split adds up
//! to the total, the plan is never faster than distance/feed, the trace has
//! one row per period and ends at rest, and alarms set the exit code.

use crate::common::{TempDir, vcnc};
use serde_json::Value;

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

/// The filter profile's moving average holds T/period samples: a machine
/// with T = 2 s traced every 1 µs would need 2,000,000. More than 100,000
/// is refused before any output, not allocated; at 1 ms the same trace
/// ends at rest at X10 after its 2 s run-out.
#[test]
fn a_trace_period_too_short_for_the_filter_is_refused() {
    let dir = TempDir::new("filter");
    let machine = dir.write(
        "slow.toml",
        "name = \"slow jerk\"\n[[axes]]\nletter = \"x\"\nrapid_mm_per_min = 6000.0\n\
         max_feed_mm_per_min = 6000.0\naccel_mm_s2 = 2000.0\njerk_mm_s3 = 1000.0\n\
         [motion]\nprofile = \"filter\"\n",
    );
    let program = dir.write("one.nc", "G1 X10. F6000\nM30\n");
    let run = |period: &str| {
        vcnc(&[
            "run",
            "--format",
            "trace",
            "--period",
            period,
            "--dialect",
            "fanuc",
            "--machine",
            machine.to_str().unwrap(),
            program.to_str().unwrap(),
        ])
    };
    let o = run("0.000001");
    assert_eq!(o.status.code(), Some(2));
    assert!(o.stdout.is_empty());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("more than 100000"), "{err}");
    let o = run("0.001");
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    // X10 at rest, after the 2 s run-out.
    assert_eq!((last[1], last[2], last[3]), (10.0, 0.0, 0.0));
}

/// `time DIR` walks the directory as `check` does, each program on the
/// dialect detected for it, and the text report puts the planned time
/// first and the distance/feed estimate second, in `check`'s format.
#[test]
fn time_takes_a_directory_and_reads_like_check() {
    let o = vcnc(&["time", "examples/fanuc-lathe"]);
    assert_eq!(o.status.code(), Some(0));
    let text = String::from_utf8(o.stdout).unwrap();
    let reports: Vec<&str> = text.split("\n\n").collect();
    assert_eq!(reports.len(), 12, "{text}");
    for r in &reports {
        let lines: Vec<&str> = r.lines().collect();
        assert!(
            lines[0].starts_with("program     examples/fanuc-lathe/"),
            "{r}"
        );
        assert!(
            lines[1].starts_with("dialect     fanuc-lathe (auto: "),
            "{r}"
        );
        assert!(lines[3].starts_with("cycle time  "), "{r}");
        assert!(lines[4].starts_with("dist/feed   "), "{r}");
    }
    // The same figures as `check` prints for the first program.
    let o = vcnc(&["check", "examples/fanuc-lathe/01_od_rough_finish.nc"]);
    let check = String::from_utf8(o.stdout).unwrap();
    let planned = |t: &str, label: &str| {
        t.lines()
            .find_map(|l| l.strip_prefix(label))
            .map(|v| v.trim().split(' ').next().unwrap().to_string())
            .unwrap()
    };
    assert_eq!(
        planned(reports[0], "cycle time"),
        planned(&check, "cycle time")
    );
    assert_eq!(
        planned(reports[0], "dist/feed"),
        planned(&check, "dist/feed")
    );
}

/// `--units in`: distances in inches, 4 decimals (349.540 mm of cutting
/// in the bracket is 13.7614 in); JSON stays in mm and says the dialect.
#[test]
fn time_shows_inches_and_json_says_the_dialect() {
    let o = vcnc(&["time", "examples/bracket.nc", "--units", "in"]);
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains(" over 13.7614 in\n"), "{text}");
    let o = vcnc(&["time", "examples/bracket.nc", "--format", "json"]);
    let v: Value = serde_json::from_str(String::from_utf8(o.stdout).unwrap().trim()).unwrap();
    assert_eq!(v["dialect"], "syntec");
    assert_eq!(v["dialect_confidence"], "high");
    assert_eq!(v["dialect_evidence"][0], "G71");
    // 239.832 + 2 × 54.854 (see cli.rs's bracket summary), to the µm.
    assert!((f(&v, "cutting_mm") - 349.540).abs() < 1e-3, "{v}");
}
