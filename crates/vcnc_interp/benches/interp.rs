//! Interpretation throughput: a generated 3-axis surfacing program (the shape
//! of `tools/bench/gen_surfacing.py`) interpreted from memory into a sink
//! that drops every event. Target (issue #2): ≥ 10 M blocks/s on the 2-core
//! CI machine. Run with `cargo bench -p vcnc_interp`.

use divan::{Bencher, counter::ItemsCount};
use std::fmt::Write;
use vcnc_interp::{Dialect, Interpreter, Machine, NullSink, Options};

fn main() {
    divan::main();
}

/// A zig-zag raster of `blocks` blocks over a gently waving surface.
fn surfacing(blocks: usize) -> String {
    let mut s = String::with_capacity(blocks * 24);
    s.push_str("G21 G17 G90 G94\nG0 Z10.0\nG0 X-100.000 Y-75.000\nG1 Z-1.0 F1500.0\n");
    let mut n = 4;
    let mut row = 0usize;
    while n < blocks - 1 {
        let y = -75.0 + (row % 300) as f64 * 0.5;
        for k in 0..200 {
            let x = if row.is_multiple_of(2) {
                -100.0 + k as f64
            } else {
                100.0 - k as f64
            };
            let z = -1.0 - 0.5 * ((x / 20.0).sin() * (y / 15.0).cos());
            let _ = writeln!(s, "X{x:.3} Y{y:.3} Z{z:.4}");
            n += 1;
            if n >= blocks - 1 {
                break;
            }
        }
        row += 1;
    }
    s.push_str("M2\n");
    s
}

#[divan::bench(args = [100_000])]
fn interpret_to_null_sink(bencher: Bencher, blocks: usize) {
    let program = surfacing(blocks);
    let machine = Machine::default_mill();
    let dialect = Dialect::fanuc();
    bencher.counter(ItemsCount::new(blocks)).bench(|| {
        let mut sink = NullSink;
        Interpreter::new(&machine, &dialect, Options::default()).run_str(&program, &mut sink)
    });
}
