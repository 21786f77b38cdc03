//! Chamfer and corner rounding at the end of a G01 (`,C` and `,R`, Fanuc
//! 0i-TF "chamfering and corner R"), between that G01 and the G01 of the
//! next block.
//!
//! ```text
//!            P1 ──── corner          ,C c: P1 and P2 are c from the corner
//!   G01 ─────●╲     ╱                       along each line, joined by a G01
//!              ╲   ╱ (not cut)       ,R r: P1 and P2 are t = r·tan(θ/2) from
//!               ● P2                        it (θ: the turn), joined by an arc
//!               │ next G01                  of radius r tangent to both
//! ```
//!
//! The G01 with `,C`/`,R` is held: its block moves nothing, and the
//! programmed point becomes the corner, so that the next block's U/W count
//! from it, as Fanuc's do. The next move (a G01, G02 or G03 in the plane)
//! first sends the held move to P1 and the chamfer or round to P2, with the
//! held block's line, then its own move from P2. Anything else in the next
//! block — no move, a rapid, a cycle — alarms E347 there, as does a
//! chamfer longer than either move or two moves in one direction. Where an
//! arc meets the corner (Fanuc 0i-MF), `corner_cut_segs` measures a
//! chamfer as a chord on it and rounds tangent to the arc's circle.

use crate::alarms;
use crate::interpreter::Machining;
use crate::motion::Goal;
use crate::motion::{Move, MoveKind, Target};
use crate::plane::{Curve, P2, Seg, ZERO_MM, intersect};
use crate::state::lathe::{CornerKind, PendingCorner};
use crate::words::Words;
use vcnc_core::events::{Feed, Pos};
use vcnc_syntax::{Addr, Diagnostic, Span};

/// Where a corner's chamfer or round starts and ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CornerCut {
    /// End of the shortened first line.
    pub p1: P2,
    /// Start of the shortened second line.
    pub p2: P2,
    /// For a round: its centre and whether it turns counter-clockwise.
    pub arc: Option<(P2, bool)>,
}

/// Below this two lines run in one direction, or straight back, radians.
const STRAIGHT_RAD: f64 = 1e-7;
/// How much further than a line's length a chamfer or round may cut it
/// back, mm: the cut-back of a `,R` comes from `tan` (and an inch `,C`
/// from a unit conversion), whose rounding must not turn a corner that
/// exactly uses up a line into an alarm.
const OVERRUN_MM: f64 = 1e-6;

/// The chamfer or round between `a → corner` and `corner → b`, or why it
/// cannot be made.
pub(crate) fn corner_cut(
    a: P2,
    corner: P2,
    b: P2,
    kind: CornerKind,
) -> Result<CornerCut, &'static str> {
    let (d1, d2) = (corner - a, b - corner);
    let (l1, l2) = (d1.hypot(), d2.hypot());
    if l1 < ZERO_MM || l2 < ZERO_MM {
        return Err("one of the two moves has no length");
    }
    let (u1, u2) = (d1 / l1, d2 / l2);
    let cross = u1.cross(u2);
    let turn = cross.atan2(u1.dot(u2));
    if turn.abs() < STRAIGHT_RAD {
        return Err("the two moves run in one direction, there is no corner");
    }
    if (turn.abs() - std::f64::consts::PI).abs() < STRAIGHT_RAD {
        return Err("the next move turns straight back");
    }
    let (t, arc) = match kind {
        CornerKind::Chamfer(c) => (c, None),
        CornerKind::Round(r) => (r * (turn.abs() / 2.0).tan(), Some(r)),
    };
    if t <= 0.0 {
        return Err("the chamfer or radius is not positive");
    }
    if t > l1 + OVERRUN_MM || t > l2 + OVERRUN_MM {
        return Err("it is longer than one of the two moves");
    }
    let p1 = corner - u1 * t;
    let p2 = corner + u2 * t;
    let arc = arc.map(|r| {
        // The centre is r from P1 on the inside of the turn.
        let ccw = cross > 0.0;
        let n = if ccw { u1.left() } else { u1.left() * -1.0 };
        (p1 + n * r, ccw)
    });
    Ok(CornerCut { p1, p2, arc })
}

/// The chamfer or round between two elements that meet at `s1`'s end and
/// `s2`'s start, when either is an arc (two lines: [`corner_cut`]). A
/// chamfer's ends lie `c` from the corner in a straight line on each
/// element; a round's centre is `r` from both, on the inside of the turn,
/// and its ends are the feet of that centre on each.
pub(crate) fn corner_cut_segs(
    s1: &Seg,
    s2: &Seg,
    kind: CornerKind,
) -> Result<CornerCut, &'static str> {
    if !s1.is_arc() && !s2.is_arc() {
        return corner_cut(s1.start(), s1.end(), s2.end(), kind);
    }
    let corner = s1.end();
    let (t1, t2) = (s1.tangent(true), s2.tangent(false));
    let cross = t1.cross(t2);
    let turn = cross.atan2(t1.dot(t2));
    if turn.abs() < STRAIGHT_RAD {
        return Err("the two moves run in one direction, there is no corner");
    }
    if (turn.abs() - std::f64::consts::PI).abs() < STRAIGHT_RAD {
        return Err("the next move turns straight back");
    }
    let (p1, p2, arc) = match kind {
        CornerKind::Chamfer(c) => {
            let at = |s: &Seg, back: bool| match s.arc_of() {
                None => Some(corner + s.tangent(back) * if back { -c } else { c }),
                Some((centre, _)) => {
                    let guess = corner + s.tangent(back) * if back { -c } else { c };
                    intersect(
                        Curve::Circle {
                            c: centre,
                            r: centre.dist(corner),
                        },
                        Curve::Circle { c: corner, r: c },
                        guess,
                        0.0,
                    )
                }
            };
            let (Some(p1), Some(p2)) = (at(s1, true), at(s2, false)) else {
                return Err("it is longer than one of the two moves");
            };
            (p1, p2, None)
        }
        CornerKind::Round(r) => {
            // Left turn: the round's centre is on the left of both paths.
            let side = if cross > 0.0 { 1.0 } else { -1.0 };
            let offset = |s: &Seg| match s.arc_of() {
                None => Curve::Line {
                    p: s.start() + s.tangent(false).left() * (side * r),
                    d: s.tangent(false),
                },
                Some((centre, ccw)) => {
                    let big = centre.dist(corner);
                    // The path's centre is on its left when it turns ccw.
                    let inward = if ccw { side > 0.0 } else { side < 0.0 };
                    Curve::Circle {
                        c: centre,
                        r: if inward { big - r } else { big + r },
                    }
                }
            };
            let guess = corner + (t2 - t1).unit() * r;
            let Some(c) = intersect(offset(s1), offset(s2), guess, 0.0) else {
                return Err("no round of that radius touches both moves");
            };
            let foot = |s: &Seg| match s.arc_of() {
                None => c - s.tangent(false).left() * (side * r),
                Some((centre, _)) => centre + (c - centre).unit() * centre.dist(corner),
            };
            (foot(s1), foot(s2), Some((c, cross > 0.0)))
        }
    };
    if !on_seg(s1, p1) || !on_seg(s2, p2) {
        return Err("it is longer than one of the two moves");
    }
    Ok(CornerCut { p1, p2, arc })
}

/// Whether `p` (on the element's line or circle) lies between its ends.
fn on_seg(s: &Seg, p: P2) -> bool {
    match s.arc_of() {
        None => {
            let d = s.end() - s.start();
            let t = (p - s.start()).dot(d);
            t >= -OVERRUN_MM && t <= d.dot(d) + OVERRUN_MM * d.hypot()
        }
        Some((c, ccw)) => {
            let sweep = |a: P2, b: P2| {
                let x = (a - c).angle_to(b - c);
                let x = if ccw { x } else { -x };
                if x < 0.0 {
                    x + std::f64::consts::TAU
                } else {
                    x
                }
            };
            let whole = match sweep(s.start(), s.end()) {
                x if x <= 0.0 => std::f64::consts::TAU,
                x => x,
            };
            sweep(s.start(), p) <= whole + OVERRUN_MM / c.dist(p).max(ZERO_MM)
        }
    }
}

impl<'a> Machining<'_, 'a> {
    /// A G01 with `,C` or `,R`: hold it until the next block.
    pub(crate) fn hold_corner(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        feed: Feed,
        goal: &Goal,
        arc: Option<(Pos, bool)>,
    ) -> Result<(), Diagnostic> {
        let (kind, word) = match (w.get_ext(Addr::COMMA_C), w.get_ext(Addr::COMMA_R)) {
            (Some(_), Some(r)) => return Err(alarms::corner_fault(r.span, "both ,C and ,R")),
            (Some(c), None) => (CornerKind::Chamfer(self.units().length_mm(&c)), c),
            (None, Some(r)) => (CornerKind::Round(self.units().length_mm(&r)), r),
            (None, None) => return Ok(()),
        };
        if goal.named == 0 {
            return Err(alarms::corner_fault(word.span, "the G01 has no end point"));
        }
        if word.value <= 0.0 {
            // Known here already: say so at the word, not at the next block.
            return Err(alarms::corner_fault(
                word.span,
                "the chamfer or radius is not positive",
            ));
        }
        if self.state.lathe.corner.is_some() {
            // The corner held before this G01 is cut first.
            let kind = match arc {
                Some((c, cw)) => {
                    let here = self.state.prog;
                    let mut offset = Pos::default();
                    for i in 0..vcnc_core::events::MAX_AXES {
                        offset.set(i, c.get(i) - here.get(i));
                    }
                    MoveKind::Arc {
                        offset,
                        plane: self.state.modal.plane,
                        cw,
                        feed,
                    }
                }
                None => MoveKind::Feed(feed),
            };
            let mv = Move {
                kind,
                to: Target::Program(goal.prog),
                exact_stop: false,
                cmd,
            };
            self.cut_corner(mv, w)?;
        }
        self.state.lathe.corner = Some(PendingCorner {
            kind,
            start: self.state.prog,
            feed,
            arc,
            cmd,
            word: word.span,
            line: self.at.loc().line,
            block_at: w.first.start,
            source_line: self.stage.cur_line,
        });
        self.state.prog = goal.prog;
        Ok(())
    }

    /// Before the move after a held G01: the G01 to P1 and the chamfer or
    /// round to P2 (with the held block's line).
    pub(crate) fn cut_corner(&mut self, mv: Move, w: &Words<'_>) -> Result<Move, Diagnostic> {
        let Some(held) = self.state.lathe.corner.take() else {
            return Ok(mv);
        };
        let corner = self.state.prog;
        let end = match (mv.kind, mv.to) {
            (MoveKind::Feed(_) | MoveKind::Arc { .. }, Target::Program(p)) => p,
            (MoveKind::Feed(_) | MoveKind::Arc { .. }, Target::Relative(d)) => corner.plus(d),
            _ => {
                return Err(alarms::corner_fault(
                    mv.cmd,
                    "the block after a ,C or ,R must be a G01, G02 or G03 move",
                ));
            }
        };
        let axes = self.cfg.plane_axes(self.state.modal.plane, mv.cmd)?;
        let ab = (axes.a, axes.b);
        let p = |q: Pos| P2::of(&q, ab);
        let off_plane = (0..vcnc_core::events::MAX_AXES)
            .filter(|&i| i != axes.a && i != axes.b)
            .any(|i| {
                (end.get(i) - corner.get(i)).abs() > ZERO_MM
                    || (corner.get(i) - held.start.get(i)).abs() > ZERO_MM
            });
        if off_plane {
            return Err(alarms::corner_fault(mv.cmd, "the moves leave the plane"));
        }
        let seg = |from: Pos, to: Pos, arc: Option<(Pos, bool)>| match arc {
            Some((c, cw)) => Seg::arc(p(from), p(to), p(c), !cw),
            None => Seg::line(p(from), p(to)),
        };
        let next_arc = match mv.kind {
            MoveKind::Arc { offset, cw, .. } => Some((corner.plus(offset), cw)),
            _ => None,
        };
        let cut = corner_cut_segs(
            &seg(held.start, corner, held.arc),
            &seg(corner, end, next_arc),
            held.kind,
        )
        .map_err(|why| alarms::corner_fault(mv.cmd, why))?;
        let at = |q: P2| q.placed(corner, ab);
        // The held block's moves carry its line (and its alarms its place).
        let line = self.at.set_line(held.line);
        let cur_line = std::mem::replace(&mut self.stage.cur_line, held.source_line);
        self.state.prog = held.start;
        let first_kind = match held.arc {
            Some((c, cw)) => MoveKind::Arc {
                offset: (p(c) - p(held.start)).placed(Pos::default(), ab),
                plane: self.state.modal.plane,
                cw,
                feed: held.feed,
            },
            None => MoveKind::Feed(held.feed),
        };
        let first = Move {
            kind: first_kind,
            to: Target::Program(at(cut.p1)),
            exact_stop: false,
            cmd: held.cmd,
        };
        let mut out = self.send(first, w);
        if out.is_ok() {
            let kind = match cut.arc {
                Some((c, ccw)) => {
                    let offset = (c - cut.p1).placed(Pos::default(), ab);
                    MoveKind::Arc {
                        offset,
                        plane: self.state.modal.plane,
                        cw: !ccw,
                        feed: held.feed,
                    }
                }
                None => MoveKind::Feed(held.feed),
            };
            let round = Move {
                kind,
                to: Target::Program(at(cut.p2)),
                exact_stop: false,
                cmd: held.cmd,
            };
            out = self.send(round, w);
        }
        self.at.set_line(line);
        let out = match (out, held.source_line) {
            (Err(d), Some((src, l))) => Err(self.at.locate(d, src, &l)),
            (out, _) => out,
        };
        self.stage.cur_line = cur_line;
        out?;
        // The next move starts where the chamfer or round ends: an arc's
        // centre offset counts from there.
        let kind = match (mv.kind, next_arc) {
            (
                MoveKind::Arc {
                    plane, cw, feed, ..
                },
                Some((c, _)),
            ) => MoveKind::Arc {
                offset: (p(c) - cut.p2).placed(Pos::default(), ab),
                plane,
                cw,
                feed,
            },
            (kind, _) => kind,
        };
        Ok(Move { kind, ..mv })
    }

    /// Under keep-going, after an alarm (the state is as it was before
    /// the alarmed block): a G01 still held for its corner runs straight
    /// to the corner, unrounded, so that the blocks after it are read as
    /// written instead of each alarming against the same stale corner, and
    /// the path keeps the move. A move that cannot be made is dropped and
    /// its alarm returned, placed at the held block.
    pub(crate) fn release_corner(&mut self) -> Option<Diagnostic> {
        let held = self.state.lathe.corner.take()?;
        let corner = self.state.prog;
        let block = vcnc_syntax::Block::default();
        let w = Words::new(&block);
        let line = self.at.set_line(held.line);
        let cur_line = std::mem::replace(&mut self.stage.cur_line, held.source_line);
        self.state.prog = held.start;
        let straight = Move {
            kind: MoveKind::Feed(held.feed),
            to: Target::Program(corner),
            exact_stop: false,
            cmd: held.cmd,
        };
        let dropped = match self.commit(straight, &w) {
            Ok(()) => None,
            Err(d) => {
                self.state.prog = corner;
                Some(match held.source_line {
                    Some((src, at)) => self.at.locate(d, src, &at),
                    None => d,
                })
            }
        };
        self.at.set_line(line);
        self.stage.cur_line = cur_line;
        dropped
    }

    /// At the end of the program (its last block being the G01 with the
    /// corner): the move it waits for never comes.
    pub(crate) fn check_corner_at_end(&self) -> Result<(), Diagnostic> {
        match self.state.lathe.corner {
            Some(held) => Err(alarms::corner_fault(
                held.word,
                "the program ends after this ,C or ,R",
            )),
            None => Ok(()),
        }
    }

    /// After a block's motion: a corner held by an earlier block that
    /// this block did not cut (it did not move with G01) alarms.
    pub(crate) fn check_corner_cut(&self, w: &Words<'_>) -> Result<(), Diagnostic> {
        match self.state.lathe.corner {
            Some(held) if (held.line, held.block_at) != (self.at.loc().line, w.first.start) => Err(
                alarms::corner_fault(w.first, "the block after a ,C or ,R must be a G01 move"),
            ),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(p: P2, q: P2) -> bool {
        p.dist(q) < 1e-12
    }

    #[test]
    fn chamfers_and_rounds_cut_back_both_lines_at_a_left_turn() {
        // +X to (10, 0), then +Y: a 90° turn to the left.
        let (a, corner, b) = (P2(0.0, 0.0), P2(10.0, 0.0), P2(10.0, 10.0));
        let cut = corner_cut(a, corner, b, CornerKind::Chamfer(2.0)).unwrap();
        assert!(close(cut.p1, P2(8.0, 0.0)) && close(cut.p2, P2(10.0, 2.0)));
        assert_eq!(cut.arc, None);
        // ,R2 at 90°: cut back r·tan 45° = 2, centre 2 to the left of P1.
        let cut = corner_cut(a, corner, b, CornerKind::Round(2.0)).unwrap();
        assert!(close(cut.p1, P2(8.0, 0.0)) && close(cut.p2, P2(10.0, 2.0)));
        let (c, ccw) = cut.arc.unwrap();
        assert!(close(c, P2(8.0, 2.0)) && ccw);
        // Turning right instead: the centre is to the right, clockwise.
        let cut = corner_cut(a, corner, P2(10.0, -10.0), CornerKind::Round(2.0)).unwrap();
        let (c, ccw) = cut.arc.unwrap();
        assert!(close(c, P2(8.0, -2.0)) && !ccw);
    }

    #[test]
    fn a_corner_that_is_not_one_is_refused() {
        let (a, corner) = (P2(0.0, 0.0), P2(10.0, 0.0));
        let chamfer = CornerKind::Chamfer(1.0);
        assert!(corner_cut(a, corner, P2(20.0, 0.0), chamfer).is_err());
        assert!(corner_cut(a, corner, P2(5.0, 0.0), chamfer).is_err());
        assert!(corner_cut(a, a, P2(5.0, 5.0), chamfer).is_err());
        let long = CornerKind::Chamfer(10.5);
        assert!(corner_cut(a, corner, P2(10.0, 10.0), long).is_err());
    }
}
