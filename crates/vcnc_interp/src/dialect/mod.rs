//! Dialects as data: which G and M codes exist, what operation each one is,
//! which modal group it belongs to and which words it reads.
//!
//! A [`Dialect`] is built from rows (`code, op, group`) into flat lookup
//! tables indexed by the code × 10 (`G59.1` → 591), so the interpreter asks
//! "what is G20 here?" with one array index and never branches on the
//! dialect's name. Syntec and Fanuc share every row except the unit codes
//! (G70/G71 against G20/G21) (`mill.rs`); the lathe profile of seed 003
//! (`lathe.rs`) gives many of the same numbers other operations (G20 is a
//! subroutine call, G05 a three-point arc, G53 cancels the work offset) and
//! adds word rules: U/W incremental axes, X in diameters, `CR=`, `IX`/`IZ`.

mod axes;
mod cycle_rules;
mod eia;
mod fanuc_lathe;
mod grbl;
mod lathe;
mod linuxcnc;
mod m_codes;
mod mach3;
mod macro_rules;
mod mill;
mod ops;

pub(crate) use axes::AxisWord;
pub use cycle_rules::{Approach, CycleRules, PeckClearance, Repeat, TapStyle};
pub use macro_rules::{
    ExtendedG, IsoMacros, MachineVars, MacroFiles, MacroRules, ModalLocals, VarTable,
};
pub use ops::{
    CircleCutForm, CompOp, CycleOp, FlowOp, FrameOp, GOp, Hole, ModeOp, MotionOp, MoveOp, PaceOp,
    RoughPockets, SetOp, TurnOp,
};

use vcnc_core::events::Plane;
use vcnc_syntax::LexRules;

/// The data words of a canned cycle block: R level, Q peck or shift, P
/// dwell, K repeats.
pub(crate) const CYCLE_WORDS: u32 = bit(b'R') | bit(b'Q') | bit(b'P') | bit(b'K');

/// The cycle data words where L repeats (Haas, LinuxCNC): R, Q, P, L.
pub(crate) const CYCLE_WORDS_L: u32 = bit(b'R') | bit(b'Q') | bit(b'P') | bit(b'L');

/// Haas's reduced peck of G73/G83: first peck I, J less each time, at
/// least K.
pub(crate) const HAAS_PECK_WORDS: u32 = bit(b'I') | bit(b'J') | bit(b'K');

/// Modal groups (Fanuc numbering in the comments). `NonModal` is group 00.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// 00: one-shot codes.
    NonModal,
    /// 01: motion.
    Motion,
    /// 02: plane.
    Plane,
    /// 03: absolute/incremental.
    Distance,
    /// 05: feed per minute / per revolution.
    FeedMode,
    /// 06: inch/metric.
    Units,
    /// 07: cutter radius compensation.
    CutterComp,
    /// 08: tool length compensation.
    ToolLength,
    /// 09: canned cycles.
    Cycle,
    /// 10: canned-cycle return level.
    ReturnLevel,
    /// 11: scaling.
    Scaling,
    /// 12: modal macro call.
    MacroModal,
    /// 13: constant surface speed.
    SpindleMode,
    /// 14: work coordinate system.
    Wcs,
    /// 15: path control.
    Path,
    /// 16: coordinate rotation.
    Rotation,
    /// 17: polar coordinate input.
    Polar,
    /// 22: programmable mirror image.
    Mirror,
    /// Lathe G22/G23: radius or diameter programming.
    DiameterMode,
    /// G90.1/G91.1: arc centres absolute or incremental (LinuxCNC, grbl).
    ArcDistance,
}

/// Number of modal groups other than `NonModal`.
pub const MODAL_GROUPS: usize = 19;

impl Group {
    /// Slot of a modal group in per-block tables (`None` for group 00).
    pub fn slot(self) -> Option<usize> {
        match self {
            Group::NonModal => None,
            // The discriminants of the modal groups are 1..=MODAL_GROUPS.
            g => Some(g as usize - 1),
        }
    }
}

/// What a one-shot code does with the block's axis words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AxisWords {
    /// Nothing: they go to the modal motion.
    Free,
    /// They are the code's arguments (G28 X0, G74 X Z), incremental words too.
    Claim,
    /// They are absolute coordinates for the code (G92, G52, G10, G53):
    /// the dialect's incremental words (U, W) are not allowed.
    ClaimAbsolute,
    /// The code takes the block; axis words are not allowed except those in
    /// its `letters` (G04 X2.5).
    Refuse,
}

/// What an M code does (in words: [`MOp::meaning`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(test, derive(strum::EnumIter))]
#[allow(missing_docs)]
pub enum MOp {
    Stop,
    OptionalStop,
    End,
    EndRewind,
    SpindleCw,
    SpindleCcw,
    SpindleStop,
    SpindleOrient,
    ToolChange,
    CoolantOn,
    CoolantOff,
    Call,
    Return,
    /// Haas M97: a subprogram at a sequence number of this program.
    LocalCall,
    /// Fanuc/Haas M29: rigid tapping mode for the next G84/G74.
    RigidTap,
}

/// M-code groups: two codes of one group in a block alarm (E206).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MGroup {
    /// M00 M01 M02 M30 M98 M99: program flow, executed last.
    Flow = 0,
    /// M03 M04 M05 M19.
    Spindle = 1,
    /// M08 M09.
    Coolant = 2,
    /// M06.
    Tool = 3,
}

/// Number of M groups.
pub const M_GROUPS: usize = 4;

/// One G-code row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GDef {
    /// Operation.
    pub op: GOp,
    /// Modal group.
    pub group: Group,
    /// Letters (bit 0 = 'A') the code reads besides the axes it moves.
    pub letters: u32,
    /// What it does with the axis words.
    pub axes: AxisWords,
    /// Whether it must stand alone in its block (lathe G20, G24, G08 …).
    pub alone: bool,
}

impl GDef {
    /// Whether the code takes the block's axis words (claims or refuses them).
    pub fn takes_axes(&self) -> bool {
        self.axes != AxisWords::Free
    }
}

/// One G-code row of a dialect table.
#[derive(Debug, Clone, Copy)]
pub(crate) struct GRow {
    code: u16,
    def: GDef,
}

/// A row: G `code` (× 10) is `op` in `group`, reads no extra letters.
pub(crate) const fn g(code: u16, op: GOp, group: Group) -> GRow {
    GRow {
        code,
        def: GDef {
            op,
            group,
            letters: 0,
            axes: AxisWords::Free,
            alone: false,
        },
    }
}

impl GRow {
    /// Also reads the letters of `mask`.
    pub(crate) const fn reads(mut self, mask: u32) -> GRow {
        self.def.letters |= mask;
        self
    }
    /// The axis words are its arguments.
    pub(crate) const fn claims_axes(mut self) -> GRow {
        self.def.axes = AxisWords::Claim;
        self
    }
    /// The axis words are absolute coordinates for it.
    pub(crate) const fn claims_absolute_axes(mut self) -> GRow {
        self.def.axes = AxisWords::ClaimAbsolute;
        self
    }
    /// Takes the block; no axis words except its letters.
    pub(crate) const fn refuses_axes(mut self) -> GRow {
        self.def.axes = AxisWords::Refuse;
        self
    }
    /// Must stand alone in its block.
    pub(crate) const fn alone(mut self) -> GRow {
        self.def.alone = true;
        self
    }
}

/// One M-code row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MDef {
    /// Operation.
    pub op: MOp,
    /// Group.
    pub group: MGroup,
    /// Letters the code reads.
    pub letters: u32,
}

/// `WorkSystem` index of "no work offset" (lathe G53/G500).
#[allow(clippy::cast_possible_truncation)] // WORK_SYSTEMS is 15
pub const WORK_NONE: u8 = vcnc_core::machine::WORK_SYSTEMS as u8;

/// Bit of a letter in a letter mask.
pub const fn bit(l: u8) -> u32 {
    1 << (l - b'A')
}

/// How a length word written without a decimal point is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegerWords {
    /// In least input increments: `X5500` is 5.5 mm (Fanuc, Syntec).
    LeastIncrement,
    /// In whole units: `X75` is 75 mm (the seed lathe, grbl, LinuxCNC).
    WholeUnits,
}

/// What an R arc does when its chord is longer than 2R.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LongChord {
    /// Alarm E302 (Fanuc).
    Alarm,
    /// Cut a straight line instead (the seed lathe document).
    Line,
}

/// How far an I/J/K arc's end may lie off the circle through its start.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArcEnd {
    /// The two radii may differ by the machine's `arc_tolerance_mm` (E303
    /// beyond): Fanuc, Syntec, Haas and grbl-class controls.
    MachineTolerance,
    /// rs274's rule (LinuxCNC 2.9): the radii may differ by 0.02·√2 mm
    /// (0.002·√2 in under G20), or by up to 0.1 % of the larger radius,
    /// but never by more than 100 times that length.
    Rs274,
}

/// What an `O` number met in the program's flow (not as the target of a
/// call) does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OInFlow {
    /// It is the next program's header: this program ends there (Fanuc's
    /// program memory, where each O starts a program).
    EndsProgram,
    /// It starts a subprogram that only a call runs: the flow skips to the
    /// block after its M99 (Mach3, whose posts write `O1 … M99` between
    /// the main program's blocks).
    SkipsSubprogram,
}

/// Diameter programming: which axis, and whether it is on at power-on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Diameter {
    /// The axis programmed in diameters under G23 (X on a lathe).
    pub axis: Option<u8>,
    /// Whether diameter programming is on at power-on.
    pub at_power_on: bool,
    /// A lathe's dialect: X is the work's radius, G41/G42 take a tool's
    /// nose radius and tip. LinuxCNC's mill reads G7/G8 on its X axis
    /// (`axis`) without being one.
    pub lathe: bool,
}

/// The path of a G00 that moves several axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RapidPath {
    /// Interpolated, or each axis at its own rapid rate under parameter
    /// 411 = 1 (`g00_mode` of the machine file): Fanuc, Syntec.
    ByParameter,
    /// EIA-274-D axis priority: Z first when it rises, last when it falls;
    /// X and Y at the same speed (a 45° leg, then the longer axis alone).
    ZPriority,
}

/// What G28 without axis words does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BareReturn {
    /// Alarm E312: the command names the axes to return (Syntec 1.2.13,
    /// Fanuc).
    NeedsAxes,
    /// Every axis goes straight to the reference point (Haas, grbl).
    AllAxes,
}

/// What M00 (and an effective M01) does besides waiting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramStop {
    /// The spindle and the coolant stop (Syntec M-code table: "the spindle
    /// will stop to rotate … cutting oil will stop"); the program starts
    /// them again.
    StopsSpindleAndCoolant,
    /// A pause: spindle and coolant stay as they are (grbl).
    Pause,
}

/// When a change of tool length offset (G43/G44/G49) takes effect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolLengthChange {
    /// A block that changes it and does not move moves Z so that the
    /// programmed point stays (Fanuc type A, Syntec 1.2.19).
    MovesNow,
    /// Nothing moves; the next move goes where the new offset puts the
    /// program point (grbl, LinuxCNC).
    AtNextMove,
}

/// Which G10 forms a dialect has, as the behaviours they differ by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct G10Rules {
    /// L1 P R Z writes tool P's radius and length (LinuxCNC's tool table).
    pub tool_table_l1: bool,
    /// L10–L13 P R write the H and D registers, geometry and wear (Fanuc,
    /// Syntec, grbl).
    pub registers_l10_l13: bool,
    /// L20 sets work offset P so that the current position reads as the
    /// axis words, and P0 names the active system (grbl, LinuxCNC).
    pub from_position_l20: bool,
    /// The highest work offset number of L2/L20 (6: G59; 9: G59.3).
    pub last_work_offset: u8,
    /// L2 under G91 adds its values to the offset (Fanuc); elsewhere it
    /// sets them as they are.
    pub l2_adds_under_g91: bool,
}

impl G10Rules {
    /// L2 P1–P6 work offsets, L10–L13 P R tool offsets (Fanuc, Syntec); no
    /// L20 (Fanuc's G54.1 extended offsets, which vcnc does not run: E109).
    pub const FANUC: G10Rules = G10Rules {
        tool_table_l1: false,
        registers_l10_l13: true,
        from_position_l20: false,
        last_work_offset: 6,
        l2_adds_under_g91: true,
    };

    /// Fanuc's, and L20 (grbl); L2 sets under G91 too.
    pub const GRBL: G10Rules = G10Rules {
        from_position_l20: true,
        l2_adds_under_g91: false,
        ..G10Rules::FANUC
    };

    /// LinuxCNC: L1 writes the tool table, L2 and L20 take P0 (the active
    /// system) to P9 (G59.3); no L10–L13.
    pub const RS274: G10Rules = G10Rules {
        tool_table_l1: true,
        registers_l10_l13: false,
        from_position_l20: true,
        last_work_offset: 9,
        l2_adds_under_g91: false,
    };

    /// The L values this dialect has, for an alarm's help.
    pub(crate) fn forms(self) -> &'static str {
        match (self.tool_table_l1, self.from_position_l20) {
            (true, _) => {
                "G10 L is 1, 2 or 20 (L10/L11, the tool table from the current position, are not run by vcnc)"
            }
            (false, true) => "G10 L is 2, 10, 11, 12, 13 or 20",
            (false, false) => "G10 L is 2, 10, 11, 12 or 13",
        }
    }
}

/// What H and D number, and which offset G43 without H and G41/G42
/// without D use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OffsetDefault {
    /// Offset registers, modal: the H or D number in force; a D alone in a
    /// block selects the next radius (Fanuc, Syntec).
    Modal,
    /// Tool numbers, read only with their code (G43 H, G41/G42 D; a D
    /// elsewhere is E203); without one, and as 0, the tool in the spindle
    /// (LinuxCNC: "if H is not given, the tool in the spindle"; G41 without
    /// D "uses the diameter of the currently loaded tool").
    ToolInSpindle,
}

/// Which word gives the lead of G33 (spindle-synchronized motion).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ThreadLead {
    /// F, in the G33/G32 block or before it (Fanuc, the lathes); a value
    /// without a decimal point is read as the feed's plain number.
    F,
    /// F as above, but a value without a decimal point counts 0.01 mm
    /// (Syntec 900M 1.2.17, "F: the thread of a screw (0.01mm)": `F150` is
    /// a 1.5 mm lead, `F1.5` too). The manual gives no inch unit, so under
    /// inch a lead without a point is an alarm.
    FHundredths,
    /// K, the distance per revolution; F stays the feed (LinuxCNC).
    K,
}

/// G53 (a move in machine coordinates) under G91.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum G53Incremental {
    /// An alarm: under G91 E308 (Syntec 1.2.23 says G53 "is not effective
    /// in increment mode", and an ignored move is worse than an alarm;
    /// rs274 refuses it too, "Cannot use g53 incremental").
    Alarm,
    /// G53 is ignored, with a warning (W110) under G91: Fanuc 0i's
    /// operator's manual (machine coordinate system, restrictions): "When
    /// an incremental command is specified, the G53 command is ignored".
    /// Haas follows Fanuc.
    Ignored,
}

/// G16 (polar coordinate input): where a G91 radius is measured from, what
/// a G91 angle adds to, and what an omitted radius or angle is. Under G90
/// every dialect reads the radius and angle about the program origin.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PolarIncremental {
    /// The radius and the angle each add to the last radius and angle,
    /// about the program origin (Syntec 900M 1.2.11: "in increment mode,
    /// angle or radius total from the last radius or angle"); an omitted
    /// one is the last polar block's.
    AddsToLast,
    /// A radius under G91 is measured from the current position, which
    /// becomes the polar centre for that block; the angle adds to the
    /// last angle, which is the current point's angle about the origin —
    /// after any move, polar or not (G53, G28, G92), and in the plane
    /// chosen now. A G91 block without a radius keeps the origin as the
    /// centre and the current point's distance from it as the radius; under
    /// G90 too an omitted radius or angle is the current point's (FANUC Series 16/18-MC §9.2
    /// "Polar coordinate command (G15, G16)": "G91 specifies the current
    /// position as the origin of the polar coordinate system, from which a
    /// radius is measured"; Mitsubishi M700V §6.12 says the same of an
    /// omitted radius or angle). Haas follows Fanuc.
    CentreAtCurrentPosition,
}

/// G53 without axis words (`G53 G49 M05`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum G53WithoutAxes {
    /// It moves nothing and is no alarm: Fanuc 0i and Haas document none
    /// (Fanuc: "IP_: absolute dimension word"), and the other Fanuc-style
    /// manuals are silent, so Fanuc decides.
    MovesNothing,
    /// E312 unless the block has a motion code: rs274 refuses a bare G53
    /// ("Must use g0 or g1 with g53": G53 only modifies a G0/G1 move) and
    /// lets `G53 G0` without axes pass.
    Alarm,
}

/// G41/G42 (and LinuxCNC's G41.1/G42.1) while compensation is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompWhenOn {
    /// The side and the radius change without a G40 (Fanuc 0i: G41/G42
    /// in offset mode changes the offset direction or value).
    Changes,
    /// E320: rs274 refuses it ("Cannot turn cutter radius comp on when
    /// on"); the program must G40 first.
    Alarm,
}

/// What move may start cutter compensation (G41/G42).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompStart {
    /// Only a straight move: an arc there is E317 (Fanuc 0i type A,
    /// Syntec: "G41/G42 ... only with G00 and G01").
    Line,
    /// A straight move or an entry arc (rs274): the arc ends r from its
    /// programmed end along the radius, about a centre on the line through
    /// the programmed centre and end, as far from the start as from the
    /// new end (`motion/comp/pass.rs`).
    LineOrArc,
}

/// The feed mode at power-on (group 05).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedAtPowerOn {
    /// Per minute (G94 on mills, Fanuc 0i-M).
    PerMinute,
    /// Per revolution (G99 on Fanuc lathes).
    PerRevolution,
}

/// What G96's constant surface speed is measured on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceSpeedOn {
    /// The active tool's diameter (a milling cutter's edge: Syntec 1.2.46).
    ToolDiameter,
    /// The work diameter under the tool, twice the program X (a lathe):
    /// the speed follows every move.
    WorkDiameter,
}

/// How a T word is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolWords {
    /// T selects a tool, M06 changes it (mills, the seed lathe).
    Select,
    /// `T tt oo`: the turret indexes to station tt at once and offset oo
    /// (X/Z geometry and wear, nose radius, tip) applies; `oo = 00`
    /// cancels the offset; no M06 (Fanuc lathes).
    TurretOffset,
}

/// A dialect profile: code tables plus the word rules that differ.
pub struct Dialect {
    /// Name as given to `--dialect`.
    pub name: &'static str,
    /// Lexical rules.
    pub lex: LexRules,
    g: Vec<Option<GDef>>,
    m: Vec<Option<MDef>>,
    /// Incremental words of axes: (word, axis), e.g. (U, X) on a lathe.
    pub incremental_words: &'static [(u8, u8)],
    /// Diameter programming.
    pub diameter: Diameter,
    /// How integers in length words are read.
    pub integers: IntegerWords,
    /// Plane at power-on (G17 on a mill, the ZX plane on a lathe).
    pub plane: Plane,
    /// What an R arc with a chord longer than 2R does.
    pub long_chord: LongChord,
    /// How far an I/J/K arc's end may lie off its circle.
    pub arc_end: ArcEnd,
    /// What an O number in the flow does.
    pub o_in_flow: OInFlow,
    /// Letters an arc reads besides the plane's centre offsets and R (the
    /// lathe's D diameter).
    pub arc_letters: u32,
    /// The embedded machine used when no `--machine` is given.
    pub default_machine: &'static str,
    /// Codes the dialect's document lists that vcnc does not run, and why
    /// (E201 quotes it).
    pub unsupported: &'static [(u16, &'static str)],
    /// The path of a multi-axis G00.
    pub rapid: RapidPath,
    /// The canned cycles' reading.
    pub cycles: CycleRules,
    /// G28 without axis words.
    pub bare_return: BareReturn,
    /// G10's forms.
    pub g10: G10Rules,
    /// M00.
    pub program_stop: ProgramStop,
    /// G43/G44/G49 without a move (and a lathe T word's offset).
    pub tool_length_change: ToolLengthChange,
    /// G43 without H, G41/G42 without D.
    pub offset_default: OffsetDefault,
    /// Macros: languages, variables, calls.
    pub macros: MacroRules,
    /// G94/G99 at power-on.
    pub feed_at_power_on: FeedAtPowerOn,
    /// G96 on the tool or on the work.
    pub surface_speed: SurfaceSpeedOn,
    /// T words.
    pub tool_words: ToolWords,
    /// What a decimal point in G04's P means.
    pub dwell_p: DwellP,
    /// What M06 does to a turning spindle.
    pub tool_change: ToolChangeSpindle,
    /// The lead of G33.
    pub thread_lead: ThreadLead,
    /// G53 under G91.
    pub g53_incremental: G53Incremental,
    /// G53 without axis words.
    pub g53_without_axes: G53WithoutAxes,
    /// G41/G42 (G41.1/G42.1) while cutter compensation is already on.
    pub comp_when_on: CompWhenOn,
    /// What move may start cutter compensation.
    pub comp_start: CompStart,
    /// Whether the code numbers follow the machine's `gcode_system`
    /// (Fanuc 0i-TF's systems A, B and C, other tables of this profile);
    /// a dialect without it has one numbering.
    pub gcode_systems: bool,
    /// LinuxCNC's polar words: `@` a distance and `^` an angle in degrees
    /// give X and Y, about the origin under G90 and adding to the current
    /// point's distance and angle under G91 (`block/convert.rs`).
    pub polar_words: bool,
    /// What G91 means to G16's radius and angle.
    pub polar_incremental: PolarIncremental,
    /// How the tip directions of the offset registers (and of a `.tbl`'s
    /// Q) are numbered: Fanuc's, or LinuxCNC's lathe orientation.
    pub tip_numbering: vcnc_core::tooling::TipNumbering,
    /// M codes the controller itself passes on as auxiliary functions
    /// (`aux` events), with the letters they read (LinuxCNC's M62–M68).
    pub aux_m: &'static [AuxM],
}

/// What M06 does to a turning spindle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToolChangeSpindle {
    /// Nothing the interpreter sees: the machine builder's tool-change
    /// macro stops and restarts it (Fanuc, Syntec, Haas).
    Keeps,
    /// It stops, and the program starts it again (LinuxCNC: rs274 stops
    /// the spindle before CHANGE_TOOL).
    Stops,
}

/// A range of M codes a controller defines as auxiliary functions: the
/// machine acts on them, the interpreter only passes them on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AuxM {
    /// The first code of the range.
    pub first: u16,
    /// The last code of the range.
    pub last: u16,
    /// What they do (the `aux` event's description).
    pub what: &'static str,
    /// Letters they read.
    pub letters: u32,
}

impl AuxM {
    /// Whether the range is a control's "any other M code runs the user's
    /// macro of that number" (Mach3), which says nothing of the program's
    /// control when detecting it.
    pub fn is_user_macro(&self) -> bool {
        self.what == mach3::USER_MACRO
    }
}

/// G04 P with a decimal point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DwellP {
    /// P is whole milliseconds; a point alarms E108 (Fanuc, Syntec 1.2.5).
    WholeMilliseconds,
    /// `P2.5` is 2.5 s, `P2500` 2.5 s in milliseconds (Haas mill operator's
    /// manual, G04: "G04 P10. is a dwell of 10 seconds").
    SecondsWithPoint,
}

impl std::fmt::Debug for Dialect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Dialect")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// Largest G code × 10 in the tables.
const G_SLOTS: usize = 10_000;
/// Largest M code + 1.
const M_SLOTS: usize = 1_000;

use m_codes::MRow;

impl Dialect {
    /// Every dialect, built once, in [`Dialect::NAMES`] order.
    pub fn all() -> &'static [Dialect] {
        static ALL: std::sync::OnceLock<Vec<Dialect>> = std::sync::OnceLock::new();
        ALL.get_or_init(|| {
            Dialect::NAMES
                .iter()
                .filter_map(|n| Dialect::by_name(n))
                .collect()
        })
    }

    /// The dialect named `name`, in any case (`Haas`, `FANUC-LATHE`), built
    /// once.
    pub fn named(name: &str) -> Option<&'static Dialect> {
        Dialect::all()
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case(name.trim()))
    }

    /// Looks a dialect up by its `--dialect` name (a new table each call;
    /// [`named`](Self::named) shares one).
    pub fn by_name(name: &str) -> Option<Dialect> {
        match name {
            "syntec" => Some(mill::syntec()),
            "fanuc" => Some(mill::fanuc()),
            "lathe" => Some(lathe::lathe()),
            "eia" => Some(eia::eia()),
            "grbl" => Some(grbl::grbl()),
            "haas" => Some(mill::haas()),
            "fanuc-lathe" => Some(fanuc_lathe::fanuc_lathe()),
            "haas-lathe" => Some(fanuc_lathe::haas_lathe()),
            "linuxcnc" => Some(linuxcnc::linuxcnc()),
            "linuxcnc-lathe" => Some(linuxcnc::linuxcnc_lathe()),
            "mach3" => Some(mach3::mach3()),
            _ => None,
        }
    }

    /// Names accepted by [`by_name`](Self::by_name).
    pub const NAMES: &'static [&'static str] = &[
        "syntec",
        "fanuc",
        "lathe",
        "eia",
        "grbl",
        "haas",
        "fanuc-lathe",
        "haas-lathe",
        "linuxcnc",
        "linuxcnc-lathe",
        "mach3",
    ];

    /// Syntec 900M mill (the default).
    pub fn syntec() -> Dialect {
        mill::syntec()
    }

    /// Fanuc 0i mill.
    pub fn fanuc() -> Dialect {
        mill::fanuc()
    }

    /// The lathe controller of seed 003.
    pub fn lathe() -> Dialect {
        lathe::lathe()
    }

    /// Generic EIA-274-D (seed 004).
    pub fn eia() -> Dialect {
        eia::eia()
    }

    /// grbl 1.1 and the hobby CAM programs written for it.
    pub fn grbl() -> Dialect {
        grbl::grbl()
    }

    /// Haas mills (Fanuc with Haas's differences).
    pub fn haas() -> Dialect {
        mill::haas()
    }

    /// Fanuc 0i-TF lathes (G-code system A).
    pub fn fanuc_lathe() -> Dialect {
        fanuc_lathe::fanuc_lathe()
    }

    /// Haas lathes: the Fanuc lathe with Haas's G04 P and tool-life
    /// variables.
    pub fn haas_lathe() -> Dialect {
        fanuc_lathe::haas_lathe()
    }

    /// LinuxCNC 2.9's RS274/NGC mill interpreter.
    pub fn linuxcnc() -> Dialect {
        linuxcnc::linuxcnc()
    }

    /// LinuxCNC 2.9 in lathe mode (G7/G8, XZ plane).
    pub fn linuxcnc_lathe() -> Dialect {
        linuxcnc::linuxcnc_lathe()
    }

    /// Mach3: RS274/NGC as LinuxCNC reads it, with O-number subprograms
    /// (M98/M99) and M-code macros.
    pub fn mach3() -> Dialect {
        mach3::mach3()
    }

    /// Fills the code tables from rows; the rest of the profile is set by the
    /// caller with struct update syntax.
    pub(crate) fn tables(
        g_rows: &[&[GRow]],
        m_rows: &[&[MRow]],
    ) -> (Vec<Option<GDef>>, Vec<Option<MDef>>) {
        let mut g = vec![None; G_SLOTS];
        for row in g_rows.iter().flat_map(|r| r.iter()) {
            g[usize::from(row.code)] = Some(row.def);
        }
        let mut m = vec![None; M_SLOTS];
        for row in m_rows.iter().flat_map(|r| r.iter()) {
            m[usize::from(row.code)] = Some(MDef {
                op: row.op,
                group: row.op.group(),
                letters: row.letters,
            });
        }
        (g, m)
    }

    /// Every G code of the table, in code order: the code × 10 (`591` is
    /// G59.1) and its row. `vcnc explain`, the dialect matrix and the
    /// editor's hover read the tables through this.
    pub fn g_rows(&self) -> impl Iterator<Item = (u16, GDef)> + '_ {
        self.g
            .iter()
            .enumerate()
            .filter_map(|(i, d)| Some((u16::try_from(i).ok()?, (*d)?)))
    }

    /// Every M code of the table, in code order, and its row.
    pub fn m_rows(&self) -> impl Iterator<Item = (u16, MDef)> + '_ {
        self.m
            .iter()
            .enumerate()
            .filter_map(|(i, d)| Some((u16::try_from(i).ok()?, (*d)?)))
    }

    /// This dialect with the code numbers of the machine's G-code system
    /// (`gcode_system` in the machine file): the Fanuc lathe's systems B
    /// and C are other tables of the same profile, built once. Every other
    /// dialect has one numbering and is returned as it is.
    pub fn for_system(&'static self, system: vcnc_core::machine::GcodeSystem) -> &'static Dialect {
        use std::sync::OnceLock;
        use vcnc_core::machine::GcodeSystem;
        static B: OnceLock<Dialect> = OnceLock::new();
        static C: OnceLock<Dialect> = OnceLock::new();
        if !self.gcode_systems {
            return self;
        }
        match system {
            GcodeSystem::A => self,
            GcodeSystem::B => B.get_or_init(|| fanuc_lathe::fanuc_lathe_in(GcodeSystem::B)),
            GcodeSystem::C => C.get_or_init(|| fanuc_lathe::fanuc_lathe_in(GcodeSystem::C)),
        }
    }

    /// [`for_system`](Self::for_system) for a dialect that may not be one
    /// of the built-in ones: a profile with [`gcode_systems`](Self::gcode_systems)
    /// takes its built-in table of `system`; any other dialect is returned
    /// as it is.
    pub fn under_system(&self, system: vcnc_core::machine::GcodeSystem) -> &Dialect {
        match Dialect::named(self.name) {
            Some(base) if self.gcode_systems => base.for_system(system),
            _ => self,
        }
    }

    /// The embedded machine this dialect runs on by default.
    pub fn machine(&self) -> vcnc_core::machine::Machine {
        match vcnc_core::machine::Machine::from_toml(self.default_machine) {
            Ok(m) => m,
            // Each embedded file is checked by a unit test; this cannot happen.
            Err(e) => unreachable!("embedded machine of {} is invalid: {e}", self.name),
        }
    }

    /// Why G `value` is listed but not run here, if it is.
    pub fn unsupported_reason(&self, value: f64) -> Option<&'static str> {
        let tenths = (value * 10.0).round();
        self.unsupported
            .iter()
            .find(|(c, _)| f64::from(*c) == tenths)
            .map(|(_, why)| *why)
    }

    /// The G code whose value is `value` (`59.1`), if this dialect has it.
    pub fn g(&self, value: f64) -> Option<GDef> {
        let tenths = (value * 10.0).round();
        if (value * 10.0 - tenths).abs() > 1e-6 || !(0.0..G_SLOTS as f64).contains(&tenths) {
            return None;
        }
        // In 0..G_SLOTS and whole, so the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let slot = tenths as usize;
        self.g.get(slot).copied().flatten()
    }

    /// Whether a D word selects a cutter-radius offset in this dialect (its
    /// G41 reads D): then D is modal and may stand without G41/G42.
    pub(crate) fn d_is_radius_offset(&self) -> bool {
        self.offset_default == OffsetDefault::Modal
            && self
                .g(41.0)
                .is_some_and(|g| g.op == GOp::Comp(CompOp::Left) && g.letters & bit(b'D') != 0)
    }

    /// Whether H is a tool length offset register in this dialect (it has
    /// G43, and H names a register, not a tool): then `H0` ("no offset")
    /// may stand in any block. rs274 refuses `G49 H0` ("H word with no G43
    /// or G76 to use it").
    pub(crate) fn h_is_length_offset(&self) -> bool {
        self.offset_default == OffsetDefault::Modal
            && self
                .g(43.0)
                .is_some_and(|g| g.op == GOp::Frame(FrameOp::ToolLengthPlus))
    }

    /// The G code that does `op` in this dialect (the first in the table),
    /// for a help text that must name the dialect's own code: feed per
    /// minute is G94 on a mill and G98 on a Fanuc lathe, whose G94 is a
    /// facing cycle.
    pub fn g_for(&self, op: GOp) -> Option<f64> {
        let slot = self.g.iter().position(|d| d.is_some_and(|d| d.op == op))?;
        // A table index is far below 2^32, so the conversion is exact.
        u32::try_from(slot).ok().map(|t| f64::from(t) / 10.0)
    }

    /// The M code `value`, if this dialect has it.
    pub fn m(&self, value: f64) -> Option<MDef> {
        if value.fract() != 0.0 || !(0.0..M_SLOTS as f64).contains(&value) {
            return None;
        }
        // In 0..M_SLOTS and whole, so the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let slot = value as usize;
        self.m.get(slot).copied().flatten()
    }

    /// The controller's auxiliary M code `code`, if it is one.
    pub fn aux_m(&self, code: u32) -> Option<&AuxM> {
        self.aux_m
            .iter()
            .find(|a| (u32::from(a.first)..=u32::from(a.last)).contains(&code))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_codes_differ_by_dialect_only() {
        let s = Dialect::syntec();
        let f = Dialect::fanuc();
        assert_eq!(s.g(70.0).map(|d| d.op), Some(GOp::Mode(ModeOp::Inch)));
        assert_eq!(s.g(20.0), None);
        assert_eq!(f.g(20.0).map(|d| d.op), Some(GOp::Mode(ModeOp::Inch)));
        assert_eq!(f.g(70.0), None);
        assert_eq!(
            s.g(59.1).map(|d| d.op),
            Some(GOp::Mode(ModeOp::WorkSystem(6)))
        );
        assert_eq!(s.g(59.15), None);
        assert_eq!(s.g(-1.0), None);
    }

    #[test]
    fn every_dialects_machine_is_valid() {
        for name in Dialect::NAMES {
            let d = Dialect::by_name(name).unwrap();
            assert!(
                vcnc_core::machine::Machine::from_toml(d.default_machine).is_ok(),
                "{name}"
            );
        }
    }

    #[test]
    fn the_lathe_gives_the_same_numbers_other_meanings() {
        let l = Dialect::lathe();
        let s = Dialect::syntec();
        assert_eq!(l.g(20.0).map(|d| d.op), Some(GOp::Flow(FlowOp::SubCall)));
        assert_eq!(
            l.g(5.0).map(|d| d.op),
            Some(GOp::Motion(MotionOp::ThreePointArc))
        );
        assert_eq!(
            l.g(53.0).map(|d| d.op),
            Some(GOp::Mode(ModeOp::CancelOffsets))
        );
        assert_eq!(
            s.g(53.0).map(|d| d.op),
            Some(GOp::Move(MoveOp::MachineCoords))
        );
        assert_eq!(l.g(16.0), None);
        assert!(l.unsupported_reason(7.0).is_some());
    }

    #[test]
    fn the_fanuc_lathe_reads_system_a() {
        let f = Dialect::fanuc_lathe();
        assert_eq!(
            f.g(90.0).map(|d| d.op),
            Some(GOp::Motion(MotionOp::TurnCycle))
        );
        assert_eq!(
            f.g(92.0).map(|d| d.op),
            Some(GOp::Motion(MotionOp::ThreadingCycle))
        );
        assert_eq!(
            f.g(94.0).map(|d| d.op),
            Some(GOp::Motion(MotionOp::FaceCycle))
        );
        assert_eq!(f.g(99.0).map(|d| d.op), Some(GOp::Mode(ModeOp::PerRev)));
        assert_eq!(
            f.g(50.0).map(|d| d.op),
            Some(GOp::Set(SetOp::PresetOrClamp))
        );
        assert_eq!(f.g(32.0).map(|d| d.op), Some(GOp::Motion(MotionOp::Thread)));
        assert_eq!(f.m(6.0), None);
        // A Fanuc lathe's G17 (live tooling) is listed as not run.
        assert!(f.unsupported_reason(17.0).is_some());
    }

    #[test]
    fn the_fanuc_lathes_systems_b_and_c_renumber_its_codes() {
        use vcnc_core::machine::GcodeSystem;
        let a = Dialect::named("fanuc-lathe").unwrap();
        assert!(std::ptr::eq(a.for_system(GcodeSystem::A), a));
        let op = |d: &Dialect, v: f64| d.g(v).map(|r| r.op);
        for sys in [GcodeSystem::B, GcodeSystem::C] {
            let d = a.for_system(sys);
            assert_eq!(d.name, "fanuc-lathe");
            assert_eq!(op(d, 90.0), Some(GOp::Mode(ModeOp::Absolute)));
            assert_eq!(op(d, 91.0), Some(GOp::Mode(ModeOp::Incremental)));
            assert_eq!(op(d, 92.0), Some(GOp::Set(SetOp::PresetOrClamp)));
            assert_eq!(op(d, 94.0), Some(GOp::Mode(ModeOp::PerMinute)));
            assert_eq!(op(d, 95.0), Some(GOp::Mode(ModeOp::PerRev)));
            assert_eq!(op(d, 33.0), Some(GOp::Motion(MotionOp::Thread)));
            assert_eq!(op(d, 32.0), None);
            assert_eq!(op(d, 50.0), None);
        }
        let b = a.for_system(GcodeSystem::B);
        assert_eq!(op(b, 77.0), Some(GOp::Motion(MotionOp::TurnCycle)));
        assert_eq!(op(b, 71.0), Some(GOp::Turn(TurnOp::RoughTurnCycle)));
        assert_eq!(op(b, 21.0), Some(GOp::Mode(ModeOp::Metric)));
        let c = a.for_system(GcodeSystem::C);
        assert_eq!(op(c, 20.0), Some(GOp::Motion(MotionOp::TurnCycle)));
        assert_eq!(op(c, 21.0), Some(GOp::Motion(MotionOp::ThreadingCycle)));
        assert_eq!(op(c, 24.0), Some(GOp::Motion(MotionOp::FaceCycle)));
        assert_eq!(op(c, 71.0), Some(GOp::Mode(ModeOp::Metric)));
        assert_eq!(op(c, 72.0), Some(GOp::Turn(TurnOp::FinishCycle)));
        assert_eq!(op(c, 78.0), Some(GOp::Turn(TurnOp::ThreadMultiCycle)));
        // Haas lathes have system A only.
        let haas = Dialect::named("haas-lathe").unwrap();
        assert!(std::ptr::eq(haas.for_system(GcodeSystem::B), haas));
    }
}
