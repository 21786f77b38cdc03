#!/usr/bin/env bash
# What `--dialect auto` (the default) costs `vcnc check` on the generated
# 1 M-block surfacing program: rounds of `check --dialect D`, D the dialect
# detection chooses for it, and `check` (detection from the file's first
# 64 KiB, every dialect's tables built once) interleaved, so that the
# host's phase moves both alike; prints each one's median and best and the
# difference of the medians.
#
# Usage: tools/bench/detect.sh [ROUNDS]   (default 21)
# Environment: VCNC vcnc binary (default target/release/vcnc)
#              N    blocks (default 1000000)
set -euo pipefail
cd "$(dirname "$0")/../.."
ROUNDS=${1:-21}
N=${N:-1000000}
VCNC=${VCNC:-target/release/vcnc}
FILE=/tmp/vcnc_bench_surfacing_${N}.nc
[ -x "$VCNC" ] || { echo "build first: cargo build --release -p vcnc" >&2; exit 1; }
[ -f "$FILE" ] || python3 tools/bench/gen_surfacing.py "$N" "$FILE"
now() { date +%s%N; }
line=$("$VCNC" check "$FILE" 2>/dev/null | grep '^dialect')
echo "$line"
D=$(echo "$line" | awk '{ print $2 }')
given=() auto=()
for _ in $(seq "$ROUNDS"); do
    t0=$(now); "$VCNC" check --dialect "$D" "$FILE" > /dev/null 2>&1; t1=$(now)
    "$VCNC" check "$FILE" > /dev/null 2>&1; t2=$(now)
    given+=($(( (t1 - t0) / 1000 ))) auto+=($(( (t2 - t1) / 1000 )))
done
python3 - "${given[*]}" "${auto[*]}" "$D" <<'PY'
import statistics, sys
g = [int(x) for x in sys.argv[1].split()]
a = [int(x) for x in sys.argv[2].split()]
mg, ma = statistics.median(g), statistics.median(a)
name = f"--dialect {sys.argv[3]}:"
print(f"{name:20} median {mg/1000:.1f} ms, best {min(g)/1000:.1f} ms")
print(f"{'auto:':20} median {ma/1000:.1f} ms, best {min(a)/1000:.1f} ms")
print(f"difference of the medians: {(ma-mg)/1000:+.1f} ms ({(ma-mg)/mg*100:+.2f} %); of the bests: {(min(a)-min(g))/1000:+.1f} ms")
PY
