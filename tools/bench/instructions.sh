#!/usr/bin/env bash
# Instructions per block of the interpreter benches (callgrind), which the
# host's load does not move: each divan bench of
# crates/vcnc_interp/benches/interp.rs runs once under callgrind, counting
# only inside `Interpreter::run` (--toggle-collect), and the count is
# divided by 200,000 (divan runs the 100,000-block program twice: once to
# warm up, once sampled).
#   tools/bench/instructions.sh               # every bench
#   tools/bench/instructions.sh compensated   # those whose name contains it
set -euo pipefail
cd "$(dirname "$0")/../.."
filter=${1:-}
cargo bench -p vcnc_interp --bench interp --no-run 2>/dev/null
bin=$(ls -t target/release/deps/interp-* | grep -v '\.d$' | head -1)
out=$(mktemp -d)
for bench in $("$bin" --list 2>/dev/null | grep -o 'interpret_[a-z_]*' | sort -u); do
  [[ -n "$filter" && "$bench" != *"$filter"* ]] && continue
  valgrind --tool=callgrind --toggle-collect='vcnc_interp::interpreter::Interpreter::run*' \
    --callgrind-out-file="$out/$bench.cg" \
    "$bin" --bench --sample-count 1 --sample-size 1 "$bench" >/dev/null 2>&1
  total=$(awk '/^summary:/ {print $2}' "$out/$bench.cg")
  echo "$bench $((total / 200000))"
done
rm -rf "$out"
