#!/usr/bin/env python3
"""Write tests/fixtures/linuxcnc_lathe/: turning programs (gen_lathe.py)
whose moves come from LinuxCNC 2.9's standalone interpreter rs274, for
vcnc's fanuc-lathe dialect.

For each program this script runs `rs274 -g` on the LinuxCNC spelling
(NNN.ngc, lines prefixed with N<line>), converts the canonical calls to
vcnc motion events in machine mm (X a radius: rs274 in G7 diameter mode
prints radii) and writes NNN.expected.jsonl with the moves (rapid, feed,
arc, thread) and the end; the test compares vcnc's moves of NNN.nc with
them (`linuxcnc_lathe_moves_match_rs274` in crates/vcnc/tests/behaviour/fixtures.rs).
Spindle events are not compared: under G96 rs274 hands the speed to the
motion controller (SET_SPINDLE_MODE with the D clamp), it prints no rpm.

  * STRAIGHT_TRAVERSE -> rapid; STRAIGHT_FEED -> feed (feed_per_rev after
    SET_FEED_MODE(0, 1), G95), or thread with lead_mm between
    START_SPEED_FEED_SYNC(k, 0) and STOP_SPEED_FEED_SYNCH (G33 K);
    ARC_FEED in the XZ plane (first Z, second X) -> arc; PROGRAM_END -> end
    M30 (the .nc's end code); machine = program + G5x + G92 offsets.
  * Moves that do not move (rs274's G70 starts with a traverse to where the
    tool is) are dropped, here and by the test on vcnc's side.
  * G70 (what both define: one pass along the profile): rs274 reports the
    moves of G70 with the line of the sub's `O100 endsub`; the k-th of them
    is the k-th block of the sub, which is the .nc's profile block on the
    same line, so it gets that line. A Fanuc G70 then returns to its start
    point at rapid, LinuxCNC's stays at the profile's end: the converter
    adds that rapid, with the G70's line. These are the only changes to
    rs274's output.

Usage: make_lathe_fixtures.py [--count N] [--rs274 PATH]
"""

import argparse
import json
import os
import re
import shutil
import sys
from decimal import Decimal

import gen_lathe
import rs274_events as rv
from rs274_events import ConvertError

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
FOLDER = os.path.join(REPO, "tests", "fixtures", "linuxcnc_lathe")
DEFAULT = os.path.join(REPO, "crates", "vcnc_core", "src", "default_fanuc_lathe.toml")


def machine_toml():
    """The built-in turning centre, starting at X0 Z0 as rs274 does."""
    with open(DEFAULT) as f:
        text = f.read()
    text = re.sub(r"^start_mm = .*$", "start_mm = { x = 0.0, z = 0.0 }", text, count=1, flags=re.M)
    text = re.sub(r'^name = "([^"]*)"', r'name = "\1 (starts at X0 Z0 like rs274)"', text,
                  count=1, flags=re.M)
    return text


def pt(x, z):
    return {"x": rv.out_num(x), "z": rv.out_num(z)}


class Lathe:
    """rs274 canonical calls of one program -> vcnc motion events."""

    def __init__(self, name, ngc):
        self.name = name
        self.ngc = ngc
        self.line = None
        self.events = []
        self.pos = (Decimal(0), Decimal(0))   # (x radius, z), machine
        self.g5x = (Decimal(0), Decimal(0))
        self.g92 = (Decimal(0), Decimal(0))
        self.feed = None
        self.per_rev = False
        self.lead = None
        self.g70 = {}        # G70 line -> the sub body's lines
        sub = None
        for i, text in enumerate(ngc, 1):
            code = rv.strip_comments(text)
            if re.search(r"O100\s+SUB", code):
                sub = []
            elif re.search(r"O100\s+ENDSUB", code):
                self.endsub = i
                self.body = sub
                sub = None
            elif sub is not None:
                sub.append(i)
            elif re.search(r"G70", code):
                self.g70[i] = True
        self.pending_body = []

    def err(self, msg):
        raise ConvertError("%s:%s: %s" % (self.name, self.line, msg))

    def machine(self, x, z):
        return (x + self.g5x[0] + self.g92[0], z + self.g5x[1] + self.g92[1])

    def move(self, kind, to, extra):
        if to == self.pos:
            return
        line = self.line
        if getattr(self, "endsub", None) == line:
            # The k-th G70 move is the k-th block of the sub.
            if not self.pending_body:
                self.err("more G70 moves than profile blocks")
            line = self.pending_body.pop(0)
        ev = {"type": kind, "line": line, "to": pt(*to)}
        ev.update(extra)
        self.events.append(ev)
        self.pos = to

    def feed_key(self):
        if self.feed is None:
            self.err("a cut with no feed")
        return {"feed_per_rev" if self.per_rev else "feed": rv.out_num(self.feed)}

    def call(self, call, args):
        if call == "STRAIGHT_TRAVERSE":
            self.move("rapid", self.machine(rv.num(args[0]), rv.num(args[2])), {})
        elif call == "STRAIGHT_FEED":
            to = self.machine(rv.num(args[0]), rv.num(args[2]))
            if self.lead is not None:
                self.move("thread", to, {"lead_mm": rv.out_num(self.lead)})
            else:
                self.move("feed", to, self.feed_key())
        elif call == "ARC_FEED":
            if getattr(self, "plane", None) != "CANON_PLANE_XZ":
                self.err("an arc outside the XZ plane")
            # XZ plane: (z end, x end, z centre, x centre, rotation, y end)
            to = self.machine(rv.num(args[1]), rv.num(args[0]))
            c = self.machine(rv.num(args[3]), rv.num(args[2]))
            rot = int(args[4])
            if abs(rot) != 1:
                self.err("arc rotation %d" % rot)
            ev = {"center": pt(*c), "plane": "zx", "dir": "ccw" if rot > 0 else "cw"}
            ev.update(self.feed_key())
            self.move("arc", to, ev)
        elif call == "SET_FEED_RATE":
            self.feed = rv.num(args[0])
        elif call == "SET_FEED_MODE":
            self.per_rev = args[1] == "1"
        elif call == "START_SPEED_FEED_SYNC":
            self.lead = rv.num(args[0])
        elif call == "STOP_SPEED_FEED_SYNCH":
            self.lead = None
        elif call == "SET_G5X_OFFSET":
            self.g5x = (rv.num(args[1]), rv.num(args[3]))
        elif call == "SET_G92_OFFSET":
            self.g92 = (rv.num(args[0]), rv.num(args[2]))
        elif call == "SELECT_PLANE":
            # G18 at the start; M2 selects XY again after the last move.
            self.plane = args[0]
        elif call == "USE_LENGTH_UNITS":
            if args[0] != "CANON_UNITS_MM":
                self.err("units %s" % args[0])

    def convert(self, text):
        for raw in text.splitlines():
            if not raw.strip():
                continue
            m = rv.CANON_RE.match(raw)
            if not m:
                raise ConvertError("%s: cannot parse %r" % (self.name, raw))
            _, nword, call, args_s = m.groups()
            args = [a.strip() for a in args_s.split(",")] if args_s.strip() else []
            line = None if nword == "....." else int(nword)
            if line is not None and line != self.line:
                self.block_end()
                self.line = line
                if line in self.g70:
                    self.pending_body = list(self.body)
                    self.g70_start = self.pos
                    self.g70_line = line
            if call == "PROGRAM_END":
                self.block_end()
                self.events.append({"type": "end", "line": line, "code": "M30"})
                return self.events
            if line is None and call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
                self.err("%s without a line" % call)
            self.call(call, args)
        raise ConvertError("%s: no PROGRAM_END" % self.name)

    def block_end(self):
        """After the G70's moves: Fanuc's rapid back to its start point."""
        if self.line is not None and self.line == getattr(self, "endsub", None) \
                and getattr(self, "g70_start", None) is not None:
            if self.pending_body:
                self.err("G70 made fewer moves than its profile has blocks")
            start, self.g70_start = self.g70_start, None
            if start != self.pos:
                self.events.append({"type": "rapid", "line": self.g70_line, "to": pt(*start)})
                self.pos = start


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--rs274", default=shutil.which("rs274") or "rs274")
    a = ap.parse_args()
    os.makedirs(FOLDER, exist_ok=True)
    for f in os.listdir(FOLDER):
        if re.fullmatch(r"\d{3}\.(nc|ngc|expected\.jsonl)", f):
            os.remove(os.path.join(FOLDER, f))
    with open(os.path.join(FOLDER, "machine.toml"), "w") as f:
        f.write(machine_toml())
    table = "T1 P1 D0 Z0 ;\n"
    written = 0
    seed = 0
    while written < a.count:
        seed += 1
        if seed > 20 * a.count:
            sys.exit("too many programs refused by rs274: see the messages above")
        nc, ngc = gen_lathe.generate(seed)
        name = "%03d" % (written + 1)
        try:
            canon = rv.run_rs274(a.rs274, ngc, table, name)
            events = Lathe(name, ngc).convert(canon)
        except ConvertError as e:
            # rs274 refuses some random programs (an arc it finds off its
            # circle at its own tolerance, a profile it calls not monotone):
            # say so and take the next seed.
            print("seed %d skipped: %s" % (seed, e), file=sys.stderr, flush=True)
            continue
        for ext, lines in (("nc", nc), ("ngc", ngc)):
            with open(os.path.join(FOLDER, "%s.%s" % (name, ext)), "w") as f:
                f.write("\n".join(lines) + "\n")
        rv.write_jsonl(os.path.join(FOLDER, name + ".expected.jsonl"), events)
        written += 1
    print("%d programs written (%d seeds)" % (written, seed))


if __name__ == "__main__":
    main()
