//! Reading the finishing profile of G70–G73: the blocks from `N P` to
//! `N Q` of the current program, read once per cycle straight from the
//! program text (they are not executed), turned into line and arc
//! elements in program coordinates and checked as they are read.
//!
//! ```text
//!   G71 P10 Q50 …      ─▶ find N10 (the label cache) ─▶ lex each block
//!   N10 G00 X20.          └ G00/G01/G02/G03, X/Z/U/W, I/K or R, ,C/,R,
//!   …                       G40/G41/G42 (applied by G70 only)
//!   …                     └ F S T, M codes, G04, G96/G97, G98/G99: kept
//!   …                       as the block's words, run by G70 only
//!   …                     └ anything else: E344 at the word
//!   N50 X60.           ─▶ elements A→A', …, →B; the cursor after N50
//! ```
//!
//! Fanuc 0i-TF forbids in a profile one-shot G codes other than G04,
//! group-01 codes other than G00–G03, G20/G21 and M98/M99; F, S and T
//! there are ignored by G71–G73 and valid in G70. So a block that carries
//! more than its move keeps its words (an [`Aside`]); the roughing reads
//! only the elements, and G70 runs a block's asides before its element,
//! in program order, as the ordinary steps of a block would
//! (`execute.rs`: modes, F, S, T, spindle, coolant, builder M codes, G04).
//! Program stops, ends and calls (M00, M01, M02, M30, M97, M98, M99) stay
//! E344: vcnc does not run a program's flow from inside a cycle.
//!
//! The first block must move with G00 or G01 (it is the approach from the
//! cycle's start point A); a `,C`/`,R` is resolved between two lines as
//! in a program (`corner.rs`); the profile ends at the block numbered Q,
//! and a program that ends first is E345. At most [`MAX_BLOCKS`] blocks.
//! Alarms point at the profile block's line and column.

use crate::alarms;
use crate::codes::corner::corner_cut;
use crate::dialect::{CompOp, ModeOp, MotionOp, PaceOp};
use crate::dialect::{GOp, MGroup, bit};
use crate::flow::first_value;
use crate::interpreter::Interpreter;
use crate::interpreter::Machining;
use crate::plane::{P2, RadiusFault, Seg, Xz, ZERO_MM, centre_from_radius};
use crate::state::CompSide;
use crate::state::lathe::CornerKind;
use crate::words::Words;
use crate::words::whole;
use vcnc_syntax::{Addr, Block, Cursor, Diagnostic, Line, Span, Word, lex_block};

/// Most blocks a profile may have.
pub(crate) const MAX_BLOCKS: usize = 1000;

/// One element of a profile and where it was written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Elem {
    pub seg: Seg,
    /// G00 (only the first element may be one that matters to G71–G73).
    pub rapid: bool,
    /// The asides G70 runs before this element (a range of
    /// [`Profile::asides`]): its block's and those of the blocks without
    /// a move since the last element.
    pub asides: (u32, u32),
    /// G40/G41/G42 written in its block or since the last element, for
    /// G70 (the rough cycles run without compensation).
    pub comp: Option<CompSide>,
    /// Its block: the line and the span of its motion word (else its
    /// first word), for alarms and for G70's events.
    pub line: Line,
    pub span: Span,
}

/// The words of a profile block beyond its move (F, S, T, M codes, G04,
/// G96/G97, G98/G99): the block itself, which G70 runs through the
/// ordinary steps of a block, and its line.
#[derive(Debug, Clone)]
pub(crate) struct Aside {
    pub block: Block,
    pub line: Line,
}

/// A profile read from the program.
#[derive(Debug, Clone)]
pub(crate) struct Profile {
    /// The elements, the first one the approach from A.
    pub elems: Vec<Elem>,
    /// The blocks with words beyond their move, in program order.
    pub asides: Vec<Aside>,
    /// The asides of blocks after the last element (`N50 M09`).
    pub asides_after: (u32, u32),
    /// Which axes the first block names: (X or U, Z or W).
    pub first_names: (bool, bool),
    /// The source the profile is in (for alarms about its blocks).
    pub src: usize,
    /// Where the program goes on after a cycle whose profile follows it.
    pub after: Cursor,
    /// Whether the profile follows the cycle block in the program.
    pub follows: bool,
    /// A G40/G41/G42 in blocks after the last element (`N50 G40`).
    pub comp_after: Option<CompSide>,
}

/// What reading a profile keeps from block to block.
struct Reading {
    profile: Profile,
    /// Where the profile is so far (X radius, Z).
    at: Xz,
    /// The modal motion within the profile.
    motion: Option<GOp>,
    /// The first aside not yet given to an element.
    asides_from: u32,
    /// G40/G41/G42 written since the last element.
    carry_comp: Option<CompSide>,
    /// A `,C`/`,R` waiting for the next element, its word and line.
    pending: Option<(CornerKind, Span, Line)>,
    /// Blocks read.
    blocks: usize,
    /// Letters a block may carry that the profile ignores: a LinuxCNC
    /// subroutine's rotary axis words (rs274's G70–G72 read only X, Z, I,
    /// K and R of its blocks; LinuxCNC's own demo `lathe_g70_71_demo.ngc`
    /// writes `G1 X10 A0.2` there).
    ignored: u32,
}

/// What a profile block says, after validation.
struct Move {
    motion: Option<GOp>,
    to: Xz,
    named: (bool, bool),
    arc: Option<ArcWords>,
    /// The block has words G70 runs beyond its move (an [`Aside`]).
    aside: bool,
    comp: Option<CompSide>,
    corner: Option<(CornerKind, Span)>,
    span: Span,
}

/// Where a profile ends: at the block numbered Q (Fanuc), or before the
/// line at this offset (LinuxCNC's `endsub`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ProfileEnd {
    Sequence(u32),
    Before(u64),
}

/// An arc's centre words.
#[derive(Clone, Copy)]
enum ArcWords {
    Offsets(f64, f64),
    Radius(f64, Span),
}

impl Interpreter<'_> {
    /// Reads the profile `N p` … `N q` for the cycle block whose next
    /// block starts at `next`.
    pub(crate) fn read_profile(
        &mut self,
        p: Word,
        q: Word,
        next: Cursor,
    ) -> Result<Profile, Diagnostic> {
        let ns = whole(
            &p,
            b'P',
            0.0,
            99_999_999.0,
            "P is the profile's first sequence number",
        )?;
        let nf = whole(
            &q,
            b'Q',
            0.0,
            99_999_999.0,
            "Q is the profile's last sequence number",
        )?;
        let frame = self.flow.frame();
        let (src, lex) = (frame.source, self.cfg.dialect.lex);
        let start = self
            .flow
            .find_sequence(src, frame.program, ns, &lex)
            .ok_or_else(|| alarms::sequence_not_found(p.span, ns))?;
        // The last block must exist after the first: checked before any
        // block is read, so that a missing Q is said as such.
        let end = self.flow.find_sequence(src, frame.program, nf, &lex);
        if end.is_none_or(|e| (e.offset, e.col) < (start.offset, start.col)) {
            return Err(alarms::profile_end_missing(q.span, nf));
        }
        // Only a profile right after the cycle block is skipped by it; one
        // after M30 or before the cycle leaves the program to go on after
        // the cycle block.
        let follows = self.flow.first_block_from(src, next, &lex) == Some(start);
        self.read_profile_blocks(src, start, follows, ProfileEnd::Sequence(nf), q.span)
    }

    /// LinuxCNC's G70–G72 profile: the body of subroutine `o<label>` of
    /// source `src`, from `start` (the line after its `sub`) up to the
    /// line at `endsub` (its `endsub`), read as the blocks of a Fanuc
    /// profile are.
    pub(crate) fn read_sub_profile(
        &mut self,
        src: usize,
        start: Cursor,
        endsub: u64,
        q: Span,
    ) -> Result<Profile, Diagnostic> {
        self.read_profile_blocks(src, start, false, ProfileEnd::Before(endsub), q)
    }

    /// The profile's blocks from `start` to its end.
    fn read_profile_blocks(
        &mut self,
        src: usize,
        start: Cursor,
        follows: bool,
        end: ProfileEnd,
        q_span: Span,
    ) -> Result<Profile, Diagnostic> {
        let lex = self.cfg.dialect.lex;
        let nf = match end {
            ProfileEnd::Sequence(n) => n,
            ProfileEnd::Before(_) => 0,
        };
        let q = Word {
            addr: Addr::letter(b'Q'),
            value: f64::from(nf),
            point: false,
            span: q_span,
        };
        let axes = self.machining().lathe_axes(q_span)?;
        let mut r = Reading {
            profile: Profile {
                elems: Vec::new(),
                asides: Vec::new(),
                asides_after: (0, 0),
                first_names: (false, false),
                src,
                after: start,
                follows,
                comp_after: None,
            },
            at: self.machining().here_xz(axes),
            motion: None,
            asides_from: 0,
            carry_comp: None,
            pending: None,
            blocks: 0,
            ignored: match end {
                ProfileEnd::Before(_) => bit(b'A') | bit(b'B') | bit(b'C'),
                ProfileEnd::Sequence(_) => 0,
            },
        };
        let mut block = Block::default();
        if let Some(s) = self.flow.source(src) {
            s.reader.seek(Cursor { col: 0, ..start });
        }
        let mut col = start.col as usize;
        loop {
            let Some((line, bytes)) = self.profile_line(src) else {
                return Err(alarms::profile_end_missing(q.span, nf));
            };
            if end == ProfileEnd::Before(line.offset) {
                // The subroutine's `endsub`: the profile ends before it.
                if let Some((_, word, held_at)) = r.pending {
                    let d = alarms::corner_fault(word, "the profile ends at this corner");
                    return Err(self.locate(d, src, &held_at));
                }
                if r.profile.elems.is_empty() {
                    return Err(alarms::profile_end_missing(q.span, nf));
                }
                r.profile.comp_after = r.carry_comp;
                r.profile.asides_after = (r.asides_from, aside_count(&r.profile));
                r.profile.after = Cursor {
                    offset: line.offset,
                    line: line.number,
                    col: 0,
                };
                return Ok(r.profile);
            }
            let mut i = std::mem::take(&mut col);
            while i < bytes.len() {
                let lexed = lex_block(&bytes, i, &lex, &mut block);
                i = match lexed {
                    Ok(next) => Ok(next),
                    Err(d) => self.profile_macro_block(&bytes, i, d, &mut block),
                }
                .map_err(|d| self.locate(d, src, &line))?;
                if block.is_empty() || (block.deleted.is_some() && self.cfg.opts.block_delete) {
                    continue;
                }
                if block.percent || first_value(&block, b'O').is_some() {
                    return Err(alarms::profile_end_missing(q.span, nf));
                }
                r.blocks += 1;
                if r.blocks > MAX_BLOCKS {
                    return Err(alarms::profile_too_long(q.span, MAX_BLOCKS));
                }
                self.machining().profile_take(&mut r, &block, line, axes)?;
                let last = matches!(end, ProfileEnd::Sequence(_))
                    && block.words().iter().any(|w| {
                        w.addr == Addr::letter(b'N') && !w.point && w.value == f64::from(nf)
                    });
                if last {
                    if let Some((_, word, held_at)) = r.pending {
                        let d = alarms::corner_fault(word, "the profile ends at this corner");
                        return Err(self.locate(d, src, &held_at));
                    }
                    r.profile.comp_after = r.carry_comp;
                    r.profile.asides_after = (r.asides_from, aside_count(&r.profile));
                    r.profile.after = Cursor {
                        offset: line.offset,
                        line: line.number,
                        col: vcnc_syntax::clamp_u32(i),
                    };
                    return Ok(r.profile);
                }
            }
        }
    }

    /// The next line of source `src`, copied (the reader is shared).
    fn profile_line(&mut self, src: usize) -> Option<(Line, Vec<u8>)> {
        let source = self.flow.source(src)?;
        loop {
            match source.reader.next_line() {
                Ok(Some(line)) => return Some((line, source.reader.bytes(&line).to_vec())),
                Ok(None) | Err(vcnc_syntax::ReadError::Io(_)) => return None,
                Err(vcnc_syntax::ReadError::TooLong { .. }) => {}
            }
        }
    }
}

/// The number of asides so far, as the ranges of [`Elem::asides`] count
/// them (at most [`MAX_BLOCKS`]).
fn aside_count(profile: &Profile) -> u32 {
    u32::try_from(profile.asides.len()).unwrap_or(u32::MAX)
}

impl<'a> Machining<'_, 'a> {
    /// One profile block: its element (with the asides since the last
    /// one), a chamfer or round the block before asked for, and the corner
    /// this block asks for.
    fn profile_take(
        &mut self,
        r: &mut Reading,
        block: &Block,
        line: Line,
        axes: (usize, usize),
    ) -> Result<(), Diagnostic> {
        let src = r.profile.src;
        let first = r.blocks == 1;
        let mv = self
            .profile_block(block, axes, (r.at, r.ignored), &mut r.motion, first)
            .map_err(|d| self.at.locate(d, src, &line))?;
        if first {
            r.profile.first_names = mv.named;
        }
        if mv.aside {
            r.profile.asides.push(Aside {
                block: block.clone(),
                line,
            });
        }
        r.carry_comp = mv.comp.or(r.carry_comp);
        let elem = self
            .profile_elem(&mv, r.at, line, first)
            .map_err(|d| self.at.locate(d, src, &line))?;
        if let Some(elem) = elem {
            let end = aside_count(&r.profile);
            let elem = Elem {
                asides: (r.asides_from, end),
                comp: r.carry_comp,
                ..elem
            };
            r.asides_from = end;
            r.carry_comp = None;
            match r.pending.take() {
                Some((kind, word, held_at)) => {
                    let prev = r.profile.elems.pop();
                    self.push_corner(&mut r.profile.elems, prev, elem, kind)
                        .map_err(|why| {
                            let d = alarms::corner_fault(word, why);
                            self.at.locate(d, src, &held_at)
                        })?;
                }
                None => r.profile.elems.push(elem),
            }
            r.at = elem.seg.end();
        }
        if let Some((kind, word)) = mv.corner {
            r.pending = Some((kind, word, line));
        }
        Ok(())
    }

    /// Validates one profile block and reads its words.
    fn profile_block(
        &self,
        block: &Block,
        (ix, iz): (usize, usize),
        (at, ignored): (Xz, u32),
        motion: &mut Option<GOp>,
        first: bool,
    ) -> Result<Move, Diagnostic> {
        let mut w = Words::new(block);
        w.fill(self.cfg.dialect, self.cfg.machine, self.cfg.axis_mask)?;
        let mut dwell = false;
        for code in w.once_codes() {
            if code.def.op != GOp::Pace(PaceOp::Dwell) {
                return Err(alarms::profile_word(
                    code.span,
                    "a one-shot G code other than G04",
                ));
            }
            dwell = true;
        }
        let mut span = w.first;
        let mut comp = None;
        let mut modes = false;
        for code in w.modal_codes() {
            match code.def.op {
                GOp::Motion(MotionOp::Rapid)
                | GOp::Motion(MotionOp::Linear)
                | GOp::Motion(MotionOp::ArcCw)
                | GOp::Motion(MotionOp::ArcCcw) => {
                    *motion = Some(code.def.op);
                    span = code.span;
                }
                GOp::Comp(CompOp::Cancel) => comp = Some(CompSide::Off),
                GOp::Comp(CompOp::Left | CompOp::LeftDiameter) => comp = Some(CompSide::Left),
                GOp::Comp(CompOp::Right | CompOp::RightDiameter) => comp = Some(CompSide::Right),
                GOp::Mode(ModeOp::SurfaceSpeed)
                | GOp::Mode(ModeOp::SpindleRpm)
                | GOp::Mode(ModeOp::PerMinute)
                | GOp::Mode(ModeOp::PerRev) => {
                    modes = true;
                }
                _ => return Err(alarms::profile_word(code.span, "this G code")),
            }
        }
        if let Some(m) = w.m_of(MGroup::Flow) {
            return Err(alarms::profile_word(
                m.span,
                "a program stop, end or call (M00, M01, M02, M30, M97, M98, M99)",
            ));
        }
        let m_codes =
            w.m.iter().flatten().next().is_some() || w.other_m.iter().flatten().next().is_some();
        let mut allowed = [
            b'N', b'X', b'Z', b'U', b'W', b'I', b'K', b'R', b'F', b'S', b'T',
        ]
        .iter()
        .fold(ignored, |m, l| m | bit(*l));
        if dwell {
            allowed |= bit(b'P');
        }
        if let Some(word) = block.words().iter().find(|wd| {
            wd.addr
                .as_letter()
                .is_some_and(|l| l != b'G' && l != b'M' && allowed & bit(l) == 0)
        }) {
            return Err(alarms::profile_word(
                word.span,
                &format!("the word {}", char::from(word.addr.0)),
            ));
        }
        let aside = dwell || modes || m_codes || w.any(bit(b'F') | bit(b'S') | bit(b'T'));
        for (abs, inc) in [(b'X', b'U'), (b'Z', b'W')] {
            if let (Some(_), Some(i)) = (w.get(abs), w.get(inc)) {
                return Err(alarms::absolute_and_incremental(i.span, abs, inc));
            }
        }
        let Some(op) = *motion else {
            return Err(alarms::profile_not_cut(
                w.first,
                "the profile's first block must move with G00 or G01",
            ));
        };
        if dwell {
            // G04's X/U/P are its time: the block does not move.
            if first {
                return Err(alarms::profile_not_cut(
                    span,
                    "the profile's first block must move with G00 or G01, not dwell",
                ));
            }
            let corner = w.get_ext(Addr::COMMA_C).or(w.get_ext(Addr::COMMA_R));
            if let Some(word) = corner {
                return Err(alarms::corner_fault(word.span, "only a G01 takes ,C or ,R"));
            }
            return Ok(Move {
                motion: Some(op),
                to: at,
                named: (false, false),
                arc: None,
                aside,
                comp,
                corner: None,
                span,
            });
        }
        let arc = matches!(
            op,
            GOp::Motion(MotionOp::ArcCw) | GOp::Motion(MotionOp::ArcCcw)
        );
        if arc && comp.is_some() {
            return Err(alarms::comp_arc_startup(span));
        }
        if first && arc {
            return Err(alarms::profile_not_cut(
                span,
                "the profile's first block must move with G00 or G01, not an arc",
            ));
        }
        let coord = |abs: u8, inc: u8, i: usize, from: f64| match (w.get(abs), w.get(inc)) {
            (Some(word), _) => (
                self.units().axis_value(&self.cfg.axis_words, i, &word),
                true,
            ),
            (None, Some(word)) => (
                from + self.units().axis_value(&self.cfg.axis_words, i, &word),
                true,
            ),
            (None, None) => (from, false),
        };
        let (x, nx) = coord(b'X', b'U', ix, at.0);
        let (z, nz) = coord(b'Z', b'W', iz, at.1);
        let arc_words = if arc {
            match (w.get(b'R'), w.get(b'I'), w.get(b'K')) {
                (Some(r), _, _) => Some(ArcWords::Radius(self.units().length_mm(&r), r.span)),
                // G90.1: I and K are the centre's program coordinates, as
                // for an arc outside a cycle (rs274 reads the profile so).
                (None, Some(i), Some(k)) if self.state.modal.arc_absolute => {
                    Some(ArcWords::Offsets(
                        self.units().length_mm(&i) - at.0,
                        self.units().length_mm(&k) - at.1,
                    ))
                }
                (None, _, _) if self.state.modal.arc_absolute => {
                    return Err(alarms::arc_without_center(span, "zx"));
                }
                (None, i, k) if i.is_some() || k.is_some() => Some(ArcWords::Offsets(
                    i.map_or(0.0, |i| self.units().length_mm(&i)),
                    k.map_or(0.0, |k| self.units().length_mm(&k)),
                )),
                _ => return Err(alarms::arc_without_center(span, "zx")),
            }
        } else {
            for l in [b'I', b'K', b'R'] {
                if let Some(word) = w.get(l) {
                    return Err(alarms::word_not_allowed(word.span, l));
                }
            }
            None
        };
        let corner = match (w.get_ext(Addr::COMMA_C), w.get_ext(Addr::COMMA_R)) {
            (Some(_), Some(r)) => return Err(alarms::corner_fault(r.span, "both ,C and ,R")),
            (Some(c), None) => Some((CornerKind::Chamfer(self.units().length_mm(&c)), c.span)),
            (None, Some(r)) => Some((CornerKind::Round(self.units().length_mm(&r)), r.span)),
            (None, None) => None,
        };
        if let Some((_, word)) = corner.filter(|_| op != GOp::Motion(MotionOp::Linear)) {
            return Err(alarms::corner_fault(word, "only a G01 takes ,C or ,R"));
        }
        Ok(Move {
            motion: Some(op),
            to: P2(x, z),
            named: (nx, nz),
            arc: arc_words,
            aside,
            comp,
            corner,
            span,
        })
    }

    /// The element a validated block moves along, if it moves (the first
    /// block always makes one: the approach).
    fn profile_elem(
        &self,
        mv: &Move,
        at: Xz,
        line: Line,
        first: bool,
    ) -> Result<Option<Elem>, Diagnostic> {
        let moved = (mv.to.0 - at.0).abs() > ZERO_MM || (mv.to.1 - at.1).abs() > ZERO_MM;
        if !moved && !first && mv.arc.is_none() {
            return Ok(None);
        }
        let arc = match (mv.motion, mv.arc) {
            (
                Some(op @ (GOp::Motion(MotionOp::ArcCw) | GOp::Motion(MotionOp::ArcCcw))),
                Some(words),
            ) => {
                let cw = op == GOp::Motion(MotionOp::ArcCw);
                // A G02 turns clockwise in G18's (Z, X), which is
                // counter-clockwise in the (X, Z) order the profile keeps.
                let ccw_xz = cw;
                Some((self.profile_center(at, mv.to, words, cw, mv.span)?, ccw_xz))
            }
            _ => None,
        };
        Ok(Some(Elem {
            seg: Seg::new(at, mv.to, arc),
            rapid: mv.motion == Some(GOp::Motion(MotionOp::Rapid)),
            asides: (0, 0),
            comp: None,
            line,
            span: mv.span,
        }))
    }

    /// The centre of a profile arc (X radius, Z), checked on the circle.
    fn profile_center(
        &self,
        s: Xz,
        e: Xz,
        words: ArcWords,
        cw: bool,
        span: Span,
    ) -> Result<Xz, Diagnostic> {
        let tol = self.cfg.machine.params.arc_tolerance_mm;
        let c = match words {
            ArcWords::Offsets(i, k) => s + P2(i, k),
            // In G18's (Z, X) order, where a G02 turns clockwise.
            ArcWords::Radius(r, rspan) => centre_from_radius(s.swapped(), e.swapped(), r, !cw, tol)
                .map_err(|f| match f {
                    RadiusFault::Zero => alarms::zero_radius(span),
                    RadiusFault::FullCircle => alarms::r_full_circle(rspan),
                    RadiusFault::TooSmall { chord } => {
                        alarms::radius_too_small(rspan, r.abs(), chord)
                    }
                })?
                .swapped(),
        };
        let (r0, r1) = ((s - c).hypot(), (e - c).hypot());
        if r0 < ZERO_MM {
            return Err(alarms::zero_radius(span));
        }
        if (r0 - r1).abs() > tol {
            return Err(alarms::end_off_circle(span, r0, r1));
        }
        if (s.0 - e.0).abs() < ZERO_MM && (s.1 - e.1).abs() < ZERO_MM {
            return Err(alarms::profile_not_cut(span, "a full circle"));
        }
        Ok(c)
    }

    /// Replaces `prev` (a line whose block asked for a corner) and pushes
    /// the chamfer or round and `next` (which must be a line).
    fn push_corner(
        &self,
        elems: &mut Vec<Elem>,
        prev: Option<Elem>,
        next: Elem,
        kind: CornerKind,
    ) -> Result<(), &'static str> {
        let Some(prev) = prev else {
            return Err("there is no move before the corner");
        };
        if next.seg.is_arc() || next.rapid || prev.rapid {
            return Err("the block after a ,C or ,R must be a G01 move");
        }
        // In G18's (Z, X) order, like a program's corner.
        let cut = corner_cut(
            prev.seg.start().swapped(),
            prev.seg.end().swapped(),
            next.seg.end().swapped(),
            kind,
        )?;
        let mut first = prev;
        first.seg = prev.seg.with_end(cut.p1.swapped());
        elems.push(first);
        elems.push(Elem {
            seg: Seg::new(cut.p1, cut.p2, cut.arc).swapped(),
            asides: (0, 0),
            ..prev
        });
        let mut second = next;
        second.seg = next.seg.with_start(cut.p2.swapped());
        elems.push(second);
        Ok(())
    }
}
