//! Syntec G06.2 NURBS interpolation (manual 1.2.8), inside G05 P10000 only.
//!
//! ```text
//!  G06.2 P3 K0. X0. Y0. Z0. R1. F5000.   first block: order P (2–4, default
//!  K0. X0. Y5. Z0. R1.                   4), then one knot K, control point
//!  K0. X5. Y5. Z0. R1.                   (X Y Z) and weight R (default 1) a
//!  K1.                                   block; then K-only blocks give the
//!  K1.                                   last P knots. The curve is complete
//!  K1.                                   when n points have n + P knots: it is
//!                                        emitted at that block as one `nurbs`
//! ```                                    event (`vcnc_core::nurbs` evaluates it).
//!
//! Control points are programmed points (G90/G91, units, offsets and
//! transforms apply as to any G01 end point; the curve is affine-invariant,
//! so mapping the control points maps the curve). The first must be where
//! the tool is and the knots clamped (Fanuc's rule): the curve starts at
//! the tool and ends at the last control point. As the curve lies in the
//! convex hull of its control points (positive weights), checking them
//! against the travel limits checks the curve. Unlike the other codes this
//! one emits its motion event itself: a curve is not a line or an arc and
//! does not pass the compensation stage (alarm under G41/G42).

use crate::alarms;
use crate::dialect::MotionOp;
use crate::dialect::{GOp, Group};
use crate::interpreter::Machining;
use crate::motion::{MachineKind, MachineMove, Target, travel};
use crate::state::{Motion, NurbsBuild};
use crate::words::Words;
use std::sync::Arc;
use vcnc_core::Nurbs;
use vcnc_core::events::{Event, Pos};
use vcnc_core::nurbs::MAX_NURBS_POINTS;
use vcnc_syntax::{Diagnostic, Span};

fn distance(a: &Pos, b: &Pos) -> f64 {
    a.minus(*b).0.iter().map(|v| v * v).sum::<f64>().sqrt()
}

impl<'a> Machining<'_, 'a> {
    /// A control point and its weight: the block's end point, as a G01's.
    fn nurbs_point(&mut self, b: &mut NurbsBuild, w: &Words<'_>) -> Result<(), Diagnostic> {
        if b.knots_only {
            return Err(alarms::bad_nurbs(
                w.first,
                "control points come before the K-only blocks",
            ));
        }
        if b.curve.points.len() >= MAX_NURBS_POINTS {
            return Err(alarms::bad_nurbs(
                w.first,
                "more than 10,000 control points",
            ));
        }
        let weight = match w.get(b'R') {
            None => 1.0,
            Some(r) if (0.001..=1000.0).contains(&r.value) => r.value,
            Some(r) => {
                return Err(alarms::value_out_of_range(
                    r.span,
                    b'R',
                    r.value,
                    "R is a weight, 0.001 to 1000",
                ));
            }
        };
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let frame = &self.state.frame;
        let (prog, machine) = match self.state.move_target(&goal) {
            Target::Relative(d) => (
                self.state.prog.plus(d),
                self.state.nominal.plus(frame.vector_to_machine(d)),
            ),
            Target::Program(p) | Target::Machine(p) => (p, frame.machine_of(p)),
        };
        let check = MachineMove {
            kind: MachineKind::Feed(vcnc_core::Feed::PerMin(1.0)),
            from: machine,
            to: machine,
            exact_stop: false,
        };
        if let Err(out) = travel::check(self.cfg.machine, &check, None) {
            return Err(out.alarm(self.cfg.machine, w.first));
        }
        if b.curve.points.is_empty() && distance(&machine, &self.state.pos) > 1e-6 {
            return Err(alarms::bad_nurbs(
                w.first,
                "the first control point must be where the tool is",
            ));
        }
        self.state.prog = prog;
        self.state.nominal = machine;
        self.state.detached = false;
        b.curve.points.push(machine);
        b.curve.weights.push(weight);
        Ok(())
    }

    fn nurbs_emit(&mut self, b: NurbsBuild) -> Result<(), Diagnostic> {
        b.curve
            .check()
            .map_err(|why| alarms::bad_nurbs(b.cmd, why))?;
        let feed = self.feed(b.cmd)?;
        let end = b.curve.points.last().copied().unwrap_or(self.state.pos);
        self.report_frame();
        self.stage.moves += 1;
        let curve = Arc::new(b.curve);
        self.emit(|loc| Event::Nurbs { loc, curve, feed });
        self.state.pos = end;
        Ok(())
    }

    /// A curve still being defined takes nothing but its own blocks
    /// (Fanuc: no other command until the definition is complete): a
    /// block that leaves G06.2 (G00–G03 …) or gives a code that takes the
    /// axis words (G05 P0, G04 …) alarms E329 there, before it moves; the
    /// curve's control points would otherwise be dropped unseen while the
    /// program point already stands at the last of them.
    #[cold]
    #[inline(never)]
    pub(crate) fn check_curve_pending(&self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let Some(b) = self.stage.nurbs.as_ref() else {
            return Ok(());
        };
        // Whether the block's motion (its own G code, else the modal one)
        // is G06.2's: asked before or after the block's modal codes.
        let leaves = match w.group(Group::Motion) {
            Some(g) => g.def.op != GOp::Motion(MotionOp::Nurbs),
            None => self.state.modal.motion != Motion::Nurbs,
        };
        let other = w
            .axis_user
            .map(|u| u.span)
            .or_else(|| leaves.then(|| w.group(Group::Motion).map_or(w.first, |g| g.span)));
        match other {
            Some(at) => Err(alarms::bad_nurbs(
                at,
                if b.knots_only {
                    "the curve needs more K-only blocks (n + P knots) before another command"
                } else {
                    "the curve's definition is not complete: every block of it has a knot K"
                },
            )),
            None => Ok(()),
        }
    }
}

impl<'a> Machining<'_, 'a> {
    /// One block under the modal G06.2.
    #[inline(never)]
    pub(crate) fn nurbs_block(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let starts = w
            .group(Group::Motion)
            .is_some_and(|g| g.def.op == GOp::Motion(MotionOp::Nurbs));
        if starts {
            self.nurbs_start(w, cmd)?;
        }
        let Some(k) = w.get(b'K') else {
            return match self.stage.nurbs.as_ref() {
                Some(b) => Err(alarms::bad_nurbs(
                    w.first,
                    if b.knots_only {
                        "the curve needs more K-only blocks (n + P knots)"
                    } else {
                        "every block of a NURBS definition has a knot K"
                    },
                )),
                None if w.any(self.cfg.axis_mask) => Err(alarms::bad_nurbs(
                    w.first,
                    "a new curve starts with G06.2 (P K X Y Z R)",
                )),
                None => Ok(()),
            };
        };
        let Some(mut b) = self.stage.nurbs.take() else {
            return Err(alarms::bad_nurbs(
                k.span,
                "a new curve starts with G06.2 (P K X Y Z R)",
            ));
        };
        // What the block adds, taken back if it alarms: the curve stays as
        // the blocks before left it (a run that keeps going reads its next
        // blocks against it).
        let mark = (b.curve.knots.len(), b.curve.points.len(), b.knots_only);
        match self.nurbs_knot(&mut b, w, k) {
            Ok(true) => self.nurbs_emit(b),
            Ok(false) => {
                self.stage.nurbs = Some(b);
                Ok(())
            }
            Err(d) => {
                b.curve.knots.truncate(mark.0);
                b.curve.points.truncate(mark.1);
                b.curve.weights.truncate(mark.1);
                b.knots_only = mark.2;
                self.stage.nurbs = Some(b);
                Err(d)
            }
        }
    }

    /// One block's knot `k` (and control point) added to the curve `b`;
    /// whether the curve is then complete.
    fn nurbs_knot(
        &mut self,
        b: &mut NurbsBuild,
        w: &Words<'_>,
        k: vcnc_syntax::Word,
    ) -> Result<bool, Diagnostic> {
        if !k.value.is_finite() || b.curve.knots.last().is_some_and(|last| k.value < *last) {
            return Err(alarms::bad_nurbs(k.span, "the knots must not decrease"));
        }
        b.curve.knots.push(k.value);
        if w.any(self.cfg.axis_mask) {
            self.nurbs_point(b, w)?;
        } else {
            b.knots_only = true;
            if let Some(r) = w.get(b'R') {
                return Err(alarms::bad_nurbs(
                    r.span,
                    "a weight R belongs to a control point",
                ));
            }
        }
        let need = b.curve.points.len() + usize::from(b.curve.order);
        if b.knots_only && b.curve.knots.len() == need {
            return Ok(true);
        }
        if b.curve.knots.len() > need.max(MAX_NURBS_POINTS + 4) {
            return Err(alarms::bad_nurbs(k.span, "more knots than n + P"));
        }
        Ok(false)
    }

    fn nurbs_start(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        if self.state.high_speed_p != 10_000 {
            return Err(alarms::nurbs_outside_high_speed(cmd));
        }
        if self.stage.nurbs.is_some() {
            return Err(alarms::bad_nurbs(cmd, "the previous curve is not complete"));
        }
        if self.stage.comp.engaged() {
            return Err(alarms::bad_nurbs(
                cmd,
                "no NURBS under cutter compensation (G41/G42)",
            ));
        }
        let order = match w.get(b'P') {
            None => 4,
            Some(p) if p.value == 2.0 => 2,
            Some(p) if p.value == 3.0 => 3,
            Some(p) if p.value == 4.0 => 4,
            Some(p) => {
                return Err(alarms::value_out_of_range(
                    p.span,
                    b'P',
                    p.value,
                    "P is the order, 2 to 4",
                ));
            }
        };
        self.stage.nurbs = Some(NurbsBuild {
            curve: Nurbs {
                order,
                knots: Vec::new(),
                points: Vec::new(),
                weights: Vec::new(),
            },
            knots_only: false,
            cmd,
        });
        Ok(())
    }
}
