#!/usr/bin/env bash
# Speed and memory of vcnc under --dialect lathe on a generated turning
# program (LinuxCNC cannot run this dialect, so vcnc alone).
# Usage: tools/bench/lathe.sh [N]   (default 1000000 blocks; needs GNU time)
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-1000000}
VCNC=${VCNC:-target/release/vcnc}
FILE=/tmp/vcnc_bench_turning_${N}.nc
[ -x "$VCNC" ] || { echo "build first: cargo build --release -p vcnc" >&2; exit 1; }
python3 tools/bench/gen_turning.py "$N" "$FILE"
for args in "run --format jsonl" "check"; do
    log=$(mktemp)
    start=$(date +%s%N)
    /usr/bin/time -v -o "$log" $VCNC $args --dialect lathe "$FILE" > /dev/null
    end=$(date +%s%N)
    awk -v a="$start" -v b="$end" -v n="$N" -v name="vcnc $args --dialect lathe" \
        -v kb="$(awk -F': ' '/Maximum resident/ {print $2}' "$log")" \
        'BEGIN { s = (b - a) / 1e9; printf "%-36s %7.3f s %12.0f blocks/s %7.1f MB max RSS\n", name, s, n / s, kb / 1024 }'
    rm -f "$log"
done
