//! Syntec G05.1 path smoothing (manual 1.2.7): `G05.1 Q1 E…` lets the
//! controller turn the following G01 chains into smooth curves that stay
//! within E of the programmed points; `G05.1 Q0` ends it. The interpreter
//! does not move the path: it tells the planner, through `smoothing`
//! events, which G01 moves may be smoothed and by how much.
//!
//! The manual's rules, in the order they are applied:
//!
//! ```text
//!  G05.1 without Q, or Q1 without E   ineffective: nothing changes (1)
//!  G05.1 Q1 E under G61 or G63        alarm E327 (condition 1)
//!  G61 / G63 while on                 smoothing stops; it resumes when the
//!                                     mode leaves G61/G63 (condition 2)
//!  the G01 right after G43/G44/G49 or a work system change (G54…)
//!                                     is not smoothed; the next one is
//!                                     again (condition 3)
//!  only G01 is smoothed               (description 3)
//! ```
//!
//! What a G01 gets is decided when it is executed; a `smoothing` event is
//! sent before it whenever that differs from what the last G01 got (and at
//! `G05.1 Q0` when it was on), so the planner knows, move by move.
//!
//! Fanuc (and Haas, which reads Fanuc's codes) has one look-ahead
//! smoothing mode that two codes switch: G05.1 Q1 (AI contour control) and
//! G08 P1 (AI look-ahead control) start it, G05.1 Q0 and G08 P0 end it,
//! whichever started it. There `G05.1 Q1` without E is not ineffective: it
//! starts the mode as `G08 P1` does, with the machine's corner tolerance.

use crate::alarms;
use crate::block::words::Words;
use crate::dialect::{GOp, Group, PaceOp};
use crate::events::{Event, PathMode};
use crate::interpreter::Interpreter;
use vcnc_syntax::{Diagnostic, Span};

impl Interpreter<'_> {
    /// G05.1 Q1 E / Q0.
    pub(crate) fn path_smoothing(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let Some(q) = w.get(b'Q') else {
            return Ok(()); // ineffective (rule 1)
        };
        if q.value != 0.0 && q.value != 1.0 {
            return Err(alarms::value_out_of_range(
                q.span,
                b'Q',
                q.value,
                "G05.1 Q is 1 (start) or 0 (stop)",
            ));
        }
        if q.value == 0.0 {
            self.smoothing_off();
            return Ok(());
        }
        let Some(e) = w.get(b'E') else {
            if self.has_look_ahead_mode() {
                // Fanuc's AI contour control: G08 P1's mode.
                self.look_ahead_on();
            }
            return Ok(()); // ineffective (rule 1)
        };
        if matches!(
            self.state.modal.path,
            PathMode::ExactStop | PathMode::Tapping
        ) {
            return Err(alarms::smoothing_in_exact_stop(cmd));
        }
        let tol = e.value * self.unit_mm();
        if !(tol.is_finite() && tol > 0.0 && tol <= 10.0) {
            return Err(alarms::value_out_of_range(
                e.span,
                b'E',
                e.value,
                "G05.1 E is the largest path error, more than 0 and at most 10 mm",
            ));
        }
        self.state.smoothing.tolerance_mm = tol;
        Ok(())
    }

    /// Whether this dialect's G05.1 Q1 and G08 P1 are one mode (Fanuc,
    /// Haas): it has G08 look-ahead.
    fn has_look_ahead_mode(&self) -> bool {
        self.cfg
            .dialect
            .g(8.0)
            .is_some_and(|d| d.op == GOp::Pace(PaceOp::LookAhead))
    }

    /// G08 P1, Fanuc's G05.1 Q1 without E: smoothing on with the
    /// machine's corner tolerance, reported at once.
    pub(crate) fn look_ahead_on(&mut self) {
        let tol = self.cfg.machine.motion.corner_tolerance_mm;
        self.state.smoothing.tolerance_mm = tol;
        self.state.smoothing.skip_next = false;
        if self.state.smoothing.reported_mm != tol {
            self.report_smoothing(tol);
        }
    }

    /// G05.1 Q0, G08 P0: the mode ends, whichever code started it; `off`
    /// when the planner was last told `on`.
    pub(crate) fn smoothing_off(&mut self) {
        self.state.smoothing.tolerance_mm = 0.0;
        self.state.smoothing.skip_next = false;
        if self.state.smoothing.reported_mm > 0.0 {
            self.report_smoothing(0.0);
        }
    }

    /// Step 6: a tool length or work system code exempts the next G01.
    pub(crate) fn smoothing_frame_change(&mut self, w: &Words<'_>) {
        if self.state.smoothing.tolerance_mm > 0.0
            && (w.group(Group::ToolLength).is_some() || w.group(Group::Wcs).is_some())
        {
            self.state.smoothing.skip_next = true;
        }
    }

    /// Before a G01: what smoothing it gets, reported when it changes.
    #[inline]
    pub(crate) fn smoothing_before_linear(&mut self) {
        let s = self.state.smoothing;
        let suspended = matches!(
            self.state.modal.path,
            PathMode::ExactStop | PathMode::Tapping
        );
        let now = if s.tolerance_mm > 0.0 && !suspended && !s.skip_next {
            s.tolerance_mm
        } else {
            0.0
        };
        self.state.smoothing.skip_next = false;
        if now != s.reported_mm {
            self.report_smoothing(now);
        }
    }

    #[inline(never)]
    fn report_smoothing(&mut self, tolerance_mm: f64) {
        self.state.smoothing.reported_mm = tolerance_mm;
        self.emit(|loc| Event::Smoothing {
            loc,
            on: tolerance_mm > 0.0,
            tolerance_mm,
        });
    }
}
