#!/usr/bin/env bash
# Builds the offline vcnc page, target/web/vcnc.html (docs/web.md): the
# engine (crates/vcnc_web) for wasm32, wrapped by wasm-bindgen, inlined in
# base64 beside the app's scripts (web/src, bundled by esbuild with
# CodeMirror 6) into one self-contained HTML file that makes no network
# request.
#
#   tools/build-web.sh                 install what is missing, then build
#   tools/build-web.sh --install-only  only install (tools/install-test-deps.sh)
#
# It installs what it needs: the wasm32-unknown-unknown target (rustup),
# wasm-bindgen-cli at exactly the version of the wasm-bindgen crate in
# Cargo.lock (cargo install into target/web-tools, kept there), and the
# npm packages of web/package-lock.json (npm ci into web/node_modules).
# Needs cargo, rustup, node and npm. Run it from anywhere; it does not
# take the workspace's cargo lock (the caller does).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
target="${CARGO_TARGET_DIR:-$root/target}"
tools="$root/target/web-tools"
out="$root/target/web"
build="$root/target/web-build"

# The wasm-bindgen crate's version, which the CLI must match exactly.
bindgen_version="$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)"
if [ -z "$bindgen_version" ]; then
    echo "build-web: no wasm-bindgen in Cargo.lock" >&2
    exit 2
fi

install() {
    if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
        rustup target add wasm32-unknown-unknown
    fi
    if [ "$("$tools/bin/wasm-bindgen" --version 2>/dev/null | awk '{print $2}')" != "$bindgen_version" ]; then
        cargo install wasm-bindgen-cli --version "$bindgen_version" --root "$tools" --quiet
    fi
    # npm ci when the lock file changed since the last install.
    if ! cmp -s web/package-lock.json web/node_modules/.vcnc-lock 2>/dev/null; then
        (cd web && npm ci --no-audit --no-fund --loglevel=error)
        cp web/package-lock.json web/node_modules/.vcnc-lock
    fi
}

install
if [ "${1:-}" = "--install-only" ]; then
    exit 0
fi

cargo build --release --target wasm32-unknown-unknown -p vcnc_web --quiet
mkdir -p "$build/pkg" "$out"
"$tools/bin/wasm-bindgen" --target no-modules --no-typescript \
    --out-dir "$build/pkg" "$target/wasm32-unknown-unknown/release/vcnc_web.wasm"
node web/build.mjs "$build/pkg" "$out/vcnc.html"
