#!/usr/bin/env bash
# Runs tools/editor/nvim-lsp.lua: Neovim's built-in LSP client, headless,
# against `vcnc lsp` on the program of crates/vcnc/tests/behaviour/lsp.rs. Needs
# Debian's neovim (`apt-get install neovim`) and a built vcnc
# (`cargo build -p vcnc`, or VCNC_BIN). Prints what each step gave.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
bin="${VCNC_BIN:-$root/target/debug/vcnc}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
# The test's program, taken from the test so that the two cannot drift.
sed -n '/^const PROGRAM: &str = "/,/^";/p' "$root/crates/vcnc/tests/behaviour/lsp.rs" \
  | sed '1s/^const PROGRAM: &str = "//; $d' > "$dir/bracket.nc"
status=0
VCNC_BIN="$bin" VCNC_PROGRAM="$dir/bracket.nc" VCNC_LOG="$dir/log" \
  timeout 120 nvim --headless --clean -c "luafile $root/tools/editor/nvim-lsp.lua" || status=$?
cat "$dir/log"
echo "neovim $(nvim --version | head -1 | cut -d' ' -f2): exit $status"
exit "$status"
