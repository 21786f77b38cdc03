//! `Sink::stop_after_line`: a sink stops the run right after a line of the
//! main program's text and the state there is read (the language server's
//! hover). Expected states are worked out from the programs by hand.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use vcnc_interp::{Dialect, Event, Interpreter, Machine, Options, Outcome, Sink, State};

/// Stops after `line`; counts the lines it was asked about.
struct StopAt {
    line: u64,
    asked: Vec<u64>,
    /// The line of every event with one.
    event_lines: Vec<u64>,
}

impl Sink for StopAt {
    fn event(&mut self, e: &Event) {
        self.event_lines.extend(e.loc().map(|l| l.line));
    }
    fn stop_after_line(&mut self, line: u64) -> bool {
        self.asked.push(line);
        line == self.line
    }
}

fn state_after(program: &str, line: u64) -> (Outcome, State, StopAt) {
    let machine = Machine::default_mill();
    let dialect = Dialect::fanuc();
    let mut sink = StopAt {
        line,
        asked: Vec::new(),
        event_lines: Vec::new(),
    };
    let mut interp = Interpreter::new(&machine, &dialect, Options::default());
    let out = interp.run_str(program, &mut sink);
    (out, *interp.state(), sink)
}

#[test]
fn the_run_stops_after_the_asked_line_with_its_state() {
    let program = "G90 G00 X1. Y2.\nG91 G01 X3. F200.\nG90 X9.\nM30\n";
    let (out, s, sink) = state_after(program, 2);
    assert_eq!(out, Outcome::Stopped);
    // After line 2: incremental, X 1 + 3, Y 2, F200; line 3 never ran.
    assert!(s.modal.incremental);
    assert_eq!(s.program_pos().get(0), 4.0);
    assert_eq!(s.program_pos().get(1), 2.0);
    assert_eq!(s.feed, 200.0);
    assert_eq!(sink.asked, vec![1, 2]);
    // The rapid and the feed (and its warning, which is located by its
    // diagnostic); not line 3's feed.
    assert_eq!(sink.event_lines, vec![1, 2]);
}

#[test]
fn a_subprogram_in_the_same_text_is_asked_about_its_own_lines() {
    // M98 runs O100 (lines 4-6) from line 1; line 5 ends with X7.
    let program = "M98 P100\nG00 X1.\nM30\nO100\nG00 X7.\nM99\n";
    let (out, s, sink) = state_after(program, 5);
    assert_eq!(out, Outcome::Stopped);
    assert_eq!(s.program_pos().get(0), 7.0);
    assert_eq!(sink.asked, vec![1, 5]);
}

#[test]
fn a_line_that_never_runs_lets_the_program_end() {
    let (out, _, sink) = state_after("G00 X1.\nM30\nG00 X5.\n", 3);
    assert!(matches!(out, Outcome::Ended(_)));
    assert_eq!(sink.asked, vec![1, 2]);
}
