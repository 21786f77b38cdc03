//! Interpretation throughput: a generated 3-axis surfacing program (the shape
//! of `tools/bench/gen_surfacing.py`) interpreted from memory into a sink
//! that drops every event, plain and under rotation + scaling + tool length
//! (issue #6: ≥ 3 M blocks/s), a contour under cutter compensation
//! (issue #7: ≥ 3 M blocks/s), a turning program under the seed lathe and
//! the same passes under the Fanuc lathe (issue #11: its speed), and
//! 100,000 G83 holes (issue #8; counted in events, about ten a hole).
//! Run with `cargo bench -p vcnc_interp`; figures in docs/performance.md.

use divan::{Bencher, counter::ItemsCount};
use std::fmt::Write;
use std::sync::Arc;
use vcnc_interp::{Dialect, Interpreter, Machine, NoPrograms, NullSink, Options, Outcome};
use vcnc_syntax::MemSource;

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
    let dialect = Dialect::fanuc();
    bench_program(
        bencher,
        blocks,
        surfacing(blocks),
        &Machine::default_mill(),
        &dialect,
        "M02",
    );
}

/// Checks that `program` runs to `end`, then measures it into a null sink.
fn bench_program(
    bencher: Bencher,
    blocks: usize,
    program: String,
    machine: &Machine,
    dialect: &Dialect,
    end: &str,
) {
    let check =
        Interpreter::new(machine, dialect, Options::default()).run_str(&program, &mut NullSink);
    assert!(
        matches!(check, Outcome::Ended(code) if code.as_str() == end),
        "the benchmark program must run to its end: {check:?}"
    );
    // Shared, so an iteration does not copy the program.
    let text: Arc<[u8]> = program.into_bytes().into();
    bencher.counter(ItemsCount::new(blocks)).bench(|| {
        Interpreter::new(machine, dialect, Options::default()).run(
            Box::new(MemSource(text.clone())),
            &mut NoPrograms,
            &mut NullSink,
        )
    });
}

#[divan::bench(args = [100_000])]
fn interpret_transformed_to_null_sink(bencher: Bencher, blocks: usize) {
    let dialect = Dialect::fanuc();
    // The same raster under G68 + G51 + G43 (tool 1 given a length).
    let program = surfacing(blocks).replacen(
        "G21 G17 G90 G94\n",
        "G21 G17 G90 G94\nG10 L10 P1 R-50.\nG43 H1 Z20.\nG51 X0 Y0 Z0 P0.8\nG68 X10. Y-5. R30.\n",
        1,
    );
    bench_program(
        bencher,
        blocks,
        program,
        &Machine::default_mill(),
        &dialect,
        "M02",
    );
}

/// A closed wavy contour of `blocks` lines cut under G41 (issue #7:
/// ≥ 3 M blocks/s): every block is held and released by the compensation.
fn contour(blocks: usize) -> String {
    let mut s = String::with_capacity(blocks * 24);
    // Enter along the contour's tangent (a start-up across it would make
    // an inside corner that consumes the first short segment).
    s.push_str("G21 G17 G90 G94\nG0 X61. Y-10. Z5.\nG1 Z-1. F800.\nG41 D1 G1 X61. Y0\n");
    let n = blocks.saturating_sub(6).max(8);
    for k in 1..=n {
        let a = std::f64::consts::TAU * (k % 720) as f64 / 720.0;
        let r = 60.0 + (a * 6.0).sin();
        let _ = writeln!(s, "X{:.3} Y{:.3}", r * a.cos(), r * a.sin());
    }
    s.push_str("G40\nG0 Z5.\nM2\n");
    s
}

#[divan::bench(args = [100_000])]
fn interpret_compensated_to_null_sink(bencher: Bencher, blocks: usize) {
    let dialect = Dialect::fanuc();
    bench_program(
        bencher,
        blocks,
        contour(blocks),
        &Machine::default_mill(),
        &dialect,
        "M02",
    );
}

/// `blocks` blocks of roughing passes: `header`, then five blocks a pass
/// (`pass` spells them for a diameter), then M30.
fn passes(blocks: usize, header: &str, pass: fn(f64) -> [String; 5]) -> String {
    let mut s = String::with_capacity(blocks * 24);
    s.push_str(header);
    let mut n = 3;
    let mut k = 0usize;
    while n < blocks - 1 {
        let d = 118.0 - (k % 50) as f64 * 2.0;
        for line in pass(d) {
            s.push_str(&line);
            s.push('\n');
            n += 1;
            if n >= blocks - 1 {
                break;
            }
        }
        k += 1;
    }
    s.push_str("M30\n");
    s
}

/// A turning program of `blocks` blocks: roughing passes in diameters with
/// U/W increments and arcs, the shape of `tools/bench/gen_turning.py`.
fn turning(blocks: usize) -> String {
    passes(blocks, "G23\nG90 G94\nG00 X120 Z5\n", |d| {
        [
            format!("G00 X{d:.3} Z2.000"),
            "G01 Z-80.000 F200".to_string(),
            "G02 U4.000 W-2.000 R2.000".to_string(),
            "G01 U2.000".to_string(),
            "G00 Z2.000".to_string(),
        ]
    })
}

#[divan::bench(args = [100_000])]
fn interpret_turning_to_null_sink(bencher: Bencher, blocks: usize) {
    let dialect = Dialect::lathe();
    bench_program(
        bencher,
        blocks,
        turning(blocks),
        &dialect.machine(),
        &dialect,
        "M30",
    );
}

/// The passes of [`turning`] spelled for a Fanuc lathe (decimal points,
/// feed per revolution at a constant speed), the shape of
/// `tools/bench/gen_fanuc_turning.py`.
fn fanuc_turning(blocks: usize) -> String {
    passes(
        blocks,
        "G00 G18 G21 G40 G80 G99\nG97 S1000 M03\nG00 X120. Z5.\n",
        |d| {
            [
                format!("G00 X{d:.3} Z2."),
                "G01 Z-80. F0.2".to_string(),
                "G02 U4. W-2. R2.".to_string(),
                "G01 U2.".to_string(),
                "G00 Z2.".to_string(),
            ]
        },
    )
}

#[divan::bench(args = [100_000])]
fn interpret_fanuc_turning_to_null_sink(bencher: Bencher, blocks: usize) {
    let dialect = Dialect::fanuc_lathe();
    bench_program(
        bencher,
        blocks,
        fanuc_turning(blocks),
        &dialect.machine(),
        &dialect,
        "M30",
    );
}

/// `holes` G83 holes, three pecks each, the shape of
/// `tools/bench/gen_drilling.py`.
fn drilling(holes: usize) -> String {
    let mut s = String::with_capacity(holes * 16);
    s.push_str("G21 G17 G90 G94\nS3000 M03\nG00 X0 Y0 Z10.\n");
    s.push_str("G99 G83 X0.000 Y0.000 Z-5.3 R1. Q2. F300.\n");
    for k in 1..holes {
        let _ = writeln!(
            s,
            "X{:.3} Y{:.3}",
            (k % 1600) as f64 * 0.5,
            (k / 1600) as f64 * 0.5
        );
    }
    s.push_str("G80\nG00 Z10.\nM30\n");
    s
}

/// Counts the events of a run.
struct Count(usize);

impl vcnc_interp::Sink for Count {
    fn event(&mut self, _: &vcnc_interp::Event) {
        self.0 += 1;
    }
}

#[divan::bench(args = [100_000])]
fn interpret_drilling_to_null_sink(bencher: Bencher, holes: usize) {
    let dialect = Dialect::fanuc();
    let machine = Machine::default_mill();
    let program = drilling(holes);
    let mut count = Count(0);
    Interpreter::new(&machine, &dialect, Options::default()).run_str(&program, &mut count);
    // Items are events here, not blocks.
    bench_program(bencher, count.0, program, &machine, &dialect, "M30");
}
