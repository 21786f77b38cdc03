//! The geometry of one planned move: a straight line or an arc (helix) in
//! machine coordinates, parametrised by the distance `s` along it, with its
//! unit tangent and curvature — what the look-ahead needs for corner and
//! arc speeds, and what the trace samples. Arcs use the shared
//! [`vcnc_core::geometry::ArcPath`], so the planner follows exactly the
//! circle every other consumer draws.

use vcnc_core::geometry::{ArcPath, PlaneAxes, ZERO_MM};
use vcnc_core::{ArcDir, MAX_AXES, Plane, Pos};

/// A vector over the machine's axes.
pub type Vector = [f64; MAX_AXES];

/// A straight move or an arc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Straight line; the unit direction.
    Line(Vector),
    /// Arc or helix.
    Arc(ArcPath),
}

/// A move's path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    /// Start point.
    pub from: Pos,
    /// End point.
    pub to: Pos,
    /// Length, mm.
    pub len: f64,
    /// Line or arc.
    pub shape: Shape,
}

impl Path {
    /// The line from `from` to `to` over the first `n` axes; `None` when it
    /// has no length.
    pub fn line(from: Pos, to: Pos, n: usize) -> Option<Path> {
        let mut d = [0.0; MAX_AXES];
        for (i, di) in d.iter_mut().enumerate().take(n) {
            *di = to.get(i) - from.get(i);
        }
        let len = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        // `len ≤ f64::MAX`: finite, in one compare (see `ramp::finite`).
        if !(len > ZERO_MM && len <= f64::MAX) {
            return None;
        }
        for di in &mut d {
            *di /= len;
        }
        Some(Path {
            from,
            to,
            len,
            shape: Shape::Line(d),
        })
    }

    /// The arc from `from` to `to` about `center`; `None` when degenerate.
    pub fn arc(from: Pos, to: Pos, center: Pos, axes: PlaneAxes, dir: ArcDir) -> Option<Path> {
        let arc = ArcPath::new(from, to, center, axes, dir);
        let len = arc.length();
        if !(len > ZERO_MM && len.is_finite() && arc.radius > ZERO_MM) {
            return Path::line(from, to, MAX_AXES);
        }
        Some(Path {
            from,
            to,
            len,
            shape: Shape::Arc(arc),
        })
    }

    /// The point at distance `s` along the path.
    pub fn point(&self, s: f64) -> Pos {
        match &self.shape {
            Shape::Line(u) => {
                if s >= self.len {
                    return self.to;
                }
                let mut p = self.from;
                for (pi, ui) in p.0.iter_mut().zip(u) {
                    *pi += ui * s;
                }
                p
            }
            Shape::Arc(arc) => arc.point_at((s / self.len).clamp(0.0, 1.0)),
        }
    }

    /// The unit tangent (d point / ds) at distance `s`.
    #[inline]
    pub fn tangent(&self, s: f64) -> Vector {
        match &self.shape {
            Shape::Line(u) => *u,
            Shape::Arc(arc) => {
                let mut t = [0.0; MAX_AXES];
                for (i, ti) in t.iter_mut().enumerate() {
                    *ti = (arc.to.get(i) - arc.from.get(i)) / self.len;
                }
                let w = arc.sweep / self.len;
                let angle = arc.start_angle + w * (s / self.len).clamp(0.0, 1.0) * self.len;
                t[arc.axes.a] = -arc.radius * w * angle.sin();
                t[arc.axes.b] = arc.radius * w * angle.cos();
                t
            }
        }
    }

    /// The curvature vector (d² point / ds²) at distance `s`: zero on a line,
    /// towards the centre on an arc.
    pub fn curvature(&self, s: f64) -> Vector {
        let mut k = [0.0; MAX_AXES];
        if let Shape::Arc(arc) = &self.shape {
            let w = arc.sweep / self.len;
            let angle = arc.start_angle + w * s.clamp(0.0, self.len);
            k[arc.axes.a] = -arc.radius * w * w * angle.cos();
            k[arc.axes.b] = -arc.radius * w * w * angle.sin();
        }
        k
    }

    /// The magnitude of the curvature (1/radius of a circle, less on a helix).
    pub fn curvature_magnitude(&self) -> f64 {
        match &self.shape {
            Shape::Line(_) => 0.0,
            Shape::Arc(arc) => {
                let w = arc.sweep / self.len;
                arc.radius * w * w
            }
        }
    }

    /// The largest |d axis / ds| of each axis along the path: how fast each
    /// axis moves, at most, relative to the path speed.
    #[inline]
    pub fn axis_share(&self) -> Vector {
        match &self.shape {
            Shape::Line(u) => u.map(f64::abs),
            Shape::Arc(arc) => {
                let mut share = [0.0; MAX_AXES];
                for (i, si) in share.iter_mut().enumerate() {
                    *si = ((arc.to.get(i) - arc.from.get(i)) / self.len).abs();
                }
                let planar = arc.planar_length() / self.len;
                let (peak_sin, peak_cos) = arc.peak_sin_cos();
                share[arc.axes.a] = planar * peak_sin;
                share[arc.axes.b] = planar * peak_cos;
                share
            }
        }
    }

    /// The arc's plane axes, if it is an arc.
    pub fn plane(&self) -> Option<PlaneAxes> {
        match &self.shape {
            Shape::Line(_) => None,
            Shape::Arc(arc) => Some(arc.axes),
        }
    }
}

/// The axis indices of `plane` on a machine whose axis letters are `letters`.
pub fn plane_axes(plane: Plane, letters: &[u8]) -> Option<PlaneAxes> {
    let idx = |l: u8| letters.iter().position(|x| *x == l);
    let [a, b, n] = plane.letters();
    Some(PlaneAxes {
        a: idx(a)?,
        b: idx(b)?,
        n: idx(n),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tangent_of_a_quarter_arc_turns_by_ninety_degrees() {
        let axes = PlaneAxes {
            a: 0,
            b: 1,
            n: Some(2),
        };
        let p = |x, y| Pos([x, y, 0.0, 0.0, 0.0, 0.0]);
        let path = Path::arc(p(10.0, 0.0), p(0.0, 10.0), p(0.0, 0.0), axes, ArcDir::Ccw).unwrap();
        let t0 = path.tangent(0.0);
        let t1 = path.tangent(path.len);
        assert!((t0[0]).abs() < 1e-12 && (t0[1] - 1.0).abs() < 1e-12);
        assert!((t1[0] + 1.0).abs() < 1e-12 && t1[1].abs() < 1e-12);
        assert!((path.curvature_magnitude() - 0.1).abs() < 1e-12);
        let mid = path.point(path.len / 2.0);
        assert!((mid.get(0) - 10.0 / 2f64.sqrt()).abs() < 1e-9);
    }
}
