#!/usr/bin/env python3
"""Write the LinuxCNC-derived fixture sets linuxcnc_tlo, linuxcnc_cycles,
linuxcnc_comp and linuxcnc_grbl (tests/fixtures/<set>/).

For each program of a set (gen_tlo.py, gen_cycles.py, gen_comp.py,
gen_grbl.py; seeded, so the output is byte-for-byte reproducible) this
script

  1. checks that the .nc (vcnc, fanuc dialect) and the .ngc (LinuxCNC) have
     the same lines and differ only in the spellings the set's README lists;
  2. runs rs274 -g on the .ngc (lines prefixed with N<line>) with the set's
     tool table (in inches: see rs274_events.tool_table_text) and a fresh
     parameter file;
  3. converts the canonical calls to vcnc events in machine coordinates
     (rs274_events.py) and checks them against the generator's own model of
     the program (motion end points, frames, holes: an independent Fanuc
     reading of the same program), so a program on which LinuxCNC and
     Fanuc disagree stops the script instead of becoming a fixture;
  4. writes NNN.nc, NNN.ngc and NNN.expected.jsonl (tlo, cycles, grbl) or
     NNN.points.jsonl (comp), and machine.toml (the default mill with the
     set's tool table and parameters; not for grbl, which runs on vcnc's
     built-in mill). The grbl set also (re)writes sanity_*.expected.jsonl
     from the hand-written sanity_*.ngc in its folder.

Usage: make_ext_fixtures.py [--set tlo|cycles|comp|grbl|all] [--rs274 PATH] [-j N]
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
FIXTURES = os.path.join(REPO, "tests", "fixtures")
# The default mill moved from vcnc_interp to vcnc_core; either will do.
DEFAULT_MILLS = [os.path.join(REPO, "crates", c, "src", "default_mill.toml")
                 for c in ("vcnc_core", "vcnc_interp")]
TOL = 1e-4


def machine_toml(tools, parameters=(), header=""):
    """default_mill.toml with its tool table replaced by `tools`
    ({n: (length mm, radius mm)}) and extra [parameters] lines."""
    path = next((p for p in DEFAULT_MILLS if os.path.exists(p)), DEFAULT_MILLS[0])
    with open(path) as f:
        text = f.read()
    # The tool section's comment: "# Tool table" before the built-in mill
    # lost its tools, "# Tool offsets" since.
    start = min(text.find(m) for m in ("# Tool table", "# Tool offsets") if m in text)
    end = text.index("[parameters]")
    table = ["# Tool table: H is a length, D a radius (geometry + wear). The same",
             "# tools as the LinuxCNC tool table of the fixture generator (there in",
             "# inches, D a diameter)."]
    for n in sorted(tools):
        length, radius = tools[n]
        table += ["[tools.%d]" % n, "h_mm = %r" % float(length),
                  "d_mm = %r" % float(radius)]
    text = text[:start] + "\n".join(table) + "\n\n" + text[end:]
    if parameters:
        # A key the default already sets is replaced (TOML forbids a key
        # twice); comments and new keys go right after [parameters].
        keys = {l.split("=")[0].strip() for l in parameters if "=" in l and not l.startswith("#")}
        text = "\n".join(l for l in text.split("\n")
                         if l.split("=")[0].strip() not in keys or "=" not in l)
        marker = "[parameters]\n"
        i = text.index(marker) + len(marker)
        text = text[:i] + "".join(l + "\n" for l in parameters) + text[i:]
    text = re.sub(r'name = "([^"]*)"', lambda m: 'name = "%s (%s)"' % (m.group(1), header),
                  text, count=1)
    return text


def check_spellings(ngc, nc, to_ngc, name):
    if len(ngc) != len(nc):
        raise ConvertError("%s: .ngc has %d lines, .nc %d" % (name, len(ngc), len(nc)))
    for i, (a, b) in enumerate(zip(ngc, nc), 1):
        if a != to_ngc(b):
            raise ConvertError("%s:%d: spellings differ beyond the known ones: %r vs %r"
                               % (name, i, a, b))


def close(p, q):
    return all(abs(p[a] - q[a]) <= TOL for a in rv.AXES)


def mm_point(units):
    return {a: units[i] / 10000.0 for i, a in enumerate(rv.AXES)}


def check_trace(events, trace, name, kinds=("rapid", "feed", "arc")):
    got = [(e["line"], e["type"], e["to"]) for e in events if e["type"] in kinds]
    if len(got) != len(trace):
        raise ConvertError("%s: %d motions from rs274, %d expected by the generator"
                           % (name, len(got), len(trace)))
    for (gl, gk, gto), (el, ek, eto) in zip(got, trace):
        e = eto if isinstance(eto, dict) else mm_point(eto)
        if gl != el or gk != ek or not close(gto, e):
            raise ConvertError("%s:%d: rs274 gives %s to %s, the generator %s:%d %s to %s"
                               % (name, gl, gk, gto, name, el, ek, e))


def write_program(folder, stem, ngc, nc):
    for ext, lines in (("ngc", ngc), ("nc", nc)):
        with open(os.path.join(folder, "%s.%s" % (stem, ext)), "w") as f:
            f.write("\n".join(lines) + "\n")


def clean(folder, suffixes):
    os.makedirs(folder, exist_ok=True)
    for f in os.listdir(folder):
        if re.fullmatch(r"\d{3}\.(%s)" % "|".join(re.escape(s) for s in suffixes), f):
            os.remove(os.path.join(folder, f))


# -- linuxcnc_tlo ---------------------------------------------------------------

def tlo_to_ngc(line):
    line = re.sub(r"^G4 X", "G4 P", line)
    return re.sub(r"^G10 L10 P(\d+) R", r"G10 L1 P\1 Z", line)


def tlo_one(i, rs274):
    import gen_tlo
    stem = "%03d" % i
    ngc, nc, trace, frames = gen_tlo.generate(i)
    check_spellings(ngc, nc, tlo_to_ngc, stem)
    end, cycles, m5 = rv.program_facts(ngc)
    out = rv.run_rs274(rs274, ngc, rv.tool_table_text(gen_tlo.TOOLS), stem)
    events = rv.convert(out, stem, end, cycles, m5)
    check_trace(events, trace, stem)
    got = [(e["line"], e["origin"], e.get("tool_offset", {"z": 0.0})["z"])
           for e in events if e["type"] == "frame"]
    want = [(l, mm_point(o), t / 10000.0) for l, o, t in frames]
    if len(got) != len(want) or any(
            gl != wl or not close(go, wo) or abs(gt - wt) > TOL
            for (gl, go, gt), (wl, wo, wt) in zip(got, want)):
        raise ConvertError("%s: frames from rs274 %s, generator %s" % (stem, got, want))
    return stem, ngc, nc, events


def make_tlo(rs274, jobs):
    import gen_tlo
    folder = os.path.join(FIXTURES, "linuxcnc_tlo")
    results = run_all(lambda i: tlo_one(i, rs274), range(1, gen_tlo.DEFAULT_COUNT + 1), jobs)
    clean(folder, ["nc", "ngc", "expected.jsonl"])
    n = 0
    for stem, ngc, nc, events in results:
        write_program(folder, stem, ngc, nc)
        rv.write_jsonl(os.path.join(folder, stem + ".expected.jsonl"), events)
        n += len(events)
    with open(os.path.join(folder, "machine.toml"), "w") as f:
        f.write(machine_toml(gen_tlo.TOOLS, header="linuxcnc_tlo fixtures"))
    return "%d programs, %d events -> %s" % (len(results), n, folder)


# -- linuxcnc_cycles --------------------------------------------------------------

def cycles_to_ngc(line):
    """vcnc spelling -> LinuxCNC spelling of one line of gen_cycles.py."""
    m = re.search(r"G(8[1-9]|73)(?!\d)", line)
    line = re.sub(r" K(\d+)$", r" L\1", line)
    if m and m.group(1) in ("73", "83"):
        # the P0 that clears a modal dwell for vcnc (gen_cycles.py)
        line = line.replace(" P0", "", 1) if re.search(r" P0(?![\d.])", line) else line
    if not line.startswith("G10") and re.search(r"P\d+(?![\d.])", line):
        ms = int(re.search(r"P(\d+)(?![\d.])", line).group(1))
        s = "%d.%03d" % divmod(ms, 1000)
        s = s[:-2] if s.endswith(".000") else s.rstrip("0")
        line = re.sub(r"P\d+(?![\d.])", "P" + s, line)
    if m and m.group(1) == "86":
        # G86 needs a P in LinuxCNC: before F and L
        parts = line.split(" ")
        k = len(parts)
        while k > 0 and parts[k - 1][0] in "FL":
            k -= 1
        parts.insert(k, "P0.")
        line = " ".join(parts)
    return line


def same_events(got, want):
    if len(got) != len(want):
        return False
    for g, w in zip(got, want):
        if set(g) != set(w):
            return False
        for k in g:
            a, b = g[k], w[k]
            if isinstance(a, dict):
                if not close(a, b):
                    return False
            elif isinstance(a, float) or isinstance(b, float):
                if abs(a - b) > TOL:
                    return False
            elif a != b:
                return False
    return True


def cycles_one(i, rs274):
    import gen_cycles
    stem = "%03d" % i
    ngc, nc, model = gen_cycles.generate(i)
    check_spellings(ngc, nc, cycles_to_ngc, stem)
    end, cycles, m5 = rv.program_facts(ngc)
    out = rv.run_rs274(rs274, ngc, rv.tool_table_text(gen_cycles.TOOLS), stem)
    events = rv.convert(out, stem, end, cycles, m5)
    got = [e for e in events if e["type"] != "end"]
    if not same_events(got, model):
        for k, (g, w) in enumerate(zip(got, model)):
            if not same_events([g], [w]):
                raise ConvertError("%s: event %d: rs274 %s, generator %s" % (stem, k + 1, g, w))
        raise ConvertError("%s: %d events from rs274, %d from the generator"
                           % (stem, len(got), len(model)))
    return stem, ngc, nc, events


def make_cycles(rs274, jobs):
    import gen_cycles
    folder = os.path.join(FIXTURES, "linuxcnc_cycles")
    results = run_all(lambda i: cycles_one(i, rs274),
                      range(1, gen_cycles.DEFAULT_COUNT + 1), jobs)
    clean(folder, ["nc", "ngc", "expected.jsonl"])
    n = 0
    for stem, ngc, nc, events in results:
        write_program(folder, stem, ngc, nc)
        rv.write_jsonl(os.path.join(folder, stem + ".expected.jsonl"), events)
        n += len(events)
    with open(os.path.join(folder, "machine.toml"), "w") as f:
        f.write(machine_toml(gen_cycles.TOOLS, header="linuxcnc_cycles fixtures",
                             parameters=[
                                 "# Syntec 4002 (G73 retract, G83 re-approach d): LinuxCNC's",
                                 "# 0.010 in.",
                                 "peck_return_mm = 0.254"]))
    return "%d programs, %d events -> %s" % (len(results), n, folder)


# -- linuxcnc_comp -------------------------------------------------------------------

COMP_TOL = 1e-3     # matching a Fanuc point with a LinuxCNC end point


def comp_one(i, rs274):
    import gen_comp
    stem = "%03d" % i
    ngc, nc, points = gen_comp.generate(i)
    check_spellings(ngc, nc, lambda l: l, stem)
    end, cycles, m5 = rv.program_facts(ngc)
    out = rv.run_rs274(rs274, ngc, rv.tool_table_text(gen_comp.TOOLS), stem)
    events = rv.convert(out, stem, end, cycles, m5)
    ends = [e["to"] for e in events if e["type"] in ("rapid", "feed", "arc")]
    rows = []
    k = 0
    worst = 0.0
    for line, kind, p in points:
        want = dict(zip(rv.AXES, p))
        while k < len(ends) and not all(abs(ends[k][a] - want[a]) <= COMP_TOL for a in rv.AXES):
            k += 1
        if k == len(ends):
            raise ConvertError("%s:%d: %s point %s is not among rs274's end points "
                               "(in order)" % (stem, line, kind, want))
        worst = max(worst, max(abs(ends[k][a] - want[a]) for a in rv.AXES))
        rows.append({"line": line, "kind": kind, "to": ends[k]})
        k += 1
    return stem, ngc, nc, rows, worst


def make_comp(rs274, jobs):
    import gen_comp
    folder = os.path.join(FIXTURES, "linuxcnc_comp")
    results = run_all(lambda i: comp_one(i, rs274), range(1, gen_comp.DEFAULT_COUNT + 1), jobs)
    clean(folder, ["nc", "ngc", "points.jsonl"])
    n = 0
    worst = 0.0
    for stem, ngc, nc, rows, w in results:
        write_program(folder, stem, ngc, nc)
        rv.write_jsonl(os.path.join(folder, stem + ".points.jsonl"), rows)
        n += len(rows)
        worst = max(worst, w)
    with open(os.path.join(folder, "machine.toml"), "w") as f:
        f.write(machine_toml(gen_comp.TOOLS, header="linuxcnc_comp fixtures"))
    return ("%d programs, %d points (largest distance between a Fanuc point and "
            "rs274's: %.6f mm) -> %s" % (len(results), n, worst, folder))


# -- linuxcnc_grbl ------------------------------------------------------------------

def grbl_events(ngc, stem, rs274):
    """rs274's trace of a grbl-set program (both spellings are this text)."""
    import gen_grbl
    end, cycles, m5 = rv.program_facts(ngc)
    if cycles or end is None:
        raise ConvertError("%s: canned cycles or no M2/M30" % stem)
    out = rv.run_rs274(rs274, ngc, rv.tool_table_text(gen_grbl.TOOLS), stem,
                       var_text=gen_grbl.VAR_TEXT)
    return rv.convert(out, stem, end, None, m5, inch=True,
                      end_code=rv.end_code(ngc, end),
                      home_lines=rv.home_lines(ngc),
                      optional_stop="--optional-stop" in ngc[0])


def grbl_one(i, rs274):
    import gen_grbl
    stem = "%03d" % i
    lines, trace, frames, feeds = gen_grbl.generate(i)
    events = grbl_events(lines, stem, rs274)
    check_trace(events, trace, stem)
    got = [(e["line"], e["origin"], e.get("tool_offset", {"z": 0.0})["z"])
           for e in events if e["type"] == "frame"]
    want = [(l, mm_point(o), t / 10000.0) for l, o, t in frames]
    if len(got) != len(want) or any(
            gl != wl or not close(go, wo) or abs(gt - wt) > TOL
            for (gl, go, gt), (wl, wo, wt) in zip(got, want)):
        raise ConvertError("%s: frames from rs274 %s, generator %s" % (stem, got, want))
    # inverse time: rs274's equivalent feed, the generator's length x F
    by_line = {e["line"]: e["feed"] for e in events
               if e["type"] in ("feed", "arc") and e["line"] in dict(feeds)}
    for line, f in feeds:
        if line not in by_line or abs(by_line[line] - f) > TOL:
            raise ConvertError("%s:%d: G93 feed from rs274 %s, generator %.6f"
                               % (stem, line, by_line.get(line), f))
    return stem, lines, events


def make_grbl(rs274, jobs):
    import gen_grbl
    folder = os.path.join(FIXTURES, "linuxcnc_grbl")
    results = run_all(lambda i: grbl_one(i, rs274),
                      range(1, gen_grbl.DEFAULT_COUNT + 1), jobs)
    clean(folder, ["nc", "ngc", "expected.jsonl"])
    n = 0
    for stem, lines, events in results:
        write_program(folder, stem, lines, lines)
        rv.write_jsonl(os.path.join(folder, stem + ".expected.jsonl"), events)
        n += len(events)
    sanity = sorted(f[:-4] for f in os.listdir(folder)
                    if f.startswith("sanity_") and f.endswith(".ngc"))
    for stem in sanity:
        with open(os.path.join(folder, stem + ".ngc")) as f:
            ngc = f.read().split("\n")
        with open(os.path.join(folder, stem + ".nc")) as f:
            if f.read().split("\n") != ngc:
                sys.exit("%s: .nc and .ngc differ" % stem)
        if ngc[-1] != "":
            sys.exit("%s: no final newline" % stem)
        events = grbl_events(ngc[:-1], stem, rs274)
        rv.write_jsonl(os.path.join(folder, stem + ".expected.jsonl"), events)
        n += len(events)
    return "%d programs + %d sanity programs, %d events -> %s" % (
        len(results), len(sanity), n, folder)


# -- driver ------------------------------------------------------------------------

def run_all(fn, indices, jobs):
    failures = []

    def work(i):
        try:
            return fn(i)
        except ConvertError as e:
            failures.append(str(e))
            return None

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as ex:
        results = list(ex.map(work, indices))
    if failures:
        for msg in sorted(failures):
            print("ERROR " + msg, file=sys.stderr)
        sys.exit("%d of %d programs failed" % (len(failures), len(results)))
    return results


SETS = {"tlo": make_tlo, "cycles": make_cycles, "comp": make_comp, "grbl": make_grbl}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--set", default="all", choices=sorted(SETS) + ["all"])
    ap.add_argument("--rs274", default=shutil.which("rs274") or "rs274")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args(argv)
    if not os.path.exists(args.rs274) and not shutil.which(args.rs274):
        sys.exit("rs274 not found: apt-get install linuxcnc-uspace")
    for name in (sorted(SETS) if args.set == "all" else [args.set]):
        print(name + ": " + SETS[name](args.rs274, args.jobs))
    return 0


if __name__ == "__main__":
    sys.exit(main())
