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
     persists between runs;
  3. converts the canonical calls to vcnc's event contract (docs/events.md)
     in MACHINE coordinates and mm: machine = program position + G5x offset
     + G92 offset, tracking SET_G5X_OFFSET and SET_G92_OFFSET; after
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
  (G28 has no call of its own: its two legs are two STRAIGHT_TRAVERSEs.)

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
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from decimal import Decimal

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
DEFAULT_PROGRAMS = "/tmp/vcnc_linuxcnc_programs"
DEFAULT_FIXTURES = os.path.join(REPO, "tests", "fixtures", "linuxcnc")

TOOL_TABLE = "T1 P1 D10.000 Z+0.000 ;\nT2 P2 D6.000 Z+0.000 ;\n"

# "   12 N34    STRAIGHT_FEED(1.0000, 2.0000, ...)"; the N column is "N....."
# for calls not made by a numbered block, and has no trailing blank once the
# number has 6 digits or more.
CANON_RE = re.compile(r"^\s*(\d+)\s+N(\.\.\.\.\.|\d+)\s*([A-Z_0-9]+)\((.*)\)\s*$")

PLANES = {
    # canon plane -> (vcnc name, first axis, second axis, normal axis)
    "CANON_PLANE_XY": ("xy", "x", "y", "z"),
    "CANON_PLANE_XZ": ("zx", "z", "x", "y"),
    "CANON_PLANE_YZ": ("yz", "y", "z", "x"),
}

# Calls that carry nothing for the event trace on this subset.
IGNORED = {
    "USE_LENGTH_UNITS", "SET_XY_ROTATION", "SET_FEED_REFERENCE", "ON_RESET",
    "COMMENT", "SET_FEED_MODE", "STOP_SPINDLE_TURNING", "SET_SPINDLE_MODE",
    "SELECT_PLANE", "SET_G5X_OFFSET", "SET_G92_OFFSET", "SET_FEED_RATE",
}

AXES = ("x", "y", "z")
Q = Decimal("0.0001")
MM_PER = {"CANON_UNITS_MM": Decimal(1), "CANON_UNITS_INCHES": Decimal("25.4")}


class ConvertError(Exception):
    pass


def num(s):
    return Decimal(s.strip())


def out_num(d):
    """Decimal -> float rounded to 4 decimals, never -0.0."""
    f = float(d.quantize(Q))
    return 0.0 if f == 0 else f


def point(d):
    return {a: out_num(d[a]) for a in AXES}


def convert(canon_text, name="?"):
    """rs274 canonical output -> list of event dicts (vcnc contract)."""
    g5x = {a: Decimal(0) for a in AXES}
    g92 = {a: Decimal(0) for a in AXES}
    # rs274 starts at program (and machine) 0,0,0 with zero offsets, which is
    # also vcnc's default machine start.
    pos = {a: Decimal(0) for a in AXES}    # machine
    plane = "CANON_PLANE_XY"
    unit = MM_PER["CANON_UNITS_MM"]    # mm per printed length unit
    feed = None                        # mm/min
    feed_unit = unit                   # the units F was set in
    events = []
    ended = False
    where = [name]

    def machine(prog):
        return {a: prog[a] + g5x[a] + g92[a] for a in AXES}

    def mm(s, exact=True):
        """A printed length -> Decimal mm; `exact`: refuse an inch value
        whose 4-decimal print cannot be the exact length."""
        v = num(s) * unit
        if exact and v != v.quantize(Q):
            raise ConvertError("%s: %s in is not a multiple of 0.0005 in: its "
                               "4-decimal print is not exact in mm"
                               % (where[0], s.strip()))
        return v

    for raw in canon_text.splitlines():
        if not raw.strip():
            continue
        m = CANON_RE.match(raw)
        if not m:
            raise ConvertError("%s: cannot parse rs274 line %r" % (name, raw))
        _, nword, call, args_s = m.groups()
        args = [a.strip() for a in args_s.split(",")] if args_s.strip() else []
        line = None if nword == "....." else int(nword)
        where[0] = "%s:%s" % (name, line)
        if ended:
            continue   # ON_RESET etc. after PROGRAM_END
        if call == "USE_LENGTH_UNITS":
            if len(args) != 1 or args[0] not in MM_PER:
                raise ConvertError("%s: units %r" % (name, args))
            unit = MM_PER[args[0]]
        elif call == "SET_XY_ROTATION":
            if num(args[0]) != 0:
                raise ConvertError("%s: XY rotation %s" % (name, args[0]))
        elif call == "SET_G5X_OFFSET":
            # (index, x, y, z, a, b, c)
            g5x = dict(zip(AXES, map(mm, args[1:4])))
        elif call == "SET_G92_OFFSET":
            g92 = dict(zip(AXES, map(mm, args[0:3])))
        elif call == "SET_FEED_RATE":
            feed = mm(args[0], exact=False)   # rates: quantized on output
            feed_unit = unit
        elif call == "SELECT_PLANE":
            if args[0] not in PLANES:
                raise ConvertError("%s: plane %r" % (name, args[0]))
            plane = args[0]
        elif call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED"):
            to = machine(dict(zip(AXES, map(mm, args[0:3]))))
            ev = {"type": "rapid" if call == "STRAIGHT_TRAVERSE" else "feed",
                  "line": line, "to": point(to)}
            if call == "STRAIGHT_FEED":
                if not feed:
                    raise ConvertError("%s:%s feed move with no feed" % (name, line))
                if feed_unit != unit:
                    raise ConvertError("%s:%s feed set before a unit change"
                                       % (name, line))
                ev["feed"] = out_num(feed)
            events.append(ev)
            pos = to
        elif call == "ARC_FEED":
            pname, fa, sa, na = PLANES[plane]
            first_end, second_end = mm(args[0]), mm(args[1])
            first_c, second_c = mm(args[2], False), mm(args[3], False)
            rotation = int(args[4])
            normal_end = mm(args[5])
            prog_end = {fa: first_end, sa: second_end, na: normal_end}
            to = machine(prog_end)
            off = {a: g5x[a] + g92[a] for a in AXES}
            center = {fa: first_c + off[fa], sa: second_c + off[sa], na: pos[na]}
            if rotation == 0 or abs(rotation) > 1:
                raise ConvertError("%s:%s arc rotation %d" % (name, line, rotation))
            if not feed:
                raise ConvertError("%s:%s arc with no feed" % (name, line))
            if feed_unit != unit:
                raise ConvertError("%s:%s feed set before a unit change"
                                   % (name, line))
            events.append({"type": "arc", "line": line, "to": point(to),
                           "center": point(center), "plane": pname,
                           "dir": "ccw" if rotation > 0 else "cw",
                           "feed": out_num(feed)})
            pos = to
        elif call == "DWELL":
            events.append({"type": "dwell", "line": line,
                           "seconds": out_num(num(args[0]))})
        elif call == "PROGRAM_END":
            events.append({"type": "end", "line": line, "code": "M02"})
            ended = True
        elif call in IGNORED:
            pass
        else:
            raise ConvertError("%s: unexpected canonical call %s" % (name, raw))
        if call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "DWELL",
                    "PROGRAM_END") and line is None:
            raise ConvertError("%s: %s without a line number" % (name, call))
    if not ended:
        raise ConvertError("%s: no PROGRAM_END in rs274 output" % name)
    return events


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


def run_rs274(rs274, ngc_lines, name):
    with tempfile.TemporaryDirectory(prefix="vcnc_rs274_") as tmp:
        prog = os.path.join(tmp, "prog.ngc")
        with open(prog, "w") as f:
            for i, text in enumerate(ngc_lines, 1):
                f.write("N%d %s\n" % (i, text))
        tbl = os.path.join(tmp, "tool.tbl")
        with open(tbl, "w") as f:
            f.write(TOOL_TABLE)
        var = os.path.join(tmp, "params.var")
        open(var, "w").close()
        # HOME: rs274 writes ~/.tool.mmap; keep it in the scratch folder.
        env = dict(os.environ, HOME=tmp)
        r = subprocess.run([rs274, "-g", "-t", tbl, "-v", var, prog],
                           stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, env=env, cwd=tmp)
        err = r.stderr.replace("executing", "").strip()
        if r.returncode != 0 or err:
            raise ConvertError("%s: rs274 failed (exit %d): %s"
                               % (name, r.returncode, err or r.stdout[-500:]))
        return r.stdout


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
    events = convert(run_rs274(rs274, ngc, stem), stem)
    if copy:
        shutil.copyfile(ngc_path, os.path.join(fixtures, stem + ".ngc"))
        shutil.copyfile(nc_path, os.path.join(fixtures, stem + ".nc"))
    with open(os.path.join(fixtures, stem + ".expected.jsonl"), "w") as f:
        for ev in events:
            f.write(json.dumps(ev, separators=(",", ":")) + "\n")
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
