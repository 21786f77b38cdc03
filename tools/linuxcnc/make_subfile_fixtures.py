#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_subfiles: the expected events of LinuxCNC
programs that call subroutines kept in their own files (`o<name> call`,
the file `name.ngc` found along LinuxCNC's subroutine path), from
LinuxCNC's own rs274.

The folder holds programs (a .ngc whose first line is a `(vcnc-args: …)`
comment) and subroutine files (every other .ngc). rs274 standalone looks
subroutine files up in its working directory, so each program runs in a
temporary directory beside copies of every subroutine file. Lines are
prefixed with N numbers so that rs274 names the file and line of each
call: the program's line k is N<k>, line k of the i-th subroutine file
(in name order) N<100000*i + k>. An event of a subroutine file's block
gets `"file": "<name>.ngc"` and that file's line, as vcnc reports it
(`crates/vcnc/tests/behaviour/fixtures.rs`, `linuxcnc_subroutine_files_match_rs274`
compares the file's name only). The tool table and machine are those of
make_dialect_fixtures.py.

Usage: make_subfile_fixtures.py [--rs274 PATH]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import rs274_events as rv
from make_ext_fixtures import FIXTURES, machine_toml
from make_dialect_fixtures import TOOLS, cycle_lines

FOLDER = os.path.join(FIXTURES, "linuxcnc_subfiles")
FILE_STEP = 100000


def read_lines(path):
    with open(path) as f:
        text = f.read().split("\n")
    if text[-1] != "":
        sys.exit("%s: no final newline" % path)
    return text[:-1]


def run(rs274, name, ngc, subs):
    """rs274's canonical calls for program `ngc` with the subroutine files
    `subs` ([(file name, lines)]) beside it."""
    with tempfile.TemporaryDirectory(prefix="vcnc_rs274_") as tmp:
        def write(fname, lines, base):
            with open(os.path.join(tmp, fname), "w") as f:
                for k, text in enumerate(lines, 1):
                    f.write("N%d %s\n" % (base + k, text))
        write("prog.ngc", ngc, 0)
        for i, (fname, lines) in enumerate(subs, 1):
            write(fname, lines, i * FILE_STEP)
        tbl = os.path.join(tmp, "tool.tbl")
        with open(tbl, "w") as f:
            f.write(rv.tool_table_text(TOOLS))
        var = os.path.join(tmp, "params.var")
        open(var, "w").close()
        env = dict(os.environ, HOME=tmp)
        r = subprocess.run([rs274, "-g", "-t", tbl, "-v", var, "prog.ngc"],
                           stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, env=env, cwd=tmp)
        err = r.stderr.replace("executing", "").strip()
        if r.returncode != 0 or err:
            sys.exit("%s: rs274 failed (exit %d): %s"
                     % (name, r.returncode, err or r.stdout[-500:]))
        return r.stdout


def place(events, subs):
    """Lines N<100000*i + k> back to line k of subroutine file i."""
    for ev in events:
        i, k = divmod(ev["line"], FILE_STEP)
        if i:
            ev["line"] = k
            ev["file"] = subs[i - 1][0]
    return events


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rs274", default=shutil.which("rs274"))
    a = ap.parse_args()
    if not a.rs274:
        sys.exit("needs LinuxCNC's rs274: apt-get install linuxcnc-uspace")
    files = sorted(f for f in os.listdir(FOLDER) if f.endswith(".ngc"))
    texts = {f: read_lines(os.path.join(FOLDER, f)) for f in files}
    programs = [f for f in files if texts[f] and texts[f][0].startswith("(vcnc-args:")]
    subs = [(f, texts[f]) for f in files if f not in programs]
    n = 0
    for f in programs:
        name = f[:-4]
        ngc = texts[f]
        end, _, m5 = rv.program_facts(ngc)
        out = run(a.rs274, name, ngc, subs)
        events = rv.convert(out, name, end, cycle_lines(ngc), m5, inch=True,
                            end_code=rv.end_code(ngc, end),
                            home_lines=rv.home_lines(ngc))
        rv.write_jsonl(os.path.join(FOLDER, name + ".expected.jsonl"), place(events, subs))
        n += len(events)
    with open(os.path.join(FOLDER, "machine.toml"), "w") as f:
        f.write(machine_toml(TOOLS, header="linuxcnc_subfiles fixtures"))
    print("%d events -> %s" % (n, FOLDER))


if __name__ == "__main__":
    main()
