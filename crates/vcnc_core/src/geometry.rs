//! Path geometry every consumer of events shares: the sweep, length, bounds
//! and sampled points of an arc or helix, in one place so that the
//! interpreter's travel check, the summary's extents and the plotter's
//! drawing agree to the last bit.
//!
//! ```text
//!      b ▲          ● end          an arc lives in a plane (a, b) with the
//!        │      ╱                  normal axis n; angles are measured from
//!        │   ╱  sweep > 0 (ccw)    +a towards +b, so "counter-clockwise"
//!        │ c ────────● start       means seen from +n. A helix adds a
//!        └──────────────▶ a        straight move along n over the sweep.
//! ```
//!
//! Arcs are described by their start, end and centre in machine
//! coordinates plus the plane's axis indices; a full circle has its end
//! equal to its start.

use crate::events::{ArcDir, MAX_AXES, Pos};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Below this a length is zero, mm.
pub const ZERO_MM: f64 = 1e-9;

/// The axis indices of an arc's plane: first, second and (if the machine
/// has it) normal axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlaneAxes {
    /// First axis of the plane (X in G17).
    pub a: usize,
    /// Second axis of the plane (Y in G17).
    pub b: usize,
    /// The normal axis (Z in G17), if the machine has it.
    pub n: Option<usize>,
}

/// An arc resolved in its plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcPath {
    /// Start point (every axis).
    pub from: Pos,
    /// End point (every axis).
    pub to: Pos,
    /// Centre in the plane.
    pub center: (f64, f64),
    /// Radius at the start.
    pub radius: f64,
    /// Angle of the start point about the centre, radians.
    pub start_angle: f64,
    /// Signed sweep, radians: positive counter-clockwise; ±2π for a full circle.
    pub sweep: f64,
    /// The plane's axes.
    pub axes: PlaneAxes,
}

/// The signed sweep from angle `a0` to `a1`: positive counter-clockwise,
/// a whole turn when start and end coincide (`full`).
pub fn signed_sweep(a0: f64, a1: f64, full: bool, cw: bool) -> f64 {
    let ccw = if full { TAU } else { (a1 - a0).rem_euclid(TAU) };
    if !cw {
        ccw
    } else if full {
        -TAU
    } else {
        ccw - TAU
    }
}

impl ArcPath {
    /// The arc from `from` to `to` about `center` (a machine position; only
    /// its plane coordinates matter) in direction `dir`.
    pub fn new(from: Pos, to: Pos, center: Pos, axes: PlaneAxes, dir: ArcDir) -> ArcPath {
        let c = (center.get(axes.a), center.get(axes.b));
        let (s, e) = (
            (from.get(axes.a), from.get(axes.b)),
            (to.get(axes.a), to.get(axes.b)),
        );
        let radius = (s.0 - c.0).hypot(s.1 - c.1);
        let a0 = (s.1 - c.1).atan2(s.0 - c.0);
        let a1 = (e.1 - c.1).atan2(e.0 - c.0);
        let full = (s.0 - e.0).hypot(s.1 - e.1) < ZERO_MM;
        ArcPath {
            from,
            to,
            center: c,
            radius,
            start_angle: a0,
            sweep: signed_sweep(a0, a1, full, dir == ArcDir::Cw),
            axes,
        }
    }

    /// Travel along the normal axis (a helix), mm.
    pub fn rise(&self) -> f64 {
        self.axes
            .n
            .map_or(0.0, |n| self.to.get(n) - self.from.get(n))
    }

    /// Length of the path in the plane, mm.
    pub fn planar_length(&self) -> f64 {
        self.radius * self.sweep.abs()
    }

    /// Length of the whole path (helix included), mm. Other axes that move
    /// (a rotary axis along an arc) are not part of the path length.
    pub fn length(&self) -> f64 {
        self.planar_length().hypot(self.rise())
    }

    /// Whether the sweep passes the angle `phi` (radians).
    pub fn passes(&self, phi: f64) -> bool {
        if self.sweep >= 0.0 {
            (phi - self.start_angle).rem_euclid(TAU) <= self.sweep
        } else {
            (self.start_angle - phi).rem_euclid(TAU) <= -self.sweep
        }
    }

    /// The point at fraction `t` (0..=1) of the sweep, every axis (axes other
    /// than the plane's move linearly).
    pub fn point_at(&self, t: f64) -> Pos {
        let mut p = self.from;
        for i in 0..MAX_AXES {
            p.set(
                i,
                self.from.get(i) + (self.to.get(i) - self.from.get(i)) * t,
            );
        }
        let angle = self.start_angle + self.sweep * t;
        p.set(self.axes.a, self.center.0 + self.radius * angle.cos());
        p.set(self.axes.b, self.center.1 + self.radius * angle.sin());
        if t >= 1.0 {
            // The exact end point, free of the cosine's rounding.
            p.set(self.axes.a, self.to.get(self.axes.a));
            p.set(self.axes.b, self.to.get(self.axes.b));
        }
        p
    }

    /// Bounding box of the swept path: its end points plus the circle's
    /// extreme points (0°, 90°, 180°, 270°) that the sweep passes, for the
    /// first `n_axes` axes.
    pub fn bounds(&self, n_axes: usize) -> (Pos, Pos) {
        let mut lo = self.from;
        let mut hi = self.from;
        for i in 0..n_axes.min(MAX_AXES) {
            lo.set(i, self.from.get(i).min(self.to.get(i)));
            hi.set(i, self.from.get(i).max(self.to.get(i)));
        }
        // Unit vectors of 0°, 90°, 180°, 270°, exact (no sin/cos rounding).
        const EXTREMES: [(f64, f64); 4] = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)];
        for (k, (cos, sin)) in (0u8..).zip(EXTREMES.iter()) {
            if self.passes(f64::from(k) * FRAC_PI_2) {
                let (a, b) = (
                    self.center.0 + self.radius * cos,
                    self.center.1 + self.radius * sin,
                );
                let (ia, ib) = (self.axes.a, self.axes.b);
                lo.set(ia, lo.get(ia).min(a));
                hi.set(ia, hi.get(ia).max(a));
                lo.set(ib, lo.get(ib).min(b));
                hi.set(ib, hi.get(ib).max(b));
            }
        }
        (lo, hi)
    }

    /// The largest |sin| and |cos| of the angle along the sweep: how fast
    /// the plane's second and first axis move relative to the path speed in
    /// the plane, at their peak.
    pub fn peak_sin_cos(&self) -> (f64, f64) {
        let a1 = self.start_angle + self.sweep;
        let a0 = self.start_angle;
        let peak_sin = if self.passes(FRAC_PI_2) || self.passes(3.0 * FRAC_PI_2) {
            1.0
        } else {
            a0.sin().abs().max(a1.sin().abs())
        };
        let peak_cos = if self.passes(0.0) || self.passes(std::f64::consts::PI) {
            1.0
        } else {
            a0.cos().abs().max(a1.cos().abs())
        };
        (peak_sin, peak_cos)
    }

    /// Points along the arc whose chords stay within `tolerance_mm` of it,
    /// the end point included (the start point is not), at most `max` of them.
    pub fn tessellate(&self, tolerance_mm: f64, max: usize) -> impl Iterator<Item = Pos> + '_ {
        let tol = tolerance_mm.max(1e-6);
        // A chord of angle θ deviates r(1 − cos θ/2) from the arc.
        let step = if self.radius > tol {
            2.0 * (1.0 - tol / self.radius).clamp(-1.0, 1.0).acos()
        } else {
            std::f64::consts::PI
        };
        let wanted = (self.sweep.abs() / step.max(1e-9)).ceil();
        let cap = u32::try_from(max.max(1)).unwrap_or(u32::MAX);
        // Clamped to 1..=cap (a u32), so the conversion is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = if wanted.is_finite() {
            wanted.clamp(1.0, f64::from(cap)) as u32 as usize
        } else {
            cap as usize
        };
        (1..=n).map(move |k| self.point_at(k as f64 / n as f64))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn xy() -> PlaneAxes {
        PlaneAxes {
            a: 0,
            b: 1,
            n: Some(2),
        }
    }

    fn p(x: f64, y: f64, z: f64) -> Pos {
        Pos([x, y, z, 0.0, 0.0, 0.0])
    }

    #[test]
    fn a_quarter_circle_has_its_length_and_box() {
        let arc = ArcPath::new(
            p(10.0, 0.0, 0.0),
            p(0.0, 10.0, 0.0),
            p(0.0, 0.0, 0.0),
            xy(),
            ArcDir::Ccw,
        );
        assert!((arc.length() - 10.0 * FRAC_PI_2).abs() < 1e-12);
        let (lo, hi) = arc.bounds(3);
        assert_eq!(
            (lo.get(0), lo.get(1), hi.get(0), hi.get(1)),
            (0.0, 0.0, 10.0, 10.0)
        );
        // Clockwise the other way round covers three quadrants.
        let cw = ArcPath::new(
            p(10.0, 0.0, 0.0),
            p(0.0, 10.0, 0.0),
            p(0.0, 0.0, 0.0),
            xy(),
            ArcDir::Cw,
        );
        let (lo, _) = cw.bounds(3);
        assert_eq!((lo.get(0), lo.get(1)), (-10.0, -10.0));
    }

    #[test]
    fn a_full_helix_turns_once_and_rises() {
        let arc = ArcPath::new(
            p(5.0, 0.0, 0.0),
            p(5.0, 0.0, 3.0),
            p(0.0, 0.0, 0.0),
            xy(),
            ArcDir::Cw,
        );
        assert!((arc.sweep + TAU).abs() < 1e-12);
        assert!((arc.length() - (10.0 * std::f64::consts::PI).hypot(3.0)).abs() < 1e-9);
        let pts: Vec<Pos> = arc.tessellate(0.01, 10_000).collect();
        assert_eq!(pts.last().copied(), Some(arc.to));
        for q in &pts {
            assert!((q.get(0).hypot(q.get(1)) - 5.0).abs() < 1e-9);
        }
    }
}
