//! G02/G03: circular and helical interpolation in G17/G18/G19, resolved in
//! program coordinates before the arc is committed to the motion stage.
//!
//! ```text
//!        second axis            centre from I/J/K: c = start + (I,J)
//!            ▲   ● end          centre from R:     c = mid ± h·n̂,
//!            │  ╱                 h = √(R² − (d/2)²), n̂ ⟂ chord,
//!            │ ╱  c               + for G03 with R > 0 (arc ≤ 180°),
//!            ●────────▶ first     sign flipped for G02 and for R < 0
//!          start
//! ```
//!
//! Planes are named by their axes in rotation order (XY, ZX, YZ) so that
//! "counter-clockwise" always means looking from the positive normal axis.
//! The end point must lie on the circle within `arc_tolerance_mm` (E303);
//! a chord longer than 2R alarms (E302) unless within that tolerance, where
//! the arc becomes a half circle. R wins over I/J/K when both are written
//! (Fanuc 0i). I/J/K are offsets in program coordinates (never polar);
//! the frame then maps the centre like any other point.

use super::{MoveKind, Target};
use crate::alarms;
use crate::dialect::{ArcEnd, LongChord, bit};
use crate::interpreter::Machining;
use crate::motion::Goal;
use crate::state::frame::plane_rows;
use crate::words::Words;
use std::f64::consts::TAU;
use vcnc_core::events::{Plane, Pos};
use vcnc_core::geometry::ZERO_MM;
use vcnc_syntax::{Addr, Diagnostic, Span};

/// Most turns one G2/G3 P may ask for (each is an event of its block,
/// held until the block succeeds).
const MAX_TURNS: f64 = 10_000.0;

/// The radius an arc block gives.
#[derive(Debug, Clone, Copy)]
struct Radius {
    /// Signed radius, mm (negative: more than 180°).
    mm: f64,
    /// The word that gave it.
    span: Span,
    /// A chord longer than 2R is cut as a straight line instead of alarming.
    line_if_short: bool,
}

/// The program-coordinate indices of a plane's first and second axis.
#[derive(Debug, Clone, Copy)]
struct PlaneIdx {
    a: usize,
    b: usize,
}

/// rs274's length tolerance of an arc's two radii, mm under G21 and inches
/// under G20 (LinuxCNC's `center_arc_radius_tolerance`: 2·√2 least steps of
/// 0.01 mm or 0.001 in). Probed with rs274 2.9: under G21 a 1 mm arc runs
/// with radii 0.0282 mm apart and stops at 0.0284.
const RS274_ARC_TOL_MM: f64 = 0.01 * 2.0 * std::f64::consts::SQRT_2;
const RS274_ARC_TOL_INCH: f64 = 0.001 * 2.0 * std::f64::consts::SQRT_2;
/// Beyond that length, the part of the larger radius the two may differ by
/// (0.1 %: a 100 mm arc runs with its end 0.1001 mm outside, not inside).
const RS274_ARC_RATIO: f64 = 0.001;
/// And never by more than this many times the length (a 10,000 mm arc
/// stops at 2.84 mm).
const RS274_ARC_CAP: f64 = 100.0;

/// The centre-offset letters of a plane's first and second axis.
fn center_letters(plane: Plane) -> [u8; 2] {
    let (a, b) = plane_rows(plane);
    [b"IJK"[a], b"IJK"[b]]
}

impl<'a> Machining<'_, 'a> {
    /// One G02/G03 block (a block with no arc words only sets the mode).
    #[inline(never)]
    pub(crate) fn arc(&mut self, w: &Words<'_>, cmd: Span, cw: bool) -> Result<(), Diagnostic> {
        let plane = self.state.modal.plane;
        let [oa, ob] = center_letters(plane);
        let has_center = w.get(oa).is_some() || w.get(ob).is_some();
        let radius = self.radius_word(w);
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let (to, named) = (goal.prog, goal.named);
        if named == 0 && !has_center && radius.is_none() {
            return Ok(());
        }
        let turns = self.arc_turns(w)?;
        let idx = self.plane_idx(plane, cmd)?;
        let feed = self.feed(cmd)?;
        let from = self.state.prog;
        let s = (from.get(idx.a), from.get(idx.b));
        let e = (to.get(idx.a), to.get(idx.b));
        let center = match radius {
            Some(r) => match self.center_from_radius(s, e, r, cw, cmd)? {
                Some(c) => c,
                // The lathe document: a chord longer than 2R is cut straight.
                None => {
                    return self.straight(
                        MoveKind::Feed(feed),
                        self.state.move_target(&goal),
                        w,
                        cmd,
                    );
                }
            },
            None if has_center && self.state.modal.arc_absolute => {
                // G90.1: I/J/K are the centre's program coordinates; both
                // are needed (LinuxCNC).
                let (Some(i), Some(j)) = (w.get(oa), w.get(ob)) else {
                    return Err(alarms::arc_without_center(cmd, plane.as_str()));
                };
                (self.units().length_mm(&i), self.units().length_mm(&j))
            }
            None if has_center => {
                let off = |l: u8| w.get(l).map_or(0.0, |word| self.units().length_mm(&word));
                (s.0 + off(oa), s.1 + off(ob))
            }
            None => return Err(alarms::arc_without_center(cmd, plane.as_str())),
        };
        if turns > 1 {
            return self.multi_turn_arc(goal, center, cw, turns, w, cmd);
        }
        self.commit_arc(goal, center, cw, w, cmd)
    }

    /// LinuxCNC's G2/G3 P, the number of turns: a whole number from 1 (as
    /// rs274 wants: "P value should be 1 or greater with G2 or G3", "P
    /// value not an integer"), at most `MAX_TURNS`; 1 without P.
    fn arc_turns(&self, w: &Words<'_>) -> Result<u32, Diagnostic> {
        let reads_p = self.cfg.dialect.arc_letters & bit(b'P') != 0;
        let Some(p) = w.get(b'P').filter(|_| reads_p) else {
            return Ok(1);
        };
        crate::words::whole(
            &p,
            b'P',
            1.0,
            MAX_TURNS,
            "P is the arc's number of turns, a whole number from 1 to 10000",
        )
    }

    /// G2/G3 P n (n > 1, LinuxCNC): n − 1 full circles, then the arc to its
    /// end point, as rs274's one `ARC_FEED(…, turns, …)` runs:
    ///
    /// ```text
    ///   P3, Z from z0 to z1:   circle   circle   last arc (sweep θ)
    ///   normal axis at each    z0+Δ·2π/T  z0+Δ·4π/T   z1      T = 2·2π + θ
    /// ```
    ///
    /// The axes off the plane (the helix's normal axis and any other) move
    /// linearly with the angle turned, over the whole path, as LinuxCNC's
    /// helix does (its motion plans one circle segment of T radians, the
    /// normal axis proportional to the angle). Each circle ends where the
    /// arc started in the plane; every piece is an `arc` event, so the
    /// planner, the flattened G-code and the plots see plain arcs.
    fn multi_turn_arc(
        &mut self,
        goal: Goal,
        center: (f64, f64),
        cw: bool,
        turns: u32,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let plane = self.state.modal.plane;
        let idx = self.plane_idx(plane, cmd)?;
        let (from, to) = (self.state.prog, goal.prog);
        let s = (from.get(idx.a), from.get(idx.b));
        let e = (to.get(idx.a), to.get(idx.b));
        self.check_on_circle(s, e, center, cmd)?;
        let last = self.arc_path(to, center, cw, plane, cmd)?;
        let circles = f64::from(turns - 1);
        let total = circles * TAU + last.sweep.abs();
        let feed = if self.state.modal.inverse_time {
            // F is the inverse of the whole move's minutes.
            let len = (last.radius * total).hypot(last.rise());
            self.inverse_time_feed(w, cmd, len)?
        } else {
            self.feed(cmd)?
        };
        let mut offset = Pos::default();
        offset.set(idx.a, center.0 - s.0);
        offset.set(idx.b, center.1 - s.1);
        let kind = MoveKind::Arc {
            offset,
            plane,
            cw,
            feed,
        };
        for k in 1..turns {
            let f = f64::from(k) * TAU / total;
            let mut p = from;
            for i in (0..vcnc_core::events::MAX_AXES).filter(|&i| i != idx.a && i != idx.b) {
                p.set(i, from.get(i) + (to.get(i) - from.get(i)) * f);
            }
            self.straight(kind, Target::Program(p), w, cmd)?;
        }
        // The program point, not an increment: the circles have moved the
        // tool (no LinuxCNC code detaches the program point from it).
        self.straight(kind, Target::Program(to), w, cmd)
    }

    /// The arc from the program point to `to` about `center` (the plane's
    /// two coordinates; the other axes at the start point's).
    fn arc_path(
        &self,
        to: Pos,
        center: (f64, f64),
        cw: bool,
        plane: Plane,
        cmd: Span,
    ) -> Result<vcnc_core::geometry::ArcPath, Diagnostic> {
        let axes = self.cfg.plane_axes(plane, cmd)?;
        let from = self.state.prog;
        let mut c = from;
        c.set(axes.a, center.0);
        c.set(axes.b, center.1);
        let dir = if cw {
            vcnc_core::events::ArcDir::Cw
        } else {
            vcnc_core::events::ArcDir::Ccw
        };
        Ok(vcnc_core::geometry::ArcPath::new(from, to, c, axes, dir))
    }

    /// Program indices of a plane's axes (E305 if the machine lacks one).
    fn plane_idx(&self, plane: Plane, cmd: Span) -> Result<PlaneIdx, Diagnostic> {
        let axes = self.cfg.plane_axes(plane, cmd)?;
        Ok(PlaneIdx {
            a: axes.a,
            b: axes.b,
        })
    }

    /// The arc's radius word: R (signed), or on the lathe `CR=` (a radius)
    /// or D (a diameter), with whether a too-long chord becomes a line.
    fn radius_word(&self, w: &Words<'_>) -> Option<Radius> {
        if let Some(r) = w.get(b'R') {
            return Some(Radius {
                mm: self.units().length_mm(&r),
                span: r.span,
                line_if_short: self.cfg.dialect.long_chord == LongChord::Line,
            });
        }
        // `CR=` and D behave like R (the lathe document: "the formats behave
        // alike"), a too-long chord included.
        let line_if_short = self.cfg.dialect.long_chord == LongChord::Line;
        if let Some(cr) = w.get_ext(Addr::CR) {
            return Some(Radius {
                mm: self.units().length_mm(&cr),
                span: cr.span,
                line_if_short,
            });
        }
        if self.cfg.dialect.arc_letters & bit(b'D') == 0 {
            // Elsewhere D is the cutter radius offset (G41/G42), not a diameter.
            return None;
        }
        w.get(b'D').map(|d| Radius {
            mm: self.units().length_mm(&d) / 2.0,
            span: d.span,
            line_if_short,
        })
    }

    /// Checks an arc with a known centre (program coordinates) and commits it.
    fn commit_arc(
        &mut self,
        goal: Goal,
        center: (f64, f64),
        cw: bool,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let plane = self.state.modal.plane;
        let idx = self.plane_idx(plane, cmd)?;
        let (from, to) = (self.state.prog, goal.prog);
        let s = (from.get(idx.a), from.get(idx.b));
        let e = (to.get(idx.a), to.get(idx.b));
        self.check_on_circle(s, e, center, cmd)?;
        let mut offset = Pos::default();
        offset.set(idx.a, center.0 - s.0);
        offset.set(idx.b, center.1 - s.1);
        let feed = if self.state.modal.inverse_time {
            let len = self.arc_path(to, center, cw, plane, cmd)?.length();
            self.inverse_time_feed(w, cmd, len)?
        } else {
            self.feed(cmd)?
        };
        if w.get_ext(Addr::COMMA_C).is_some() || w.get_ext(Addr::COMMA_R).is_some() {
            // `,C`/`,R` at the arc's end: the corner waits for the next block.
            let mut c = from;
            c.set(idx.a, center.0);
            c.set(idx.b, center.1);
            return self.hold_corner(w, cmd, feed, &goal, Some((c, cw)));
        }
        self.straight(
            MoveKind::Arc {
                offset,
                plane,
                cw,
                feed,
            },
            self.state.move_target(&goal),
            w,
            cmd,
        )
    }

    /// Lathe G05: the arc from here through the middle point (IX, IZ) to
    /// the end point; its direction is the turn the three points make.
    #[inline(never)]
    pub(crate) fn three_point_arc(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let (to, named) = (goal.prog, goal.named);
        let mid_words = [(Addr::IX, b'X'), (Addr::IZ, b'Z')];
        if named == 0 && mid_words.iter().all(|(a, _)| w.get_ext(*a).is_none()) {
            return Ok(());
        }
        let idx = self.plane_idx(self.state.modal.plane, cmd)?;
        self.feed(cmd)?;
        let from = self.state.prog;
        let mut mid = from;
        for (addr, letter) in mid_words {
            let (Some(word), Some(i)) = (w.get_ext(addr), self.cfg.machine.axis_of(letter)) else {
                continue;
            };
            let v = self.units().axis_value(&self.cfg.axis_words, i, &word);
            mid.set(
                i,
                if self.state.modal.incremental {
                    from.get(i) + v
                } else {
                    v
                },
            );
        }
        let (s, m, e) = (
            (from.get(idx.a), from.get(idx.b)),
            (mid.get(idx.a), mid.get(idx.b)),
            (to.get(idx.a), to.get(idx.b)),
        );
        let d = 2.0 * (s.0 * (m.1 - e.1) + m.0 * (e.1 - s.1) + e.0 * (s.1 - m.1));
        if d.abs() < ZERO_MM {
            return Err(alarms::three_points_on_a_line(cmd));
        }
        let sq = |p: (f64, f64)| p.0 * p.0 + p.1 * p.1;
        let center = (
            (sq(s) * (m.1 - e.1) + sq(m) * (e.1 - s.1) + sq(e) * (s.1 - m.1)) / d,
            (sq(s) * (e.0 - m.0) + sq(m) * (s.0 - e.0) + sq(e) * (m.0 - s.0)) / d,
        );
        // Turning left (positive cross product) from S→M to M→E is counter-clockwise.
        let cross = (m.0 - s.0) * (e.1 - m.1) - (m.1 - s.1) * (e.0 - m.0);
        self.commit_arc(goal, center, cross < 0.0, w, cmd)
    }

    /// Centre of an R arc; negative R takes the arc over 180°.
    fn center_from_radius(
        &self,
        s: (f64, f64),
        e: (f64, f64),
        radius: Radius,
        cw: bool,
        cmd: Span,
    ) -> Result<Option<(f64, f64)>, Diagnostic> {
        let (r, span) = (radius.mm, radius.span);
        let (dx, dy) = (e.0 - s.0, e.1 - s.1);
        let chord = dx.hypot(dy);
        if r.abs() < ZERO_MM {
            return Err(alarms::zero_radius(cmd));
        }
        if chord < ZERO_MM {
            return Err(alarms::r_full_circle(span));
        }
        let half = chord / 2.0;
        let h2 = r * r - half * half;
        if h2 < 0.0 && chord - 2.0 * r.abs() > self.cfg.machine.params.arc_tolerance_mm {
            if radius.line_if_short {
                return Ok(None);
            }
            return Err(alarms::radius_too_small(span, r.abs(), chord));
        }
        let h = h2.max(0.0).sqrt();
        // Left normal of the chord; G03 with R > 0 has its centre on the left.
        let (nx, ny) = (-dy / chord, dx / chord);
        let side = if cw { -1.0 } else { 1.0 } * r.signum();
        Ok(Some((
            s.0 + dx / 2.0 + side * h * nx,
            s.1 + dy / 2.0 + side * h * ny,
        )))
    }

    /// The on-circle checks (E303, E304).
    fn check_on_circle(
        &self,
        s: (f64, f64),
        e: (f64, f64),
        c: (f64, f64),
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let r_start = (s.0 - c.0).hypot(s.1 - c.1);
        let r_end = (e.0 - c.0).hypot(e.1 - c.1);
        if r_start < ZERO_MM {
            return Err(alarms::zero_radius(cmd));
        }
        let off = (r_start - r_end).abs();
        let beyond = match self.cfg.dialect.arc_end {
            ArcEnd::MachineTolerance => off > self.cfg.machine.params.arc_tolerance_mm,
            ArcEnd::Rs274 => {
                let tol = if self.state.modal.inch {
                    RS274_ARC_TOL_INCH * 25.4
                } else {
                    RS274_ARC_TOL_MM
                };
                off > RS274_ARC_CAP * tol
                    || (off > tol && off / r_start.max(r_end) > RS274_ARC_RATIO)
            }
        };
        if beyond {
            return Err(alarms::end_off_circle(cmd, r_start, r_end));
        }
        Ok(())
    }
}
