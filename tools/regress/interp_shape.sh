#!/usr/bin/env bash
# The shape of the interpreter that issue #25 set targets for: methods on
# `Interpreter` and the files they sit in, and its fields.
set -euo pipefail
cd "$(dirname "$0")/../../crates/vcnc_interp/src"
python3 - <<'PY'
import re, glob
total = 0; files = {}
for f in sorted(glob.glob('**/*.rs', recursive=True)):
    s = open(f).read()
    n = 0
    for m in re.finditer(r"^impl(?:<[^>]*>)? Interpreter<[^>]*> \{\n(.*?)^\}", s, re.M | re.S):
        n += len(re.findall(r"^    (?:pub(?:\([a-z]+\))? )?(?:const )?fn ", m.group(1), re.M))
    if n:
        files[f] = n; total += n
s = open('interpreter.rs').read()
m = re.search(r"^pub struct Interpreter<'a> \{\n(.*?)^\}", s, re.M | re.S)
fields = len(re.findall(r"^    (?:pub(?:\([a-z]+\))? )?[a-z_]+:", m.group(1), re.M))
print(f"Interpreter: {fields} fields, {total} methods in {len(files)} files")
for f, n in sorted(files.items(), key=lambda kv: -kv[1]):
    print(f"  {n:4} {f}")
PY
