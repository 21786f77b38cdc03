//! One-shot (group 00) codes that take the block's axis words: G04 dwell,
//! G10/G52/G92 offsets (in `coords.rs`), G28/G29/G30 reference returns, G53
//! machine-coordinate moves and G31 skip.
//!
//! ```text
//!   G28 X Y:  start ──rapid──▶ intermediate (program coords) ──rapid──▶ reference 1
//!   G29 X Y:  here  ──rapid──▶ that intermediate ──rapid──▶ commanded point
//! ```
//!
//! Only the named axes move, as in Fanuc 0i. The intermediate point is kept
//! per axis in program coordinates, so G29 after a change of work system
//! passes through the same program point in the new system.

use crate::alarms;
use crate::convert::whole;
use crate::dialect::GOp;
use crate::events::{Event, Pos};
use crate::interpreter::Interpreter;
use crate::sink::Sink;
use crate::words::Words;
use vcnc_syntax::{Diagnostic, Span};

impl Interpreter<'_> {
    /// Step 6/7: the block's axis-taking one-shot code.
    pub(crate) fn one_shot<S: Sink>(
        &mut self,
        op: GOp,
        cmd: Span,
        w: &Words<'_>,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        match op {
            GOp::Dwell => self.dwell(w, sink),
            GOp::SetData => self.set_work_offset(w, cmd),
            GOp::PresetOrClamp => self.preset(w, cmd),
            GOp::LocalSystem => self.local_system(w, cmd),
            GOp::RefReturn => self.reference_return(w, cmd, 1, sink),
            GOp::RefReturnN => {
                let n = match w.get(b'P') {
                    Some(p) => whole(&p, b'P', 1.0, 4.0, "P is a reference point number")?,
                    None => 2,
                };
                self.reference_return(w, cmd, n as usize, sink)
            }
            GOp::RefFrom => self.return_from_reference(w, cmd, sink),
            GOp::MachineCoords => self.machine_move(w, cmd, sink),
            GOp::Skip => self.skip(w, cmd, sink),
            GOp::DwellSeconds => self.dwell_seconds(w, sink),
            GOp::HighSpeed => self.high_speed(w, cmd, sink),
            GOp::FeedUp => self.feed_step(1, cmd),
            GOp::FeedDown => self.feed_step(-1, cmd),
            GOp::OverrideCancel => {
                self.set_magnification(100.0);
                Ok(())
            }
            GOp::OverrideSet => self.magnification(w, cmd),
            GOp::RefXThenZ => self.reference_x_then_z(w, cmd, sink),
            GOp::ProgramZero => self.program_zero(w, cmd, sink),
            GOp::StartPoint => {
                let to = self.state.start_pos;
                self.rapid_to(to, w, cmd, sink)
            }
            GOp::CylinderCycle => self.cylinder_cycle(w, cmd, sink),
            GOp::ThreadCycle => self.thread_cycle(w, cmd, sink),
            _ => Ok(()),
        }
    }

    /// G04: P whole milliseconds, or X seconds (milliseconds without a point).
    fn dwell<S: Sink>(&mut self, w: &Words<'_>, sink: &mut S) -> Result<(), Diagnostic> {
        let seconds = match (w.get(b'P'), w.get(b'X')) {
            (Some(_), Some(x)) => return Err(alarms::word_not_allowed(x.span, b'X')),
            (Some(p), None) => {
                f64::from(whole(
                    &p,
                    b'P',
                    0.0,
                    99_999_999.0,
                    "G04 P is whole milliseconds (use X for seconds)",
                )?) / 1000.0
            }
            (None, Some(x)) if x.value < 0.0 => {
                return Err(alarms::value_out_of_range(
                    x.span,
                    b'X',
                    x.value,
                    "a dwell is not negative",
                ));
            }
            (None, Some(x)) => self.seconds(&x),
            (None, None) => 0.0,
        };
        // Manual 1.2.5: 0.001 to 9999.999 s (0 is the exact-stop check).
        if seconds > 9_999.999 {
            let word = w.get(b'X').or(w.get(b'P')).unwrap_or_default();
            return Err(alarms::value_out_of_range(
                word.span,
                word.addr.0,
                word.value,
                "a dwell is at most 9999.999 s",
            ));
        }
        self.emit(sink, |loc| Event::Dwell { loc, seconds });
        Ok(())
    }

    /// Syntec G05 P10000 / P1–P5 (on) and P0 (off), manual 1.2.6: recorded
    /// for the planner; the path itself is unchanged here.
    fn high_speed<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G05", "P (0 off, 1-5 or 10000 on)"))?;
        let n = whole(&p, b'P', 0.0, 10_000.0, "G05 P is 0, 1-5 or 10000")?;
        if !matches!(n, 0..=5 | 10_000) {
            return Err(alarms::value_out_of_range(
                p.span,
                b'P',
                p.value,
                "G05 P is 0, 1-5 or 10000",
            ));
        }
        self.emit(sink, |loc| Event::HighSpeed {
            loc,
            on: n != 0,
            p: n,
        });
        Ok(())
    }

    /// Machine position with the named axes at program coordinates `prog`.
    fn with_program_coords(&self, base: Pos, named: u32, prog: &[Option<f64>]) -> Pos {
        let mut p = base;
        for i in 0..self.machine.axes.len() {
            if let Some(v) = prog
                .get(i)
                .copied()
                .flatten()
                .filter(|_| named & (1 << i) != 0)
            {
                p.set(i, v + self.state.origin.get(i));
            }
        }
        p
    }

    /// G28 (n = 1) and G30 Pn.
    fn reference_return<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        n: usize,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let (mid, named) = self.target(w, self.state.modal.incremental);
        if named == 0 {
            return Err(alarms::needs_axes(cmd, "a reference return"));
        }
        let reference = self.machine.reference.get(n - 1).copied().flatten();
        let reference = reference
            .ok_or_else(|| alarms::no_reference(w.get(b'P').map_or(cmd, |p| p.span), n))?;
        let mut end = mid;
        for i in 0..self.machine.axes.len() {
            if named & (1 << i) != 0 {
                end.set(i, reference.get(i));
            }
        }
        for i in 0..self.machine.axes.len() {
            if named & (1 << i) != 0 {
                self.state.intermediate[i] = Some(mid.get(i) - self.state.origin.get(i));
            }
        }
        // Both legs move like G00 (dog-legs with parameter 411 = 1); the
        // block is all or nothing, so a second leg that alarms drops the first.
        self.rapid_to(mid, w, cmd, sink)?;
        self.rapid_to(end, w, cmd, sink)?;
        Ok(())
    }

    /// G29: back through the intermediate point to the commanded point.
    fn return_from_reference<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let mut named = 0u32;
        let mut target = self.state.pos;
        for (i, axis) in self.machine.axes.iter().enumerate() {
            let Some(word) = w.get(axis.letter) else {
                continue;
            };
            let mid = self.state.intermediate[i]
                .ok_or_else(|| alarms::g29_without_g28(cmd, axis.letter))?;
            let v = self.axis_value(i, &word);
            let prog = if self.state.modal.incremental {
                mid + v
            } else {
                v
            };
            target.set(i, prog + self.state.origin.get(i));
            named |= 1 << i;
        }
        if named == 0 {
            return Err(alarms::needs_axes(cmd, "G29"));
        }
        let mid = self.with_program_coords(self.state.pos, named, &self.state.intermediate);
        self.rapid_to(mid, w, cmd, sink)?;
        self.rapid_to(target, w, cmd, sink)?;
        Ok(())
    }

    /// G53: a rapid to machine coordinates (absolute only).
    fn machine_move<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        if self.state.modal.incremental {
            return Err(alarms::g53_incremental(cmd));
        }
        let mut to = self.state.pos;
        let mut named = 0;
        for (i, axis) in self.machine.axes.iter().enumerate() {
            if let Some(word) = w.get(axis.letter) {
                to.set(i, self.axis_value(i, &word));
                named |= 1 << i;
            }
        }
        if named == 0 {
            return Err(alarms::needs_axes(cmd, "G53"));
        }
        self.rapid_to(to, w, cmd, sink)
    }
}
