//! Canned drilling cycles G73, G74, G76, G81–G89 and the hole patterns
//! G134–G137.1 of the mill (Syntec 1.2.30–1.2.53), as `docs/cycles-spec.md`
//! specifies them step by step.
//!
//! ```text
//!   initial level ─ ─ ●─────────▶●  positioning (G00, in the plane)
//!                     │ G98      │
//!   R level   ─ ─ ─ ─ ┼ ─ ─ ─ ─ ─●  approach (G00); G99 returns here
//!                     │          │
//!                     │          ▼  the cycle's steps (feed, pecks,
//!   Z point   ─ ─ ─ ─ ┴ ─ ─ ─ ─ ─●  dwell, spindle reversal, shift)
//! ```
//!
//! Every point is a program point on the motion stage, so offsets, tool
//! length, rotation, scaling and mirror apply to holes and levels alike;
//! the G76/G87 shift is a machine direction (parameter 4020). Cutter
//! compensation is suspended for the holes and starts again at the next
//! move in the plane (Fanuc). A hole is announced by a `hole` event; steps
//! that would not move are not reported. A block's holes are bounded
//! (`MAX_HOLES`), since its events are held until it has succeeded.

use crate::alarms;
use crate::dialect::{Approach, GOp, Group, Hole, PeckClearance, TapStyle};
use crate::dialect::{CycleOp, ModeOp};
use crate::interpreter::Machining;
use crate::motion::{Move, MoveKind, Target};
use crate::state::{CycleData, ReducedPeck};
use crate::words::Words;
use vcnc_core::events::{Cycle, Event, Feed, Plane, Pos, SpindleDir, WaitReason};
use vcnc_syntax::{Diagnostic, Span, Word};

/// The chip-breaking cycle's back-off between pecks (EIA G87): the
/// chapter's 0.010 inch.
const CHIP_BREAK_BACK_OFF_MM: f64 = 0.254;

/// Most holes one block may drill (a K count or a pattern).
const MAX_HOLES: u64 = 10_000;

/// Most pecks one block may ask for over all its holes.
const MAX_PECKS: u64 = 100_000;

/// Below this two levels or points are the same, mm.
pub(crate) const SAME_MM: f64 = 1e-6;

/// The depth of each next peck: a constant Q, or Haas's reduced I, J, K.
#[derive(Debug, Clone, Copy)]
struct PeckDepths {
    next: f64,
    less: f64,
    least: f64,
}

impl PeckDepths {
    fn constant(q: f64) -> PeckDepths {
        PeckDepths {
            next: q,
            less: 0.0,
            least: q,
        }
    }

    fn reduced(rp: ReducedPeck) -> PeckDepths {
        PeckDepths {
            next: rp.first.max(rp.least),
            less: rp.less,
            least: rp.least,
        }
    }

    /// The cycle's pecks over a hole `depth` deep: Haas's I, J, K if set,
    /// else Q, else one peck to the bottom.
    fn of(data: &CycleData, depth: f64) -> PeckDepths {
        match data.reduced {
            Some(rp) => PeckDepths::reduced(rp),
            None => PeckDepths::constant(data.q.unwrap_or(depth)),
        }
    }

    /// This peck's depth; the next is `less` shorter, but not below `least`.
    fn take(&mut self) -> f64 {
        let d = self.next;
        self.next = (d - self.less).max(self.least);
        d
    }
}

/// The axes of a cycle: two positioning axes and the drilling axis
/// (machine indices).
#[derive(Debug, Clone, Copy)]
pub(crate) struct CycleAxes {
    pub a: usize,
    pub b: usize,
    pub z: usize,
}

/// A cycle's moves about one point of the plane (a hole's position, a
/// pocket's or a circular pocket's centre): straight steps to points given
/// relative to it at a level of the drilling axis (a step that would not
/// move is left out), and arcs in the plane. The drilling cycles, EIA's
/// G78/G79 pockets and G12/G13 walk their paths with it.
pub(crate) struct Steps<'w, 'b> {
    pub axes: CycleAxes,
    /// The point, in program coordinates of the plane's two axes.
    pub at: (f64, f64),
    pub w: &'w Words<'b>,
    pub cmd: Span,
}

impl Steps<'_, '_> {
    /// The program point `d` from the cycle's point, at level `z`.
    #[inline(always)]
    pub fn point(&self, it: &Machining<'_, '_>, (da, db): (f64, f64), z: f64) -> Pos {
        let mut p = it.state.prog;
        p.set(self.axes.a, self.at.0 + da);
        p.set(self.axes.b, self.at.1 + db);
        p.set(self.axes.z, z);
        p
    }

    fn go(&self, it: &mut Machining<'_, '_>, kind: MoveKind, p: Pos) -> Result<(), Diagnostic> {
        it.step_to(kind, p, self.w, self.cmd)
    }

    /// A straight step to `d` from the cycle's point, at level `z`.
    #[inline(always)]
    pub fn to(
        &self,
        it: &mut Machining<'_, '_>,
        kind: MoveKind,
        d: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        let p = self.point(it, d, z);
        self.go(it, kind, p)
    }

    /// An arc in the XY plane to `to` about `centre` (both from the
    /// cycle's point), at level `z`: its callers, G78/G79 and G12/G13, run
    /// in G17 only (they refuse the other planes).
    pub fn arc(
        &self,
        it: &mut Machining<'_, '_>,
        (to, centre): ((f64, f64), (f64, f64)),
        z: f64,
        (cw, feed): (bool, Feed),
    ) -> Result<(), Diagnostic> {
        let end = self.point(it, to, z);
        let here = it.state.prog;
        let mut offset = Pos::default();
        offset.set(self.axes.a, self.at.0 + centre.0 - here.get(self.axes.a));
        offset.set(self.axes.b, self.at.1 + centre.1 - here.get(self.axes.b));
        let mv = Move {
            kind: MoveKind::Arc {
                offset,
                plane: Plane::Xy,
                cw,
                feed,
            },
            to: Target::Program(end),
            exact_stop: false,
            cmd: self.cmd,
        };
        it.send(mv, self.w)
    }

    /// A hole's rapid along the drilling axis at its position.
    fn rapid(&mut self, it: &mut Machining<'_, '_>, z: f64) -> Result<(), Diagnostic> {
        self.to(it, MoveKind::Rapid, (0.0, 0.0), z)
    }

    /// A hole's feed along the drilling axis at its position.
    fn feed(&mut self, it: &mut Machining<'_, '_>, z: f64, feed: Feed) -> Result<(), Diagnostic> {
        self.to(it, MoveKind::Feed(feed), (0.0, 0.0), z)
    }

    /// A rapid to the shifted (or, with (0,0), centred) point at level
    /// `z`: in the plane, or along the drilling axis at the shifted point.
    fn shift(
        &mut self,
        it: &mut Machining<'_, '_>,
        s: (f64, f64),
        z: f64,
    ) -> Result<(), Diagnostic> {
        self.to(it, MoveKind::Rapid, s, z)
    }
}

/// The value `v` of `word` if it is more than 0, else E109 saying `why`.
pub(crate) fn positive(word: Word, v: f64, why: &str) -> Result<f64, Diagnostic> {
    in_range(word, v, v > 0.0, why)
}

/// The value `v` of `word` if it is 0 or more, else E109 saying `why`.
pub(crate) fn not_negative(word: Word, v: f64, why: &str) -> Result<f64, Diagnostic> {
    in_range(word, v, v >= 0.0, why)
}

fn in_range(word: Word, v: f64, ok: bool, why: &str) -> Result<f64, Diagnostic> {
    if ok {
        Ok(v)
    } else {
        Err(alarms::value_out_of_range(
            word.span,
            word.addr.0,
            word.value,
            why,
        ))
    }
}

/// Whether a cycle doing `hole` pecks by Q (and so needs Q > 0).
fn pecks_with_q(hole: Hole) -> bool {
    matches!(hole, Hole::HighSpeedPeck | Hole::DeepPeck | Hole::ChipBreak)
}

impl<'a> Machining<'_, 'a> {
    pub(crate) fn cycle_axes(&self, cmd: Span) -> Result<CycleAxes, Diagnostic> {
        let axes = self.cfg.plane_axes(self.state.modal.plane, cmd)?;
        let z = axes
            .n
            .ok_or_else(|| alarms::needs_axes(cmd, "a canned cycle"))?;
        Ok(CycleAxes {
            a: axes.a,
            b: axes.b,
            z,
        })
    }

    /// Before step 1: G17/G18/G19 may not change the plane under a cycle
    /// (the drilling axis would change under the stored levels).
    pub(crate) fn check_cycle_plane(&self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let Some(p) = w.group(Group::Plane) else {
            return Ok(());
        };
        let cancels = w.group(Group::Motion).is_some()
            || w.group(Group::Cycle)
                .is_some_and(|c| c.def.op == GOp::Cycle(CycleOp::Cancel));
        if self.state.cycle.code.is_none() || cancels {
            return Ok(());
        }
        let plane = match p.def.op {
            GOp::Mode(ModeOp::PlaneXy) => Plane::Xy,
            GOp::Mode(ModeOp::PlaneZx) => Plane::Zx,
            _ => Plane::Yz,
        };
        if plane != self.state.modal.plane {
            return Err(alarms::cycle_plane(p.span));
        }
        Ok(())
    }

    /// Step 1 for the cycle codes: a cycle code enters the cycle mode (the
    /// initial level is latched when it is entered from the cancelled
    /// state); otherwise G80 and the group-01 codes cancel it and its data.
    /// A group-01 code in the block of a cycle code wins (1.2.31 condition
    /// 4: the cycle "will be cancel"): the block is an ordinary move.
    pub(crate) fn cycle_modes(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let code = w.group(Group::Cycle);
        let motion = w.group(Group::Motion).is_some();
        if let Some(GOp::Cycle(CycleOp::Drill(c, hole))) = code.map(|c| c.def.op)
            && !motion
        {
            if self.state.cycle.code.is_none() {
                let axes = self.cycle_axes(code.map_or(w.first, |c| c.span))?;
                self.state.cycle = CycleData {
                    initial: self.state.prog.get(axes.z),
                    ..CycleData::OFF
                };
            }
            self.state.cycle.before = self.state.cycle.code;
            self.state.cycle.code = Some(c);
            self.state.cycle.hole = hole;
        } else if motion || code.is_some() {
            // Rigid tapping (M29) ends with the cycle mode it was for.
            if self.state.cycle.code.is_some() {
                self.state.rigid_tap = false;
            }
            self.state.cycle = CycleData::OFF;
        }
        Ok(())
    }

    /// A block in cycle mode: drill K holes if it has an axis word of the
    /// plane or the drilling axis, else only check its words.
    #[inline(never)]
    pub(crate) fn drill(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let cmd = w.group(Group::Cycle).map_or(cmd, |c| c.span);
        let axes = self.cycle_axes(cmd)?;
        let letters: Vec<u8> = self.cfg.axis_words.iter().map(|a| a.letter).collect();
        let letter = |i: usize| letters.get(i).copied();
        let drills = [axes.a, axes.b, axes.z]
            .iter()
            .filter_map(|&i| letter(i))
            .any(|l| w.get(l).is_some());
        let rules = self.cfg.dialect.cycles;
        if !drills && rules.rs274_words && w.group(Group::Cycle).is_some() {
            // rs274: "All axes missing with motion code".
            return Err(alarms::needs_word(
                cmd,
                self.state.cycle.code.map_or("the cycle", |c| c.as_str()),
                "an axis word (the hole's position or depth)",
            ));
        }
        if !drills {
            // R, Q, P are stored only by a block that drills (1.2.31), and
            // only it repeats.
            let data = rules.words;
            for l in [b'R', b'Q', b'P', b'K', b'L', b'I', b'J'] {
                if data & crate::dialect::bit(l) != 0
                    && let Some(word) = w.get(l)
                {
                    return Err(alarms::word_not_allowed(word.span, l));
                }
            }
            return Ok(());
        }
        if rules.rs274_words {
            self.rewritten_on_change(w, axes, cmd)?;
        }
        self.store_cycle_words(w, axes)?;
        // An M code of the block that reads the letter (Haas: `M98 P.. L..`,
        // `M97 P.. L..` beside a hole) takes it: the call repeats, the hole
        // does not.
        let m_letters = w.m.iter().flatten().fold(0, |m, a| m | a.def.letters);
        let repeat = rules
            .repeat
            .filter(|r| m_letters & crate::dialect::bit(r.letter) == 0);
        let count = match repeat.and_then(|r| w.get(r.letter).map(|k| (r, k))) {
            Some((r, k)) => {
                // LinuxCNC: "Cannot do zero repeats of cycle".
                let why = match (r.letter, r.least) {
                    (b'L', 1) => "L is a repeat count 1-9999",
                    (b'L', _) => "L is a repeat count 0-9999",
                    _ => "K is a repeat count 0-9999",
                };
                crate::words::whole(&k, r.letter, f64::from(r.least), 9999.0, why)?
            }
            None => 1,
        };
        let drill_letter = letter(axes.z).unwrap_or(b'Z');
        // Where each hole is: the block's plane words (G91: once more per
        // repeat), the drilling axis at the tool's level.
        let keep = |g: &mut crate::motion::Goal, prog: Pos| g.prog.set(axes.z, prog.get(axes.z));
        if count == 0 {
            // K0 stores the data and moves nothing (1.2.30).
            return self.cycle_ready(cmd, w.get(drill_letter)).map(|_| ());
        }
        let c = self.cycle_ready(cmd, w.get(drill_letter))?;
        self.spindle_ready(c, cmd)?;
        self.check_pecks(count.into(), cmd)?;
        let suspended = self.suspend_comp()?;
        for _ in 0..count {
            let mut goal = self.state.target(self.cfg, w, self.state.modal.incremental);
            keep(&mut goal, self.state.prog);
            self.hole(
                c,
                axes,
                goal.prog.get(axes.a),
                goal.prog.get(axes.b),
                w,
                cmd,
            )?;
        }
        self.resume_comp(suspended);
        Ok(())
    }

    /// rs274's words: a block that changes the cycle (or enters one) writes R,
    /// the depth, and the P of G82/G86/G89 or the Q of G73/G83 again
    /// (rs274: "R clearance plane unspecified in cycle", "Z value
    /// unspecified", "Dwell time P word missing with G86" …): nothing is
    /// taken over from the cycle before.
    fn rewritten_on_change(
        &self,
        w: &Words<'_>,
        axes: CycleAxes,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let data = self.state.cycle;
        let Some(c) = data
            .code
            .filter(|c| w.group(Group::Cycle).is_some() && data.before != Some(*c))
        else {
            return Ok(());
        };
        let depth = self.cfg.axis_words.get(axes.z).map_or(b'Z', |a| a.letter);
        let extra = match data.hole {
            Hole::DrillDwell | Hole::BoreStop | Hole::BoreDwell => Some((b'P', "P (the dwell)")),
            Hole::HighSpeedPeck | Hole::DeepPeck => Some((b'Q', "Q (the peck)")),
            _ => None,
        };
        let missing: Vec<&str> = [(b'R', "R (the R level)"), (depth, "the depth")]
            .into_iter()
            .chain(extra)
            .filter(|(l, _)| w.get(*l).is_none())
            .map(|(_, what)| what)
            .collect();
        if missing.is_empty() {
            return Ok(());
        }
        Err(alarms::needs_word(
            cmd,
            c.as_str(),
            &format!(
                "{}, written again in the block that changes the cycle",
                missing.join(" and ")
            ),
        ))
    }

    /// Z, R, Q, P of a drilling block into the cycle data (levels resolved
    /// to absolute program levels: under G91 R is from the initial level
    /// and Z from the R level).
    fn store_cycle_words(&mut self, w: &Words<'_>, axes: CycleAxes) -> Result<(), Diagnostic> {
        let inc = self.state.modal.incremental;
        let z_letter = self.cfg.axis_words.get(axes.z).map_or(b'Z', |a| a.letter);
        let r_word = w.get(b'R').map(|r| self.units().length_mm(&r));
        let z_word = w
            .get(z_letter)
            .map(|z| self.units().axis_value(&self.cfg.axis_words, axes.z, &z));
        let cycle = &mut self.state.cycle;
        let (r_word, z_word) = if self.cfg.dialect.cycles.rs274_words {
            // LinuxCNC keeps the words and reads them under each block's
            // G90/G91 (`G90 G81 … R2`, then `G91 X10 L2`: R is 2 above the
            // initial level there).
            let (r, z) = &mut cycle.written_rz;
            *r = r_word.or(*r);
            *z = z_word.or(*z);
            (*r, *z)
        } else {
            (r_word, z_word)
        };
        if let Some(v) = r_word {
            cycle.r = Some(if inc { cycle.initial + v } else { v });
        }
        if let Some(v) = z_word {
            let r_level = cycle.r.unwrap_or(cycle.initial);
            cycle.z = Some(if inc { r_level + v } else { v });
        }
        let rules = self.cfg.dialect.cycles;
        let hole = self.state.cycle.hole;
        if self.state.cycle.code.is_some() {
            // An M code of the block may read them (LinuxCNC's `M62 P1`).
            let m_letters =
                w.other_letters | w.m.iter().flatten().fold(0, |m, a| m | a.def.letters);
            for (l, read) in [(b'P', rules.reads_p(hole)), (b'Q', rules.reads_q(hole))] {
                let read = read || m_letters & crate::dialect::bit(l) != 0;
                if let Some(word) = w.get(l).filter(|_| !read) {
                    return Err(alarms::word_not_allowed(word.span, l));
                }
            }
        }
        if let Some(q) = w.get(b'Q') {
            let v = self.units().length_mm(&q);
            let bad = match self.state.cycle.code.map(|_| hole) {
                // A tap that pecks takes Q ≥ 0 (0: no pecks).
                Some(Hole::Tap) => v < 0.0,
                Some(h) => pecks_with_q(h) && v <= 0.0,
                None => false,
            };
            if bad {
                return Err(alarms::value_out_of_range(
                    q.span,
                    b'Q',
                    q.value,
                    "a peck depth Q is more than 0",
                ));
            }
            self.state.cycle.q = Some(v);
            // A Q written later replaces Haas's I, J, K (in their own block
            // they win: `store_reduced_peck` runs after).
            self.state.cycle.reduced = None;
        }
        if let Some(p) = w.get(b'P') {
            crate::words::dwell_not_negative(&p)?;
            self.state.cycle.p_s = Some(self.units().seconds(&p));
        }
        if self.cfg.dialect.cycles.reduced_pecks {
            self.store_reduced_peck(w)?;
        }
        Ok(())
    }

    /// Haas G73/G83 I, J, K: all three or none (the manual: "if I, J, and K
    /// are specified, a different operating mode is selected"); I and K
    /// more than 0, J not negative. They stay for the cycle's later holes,
    /// like Q.
    fn store_reduced_peck(&mut self, w: &Words<'_>) -> Result<(), Diagnostic> {
        let (i, j, k) = (w.get(b'I'), w.get(b'J'), w.get(b'K'));
        let Some(first_word) = i.or(j).or(k) else {
            return Ok(());
        };
        let code = self.state.cycle.code;
        let pecks = matches!(self.state.cycle.hole, Hole::HighSpeedPeck | Hole::DeepPeck);
        if code.is_none() || !pecks {
            return Err(alarms::word_not_allowed(first_word.span, first_word.addr.0));
        }
        let (Some(i), Some(j), Some(k)) = (i, j, k) else {
            return Err(alarms::needs_word(
                first_word.span,
                code.map_or("G83", Cycle::as_str),
                "I, J and K together (the first peck, how much less each next one, the least)",
            ));
        };
        let (first, less, least) = (
            self.units().length_mm(&i),
            self.units().length_mm(&j),
            self.units().length_mm(&k),
        );
        for (word, v, ok, why) in [
            (i, first, first > 0.0, "the first peck I is more than 0"),
            (j, less, less >= 0.0, "the reduction J is not negative"),
            (k, least, least > 0.0, "the least peck K is more than 0"),
        ] {
            if !ok {
                return Err(alarms::value_out_of_range(word.span, word.addr.0, v, why));
            }
        }
        self.state.cycle.reduced = Some(ReducedPeck { first, less, least });
        Ok(())
    }

    /// Checks that the stored data can drill: Z and R known, Z below R (above
    /// for G87), Q for the pecking cycles.
    fn cycle_ready(&self, cmd: Span, z_word: Option<Word>) -> Result<Cycle, Diagnostic> {
        let data = self.state.cycle;
        let c = data
            .code
            .ok_or_else(|| alarms::pattern_without_cycle(cmd))?;
        let rules = self.cfg.dialect.cycles;
        // EIA: R is optional, the R level is then the initial level.
        let r = if rules.r_optional {
            Some(data.r.unwrap_or(data.initial))
        } else {
            data.r
        };
        let (Some(z), Some(r)) = (data.z, r) else {
            let what = if rules.r_optional {
                "Z (the hole depth)"
            } else {
                "Z (the hole bottom) and R (the R level)"
            };
            return Err(alarms::needs_word(cmd, c.as_str(), what));
        };
        let upward = data.hole == Hole::BackBore;
        // LinuxCNC refuses only a bottom above R ("R less than Z").
        let flat = if rules.bottom_at_r { -SAME_MM } else { SAME_MM };
        if (upward && z <= r + SAME_MM) || (!upward && z >= r - flat) {
            return Err(alarms::cycle_direction(
                z_word.map_or(cmd, |w| w.span),
                upward,
            ));
        }
        // EIA G82/G89: the dwell is part of the cycle's data (§2).
        if rules.dwell_required
            && matches!(data.hole, Hole::DrillDwell | Hole::BoreDwell)
            && data.p_s.is_none()
        {
            return Err(alarms::needs_word(
                cmd,
                c.as_str(),
                "P (the dwell at the hole bottom)",
            ));
        }
        if pecks_with_q(data.hole) && data.reduced.is_none() && data.q.is_none_or(|q| q <= 0.0) {
            return Err(alarms::needs_word(
                cmd,
                c.as_str(),
                "Q (the depth of each peck)",
            ));
        }
        Ok(c)
    }

    /// Checks that the spindle turns the way tapping cycle `c` needs
    /// (only when it drills: K0 stores the data with the spindle stopped).
    fn spindle_ready(&self, c: Cycle, cmd: Span) -> Result<(), Diagnostic> {
        let turning =
            matches!(self.state.spindle, SpindleDir::Cw | SpindleDir::Ccw) && self.state.rpm > 0.0;
        let wanted = match self.state.cycle.hole {
            // EIA: a tap in either direction (a left-hand tap turns M04).
            Hole::TapEitherWay => Some(None),
            Hole::Tap => Some(Some(SpindleDir::Cw)),
            Hole::LeftTap => Some(Some(SpindleDir::Ccw)),
            _ => None,
        };
        if self.state.rigid_tap && self.state.s_value > 0.0 && wanted.is_some() {
            // M29: the cycle turns the spindle itself.
            return Ok(());
        }
        if let Some(dir) = wanted
            && (!turning || dir.is_some_and(|d| d != self.state.spindle))
        {
            let cw = dir.map(|d| d == SpindleDir::Cw);
            return Err(alarms::tapping_spindle(cmd, c.as_str(), cw));
        }
        Ok(())
    }

    /// Alarms when `holes` holes of cycle `c` would peck more than
    /// `MAX_PECKS` times: a tiny Q over a deep hole would otherwise hold
    /// millions of moves until the block succeeds.
    fn check_pecks(&self, holes: u64, cmd: Span) -> Result<(), Diagnostic> {
        let data = self.state.cycle;
        let pecking = pecks_with_q(data.hole) || data.hole == Hole::Tap;
        let Some(z) = data.z.filter(|_| pecking) else {
            return Ok(());
        };
        let depth = (data.r.unwrap_or(data.initial) - z).abs();
        let per_hole = match data.reduced {
            // Count Haas's shrinking pecks, no further than the bound.
            Some(_) if pecks_with_q(data.hole) => {
                let cap = MAX_PECKS / holes.max(1) + 1;
                let (mut depths, mut done, mut n) = (PeckDepths::of(&data, depth), 0.0, 0u64);
                while done < depth - SAME_MM && n <= cap {
                    done += depths.take();
                    n += 1;
                }
                n as f64
            }
            _ => match data.q.filter(|q| *q > 0.0) {
                Some(q) => (depth / q).ceil(),
                None => return Ok(()),
            },
        };
        if per_hole * holes as f64 > MAX_PECKS as f64 {
            return Err(alarms::too_many_pecks(cmd, MAX_PECKS));
        }
        Ok(())
    }

    /// A step of a cycle or pocket: a move to program point `p` unless the
    /// tool is there already (steps that would not move are not reported).
    pub(crate) fn step_to(
        &mut self,
        kind: MoveKind,
        p: Pos,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let here = self.state.prog;
        let same =
            (0..vcnc_core::events::MAX_AXES).all(|i| (p.get(i) - here.get(i)).abs() <= SAME_MM);
        if same {
            return Ok(());
        }
        self.straight(kind, Target::Program(p), w, cmd)
    }

    /// rs274's way to a hole, before the move to R (`Approach::ReturnLevelFirst`,
    /// LinuxCNC's `convert_cycle_xy`): a tool whose cycle started
    /// below R first goes straight to R where it is (up, or down to a
    /// lowered R); the return level is R under G99, else the level the
    /// cycle started at (R if that was below); the tool goes to the hole at
    /// its own level when that is above R, else straight (diagonally, from
    /// R or below) to the return level. Returns the return level.
    fn return_level_first(
        &mut self,
        s: &mut Steps<'_, '_>,
        zr: f64,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<f64, Diagnostic> {
        let z = s.axes.z;
        let mut start = self.state.cycle.initial;
        if start < zr {
            let mut here = self.state.prog;
            here.set(z, zr);
            self.step_to(MoveKind::Rapid, here, w, cmd)?;
            start = zr;
        }
        let ret = if self.state.modal.return_r { zr } else { start };
        let here = self.state.prog.get(z);
        s.rapid(self, if here > zr { here } else { ret })?;
        Ok(ret)
    }

    /// Cutter compensation is suspended for a cycle's holes (Fanuc): the
    /// held move ends square to its path.
    pub(crate) fn suspend_comp(&mut self) -> Result<bool, Diagnostic> {
        if !self.stage.comp.engaged() {
            return Ok(false);
        }
        self.comp_finish()?;
        Ok(self.state.modal.comp != crate::state::CompSide::Off)
    }

    /// After the holes: the next move in the plane starts compensation again.
    pub(crate) fn resume_comp(&mut self, suspended: bool) {
        if suspended {
            self.stage.comp.mode = crate::motion::comp::Mode::Starting;
        }
    }

    /// One hole at program (a, b) with the stored data.
    fn hole(
        &mut self,
        c: Cycle,
        axes: CycleAxes,
        a: f64,
        b: f64,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let data = self.state.cycle;
        let Some(zz) = data.z else {
            return Err(alarms::needs_word(cmd, c.as_str(), "Z"));
        };
        // `cycle_ready` has checked that R is given where it is required.
        let zr = data.r.unwrap_or(data.initial);
        let mut at = self.state.prog;
        at.set(axes.a, a);
        at.set(axes.b, b);
        at.set(axes.z, zz);
        let at = self.state.frame.machine_of(at);
        self.emit(|loc| Event::Hole { loc, cycle: c, at });
        let rules = self.cfg.dialect.cycles;
        let hole = data.hole;
        let mut ret =
            if rules.always_back_to_r || (self.state.modal.return_r && hole != Hole::BackBore) {
                zr
            } else {
                data.initial
            };
        let mut s = Steps {
            axes,
            at: (a, b),
            w,
            cmd,
        };
        match rules.approach {
            Approach::ReturnLevelFirst => ret = self.return_level_first(&mut s, zr, w, cmd)?,
            Approach::PlaneThenR => {
                // Positioning in the plane at the current level, then to R.
                let z_now = self.state.prog.get(axes.z);
                s.rapid(self, z_now)?;
            }
        }
        if hole == Hole::BackBore {
            return self.back_bore(&mut s, zr, zz, data);
        }
        s.rapid(self, zr)?;
        let feed = self.feed(cmd)?;
        let dwell = data.p_s.filter(|p| *p > 0.0);
        // A spindle the cycle stops or orients starts again as it turned.
        let turning = self.state.spindle;
        match hole {
            Hole::Drill => s.feed(self, zz, feed)?,
            Hole::DrillDwell | Hole::BoreDwell => {
                s.feed(self, zz, feed)?;
                self.cycle_dwell(dwell);
                if hole == Hole::BoreDwell {
                    // LinuxCNC feeds out all the way to the return level.
                    let out = if rules.bore_out_to_return_level {
                        ret
                    } else {
                        zr
                    };
                    s.feed(self, out, feed)?;
                }
            }
            Hole::HighSpeedPeck | Hole::DeepPeck => {
                self.pecks(&mut s, hole, zr, zz, data, feed)?;
            }
            // Chip breaking: back off 0.010 inch between pecks.
            Hole::ChipBreak => {
                let q = PeckDepths::of(&data, zr - zz);
                self.peck_moves(&mut s, (zr, zz), q, CHIP_BREAK_BACK_OFF_MM, false, feed)?;
            }
            Hole::Tap | Hole::LeftTap => {
                let (fwd, rev) = if hole == Hole::Tap {
                    (SpindleDir::Cw, SpindleDir::Ccw)
                } else {
                    (SpindleDir::Ccw, SpindleDir::Cw)
                };
                match rules.tap {
                    TapStyle::ReverseDwellOut => {
                        // Reverse at the bottom, dwell P, feed out all the
                        // way to the return level.
                        s.feed(self, zz, feed)?;
                        self.cycle_spindle(rev);
                        self.cycle_dwell(dwell);
                        s.feed(self, ret, feed)?;
                        self.cycle_spindle(fwd);
                    }
                    TapStyle::PeckByQ => {
                        let peck = data.q.filter(|q| *q > 0.0 && hole == Hole::Tap);
                        // Rigid tapping (M29) turns a stopped spindle for
                        // the tap and stops it again at R.
                        let started = self.rigid_start(fwd);
                        let end = started.map_or(fwd, |(dir, _)| dir);
                        self.tap(&mut s, (fwd, rev, end), (zr, zz), peck, dwell, feed)?;
                        if let Some((_, rpm)) = started {
                            self.state.rpm = rpm;
                        }
                    }
                }
            }
            Hole::TapEitherWay => {
                let fwd = self.state.spindle;
                let rev = if fwd == SpindleDir::Ccw {
                    SpindleDir::Cw
                } else {
                    SpindleDir::Ccw
                };
                self.tap(&mut s, (fwd, rev, fwd), (zr, zz), None, None, feed)?;
            }
            Hole::Bore => {
                s.feed(self, zz, feed)?;
                s.feed(self, zr, feed)?;
            }
            Hole::BoreStop => {
                s.feed(self, zz, feed)?;
                // LinuxCNC's G86 dwells P at the bottom; Fanuc's has no P.
                if rules.bore_stop_dwell {
                    self.cycle_dwell(dwell);
                }
                self.cycle_spindle(SpindleDir::Stop);
                s.rapid(self, ret)?;
                self.cycle_spindle(turning);
                return Ok(());
            }
            Hole::BoreWaitStart => {
                // The cutter rapids out when the operator presses START.
                s.feed(self, zz, feed)?;
                self.emit(|loc| Event::Wait {
                    loc,
                    reason: WaitReason::CycleStart,
                });
            }
            Hole::BoreManual => {
                // The way out is fed with the spindle stopped (1.2.41
                // step 6): per revolution it cannot move.
                if matches!(feed, Feed::PerRev(_)) {
                    return Err(alarms::per_rev_spindle_stopped(
                        cmd,
                        self.cfg.dialect.g_for(GOp::Mode(ModeOp::PerMinute)),
                    ));
                }
                s.feed(self, zz, feed)?;
                self.cycle_dwell(dwell);
                self.cycle_spindle(SpindleDir::Stop);
                self.emit(|loc| Event::Wait {
                    loc,
                    reason: WaitReason::ManualMotion,
                });
                s.feed(self, zr, feed)?;
                s.rapid(self, ret)?;
                self.cycle_spindle(turning);
                return Ok(());
            }
            Hole::FineBore => {
                s.feed(self, zz, feed)?;
                self.cycle_dwell(dwell);
                self.cycle_spindle(SpindleDir::Orient);
                let shift = self.shift_vector(axes, data);
                s.shift(self, shift, zz)?;
                s.shift(self, shift, ret)?;
                s.shift(self, (0.0, 0.0), ret)?;
                self.cycle_spindle(turning);
                return Ok(());
            }
            // Bored above, from below the part.
            Hole::BackBore => {}
        }
        s.rapid(self, ret)
    }

    /// G73 (retract d) and G83 (back to R, down to d above the last depth).
    fn pecks(
        &mut self,
        s: &mut Steps<'_, '_>,
        hole: Hole,
        zr: f64,
        zz: f64,
        data: CycleData,
        feed: Feed,
    ) -> Result<(), Diagnostic> {
        // LinuxCNC's clearance is fixed at 0.010 inch (its G73 back-off and
        // G83 rapid delta); the Fanuc's is a parameter (5114).
        let rules = self.cfg.dialect.cycles;
        let d = match rules.peck_clearance {
            PeckClearance::Fixed(d) => d,
            PeckClearance::Parameter => self.cfg.machine.params.peck_return_mm,
        };
        let back_to_r = hole == Hole::DeepPeck;
        self.peck_moves(
            s,
            (zr, zz),
            PeckDepths::of(&data, zr - zz),
            d,
            back_to_r,
            feed,
        )?;
        if rules.peck_dwell && rules.reads_p(hole) {
            self.cycle_dwell(data.p_s.filter(|p| *p > 0.0));
        }
        Ok(())
    }

    /// Pecks of `depths` from zr down to zz: after each peck back to R and
    /// down again to d above the last depth (`back_to_r`, G83), or back
    /// off by d (G73, EIA G87).
    fn peck_moves(
        &mut self,
        s: &mut Steps<'_, '_>,
        (zr, zz): (f64, f64),
        mut depths: PeckDepths,
        d: f64,
        back_to_r: bool,
        feed: Feed,
    ) -> Result<(), Diagnostic> {
        let mut depth = zr;
        loop {
            let next = (depth - depths.take()).max(zz);
            if back_to_r && depth < zr - SAME_MM {
                // Back down to d above the last depth.
                s.rapid(self, (depth + d).min(zr))?;
            }
            s.feed(self, next, feed)?;
            if next <= zz + SAME_MM {
                return Ok(());
            }
            if back_to_r {
                s.rapid(self, zr)?;
            } else {
                s.rapid(self, next + d)?;
            }
            depth = next;
        }
    }

    /// Under M29 with the spindle not already turning `fwd`: turns it at
    /// S for the tap and returns how it was, for after the hole.
    fn rigid_start(&mut self, fwd: SpindleDir) -> Option<(SpindleDir, f64)> {
        if !self.state.rigid_tap || (self.state.spindle == fwd && self.state.rpm > 0.0) {
            return None;
        }
        let before = (self.state.spindle, self.state.rpm);
        self.state.rpm = self.state.s_value;
        self.cycle_spindle(fwd);
        Some(before)
    }

    /// G74/G84: in with the spindle forward, out reversed; with a peck
    /// depth, pecks (parameter 4001: type II backs off d, type III goes
    /// back to R). Back at R the spindle turns `end` (forward, or stopped
    /// after a rigid tap that started it).
    fn tap(
        &mut self,
        s: &mut Steps<'_, '_>,
        (fwd, rev, end): (SpindleDir, SpindleDir, SpindleDir),
        (zr, zz): (f64, f64),
        peck: Option<f64>,
        dwell: Option<f64>,
        feed: Feed,
    ) -> Result<(), Diagnostic> {
        let type_two = self.cfg.machine.params.tapping_type == 1;
        let d = self.cfg.machine.params.peck_return_mm;
        let mut depth = zr;
        loop {
            let next = match peck {
                Some(q) => (depth - q).max(zz),
                None => zz,
            };
            s.feed(self, next, feed)?;
            self.cycle_dwell(dwell);
            self.cycle_spindle(rev);
            let last = next <= zz + SAME_MM;
            let out = if last || !type_two { zr } else { next + d };
            s.feed(self, out, feed)?;
            self.cycle_dwell(dwell);
            if last {
                self.cycle_spindle(end);
                return Ok(());
            }
            self.cycle_spindle(fwd);
            depth = next;
        }
    }

    /// G87 back boring: shifted down to R below the part, bore up to Z,
    /// shifted out to the initial level.
    fn back_bore(
        &mut self,
        s: &mut Steps<'_, '_>,
        zr: f64,
        zz: f64,
        data: CycleData,
    ) -> Result<(), Diagnostic> {
        let shift = self.shift_vector(s.axes, data);
        let feed = self.feed(s.cmd)?;
        let z_now = self.state.prog.get(s.axes.z);
        let turning = self.state.spindle;
        self.cycle_spindle(SpindleDir::Orient);
        s.shift(self, shift, z_now)?;
        s.shift(self, shift, zr)?;
        s.shift(self, (0.0, 0.0), zr)?;
        self.cycle_spindle(turning);
        s.feed(self, zz, feed)?;
        self.cycle_dwell(data.p_s.filter(|p| *p > 0.0));
        self.cycle_spindle(SpindleDir::Orient);
        s.shift(self, shift, zz)?;
        s.shift(self, shift, data.initial)?;
        s.shift(self, (0.0, 0.0), data.initial)?;
        self.cycle_spindle(turning);
        Ok(())
    }

    /// The G76/G87 shift in program coordinates of the plane: |Q| along the
    /// machine direction of parameter 4020.
    fn shift_vector(&self, axes: CycleAxes, data: CycleData) -> (f64, f64) {
        let q = data.q.unwrap_or(0.0).abs();
        let mut m = Pos::default();
        let (i, sign) = match self.cfg.machine.params.shift_direction {
            0 => (axes.a, 1.0),
            1 => (axes.a, -1.0),
            2 => (axes.b, 1.0),
            _ => (axes.b, -1.0),
        };
        m.set(i, sign * q);
        // A machine direction, brought back through the frame's linear part.
        let origin = self.state.frame.program_of(Pos::default());
        let p = self.state.frame.program_of(m);
        (
            p.get(axes.a) - origin.get(axes.a),
            p.get(axes.b) - origin.get(axes.b),
        )
    }

    fn cycle_dwell(&mut self, seconds: Option<f64>) {
        if let Some(seconds) = seconds {
            self.emit(|loc| Event::Dwell { loc, seconds });
        }
    }

    /// A spindle change inside a cycle (reversal, stop, orientation).
    pub(crate) fn cycle_spindle(&mut self, dir: SpindleDir) {
        let rpm = match dir {
            SpindleDir::Cw | SpindleDir::Ccw => self.state.rpm,
            _ => 0.0,
        };
        let (surface, keep) = (None, self.state.rpm);
        self.state.spindle = dir;
        self.state.rpm = keep;
        self.emit(|loc| Event::Spindle {
            loc,
            dir,
            rpm,
            surface_m_per_min: surface,
        });
    }

    /// A hole pattern G134–G137.1: the holes of the active cycle at the
    /// pattern's positions, in the order of `docs/cycles-spec.md` §8.
    pub(crate) fn pattern(
        &mut self,
        op: CycleOp,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let c = self.cycle_ready(cmd, None)?;
        self.spindle_ready(c, cmd)?;
        let axes = self.cycle_axes(cmd)?;
        let (x, y) = {
            let mut goal = self.state.target(self.cfg, w, self.state.modal.incremental);
            goal.prog.set(axes.z, self.state.prog.get(axes.z));
            (goal.prog.get(axes.a), goal.prog.get(axes.b))
        };
        let holes = self.pattern_holes(op, w, cmd, (x, y))?;
        self.check_pecks(holes.len() as u64, cmd)?;
        let suspended = self.suspend_comp()?;
        for (a, b) in holes {
            self.hole(c, axes, a, b, w, cmd)?;
        }
        self.resume_comp(suspended);
        Ok(())
    }

    /// The hole positions of a pattern.
    fn pattern_holes(
        &self,
        op: CycleOp,
        w: &Words<'_>,
        cmd: Span,
        (x, y): (f64, f64),
    ) -> Result<Vec<(f64, f64)>, Diagnostic> {
        let need = |l: u8, what: &str| {
            w.get(l)
                .ok_or_else(|| alarms::needs_word(cmd, "a hole pattern", what))
        };
        let count = |word: Word, min: f64, why: &str| {
            crate::words::whole(&word, word.addr.0, min, 9999.0, why)
        };
        let positive = |word: Word, v: f64, why: &str| {
            if v <= 0.0 {
                Err(alarms::value_out_of_range(
                    word.span,
                    word.addr.0,
                    word.value,
                    why,
                ))
            } else {
                Ok(v)
            }
        };
        let mut out = Vec::new();
        match op {
            CycleOp::PatternCircle => {
                let i = need(b'I', "I (the radius)")?;
                let r = positive(i, self.units().length_mm(&i), "the radius I is more than 0")?;
                let start = w.get(b'J').map_or(0.0, |j| self.units().angle_deg(&j));
                let k = need(b'K', "K (the number of holes)")?;
                if k.point {
                    return Err(alarms::no_decimal_point(k.span, b'K', "K counts holes"));
                }
                if k.value == 0.0 || k.value.abs() > 9999.0 {
                    return Err(alarms::value_out_of_range(
                        k.span,
                        b'K',
                        k.value,
                        "K is ±1 to ±9999 holes",
                    ));
                }
                let n = k.value.abs();
                let step = 360.0 / n * k.value.signum();
                let mut i = 0.0;
                while i < n {
                    let ang = (start + i * step).to_radians();
                    out.push((x + r * ang.cos(), y + r * ang.sin()));
                    i += 1.0;
                }
            }
            CycleOp::PatternLine => {
                let i = need(b'I', "I (the interval)")?;
                let step = self.units().length_mm(&i);
                if step == 0.0 {
                    return Err(alarms::value_out_of_range(
                        i.span,
                        b'I',
                        i.value,
                        "the interval I is not 0",
                    ));
                }
                let ang = w
                    .get(b'J')
                    .map_or(0.0, |j| self.units().angle_deg(&j))
                    .to_radians();
                let n = count(
                    need(b'K', "K (the number of holes)")?,
                    1.0,
                    "K is 1 to 9999 holes",
                )?;
                for k in 0..n {
                    let d = f64::from(k) * step;
                    out.push((x + d * ang.cos(), y + d * ang.sin()));
                }
            }
            CycleOp::PatternArc => {
                let i = need(b'I', "I (the radius)")?;
                let r = positive(i, self.units().length_mm(&i), "the radius I is more than 0")?;
                let start = w.get(b'J').map_or(0.0, |j| self.units().angle_deg(&j));
                let n = count(
                    need(b'K', "K (the number of holes)")?,
                    1.0,
                    "K is 1 to 9999 holes",
                )?;
                let p = need(b'P', "P (the angle between holes)")?;
                let step = self.units().angle_deg(&p);
                if step == 0.0 && n > 1 {
                    return Err(alarms::value_out_of_range(
                        p.span,
                        b'P',
                        p.value,
                        "the angle step P is not 0",
                    ));
                }
                for k in 0..n {
                    let ang = (start + f64::from(k) * step).to_radians();
                    out.push((x + r * ang.cos(), y + r * ang.sin()));
                }
            }
            // Not patterns: `axis_code` sends them elsewhere.
            CycleOp::Drill(..)
            | CycleOp::Cancel
            | CycleOp::PocketRect
            | CycleOp::PocketCircle
            | CycleOp::CircleCut(..) => {}
            CycleOp::PatternGrid => {
                let (iw, jw) = (
                    need(b'I', "I (the X interval)")?,
                    need(b'J', "J (the Y interval)")?,
                );
                let (di, dj) = (self.units().length_mm(&iw), self.units().length_mm(&jw));
                let per_row = count(
                    need(b'P', "P (holes per row)")?,
                    1.0,
                    "P is 1 to 9999 holes",
                )?;
                let rows = count(
                    need(b'K', "K (the number of rows)")?,
                    1.0,
                    "K is 1 to 9999 rows",
                )?;
                if u64::from(per_row) * u64::from(rows) > MAX_HOLES {
                    return Err(alarms::too_many_holes(cmd, MAX_HOLES));
                }
                if di == 0.0 && per_row > 1 {
                    return Err(alarms::value_out_of_range(
                        iw.span,
                        b'I',
                        iw.value,
                        "the interval I is not 0",
                    ));
                }
                if dj == 0.0 && rows > 1 {
                    return Err(alarms::value_out_of_range(
                        jw.span,
                        b'J',
                        jw.value,
                        "the interval J is not 0",
                    ));
                }
                for row in 0..rows {
                    for k in 0..per_row {
                        // Serpentine: every other row runs back.
                        let col = if row % 2 == 0 { k } else { per_row - 1 - k };
                        out.push((x + f64::from(col) * di, y + f64::from(row) * dj));
                    }
                }
            }
        }
        if out.len() as u64 > MAX_HOLES {
            return Err(alarms::too_many_holes(cmd, MAX_HOLES));
        }
        Ok(out)
    }
}
