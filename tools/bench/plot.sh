#!/usr/bin/env bash
# Time `vcnc plot` on a large surfacing program: PNG, SVG and HTML output
# (wall time and max RSS, three runs each), then load the HTML page in
# headless Chromium and measure its load, frame and slider times
# (crates/vcnc/benches/plot_page.rs).
#
# Usage: tools/bench/plot.sh [N]        (N blocks, default 1000000)
# Needs: cargo build --release -p vcnc; GNU time; chromium and
#        chromium-driver for the page figures.
set -euo pipefail

cd "$(dirname "$0")/../.."
N=${1:-${N:-1000000}}
VCNC=${VCNC:-target/release/vcnc}
DIR=${DIR:-/tmp/vcnc_bench_plot_${N}}
mkdir -p "$DIR"

echo "generating $N blocks -> $DIR/surfacing.nc"
python3 tools/bench/gen_surfacing.py "$N" "$DIR/surfacing.nc"

for fmt in png svg html; do
    for run in 1 2 3; do
        /usr/bin/time -f "$fmt run $run: %e s wall, %M KB max RSS" \
            "$VCNC" plot "$DIR/surfacing.nc" --dialect fanuc -o "$DIR/surfacing.$fmt"
    done
    echo "$fmt size: $(stat -c %s "$DIR/surfacing.$fmt") bytes"
done

VCNC_PLOT_PAGE="$DIR/surfacing.html" cargo bench -p vcnc --bench plot_page
