//! CLI tests: run the built `vcnc` binary and check its exit code, stdout and
//! stderr.
//!
//! Expected text is written here by hand from the documents, not captured
//! from a run: the summary of `examples/bracket.nc` is the README's (its
//! distances re-derived in `check_bracket_prints_the_summary`), event lines
//! follow `docs/events.md`, the alarm rendering follows the README's example
//! and the exit codes follow the README (0 clean, 1 alarm, 2 usage error).

use crate::common::{TempDir, code, jsonl, stderr, stdout, vcnc, vcnc_fed, vcnc_in, workspace};
use serde_json::{Value, json};
use std::process::{Command, Output};

// ---------------------------------------------------------------------------
// check
// ---------------------------------------------------------------------------

/// The README's summary. Hand check of the distances: rapids 51.962 (to
/// X-10 Y-10 Z50) + 45 (Z5) + 7 (Z5 after the outline) + 29.155 (to X15
/// Y15) + 2 × 7 (Z+7 in the pocket) + 15.811 (to X35 Y15) + 5 (G28 Z0)
/// = 167.928 mm; cutting: outline 7 + 60 + 30 + 50 + 30 + 4 quarter circles
/// of R10 (62.832) = 239.832, each pocket 7 + 40 + a quarter circle of R5
/// (7.854) = 54.854, in all 349.540 mm. The planned cycle time is the
/// planner's figure (its closed forms are tested in
/// `vcnc_planner/tests/analytic.rs`); it must stay above distance/feed.
/// The dialect is detected: G71 is Syntec's metric code (Fanuc's is G21)
/// and the header names the Syntec 900M. The work extents leave out the
/// power-on position the machine extents start from (X0 Y0 Z0 here, inside
/// the part's box, so they are the same).
#[test]
fn check_bracket_prints_the_summary() {
    let o = vcnc(&["check", "examples/bracket.nc"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "\
program    examples/bracket.nc (generic mill)
dialect    syntec (auto: G71, \"…subprogram, Syntec 900M style)\" header)
result     ended by M30
cycle time 41.7s (planned: filter profile, look-ahead 200 blocks)
dist/feed  33.7s (distance/feed estimate, no acceleration)
rapid      167.928 mm
cutting    349.540 mm
extents    X -10.000 .. 60.000   Y -10.000 .. 40.000   Z -2.000 .. 50.000 (machine mm)
work       X -10.000 .. 60.000   Y -10.000 .. 40.000   Z -2.000 .. 50.000 (work coordinates, mm)
tools      T1
spindle    2400 rpm
travel     not checked: the machine has no travel limits (give --machine FILE)
"
    );
    assert_eq!(stderr(&o), "");
}

/// The same summary in inches: 167.928 mm / 25.4 = 6.6113 in, 349.540 mm
/// = 13.7614 in, X -10 .. 60 mm = -0.3937 .. 2.3622 in.
#[test]
fn check_units_in_shows_lengths_in_inches() {
    let o = vcnc(&["check", "examples/bracket.nc", "--units", "in"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("\nrapid      6.6113 in\n"), "{out}");
    assert!(out.contains("\ncutting    13.7614 in\n"), "{out}");
    assert!(
        out.contains("\nextents    X -0.3937 .. 2.3622   Y -0.3937 .. 1.5748   Z -0.0787 .. 1.9685 (machine in)\n"),
        "{out}"
    );
}

#[test]
fn check_names_the_dialect() {
    // Names in any case.
    let o = vcnc(&["check", "examples/bracket.nc", "--dialect", "FaNuC"]);
    // G71 is Syntec's metric code; Fanuc does not know it.
    assert_eq!(code(&o), 1);
    let out = stdout(&o);
    assert!(
        out.starts_with(
            "program    examples/bracket.nc (generic mill)\ndialect    fanuc (--dialect)\n"
        ),
        "{out}"
    );
    assert!(
        out.contains("\nresult     alarm E201 at line 3, column 13\n"),
        "{out}"
    );
    assert!(stderr(&o).starts_with("error[E201]: "), "{}", stderr(&o));
}

// ---------------------------------------------------------------------------
// run --format …
// ---------------------------------------------------------------------------

#[test]
fn run_jsonl_is_the_event_contract() {
    let o = vcnc(&["run", "examples/bracket.nc", "--format", "jsonl"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    assert_eq!(stderr(&o), "");
    let events = jsonl(&o);
    for e in &events {
        assert!(
            e["type"].is_string() && e["line"].as_u64().is_some_and(|l| l >= 1),
            "{e}"
        );
    }
    assert_eq!(
        events.last(),
        Some(&json!({"type": "end", "line": 30, "code": "M30"}))
    );
    // Hand-derived events (docs/events.md): N20 G28 Z0 goes through Z0 to
    // reference point 1, both at the power-on point 0,0,0: neither leg
    // moves, so neither is reported; T1 M06; S2400 M03.
    assert_eq!(
        events[0],
        json!({"type": "tool_change", "line": 5, "tool": 1})
    );
    assert_eq!(
        events[1],
        json!({"type": "spindle", "line": 6, "dir": "cw", "rpm": 2400.0})
    );
    assert_eq!(events[3], json!({"type": "coolant", "line": 8, "on": true}));
    // N100 G03 X60. Y0. R10. from X50 Y-10: a quarter circle about X50 Y0.
    let arc = json!({"type": "arc", "line": 13, "to": {"x": 60.0, "y": 0.0, "z": -2.0},
        "center": {"x": 50.0, "y": 0.0, "z": -2.0}, "plane": "xy", "dir": "ccw", "feed": 800.0});
    assert!(events.contains(&arc), "no {arc}");
    // O0100 N60 G02 X5. Y5. R5. (incremental) from X15 Y15: R > 0 clockwise
    // is the quarter circle about X20 Y15; line 37 of the file.
    let arc = json!({"type": "arc", "line": 37, "to": {"x": 20.0, "y": 20.0, "z": -2.0},
        "center": {"x": 20.0, "y": 15.0, "z": -2.0}, "plane": "xy", "dir": "cw", "feed": 600.0});
    assert_eq!(events.iter().filter(|e| **e == arc).count(), 1, "no {arc}");
    assert!(events.contains(&json!({"type": "dwell", "line": 26, "seconds": 0.5})));
}

#[test]
fn run_defaults_to_jsonl() {
    let explicit = vcnc(&["run", "examples/bracket.nc", "--format", "jsonl"]);
    let default = vcnc(&["run", "examples/bracket.nc"]);
    assert_eq!(code(&default), 0);
    assert_eq!(default.stdout, explicit.stdout);
}

#[test]
fn run_csv_has_a_header_and_one_row_per_event() {
    let o = vcnc(&["run", "examples/bracket.nc", "--format", "csv"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    let text = stdout(&o);
    let mut lines = text.lines();
    let header = lines.next().expect("header");
    assert_eq!(
        header,
        "type,line,file,x,y,z,a,b,c,center_x,center_y,center_z,center_a,center_b,center_c,plane,dir,feed,feed_per_rev,lead_mm,seconds,tool,spindle,rpm,on,mode,code,column,message,triggered,exact_stop,p,surface_m_per_min,help,linear,tool_offset_x,tool_offset_y,tool_offset_z,tool_offset_a,tool_offset_b,tool_offset_c,tolerance_mm"
    );
    let columns = header.split(',').count();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    for r in &rows {
        assert_eq!(r.len(), columns, "{r:?}");
    }
    let events = jsonl(&vcnc(&["run", "examples/bracket.nc"]));
    assert_eq!(rows.len(), events.len(), "one row per event");
    let col = |name: &str| header.split(',').position(|h| h == name).unwrap();
    let last = rows.last().unwrap();
    assert_eq!(
        (last[col("type")], last[col("line")], last[col("code")]),
        ("end", "30", "M30")
    );
    let arc = rows
        .iter()
        .find(|r| r[col("type")] == "arc" && r[col("line")] == "13")
        .expect("arc row of N100");
    assert_eq!(
        [
            arc[col("x")],
            arc[col("y")],
            arc[col("center_x")],
            arc[col("center_y")],
            arc[col("dir")],
            arc[col("feed")]
        ],
        ["60.0", "0.0", "50.0", "0.0", "ccw", "800.0"]
    );
    // The rotary axes of the built-in mill stay empty until they move.
    assert_eq!([arc[col("a")], arc[col("center_c")]], ["", ""]);
}

#[test]
fn run_gcode_is_a_flat_program_ending_in_m30() {
    let o = vcnc(&["run", "examples/bracket.nc", "--format", "gcode"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines[0].starts_with('('), "header comment: {}", lines[0]);
    let starts = |p: &str| lines.iter().any(|l| l.starts_with(p));
    assert!(starts("G0 "), "{text}");
    assert!(starts("G1 "), "{text}");
    assert!(starts("G2 ") && starts("G3 "), "{text}");
    assert!(lines.contains(&"T1 M6"), "{text}");
    assert!(lines.contains(&"M3 S2400"), "{text}");
    assert!(lines.contains(&"G4 P0.5"), "{text}");
    assert_eq!(lines.last(), Some(&"M30"));
    // Flattened: no subprogram calls, no incremental mode, no Syntec codes.
    for l in &lines {
        assert!(
            !l.contains("M98") && !l.contains("M99") && !l.contains("G91") && !l.contains("G71"),
            "{l}"
        );
    }
}

/// The flattened program carries the compensated tool-centre path, so a
/// G41 program runs on grbl, which has no cutter compensation: run again,
/// the flattened program moves exactly as the original did.
#[test]
fn run_gcode_flattens_cutter_compensation_and_transforms() {
    let dir = TempDir::new("flatten-comp");
    dir.write(
        "comp.nc",
        "G10 L12 P1 R5.\nG21 G17 G90 G00 X0 Y-20. Z5.\nS1000 M03\nG68 X0 Y0 R30.\nG41 D1 G01 X0 Y0 F500.\nX40.\nG03 X40. Y20. R10.\nG01 X-5.\nG40 Y-20.\nG69\nM30\n",
    );
    let original = vcnc_in(dir.path(), &["run", "comp.nc", "--dialect", "fanuc"]);
    assert_eq!(code(&original), 0, "{}", stderr(&original));
    let flat = vcnc_in(
        dir.path(),
        &["run", "comp.nc", "--dialect", "fanuc", "--format", "gcode"],
    );
    let text = stdout(&flat);
    assert!(!text.contains("G41") && !text.contains("G68"), "{text}");
    dir.write("flat.nc", &text);
    let again = vcnc_in(dir.path(), &["run", "flat.nc", "--dialect", "fanuc"]);
    assert_eq!(code(&again), 0, "{}", stderr(&again));
    let ends = |o: &Output| -> Vec<Value> {
        jsonl(o)
            .into_iter()
            .filter(|e| matches!(e["type"].as_str(), Some("feed" | "arc")))
            .map(|e| json!([e["to"], e["center"]]))
            .collect()
    };
    let (a, b) = (ends(&original), ends(&again));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        for (p, q) in x.as_array().unwrap().iter().zip(y.as_array().unwrap()) {
            if let (Some(p), Some(q)) = (p.as_object(), q.as_object()) {
                for k in ["x", "y", "z"] {
                    let d = p[k].as_f64().unwrap() - q[k].as_f64().unwrap();
                    assert!(d.abs() < 1e-4, "{x} vs {y}");
                }
            }
        }
    }
}

const DRILLING: &str = "G21 G17 G90 G0 X0 Y0 Z20.\nT1 M06\nS1000 M03\n\
G99 G83 X10. Y10. Z-10. R2. Q4. F200.\nG98 X20.\nG80\nT2 M06\n\
G81 Z-3. R2. F300. K0\nG134 X50. Y50. I10. J0 K6\nG80\n\
G84 X70. Y10. Z-8. R2. F1000.\nG88 X80. Z-5.\nG80\nM30\n";

/// `check` counts the holes each tool drills (two G83 holes with T1; the
/// six of a G134 circle and one tapped and one G88 hole with T2).
#[test]
fn check_counts_holes_per_tool() {
    let dir = TempDir::new("check-holes");
    dir.write("drill.nc", DRILLING);
    let o = vcnc_in(dir.path(), &["check", "drill.nc", "--dialect", "fanuc"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("holes      10 (T1 2, T2 8)\n"), "{text}");
    // G88 waits for the operator: not part of the time estimate.
    assert!(text.contains("plus 1 wait for the operator"), "{text}");
}

/// `--format gcode` expands every cycle and pattern into plain moves (grbl
/// has no canned cycles); run again, it moves as the original did.
#[test]
fn run_gcode_expands_canned_cycles() {
    let dir = TempDir::new("flatten-cycles");
    dir.write("drill.nc", DRILLING);
    let original = vcnc_in(dir.path(), &["run", "drill.nc", "--dialect", "fanuc"]);
    assert_eq!(code(&original), 0, "{}", stderr(&original));
    let flat = vcnc_in(
        dir.path(),
        &["run", "drill.nc", "--dialect", "fanuc", "--format", "gcode"],
    );
    let text = stdout(&flat);
    for code in ["G81", "G83", "G84", "G88", "G134", "G98", "G99"] {
        let uncommented = text
            .lines()
            .any(|l| l.split('(').next().unwrap_or("").contains(code));
        assert!(!uncommented, "{code} left in:\n{text}");
    }
    dir.write("flat.nc", &text);
    let again = vcnc_in(dir.path(), &["run", "flat.nc", "--dialect", "fanuc"]);
    assert_eq!(code(&again), 0, "{}", stderr(&again));
    // Moves that go somewhere (the flat preamble's move to the start does
    // not), to 0.0001 mm (the flat program's resolution).
    let motion = |o: &Output| -> Vec<(String, [f64; 3])> {
        let mut at = [0.0; 3];
        let mut out = Vec::new();
        for e in jsonl(o) {
            let kind = e["type"].as_str().unwrap_or("").to_string();
            if !matches!(kind.as_str(), "rapid" | "feed") {
                continue;
            }
            let to = ["x", "y", "z"].map(|k| e["to"][k].as_f64().unwrap());
            if to.iter().zip(&at).any(|(a, b)| (a - b).abs() > 1e-4) {
                out.push((kind, to));
            }
            at = to;
        }
        out
    };
    let (a, b) = (motion(&original), motion(&again));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.0, y.0);
        assert!(
            x.1.iter().zip(&y.1).all(|(p, q)| (p - q).abs() < 1e-4),
            "{x:?} vs {y:?}"
        );
    }
    // The spindle reversals of the tap and the G88 stop are there too.
    let spindle = |o: &Output| -> Vec<Value> {
        jsonl(o)
            .into_iter()
            .filter(|e| e["type"] == "spindle")
            .map(|e| e["dir"].clone())
            .collect()
    };
    assert_eq!(spindle(&original), spindle(&again));
}

// ---------------------------------------------------------------------------
// check: many programs, JSON, SARIF, stdin, --deny-warnings
// ---------------------------------------------------------------------------

/// A directory of programs: two clean, one that alarms, one that warns, a
/// file that is not a program, and a nested folder.
fn batch_dir() -> TempDir {
    let dir = TempDir::new("batch");
    dir.write("good.nc", "S1000 M03\nG00 X1.\nG01 X2. F100.\nM30\n");
    dir.write("bad.nc", "G00 X1.\nG02 X5. Y0 I-3. J-1. F100.\nM30\n");
    dir.write("warns.ngc", "G00 X1.\nG01 X2. F100.\nM30\n");
    dir.write("notes.md", "not a program\n");
    std::fs::create_dir_all(dir.path().join("sub")).unwrap();
    dir.write("sub/O1234", "S1000 M03\nG00 Y1.\nM30\n");
    dir
}

#[test]
fn check_runs_every_program_of_a_directory_with_one_line_each() {
    let dir = batch_dir();
    let o = vcnc_in(dir.path(), &["check", "."]);
    assert_eq!(code(&o), 1, "an alarm fails the batch: {}", stderr(&o));
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 5, "{text}");
    // Each program with the dialect detected for it: `X1.` is the Fanuc
    // posts' style, `.ngc` LinuxCNC's extension, and a program with
    // neither (all its lengths with points) grbl's, the commonest.
    assert!(
        lines[0].starts_with("./bad.nc [fanuc]: alarm E303 at line 2, column 1: "),
        "{text}"
    );
    assert!(
        lines[1].starts_with("./good.nc [fanuc]: ended by M30, "),
        "{text}"
    );
    assert!(
        lines[2].starts_with("./sub/O1234 [grbl]: ended by M30"),
        "{text}"
    );
    assert!(
        lines[3].starts_with("./warns.ngc [linuxcnc]: ended by M30, ")
            && lines[3].ends_with(", 1 warning"),
        "{text}"
    );
    // Under --dialect, no tags.
    let o = vcnc_in(dir.path(), &["check", ".", "--dialect", "fanuc"]);
    let text = stdout(&o);
    assert!(text.starts_with("./bad.nc: alarm E303"), "{text}");
    assert_eq!(
        lines[4],
        "4 programs: 3 ran to the end, 1 stopped by an alarm, 1 with warnings (1 in all)"
    );
}

#[test]
fn check_json_is_one_document_per_run() {
    let dir = batch_dir();
    let o = vcnc_in(
        dir.path(),
        &["check", ".", "--format", "json", "--jobs", "2"],
    );
    assert_eq!(code(&o), 1);
    let doc: Value = serde_json::from_str(&stdout(&o)).expect("one JSON document");
    assert_eq!(doc["version"], 1);
    assert_eq!(doc["totals"]["programs"], 4);
    assert_eq!(doc["totals"]["alarms"], 1);
    let files = doc["files"].as_array().unwrap();
    let bad = &files[0];
    assert_eq!(bad["path"], "./bad.nc");
    assert_eq!(bad["result"], "alarm");
    assert_eq!(
        (
            &bad["alarm"]["code"],
            &bad["alarm"]["line"],
            &bad["alarm"]["column"]
        ),
        (&json!("E303"), &json!(2), &json!(1))
    );
    // Each file says its dialect and why; the run says it chose.
    assert_eq!(doc["dialect"], "auto");
    assert_eq!(bad["dialect"], "fanuc");
    assert_eq!(bad["dialect_confidence"], "high");
    assert_eq!(bad["machine"], "generic mill");
    let ngc = &files[3];
    assert_eq!(ngc["dialect"], "linuxcnc");
    assert!(
        ngc["dialect_evidence"]
            .as_array()
            .unwrap()
            .contains(&json!(".ngc file")),
        "{ngc}"
    );
    let warns = &files[3];
    assert_eq!(warns["warning_count"], 1);
    assert_eq!(warns["warnings"][0]["code"], "W104");
    assert_eq!(warns["summary"]["extents"]["max"]["x"], 2.0);
    // Work extents leave the power-on position (X0) out: X1 to X2.
    assert_eq!(warns["summary"]["work_extents"]["min"]["x"], 1.0);
    assert_eq!(warns["summary"]["work_extents"]["max"]["x"], 2.0);
    assert!(
        warns["summary"]["extents"]["max"].get("a").is_none(),
        "rotary axes that never moved are left out"
    );
}

#[test]
fn check_sarif_has_what_ci_annotations_need() {
    let dir = batch_dir();
    let o = vcnc_in(dir.path(), &["check", ".", "--format", "sarif"]);
    assert_eq!(code(&o), 1);
    let doc: Value = serde_json::from_str(&stdout(&o)).expect("SARIF is JSON");
    // The required properties of SARIF 2.1.0: version, runs, runs[].tool.
    // driver.name, results[].message.text (and, for annotations, ruleId,
    // level and a physical location with a region).
    assert_eq!(doc["version"], "2.1.0");
    assert!(doc["$schema"].as_str().unwrap().contains("sarif-2.1.0"));
    let run = &doc["runs"][0];
    assert_eq!(run["tool"]["driver"]["name"], "vcnc");
    let rules: Vec<&str> = run["tool"]["driver"]["rules"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["id"].as_str().unwrap())
        .collect();
    assert_eq!(rules, ["E303", "W104"]);
    let results = run["results"].as_array().unwrap();
    assert_eq!(results.len(), 2);
    for r in results {
        assert!(r["message"]["text"].as_str().is_some_and(|t| !t.is_empty()));
        assert!(rules.contains(&r["ruleId"].as_str().unwrap()));
        let loc = &r["locations"][0]["physicalLocation"];
        assert!(loc["artifactLocation"]["uri"].as_str().is_some());
        assert!(loc["region"]["startLine"].as_u64().unwrap() >= 1);
    }
    // Each checked file is an artifact with its dialect and the evidence.
    let artifacts = run["artifacts"].as_array().unwrap();
    assert_eq!(artifacts.len(), 4);
    let ngc = artifacts
        .iter()
        .find(|a| a["location"]["uri"] == "./warns.ngc")
        .unwrap();
    assert_eq!(ngc["properties"]["dialect"], "linuxcnc");
    assert_eq!(ngc["properties"]["dialectConfidence"], "high");
    assert!(
        ngc["properties"]["dialectEvidence"]
            .as_array()
            .unwrap()
            .contains(&json!(".ngc file"))
    );
    let alarm = results.iter().find(|r| r["ruleId"] == "E303").unwrap();
    assert_eq!(alarm["level"], "error");
    assert_eq!(
        alarm["locations"][0]["physicalLocation"]["artifactLocation"]["uri"],
        "./bad.nc"
    );
    assert_eq!(
        alarm["locations"][0]["physicalLocation"]["region"]["startColumn"],
        1
    );
}

#[test]
fn check_reads_a_program_from_stdin() {
    let o = vcnc_fed(
        &workspace(),
        &["check", "-"],
        b"G00 X1.\nG02 X5. Y0 I-3. J-1. F100.\nM30\n",
    );
    assert_eq!(code(&o), 1);
    // Detected from the text alone (no file name): `X1.` is the Fanuc
    // posts' style.
    assert!(
        stdout(&o).starts_with("program    <stdin> (generic mill)\ndialect    fanuc (auto: "),
        "{}",
        stdout(&o)
    );
    // The alarm shows the line from standard input.
    let err = stderr(&o);
    assert!(err.contains("--> <stdin>:2:1"), "{err}");
    assert!(err.contains("2 | G02 X5. Y0 I-3. J-1. F100."), "{err}");
}

#[test]
fn deny_warnings_fails_a_run_that_warns() {
    let dir = batch_dir();
    let o = vcnc_in(dir.path(), &["check", "warns.ngc"]);
    assert_eq!(code(&o), 0);
    assert!(stderr(&o).contains("warning[W104]"), "{}", stderr(&o));
    let o = vcnc_in(dir.path(), &["check", "warns.ngc", "--deny-warnings"]);
    assert_eq!(code(&o), 1);
    let o = vcnc_in(dir.path(), &["run", "warns.ngc", "--deny-warnings"]);
    assert_eq!(code(&o), 1);
    assert!(
        stdout(&o).contains("\"type\":\"warning\""),
        "{}",
        stdout(&o)
    );
    let o = vcnc_in(dir.path(), &["check", "good.nc", "--deny-warnings"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
}

#[test]
fn a_directory_without_programs_is_a_usage_error() {
    let dir = TempDir::new("empty-batch");
    dir.write("readme.md", "nothing here\n");
    let o = vcnc_in(dir.path(), &["check", "."]);
    assert_usage_error(&o, "no programs found under .");
}

// ---------------------------------------------------------------------------
// Alarms
// ---------------------------------------------------------------------------

/// The README's E303 example, started at X0 Y0: centre X-3 Y-1, start radius
/// √10, end radius √45.25.
const E303_PROGRAM: &str =
    "(E303)\nG90 G00 X0 Y0\nG17 G90 G03 X1500 Y4000 I-3000 J-1000 F200; //absolute command\nM30\n";

fn e303_rendering(path: &str) -> String {
    format!(
        "\
error[E303]: alarm: arc end point is not on the circle: start radius 3.1623 mm, end radius 6.7268 mm
 --> {path}:3:9
  |
3 | G17 G90 G03 X1500 Y4000 I-3000 J-1000 F200; //absolute command
  |         ^^^ E303
  |
  = help: check the end point and I/J/K (I/J/K are measured from the start point to the centre)
"
    )
}

#[test]
fn an_alarm_exits_1_and_is_rendered_like_a_compiler_error() {
    let dir = TempDir::new("e303");
    dir.write("arc.nc", E303_PROGRAM);
    let o = vcnc_in(dir.path(), &["run", "arc.nc", "--format", "jsonl"]);
    assert_eq!(code(&o), 1);
    let events = jsonl(&o);
    // `G90 G00 X0 Y0` at the power-on point does not move: no event.
    assert_eq!(events.len(), 1, "{events:?}");
    let alarm = &events[0];
    assert_eq!(
        (
            &alarm["type"],
            &alarm["line"],
            &alarm["column"],
            &alarm["code"]
        ),
        (&json!("alarm"), &json!(3), &json!(9), &json!("E303"))
    );
    assert!(
        alarm["message"]
            .as_str()
            .unwrap()
            .contains("not on the circle"),
        "{alarm}"
    );
    assert!(alarm["help"].is_string(), "{alarm}");
    assert_eq!(stderr(&o), e303_rendering("arc.nc"));

    // `check` renders the same alarm and reports it in the summary.
    let o = vcnc_in(dir.path(), &["check", "arc.nc"]);
    assert_eq!(code(&o), 1);
    assert_eq!(stderr(&o), e303_rendering("arc.nc"));
    let out = stdout(&o);
    assert!(
        out.contains("\nresult     alarm E303 at line 3, column 9\n"),
        "{out}"
    );

    // csv: the alarm row carries code and column; gcode: the flattened
    // program stops with a comment and M2.
    let o = vcnc_in(dir.path(), &["run", "arc.nc", "--format", "csv"]);
    assert_eq!(code(&o), 1);
    let text = stdout(&o);
    let last = text.lines().last().unwrap();
    assert!(
        last.starts_with("alarm,3,,") && last.contains(",E303,9,"),
        "{last}"
    );
    let o = vcnc_in(dir.path(), &["run", "arc.nc", "--format", "gcode"]);
    assert_eq!(code(&o), 1);
    let text = stdout(&o);
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines[lines.len() - 2].starts_with("(ALARM E303 line 3"),
        "{text}"
    );
    assert_eq!(lines.last(), Some(&"M2"));
}

#[test]
fn an_alarm_in_a_called_program_names_its_file() {
    let dir = TempDir::new("sub-alarm");
    dir.write("main.nc", "G90 G00 X1.\nM98 P10\nM30\n");
    let sub = dir.write("O0010.nc", "G00 Y2.\n  G01 X5000. F100\nM99\n");
    let limited = workspace().join("tests/fixtures/machines/mill_travel_limits.toml");
    let o = vcnc_in(
        dir.path(),
        &["run", "main.nc", "--machine", limited.to_str().unwrap()],
    );
    assert_eq!(code(&o), 1);
    let events = jsonl(&o);
    let alarm = events.last().unwrap();
    assert_eq!(
        (
            &alarm["type"],
            &alarm["line"],
            &alarm["column"],
            &alarm["code"]
        ),
        (&json!("alarm"), &json!(2), &json!(7), &json!("E501"))
    );
    // `file` is the path the program was found at (here relative to the
    // working directory, like the main program's).
    let file = alarm["file"]
        .as_str()
        .expect("the alarm names the called program's file");
    assert_eq!(
        dir.path().join(file).canonicalize().unwrap(),
        sub.canonicalize().unwrap(),
        "{file}"
    );
    let err = stderr(&o);
    assert!(err.starts_with("error[E501]: alarm: over-travel"), "{err}");
    assert!(err.contains(&format!(" --> {file}:2:7\n")), "{err}");
    assert!(err.contains("2 |   G01 X5000. F100\n"), "{err}");
    assert!(err.contains("  |       ^^^^^^ E501\n"), "{err}");
}

/// The twelve lathe programs of `examples/fanuc-lathe/` (Haas safe-start
/// line, G50 S, G96, T0101, G71 P Q, G70, G76 …) run to their M30 with no
/// alarm and no warning.
#[test]
fn the_fanuc_lathe_examples_run_to_the_end() {
    let o = vcnc(&[
        "check",
        "--dialect",
        "fanuc-lathe",
        "--machine",
        "examples/fanuc-lathe/turret.toml",
        "--deny-warnings",
        "examples/fanuc-lathe",
    ]);
    assert_eq!(
        code(&o),
        0,
        "stdout: {}\nstderr: {}",
        stdout(&o),
        stderr(&o)
    );
    let out = stdout(&o);
    assert_eq!(out.matches(": ended by M30").count(), 12, "{out}");
    assert!(
        out.contains("12 programs: 12 ran to the end, 0 stopped by an alarm, 0 with warnings"),
        "{out}"
    );
}

// ---------------------------------------------------------------------------
// Usage errors: exit 2, a message on stderr, nothing on stdout
// ---------------------------------------------------------------------------

fn assert_usage_error(o: &Output, needle: &str) {
    assert_eq!(code(o), 2, "stdout: {}\nstderr: {}", stdout(o), stderr(o));
    let err = stderr(o);
    assert!(
        err.starts_with("error: ") && err.contains(needle),
        "stderr: {err}"
    );
}

#[test]
fn unknown_dialect_is_a_usage_error() {
    let o = vcnc(&["check", "examples/bracket.nc", "--dialect", "heidenhain"]);
    assert_usage_error(&o, "invalid value 'heidenhain' for '--dialect");
    assert!(
        stderr(&o).contains(
            "[possible values: auto, syntec, fanuc, lathe, eia, grbl, haas, fanuc-lathe, haas-lathe, linuxcnc, linuxcnc-lathe, mach3]"
        ),
        "{}",
        stderr(&o)
    );
    assert_eq!(stdout(&o), "");
}

#[test]
fn missing_file_is_a_usage_error() {
    let o = vcnc(&["check", "examples/no_such_program.nc"]);
    assert_usage_error(&o, "examples/no_such_program.nc");
    assert_eq!(stdout(&o), "");
    let o = vcnc(&["run", "examples/no_such_program.nc"]);
    assert_usage_error(&o, "examples/no_such_program.nc");
    assert_eq!(stdout(&o), "");
    let o = vcnc(&["run", "examples"]);
    assert_usage_error(&o, "examples is a directory");
}

/// A usage error must not leave a partial result on stdout: a CSV header or
/// the flattened program's preamble with exit 2 looks like an empty result to
/// a pipeline.
#[test]
fn usage_errors_print_nothing_on_stdout_in_any_format() {
    for format in ["jsonl", "csv", "gcode"] {
        let o = vcnc(&["run", "examples/no_such_program.nc", "--format", format]);
        assert_usage_error(&o, "examples/no_such_program.nc");
        assert_eq!(stdout(&o), "", "--format {format}");
    }
}

#[test]
fn bad_machine_file_is_a_usage_error() {
    let dir = TempDir::new("machine");
    let bad = dir.write("bad.toml", "name = \"bad\"\naxes = []\n");
    let o = vcnc(&[
        "check",
        "examples/bracket.nc",
        "--machine",
        bad.to_str().unwrap(),
    ]);
    assert_usage_error(&o, "machine file");
    assert!(stderr(&o).contains("1 to 6 axes"), "{}", stderr(&o));
    let typo = dir.write("typo.toml", "name = 1\n");
    let o = vcnc(&[
        "run",
        "examples/bracket.nc",
        "--machine",
        typo.to_str().unwrap(),
    ]);
    assert_usage_error(&o, "machine file");
    let missing = dir.path().join("missing.toml");
    let o = vcnc(&[
        "check",
        "examples/bracket.nc",
        "--machine",
        missing.to_str().unwrap(),
    ]);
    assert_usage_error(&o, "cannot read machine file");
}

#[test]
fn a_valid_machine_file_is_used() {
    // The README's machine format: a small machine whose X travel ends at 50.
    let dir = TempDir::new("small-machine");
    let machine = dir.write(
        "small.toml",
        "name = \"small mill\"\n\
         [[axes]]\nletter = \"x\"\nmin_mm = -20.0\nmax_mm = 50.0\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
         [[axes]]\nletter = \"y\"\nmin_mm = -20.0\nmax_mm = 50.0\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
         [[axes]]\nletter = \"z\"\nmin_mm = -20.0\nmax_mm = 60.0\nrapid_mm_per_min = 10000.0\nmax_feed_mm_per_min = 5000.0\n\
         [reference]\np1 = { x = 0.0, y = 0.0, z = 0.0 }\n\
         [tools.1]\nd_mm = 5.0\n",
    );
    let o = vcnc(&[
        "check",
        "examples/bracket.nc",
        "--machine",
        machine.to_str().unwrap(),
    ]);
    assert_eq!(code(&o), 1, "{}", stdout(&o));
    let out = stdout(&o);
    assert!(
        out.starts_with("program    examples/bracket.nc (small mill)\ndialect    syntec (auto"),
        "{out}"
    );
    // N90 G01 X50. is on the limit; N100's arc to X60. leaves it.
    assert!(
        out.contains("\nresult     alarm E501 at line 13, column 10\n"),
        "{out}"
    );
}

#[test]
fn unknown_subcommand_and_bad_arguments_are_usage_errors() {
    let o = vcnc(&["frobnicate", "examples/bracket.nc"]);
    assert_eq!(code(&o), 2);
    assert!(
        stderr(&o).contains("unrecognized subcommand 'frobnicate'"),
        "{}",
        stderr(&o)
    );
    assert_eq!(stdout(&o), "");
    let o = vcnc(&["run", "examples/bracket.nc", "--format", "xml"]);
    assert_eq!(code(&o), 2);
    assert!(stderr(&o).contains("invalid value 'xml'"), "{}", stderr(&o));
    let o = vcnc(&["check"]);
    assert_eq!(code(&o), 2);
    let o = vcnc(&[]);
    assert_eq!(code(&o), 2);
}

// ---------------------------------------------------------------------------
// Options
// ---------------------------------------------------------------------------

/// LinuxCNC's `o<name> call` of a subroutine kept in its own file reads
/// `name.ngc` from the program directory, and nothing outside it: a name
/// with a path (`../x`, an absolute one) or a file that is a link leading
/// out of the directory alarms at the call, and the outside file's text
/// never appears (alarm text quotes source lines, so a server checking
/// untrusted programs would leak files otherwise).
#[test]
fn subroutine_files_are_read_from_the_program_directory_only() {
    let dir = TempDir::new("ngc-subs");
    let secret = dir.write(
        "secret.ngc",
        "o<secret> sub\n(TOP SECRET)\no<secret> endsub\n",
    );
    let subs = dir.path().join("subs");
    dir.write(
        "subs/mark.ngc",
        "o<mark> sub\nG0 X#1\no<mark> endsub [#1 * 2]\nM2\n",
    );
    dir.write(
        "subs/main.ngc",
        "G21\no<mark> call [3]\nG0 Y#<_value>\nM2\n",
    );
    let o = vcnc_in(&subs, &["run", "main.ngc", "--dialect", "linuxcnc"]);
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    let moves: Vec<_> = jsonl(&o)
        .into_iter()
        .filter(|e| e["type"] == "rapid")
        .map(|e| (e["to"]["x"].clone(), e["to"]["y"].clone()))
        .collect();
    assert_eq!(
        moves,
        vec![(json!(3.0), json!(0.0)), (json!(3.0), json!(6.0))]
    );
    #[cfg(unix)]
    std::os::unix::fs::symlink(&secret, subs.join("leak.ngc")).expect("symlink");
    let absolute = secret.with_extension("").display().to_string();
    let mut calls = vec![
        ("o<../secret> call".to_string(), "E611"),
        (format!("o<{absolute}> call"), "E611"),
        ("o<nowhere> call".to_string(), "E611"),
    ];
    if cfg!(unix) {
        calls.push(("o<leak> call".to_string(), "E408"));
    }
    for (call, alarm) in calls {
        dir.write("subs/probe.ngc", format!("G21\n{call}\nG0 X1\nM2\n"));
        let o = vcnc_in(&subs, &["run", "probe.ngc", "--dialect", "linuxcnc"]);
        assert_eq!(code(&o), 1, "{call}");
        let events = jsonl(&o);
        let last = events.last().unwrap();
        assert_eq!(
            (&last["code"], &last["line"], &last["column"]),
            (&json!(alarm), &json!(2), &json!(1)),
            "{call}"
        );
        assert!(!events.iter().any(|e| e["type"] == "rapid"), "{call}");
        let all = format!("{}{}", String::from_utf8_lossy(&o.stdout), stderr(&o));
        assert!(!all.contains("TOP SECRET"), "{call} leaked the file: {all}");
    }
}

#[test]
fn program_dir_finds_called_programs() {
    let dir = TempDir::new("program-dir");
    dir.write("main.nc", "G90 G00 X1.\nM98 P10\nG00 X3.\nM30\n");
    let sub = dir.write("subs/O0010.nc", "G00 Y2.\nM99\n");
    let subs = dir.path().join("subs");

    let o = vcnc_in(
        dir.path(),
        &["run", "main.nc", "--program-dir", subs.to_str().unwrap()],
    );
    assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
    let file = sub.display().to_string();
    assert_eq!(
        jsonl(&o),
        vec![
            json!({"type": "rapid", "line": 1, "to": {"x": 1.0, "y": 0.0, "z": 0.0}}),
            json!({"type": "rapid", "line": 1, "file": file, "to": {"x": 1.0, "y": 2.0, "z": 0.0}}),
            json!({"type": "rapid", "line": 3, "to": {"x": 3.0, "y": 2.0, "z": 0.0}}),
            json!({"type": "end", "line": 4, "code": "M30"}),
        ]
    );

    // Without --program-dir the program's own directory is searched: no O0010.
    let limited = workspace().join("tests/fixtures/machines/mill_travel_limits.toml");
    let o = vcnc_in(
        dir.path(),
        &["run", "main.nc", "--machine", limited.to_str().unwrap()],
    );
    assert_eq!(code(&o), 1);
    let events = jsonl(&o);
    let alarm = events.last().unwrap();
    assert_eq!(
        (&alarm["code"], &alarm["line"], &alarm["column"]),
        (&json!("E401"), &json!(2), &json!(5))
    );
    assert!(
        stderr(&o).starts_with("error[E401]: alarm: program O0010 not found"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn optional_stop_switch() {
    let dir = TempDir::new("optional-stop");
    dir.write("p.nc", "G00 X1.\nM01\nG00 X2.\nM00\nM30\n");
    let stops = |args: &[&str]| -> Vec<Value> {
        let o = vcnc_in(dir.path(), args);
        assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
        let events = jsonl(&o);
        assert_eq!(
            events.last(),
            Some(&json!({"type": "end", "line": 5, "code": "M30"}))
        );
        events.into_iter().filter(|e| e["type"] == "stop").collect()
    };
    assert_eq!(
        stops(&["run", "p.nc"]),
        vec![json!({"type": "stop", "line": 4, "code": "M00"})]
    );
    assert_eq!(
        stops(&["run", "p.nc", "--optional-stop"]),
        vec![
            json!({"type": "stop", "line": 2, "code": "M01"}),
            json!({"type": "stop", "line": 4, "code": "M00"}),
        ]
    );
}

#[test]
fn block_delete_switch() {
    let dir = TempDir::new("block-delete");
    dir.write("p.nc", "G00 X1.\n/G00 X5.\n/2 G00 Y5.\nG00 X2.\nM30\n");
    let xs = |args: &[&str]| -> Vec<Value> {
        let o = vcnc_in(dir.path(), args);
        assert_eq!(code(&o), 0, "stderr: {}", stderr(&o));
        jsonl(&o)
            .into_iter()
            .filter(|e| e["type"] == "rapid")
            .map(|e| e["to"].clone())
            .collect()
    };
    let to = |x: f64, y: f64| json!({"x": x, "y": y, "z": 0.0});
    assert_eq!(
        xs(&["run", "p.nc"]),
        vec![to(1.0, 0.0), to(5.0, 0.0), to(5.0, 5.0), to(2.0, 5.0)]
    );
    assert_eq!(
        xs(&["run", "p.nc", "--block-delete"]),
        vec![to(1.0, 0.0), to(2.0, 0.0)]
    );
}

/// Regression: `vcnc check` on a lathe program that speaks in diameters
/// reports X extents as diameters (events carry radii).
#[test]
fn check_reports_lathe_diameters() {
    let dir = TempDir::new("lathe");
    let file = dir.write("turn.nc", "G00 X40 Z5\nG01 Z-20 F100\nG00 X60\nM30\n");
    let out = vcnc(&["check", "--dialect", "lathe", file.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("(generic 2-axis lathe)\ndialect    lathe (--dialect)\n"),
        "{stdout}"
    );
    // Power-on at diameter 200; the program goes down to diameter 40.
    assert!(stdout.contains("X diameter 40.000 .. 200.000"), "{stdout}");
    assert!(stdout.contains("Z -20.000 .. 250.000"), "{stdout}");
    // Where the tool went, without the power-on position: diameters 40 to
    // 60, Z -20 to 90 — the built-in lathe's G00 moves each axis at its own
    // (equal) rapid rate, so X's 80 mm of radius (100 to 20) end when Z has
    // gone 160 mm of its 245, at Z 90, and Z goes on alone to 5.
    assert!(
        stdout.contains(
            "\nwork       X diameter 40.000 .. 60.000   Z -20.000 .. 90.000 (work coordinates, mm)\n"
        ),
        "{stdout}"
    );
}

/// Regression: an alarm on a line that is not UTF-8 (a GBK comment, common
/// in Syntec programs) used to panic while rendering; the printed column
/// and the JSON column now agree.
#[test]
fn an_alarm_on_a_gbk_line_is_rendered_without_panic() {
    let dir = TempDir::new("gbk");
    // "(中文注释) G01 X1." in GBK; the G01 has no feed: E301 at the G01.
    let file = dir.write("gbk.nc", b"(\xd6\xd0\xce\xc4\xd7\xa2\xca\xcd) G01 X1.\n");
    let out = vcnc(&["run", file.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("error[E301]"), "{stderr}");
    // Each of the 8 GBK bytes that do not form UTF-8 shows as one U+FFFD:
    // '(' + 8 + ')' + ' ' puts the G at column 11.
    assert!(stdout.contains("\"column\":11"), "{stdout}");
    assert!(stderr.contains(":1:11"), "{stderr}");
}

/// Feed per revolution with the spindle stopped cannot move (E342); with
/// the spindle turning it flattens to feed per minute at the speed in
/// force. Regression: it used to be flattened as `F0`, which LinuxCNC
/// rejects.
#[test]
fn feed_per_rev_flattens_at_the_spindle_speed_and_alarms_when_stopped() {
    let dir = TempDir::new("g95");
    dir.write("stopped.nc", "G95 G01 X10. F0.1\nS1000 M03\nX20.\nM30\n");
    let o = vcnc_in(dir.path(), &["run", "--format", "gcode", "stopped.nc"]);
    assert_eq!(code(&o), 1);
    let text = stdout(&o);
    assert!(text.contains("(ALARM E342 line 1:"), "{text}");
    dir.write("turning.nc", "S1000 M03\nG95 G01 X10. F0.1\nX20.\nM30\n");
    let o = vcnc_in(dir.path(), &["run", "--format", "gcode", "turning.nc"]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let text = stdout(&o);
    // 0.1 mm/rev at 1000 rpm is 100 mm/min; Y and Z, never moved, are not
    // written (the program starts where the machine is).
    assert!(text.contains("\nG1 X10. F100\n"), "{text}");
    // `--coords machine`, for comparisons: the flattened program starts
    // where the source machine does.
    let o = vcnc_in(
        dir.path(),
        &[
            "run",
            "--format",
            "gcode",
            "--coords",
            "machine",
            "turning.nc",
        ],
    );
    let text = stdout(&o);
    assert!(
        text.contains("G21 G90 G94 G17\nG0 X0. Y0. Z0. (power-on position)\n"),
        "{text}"
    );
    assert!(text.contains("G1 X10. Y0. Z0. F100\n"), "{text}");
}

/// `vcnc run big.nc | head -1`: when the reader goes away the run stops at
/// once. The program here runs a subprogram 99,999,999 times and would run
/// until the block limit alarms (exit 1); stopping because the output
/// closed is a clean exit 0.
#[test]
fn run_stops_when_its_reader_goes_away() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let dir = TempDir::new("head");
    let file = dir.write(
        "forever.nc",
        "S1000 M03\nM98 P2 L99999999\nM30\nO0002\nG91 G01 X0.001 F1000.\nG01 X-0.001\nM99\n",
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["run", file.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vcnc starts");
    let mut out = BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    out.read_line(&mut first).unwrap();
    assert!(first.starts_with("{\"type\":\"spindle\""), "{first}");
    drop(out);
    let status = child.wait().unwrap();
    assert_eq!(
        status.code(),
        Some(0),
        "stopped early, not by the jump limit"
    );
}

/// `vcnc check bracket.nc | head -1`: the summary's reader went away after
/// one line; `check` exits as the program's result says (0 here) without
/// an `error: Broken pipe` on stderr.
#[test]
fn check_is_quiet_when_its_reader_goes_away() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["check", "examples/bracket.nc"])
        .current_dir(workspace())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("vcnc starts");
    // Close the pipe before vcnc writes: its first write fails.
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
}

/// Without `--dialect`, a `.ngc` program (LinuxCNC's extension) is read as
/// LinuxCNC: `G20`, integers in whole units, `;` comments; the same text
/// in a `.nc` file is read by its text alone (grbl, which reads it the
/// same); `--dialect` always wins.
#[test]
fn a_ngc_program_defaults_to_the_linuxcnc_dialect() {
    let dir = TempDir::new("ngc");
    let text = "G21 G90 ; mm\nG0 X5\nM2\n";
    let ngc = dir.write("part.ngc", text);
    let nc = dir.write("part.nc", text);
    let (ngc, nc) = (ngc.to_str().unwrap(), nc.to_str().unwrap());
    let o = vcnc(&["run", ngc]);
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    assert_eq!(jsonl(&o)[0]["to"]["x"], json!(5.0));
    let o = vcnc(&["check", ngc]);
    assert!(
        stdout(&o).contains("\ndialect    linuxcnc (auto: .ngc file, "),
        "{}",
        stdout(&o)
    );
    let o = vcnc(&["check", nc]);
    assert_eq!(code(&o), 0);
    assert!(
        stdout(&o).contains("\ndialect    grbl (auto: whole-unit integers (X5), \"; comments\", no lathe sign; linuxcnc read it alike)\n"),
        "{}",
        stdout(&o)
    );
    // Each file of a directory by itself: both run.
    assert_eq!(code(&vcnc(&["check", ngc, nc])), 0);
    // Syntec: G21 is no code of its (G70/G71 units).
    assert_eq!(code(&vcnc(&["check", nc, "--dialect", "syntec"])), 1);
    let o = vcnc(&["check", ngc, "--dialect", "fanuc"]);
    assert_eq!(
        code(&o),
        1,
        "`;` ends the block under fanuc: {}",
        stdout(&o)
    );
}

/// `vcnc explain` answers from the dialect tables: G87 is back boring on a
/// Fanuc mill (Syntec manual 1.2.40) and chip-breaking pecks in EIA-274-D
/// (seed 004, §5), and grbl has no G87.
#[test]
fn explain_g87_says_what_each_table_says() {
    let o = vcnc(&["explain", "G87"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("G87 (syntec, fanuc): back boring"), "{out}");
    assert!(
        out.contains("G87 (eia): chip-breaking peck drilling"),
        "{out}"
    );
    assert!(out.contains("grbl"), "{out}");
    let o = vcnc(&["explain", "g87", "--dialect", "GRBL"]);
    assert_eq!(stdout(&o), "G87 (grbl): not a code of this dialect\n");
}

/// A query that is neither a code nor a letter is a usage error.
#[test]
fn explain_refuses_what_is_not_a_code() {
    let o = vcnc(&["explain", "G1e5"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("is not a code or an address"),
        "{}",
        stderr(&o)
    );
}

/// The matrix in docs/dialects.md is the one the tables make today.
#[test]
fn the_dialect_matrix_in_the_docs_is_the_tables() {
    let o = vcnc(&["explain", "--matrix"]);
    assert_eq!(o.status.code(), Some(0));
    let doc = std::fs::read_to_string(workspace().join("docs/dialects.md")).unwrap();
    let start = doc.find("<!-- matrix:start -->\n").expect("start marker") + 22;
    let end = doc.find("<!-- matrix:end -->").expect("end marker");
    assert!(
        doc[start..end] == stdout(&o),
        "docs/dialects.md's matrix is stale: regenerate it with `vcnc explain --matrix`"
    );
}

// ---------------------------------------------------------------------------
// Tools and machines: --tools, vcnc tools, machine --print, $$ dumps
// ---------------------------------------------------------------------------

/// `--tools` fills D: G41 D1 with tools.csv's tool 1 (6 mm across, radius
/// 3) offsets the path; without a table the built-in mill's D1 is 0, the
/// path is the programmed one and W108 says why.
#[test]
fn a_tool_table_fills_the_radius_compensation_reads() {
    let dir = TempDir::new("tools-comp");
    dir.write(
        "comp.nc",
        "S1000 M03\nG00 X-10. Y0. Z0.\nG41 D1 G01 X0. Y0. F300.\nX50.\nG40 X60. Y-10.\nM30\n",
    );
    let table = workspace().join("tests/fixtures/tools/tools.csv");
    let table = table.to_str().unwrap();
    // Start-up east along Y0 with the tool on the left: the offset path is
    // Y = +3, so the first compensated move ends at X0 Y3.
    let o = vcnc_in(
        dir.path(),
        &["run", "comp.nc", "--dialect", "fanuc", "--tools", table],
    );
    assert_eq!(code(&o), 0, "{}", stderr(&o));
    let feeds: Vec<Value> = jsonl(&o)
        .into_iter()
        .filter(|e| e["type"] == "feed")
        .collect();
    assert_eq!(feeds[0]["to"], json!({"x": 0.0, "y": 3.0, "z": 0.0}));
    assert!(!stderr(&o).contains("W108"), "{}", stderr(&o));
    let o = vcnc_in(dir.path(), &["run", "comp.nc", "--dialect", "fanuc"]);
    let feeds: Vec<Value> = jsonl(&o)
        .into_iter()
        .filter(|e| e["type"] == "feed")
        .collect();
    assert_eq!(feeds[0]["to"], json!({"x": 0.0, "y": 0.0, "z": 0.0}));
    assert!(
        stderr(&o).contains("warning[W108]: compensation with G41 D1 = 0"),
        "{}",
        stderr(&o)
    );
}

/// What `vcnc machine --print` prints reads back to the machine a run
/// uses: every dialect's built-in machine, a machine file, a `$$` dump.
#[test]
fn machine_print_reads_back_to_the_same_machine() {
    use vcnc_interp::{Dialect, Machine};
    for name in Dialect::NAMES {
        let o = vcnc(&["machine", "--print", "--dialect", name]);
        assert_eq!(code(&o), 0, "{name}: {}", stderr(&o));
        let printed = Machine::from_toml(&stdout(&o)).expect(name);
        assert_eq!(printed, Dialect::by_name(name).unwrap().machine(), "{name}");
    }
    let file = "tests/fixtures/machines/mill_tools.toml";
    let o = vcnc(&["machine", "--print", "--machine", file]);
    let text = std::fs::read_to_string(workspace().join(file)).unwrap();
    assert_eq!(stdout(&o), text);
    let dump = "tests/fixtures/machines/grblhal_4axis.txt";
    let o = vcnc(&["machine", "--print", "--machine", dump]);
    let printed = Machine::from_toml(&stdout(&o)).unwrap();
    let text = std::fs::read_to_string(workspace().join(dump)).unwrap();
    assert_eq!(
        printed,
        vcnc_core::grbl_settings::machine(&text, dump).unwrap()
    );
    // A run on the dump is a run on that machine: 4 axes, soft limits.
    let dir = TempDir::new("grbl-dump");
    dir.write("over.nc", "G0 X-350.\nM30\n");
    let dump_path = workspace().join(dump);
    let o = vcnc_in(
        dir.path(),
        &[
            "check",
            "over.nc",
            "--dialect",
            "grbl",
            "--machine",
            dump_path.to_str().unwrap(),
        ],
    );
    assert_eq!(
        code(&o),
        1,
        "X travel is 300 mm from 0 down: {}",
        stdout(&o)
    );
    assert!(stderr(&o).contains("E501"), "{}", stderr(&o));
    // `machine` without --print is a usage error.
    assert_eq!(code(&vcnc(&["machine"])), 2);
}

/// Files that are not tool tables or machines stop the run with exit 2 and
/// nothing on stdout: an empty table, binary bytes, a file too large to be
/// one (not read into memory), a directory.
#[test]
fn files_that_are_not_tables_or_machines_are_refused() {
    let dir = TempDir::new("not-tables");
    dir.write("p.nc", "G0 X1.\nM30\n");
    dir.write("empty.tbl", "");
    std::fs::write(
        dir.path().join("binary.tbl"),
        [0u8, 159, 146, 150, 255, 10, 84],
    )
    .unwrap();
    let huge = std::fs::File::create(dir.path().join("huge.tbl")).unwrap();
    huge.set_len(17 << 20).unwrap();
    for (option, file, needle) in [
        (
            "--tools",
            "empty.tbl",
            "empty.tbl:0: the table lists no tool",
        ),
        ("--tools", "binary.tbl", "binary.tbl:1:"),
        ("--tools", "huge.tbl", "larger than 16 MiB"),
        ("--machine", "huge.tbl", "larger than 16 MiB"),
        ("--tools", ".", "cannot read tool table"),
    ] {
        let o = vcnc_in(dir.path(), &["run", "p.nc", option, file]);
        assert_eq!(code(&o), 2, "{file}: {}", stderr(&o));
        assert_eq!(stdout(&o), "", "{file}");
        assert!(stderr(&o).contains(needle), "{file}: {}", stderr(&o));
    }
}

/// Review #15: a tool table or machine file that holds terminal escape
/// sequences (ESC ] … BEL sets the window title, ESC [ 2 J clears the
/// screen) is quoted in its error with the control characters shown as
/// control pictures (`␛`, `␇`), as an alarm's source line shows a
/// program's, never written raw to the terminal.
#[test]
fn tool_table_and_machine_file_errors_do_not_write_escape_sequences() {
    let dir = TempDir::new("escapes");
    dir.write("h.nc", "G0 X0\nM30\n");
    dir.write("esc.csv", "tool,diameter\n1,\u{1b}]0;pwned\u{7}\n");
    dir.write("esc.tbl", "T1 P1 D\u{1b}[31m6 ;\n");
    dir.write("esc.toml", "[axes.x]\nfoo\u{1b}[2J = 1\n");
    for (flag, file, shown) in [
        ("--tools", "esc.csv", "\u{241b}]0;pwned\u{2407}"),
        ("--tools", "esc.tbl", "D\u{241b}[31m6"),
        ("--machine", "esc.toml", "foo\u{241b}[2J"),
    ] {
        let o = vcnc_in(
            dir.path(),
            &["check", "--dialect", "fanuc", flag, file, "h.nc"],
        );
        let err = stderr(&o);
        assert_eq!(code(&o), 2, "{file}: {err}");
        assert!(
            !err.contains('\u{1b}') && !err.contains('\u{7}'),
            "{file}: {err:?}"
        );
        assert!(err.contains(shown), "{file}: {err}");
    }
}
