#!/usr/bin/env bash
# Speed and memory of canned cycles: a generated N-hole G83 program through
# `vcnc run --format jsonl` (issue #8: >= 1 M events/s in flat memory).
# Usage: tools/bench/drilling.sh [N]   (default 100000 holes; needs GNU time)
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-100000}
VCNC=${VCNC:-target/release/vcnc}
FILE=/tmp/vcnc_bench_drilling_${N}.nc
[ -x "$VCNC" ] || { echo "build first: cargo build --release -p vcnc" >&2; exit 1; }
python3 tools/bench/gen_drilling.py "$N" "$FILE"
EVENTS=$($VCNC run --format jsonl --dialect fanuc "$FILE" | wc -l)
for args in "run --format jsonl" "check"; do
    log=$(mktemp)
    start=$(date +%s%N)
    /usr/bin/time -v -o "$log" $VCNC $args --dialect fanuc "$FILE" > /dev/null
    end=$(date +%s%N)
    awk -v a="$start" -v b="$end" -v n="$EVENTS" -v name="vcnc $args ($N holes)" \
        -v kb="$(awk -F': ' '/Maximum resident/ {print $2}' "$log")" \
        'BEGIN { s = (b - a) / 1e9; printf "%-36s %7.3f s %12.0f events/s %7.1f MB max RSS\n", name, s, n / s, kb / 1024 }'
    rm -f "$log"
done
