//! The merged path: a bounded polyline (with true arcs) built one point at a
//! time, so that a 1,000,000-block program plots in bounded memory and time.
//!
//! Merging rule. Distances are measured in *merge units* — pixels of the
//! final picture for a flat view, 1/2048 of the model's size for the 3D page
//! (a [`Metric`]). The path keeps a vertex only where dropping it would move
//! the drawing by more than half a unit:
//!
//! ```text
//!   kept ●────○────○───○────● pending         ○ merged: each within ½ unit
//!   anchor     (at most 64 merged points)        of the chord anchor → next
//! ```
//!
//! - Consecutive straight moves of the same kind (rapid or cut), tool and
//!   colour merge while every point they replace lies within half a unit of
//!   the merged chord (a flat view also keeps the depth within half a
//!   colour step, so colours stay true).
//! - A move that ends within half a unit (on the screen) of the last point
//!   kept or pending is not drawn at all, whatever its kind: it cannot be
//!   seen (a drill's plunge seen from the top is a dot; the hole mark shows
//!   it). The pending point takes its source line and time.
//! - An arc stays one vertex (a true arc) unless it is flatter and shorter
//!   than half a unit; arcs are never merged with their neighbours.
//! - When the path holds more than its budget of vertices, the tolerance
//!   doubles and the stored path is merged again, so memory is bounded by
//!   construction whatever the program. A point merged at several levels
//!   stays within the sum of their tolerances (less than twice the last).
//!
//! A merged vertex keeps the source line, time and feed of the last point
//! it absorbs, so the viewer's slider steps over merged blocks together.

use crate::view::{P3, plane_indices};
use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_core::{ArcDir, Plane, Pos};

/// What the segment that ends at a vertex is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// No segment: the path starts (or, in a contour, restarts) here.
    Jump,
    /// A rapid positioning move.
    Rapid,
    /// A cutting move: feed, arc, thread or skip.
    Cut,
}

/// Marks a vertex whose segment is straight.
pub const NO_ARC: u32 = u32::MAX;

/// One vertex of the path and the segment that ends at it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Vertex {
    /// Where the segment ends, plot space.
    pub at: P3,
    /// What the segment is.
    pub kind: Kind,
    /// Index into [`Path::arcs`] when the segment is an arc, else [`NO_ARC`].
    pub arc: u32,
    /// Index into the plot's tools (0: before any tool change).
    pub tool: u16,
    /// 0 for the main program, `i` for the plot's `files[i - 1]`.
    pub file: u16,
    /// Source line of the (last) block drawn by the segment.
    pub line: u32,
    /// Feed of a cut, mm/min (0 when unknown or a rapid).
    pub feed_mm_per_min: f32,
    /// Time from the start of the program when the segment ends, s.
    pub time_s: f32,
}

/// The arc of an arc segment; its start is the previous vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcRec {
    /// Centre, plot space (its normal coordinate is the start's).
    pub center: P3,
    /// Plane.
    pub plane: Plane,
    /// Direction.
    pub dir: ArcDir,
}

/// A linear map from plot space into merge units; the first `visible` rows
/// are what the screen shows (the rest, a depth row, only keeps colours).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metric {
    /// Rows of the map.
    pub rows: [P3; 3],
    /// How many rows are screen geometry.
    pub visible: usize,
}

impl Metric {
    /// The point in merge units.
    pub(crate) fn apply(&self, p: P3) -> P3 {
        self.rows.map(|r| r[0] * p[0] + r[1] * p[1] + r[2] * p[2])
    }

    /// Screen length of a move in merge units.
    fn visible_len(&self, a: P3, b: P3) -> f64 {
        let (a, b) = (self.apply(a), self.apply(b));
        (0..self.visible.min(3))
            .map(|i| (a[i] - b[i]) * (a[i] - b[i]))
            .sum::<f64>()
            .sqrt()
    }

    /// Plot-space length of one merge unit along the coarsest visible row.
    pub fn unit_mm(&self) -> f64 {
        let mut unit = 0.0f64;
        for r in self.rows.iter().take(self.visible) {
            let n = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
            if n > 0.0 {
                unit = unit.max(1.0 / n);
            }
        }
        unit
    }
}

/// Half a merge unit: what merging may move the drawing by.
const HALF: f64 = 0.5;
/// Most points merged into one chord (bounds the work per point).
const MAX_RUN: usize = 64;

/// A merged, bounded path.
#[derive(Debug, Clone)]
pub struct Path {
    /// The kept vertices; the first is a [`Kind::Jump`].
    pub vertices: Vec<Vertex>,
    /// The arcs that vertices point to.
    pub arcs: Vec<ArcRec>,
    pending: Option<Vertex>,
    between: Vec<P3>,
    coarseness: f64,
    budget: usize,
    feed_breaks: bool,
}

/// Squared distance from `q` to the segment `a`–`b`.
fn seg_dist2(q: P3, a: P3, b: P3) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let aq = [q[0] - a[0], q[1] - a[1], q[2] - a[2]];
    let len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if len2 > 0.0 {
        ((aq[0] * ab[0] + aq[1] * ab[1] + aq[2] * ab[2]) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [aq[0] - t * ab[0], aq[1] - t * ab[1], aq[2] - t * ab[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

impl Path {
    /// An empty path that keeps at most about `budget` vertices; with
    /// `feed_breaks`, cuts at different feeds are not merged.
    pub fn new(budget: usize, feed_breaks: bool) -> Path {
        Path {
            vertices: Vec::new(),
            arcs: Vec::new(),
            pending: None,
            between: Vec::new(),
            coarseness: 1.0,
            budget: budget.max(16),
            feed_breaks,
        }
    }

    /// The merge tolerance in merge units (half a unit, doubled at each
    /// coarsening).
    pub fn tolerance(&self) -> f64 {
        HALF * self.coarseness
    }

    /// The last point, pending or kept.
    pub fn last(&self) -> Option<&Vertex> {
        self.pending.as_ref().or(self.vertices.last())
    }

    /// Adds a straight segment (or a jump) ending at `v`.
    pub fn push_line(&mut self, mut v: Vertex, m: &Metric) {
        v.arc = NO_ARC;
        self.push(v, m);
        self.bound(m);
    }

    /// Adds an arc segment ending at `v` (its start is the last point); a
    /// flat, short arc becomes a straight segment.
    pub fn push_arc(&mut self, mut v: Vertex, arc: ArcRec, m: &Metric) {
        let flat = match self.last() {
            Some(from) => self.is_flat(from.at, &v, &arc, m),
            None => true,
        };
        if flat {
            self.push_line(v, m);
            return;
        }
        match u32::try_from(self.arcs.len()) {
            Ok(i) if i != NO_ARC => {
                self.arcs.push(arc);
                v.arc = i;
            }
            _ => v.arc = NO_ARC,
        }
        self.push(v, m);
        self.bound(m);
    }

    /// Whether the arc from `from` to `v` is within tolerance of its chord
    /// and shorter than the tolerance: then it may be drawn straight.
    fn is_flat(&self, from: P3, v: &Vertex, arc: &ArcRec, m: &Metric) -> bool {
        let path = arc_path(from, v.at, arc);
        let mid = path.point_at(0.5);
        let mid = [mid.get(0), mid.get(1), mid.get(2)];
        let (a, b, q) = (m.apply(from), m.apply(v.at), m.apply(mid));
        let tol = self.tolerance();
        seg_dist2(q, a, b) <= tol * tol
            && path.sweep.abs() <= std::f64::consts::PI
            && m.visible_len(from, v.at) <= tol
    }

    /// The arc of vertex `i`, if its segment is one.
    pub fn arc_of(&self, i: usize) -> Option<ArcPath> {
        let v = self.vertices.get(i)?;
        let rec = self.arcs.get(usize::try_from(v.arc).ok()?)?;
        let from = self.vertices.get(i.checked_sub(1)?)?;
        Some(arc_path(from.at, v.at, rec))
    }

    fn push(&mut self, v: Vertex, m: &Metric) {
        let Some(mut p) = self.pending.take() else {
            self.pending = Some(v);
            return;
        };
        let tol = self.tolerance();
        // A step too short to see is not drawn: the pending point stands
        // for it (and takes its line and time, so the slider still steps
        // through it). Steps are measured from the pending point, so many
        // tiny steps never drift more than the tolerance.
        if v.kind != Kind::Jump && v.arc == NO_ARC && m.visible_len(p.at, v.at) < tol {
            if p.kind != Kind::Jump {
                p.line = v.line;
                p.file = v.file;
                p.time_s = v.time_s;
            }
            self.pending = Some(p);
            return;
        }
        let Some(anchor) = self.vertices.last().map(|a| a.at) else {
            self.vertices.push(p);
            self.pending = Some(v);
            return;
        };
        if self.mergeable(&p, &v) && self.fits(anchor, &p, v.at, m) {
            self.between.push(p.at);
            self.pending = Some(v);
            return;
        }
        self.vertices.push(p);
        self.between.clear();
        self.pending = Some(v);
    }

    fn mergeable(&self, p: &Vertex, v: &Vertex) -> bool {
        p.kind == v.kind
            && p.kind != Kind::Jump
            && p.arc == NO_ARC
            && v.arc == NO_ARC
            && p.tool == v.tool
            && (!self.feed_breaks || p.feed_mm_per_min.to_bits() == v.feed_mm_per_min.to_bits())
            && self.between.len() < MAX_RUN
    }

    /// Whether every point between the anchor and `to` (the merged ones and
    /// the pending one) is within tolerance of the chord anchor → `to`.
    fn fits(&self, anchor: P3, p: &Vertex, to: P3, m: &Metric) -> bool {
        let (a, b) = (m.apply(anchor), m.apply(to));
        let tol2 = self.tolerance() * self.tolerance();
        std::iter::once(&p.at)
            .chain(self.between.iter())
            .all(|q| seg_dist2(m.apply(*q), a, b) <= tol2)
    }

    /// Keeps the vertex count within the budget: doubles the tolerance and
    /// merges the kept path again until it fits in three quarters of it.
    fn bound(&mut self, m: &Metric) {
        // Each round at least halves what can still be told apart; 64
        // doublings exceed any extent in f64, where everything merges.
        if self.vertices.len() < self.budget {
            return;
        }
        for _ in 0..64 {
            self.coarseness *= 2.0;
            let old = std::mem::take(&mut self.vertices);
            let pending = self.pending.take();
            self.between.clear();
            let arcs = std::mem::take(&mut self.arcs);
            for v in old.into_iter().chain(pending) {
                self.replay(v, &arcs, m);
            }
            if self.vertices.len() < self.budget / 4 * 3 {
                break;
            }
        }
    }

    /// Pushes a kept vertex again after a coarsening, re-indexing its arc.
    fn replay(&mut self, mut v: Vertex, arcs: &[ArcRec], m: &Metric) {
        let arc = usize::try_from(v.arc)
            .ok()
            .and_then(|i| arcs.get(i))
            .copied();
        match arc {
            Some(rec) => {
                let flat = self
                    .last()
                    .is_none_or(|from| self.is_flat(from.at, &v, &rec, m));
                if flat {
                    v.arc = NO_ARC;
                } else if let Ok(i) = u32::try_from(self.arcs.len()) {
                    self.arcs.push(rec);
                    v.arc = i;
                }
                self.push(v, m);
            }
            None => {
                v.arc = NO_ARC;
                self.push(v, m);
            }
        }
    }

    /// The path is complete: keeps the pending point.
    pub fn finish(&mut self) {
        if let Some(p) = self.pending.take() {
            self.vertices.push(p);
        }
        self.between.clear();
    }
}

/// The [`ArcPath`] of an arc segment in plot space.
pub fn arc_path(from: P3, to: P3, rec: &ArcRec) -> ArcPath {
    let [a, b, n] = plane_indices(rec.plane);
    let pos = |p: P3| Pos([p[0], p[1], p[2], 0.0, 0.0, 0.0]);
    ArcPath::new(
        pos(from),
        pos(to),
        pos(rec.center),
        PlaneAxes { a, b, n: Some(n) },
        rec.dir,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_metric(px_mm: f64) -> Metric {
        Metric {
            rows: [
                [1.0 / px_mm, 0.0, 0.0],
                [0.0, 1.0 / px_mm, 0.0],
                [0.0, 0.0, 0.0],
            ],
            visible: 2,
        }
    }

    fn v(x: f64, y: f64, kind: Kind, line: u32) -> Vertex {
        Vertex {
            at: [x, y, 0.0],
            kind,
            arc: NO_ARC,
            tool: 0,
            file: 0,
            line,
            feed_mm_per_min: 100.0,
            time_s: 0.0,
        }
    }

    #[test]
    fn a_straight_run_of_short_cuts_becomes_one_segment() {
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        for i in 1..=50 {
            path.push_line(v(f64::from(i), 0.0, Kind::Cut, i + 1), &m);
        }
        path.finish();
        assert_eq!(path.vertices.len(), 2);
        assert_eq!(path.vertices[1].at, [50.0, 0.0, 0.0]);
        assert_eq!(
            path.vertices[1].line, 51,
            "the merged vertex keeps the last line"
        );
    }

    #[test]
    fn a_corner_is_kept_and_kinds_do_not_mix() {
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        path.push_line(v(10.0, 0.0, Kind::Rapid, 2), &m);
        path.push_line(v(20.0, 0.0, Kind::Cut, 3), &m);
        path.push_line(v(20.0, 10.0, Kind::Cut, 4), &m);
        path.push_line(v(20.0, 20.0, Kind::Cut, 5), &m);
        path.finish();
        let pts: Vec<_> = path
            .vertices
            .iter()
            .map(|v| (v.at[0], v.at[1], v.kind))
            .collect();
        assert_eq!(
            pts,
            vec![
                (0.0, 0.0, Kind::Jump),
                (10.0, 0.0, Kind::Rapid),
                (20.0, 0.0, Kind::Cut),
                (20.0, 20.0, Kind::Cut)
            ]
        );
    }

    #[test]
    fn a_bump_of_more_than_half_a_unit_is_kept() {
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        path.push_line(v(5.0, 0.4, Kind::Cut, 2), &m);
        path.push_line(v(10.0, 0.0, Kind::Cut, 3), &m);
        path.push_line(v(15.0, 0.6, Kind::Cut, 4), &m);
        path.push_line(v(20.0, 0.0, Kind::Cut, 5), &m);
        path.finish();
        // (5, 0.4) and (10, 0) are within ½ of the chord to (15, 0.6), but
        // (15, 0.6) is 0.6 from the chord to (20, 0): it is kept.
        let xs: Vec<f64> = path.vertices.iter().map(|v| v.at[0]).collect();
        assert_eq!(xs, vec![0.0, 15.0, 20.0]);
    }

    #[test]
    fn a_move_too_short_to_see_is_not_drawn_whatever_its_kind() {
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        path.push_line(v(10.0, 0.0, Kind::Rapid, 2), &m);
        // A plunge seen from the top: no visible length. The rapids on
        // either side of it are one straight line.
        path.push_line(v(10.0, 0.0, Kind::Cut, 3), &m);
        path.push_line(v(20.0, 0.0, Kind::Rapid, 4), &m);
        path.finish();
        let kinds: Vec<(f64, Kind)> = path.vertices.iter().map(|v| (v.at[0], v.kind)).collect();
        assert_eq!(kinds, vec![(0.0, Kind::Jump), (20.0, Kind::Rapid)]);
    }

    #[test]
    fn tiny_steps_do_not_drift() {
        // 100 steps of 0.1 unit: each too short to see, together 10 units.
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        for i in 1..=100u32 {
            path.push_line(v(f64::from(i) * 0.1, 0.0, Kind::Cut, i + 1), &m);
        }
        path.finish();
        let last = path.vertices.last().unwrap();
        assert!((last.at[0] - 10.0).abs() <= 0.5, "{:?}", last.at);
        assert_eq!(last.line, 101, "the slider reaches the last block");
    }

    #[test]
    fn the_budget_bounds_a_path_that_never_merges() {
        // A zig-zag whose every corner is 10 units away from its chord.
        let m = unit_metric(1.0);
        let mut path = Path::new(1000, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        for i in 1..200_000u32 {
            let y = if i % 2 == 0 { 0.0 } else { 10.0 };
            path.push_line(v(f64::from(i), y, Kind::Cut, i), &m);
            assert!(path.vertices.len() < 1000);
        }
        path.finish();
        // Once the tolerance passes the zig-zag's height it is one band.
        assert!(path.tolerance() > 10.0, "{}", path.tolerance());
        // The path ends within the tolerance of the last point.
        let end = path.vertices.last().map_or(0.0, |v| v.at[0]);
        assert!((end - 199_999.0).abs() <= path.tolerance(), "{end}");
    }

    #[test]
    fn alternating_kinds_are_bounded_too() {
        // A drilling pattern seen from the side: rapid, cut, rapid, cut …
        let m = unit_metric(1.0);
        let mut path = Path::new(500, false);
        path.push_line(v(0.0, 0.0, Kind::Jump, 1), &m);
        for i in 1..100_000u32 {
            let kind = if i % 2 == 0 { Kind::Rapid } else { Kind::Cut };
            let y = if i % 2 == 0 { 0.0 } else { -5.0 };
            path.push_line(v(f64::from(i / 2), y, kind, i), &m);
        }
        path.finish();
        assert!(path.vertices.len() <= 500, "{}", path.vertices.len());
    }

    #[test]
    fn a_visible_arc_stays_an_arc_and_a_tiny_one_becomes_a_line() {
        let m = unit_metric(0.1);
        let mut path = Path::new(1000, false);
        path.push_line(v(10.0, 0.0, Kind::Jump, 1), &m);
        let rec = ArcRec {
            center: [0.0, 0.0, 0.0],
            plane: Plane::Xy,
            dir: ArcDir::Ccw,
        };
        path.push_arc(v(0.0, 10.0, Kind::Cut, 2), rec, &m);
        // 0.001 mm of arc at 0.1 mm per unit: invisible.
        let a = 0.0001f64;
        let end = v(
            10.0 * (std::f64::consts::FRAC_PI_2 + a).cos(),
            10.0 * (std::f64::consts::FRAC_PI_2 + a).sin(),
            Kind::Cut,
            3,
        );
        path.push_arc(end, rec, &m);
        path.finish();
        assert_eq!(path.arcs.len(), 1);
        let arc = path.arc_of(1).unwrap();
        assert!((arc.sweep - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(path.vertices.iter().skip(2).all(|v| v.arc == NO_ARC));
    }
}
