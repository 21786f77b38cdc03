#!/usr/bin/env bash
# Compare vcnc with LinuxCNC's standalone interpreter (rs274) on a large
# surfacing program: wall time and max RSS, printed as blocks/s and MB.
#
# Usage: tools/bench/compare_linuxcnc.sh [N]        (N blocks, default 1000000)
# Environment: VCNC   vcnc binary (default target/release/vcnc)
#              RS274  rs274 binary (default: rs274 on PATH)
#              FILE   where to write the program (default /tmp/vcnc_bench_surfacing_N.nc)
set -euo pipefail

cd "$(dirname "$0")/../.."
N=${1:-${N:-1000000}}
VCNC=${VCNC:-target/release/vcnc}
RS274=${RS274:-$(command -v rs274 || true)}
FILE=${FILE:-/tmp/vcnc_bench_surfacing_${N}.nc}

if [ ! -x /usr/bin/time ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "installing GNU time (/usr/bin/time) ..." >&2
        DEBIAN_FRONTEND=noninteractive apt-get install -y time >/dev/null
    else
        echo "needs GNU time: sudo apt-get install time" >&2
        exit 1
    fi
fi

echo "generating $N blocks -> $FILE"
python3 tools/bench/gen_surfacing.py "$N" "$FILE"
BLOCKS=$(wc -l < "$FILE")

SCRATCH=$(mktemp -d /tmp/vcnc_bench.XXXXXX)
trap 'rm -rf "$SCRATCH"' EXIT

# measure NAME CMD...: runs CMD (stdout to /dev/null) under /usr/bin/time -v
measure() {
    local name=$1; shift
    local log="$SCRATCH/time.log"
    local rc=0 t0 t1 kb secs
    t0=$(date +%s%N)
    /usr/bin/time -v -o "$log" "$@" > /dev/null 2> "$SCRATCH/stderr" < /dev/null || rc=$?
    t1=$(date +%s%N)
    # wall time from date (ns resolution; time -v only prints 1/100 s)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", (b - a) / 1e9 }')
    kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$log")
    awk -v name="$name" -v n="$BLOCKS" -v s="$secs" -v kb="$kb" -v rc="$rc" 'BEGIN {
        bps = (s > 0) ? n / s : 0
        printf "%-34s %9.3f s  %12.0f blocks/s  %8.1f MB max RSS%s\n",
               name, s, bps, kb / 1024, (rc != 0) ? "  (exit " rc ")" : ""
    }'
    if [ "$rc" != 0 ]; then
        echo "  stderr (last lines):" >&2
        { grep -v '^executing$' "$SCRATCH/stderr" | tail -5 | sed 's/^/    /' >&2; } || true
    fi
}

echo "program: $FILE ($BLOCKS blocks, $(du -m "$FILE" | cut -f1) MB)"
echo

if [ -n "$RS274" ]; then
    # rs274 wants a tool table and a parameter file; give it throwaway ones and
    # keep its ~/.tool.mmap in the scratch folder.
    printf 'T1 P1 D10.000 Z+0.000 ;\n' > "$SCRATCH/tool.tbl"
    : > "$SCRATCH/params.var"
    HOME="$SCRATCH" measure "rs274 -g (LinuxCNC)" \
        "$RS274" -g -t "$SCRATCH/tool.tbl" -v "$SCRATCH/params.var" "$FILE"
else
    echo "rs274 not found (apt-get install linuxcnc-uspace); skipping LinuxCNC"
fi

if [ -x "$VCNC" ]; then
    measure "vcnc run --format jsonl" "$VCNC" run --dialect fanuc --format jsonl "$FILE"
    measure "vcnc check" "$VCNC" check --dialect fanuc "$FILE"
else
    echo "$VCNC not found: build it with 'cargo build --release -p vcnc'" \
         "(or set VCNC=/path/to/vcnc); only rs274 was measured"
fi
