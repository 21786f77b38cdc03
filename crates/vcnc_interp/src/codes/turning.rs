//! Lathe one-shot codes of seed 003 that are not motion cycles: G04 with F
//! or K seconds, G08/G09 feed steps, G30/G31 feed magnification, G74
//! reference return X then Z, G75 return to program zero.
//!
//! The feed a cutting move uses is the programmed F times
//! `(1 + 0.1 · steps) · magnification / 100`: each G08 adds 10 % and each
//! G09 takes 10 % away (the document: "to increase 20 % write two"), within
//! 10 %..200 %; G31 F sets a magnification in percent (1..200) and G30
//! cancels it, leaving the G08/G09 steps alone.

use crate::alarms;
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::words::Words;
use vcnc_core::events::Event;
use vcnc_syntax::{Diagnostic, Span};

/// G04 limits of the lathe document, seconds.
const DWELL_MIN_S: f64 = 0.01;
const DWELL_MAX_S: f64 = 300.0;

impl<'a> Machining<'_, 'a> {
    /// G04 F or K: seconds, 0.01 to 300.
    pub(crate) fn dwell_seconds(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let word = match (w.get(b'F'), w.get(b'K')) {
            (Some(_), Some(k)) => return Err(alarms::word_not_allowed(k.span, b'K')),
            (Some(f), None) => f,
            (None, Some(k)) => k,
            (None, None) => return Err(alarms::needs_word(w.first, "G04", "F or K (seconds)")),
        };
        let seconds = word.value;
        if !(DWELL_MIN_S..=DWELL_MAX_S).contains(&seconds) {
            return Err(alarms::value_out_of_range(
                word.span,
                word.addr.0,
                seconds,
                "a dwell is 0.01 to 300 s",
            ));
        }
        self.emit(|loc| Event::Dwell { loc, seconds });
        Ok(())
    }

    /// G08 (+1) or G09 (−1): a 10 % feed step.
    pub(crate) fn feed_step(&mut self, step: i32, cmd: Span) -> Result<(), Diagnostic> {
        let steps = self.state.feed_steps + step;
        if !(-9..=10).contains(&steps) {
            let pct = 100 + 10 * steps;
            return Err(alarms::feed_steps_out_of_range(cmd, pct));
        }
        self.state.feed_steps = steps;
        self.refresh_feed_factor();
        Ok(())
    }

    /// G31 F: feed magnification in percent.
    pub(crate) fn magnification(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let f = w.get(b'F').ok_or_else(|| {
            alarms::needs_word(cmd, "G31", "F (the feed magnification in percent)")
        })?;
        if !(f.value > 0.0 && f.value <= 200.0) {
            return Err(alarms::value_out_of_range(
                f.span,
                b'F',
                f.value,
                "a magnification is 1 to 200 %",
            ));
        }
        self.set_magnification(f.value);
        Ok(())
    }

    pub(crate) fn set_magnification(&mut self, pct: f64) {
        self.state.magnification_pct = pct;
        self.refresh_feed_factor();
    }

    fn refresh_feed_factor(&mut self) {
        let s = &mut self.state;
        s.feed_factor = (1.0 + 0.1 * f64::from(s.feed_steps)) * s.magnification_pct / 100.0;
    }

    /// G74: the named axes to reference point 1, X first, then Z.
    pub(crate) fn reference_x_then_z(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let reference =
            self.cfg.machine.reference[0].ok_or_else(|| alarms::no_reference(cmd, 1))?;
        let mut any = false;
        // The document: "return to zero in order of X, Z".
        let mut order: Vec<(usize, crate::dialect::AxisWord)> =
            self.cfg.axis_words.iter().copied().enumerate().collect();
        order.sort_by_key(|(_, a)| match a.letter {
            b'X' => 0,
            b'Z' => 1,
            _ => 2,
        });
        for (i, a) in order {
            if w.get(a.letter).is_none() && a.inc.and_then(|l| w.get(l)).is_none() {
                continue;
            }
            let mut to = self.settled_tool_pos()?;
            to.set(i, reference.get(i));
            self.straight(MoveKind::Rapid, Target::Machine(to), w, cmd)?;
            any = true;
        }
        if !any {
            return Err(alarms::needs_axes(cmd, "G74"));
        }
        Ok(())
    }

    /// G75: the named axes to program zero, together.
    pub(crate) fn program_zero(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let mut to = self.state.prog;
        let mut any = false;
        for (i, a) in self.cfg.axis_words.iter().enumerate() {
            if w.get(a.letter).is_some() || a.inc.and_then(|l| w.get(l)).is_some() {
                to.set(i, 0.0);
                any = true;
            }
        }
        if !any {
            return Err(alarms::needs_axes(cmd, "G75"));
        }
        self.straight(MoveKind::Rapid, Target::Program(to), w, cmd)
    }
}
