//! Property tests for the lathe dialect: random programs made of the lathe
//! document's tokens (G20/G24/G25/G26 flow, U/W, CR=, IX/IZ, G81, G331 …)
//! never panic or hang, always end with `end` or `alarm`, and never leave
//! the machine's travel; alarms have a line and a column.
#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use std::sync::mpsc;
use std::time::Duration;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, VecSink};

/// The default lathe with small runaway limits, so loops alarm quickly.
fn small_lathe() -> Machine {
    let d = Dialect::lathe();
    let text = d
        .default_machine
        .replace("max_jumps = 1000000", "max_jumps = 40")
        .replace("max_executed_blocks = 5000000", "max_executed_blocks = 400")
        .replace("max_call_depth = 10", "max_call_depth = 4");
    Machine::from_toml(&text).unwrap()
}

const TOKENS: &[&str] = &[
    "G00", "G01", "G02", "G03", "G04", "G05", "G07", "G08", "G09", "G20", "G22", "G23", "G24",
    "G25", "G26", "G30", "G31", "G32", "G33", "G53", "G500", "G54", "G60", "G64", "G70", "G71",
    "G74", "G75", "G76", "G81", "G331", "G90", "G91", "G92", "G94", "G95", "G16", "X10", "X-5.5",
    "X200", "X0", "Z-30", "Z5.", "Z 100", "U4", "U-2.5", "W-10", "W3", "I-3", "I2", "K-1", "K1",
    "K2", "R15", "R-4", "R0", "CR=5", "CR=0.1", "D8", "D=6", "IX50", "IZ60", "F100", "F0", "F2",
    "L10", "L200", "L7", "Q3", "Q0", "P5", "P0", "M03", "M05", "M99", "M98", "M30", "S1000", "T1",
    "N10", "N200", "N7", "(c)", ";", "\n", "\n", "\n", "%", "/", "1e400", "NaN",
];

fn program() -> impl Strategy<Value = String> {
    proptest::collection::vec(proptest::sample::select(TOKENS), 0..120).prop_map(|t| t.join(" "))
}

/// Runs in a thread so that a hang fails the test instead of stalling it.
fn run(program: String) -> Vec<Event> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let machine = small_lathe();
        let dialect = Dialect::lathe();
        let mut sink = VecSink::default();
        Interpreter::new(&machine, &dialect, Options::default()).run_str(&program, &mut sink);
        let _ = tx.send(sink.0);
    });
    rx.recv_timeout(Duration::from_secs(20))
        .expect("the run finished (no hang, no panic)")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    #[test]
    fn lathe_token_soup_ends_cleanly(p in program()) {
        let machine = small_lathe();
        let events = run(p.clone());
        let last = events.last().expect("at least an end or an alarm");
        match last {
            Event::End { .. } => {}
            Event::Alarm(d) => prop_assert!(d.line >= 1 && d.column >= 1, "alarm without a place: {d:?}\n{p}"),
            other => prop_assert!(false, "last event is {other:?}\n{p}"),
        }
        let ends = events.iter().filter(|e| matches!(e, Event::End { .. } | Event::Alarm(_))).count();
        prop_assert_eq!(ends, 1, "exactly one end or alarm\n{}", p);
        for e in &events {
            let to = match e {
                Event::Rapid { to, .. } | Event::Feed { to, .. } | Event::Arc { to, .. } | Event::Thread { to, .. } => to,
                _ => continue,
            };
            for (i, a) in machine.axes.iter().enumerate() {
                let v = to.get(i);
                prop_assert!(v.is_finite() && v >= a.min_mm - 1e-6 && v <= a.max_mm + 1e-6, "{e:?} leaves travel\n{p}");
            }
        }
    }
}
