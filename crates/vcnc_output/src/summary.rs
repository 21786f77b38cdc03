//! The numbers `vcnc check` prints: cycle time, rapid and cutting distance,
//! extents, tools and spindle speeds.
//!
//! Cycle time here is kinematic-free: a rapid takes as long as its slowest
//! axis at that axis's rapid rate, a cut takes its path length over the feed
//! (capped by the axes' maximum feed; per-revolution feeds and threads use
//! the spindle speed in force), plus dwells. Acceleration is the planner's
//! business (a later crate); this is the distance/feed estimate.

use vcnc_interp::arc::arc_bounds;
use vcnc_interp::{Event, Feed, Machine, Plane, Pos, Sink};

/// Accumulates the summary of a run.
#[derive(Debug, Clone)]
pub struct Summary {
    rapid_rates: Vec<f64>,
    max_feeds: Vec<f64>,
    letters: Vec<u8>,
    pos: Pos,
    rpm: f64,
    /// Events seen.
    pub events: u64,
    /// Estimated cycle time.
    pub cycle_time_s: f64,
    /// Rapid path length.
    pub rapid_mm: f64,
    /// Cutting path length (feeds, arcs, threads, skips).
    pub cut_mm: f64,
    /// Smallest and largest machine coordinate per axis (`None` if no motion).
    pub extents: Option<(Pos, Pos)>,
    /// Tools changed to, in order of first use.
    pub tools: Vec<u32>,
    /// Slowest and fastest spindle speed commanded, rpm.
    pub spindle_rpm: Option<(f64, f64)>,
    /// Cutting moves whose time is unknown (feed per rev with the spindle stopped).
    pub untimed_moves: u64,
}

impl Summary {
    /// An empty summary for `machine`, starting at its power-on position.
    pub fn new(machine: &Machine) -> Summary {
        Summary {
            rapid_rates: machine
                .axes
                .iter()
                .map(|a| a.rapid_mm_per_min / 60.0)
                .collect(),
            max_feeds: machine.axes.iter().map(|a| a.max_feed_mm_per_min).collect(),
            letters: machine.axes.iter().map(|a| a.letter).collect(),
            pos: machine.start,
            rpm: 0.0,
            events: 0,
            cycle_time_s: 0.0,
            rapid_mm: 0.0,
            cut_mm: 0.0,
            extents: None,
            tools: Vec::new(),
            spindle_rpm: None,
            untimed_moves: 0,
        }
    }

    /// The machine's axis letters, in event order.
    pub fn axis_letters(&self) -> &[u8] {
        &self.letters
    }

    fn extend(&mut self, lo: Pos, hi: Pos) {
        let (mut a, mut b) = self.extents.unwrap_or((lo, hi));
        for i in 0..self.letters.len() {
            a.set(i, a.get(i).min(lo.get(i)));
            b.set(i, b.get(i).max(hi.get(i)));
        }
        self.extents = Some((a, b));
    }

    fn line_box(&mut self, to: &Pos) {
        let (mut lo, mut hi) = (self.pos, self.pos);
        for i in 0..self.letters.len() {
            lo.set(i, lo.get(i).min(to.get(i)));
            hi.set(i, hi.get(i).max(to.get(i)));
        }
        self.extend(lo, hi);
    }

    fn distance(&self, to: &Pos) -> f64 {
        (0..self.letters.len())
            .map(|i| (to.get(i) - self.pos.get(i)).powi(2))
            .sum::<f64>()
            .sqrt()
    }

    /// Cut time at `feed` over `len_mm`, capped by the slowest axis limit.
    fn cut_time(&mut self, len_mm: f64, feed: Feed, cap: f64) -> f64 {
        let per_min = match feed {
            Feed::PerMin(f) => f,
            Feed::PerRev(f) => f * self.rpm,
        };
        let per_min = per_min.min(cap);
        if per_min <= 0.0 {
            self.untimed_moves += 1;
            return 0.0;
        }
        len_mm / per_min * 60.0
    }

    /// The fastest path feed a straight move to `to` allows: each moving
    /// axis stays within its own maximum feed.
    fn line_cap(&self, to: &Pos, len_mm: f64) -> f64 {
        (0..self.letters.len())
            .filter_map(|i| {
                let d = (to.get(i) - self.pos.get(i)).abs();
                (d > 1e-12).then(|| self.max_feeds[i] * len_mm / d)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Length of an arc or helix, its plane axes, and the fastest path
    /// feed its axes allow: each plane axis moves at the path speed times
    /// `r·sweep/L` times |sin| or |cos| of the angle (its peak over the
    /// sweep), the normal axis at `|h|/L` of it.
    fn arc_len(
        &self,
        to: &Pos,
        center: &Pos,
        plane: Plane,
        cw: bool,
    ) -> (f64, (usize, usize), f64) {
        use std::f64::consts::{FRAC_PI_2, PI, TAU};
        let idx = |l: u8| self.letters.iter().position(|x| *x == l);
        let [a, b, n] = plane.letters();
        let (ia, ib) = (idx(a).unwrap_or(0), idx(b).unwrap_or(0));
        let (sa, sb) = (
            self.pos.get(ia) - center.get(ia),
            self.pos.get(ib) - center.get(ib),
        );
        let (ea, eb) = (to.get(ia) - center.get(ia), to.get(ib) - center.get(ib));
        let r = sa.hypot(sb);
        let a0 = sb.atan2(sa);
        let mut sweep = (eb.atan2(ea) - a0).rem_euclid(TAU);
        if cw {
            sweep = (TAU - sweep) % TAU;
        }
        if sweep < 1e-12 {
            sweep = TAU;
        }
        let inn = idx(n);
        let h = inn.map_or(0.0, |i| to.get(i) - self.pos.get(i));
        let planar = r * sweep;
        let len = planar.hypot(h);
        // Angles along the sweep, in the arc's direction.
        let passes = |phi: f64| {
            let d = if cw {
                (a0 - phi).rem_euclid(TAU)
            } else {
                (phi - a0).rem_euclid(TAU)
            };
            d <= sweep
        };
        let a1 = if cw { a0 - sweep } else { a0 + sweep };
        let peak_sin = if passes(FRAC_PI_2) || passes(3.0 * FRAC_PI_2) {
            1.0
        } else {
            a0.sin().abs().max(a1.sin().abs())
        };
        let peak_cos = if passes(0.0) || passes(PI) {
            1.0
        } else {
            a0.cos().abs().max(a1.cos().abs())
        };
        let feed_max = |i: usize| self.max_feeds.get(i).copied().unwrap_or(f64::INFINITY);
        let share = if len > 0.0 { planar / len } else { 0.0 };
        let mut cap = f64::INFINITY;
        for (i, k) in [(ia, peak_sin), (ib, peak_cos)] {
            if share * k > 1e-12 {
                cap = cap.min(feed_max(i) / (share * k));
            }
        }
        if let Some(i) = inn.filter(|_| h.abs() > 1e-12) {
            cap = cap.min(feed_max(i) * len / h.abs());
        }
        (len, (ia, ib), cap)
    }
}

impl Sink for Summary {
    fn event(&mut self, event: &Event) {
        self.events += 1;
        match event {
            Event::Rapid { to, .. } => {
                let t = (0..self.letters.len())
                    .map(|i| (to.get(i) - self.pos.get(i)).abs() / self.rapid_rates[i])
                    .fold(0.0, f64::max);
                self.cycle_time_s += t;
                self.rapid_mm += self.distance(to);
                self.line_box(to);
                self.pos = *to;
            }
            Event::Feed { to, feed, .. } | Event::Skip { to, feed, .. } => {
                let d = self.distance(to);
                self.cut_mm += d;
                let cap = self.line_cap(to, d);
                self.cycle_time_s += self.cut_time(d, *feed, cap);
                self.line_box(to);
                self.pos = *to;
            }
            Event::Thread { to, lead_mm, .. } => {
                let d = self.distance(to);
                self.cut_mm += d;
                let cap = self.line_cap(to, d);
                self.cycle_time_s += self.cut_time(d, Feed::PerRev(*lead_mm), cap);
                self.line_box(to);
                self.pos = *to;
            }
            Event::Arc {
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => {
                let cw = *dir == vcnc_interp::ArcDir::Cw;
                let (len, axes, cap) = self.arc_len(to, center, *plane, cw);
                self.cut_mm += len;
                self.cycle_time_s += self.cut_time(len, *feed, cap);
                let (lo, hi) = arc_bounds(self.pos, *to, *center, axes, *dir, self.letters.len());
                self.extend(lo, hi);
                self.pos = *to;
            }
            Event::Dwell { seconds, .. } => self.cycle_time_s += seconds,
            Event::ToolChange { tool, .. } if !self.tools.contains(tool) => self.tools.push(*tool),
            Event::Spindle { rpm, .. } => {
                self.rpm = *rpm;
                if *rpm > 0.0 {
                    let (lo, hi) = self.spindle_rpm.unwrap_or((*rpm, *rpm));
                    self.spindle_rpm = Some((lo.min(*rpm), hi.max(*rpm)));
                }
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_interp::Loc;

    /// Regression: a cut was capped by the slowest maximum feed of all axes
    /// (Z, 8000 mm/min), not of the axes that move.
    #[test]
    fn a_cut_is_capped_only_by_the_axes_that_move() {
        let m = Machine::default_mill();
        let mut s = Summary::new(&m);
        let mut to = m.start;
        to.set(0, 900.0);
        s.event(&Event::Feed {
            loc: Loc::default(),
            to,
            feed: Feed::PerMin(9000.0),
            exact_stop: false,
        });
        assert!((s.cycle_time_s - 6.0).abs() < 1e-9, "{}", s.cycle_time_s);
        // Along Z the cap is Z's own 8000 mm/min: 80 mm takes 0.6 s.
        let mut down = to;
        down.set(2, -80.0);
        s.event(&Event::Feed {
            loc: Loc::default(),
            to: down,
            feed: Feed::PerMin(9000.0),
            exact_stop: false,
        });
        assert!((s.cycle_time_s - 6.6).abs() < 1e-9, "{}", s.cycle_time_s);
    }

    /// Regression: a helix ignored its normal axis's limit, and a shallow
    /// arc was capped by a plane axis that barely moves.
    #[test]
    fn arcs_are_capped_by_how_fast_each_axis_really_moves() {
        let m = Machine::default_mill();
        let arc = |s: &mut Summary, to: Pos, center: Pos, dir| {
            s.event(&Event::Arc {
                loc: Loc::default(),
                to,
                center,
                plane: Plane::Xy,
                dir,
                feed: Feed::PerMin(10_000.0),
                exact_stop: false,
            });
        };
        // Helix: a full circle of radius 10 rising 100 mm: L = √((20π)² + 100²).
        // Z may move 8000 mm/min, so the path feed is at most 8000·L/100.
        let mut s = Summary::new(&m);
        let (mut to, mut center) = (m.start, m.start);
        to.set(2, 100.0);
        center.set(0, 10.0);
        arc(&mut s, to, center, vcnc_interp::ArcDir::Ccw);
        let len = (20.0 * std::f64::consts::PI).hypot(100.0);
        let expected = len / (8000.0 * len / 100.0) * 60.0;
        assert!(
            (s.cycle_time_s - expected).abs() < 1e-9,
            "{} vs {expected}",
            s.cycle_time_s
        );
        // A shallow clockwise arc over the top of a circle of radius 1000 on
        // a machine whose Y may only go 1000 mm/min: Y moves by 0.05 mm while
        // X moves 20, so the 10000 mm/min feed is not capped by Y's limit.
        let text = vcnc_interp::machine::DEFAULT_MILL_TOML;
        let y = text.find("letter = \"y\"").unwrap();
        let slow_y = format!(
            "{}{}",
            &text[..y],
            text[y..].replacen(
                "max_feed_mm_per_min = 10000.0",
                "max_feed_mm_per_min = 1000.0",
                1
            )
        );
        let m = Machine::from_toml(&slow_y).unwrap();
        let mut s = Summary::new(&m);
        let mut from = m.start;
        from.set(0, -10.0);
        from.set(1, 999.95);
        s.pos = from;
        let mut to = from;
        to.set(0, 10.0);
        let mut c = m.start;
        c.set(2, 0.0);
        arc(&mut s, to, c, vcnc_interp::ArcDir::Cw);
        assert!(s.cut_mm < 21.0, "the short way over the top: {}", s.cut_mm);
        let capped = s.cycle_time_s;
        let length = s.cut_mm;
        assert!(
            (capped - length / 10_000.0 * 60.0).abs() < 1e-6,
            "{capped} vs {}",
            length / 10_000.0 * 60.0
        );
    }
}
