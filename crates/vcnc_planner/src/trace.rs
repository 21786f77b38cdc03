//! Sampling a planned timeline at a fixed period: position, velocity,
//! acceleration and jerk of every axis at t = 0, T, 2T, … — the
//! commanded trajectory at the interpolator (`vcnc run --format trace`).
//!
//! Each piece is evaluated in closed form at the sample times that fall in
//! it: distance s(t), speed, tangential acceleration and jerk from its
//! profile, then per axis `p(s)`, `v·t̂`, `a·t̂ + v²·κ` (κ the curvature
//! vector). A corner passed at speed shows as a change of direction between
//! two samples: the commanded path goes through the corner point, at the
//! speed a rounding within the corner tolerance allows (`limits.rs`).

use crate::ramp::Profile;
use crate::timeline::{Attr, AxesMove, Pause, Segment, Timeline};
use vcnc_core::{MAX_AXES, Pos};

/// One sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time since the start, s.
    pub t: f64,
    /// Position, machine mm.
    pub pos: Pos,
    /// Velocity per axis, mm/s.
    pub vel: [f64; MAX_AXES],
    /// Acceleration per axis, mm/s².
    pub acc: [f64; MAX_AXES],
    /// Path speed, mm/s.
    pub speed: f64,
    /// Jerk along the path, mm/s³ (0 on pauses).
    pub path_jerk: f64,
    /// Source line of the piece.
    pub line: u64,
}

/// Receives samples.
pub trait SampleSink {
    /// One sample, in time order.
    fn sample(&mut self, s: &Sample);
}

impl<F: FnMut(&Sample)> SampleSink for F {
    fn sample(&mut self, s: &Sample) {
        self(s);
    }
}

/// Hands every sample of the timeline to `f`.
#[derive(Debug)]
pub struct Sampler<F: SampleSink> {
    period: f64,
    /// Start time of the next piece.
    t0: f64,
    /// Index of the next sample.
    k: u64,
    pos: Pos,
    f: F,
}

impl<F: SampleSink> Sampler<F> {
    /// The receiver of the samples.
    pub fn sink(&self) -> &F {
        &self.f
    }

    /// The receiver of the samples, to change.
    pub fn sink_mut(&mut self) -> &mut F {
        &mut self.f
    }

    /// Samples every `period_s` seconds (at least 1 µs), starting at `start`.
    pub fn new(period_s: f64, start: Pos, f: F) -> Sampler<F> {
        Sampler {
            period: sample_period(period_s),
            t0: 0.0,
            k: 0,
            pos: start,
            f,
        }
    }

    /// The end time of what was sampled so far.
    pub fn elapsed_s(&self) -> f64 {
        self.t0
    }

    /// Emits one last sample at rest at the end of the timeline.
    pub fn finish(&mut self) {
        let s = Sample {
            t: self.t0,
            pos: self.pos,
            vel: [0.0; MAX_AXES],
            acc: [0.0; MAX_AXES],
            speed: 0.0,
            path_jerk: 0.0,
            line: 0,
        };
        self.f.sample(&s);
    }

    /// Samples the piece of `duration` from the current time with `eval`.
    fn piece(&mut self, duration: f64, mut eval: impl FnMut(f64) -> Sample) {
        let end = self.t0 + duration;
        loop {
            #[allow(clippy::cast_precision_loss)] // sample counts stay far below 2^52
            let t = self.k as f64 * self.period;
            if t >= end {
                break;
            }
            let mut s = eval((t - self.t0).max(0.0));
            s.t = t;
            self.f.sample(&s);
            self.k += 1;
        }
        self.t0 = end;
    }
}

/// Most samples [`Smoothed`]'s window holds (9.6 MB).
pub const MAX_FILTER_SAMPLES: f64 = 100_000.0;

/// The period a sampler keeps: at least 1 µs, 1 ms if not finite.
fn sample_period(period_s: f64) -> f64 {
    if period_s.is_finite() {
        period_s.max(1e-6)
    } else {
        1e-3
    }
}

/// One input sample's position and velocity: what [`Smoothed`] keeps of
/// the last T.
#[derive(Debug, Clone, Copy)]
struct Kept {
    pos: [f64; MAX_AXES],
    vel: [f64; MAX_AXES],
}

/// The `filter` profile at the interpolator's output: every axis' samples
/// through one moving average of `n` samples (T = n · period), as a
/// controller's acceleration/deceleration after interpolation filters its
/// commanded positions. With p and v the planned samples, k the newest and
/// k − n the one the average drops:
///
/// ```text
///   position      P_k = (p_k + … + p_(k−n+1)) / n
///   velocity      V_k = (p_k − p_(k−n)) / T      = (P_k − P_(k−1)) / period
///   acceleration  A_k = (v_k − v_(k−n)) / T      (a corner's jump of v too)
///   path_jerk     (A_k − A_(k−1)) / period, its part along V_k
/// ```
///
/// The position sum is kept running and worked out afresh every `n`
/// samples, so rounding does not build up.
#[derive(Debug)]
pub struct Smoothed<F: SampleSink> {
    ring: Vec<Kept>,
    at: usize,
    sum: [f64; MAX_AXES],
    window_s: f64,
    period_s: f64,
    acc: [f64; MAX_AXES],
    inner: F,
}

/// How many samples [`Smoothed`]'s average of `filter_s` at `period_s`
/// holds: the whole periods within T (one at least), so that the run-out
/// of T the planner adds after a stop always fills the window with samples
/// at rest and the trace stops where the plan does. When T is not a whole
/// number of periods the average is up to a period shorter than T (its
/// jerk up to a/(T − period)); at the default 1 ms it is T.
pub fn filter_samples(filter_s: f64, period_s: f64) -> f64 {
    (filter_s / sample_period(period_s) + 1e-9).floor().max(1.0)
}

impl<F: SampleSink> Smoothed<F> {
    /// A moving average over `filter_s` at `period_s` (a filter shorter
    /// than two periods passes samples through), starting at rest at
    /// `start`. The window holds at most [`MAX_FILTER_SAMPLES`] samples
    /// (the CLI refuses a period that needs more).
    pub fn new(filter_s: f64, period_s: f64, start: Pos, inner: F) -> Smoothed<F> {
        let period_s = sample_period(period_s);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = filter_samples(filter_s, period_s).min(MAX_FILTER_SAMPLES) as usize;
        let rest = Kept {
            pos: start.0,
            vel: [0.0; MAX_AXES],
        };
        #[allow(clippy::cast_precision_loss)] // n ≤ MAX_FILTER_SAMPLES
        let nf = n as f64;
        Smoothed {
            ring: vec![rest; n],
            at: 0,
            sum: start.0.map(|p| p * nf),
            window_s: nf * period_s,
            period_s,
            acc: [0.0; MAX_AXES],
            inner,
        }
    }

    /// The sink after the filter.
    pub fn sink(&self) -> &F {
        &self.inner
    }

    /// The sink after the filter, to change.
    pub fn sink_mut(&mut self) -> &mut F {
        &mut self.inner
    }
}

impl<F: SampleSink> SampleSink for Smoothed<F> {
    fn sample(&mut self, s: &Sample) {
        let n = self.ring.len();
        if n <= 1 {
            self.inner.sample(s);
            return;
        }
        let new = Kept {
            pos: s.pos.0,
            vel: s.vel,
        };
        let Some(slot) = self.ring.get_mut(self.at) else {
            return;
        };
        let old = std::mem::replace(slot, new);
        self.at += 1;
        if self.at == n {
            self.at = 0;
            self.sum = [0.0; MAX_AXES];
            for k in &self.ring {
                for i in 0..MAX_AXES {
                    self.sum[i] += k.pos[i];
                }
            }
        } else {
            for i in 0..MAX_AXES {
                self.sum[i] += new.pos[i] - old.pos[i];
            }
        }
        #[allow(clippy::cast_precision_loss)] // n ≤ MAX_FILTER_SAMPLES
        let inv = 1.0 / n as f64;
        let mut out = *s;
        let (mut v2, mut jv, mut j2) = (0.0, 0.0, 0.0);
        for i in 0..MAX_AXES {
            out.pos.0[i] = self.sum[i] * inv;
            out.vel[i] = (new.pos[i] - old.pos[i]) / self.window_s;
            out.acc[i] = (new.vel[i] - old.vel[i]) / self.window_s;
            let j = (out.acc[i] - self.acc[i]) / self.period_s;
            v2 += out.vel[i] * out.vel[i];
            jv += j * out.vel[i];
            j2 += j * j;
        }
        self.acc = out.acc;
        out.speed = v2.sqrt();
        out.path_jerk = if out.speed > 1e-12 {
            jv / out.speed
        } else {
            j2.sqrt()
        };
        self.inner.sample(&out);
    }
}

fn at_rest(pos: Pos, line: u64) -> Sample {
    Sample {
        t: 0.0,
        pos,
        vel: [0.0; MAX_AXES],
        acc: [0.0; MAX_AXES],
        speed: 0.0,
        path_jerk: 0.0,
        line,
    }
}

impl<F: SampleSink> Timeline for Sampler<F> {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        let path = seg.path;
        let line = seg.attr.line;
        self.piece(profile.duration(), |t| {
            let [s, v, a, j] = profile.at(t);
            let s = s.clamp(0.0, path.len);
            let tan = path.tangent(s);
            let curv = path.curvature(s);
            let mut out = at_rest(path.point(s), line);
            for i in 0..MAX_AXES {
                out.vel[i] = v * tan[i];
                out.acc[i] = a * tan[i] + v * v * curv[i];
            }
            out.speed = v;
            out.path_jerk = j;
            out
        });
        self.pos = path.to;
    }

    fn axes(&mut self, mv: &AxesMove) {
        let line = mv.attr.line;
        let (from, to) = (mv.from, mv.to);
        let profiles = mv.profiles;
        self.piece(mv.duration_s, |t| {
            let mut out = at_rest(from, line);
            let mut v2 = 0.0;
            for (i, p) in profiles.iter().enumerate() {
                let Some(p) = p else { continue };
                let sign = if to.get(i) >= from.get(i) { 1.0 } else { -1.0 };
                let [s, v, a, _] = p.at(t);
                out.pos.set(i, from.get(i) + sign * s);
                out.vel[i] = sign * v;
                out.acc[i] = sign * a;
                v2 += v * v;
            }
            out.speed = v2.sqrt();
            out
        });
        self.pos = to;
    }

    fn pause(&mut self, p: &Pause) {
        let pos = self.pos;
        let line = p.attr.line;
        self.piece(p.seconds, |_| at_rest(pos, line));
    }

    fn untimed(&mut self, _from: Pos, to: Pos, _attr: &Attr) {
        self.pos = to;
    }
}
