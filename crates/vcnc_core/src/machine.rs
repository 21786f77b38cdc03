//! The machine model: axes and travel limits, rates, reference points, work
//! offsets, tool table, parameters and runaway limits.
//!
//! It is read from TOML (`--machine FILE.toml`; the format is documented in
//! `docs/machine.md` and by the embedded default, `default_mill.toml`) into a
//! validated [`Machine`] with fixed-size, axis-indexed arrays so that the
//! interpreter's hot path never looks anything up by name. Parsing text is
//! the only thing done here; reading the file is the CLI's job. It lives in
//! the contract crate because every consumer of events (summary, planner,
//! plotter) needs the same axes, rates and limits as the interpreter.

use crate::events::{MAX_AXES, Pos};
use crate::motion::Motion;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The embedded default mill.
pub const DEFAULT_MILL_TOML: &str = include_str!("default_mill.toml");

/// The embedded mill of the haas dialect (the default mill with Haas's M
/// codes).
pub const DEFAULT_HAAS_TOML: &str = include_str!("default_haas.toml");

/// The embedded 2-axis lathe of the seed-003 dialect.
pub const DEFAULT_LATHE_TOML: &str = include_str!("default_lathe.toml");

/// The embedded turning centre of the fanuc-lathe dialect (X radius, Z,
/// a turret tool table).
pub const DEFAULT_FANUC_LATHE_TOML: &str = include_str!("default_fanuc_lathe.toml");

/// Number of work coordinate systems (G54–G59, G59.1–G59.9).
pub const WORK_SYSTEMS: usize = 15;

/// One axis. A rotary axis (A, B, C) counts in degrees where a linear one
/// counts in mm.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Uppercase letter.
    pub letter: u8,
    /// Travel limits, machine coordinates (infinite when the machine file
    /// gives none).
    pub min_mm: f64,
    /// Travel limits, machine coordinates (infinite when not given).
    pub max_mm: f64,
    /// Rapid rate.
    pub rapid_mm_per_min: f64,
    /// Highest cutting feed.
    pub max_feed_mm_per_min: f64,
    /// Acceleration.
    pub accel_mm_s2: f64,
    /// Jerk (rate of change of acceleration), for jerk-limited profiles.
    pub jerk_mm_s3: f64,
    /// In-position window of cutting moves (Syntec 421–440).
    pub in_position_mm: f64,
    /// In-position window of rapids (Syntec 461–480).
    pub in_position_rapid_mm: f64,
}

/// How words without a decimal point are read (Fanuc parameter DPI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DecimalInput {
    /// `X5500` is 5500 least input increments = 5.5 mm.
    Increment,
    /// `X5500` is 5500 mm.
    Calculator,
}

/// What to do with two G codes of one modal group in one block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SameGroup {
    /// The last one written wins (Fanuc 0i).
    LastWins,
    /// Alarm E205.
    Alarm,
}

/// Parameters named in the manuals.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Params {
    /// Syntec 411: 0 = G00 interpolated, 1 = each axis at its own rapid rate.
    pub g00_mode: u8,
    /// Decimal point input.
    pub decimal_input: DecimalInput,
    /// Largest start/end radius difference of an arc.
    pub arc_tolerance_mm: f64,
    /// Same-group G codes in one block.
    pub same_group_in_block: SameGroup,
    /// Tool offset registers: H and D numbers 0 to this (offsets the tool
    /// table does not list are zero).
    pub offset_registers: u32,
    /// Most blocks in a row without motion in the plane while cutter
    /// compensation holds a move (E319 beyond).
    pub comp_lookahead_blocks: u32,
    /// Syntec 4002: the retract d of G73 and G84 type II pecks, and the
    /// clearance G83 rapids back down to, mm.
    pub peck_return_mm: f64,
    /// Syntec 4001: peck tapping (G84 with Q) type: 0 general (type III,
    /// back to R), 1 high speed (type II, back by d).
    pub tapping_type: u8,
    /// Syntec 4020: the direction G76/G87 shift away from the bore wall:
    /// 0 +first axis, 1 −first, 2 +second, 3 −second axis of the plane.
    pub shift_direction: u8,
    /// Syntec 4010: pocket stepover, percent of the tool diameter.
    pub pocket_stepover_pct: f64,
    /// Highest spindle speed; a higher S is clamped with warning W103
    /// (0: no limit).
    pub max_spindle_rpm: f64,
    /// An M code neither the dialect nor `[m_codes]` knows: alarm E202
    /// (`true`) or warning W105 and ignored (`false`).
    pub strict_m_codes: bool,
    /// Fanuc 5130: the chamfer at the end of a G92/G76 thread, in tenths
    /// of the lead (0: none; G76's P sets it for both).
    pub thread_chamfer_tenths: u8,
    /// Fanuc 5131: the angle of that chamfer from the Z axis, degrees.
    pub thread_chamfer_deg: f64,
}

impl Default for Params {
    fn default() -> Params {
        Params {
            g00_mode: 0,
            decimal_input: DecimalInput::Increment,
            arc_tolerance_mm: 0.01,
            same_group_in_block: SameGroup::LastWins,
            offset_registers: 200,
            comp_lookahead_blocks: 5,
            peck_return_mm: 1.0,
            tapping_type: 0,
            shift_direction: 0,
            pocket_stepover_pct: 50.0,
            max_spindle_rpm: 0.0,
            strict_m_codes: false,
            thread_chamfer_tenths: 10,
            thread_chamfer_deg: 45.0,
        }
    }
}

/// Runaway-program limits.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Limits {
    /// Deepest subprogram nesting (E403).
    pub max_call_depth: u32,
    /// Most jumps: M98 calls, M99 returns to a sequence, main-program repeats (E405).
    pub max_jumps: u64,
    /// Most blocks executed beyond one per byte of program text read
    /// (E404): a program that runs straight through never reaches it, a
    /// loop does within about a second.
    pub max_executed_blocks: u64,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_call_depth: 10,
            max_jumps: 1_000_000,
            max_executed_blocks: 5_000_000,
        }
    }
}

/// One tool of the tool table (one offset register: a mill's H and D, a
/// lathe's geometry and wear offsets).
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Tool {
    /// Length geometry (H).
    pub h_mm: f64,
    /// Length wear (H).
    pub h_wear_mm: f64,
    /// Radius geometry (D).
    pub d_mm: f64,
    /// Radius wear (D).
    pub d_wear_mm: f64,
    /// Lathe X geometry offset (a radius: machine X is the radius).
    pub x_mm: f64,
    /// Lathe X wear offset (radius).
    pub x_wear_mm: f64,
    /// Lathe Z geometry offset.
    pub z_mm: f64,
    /// Lathe Z wear offset.
    pub z_wear_mm: f64,
    /// Tool nose radius (geometry).
    pub nose_radius_mm: f64,
    /// Tool nose radius wear.
    pub nose_radius_wear_mm: f64,
    /// Imaginary tool tip direction, 0–9 (0 and 9: the nose centre).
    pub tip: u8,
}

/// Where the skip signal of G31 fires: when `axis` crosses `at_mm`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkipTrigger {
    /// Axis index.
    pub axis: usize,
    /// Machine coordinate.
    pub at_mm: f64,
}

/// A validated machine.
#[derive(Debug, Clone, PartialEq)]
pub struct Machine {
    /// Display name.
    pub name: String,
    /// Axes in event order.
    pub axes: Vec<Axis>,
    letter_axis: [Option<u8>; 26],
    /// Power-on position.
    pub start: Pos,
    /// Reference points 1–4.
    pub reference: [Option<Pos>; 4],
    /// Work offsets, G54 first.
    pub work_offsets: [Pos; WORK_SYSTEMS],
    /// Tool table.
    pub tools: BTreeMap<u32, Tool>,
    /// Parameters.
    pub params: Params,
    /// Runaway limits.
    pub limits: Limits,
    /// G31 skip triggers.
    pub skip: Vec<SkipTrigger>,
    /// The machine builder's M codes (auxiliary functions) and what each
    /// does: they pass through as `aux` events.
    pub m_codes: BTreeMap<u32, std::sync::Arc<str>>,
    /// Motion planning: profile, look-ahead, corner tolerance, times.
    pub motion: Motion,
    /// M codes that call a macro program (Syntec's registered M codes,
    /// Fanuc parameters 6080–6089): the program's name (`M0123`, `O9020`).
    pub m_macros: BTreeMap<u32, std::sync::Arc<str>>,
    /// Machine Z of the table's top, where a tool's tip would touch it
    /// (`vcnc sim`'s fixture check); `None` when the file gives none.
    pub table_z_mm: Option<f64>,
    /// The Fanuc lathe G-code system (`gcode_system = "A"`, `"B"` or
    /// `"C"`, Fanuc 0i-TF parameter GSB/GSC No. 3401): which numbers the
    /// `fanuc-lathe` dialect gives its codes. Other dialects ignore it.
    pub gcode_system: GcodeSystem,
}

/// The three G-code systems of a Fanuc lathe (0i-TF operator's manual,
/// "G code list": table of systems A, B and C).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GcodeSystem {
    /// G90/G92/G94 are the turning, threading and facing cycles, G50 sets
    /// coordinates, G98/G99 feed per minute/revolution, U/W incremental.
    #[default]
    A,
    /// G77/G78/G79 are the cycles, G90/G91 absolute/incremental, G92 sets
    /// coordinates, G94/G95 feed per minute/revolution, G98/G99 cycle
    /// return levels.
    B,
    /// As B, with G20/G21/G24 the cycles, G70/G71 inch/mm and the
    /// multiple repetitive cycles at G72–G78.
    C,
}

impl GcodeSystem {
    /// `A`, `B` or `C`.
    pub fn letter(self) -> &'static str {
        match self {
            GcodeSystem::A => "A",
            GcodeSystem::B => "B",
            GcodeSystem::C => "C",
        }
    }
}

/// Why a machine file was rejected.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineError(pub String);

impl std::fmt::Display for MachineError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for MachineError {}

type AxisMap = BTreeMap<String, f64>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileAxis {
    letter: String,
    #[serde(default)]
    min_mm: Option<f64>,
    #[serde(default)]
    max_mm: Option<f64>,
    rapid_mm_per_min: f64,
    max_feed_mm_per_min: f64,
    #[serde(default = "default_accel")]
    accel_mm_s2: f64,
    jerk_mm_s3: Option<f64>,
    #[serde(default = "default_in_position")]
    in_position_mm: f64,
    #[serde(default = "default_in_position_rapid")]
    in_position_rapid_mm: f64,
}

fn default_accel() -> f64 {
    1000.0
}

fn default_in_position() -> f64 {
    0.01
}

fn default_in_position_rapid() -> f64 {
    0.02
}

/// Longest time an axis may take to reach its acceleration (a/j), s.
pub const MAX_JERK_TIME_S: f64 = 10.0;

/// Without `jerk_mm_s3`, an axis reaches its acceleration in this time
/// (jerk = acceleration / 0.05 s), a common bell-shaped time constant.
pub const DEFAULT_JERK_TIME_S: f64 = 0.05;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSkip {
    axis: String,
    at_mm: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    name: String,
    axes: Vec<FileAxis>,
    #[serde(default)]
    start_mm: AxisMap,
    #[serde(default)]
    reference: BTreeMap<String, AxisMap>,
    #[serde(default)]
    work_offsets: BTreeMap<String, AxisMap>,
    #[serde(default)]
    tools: BTreeMap<String, Tool>,
    #[serde(default)]
    parameters: Params,
    #[serde(default)]
    limits: Limits,
    #[serde(default)]
    skip: Vec<FileSkip>,
    #[serde(default)]
    m_codes: BTreeMap<String, String>,
    #[serde(default)]
    motion: Motion,
    #[serde(default)]
    m_macros: BTreeMap<String, String>,
    #[serde(default)]
    table_z_mm: Option<f64>,
    #[serde(default)]
    gcode_system: GcodeSystem,
}

/// `gcode_system` is exactly `"A"`, `"B"` or `"C"`; anything else is an
/// error at its line and column in the file.
impl<'de> Deserialize<'de> for GcodeSystem {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<GcodeSystem, D::Error> {
        let text = String::deserialize(d)?;
        match text.as_str() {
            "A" => Ok(GcodeSystem::A),
            "B" => Ok(GcodeSystem::B),
            "C" => Ok(GcodeSystem::C),
            other => Err(serde::de::Error::custom(format!(
                "gcode_system: {other:?} is not a Fanuc lathe G-code system; write \"A\", \"B\" or \"C\" (docs/machine.md)"
            ))),
        }
    }
}

/// Validates one `[m_macros]` entry: an M code the controller does not
/// keep for itself, and a program name of letters and digits.
fn m_macro_code(key: &str, program: &str) -> Result<u32, MachineError> {
    let n: u32 = key
        .parse()
        .ok()
        .filter(|n| *n < 1000)
        .ok_or_else(|| MachineError(format!("m_macros.{key}: an M code is 0 to 999")))?;
    // Program flow and the call codes cannot be taken over (Syntec's §5.3.3).
    if matches!(n, 0 | 1 | 2 | 30 | 96 | 97 | 98 | 99 | 198) {
        return Err(MachineError(format!(
            "m_macros.{key}: M{n} is a program-flow code of the controller and cannot call a macro"
        )));
    }
    let ok = !program.is_empty()
        && program.len() <= 16
        && program.bytes().all(|b| b.is_ascii_alphanumeric());
    if !ok {
        return Err(MachineError(format!(
            "m_macros.{key}: {program:?} is not a program name (letters and digits, e.g. \"M0123\")"
        )));
    }
    Ok(n)
}

impl Machine {
    /// The embedded 3-axis mill.
    pub fn default_mill() -> Machine {
        match Machine::from_toml(DEFAULT_MILL_TOML) {
            Ok(m) => m,
            // The embedded file is checked by a unit test; this cannot happen.
            Err(e) => unreachable!("embedded machine is invalid: {e}"),
        }
    }

    /// Parses and validates a machine file.
    pub fn from_toml(text: &str) -> Result<Machine, MachineError> {
        let file: File = toml::from_str(text).map_err(|e| MachineError(e.to_string()))?;
        Machine::from_file(file)
    }

    /// The axis index of an uppercase letter, if the machine has that axis.
    pub fn axis_of(&self, letter: u8) -> Option<usize> {
        let i = usize::from(letter.checked_sub(b'A')?);
        self.letter_axis.get(i).copied().flatten().map(usize::from)
    }

    /// Whether any axis has a travel limit (else E501 cannot happen).
    pub fn has_travel_limits(&self) -> bool {
        self.axes
            .iter()
            .any(|a| a.min_mm.is_finite() || a.max_mm.is_finite())
    }

    /// The highest cutting feed any axis allows (the control's clamp).
    pub fn max_feed_mm_per_min(&self) -> f64 {
        self.axes
            .iter()
            .map(|a| a.max_feed_mm_per_min)
            .fold(0.0, f64::max)
    }

    /// Bit mask (bit 0 = 'A') of the machine's axis letters.
    pub fn axis_letter_mask(&self) -> u32 {
        self.axes.iter().fold(0, |m, a| m | 1 << (a.letter - b'A'))
    }

    fn from_file(f: File) -> Result<Machine, MachineError> {
        if f.axes.is_empty() || f.axes.len() > MAX_AXES {
            return Err(MachineError(format!(
                "a machine has 1 to {MAX_AXES} axes, this one has {}",
                f.axes.len()
            )));
        }
        let mut m = Machine {
            name: f.name,
            axes: Vec::new(),
            letter_axis: [None; 26],
            start: Pos::default(),
            reference: [None; 4],
            work_offsets: [Pos::default(); WORK_SYSTEMS],
            tools: BTreeMap::new(),
            params: f.parameters,
            limits: f.limits,
            skip: Vec::new(),
            m_codes: BTreeMap::new(),
            motion: f.motion,
            m_macros: BTreeMap::new(),
            table_z_mm: f.table_z_mm,
            gcode_system: f.gcode_system,
        };
        if f.table_z_mm.is_some_and(|z| !z.is_finite()) {
            return Err(MachineError(
                "table_z_mm: the table's height is a finite number of mm".into(),
            ));
        }
        for (i, a) in f.axes.into_iter().enumerate() {
            m.add_axis(i, a)?;
        }
        m.start = m.pos_of(&f.start_mm, "start_mm")?;
        m.check_inside(&m.start, "start_mm")?;
        for (key, map) in &f.reference {
            let n = match key.as_str() {
                "p1" => 0,
                "p2" => 1,
                "p3" => 2,
                "p4" => 3,
                _ => {
                    return Err(MachineError(format!(
                        "reference.{key}: use p1, p2, p3 or p4"
                    )));
                }
            };
            m.reference[n] = Some(m.pos_of(map, &format!("reference.{key}"))?);
        }
        for (key, map) in &f.work_offsets {
            let n = work_system_index(key).ok_or_else(|| {
                MachineError(format!("work_offsets.{key}: use G54..G59 or G59.1..G59.9"))
            })?;
            m.work_offsets[n] = m.pos_of(map, &format!("work_offsets.{key}"))?;
        }
        for (key, tool) in f.tools {
            let n: u32 = key
                .parse()
                .map_err(|_| MachineError(format!("tools.{key}: a tool number is an integer")))?;
            if tool.tip > 9 {
                return Err(MachineError(format!(
                    "tools.{key}.tip: the tip direction is 0 to 9"
                )));
            }
            m.tools.insert(n, tool);
        }
        for (key, what) in f.m_codes {
            let n: u32 = key
                .parse()
                .ok()
                .filter(|n| *n < 1000)
                .ok_or_else(|| MachineError(format!("m_codes.{key}: an M code is 0 to 999")))?;
            m.m_codes.insert(n, what.into());
        }
        for (key, program) in f.m_macros {
            let n = m_macro_code(&key, &program)?;
            m.m_macros.insert(n, program.into());
        }
        for s in f.skip {
            let axis = m.letter_index(&s.axis, "skip.axis")?;
            m.skip.push(SkipTrigger {
                axis,
                at_mm: s.at_mm,
            });
        }
        m.check_params()?;
        Ok(m)
    }

    fn add_axis(&mut self, i: usize, a: FileAxis) -> Result<(), MachineError> {
        let letter = match a.letter.to_ascii_uppercase().as_bytes() {
            [l @ (b'X' | b'Y' | b'Z' | b'A' | b'B' | b'C')] => *l,
            _ => {
                return Err(MachineError(format!(
                    "axes[{i}].letter: use one of x y z a b c, not {:?}",
                    a.letter
                )));
            }
        };
        let slot = &mut self.letter_axis[usize::from(letter - b'A')];
        if slot.is_some() {
            return Err(MachineError(format!("axis {} is defined twice", a.letter)));
        }
        *slot = u8::try_from(i).ok();
        // No limit given: the axis travels without limit (no E501 on it).
        let (min_mm, max_mm) = (
            a.min_mm.unwrap_or(f64::NEG_INFINITY),
            a.max_mm.unwrap_or(f64::INFINITY),
        );
        let finite = [a.rapid_mm_per_min, a.max_feed_mm_per_min, a.accel_mm_s2];
        let given = [a.min_mm, a.max_mm];
        if finite.iter().any(|v| !v.is_finite())
            || given.iter().flatten().any(|v| !v.is_finite())
            || min_mm > max_mm
        {
            return Err(MachineError(format!(
                "axis {}: limits must be finite with min_mm <= max_mm",
                a.letter
            )));
        }
        if a.rapid_mm_per_min <= 0.0 || a.max_feed_mm_per_min <= 0.0 || a.accel_mm_s2 <= 0.0 {
            return Err(MachineError(format!(
                "axis {}: rates and acceleration must be positive",
                a.letter
            )));
        }
        let jerk_mm_s3 = a.jerk_mm_s3.unwrap_or(a.accel_mm_s2 / DEFAULT_JERK_TIME_S);
        let positive = [jerk_mm_s3, a.in_position_mm, a.in_position_rapid_mm];
        if positive.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(MachineError(format!(
                "axis {}: jerk_mm_s3, in_position_mm and in_position_rapid_mm must be positive",
                a.letter
            )));
        }
        // a/j is how long the axis takes to reach its acceleration, and the
        // `filter` profile's time constant: real machines take well under
        // a second.
        let ramp_s = a.accel_mm_s2 / jerk_mm_s3;
        if ramp_s.is_nan() || ramp_s > MAX_JERK_TIME_S {
            return Err(MachineError(format!(
                "axis {}: accel_mm_s2 / jerk_mm_s3 is {ramp_s} s, the time to reach the \
                 acceleration; it must be at most {MAX_JERK_TIME_S} s (raise the jerk)",
                a.letter
            )));
        }
        self.axes.push(Axis {
            letter,
            min_mm,
            max_mm,
            rapid_mm_per_min: a.rapid_mm_per_min,
            max_feed_mm_per_min: a.max_feed_mm_per_min,
            accel_mm_s2: a.accel_mm_s2,
            jerk_mm_s3,
            in_position_mm: a.in_position_mm,
            in_position_rapid_mm: a.in_position_rapid_mm,
        });
        Ok(())
    }

    fn letter_index(&self, key: &str, what: &str) -> Result<usize, MachineError> {
        let up = key.to_ascii_uppercase();
        match up.as_bytes() {
            [l] => self.axis_of(*l),
            _ => None,
        }
        .ok_or_else(|| MachineError(format!("{what}: the machine has no axis {key:?}")))
    }

    fn pos_of(&self, map: &AxisMap, what: &str) -> Result<Pos, MachineError> {
        let mut p = Pos::default();
        for (k, v) in map {
            if !v.is_finite() {
                return Err(MachineError(format!("{what}.{k} must be a finite number")));
            }
            p.set(self.letter_index(k, what)?, *v);
        }
        Ok(p)
    }

    fn check_inside(&self, p: &Pos, what: &str) -> Result<(), MachineError> {
        for (i, a) in self.axes.iter().enumerate() {
            let v = p.get(i);
            if v < a.min_mm || v > a.max_mm {
                return Err(MachineError(format!(
                    "{what}: {} = {v} is outside the travel limits",
                    char::from(a.letter)
                )));
            }
        }
        Ok(())
    }

    fn check_params(&self) -> Result<(), MachineError> {
        let p = &self.params;
        if p.g00_mode > 1 {
            return Err(MachineError("parameters.g00_mode is 0 or 1".into()));
        }
        if !(p.arc_tolerance_mm.is_finite() && p.arc_tolerance_mm > 0.0) {
            return Err(MachineError(
                "parameters.arc_tolerance_mm must be positive".into(),
            ));
        }
        if !(p.peck_return_mm.is_finite() && p.peck_return_mm >= 0.0) {
            return Err(MachineError(
                "parameters.peck_return_mm must be a length >= 0".into(),
            ));
        }
        if p.tapping_type > 1 {
            return Err(MachineError("parameters.tapping_type is 0 or 1".into()));
        }
        if p.shift_direction > 3 {
            return Err(MachineError("parameters.shift_direction is 0 to 3".into()));
        }
        if !(p.max_spindle_rpm.is_finite() && p.max_spindle_rpm >= 0.0) {
            return Err(MachineError(
                "parameters.max_spindle_rpm is a speed >= 0 (0: no limit)".into(),
            ));
        }
        if !(p.thread_chamfer_deg > 0.0 && p.thread_chamfer_deg < 90.0)
            || p.thread_chamfer_tenths > 99
        {
            return Err(MachineError(
                "parameters.thread_chamfer_tenths is 0..99 and thread_chamfer_deg is more than 0 and less than 90".into(),
            ));
        }
        if !(p.pocket_stepover_pct > 0.0 && p.pocket_stepover_pct <= 100.0) {
            return Err(MachineError(
                "parameters.pocket_stepover_pct is a percentage, more than 0 and at most 100"
                    .into(),
            ));
        }
        self.motion.check()?;
        // Every level may hold an open program file (64 KiB each): 50
        // levels keep memory bounded (Fanuc 0i allows 10).
        if self.limits.max_call_depth == 0 || self.limits.max_call_depth > 50 {
            return Err(MachineError("limits.max_call_depth is 1..50".into()));
        }
        Ok(())
    }
}

/// `G54` → 0 … `G59` → 5, `G59.1` → 6 … `G59.9` → 14.
pub fn work_system_index(name: &str) -> Option<usize> {
    match name.to_ascii_uppercase().as_str() {
        "G54" => Some(0),
        "G55" => Some(1),
        "G56" => Some(2),
        "G57" => Some(3),
        "G58" => Some(4),
        "G59" => Some(5),
        s => {
            let d = s.strip_prefix("G59.")?.parse::<usize>().ok()?;
            (1..=9).contains(&d).then_some(5 + d)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_machine_is_valid() {
        let m = Machine::from_toml(DEFAULT_MILL_TOML).unwrap();
        assert_eq!(m.axes.len(), 6);
        assert!(!m.has_travel_limits());
        assert_eq!(m.axis_of(b'Z'), Some(2));
        assert_eq!(m.reference[1].unwrap().get(0), 200.0);
    }

    #[test]
    fn the_embedded_haas_and_lathe_machines_are_valid() {
        let haas = Machine::from_toml(DEFAULT_HAAS_TOML).unwrap();
        assert_eq!(
            haas.m_codes.get(&31).map(|d| &**d),
            Some("chip conveyor forward")
        );
        assert!(Machine::from_toml(DEFAULT_LATHE_TOML).is_ok());
        let fl = Machine::from_toml(DEFAULT_FANUC_LATHE_TOML).unwrap();
        assert!(!fl.has_travel_limits());
        let tipped = format!("{DEFAULT_FANUC_LATHE_TOML}\n[tools.1]\ntip = 3\n");
        assert_eq!(
            Machine::from_toml(&tipped)
                .unwrap()
                .tools
                .get(&1)
                .map(|t| t.tip),
            Some(3)
        );
        let bad = tipped.replacen("[tools.1]\ntip = 3", "[tools.1]\ntip = 10", 1);
        assert!(Machine::from_toml(&bad).unwrap_err().0.contains("tip"));
    }

    /// The built-in machines invent no tools: their offset memory is empty,
    /// like a control whose offset page was never filled (issue 22).
    #[test]
    fn the_embedded_machines_have_empty_offset_memory() {
        for text in [
            DEFAULT_MILL_TOML,
            DEFAULT_HAAS_TOML,
            DEFAULT_LATHE_TOML,
            DEFAULT_FANUC_LATHE_TOML,
        ] {
            let m = Machine::from_toml(text).unwrap();
            assert!(m.tools.is_empty(), "{}: {:?}", m.name, m.tools);
        }
    }

    #[test]
    fn bad_files_are_explained() {
        let bad = DEFAULT_MILL_TOML.replace("letter = \"z\"", "letter = \"q\"");
        assert!(Machine::from_toml(&bad).unwrap_err().0.contains("letter"));
        let bad = DEFAULT_MILL_TOML.replace("G54 =", "G60 =");
        assert!(Machine::from_toml(&bad).unwrap_err().0.contains("G60"));
        assert_eq!(work_system_index("g59.9"), Some(14));
        assert_eq!(work_system_index("G59.0"), None);
    }

    #[test]
    fn gcode_system_is_a_b_or_c_and_defaults_to_a() {
        let fl = Machine::from_toml(DEFAULT_FANUC_LATHE_TOML).unwrap();
        assert_eq!(fl.gcode_system, GcodeSystem::A);
        for (text, sys) in [
            ("B", GcodeSystem::B),
            ("C", GcodeSystem::C),
            ("A", GcodeSystem::A),
        ] {
            let file = format!("gcode_system = \"{text}\"\n{DEFAULT_FANUC_LATHE_TOML}");
            assert_eq!(Machine::from_toml(&file).unwrap().gcode_system, sys);
        }
        // Lowercase, another letter, or a number: each says what to write.
        for bad in ["\"b\"", "\"D\"", "\"\""] {
            let file = format!("gcode_system = {bad}\n{DEFAULT_FANUC_LATHE_TOML}");
            let e = Machine::from_toml(&file).unwrap_err().0;
            assert!(e.contains("line 1") && e.contains("gcode_system: "), "{e}");
            assert!(e.contains("\"A\", \"B\" or \"C\""), "{e}");
        }
        let file = format!("gcode_system = 2\n{DEFAULT_FANUC_LATHE_TOML}");
        let e = Machine::from_toml(&file).unwrap_err().0;
        assert!(e.contains("gcode_system") && e.contains("line 1"), "{e}");
    }
}
