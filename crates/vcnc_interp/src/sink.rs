//! Where events go: the [`Sink`] trait and two small sinks.
//!
//! The interpreter calls [`Sink::event`] once per event, in order, with a
//! borrowed event, so a sink that only counts or formats never clones. Output
//! formats live in `vcnc_output`; the CLI wires them up.

use crate::events::Event;

/// Receives events in program order.
pub trait Sink {
    /// One event.
    fn event(&mut self, event: &Event);
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
}
