#!/usr/bin/env bash
# The browser's engine against the native CLI on the surfacing program
# (docs/performance.md, "The browser's engine"): the same wasm the page
# inlines (crates/vcnc_web, release, wasm-opt -O3, wasm-bindgen's Node.js wrapper) run
# by node, against `vcnc time` and `vcnc check` (release). Three runs each;
# the wasm figures are inside one node process (no start-up), the CLI's
# are whole commands (start-up and file reading included).
#
# Then the page itself in headless Chromium (crates/vcnc/benches/web_page.rs):
# the program opened in the editor, checked, and drawn by the viewer.
#
# Usage: tools/bench/web.sh [N]      (N blocks, default 1000000)
# Needs: tools/build-web.sh's tools (it installs them); node; GNU time;
#        chromium and chromium-driver for the page figures.
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-${N:-1000000}}
DIR=${DIR:-/tmp/vcnc_bench_web_${N}}
mkdir -p "$DIR"
tools/build-web.sh --install-only
cargo build --release -p vcnc --quiet
cargo build --release --target wasm32-unknown-unknown -p vcnc_web --quiet
target/web-tools/bin/wasm-bindgen --target nodejs --no-typescript \
    --out-dir "$DIR/node" target/wasm32-unknown-unknown/release/vcnc_web.wasm
# Optimised as the page's (wasm-opt -O3).
tools/build-web.sh --wasm-opt "$DIR/node/vcnc_web_bg.wasm" "$DIR/node/vcnc_web_bg.wasm"
echo "generating $N blocks -> $DIR/surfacing.nc"
python3 tools/bench/gen_surfacing.py "$N" "$DIR/surfacing.nc"

for cmd in time check; do
    for run in 1 2 3; do
        /usr/bin/time -f "native vcnc $cmd run $run: %e s wall, %M KB max RSS" \
            target/release/vcnc "$cmd" "$DIR/surfacing.nc" --dialect fanuc >/dev/null
    done
done
node tools/bench/web_engine.cjs "$DIR/node/vcnc_web.js" "$DIR/surfacing.nc"
tools/build-web.sh
VCNC_WEB_PAGE="$PWD/target/web/vcnc.html" VCNC_WEB_PROGRAM="$DIR/surfacing.nc" \
    cargo bench -p vcnc --bench web_page
