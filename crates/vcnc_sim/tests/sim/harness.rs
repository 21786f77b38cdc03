//! Runs a program through the interpreter into a simulation.

use vcnc_core::{ToolKind, ToolLibrary, ToolShape, ToolSource};
use vcnc_interp::{Dialect, Interpreter, Options};
use vcnc_sim::{Finished, SimOptions, Simulation, StockOrigin, StockSpec};

/// A tool described as a table would.
pub fn tool(number: u32, kind: ToolKind, diameter_mm: f64) -> ToolShape {
    ToolShape {
        kind,
        diameter_mm,
        source: ToolSource::Registers,
        ..ToolShape::assumed(number)
    }
}

/// A library of these tools.
pub fn library(tools: &[ToolShape]) -> ToolLibrary {
    let mut l = ToolLibrary::default();
    for t in tools {
        l.insert(t.clone());
    }
    l
}

/// Runs `program` under `dialect` on its built-in machine.
pub fn run_with(
    program: &str,
    dialect: &str,
    tools: &ToolLibrary,
    stock: &str,
    resolution: Option<f64>,
    table_z_mm: Option<f64>,
) -> Finished {
    let d = Dialect::by_name(dialect).unwrap();
    let machine = d.machine();
    let lathe = d.diameter.lathe;
    let options = SimOptions {
        stock: StockSpec::parse(stock).unwrap(),
        stock_origin: StockOrigin::Option,
        resolution_mm: resolution,
        lathe,
        workers: 2,
        replay: None,
    };
    let mut sim = Simulation::new(&machine, tools, table_z_mm, options).unwrap();
    Interpreter::new(&machine, &d, Options::default()).run_str(program, &mut sim);
    sim.finish_run().unwrap()
}

/// A mill program (fanuc dialect) at 0.1 mm.
pub fn mill(program: &str, tools: &[ToolShape], stock: &str) -> Finished {
    run_with(program, "fanuc", &library(tools), stock, Some(0.1), None)
}

/// Asserts `got` is within `rel` of `want`.
#[track_caller]
pub fn close(got: f64, want: f64, rel: f64) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "got {got:.4}, want {want:.4} (off by {:.3} %)",
        100.0 * (got - want) / want
    );
}
