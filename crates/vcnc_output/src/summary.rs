//! The numbers `vcnc check` prints: cycle time, rapid and cutting distance,
//! extents, tools, holes per tool, operator waits and spindle speeds.
//!
//! Extents are kept twice: in machine coordinates, and in work
//! coordinates — each move seen from the frame in force (`frame` events:
//! `machine = linear · work + origin + tool_offset`), so that a part
//! programmed from 0 to 50 on a G54 of X-300 reads 0 .. 50 there. Moves are
//! boxed in machine coordinates while one frame lasts, and that box is
//! carried into the work box when the frame changes (exactly under a plain
//! offset; under a rotation, the box of its rotated corners).
//!
//! Cycle time here is kinematic-free: a rapid takes as long as its slowest
//! axis at that axis's rapid rate, a cut takes its path length over the feed
//! (capped by the axes' maximum feed; per-revolution feeds and threads use
//! the spindle speed in force), plus dwells. Acceleration is the planner's
//! business (a later crate); this is the distance/feed estimate.

use std::collections::BTreeMap;
use vcnc_core::geometry::{ArcPath, PlaneAxes};
use vcnc_core::{ArcDir, Code, Diagnostic, Event, Feed, MAX_AXES, Machine, Plane, Pos, Sink};

/// One value per axis slot from the machine's axes, `unused` beyond them.
fn per_axis(
    machine: &Machine,
    f: impl Fn(&vcnc_core::machine::Axis) -> f64,
    unused: f64,
) -> [f64; vcnc_core::MAX_AXES] {
    let mut out = [unused; vcnc_core::MAX_AXES];
    for (slot, a) in out.iter_mut().zip(&machine.axes) {
        *slot = f(a);
    }
    out
}

/// Warnings kept whole (with their text and place) by a summary; beyond,
/// they are only counted.
pub const KEPT_WARNINGS: usize = 100;

/// Accumulates the summary of a run.
#[derive(Debug, Clone)]
pub struct Summary {
    /// Per axis, in event order (unused slots: infinite rate, no feed cap).
    rapid_rates: [f64; vcnc_core::MAX_AXES],
    max_feeds: [f64; vcnc_core::MAX_AXES],
    /// 1/`max_feeds` and a margin of 2e-12 ([`Summary::under_line_cap`]).
    per_max_feed_over: [f64; vcnc_core::MAX_AXES],
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
    /// The same for the programmed path of the blocks cutter compensation
    /// offset (`contour` events; `None` without compensation).
    pub contour_extents: Option<(Pos, Pos)>,
    /// Work-coordinate extents of the frames that ended (see
    /// [`Summary::work_extents`]).
    work_done: Option<(Pos, Pos)>,
    /// Machine box of the moves made in the frame in force.
    in_frame: Option<(Pos, Pos)>,
    /// The frame in force.
    frame: vcnc_core::FrameInfo,
    /// Tools changed to, in order of first use.
    pub tools: Vec<u32>,
    /// Slowest and fastest spindle speed commanded, rpm.
    pub spindle_rpm: Option<(f64, f64)>,
    /// Cutting moves whose time is unknown (feed per rev with the spindle stopped).
    pub untimed_moves: u64,
    /// Holes drilled by each tool, in order of first hole (`None`: before
    /// any tool change).
    pub holes: Vec<(Option<u32>, u64)>,
    /// Times the program waits for the operator (not in the cycle time).
    pub waits: u64,
    /// Warnings by code.
    pub warning_counts: BTreeMap<Code, u64>,
    /// The first warnings (at most [`KEPT_WARNINGS`]).
    pub warnings: Vec<Diagnostic>,
    /// The alarms, in order: one (the run's end), or under keep-going
    /// every alarm the run went on after (at most [`KEPT_WARNINGS`]).
    pub alarms: Vec<Diagnostic>,
    /// Auxiliary (machine-builder) M codes passed to the machine.
    pub aux_codes: u64,
    /// Messages of macro programs (#3006 stops, MSG).
    pub messages: u64,
    /// Variables the program read while nothing had set them (name, line,
    /// file).
    pub unset_variables: Vec<vcnc_core::UnsetVariable>,
    tool: Option<u32>,
}

impl Summary {
    /// An empty summary for `machine`, starting at its power-on position.
    pub fn new(machine: &Machine) -> Summary {
        Summary {
            rapid_rates: per_axis(machine, |a| a.rapid_mm_per_min / 60.0, f64::INFINITY),
            max_feeds: per_axis(machine, |a| a.max_feed_mm_per_min, f64::INFINITY),
            per_max_feed_over: per_axis(machine, |a| (1.0 + 2e-12) / a.max_feed_mm_per_min, 0.0),
            letters: machine.axes.iter().map(|a| a.letter).collect(),
            pos: machine.start,
            rpm: 0.0,
            events: 0,
            cycle_time_s: 0.0,
            rapid_mm: 0.0,
            cut_mm: 0.0,
            extents: None,
            contour_extents: None,
            work_done: None,
            in_frame: None,
            frame: vcnc_core::FrameInfo {
                origin: Pos::default(),
                linear: None,
                tool_offset: Pos::default(),
            },
            tools: Vec::new(),
            spindle_rpm: None,
            untimed_moves: 0,
            holes: Vec::new(),
            waits: 0,
            warning_counts: BTreeMap::new(),
            warnings: Vec::new(),
            alarms: Vec::new(),
            aux_codes: 0,
            messages: 0,
            unset_variables: Vec::new(),
            tool: None,
        }
    }

    /// The machine's axis letters, in event order.
    pub fn axis_letters(&self) -> &[u8] {
        &self.letters
    }

    /// Warnings in all.
    pub fn warning_total(&self) -> u64 {
        self.warning_counts.values().sum()
    }

    /// Whether axis `i` belongs in a report: a linear axis always, a rotary
    /// one when the program moved it.
    pub fn reports_axis(&self, i: usize) -> bool {
        let linear = matches!(self.letters.get(i), Some(b'X' | b'Y' | b'Z'));
        linear
            || self
                .extents
                .is_some_and(|(lo, hi)| lo.get(i) != 0.0 || hi.get(i) != 0.0)
    }

    /// Smallest and largest work coordinate per axis: where the moves'
    /// end points and arcs went, seen from the frame each ran in (`None`
    /// if no motion). The power-on position is not in it.
    pub fn work_extents(&self) -> Option<(Pos, Pos)> {
        let now = self
            .in_frame
            .map(|b| work_box(&self.frame, &self.letters, b));
        union(self.work_done, now)
    }

    /// A new frame: the moves of the last one go into the work box.
    fn frame_changed(&mut self, frame: &vcnc_core::FrameInfo) {
        if let Some(b) = self.in_frame.take() {
            let done = work_box(&self.frame, &self.letters, b);
            self.work_done = union(self.work_done, Some(done));
        }
        self.frame = *frame;
    }

    fn extend(&mut self, lo: Pos, hi: Pos) {
        self.in_frame = union(self.in_frame, Some((lo, hi)));
        let (mut a, mut b) = self.extents.unwrap_or((lo, hi));
        // Every slot: the unused ones stay 0 on both sides.
        for i in 0..vcnc_core::MAX_AXES {
            if lo.0[i] < a.0[i] {
                a.0[i] = lo.0[i];
            }
            if hi.0[i] > b.0[i] {
                b.0[i] = hi.0[i];
            }
        }
        self.extents = Some((a, b));
    }

    /// A straight move to `to`: the box of a segment is the box of its ends,
    /// and its start is already inside the extents (but for the first move,
    /// whose start — the power-on position — the machine box keeps).
    fn line_box(&mut self, to: &Pos) {
        if self.extents.is_none() {
            self.extents = Some((self.pos, self.pos));
        }
        self.extend(*to, *to);
    }

    /// Length of the straight move to `to`, and how far each axis moves.
    fn line(&self, to: &Pos) -> (f64, [f64; MAX_AXES]) {
        let mut d = [0.0f64; MAX_AXES];
        let mut sq = 0.0;
        for ((di, t), p) in d.iter_mut().zip(&to.0).zip(&self.pos.0) {
            *di = (t - p).abs();
            sq += *di * *di;
        }
        (sq.sqrt(), d)
    }

    /// The fastest path feed of a straight move of `len` mm that moves each
    /// axis by `d`: each moving axis stays within its own maximum feed.
    fn line_cap(&self, len: f64, d: &[f64; MAX_AXES]) -> f64 {
        // The axis that reaches its cap first: max·len/d smallest, i.e.
        // d/max largest.
        let mut worst = 0.0f64;
        for (di, max) in d.iter().zip(&self.max_feeds) {
            if *di > 1e-12 {
                worst = worst.max(di / max);
            }
        }
        if worst > 0.0 {
            len / worst
        } else {
            f64::INFINITY
        }
    }

    /// Whether the feed `per_min` is below [`Summary::line_cap`], shown
    /// without its divisions: per_min·d/max·(1 + 2e-12) ≤ len on every
    /// axis puts per_min below every len·max/d, and so below the cap, by
    /// far more than their rounding. Axes that do not move only make the
    /// test stricter, and NaN is passed over as `f64::max` passes it over
    /// in the cap. A feed within 1e±100 keeps the products normal where
    /// they matter; out of it, or NaN, the answer is false.
    #[inline]
    fn under_line_cap(&self, per_min: f64, len: f64, d: &[f64; MAX_AXES]) -> bool {
        let mut most = 0.0f64;
        for (di, r) in d.iter().zip(&self.per_max_feed_over) {
            let share = di * r;
            most = if share > most { share } else { most };
        }
        (1e-100..=1e100).contains(&per_min) && len <= 1e100 && per_min * most <= len
    }

    fn distance(&self, to: &Pos) -> f64 {
        self.line(to).0
    }

    /// The feed of a cut, mm/min, before any cap.
    fn per_min(&self, feed: Feed) -> f64 {
        match feed {
            Feed::PerMin(f) => f,
            Feed::PerRev(f) => f * self.rpm,
        }
    }

    /// Cut time at `feed` over a straight `len_mm` moving each axis by `d`,
    /// capped by the slowest axis limit: the cap is worked out only when
    /// the feed may reach it (the same time, two divisions fewer a block).
    fn line_cut_time(&mut self, len_mm: f64, feed: Feed, d: &[f64; MAX_AXES]) -> f64 {
        let per_min = self.per_min(feed);
        let cap = if self.under_line_cap(per_min, len_mm, d) {
            f64::INFINITY
        } else {
            self.line_cap(len_mm, d)
        };
        self.cut_time(len_mm, feed, cap)
    }

    /// Cut time at `feed` over `len_mm`, capped by the slowest axis limit.
    fn cut_time(&mut self, len_mm: f64, feed: Feed, cap: f64) -> f64 {
        let per_min = self.per_min(feed).min(cap);
        if per_min <= 0.0 {
            self.untimed_moves += 1;
            return 0.0;
        }
        len_mm / per_min * 60.0
    }

    /// The arc from the current position, and the fastest path feed its
    /// axes allow: each plane axis moves at the path speed times
    /// `r·sweep/L` times |sin| or |cos| of the angle (its peak over the
    /// sweep), the normal axis at `|h|/L` of it.
    fn arc_path(&self, to: &Pos, center: &Pos, plane: Plane, dir: ArcDir) -> (ArcPath, f64) {
        let idx = |l: u8| self.letters.iter().position(|x| *x == l);
        let [a, b, n] = plane.letters();
        let axes = PlaneAxes {
            a: idx(a).unwrap_or(0),
            b: idx(b).unwrap_or(0),
            n: idx(n),
        };
        let path = ArcPath::new(self.pos, *to, *center, axes, dir);
        let (len, planar, h) = (path.length(), path.planar_length(), path.rise());
        let (peak_sin, peak_cos) = path.peak_sin_cos();
        let feed_max = |i: usize| self.max_feeds.get(i).copied().unwrap_or(f64::INFINITY);
        let share = if len > 0.0 { planar / len } else { 0.0 };
        let mut cap = f64::INFINITY;
        for (i, k) in [(axes.a, peak_sin), (axes.b, peak_cos)] {
            if share * k > 1e-12 {
                cap = cap.min(feed_max(i) / (share * k));
            }
        }
        if let Some(i) = axes.n.filter(|_| h.abs() > 1e-12) {
            cap = cap.min(feed_max(i) * len / h.abs());
        }
        (path, cap)
    }
}

impl Sink for Summary {
    fn event(&mut self, event: &Event) {
        self.events += 1;
        match event {
            Event::Rapid { to, .. } => {
                let mut t = 0.0f64;
                for i in 0..vcnc_core::MAX_AXES {
                    t = t.max((to.0[i] - self.pos.0[i]).abs() / self.rapid_rates[i]);
                }
                self.cycle_time_s += t;
                self.rapid_mm += self.distance(to);
                self.line_box(to);
                self.pos = *to;
            }
            Event::Feed { to, feed, .. } | Event::Skip { to, feed, .. } => {
                let (len, d) = self.line(to);
                self.cut_mm += len;
                self.cycle_time_s += self.line_cut_time(len, *feed, &d);
                self.line_box(to);
                self.pos = *to;
            }
            Event::Nurbs { curve, feed, .. } => {
                // The curve as chords within 1 µm, each at the feed capped
                // by its own axes.
                let mut untimed = false;
                for p in curve.flatten(0.001) {
                    let (len, d) = self.line(&p);
                    let before = self.untimed_moves;
                    self.cut_mm += len;
                    self.cycle_time_s += self.line_cut_time(len, *feed, &d);
                    untimed |= self.untimed_moves > before;
                    self.untimed_moves = before;
                    self.line_box(&p);
                    self.pos = p;
                }
                self.untimed_moves += u64::from(untimed);
            }
            Event::Thread { to, lead_mm, .. } => {
                let (len, d) = self.line(to);
                self.cut_mm += len;
                self.cycle_time_s += self.line_cut_time(len, Feed::PerRev(*lead_mm), &d);
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
                let (path, cap) = self.arc_path(to, center, *plane, *dir);
                let len = path.length();
                self.cut_mm += len;
                self.cycle_time_s += self.cut_time(len, *feed, cap);
                let (lo, hi) = path.bounds(self.letters.len());
                self.extend(lo, hi);
                self.pos = *to;
            }
            Event::Contour { from, to, arc, .. } => {
                let (lo, hi) = match arc {
                    Some((center, plane, dir)) => {
                        let idx = |l: u8| self.letters.iter().position(|x| *x == l);
                        let [a, b, n] = plane.letters();
                        let axes = PlaneAxes {
                            a: idx(a).unwrap_or(0),
                            b: idx(b).unwrap_or(0),
                            n: idx(n),
                        };
                        ArcPath::new(*from, *to, *center, axes, *dir).bounds(self.letters.len())
                    }
                    None => {
                        let (mut lo, mut hi) = (*from, *from);
                        for i in 0..self.letters.len() {
                            lo.0[i] = lo.0[i].min(to.0[i]);
                            hi.0[i] = hi.0[i].max(to.0[i]);
                        }
                        (lo, hi)
                    }
                };
                let (mut a, mut b) = self.contour_extents.unwrap_or((lo, hi));
                for i in 0..self.letters.len() {
                    a.0[i] = a.0[i].min(lo.0[i]);
                    b.0[i] = b.0[i].max(hi.0[i]);
                }
                self.contour_extents = Some((a, b));
            }
            Event::Frame { frame, .. } => self.frame_changed(frame),
            Event::Dwell { seconds, .. } => self.cycle_time_s += seconds,
            Event::ToolChange { tool, .. } => {
                self.tool = Some(*tool);
                if !self.tools.contains(tool) {
                    self.tools.push(*tool);
                }
            }
            Event::Hole { .. } => match self.holes.iter_mut().find(|(t, _)| *t == self.tool) {
                Some((_, n)) => *n += 1,
                None => self.holes.push((self.tool, 1)),
            },
            Event::Wait { .. } => self.waits += 1,
            Event::Aux { .. } => self.aux_codes += 1,
            Event::Message { stop, .. } => {
                self.messages += 1;
                // A #3006 stop waits for the operator like M00.
                self.waits += u64::from(*stop);
            }
            Event::UnsetVariables { variables, .. } => {
                self.unset_variables.extend(variables.iter().cloned());
            }
            Event::Alarm(d) if self.alarms.len() < KEPT_WARNINGS => {
                self.alarms.push(d.clone());
            }
            Event::Warning(d) => {
                *self.warning_counts.entry(d.code).or_insert(0) += 1;
                if self.warnings.len() < KEPT_WARNINGS {
                    self.warnings.push(d.clone());
                }
            }
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

/// The smallest box holding both.
fn union(a: Option<(Pos, Pos)>, b: Option<(Pos, Pos)>) -> Option<(Pos, Pos)> {
    match (a, b) {
        (None, x) | (x, None) => x,
        (Some((mut lo, mut hi)), Some((l, h))) => {
            for i in 0..vcnc_core::MAX_AXES {
                lo.0[i] = lo.0[i].min(l.0[i]);
                hi.0[i] = hi.0[i].max(h.0[i]);
            }
            Some((lo, hi))
        }
    }
}

/// A machine box in work coordinates under `frame`: the offset taken
/// away, and under a rotation, scaling or mirror the box of the eight
/// corners taken back through the inverse of its linear part.
fn work_box(frame: &vcnc_core::FrameInfo, letters: &[u8], (lo, hi): (Pos, Pos)) -> (Pos, Pos) {
    let shift = frame.origin.plus(frame.tool_offset);
    let (lo, hi) = (lo.minus(shift), hi.minus(shift));
    let Some(inverse) = frame.linear.as_ref().and_then(invert3) else {
        return (lo, hi);
    };
    let xyz: Vec<Option<usize>> = [b'X', b'Y', b'Z']
        .iter()
        .map(|l| letters.iter().position(|x| x == l))
        .collect();
    let (mut out_lo, mut out_hi) = (lo, hi);
    for i in xyz.iter().flatten() {
        out_lo.set(*i, f64::INFINITY);
        out_hi.set(*i, f64::NEG_INFINITY);
    }
    for corner in 0..8u8 {
        let mut v = [0.0f64; 3];
        for (k, i) in xyz.iter().enumerate() {
            if let (Some(i), Some(slot)) = (i, v.get_mut(k)) {
                *slot = if corner & (1 << k) == 0 {
                    lo.get(*i)
                } else {
                    hi.get(*i)
                };
            }
        }
        for (row, i) in inverse.iter().zip(&xyz) {
            if let Some(i) = i {
                let w = row[0] * v[0] + row[1] * v[1] + row[2] * v[2];
                out_lo.set(*i, out_lo.get(*i).min(w));
                out_hi.set(*i, out_hi.get(*i).max(w));
            }
        }
    }
    (out_lo, out_hi)
}

/// The inverse of a 3 × 3 matrix (`None` when singular).
fn invert3(m: &[[f64; 3]; 3]) -> Option<[[f64; 3]; 3]> {
    let [[a, b, c], [d, e, f], [g, h, i]] = *m;
    let det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    if det.abs() < 1e-12 || !det.is_finite() {
        return None;
    }
    let r = 1.0 / det;
    Some([
        [
            (e * i - f * h) * r,
            (c * h - b * i) * r,
            (b * f - c * e) * r,
        ],
        [
            (f * g - d * i) * r,
            (a * i - c * g) * r,
            (c * d - a * f) * r,
        ],
        [
            (d * h - e * g) * r,
            (b * g - a * h) * r,
            (a * e - b * d) * r,
        ],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_core::Loc;

    /// The cap of a straight cut is skipped only when the feed is below
    /// it: the time is the one the cap gives. Feeds are drawn around the
    /// cap itself, where the test must hold back.
    #[test]
    fn a_line_cap_is_skipped_only_below_it() {
        let m = Machine::default_mill();
        let s = Summary::new(&m);
        let mut seed: u64 = 20_261_122;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut skipped, mut kept) = (0, 0);
        for _ in 0..200_000 {
            let mut to = m.start;
            for i in 0..MAX_AXES {
                if next() < 0.6 {
                    to.0[i] += (next() - 0.5) * 10f64.powf(6.0 * next() - 4.0);
                }
            }
            let (len, d) = s.line(&to);
            let cap = s.line_cap(len, &d);
            let per_min = if cap.is_finite() && next() < 0.7 {
                cap * (1.0 + (next() - 0.5) * 1e-10)
            } else {
                20_000.0 * next()
            };
            if s.under_line_cap(per_min, len, &d) {
                skipped += 1;
                assert_eq!(
                    per_min.min(cap).to_bits(),
                    per_min.to_bits(),
                    "{per_min} {cap}"
                );
            } else {
                kept += 1;
            }
        }
        assert!(skipped > 10_000 && kept > 10_000, "{skipped} {kept}");
    }

    fn feed_to(s: &mut Summary, x: f64, y: f64, z: f64) {
        let mut to = Pos::default();
        to.set(0, x);
        to.set(1, y);
        to.set(2, z);
        s.event(&Event::Feed {
            loc: Loc::default(),
            to,
            feed: Feed::PerMin(1000.0),
            exact_stop: false,
        });
    }

    fn frame(origin: [f64; 3], linear: Option<[[f64; 3]; 3]>, tool_z: f64) -> Event {
        let mut o = Pos::default();
        for (i, v) in origin.iter().enumerate() {
            o.set(i, *v);
        }
        let mut tool = Pos::default();
        tool.set(2, tool_z);
        Event::Frame {
            loc: Loc::default(),
            frame: vcnc_core::FrameInfo {
                origin: o,
                linear,
                tool_offset: tool,
            },
        }
    }

    /// Work extents under a work offset and a tool length: machine minus
    /// origin minus tool offset, by hand: (110, 60, 15) - (100, 50, 0) -
    /// (0, 0, 10) = (10, 10, 5), (130, 60, 5) → (30, 10, -5). The power-on
    /// position (machine 0, 0, 0) is in the machine extents only.
    #[test]
    fn work_extents_take_the_frame_away() {
        let m = Machine::default_mill();
        let mut s = Summary::new(&m);
        s.event(&frame([100.0, 50.0, 0.0], None, 10.0));
        feed_to(&mut s, 110.0, 60.0, 15.0);
        feed_to(&mut s, 130.0, 60.0, 5.0);
        let (lo, hi) = s.work_extents().unwrap();
        assert_eq!((lo.get(0), lo.get(1), lo.get(2)), (10.0, 10.0, -5.0));
        assert_eq!((hi.get(0), hi.get(1), hi.get(2)), (30.0, 10.0, 5.0));
        let (lo, _) = s.extents.unwrap();
        assert_eq!(lo.get(0), 0.0);
        // Back to the zero frame: the moves after it count as they are, the
        // ones before keep their work coordinates.
        s.event(&frame([0.0; 3], None, 0.0));
        feed_to(&mut s, 40.0, 0.0, 0.0);
        let (lo, hi) = s.work_extents().unwrap();
        assert_eq!((lo.get(1), hi.get(0)), (0.0, 40.0));
    }

    /// Under G68 R90 (machine = R·work + origin, R turning X onto Y), the
    /// machine point (0, 10) is the work point (10, 0); a box is taken back
    /// through R's inverse corner by corner.
    #[test]
    fn work_extents_undo_a_rotation() {
        let m = Machine::default_mill();
        let mut s = Summary::new(&m);
        let r90 = [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        s.event(&frame([0.0; 3], Some(r90), 0.0));
        feed_to(&mut s, 0.0, 10.0, 0.0);
        feed_to(&mut s, -5.0, 10.0, 0.0);
        let (lo, hi) = s.work_extents().unwrap();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(
            close(lo.get(0), 10.0) && close(hi.get(0), 10.0),
            "{lo:?} {hi:?}"
        );
        assert!(
            close(lo.get(1), 0.0) && close(hi.get(1), 5.0),
            "{lo:?} {hi:?}"
        );
    }

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
        arc(&mut s, to, center, ArcDir::Ccw);
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
        let text = vcnc_core::machine::DEFAULT_MILL_TOML;
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
        arc(&mut s, to, c, ArcDir::Cw);
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
