//! Straight motion: G00 (interpolated or dog-leg, parameter 411), G01, G31
//! skip and G33 threads, and the soft over-travel check every move passes.
//!
//! Travel limits are checked on the whole swept path before the event is
//! emitted: a straight segment stays inside the limit box exactly when its
//! end points do (the box is convex), so checking its bounding box suffices;
//! arcs add their axis extremes (see `arc.rs`).

use crate::alarms;
use crate::dialect::GOp;
use crate::events::{Event, Feed, MAX_AXES, Pos};
use crate::interpreter::Interpreter;
use crate::sink::Sink;
use crate::state::Motion;
use crate::words::Words;
use vcnc_syntax::{Diagnostic, Span};

/// Slack on travel limits for rounding noise, mm.
const TRAVEL_EPS_MM: f64 = 1e-9;

impl Interpreter<'_> {
    /// Step 7 without a one-shot code: the modal motion, if the block moves.
    pub(crate) fn modal_motion<S: Sink>(
        &mut self,
        w: &Words<'_>,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let motion = self.state.modal.motion;
        let cmd = w
            .group(crate::dialect::Group::Motion)
            .map_or(w.first, |a| a.span);
        match motion {
            Motion::ArcCw | Motion::ArcCcw => self.arc(w, cmd, motion == Motion::ArcCw, sink),
            Motion::ThreePoint => self.three_point_arc(w, cmd, sink),
            _ if !w.any(self.axis_mask) => Ok(()),
            Motion::Rapid => {
                let (to, _) = self.target(w, self.state.modal.incremental);
                self.rapid_to(to, w, cmd, sink)
            }
            Motion::Linear => {
                let feed = self.feed(cmd)?;
                let (to, _) = self.target(w, self.state.modal.incremental);
                self.feed_to(to, feed, w, cmd, sink)
            }
            Motion::Thread | Motion::ThreadInch => self.thread(w, cmd, sink),
        }
    }

    /// A straight cutting move to `to`.
    pub(crate) fn feed_to<S: Sink>(
        &mut self,
        to: Pos,
        feed: Feed,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        self.check_segment(self.state.pos, to, w, cmd)?;
        let exact_stop = self.exact_stop(w);
        self.emit(sink, |loc| Event::Feed {
            loc,
            to,
            feed,
            exact_stop,
        });
        self.state.pos = to;
        Ok(())
    }

    /// Whether G09 is in the block.
    pub(crate) fn exact_stop(&self, w: &Words<'_>) -> bool {
        w.once(GOp::ExactStopOnce).is_some()
    }

    /// The current feed, or E301 when it is zero.
    pub(crate) fn feed(&self, cmd: Span) -> Result<Feed, Diagnostic> {
        let f = self.state.feed * self.unit_mm() * self.state.feed_factor;
        if f <= 0.0 {
            return Err(alarms::zero_feed(cmd));
        }
        Ok(if self.state.modal.per_rev {
            Feed::PerRev(f)
        } else {
            Feed::PerMin(f)
        })
    }

    /// A rapid to `to`: one event, or the dog-leg of parameter 411 = 1.
    pub(crate) fn rapid_to<S: Sink>(
        &mut self,
        to: Pos,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        self.check_segment(self.state.pos, to, w, cmd)?;
        let exact_stop = self.exact_stop(w);
        if self.machine.params.g00_mode == 1 {
            let (corners, count) = self.dog_leg(self.state.pos, to);
            for &corner in &corners[..count] {
                self.emit(sink, |loc| Event::Rapid {
                    loc,
                    to: corner,
                    exact_stop,
                });
            }
        } else {
            self.emit(sink, |loc| Event::Rapid {
                loc,
                to,
                exact_stop,
            });
        }
        self.state.pos = to;
        Ok(())
    }

    /// Corners of a rapid where each axis runs at its own rate: every axis
    /// starts together and stops when its own distance is covered.
    ///
    /// ```text
    ///   Y ▲        ┌── end         axis X (fast) and Y (slow) start together;
    ///     │      ╱                 after X arrives only Y moves on.
    ///     └──╱─────▶ X
    /// ```
    fn dog_leg(&self, from: Pos, to: Pos) -> ([Pos; MAX_AXES], usize) {
        let n = self.machine.axes.len().min(MAX_AXES);
        let mut times = [0.0f64; MAX_AXES];
        for (i, axis) in self.machine.axes.iter().enumerate().take(n) {
            times[i] = (to.get(i) - from.get(i)).abs() / axis.rapid_mm_per_min;
        }
        // Distinct arrival times, in order; no allocation on this path.
        let mut order = times;
        order[..n].sort_by(f64::total_cmp);
        let mut corners = [to; MAX_AXES];
        let mut count = 0;
        let mut last = 0.0;
        for &t in &order[..n] {
            if t <= last {
                continue;
            }
            last = t;
            let mut p = from;
            for (i, axis) in self.machine.axes.iter().enumerate().take(n) {
                let d = to.get(i) - from.get(i);
                let moved = (t * axis.rapid_mm_per_min).min(d.abs());
                p.set(
                    i,
                    if t >= times[i] {
                        to.get(i)
                    } else {
                        from.get(i) + moved.copysign(d)
                    },
                );
            }
            corners[count] = p;
            count += 1;
        }
        (corners, count.max(1))
    }

    /// G33: a straight move whose feed is locked to the spindle.
    fn thread<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let lead_mm = self
            .state
            .thread_lead_mm
            .filter(|l| *l > 0.0)
            .ok_or_else(|| alarms::thread_without_lead(cmd))?;
        let (to, _) = self.target(w, self.state.modal.incremental);
        self.check_segment(self.state.pos, to, w, cmd)?;
        self.emit(sink, |loc| Event::Thread { loc, to, lead_mm });
        self.state.pos = to;
        Ok(())
    }

    /// G31: moves like G01 until the skip signal of the machine file fires.
    pub(crate) fn skip<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let feed = self.feed(cmd)?;
        let (end, named) = self.target(w, self.state.modal.incremental);
        if named == 0 {
            return Err(alarms::needs_axes(cmd, "G31"));
        }
        self.check_segment(self.state.pos, end, w, cmd)?;
        let from = self.state.pos;
        let hit = self.skip_fraction(from, end);
        let to = match hit {
            Some(t) => lerp(from, end, t),
            None => end,
        };
        let triggered = hit.is_some();
        self.emit(sink, |loc| Event::Skip {
            loc,
            to,
            feed,
            triggered,
        });
        self.state.pos = to;
        self.state.skip_pos = Some(to);
        Ok(())
    }

    /// The earliest fraction of `from → to` at which a skip trigger fires.
    fn skip_fraction(&self, from: Pos, to: Pos) -> Option<f64> {
        self.machine
            .skip
            .iter()
            .filter_map(|s| {
                let (a, b) = (from.get(s.axis), to.get(s.axis));
                let crosses = (a < s.at_mm && b >= s.at_mm) || (a > s.at_mm && b <= s.at_mm);
                crosses.then(|| (s.at_mm - a) / (b - a))
            })
            .min_by(f64::total_cmp)
    }

    /// E501 unless the segment `from → to` stays inside the travel limits
    /// (the limit box is convex, so its end points decide).
    #[inline]
    pub(crate) fn check_segment(
        &self,
        from: Pos,
        to: Pos,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        for (i, axis) in self.machine.axes.iter().enumerate() {
            let (a, b) = (from.get(i), to.get(i));
            if a.min(b) < axis.min_mm - TRAVEL_EPS_MM || a.max(b) > axis.max_mm + TRAVEL_EPS_MM {
                return self
                    .check_box(from, to, w, cmd)
                    .and_then(|()| self.check_box(to, from, w, cmd));
            }
        }
        Ok(())
    }

    /// E501 unless the box `lo..hi` is inside the travel limits.
    pub(crate) fn check_box(
        &self,
        lo: Pos,
        hi: Pos,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        for (i, axis) in self.machine.axes.iter().enumerate() {
            let bad = if lo.get(i) < axis.min_mm - TRAVEL_EPS_MM {
                Some(lo.get(i))
            } else if hi.get(i) > axis.max_mm + TRAVEL_EPS_MM {
                Some(hi.get(i))
            } else {
                None
            };
            if let Some(v) = bad {
                let inc = self
                    .axis_words
                    .get(i)
                    .and_then(|a| a.inc)
                    .and_then(|l| w.get(l));
                let span = w.get(axis.letter).or(inc).map_or(cmd, |word| word.span);
                return Err(alarms::over_travel(
                    span,
                    axis.letter,
                    v,
                    axis.min_mm,
                    axis.max_mm,
                ));
            }
        }
        Ok(())
    }
}

fn lerp(a: Pos, b: Pos, t: f64) -> Pos {
    let mut p = a;
    for (i, v) in p.0.iter_mut().enumerate() {
        *v = a.0[i] + (b.0[i] - a.0[i]) * t;
    }
    p
}
