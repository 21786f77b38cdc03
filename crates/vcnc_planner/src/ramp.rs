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
        if self.jerk.is_finite() {
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
                + if self.jerk.is_finite() {
                    self.accel / self.jerk
                } else {
                    0.0
                }
        } else {
            2.0 * (dv / self.jerk).sqrt()
        }
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

    /// The highest speed reachable from `v0` (or from which `v0` is
    /// reachable) within `len` mm.
    pub fn reach(self, v0: f64, len: f64) -> f64 {
        let len = len.max(0.0);
        if !self.jerk.is_finite() {
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
    pub fn plan(v0: f64, v1: f64, v_max: f64, len: f64, kin: Kin) -> Profile {
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
