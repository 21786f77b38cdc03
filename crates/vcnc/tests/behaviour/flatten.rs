//! The flattened program a user runs (`vcnc run --format gcode`): written
//! in the program's work systems and units, it moves the machine as the
//! original did — run again by vcnc under the grbl and linuxcnc dialects,
//! and by LinuxCNC's `rs274`, on a machine whose G54 and G55 are not zero
//! (`tests/fixtures/flatten/`).
//!
//! rs274's moves were made by `tools/linuxcnc/make_flatten_fixtures.py` from
//! the flattened text committed beside them (`NAME.flat.ngc`), so a test
//! also checks that vcnc still writes exactly that text; CI needs no
//! LinuxCNC. Moves compare as the sequence of distinct end points (a move
//! that goes nowhere moves nothing), arcs with their centres and sense,
//! feeds where both give one; within rs274's four printed decimals.

use crate::common::{vcnc_fed, workspace};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn set() -> PathBuf {
    workspace().join("tests/fixtures/flatten")
}

/// Runs vcnc in the repository root, `stdin` as standard input: exit code,
/// stdout, stderr.
fn vcnc(args: &[&str], stdin: Option<&str>) -> (i32, String, String) {
    let o = vcnc_fed(&workspace(), args, stdin.unwrap_or("").as_bytes());
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// One move: kind, end point, arc centre and sense, feed.
#[derive(Debug)]
struct Move {
    kind: String,
    to: [f64; 3],
    center: Option<([f64; 3], String)>,
    feed: Option<f64>,
}

fn xyz(v: &Value) -> [f64; 3] {
    ["x", "y", "z"].map(|k| v[k].as_f64().unwrap_or(0.0))
}

/// The moves of JSON-lines events, without the ones that go nowhere.
fn moves(jsonl: &str) -> Vec<Move> {
    let mut at = [0.0; 3];
    let mut out = Vec::new();
    for line in jsonl.lines().filter(|l| !l.trim().is_empty()) {
        let e: Value = serde_json::from_str(line).unwrap();
        let kind = e["type"].as_str().unwrap_or("").to_string();
        if !matches!(kind.as_str(), "rapid" | "feed" | "arc") {
            continue;
        }
        let to = xyz(&e["to"]);
        let still = (0..3).all(|i| (to[i] - at[i]).abs() < 1e-7);
        if still && kind != "arc" {
            continue;
        }
        at = to;
        out.push(Move {
            center: (kind == "arc").then(|| {
                (
                    xyz(&e["center"]),
                    e["dir"].as_str().unwrap_or("").to_string(),
                )
            }),
            kind,
            to,
            feed: e["feed"].as_f64(),
        });
    }
    out
}

fn same(want: &[Move], got: &[Move], tol: f64, what: &str) {
    assert_eq!(
        want.len(),
        got.len(),
        "{what}: {} moves, the original makes {}\n{got:?}",
        got.len(),
        want.len()
    );
    for (i, (a, b)) in want.iter().zip(got).enumerate() {
        let near = |p: [f64; 3], q: [f64; 3]| (0..3).all(|k| (p[k] - q[k]).abs() <= tol);
        let ok = a.kind == b.kind
            && near(a.to, b.to)
            && match (&a.center, &b.center) {
                (Some((c, d)), Some((e, f))) => near(*c, *e) && d == f,
                (None, None) => true,
                _ => false,
            }
            && match (a.feed, b.feed) {
                (Some(f), Some(g)) => (f - g).abs() <= 0.01 + f * 1e-6,
                _ => true,
            };
        assert!(
            ok,
            "{what}: move {} differs\n  original: {a:?}\n  got:      {b:?}",
            i + 1
        );
    }
}

struct Program {
    path: String,
    dialect: String,
    opts: Vec<String>,
}

fn programs() -> Vec<Program> {
    std::fs::read_to_string(set().join("programs.txt"))
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let mut w = l.split_whitespace().map(str::to_string);
            Program {
                path: w.next().unwrap(),
                dialect: w.next().unwrap(),
                opts: w.collect(),
            }
        })
        .collect()
}

fn name_of(path: &str) -> String {
    Path::new(path)
        .file_stem()
        .unwrap()
        .to_string_lossy()
        .into_owned()
}

const MACHINE: &str = "tests/fixtures/flatten/machine.toml";

fn run(p: &Program, extra: &[&str]) -> String {
    let mut args = vec!["run", "--dialect", &p.dialect, "--machine", MACHINE];
    args.extend(p.opts.iter().map(String::as_str));
    args.extend_from_slice(extra);
    args.push(&p.path);
    let (code, out, err) = vcnc(&args, None);
    assert_eq!(code, 0, "{}: {err}", p.path);
    out
}

#[test]
fn flattened_programs_move_as_the_originals_under_grbl_and_linuxcnc() {
    let list = programs();
    assert!(list.len() >= 7, "only {} programs", list.len());
    for p in &list {
        let original = moves(&run(p, &[]));
        let flat = run(p, &["--format", "gcode"]);
        for dialect in ["grbl", "linuxcnc"] {
            let (code, out, err) = vcnc(
                &["run", "--dialect", dialect, "--machine", MACHINE, "-"],
                Some(&flat),
            );
            assert_eq!(code, 0, "{} under {dialect}: {err}\n{flat}", p.path);
            same(
                &original,
                &moves(&out),
                1e-4,
                &format!("{} under {dialect}", p.path),
            );
        }
    }
}

#[test]
fn flattened_programs_move_as_the_originals_under_rs274() {
    for p in &programs() {
        let name = name_of(&p.path);
        let flat = run(p, &["--format", "gcode"]);
        let committed = std::fs::read_to_string(set().join(format!("{name}.flat.ngc"))).unwrap();
        assert!(
            flat == committed,
            "{name}: vcnc no longer writes the text rs274 ran; run \
             tools/linuxcnc/make_flatten_fixtures.py and review the diff\n{flat}"
        );
        let rs274 = std::fs::read_to_string(set().join(format!("{name}.rs274.jsonl"))).unwrap();
        // rs274 prints four decimals of the program's units.
        let tol = if flat.contains("\nG20") { 2e-3 } else { 2e-4 };
        same(
            &moves(&run(p, &[])),
            &moves(&rs274),
            tol,
            &format!("{name} by rs274"),
        );
    }
}

/// The header names the first work system and the program's units; no
/// move is invented; G53 stays G53; `--units` and `--coords machine`.
#[test]
fn work_systems_units_and_machine_moves_are_written_out() {
    let p = |path: &str| Program {
        path: format!("tests/fixtures/flatten/{path}"),
        dialect: "fanuc".into(),
        opts: Vec::new(),
    };
    let work = run(&p("work_systems.nc"), &["--format", "gcode"]);
    let lines: Vec<&str> = work.lines().collect();
    assert_eq!(lines[2], "G21 G90 G94 G17 G54");
    // G53 G0 Z0. at the power-on point (machine Z0) does not move, so it is
    // not written; X and Y, which the program has not placed, are not
    // written before it places them.
    assert_eq!(lines[4], "G0 X10. Y10.");
    assert!(lines.contains(&"G55"), "{work}");
    // G28 X0. Y0.: its reference leg is a machine move of X and Y.
    assert!(lines.contains(&"G53 G0 X0. Y0."), "{work}");
    assert!(!work.contains("power-on"), "{work}");

    let inch = run(&p("inch_rotated_comp.nc"), &["--format", "gcode"]);
    assert!(inch.contains("\nG20 G90 G94 G17 G55\n"), "{inch}");
    let mm = run(
        &p("inch_rotated_comp.nc"),
        &["--format", "gcode", "--units", "mm"],
    );
    assert!(mm.contains("\nG21 G90 G94 G17 G55\n"), "{mm}");
    // Y-0.5 in G55 is -12.7 mm either way.
    assert!(mm.contains("\nG0 X-12.7 Y-12.7\n"), "{mm}");
    assert!(inch.contains("\nG0 X-0.5 Y-0.5\n"), "{inch}");

    let machine = run(
        &p("work_systems.nc"),
        &["--format", "gcode", "--coords", "machine"],
    );
    assert!(
        machine.contains("G21 G90 G94 G17\nG0 X0. Y0. Z0. (power-on position)\n"),
        "{machine}"
    );
    // G54 X10. Y10. is machine X111.6 Y60.8.
    assert!(machine.contains("\nG0 X111.6 Y60.8 Z0.\n"), "{machine}");
}

/// The markers `with_program_markers` adds, worked out by hand: G53 Z0.
/// names Z (a machine move); G55 and G20 change the work system and the
/// units; X0 Y0 places X and Y although they do not move (the built-in
/// mill starts at 0); Z1 places Z again after the G53; G28 X0 names X, whose
/// reference leg is a machine move. Without the builder call none come.
#[test]
fn program_markers_say_what_program_coordinates_need() {
    use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, VecSink};
    let program = "G53 G0 Z0.\nG55 G20\nG0 X0. Y0.\nZ1.\nG28 X0.\nM30\n";
    let m = Machine::default_mill();
    let d = Dialect::fanuc();
    let mut sink = VecSink::default();
    Interpreter::new(&m, &d, Options::default())
        .with_program_markers()
        .run_str(program, &mut sink);
    let markers: Vec<String> = sink
        .0
        .iter()
        .filter_map(|e| match e {
            Event::MachineMove { loc, axes, .. } => Some(format!("{} machine {axes:b}", loc.line)),
            Event::Placed { loc, axes } => Some(format!("{} placed {axes:b}", loc.line)),
            Event::WorkSystem { loc, system } => Some(format!("{} system {system:?}", loc.line)),
            Event::Units { loc, inch } => Some(format!("{} inch {inch}", loc.line)),
            _ => None,
        })
        .collect();
    assert_eq!(
        markers,
        vec![
            "1 machine 100",
            "2 system Some(1)",
            "2 inch true",
            "3 placed 11",
            "4 placed 100",
            "5 machine 1",
        ]
    );
    let mut plain = VecSink::default();
    Interpreter::new(&m, &d, Options::default()).run_str(program, &mut plain);
    assert!(plain.0.iter().all(|e| !matches!(
        e,
        Event::MachineMove { .. }
            | Event::Placed { .. }
            | Event::WorkSystem { .. }
            | Event::Units { .. }
    )));
}
