//! Per-axis limits turned into limits along a path: the highest speed,
//! acceleration and jerk of a move whose axes move in given proportions,
//! the speed limit of an arc from its centripetal acceleration, and the
//! speed at which a corner may be passed within the corner tolerance.
//!
//! Corners follow the junction-deviation model (Sonny Jeon, grbl, 2011;
//! here derived afresh): a corner of deflection θ between the unit tangents
//! u₁ and u₂ is taken as if rounded by the circle tangent to both paths that
//! passes at distance δ (the corner tolerance) from the corner point:
//!
//! ```text
//!        u₁ ───────────●╮ corner         R = δ·cos(θ/2) / (1 − cos(θ/2)),
//!                   δ ┆  ╲ ╮               at most (L/2)/tan(θ/2)
//!                      ╰──╮╲             v² = a_c·R   (centripetal limit)
//!                      ╰──╮╲             v³ = j_c·R²  (jerk limit, S-curve)
//!                   circle ╲ u₂
//! ```
//!
//! L is the shorter of the two moves: the rounding must fit in half of each,
//! which on a chain of short chords (a curve a CAM system flattened) limits
//! the speed to the curve's own centripetal limit. a_c and j_c are the
//! smallest axis limits scaled by how much of the
//! corner's plane each axis spans, so no axis exceeds its own limit
//! anywhere on that circle. The commanded path still goes through the
//! corner point (the interpolator's path); the servo's rounding stays within
//! δ because the speed is the circle's. Fanuc 0i calls this corner
//! deceleration by the allowable speed difference; the tolerance is the
//! more readable parameter, as on Syntec's and LinuxCNC's controllers.

use crate::path::Vector;
use crate::ramp::{Kin, finite};
use vcnc_core::{MAX_AXES, Machine};

/// An arc uses at most this share of the acceleration for the centripetal
/// part, leaving 0.6 for speeding up and slowing down (0.8² + 0.6² = 1, so
/// no axis exceeds its limit when both act).
pub const ARC_NORMAL_SHARE: f64 = 0.8;
/// The tangential share on an arc.
pub const ARC_TANGENT_SHARE: f64 = 0.6;

/// Below this a direction component is zero.
const TINY: f64 = 1e-12;

/// The machine's axis limits in mm and seconds.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisLimits {
    /// Number of axes.
    pub n: usize,
    /// Rapid rate, mm/s.
    pub rapid: Vector,
    /// Highest cutting feed, mm/s.
    pub max_feed: Vector,
    /// Acceleration, mm/s².
    pub accel: Vector,
    /// Jerk, mm/s³ (infinite under the trapezoid profile).
    pub jerk: Vector,
    /// In-position window of cutting moves, mm.
    pub in_position: Vector,
    /// In-position window of rapids, mm.
    pub in_position_rapid: Vector,
    /// Axis letters.
    pub letters: Vec<u8>,
    /// The smallest acceleration of any axis.
    pub min_accel: f64,
    /// The smallest jerk of any axis.
    pub min_jerk: f64,
    /// Whether [`corner_is_free`] may use `min_accel` and `min_jerk`
    /// (figures within 1e±30, the jerk only when finite): they are the
    /// machine's, so this is settled once rather than at every corner.
    pub(crate) corner_limits_ordinary: bool,
}

impl AxisLimits {
    /// The limits of `machine`, jerk-limited or not.
    pub fn new(machine: &Machine, jerk_limited: bool) -> AxisLimits {
        let mut l = AxisLimits {
            n: machine.axes.len().min(MAX_AXES),
            rapid: [f64::INFINITY; MAX_AXES],
            max_feed: [f64::INFINITY; MAX_AXES],
            accel: [f64::INFINITY; MAX_AXES],
            jerk: [f64::INFINITY; MAX_AXES],
            in_position: [f64::INFINITY; MAX_AXES],
            in_position_rapid: [f64::INFINITY; MAX_AXES],
            letters: machine.axes.iter().map(|a| a.letter).collect(),
            min_accel: f64::INFINITY,
            min_jerk: f64::INFINITY,
            corner_limits_ordinary: false,
        };
        for (i, a) in machine.axes.iter().enumerate().take(MAX_AXES) {
            l.rapid[i] = a.rapid_mm_per_min / 60.0;
            l.max_feed[i] = a.max_feed_mm_per_min / 60.0;
            l.accel[i] = a.accel_mm_s2;
            if jerk_limited {
                l.jerk[i] = a.jerk_mm_s3;
            }
            l.in_position[i] = a.in_position_mm;
            l.in_position_rapid[i] = a.in_position_rapid_mm;
        }
        l.min_accel = l.n_min(&l.accel);
        l.min_jerk = l.n_min(&l.jerk);
        l.corner_limits_ordinary =
            ordinary(l.min_accel) && (ordinary(l.min_jerk) || !finite(l.min_jerk));
        l
    }

    /// |u|² over the machine's axes, summed in axis order: what
    /// [`corner_is_free`] takes with each tangent, worked out once per
    /// move when it is pushed (its end tangent is asked again at the
    /// corner after it).
    #[inline]
    pub(crate) fn norm2(&self, u: &Vector) -> f64 {
        let mut n = 0.0;
        for x in u.iter().take(self.n) {
            n += x * x;
        }
        n
    }

    /// The time constant of the `filter` profile: the longest a/j of the
    /// machine's axes (0 when no axis has a finite, positive jerk). A
    /// moving average of T turns a ramp of acceleration a into one whose
    /// acceleration rises at a/T ≤ j; one filter for all axes keeps the
    /// path (each axis with its own T would bend it).
    pub fn filter_time(machine: &Machine) -> f64 {
        machine
            .axes
            .iter()
            .take(MAX_AXES)
            .map(|a| a.accel_mm_s2 / a.jerk_mm_s3)
            .filter(|t| t.is_finite() && *t > 0.0)
            .fold(0.0, f64::max)
    }

    /// The smallest of `v` over the machine's axes.
    pub fn n_min(&self, v: &Vector) -> f64 {
        v.iter().take(self.n).fold(f64::INFINITY, |a, b| a.min(*b))
    }

    /// The smallest `limit[i] / share[i]` over the axes that move.
    pub fn along(&self, limit: &Vector, share: &Vector) -> f64 {
        let mut best = f64::INFINITY;
        for i in 0..self.n {
            if share[i] > TINY {
                best = best.min(limit[i] / share[i]);
            }
        }
        best
    }

    /// Acceleration and jerk along a path whose axes move at most `share`
    /// of the path speed, and `along(speed, share)`: the three in one pass
    /// over the axes, each minimum taken in the order [`along`] takes it,
    /// so each is what `along` gives (what every move needs).
    ///
    /// [`along`]: AxisLimits::along
    pub(crate) fn kin_and_speed_along(&self, speed: &Vector, share: &Vector) -> (Kin, f64) {
        let (mut accel, mut jerk, mut v) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
        for i in 0..self.n {
            if share[i] > TINY {
                accel = accel.min(self.accel[i] / share[i]);
                jerk = jerk.min(self.jerk[i] / share[i]);
                v = v.min(speed[i] / share[i]);
            }
        }
        (Kin { accel, jerk }, v)
    }
}

/// A move's tangent at one end as [`corner_speed_units`] needs it:
/// normalised only for the corners [`corner_is_free`] cannot show free.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Unit {
    /// The unit vector; zero beyond `m`.
    e: Vector,
    /// Whether the tangent had a length at all (above [`TINY`]).
    ok: bool,
    /// The axes from `m` on do not move: the sums of a corner stop there
    /// (the terms they would add are zeros, which change no sum).
    m: usize,
}

impl Unit {
    /// The unit vector of `u` over the machine's axes.
    pub(crate) fn new(l: &AxisLimits, u: &Vector) -> Unit {
        let (mut norm, mut m) = (0.0, 0);
        for (i, ui) in u.iter().enumerate().take(l.n) {
            norm += ui * ui;
            if *ui != 0.0 {
                m = i + 1;
            }
        }
        let norm: f64 = norm.sqrt();
        let mut e = [0.0; MAX_AXES];
        for (ei, ui) in e.iter_mut().zip(u).take(m) {
            *ei = ui / norm;
        }
        Unit {
            e,
            ok: norm > TINY,
            m,
        }
    }
}

/// Speed limit and tangential limits of an arc of curvature `kappa` in the
/// plane of the axes `a` and `b`: the centripetal part stays within
/// [`ARC_NORMAL_SHARE`] of the plane axes' acceleration (and, with jerk,
/// v³κ² within that share of their jerk).
pub fn arc_limits(l: &AxisLimits, kappa: f64, a: usize, b: usize, kin: Kin) -> (f64, Kin) {
    let plane_accel = l.accel[a].min(l.accel[b]);
    let plane_jerk = l.jerk[a].min(l.jerk[b]);
    let mut v = f64::INFINITY;
    if kappa > TINY {
        v = (ARC_NORMAL_SHARE * plane_accel / kappa).sqrt();
        if plane_jerk.is_finite() {
            v = v.min((ARC_NORMAL_SHARE * plane_jerk / (kappa * kappa)).cbrt());
        }
    }
    let kin = Kin {
        accel: kin.accel.min(ARC_TANGENT_SHARE * plane_accel),
        jerk: kin.jerk.min(ARC_TANGENT_SHARE * plane_jerk),
    };
    (v, kin)
}

/// The speed at which the corner from direction `u1` to `u2` may be passed
/// with corner tolerance `tol_mm`, a rounding that stays within `half_len`
/// of the corner on either move, and the per-axis speed limits `vlim` in
/// the corner's plane; infinite when it is at least `v_cap` (the moves' own
/// limit), which a cheap bound often shows.
pub fn corner_speed(
    l: &AxisLimits,
    u1: &Vector,
    u2: &Vector,
    tol_mm: f64,
    half_len: f64,
    vlim: &Vector,
    v_cap: f64,
) -> f64 {
    let (u1, u2) = (Unit::new(l, u1), Unit::new(l, u2));
    let corner = Corner {
        tol_mm,
        half_len,
        vlim,
        vlim_min: l.n_min(vlim),
        v_cap,
    };
    corner_speed_units(l, &u1, &u2, &corner)
}

/// A corner's limits besides its tangents (see [`corner_speed`]).
pub(crate) struct Corner<'a> {
    pub tol_mm: f64,
    pub half_len: f64,
    pub vlim: &'a Vector,
    /// The smallest of `vlim` over the machine's axes.
    pub vlim_min: f64,
    pub v_cap: f64,
}

/// `x` within 1e±30: figures whose products in [`corner_is_free`] stay
/// normal.
#[inline]
fn ordinary(x: f64) -> bool {
    (1e-30..=1e30).contains(&x)
}

/// Whether [`corner_speed_units`] of the tangents `u1` and `u2`, once
/// normalised, is infinite (the corner is faster than either move may go),
/// shown without normalising them and without a square root or a
/// division; false when not shown, and the caller works it out. Most
/// corners of a chain of short moves are such, and normalising both
/// tangents and finding sin(θ/2) and cos(θ/2) (the radius) is a chain of
/// three square roots and two divisions.
///
/// The tangents must be unit within 1e-12 (a line's direction, an arc's
/// tangent are, to rounding): each normalised one is then within
/// δ/2 = 0.51e-12 of its raw self, rounding included. The raw
/// c = |u₂ − u₁|² = n₁ + n₂ − 2·u₁·u₂ and s = |u₂ + u₁|² = n₁ + n₂ + 2·u₁·u₂
/// come from three sums (nᵢ = |uᵢ|²) to within 2e-14 (the cancellation
/// in c is absolute, not relative), so with μ = 1e-6
///
/// ```text
///   4·sin²(θ/2) = |e₂ − e₁|² ≤ (c + 2e-14)·(1 + μ) + δ²·(1 + 1/μ) ≤ c·(1 + μ) + 1e-13 = 4·S
///   4·cos²(θ/2) = |e₂ + e₁|² ≥ (s − 2e-14)·(1 − μ) − δ²/μ        ≥ s·(1 − μ) − 1e-13 = 4·C
/// ```
///
/// and cos(θ/2) ≥ cos²(θ/2) ≥ C. [`corner_speed_units`]'s test on its
/// radius min(δ_c·ch·(1 + ch)/sh², (L/2)·ch/sh), with sh, ch = sin, cos
/// of θ/2, is then implied, squared where it has a square root, by
///
/// ```text
///   a·δ_c·C·(1 + C) ≥ v²·S            a²·(L/2)²·C ≥ v⁴·S
///   j·(δ_c·C·(1 + C))² ≥ v³·S²         j·(L/2)²·C ≥ v³·S
/// ```
///
/// (a, j the smallest axis limits, v the moves' cap; the jerk pair only
/// under a finite jerk) each with a margin of 1e-9, far above the
/// rounding of either computation. Figures within 1e±30 keep every
/// product normal; out of it, the answer is false.
///
/// Each tangent comes with |u|² ([`AxisLimits::norm2`]): the planner sums
/// a move's once, when it is pushed, and the function is inlined into the
/// push (a call passes the corner through memory, read back at once).
#[inline(always)]
pub(crate) fn corner_is_free(
    l: &AxisLimits,
    (u1, n1): (&Vector, f64),
    (u2, n2): (&Vector, f64),
    c: &Corner,
) -> bool {
    let jerk_limited = finite(l.min_jerk);
    let inputs = l.corner_limits_ordinary
        && ordinary(c.tol_mm)
        && ordinary(c.half_len)
        && ordinary(c.v_cap)
        && c.vlim_min >= c.v_cap;
    let unit = |n: f64| (1.0 - 1e-12..=1.0 + 1e-12).contains(&n);
    if !(inputs && unit(n1) && unit(n2)) {
        return false;
    }
    let mut dot = 0.0;
    for (a, b) in u1.iter().zip(u2).take(l.n) {
        dot += a * b;
    }
    let (chord, sum) = (n1 + n2 - 2.0 * dot, n1 + n2 + 2.0 * dot);
    let sin2 = 0.25 * (chord * (1.0 + 1e-6) + 1e-13);
    let cos2 = 0.25 * (sum * (1.0 - 1e-6) - 1e-13);
    // Finite: both tangents passed the unit test.
    if cos2 <= 0.0 {
        return false;
    }
    let (a, v, half) = (l.min_accel, c.v_cap, c.half_len);
    let round = c.tol_mm * cos2 * (1.0 + cos2);
    let v2 = v * v * (1.0 + 1e-9);
    let accel = a * round >= v2 * sin2 && (a * half) * (a * half) * cos2 >= v2 * v2 * sin2;
    if !jerk_limited {
        return accel;
    }
    let (j, v3) = (l.min_jerk, v * v * v * (1.0 + 1e-9));
    accel && j * round * round >= v3 * sin2 * sin2 && j * half * half * cos2 >= v3 * sin2
}

/// [`corner_speed`] from tangents normalised beforehand.
#[inline]
pub(crate) fn corner_speed_units(l: &AxisLimits, u1: &Unit, u2: &Unit, c: &Corner) -> f64 {
    let (tol_mm, half_len, vlim, v_cap) = (c.tol_mm, c.half_len, c.vlim, c.v_cap);
    if !(u1.ok && u2.ok) {
        return 0.0;
    }
    // e1, e2: the unit tangents; |e2 − e1| = 2·sin(θ/2), |e2 + e1| = 2·cos(θ/2).
    let (e1, e2, m) = (&u1.e, &u2.e, u1.m.max(u2.m));
    let (mut chord, mut sum, mut dot) = (0.0, 0.0, 0.0);
    for i in 0..m {
        chord += (e2[i] - e1[i]) * (e2[i] - e1[i]);
        sum += (e2[i] + e1[i]) * (e2[i] + e1[i]);
        dot += e1[i] * e2[i];
    }
    let (sh, ch) = (0.5 * chord.sqrt(), 0.5 * sum.sqrt());
    if sh < 1e-9 {
        return f64::INFINITY; // tangent: only the moves' own limits
    }
    // R = δ·cos(θ/2) / (1 − cos(θ/2)), with 1 − cos = sin²/(1 + cos): no
    // cancellation at small angles, no trigonometry.
    // The rounding must also fit in half of the shorter move: the circle
    // tangent to both at `half_len` from the corner has r = half_len/tan(θ/2).
    // On a chain of short chords this is the curve's own radius, so the
    // chain runs at its centripetal limit.
    let radius = (tol_mm * ch * (1.0 + ch) / (sh * sh)).min(half_len * ch / sh);
    // Every axis spans at most all of the plane: with the smallest limits
    // of all axes the corner is already faster than either move may go.
    if l.min_accel * radius >= v_cap * v_cap
        && (!finite(l.min_jerk) || l.min_jerk * radius * radius >= v_cap * v_cap * v_cap)
        && c.vlim_min >= v_cap
    {
        return f64::INFINITY;
    }
    // The corner's plane: e1 and the unit part of e2 orthogonal to it.
    let mut w = [0.0; MAX_AXES];
    let mut wn = 0.0;
    for i in 0..m {
        w[i] = e2[i] - dot * e1[i];
        wn += w[i] * w[i];
    }
    let wn = wn.sqrt();
    let mut span = [0.0; MAX_AXES];
    for i in 0..m {
        let wi = if wn > TINY { w[i] / wn } else { 0.0 };
        span[i] = (e1[i] * e1[i] + wi * wi).sqrt();
    }
    let accel = l.along(&l.accel, &span);
    let jerk = l.along(&l.jerk, &span);
    let mut v = (accel * radius).sqrt();
    if finite(jerk) && v * v * v > jerk * radius * radius {
        v = (jerk * radius * radius).cbrt();
    }
    v.min(l.along(vlim, &span))
}

/// The time the following error takes to settle into the in-position
/// window after a stop: a type-1 position loop of gain K that decelerated
/// at `a_i` lags a_i/K² behind, and the lag decays as e^(−K·t).
pub fn settle_time(gain: f64, accel_along: f64, share: &Vector, window: &Vector, n: usize) -> f64 {
    let mut t: f64 = 0.0;
    for i in 0..n {
        let lag = accel_along * share[i] / (gain * gain);
        if lag > window[i] && window[i] > 0.0 {
            t = t.max((lag / window[i]).ln() / gain);
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> AxisLimits {
        AxisLimits::new(&Machine::default_mill(), false)
    }

    #[test]
    fn the_one_pass_limits_are_those_of_along() {
        let l = limits();
        let speed = l.rapid;
        for share in [
            [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            [0.6, 0.8, 0.0, 0.0, 0.0, 0.0],
            [0.3, 0.2, 0.93, 0.0, 0.0, 0.0],
            [1e-15, 0.0, 1.0, 0.0, 0.0, 0.0],
            [0.0; MAX_AXES],
        ] {
            let (kin, v) = l.kin_and_speed_along(&speed, &share);
            assert_eq!(kin.accel.to_bits(), l.along(&l.accel, &share).to_bits());
            assert_eq!(kin.jerk.to_bits(), l.along(&l.jerk, &share).to_bits());
            assert_eq!(v.to_bits(), l.along(&speed, &share).to_bits());
        }
    }

    #[test]
    fn a_right_angle_corner_in_xy_follows_the_closed_form() {
        let l = limits();
        let u1 = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let u2 = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
        let v = corner_speed(&l, &u1, &u2, 0.02, 10.0, &l.max_feed, f64::INFINITY);
        // θ = 90°: R = δ·cos45°/(1 − cos45°) = 2.4142·δ; v = √(a·R).
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let r = 0.02 * c / (1.0 - c);
        assert!((v - (2000.0 * r).sqrt()).abs() < 1e-9, "{v}");
    }

    proptest::proptest! {
        /// A corner `corner_is_free` shows free is free when worked out in
        /// full, at every angle from none to a reversal, with and without
        /// a jerk limit.
        #[test]
        fn a_corner_shown_free_is_free(
            jerk: bool,
            from in proptest::array::uniform3(-1.0..1.0f64),
            turn in proptest::array::uniform3(-1.0..1.0f64),
            log_angle in -10.0..0.5f64,
            tol_mm in 1e-4..0.5f64,
            half_len in 1e-3..50.0f64,
            v_cap in 0.1..140.0f64,
            edge in proptest::option::of(-1e-6..1e-6f64),
        ) {
            let angle = 10f64.powf(log_angle);
            let l = AxisLimits::new(&Machine::default_mill(), jerk);
            // Unit to rounding, as a line's direction is.
            let unit = |v: [f64; 3]| {
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                [v[0] / n, v[1] / n, v[2] / n, 0.0, 0.0, 0.0]
            };
            let u1 = unit(from);
            let u2 = unit([0, 1, 2].map(|i| u1[i] + angle * turn[i]));
            let (e1, e2) = (Unit::new(&l, &u1), Unit::new(&l, &u2));
            // Half the time, a cap at the edge of the test on the radius.
            let v_cap = match edge {
                Some(edge) => {
                    let chord: f64 = (0..3).map(|i| (e2.e[i] - e1.e[i]).powi(2)).sum();
                    let sum: f64 = (0..3).map(|i| (e2.e[i] + e1.e[i]).powi(2)).sum();
                    let (sh, ch) = (0.5 * chord.sqrt(), 0.5 * sum.sqrt());
                    let r = (tol_mm * ch * (1.0 + ch) / (sh * sh)).min(half_len * ch / sh);
                    let v = (l.min_accel * r).sqrt().min((l.min_jerk * r * r).cbrt());
                    v * (1.0 + edge)
                }
                None => v_cap,
            };
            let c = Corner { tol_mm, half_len, vlim: &l.max_feed, vlim_min: 1e9, v_cap };
            let (n1, n2) = (l.norm2(&u1), l.norm2(&u2));
            if u1.iter().chain(&u2).all(|x| x.is_finite())
                && corner_is_free(&l, (&u1, n1), (&u2, n2), &c)
            {
                let v = corner_speed_units(&l, &e1, &e2, &c);
                proptest::prop_assert!(v.is_infinite(), "{v}");
            }
        }
    }

    /// The shortcut is taken where it pays: a corner of a chain of short
    /// moves turning by a tenth of a degree.
    #[test]
    fn a_slight_corner_of_short_moves_is_shown_free() {
        for jerk in [false, true] {
            let l = AxisLimits::new(&Machine::default_mill(), jerk);
            let a: f64 = 0.1f64.to_radians();
            let u1 = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            let u2 = [a.cos(), a.sin(), 0.0, 0.0, 0.0, 0.0];
            let c = Corner {
                tol_mm: 0.02,
                half_len: 0.25,
                vlim: &l.max_feed,
                vlim_min: l.n_min(&l.max_feed),
                v_cap: 25.0,
            };
            assert!(corner_is_free(
                &l,
                (&u1, l.norm2(&u1)),
                (&u2, l.norm2(&u2)),
                &c
            ));
            assert!(
                corner_speed_units(&l, &Unit::new(&l, &u1), &Unit::new(&l, &u2), &c).is_infinite()
            );
        }
    }

    #[test]
    fn straight_on_is_unlimited_and_a_reversal_stops() {
        let l = limits();
        let u = [0.6, 0.8, 0.0, 0.0, 0.0, 0.0];
        let back = u.map(|x| -x);
        assert!(corner_speed(&l, &u, &u, 0.02, 10.0, &l.max_feed, 1e9).is_infinite());
        assert!(corner_speed(&l, &u, &back, 0.02, 10.0, &l.max_feed, 1e9) < 1e-6);
    }
}
