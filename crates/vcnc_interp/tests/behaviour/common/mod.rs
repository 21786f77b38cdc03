//! Helpers the integration tests share: programs by number and by name, a
//! run that reads variables back after it ends, a plain run of a program
//! text, and the looks at its events and alarm the tests assert on.

#![allow(dead_code)] // each test file uses a part of it

use std::collections::HashMap;
use std::io;
use vcnc_interp::{
    Dialect, Event, Interpreter, Machine, Options, Outcome, Pos, ProgramStore, VecSink,
};
use vcnc_syntax::{Code, Diagnostic, MemSource, TextSource};

/// Programs by number (`O0010`) and by name (`G0200`, `M0123`).
#[derive(Default)]
pub struct Store {
    numbered: HashMap<u32, String>,
    named: HashMap<String, String>,
}

impl Store {
    pub fn with(mut self, n: u32, text: &str) -> Store {
        self.numbered.insert(n, text.to_string());
        self
    }
    pub fn named(mut self, name: &str, text: &str) -> Store {
        self.named.insert(name.to_string(), text.to_string());
        self
    }
}

impl ProgramStore for Store {
    fn open(&mut self, n: u32) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let text = self.numbered.get(&n)?.clone();
        Some(Ok((
            Box::new(MemSource(text.into_bytes())),
            format!("O{n:04}.nc"),
        )))
    }
    fn open_named(&mut self, name: &str) -> Option<io::Result<(Box<dyn TextSource>, String)>> {
        let text = self.named.get(name)?.clone();
        Some(Ok((
            Box::new(MemSource(text.into_bytes())),
            name.to_string(),
        )))
    }
}

/// What a run did, and the variables `names` held after it.
pub struct Ran {
    pub outcome: Outcome,
    pub events: Vec<Event>,
    pub values: Vec<Option<f64>>,
}

/// Runs `program` under `dialect` on `machine`, its subprograms from `store`.
pub fn run_on(
    machine: &Machine,
    dialect: &str,
    program: &str,
    store: Store,
    names: &[&str],
) -> Ran {
    let dialect = Dialect::by_name(dialect).unwrap();
    let mut sink = VecSink::default();
    let mut store = store;
    let mut interp = Interpreter::new(machine, &dialect, Options::default());
    let outcome = interp.run(
        Box::new(MemSource(program.as_bytes().to_vec())),
        &mut store,
        &mut sink,
    );
    let values = names.iter().map(|n| interp.variable(n)).collect();
    Ran {
        outcome,
        events: sink.0,
        values,
    }
}

/// [`run_on`] the built-in mill.
pub fn run(dialect: &str, program: &str, store: Store, names: &[&str]) -> Ran {
    run_on(&Machine::default_mill(), dialect, program, store, names)
}

/// Asserts the run ended without an alarm.
pub fn ended(r: &Ran) {
    assert!(
        matches!(r.outcome, Outcome::Ended(_)),
        "{:?}\n{:?}",
        r.outcome,
        r.events
    );
}

/// Runs `program` under `dialect` on the built-in mill: its events and how
/// it ended.
pub fn run_str(dialect: &Dialect, program: &str) -> (Vec<Event>, Outcome) {
    run_str_on(&Machine::default_mill(), dialect, program)
}

/// Runs `program` under `dialect` on `machine`: its events and how it
/// ended.
pub fn run_str_on(machine: &Machine, dialect: &Dialect, program: &str) -> (Vec<Event>, Outcome) {
    let mut sink = VecSink::default();
    let out = Interpreter::new(machine, dialect, Options::default()).run_str(program, &mut sink);
    (sink.0, out)
}

/// Runs `program` under `dialect` on the dialect's own built-in machine
/// (a lathe dialect's lathe): its events and how it ended.
pub fn run_on_its_machine(dialect: &Dialect, program: &str) -> (Vec<Event>, Outcome) {
    run_str_on(&dialect.machine(), dialect, program)
}

/// The built-in mill with tools in its offset memory
/// (`tests/fixtures/machines/mill_tools.toml`): D1 = D2 = 5 mm, D3 = 3 mm,
/// every H 0. The built-in mill's own memory is empty.
pub fn mill_with_tools() -> Machine {
    Machine::from_toml(include_str!(
        "../../../../../tests/fixtures/machines/mill_tools.toml"
    ))
    .unwrap()
}

/// The alarm of a run, checked to be the last event (no motion after it).
pub fn alarm(r: &Ran) -> &Diagnostic {
    let Outcome::Alarm(d) = &r.outcome else {
        panic!("no alarm: {:?}\n{:?}", r.outcome, r.events);
    };
    assert!(matches!(r.events.last(), Some(Event::Alarm(a)) if a == d));
    d
}

/// Where an alarm points: (code, line, column).
pub fn at(d: &Diagnostic) -> (Code, u64, u32) {
    (d.code, d.line, d.column)
}

/// The alarm of a run and where it points.
pub fn alarm_of(r: &Ran) -> (Code, u64, u32) {
    at(alarm(r))
}

/// End points of the motion events, X only, to the micrometre.
pub fn xs(events: &[Event]) -> Vec<f64> {
    events
        .iter()
        .filter_map(Event::motion_end)
        .map(|p| (p.get(0) * 1e6).round() / 1e6)
        .collect()
}

/// The end points of the rapids, feeds and arcs of line `line`.
pub fn ends(events: &[Event], line: u64) -> Vec<Pos> {
    events
        .iter()
        .filter(|e| e.loc().is_some_and(|l| l.line == line))
        .filter_map(|e| match e {
            Event::Feed { to, .. } | Event::Rapid { to, .. } | Event::Arc { to, .. } => Some(*to),
            _ => None,
        })
        .collect()
}

/// Whether `p` is (x, y, z) within a nanometre.
pub fn near(p: Pos, x: f64, y: f64, z: f64) -> bool {
    (p.0[0] - x).abs() < 1e-6 && (p.0[1] - y).abs() < 1e-6 && (p.0[2] - z).abs() < 1e-6
}
