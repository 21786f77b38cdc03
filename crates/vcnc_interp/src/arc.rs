//! G02/G03: circular and helical interpolation in G17/G18/G19.
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
//! (Fanuc 0i). The swept path, including the circle's extreme points inside
//! the sweep, is checked against the travel limits.

use crate::alarms;
use crate::events::{ArcDir, Event, Feed, Plane, Pos};
use crate::interpreter::Interpreter;
use crate::sink::Sink;
use crate::words::Words;
use std::f64::consts::{FRAC_PI_2, TAU};
use vcnc_syntax::{Addr, Diagnostic, Span};

/// Below this a length is zero, mm.
const ZERO_MM: f64 = 1e-9;

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

/// A resolved arc in its plane: first/second axis coordinates.
struct Geometry {
    center: (f64, f64),
    radius: f64,
    /// Signed sweep, radians: positive counter-clockwise.
    sweep: f64,
    start_angle: f64,
}

impl Interpreter<'_> {
    /// One G02/G03 block (a block with no arc words only sets the mode).
    pub(crate) fn arc<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        cw: bool,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let plane = self.state.modal.plane;
        let [oa, ob] = center_letters(plane);
        let has_center = w.get(oa).is_some() || w.get(ob).is_some();
        let radius = self.radius_word(w);
        let (to, named) = self.target(w, self.state.modal.incremental);
        if named == 0 && !has_center && radius.is_none() {
            return Ok(());
        }
        let (ia, ib) = self.plane_axes(cmd)?;
        let feed = self.feed(cmd)?;
        let from = self.state.pos;
        let s = (from.get(ia), from.get(ib));
        let e = (to.get(ia), to.get(ib));
        let center = match radius {
            Some(r) => match self.center_from_radius(s, e, r, cw, cmd)? {
                Some(c) => c,
                // The lathe document: a chord longer than 2R is cut straight.
                None => return self.feed_to(to, feed, w, cmd, sink),
            },
            None if has_center => {
                let off = |l: u8| w.get(l).map_or(0.0, |word| self.length_mm(&word));
                (s.0 + off(oa), s.1 + off(ob))
            }
            None => return Err(alarms::arc_without_center(cmd, plane.as_str())),
        };
        self.emit_arc(from, to, center, cw, feed, w, cmd, sink)
    }

    /// The machine axes of the active plane's first and second axis.
    fn plane_axes(&self, cmd: Span) -> Result<(usize, usize), Diagnostic> {
        let plane = self.state.modal.plane;
        let [la, lb, _] = plane.letters();
        match (self.machine.axis_of(la), self.machine.axis_of(lb)) {
            (Some(ia), Some(ib)) => Ok((ia, ib)),
            _ => Err(alarms::arc_without_center(cmd, plane.as_str())),
        }
    }

    /// The arc's radius word: R (signed), or on the lathe `CR=` (a radius)
    /// or D (a diameter), with whether a too-long chord becomes a line.
    fn radius_word(&self, w: &Words<'_>) -> Option<Radius> {
        if let Some(r) = w.get(b'R') {
            let line_if_short = self.dialect.long_chord_is_line;
            return Some(Radius {
                mm: self.length_mm(&r),
                span: r.span,
                line_if_short,
            });
        }
        if let Some(cr) = w.get_ext(Addr::CR) {
            return Some(Radius {
                mm: self.length_mm(&cr),
                span: cr.span,
                line_if_short: false,
            });
        }
        w.get(b'D').map(|d| Radius {
            mm: self.length_mm(&d) / 2.0,
            span: d.span,
            line_if_short: false,
        })
    }

    /// Checks an arc with a known centre and sends it.
    #[allow(clippy::too_many_arguments)]
    fn emit_arc<S: Sink>(
        &mut self,
        from: Pos,
        to: Pos,
        center: (f64, f64),
        cw: bool,
        feed: Feed,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let plane = self.state.modal.plane;
        let (ia, ib) = self.plane_axes(cmd)?;
        let s = (from.get(ia), from.get(ib));
        let e = (to.get(ia), to.get(ib));
        let geo = self.geometry(s, e, center, cw, cmd)?;
        self.check_arc(&geo, from, to, (ia, ib), w, cmd)?;
        let mut c = from;
        c.set(ia, center.0);
        c.set(ib, center.1);
        let dir = if cw { ArcDir::Cw } else { ArcDir::Ccw };
        let exact_stop = self.exact_stop(w);
        self.emit(sink, |loc| Event::Arc {
            loc,
            to,
            center: c,
            plane,
            dir,
            feed,
            exact_stop,
        });
        self.state.pos = to;
        Ok(())
    }

    /// Lathe G05: the arc from here through the middle point (IX, IZ) to
    /// the end point; its direction is the turn the three points make.
    pub(crate) fn three_point_arc<S: Sink>(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        sink: &mut S,
    ) -> Result<(), Diagnostic> {
        let (to, named) = self.target(w, self.state.modal.incremental);
        let mid_words = [(Addr::IX, b'X'), (Addr::IZ, b'Z')];
        if named == 0 && mid_words.iter().all(|(a, _)| w.get_ext(*a).is_none()) {
            return Ok(());
        }
        let (ia, ib) = self.plane_axes(cmd)?;
        let feed = self.feed(cmd)?;
        let from = self.state.pos;
        let mut mid = from;
        for (addr, letter) in mid_words {
            let (Some(word), Some(i)) = (w.get_ext(addr), self.machine.axis_of(letter)) else {
                continue;
            };
            let v = self.axis_value(i, &word);
            mid.set(
                i,
                if self.state.modal.incremental {
                    from.get(i) + v
                } else {
                    v + self.state.origin.get(i)
                },
            );
        }
        let (s, m, e) = (
            (from.get(ia), from.get(ib)),
            (mid.get(ia), mid.get(ib)),
            (to.get(ia), to.get(ib)),
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
        self.emit_arc(from, to, center, cross < 0.0, feed, w, cmd, sink)
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
        if h2 < 0.0 && chord - 2.0 * r.abs() > self.machine.params.arc_tolerance_mm {
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

    /// Radius, sweep and the on-circle check (E303, E304).
    fn geometry(
        &self,
        s: (f64, f64),
        e: (f64, f64),
        c: (f64, f64),
        cw: bool,
        cmd: Span,
    ) -> Result<Geometry, Diagnostic> {
        let r_start = (s.0 - c.0).hypot(s.1 - c.1);
        let r_end = (e.0 - c.0).hypot(e.1 - c.1);
        if r_start < ZERO_MM {
            return Err(alarms::zero_radius(cmd));
        }
        if (r_start - r_end).abs() > self.machine.params.arc_tolerance_mm {
            return Err(alarms::end_off_circle(cmd, r_start, r_end));
        }
        let a0 = (s.1 - c.1).atan2(s.0 - c.0);
        let a1 = (e.1 - c.1).atan2(e.0 - c.0);
        let full = (s.0 - e.0).hypot(s.1 - e.1) < ZERO_MM;
        let sweep = signed_sweep(a0, a1, full, cw);
        Ok(Geometry {
            center: c,
            radius: r_start,
            sweep,
            start_angle: a0,
        })
    }

    /// Travel check of the swept arc.
    fn check_arc(
        &self,
        g: &Geometry,
        from: Pos,
        to: Pos,
        axes: (usize, usize),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let (lo, hi) = swept_box(
            from,
            to,
            g.center,
            axes,
            g.start_angle,
            g.sweep,
            g.radius,
            self.machine.axes.len(),
        );
        self.check_box(lo, hi, w, cmd)
    }
}

/// Bounding box of an arc from `from` to `to`: its end points plus the
/// circle's extreme points (0°, 90°, 180°, 270°) that the sweep passes.
#[allow(clippy::too_many_arguments)]
fn swept_box(
    from: Pos,
    to: Pos,
    center: (f64, f64),
    (ia, ib): (usize, usize),
    start_angle: f64,
    sweep: f64,
    radius: f64,
    n_axes: usize,
) -> (Pos, Pos) {
    let mut lo = from;
    let mut hi = from;
    for i in 0..n_axes {
        lo.set(i, from.get(i).min(to.get(i)));
        hi.set(i, from.get(i).max(to.get(i)));
    }
    // Unit vectors of 0°, 90°, 180°, 270°, exact (no sin/cos rounding).
    const EXTREMES: [(f64, f64); 4] = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
    for (k, (cos, sin)) in (0u8..).zip(EXTREMES.iter()) {
        let phi = f64::from(k) * FRAC_PI_2;
        let passed = if sweep >= 0.0 {
            (phi - start_angle).rem_euclid(TAU) <= sweep
        } else {
            (start_angle - phi).rem_euclid(TAU) <= -sweep
        };
        if passed {
            let (a, b) = (center.0 + radius * cos, center.1 + radius * sin);
            lo.set(ia, lo.get(ia).min(a));
            hi.set(ia, hi.get(ia).max(a));
            lo.set(ib, lo.get(ib).min(b));
            hi.set(ib, hi.get(ib).max(b));
        }
    }
    (lo, hi)
}

/// Bounding box of an arc event's path, for sinks that report extents.
/// `axes` are the indices of the plane's first and second axis.
pub fn arc_bounds(
    from: Pos,
    to: Pos,
    center: Pos,
    axes: (usize, usize),
    dir: ArcDir,
    n_axes: usize,
) -> (Pos, Pos) {
    let (ia, ib) = axes;
    let c = (center.get(ia), center.get(ib));
    let (s, e) = ((from.get(ia), from.get(ib)), (to.get(ia), to.get(ib)));
    let radius = (s.0 - c.0).hypot(s.1 - c.1);
    let a0 = (s.1 - c.1).atan2(s.0 - c.0);
    let a1 = (e.1 - c.1).atan2(e.0 - c.0);
    let full = (s.0 - e.0).hypot(s.1 - e.1) < ZERO_MM;
    let sweep = signed_sweep(a0, a1, full, dir == ArcDir::Cw);
    swept_box(from, to, c, axes, a0, sweep, radius, n_axes)
}

/// The centre-offset letters of a plane's first and second axis.
fn center_letters(plane: Plane) -> [u8; 2] {
    match plane {
        Plane::Xy => [b'I', b'J'],
        Plane::Zx => [b'K', b'I'],
        Plane::Yz => [b'J', b'K'],
    }
}

/// The signed sweep from angle `a0` to `a1`: positive counter-clockwise,
/// a whole turn when start and end coincide (`full`).
fn signed_sweep(a0: f64, a1: f64, full: bool, cw: bool) -> f64 {
    let ccw = if full { TAU } else { (a1 - a0).rem_euclid(TAU) };
    if !cw {
        ccw
    } else if full {
        -TAU
    } else {
        ccw - TAU
    }
}
