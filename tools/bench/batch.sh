#!/usr/bin/env bash
# Batch checking on all cores (issue #10: >= 1.7x the one-core time on 2
# cores): N small generated programs in one directory, `vcnc check DIR`
# with --jobs 1 and with the default (one job per core).
# Usage: tools/bench/batch.sh [N] [BLOCKS]   (default 10000 programs of 200 blocks)
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-10000}
BLOCKS=${2:-200}
VCNC=${VCNC:-target/release/vcnc}
DIR=/tmp/vcnc_bench_batch_${N}_${BLOCKS}
[ -x "$VCNC" ] || { echo "build first: cargo build --release -p vcnc" >&2; exit 1; }
if [ ! -d "$DIR" ]; then
    mkdir -p "$DIR"
    python3 - "$DIR" "$N" "$BLOCKS" <<'PY'
import math, os, sys
d, n, blocks = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
for k in range(n):
    lines = ["G21 G17 G90 G94", "T1 M06", "S%d M03" % (2000 + k % 7 * 100), "G00 X0 Y0 Z5.", "G01 Z-1. F300."]
    for i in range(blocks - 7):
        a = (i + k) * 0.1
        lines.append("X%.3f Y%.3f" % (20 * math.cos(a) + i * 0.01, 20 * math.sin(a)))
    lines += ["G00 Z5.", "M30"]
    with open(os.path.join(d, "P%05d.nc" % k), "w") as f:
        f.write("\n".join(lines) + "\n")
PY
fi
time_of() {
    local start end
    start=$(date +%s%N)
    "$@" > /dev/null
    end=$(date +%s%N)
    echo $(( (end - start) / 1000000 ))
}
one=$(time_of $VCNC check "$DIR" --dialect fanuc --jobs 1)
all=$(time_of $VCNC check "$DIR" --dialect fanuc)
awk -v one="$one" -v all="$all" -v n="$N" -v cores="$(nproc)" \
    'BEGIN { printf "%d programs: --jobs 1 %.2f s, all %d cores %.2f s, speed-up %.2fx\n", n, one / 1000, cores, all / 1000, one / all }'
