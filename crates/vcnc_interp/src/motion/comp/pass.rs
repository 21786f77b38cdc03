//! Moves through the compensation stage: the interpreter's side of
//! `Comp` — a move in the plane is held, the corner to the next one is
//! worked out (`geom.rs`), and the held move is released to the travel
//! check and the events; a lathe's nose shifts the path (`nose.rs`). The
//! stage's own data and its marks are `mod.rs`.

use super::geom::{self, Corner, Fault};
use super::nose::{self, tip_direction};
use super::{Held, Mode, Origin, Queued, v2, with_plane};
use crate::alarms;
use crate::dialect::CompStart;
use crate::interpreter::Machining;
use crate::motion::{MachineKind, MachineMove};
use crate::plane::{P2, Seg, ZERO_MM};
use vcnc_core::events::{Event, Plane, Pos};
use vcnc_core::geometry::PlaneAxes;
use vcnc_syntax::{Diagnostic, Span};

/// The held move's kind, about the entry arc's own centre if it has one.
fn entry_kind(held: &Held) -> MachineKind {
    match (held.mm.kind, held.centre) {
        (
            MachineKind::Arc {
                plane, dir, feed, ..
            },
            Some(c),
        ) => MachineKind::Arc {
            center: (c.0, c.1),
            plane,
            dir,
            feed,
        },
        (k, _) => k,
    }
}

/// A straight move of the same kind as `mm` (an arc's extra moves are feeds).
fn straight_kind(mm: &MachineMove) -> MachineKind {
    match mm.kind {
        MachineKind::Arc { feed, .. } => MachineKind::Feed(feed),
        MachineKind::Skip(feed) => MachineKind::Feed(feed),
        k => k,
    }
}

impl<'a> Machining<'_, 'a> {
    /// The plane geometry of a machine move, or `None` without plane motion.
    fn plane_seg(&self, mm: &MachineMove, axes: PlaneAxes) -> Option<Seg> {
        let (a, b) = (v2(mm.from, axes), v2(mm.to, axes));
        match mm.kind {
            MachineKind::Arc {
                center, plane, dir, ..
            } if plane == self.stage.comp.plane => Some(Seg::arc(
                a,
                b,
                P2(center.0, center.1),
                dir == vcnc_core::events::ArcDir::Ccw,
            )),
            _ if a.dist(b) > ZERO_MM => Some(Seg::line(a, b)),
            _ => None,
        }
    }

    /// Side (+1 left, −1 right) and radius in force for a move now.
    fn side_and_radius(&self) -> (f64, f64) {
        let mut side = match self.state.modal.comp {
            crate::state::CompSide::Left => 1.0,
            crate::state::CompSide::Right => -1.0,
            crate::state::CompSide::Off => 1.0,
        };
        let d = self.state.comp_d_mm;
        if d < 0.0 {
            side = -side;
        }
        if self.state.frame.mirrors(self.stage.comp.plane) {
            side = -side;
        }
        (side, d.abs())
    }

    /// Where the current block comes from.
    fn origin(&self, cmd: Span) -> Origin {
        Origin {
            loc: self.at.loc().clone(),
            src: self.stage.cur_line.map_or(0, |(s, _)| s),
            line: self.stage.cur_line.map(|(_, l)| l),
            cmd,
        }
    }

    /// An alarm about the block `at` (not necessarily the current one).
    fn alarm_at(&mut self, d: Diagnostic, at: &Origin) -> Diagnostic {
        match at.line {
            Some(line) => self.at.locate(d, at.src, &line),
            None => d,
        }
    }

    fn fault(&mut self, f: Fault, at: &Origin) -> Diagnostic {
        let d = match f {
            Fault::ArcTooSmall => alarms::comp_arc_too_small(at.cmd),
            Fault::NoIntersection => alarms::comp_overcut(at.cmd),
        };
        self.alarm_at(d, at)
    }

    /// Stage 2: a move while compensation is engaged.
    pub(crate) fn compensate(&mut self, mm: MachineMove, cmd: Span) -> Result<(), Diagnostic> {
        let axes = self.cfg.plane_axes(self.stage.comp.plane, cmd)?;
        let at = self.origin(cmd);
        if self.stage.comp.mode == Mode::Starting
            && self.cfg.dialect.comp_start == CompStart::LineOrArc
            && !matches!(mm.kind, MachineKind::Arc { .. })
        {
            // rs274: the first move after G41/G42 is the entry, also
            // without motion in the plane, and must be longer than r.
            let (_, r) = self.side_and_radius();
            // A radius of 0 (an empty register) offsets nothing: no entry.
            if r > ZERO_MM && v2(mm.from, axes).dist(v2(mm.to, axes)) <= r {
                return Err(alarms::comp_entry_short(cmd, r));
            }
        }
        let Some(seg) = self.plane_seg(&mm, axes) else {
            // No motion in the plane: it waits behind the held move.
            if self.stage.comp.held.is_some() {
                self.stage.comp.queue.push(Queued::Move(mm, at));
                return Ok(());
            }
            return self.release(mm, &at, None);
        };
        self.stage.comp.moved_in_plane = true;
        let entry_arc = seg.is_arc()
            && self.stage.comp.mode == Mode::Starting
            && self.cfg.dialect.comp_start == CompStart::LineOrArc;
        if seg.is_arc()
            && !entry_arc
            && matches!(self.stage.comp.mode, Mode::Starting | Mode::Cancelling)
        {
            return Err(alarms::comp_arc_startup(cmd));
        }
        let (side, r) = self.side_and_radius();
        seg.check(side, r).map_err(|f| self.fault(f, &at))?;
        match self.stage.comp.mode {
            Mode::Starting if entry_arc => {
                let Some((seg, centre)) = geom::entry_arc(&seg, side, r) else {
                    return Err(alarms::comp_entry_short(cmd, r));
                };
                self.stage.comp.mode = Mode::On;
                self.stage.comp.held = Some(Box::new(Held {
                    mm,
                    seg,
                    start: seg.start(),
                    lead_in: None,
                    side,
                    r,
                    startup: false,
                    shift: self.nose_shift(r),
                    centre: Some(centre),
                    at,
                }));
                Ok(())
            }
            Mode::Starting => {
                self.stage.comp.mode = Mode::On;
                self.stage.comp.held = Some(Box::new(Held {
                    mm,
                    seg,
                    start: seg.start(),
                    lead_in: None,
                    side,
                    r,
                    startup: true,
                    shift: self.nose_shift(r),
                    centre: None,
                    at,
                }));
                Ok(())
            }
            Mode::Cancelling => {
                let Some(held) = self.stage.comp.held.take() else {
                    self.stage.comp.mode = Mode::Off;
                    return self.release(mm, &at, None);
                };
                let end = self.settle_cancel(&held, &seg, &at)?;
                self.release_held(&held, end, None)?;
                self.stage.comp.mode = Mode::Off;
                self.release(mm, &at, None)
            }
            _ => {
                if let Some(h) = self.stage.comp.held.as_ref()
                    && seg.is_arc()
                    && !h.startup
                    && (h.r - r).abs() > ZERO_MM
                {
                    // The corner before it uses the old radius, its end the new.
                    return Err(alarms::comp_radius_change_on_arc(cmd, h.r, r));
                }
                self.advance(mm, seg, side, r, at)
            }
        }
    }

    /// Settles the corner between the held move and the next move in the
    /// plane (`mm`, `seg`, `side`, `r`, `at`), sends the held one and holds
    /// the next.
    fn advance(
        &mut self,
        mm: MachineMove,
        seg: Seg,
        side: f64,
        r: f64,
        at: Origin,
    ) -> Result<(), Diagnostic> {
        let Some(held) = self.stage.comp.held.as_deref() else {
            return Ok(());
        };
        // A corner the tool cannot reach is the fault of the block that
        // leads into it (the one being read, as the controller finds it).
        let corner = if held.startup {
            // The start-up ends where the next block's offset path starts.
            geom::startup(&held.seg, &seg, side, r).map(Corner::At)
        } else {
            geom::corner(&held.seg, held.side, &seg, side, held.r)
        };
        let corner = match corner {
            Ok(c) => c,
            Err(f) => return Err(self.fault(f, &at)),
        };
        // Where the held move ends (then on to an extension), where the
        // next one starts (after a lead-in).
        let (end, extension, start, lead_in) = match corner {
            Corner::At(p) => (p, None, p, None),
            Corner::Around { p1, l1, l2, p2 } => (p1, Some(l1), p2, Some(l2)),
        };
        self.stage.comp.idle_blocks = 0;
        let shift = self.nose_shift(r);
        // The next move is written into the box of the move the last block
        // replaced, field by field; the one leaving is kept until the next
        // block (see `Scratch`).
        let mut held = match self.stage.comp.scratch.prev.take() {
            Some(mut b) => {
                b.mm = mm;
                b.seg = seg;
                b.start = start;
                b.lead_in = lead_in;
                b.side = side;
                b.r = r;
                b.startup = false;
                b.shift = shift;
                b.centre = None;
                b.at = at;
                b
            }
            None => Box::new(Held {
                mm,
                seg,
                start,
                lead_in,
                side,
                r,
                startup: false,
                shift,
                centre: None,
                at,
            }),
        };
        let Some(slot) = self.stage.comp.held.as_mut() else {
            return Ok(());
        };
        std::mem::swap(slot, &mut held);
        let out = self.release_held(&held, end, extension);
        self.stage.comp.scratch.prev = Some(held);
        self.stage.comp.scratch.replaced = true;
        out
    }

    /// Where the held move ends before the cancel move `c`.
    #[inline(never)]
    fn settle_cancel(&mut self, held: &Held, c: &Seg, at: &Origin) -> Result<P2, Diagnostic> {
        if held.startup {
            // Cancelled right after the start-up: square to the start-up.
            return Ok(held.seg.perpendicular(true, held.side, held.r));
        }
        geom::cancel(&held.seg, c, held.side, held.r).map_err(|f| self.fault(f, at))
    }

    /// G40 without a move in the plane, the end of the program, or a move
    /// to a machine point: the held move ends square to its path.
    #[inline(never)]
    pub(crate) fn comp_finish(&mut self) -> Result<(), Diagnostic> {
        if let Some(held) = self.stage.comp.held.take() {
            let end = held.seg.perpendicular(true, held.side, held.r);
            self.release_held(&held, end, None)?;
        }
        self.stage.comp.mode = Mode::Off;
        self.stage.comp.idle_blocks = 0;
        Ok(())
    }

    /// Where the tool is once the held move and what waits behind it have
    /// left: a move to a machine point (G28, G53 …) keeps the axes it does
    /// not name there, not where the tool was when the stage began to hold.
    /// Compensation starts again with the next move in the plane.
    pub(crate) fn settled_tool_pos(&mut self) -> Result<Pos, Diagnostic> {
        if self.stage.comp.engaged() {
            self.comp_finish()?;
            if self.state.modal.comp != crate::state::CompSide::Off {
                self.stage.comp.mode = Mode::Starting;
            }
        }
        Ok(self.state.pos)
    }

    /// After the held move has ended square, a move to a machine point
    /// that leaves a plane axis where the tool is (`G53 Z0`) leaves the
    /// compensation vector on it: that axis keeps its programmed value
    /// (the uncompensated `mm.from`), so the vector never becomes part of
    /// the programmed position that later increments add to.
    #[inline(never)]
    pub(crate) fn keep_programmed_plane(
        &mut self,
        mm: &MachineMove,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.cfg.plane_axes(self.stage.comp.plane, cmd)?;
        let mut plain = mm.to;
        for i in [axes.a, axes.b] {
            if (mm.to.get(i) - self.state.pos.get(i)).abs() < ZERO_MM {
                plain.set(i, mm.from.get(i));
            }
        }
        self.state.nominal = plain;
        self.state.prog = self.state.frame.program_of(plain);
        Ok(())
    }

    /// Counts a block without motion in the plane while a move is held.
    pub(crate) fn comp_block_end(&mut self, first: Span) -> Result<(), Diagnostic> {
        if self.stage.comp.mode == Mode::Cancelling && !self.stage.comp.moved_in_plane {
            return self.comp_finish();
        }
        if self.stage.comp.held.is_some() && !self.stage.comp.moved_in_plane {
            self.stage.comp.idle_blocks += 1;
            let limit = self.cfg.machine.params.comp_lookahead_blocks;
            if self.stage.comp.idle_blocks > limit {
                return Err(alarms::comp_lookahead(first, limit));
            }
        }
        self.stage.comp.moved_in_plane = false;
        Ok(())
    }

    /// Sends the held move, compensated from its start to `end` (then on to
    /// `extension`), and what queued behind it.
    fn release_held(
        &mut self,
        held: &Held,
        end: P2,
        extension: Option<P2>,
    ) -> Result<(), Diagnostic> {
        // What leaves now goes out, not behind the move held in its place.
        self.stage.comp.releasing = true;
        let out = self.release_held_now(held, end, extension);
        self.stage.comp.releasing = false;
        out
    }

    fn release_held_now(
        &mut self,
        held: &Held,
        end: P2,
        extension: Option<P2>,
    ) -> Result<(), Diagnostic> {
        let axes = self.cfg.plane_axes(self.stage.comp.plane, held.at.cmd)?;
        if !held.startup && !held.seg.keeps_direction(held.start, end) {
            return Err(self.fault(Fault::NoIntersection, &held.at));
        }
        // The compensated points are the nose centre's; the controlled
        // point is `shift` from it (a lathe's imaginary tip).
        let tip = |q: P2| q + held.shift;
        let start_pos = with_plane(held.mm.from, axes, tip(held.start));
        let arc = match held.mm.kind {
            MachineKind::Arc {
                center, plane, dir, ..
            } => Some((
                with_plane(held.mm.from, axes, P2(center.0, center.1)),
                plane,
                dir,
            )),
            _ => None,
        };
        self.stage.pending.push(Event::Contour {
            loc: held.at.loc.clone(),
            from: held.mm.from,
            to: held.mm.to,
            arc,
        });
        if let Some(l2) = held.lead_in {
            // The joining move and the lead along the tangent (α < 90°).
            let kind = straight_kind(&held.mm);
            let join = MachineMove {
                kind,
                from: self.state.pos,
                to: with_plane(held.mm.from, axes, tip(l2)),
                exact_stop: false,
            };
            self.release(join, &held.at, None)?;
            if held.seg.is_arc() && l2.dist(held.start) > ZERO_MM {
                let lead = MachineMove {
                    to: start_pos,
                    ..join
                };
                self.release(lead, &held.at, None)?;
            }
        }
        // A line's extension (α < 90°) is the same straight line: one move.
        let (end, extension) = match extension {
            Some(l1) if !held.seg.is_arc() => (l1, None),
            other => (end, other),
        };
        let to = with_plane(held.mm.to, axes, tip(end));
        if let Some(mid) = held.seg.split(held.start, end) {
            // More than a turn: two events, half the sweep (and of the
            // helix's rise) each.
            let mut half = self.state.pos;
            for (h, t) in half.0.iter_mut().zip(to.0) {
                *h = (*h + t) / 2.0;
            }
            let first = MachineMove {
                from: self.state.pos,
                to: with_plane(half, axes, tip(mid)),
                kind: nose::shifted_kind(entry_kind(held), held.shift),
                ..held.mm
            };
            self.release(first, &held.at, None)?;
        }
        // An arc its corners shrink to a point leaves as a straight move.
        let kind = if held.seg.collapses(held.start, end) {
            straight_kind(&held.mm)
        } else {
            nose::shifted_kind(entry_kind(held), held.shift)
        };
        let moved = MachineMove {
            from: self.state.pos,
            to,
            kind,
            ..held.mm
        };
        self.release(moved, &held.at, None)?;
        if let Some(l1) = extension.filter(|l1| l1.dist(end) > ZERO_MM) {
            let ext = MachineMove {
                kind: straight_kind(&held.mm),
                from: to,
                to: with_plane(held.mm.to, axes, tip(l1)),
                exact_stop: false,
            };
            self.release(ext, &held.at, None)?;
        }
        if self.stage.comp.queue.is_empty() {
            return Ok(());
        }
        let mut queue = std::mem::take(&mut self.stage.comp.queue);
        for q in queue.drain(..) {
            match q {
                Queued::Move(mm, at) => {
                    let plane = v2(self.state.pos, axes);
                    let mm = MachineMove {
                        from: self.state.pos,
                        to: with_plane(mm.to, axes, plane),
                        ..mm
                    };
                    self.release(mm, &at, None)?;
                }
                Queued::Event(e) => self.stage.pending.push(e),
            }
        }
        // Keep the queue's buffer for the next block.
        self.stage.comp.queue = queue;
        Ok(())
    }

    /// The vector from the nose centre to the controlled point for a nose
    /// of radius `r`, in the compensation plane's (first, second) axes:
    /// the tip direction of the offset in force, in the ZX plane (G18),
    /// whose first axis is Z.
    pub(crate) fn nose_shift(&self, r: f64) -> P2 {
        if self.stage.comp.plane != Plane::Zx {
            return P2::default();
        }
        let (z, x) = tip_direction(self.state.lathe.tip);
        P2(z * r, x * r)
    }
}
