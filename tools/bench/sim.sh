#!/usr/bin/env bash
# Time `vcnc sim` on a large surfacing program at 0.1 mm (the automatic
# stock, the assumed 6 mm flat end mill): wall time and max RSS of three
# runs, then the same with an STL and a PNG written. The engine alone is
# `cargo bench -p vcnc_sim` (events recorded once).
#
# Usage: tools/bench/sim.sh [N]        (N blocks, default 1000000)
# Needs: cargo build --release -p vcnc; GNU time.
set -euo pipefail

cd "$(dirname "$0")/../.."
N=${1:-${N:-1000000}}
VCNC=${VCNC:-target/release/vcnc}
DIR=${DIR:-/tmp/vcnc_bench_sim_${N}}
mkdir -p "$DIR"

echo "generating $N blocks -> $DIR/surfacing.nc"
python3 tools/bench/gen_surfacing.py "$N" "$DIR/surfacing.nc"

for run in 1 2 3; do
    /usr/bin/time -f "sim run $run: %e s wall, %U s user, %M KB max RSS" \
        "$VCNC" sim "$DIR/surfacing.nc" --dialect fanuc --format json > "$DIR/report.json" || true
done
/usr/bin/time -f "sim with STL and PNG: %e s wall, %M KB max RSS" \
    "$VCNC" sim "$DIR/surfacing.nc" --dialect fanuc -o "$DIR/part.stl" -o "$DIR/part.png" > /dev/null || true
echo "STL size: $(stat -c %s "$DIR/part.stl") bytes"
