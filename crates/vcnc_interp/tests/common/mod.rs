//! Helpers the macro test files share: programs by number and by name, and
//! a run that reads variables back after it ends.

#![allow(dead_code)] // each test file uses a part of it

use std::collections::HashMap;
use std::io;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, ProgramStore, VecSink};
use vcnc_syntax::{MemSource, TextSource};

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
