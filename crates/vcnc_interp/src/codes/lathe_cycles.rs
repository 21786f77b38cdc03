//! The lathe's turning cycles (seed 003): G81 cylinder cycle and G331
//! thread cycle, expanded into plain moves following the document's steps.
//!
//! G81 X(U) Z(W) R I K F — rough passes of depth I, a finishing pass of K:
//!
//! ```text
//!   X ▲  S ─ ─ ─ ─ ─ ─ ─ ─          S start (tool position), Zs its Z
//!     │  │1 ┌───────────┐ 3        1 G01 infeed (I, then 2·I, last I+K)
//!     │  │  │     2     │          2 G01 cut along the profile, parallel
//!     │  └4─┘───────────┘          3 G01 retract I    4 G00 back to Zs
//!     │  R at Zs ───────── X at Ze   finished profile (taper if R ≠ X)
//!     └──────────────────────▶ Z
//! ```
//!
//! The finished profile runs from diameter R at the start section (Zs) to
//! the end point X at Ze. Each rough pass cuts a line parallel to it,
//! `I` deeper than the last (measured at Zs), until the profile plus the
//! finishing allowance K is reached; then the finishing pass (infeed I + K)
//! cuts the profile itself and the tool stops at the end point. I and K are
//! X depths (diameters under G23), negative for outside turning.
//!
//! G331 X Z I K R P — a thread of lead K over Z, X the change of diameter
//! (0 = straight), R the thread depth (a diameter difference), P passes:
//! pass k feeds to depth k·R/P (rounded to 0.001), threads to Z, pulls out
//! by I in X still threading (the tail), and returns at rapid; a last
//! spring pass repeats the full depth without feeding in. The tool ends at
//! the start point. Outside threads only (the document aligns the cycle on
//! the outer circle).

use crate::alarms;
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::plane::{P2, Xz, ZERO_MM};
use crate::words::Words;
use crate::words::whole;
use vcnc_core::events::{Feed, Pos};
use vcnc_syntax::{Diagnostic, Span};

/// Most rough passes a G81 may make: a real depth of cut is never that
/// small, and the block's events are held until it completes.
const MAX_PASSES: f64 = 10_000.0;

/// How far below a whole number a count of passes (a ratio of two depths)
/// may be and still be that number: `ceil` of 3 + 1e-15 is 4, and a depth
/// that is three steps up to rounding must cut three passes. A ratio, not
/// a length, so not [`ZERO_MM`].
const WHOLE_SLACK: f64 = 1e-9;

/// How a cycle step moves.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    Rapid,
    Cut(Feed),
    Thread(f64),
}

impl<'a> Machining<'_, 'a> {
    /// Machine axis indices of X and Z.
    fn xz_axes(&self, cmd: Span) -> Result<(usize, usize), Diagnostic> {
        match (
            self.cfg.machine.axis_of(b'X'),
            self.cfg.machine.axis_of(b'Z'),
        ) {
            (Some(x), Some(z)) => Ok((x, z)),
            _ => Err(alarms::cycle_parameters(
                cmd,
                "a turning cycle needs X and Z axes",
            )),
        }
    }

    fn at(&self, axes: (usize, usize), p: Xz) -> Pos {
        p.placed(self.state.prog, axes)
    }

    /// G81.
    pub(crate) fn cylinder_cycle(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let axes = self.xz_axes(cmd)?;
        let feed = self.feed(cmd)?;
        let end = self
            .state
            .target(self.cfg, w, self.state.modal.incremental)
            .prog;
        let (r, i, k) = match (w.get(b'R'), w.get(b'I'), w.get(b'K')) {
            (Some(r), Some(i), Some(k)) => (r, i, k),
            _ => return Err(alarms::cycle_parameters(cmd, "G81 needs R, I and K")),
        };
        let start: Xz = P2::of(&self.state.prog, axes);
        let end: Xz = P2::of(&end, axes);
        let profile_x = self.units().x_length_mm(&r);
        let (step, allowance) = (self.units().x_length_mm(&i), self.units().x_length_mm(&k));
        let depth = profile_x - start.0;
        if step == 0.0 || (allowance != 0.0 && allowance.signum() != step.signum()) {
            return Err(alarms::cycle_parameters(
                i.span,
                "I must be non-zero and I and K of one sign",
            ));
        }
        if depth != 0.0 && depth.signum() != step.signum() {
            return Err(alarms::cycle_parameters(
                r.span,
                "R lies on the wrong side of the start point for the sign of I",
            ));
        }
        if allowance.abs() > depth.abs() {
            return Err(alarms::cycle_parameters(
                k.span,
                "the finishing allowance K is deeper than the whole cut",
            ));
        }
        let taper = end.0 - profile_x;
        let rough = depth - allowance;
        let passes = (rough.abs() / step.abs() - WHOLE_SLACK).ceil().max(0.0);
        if passes > MAX_PASSES {
            return Err(alarms::cycle_parameters(
                i.span,
                "I is so small that the cut needs more than 10,000 passes",
            ));
        }
        let cut = Step::Cut(feed);
        let mut moves: Vec<(Step, Xz)> = Vec::new();
        let mut k_pass = 1.0;
        while k_pass <= passes {
            let x = start.0 + step.signum() * (k_pass * step.abs()).min(rough.abs());
            moves.push((cut, P2(x, start.1)));
            moves.push((cut, P2(x + taper, end.1)));
            moves.push((cut, P2(x + taper - step, end.1)));
            moves.push((Step::Rapid, P2(x - step, start.1)));
            k_pass += 1.0;
        }
        moves.push((cut, P2(profile_x, start.1)));
        moves.push((cut, end));
        self.run_moves(&moves, axes, w, cmd)
    }

    /// Commits the moves of a cycle, `(how, point)`, through the motion
    /// stage (the block's events are held until it completes, so an alarm
    /// part-way drops them all).
    fn run_moves(
        &mut self,
        moves: &[(Step, Xz)],
        axes: (usize, usize),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        for (how, p) in moves {
            let to = self.at(axes, *p);
            if to == self.state.prog {
                // A cycle step that does not move (a tail of 0, a retract
                // already at the safe X) makes no event.
                continue;
            }
            let kind = match *how {
                Step::Rapid => MoveKind::StraightRapid,
                Step::Cut(feed) => MoveKind::Feed(feed),
                Step::Thread(lead_mm) => MoveKind::Thread { lead_mm },
            };
            self.straight(kind, Target::Program(to), w, cmd)?;
        }
        Ok(())
    }

    /// G331.
    pub(crate) fn thread_cycle(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let axes = self.xz_axes(cmd)?;
        let start: Xz = P2::of(&self.state.prog, axes);
        let end_z = self.thread_end_z(w, axes.1, cmd)?;
        let (k, r, p) = match (w.get(b'K'), w.get(b'R'), w.get(b'P')) {
            (Some(k), Some(r), Some(p)) => (k, r, p),
            _ => {
                return Err(alarms::cycle_parameters(
                    cmd,
                    "G331 needs Z, K (lead), R (depth) and P (passes)",
                ));
            }
        };
        let lead_mm = self.units().length_mm(&k);
        if lead_mm <= 0.0 {
            return Err(alarms::cycle_parameters(
                k.span,
                "the lead K must be positive",
            ));
        }
        if r.value <= 0.0 {
            return Err(alarms::cycle_parameters(
                r.span,
                "the depth R must be positive",
            ));
        }
        let passes = whole(&p, b'P', 1.0, 1000.0, "P is a number of passes")?;
        let taper = w.get(b'X').map_or(0.0, |x| self.units().x_length_mm(&x));
        let tail = w.get(b'I').map_or(0.0, |i| self.units().x_length_mm(&i));
        // "each depth of cut into R ÷ p and rounded": rounded to 0.001 in
        // program units, the last pass takes what is left.
        let step_prog = ((r.value / f64::from(passes)) * 1000.0).round() / 1000.0;
        if step_prog <= 0.0 {
            return Err(alarms::cycle_parameters(
                p.span,
                "the depth per pass R/P rounds to 0: use fewer passes",
            ));
        }
        let scale = self.units().x_length_mm(&r) / r.value;
        let total = self.units().x_length_mm(&r);
        let thread = Step::Thread(lead_mm);
        let mut moves: Vec<(Step, Xz)> = Vec::new();
        for n in 1..=passes + 1 {
            // Rounding up can reach the full depth early: never cut deeper.
            let depth = if n >= passes {
                total
            } else {
                (f64::from(n) * step_prog * scale).min(total)
            };
            let x = start.0 - depth;
            let tail_x = x + taper + tail;
            let safe = start.0.max(start.0 + taper).max(tail_x);
            moves.push((Step::Rapid, P2(x, start.1)));
            moves.push((thread, P2(x + taper, end_z)));
            if tail != 0.0 {
                moves.push((thread, P2(tail_x, end_z)));
            }
            moves.push((Step::Rapid, P2(safe, end_z)));
            moves.push((Step::Rapid, P2(safe, start.1)));
        }
        moves.push((Step::Rapid, start));
        self.run_moves(&moves, axes, w, cmd)
    }

    /// The Z end of a G331 thread: Z (absolute or incremental) or W.
    fn thread_end_z(&self, w: &Words<'_>, iz: usize, cmd: Span) -> Result<f64, Diagnostic> {
        let here = self.state.prog.get(iz);
        let z = match (w.get(b'Z'), w.get(b'W')) {
            (Some(z), _) if self.state.modal.incremental => here + self.units().length_mm(&z),
            (Some(z), _) => self.units().length_mm(&z),
            (None, Some(wz)) => here + self.units().length_mm(&wz),
            (None, None) => {
                return Err(alarms::cycle_parameters(
                    cmd,
                    "G331 needs the thread length Z",
                ));
            }
        };
        if (z - here).abs() < ZERO_MM {
            return Err(alarms::cycle_parameters(cmd, "the thread has zero length"));
        }
        Ok(z)
    }
}
