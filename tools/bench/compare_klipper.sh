#!/usr/bin/env bash
# Cross-check vcnc's trapezoid planner against klipper_estimator (a Rust
# re-implementation of Klipper's look-ahead planner: trapezoids, square
# corner velocity) configured with the same limits, on the surfacing program
# (tools/bench/gen_surfacing.py) and on the trochoidal short-segment program
# (tools/bench/gen_trochoidal.py).
#
# Usage: KLIPPER_ESTIMATOR=/path/to/klipper_estimator compare_klipper.sh [N_SURF] [N_TROCH]
#
# Needs `cargo build --release -p vcnc` and a klipper_estimator binary built
# from its sources (`cargo build --release` in its checkout). Both planners
# get: every axis 2000 mm/s² and 500 mm/s, no per-axis difference (Klipper
# limits the path, vcnc each axis: equal limits make them agree on lines
# along an axis and differ by at most √2 on diagonals), corner tolerance
# 0.02 mm = Klipper's junction deviation, so square_corner_velocity =
# √(0.02·2000/(√2 − 1)); Klipper's minimum_cruise_ratio 0 (no
# accel-to-decel reduction); vcnc with no settling time and a 200-block
# look-ahead. Rapids become G1 at the rapid rate for Klipper, which has no
# G0 of its own; vcnc stops after each rapid (a few per layer).
set -euo pipefail
KE=${KLIPPER_ESTIMATOR:?set KLIPPER_ESTIMATOR to a built klipper_estimator binary}
N_SURF=${1:-1000000}
N_TROCH=${2:-100000}
root=$(cd "$(dirname "$0")/../.." && pwd)
vcnc=$root/target/release/vcnc
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

axis() {
    cat <<AX
[[axes]]
letter = "$1"
min_mm = -10000.0
max_mm = 10000.0
rapid_mm_per_min = 30000.0
max_feed_mm_per_min = 30000.0
accel_mm_s2 = 2000.0
in_position_mm = 1000.0
in_position_rapid_mm = 1000.0
AX
}
{
    echo 'name = "klipper cross-check"'
    axis x; axis y; axis z
    cat <<'MO'
[motion]
profile = "trapezoid"
lookahead_blocks = 200
corner_tolerance_mm = 0.02
servo_gain_per_s = 1000.0
tool_change_s = 0.0
spindle_start_s = 0.0
spindle_stop_s = 0.0
MO
} > "$dir/machine.toml"
scv=$(python3 -c 'import math; print(math.sqrt(0.02*2000/(math.sqrt(2)-1)))')
cat > "$dir/klipper.json" <<KJ
{"max_velocity": 500.0, "max_acceleration": 2000.0, "minimum_cruise_ratio": 0.0,
 "square_corner_velocity": $scv, "instant_corner_velocity": 1.0, "move_checkers": []}
KJ

compare() { # name generator blocks
    local name=$1 gen=$2 n=$3
    python3 "$root/tools/bench/$gen" "$n" "$dir/$name.nc"
    local t0 t1 ours theirs
    t0=$(date +%s.%N)
    ours=$("$vcnc" time "$dir/$name.nc" --dialect fanuc --machine "$dir/machine.toml" \
        --profile trapezoid --format json |
        python3 -c 'import json,sys; d=json.load(sys.stdin); print(d["cutting_s"]+d["rapid_s"], d["distance_feed_s"])')
    t1=$(date +%s.%N)
    # Klipper's G-code: rapids as G1 at the rapid rate, every cutting move
    # with its own F (a G1 after a converted rapid would keep F30000).
    "$vcnc" run "$dir/$name.nc" --dialect fanuc --machine "$dir/machine.toml" --format gcode |
        python3 -c '
import re, sys
feed = None
for line in sys.stdin:
    line = re.sub(r"\([^)]*\)", "", line).strip()
    if not line or line.startswith(("G21", "M")):
        continue
    m = re.search(r"F([0-9.]+)", line)
    if m:
        feed = m.group(1)
        line = re.sub(r" ?F[0-9.]+", "", line)
    if line.startswith("G0 "):
        print("G1 " + line[3:] + " F30000")
    elif line.startswith("G1 ") and feed:
        print(line + " F" + feed)
    else:
        print(line)
' > "$dir/$name.gcode"
    local k0 k1
    k0=$(date +%s.%N)
    theirs=$("$KE" --config_file "$dir/klipper.json" estimate "$dir/$name.gcode" --format json |
        python3 -c 'import json,sys; d=json.load(sys.stdin); print(sum(s["total_time"] for s in d["sequences"]))')
    k1=$(date +%s.%N)
    python3 - "$name" "$n" $ours "$theirs" "$t0" "$t1" "$k0" "$k1" <<'PY'
import sys
name, n, ours, feed, theirs, t0, t1, k0, k1 = sys.argv[1:]
ours, feed, theirs = float(ours), float(feed), float(theirs)
n = int(n)
print(f"{name}: {n} blocks  vcnc {ours:.1f} s  klipper_estimator {theirs:.1f} s  "
      f"difference {100*(ours-theirs)/theirs:+.2f} %  distance/feed {feed:.1f} s  "
      f"(vcnc time {float(t1)-float(t0):.2f} s wall, klipper_estimator {float(k1)-float(k0):.2f} s)")
PY
}

compare surfacing gen_surfacing.py "$N_SURF"
compare trochoidal gen_trochoidal.py "$N_TROCH"
