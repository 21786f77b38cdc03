//! One-dimensional speed profiles along the path: the ramps between two
//! speeds under an acceleration and a jerk limit, their closed forms, and
//! the profile of one block (ramp up, cruise, ramp down).
//!
//! ```text
//!  accel ▲   ┌────────┐              a ramp from v0 to v1 = v0 + Δ:
//!     a  │  ╱│        │╲              jerk up for tj, hold a_p for ta,
//!        │ ╱ │        │ ╲             jerk down for tj (a_p = a when
//!        │╱  │        │  ╲            Δ ≥ a²/j, else a_p = √(Δ·j), ta = 0)
//!        └───┴────────┴───▶ t
//!           tj   ta    tj           time  T = Δ/a_p + a_p/j
//!                                   dist  D = (v0 + v1)/2 · T
//! ```
//!
//! A trapezoid is the same with infinite jerk (tj = 0). Every ramp starts
//! and ends at zero acceleration, so ramps join without a jump of
//! acceleration: the jerk limit holds across block junctions too. The
//! look-ahead needs the inverse, [`reach`]: the highest speed reachable from
//! `v0` within a distance — √(v0² + 2aL) for a trapezoid, and for an S-curve
//! the root of a quadratic (acceleration saturates) or of the depressed
//! cubic j·s³ + 2·v0·s = L with s = √(Δ/j) (it does not), both in closed
//! form (Cardano). Reference: Biagiotti & Melchiorri, *Trajectory Planning
//! for Automatic Machines and Robots* (2008), §3.4 (double-S profile).

/// Whether `x` is finite: `x − x` is 0 for a finite x, NaN for ±∞ and NaN.
/// The same answer as `f64::is_finite`, in two float instructions:
/// `is_finite`, and range checks such as `0 < x < ∞`, become an integer
/// classification of the bits on x86-64 today, a dozen instructions, and
/// the planner asks this a dozen times a block. A positive finite figure
/// is `0 < x ≤ f64::MAX`, two compares.
#[inline]
#[allow(
    clippy::eq_op,
    reason = "x − x is the test: 0 when finite, NaN otherwise"
)]
pub(crate) fn finite(x: f64) -> bool {
    x - x == 0.0
}

/// The limits of one profile: acceleration and jerk along the path (jerk
/// `f64::INFINITY` for a trapezoid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kin {
    /// Acceleration, mm/s².
    pub accel: f64,
    /// Jerk, mm/s³ (infinite: trapezoid).
    pub jerk: f64,
}

impl Kin {
    /// The speed change at which the acceleration saturates: a²/j.
    fn saturating_dv(self) -> f64 {
        if finite(self.jerk) {
            self.accel * self.accel / self.jerk
        } else {
            0.0
        }
    }

    /// Time of a ramp changing speed by `dv` (≥ 0).
    pub fn ramp_time(self, dv: f64) -> f64 {
        let dv = dv.max(0.0);
        if dv >= self.saturating_dv() {
            dv / self.accel
                + if finite(self.jerk) {
                    self.accel / self.jerk
                } else {
                    0.0
                }
        } else {
            2.0 * (dv / self.jerk).sqrt()
        }
    }

    /// `ramp_time(0.0) == 0.0` (a ramp by nothing takes no time), without
    /// its two divisions and square root for limits within 1e±60, where it
    /// holds: 2·√(0/j) under a jerk, 0/a under none. Asked of every move
    /// passed through at its top speed.
    #[inline]
    fn stays_in_no_time(self) -> bool {
        let ordinary = in_range(self.accel) && (in_range(self.jerk) || self.jerk == f64::INFINITY);
        ordinary || self.ramp_time(0.0) == 0.0
    }

    /// Distance of a ramp between `v0` and `v1` (either order).
    pub fn ramp_dist(self, v0: f64, v1: f64) -> f64 {
        0.5 * (v0 + v1) * self.ramp_time((v1 - v0).abs())
    }

    /// `reach(v0, len)` capped at `cap`, without solving for the reach when
    /// a ramp to `cap` already fits (the common case, and cheaper).
    pub fn reach_capped(self, v0: f64, len: f64, cap: f64) -> f64 {
        if cap <= v0 || self.ramp_dist(v0, cap) <= len {
            cap
        } else {
            self.reach(v0, len).min(cap)
        }
    }

    /// `reach_capped(0, len, cap)`, or bounds on it where finding it takes
    /// a cube root (a jerk-limited ramp too short to saturate): the
    /// look-ahead needs the exact figure of its newest move only when the
    /// move before cannot be shown to enter at its cap whatever the figure
    /// in the bounds ([`Kin::reaches_cap_from`]); on a chain of short moves
    /// it almost always can, and the figure is replaced before it is used.
    ///
    /// Such a ramp from rest reaches v with v³ = j·len² (s = ∛(len/j) in
    /// [`Kin::reach`], v = j·s²): the bounds are bounds on ∛(j·len²), with
    /// one division in all ([`cube_root_bounds`]). The ramp to `cap` needs
    /// no test of its own (a division and a square root): it fits exactly
    /// when the reach is at least `cap`, up to rounding far inside the
    /// margin, so bounds on the reach, capped, bound `reach_capped`.
    #[inline]
    pub(crate) fn reach_from_rest(self, len: f64, cap: f64) -> Result<f64, (f64, f64)> {
        let (a, j) = (self.accel, self.jerk);
        // Inside the cubic branch of `reach` by a margin, so that `reach`
        // takes it too (tested first: a long move leaves here). Within
        // 1e±60 nothing below over- or underflows (j·len², a³, and
        // `reach`'s q2² all stay normal).
        let cubic = len * j * j <= a * a * a * (1.0 - 1e-12)
            && in_range(len)
            && in_range(j)
            && in_range(a)
            && cap > 0.0;
        if cubic && let Some((lo, hi)) = cube_root_bounds(j * len * len) {
            // `reach` rounds a few times (its cube root within an ulp):
            // far inside 1e-12.
            let (lo, hi) = (lo * (1.0 - 1e-12), hi * (1.0 + 1e-12));
            return if lo >= cap {
                Ok(cap)
            } else {
                Err((lo, hi.min(cap)))
            };
        }
        Ok(self.reach_capped(0.0, len, cap))
    }

    /// Whether `reach_capped(v0, len, cap)` is `cap` for every `v0` in
    /// `[lo, hi]`. For v0 < cap it is when the ramp up to `cap` fits,
    /// ½·(v0 + cap)·T(cap − v0) ≤ len, and T grows with the speed change,
    /// so ½·(min(hi, cap) + cap)·T(cap − lo) bounds the ramp over the whole
    /// interval; the margin of 1e-9 is far above the rounding of either
    /// side. Asked for every block, it multiplies out T's division and
    /// square root (a chain of ~40 cycles): with m = ½·(min(hi, cap) +
    /// cap), d = cap − lo and l = len·(1 − 1e-9),
    ///
    /// ```text
    ///   trapezoid         m·d/a ≤ l              ⇔  m·d ≤ l·a
    ///   d ≥ a²/j          m·(d/a + a/j) ≤ l      ⇔  m·(d·j + a²) ≤ l·a·j
    ///   d < a²/j          m·2·√(d/j) ≤ l         ⇔  4·m²·d ≤ l²·j
    /// ```
    ///
    /// (the two jerk-limited forms meet at d = a²/j), for figures within
    /// 1e±60, where no product over- or underflows.
    #[inline]
    pub(crate) fn reaches_cap_from(self, (lo, hi): (f64, f64), len: f64, cap: f64) -> bool {
        if cap <= lo {
            return true;
        }
        let (a, j) = (self.accel, self.jerk);
        let m = 0.5 * (hi.min(cap) + cap);
        let l = len * (1.0 - 1e-9);
        if !(in_range(a) && in_range(len) && in_range(cap) && lo >= 0.0) {
            return m * self.ramp_time(cap - lo) <= l;
        }
        let d = cap - lo;
        if !finite(j) {
            m * d <= l * a
        } else if !in_range(j) {
            m * self.ramp_time(d) <= l
        } else if d * j >= a * a {
            m * (d * j + a * a) <= l * a * j
        } else {
            4.0 * m * m * d <= l * l * j
        }
    }

    /// The highest speed reachable from `v0` (or from which `v0` is
    /// reachable) within `len` mm.
    pub fn reach(self, v0: f64, len: f64) -> f64 {
        let len = len.max(0.0);
        if !finite(self.jerk) {
            return (v0 * v0 + 2.0 * self.accel * len).sqrt();
        }
        let (a, j) = (self.accel, self.jerk);
        let sat = a * a / j;
        if len <= (2.0 * v0 + sat) * a / j {
            // j·s³ + 2·v0·s − len = 0, one real root; s = A − p/(3A).
            let p3 = 2.0 * v0 / (3.0 * j);
            let q2 = len / (2.0 * j);
            let big = (q2 + (q2 * q2 + p3 * p3 * p3).sqrt()).cbrt();
            let s = if big > 0.0 { big - p3 / big } else { 0.0 };
            v0 + j * s * s
        } else {
            // Δ²/a + Δ(2v0/a + a/j) + 2v0·a/j − 2·len = 0, the positive root.
            let qa = 1.0 / a;
            let qb = 2.0 * v0 / a + a / j;
            let qc = 2.0 * v0 * a / j - 2.0 * len;
            let d = (-2.0 * qc) / (qb + (qb * qb - 4.0 * qa * qc).max(0.0).sqrt());
            v0 + d
        }
    }
}

/// Whether `x` lies within 1e±60 (false for NaN): figures whose products
/// of four stay normal floats.
#[inline]
fn in_range(x: f64) -> bool {
    (1e-60..=1e60).contains(&x)
}

/// How far [`cube_root_bounds`]'s figure may be from ∛w: a guess within
/// 3.3 % leaves one Halley step within 2.1e-5 (measured over 1e±180).
const CUBE_ROOT_STEP_ERROR: f64 = 3e-5;

/// Bounds `lo < ∛w < hi`, a relative 6e-5 apart, for a positive normal `w`
/// (`None` when not shown to be): a guess from the exponent bits
/// (fdlibm's, within 3.3 %), one Halley step (cubic convergence), and a
/// check of the bounds by cubing them, which holds whatever the step's
/// error. The bounds only have to decide a comparison with a margin, for
/// which one step does: each step is a division on the look-ahead's
/// longest chain of dependent instructions.
#[inline]
fn cube_root_bounds(w: f64) -> Option<(f64, f64)> {
    if !(1e-200..=1e200).contains(&w) {
        return None;
    }
    let high = u32::try_from(w.to_bits() >> 32).ok()?;
    let y = f64::from_bits(u64::from(high / 3 + 715_094_163) << 32);
    let y3 = y * y * y;
    let y = y * ((y3 + 2.0 * w) / (2.0 * y3 + w));
    let (lo, hi) = (
        y * (1.0 - CUBE_ROOT_STEP_ERROR),
        y * (1.0 + CUBE_ROOT_STEP_ERROR),
    );
    (lo * lo * lo < w && w < hi * hi * hi).then_some((lo, hi))
}

/// A ramp from `v0` to `v1` with its phase times.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    /// Start speed.
    pub v0: f64,
    /// End speed.
    pub v1: f64,
    /// Peak acceleration magnitude.
    pub peak_accel: f64,
    /// Jerk magnitude (infinite: trapezoid).
    pub jerk: f64,
    /// Duration of each jerk phase.
    pub tj: f64,
    /// Duration of the constant-acceleration phase.
    pub ta: f64,
}

impl Ramp {
    /// The ramp between two speeds.
    pub fn new(v0: f64, v1: f64, kin: Kin) -> Ramp {
        let dv = (v1 - v0).abs();
        if dv <= 0.0 {
            return Ramp {
                v0,
                v1,
                peak_accel: 0.0,
                jerk: kin.jerk,
                tj: 0.0,
                ta: 0.0,
            };
        }
        let peak = if kin.jerk.is_finite() {
            kin.accel.min((dv * kin.jerk).sqrt())
        } else {
            kin.accel
        };
        let tj = if kin.jerk.is_finite() {
            peak / kin.jerk
        } else {
            0.0
        };
        Ramp {
            v0,
            v1,
            peak_accel: peak,
            jerk: kin.jerk,
            tj,
            ta: (dv / peak - tj).max(0.0),
        }
    }

    /// Duration.
    pub fn duration(&self) -> f64 {
        2.0 * self.tj + self.ta
    }

    /// Distance.
    pub fn dist(&self) -> f64 {
        0.5 * (self.v0 + self.v1) * self.duration()
    }

    /// Distance, speed, acceleration and jerk at time `t` into the ramp.
    pub fn at(&self, t: f64) -> [f64; 4] {
        let sign = if self.v1 >= self.v0 { 1.0 } else { -1.0 };
        let (a, j) = (self.peak_accel, if self.tj > 0.0 { self.jerk } else { 0.0 });
        let t = t.clamp(0.0, self.duration());
        // Phase 1: jerk up.
        let t1 = t.min(self.tj);
        let mut s = self.v0 * t1 + sign * j * t1 * t1 * t1 / 6.0;
        let mut v = self.v0 + sign * 0.5 * j * t1 * t1;
        if t <= self.tj {
            return [s, v, sign * j * t1, sign * j];
        }
        // Phase 2: constant acceleration.
        let t2 = (t - self.tj).min(self.ta);
        s += v * t2 + sign * 0.5 * a * t2 * t2;
        v += sign * a * t2;
        if t <= self.tj + self.ta {
            return [s, v, sign * a, 0.0];
        }
        // Phase 3: jerk down.
        let t3 = t - self.tj - self.ta;
        s += v * t3 + sign * (0.5 * a * t3 * t3 - j * t3 * t3 * t3 / 6.0);
        v += sign * (a * t3 - 0.5 * j * t3 * t3);
        [s, v, sign * (a - j * t3), -sign * j]
    }
}

/// The speed profile of one block: up to its peak, cruise, down to its exit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Profile {
    /// Ramp from the entry speed to the peak.
    pub up: Ramp,
    /// Time at the peak speed.
    pub cruise_s: f64,
    /// Ramp from the peak to the exit speed.
    pub down: Ramp,
}

impl Profile {
    /// The fastest profile over `len` mm from `v0` to `v1` that stays at or
    /// below `v_max`. The entry and exit speeds must be reachable from each
    /// other within `len` (the look-ahead guarantees it up to rounding).
    #[inline]
    pub fn plan(v0: f64, v1: f64, v_max: f64, len: f64, kin: Kin) -> Profile {
        // Passing through at the top speed (most moves of a long chain):
        // when a ramp by nothing takes no time, the general case comes to
        // exactly this (no ramps, len/v of cruise). In line, for the
        // caller to keep only what it reads.
        let through = v0 == v_max && v1 == v_max && v_max > 0.0 && v_max <= f64::MAX && len > 0.0;
        if through && kin.stays_in_no_time() {
            let flat = Ramp::new(v_max, v_max, kin);
            return Profile {
                up: flat,
                cruise_s: len / v_max,
                down: flat,
            };
        }
        Profile::plan_ramps(v0, v1, v_max, len, kin)
    }

    /// [`Profile::plan`] with ramps.
    fn plan_ramps(v0: f64, v1: f64, v_max: f64, len: f64, kin: Kin) -> Profile {
        let floor = v0.max(v1);
        let v_max = v_max.max(floor);
        let fits = |vp: f64| kin.ramp_dist(v0, vp) + kin.ramp_dist(vp, v1) <= len;
        let peak = if fits(v_max) {
            v_max
        } else if !kin.jerk.is_finite() {
            let a = kin.accel;
            ((2.0 * a * len + v0 * v0 + v1 * v1) / 2.0)
                .sqrt()
                .clamp(floor, v_max)
        } else {
            bisect_peak(floor, v_max, fits)
        };
        let up = Ramp::new(v0, peak, kin);
        let down = Ramp::new(peak, v1, kin);
        let rest = len - up.dist() - down.dist();
        Profile {
            up,
            cruise_s: if peak > 0.0 {
                rest.max(0.0) / peak
            } else {
                0.0
            },
            down,
        }
    }

    /// Duration.
    pub fn duration(&self) -> f64 {
        self.up.duration() + self.cruise_s + self.down.duration()
    }

    /// The peak speed.
    pub fn peak(&self) -> f64 {
        self.up.v1
    }

    /// Distance, speed, acceleration and jerk along the path at time `t`.
    pub fn at(&self, t: f64) -> [f64; 4] {
        let tu = self.up.duration();
        if t <= tu {
            return self.up.at(t);
        }
        let s_up = self.up.dist();
        let vp = self.peak();
        if t <= tu + self.cruise_s {
            return [s_up + vp * (t - tu), vp, 0.0, 0.0];
        }
        let [s, v, a, j] = self.down.at(t - tu - self.cruise_s);
        [s_up + vp * self.cruise_s + s, v, a, j]
    }
}

/// The highest peak in `[lo, hi]` for which `fits` holds (`fits(lo)` is
/// assumed), to a relative 1e-10.
fn bisect_peak(lo: f64, hi: f64, fits: impl Fn(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..64 {
        if hi - lo <= 1e-10 * hi.max(1e-9) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        if fits(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRAP: Kin = Kin {
        accel: 1000.0,
        jerk: f64::INFINITY,
    };
    const SCURVE: Kin = Kin {
        accel: 1000.0,
        jerk: 20_000.0,
    };

    #[test]
    fn reach_inverts_the_ramp_distance() {
        for kin in [TRAP, SCURVE] {
            for v0 in [0.0, 1.0, 30.0, 200.0] {
                for len in [1e-4, 0.01, 0.5, 3.0, 40.0, 900.0] {
                    let v1 = kin.reach(v0, len);
                    let d = kin.ramp_dist(v0, v1);
                    assert!((d - len).abs() <= 1e-9 * len.max(1.0), "{v0} {len}: {d}");
                }
            }
        }
    }

    proptest::proptest! {
        /// The bounds `reach_from_rest` leaves hold the exact figure, and
        /// when they show the move before entering at its cap, the exact
        /// figure gives that cap too: the look-ahead's lazy entry bound
        /// changes no result.
        #[test]
        fn the_bounds_on_an_entry_speed_hold_it_and_decide_the_move_before(
            accel in 10.0..20_000.0f64,
            jerk in 100.0..1e6f64,
            len in 1e-4..20.0f64,
            cap in 0.1..500.0f64,
            prev_len in 1e-4..20.0f64,
            prev_cap in 0.1..500.0f64,
            prev_scale in 0.3..3.0f64,
        ) {
            let kin = Kin { accel, jerk };
            let exact = kin.reach_capped(0.0, len, cap);
            match kin.reach_from_rest(len, cap) {
                Ok(v) => proptest::prop_assert_eq!(v.to_bits(), exact.to_bits()),
                Err((lo, hi)) => {
                    proptest::prop_assert!(lo <= exact && exact <= hi, "{lo} {exact} {hi}");
                    let prev = Kin { accel: accel * prev_scale, jerk: jerk / prev_scale };
                    if prev.reaches_cap_from((lo, hi), prev_len, prev_cap) {
                        let v = prev.reach_capped(exact, prev_len, prev_cap);
                        proptest::prop_assert_eq!(v.to_bits(), prev_cap.to_bits());
                    }
                }
            }
        }
    }

    proptest::proptest! {
        /// The same at the edge, where it counts: the move before is just
        /// long enough, or just too short, to ramp from the newest move's
        /// entry speed up to its cap (under a jerk, a trapezoid, or a jerk
        /// it saturates).
        #[test]
        fn the_bounds_decide_only_rightly_at_the_edge(
            accel in 10.0..20_000.0f64,
            jerk in 100.0..1e6f64,
            len in 1e-4..20.0f64,
            cap in 0.1..500.0f64,
            prev_cap in 0.1..500.0f64,
            prev_kind in 0..3u8,
            edge in -1e-8..1e-8f64,
        ) {
            let kin = Kin { accel, jerk };
            if let Err(bounds) = kin.reach_from_rest(len, cap) {
                let exact = kin.reach_capped(0.0, len, cap);
                let prev = match prev_kind {
                    0 => kin,
                    1 => Kin { accel, jerk: f64::INFINITY },
                    _ => Kin { accel: accel * 0.01, jerk },
                };
                let prev_len = prev.ramp_dist(exact, prev_cap) * (1.0 + edge);
                // The bounds found, and the narrowest there are.
                for bounds in [bounds, (exact, exact)] {
                    if prev.reaches_cap_from(bounds, prev_len, prev_cap) {
                        let v = prev.reach_capped(exact, prev_len, prev_cap);
                        proptest::prop_assert_eq!(v.to_bits(), prev_cap.to_bits());
                    }
                }
            }
        }
    }

    #[test]
    fn stays_in_no_time_is_a_ramp_by_nothing_in_no_time() {
        let figures = [
            0.0,
            -1.0,
            1e-61,
            1e-60,
            f64::MIN_POSITIVE,
            1.0,
            2000.0,
            1e60,
            1e61,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        for accel in figures {
            for jerk in figures {
                let kin = Kin { accel, jerk };
                let slow = kin.ramp_time(0.0) == 0.0;
                assert_eq!(kin.stays_in_no_time(), slow, "{accel} {jerk}");
            }
        }
    }

    #[test]
    fn finite_is_is_finite() {
        let specials = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
        ];
        let odd = [f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        for x in specials.into_iter().chain(odd) {
            assert_eq!(finite(x), x.is_finite(), "{x}");
            let positive = x > 0.0 && x <= f64::MAX;
            assert_eq!(positive, x.is_finite() && x > 0.0, "{x}");
        }
    }

    #[test]
    fn cube_root_bounds_hold_the_cube_root() {
        let mut z: f64 = 1.7e-199;
        while z < 1e199 {
            for w in [z, z * 1.0001, z * 1.26, z * 1.587, z * 1.9999] {
                let (lo, hi) = cube_root_bounds(w).unwrap();
                let y = w.cbrt();
                assert!(lo < y && y < hi && hi - lo < 7e-5 * y, "{w}: {lo} {y} {hi}");
            }
            z *= 2.0;
        }
        for w in [0.0, 1e-201, 1e201, f64::INFINITY, f64::NAN, -1.0] {
            assert!(cube_root_bounds(w).is_none(), "{w}");
        }
    }

    #[test]
    fn a_ramp_ends_where_its_closed_form_says() {
        for kin in [TRAP, SCURVE] {
            for (v0, v1) in [(0.0, 100.0), (100.0, 20.0), (5.0, 6.0)] {
                let r = Ramp::new(v0, v1, kin);
                let [s, v, a, _] = r.at(r.duration());
                assert!((s - r.dist()).abs() < 1e-9, "{s} {}", r.dist());
                assert!((v - v1).abs() < 1e-9);
                assert!(a.abs() < 1e-6 || !kin.jerk.is_finite());
                assert!((r.duration() - kin.ramp_time((v1 - v0).abs())).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn a_profile_covers_its_length() {
        for kin in [TRAP, SCURVE] {
            for len in [0.05, 1.0, 10.0, 100.0] {
                let p = Profile::plan(0.0, 0.0, 150.0, len, kin);
                let [s, v, ..] = p.at(p.duration());
                assert!((s - len).abs() < 1e-6 * len.max(1.0), "{len}: {s}");
                assert!(v.abs() < 1e-9);
            }
        }
    }
}
