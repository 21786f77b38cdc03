//! G12/G13: a circular pocket cut about the point where the tool stands,
//! clockwise (G12) or counter-clockwise (G13), in the XY plane — Haas's
//! "circular pocket milling" and Mach3's "circular pocket". The two read
//! different words (`CircleCutForm`, the dialect's row decides).
//!
//! Haas (`Spiral`), G12 seen from +Z, ρ = radius − D's radius:
//!
//! ```text
//!              ╭──────╮            1  feed down to Z at the centre c
//!           ╭─╯  ╭──╮  ╰─╮         2  half circle of diameter ρ₁ from c
//!          │   2╭╯  ╰╮    │           out to (ρ₁, 0), in the cut's sense
//!          │   │  c ─┼─3─▶│ …      3  a full circle of radius ρ₁; then
//!          │    ╰╮  ╭╯4   │           straight out by Q and a full circle,
//!           ╰─╮  ╰──╯  ╭─╯            ring after ring, the last at K
//!              ╰──────╯            4  half circle back to c from the last
//!                                     ring; L times (Z deeper each time
//!                                     under G91)
//! ```
//!
//! The half circles are tangent to the rings at (ρ, 0), so the tool
//! enters and leaves the wall without a mark; the radial step between
//! rings is a straight feed. The manuals (Haas mill operator's manual, G12/G13;
//! the 1999 Haas programming examples, "Yasnac style"; Mitsubishi's
//! "circle cutting", which starts and ends at the centre) show the tool
//! leaving and returning to the centre but do not give the lead-in's
//! radius: `docs/dialects.md` writes this choice down.
//!
//! Mach3 (`StraightInOut`): "the tool is moved in the X direction by the
//! value of the I word and a circle is cut in the direction specified with
//! the original X and Y coordinates as the centre. The tool is returned to
//! the centre" — a feed out, the circle, a feed back, at the tool's level.
//!
//! All points are program points through the motion stage, so offsets,
//! G92 and transforms apply; cutter compensation in force is suspended as
//! for a canned cycle.

use super::cycles::{CycleAxes, SAME_MM, Steps, positive};
use crate::alarms;
use crate::dialect::CircleCutForm;
use crate::interpreter::Machining;
use crate::motion::MoveKind;
use crate::words::Words;
use crate::words::whole;
use vcnc_core::events::{ArcDir, Feed, Plane};
use vcnc_syntax::{Diagnostic, Span};

/// Most full circles one G12/G13 block may cut over its repeats (its
/// events are held until the block has succeeded), as a pocket's rings.
const MAX_CIRCLES: u64 = 20_000;

/// A circle cut resolved to program mm: where, how deep, which radii of
/// the tool centre.
struct Cut {
    /// The plane's axes and the depth axis (machine indices).
    axes: CycleAxes,
    /// The centre in the plane (program X, Y).
    centre: (f64, f64),
    /// The level of each repeat, in order.
    depths: Vec<f64>,
    /// The tool centre's radii, innermost first.
    radii: Vec<f64>,
    feed: Feed,
    cw: bool,
    /// In and out along half circles (Haas), else straight (Mach3).
    arcs_in_out: bool,
}

/// The moves of one circle cut, relative to its centre.
struct CircleSteps<'w, 'b> {
    s: Steps<'w, 'b>,
    cut: Cut,
}

impl CircleSteps<'_, '_> {
    fn z(&self, it: &Machining<'_, '_>) -> f64 {
        it.state.prog.get(self.cut.axes.z)
    }

    /// To the centre at rapid, at the level the tool is at.
    fn rapid(&mut self, it: &mut Machining<'_, '_>, z: f64) -> Result<(), Diagnostic> {
        self.s.to(it, MoveKind::Rapid, (0.0, 0.0), z)
    }

    fn feed(
        &mut self,
        it: &mut Machining<'_, '_>,
        at: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        self.s.to(it, MoveKind::Feed(self.cut.feed), at, z)
    }

    /// An arc in the cut's sense to `to` about `centre` (relative points).
    fn arc(
        &mut self,
        it: &mut Machining<'_, '_>,
        to: (f64, f64),
        centre: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        self.s
            .arc(it, (to, centre), z, (self.cut.cw, self.cut.feed))
    }

    /// From the centre round every ring and back, at level `z`.
    fn rings(&mut self, it: &mut Machining<'_, '_>, z: f64) -> Result<(), Diagnostic> {
        let radii = self.cut.radii.clone();
        let (Some(&first), Some(&last)) = (radii.first(), radii.last()) else {
            return Ok(());
        };
        if self.cut.arcs_in_out {
            self.arc(it, (first, 0.0), (first / 2.0, 0.0), z)?;
        } else {
            self.feed(it, (first, 0.0), z)?;
        }
        for (k, &r) in radii.iter().enumerate() {
            if k > 0 {
                self.feed(it, (r, 0.0), z)?;
            }
            self.arc(it, (r, 0.0), (0.0, 0.0), z)?;
        }
        if self.cut.arcs_in_out {
            self.arc(it, (0.0, 0.0), (last / 2.0, 0.0), z)
        } else {
            self.feed(it, (0.0, 0.0), z)
        }
    }
}

impl<'a> Machining<'_, 'a> {
    /// G12/G13: the whole cut, or an alarm before any of it moves.
    pub(crate) fn circle_cut(
        &mut self,
        dir: ArcDir,
        form: CircleCutForm,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let code = if dir == ArcDir::Cw { "G12" } else { "G13" };
        if self.state.modal.plane != Plane::Xy {
            return Err(alarms::circle_cut_plane(cmd, code));
        }
        let axes = self.cycle_axes(cmd)?;
        let cut = match form {
            CircleCutForm::Spiral => self.spiral_words(dir, axes, w, cmd, code)?,
            CircleCutForm::StraightInOut => self.straight_words(dir, axes, w, cmd, code)?,
        };
        let circles = (cut.radii.len() as u64).saturating_mul(cut.depths.len() as u64);
        if circles > MAX_CIRCLES {
            return Err(alarms::too_many_circles(cmd, MAX_CIRCLES));
        }
        let suspended = self.suspend_comp()?;
        let mut s = CircleSteps {
            s: Steps {
                axes: cut.axes,
                at: cut.centre,
                w,
                cmd,
            },
            cut,
        };
        let z_now = s.z(self);
        s.rapid(self, z_now)?;
        for i in 0..s.cut.depths.len() {
            let z = s.cut.depths[i];
            s.feed(self, (0.0, 0.0), z)?;
            s.rings(self, z)?;
        }
        self.resume_comp(suspended);
        Ok(())
    }

    /// Haas's words: I, K, Q, L, Z (D was read with the block's other
    /// offset words: its radius is the one compensation latched).
    fn spiral_words(
        &mut self,
        dir: ArcDir,
        axes: CycleAxes,
        w: &Words<'_>,
        cmd: Span,
        code: &str,
    ) -> Result<Cut, Diagnostic> {
        let iw = w.get(b'I').ok_or_else(|| {
            alarms::needs_word(
                cmd,
                code,
                "I (the radius of the first circle, or of the finished circle without K)",
            )
        })?;
        let first = positive(
            iw,
            self.units().length_mm(&iw),
            "I is a radius, more than 0",
        )?;
        let step = match (w.get(b'K'), w.get(b'Q')) {
            (None, None) => None,
            (Some(k), Some(q)) => {
                let finish = self.units().length_mm(&k);
                if finish <= first + SAME_MM {
                    return Err(alarms::value_out_of_range(
                        k.span,
                        b'K',
                        k.value,
                        "K, the finished circle's radius, is more than I (Haas: \"I value must be … less than K value\")",
                    ));
                }
                let q_mm = positive(q, self.units().length_mm(&q), "the step Q is more than 0")?;
                Some((finish, q_mm))
            }
            (Some(_), None) => {
                return Err(alarms::needs_word(
                    cmd,
                    &format!("{code} with K"),
                    "Q (the step from one circle to the next)",
                ));
            }
            (None, Some(q)) => {
                return Err(alarms::needs_word(
                    q.span,
                    &format!("{code}'s Q"),
                    "K (the finished circle's radius; Haas: \"must be used with K\")",
                ));
            }
        };
        let repeats = match w.get(b'L') {
            Some(l) => whole(&l, b'L', 1.0, 9_999.0, "L repeats the cut, at least once")?,
            None => 1,
        };
        // The cutter radius is the machine's, not scaled with the circle
        // (G51 scales the path, not the offset, as under G41/G42): in
        // program millimetres it is r divided by the scale. The circle lies
        // in XY (G17 only), whose scale is even or its arcs alarm.
        let scale = self.tables.transforms.x_length_scale();
        let tool_r = if scale > 0.0 {
            self.state.comp_d_mm / scale
        } else {
            self.state.comp_d_mm
        };
        let mut radii = vec![first];
        if let Some((finish, q)) = step {
            // Bounded: beyond MAX_CIRCLES the block alarms anyway.
            while let Some(&last) = radii.last()
                && last < finish - SAME_MM
                && (radii.len() as u64) <= MAX_CIRCLES
            {
                radii.push((last + q).min(finish));
            }
        }
        if first - tool_r <= SAME_MM {
            return Err(alarms::circle_cut_too_small(iw.span, first, tool_r));
        }
        let radii = radii.into_iter().map(|r| r - tool_r).collect();
        let (centre, z_start, z_goal) = self.circle_goal(axes, w);
        let inc = self.state.modal.incremental;
        let count = u64::from(repeats).min(MAX_CIRCLES + 1);
        #[allow(clippy::cast_precision_loss)] // at most MAX_CIRCLES + 1
        let depths = (1..=count)
            .map(|l| {
                if inc {
                    z_start + l as f64 * (z_goal - z_start)
                } else {
                    z_goal
                }
            })
            .collect();
        Ok(Cut {
            axes,
            centre,
            depths,
            radii,
            feed: self.feed(cmd)?,
            cw: dir == ArcDir::Cw,
            arcs_in_out: true,
        })
    }

    /// Mach3's words: I alone, the signed radius along X; no axis words.
    fn straight_words(
        &mut self,
        dir: ArcDir,
        axes: CycleAxes,
        w: &Words<'_>,
        cmd: Span,
        code: &str,
    ) -> Result<Cut, Diagnostic> {
        for a in &self.cfg.axis_words {
            if let Some(word) = w.get(a.letter) {
                return Err(alarms::word_not_allowed(word.span, a.letter));
            }
        }
        let iw = w
            .get(b'I')
            .ok_or_else(|| alarms::needs_word(cmd, code, "I (the circle's radius)"))?;
        let r = self.units().length_mm(&iw);
        if r.abs() <= SAME_MM {
            return Err(alarms::value_out_of_range(
                iw.span,
                b'I',
                iw.value,
                "I is the circle's radius, not 0",
            ));
        }
        let (centre, z, _) = self.circle_goal(axes, w);
        Ok(Cut {
            axes,
            centre,
            depths: vec![z],
            radii: vec![r],
            feed: self.feed(cmd)?,
            cw: dir == ArcDir::Cw,
            arcs_in_out: false,
        })
    }

    /// The centre (the block's X and Y, else where the tool is), the level
    /// the tool is at and the block's Z (program coordinates).
    fn circle_goal(&mut self, axes: CycleAxes, w: &Words<'_>) -> ((f64, f64), f64, f64) {
        let goal = self.state.target(self.cfg, w, self.state.modal.incremental);
        let z_start = self.state.prog.get(axes.z);
        (
            (goal.prog.get(axes.a), goal.prog.get(axes.b)),
            z_start,
            goal.prog.get(axes.z),
        )
    }
}
