//! The motion stage's own data, and how a block that alarms takes back
//! what it did to it.
//!
//! ```text
//!   block starts ─▶ Stage::begin        (mark the pending events; copy the
//!                                         compensation stage if engaged)
//!       plain G00/G01 ─▶ Stage::mark_move / mark_compensated_move
//!                        (the few state fields such a move changes before
//!                         its last check, instead of a copy of the state)
//!   block alarms ─▶ Stage::abandon      (events dropped, compensation back)
//!                   Stage::rollback_move / rollback_compensated_move
//! ```
//!
//! Every move leaves the interpreter through `Machining::commit` into
//! this stage: the compensation it holds, the events of the blocks not yet
//! handed to the sink, the move count and the spindle warning are its
//! own, and only it knows how to undo them.

use super::comp::{self, Comp};
use crate::state::{Motion, State};
use vcnc_core::events::{Event, Pos};
use vcnc_syntax::Line;

/// The stage's data.
pub(crate) struct Stage {
    /// Moves committed so far (a block compares it to know if it moved).
    pub moves: u64,
    /// The cutter compensation stage.
    pub comp: Comp,
    /// Its copy taken before a block while it is engaged (not before a
    /// plain move that undoes the stage by its `Mark`: the copy is then
    /// stale until the next block takes one).
    comp_saved: Comp,
    /// The source and line of the block being executed (for alarms about
    /// moves that compensation releases later).
    pub cur_line: Option<(usize, Line)>,
    /// Events of blocks that succeeded and not yet handed to the sink,
    /// then those of the block being executed (from the mark its start
    /// took; they are dropped if it alarms). Handed over once they reach
    /// `HAND_OVER` and when the run ends.
    pub pending: Vec<Event>,
    /// W104 was given and the spindle has not turned since (or it turns:
    /// no check needed until it stops).
    pub spindle_warned: bool,
    /// W108 was given for these registers (bit n: register n, 63 and up
    /// share bit 63): radius registers, then length registers.
    pub zero_offsets_warned: [u64; 2],
    /// Bit i: no program-coordinate move has named axis i since power-on
    /// or since a move to a machine point (`placed` events, under
    /// `Interpreter::with_program_markers`).
    pub unplaced: u8,
    /// A G06.2 curve whose definition is still being read: one `nurbs`
    /// event once its last block is in.
    pub nurbs: Option<crate::state::NurbsBuild>,
}

/// Where a block started, to take it back.
#[derive(Clone, Copy)]
pub(crate) struct BlockMark {
    pending: usize,
    comp_engaged: bool,
    /// The block undoes the compensation stage by itself (a plain move
    /// behind a held one: [`CompensatedMoveMark`]).
    comp_by_move: bool,
}

/// What a plain G00/G01 block that `Stage::moves_in_place` accepts
/// may have changed in the state when it alarms: every check of such a
/// block (a negative or zero feed, a per-revolution feed with the spindle
/// stopped, G93's F, the travel limits) comes before the move changes the
/// positions and reports the frame, so only the modal motion, F, the
/// smoothing's bookkeeping and the last polar point can have changed
/// before them. Keeping these spares the block the copy of the whole state
/// (~1 KB, the largest single cost of a plain move).
#[derive(Clone, Copy)]
pub(crate) struct MoveMark {
    motion: Motion,
    feed: f64,
    smoothing: crate::state::Smoothing,
    polar: (f64, f64),
}

/// What a plain G00/G01 under compensation may change before its last
/// check, beyond [`MoveMark`]'s fields: the compensation stage hands the
/// held move on and releases it (moving the tool) before the corner after
/// it, or the travel limits, can alarm; the programmed point and the frame
/// report move first. The compensation stage itself is undone by its
/// [`comp::Mark`].
#[derive(Clone, Copy)]
pub(crate) struct CompensatedMoveMark {
    plain: MoveMark,
    pos: Pos,
    prog: Pos,
    nominal: Pos,
    detached: bool,
    frame_dirty: bool,
    reported: u64,
    comp: comp::Mark,
}

impl Stage {
    /// The stage at power-on, on a machine of `axes` axes.
    pub fn new(axes: usize) -> Stage {
        Stage {
            moves: 0,
            comp: Comp::default(),
            comp_saved: Comp::default(),
            cur_line: None,
            pending: Vec::new(),
            spindle_warned: false,
            zero_offsets_warned: [0; 2],
            unplaced: u8::try_from((1u32 << axes.min(8)) - 1).unwrap_or(u8::MAX),
            nurbs: None,
        }
    }

    /// A block starts: marks its events, and copies the compensation stage
    /// if it is engaged, unless the block undoes it by itself
    /// (`comp_by_move`).
    #[inline(always)]
    pub fn begin(&mut self, comp_by_move: bool) -> BlockMark {
        let comp_engaged = self.comp.engaged();
        if comp_engaged && !comp_by_move {
            self.comp_saved.clone_from(&self.comp);
        }
        BlockMark {
            pending: self.pending.len(),
            comp_engaged,
            comp_by_move,
        }
    }

    /// The block alarmed: its events are dropped and the compensation
    /// stage is as the block found it.
    #[cold]
    pub fn abandon(&mut self, mark: BlockMark) {
        self.pending.truncate(mark.pending);
        if mark.comp_by_move {
            // A plain move under compensation undid the stage itself.
            return;
        }
        if mark.comp_engaged {
            std::mem::swap(&mut self.comp, &mut self.comp_saved);
        } else {
            self.comp = Comp::default();
        }
    }

    /// The events the block made so far (from its mark).
    pub fn made_since(&self, mark: BlockMark) -> usize {
        self.pending.len() - mark.pending
    }

    /// Marks a plain move.
    #[inline]
    pub fn mark_move(s: &State) -> MoveMark {
        MoveMark {
            motion: s.modal.motion,
            feed: s.feed,
            smoothing: s.smoothing,
            polar: s.polar,
        }
    }

    /// Takes a plain move back.
    #[cold]
    pub fn rollback_move(mark: MoveMark, s: &mut State) {
        s.modal.motion = mark.motion;
        s.feed = mark.feed;
        s.smoothing = mark.smoothing;
        s.polar = mark.polar;
    }

    /// Marks a plain move under compensation.
    #[inline]
    pub fn mark_compensated_move(&mut self, s: &State) -> CompensatedMoveMark {
        CompensatedMoveMark {
            plain: Stage::mark_move(s),
            pos: s.pos,
            prog: s.prog,
            nominal: s.nominal,
            detached: s.detached,
            frame_dirty: s.frame_dirty,
            reported: s.reported,
            comp: self.comp.mark(),
        }
    }

    /// Takes a plain move under compensation back.
    #[cold]
    pub fn rollback_compensated_move(&mut self, mark: CompensatedMoveMark, s: &mut State) {
        Stage::rollback_move(mark.plain, s);
        s.pos = mark.pos;
        s.prog = mark.prog;
        s.nominal = mark.nominal;
        s.detached = mark.detached;
        s.frame_dirty = mark.frame_dirty;
        s.reported = mark.reported;
        self.comp.restore(mark.comp);
    }
}
