//! Planning throughput (issue #12): the surfacing program of
//! `tools/bench/gen_surfacing.py` (same formula, generated here) is
//! interpreted once into events; each iteration plans all of them with a
//! 200-block look-ahead into the cycle-time sum — trapezoid (target ≥ 4 M
//! blocks/s) and jerk-limited (≥ 2 M blocks/s) — and a 1 kHz trace of a
//! program that runs about ten minutes is sampled (target < 2 s).
//! Run with `cargo bench -p vcnc_planner`; figures in docs/performance.md.

use divan::{Bencher, counter::ItemsCount};
use std::fmt::Write;
use vcnc_core::{Event, Machine, Sink, VecSink};
use vcnc_interp::{Dialect, Interpreter, Options};
use vcnc_planner::{CycleTime, Planner, ProfileShape, Sample, Sampler};

fn main() {
    divan::main();
}

fn surface(x: f64, y: f64) -> f64 {
    1.5 * (x / 17.0).sin() * (y / 23.0).cos() + 0.4 * ((x + y) / 7.0).sin() - 2.0
}

/// The first `n` lines of `gen_surfacing.py N`.
fn surfacing(n: usize) -> String {
    let mut lines = vec!["G21 G17 G90 G94".to_string()];
    let (nx, ny) = (400usize, 300usize);
    let mut layer = 0u32;
    'outer: loop {
        let depth = -0.25 * f64::from(layer);
        let (mut x, mut y) = (-100.0, -75.0);
        for l in [
            "G0 Z10.0".to_string(),
            format!("G0 X{x:.3} Y{y:.3}"),
            format!("G0 Z{:.4}", surface(x, y) + depth + 1.0),
            format!("G1 Z{:.4} F1500.0", surface(x, y) + depth),
        ] {
            lines.push(l);
        }
        for j in 0..=ny {
            y = -75.0 + j as f64 * 0.5;
            if j > 0 {
                lines.push(format!("G1 Y{y:.3} Z{:.4}", surface(x, y) + depth));
            }
            for i in 1..=nx {
                let k = if j % 2 == 0 { i } else { nx - i };
                x = -100.0 + k as f64 * 0.5;
                lines.push(format!("X{x:.3} Z{:.4}", surface(x, y) + depth));
                if lines.len() >= n - 1 {
                    break 'outer;
                }
            }
        }
        layer += 1;
    }
    lines.push("M2".into());
    let mut s = String::new();
    for l in lines {
        let _ = writeln!(s, "{l}");
    }
    s
}

fn events(blocks: usize) -> Vec<Event> {
    let m = Machine::default_mill();
    let mut sink = VecSink::default();
    Interpreter::new(&m, &Dialect::fanuc(), Options::default())
        .run_str(&surfacing(blocks), &mut sink);
    sink.0
}

fn plan(bencher: Bencher, blocks: usize, shape: ProfileShape) {
    let evs = events(blocks);
    let m = Machine::default_mill();
    bencher.counter(ItemsCount::new(blocks)).bench(|| {
        let mut p = Planner::with_profile(&m, shape, CycleTime::new());
        for e in &evs {
            p.event(e);
        }
        p.into_timeline().total_s
    });
}

#[divan::bench(args = [1_000_000], sample_count = 5)]
fn plan_surfacing_trapezoid(bencher: Bencher, blocks: usize) {
    plan(bencher, blocks, ProfileShape::Trapezoid);
}

#[divan::bench(args = [1_000_000], sample_count = 5)]
fn plan_surfacing_jerk(bencher: Bencher, blocks: usize) {
    plan(bencher, blocks, ProfileShape::Jerk);
}

/// The built-in mill's own profile: the trapezoid plan and a run-out
/// after each stop.
#[divan::bench(args = [1_000_000], sample_count = 5)]
fn plan_surfacing_filter(bencher: Bencher, blocks: usize) {
    plan(bencher, blocks, ProfileShape::Filter);
}

/// About 10 minutes of surfacing (F1500, 0.5 mm segments: 50 blocks/s),
/// sampled every millisecond into a sink that only sums.
#[divan::bench(sample_count = 5)]
fn trace_ten_minutes_at_1khz(bencher: Bencher) {
    let evs = events(30_500);
    let m = Machine::default_mill();
    bencher.bench(|| {
        let mut n = 0u64;
        let mut acc = 0.0;
        let sampler = Sampler::new(0.001, m.start, |s: &Sample| {
            n += 1;
            acc += s.vel[0];
        });
        let mut p = Planner::new(&m, sampler);
        for e in &evs {
            p.event(e);
        }
        let t = p.into_timeline().elapsed_s();
        (n, acc, t)
    });
}
