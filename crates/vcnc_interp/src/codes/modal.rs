//! Step 7's modal motion: what a block in group 01's mode does with its
//! axis words (a straight move, an arc, a canned cycle's holes, a NURBS
//! block, a lathe's single cycle), and the way every move of a code takes
//! to the motion stage.
//!
//! ```text
//!   modal_motion ─▶ straight / arc / drill / nurbs / single cycle
//!                     └▶ send: lathe corner (,C/,R held by the G01 before)
//!                              G96 on a lathe (the speed follows X)
//!                          └▶ commit (motion/: frame → comp → travel → events)
//! ```
//!
//! The features that act on every move (a held corner, constant surface
//! speed) act here, before the motion stage, so that `motion/` knows
//! nothing of the codes.

use crate::alarms;
use crate::dialect::{GOp, Group, PaceOp, ThreadLead};
use crate::interpreter::Machining;
use crate::motion::{Move, MoveKind, Target};
use crate::state::Motion;
use crate::words::Words;
use vcnc_core::events::MAX_AXES;
use vcnc_core::events::SpindleDir;
use vcnc_syntax::{Addr, Diagnostic, Span};

impl<'a> Machining<'_, 'a> {
    /// LinuxCNC's G33.1 K: in to the block's point locked to the spindle,
    /// K per revolution; the spindle reversed; back out the same way to
    /// where the tap started, which is where the tool stays; the spindle's
    /// direction restored. The overrun while the spindle reverses is the
    /// machine's, not modelled. rs274 wants K in every block ("K word
    /// missing with g33/g33.1") and a turning spindle ("Spindle not
    /// turning in G33.1"), either way.
    fn rigid_tap(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let k = w.get(b'K').ok_or_else(|| {
            alarms::needs_word(cmd, "G33.1", "K (the pitch: distance per revolution)")
        })?;
        let lead_mm = self.units().length_mm(&k);
        if lead_mm <= 0.0 {
            return Err(alarms::value_out_of_range(
                k.span,
                b'K',
                k.value,
                "G33.1's K is the pitch, more than 0",
            ));
        }
        let fwd = self.state.spindle;
        let rev = match fwd {
            SpindleDir::Cw => SpindleDir::Ccw,
            SpindleDir::Ccw => SpindleDir::Cw,
            _ => return Err(alarms::tapping_spindle(cmd, "G33.1", None)),
        };
        if self.state.rpm <= 0.0 {
            return Err(alarms::tapping_spindle(cmd, "G33.1", None));
        }
        let start = self.state.prog;
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let to = self.state.move_target(&goal);
        self.straight(MoveKind::Thread { lead_mm }, to, w, cmd)?;
        self.cycle_spindle(rev);
        let back = crate::motion::Target::Program(start);
        self.straight(MoveKind::Thread { lead_mm }, back, w, cmd)?;
        self.cycle_spindle(fwd);
        Ok(())
    }

    /// Commits a straight move of this block. Inlined: a plain block's
    /// move is built in its caller's frame, not copied into another.
    #[inline(always)]
    pub(crate) fn straight(
        &mut self,
        kind: MoveKind,
        to: Target,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let mv = Move {
            kind,
            to,
            exact_stop: self.exact_stop(w),
            cmd,
        };
        self.send(mv, w)
    }

    /// A move of a code on its way to the motion stage: a chamfer or corner
    /// R that the G01 before holds is cut ahead of it, and under a lathe's
    /// G96 the spindle speed follows the diameter it goes to; then
    /// [`commit`](Self::commit) takes it.
    #[inline]
    pub(crate) fn send(&mut self, mv: Move, w: &Words<'_>) -> Result<(), Diagnostic> {
        if self.state.lathe.corner.is_some() || self.state.modal.css {
            return self.send_turning(mv, w);
        }
        // Handed on as it came: a plain move is not copied on its way.
        self.commit(mv, w)
    }

    /// [`send`](Self::send) on a lathe with a corner held or under G96,
    /// out of line.
    #[inline(never)]
    fn send_turning(&mut self, mv: Move, w: &Words<'_>) -> Result<(), Diagnostic> {
        let mv = if self.state.lathe.corner.is_some() {
            // A G01's or an arc's chamfer or corner R is cut before this
            // move, which then starts where the chamfer or round ends.
            self.cut_corner(mv, w)?
        } else {
            mv
        };
        if self.state.modal.css {
            // A lathe's G96: the speed follows the diameter.
            self.css_follow(&mv)?;
        }
        self.commit(mv, w)
    }

    /// Whether G09 is in the block.
    #[inline]
    pub(crate) fn exact_stop(&self, w: &Words<'_>) -> bool {
        // A block of axis words alone has no one-shot code.
        w.has_codes && w.once(GOp::Pace(PaceOp::ExactStopOnce)).is_some()
    }
}

impl<'a> Machining<'_, 'a> {
    /// Step 7 without a one-shot code: the modal motion, if the block moves.
    pub(crate) fn modal_motion(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let motion = self.state.modal.motion;
        let cmd = w.group(Group::Motion).map_or(w.first, |a| a.span);
        if self.state.cycle.code.is_some() {
            return self.drill(w, cmd);
        }
        match motion {
            Motion::ArcCw | Motion::ArcCcw => self.arc(w, cmd, motion == Motion::ArcCw),
            Motion::ThreePointArc => self.three_point_arc(w, cmd),
            Motion::Nurbs => self.nurbs_block(w, cmd),
            Motion::TurnCycle | Motion::ThreadingCycle | Motion::FaceCycle => {
                self.single_cycle(w, cmd, motion)
            }
            _ if !w.moves(self.cfg.axis_mask) => {
                // `,C`/`,R` under G01 in a block that does not move: the
                // chamfer has no corner to cut (Fanuc PS0055).
                match (w.get_ext(Addr::COMMA_C), w.get_ext(Addr::COMMA_R)) {
                    (Some(c), _) | (None, Some(c)) if motion == Motion::Linear => {
                        Err(alarms::corner_fault(c.span, "the G01 has no end point"))
                    }
                    _ => Ok(()),
                }
            }
            Motion::Rapid => {
                let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
                let to = self.state.move_target(&goal);
                self.straight(MoveKind::Rapid, to, w, cmd)
            }
            Motion::Linear => {
                if let Some(t) = self.state.smoothing.before_linear(self.state.modal.path) {
                    self.report_smoothing(t);
                }
                let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
                let feed = if self.state.modal.inverse_time {
                    let from = self.state.prog;
                    let len = (0..MAX_AXES)
                        .map(|i| (goal.prog.get(i) - from.get(i)).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    self.inverse_time_feed(w, cmd, len)?
                } else {
                    self.feed(cmd)?
                };
                let to = self.state.move_target(&goal);
                if w.corner_word() {
                    // `,C`/`,R`: the corner waits for the next block.
                    return self.hold_corner(w, cmd, feed, &goal, None);
                }
                self.straight(MoveKind::Feed(feed), to, w, cmd)
            }
            Motion::Thread | Motion::ThreadInch => {
                if self.cfg.dialect.thread_lead == ThreadLead::K
                    && let Some(k) = w.get(b'K')
                {
                    // LinuxCNC's G33 K: distance per revolution.
                    self.state.thread_lead_mm = Some(self.state.units(self.cfg).length_mm(&k));
                }
                let lead_mm = self
                    .state
                    .thread_lead_mm
                    .filter(|l| *l > 0.0)
                    .ok_or_else(|| alarms::thread_without_lead(cmd))?;
                let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
                let to = self.state.move_target(&goal);
                self.straight(MoveKind::Thread { lead_mm }, to, w, cmd)
            }
            Motion::RigidTap => self.rigid_tap(w, cmd),
        }
    }
}
