#!/usr/bin/env bash
# What `cargo test --workspace` needs beyond cargo: headless Chromium and its
# WebDriver, for the viewer page's browser test (crates/vcnc/tests/browser.rs),
# installed with apt when missing (Debian/Ubuntu, as root); and a Python
# virtual environment with maturin and pytest for the Python module's tests
# (crates/vcnc/tests/python.rs), in target/python-venv; and what the web
# page's build needs (tools/build-web.sh --install-only: the wasm32 target,
# wasm-bindgen-cli in target/web-tools, the npm packages of web/), for its
# browser test (crates/vcnc/tests/web.rs), which builds the page. Nothing
# else is needed — the LinuxCNC comparison fixtures are committed.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y chromium chromium-driver
fi

venv="${VCNC_PYTHON_VENV:-$root/target/python-venv}"
if [ ! -x "$venv/bin/maturin" ] || [ ! -x "$venv/bin/pytest" ]; then
    if ! python3 -m venv "$venv"; then
        apt-get update
        DEBIAN_FRONTEND=noninteractive apt-get install -y python3-venv
        python3 -m venv "$venv"
    fi
    "$venv/bin/pip" install --quiet "maturin>=1.9,<2" "pytest>=7"
fi

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y nodejs npm
fi
"$root/tools/build-web.sh" --install-only
