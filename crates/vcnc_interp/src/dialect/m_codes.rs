//! The M-code rows, built once: the families of M codes that the
//! controllers share, which each dialect's table assembles and extends with
//! its own rows (Haas's M97, Syntec's M198, LinuxCNC's M60 …).
//!
//! An M code's group follows from its operation ([`MOp::group`]), so a row
//! names only the number, the operation and the letters it reads.

use super::{MGroup, MOp, bit};

/// One M-code row of a dialect table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct MRow {
    pub code: u16,
    pub op: MOp,
    pub letters: u32,
}

/// A row: M `code` is `op` and reads no letters.
pub(crate) const fn m(code: u16, op: MOp) -> MRow {
    MRow {
        code,
        op,
        letters: 0,
    }
}

impl MRow {
    /// Also reads the letters of `mask`.
    pub(crate) const fn reads(mut self, mask: u32) -> MRow {
        self.letters |= mask;
        self
    }
}

/// M00, M01, M02, M30: program stop, optional stop, end, end and rewind.
pub(crate) const PROGRAM_END: &[MRow] = &[
    m(0, MOp::Stop),
    m(1, MOp::OptionalStop),
    m(2, MOp::End),
    m(30, MOp::EndRewind),
];

/// M03, M04, M05: the spindle.
pub(crate) const SPINDLE: &[MRow] = &[
    m(3, MOp::SpindleCw),
    m(4, MOp::SpindleCcw),
    m(5, MOp::SpindleStop),
];

/// M19: spindle orientation (Syntec's M-code table, Fanuc).
pub(crate) const ORIENT: &[MRow] = &[m(19, MOp::SpindleOrient)];

/// M06: the tool change.
pub(crate) const TOOL_CHANGE: &[MRow] = &[m(6, MOp::ToolChange)];

/// M08, M09: flood coolant on, coolant off.
pub(crate) const COOLANT: &[MRow] = &[m(8, MOp::CoolantOn), m(9, MOp::CoolantOff)];

/// M07: mist coolant (grbl, LinuxCNC).
pub(crate) const MIST: &[MRow] = &[m(7, MOp::CoolantOn)];

/// M98 P (H start sequence, L repeats) and M99 (P return sequence).
pub(crate) const SUBPROGRAMS: &[MRow] = &[
    m(98, MOp::Call).reads(bit(b'P') | bit(b'H') | bit(b'L')),
    m(99, MOp::Return).reads(bit(b'P')),
];

/// The Syntec 900M / Fanuc 0i mill's M-code table (Syntec manual chapter
/// 2), also the seed lathe's and EIA's.
pub(crate) const MILL: &[&[MRow]] = &[
    PROGRAM_END,
    SPINDLE,
    TOOL_CHANGE,
    COOLANT,
    ORIENT,
    SUBPROGRAMS,
];

/// grbl 1.1's M codes: no subprograms, M07 mist coolant.
/// Fanuc's and Haas's M29 (rigid tapping mode, `M29 S…` before G84).
pub(crate) const RIGID_TAP: &[MRow] = &[m(29, MOp::RigidTap)];

pub(crate) const GRBL: &[&[MRow]] = &[PROGRAM_END, SPINDLE, TOOL_CHANGE, MIST, COOLANT];

impl MOp {
    /// The group of the operation: two codes of one group in a block
    /// alarm (E206).
    pub fn group(self) -> MGroup {
        match self {
            MOp::Stop
            | MOp::OptionalStop
            | MOp::End
            | MOp::EndRewind
            | MOp::Call
            | MOp::Return
            | MOp::LocalCall => MGroup::Flow,
            MOp::SpindleCw
            | MOp::SpindleCcw
            | MOp::SpindleStop
            | MOp::SpindleOrient
            | MOp::RigidTap => MGroup::Spindle,
            MOp::CoolantOn | MOp::CoolantOff => MGroup::Coolant,
            MOp::ToolChange => MGroup::Tool,
        }
    }

    /// What the code does, in a sentence (`vcnc explain`, hover, E201).
    pub fn meaning(self) -> &'static str {
        match self {
            MOp::Stop => "program stop: the program waits for cycle start",
            MOp::OptionalStop => "optional stop: a program stop when the operator's switch is on",
            MOp::End => "end of program",
            MOp::EndRewind => "end of program and rewind",
            MOp::SpindleCw => "spindle on clockwise at S",
            MOp::SpindleCcw => "spindle on counterclockwise at S",
            MOp::SpindleStop => "spindle stop",
            MOp::SpindleOrient => "spindle orientation: the spindle stops at its oriented angle",
            MOp::ToolChange => "tool change: the tool selected by T goes into the spindle",
            MOp::CoolantOn => "coolant on",
            MOp::CoolantOff => "coolant off",
            MOp::Call => "subprogram call: program P, L times",
            MOp::Return => "end of subprogram: return to the caller (or to sequence P)",
            MOp::LocalCall => {
                "local subprogram call: the blocks from sequence P of this program, L times"
            }
            MOp::RigidTap => {
                "rigid tapping: the next G84/G74 taps at S with the spindle synchronized to the axis, no M03 needed (G80 ends it)"
            }
        }
    }
}
