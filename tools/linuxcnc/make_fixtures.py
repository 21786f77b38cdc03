#!/usr/bin/env python3
"""Turn LinuxCNC's rs274 output into vcnc event traces (tests/fixtures/linuxcnc).

For every program NNN.ngc made by gen_programs.py (in --programs, default
/tmp/vcnc_linuxcnc_programs) and every hand-written sanity_*.ngc already in
the fixture folder, this script

  1. checks that the .nc spelling has the same lines, differing only in the
     dwell word (G4 X<s> in vcnc's fanuc dialect, G4 P<s> in LinuxCNC);
  2. runs `rs274 -g` on a temporary copy of the .ngc whose lines carry
     N<line number> (rs274 prints the N word of the block that made each
     canonical call; the fixture files themselves have no N words), with its
     own tool table and a fresh empty parameter (.var) file so that nothing
     persists between runs (rs274_events.run_rs274);
  3. converts the canonical calls to vcnc's event contract (docs/events.md)
     in MACHINE coordinates and mm with the converter shared by all LinuxCNC
     fixture sets, rs274_events.py (here with inch segments allowed):
     machine = program position + G5x offset + G92 offset, tracking
     SET_G5X_OFFSET and SET_G92_OFFSET; after
     USE_LENGTH_UNITS(CANON_UNITS_INCHES) every length rs274 prints (points,
     centres, offsets, feeds) is in inches and is multiplied by 25.4;
  4. writes NNN.nc, NNN.ngc and NNN.expected.jsonl into the fixture folder.

An rs274 error, an unknown canonical call or a program without PROGRAM_END is
fatal: it means the generator is wrong, and no fixture is dropped silently.

Mapping (verified on small programs, see tests/fixtures/linuxcnc/README.md):
  STRAIGHT_TRAVERSE(x, y, z, a, b, c)   -> rapid
  STRAIGHT_FEED(x, y, z, a, b, c)       -> feed (feed from SET_FEED_RATE)
  ARC_FEED(first_end, second_end, first_centre, second_centre, rotation,
           normal_end, a, b, c)         -> arc
      G17 (CANON_PLANE_XY): first = X, second = Y, normal = Z
      G18 (CANON_PLANE_XZ): first = Z, second = X, normal = Y
      G19 (CANON_PLANE_YZ): first = Y, second = Z, normal = X
      rotation > 0 -> "ccw", < 0 -> "cw"; |rotation| = 1 for one turn at most
      (an I/J/K full circle is rotation +-1 with end = start)
  DWELL(seconds)                        -> dwell
  PROGRAM_END()                         -> end, code "M02"
  SET_G5X_OFFSET / SET_G92_OFFSET       -> frame, when origin changes
  (G28 has no call of its own: its two legs are two STRAIGHT_TRAVERSEs.)

Frames (the `frame` event of /work/notes/conventions.md): whenever origin =
G5x offset + G92 offset (in mm, machine coordinates of program 0) differs
from the last one reported, a {"type":"frame","line":L,"origin":{x,y,z}}
with the line of the block that changed it goes before that block's first
motion, or alone when the block does not move (it comes before the next
block's events). The run starts with origin 0 reported, and the fresh
parameter file makes LinuxCNC's power-on offsets 0 (checked), so the
power-on G54 makes no frame. An offset call that leaves origin as it was
(G54..G59 or G10 L2 with equal numbers) makes none either, nor does the G54
re-selection LinuxCNC does at M2. No G43 and no rotation in this set, so a
frame never has `tool_offset` or `linear`. Removing the frame lines from
a trace gives the trace this script wrote before frames existed.

Units: rs274 prints lengths in the units in force when it prints them and
re-sends nothing on a unit change (the offsets it printed in mm stay valid as
lengths; the converter keeps everything in mm). Two checks keep inch exact:
  * an end point or offset printed in inches must be a multiple of
    0.0005 in, so that 25.4 x the 4-decimal print is the exact mm value (the
    generator keeps inch segments on that grid); only arc centres are exempt
    (rs274 computes R-arc centres, rounded to 0.0001 in = 0.00127 mm);
  * a cutting move must be in the units its F was set in: rs274 does not
    re-send the feed on G20/G21, and LinuxCNC (keeps the physical feed) and
    vcnc (keeps F's number) differ there, so such a program is rejected.

Usage: make_fixtures.py [--programs DIR] [--fixtures DIR] [--rs274 PATH] [-j N]
"""

import argparse
import os
import re
import shutil
import sys
from concurrent.futures import ThreadPoolExecutor

import rs274_events as rv
from rs274_events import ConvertError

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
DEFAULT_PROGRAMS = "/tmp/vcnc_linuxcnc_programs"
DEFAULT_FIXTURES = os.path.join(REPO, "tests", "fixtures", "linuxcnc")

TOOL_TABLE = "T1 P1 D10.000 Z+0.000 ;\nT2 P2 D6.000 Z+0.000 ;\n"


def convert(canon_text, name, ngc_lines):
    """rs274 canonical output of the program `ngc_lines` -> list of event
    dicts (vcnc contract), frames included."""
    end, cycles, m5 = rv.program_facts(ngc_lines)
    if cycles or m5:
        raise ConvertError("%s: canned cycles or M5 are not in this set" % name)
    return rv.convert(canon_text, name, end, inch=True)


def check_spellings(ngc_lines, nc_lines, name):
    if len(ngc_lines) != len(nc_lines):
        raise ConvertError("%s: .ngc has %d lines, .nc %d"
                           % (name, len(ngc_lines), len(nc_lines)))
    for i, (a, b) in enumerate(zip(ngc_lines, nc_lines), 1):
        if a == b:
            continue
        if re.fullmatch(r"G4 P[0-9.]+", a) and b == "G4 X" + a[4:]:
            continue
        raise ConvertError("%s:%d: spellings differ: %r vs %r" % (name, i, a, b))


def read_lines(path):
    with open(path) as f:
        text = f.read()
    if not text.endswith("\n"):
        raise ConvertError("%s: no final newline" % path)
    return text[:-1].split("\n")


def process(stem, src_dir, fixtures, rs274, copy):
    ngc_path = os.path.join(src_dir, stem + ".ngc")
    nc_path = os.path.join(src_dir, stem + ".nc")
    ngc = read_lines(ngc_path)
    nc = read_lines(nc_path)
    check_spellings(ngc, nc, stem)
    events = convert(rv.run_rs274(rs274, ngc, TOOL_TABLE, stem), stem, ngc)
    if copy:
        shutil.copyfile(ngc_path, os.path.join(fixtures, stem + ".ngc"))
        shutil.copyfile(nc_path, os.path.join(fixtures, stem + ".nc"))
    rv.write_jsonl(os.path.join(fixtures, stem + ".expected.jsonl"), events)
    return len(events)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--programs", default=DEFAULT_PROGRAMS)
    ap.add_argument("--fixtures", default=DEFAULT_FIXTURES)
    ap.add_argument("--rs274", default=shutil.which("rs274") or "rs274")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args(argv)

    if not os.path.exists(args.rs274) and not shutil.which(args.rs274):
        sys.exit("rs274 not found: apt-get install linuxcnc-uspace")
    os.makedirs(args.fixtures, exist_ok=True)
    generated = sorted(f[:-4] for f in os.listdir(args.programs)
                       if re.fullmatch(r"\d{3,}\.ngc", f))
    if not generated:
        sys.exit("no programs in %s: run gen_programs.py first" % args.programs)
    # drop fixtures of a previous generation
    for f in os.listdir(args.fixtures):
        if re.fullmatch(r"\d{3,}\.(nc|ngc|expected\.jsonl)", f):
            os.remove(os.path.join(args.fixtures, f))
    sanity = sorted(f[:-4] for f in os.listdir(args.fixtures)
                    if f.startswith("sanity_") and f.endswith(".ngc"))

    jobs = [(s, args.programs, True) for s in generated]
    jobs += [(s, args.fixtures, False) for s in sanity]
    failures = []
    total = 0

    def work(job):
        stem, src, copy = job
        try:
            return process(stem, src, args.fixtures, args.rs274, copy)
        except ConvertError as e:
            failures.append(str(e))
            return 0

    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        for n in ex.map(work, jobs):
            total += n
    if failures:
        for msg in sorted(failures):
            print("ERROR " + msg, file=sys.stderr)
        sys.exit("%d of %d programs failed; fix gen_programs.py" % (len(failures), len(jobs)))
    print("%d generated + %d sanity programs, %d events -> %s"
          % (len(generated), len(sanity), total, args.fixtures))
    return 0


if __name__ == "__main__":
    sys.exit(main())
