#!/usr/bin/env bash
# Speed and memory of vcnc under --dialect fanuc-lathe on a generated
# turning program (tools/bench/gen_fanuc_turning.py: the passes of the seed
# lathe's benchmark, tools/bench/lathe.sh, spelled for a Fanuc lathe), at a
# constant spindle speed and under G96 (a spindle event before each move
# that changes the diameter).
# Usage: tools/bench/fanuc_lathe.sh [N]   (default 1000000 blocks; needs GNU time)
set -euo pipefail
cd "$(dirname "$0")/../.."
N=${1:-1000000}
VCNC=${VCNC:-target/release/vcnc}
[ -x "$VCNC" ] || { echo "build first: cargo build --release -p vcnc" >&2; exit 1; }
for css in "" "--css"; do
    FILE=/tmp/vcnc_bench_fanuc_turning_${N}${css}.nc
    python3 tools/bench/gen_fanuc_turning.py "$N" $css "$FILE"
    for args in "run --format jsonl" "check"; do
        log=$(mktemp)
        start=$(date +%s%N)
        /usr/bin/time -v -o "$log" $VCNC $args --dialect fanuc-lathe "$FILE" > /dev/null
        end=$(date +%s%N)
        awk -v a="$start" -v b="$end" -v n="$N" -v name="vcnc $args${css:+ (G96)}" \
            -v kb="$(awk -F': ' '/Maximum resident/ {print $2}' "$log")" \
            'BEGIN { s = (b - a) / 1e9; printf "%-36s %7.3f s %12.0f blocks/s %7.1f MB max RSS\n", name, s, n / s, kb / 1024 }'
        rm -f "$log"
    done
done
