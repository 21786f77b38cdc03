//! The conformance snapshot: every main program of `corpus/` (real public
//! part programs, see `corpus/README.md`) run through `vcnc check` with the
//! dialect its manifest names, one line per program and a count per
//! dialect. The snapshot (`tests/snapshots/conformance__corpus.snap`)
//! changes whenever a change moves the numbers, so review shows it (the
//! model is oxc's coverage snapshots).

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../corpus")
        .canonicalize()
        .expect("corpus folder")
}

/// How one program ended, as `vcnc check` reports it.
fn result_of(dir: &Path, path: &str, dialect: &str) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_vcnc"))
        .args(["check", "--dialect", dialect, path])
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

#[test]
fn corpus_conformance() {
    let dir = corpus();
    let manifest: toml::Value =
        toml::from_str(&std::fs::read_to_string(dir.join("manifest.toml")).unwrap()).unwrap();
    let programs = manifest["program"].as_array().unwrap();
    let mut lines = Vec::new();
    // dialect → (programs, ran to the end)
    let mut counts: BTreeMap<String, (u32, u32)> = BTreeMap::new();
    for p in programs {
        if p.get("role").and_then(|r| r.as_str()) == Some("subprogram") {
            continue;
        }
        let path = p["path"].as_str().unwrap();
        let dialect = p["dialect"].as_str().unwrap();
        let result = result_of(&dir, path, dialect);
        let ended = result.starts_with("ended");
        let c = counts.entry(dialect.to_string()).or_default();
        c.0 += 1;
        c.1 += u32::from(ended);
        lines.push(format!("{path} [{dialect}]: {result}"));
    }
    let (total, ended) = counts
        .values()
        .fold((0, 0), |(t, e), (pt, pe)| (t + pt, e + pe));
    let mut text = format!("{ended} of {total} programs run to the end\n");
    for (d, (t, e)) in &counts {
        text.push_str(&format!("  {d}: {e} of {t}\n"));
    }
    text.push('\n');
    text.push_str(&lines.join("\n"));
    text.push('\n');
    insta::assert_snapshot!("corpus", text);
}
