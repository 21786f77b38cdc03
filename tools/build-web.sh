#!/usr/bin/env bash
# Builds the offline vcnc page, target/web/vcnc.html (docs/web.md): the
# engine (crates/vcnc_web) for wasm32, wrapped by wasm-bindgen, inlined in
# base64 beside the app's scripts (web/src, bundled by esbuild with
# CodeMirror 6) into one self-contained HTML file that makes no network
# request.
#
#   tools/build-web.sh                 install what is missing, then build
#   tools/build-web.sh --install-only  only install (tools/install-test-deps.sh)
#   tools/build-web.sh --wasm-opt IN OUT   only optimise a wasm-bindgen
#                                      output as the build does (tools/bench/web.sh)
#
# It installs what it needs: the wasm32-unknown-unknown target (rustup),
# wasm-bindgen-cli at exactly the version of the wasm-bindgen crate in
# Cargo.lock (cargo install into target/web-tools, kept there), and the
# npm packages of web/package-lock.json (npm ci into web/node_modules):
# CodeMirror 6, esbuild, and binaryen, whose wasm-opt -O3 optimises the
# engine after wasm-bindgen (docs/performance.md: 8 % off a warm 1 M-block
# run; it takes about a minute, so its output is kept by the input's hash).
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

# wasm-opt -O3 of IN into OUT, kept in $build/opt by IN's hash. The
# features are those rustc enables for wasm32 (rustc --print cfg).
wasm_opt() {
    local hash
    hash="$(sha256sum "$1" | cut -c1-16)"
    mkdir -p "$build/opt"
    if [ ! -f "$build/opt/$hash.wasm" ]; then
        node web/node_modules/binaryen/bin/wasm-opt -O3 \
            --enable-bulk-memory --enable-multivalue --enable-mutable-globals \
            --enable-nontrapping-float-to-int --enable-reference-types --enable-sign-ext \
            "$1" -o "$build/opt/$hash.tmp"
        mv "$build/opt/$hash.tmp" "$build/opt/$hash.wasm"
    fi
    cp "$build/opt/$hash.wasm" "$2"
}

install
if [ "${1:-}" = "--install-only" ]; then
    exit 0
fi
if [ "${1:-}" = "--wasm-opt" ]; then
    wasm_opt "$2" "$3"
    exit 0
fi

cargo build --release --target wasm32-unknown-unknown -p vcnc_web --quiet
mkdir -p "$build/pkg" "$out"
"$tools/bin/wasm-bindgen" --target no-modules --no-typescript \
    --out-dir "$build/pkg" "$target/wasm32-unknown-unknown/release/vcnc_web.wasm"
wasm_opt "$build/pkg/vcnc_web_bg.wasm" "$build/pkg/vcnc_web_bg.wasm"
node web/build.mjs "$build/pkg" "$out/vcnc.html"
