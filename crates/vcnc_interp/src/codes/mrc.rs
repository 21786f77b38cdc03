//! The Fanuc lathe's multiple repetitive cycles, two-block format (0i-TF,
//! G-code system A): what each block reads and the moves it makes.
//!
//! ```text
//!   G70 P Q                   finish along the profile N P … N Q, back to A
//!   G71 U(Δd) R(e)            first block: depth of cut, retract (modal)
//!   G71 P Q U(Δu) W(Δw) F     rough turning (rough.rs), types I and II
//!   G72 W(Δd) R(e)            rough facing: the same with X and Z swapped
//!   G72 P Q U W F
//!   G73 U(Δi) W(Δk) R(d)      pattern repeating: d passes of the profile
//!   G73 P Q U W F               shifted from Δi+Δu/2, Δk+Δw to Δu/2, Δw
//!   G74 R(e)                  face peck drilling / face grooving
//!   G74 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F
//!   G75 R(e)                  grooving: G74 with X and Z swapped
//!   G75 X(U) Z(W) P(Δi) Q(Δk) R(Δd) F
//!   G76 P(m r a) Q(Δdmin) R(d)            threading (threads.rs)
//!   G76 X(U) Z(W) R(i) P(k) Q(Δd) F(L)
//! ```
//!
//! A block with P or Q (G71–G73) or with axis words (G74–G76) is the
//! second block; the first block's values stay until changed, as Fanuc's
//! parameters 5130–5143 do. Lengths without a decimal point are least
//! increments (Fanuc writes P and Q of G74–G76 that way: `Q6000` is 6 mm);
//! U of a second block is a diameter, U of G71's first block a radius.
//! Haas's one-block G71/G72 (`D` the depth of cut) runs as a second block
//! with that depth.
//!
//! G71–G73 read the profile (profile.rs) and then, when the profile's
//! first block is the block right after the cycle block, go on after its
//! last block, else after the cycle block; G70 goes on after itself.
//! Their moves carry the cycle block's line, except G70's, which carry the
//! profile blocks' lines (the blocks it runs). Cutter compensation is
//! suspended for G71–G76 (their passes are not compensated) and runs over
//! G70's profile like over any moves.

use crate::alarms;
use crate::codes::ngc_rough::{Cut, Fault, Path, Roughing};
use crate::codes::profile::{Elem, Profile};
use crate::codes::rough::{self, Across, Frame, Rough, Step};
use crate::codes::turning_cycles::How;
use crate::dialect::GOp;
use crate::dialect::{MotionOp, RoughPockets, TurnOp};
use crate::interpreter::Interpreter;
use crate::interpreter::Machining;
use crate::motion::{MoveKind, Target};
use crate::plane::{P2, Seg, Xz, ZERO_MM};
use crate::words::Words;
use vcnc_core::events::Pos;
use vcnc_syntax::{Cursor, Diagnostic, Span, Word};

/// Most rough levels, passes or pecks one cycle block may make.
const MAX_PASSES: f64 = 10_000.0;

impl Interpreter<'_> {
    /// G70–G73; returns where the program goes on after the block.
    pub(crate) fn profile_cycle(
        &mut self,
        op: GOp,
        cmd: Span,
        w: &Words<'_>,
        next: Cursor,
    ) -> Result<Option<Cursor>, Diagnostic> {
        if op == GOp::Turn(TurnOp::NgcFinishCycle) {
            // LinuxCNC's G70: the profile is a subroutine; the program goes
            // on after the cycle block.
            self.ngc_finish_cycle(w, cmd)?;
            return Ok(Some(next));
        }
        if let GOp::Turn(TurnOp::NgcRoughCycle { facing, pockets }) = op {
            self.ngc_rough_cycle(facing, pockets, w, cmd)?;
            return Ok(Some(next));
        }
        let pq = (w.get(b'P'), w.get(b'Q'));
        if op != GOp::Turn(TurnOp::FinishCycle) && pq == (None, None) {
            self.machining().profile_first_block(op, w)?;
            return Ok(None);
        }
        let (Some(p), Some(q)) = pq else {
            return Err(alarms::needs_word(
                cmd,
                "this cycle",
                "P and Q (the profile's first and last sequence numbers)",
            ));
        };
        self.machining().refuse(w, b"XZ")?;
        match op {
            GOp::Turn(TurnOp::FinishCycle) => {
                // G70 runs the profile as written: no allowance, no depth.
                // A dialect whose G70 row reads some of these letters
                // (Haas's U, W and D) takes them and ignores them.
                let read = self.cfg.dialect.g(70.0).map_or(0, |d| d.letters);
                for letter in b"UWRD" {
                    if read & crate::dialect::bit(*letter) == 0 {
                        self.machining().refuse(w, &[*letter])?;
                    }
                }
                let profile = self.read_profile(p, q, next)?;
                self.finish(&profile, w, cmd)?;
                Ok(Some(next))
            }
            _ => {
                // R is a first-block word (G73's pass count); nothing reads
                // it in the second block.
                self.machining().refuse(w, b"R")?;
                // Compensation is suspended for the passes (like the mill's
                // canned cycles): the next move in the plane starts it again.
                let suspended = self.machining().suspend_comp()?;
                let profile = self.read_profile(p, q, next)?;
                if op == GOp::Turn(TurnOp::PatternCycle) {
                    self.machining().pattern_repeat(&profile, w, cmd)?;
                } else {
                    self.machining().rough(op, &profile, w, cmd)?;
                }
                self.machining().resume_comp(suspended);
                Ok(Some(if profile.follows { profile.after } else { next }))
            }
        }
    }

    /// LinuxCNC's G70 Q [X Z D E P]: P passes (default 1) along the
    /// profile `o<Q> sub`, each a rapid to the start point (X Z, else
    /// where the tool is) and to the profile's first point, then its
    /// blocks; the tool stays at the profile's end. With D or E the passes
    /// follow the profile offset from D … to E (`ngc_rough.rs`) and carry
    /// the cycle block's line.
    pub(crate) fn ngc_finish_cycle(&mut self, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        self.machining().ngc_cycle_plane(cmd, "G70")?;
        let axes = self.machining().lathe_axes(cmd)?;
        let passes = match w.get(b'P') {
            Some(p) => self.machining().count(&p, "P is G70's number of passes")?,
            None => 1,
        };
        let incremental = self.state.modal.incremental;
        let goal = self.state.target(&self.cfg, w, incremental);
        let a = P2::of(&goal.prog, axes);
        let mut profile = self.ngc_cycle_profile(w, cmd, "G70")?;
        let len = |l: u8| {
            w.get(l)
                .map_or(0.0, |x| self.state.units(&self.cfg).length_mm(&x))
        };
        let (d, e) = (len(b'D'), len(b'E'));
        if d != 0.0 || e != 0.0 {
            return self
                .machining()
                .ngc_offset_finish(&profile, a, (d, e, passes), w, cmd);
        }
        // rs274 goes to the profile's first point at rapid, whatever its
        // block says.
        if let Some(first) = profile.elems.first_mut() {
            first.rapid = true;
        }
        let corner = profile.elems.split_first().and_then(|(first, rest)| {
            let segs: Vec<Seg> = rest.iter().map(|e| e.seg).collect();
            Path::new(a, first.seg.end(), &segs).approach_corner()
        });
        self.machining().return_to(a, axes, w, cmd)?;
        for _ in 0..passes {
            // rs274 moves the approach's start to the corner: each pass
            // returns there.
            self.machining()
                .return_to(corner.unwrap_or(a), axes, w, cmd)?;
            let (line, cur_line) = (self.flow.loc.line, self.stage.cur_line);
            let out = self.finish_moves(&profile, axes, w);
            self.flow.loc.line = line;
            self.stage.cur_line = cur_line;
            out?;
        }
        Ok(())
    }

    /// The profile of LinuxCNC's G70–G72: the body of subroutine `o<Q>`.
    fn ngc_cycle_profile(
        &mut self,
        w: &Words<'_>,
        cmd: Span,
        code: &str,
    ) -> Result<Profile, Diagnostic> {
        let q = w
            .get(b'Q')
            .ok_or_else(|| alarms::needs_word(cmd, code, "Q (the profile's subroutine number)"))?;
        let label = crate::words::whole(
            &q,
            b'Q',
            1.0,
            99_999_999.0,
            "Q is the profile's subroutine number",
        )?;
        let (src, start, endsub) = self.ngc_sub_lines(&label.to_string(), q.span)?;
        // rs274 runs the sub as a call without arguments: #1–#30 and the
        // named locals are its own (zero) while the profile is read, and
        // the caller's come back after; #31 and up are the program's.
        let saved = self.macros.ngc.get_or_insert_with(Box::default).enter(&[]);
        let profile = self.read_sub_profile(src, start, endsub, q.span);
        if let Some(params) = self.macros.ngc.as_mut() {
            params.restore(saved);
        }
        profile
    }

    /// LinuxCNC's G71/G72 Q [X Z D I R] and their .1 and .2
    /// (`ngc_rough.rs`): levels I apart from the start point (X Z, else
    /// where the tool is) down to the profile `o<Q>` kept D away, each
    /// pass retracted R; the tool stays where the last move ends, and
    /// the modal motion is that move's, as in rs274.
    fn ngc_rough_cycle(
        &mut self,
        facing: bool,
        pockets: RoughPockets,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let code = if facing { "G72" } else { "G71" };
        self.machining().ngc_cycle_plane(cmd, code)?;
        let axes = self.machining().lathe_axes(cmd)?;
        self.machining().ngc_cycle_modes(cmd, code)?;
        let len = |l: u8, default: f64| {
            w.get(l)
                .map_or(default, |x| self.state.units(&self.cfg).length_mm(&x))
        };
        let (step, allowance, retract) = (len(b'I', 1.0), len(b'D', 0.0), len(b'R', 0.5));
        if let Some(i) = w.get(b'I').filter(|_| step < 0.0) {
            return Err(alarms::value_out_of_range(
                i.span,
                b'I',
                i.value,
                "the depth of cut is positive (rs274: \"I must be greater than zero\")",
            ));
        }
        if step == 0.0 {
            let span = w.get(b'I').map_or(cmd, |i| i.span);
            return Err(alarms::zero_amount(span, "the depth of cut I"));
        }
        let goal = self.state.target(&self.cfg, w, false);
        let a = P2::of(&goal.prog, axes);
        let profile = self.ngc_cycle_profile(w, cmd, code)?;
        let Some((first, rest)) = profile.elems.split_first() else {
            return Err(self
                .machining()
                .profile_alarm(&profile, 0, "the profile has no moves"));
        };
        let segs: Vec<Seg> = rest.iter().map(|e| e.seg).collect();
        let r = Roughing {
            pockets,
            allowance,
            step,
            retract,
            facing,
        };
        let cuts = Path::new(a, first.seg.end(), &segs)
            .rough(&r, rough::MAX_MOVES)
            .map_err(|f| self.machining().ngc_fault(f, &profile, cmd))?;
        self.machining().return_to(a, axes, w, cmd)?;
        self.machining().ngc_cuts(&cuts, axes, w, cmd)
    }

    /// G70: the profile's own moves (with their F and S, and their lines),
    /// then a G00 back to A.
    fn finish(&mut self, profile: &Profile, w: &Words<'_>, cmd: Span) -> Result<(), Diagnostic> {
        let axes = self.machining().lathe_axes(cmd)?;
        let a = self.machining().here_xz(axes);
        let (line, cur_line) = (self.flow.loc.line, self.stage.cur_line);
        let out = self.finish_moves(profile, axes, w);
        self.flow.loc.line = line;
        self.stage.cur_line = cur_line;
        out?;
        self.machining().return_to(a, axes, w, cmd)
    }

    fn finish_moves(
        &mut self,
        profile: &Profile,
        axes: (usize, usize),
        w: &Words<'_>,
    ) -> Result<(), Diagnostic> {
        for e in &profile.elems {
            self.finish_asides(profile, e.asides)?;
            // The moves, warnings and alarms of an element are its block's.
            self.flow.loc.line = e.line.number;
            self.stage.cur_line = Some((profile.src, e.line));
            self.machining()
                .finish_elem(e, axes, w)
                .map_err(|d| self.locate(d, profile.src, &e.line))?;
        }
        self.finish_asides(profile, profile.asides_after)?;
        if let Some(side) = profile.comp_after {
            self.machining().set_comp_side(side);
        }
        Ok(())
    }

    /// The asides `range` of the profile under G70: each block's words
    /// beyond its move, run with the block's line as an ordinary block's
    /// steps would run them (`Machining::profile_words`).
    fn finish_asides(&mut self, profile: &Profile, range: (u32, u32)) -> Result<(), Diagnostic> {
        let (from, to) = (range.0 as usize, range.1 as usize);
        for aside in profile.asides.get(from..to).unwrap_or_default() {
            self.flow.loc.line = aside.line.number;
            self.stage.cur_line = Some((profile.src, aside.line));
            let mut w = Words::new(&aside.block);
            let feed = self.state.feed;
            w.fill(self.cfg.dialect, self.cfg.machine, self.cfg.axis_mask)
                .and_then(|()| self.machining().profile_words(&w))
                .map_err(|d| self.locate(d, profile.src, &aside.line))?;
            // rs274's G70 reads only the geometry of its `o<Q> sub`: the
            // profile's F words neither feed the cycle nor outlast it.
            if self.macros.rules.iso == crate::dialect::IsoMacros::Ngc {
                self.state.feed = feed;
            }
        }
        Ok(())
    }
}

/// How many of the profile's last elements are straight moves on the stock
/// boundary, A's own level across the cuts (a retract along Z at A's X
/// under G71): they cut nothing, so roughing ends before them (G70 still
/// runs them). The approach and at least one element after it are kept, so
/// a profile that is nothing but such moves still meets its alarm.
fn boundary_tail(profile: &Profile, a: Xz, across: Across) -> usize {
    let level = |p: Xz| match across {
        Across::X => p.0,
        Across::Z => p.1,
    };
    let on = |p: Xz| (level(p) - level(a)).abs() <= ZERO_MM;
    let tail = profile
        .elems
        .iter()
        .rev()
        .take_while(|e| e.seg.arc_of().is_none() && on(e.seg.start()) && on(e.seg.end()))
        .count();
    tail.min(profile.elems.len().saturating_sub(2))
}

impl<'a> Machining<'_, 'a> {
    /// E203 for the first of `letters` written in the block.
    fn refuse(&self, w: &Words<'_>, letters: &[u8]) -> Result<(), Diagnostic> {
        match letters.iter().find_map(|l| w.get(*l)) {
            Some(word) => Err(alarms::word_not_allowed(word.span, word.addr.0)),
            None => Ok(()),
        }
    }

    /// G71 U R, G72 W R, G73 U W R.
    fn profile_first_block(&mut self, op: GOp, w: &Words<'_>) -> Result<(), Diagnostic> {
        self.refuse(w, b"XZD")?;
        let len = |word: Option<Word>| word.map(|x| self.units().length_mm(&x));
        match op {
            GOp::Turn(TurnOp::RoughTurnCycle) | GOp::Turn(TurnOp::RoughFaceCycle) => {
                let depth_letter = if op == GOp::Turn(TurnOp::RoughTurnCycle) {
                    b'U'
                } else {
                    b'W'
                };
                let other = if op == GOp::Turn(TurnOp::RoughTurnCycle) {
                    b'W'
                } else {
                    b'U'
                };
                self.refuse(w, &[other])?;
                let depth = len(w.get(depth_letter));
                let retract = len(w.get(b'R'));
                if let Some(word) = w.get(depth_letter).filter(|x| x.value < 0.0) {
                    return Err(alarms::value_out_of_range(
                        word.span,
                        depth_letter,
                        word.value,
                        "the depth of cut is a radius written without a sign",
                    ));
                }
                if depth.is_some_and(|d| d <= 0.0) {
                    let span = w.get(depth_letter).map_or(w.first, |x| x.span);
                    return Err(alarms::zero_amount(span, "the depth of cut"));
                }
                let mrc = &mut self.state.lathe.mrc;
                if let Some(d) = depth {
                    mrc.depth_mm = d;
                }
                if let Some(r) = retract {
                    mrc.retract_mm = r.abs();
                }
            }
            _ => {
                let (du, dw) = (len(w.get(b'U')), len(w.get(b'W')));
                let divisions = match w.get(b'R') {
                    Some(r) => Some(self.count(&r, "R is the number of passes")?),
                    None => None,
                };
                let mrc = &mut self.state.lathe.mrc;
                if let Some(u) = du {
                    mrc.relief_x_mm = u;
                }
                if let Some(v) = dw {
                    mrc.relief_z_mm = v;
                }
                if let Some(d) = divisions {
                    mrc.divisions = d;
                }
            }
        }
        Ok(())
    }

    /// A whole count ≥ 1 (a decimal point is allowed when the value is whole).
    pub(crate) fn count(&self, word: &Word, why: &str) -> Result<u32, Diagnostic> {
        if word.value.fract() != 0.0 || word.value < 0.0 || word.value > MAX_PASSES {
            return Err(alarms::value_out_of_range(
                word.span,
                word.addr.0,
                word.value,
                why,
            ));
        }
        if word.value < 1.0 {
            return Err(alarms::zero_amount(word.span, why));
        }
        // Whole and in 1..=MAX_PASSES: the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(word.value as u32)
    }

    /// The finishing allowance of a second block: U (a diameter) and W.
    fn allowance(&self, w: &Words<'_>) -> Xz {
        P2(
            w.get(b'U').map_or(0.0, |u| self.units().x_length_mm(&u)),
            w.get(b'W').map_or(0.0, |v| self.units().length_mm(&v)),
        )
    }

    /// A profile error located at element `k`'s block.
    fn profile_alarm(&mut self, profile: &Profile, k: usize, why: &str) -> Diagnostic {
        let Some(e) = profile.elems.get(k) else {
            return alarms::profile_not_cut(Span::new(0, 1), why);
        };
        let d = alarms::profile_not_cut(e.span, why);
        self.at.locate(d, profile.src, &e.line)
    }

    /// G71 / G72 second block.
    fn rough(
        &mut self,
        op: GOp,
        profile: &Profile,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        let a = self.here_xz(axes);
        let across = if op == GOp::Turn(TurnOp::RoughTurnCycle) {
            Across::X
        } else {
            Across::Z
        };
        let depth = match w.get(b'D') {
            Some(d) => self.units().length_mm(&d),
            None => self.state.lathe.mrc.depth_mm,
        };
        if depth <= 0.0 {
            let span = w.get(b'D').map_or(cmd, |d| d.span);
            return Err(alarms::zero_amount(
                span,
                "the depth of cut (the cycle's first block U, or D)",
            ));
        }
        let feed = self.feed(cmd)?;
        let (frame, chain) = self.rough_chain(profile, a, across, self.allowance(w))?;
        let P2(ua, _) = frame.uv(a);
        let lowest = chain
            .iter()
            .flat_map(|s| [frame.uv(s.start()).0, frame.uv(s.end()).0])
            .fold(f64::INFINITY, f64::min);
        if ((ua - lowest) / depth).ceil() > MAX_PASSES {
            return Err(alarms::too_many_cycle_moves(cmd));
        }
        let r = Rough {
            frame,
            depth,
            retract: self.state.lathe.mrc.retract_mm,
        };
        let moves =
            rough::rough_passes(a, &chain, &r).ok_or_else(|| alarms::too_many_cycle_moves(cmd))?;
        let first_rapid = profile.elems.first().is_some_and(|e| e.rapid);
        let approach_how = if first_rapid {
            How::Rapid
        } else {
            How::Cut(feed)
        };
        for (step, p) in moves {
            match step {
                Step::Rapid => self.cycle_moves(&[(How::Rapid, p)], axes, w, cmd)?,
                Step::Feed => self.cycle_moves(&[(How::Cut(feed), p)], axes, w, cmd)?,
                Step::Approach => self.cycle_moves(&[(approach_how, p)], axes, w, cmd)?,
                Step::Along(seg) => self.along(&seg, axes, feed, w, cmd)?,
            }
        }
        Ok(())
    }

    /// The frame of G71/G72 and the chain its levels are cut against: the
    /// profile shifted by the allowance, after the approach from A (from
    /// the stock top when the profile starts in front of the stock, else
    /// A's own line to the profile's start). Checks what the type needs.
    fn rough_chain(
        &mut self,
        profile: &Profile,
        a: Xz,
        across: Across,
        shift: Xz,
    ) -> Result<(Frame, Vec<Seg>), Diagnostic> {
        let Some((first, rest)) = profile.elems.split_first() else {
            return Err(self.profile_alarm(profile, 0, "the profile has no moves"));
        };
        let (names_across, names_along) = match across {
            Across::X => profile.first_names,
            Across::Z => (profile.first_names.1, profile.first_names.0),
        };
        if !names_across {
            let why = match across {
                Across::X => "the first block must give X (or U)",
                Across::Z => "the first block must give Z (or W)",
            };
            return Err(self.profile_alarm(profile, 0, why));
        }
        let frame = self.rough_frame(profile, a, across)?;
        let kept = rest.len() + 1 - boundary_tail(profile, a, across);
        let segs: Vec<Seg> = rest
            .iter()
            .take(kept - 1)
            .map(|e| e.seg.shifted(shift))
            .collect();
        // Type I (the first block names only the level axis) is monotone
        // both ways, type II along the cuts.
        rough::check_monotone(&segs, &frame, !names_along)
            .map_err(|u| self.profile_alarm(profile, u.elem + 1, u.why))?;
        let start = first.seg.end() + shift;
        let P2(ua, va) = frame.uv(a);
        let from = if frame.uv(start).1 >= va {
            frame.xz(P2(ua, frame.uv(start).1))
        } else {
            a
        };
        let mut chain = vec![Seg::line(from, start)];
        chain.extend(segs);
        Ok((frame, chain))
    }

    /// The normalised frame of G71/G72: the profile lies on one side of A
    /// across the levels, and its end beyond A along the cuts.
    fn rough_frame(
        &mut self,
        profile: &Profile,
        a: Xz,
        across: Across,
    ) -> Result<Frame, Diagnostic> {
        let pick = |p: Xz| match across {
            Across::X => p,
            Across::Z => p.swapped(),
        };
        let P2(aa, av) = pick(a);
        let pts: Vec<P2> = profile
            .elems
            .iter()
            .skip(1)
            .flat_map(|e| [pick(e.seg.start()), pick(e.seg.end())])
            .collect();
        let below = pts.iter().all(|p| p.0 <= aa + ZERO_MM);
        let above = pts.iter().all(|p| p.0 >= aa - ZERO_MM);
        let su = match (below, above) {
            (true, false) => 1.0,
            (false, true) => -1.0,
            // Nothing but the approach, or a shape on A's own level: on
            // neither side, so nothing to rough.
            (true, true) => {
                let why = if pts.is_empty() {
                    "it is only its first block (the approach from the start point), so it never reaches the stock: write the finished shape's blocks up to the N that Q names"
                } else {
                    "it runs on the start point's level across the cuts, so it never reaches the stock: start the cycle outside the stock, clear of the shape"
                };
                return Err(self.profile_alarm(profile, 0, why));
            }
            (false, false) => {
                return Err(self.profile_alarm(
                    profile,
                    0,
                    "the profile lies on both sides of the start point across the cuts: start the cycle outside the stock",
                ));
            }
        };
        // A last move along the stock boundary (A's own level across the
        // cuts, such as a retract back to A's Z) cuts nothing: the profile
        // the levels are cut against ends before it.
        let kept = profile.elems.len() - boundary_tail(profile, a, across);
        let end = profile
            .elems
            .get(..kept)
            .and_then(<[Elem]>::last)
            .map_or(av, |e| pick(e.seg.end()).1);
        let sv = if end < av - ZERO_MM {
            1.0
        } else if end > av + ZERO_MM {
            -1.0
        } else {
            let last = kept.saturating_sub(1);
            return Err(self.profile_alarm(
                profile,
                last,
                "the profile ends where the cycle starts along the cuts",
            ));
        };
        Ok(Frame { across, su, sv })
    }

    /// A feed along a profile element (a line or an arc).
    fn along(
        &mut self,
        seg: &Seg,
        axes: (usize, usize),
        feed: vcnc_core::events::Feed,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        match seg.arc_of() {
            None => self.cycle_moves(&[(How::Cut(feed), seg.end())], axes, w, cmd),
            // Counter-clockwise in (X, Z) is clockwise in G18's (Z, X): a G02.
            Some((c, ccw_xz)) => {
                let to: Pos = seg.end().placed(self.state.prog, axes);
                let here = self.here_xz(axes);
                let offset = (c - here).placed(Pos::default(), axes);
                let kind = MoveKind::Arc {
                    offset,
                    plane: vcnc_core::events::Plane::Zx,
                    cw: ccw_xz,
                    feed,
                };
                self.straight(kind, Target::Program(to), w, cmd)
            }
        }
    }

    /// G73 second block: the profile d times, shifted.
    fn pattern_repeat(
        &mut self,
        profile: &Profile,
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        let a = self.here_xz(axes);
        let feed = self.feed(cmd)?;
        let P2(du, dw) = self.allowance(w);
        let mrc = self.state.lathe.mrc;
        let d = mrc.divisions;
        if d == 0 {
            return Err(alarms::zero_amount(
                cmd,
                "the number of passes (the first block's R)",
            ));
        }
        if f64::from(d) * (profile.elems.len() as f64 + 1.0) > rough::MAX_MOVES as f64 {
            return Err(alarms::too_many_cycle_moves(cmd));
        }
        let approach_how = |e: &Elem| if e.rapid { How::Rapid } else { How::Cut(feed) };
        for j in 1..=d {
            let k = if d > 1 {
                f64::from(d - j) / f64::from(d - 1)
            } else {
                0.0
            };
            let shift = P2(mrc.relief_x_mm * k + du, mrc.relief_z_mm * k + dw);
            for (n, e) in profile.elems.iter().enumerate() {
                let seg = e.seg.shifted(shift);
                if n == 0 {
                    self.cycle_moves(&[(approach_how(e), seg.end())], axes, w, cmd)?;
                } else if e.rapid {
                    self.cycle_moves(&[(How::Rapid, seg.end())], axes, w, cmd)?;
                } else {
                    self.along(&seg, axes, feed, w, cmd)?;
                }
            }
            self.return_to(a, axes, w, cmd)?;
        }
        Ok(())
    }

    /// The G00 back to the cycle's start point.
    fn return_to(
        &mut self,
        a: Xz,
        axes: (usize, usize),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let to: Pos = a.placed(self.state.prog, axes);
        if to == self.state.prog {
            return Ok(());
        }
        self.straight(MoveKind::Rapid, Target::Program(to), w, cmd)
    }

    /// G70 D E P: `passes` passes along the profile offset from D to E.
    fn ngc_offset_finish(
        &mut self,
        profile: &Profile,
        a: Xz,
        (d, e, passes): (f64, f64, u32),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let axes = self.lathe_axes(cmd)?;
        let Some((first, rest)) = profile.elems.split_first() else {
            return Err(self.profile_alarm(profile, 0, "the profile has no moves"));
        };
        let segs: Vec<Seg> = rest.iter().map(|e| e.seg).collect();
        let cuts = Path::new(a, first.seg.end(), &segs)
            .finish(d, e, passes)
            .map_err(|f| self.ngc_fault(f, profile, cmd))?;
        if cuts.len() > rough::MAX_MOVES {
            return Err(alarms::too_many_cycle_moves(cmd));
        }
        self.return_to(a, axes, w, cmd)?;
        self.ngc_cuts(&cuts, axes, w, cmd)
    }

    /// rs274 runs G70–G72 only in the XZ plane ("G71.0 can only be used
    /// in XZ plane (G18)").
    fn ngc_cycle_plane(&self, cmd: Span, code: &str) -> Result<(), Diagnostic> {
        if self.state.modal.plane == vcnc_core::events::Plane::Zx {
            return Ok(());
        }
        Err(alarms::ngc_cycle_mode(cmd, code, "G18 (the XZ plane)"))
    }

    /// rs274 refuses G71/G72 under cutter compensation; under G91 its
    /// 2.9.0 reads the block's X Z as absolute and the profile as
    /// increments, which vcnc refuses rather than copies.
    fn ngc_cycle_modes(&self, cmd: Span, code: &str) -> Result<(), Diagnostic> {
        if self.state.modal.incremental {
            return Err(alarms::ngc_cycle_mode(
                cmd,
                code,
                "G90 (absolute distances)",
            ));
        }
        if self.state.modal.comp != crate::state::CompSide::Off {
            return Err(alarms::ngc_cycle_mode(
                cmd,
                code,
                "G40 (no cutter compensation)",
            ));
        }
        Ok(())
    }

    /// A fault of `ngc_rough.rs` as an alarm.
    fn ngc_fault(&mut self, f: Fault, profile: &Profile, cmd: Span) -> Diagnostic {
        match f {
            Fault::TooMany => alarms::too_many_cycle_moves(cmd),
            Fault::Profile(why) => self.profile_alarm(profile, 0, why),
            Fault::Element(k, why) => self.profile_alarm(profile, k, why),
        }
    }

    /// The moves of LinuxCNC's G70–G72 at the cycle block's feed; the
    /// modal motion becomes the last one's.
    fn ngc_cuts(
        &mut self,
        cuts: &[Cut],
        axes: (usize, usize),
        w: &Words<'_>,
        cmd: Span,
    ) -> Result<(), Diagnostic> {
        let mut last = None;
        for cut in cuts {
            last = Some(match *cut {
                Cut::Rapid(p) => {
                    self.cycle_moves(&[(How::Rapid, p)], axes, w, cmd)?;
                    MotionOp::Rapid
                }
                Cut::Feed(p) => {
                    let feed = self.feed(cmd)?;
                    self.cycle_moves(&[(How::Cut(feed), p)], axes, w, cmd)?;
                    MotionOp::Linear
                }
                Cut::Arc { to, centre, ccw_xz } => {
                    let feed = self.feed(cmd)?;
                    let seg = Seg::arc(self.here_xz(axes), to, centre, ccw_xz);
                    self.along(&seg, axes, feed, w, cmd)?;
                    if ccw_xz {
                        MotionOp::ArcCw
                    } else {
                        MotionOp::ArcCcw
                    }
                }
            });
        }
        if let Some(m) = last {
            self.state.modal.motion = m;
        }
        Ok(())
    }

    /// One profile element under G70.
    fn finish_elem(
        &mut self,
        e: &Elem,
        axes: (usize, usize),
        w: &Words<'_>,
    ) -> Result<(), Diagnostic> {
        if let Some(side) = e.comp {
            self.set_comp_side(side);
        }
        let here = self.here_xz(axes);
        let to = e.seg.end();
        let still = (to.0 - here.0).abs() < ZERO_MM && (to.1 - here.1).abs() < ZERO_MM;
        if still && !e.seg.is_arc() {
            return Ok(());
        }
        if e.rapid {
            let to: Pos = to.placed(self.state.prog, axes);
            self.straight(MoveKind::Rapid, Target::Program(to), w, e.span)
        } else {
            let feed = self.feed(e.span)?;
            self.along(&e.seg, axes, feed, w, e.span)
        }
    }
}
