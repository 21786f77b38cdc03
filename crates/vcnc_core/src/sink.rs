//! Where events go: the [`Sink`] trait and two small sinks.
//!
//! The interpreter calls [`Sink::event`] once per event, in order, with a
//! borrowed event, so a sink that only counts or formats never clones. A
//! sink that wants no more events (its reader went away: `vcnc run | head`)
//! says so through [`Sink::is_done`], which the interpreter asks after every
//! block, and the run stops at once. [`Sink::finish`] is called once after
//! the last event, so buffered writers flush and report their errors.
//! Output formats live in `vcnc_output`; the CLI wires them up.

use crate::events::Event;

/// Receives events in program order.
pub trait Sink {
    /// One event.
    fn event(&mut self, event: &Event);

    /// Whether the sink wants no further events; the interpreter stops the
    /// run after the current block when it does.
    fn is_done(&self) -> bool {
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
    fn is_done(&self) -> bool {
        (**self).is_done()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        (**self).finish()
    }
}
