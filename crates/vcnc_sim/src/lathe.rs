//! Turning: the stock's half-section (Z along the axis, r the radius) as
//! polygons, each move's swept nose region subtracted from it exactly
//! (`i_overlay`'s boolean difference), the part the section revolved.
//!
//! ```text
//!   r ▲   stock half-section            the nose circle (radius ρ, centre
//!     │ ┌──────────────────┐            the imaginary tip moved by the
//!     │ │            ◯━━━━━◯  ◀ swept   tip direction) swept along a move
//!     │ │                  │    nose    is a capsule: two half circles and
//!     │ └──────────────────┘            the band between them; an arc is
//!     └──────────────────────▶ z        cut as chords within 1 µm
//! ```
//!
//! The register gives an insert's nose radius and tip direction, not its
//! width or angles, so the insert is its nose plus a body that runs from
//! the nose away from the work — along +X for an outside tool (tips 3, 4,
//! 8), −X for an inside one (1, 2, 6), along Z for tips 5 and 7: the
//! cutting edge that rises from the nose is what removes a cut deeper than
//! the nose is wide, and the body's side stays in the air a cut leaves.
//! The swept region of that convex shape along a straight piece is the
//! convex hull of the shape at both ends.
//!
//! Circles are polygons whose chords stay within 1 µm of the circle
//! (inscribed: a hair less is removed, never more). Volumes are Pappus's:
//! V = 2π ∬ r dA, from each contour's first moment. A rapid is in the
//! stock when the nose shrunk by 0.01 mm still meets material.

use crate::kernel::Line;
use crate::motion::{Motion, Path};
use crate::report::{Collision, CollisionKind, Report};
use crate::tool::Insert;
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::single::SingleFloatOverlay;
use std::f64::consts::TAU;

/// A contour: (z, r) points, closed implicitly.
pub type Contour = Vec<[f64; 2]>;

/// Chord tolerance of nose circles, mm.
const NOSE_CHORD_MM: f64 = 1e-3;

/// The turning engine.
#[derive(Debug, Clone)]
pub struct Section {
    /// The material: shapes, each an outer contour then its holes.
    pub shapes: Vec<Vec<Contour>>,
    /// The spindle axis's X in tip coordinates.
    pub axis_x: f64,
    /// The work origin's Z in tip coordinates.
    pub origin_z: f64,
    /// The stock's volume, mm³.
    pub stock_mm3: f64,
    /// The stock's outline (z0, r0, z1, r1).
    pub stock_box: (f64, f64, f64, f64),
    bbox: (f64, f64, f64, f64),
    /// How far an insert's body reaches from its nose.
    body_mm: f64,
}

/// Signed area and first moment about the axis (∬ r dA) of a contour.
pub fn area_moment(c: &[[f64; 2]]) -> (f64, f64) {
    let (mut a, mut m) = (0.0, 0.0);
    for (k, p) in c.iter().enumerate() {
        let q = c[(k + 1) % c.len()];
        let cross = p[0] * q[1] - q[0] * p[1];
        a += cross;
        m += (p[1] + q[1]) * cross;
    }
    (a / 2.0, m / 6.0)
}

/// Area and volume of revolution of shapes.
pub fn measure(shapes: &[Vec<Contour>]) -> (f64, f64) {
    let (mut area, mut moment) = (0.0, 0.0);
    for shape in shapes {
        for (k, c) in shape.iter().enumerate() {
            let (a, m) = area_moment(c);
            let sign = if k == 0 { 1.0 } else { -1.0 };
            area += sign * a.abs();
            moment += sign * m.abs();
        }
    }
    (area, TAU * moment)
}

fn bbox_of(shapes: &[Vec<Contour>]) -> (f64, f64, f64, f64) {
    let mut b = (
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    );
    for p in shapes.iter().flatten().flatten() {
        b = (b.0.min(p[0]), b.1.min(p[1]), b.2.max(p[0]), b.3.max(p[1]));
    }
    b
}

/// Points of a circle of radius `r` about `c` whose chords stay within
/// 1 µm of it.
fn circle(c: [f64; 2], r: f64, out: &mut Vec<[f64; 2]>) {
    let step = 2.0 * (1.0 - NOSE_CHORD_MM / r).clamp(-1.0, 1.0).acos();
    let n = (TAU / step.max(1e-3)).ceil().clamp(8.0, 4000.0);
    let mut k = 0.0;
    while k < n {
        let t = TAU * k / n;
        out.push([c[0] + r * t.cos(), c[1] + r * t.sin()]);
        k += 1.0;
    }
}

/// The convex hull of `pts`, counter-clockwise (Andrew's monotone chain).
fn hull(mut pts: Vec<[f64; 2]>) -> Contour {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut lower: Vec<[f64; 2]> = Vec::new();
    for p in &pts {
        while lower.len() >= 2 && cross(lower[lower.len() - 2], lower[lower.len() - 1], *p) <= 0.0 {
            lower.pop();
        }
        lower.push(*p);
    }
    let mut upper: Vec<[f64; 2]> = Vec::new();
    for p in pts.iter().rev() {
        while upper.len() >= 2 && cross(upper[upper.len() - 2], upper[upper.len() - 1], *p) <= 0.0 {
            upper.pop();
        }
        upper.push(*p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// The region a nose of radius `r` with a body running `body` (a unit
/// vector times its length) sweeps from centre `a` to centre `b`.
pub fn sweep(a: [f64; 2], b: [f64; 2], r: f64, body: Option<[f64; 2]>) -> Contour {
    let mut pts = Vec::new();
    circle(a, r, &mut pts);
    circle(b, r, &mut pts);
    if let Some(d) = body {
        circle([a[0] + d[0], a[1] + d[1]], r, &mut pts);
        circle([b[0] + d[0], b[1] + d[1]], r, &mut pts);
    }
    hull(pts)
}

impl Section {
    /// A bar of `diameter` from `front_z` back `length`, bored to `bore`,
    /// about the axis at `axis_x` (tip coordinates).
    pub fn bar(
        axis_x: f64,
        origin_z: f64,
        front_z: f64,
        length: f64,
        diameter: f64,
        bore: f64,
    ) -> Section {
        let (z0, z1, r0, r1) = (front_z - length, front_z, bore / 2.0, diameter / 2.0);
        let shapes = vec![vec![vec![[z0, r0], [z1, r0], [z1, r1], [z0, r1]]]];
        let (_, stock_mm3) = measure(&shapes);
        Section {
            bbox: bbox_of(&shapes),
            shapes,
            axis_x,
            origin_z,
            stock_mm3,
            stock_box: (z0, r0, z1, r1),
            body_mm: 2.0 * (diameter + length) + 10.0,
        }
    }

    /// The volume removed so far, mm³.
    pub fn removed_mm3(&self) -> f64 {
        self.stock_mm3 - measure(&self.shapes).1
    }

    fn overlaps(&self, c: &[[f64; 2]]) -> bool {
        let b = bbox_of(&[vec![c.to_vec()]]);
        b.0 <= self.bbox.2 && b.2 >= self.bbox.0 && b.1 <= self.bbox.3 && b.3 >= self.bbox.1
    }

    /// Material inside contour `c`, mm².
    fn inside(&self, c: &Contour) -> f64 {
        if !self.overlaps(c) {
            return 0.0;
        }
        let common = self
            .shapes
            .overlay(c, OverlayRule::Intersect, FillRule::NonZero);
        measure(&common).0
    }

    /// Removes what the nose sweeps along `l` (tip coordinates); returns
    /// the area removed.
    fn subtract(&mut self, c: &Contour) -> f64 {
        if !self.overlaps(c) {
            return 0.0;
        }
        let before = measure(&self.shapes).0;
        self.shapes = self
            .shapes
            .overlay(c, OverlayRule::Difference, FillRule::NonZero);
        self.bbox = bbox_of(&self.shapes);
        before - measure(&self.shapes).0
    }

    /// The nose centre's (z, r) for a tip point.
    fn centre(&self, p: [f64; 3], insert: &Insert) -> [f64; 2] {
        let (cz, cx) = insert.tip_to_centre();
        [p[2] + cz, p[0] - self.axis_x + cx]
    }

    /// Cuts one move with `insert`, reporting a rapid in the stock and the
    /// time spent cutting air.
    pub fn add(&mut self, m: &Motion, insert: &Insert, report: &mut Report) {
        let pieces: Vec<Line> = match &m.path {
            Path::Arc(a) => {
                // Lathes have no Y, so arcs come as chords; an XY arc here
                // (a lathe machine file with Y) is cut as chords too.
                let mut prev = a.point_at(0.0);
                (1..=64)
                    .map(|k| {
                        let p = a.point_at(f64::from(k) / 64.0);
                        let l = Line { a: prev, b: p };
                        prev = p;
                        l
                    })
                    .collect()
            }
            _ => m.path.lines(),
        };
        let r = insert.nose_mm;
        let body = insert
            .body()
            .map(|(z, x)| [z * self.body_mm, x * self.body_mm]);
        let mut removed = 0.0;
        let mut struck = false;
        for l in &pieces {
            let (a, b) = (self.centre(l.a, insert), self.centre(l.b, insert));
            if !(a.iter().chain(&b).all(|v| v.is_finite())) {
                continue;
            }
            if m.rapid && !struck && r > 0.02 {
                struck = self.inside(&sweep(a, b, r - 0.01, body)) > 1e-9;
            }
            removed += self.subtract(&sweep(a, b, r, body));
        }
        if struck {
            let e = m.path.end();
            report.collide(Collision {
                line: m.loc.line,
                file: m.loc.file.clone(),
                kind: CollisionKind::RapidIntoStock,
                message: "a rapid cuts into the stock".to_string(),
                at: [2.0 * (e[0] - self.axis_x), 0.0, e[2] - self.origin_z],
                repeats: 0,
            });
        }
        if !m.rapid {
            if removed > 1e-9 {
                report.cutting_s += m.seconds;
            } else {
                report.air_cut_s += m.seconds;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_bar_revolves_to_its_cylinder() {
        let s = Section::bar(0.0, 0.0, 0.0, 100.0, 40.0, 10.0);
        let want = PI * (20.0f64.powi(2) - 5.0f64.powi(2)) * 100.0;
        assert!((s.stock_mm3 - want).abs() < 1e-6 * want);
    }

    #[test]
    fn a_capsule_has_the_area_of_its_sweep() {
        let c = sweep([0.0, 0.0], [10.0, 0.0], 1.0, None);
        let (a, _) = area_moment(&c);
        let want = 20.0 + PI;
        assert!(a > 0.0 && (a - want).abs() < 1e-3 * want, "{a}");
    }
}
