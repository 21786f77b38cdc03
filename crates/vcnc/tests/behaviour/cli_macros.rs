//! CLI behaviour of macro programs: `--format gcode` flattens them to plain
//! moves that grbl runs, `check` lists the variables read but never set,
//! and `--variables FILE` keeps the power-off variables between runs.
//! Expected text is written from the documents (`docs/cli.md`,
//! `docs/macros.md`), not captured from a run.

use crate::common::{vcnc_fed, workspace};
use std::path::Path;
use std::process::Output;

/// Runs `vcnc args…` in the workspace root, `stdin` as its standard input.
fn vcnc(args: &[&str], stdin: Option<&str>) -> Output {
    vcnc_fed(&workspace(), args, stdin.unwrap_or("").as_bytes())
}

fn text(o: &[u8]) -> String {
    String::from_utf8(o.to_vec()).unwrap()
}

/// End points of the motion lines of JSON-lines output, rounded to 1 µm.
fn ends(jsonl: &str) -> Vec<(String, [i64; 3])> {
    jsonl
        .lines()
        .filter_map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            let kind = v["type"].as_str()?.to_string();
            let to = v.get("to")?;
            // Machine coordinates of a test program: far within i64.
            #[allow(clippy::cast_possible_truncation)]
            let r = |k: &str| (to[k].as_f64().unwrap_or(0.0) * 1000.0).round() as i64;
            Some((kind, [r("x"), r("y"), r("z")]))
        })
        .collect()
}

#[test]
fn a_macro_program_flattens_to_plain_moves_that_grbl_runs() {
    let program = "corpus/mill-fanuc/jobline-macro-bolt-circle.nc";
    let events = vcnc(&["run", "--dialect", "fanuc", program], None);
    assert_eq!(events.status.code(), Some(0), "{}", text(&events.stderr));
    let flat = vcnc(
        &["run", "--dialect", "fanuc", "--format", "gcode", program],
        None,
    );
    assert_eq!(flat.status.code(), Some(0));
    let flat = text(&flat.stdout);
    assert!(!flat.contains('#') && !flat.contains('['), "{flat}");
    // Loops, cycles and variables are gone: only plain codes (the holes
    // stay as comments).
    assert!(!flat.contains("WHILE"), "{flat}");
    assert!(!flat.lines().any(|l| l.starts_with("G83")), "{flat}");
    // The flattened program run by the grbl dialect moves the same way.
    let again = vcnc(&["run", "--dialect", "grbl", "-"], Some(&flat));
    assert_eq!(again.status.code(), Some(0), "{}", text(&again.stderr));
    let want = ends(&text(&events.stdout));
    assert_eq!(ends(&text(&again.stdout)), want);
}

#[test]
fn check_lists_the_variables_read_but_never_set() {
    let program = "G90\n#1 = #101 + 1\nIF [#24 EQ #0] GOTO 10\nN10 #102 = 5\n#2 = #102\nM30\n";
    let out = vcnc(&["check", "--dialect", "fanuc", "-"], Some(program));
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("unset vars 2 read but never set: #101 (line 2), #24 (line 3)\n"),
        "{stdout}"
    );
    let out = vcnc(
        &["check", "--format", "json", "--dialect", "fanuc", "-"],
        Some(program),
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let unset = &doc["files"][0]["summary"]["unset_variables"];
    assert_eq!(unset[0]["name"], "#101");
    assert_eq!(unset[0]["line"], 2);
    assert_eq!(unset[1]["name"], "#24");
}

#[test]
fn kept_variables_survive_between_runs_in_a_file() {
    let dir = std::env::temp_dir().join(format!("vcnc-vars-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vars = dir.join("vars.txt");
    let _ = std::fs::remove_file(&vars);
    let program = dir.join("count.nc");
    std::fs::write(&program, "#500 = #500 + 1\n#100 = 7\nM30\n").unwrap();
    let args = |v: &Path, p: &Path| {
        vec![
            "run".to_string(),
            "--dialect".into(),
            "fanuc".into(),
            "--variables".into(),
            v.display().to_string(),
            p.display().to_string(),
        ]
    };
    for _ in 0..3 {
        let a = args(&vars, &program);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let out = vcnc(&a, None);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    }
    // Three runs counted to 3; #100 is common but not kept.
    let kept = std::fs::read_to_string(&vars).unwrap();
    assert_eq!(
        kept,
        "// vcnc kept macro variables (--variables)\n#500 = 3.0\n"
    );
    // A variable this controller does not keep is a usage error.
    std::fs::write(&vars, "#100 = 1.0\n").unwrap();
    let a = args(&vars, &program);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let out = vcnc(&a, None);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("#100"), "{}", text(&out.stderr));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `check DIR --variables F` runs the programs in order with one variable
/// memory: the second program reads what the first kept.
#[test]
fn a_batch_check_with_a_variables_file_runs_in_order_with_one_memory() {
    let dir = std::env::temp_dir().join(format!("vcnc-vars-batch-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let programs = dir.join("programs");
    std::fs::create_dir_all(&programs).unwrap();
    // In name order: a sets the counter, b doubles it, c adds one. Run in
    // parallel or out of order, the result would differ from 11.
    std::fs::write(programs.join("a.nc"), "#500 = 5\nM30\n").unwrap();
    std::fs::write(programs.join("b.nc"), "#500 = #500 * 2\nM30\n").unwrap();
    std::fs::write(programs.join("c.nc"), "#500 = #500 + 1\n#501 = #500\nM30\n").unwrap();
    let vars = dir.join("vars.txt");
    let (p, v) = (programs.display().to_string(), vars.display().to_string());
    let out = vcnc(
        &["check", "--dialect", "fanuc", "--variables", &v, &p],
        None,
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        std::fs::read_to_string(&vars).unwrap(),
        "// vcnc kept macro variables (--variables)\n#500 = 11.0\n#501 = 11.0\n"
    );
    // Nothing but the variables file is left beside it (no temporary file).
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A variables file that cannot be written after the run is an error (2),
/// but what the run wrote stays written: the CSV and G-code sinks are
/// flushed as when no variables file is given, also now that they run on
/// a second thread.
#[test]
fn a_variables_file_that_cannot_be_written_keeps_the_output() {
    let dir = std::env::temp_dir().join(format!("vcnc-vars-lost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let program = dir.join("moves.nc");
    std::fs::write(&program, "#500 = 1\nG00 X1. Y2.\nG01 Z-1. F100.\nM30\n").unwrap();
    let program = program.display().to_string();
    // Its directory does not exist.
    let vars = dir.join("missing").join("vars.txt").display().to_string();
    for format in ["csv", "gcode"] {
        let plain = vcnc(
            &["run", "--dialect", "fanuc", "--format", format, &program],
            None,
        );
        assert_eq!(plain.status.code(), Some(0), "{}", text(&plain.stderr));
        assert!(!plain.stdout.is_empty());
        let failed = vcnc(
            &[
                "run",
                "--dialect",
                "fanuc",
                "--format",
                format,
                "--variables",
                &vars,
                &program,
            ],
            None,
        );
        assert_eq!(failed.status.code(), Some(2), "{}", text(&failed.stderr));
        assert!(
            text(&failed.stderr).contains("variables file"),
            "{}",
            text(&failed.stderr)
        );
        assert_eq!(
            text(&failed.stdout),
            text(&plain.stdout),
            "--format {format}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn messages_reach_the_event_stream() {
    let out = vcnc(
        &["run", "--dialect", "fanuc", "-"],
        Some("#3006 = 1 (TURN THE PART)\nM30\n"),
    );
    assert_eq!(
        text(&out.stdout),
        "{\"type\":\"message\",\"line\":1,\"text\":\"TURN THE PART\",\"stop\":true}\n{\"type\":\"end\",\"line\":2,\"code\":\"M30\"}\n"
    );
    let out = vcnc(
        &["run", "--dialect", "fanuc", "--format", "gcode", "-"],
        Some("#3006 = 1 (TURN THE PART)\nM30\n"),
    );
    assert!(
        text(&out.stdout).contains("M0 (message: TURN THE PART)\n"),
        "{}",
        text(&out.stdout)
    );
}
