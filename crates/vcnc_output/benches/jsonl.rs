//! The JSON-lines writer alone: the events of the two whole-command
//! benchmarks of issue #25 (`vcnc run --format jsonl` on the generated
//! surfacing program, and on the Fanuc lathe's turning passes), formatted
//! into a writer that drops the bytes. This is the sink thread's work in
//! `vcnc run --format jsonl` without the interpreter and the hand-over, so
//! that `valgrind --tool=callgrind` counts the writer's instructions per
//! event (`tools/bench/writer_instructions.sh`).
//! Run with `cargo bench -p vcnc_output`; figures in docs/performance.md.

use divan::{Bencher, counter::ItemsCount};
use vcnc_core::machine::DEFAULT_FANUC_LATHE_TOML;
use vcnc_core::{ArcDir, Event, Feed, Loc, Machine, Plane, Pos, Sink};
use vcnc_output::JsonlSink;

fn main() {
    divan::main();
}

fn loc(line: u64) -> Loc {
    Loc { line, file: None }
}

fn at(x: f64, y: f64, z: f64) -> Pos {
    let mut p = Pos::default();
    p.set(0, x);
    p.set(1, y);
    p.set(2, z);
    p
}

/// The feeds of `tools/bench/gen_surfacing.py`'s zig-zag: half-millimetre
/// steps in X, a row's Y, a waving Z of four decimals, F1500.
fn surfacing(n: usize) -> Vec<Event> {
    (0..n)
        .map(|i| {
            let row = i / 400;
            let k = (i % 400) as f64 * 0.5;
            let x = if row % 2 == 0 { -100.0 + k } else { 100.0 - k };
            let y = -75.0 + (row % 300) as f64 * 0.5;
            let z = -2.0 - (0.5 * (x / 20.0).sin() * (y / 15.0).cos() * 1e4).round() / 1e4;
            Event::Feed {
                loc: loc(i as u64 + 5),
                to: at(x, y, z),
                feed: Feed::PerMin(1500.0),
                exact_stop: false,
            }
        })
        .collect()
}

/// A position on the lathe's two axes (X, a radius as the interpreter
/// reports it, then Z).
fn xz(x: f64, z: f64) -> Pos {
    let mut p = Pos::default();
    p.set(0, x);
    p.set(1, z);
    p
}

/// The five blocks of `tools/bench/gen_fanuc_turning.py`'s pass.
fn turning(n: usize) -> Vec<Event> {
    let mut events = Vec::with_capacity(n);
    let mut line = 5;
    let mut pass = 0;
    while events.len() < n {
        let r = (118.0 - f64::from(pass % 50) * 2.0) / 2.0;
        let feed = Feed::PerRev(0.2);
        let pass_events = [
            Event::Rapid {
                loc: loc(line),
                to: xz(r, 2.0),
                exact_stop: false,
            },
            Event::Feed {
                loc: loc(line + 1),
                to: xz(r, -80.0),
                feed,
                exact_stop: false,
            },
            Event::Arc {
                loc: loc(line + 2),
                to: xz(r + 2.0, -82.0),
                center: xz(r + 2.0, -80.0),
                plane: Plane::Zx,
                dir: ArcDir::Cw,
                feed,
                exact_stop: false,
            },
            Event::Feed {
                loc: loc(line + 3),
                to: xz(r + 3.0, -82.0),
                feed,
                exact_stop: false,
            },
            Event::Rapid {
                loc: loc(line + 4),
                to: xz(r + 3.0, 2.0),
                exact_stop: false,
            },
        ];
        events.extend(pass_events);
        line += 5;
        pass += 1;
    }
    events.truncate(n);
    events
}

fn write_all(bencher: Bencher, events: &[Event], machine: &Machine) {
    bencher
        .counter(ItemsCount::new(events.len()))
        .bench_local(|| format_events(events, machine));
}

/// One pass of the sink over `events`: out of line, so that callgrind
/// can count it alone (`--toggle-collect=jsonl::format_events`).
#[inline(never)]
fn format_events(events: &[Event], machine: &Machine) {
    let mut sink = JsonlSink::new(std::io::sink(), machine);
    for e in events {
        sink.event(e);
    }
    let _ = sink.finish();
}

#[divan::bench(args = [100_000])]
fn jsonl_surfacing(bencher: Bencher, n: usize) {
    let machine = Machine::default_mill();
    write_all(bencher, &surfacing(n), &machine);
}

#[divan::bench(args = [100_000])]
fn jsonl_fanuc_turning(bencher: Bencher, n: usize) {
    let machine =
        Machine::from_toml(DEFAULT_FANUC_LATHE_TOML).unwrap_or_else(|_| Machine::default_mill());
    write_all(bencher, &turning(n), &machine);
}
