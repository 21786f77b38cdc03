//! The EIA-274-D pocket cycles G78 (rectangular) and G79 (circular), as
//! `docs/eia-spec.md` §6 defines them (the chapter names them only).
//!
//! ```text
//!   ┌───────────────────┐   concentric rings from the centre outwards,
//!   │ ┌───────────────┐ │   counter-clockwise, spaced by at most the
//!   │ │ ┌───────────┐ │ │   stepover (parameter 4010, % of the tool
//!   │ │ │ ●───slot  ├─┼─┤   diameter); the last ring is the wall (less
//!   │ │ └───────────┘ │ │   the finishing allowance P, then one
//!   │ └───────────────┘ │   finishing loop)
//!   └───────────────────┘
//! ```
//!
//! Each level (Q per pass from R down to Z) starts with a plunge at the
//! centre at the entry feed E; the tool ends over the last loop's end at
//! the level where the block started. All points are program points on
//! the motion stage, so offsets and G92 apply.

use super::cycles::{CycleAxes, SAME_MM, Steps, not_negative, positive};
use crate::alarms;
use crate::dialect::CycleOp;
use crate::interpreter::Machining;
use crate::motion::MoveKind;
use crate::words::Words;
use vcnc_core::events::Feed;
use vcnc_syntax::{Diagnostic, Span};

/// Most rings one pocket block may cut over all its levels (its events
/// are held until the block has succeeded).
const MAX_RINGS: u64 = 20_000;

/// One pass round the pocket: half sizes and corner radius (a circle: `a`
/// is the radius, `circle` set).
#[derive(Debug, Clone, Copy)]
struct Ring {
    a: f64,
    b: f64,
    corner: f64,
    circle: bool,
}

/// What a pocket block asks for, resolved to program mm.
#[derive(Debug, Clone, Copy)]
struct Pocket {
    centre: (f64, f64),
    /// Finished contour of the tool centre.
    wall: Ring,
    /// Roughing contour (the wall less the allowance).
    rough: Ring,
    allowance: f64,
    stepover: f64,
    initial: f64,
    r_level: f64,
    bottom: f64,
    q: Option<f64>,
    feed: Feed,
    entry: Feed,
}

/// The roughing rings, innermost first, spaced by at most the stepover;
/// the last is `rough` itself.
fn rings(rough: Ring, stepover: f64) -> Vec<Ring> {
    let span = rough.a.min(rough.b);
    let n = (span / stepover - 1e-9).ceil().max(1.0);
    let d = span / n;
    // At least 1; beyond MAX_RINGS the caller alarms, so the list is cut
    // there before it is built.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let count = n.min(MAX_RINGS as f64 + 1.0) as usize;
    (1..=count)
        .map(|k| {
            let back = (count - k) as f64 * d;
            if rough.circle {
                Ring {
                    a: k as f64 * d,
                    b: k as f64 * d,
                    corner: 0.0,
                    circle: true,
                }
            } else {
                Ring {
                    a: rough.a - back,
                    b: rough.b - back,
                    corner: (rough.corner - back).max(0.0),
                    circle: false,
                }
            }
        })
        .collect()
}

/// The cutting levels: Q per pass from R, the last at the bottom.
fn levels(r_level: f64, bottom: f64, q: Option<f64>) -> Vec<f64> {
    let Some(q) = q else { return vec![bottom] };
    let mut out = Vec::new();
    let mut k = 1.0;
    loop {
        let l = r_level - k * q;
        if l <= bottom + SAME_MM || out.len() as u64 > MAX_RINGS {
            out.push(bottom);
            return out;
        }
        out.push(l);
        k += 1.0;
    }
}

/// The moves of one pocket, relative to its centre.
struct PocketSteps<'w, 'b> {
    s: Steps<'w, 'b>,
    p: Pocket,
}

impl PocketSteps<'_, '_> {
    fn rapid(
        &mut self,
        it: &mut Machining<'_, '_>,
        at: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        self.s.to(it, MoveKind::Rapid, at, z)
    }

    fn feed(
        &mut self,
        it: &mut Machining<'_, '_>,
        at: (f64, f64),
        z: f64,
        feed: Feed,
    ) -> Result<(), Diagnostic> {
        self.s.to(it, MoveKind::Feed(feed), at, z)
    }

    /// A counter-clockwise arc to `to` about `centre` (relative points).
    fn arc(
        &mut self,
        it: &mut Machining<'_, '_>,
        to: (f64, f64),
        centre: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        self.s.arc(it, (to, centre), z, (false, self.p.feed))
    }

    /// From the plunge at the centre to the first ring's start: along the
    /// long side first (a slot), so that no material is left in the middle.
    fn slot(&mut self, it: &mut Machining<'_, '_>, first: Ring, z: f64) -> Result<(), Diagnostic> {
        let (a, b) = (self.p.rough.a, self.p.rough.b);
        let f = self.p.feed;
        if !first.circle {
            if a > b + SAME_MM {
                self.feed(it, (-(a - b), 0.0), z, f)?;
            } else if b > a + SAME_MM {
                self.feed(it, (0.0, -(b - a)), z, f)?;
                self.feed(it, (0.0, b - a), z, f)?;
            }
        }
        self.feed(it, (first.a, 0.0), z, f)
    }

    /// One closed loop, counter-clockwise from the middle of its +X side.
    fn ring(&mut self, it: &mut Machining<'_, '_>, r: Ring, z: f64) -> Result<(), Diagnostic> {
        let f = self.p.feed;
        if r.circle {
            return self.arc(it, (r.a, 0.0), (0.0, 0.0), z);
        }
        let (a, b, c) = (r.a, r.b, r.corner);
        // Corners in turn: the line to the corner's start, then its arc.
        let corners = [
            ((a, b - c), (a - c, b), (a - c, b - c)),
            ((-a + c, b), (-a, b - c), (-a + c, b - c)),
            ((-a, -b + c), (-a + c, -b), (-a + c, -b + c)),
            ((a - c, -b), (a, -b + c), (a - c, -b + c)),
        ];
        for (start, end, centre) in corners {
            self.feed(it, start, z, f)?;
            if c > SAME_MM {
                self.arc(it, end, centre, z)?;
            }
        }
        self.feed(it, (a, 0.0), z, f)
    }
}

impl<'a> Machining<'_, 'a> {
    /// G78/G79: the whole pocket, or an alarm before any of it moves.
    pub(crate) fn pocket(
        &mut self,
        op: CycleOp,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.cycle_axes(cmd)?;
        // The centre: X/Y absolute, or from where the tool is under G91.
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let centre = (goal.prog.get(axes.a), goal.prog.get(axes.b));
        let p = self.pocket_words(op, w, cmd, axes, centre)?;
        let rings = rings(p.rough, p.stepover);
        let levels = levels(p.r_level, p.bottom, p.q);
        let passes = (levels.len() as u64).saturating_mul(rings.len() as u64);
        if passes > MAX_RINGS {
            return Err(alarms::too_many_passes(cmd, MAX_RINGS));
        }
        let suspended = self.suspend_comp()?;
        let mut s = PocketSteps {
            s: Steps {
                axes,
                at: p.centre,
                w,
                cmd,
            },
            p,
        };
        let z_now = self.state.prog.get(axes.z);
        s.rapid(self, (0.0, 0.0), z_now)?;
        s.rapid(self, (0.0, 0.0), p.r_level)?;
        for (i, &level) in levels.iter().enumerate() {
            // The entry: a plunge at the centre.
            s.feed(self, (0.0, 0.0), level, p.entry)?;
            s.slot(self, rings[0], level)?;
            for (k, ring) in rings.iter().enumerate() {
                if k > 0 {
                    s.feed(self, (ring.a, 0.0), level, p.feed)?;
                }
                s.ring(self, *ring, level)?;
            }
            if i + 1 < levels.len() {
                s.feed(self, (0.0, 0.0), level, p.feed)?;
            }
        }
        if p.allowance > 0.0 {
            s.feed(self, (p.wall.a, 0.0), p.bottom, p.feed)?;
            s.ring(self, p.wall, p.bottom)?;
        }
        let end = self.state.prog;
        let (ea, eb) = (end.get(axes.a) - p.centre.0, end.get(axes.b) - p.centre.1);
        s.rapid(self, (ea, eb), p.initial)?;
        self.resume_comp(suspended);
        Ok(())
    }

    /// The pocket's words, checked (§2, §6).
    fn pocket_words(
        &self,
        op: CycleOp,
        w: &Words<'_>,
        cmd: Span,
        axes: CycleAxes,
        centre: (f64, f64),
    ) -> Result<Pocket, Diagnostic> {
        let code = if op == CycleOp::PocketRect {
            "G78"
        } else {
            "G79"
        };
        let circle = op == CycleOp::PocketCircle;
        if circle {
            for l in [b'J', b'K'] {
                if let Some(word) = w.get(l) {
                    return Err(alarms::word_not_allowed(word.span, l));
                }
            }
        }
        let need = |l: u8, what: &str| w.get(l).ok_or_else(|| alarms::needs_word(cmd, code, what));
        let iw = need(
            b'I',
            if circle {
                "I (the diameter)"
            } else {
                "I (the length in X)"
            },
        )?;
        let size_i = positive(
            iw,
            self.units().length_mm(&iw),
            "the pocket size I is more than 0",
        )?;
        let size_j = if circle {
            size_i
        } else {
            let jw = need(b'J', "J (the width in Y)")?;
            positive(
                jw,
                self.units().length_mm(&jw),
                "the pocket size J is more than 0",
            )?
        };
        let corner = match w.get(b'K') {
            Some(k) => not_negative(
                k,
                self.units().length_mm(&k),
                "the corner radius K is not negative",
            )?,
            None => 0.0,
        };
        let allowance = match w.get(b'P') {
            Some(pw) => not_negative(
                pw,
                self.units().length_mm(&pw),
                "the allowance P is not negative",
            )?,
            None => 0.0,
        };
        let q = match w.get(b'Q') {
            Some(qw) => Some(positive(
                qw,
                self.units().length_mm(&qw),
                "a depth per pass Q is more than 0",
            )?),
            None => None,
        };
        // The tool in the spindle and the stepover.
        let tool = self.state.tool_active;
        let r = tool
            .map(|t| self.tables.tool(t))
            .map(|t| t.d_mm + t.d_wear_mm)
            .filter(|r| *r > 0.0)
            .ok_or_else(|| alarms::pocket_without_tool(cmd, tool))?;
        let stepover = self.cfg.machine.params.pocket_stepover_pct / 100.0 * 2.0 * r;
        let too_small = |what: &str| alarms::pocket_too_small(cmd, what, 2.0 * r);
        let wall = if circle {
            let rho = size_i / 2.0 - r;
            if rho <= SAME_MM {
                return Err(too_small("diameter I"));
            }
            Ring {
                a: rho,
                b: rho,
                corner: 0.0,
                circle,
            }
        } else {
            let (a, b) = (size_i / 2.0 - r, size_j / 2.0 - r);
            if a <= SAME_MM || b <= SAME_MM {
                return Err(too_small("length I or width J"));
            }
            if corner > size_i.min(size_j) / 2.0 + SAME_MM {
                let k = w.get(b'K').unwrap_or_default();
                return Err(alarms::value_out_of_range(
                    k.span,
                    b'K',
                    k.value,
                    "the corner radius K is at most half the pocket's width",
                ));
            }
            Ring {
                a,
                b,
                corner: (corner - r).max(0.0),
                circle,
            }
        };
        let rough = Ring {
            a: wall.a - allowance,
            b: wall.b - allowance,
            corner: (wall.corner - allowance).max(0.0),
            circle,
        };
        if rough.a <= SAME_MM || rough.b <= SAME_MM {
            return Err(too_small("size less the allowance P"));
        }
        // Levels: under G91 R from the initial level, Z from R.
        let inc = self.state.modal.incremental;
        let initial = self.state.prog.get(axes.z);
        let r_level = match w.get(b'R') {
            Some(rw) => {
                let v = self.units().length_mm(&rw);
                if inc { initial + v } else { v }
            }
            None => initial,
        };
        let z_letter = self.cfg.axis_words.get(axes.z).map_or(b'Z', |a| a.letter);
        let zw = need(z_letter, "Z (the pocket's depth)")?;
        let bottom = {
            let v = self.units().axis_value(&self.cfg.axis_words, axes.z, &zw);
            if inc { r_level + v } else { v }
        };
        if bottom >= r_level - SAME_MM {
            return Err(alarms::cycle_direction(zw.span, false));
        }
        let feed = self.feed(cmd)?;
        let entry = match w.get(b'E') {
            Some(e) => {
                let v = positive(e, e.value, "an entry feed E is more than 0")?;
                let f = v * self.unit_mm() * self.state.feed_factor;
                if self.state.modal.per_rev {
                    Feed::PerRev(f)
                } else {
                    Feed::PerMin(f)
                }
            }
            None => feed,
        };
        Ok(Pocket {
            centre,
            wall,
            rough,
            allowance,
            stepover,
            initial,
            r_level,
            bottom,
            q,
            feed,
            entry,
        })
    }
}
