//! Straight motion's details: the feed a move runs at (F, its clamp, G93's
//! inverse time), G31 skip, and the two machine-side details of a straight
//! move the event stage needs: the dog-leg of a G00 under parameter 411 = 1
//! and where a skip fires. The group-01 dispatcher that builds the moves is
//! `codes/modal.rs`.

use super::MoveKind;
use crate::alarms;
use crate::interpreter::Machining;
use crate::words::Words;
use vcnc_core::events::{Feed, MAX_AXES, Pos};
use vcnc_core::machine::Machine;
use vcnc_syntax::{Diagnostic, Span};

/// Corners of a rapid where each axis runs at its own rate: every axis
/// starts together and stops when its own distance is covered.
///
/// ```text
///   Y ▲        ┌── end         axis X (fast) and Y (slow) start together;
///     │      ╱                 after X arrives only Y moves on.
///     └──╱─────▶ X
/// ```
#[inline(never)]
pub(crate) fn dog_leg(machine: &Machine, from: Pos, to: Pos) -> ([Pos; MAX_AXES], usize) {
    let n = machine.axes.len().min(MAX_AXES);
    let mut times = [0.0f64; MAX_AXES];
    for (i, axis) in machine.axes.iter().enumerate().take(n) {
        times[i] = (to.get(i) - from.get(i)).abs() / axis.rapid_mm_per_min;
    }
    // Distinct arrival times, in order; no allocation on this path.
    let mut order = times;
    order[..n].sort_by(f64::total_cmp);
    let mut corners = [to; MAX_AXES];
    let mut count = 0;
    let mut last = 0.0;
    for &t in &order[..n] {
        if t <= last {
            continue;
        }
        last = t;
        let mut p = from;
        for (i, axis) in machine.axes.iter().enumerate().take(n) {
            let d = to.get(i) - from.get(i);
            let moved = (t * axis.rapid_mm_per_min).min(d.abs());
            p.set(
                i,
                if t >= times[i] {
                    to.get(i)
                } else {
                    from.get(i) + moved.copysign(d)
                },
            );
        }
        corners[count] = p;
        count += 1;
    }
    (corners, count.max(1))
}

/// The legs of an EIA-274-D G00 (`docs/eia-spec.md` §3): Z alone first
/// when it rises; X and Y together at the same speed (both by the shorter
/// travel, a 45° leg), then the longer one alone, other axes with the
/// first of these legs; Z alone last when it falls.
///
/// ```text
///   Z ▲ 1 rise          │ 3 plunge
///     │      2 ╱────────┤ (X, Y: 45°, then the longer axis)
///     └──────────────────▶ X/Y
/// ```
#[inline(never)]
pub(crate) fn z_priority(machine: &Machine, from: Pos, to: Pos) -> ([Pos; MAX_AXES], usize) {
    let mut legs = [to; MAX_AXES];
    let mut count = 0;
    let mut push = |p: Pos| {
        if count < MAX_AXES && (count == 0 || legs[count - 1] != p) {
            legs[count] = p;
            count += 1;
        }
    };
    let (x, y, z) = (
        machine.axis_of(b'X'),
        machine.axis_of(b'Y'),
        machine.axis_of(b'Z'),
    );
    let mut p = from;
    let dz = z.map_or(0.0, |z| to.get(z) - from.get(z));
    if let Some(z) = z.filter(|_| dz > 0.0) {
        p.set(z, to.get(z));
        push(p);
    }
    // Every axis but Z reaches its end in the plane legs.
    let mut plane_end = to;
    if let Some(z) = z {
        plane_end.set(z, p.get(z));
    }
    if let (Some(x), Some(y)) = (x, y) {
        let (dx, dy) = (to.get(x) - p.get(x), to.get(y) - p.get(y));
        let m = dx.abs().min(dy.abs());
        if m > 0.0 && (dx.abs() - dy.abs()).abs() > vcnc_core::geometry::ZERO_MM {
            let mut corner = plane_end;
            corner.set(x, p.get(x) + m.copysign(dx));
            corner.set(y, p.get(y) + m.copysign(dy));
            push(corner);
        }
    }
    if plane_end != p {
        push(plane_end);
    }
    push(to);
    (legs, count)
}

/// The earliest fraction of `from → to` at which a skip trigger fires.
#[inline(never)]
pub(crate) fn skip_fraction(machine: &Machine, from: Pos, to: Pos) -> Option<f64> {
    machine
        .skip
        .iter()
        .filter_map(|s| {
            let (a, b) = (from.get(s.axis), to.get(s.axis));
            let crosses = (a < s.at_mm && b >= s.at_mm) || (a > s.at_mm && b <= s.at_mm);
            crosses.then(|| (s.at_mm - a) / (b - a))
        })
        .min_by(f64::total_cmp)
}

/// The point at fraction `t` of `a → b`.
pub(crate) fn lerp(a: Pos, b: Pos, t: f64) -> Pos {
    let mut p = a;
    for (i, v) in p.0.iter_mut().enumerate() {
        *v = a.0[i] + (b.0[i] - a.0[i]) * t;
    }
    p
}

impl<'a> Machining<'_, 'a> {
    /// The current feed (clamped to the machine's maximum), or E301 when
    /// it is zero. Inlined: every cut asks.
    #[inline(always)]
    pub(crate) fn feed(&self, cmd: Span) -> Result<Feed, Diagnostic> {
        let f = self.state.feed * self.unit_mm() * self.state.feed_factor;
        if f <= 0.0 {
            return Err(alarms::zero_feed(cmd));
        }
        Ok(if self.state.modal.per_rev {
            Feed::PerRev(f)
        } else {
            // The control clamps a feed above its maximum (warning W102
            // when F was given).
            Feed::PerMin(f.min(self.cfg.max_feed))
        })
    }

    /// G93 (grbl, LinuxCNC): F is the inverse of the move's time in minutes,
    /// given in every cutting block; the feed is the path length times F
    /// (clamped to the machine's maximum).
    pub(crate) fn inverse_time_feed(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        length_mm: f64,
    ) -> Result<Feed, Diagnostic> {
        let f = w.get(b'F').ok_or_else(|| {
            alarms::needs_word(cmd, "a cut under G93", "F (1 / the move's time in minutes)")
        })?;
        if f.value <= 0.0 {
            return Err(alarms::zero_feed(f.span));
        }
        let rate = length_mm * f.value;
        if rate > self.cfg.max_feed {
            self.warn(alarms::feed_clamped(f.span, rate, self.cfg.max_feed));
        }
        // A move of no length takes no time: any feed will do, and a
        // zero feed would stall a planner.
        Ok(Feed::PerMin(if rate > 0.0 {
            rate.min(self.cfg.max_feed)
        } else {
            self.cfg.max_feed
        }))
    }

    /// G31: moves like G01 until the skip signal of the machine file fires.
    pub(crate) fn skip(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        if self.stage.comp.engaged() {
            // The compensated corner at its end would be wrong once it stops short.
            return Err(alarms::skip_under_comp(cmd));
        }
        let feed = self.feed(cmd)?;
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        if goal.named == 0 {
            return Err(alarms::needs_axes(cmd, "G31"));
        }
        self.straight(
            MoveKind::Skip { feed },
            self.state.move_target(&goal),
            w,
            cmd,
        )
    }
}
