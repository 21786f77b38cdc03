//! Mach3 (ArtSoft/Newfangled, "Using Mach3Mill"), the hobby control that
//! many Vectric, Fusion, SheetCam and pcb2gcode posts write for: RS274/NGC
//! as LinuxCNC reads it (whole-unit integers, `#` parameters and `[ ]`
//! expressions, G90.1/G91.1, G28 through the point named, G52, the canned
//! cycles with L repeats), with Mach3's own program structure:
//!
//! ```text
//!   M98 P1 L6      call the subprogram O1 of this file (or of the
//!   ...             program store) six times
//!   M30
//!   O1 (probe)     the label an M98 P names: an O number, not LinuxCNC's
//!   ...             `o1 sub … o1 endsub`
//!   M99            back after the M98
//!   M40  M1000     an M code Mach3 does not define runs the user macro
//!                   M40.m1s: an `aux` event with its P, Q, R
//! ```
//!
//! LinuxCNC's O-word flow (`o100 sub`, `o101 while`) is not Mach3's (its
//! manual has none): E604 says so. Decisions and sources are in
//! `docs/dialects.md` ("The mach3 dialect").

use super::grbl::GRBL_G;
use super::linuxcnc::{LINUXCNC_G, linuxcnc};
use super::m_codes::{self, MRow};
use super::{
    AuxM, CircleCutForm, CycleOp, Dialect, GOp, GRow, Group, MOp, MacroRules, MoveOp, bit, g,
};
use vcnc_core::events::ArcDir;

/// Mach3's codes beyond LinuxCNC's: G31, its straight probe, moves towards
/// the point named and stops where the probe touches (Fanuc's skip: without
/// a probe signal the whole move).
/// G12/G13 (manual, "Clockwise/counterclockwise circular pocket"): a
/// circle of radius I about where the tool stands (`codes/circle_cut.rs`).
const MACH3_G: &[GRow] = &[
    g(310, GOp::Move(MoveOp::Skip), Group::NonModal).claims_axes(),
    g(
        120,
        GOp::Cycle(CycleOp::CircleCut(ArcDir::Cw, CircleCutForm::StraightInOut)),
        Group::NonModal,
    )
    .reads(bit(b'I'))
    .claims_axes(),
    g(
        130,
        GOp::Cycle(CycleOp::CircleCut(
            ArcDir::Ccw,
            CircleCutForm::StraightInOut,
        )),
        Group::NonModal,
    )
    .reads(bit(b'I'))
    .claims_axes(),
];

/// Mach3's built-in M codes: program stops and ends, spindle, tool change,
/// coolant, M98/M99 subprograms; the rest are macros (below).
const MACH3_M: &[&[MRow]] = &[
    m_codes::PROGRAM_END,
    m_codes::SPINDLE,
    m_codes::TOOL_CHANGE,
    m_codes::MIST,
    m_codes::COOLANT,
    MACH3_CALLS,
];

/// M98 P (the O number) L (repeats) and M99: Mach3's calls read no H.
const MACH3_CALLS: &[MRow] = &[
    m_codes::m(98, MOp::Call).reads(bit(b'P') | bit(b'L')),
    m_codes::m(99, MOp::Return).reads(bit(b'P')),
];

/// What a user macro does, for the `aux` event.
pub(super) const USER_MACRO: &str =
    "Mach3 user macro (the M-code script M<n>.m1s of the profile's macro folder)";

/// M codes Mach3 does not define call the user macro of that number with
/// the block's P, Q and R as its parameters (manual, "Macro M-codes");
/// M48/M49 switch the overrides. M47 (run again from the first line) is
/// left out: a checker runs a program once (W105 says it is ignored).
const MACH3_AUX_M: &[AuxM] = &[
    aux(10, 18, USER_MACRO),
    aux(20, 29, USER_MACRO),
    aux(31, 46, USER_MACRO),
    AuxM {
        first: 48,
        last: 49,
        what: "feed and speed overrides on (M48) or off (M49)",
        letters: 0,
    },
    aux(50, 97, USER_MACRO),
    aux(100, 999, USER_MACRO),
];

const fn aux(first: u16, last: u16, what: &'static str) -> AuxM {
    AuxM {
        first,
        last,
        what,
        letters: bit(b'P') | bit(b'Q') | bit(b'R'),
    }
}

/// Codes of Mach3's G-code list that vcnc does not run, and why (E201).
const NOT_RUN: &[(u16, &str)] = &[
    (
        150,
        "Mach3's polar mode G15/G16 (about the point where G16 was given) is not run by vcnc",
    ),
    (
        160,
        "Mach3's polar mode G15/G16 (about the point where G16 was given) is not run by vcnc",
    ),
    (500, "Mach3's per-axis scaling G50/G51 is not run by vcnc"),
    (510, "Mach3's per-axis scaling G50/G51 is not run by vcnc"),
    (870, "Mach3's back boring G87 is not run by vcnc"),
    (
        880,
        "Mach3's G88 (stop for a manual retract) is not run by vcnc",
    ),
    (
        680,
        "Mach3's coordinate rotation G68 A B R is not run by vcnc",
    ),
    (
        690,
        "Mach3's coordinate rotation G68 A B R is not run by vcnc",
    ),
];

/// The Mach3 dialect.
pub(super) fn mach3() -> Dialect {
    let (g, m) = Dialect::tables(&[GRBL_G, LINUXCNC_G, MACH3_G], MACH3_M);
    Dialect {
        name: "mach3",
        g,
        m,
        unsupported: NOT_RUN,
        aux_m: MACH3_AUX_M,
        macros: MacroRules::MACH3,
        o_in_flow: super::OInFlow::SkipsSubprogram,
        // Mach3 programs write a bare `G53 G90 G40` in their headers.
        g53_without_axes: super::G53WithoutAxes::MovesNothing,
        comp_when_on: super::CompWhenOn::Changes,
        comp_start: super::CompStart::Line,
        polar_words: false,
        polar_incremental: super::PolarIncremental::CentreAtCurrentPosition,
        // Mach3Mill has no G7/G8 (diameter mode is Mach3 Turn's).
        diameter: super::Diameter {
            axis: None,
            at_power_on: false,
            lathe: false,
        },
        // Mach3 reads as grbl does: no polar words, no nested-comment
        // alarm (those are rs274's).
        lex: super::grbl::GRBL_LEX,
        ..linuxcnc()
    }
}
