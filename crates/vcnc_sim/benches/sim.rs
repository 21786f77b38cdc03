//! Simulation throughput (issue #23): the surfacing program of
//! `tools/bench/gen_surfacing.py` (same formula, generated here: a
//! 200 × 150 mm wavy surface of 0.5 mm G1 segments, eight layers in a
//! million blocks) is interpreted once into events; each iteration
//! simulates all of them on a fresh Z-map at 0.1 mm (the automatic stock:
//! 206 × 156 mm, 3.2 M cells) with the assumed 6 mm flat end mill, on
//! every core (target ≥ 1 M blocks/s on 2 cores). A 100,000-block run of
//! a 6 mm ball end mill shows the closed-form ball path.
//! Run with `cargo bench -p vcnc_sim`; figures in docs/performance.md.

use divan::{Bencher, counter::ItemsCount};
use std::fmt::Write;
use vcnc_core::{Event, Sink, ToolKind, ToolLibrary, ToolShape, VecSink};
use vcnc_interp::{Dialect, Interpreter, Options};
use vcnc_sim::{SimOptions, Simulation, StockOrigin, StockSpec};

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
    let m = Dialect::fanuc().machine();
    let mut sink = VecSink::default();
    Interpreter::new(&m, &Dialect::fanuc(), Options::default())
        .run_str(&surfacing(blocks), &mut sink);
    sink.0
}

fn simulate(bencher: Bencher, blocks: usize, library: &ToolLibrary) {
    let evs = events(blocks);
    let m = Dialect::fanuc().machine();
    let workers = std::env::var("SIM_WORKERS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from));
    // The automatic stock of the program: the raster's extents grown by
    // the tool's 3 mm radius, Z0 down to 1 mm under the deepest cut.
    let stock = StockSpec::Box {
        min: [-103.0, -78.0, -6.0],
        max: [103.0, 78.0, 0.0],
    };
    bencher.counter(ItemsCount::new(blocks)).bench(|| {
        let options = SimOptions {
            stock: stock.clone(),
            stock_origin: StockOrigin::Auto,
            resolution_mm: Some(0.1),
            lathe: false,
            workers,
            replay: None,
        };
        let Ok(mut sim) = Simulation::new(&m, library, None, options) else {
            return 0.0;
        };
        for e in &evs {
            sim.event(e);
        }
        sim.finish_run().map_or(0.0, |f| f.report.removed_mm3)
    });
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn surfacing_1m_flat_0_1mm(bencher: Bencher) {
    simulate(bencher, 1_000_000, &ToolLibrary::default());
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn surfacing_100k_ball_0_1mm(bencher: Bencher) {
    let mut lib = ToolLibrary::default();
    lib.insert(ToolShape {
        kind: ToolKind::Ball,
        ..ToolShape::assumed(0)
    });
    simulate(bencher, 100_000, &lib);
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn surfacing_100k_flat_0_1mm(bencher: Bencher) {
    simulate(bencher, 100_000, &ToolLibrary::default());
}
