"""The `vcnc` module: check, events, flatten, time and errors.

Expected values are worked out by hand from the programs (distances,
extents, dwell times) or are the command line's own output for the same
program (the module must say exactly what `vcnc run` says).
"""

import itertools
import json
import math
import subprocess
import threading
import time as clock

import pytest
from pathlib import Path

import vcnc

# A bracket: a 10 mm rapid up, a cut down and around, a drilled hole.
PART = """G90 G54 G17 G21 G00 X0 Y0 Z10.
T1 M06
S1000 M03
G01 Z-1. F100.
X20.
Y10.
G00 Z10.
T2 M06
G81 X5. Y5. Z-3. R2. F50.
G80
M30
"""

# Two independent mistakes: an arc off its circle (line 3), and a code
# Fanuc mills lack (line 4).
TWO_MISTAKES = """S1000 M03 G90 G00 X0 Y0
G01 X20. F200.
G02 X30. Y0 I3. J0.
G145 X40.
M30
"""

# A loop that never ends: the machine's jump limit ends it.
FOREVER = "S1000 M03\n#1 = 1\nWHILE [1 EQ 1] DO1\nG01 X[#1] F100.\n#1 = #1 + 1\nEND1\nM30\n"


def test_check_reports_the_summary_worked_out_by_hand():
    r = vcnc.check(PART, dialect="fanuc")
    assert r.ended and r.end == "M30" and r.alarm is None
    assert r.alarms == [] and r.warnings == [] and r.warning_count == 0
    assert r.tools == [1, 2]
    assert r.holes == 1
    assert r.spindle_rpm == (1000.0, 1000.0)
    assert r.extents == {
        "min": {"x": 0.0, "y": 0.0, "z": -3.0},
        "max": {"x": 20.0, "y": 10.0, "z": 10.0},
    }
    # Cuts: 11 down, 20 along X, 10 along Y, 5 drilled (R2 to Z-3).
    assert r.cut_mm == pytest.approx(46.0)
    # Rapids: 10 up, 11 up, sqrt(15^2 + 5^2) across, 8 down to R, 13 out.
    assert r.rapid_mm == pytest.approx(10 + 11 + math.sqrt(250) + 8 + 13)
    assert r.dialect == "fanuc"
    assert r.cycle_time_s > r.distance_feed_s > 0
    assert "ended by M30" in repr(r)


def test_check_reports_alarms_and_keeps_going_on_request():
    r = vcnc.check(TWO_MISTAKES, dialect="fanuc")
    assert not r.ended and r.end is None
    a = r.alarm
    assert (a.code, a.line, a.column) == ("E303", 3, 1)
    assert "not on the circle" in a.message and a.help
    assert not a.is_warning and a.file is None
    assert [d.code for d in r.alarms] == ["E303"]
    r = vcnc.check(TWO_MISTAKES, dialect="fanuc", keep_going=True)
    assert [(d.code, d.line) for d in r.alarms] == [("E303", 3), ("E201", 4)]
    assert r.alarm.code == "E303"


def test_warnings_are_diagnostics():
    # A cut with the spindle stopped: W104.
    r = vcnc.check("G01 X10. F100.\nM30\n", dialect="fanuc")
    assert r.ended
    assert [w.code for w in r.warnings] == ["W104"]
    assert r.warnings[0].is_warning and r.warning_count == 1


def test_the_dialect_comes_from_the_first_line_or_the_argument():
    text = "(vcnc: --dialect linuxcnc)\nG64 P0.01\nG01 X1 F100\nM2\n"
    assert vcnc.check(text).dialect == "linuxcnc"
    # Detected as the command line's --dialect auto does: nothing but a
    # move, no industrial sign: grbl (docs/dialects.md, detection).
    assert vcnc.check("G00 X1.\nM30\n").dialect == "grbl"
    assert vcnc.check("G00 X1.\nM30\n", dialect="HAAS").dialect == "haas"
    assert "syntec" in vcnc.dialects()


def test_events_are_the_jsonl_of_the_command_line(vcnc_bin, tmp_path):
    got = list(vcnc.events(PART, dialect="fanuc"))
    path = tmp_path / "part.nc"
    path.write_text(PART)
    out = subprocess.run(
        [vcnc_bin, "run", "--dialect", "fanuc", str(path)],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    assert got == [json.loads(line) for line in out.splitlines()]
    # And by hand: the first rapid, the tool change, the hole.
    assert got[0] == {"type": "rapid", "line": 1, "to": {"x": 0.0, "y": 0.0, "z": 10.0}}
    assert got[1] == {"type": "tool_change", "line": 2, "tool": 1}
    assert {"type": "hole", "line": 9, "cycle": "G81", "at": {"x": 5.0, "y": 5.0, "z": -3.0}} in got
    assert got[-1] == {"type": "end", "line": 11, "code": "M30"}


def test_events_are_lazy_and_end_with_the_alarm():
    # The first events of an endless program come at once; the rest are
    # never computed once the iterator is dropped.
    it = vcnc.events(FOREVER, dialect="fanuc")
    first = list(itertools.islice(it, 6))
    assert [e["type"] for e in first] == ["spindle"] + ["feed"] * 5
    # (From X1: a first move to X0, where the tool is, would not be reported.)
    assert [e["to"]["x"] for e in first[1:]] == [1.0, 2.0, 3.0, 4.0, 5.0]
    del it
    last = list(vcnc.events(TWO_MISTAKES, dialect="fanuc"))[-1]
    assert last["type"] == "alarm" and last["code"] == "E303" and last["line"] == 3


def test_flatten_expands_cycles_like_the_command_line(vcnc_bin, tmp_path):
    flat = vcnc.flatten(PART, dialect="fanuc")
    path = tmp_path / "part.nc"
    path.write_text(PART)
    out = subprocess.run(
        [vcnc_bin, "run", "--format", "gcode", "--dialect", "fanuc", str(path)],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    assert flat == out
    # No cycle code is left in a block (a comment names the hole).
    blocks = [line.split("(")[0] for line in flat.splitlines()]
    assert not any("G81" in b or "G80" in b for b in blocks)
    # The hole as plain moves: down at feed to Z-3 at X5 Y5.
    assert any("Z-3" in line and line.startswith("G1") for line in flat.splitlines())


def test_time_splits_the_planned_time():
    t = vcnc.time("G04 X2.\nG04 X0.5\nM30\n", dialect="fanuc")
    assert t.dwell_s == pytest.approx(2.5)
    assert t.total_s == pytest.approx(2.5)
    assert t.cutting_mm == 0.0
    part = vcnc.time(PART, dialect="fanuc")
    assert part.total_s == pytest.approx(vcnc.check(PART, dialect="fanuc").cycle_time_s)
    assert part.cutting_mm == pytest.approx(46.0)
    assert set(part.per_tool) <= {None, 1, 2} and 2 in part.per_tool


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="unknown dialect"):
        vcnc.check("M30\n", dialect="okuma")
    with pytest.raises(ValueError, match="cannot read machine file"):
        vcnc.check("M30\n", machine="/no/such/machine.toml")
    with pytest.raises(TypeError):
        vcnc.check(42)
    with pytest.raises(ValueError, match="cannot read tool table"):
        vcnc.check("M30\n", tools="/no/such/tools.tbl")
    with pytest.raises(ValueError, match="unknown dialect"):
        vcnc.check("(vcnc: --dialect nope)\nM30\n")


def test_a_bad_machine_file_names_itself(tmp_path):
    bad = tmp_path / "machine.toml"
    bad.write_text("this is = not [ toml")
    with pytest.raises(ValueError, match="machine.toml"):
        vcnc.check("M30\n", machine=bad)


def test_alarms_in_flatten_and_time_raise_program_alarm():
    with pytest.raises(vcnc.ProgramAlarm) as e:
        vcnc.flatten(TWO_MISTAKES, dialect="fanuc")
    assert e.value.alarm.code == "E303" and e.value.alarm.line == 3
    assert isinstance(e.value, vcnc.Error)
    with pytest.raises(vcnc.ProgramAlarm):
        vcnc.time(TWO_MISTAKES, dialect="fanuc")


def test_junk_is_a_result_not_a_crash():
    junk = bytes(range(256)) * 64
    r = vcnc.check(junk)
    assert not r.ended and r.alarm is not None
    assert list(vcnc.events(junk))[-1]["type"] == "alarm"
    r = vcnc.check(FOREVER, dialect="fanuc")
    assert r.alarm.code == "E405"


def test_the_gil_is_released_while_interpreting():
    # While one thread runs the endless program to its limit, this one
    # keeps running Python code.
    done = threading.Event()
    result = {}

    def run():
        result["r"] = vcnc.check(FOREVER, dialect="fanuc")
        done.set()

    t = threading.Thread(target=run)
    ticks = 0
    t.start()
    start = clock.monotonic()
    while not done.is_set():
        ticks += 1
        clock.sleep(0.001)
    t.join()
    elapsed = clock.monotonic() - start
    assert result["r"].alarm.code == "E405"
    # A run of a million jumps takes far longer than a few milliseconds;
    # with the GIL held the loop above could not have ticked meanwhile.
    assert elapsed > 0.05 and ticks > 10, (elapsed, ticks)


def test_a_tool_table_fills_the_radius_compensation_reads(tmp_path):
    # tools.csv's tool 1 is 6 mm across: G41 D1 starts east along Y0 with
    # the tool on the left, so the first compensated move ends at X0 Y3.
    # Without a table the built-in mill's D1 is 0 and the path stays on Y0.
    table = Path(__file__).resolve().parents[2] / "tests/fixtures/tools/tools.csv"
    program = "S1000 M03\nG00 X-10. Y0. Z0.\nG41 D1 G01 X0. Y0. F300.\nX50.\nG40 X60. Y-10.\nM30\n"
    feeds = [e for e in vcnc.events(program, dialect="fanuc", tools=str(table)) if e["type"] == "feed"]
    assert feeds[0]["to"] == {"x": 0.0, "y": 3.0, "z": 0.0}
    feeds = [e for e in vcnc.events(program, dialect="fanuc") if e["type"] == "feed"]
    assert feeds[0]["to"]["y"] == 0.0
    bad = tmp_path / "bad.tbl"
    bad.write_text("T1 P1 D-6.0\n")
    with pytest.raises(ValueError, match="bad.tbl"):
        vcnc.check(program, dialect="fanuc", tools=str(bad))
