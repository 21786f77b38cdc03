#!/usr/bin/env bash
# What `cargo test --workspace` needs beyond cargo: headless Chromium and its
# WebDriver, for the viewer page's browser test (crates/vcnc/tests/browser.rs).
# Installed with apt when missing (Debian/Ubuntu, as root); nothing else is
# needed — the LinuxCNC comparison fixtures are committed.
set -euo pipefail
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y chromium chromium-driver
fi
