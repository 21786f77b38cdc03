//! Stage 2 of the motion stage: cutter radius compensation G40/G41/G42
//! (Syntec 1.2.18, Fanuc 0i type A), between the frame and the travel check.
//!
//! ```text
//!   G41 D1 … ──▶ Starting ──(first move in the plane: the start-up)──▶ On
//!   On:  a move in the plane is held until the next one is read; then the
//!        corner between them (geom::corner) settles where the held one ends
//!        and it leaves, followed by what queued behind it (moves without
//!        plane motion, at the tool's compensated position, and other events)
//!   G40 ──▶ Cancelling ──(next move in the plane, or the end of the block
//!        without one)──▶ Off
//! ```
//!
//! The compensation works on machine moves, after rotation, scaling and
//! mirror: the radius is not scaled, and one mirrored axis in the plane
//! swaps the side (manual 1.2.21). The queue is bounded: more than
//! `parameters.comp_lookahead_blocks` blocks without motion in the plane
//! alarm. A block that alarms restores the whole stage (the interpreter
//! copies it before each block while compensation is engaged, but for a
//! plain G00/G01 behind a held move, which undoes it by a `Mark`), so
//! moves still held when a later block alarms never reach the output.

pub(crate) mod geom;
pub(crate) mod nose;
mod pass;

use super::MachineMove;
use crate::plane::{P2, Seg};
use vcnc_core::events::{Event, Loc, Plane, Pos};
use vcnc_core::geometry::PlaneAxes;
use vcnc_syntax::{Line, Span};

/// Where the stage is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// No compensation.
    Off,
    /// G41/G42 given, waiting for the start-up move.
    Starting,
    /// Compensating.
    On,
    /// G40 given, waiting for the cancel move.
    Cancelling,
}

/// Where a held move comes from, to report it and its alarms.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Origin {
    pub loc: Loc,
    pub src: usize,
    pub line: Option<Line>,
    pub cmd: Span,
}

/// A move in the plane whose end is not settled yet.
#[derive(Debug, PartialEq)]
struct Held {
    mm: MachineMove,
    seg: Seg,
    /// Where its compensated path starts.
    start: P2,
    /// A joining move before it (a corner with α < 90°): to `l2`, then to
    /// `start` along its tangent.
    lead_in: Option<P2>,
    side: f64,
    r: f64,
    /// The start-up move (from the uncompensated point).
    startup: bool,
    /// From the nose centre to the controlled point: a lathe's imaginary
    /// tool tip (`nose.rs`); zero on a mill.
    shift: P2,
    /// The compensated arc's centre when it is not the programmed one (an
    /// entry arc, `CompStart::LineOrArc`): `seg` is then the arc about it
    /// whose offset the tool follows.
    centre: Option<P2>,
    at: Origin,
}

/// What waits behind the held move.
#[derive(Debug, Clone, PartialEq)]
enum Queued {
    /// A move without plane motion (its plane coordinates are set when it leaves).
    Move(MachineMove, Origin),
    Event(Event),
}

/// The compensation stage.
#[derive(Debug, PartialEq)]
pub(crate) struct Comp {
    pub mode: Mode,
    /// The plane compensation runs in (set by G41/G42).
    pub plane: Plane,
    /// Boxed, so that a block hands the held move on by swapping pointers
    /// instead of moving ~360 bytes twice.
    held: Option<Box<Held>>,
    queue: Vec<Queued>,
    /// Blocks without motion in the plane since the held move.
    idle_blocks: u32,
    /// Whether the current block put a move in the plane.
    moved_in_plane: bool,
    /// A held move is leaving: its events go out at once.
    releasing: bool,
    /// The move the current block replaced (see [`Mark`]).
    scratch: Scratch,
}

/// Storage, not state: the held move the current block replaced, kept so
/// that an alarm can put it back without a copy of the stage, and reused
/// as the box of the next held move. Equal to any other, cloned empty.
#[derive(Debug, Default)]
struct Scratch {
    prev: Option<Box<Held>>,
    /// Whether `prev` is the move held when the current block began.
    replaced: bool,
}

impl PartialEq for Scratch {
    fn eq(&self, _: &Scratch) -> bool {
        true
    }
}

/// What a plain move block needs to undo the stage when it alarms, taken by
/// [`Comp::mark`] where [`Comp::can_mark`] allows: such a block changes the
/// stage only by replacing the held move (kept in [`Scratch`]), queueing
/// behind it (the queue was empty) and through these fields.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mark {
    mode: Mode,
    plane: Plane,
    idle_blocks: u32,
    moved_in_plane: bool,
    releasing: bool,
}

// `Held` and `Comp` spell out `clone_from`: the interpreter saves the stage
// before a block while compensation is engaged (an alarm puts it back; a
// plain move behind a held one uses a `Mark` instead),
// and the derived `clone_from` builds a whole new value, then drops the old
// one. These assign in place and keep the queue's buffer; they name every
// field, so a new field fails to compile until it is copied here too.
impl Clone for Held {
    fn clone(&self) -> Held {
        Held {
            at: self.at.clone(),
            ..*self
        }
    }

    fn clone_from(&mut self, src: &Held) {
        let Held {
            mm,
            seg,
            start,
            lead_in,
            side,
            r,
            startup,
            shift,
            centre,
            at,
        } = src;
        self.mm = *mm;
        self.seg = *seg;
        self.start = *start;
        self.lead_in = *lead_in;
        self.side = *side;
        self.r = *r;
        self.startup = *startup;
        self.shift = *shift;
        self.centre = *centre;
        self.at.clone_from(at);
    }
}

impl Clone for Comp {
    fn clone(&self) -> Comp {
        Comp {
            mode: self.mode,
            plane: self.plane,
            held: self.held.clone(),
            queue: self.queue.clone(),
            idle_blocks: self.idle_blocks,
            moved_in_plane: self.moved_in_plane,
            releasing: self.releasing,
            scratch: Scratch::default(),
        }
    }

    fn clone_from(&mut self, src: &Comp) {
        let Comp {
            mode,
            plane,
            held,
            queue,
            idle_blocks,
            moved_in_plane,
            releasing,
            scratch: _,
        } = src;
        self.mode = *mode;
        self.plane = *plane;
        self.held.clone_from(held);
        self.queue.clone_from(queue);
        self.idle_blocks = *idle_blocks;
        self.moved_in_plane = *moved_in_plane;
        self.releasing = *releasing;
    }
}

impl Default for Comp {
    fn default() -> Comp {
        Comp {
            mode: Mode::Off,
            plane: Plane::Xy,
            held: None,
            queue: Vec::new(),
            idle_blocks: 0,
            moved_in_plane: false,
            releasing: false,
            scratch: Scratch::default(),
        }
    }
}

impl Comp {
    /// Whether moves go through this stage.
    #[inline]
    pub fn engaged(&self) -> bool {
        self.mode != Mode::Off
    }

    /// Whether events must wait behind a held move.
    #[inline]
    pub fn holding(&self) -> bool {
        self.held.is_some() && !self.releasing
    }

    /// Whether a plain move block may [`mark`](Self::mark) the stage
    /// instead of copying it: compensating, a move held and nothing queued.
    #[inline]
    pub fn can_mark(&self) -> bool {
        self.mode == Mode::On && self.held.is_some() && self.queue.is_empty()
    }

    /// Begins a block that [`restore`](Self::restore) can undo.
    #[inline]
    pub fn mark(&mut self) -> Mark {
        self.scratch.replaced = false;
        Mark {
            mode: self.mode,
            plane: self.plane,
            idle_blocks: self.idle_blocks,
            moved_in_plane: self.moved_in_plane,
            releasing: self.releasing,
        }
    }

    /// Puts the stage back as it was at [`mark`](Self::mark).
    #[cold]
    pub fn restore(&mut self, m: Mark) {
        if self.scratch.replaced {
            std::mem::swap(&mut self.held, &mut self.scratch.prev);
            self.scratch.replaced = false;
        }
        self.queue.clear();
        self.mode = m.mode;
        self.plane = m.plane;
        self.idle_blocks = m.idle_blocks;
        self.moved_in_plane = m.moved_in_plane;
        self.releasing = m.releasing;
    }

    /// Queues an event behind the held move.
    pub fn queue_event(&mut self, e: Event) {
        self.queue.push(Queued::Event(e));
    }
}

fn v2(p: Pos, axes: PlaneAxes) -> P2 {
    P2::of(&p, (axes.a, axes.b))
}

fn with_plane(p: Pos, axes: PlaneAxes, q: P2) -> Pos {
    q.placed(p, (axes.a, axes.b))
}
