//! What `--dialect auto` costs a run: `detect` on a program's first 64 KiB
//! (the corpus's largest CAM program, 15,163 short G1 lines: the most
//! blocks a prefix holds, as the 1 M-block surfacing program's does), and
//! the one-time cost of the first detection in a process — every
//! dialect's code tables and built-in machines, built once. Against
//! `vcnc check` of the surfacing program (docs/performance.md, "Dialect
//! detection"). Run with `cargo bench -p vcnc_interp --bench detect`.

use divan::Bencher;
use vcnc_interp::detect::{PREFIX_BYTES, detect};
use vcnc_interp::{Dialect, Machine};

fn main() {
    divan::main();
}

fn corpus(path: &str) -> Vec<u8> {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../corpus")
        .join(path);
    match std::fs::read(&file) {
        Ok(bytes) => bytes,
        Err(e) => panic!("{}: {e}", file.display()),
    }
}

/// Detection on a whole file; it reads the first [`PREFIX_BYTES`].
#[divan::bench(args = ["cam-grbl/camotics-bear.nc", "mill-haas/jobline-haas-vf2-lang-makrogrip.nc", "lathe-fanuc/jobline-lathe-turning.nc"])]
fn detect_a_program(bencher: Bencher, path: &str) {
    let bytes = corpus(path);
    assert!(path.contains("haas") || path.contains("lathe") || bytes.len() > PREFIX_BYTES);
    // Warm: the tables are built once per process.
    let _ = detect(&bytes, Some(path));
    bencher.bench(|| detect(divan::black_box(&bytes), Some(path)));
}

/// What the first detection of a process builds: every dialect's tables
/// and its built-in machine's (four distinct) machine files.
#[divan::bench]
fn build_every_dialect_and_machine() -> usize {
    let mut n = 0;
    for name in Dialect::NAMES {
        if let Some(d) = Dialect::by_name(name) {
            n += Machine::from_toml(d.default_machine).map_or(0, |m| m.m_codes.len());
        }
    }
    n
}
