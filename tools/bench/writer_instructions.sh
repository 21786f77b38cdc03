#!/usr/bin/env bash
# Instructions per event of the JSON-lines writer alone (callgrind), which
# the host's load does not move: each divan bench of
# crates/vcnc_output/benches/jsonl.rs (the events of the surfacing and the
# Fanuc turning programs, 100,000 each) runs once under callgrind, counting
# only inside its `format_events` (--toggle-collect), and the count is
# divided by 100,000 events times the passes callgrind saw (one with
# --sample-count 1 --sample-size 1). This is the sink thread's share of
# `vcnc run --format jsonl`.
#   tools/bench/writer_instructions.sh            # every bench
#   tools/bench/writer_instructions.sh turning    # those whose name contains it
set -euo pipefail
cd "$(dirname "$0")/../.."
filter=${1:-}
cargo bench -p vcnc_output --bench jsonl --no-run 2>/dev/null
bin=$(ls -t target/release/deps/jsonl-* | grep -v '\.d$' | head -1)
out=$(mktemp -d)
for bench in $("$bin" --list 2>/dev/null | grep -o 'jsonl_[a-z_]*' | sort -u); do
  [[ -n "$filter" && "$bench" != *"$filter"* ]] && continue
  valgrind --tool=callgrind --toggle-collect='jsonl::format_events*' \
    --callgrind-out-file="$out/$bench.cg" \
    "$bin" --bench --sample-count 1 --sample-size 1 "$bench" >/dev/null 2>&1
  total=$(awk '/^summary:/ {print $2}' "$out/$bench.cg")
  # The passes: the calls recorded against format_events's id.
  id=$(grep -m1 -o 'fn=([0-9]*) jsonl::format_events' "$out/$bench.cg" | grep -o '([0-9]*)')
  passes=$(awk -v id="cfn=$id" '$1 == id { getline; sub("calls=", "", $1); s += $1 } END { print s }' "$out/$bench.cg")
  echo "$bench $((total / 100000 / passes)) ($passes passes)"
done
rm -rf "$out"
