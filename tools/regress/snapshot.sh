#!/usr/bin/env bash
# Behaviour snapshot for refactors: runs a vcnc binary on every program in
# examples/, tests/fixtures/ and corpus/ under every dialect, and writes one
# line per run (file, dialect, command, exit code, hashes of stdout and
# stderr). Two snapshots taken before and after a change that must not change
# behaviour should be identical:
#   tools/regress/snapshot.sh target/release/vcnc > /tmp/before.txt
#   ... change, rebuild ...
#   tools/regress/snapshot.sh target/release/vcnc > /tmp/after.txt
#   diff /tmp/before.txt /tmp/after.txt
# Set DIALECTS to limit the dialects; CMDS (a `|`-separated list) to change
# what is run (default: `run --format jsonl|check --format json|run --format gcode`).
set -euo pipefail
bin=$(realpath "${1:?usage: snapshot.sh VCNC_BINARY}")
cd "$(dirname "$0")/../.."
dialects=${DIALECTS:-"syntec fanuc haas lathe eia grbl fanuc-lathe haas-lathe linuxcnc linuxcnc-lathe"}
cmds=${CMDS:-"run --format jsonl|check --format json|run --format gcode"}
export bin dialects cmds
find examples tests/fixtures corpus -type f \( -iname '*.nc' -o -iname '*.ngc' -o -iname '*.gcode' \
    -o -iname '*.cnc' -o -iname '*.tap' -o -iname '*.eia' -o -iname '*.mpf' \) | LC_ALL=C sort |
xargs -P "${JOBS:-2}" -n 8 bash -c '
for f in "$@"; do
  for d in $dialects; do
    IFS="|" read -ra list <<< "$cmds"
    for cmd in "${list[@]}"; do
      out=$(timeout 20 "$bin" $cmd --dialect "$d" "$f" 2>/tmp/snap.$$.err | sha256sum | cut -c1-16; echo "rc=${PIPESTATUS[0]}")
      err=$(sha256sum < /tmp/snap.$$.err | cut -c1-16)
      echo "$f $d ${cmd// /_} $(echo $out) $err"
    done
  done
done
rm -f /tmp/snap.$$.err' _ | LC_ALL=C sort
