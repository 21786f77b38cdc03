//! Macro throughput (issue 9: a macro loop runs ≥ 5 M statements/s):
//! Custom Macro B, Syntec MACRO and LinuxCNC loops of assignments, and a
//! loop of word blocks whose values are expressions, interpreted from memory into a sink
//! that drops every event. Items are statements executed (loop heads,
//! bodies and ends), counted by hand from each program's shape. The
//! literal-program benchmarks in `interp.rs` guard that the macro front end
//! costs nothing when a program has no macro syntax. Run with `cargo bench
//! -p vcnc_interp --bench macros`; figures in docs/performance.md.

use divan::{Bencher, counter::ItemsCount};
use std::sync::Arc;
use vcnc_interp::{Dialect, Interpreter, Machine, NoPrograms, NullSink, Options, Outcome};
use vcnc_syntax::MemSource;

fn main() {
    divan::main();
}

/// Passes of each loop: 3 × 200,000 statements for the WHILE loop.
const PASSES: usize = 200_000;

/// A machine whose runaway limits let the loops run to their end.
fn machine() -> Machine {
    let text = vcnc_interp::machine::DEFAULT_MILL_TOML
        .replace("max_jumps = 1000000", "max_jumps = 100000000")
        .replace(
            "max_executed_blocks = 5000000",
            "max_executed_blocks = 100000000",
        );
    Machine::from_toml(&text).unwrap_or_else(|e| panic!("bench machine: {e}"))
}

fn bench(bencher: Bencher, statements: usize, program: String, dialect: &Dialect) {
    let machine = machine();
    let check =
        Interpreter::new(&machine, dialect, Options::default()).run_str(&program, &mut NullSink);
    assert!(
        matches!(check, Outcome::Ended(_)),
        "the benchmark program must run to its end: {check:?}"
    );
    let text: Arc<[u8]> = program.into_bytes().into();
    bencher.counter(ItemsCount::new(statements)).bench(|| {
        Interpreter::new(&machine, dialect, Options::default()).run(
            Box::new(MemSource(text.clone())),
            &mut NoPrograms,
            &mut NullSink,
        )
    });
}

/// WHILE, an assignment and END per pass: 3 statements.
#[divan::bench]
fn macro_b_while_loop(bencher: Bencher) {
    let program = format!("#1 = 0\nWHILE [#1 LT {PASSES}] DO 1\n#1 = #1 + 1\nEND 1\nM30\n");
    bench(bencher, 3 * PASSES, program, &Dialect::fanuc());
}

/// A FOR body of one assignment and END_FOR per pass: 2 statements (the
/// FOR head steps at END_FOR's jump back, so it runs once a pass too: 3).
#[divan::bench]
fn syntec_for_loop(bencher: Bencher) {
    let program = format!(
        "%@MACRO\n#2 := 0;\nFOR #1 := 1 TO {PASSES} DO\n  #2 := #2 + #1;\nEND_FOR;\nM30;\n"
    );
    bench(bencher, 3 * PASSES, program, &Dialect::syntec());
}

/// A loop that moves: WHILE, a word block with two expressions, an
/// assignment and END per pass (4 statements, one motion event).
#[divan::bench]
fn macro_b_moving_loop(bencher: Bencher) {
    let program = format!(
        "G90 G01 F1000.\n#1 = 0\nWHILE [#1 LT {PASSES}] DO 1\nX[#1 MOD 100] Y-#1\n#1 = #1 + 1\nEND 1\nM30\n"
    );
    bench(bencher, 4 * PASSES, program, &Dialect::fanuc());
}

/// LinuxCNC: `o100 while`, a parameter setting and `o100 endwhile` per
/// pass (3 statements).
#[divan::bench]
fn ngc_while_loop(bencher: Bencher) {
    let program =
        format!("#1 = 0\no100 while [#1 LT {PASSES}]\n#1 = [#1 + 1]\no100 endwhile\nM2\n");
    bench(bencher, 3 * PASSES, program, &Dialect::linuxcnc());
}
