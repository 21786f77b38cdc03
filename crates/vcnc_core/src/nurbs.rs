//! NURBS curves (G06.2, Syntec 1.2.8): exact evaluation by de Boor's
//! algorithm in homogeneous coordinates, and flattening into chords within
//! a tolerance — shared by the interpreter (checks), the planner (the path
//! it follows) and the flattened G-code output, so that all follow one
//! curve.
//!
//! ```text
//!   C(u) = Σ N_i,p(u)·w_i·P_i / Σ N_i,p(u)·w_i        u in [t_p, t_n]
//!
//!   de Boor, degree p, span k (t_k ≤ u < t_k+1), on Q_i = (w_i·P_i, w_i):
//!     d_j ← Q_(j+k−p)                       j = 0..p
//!     for r = 1..p, j = p..r:  α = (u − t_(j+k−p)) / (t_(j+1+k−r) − t_(j+k−p))
//!                              d_j ← (1 − α)·d_(j−1) + α·d_j
//!     C(u) = d_p.xyz / d_p.w
//! ```
//!
//! Reference: Piegl & Tiller, *The NURBS Book* (2nd ed., 1997), A2.1 and
//! A4.1 (evaluated here without the basis functions). A curve is valid when
//! its order is 2–4, it has at least `order` control points and `n + order`
//! non-decreasing knots clamped at both ends (the first and last `order`
//! knots equal, so the curve starts at the first control point and ends at
//! the last, as Fanuc requires), and positive weights.

use crate::events::{MAX_AXES, Nurbs, Pos};

/// Most control points one curve may have (memory bound).
pub const MAX_NURBS_POINTS: usize = 10_000;

/// Most chords one curve is flattened into.
pub const MAX_NURBS_CHORDS: usize = 100_000;

impl Nurbs {
    /// Why the definition is not a curve, if it is not.
    pub fn check(&self) -> Result<(), &'static str> {
        let order = usize::from(self.order);
        let n = self.points.len();
        if !(2..=4).contains(&order) {
            return Err("the order P is 2, 3 or 4");
        }
        if n < order {
            return Err("a curve of order P needs at least P control points");
        }
        if n > MAX_NURBS_POINTS {
            return Err("more than 10,000 control points");
        }
        if self.weights.len() != n {
            return Err("every control point has one weight");
        }
        if self.knots.len() != n + order {
            return Err("n control points need n + P knots");
        }
        if self.knots.iter().any(|k| !k.is_finite()) || self.knots.windows(2).any(|w| w[1] < w[0]) {
            return Err("the knots must not decrease");
        }
        if self.weights.iter().any(|w| !(w.is_finite() && *w > 0.0)) {
            return Err("weights must be positive");
        }
        let (first, last) = (self.knots[0], self.knots[n + order - 1]);
        if self.knots[..order].iter().any(|k| *k != first)
            || self.knots[n..].iter().any(|k| *k != last)
        {
            return Err("the first P and the last P knots must be equal (a clamped curve)");
        }
        if last <= first {
            return Err("the knots span no interval");
        }
        Ok(())
    }

    /// The parameter interval of the curve.
    pub fn domain(&self) -> (f64, f64) {
        let p = usize::from(self.order).saturating_sub(1);
        let n = self.points.len();
        (
            self.knots.get(p).copied().unwrap_or(0.0),
            self.knots.get(n).copied().unwrap_or(0.0),
        )
    }

    /// The point at parameter `u` (clamped to the domain). The curve must
    /// have passed [`Nurbs::check`]; otherwise the first control point.
    pub fn point(&self, u: f64) -> Pos {
        let first = self.points.first().copied().unwrap_or_default();
        if self.check().is_err() {
            return first;
        }
        self.eval(u)
    }

    /// de Boor on a checked curve.
    fn eval(&self, u: f64) -> Pos {
        let p = usize::from(self.order) - 1;
        let n = self.points.len();
        let (lo, hi) = self.domain();
        let u = u.clamp(lo, hi);
        // The span k in p..n−1 with t_k ≤ u < t_(k+1); the last non-empty
        // span at the end of the domain.
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= u {
            k += 1;
        }
        let mut d = [[0.0f64; MAX_AXES + 1]; 4];
        for (j, dj) in d.iter_mut().enumerate().take(p + 1) {
            let i = j + k - p;
            let w = self.weights[i];
            for (slot, x) in dj.iter_mut().zip(self.points[i].0) {
                *slot = x * w;
            }
            dj[MAX_AXES] = w;
        }
        for r in 1..=p {
            for j in (r..=p).rev() {
                let t0 = self.knots[j + k - p];
                let t1 = self.knots[j + 1 + k - r];
                let alpha = if t1 > t0 { (u - t0) / (t1 - t0) } else { 0.0 };
                let prev = d[j - 1];
                for (x, q) in d[j].iter_mut().zip(prev) {
                    *x = (1.0 - alpha) * q + alpha * *x;
                }
            }
        }
        let w = d[p][MAX_AXES];
        let mut out = Pos::default();
        for (o, x) in out.0.iter_mut().zip(d[p]) {
            *o = x / w;
        }
        out
    }

    /// Points along the curve, the end included (the start is not), whose
    /// chords stay within `tolerance_mm` of it: the domain is split into
    /// equal steps, doubled until every chord's midpoint and quarter points
    /// are within the tolerance of the curve, at most
    /// [`MAX_NURBS_CHORDS`] chords.
    pub fn flatten(&self, tolerance_mm: f64) -> Vec<Pos> {
        if self.check().is_err() {
            return self.points.last().copied().into_iter().collect();
        }
        let tol = tolerance_mm.max(1e-6);
        let (lo, hi) = self.domain();
        let spans = self.points.len() - usize::from(self.order) + 1;
        let mut n = (4 * spans).max(8);
        loop {
            let ok = (0..n).all(|i| {
                let (a, b) = (
                    lo + (hi - lo) * i as f64 / n as f64,
                    lo + (hi - lo) * (i + 1) as f64 / n as f64,
                );
                let (pa, pb) = (self.eval(a), self.eval(b));
                [0.25, 0.5, 0.75].iter().all(|f| {
                    let m = self.eval(a + (b - a) * f);
                    distance_to_chord(&m, &pa, &pb) <= tol
                })
            });
            if ok || n * 2 > MAX_NURBS_CHORDS {
                break;
            }
            n *= 2;
        }
        (1..=n)
            .map(|i| {
                if i == n {
                    self.points.last().copied().unwrap_or_default()
                } else {
                    self.eval(lo + (hi - lo) * i as f64 / n as f64)
                }
            })
            .collect()
    }
}

fn distance_to_chord(m: &Pos, a: &Pos, b: &Pos) -> f64 {
    let (mut ab2, mut am_ab) = (0.0, 0.0);
    for i in 0..MAX_AXES {
        let ab = b.0[i] - a.0[i];
        ab2 += ab * ab;
        am_ab += (m.0[i] - a.0[i]) * ab;
    }
    let t = if ab2 > 0.0 {
        (am_ab / ab2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut d2 = 0.0;
    for i in 0..MAX_AXES {
        let q = a.0[i] + t * (b.0[i] - a.0[i]) - m.0[i];
        d2 += q * q;
    }
    d2.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Pos {
        Pos([x, y, 0.0, 0.0, 0.0, 0.0])
    }

    /// The manual's example (1.2.8): order 3, knots 0 0 0 1 1 1, points
    /// (0,0) (0,5) (5,5), weights 1: a quadratic Bézier,
    /// C(u) = (1−u)²·P0 + 2u(1−u)·P1 + u²·P2.
    #[test]
    fn the_manual_example_is_a_quadratic_bezier() {
        let c = Nurbs {
            order: 3,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points: vec![p(0.0, 0.0), p(0.0, 5.0), p(5.0, 5.0)],
            weights: vec![1.0; 3],
        };
        assert_eq!(c.check(), Ok(()));
        for u in [0.0, 0.25, 0.5, 0.9, 1.0] {
            let q = c.point(u);
            let x = u * u * 5.0;
            let y = 2.0 * u * (1.0 - u) * 5.0 + u * u * 5.0;
            assert!(
                (q.get(0) - x).abs() < 1e-12 && (q.get(1) - y).abs() < 1e-12,
                "{u}"
            );
        }
        let pts = c.flatten(0.001);
        assert_eq!(pts.last(), Some(&p(5.0, 5.0)));
    }

    #[test]
    fn a_rational_quadratic_draws_a_quarter_circle() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let c = Nurbs {
            order: 3,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points: vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
            weights: vec![1.0, w, 1.0],
        };
        for i in 0..=20 {
            let q = c.point(f64::from(i) / 20.0);
            assert!((q.get(0).hypot(q.get(1)) - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn bad_definitions_are_named() {
        let good = Nurbs {
            order: 3,
            knots: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            points: vec![p(0.0, 0.0), p(0.0, 5.0), p(5.0, 5.0)],
            weights: vec![1.0; 3],
        };
        let mut c = good.clone();
        c.knots[3] = -1.0;
        assert!(c.check().is_err());
        let mut c = good.clone();
        c.weights[1] = 0.0;
        assert!(c.check().is_err());
        let mut c = good.clone();
        c.knots.pop();
        assert!(c.check().is_err());
        let mut c = good;
        c.order = 5;
        assert!(c.check().is_err());
    }
}
