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
use crate::block::convert::Units;
use crate::dialect::Group;
use crate::state::Smoothing;
use crate::words::Words;
use vcnc_core::events::{Event, Loc, PathMode};
use vcnc_syntax::{Diagnostic, Span};

// The smoothing state decides; the interpreter only emits what it returns:
// each method that can change what the planner was told returns
// `Some(tolerance_mm)` (0: off) for a `smoothing` event, already noted as
// reported.
impl Smoothing {
    /// G05.1 Q1 E / Q0. `look_ahead` is the machine's corner tolerance
    /// where the dialect's G05.1 Q1 and G08 P1 are one mode (Fanuc, Haas:
    /// it has G08 look-ahead), `path` the path mode in force, and
    /// `mm_per_unit` the program's units.
    pub fn path_smoothing(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        (path, mm_per_unit, look_ahead): (PathMode, f64, Option<f64>),
    ) -> Result<Option<f64>, Diagnostic> {
        let Some(q) = w.get(b'Q') else {
            return Ok(None); // ineffective (rule 1)
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
            return Ok(self.off());
        }
        let Some(e) = w.get(b'E') else {
            // Fanuc's AI contour control: G08 P1's mode; elsewhere
            // ineffective (rule 1).
            return Ok(look_ahead.and_then(|tol| self.look_ahead_on(tol)));
        };
        if matches!(path, PathMode::ExactStop | PathMode::Tapping) {
            return Err(alarms::smoothing_in_exact_stop(cmd));
        }
        let tol = e.value * mm_per_unit;
        if !(tol.is_finite() && tol > 0.0 && tol <= 10.0) {
            return Err(alarms::value_out_of_range(
                e.span,
                b'E',
                e.value,
                "G05.1 E is the largest path error, more than 0 and at most 10 mm",
            ));
        }
        self.tolerance_mm = tol;
        Ok(None)
    }

    /// Fanuc G08 P1 / P0: AI look-ahead control. It reads blocks ahead and
    /// lowers the feed before corners by the allowed acceleration, keeping
    /// to the path: a `smoothing` event for the planner, on with the
    /// machine's own corner tolerance `corner_mm`
    /// (`motion.corner_tolerance_mm`, no path error of its own, unlike
    /// G05.1's E), or off. It is the mode G05.1 Q1 starts too: G05.1 Q0
    /// ends it and G08 P0 ends G05.1's.
    pub fn look_ahead(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        corner_mm: f64,
    ) -> Result<Option<f64>, Diagnostic> {
        let p = w
            .get(b'P')
            .ok_or_else(|| alarms::needs_word(cmd, "G08", "P (1 on, 0 off)"))?;
        match p.value {
            1.0 => Ok(self.look_ahead_on(corner_mm)),
            0.0 => Ok(self.off()),
            _ => Err(alarms::value_out_of_range(
                p.span,
                b'P',
                p.value,
                "G08 P is 1 (look-ahead on) or 0 (off)",
            )),
        }
    }

    /// G08 P1, Fanuc's G05.1 Q1 without E: smoothing on with the
    /// machine's corner tolerance, reported at once.
    fn look_ahead_on(&mut self, tol: f64) -> Option<f64> {
        self.tolerance_mm = tol;
        self.skip_next = false;
        self.report(tol)
    }

    /// G05.1 Q0, G08 P0: the mode ends, whichever code started it; `off`
    /// when the planner was last told `on`.
    fn off(&mut self) -> Option<f64> {
        self.tolerance_mm = 0.0;
        self.skip_next = false;
        if self.reported_mm > 0.0 {
            self.report(0.0)
        } else {
            None
        }
    }

    /// Step 6: a tool length or work system code exempts the next G01.
    pub fn frame_change(&mut self, w: &Words<'_>) {
        if self.tolerance_mm > 0.0
            && (w.group(Group::ToolLength).is_some() || w.group(Group::Wcs).is_some())
        {
            self.skip_next = true;
        }
    }

    /// Before a G01 under the path mode `path`: what smoothing it gets,
    /// reported when it changes. Inlined: every G01 asks.
    #[inline(always)]
    pub fn before_linear(&mut self, path: PathMode) -> Option<f64> {
        let suspended = matches!(path, PathMode::ExactStop | PathMode::Tapping);
        let now = if self.tolerance_mm > 0.0 && !suspended && !self.skip_next {
            self.tolerance_mm
        } else {
            0.0
        };
        self.skip_next = false;
        self.report(now)
    }

    /// Notes `tolerance_mm` as told to the planner, if it was not.
    #[inline]
    fn report(&mut self, tolerance_mm: f64) -> Option<f64> {
        if self.reported_mm == tolerance_mm {
            return None;
        }
        self.reported_mm = tolerance_mm;
        Some(tolerance_mm)
    }

    /// The `smoothing` event that tells the planner `tolerance_mm` (0: off).
    pub fn event(tolerance_mm: f64) -> impl FnOnce(Loc) -> Event {
        move |loc| Event::Smoothing {
            loc,
            on: tolerance_mm > 0.0,
            tolerance_mm,
        }
    }

    /// Haas G187: P1 rough, P2 medium, P3 finish with a corner tolerance E
    /// (else the level's: 0.05, 0.02, 0.005 mm); G187 alone returns to the
    /// machine's own setting (smoothing off). Its `smoothing` event: whether
    /// it is on, and the tolerance. It leaves G05.1's state alone.
    pub fn haas_level(w: &Words<'_>, units: Units) -> (bool, f64) {
        let level = w.get(b'P').map(|p| p.value);
        let tolerance_mm = match (w.get(b'E'), level) {
            (Some(e), _) => units.length_mm(&e),
            (None, Some(p)) if p >= 3.0 => 0.005,
            (None, Some(p)) if p >= 2.0 => 0.02,
            (None, Some(_)) => 0.05,
            (None, None) => 0.0,
        };
        (level.is_some() || w.get(b'E').is_some(), tolerance_mm)
    }
}
