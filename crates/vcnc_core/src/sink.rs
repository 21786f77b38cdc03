//! Where events go: the [`Sink`] trait and two small sinks.
//!
//! The interpreter gathers the events of the blocks that succeeded and
//! hands them over in order, a thousand or so at a time and the rest when
//! the run ends, through [`Sink::take_events`]. By default that calls
//! [`Sink::event`] once per event with a borrowed event, so a sink that
//! only counts or formats never clones, and one that keeps them (the CLI's
//! second-core hand-over) moves them. A sink that wants no more events
//! (its reader went away: `vcnc run | head`) says so through
//! [`Sink::is_done`], which the interpreter asks after every block, and
//! the run stops at the first block after the batch that made it done (a
//! sink on another thread may say so a few batches late);
//! [`Sink::stop_after_line`] stops it after a given line of the main
//! program, so that a caller can read the state there.
//! [`Sink::finish`] is called once after the last event, so buffered
//! writers flush and report their errors.
//! Output formats live in `vcnc_output`; the CLI wires them up.

use crate::events::Event;

/// Receives events in program order.
pub trait Sink {
    /// One event.
    fn event(&mut self, event: &Event);

    /// Events of one or more whole blocks, in order, handed over by value:
    /// the interpreter calls this (not [`event`](Self::event)) and `events`
    /// is empty afterwards (it may hold another buffer, of any
    /// capacity). A sink that keeps events moves them instead of
    /// cloning each; by default each goes to [`event`](Self::event).
    fn take_events(&mut self, events: &mut Vec<Event>) {
        for e in events.iter() {
            self.event(e);
        }
        events.clear();
    }

    /// Whether the sink wants no further events; the interpreter stops the
    /// run after the current block when it does.
    fn is_done(&self) -> bool {
        false
    }

    /// Whether the run should stop right after the block that just ran on
    /// `line` (1-based) of the main program's text, to read the
    /// interpreter's state there (the language server's hover shows the
    /// modal state and the work position at the end of a block). Asked
    /// after every block of the main program's text; by default never,
    /// which the compiler folds away from the run loop of every other sink.
    fn stop_after_line(&mut self, _line: u64) -> bool {
        false
    }

    /// The run is over: flush what is buffered.
    fn finish(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Drops every event (benchmarks).
#[derive(Debug, Default)]
pub struct NullSink;

impl Sink for NullSink {
    fn event(&mut self, _: &Event) {}
}

/// Keeps every event (tests, small programs).
#[derive(Debug, Default)]
pub struct VecSink(pub Vec<Event>);

impl Sink for VecSink {
    fn event(&mut self, event: &Event) {
        self.0.push(event.clone());
    }
}

impl<S: Sink + ?Sized> Sink for &mut S {
    fn event(&mut self, event: &Event) {
        (**self).event(event);
    }
    fn take_events(&mut self, events: &mut Vec<Event>) {
        (**self).take_events(events);
    }
    fn is_done(&self) -> bool {
        (**self).is_done()
    }
    fn stop_after_line(&mut self, line: u64) -> bool {
        (**self).stop_after_line(line)
    }
    fn finish(&mut self) -> std::io::Result<()> {
        (**self).finish()
    }
}
