//! The conformance snapshot: every main program of `corpus/` (real public
//! part programs, see `corpus/README.md`) run through `vcnc check` with the
//! dialect its manifest names, and again with none (`--dialect auto`), one
//! line per program and a count per dialect. The snapshot
//! (`tests/behaviour/snapshots/behaviour__conformance__corpus.snap`) changes whenever a change
//! moves the numbers, so review shows it (the model is oxc's coverage
//! snapshots).
//!
//! Detection must agree with the manifest — the same dialect, or one whose
//! event stream for the program is the same (alarms compared by code, line
//! and column: their messages name the dialect) — for at least 95 % of the
//! programs, and run at least as many of them to the end.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../corpus")
        .canonicalize()
        .expect("corpus folder")
}

/// How one program ended, as `vcnc check` reports it, under `dialect`
/// (`None`: detected).
fn result_of(dir: &Path, path: &str, dialect: Option<&str>) -> String {
    let mut args = vec!["check", path];
    if let Some(d) = dialect {
        args.extend(["--dialect", d]);
    }
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(&args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("vcnc runs");
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    match o.status.code() {
        Some(0 | 1) => {
            let result = stdout
                .lines()
                .find_map(|l| l.strip_prefix("result"))
                .unwrap_or("(no result line)")
                .trim()
                .to_string();
            // The alarm's message, shortened: what stops the program.
            let why = stderr
                .lines()
                .find_map(|l| l.strip_prefix("error["))
                .and_then(|l| l.split_once("alarm: "))
                .map(|(_, m)| {
                    let m: String = m.chars().take(70).collect();
                    format!(" — {m}")
                })
                .unwrap_or_default();
            format!("{result}{why}")
        }
        _ => format!(
            "not run: {}",
            stderr
                .lines()
                .next()
                .unwrap_or("")
                .trim_start_matches("error: ")
        ),
    }
}

/// The dialect `vcnc check` detected for a program (its `dialect` line).
fn detected(dir: &Path, path: &str) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["check", "--format", "json", path])
        .current_dir(dir)
        .output()
        .expect("vcnc runs");
    let doc: serde_json::Value =
        serde_json::from_slice(&o.stdout).unwrap_or(serde_json::Value::Null);
    doc["files"][0]["dialect"]
        .as_str()
        .unwrap_or("(none)")
        .to_string()
}

/// The program's events under `dialect`, alarms and warnings reduced to
/// code, line and column.
fn events(dir: &Path, path: &str, dialect: &str) -> Vec<String> {
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["run", "--format", "jsonl", "--dialect", dialect, path])
        .current_dir(dir)
        .output()
        .expect("vcnc runs");
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| match serde_json::from_str::<serde_json::Value>(l) {
            Ok(mut v) if v["type"] == "alarm" || v["type"] == "warning" => {
                if let Some(obj) = v.as_object_mut() {
                    obj.remove("message");
                    obj.remove("help");
                }
                v.to_string()
            }
            _ => l.to_string(),
        })
        .collect()
}

#[test]
fn corpus_conformance() {
    let dir = corpus();
    let manifest: toml::Value =
        toml::from_str(&std::fs::read_to_string(dir.join("manifest.toml")).unwrap()).unwrap();
    let programs = manifest["program"].as_array().unwrap();
    let mut lines = Vec::new();
    // dialect → (programs, ran to the end)
    let mut counts: BTreeMap<String, (u32, u32)> = BTreeMap::new();
    // Detection: ran to the end, the manifest's dialect, one that runs
    // the program identically.
    let (mut auto_ended, mut same, mut alike) = (0, 0, 0);
    for p in programs {
        if p.get("role").and_then(|r| r.as_str()) == Some("subprogram") {
            continue;
        }
        let path = p["path"].as_str().unwrap();
        let dialect = p["dialect"].as_str().unwrap();
        let result = result_of(&dir, path, Some(dialect));
        let ended = result.starts_with("ended");
        let c = counts.entry(dialect.to_string()).or_default();
        c.0 += 1;
        c.1 += u32::from(ended);
        let auto = detected(&dir, path);
        let auto_result = result_of(&dir, path, None);
        auto_ended += u32::from(auto_result.starts_with("ended"));
        let detection = if auto == dialect {
            same += 1;
            format!("auto {auto}")
        } else if events(&dir, path, &auto) == events(&dir, path, dialect) {
            alike += 1;
            format!("auto {auto}, the same events")
        } else {
            format!("auto {auto}: {auto_result}")
        };
        lines.push(format!("{path} [{dialect}]: {result} | {detection}"));
    }
    let (total, ended) = counts
        .values()
        .fold((0, 0), |(t, e), (pt, pe)| (t + pt, e + pe));
    let mut text = format!("{ended} of {total} programs run to the end\n");
    for (d, (t, e)) in &counts {
        text.push_str(&format!("  {d}: {e} of {t}\n"));
    }
    text.push_str(&format!(
        "with --dialect auto: {auto_ended} of {total} run to the end; the dialect agrees for {} ({same} the manifest's, {alike} one that runs the program identically)\n",
        same + alike
    ));
    assert!(
        auto_ended >= ended,
        "detection runs fewer programs to the end: {auto_ended} < {ended}"
    );
    assert!(
        f64::from(same + alike) >= 0.95 * f64::from(total),
        "detection agrees with the manifest for {} of {total}",
        same + alike
    );
    text.push('\n');
    text.push_str(&lines.join("\n"));
    text.push('\n');
    insta::assert_snapshot!("corpus", text);
}
