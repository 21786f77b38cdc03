//! The look-ahead planner: a [`Sink`] of events that turns moves into
//! timed segments on the machine model and hands them, in order, to a
//! [`Timeline`].
//!
//! ```text
//!  events ─▶ segment (limits along the path, corner speed cap with the
//!            previous move, how it ends: stop / blend / G99 tangent)
//!        ─▶ window of at most N segments (the look-ahead)
//!            backward pass on every push: entry_max[i] = min(cap[i],
//!              reach(entry_max[i+1], len[i]))   — stop where nothing changes
//!            the newest segment is assumed to end at rest (the unknown future)
//!        ─▶ commit the oldest when the window is full (forward pass, one
//!            segment at a time): exit = min(entry_max[next], reach(entry, len)),
//!            profile = ramp up / cruise / ramp down  ─▶ Timeline
//!  aux events (dwell, M06, spindle start/stop, M00, M30, coolant) flush the
//!  window: the last move ends at rest, then the pause follows.
//! ```
//!
//! Because a segment's entry bound only grows as more segments arrive, the
//! backward pass is amortised: it walks back only over segments whose bound
//! changed, and the forward pass is done once per segment at commit time.
//! Memory is the window (at most `MAX_LOOKAHEAD_BLOCKS` segments) whatever
//! the program length, in a ring of reused slots ([`crate::ring`]) that a
//! segment is written into once. The newest segment's own bound, from
//! rest, is kept as bounds while they decide the segment before it
//! ([`Kin::reach_from_rest`]): on a chain of short jerk-limited moves that
//! saves a cube root per block, and the results are those of the exact
//! pass. Likewise a corner is first tested, on its raw tangents and with
//! multiplications only, for being faster than either move may go
//! ([`corner_is_free`]); only the others are worked out in full. The
//! look-ahead follows grbl's planner and Klipper's
//! `toolhead.py` in idea (both read, neither copied); the S-curve ramps are
//! in [`crate::ramp`].

use crate::limits::{
    AxisLimits, Corner, Unit, arc_limits, corner_is_free, corner_speed_units, settle_time,
};
use crate::path::{Path, Shape, Vector, plane_axes};
use crate::ramp::{Kin, Profile};
use crate::ring::Ring;
use crate::timeline::{Attr, AxesMove, MoveKind, Pause, PauseKind, Segment, Timeline};
use std::sync::Arc;
use vcnc_core::motion::Profile as ProfileShape;
use vcnc_core::{Event, Feed, Loc, MAX_AXES, Machine, PathMode, Plane, Pos, Sink, SpindleDir};

/// Two tangents closer than this (1°) make a tangent junction for G99.
const TANGENT_COS: f64 = 0.999_847_695;
/// G99 blends only between feeds within this ratio.
const FEED_RATIO: f64 = 1.1;
/// How far the chords a NURBS curve is followed by may pass from it, mm.
pub const NURBS_CHORD_MM: f64 = 0.001;

/// How a segment ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum End {
    /// At rest (exact stop, rapid, G63, skip).
    Stop,
    /// Passed at the corner speed (G64, G62).
    Blend,
    /// At rest unless the next move is tangent with a close feed (EIA G99).
    Tangent,
}

/// A segment in the look-ahead window.
#[derive(Debug, Clone)]
struct Pending {
    seg: Segment,
    end: End,
    settle_s: f64,
    /// Highest entry speed from the corner before it.
    entry_cap: f64,
    /// Highest entry speed from which everything after it can still stop
    /// in time (the backward pass).
    entry_max: f64,
    /// Bounds on `entry_max` while it is not worked out: only the newest
    /// move's can be, as [`Kin::reach_from_rest`] says.
    entry_bounds: Option<(f64, f64)>,
    /// The tangent at the end of an arc, unit to rounding (a line's is
    /// its direction, in its path: see [`Pending::end_tangent`]).
    arc_end: Vector,
    /// |end tangent|² ([`AxisLimits::norm2`]), for the corner after it
    /// (NaN for a rapid, whose corners are not worked out).
    end_norm2: f64,
    /// G05.1 tolerance of a smoothed G01 (0: not smoothed).
    smooth_mm: f64,
}

impl Pending {
    /// The tangent at its end, unit to rounding.
    fn end_tangent(&self) -> &Vector {
        match &self.seg.path.shape {
            Shape::Line(u) => u,
            Shape::Arc(_) => &self.arc_end,
        }
    }

    /// Its entry bound as the exit of the move before: worked out here
    /// (and again later, to the same figure) if it is left as bounds.
    fn exit_bound(&self) -> f64 {
        match self.entry_bounds {
            None => self.entry_max,
            Some(_) => self
                .seg
                .kin
                .reach_capped(0.0, self.seg.path.len, self.entry_cap),
        }
    }
}

/// What the corner before a move needs of it.
struct Next {
    kind: MoveKind,
    v_max: f64,
    /// Path length, mm.
    len: f64,
    /// The corner tolerance, mm.
    tol_mm: f64,
}

/// Settings from the machine file and G05.
#[derive(Debug, Clone)]
struct Settings {
    lookahead: usize,
    corner_tolerance_mm: f64,
    gain: f64,
    tool_change_s: f64,
    spindle_start_s: f64,
    spindle_stop_s: f64,
    independent_rapids: bool,
}

/// The planner; see the module documentation.
#[derive(Debug)]
pub struct Planner<T: Timeline> {
    lim: AxisLimits,
    /// The smallest maximum feed of any axis, mm/s.
    max_feed_min: f64,
    set: Settings,
    normal: (usize, f64),
    machine_motion: vcnc_core::motion::Motion,
    out: T,
    window: Ring<Pending>,
    v_entry: f64,
    pos: Pos,
    rpm: f64,
    spindle: SpindleDir,
    mode: PathMode,
    tool: Option<u32>,
    dogleg: Option<(Attr, Pos, Pos)>,
    in_position_check: bool,
    /// The direction (−1, 0, +1) of each axis on the last dog-leg leg.
    last_leg: [i8; MAX_AXES],
    /// G05.1 tolerance the next G01 moves get (0: none).
    smoothing_mm: f64,
    /// The segment being pushed is a smoothed G01.
    smooth_next: f64,
    /// Moves that could not be timed.
    pub untimed_moves: u64,
    /// The `filter` profile's time constant (0 under the others): each
    /// stop waits this long for the moving average to run out.
    filter_s: f64,
}

impl<T: Timeline> Planner<T> {
    /// A planner for `machine` with its own profile shape, feeding `out`.
    pub fn new(machine: &Machine, out: T) -> Planner<T> {
        Planner::with_profile(machine, machine.motion.profile, out)
    }

    /// A planner for `machine` with the given profile shape.
    pub fn with_profile(machine: &Machine, shape: ProfileShape, out: T) -> Planner<T> {
        let m = &machine.motion;
        let lookahead = usize::try_from(m.lookahead_blocks).unwrap_or(200).max(2);
        // The filter profile plans trapezoids and smooths them afterwards.
        let lim = AxisLimits::new(machine, shape == ProfileShape::Jerk);
        let filter_s = filter_time(machine, shape);
        Planner {
            max_feed_min: lim.n_min(&lim.max_feed),
            lim,
            set: Settings {
                lookahead,
                corner_tolerance_mm: m.corner_tolerance_mm,
                gain: m.servo_gain_per_s,
                tool_change_s: m.tool_change_s,
                spindle_start_s: m.spindle_start_s,
                spindle_stop_s: m.spindle_stop_s,
                independent_rapids: machine.params.g00_mode == 1,
            },
            normal: (lookahead, m.corner_tolerance_mm),
            machine_motion: m.clone(),
            out,
            window: Ring::with_capacity(lookahead + 1),
            v_entry: 0.0,
            pos: machine.start,
            rpm: 0.0,
            spindle: SpindleDir::Stop,
            mode: PathMode::Cutting,
            tool: None,
            dogleg: None,
            in_position_check: false,
            last_leg: [0; MAX_AXES],
            smoothing_mm: 0.0,
            smooth_next: 0.0,
            untimed_moves: 0,
            filter_s,
        }
    }

    /// The consumer.
    pub fn timeline(&self) -> &T {
        &self.out
    }

    /// The consumer, to change.
    pub fn timeline_mut(&mut self) -> &mut T {
        &mut self.out
    }

    /// Flushes and returns the consumer.
    pub fn into_timeline(mut self) -> T {
        self.flush();
        self.out
    }

    /// Ends every planned move at rest and hands it on.
    pub fn flush(&mut self) {
        self.finish_dogleg();
        if let Some(last) = self.window.back_mut() {
            if last.end == End::Blend {
                last.settle_s = 0.0;
            }
            last.end = End::Stop;
        }
        while !self.window.is_empty() {
            self.commit();
        }
    }

    fn attr(&self, loc: &Loc) -> Attr {
        Attr {
            line: loc.line,
            file: loc.file.as_ref().map(Arc::clone),
            tool: self.tool,
        }
    }

    /// Path speed of a feed, mm/s; `None` when it cannot move.
    fn feed_speed(&self, feed: Feed) -> Option<f64> {
        let turning = matches!(self.spindle, SpindleDir::Cw | SpindleDir::Ccw);
        let v = match feed {
            Feed::PerMin(f) => f / 60.0,
            Feed::PerRev(f) if turning => f * self.rpm / 60.0,
            Feed::PerRev(_) => 0.0,
        };
        // Positive and finite (see `ramp::finite`).
        (v > 0.0 && v <= f64::MAX).then_some(v)
    }

    fn plane_of(&self, plane: Plane) -> Option<vcnc_core::geometry::PlaneAxes> {
        plane_axes(plane, &self.lim.letters)
    }

    /// A motion to `path` (or an untimed jump when `speed` is `None`).
    fn motion(
        &mut self,
        path: Option<Path>,
        to: Pos,
        kind: MoveKind,
        speed: Option<f64>,
        end: End,
        loc: &Loc,
    ) {
        let from = self.pos;
        self.pos = to;
        let Some(path) = path else { return };
        let attr = self.attr(loc);
        let Some((v_max, kin)) = self.limits_along(&path, kind, speed) else {
            self.flush();
            self.untimed_moves += 1;
            self.out.untimed(from, to, &attr);
            return;
        };
        let window = if kind == MoveKind::Rapid {
            self.lim.in_position_rapid
        } else {
            self.lim.in_position
        };
        // Rapids and exact stops (G09, G61) wait for the in-position
        // window; G63 and skips stop without the check.
        let settle_s = match end {
            End::Stop if kind == MoveKind::Rapid || self.in_position_check => settle_time(
                self.set.gain,
                kin.accel,
                &path.axis_share(),
                &window,
                self.lim.n,
            ),
            _ => 0.0,
        };
        self.push(path, kind, attr, (v_max, kin), end, settle_s);
    }

    /// The highest speed along `path` and its acceleration and jerk;
    /// `None` if it cannot move.
    fn limits_along(&self, path: &Path, kind: MoveKind, speed: Option<f64>) -> Option<(f64, Kin)> {
        let share = path.axis_share();
        let axis_speed = match kind {
            MoveKind::Rapid => &self.lim.rapid,
            MoveKind::Cut => &self.lim.max_feed,
        };
        let (mut kin, along) = self.lim.kin_and_speed_along(axis_speed, &share);
        let mut v_max = match kind {
            MoveKind::Rapid => along,
            MoveKind::Cut => speed?.min(along),
        };
        if let Some(p) = path.plane() {
            let (v_arc, k) = arc_limits(&self.lim, path.curvature_magnitude(), p.a, p.b, kin);
            v_max = v_max.min(v_arc);
            kin = k;
        }
        // Positive and finite, in compares (see `ramp::finite`).
        let ok = v_max > 0.0 && v_max <= f64::MAX && kin.accel > 0.0 && kin.accel <= f64::MAX;
        ok.then_some((v_max, kin))
    }

    /// Adds a segment to the window: corner cap, backward pass, commit.
    /// The move is built in its slot of the window, not moved there.
    fn push(
        &mut self,
        path: Path,
        kind: MoveKind,
        attr: Attr,
        (v_max, kin): (f64, Kin),
        end: End,
        settle_s: f64,
    ) {
        let arc_start;
        let u_start = match &path.shape {
            Shape::Line(u) => u,
            Shape::Arc(_) => {
                arc_start = path.tangent(0.0);
                &arc_start
            }
        };
        let arc_end = match path.shape {
            Shape::Line(_) => None,
            Shape::Arc(_) => Some(path.tangent(path.len)),
        };
        // A rapid has no corner worked out on either side: no norms.
        let (start_norm2, end_norm2) = if kind == MoveKind::Cut {
            let n = self.lim.norm2(u_start);
            (n, arc_end.as_ref().map_or(n, |t| self.lim.norm2(t)))
        } else {
            (f64::NAN, f64::NAN)
        };
        let corner_tolerance_mm =
            if self.smooth_next > 0.0 && self.window.back().is_some_and(|p| p.smooth_mm > 0.0) {
                self.smooth_next
            } else {
                self.set.corner_tolerance_mm
            };
        let next = Next {
            kind,
            v_max,
            len: path.len,
            tol_mm: corner_tolerance_mm,
        };
        let cap = self.corner_cap(&next, (u_start, start_norm2)).min(v_max);
        let from_rest = if exact_only() {
            Ok(kin.reach_capped(0.0, path.len, cap))
        } else {
            kin.reach_from_rest(path.len, cap)
        };
        let (entry_max, entry_bounds) = match from_rest {
            Ok(v) => (v, None),
            Err(bounds) => (f64::NAN, Some(bounds)),
        };
        let smooth_mm = self.smooth_next;
        if let Some(slot) = self.window.push_reused() {
            // Field by field into the slot a committed move left: building
            // a `Pending` and moving it there copies it twice over. Every
            // field is named, so a new one cannot be forgotten here.
            let Pending {
                seg:
                    Segment {
                        path: s_path,
                        kind: s_kind,
                        attr: s_attr,
                        v_max: s_v_max,
                        kin: s_kin,
                        corner_tolerance_mm: s_tol,
                    },
                end: s_end,
                settle_s: s_settle,
                entry_cap: s_cap,
                entry_max: s_max,
                entry_bounds: s_bounds,
                arc_end: s_arc_end,
                end_norm2: s_end_norm2,
                smooth_mm: s_smooth,
            } = slot;
            // A line fills a third of a path's room (sized for an arc):
            // copy only what it has, into a slot a line left if it can
            // (assigning a whole `Shape` copies all of its room).
            match (path.shape, &mut s_path.shape) {
                (Shape::Line(u), Shape::Line(s_u)) => {
                    s_path.from = path.from;
                    s_path.to = path.to;
                    s_path.len = path.len;
                    *s_u = u;
                }
                _ => *s_path = path,
            }
            *s_kind = kind;
            *s_attr = attr;
            *s_v_max = v_max;
            *s_kin = kin;
            *s_tol = corner_tolerance_mm;
            *s_end = end;
            *s_settle = settle_s;
            *s_cap = cap;
            *s_max = entry_max;
            *s_bounds = entry_bounds;
            if let Some(t) = arc_end {
                *s_arc_end = t;
            }
            *s_end_norm2 = end_norm2;
            *s_smooth = smooth_mm;
        } else {
            self.window.push_back(Pending {
                seg: Segment {
                    path,
                    kind,
                    attr,
                    v_max,
                    kin,
                    corner_tolerance_mm,
                },
                end,
                settle_s,
                entry_cap: cap,
                entry_max,
                entry_bounds,
                arc_end: arc_end.unwrap_or_default(),
                end_norm2,
                smooth_mm,
            });
        }
        self.backward();
        while self.window.len() > self.set.lookahead {
            self.commit();
        }
    }

    /// The highest speed at the junction between the newest segment in
    /// the window and `seg`; decides how a G99 junction ends.
    fn corner_cap(&mut self, seg: &Next, (u_start, start_norm2): (&Vector, f64)) -> f64 {
        // Between two smoothed G01 moves the corner tolerance is G05.1's E.
        let tol = seg.tol_mm;
        let lim = &self.lim;
        let Some(prev) = self.window.back_mut() else {
            return 0.0;
        };
        if prev.end == End::Stop || seg.kind == MoveKind::Rapid || prev.seg.kind == MoveKind::Rapid
        {
            prev.end = End::Stop;
            return 0.0;
        }
        let v_cap = prev.seg.v_max.min(seg.v_max);
        let half_len = 0.5 * prev.seg.path.len.min(seg.len);
        let corner = Corner {
            tol_mm: tol,
            half_len,
            vlim: &lim.max_feed,
            vlim_min: self.max_feed_min,
            v_cap,
        };
        // Most corners are shown to be free without normalising the
        // tangents; the others are worked out in full.
        let u_end = prev.end_tangent();
        let free = || {
            corner_is_free(
                lim,
                (u_end, prev.end_norm2),
                (u_start, start_norm2),
                &corner,
            )
        };
        let v = if !exact_only() && free() {
            f64::INFINITY
        } else {
            let (e_end, e_start) = (Unit::new(lim, u_end), Unit::new(lim, u_start));
            corner_speed_units(lim, &e_end, &e_start, &corner)
        };
        let v = v.min(v_cap);
        if prev.end == End::Tangent {
            let u_end = prev.seg.path.tangent(prev.seg.path.len);
            let tangent = cosine(&u_end, u_start) >= TANGENT_COS;
            let (a, b) = (prev.seg.v_max, seg.v_max);
            if tangent && a.max(b) <= FEED_RATIO * a.min(b) {
                prev.end = End::Blend;
                prev.settle_s = 0.0;
                return v;
            }
            prev.end = End::Stop;
            return 0.0;
        }
        v
    }

    fn backward(&mut self) {
        let Some(last) = self.window.back() else {
            return;
        };
        // The entry bound of the move after the one at `i`, or bounds on
        // it (as `Kin::reach_from_rest` gives them).
        let mut exit = match last.entry_bounds {
            Some(bounds) => Err(bounds),
            None => Ok(last.entry_max),
        };
        let mut i = self.window.len() - 1;
        while i > 0 {
            i -= 1;
            let Some(p) = self.window.get_mut(i) else {
                break;
            };
            let (kin, len, cap) = (p.seg.kin, p.seg.path.len, p.entry_cap);
            let new = match exit {
                Ok(x) => kin.reach_capped(x, len, cap),
                Err(b) if kin.reaches_cap_from(b, len, cap) => cap,
                Err(_) => {
                    // Only the newest move's bound can be left as bounds:
                    // work it out and start again from it.
                    self.work_out_entry_max(i + 1);
                    return self.backward();
                }
            };
            if p.entry_bounds.is_none() && new == p.entry_max {
                break;
            }
            p.entry_max = new;
            p.entry_bounds = None;
            exit = Ok(new);
        }
    }

    /// Works out the entry bound of the move at `i` in the window if it
    /// was left as bounds.
    fn work_out_entry_max(&mut self, i: usize) {
        if let Some(p) = self.window.get_mut(i) {
            p.entry_max = p.exit_bound();
            p.entry_bounds = None;
        }
    }

    /// Plans the oldest segment for good and hands it on.
    fn commit(&mut self) {
        let Some(p) = self.window.front() else {
            return;
        };
        let stops = p.end == End::Stop;
        let next = match self.window.get(1) {
            Some(n) if !stops => n.exit_bound(),
            _ => 0.0,
        };
        let len = p.seg.path.len;
        let v0 = self.v_entry.min(p.seg.v_max);
        let v1 = if stops {
            0.0
        } else {
            p.seg.kin.reach_capped(v0, len, next)
        };
        let profile = Profile::plan(v0, v1, p.seg.v_max, len, p.seg.kin);
        self.out.segment(&p.seg, &profile);
        self.v_entry = v1;
        let settle = (stops && p.settle_s > 0.0).then(|| (p.settle_s, p.seg.attr.clone()));
        let run_out = (stops && self.filter_s > 0.0).then(|| p.seg.attr.clone());
        self.window.pop_front();
        if let Some(attr) = run_out {
            self.pause(PauseKind::Filter, self.filter_s, attr);
        }
        if let Some((seconds, attr)) = settle {
            self.pause(PauseKind::InPosition, seconds, attr);
        }
    }

    fn pause(&mut self, kind: PauseKind, seconds: f64, attr: Attr) {
        self.out.pause(&Pause {
            kind,
            seconds,
            attr,
        });
    }

    /// A rapid under parameter 411 = 1: legs of one block join into one
    /// move whose axes run each at its own rate. A leg continues the
    /// dog-leg only if it comes from the same block and moves a strict
    /// subset of the previous leg's axes the same way (an axis stops when it
    /// arrives), so a block repeated by a subprogram's L count stays
    /// separate moves.
    fn rapid_leg(&mut self, to: Pos, loc: &Loc) {
        let leg = leg_signs(&self.pos, &to, self.lim.n);
        if let Some((attr, _, end)) = &mut self.dogleg
            && attr.line == loc.line
            && attr.file == loc.file
            && continues(&self.last_leg, &leg)
        {
            *end = to;
            self.pos = to;
            self.last_leg = leg;
            return;
        }
        self.finish_dogleg();
        self.flush();
        self.dogleg = Some((self.attr(loc), self.pos, to));
        self.pos = to;
        self.last_leg = leg;
    }

    /// Hands on the dog-leg rapid being built, if there is one (checked in
    /// line: every event asks).
    #[inline]
    fn finish_dogleg(&mut self) {
        if self.dogleg.is_some() {
            self.finish_dogleg_now();
        }
    }

    fn finish_dogleg_now(&mut self) {
        let Some((attr, from, to)) = self.dogleg.take() else {
            return;
        };
        let mut profiles = [None; MAX_AXES];
        let (mut duration, mut settle): (f64, f64) = (0.0, 0.0);
        for (i, slot) in profiles.iter_mut().enumerate().take(self.lim.n) {
            let d = (to.get(i) - from.get(i)).abs();
            if d <= vcnc_core::geometry::ZERO_MM {
                continue;
            }
            let kin = Kin {
                accel: self.lim.accel[i],
                jerk: self.lim.jerk[i],
            };
            let prof = Profile::plan(0.0, 0.0, self.lim.rapid[i], d, kin);
            duration = duration.max(prof.duration());
            let mut one = [0.0; MAX_AXES];
            one[i] = 1.0;
            let window = self.lim.in_position_rapid;
            settle = settle.max(settle_time(
                self.set.gain,
                kin.accel,
                &one,
                &window,
                self.lim.n,
            ));
            *slot = Some(prof);
        }
        if duration <= 0.0 {
            return;
        }
        self.out.axes(&AxesMove {
            from,
            to,
            profiles,
            duration_s: duration,
            attr: attr.clone(),
        });
        if self.filter_s > 0.0 {
            self.pause(PauseKind::Filter, self.filter_s, attr.clone());
        }
        if settle > 0.0 {
            self.pause(PauseKind::InPosition, settle, attr);
        }
    }

    fn high_speed(&mut self, on: bool, p: u32) {
        let (n, tol) = if on {
            let s = self.machine_motion.high_speed_set(p);
            (
                usize::try_from(s.lookahead_blocks).unwrap_or(1000),
                s.corner_tolerance_mm,
            )
        } else {
            self.normal
        };
        self.set.lookahead = n.max(2);
        self.set.corner_tolerance_mm = tol;
        while self.window.len() > self.set.lookahead {
            self.commit();
        }
    }

    fn spindle_event(&mut self, dir: SpindleDir, rpm: f64, loc: &Loc) {
        let running = |d| matches!(d, SpindleDir::Cw | SpindleDir::Ccw);
        let seconds = match (running(self.spindle), running(dir)) {
            (false, true) => self.set.spindle_start_s,
            (true, true) if dir != self.spindle => self.set.spindle_start_s,
            (true, false) => self.set.spindle_stop_s,
            _ => 0.0,
        };
        self.spindle = dir;
        self.rpm = if rpm.is_finite() { rpm.max(0.0) } else { 0.0 };
        if seconds > 0.0 {
            self.flush();
            let attr = self.attr(loc);
            self.pause(PauseKind::Spindle, seconds, attr);
        }
    }

    /// A NURBS curve: its chords within [`NURBS_CHORD_MM`], blended
    /// into each other, the last one ending as the block's mode says.
    fn nurbs(&mut self, curve: &vcnc_core::Nurbs, feed: Feed, loc: &Loc) {
        let points = curve.flatten(NURBS_CHORD_MM);
        let v = self.feed_speed(feed);
        let last = points.len().saturating_sub(1);
        for (i, to) in points.into_iter().enumerate() {
            let end = if i == last {
                self.cut_end(false)
            } else {
                End::Blend
            };
            let path = Path::line(self.pos, to, self.lim.n);
            self.motion(path, to, MoveKind::Cut, v, end, loc);
        }
    }

    /// How a cutting move ends, and whether it checks the in-position
    /// window (G09, G61; G63 stops without the check).
    fn cut_end(&mut self, exact_stop: bool) -> End {
        self.in_position_check = exact_stop || self.mode == PathMode::ExactStop;
        if self.in_position_check || self.mode == PathMode::Tapping {
            End::Stop
        } else {
            End::Blend
        }
    }
}

#[cfg(test)]
thread_local! {
    /// In this crate's tests: plan without the shortcuts, every figure
    /// worked out in full, to compare the planner against.
    static EXACT_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// The moving average the `filter` profile passes the plan through, s
/// ([`AxisLimits::filter_time`]); 0 for the other profiles.
pub fn filter_time(machine: &Machine, shape: ProfileShape) -> f64 {
    if shape == ProfileShape::Filter {
        AxisLimits::filter_time(machine)
    } else {
        0.0
    }
}

/// Whether to plan without the shortcuts (only ever in tests).
#[cfg(test)]
fn exact_only() -> bool {
    EXACT_ONLY.with(std::cell::Cell::get)
}

#[cfg(not(test))]
#[inline(always)]
fn exact_only() -> bool {
    false
}

/// The direction of each axis from `a` to `b`.
fn leg_signs(a: &Pos, b: &Pos, n: usize) -> [i8; MAX_AXES] {
    let mut out = [0; MAX_AXES];
    for (i, o) in out.iter_mut().enumerate().take(n) {
        let d = b.get(i) - a.get(i);
        *o = if d > vcnc_core::geometry::ZERO_MM {
            1
        } else if d < -vcnc_core::geometry::ZERO_MM {
            -1
        } else {
            0
        };
    }
    out
}

/// Whether leg `next` continues a dog-leg whose last leg was `prev`: it
/// moves fewer axes, each of them the way it moved before.
fn continues(prev: &[i8; MAX_AXES], next: &[i8; MAX_AXES]) -> bool {
    let fewer = next.iter().filter(|d| **d != 0).count() < prev.iter().filter(|d| **d != 0).count();
    fewer && next.iter().zip(prev).all(|(n, p)| *n == 0 || n == p)
}

fn cosine(a: &Vector, b: &Vector) -> f64 {
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for i in 0..MAX_AXES {
        ab += a[i] * b[i];
        aa += a[i] * a[i];
        bb += b[i] * b[i];
    }
    let d = (aa * bb).sqrt();
    if d > 0.0 { ab / d } else { 1.0 }
}

impl<T: Timeline> Sink for Planner<T> {
    fn event(&mut self, event: &Event) {
        if !matches!(event, Event::Rapid { .. }) {
            self.finish_dogleg();
        }
        let n = self.lim.n;
        match event {
            Event::Rapid { loc, to, .. } => {
                if self.set.independent_rapids {
                    self.rapid_leg(*to, loc);
                } else {
                    let path = Path::line(self.pos, *to, n);
                    self.motion(path, *to, MoveKind::Rapid, None, End::Stop, loc);
                }
            }
            Event::Feed {
                loc,
                to,
                feed,
                exact_stop,
            } => {
                let path = Path::line(self.pos, *to, n);
                let end = self.cut_end(*exact_stop);
                let v = self.feed_speed(*feed);
                self.smooth_next = self.smoothing_mm;
                self.motion(path, *to, MoveKind::Cut, v, end, loc);
                self.smooth_next = 0.0;
            }
            Event::Nurbs { loc, curve, feed } => self.nurbs(curve, *feed, loc),
            Event::Smoothing {
                on, tolerance_mm, ..
            } => {
                self.smoothing_mm = if *on && tolerance_mm.is_finite() {
                    tolerance_mm.max(0.0)
                } else {
                    0.0
                };
            }
            Event::Arc {
                loc,
                to,
                center,
                plane,
                dir,
                feed,
                exact_stop,
            } => {
                let path = match self.plane_of(*plane) {
                    Some(axes) => Path::arc(self.pos, *to, *center, axes, *dir),
                    None => Path::line(self.pos, *to, n),
                };
                let end = self.cut_end(*exact_stop);
                let v = self.feed_speed(*feed);
                self.motion(path, *to, MoveKind::Cut, v, end, loc);
            }
            Event::Thread { loc, to, lead_mm } => {
                let path = Path::line(self.pos, *to, n);
                let end = self.cut_end(false);
                let v = self.feed_speed(Feed::PerRev(*lead_mm));
                self.motion(path, *to, MoveKind::Cut, v, end, loc);
            }
            Event::Skip { loc, to, feed, .. } => {
                let path = Path::line(self.pos, *to, n);
                let v = self.feed_speed(*feed);
                self.in_position_check = false;
                self.motion(path, *to, MoveKind::Cut, v, End::Stop, loc);
            }
            Event::Dwell { loc, seconds } => {
                self.flush();
                let attr = self.attr(loc);
                if seconds.is_finite() && *seconds > 0.0 {
                    self.pause(PauseKind::Dwell, *seconds, attr);
                }
            }
            Event::ToolChange { loc, tool } => {
                self.flush();
                self.tool = Some(*tool);
                let attr = self.attr(loc);
                self.pause(PauseKind::ToolChange, self.set.tool_change_s, attr);
            }
            Event::Spindle { loc, dir, rpm, .. } => self.spindle_event(*dir, *rpm, loc),
            Event::PathMode { mode, .. } => self.mode = *mode,
            Event::HighSpeed { on, p, .. } => self.high_speed(*on, *p),
            Event::Junction { blend: true, .. } => {
                if let Some(last) = self.window.back_mut()
                    && last.end == End::Stop
                    && last.seg.kind == MoveKind::Cut
                {
                    last.end = End::Tangent;
                }
            }
            Event::Coolant { .. }
            | Event::Stop { .. }
            | Event::Message { stop: true, .. }
            | Event::End { .. }
            | Event::Wait { .. }
            | Event::Alarm(_) => self.flush(),
            _ => {}
        }
    }

    fn finish(&mut self) -> std::io::Result<()> {
        self.flush();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use vcnc_core::ArcDir;

    /// Every planned move as bits: the shortcuts must not change one.
    #[derive(Default)]
    struct Bits(Vec<u64>);

    impl Timeline for Bits {
        fn segment(&mut self, seg: &Segment, p: &Profile) {
            let figures = [
                seg.path.len,
                seg.v_max,
                p.up.v0,
                p.up.v1,
                p.up.tj,
                p.up.ta,
                p.cruise_s,
                p.down.v1,
                p.down.tj,
                p.down.ta,
            ];
            self.0.extend(figures.map(f64::to_bits));
        }
        fn axes(&mut self, mv: &AxesMove) {
            self.0.push(mv.duration_s.to_bits());
        }
        fn pause(&mut self, p: &Pause) {
            self.0.push(p.seconds.to_bits());
        }
    }

    /// Plans `events` twice in step, with the shortcuts and without, and
    /// checks after every event that the look-ahead holds the same figures
    /// (the newest move's entry bound, if left as bounds, around the full
    /// figure, and each move's |end tangent|² as summed afresh); then that
    /// every planned move has the same bits.
    fn plan_both(machine: &Machine, shape: ProfileShape, events: &[Event]) -> Result<(), String> {
        let mut fast = Planner::with_profile(machine, shape, Bits::default());
        let mut exact = Planner::with_profile(machine, shape, Bits::default());
        for (k, e) in events.iter().enumerate() {
            fast.event(e);
            EXACT_ONLY.with(|x| x.set(true));
            exact.event(e);
            EXACT_ONLY.with(|x| x.set(false));
            if fast.window.len() != exact.window.len() {
                return Err(format!("event {k}: window lengths differ"));
            }
            for i in 0..fast.window.len() {
                let (f, x) = (&fast.window[i], &exact.window[i]);
                let same = match f.entry_bounds {
                    None => f.entry_max.to_bits() == x.entry_max.to_bits(),
                    Some((lo, hi)) => lo <= x.entry_max && x.entry_max <= hi,
                };
                // The |u|² kept for the next corner is its end tangent's,
                // in a slot a line or an arc left alike.
                let norm = fast.lim.norm2(f.end_tangent());
                if f.seg.kind == MoveKind::Cut && f.end_norm2.to_bits() != norm.to_bits() {
                    return Err(format!(
                        "event {k}, move {i}: |u|² {} kept, {norm} now",
                        f.end_norm2
                    ));
                }
                if !same || f.entry_cap.to_bits() != x.entry_cap.to_bits() {
                    return Err(format!(
                        "event {k}, move {i}: {:?} {:?} against {} {}",
                        f.entry_max, f.entry_bounds, x.entry_max, x.entry_cap
                    ));
                }
            }
        }
        let (fast, exact) = (fast.into_timeline().0, exact.into_timeline().0);
        if fast.is_empty() || fast != exact {
            return Err("the planned moves differ".into());
        }
        Ok(())
    }

    /// A chain of short moves turning a little at each corner, now and
    /// then sharply or by a half circle, at feeds that the moves reach or
    /// do not.
    fn chain() -> impl Strategy<Value = Vec<Event>> {
        let step = (
            0.005..3.0f64,
            -0.2..0.2f64,
            -0.05..0.05f64,
            prop::bool::weighted(0.05),
            prop::bool::weighted(0.05),
            prop::sample::select(vec![300.0, 1500.0, 6000.0, 20_000.0]),
        );
        prop::collection::vec(step, 2..60).prop_map(|steps| {
            let (mut p, mut heading) = ([0.0; 6], 0.0f64);
            let mut events = Vec::new();
            for (len, turn, dz, sharp, arc, feed) in steps {
                heading += if sharp { 2.0 + turn } else { turn };
                let mut to = p;
                to[0] += len * heading.cos();
                to[1] += len * heading.sin();
                let (loc, feed) = (Loc::default(), Feed::PerMin(feed));
                if arc {
                    // A half circle to the left of the heading.
                    let mut center = p;
                    center[0] = 0.5 * (p[0] + to[0]);
                    center[1] = 0.5 * (p[1] + to[1]);
                    heading += std::f64::consts::PI;
                    events.push(Event::Arc {
                        loc,
                        to: Pos(to),
                        center: Pos(center),
                        plane: Plane::Xy,
                        dir: ArcDir::Ccw,
                        feed,
                        exact_stop: false,
                    });
                } else {
                    to[2] += dz * len;
                    events.push(Event::Feed {
                        loc,
                        to: Pos(to),
                        feed,
                        exact_stop: false,
                    });
                }
                p = to;
            }
            events
        })
    }

    proptest! {
        /// The lazy entry bounds (`Kin::reach_from_rest`) and the corners
        /// shown free without normalising (`corner_is_free`) plan every
        /// move to the same bits as working everything out. A short
        /// look-ahead commits moves along the way, so that new ones are
        /// written into the slots committed lines and arcs left.
        #[test]
        fn the_shortcuts_plan_what_the_full_figures_plan(
            events in chain(),
            jerk: bool,
            short_lookahead: bool,
        ) {
            let mut machine = Machine::default_mill();
            if short_lookahead {
                machine.motion.lookahead_blocks = 3;
            }
            let shape = if jerk { ProfileShape::Jerk } else { ProfileShape::Trapezoid };
            if let Err(e) = plan_both(&machine, shape, &events) {
                return Err(TestCaseError::fail(e));
            }
        }
    }
}
