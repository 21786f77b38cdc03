//! Offsets that move the program origin without moving the machine:
//! G10 L2 (work offsets), G92 (shift, or S spindle clamp) and G52 (local).
//!
//! G92 and G52 values are absolute program coordinates whatever G90/G91
//! says (Fanuc 0i); G10 L2 adds to the offset under G91 (Syntec 1.2.10).
//! G92 cancels the local system of the axes it names (Fanuc 0i, "local
//! coordinate system"), so the preset position is what the axis then reads.

use crate::alarms;
use crate::convert::whole;
use crate::interpreter::Interpreter;
use crate::words::Words;
use vcnc_syntax::{Diagnostic, Span};

impl Interpreter<'_> {
    /// `(axis index, value in mm)` of each named axis.
    fn named_values(&self, w: &Words<'_>) -> Vec<(usize, f64)> {
        self.machine
            .axes
            .iter()
            .enumerate()
            .filter_map(|(i, a)| w.get(a.letter).map(|word| (i, self.axis_value(i, &word))))
            .collect()
    }

    /// G10 L2 Pn: sets work offset n (1 = G54 … 6 = G59).
    pub(crate) fn set_work_offset(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let l = w
            .get(b'L')
            .ok_or_else(|| alarms::needs_word(cmd, "G10", "L2 and P (the work offset number)"))?;
        whole(&l, b'L', 2.0, 2.0, "G10 L2 sets work offsets")?;
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::bad_offset_number(cmd, 0.0))?;
        if p.point || !(1.0..=6.0).contains(&p.value) {
            return Err(alarms::bad_offset_number(p.span, p.value));
        }
        let n = whole(&p, b'P', 1.0, 6.0, "P is a work offset number")? as usize - 1;
        let values = self.named_values(w);
        if values.is_empty() {
            return Err(alarms::needs_axes(cmd, "G10 L2"));
        }
        let incremental = self.state.modal.incremental;
        let offset = &mut self.state.offsets.work[n];
        for (i, v) in values {
            offset.set(i, if incremental { offset.get(i) + v } else { v });
        }
        self.state.refresh_origin();
        Ok(())
    }

    /// G92: preset the current position (axes), or clamp the spindle (S).
    pub(crate) fn preset(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let values = self.named_values(w);
        if let Some(s) = w.get(b'S') {
            if !values.is_empty() {
                return Err(alarms::g92_axes_and_s(s.span));
            }
            // The clamp itself was set with the spindle words (execute.rs).
            return Ok(());
        }
        if values.is_empty() {
            return Err(alarms::needs_axes(cmd, "G92"));
        }
        let wcs = self.state.modal.wcs;
        for (i, v) in values {
            let o = &mut self.state.offsets;
            o.local.set(i, 0.0);
            let work = o.work.get(wcs).map_or(0.0, |p| p.get(i));
            o.shift.set(i, self.state.pos.get(i) - work - v);
        }
        self.state.refresh_origin();
        Ok(())
    }

    /// G52: the local system's origin in the work system; zero cancels.
    pub(crate) fn local_system(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let values = self.named_values(w);
        if values.is_empty() {
            return Err(alarms::needs_axes(cmd, "G52"));
        }
        for (i, v) in values {
            self.state.offsets.local.set(i, v);
        }
        self.state.refresh_origin();
        Ok(())
    }
}
