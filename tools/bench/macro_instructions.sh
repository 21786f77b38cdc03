#!/usr/bin/env bash
# Instructions of the macro benches (callgrind), which the host's load does
# not move: each divan bench of crates/vcnc_interp/benches/macros.rs runs
# once under callgrind (--sample-count 1 --sample-size 1), counting only
# inside `Interpreter::run`; printed: the bench, its total, and the total
# divided by twice its statements (the sampled run and divan's warm-up;
# the bench's own check run is counted too, so compare counts with each
# other, not with a statement's true cost).
#   tools/bench/macro_instructions.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo bench -p vcnc_interp --bench macros --no-run 2>/dev/null
bin=$(ls -t target/release/deps/macros-* | grep -v '\.d$' | head -1)
out=$(mktemp -d)
# Statements of each bench (benches/macros.rs: 200,000 passes).
declare -A statements=([macro_b_while_loop]=600000 [syntec_for_loop]=600000 [macro_b_moving_loop]=800000 [ngc_while_loop]=600000)
for bench in "${!statements[@]}"; do
  valgrind --tool=callgrind --toggle-collect='vcnc_interp::interpreter::Interpreter::run*' \
    --callgrind-out-file="$out/$bench.cg" \
    "$bin" --bench --sample-count 1 --sample-size 1 "$bench" >/dev/null 2>&1
  total=$(awk '/^summary:/ {print $2}' "$out/$bench.cg")
  echo "$bench $total $((total / (2 * ${statements[$bench]})))"
done
rm -rf "$out"
