//! The Python module's tests (python/tests, pytest), run from `cargo test`
//! so that `.ci/run` runs them: the module is built and installed with
//! maturin (`pip install ./python`, as a user does) into the virtual
//! environment that `tools/install-test-deps.sh` makes with maturin and
//! pytest (`target/python-venv`, or `$VCNC_PYTHON_VENV`). Without it this
//! test fails and says how to make it.
//!
//! The module builds in `target/python` (its own Cargo workspace: see
//! python/Cargo.toml), so a second run rebuilds only what changed.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use std::path::{Path, PathBuf};
use std::process::Command;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

fn run(cmd: &mut Command, what: &str) {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    println!("{stdout}");
    assert!(out.status.success(), "{what} failed:\n{stdout}\n{stderr}");
}

#[test]
fn the_python_module_builds_and_passes_its_tests() {
    let root = workspace();
    let venv = std::env::var_os("VCNC_PYTHON_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target/python-venv"));
    let bin = venv.join("bin");
    assert!(
        bin.join("maturin").exists() && bin.join("pytest").exists(),
        "this test fails: no virtual environment with maturin and pytest at {}; run tools/install-test-deps.sh (or set VCNC_PYTHON_VENV)",
        venv.display()
    );
    let path = std::env::join_paths(std::iter::once(bin.clone()).chain(std::env::split_paths(
        &std::env::var_os("PATH").unwrap_or_default(),
    )))
    .unwrap();
    run(
        Command::new(bin.join("pip"))
            .args([
                "install",
                "--quiet",
                "--no-build-isolation",
                "--force-reinstall",
                "--no-deps",
            ])
            .arg(root.join("python"))
            .env("PATH", &path)
            .env("CARGO_TARGET_DIR", root.join("target/python"))
            .env_remove("CARGO_BUILD_TARGET_DIR"),
        "pip install ./python",
    );
    run(
        Command::new(bin.join("python"))
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(root.join("python/tests"))
            .env("PATH", &path)
            .env("VCNC_BIN", env!("CARGO_BIN_EXE_vcnc"))
            .current_dir(root.join("python")),
        "pytest python/tests",
    );
}
