//! `vcnc run --format trace --period T`: the planned trajectory sampled
//! every T seconds as CSV — time, position, velocity and acceleration per
//! axis, path speed and the source line:
//!
//! ```text
//! t,x,y,z,vx,vy,vz,ax,ay,az,speed,line
//! 0,0,0,0,0,0,0,0,0,0,0,1
//! ```
//!
//! Units: s, mm, mm/s, mm/s². The last row is the end point at rest.
//! Under the `filter` profile the rows are the plan after the moving
//! average (acceleration and deceleration after interpolation).

use std::io::Write;
use vcnc_interp::{Event, Machine, Sink};
use vcnc_planner::{
    MAX_FILTER_SAMPLES, Planner, ProfileShape, Sample, SampleSink, Sampler, Smoothed,
    filter_samples, filter_time,
};

/// Formats samples as CSV rows.
pub struct CsvRows<W: Write> {
    out: W,
    n: usize,
    buf: Vec<u8>,
    error: Option<std::io::Error>,
}

impl<W: Write> CsvRows<W> {
    fn push(&mut self, v: f64) {
        let r = (v * 1e6).round() / 1e6;
        let r = if r == 0.0 { 0.0 } else { r }; // no "-0"
        let mut b = ryu::Buffer::new();
        let s = b.format(r);
        self.buf
            .extend_from_slice(s.strip_suffix(".0").unwrap_or(s).as_bytes());
        self.buf.push(b',');
    }

    fn flush_buf(&mut self) {
        if self.error.is_none()
            && let Err(e) = self.out.write_all(&self.buf)
        {
            self.error = Some(e);
        }
        self.buf.clear();
    }
}

impl<W: Write> SampleSink for CsvRows<W> {
    fn sample(&mut self, s: &Sample) {
        self.push(s.t);
        for i in 0..self.n {
            self.push(s.pos.get(i));
        }
        for v in s.vel.iter().take(self.n) {
            self.push(*v);
        }
        for a in s.acc.iter().take(self.n) {
            self.push(*a);
        }
        self.push(s.speed);
        self.buf.extend_from_slice(s.line.to_string().as_bytes());
        self.buf.push(b'\n');
        if self.buf.len() > 1 << 16 {
            self.flush_buf();
        }
    }
}

/// Refuses a `--period` so short that the `filter` profile's moving
/// average would hold more than [`MAX_FILTER_SAMPLES`] samples.
pub fn check_period(
    machine: &Machine,
    period_s: f64,
    profile: Option<ProfileShape>,
) -> Result<(), String> {
    let shape = profile.unwrap_or(machine.motion.profile);
    let t = filter_time(machine, shape);
    let n = filter_samples(t, period_s);
    if n > MAX_FILTER_SAMPLES {
        return Err(format!(
            "--period {period_s} samples the filter profile's {t} s average {n} times, \
             more than {MAX_FILTER_SAMPLES}: use a longer period"
        ));
    }
    Ok(())
}

/// The sink behind `--format trace`.
pub struct TraceSink<W: Write> {
    planner: Planner<Sampler<Smoothed<CsvRows<W>>>>,
}

impl<W: Write> TraceSink<W> {
    /// Samples every `period_s` on `machine`, writing CSV to `out`.
    pub fn new(
        mut out: W,
        machine: &Machine,
        period_s: f64,
        profile: Option<ProfileShape>,
    ) -> Self {
        let n = machine.axes.len();
        let letters: Vec<char> = machine
            .axes
            .iter()
            .map(|a| char::from(a.letter.to_ascii_lowercase()))
            .collect();
        let mut header = String::from("t");
        for prefix in ["", "v", "a"] {
            for l in &letters {
                header.push_str(&format!(",{prefix}{l}"));
            }
        }
        header.push_str(",speed,line\n");
        let error = out.write_all(header.as_bytes()).err();
        let rows = CsvRows {
            out,
            n,
            buf: Vec::with_capacity(1 << 17),
            error,
        };
        let shape = profile.unwrap_or(machine.motion.profile);
        // The filter profile's moving average (a pass-through otherwise).
        let filtered = Smoothed::new(filter_time(machine, shape), period_s, machine.start, rows);
        let sampler = Sampler::new(period_s, machine.start, filtered);
        TraceSink {
            planner: Planner::with_profile(machine, shape, sampler),
        }
    }
}

impl<W: Write> Sink for TraceSink<W> {
    fn event(&mut self, event: &Event) {
        self.planner.event(event);
    }
    fn is_done(&self) -> bool {
        self.planner.timeline().sink().sink().error.is_some()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.planner.flush();
        let sampler = self.planner.timeline_mut();
        sampler.finish();
        let rows = sampler.sink_mut().sink_mut();
        rows.flush_buf();
        if let Some(e) = rows.error.take() {
            return Err(e);
        }
        rows.out.flush()
    }
}
