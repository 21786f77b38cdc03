//! The swept envelope at one point: the lowest the bottom of the tool gets
//! over a grid cell's centre while the tip moves along a line, an arc or a
//! helix. This is what the Z-map lowers each cell to; it is computed per
//! cell, exactly for the tool's profile, never by stamping the tool at
//! sample points along the path.
//!
//! ```text
//!   tip path P(t) = A + t·(B − A),  t ∈ [0, 1]      (a line; an arc is the
//!                                                   same with an angle)
//!        A ●━━━━━━━━━━━━━━━━━━━━━━━● B              ρ(t): horizontal distance
//!            ╲    ρ(t)                              from the cell centre c to
//!             ╲                                     P(t)
//!              ● c
//!   bottom over c at t:  f(t) = z(t) + g(ρ(t))      (only where ρ(t) ≤ R)
//!   envelope at c:       min f(t) over the t where ρ(t) ≤ R
//! ```
//!
//! Along a line ρ(t) = √(d⊥² + |AB|²·(t − t_c)²) is convex in t, g is
//! convex and non-decreasing, and z(t) is linear, so f is convex on the
//! interval where the tool covers c, which is itself one interval
//! [t_c − s, t_c + s] ∩ [0, 1]. Hence:
//!
//! - level moves: f is smallest where ρ is, at the point of the segment
//!   nearest to c: z + g(ρ_min), closed form;
//! - flat end mill: f is linear, smallest at an end of the covering
//!   interval: closed form;
//! - ball end mill: f′(t) = 0 has the closed-form root
//!   t* = t_c − Δz·√(K / (L²(L² + Δz²))), K = R² − d⊥², clamped to the
//!   interval (the lowest point of the swept sphere on the cell's vertical);
//! - bull, drill and V: golden-section search on the convex f, to 1e-9 of
//!   the parameter (a nanometre on any move shorter than a metre).
//!
//! Along an arc of radius ρ_p about O, the cell at distance ρ_c from O at
//! angle φ is covered where cos(θ − φ) ≥ κ = (ρ_c² + ρ_p² − R²)/(2ρ_cρ_p):
//! one angular interval per turn. Level arcs take the angle nearest φ
//! (closed form), flat tools on a helix take an end of a covering interval
//! (closed form); other tools on a helix are minimised by sampling the
//! interval every 1/32 of it and refining the best sample's bracket by
//! golden section, which is exact where f is unimodal between samples
//! (docs/sim.md says where that can fail).

use crate::tool::Cutter;
use std::f64::consts::{PI, TAU};

/// A straight move of the tip, mm: `a` to `b` (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Start.
    pub a: [f64; 3],
    /// End.
    pub b: [f64; 3],
}

/// An arc or helix of the tip in the XY plane, mm and radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Centre X, Y.
    pub center: [f64; 2],
    /// Radius of the tip's path.
    pub radius: f64,
    /// Angle of the start point about the centre.
    pub start_angle: f64,
    /// Signed sweep: positive counter-clockwise.
    pub sweep: f64,
    /// Z at the start.
    pub z0: f64,
    /// Z travelled over the sweep (a helix when not zero).
    pub dz: f64,
}

/// Below this a length or a height difference is zero, mm.
const EPS: f64 = 1e-12;

/// The envelope of `cutter` along `line` over the point (`px`, `py`), or
/// `None` where the tool never covers the point.
pub fn line_envelope(px: f64, py: f64, line: &Line, cutter: &Cutter) -> Option<f64> {
    let r = cutter.radius;
    let [ax, ay, az] = line.a;
    let (dx, dy, dz) = (line.b[0] - ax, line.b[1] - ay, line.b[2] - az);
    let (wx, wy) = (px - ax, py - ay);
    let l2 = dx * dx + dy * dy;
    let w2 = wx * wx + wy * wy;
    if l2 < EPS * EPS {
        // A plunge or retract: the tool stands over the point.
        if w2 > r * r {
            return None;
        }
        return Some(az.min(line.b[2]) + cutter.g(w2.sqrt()));
    }
    let tc = (wx * dx + wy * dy) / l2;
    let d2 = (w2 - tc * tc * l2).max(0.0);
    if d2 > r * r {
        return None;
    }
    let s = ((r * r - d2) / l2).sqrt();
    let (t0, t1) = ((tc - s).max(0.0), (tc + s).min(1.0));
    if t0 > t1 {
        return None;
    }
    let rho = |t: f64| (d2 + l2 * (t - tc) * (t - tc)).sqrt();
    if dz.abs() < EPS {
        return Some(az + cutter.g(rho(tc.clamp(t0, t1))));
    }
    let f = |t: f64| az + dz * t + cutter.g(rho(t));
    Some(match cutter.profile {
        crate::tool::Profile::Flat => az + dz * if dz > 0.0 { t0 } else { t1 },
        crate::tool::Profile::Ball => {
            let k = (r * r - d2).max(0.0);
            let t = tc - dz * (k / (l2 * (l2 + dz * dz))).sqrt();
            f(t.clamp(t0, t1))
        }
        _ => golden(&f, t0, t1),
    })
}

/// The lowest value of the convex `f` on [`lo`, `hi`], by golden-section
/// search to 1e-9 of the parameter.
pub fn golden(f: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let mut best = f(lo).min(f(hi));
    let mut x1 = hi - INV_PHI * (hi - lo);
    let mut x2 = lo + INV_PHI * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    // 45 steps shrink any interval of [0, 1] below 1e-9.
    for _ in 0..45 {
        if hi - lo < 1e-9 {
            break;
        }
        if f1 <= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - INV_PHI * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + INV_PHI * (hi - lo);
            f2 = f(x2);
        }
    }
    best = best.min(f1).min(f2);
    best
}

/// The lowest value of `f` on [`lo`, `hi`] when it may not be convex:
/// `n` equal steps, then golden section between the best sample's
/// neighbours.
fn bracketed(f: &dyn Fn(f64) -> f64, lo: f64, hi: f64, n: u32) -> f64 {
    let step = (hi - lo) / f64::from(n);
    let (mut best_i, mut best) = (0u32, f(lo));
    for i in 1..=n {
        let v = f(lo + step * f64::from(i));
        if v < best {
            best = v;
            best_i = i;
        }
    }
    let a = lo + step * f64::from(best_i.saturating_sub(1));
    let b = (lo + step * f64::from(best_i + 1)).min(hi);
    best.min(golden(f, a, b))
}

impl Arc {
    /// The tip at fraction `t` of the sweep: x, y, z.
    pub fn point_at(&self, t: f64) -> [f64; 3] {
        let a = self.start_angle + self.sweep * t;
        [
            self.center[0] + self.radius * a.cos(),
            self.center[1] + self.radius * a.sin(),
            self.z0 + self.dz * t,
        ]
    }
}

/// The envelope of `cutter` along `arc` over the point (`px`, `py`), or
/// `None` where the tool never covers the point.
pub fn arc_envelope(px: f64, py: f64, arc: &Arc, cutter: &Cutter) -> Option<f64> {
    let r = cutter.radius;
    let (wx, wy) = (px - arc.center[0], py - arc.center[1]);
    let rc = wx.hypot(wy);
    let rp = arc.radius;
    if arc.sweep.abs() < EPS || rc * rp < EPS {
        // The tool's distance to the point does not change along the arc.
        let d = if arc.sweep.abs() < EPS {
            let p = arc.point_at(0.0);
            (px - p[0]).hypot(py - p[1])
        } else {
            (rc * rc + rp * rp).sqrt()
        };
        if d > r {
            return None;
        }
        return Some(arc.z0.min(arc.z0 + arc.dz) + cutter.g(d));
    }
    let kappa = (rc * rc + rp * rp - r * r) / (2.0 * rc * rp);
    if kappa > 1.0 {
        return None;
    }
    let alpha = if kappa <= -1.0 { PI } else { kappa.acos() };
    let phi = wy.atan2(wx);
    // Angles along the sweep as fractions t: θ(t) = start + sweep·t.
    let (th_lo, th_hi) = if arc.sweep > 0.0 {
        (arc.start_angle, arc.start_angle + arc.sweep)
    } else {
        (arc.start_angle + arc.sweep, arc.start_angle)
    };
    let t_of = |th: f64| ((th - arc.start_angle) / arc.sweep).clamp(0.0, 1.0);
    let dist = |t: f64| {
        let u = arc.start_angle + arc.sweep * t - phi;
        (rc * rc + rp * rp - 2.0 * rc * rp * u.cos())
            .max(0.0)
            .sqrt()
    };
    // The turns k whose covering window [φ + 2πk − α, φ + 2πk + α] may
    // meet the sweep's angles.
    let k_lo = ((th_lo - phi - alpha) / TAU).floor();
    let k_hi = ((th_hi - phi + alpha) / TAU).ceil();
    let mut best: Option<f64> = None;
    let mut k = k_lo;
    while k <= k_hi {
        let centre = phi + TAU * k;
        k += 1.0;
        let (lo, hi) = ((centre - alpha).max(th_lo), (centre + alpha).min(th_hi));
        if lo > hi {
            continue;
        }
        let (ta, tb) = {
            let (a, b) = (t_of(lo), t_of(hi));
            (a.min(b), a.max(b))
        };
        let v = if arc.dz.abs() < EPS {
            // Level: nearest angle to φ inside the window.
            let nearest = centre.clamp(lo, hi);
            arc.z0 + cutter.g(dist(t_of(nearest)))
        } else if matches!(cutter.profile, crate::tool::Profile::Flat) {
            arc.z0 + arc.dz * if arc.dz > 0.0 { ta } else { tb }
        } else {
            let f = |t: f64| arc.z0 + arc.dz * t + cutter.g(dist(t));
            bracketed(&f, ta, tb, 32)
        };
        best = Some(best.map_or(v, |b: f64| b.min(v)));
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tool::{Cutter, Profile};

    fn ball(r: f64) -> Cutter {
        Cutter {
            profile: Profile::Ball,
            ..Cutter::flat(1, r)
        }
    }

    /// The envelope by brute force: the tool at 200,001 points.
    fn dense_line(px: f64, py: f64, l: &Line, c: &Cutter) -> Option<f64> {
        let mut best: Option<f64> = None;
        for i in 0..=200_000 {
            let t = f64::from(i) / 200_000.0;
            let p = [
                l.a[0] + (l.b[0] - l.a[0]) * t,
                l.a[1] + (l.b[1] - l.a[1]) * t,
                l.a[2] + (l.b[2] - l.a[2]) * t,
            ];
            let rho = (px - p[0]).hypot(py - p[1]);
            if rho <= c.radius {
                let v = p[2] + c.g(rho);
                best = Some(best.map_or(v, |b: f64| b.min(v)));
            }
        }
        best
    }

    #[test]
    fn a_ball_on_a_ramp_matches_brute_force() {
        let l = Line {
            a: [0.0, 0.0, 0.0],
            b: [10.0, 0.0, -3.0],
        };
        let c = ball(3.0);
        for (px, py) in [
            (5.0, 0.0),
            (5.0, 2.0),
            (11.0, 1.0),
            (-1.0, 0.5),
            (12.9, 0.0),
        ] {
            let exact = line_envelope(px, py, &l, &c).unwrap();
            let dense = dense_line(px, py, &l, &c).unwrap();
            assert!(exact <= dense + 1e-9, "{px},{py}: {exact} > {dense}");
            assert!(dense - exact < 1e-6, "{px},{py}: {exact} vs {dense}");
        }
    }

    #[test]
    fn a_flat_tool_on_a_ramp_takes_the_low_end_of_its_cover() {
        let l = Line {
            a: [0.0, 0.0, 0.0],
            b: [10.0, 0.0, -1.0],
        };
        let c = Cutter::flat(1, 2.0);
        // Covered from x−2 to x+2: at x = 5 the lowest is where the tip is
        // at x = 7, z = −0.7.
        assert!((line_envelope(5.0, 0.0, &l, &c).unwrap() + 0.7).abs() < 1e-12);
        assert_eq!(line_envelope(5.0, 2.5, &l, &c), None);
    }

    #[test]
    fn a_ball_on_a_helix_matches_brute_force() {
        // One turn of radius 4 down 2 mm with a 3 mm ball: points on,
        // inside and outside the path's circle.
        let a = Arc {
            center: [0.0, 0.0],
            radius: 4.0,
            start_angle: 0.3,
            sweep: TAU,
            z0: 0.0,
            dz: -2.0,
        };
        let c = ball(3.0);
        for (px, py) in [(4.0, 0.0), (1.2, 0.2), (1.5, 1.0), (-6.5, 0.5), (2.0, -5.5)] {
            let exact = arc_envelope(px, py, &a, &c).unwrap();
            let mut dense = f64::INFINITY;
            for i in 0..=400_000 {
                let p = a.point_at(f64::from(i) / 400_000.0);
                let rho = (px - p[0]).hypot(py - p[1]);
                if rho <= c.radius {
                    dense = dense.min(p[2] + c.g(rho));
                }
            }
            assert!(exact <= dense + 1e-9, "{px},{py}: {exact} > {dense}");
            assert!(dense - exact < 1e-5, "{px},{py}: {exact} vs {dense}");
        }
    }

    #[test]
    fn a_helix_with_a_flat_tool_goes_down_with_the_turns() {
        // A full turn from z 0 to −1 of radius 5 with a 2 mm tool: the
        // point (5, 0) is last covered at the end (θ = 2π), z = −1.
        let a = Arc {
            center: [0.0, 0.0],
            radius: 5.0,
            start_angle: 0.0,
            sweep: TAU,
            z0: 0.0,
            dz: -1.0,
        };
        let c = Cutter::flat(1, 1.0);
        assert!((arc_envelope(5.0, 0.0, &a, &c).unwrap() + 1.0).abs() < 1e-9);
        // (−5, 0) is covered from θ = π − α to π + α, α = 2·asin(0.1).
        let alpha = 2.0 * (0.1f64).asin();
        let want = -(PI + alpha) / TAU;
        assert!((arc_envelope(-5.0, 0.0, &a, &c).unwrap() - want).abs() < 1e-9);
        assert_eq!(arc_envelope(0.0, 0.0, &a, &c), None);
    }
}
