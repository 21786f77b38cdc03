//! The Fanuc lathe's single cycles G90 (turning), G92 (threading) and G94
//! (facing): modal in group 01, each block with an axis word cuts once
//! from the start point A and comes back to it.
//!
//! ```text
//!   G90 (turning)                 G94 (facing)               G92 (threading)
//!   X ▲ A ◀──4(R)── ┐           X ▲ A ──1(R)──┐            like G90, 2 is a
//!     │ 1(R)        │3(F)         │           │2(F)        thread and ends
//!     │ ▼           │             │ 4(R)      ▼            with a chamfer-out
//!     │ ●──2(F)────▶E            │ ▲ ◀─3(F)── E            (parameter 5130:
//!     └──────────────▶ Z          └──────────────▶ Z        tenths of the lead
//!   R: X at the cut's start      R: Z at the cut's start   at 5131 degrees)
//!      minus X at E (radius)        minus Z at E
//! ```
//!
//! X(U), Z(W) and R are modal while the cycle is (Fanuc: "data items X
//! (U), Z (W) and R during the canned cycle are modal"): a block that
//! writes the cycle code starts afresh (an axis it does not name stays at
//! A, R is 0), a later block of the mode with only X repeats the cycle
//! with the new X and the last Z and R. A block without an axis word cuts
//! nothing. The taper may not move the cut's start past A (E314), as
//! Fanuc's four sign cases allow.

use crate::alarms;
use crate::dialect::Group;
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::plane::{P2, Xz, ZERO_MM};
use crate::state::Motion;
use crate::state::lathe::SingleCycle;
use crate::words::Words;
use vcnc_core::events::{Feed, Pos};
use vcnc_syntax::{Diagnostic, Span};

/// How a cycle step moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum How {
    /// G00 (a straight line: the cycles move one axis, or clear a cut).
    Rapid,
    /// G01 at a feed.
    Cut(Feed),
    /// A thread of this lead.
    Thread(f64),
}

/// E314 when the taper moves the cut's start past A: `r` pointing from
/// the end `e` towards A's `a` by more than the distance between them.
fn check_taper(
    r: f64,
    e: f64,
    a: f64,
    w: &Words<'_>,
    cmd: Span,
    axis: &str,
) -> Result<(), Diagnostic> {
    let towards_a = (a - e).signum() == r.signum();
    if r != 0.0 && towards_a && r.abs() > (a - e).abs() + ZERO_MM {
        let span = w.get(b'R').map_or(cmd, |r| r.span);
        return Err(alarms::cycle_parameters(
            span,
            &format!("the taper R puts the cut's start beyond the start point in {axis}"),
        ));
    }
    Ok(())
}

impl<'a> Machining<'_, 'a> {
    /// The machine (and program) indices of X and Z.
    pub(crate) fn lathe_axes(&self, cmd: Span) -> Result<(usize, usize), Diagnostic> {
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

    /// The program position in the lathe plane.
    pub(crate) fn here_xz(&self, axes: (usize, usize)) -> Xz {
        P2::of(&self.state.prog, axes)
    }

    /// Commits the steps of a cycle through the motion stage; a step to
    /// where the tool already is makes no event.
    pub(crate) fn cycle_moves(
        &mut self,
        moves: &[(How, Xz)],
        axes: (usize, usize),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        for &(how, p) in moves {
            let to: Pos = p.placed(self.state.prog, axes);
            let here = self.state.prog;
            if (to.get(axes.0) - here.get(axes.0)).abs() < ZERO_MM
                && (to.get(axes.1) - here.get(axes.1)).abs() < ZERO_MM
            {
                continue;
            }
            let kind = match how {
                How::Rapid => MoveKind::StraightRapid,
                How::Cut(feed) => MoveKind::Feed(feed),
                How::Thread(lead_mm) => MoveKind::Thread { lead_mm },
            };
            self.straight(kind, Target::Program(to), w, cmd)?;
        }
        Ok(())
    }

    /// One block under G90, G92 or G94.
    #[inline(never)]
    pub(crate) fn single_cycle(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        motion: Motion,
    ) -> Result<(), Diagnostic> {
        if !w.any(self.cfg.axis_mask) {
            // Only a block that cuts reads R.
            if let Some(r) = w.get(b'R') {
                return Err(alarms::word_not_allowed(r.span, b'R'));
            }
            return Ok(());
        }
        let axes = self.lathe_axes(cmd)?;
        let a = self.here_xz(axes);
        let data = self.single_data(w, axes, a);
        let r = data.r;
        let e = P2(data.x, data.z);
        let moves = match motion {
            Motion::FaceCycle => {
                check_taper(r, e.1, a.1, w, cmd, "Z")?;
                let feed = self.feed(cmd)?;
                vec![
                    (How::Rapid, P2(a.0, e.1 + r)),
                    (How::Cut(feed), e),
                    (How::Cut(feed), P2(e.0, a.1)),
                    (How::Rapid, a),
                ]
            }
            Motion::ThreadingCycle => {
                check_taper(r, e.0, a.0, w, cmd, "X")?;
                let lead_mm = self
                    .state
                    .thread_lead_mm
                    .filter(|l| *l > 0.0)
                    .ok_or_else(|| alarms::thread_without_lead(cmd))?;
                let mut moves = vec![(How::Rapid, P2(e.0 + r, a.1))];
                moves.extend(self.thread_with_chamfer(P2(e.0 + r, a.1), e, a.0, lead_mm));
                moves.push((How::Rapid, P2(a.0, e.1)));
                moves.push((How::Rapid, a));
                moves
            }
            _ => {
                check_taper(r, e.0, a.0, w, cmd, "X")?;
                let feed = self.feed(cmd)?;
                vec![
                    (How::Rapid, P2(e.0 + r, a.1)),
                    (How::Cut(feed), e),
                    (How::Cut(feed), P2(a.0, e.1)),
                    (How::Rapid, a),
                ]
            }
        };
        self.state.lathe.single = data;
        self.cycle_moves(&moves, axes, w, cmd)
    }

    /// The end point and taper of a cycle block: named axes from the
    /// words (U/W from A), the others from the last cycle block, or from A
    /// when the block writes the cycle code.
    fn single_data(&mut self, w: &Words<'_>, (ix, iz): (usize, usize), a: Xz) -> SingleCycle {
        let fresh = w.group(Group::Motion).is_some();
        let last = if fresh {
            SingleCycle {
                x: a.0,
                z: a.1,
                r: 0.0,
            }
        } else {
            self.state.lathe.single
        };
        let goal = self.state.target(self.cfg, w, false);
        let pick = |i: usize, old: f64| {
            if goal.named & (1 << i) != 0 {
                goal.prog.get(i)
            } else {
                old
            }
        };
        SingleCycle {
            x: pick(ix, last.x),
            z: pick(iz, last.z),
            r: w.get(b'R').map_or(last.r, |r| self.units().length_mm(&r)),
        }
    }

    /// A thread from `from` to `end` that pulls out over its last
    /// chamfer length (tenths of the lead, at the chamfer angle) towards
    /// `out_x`, the X the tool returns to.
    pub(crate) fn thread_with_chamfer(
        &self,
        from: Xz,
        end: Xz,
        out_x: f64,
        lead_mm: f64,
    ) -> Vec<(How, Xz)> {
        let thread = How::Thread(lead_mm);
        let length = (end.1 - from.1).abs();
        let gamma = (f64::from(self.state.lathe.mrc.chamfer_tenths) / 10.0 * lead_mm).min(length);
        if gamma <= ZERO_MM || length <= ZERO_MM {
            return vec![(thread, end)];
        }
        // Where the chamfer starts on the thread line (a taper included).
        let t = (length - gamma) / length;
        let start = from + (end - from) * t;
        let lift = gamma
            * self
                .cfg
                .machine
                .params
                .thread_chamfer_deg
                .to_radians()
                .tan();
        let dir = (out_x - start.0).signum();
        let lifted = start.0 + dir * lift.min((out_x - start.0).abs());
        vec![(thread, start), (thread, P2(lifted, end.1))]
    }
}
