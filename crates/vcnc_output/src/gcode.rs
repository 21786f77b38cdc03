//! A flattened plain program: what the controller did, as G0/G1/G2/G3/G4,
//! T/M6, S/M3–M5 and M8/M9 that grbl and LinuxCNC run as they are.
//!
//! Every subprogram, repeat, cycle, transform and compensation is already
//! resolved in the events, so the output is one absolute block per event.
//! By default ([`Coords::Work`]) it is written the way a user runs it: in
//! the program's work coordinate systems, written out — the one in force at
//! the first move in the header (G54 if the program names none), a `G55`
//! line where the program changes it — and in the program's units (a
//! `G20`/`G21` line where it changes them), unless [`GcodeOptions::units`]
//! fixes them.
//!
//! ```text
//!   written = machine point − the work offset the MACHINE FILE gives that
//!             system (not one a G10 of the program wrote: the flattened
//!             program has no G10), in the output units
//!   G53 / reference legs (`machine_move` events): `G53 G0` to the machine point
//! ```
//!
//! So a controller whose work offsets equal the machine file's moves as the
//! original did, and a G53 retract stays a machine move whatever its
//! offsets. No move is invented: the program starts where the machine is.
//! [`Coords::Machine`] keeps the older form for comparisons: absolute
//! machine coordinates in mm after a rapid to the power-on position.
//!
//! Feed per revolution becomes feed per minute at the spindle speed in
//! force (grbl has no G95); G33 threads stay G33 with K (LinuxCNC); path
//! modes and the G31 skip become comments. An alarm ends the program with a
//! comment and M2, so the flattened program never does more than the
//! original.

use std::io::{self, Write};
use vcnc_core::events::work_system_name;
use vcnc_core::{
    ArcDir, EndCode, Event, Feed, Loc, Machine, Plane, Pos, Sink, SpindleDir, StopCode,
};

/// The coordinates a flattened program is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coords {
    /// The program's work coordinate systems, written out.
    Work,
    /// Absolute machine coordinates from the power-on position.
    Machine,
}

/// Length units of a flattened program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// Millimetres (G21).
    Mm,
    /// Inches (G20).
    Inch,
}

/// How a flattened program is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GcodeOptions {
    /// Work or machine coordinates.
    pub coords: Coords,
    /// Fixed output units; `None`: the program's own (mm under
    /// [`Coords::Machine`]).
    pub units: Option<Units>,
}

impl Default for GcodeOptions {
    fn default() -> GcodeOptions {
        GcodeOptions {
            coords: Coords::Work,
            units: None,
        }
    }
}

/// Writes a flattened G-code program.
pub struct GcodeSink<W: Write> {
    out: W,
    letters: Vec<char>,
    /// Bit i: axis i is written (linear axes always, a rotary axis once it
    /// has moved: 3-axis programs stay 3-axis for grbl).
    shown: u32,
    /// Bit i: axis i is linear (its lengths follow the units).
    linear: u32,
    pos: Pos,
    plane: Plane,
    feed: Option<f64>,
    per_rev: bool,
    rpm: f64,
    error: Option<io::Error>,
    opts: GcodeOptions,
    name: String,
    /// The machine file's work offsets, G54 first.
    work_offsets: Vec<Pos>,
    start: Pos,
    /// Work system in force (index into `work_offsets`).
    system: u8,
    /// Whether lengths are written in inches.
    inch: bool,
    /// Lines before the header, which waits for the first move (so that it
    /// names the work system and units that move is in).
    before: Option<String>,
    /// A `machine_move` marker: motion events of this block up to the one
    /// ending at this point are written as `G53` moves of these axes.
    machine_move: Option<(Loc, Pos, u8)>,
    /// Bit i: the program has not placed axis i in program coordinates
    /// since power-on or since a `G53` move put it (`placed` events say
    /// when it does), so work-coordinate blocks leave it out unless they
    /// move it: the program starts where the machine is, and a G53 retract
    /// followed by an X Y move must not move Z back down on a machine whose
    /// work offsets differ from the machine file's.
    unplaced: u32,
}

/// How far the flattened program's chords may pass from a NURBS curve, mm.
const NURBS_CHORD_MM: f64 = 0.001;

const MM_PER_INCH: f64 = 25.4;

impl<W: Write> GcodeSink<W> {
    /// A sink writing the older form: absolute machine coordinates in mm
    /// after a rapid to the power-on position ([`Coords::Machine`]).
    pub fn new(out: W, machine: &Machine) -> GcodeSink<W> {
        GcodeSink::with_options(
            out,
            machine,
            GcodeOptions {
                coords: Coords::Machine,
                units: None,
            },
        )
    }

    /// A sink writing as `opts` says; the header comes with the first move.
    pub fn with_options(out: W, machine: &Machine, opts: GcodeOptions) -> GcodeSink<W> {
        let mask = |f: &dyn Fn(u8) -> bool| {
            machine
                .axes
                .iter()
                .enumerate()
                .filter(|(_, a)| f(a.letter))
                .fold(0, |m, (i, _)| m | 1 << i)
        };
        let xyz = mask(&|l| matches!(l, b'X' | b'Y' | b'Z'));
        GcodeSink {
            out,
            letters: machine.axes.iter().map(|a| char::from(a.letter)).collect(),
            shown: xyz,
            linear: xyz,
            pos: machine.start,
            plane: Plane::Xy,
            feed: None,
            per_rev: false,
            rpm: 0.0,
            error: None,
            opts,
            name: comment_text(&machine.name),
            work_offsets: machine.work_offsets.to_vec(),
            start: machine.start,
            system: 0,
            inch: opts.units == Some(Units::Inch),
            before: Some(String::new()),
            machine_move: None,
            unplaced: (1 << machine.axes.len()) - 1,
        }
    }

    /// The writer, after [`Sink::finish`].
    pub fn into_inner(self) -> W {
        self.out
    }

    /// The machine coordinates a written value is measured from.
    fn offset(&self) -> Pos {
        match self.opts.coords {
            Coords::Machine => Pos::default(),
            Coords::Work => self
                .work_offsets
                .get(usize::from(self.system))
                .copied()
                .unwrap_or_default(),
        }
    }

    /// A length in the output units.
    fn len(&self, mm: f64) -> f64 {
        if self.inch { mm / MM_PER_INCH } else { mm }
    }

    fn units_name(&self) -> &'static str {
        if self.inch { "in" } else { "mm" }
    }

    /// The header: where and in what the program is written.
    fn header(&mut self) -> String {
        let units = if self.inch { "G20" } else { "G21" };
        match self.opts.coords {
            Coords::Machine => {
                let start = self.start;
                let to = self.axes(&start, Pos::default());
                format!(
                    "(flattened by vcnc for {}: absolute machine coordinates, {})\n{units} G90 G94 G17\nG0{to} (power-on position)\n",
                    self.name,
                    self.units_name()
                )
            }
            Coords::Work => {
                let wcs = work_system_name(self.system);
                let off = self.offset();
                let off_text = self.axes(&off, Pos::default());
                format!(
                    "(flattened by vcnc for {}: absolute work coordinates in {wcs}, {})\n({wcs} is{off_text} in the machine file: set the machine's work offsets alike)\n{units} G90 G94 G17 {wcs}\n",
                    self.name,
                    self.units_name()
                )
            }
        }
    }

    /// The axis words of `to` measured from `from`, in the output units:
    /// every shown axis in `mask`.
    fn words(&mut self, to: &Pos, from: Pos, mask: u32) -> String {
        let mut s = String::new();
        for (i, l) in self.letters.iter().enumerate() {
            if to.get(i) != 0.0 {
                self.shown |= 1 << i;
            }
            if self.shown & mask & (1 << i) != 0 {
                let v = to.get(i) - from.get(i);
                let v = if self.linear & (1 << i) != 0 {
                    self.len(v)
                } else {
                    v
                };
                s.push_str(&format!(" {l}{}", length(v)));
            }
        }
        s
    }

    /// Every shown axis of `to` measured from `from` (headers, comments).
    fn axes(&mut self, to: &Pos, from: Pos) -> String {
        self.words(to, from, u32::MAX)
    }

    /// The axis words of a move's end: in machine coordinates every axis;
    /// in work coordinates the axes whose place is known in them, and any
    /// axis the move moves.
    fn target(&mut self, to: &Pos) -> String {
        let off = self.offset();
        if self.opts.coords == Coords::Machine {
            return self.axes(to, off);
        }
        // An axis the move moves although the block does not name it (a
        // rotation turns X into X and Y) is written too.
        let moved = (0..self.letters.len())
            .filter(|i| to.get(*i) != self.pos.get(*i))
            .fold(0u32, |m, i| m | 1 << i);
        self.unplaced &= !moved;
        self.words(to, off, !self.unplaced | moved)
    }

    /// The F word (and a feed-mode switch) a move needs. Feed per rev
    /// becomes feed per minute at the speed in force; with the spindle
    /// stopped it stays G95 (LinuxCNC then waits for the spindle, as the
    /// controller would; grbl has no G95).
    fn feed_word(&mut self, f: Feed) -> String {
        let (value, per_rev) = match f {
            Feed::PerMin(v) => (v, false),
            Feed::PerRev(v) if self.rpm > 0.0 => (v * self.rpm, false),
            Feed::PerRev(v) => (v, true),
        };
        let value = self.len(value);
        let mode = if per_rev != self.per_rev {
            if per_rev { " G95" } else { " G94" }
        } else {
            ""
        };
        if mode.is_empty() && self.feed == Some(value) {
            return String::new();
        }
        self.per_rev = per_rev;
        self.feed = Some(value);
        format!("{mode} F{}", fmt(value))
    }

    fn arc(&mut self, to: &Pos, center: &Pos, plane: Plane, dir: ArcDir, feed: Feed) -> String {
        // An arc shorter than the written precision would read back as a
        // full circle (its end the same as its start): a line then.
        let collapsed = (0..self.letters.len())
            .all(|i| length(self.len(to.get(i))) == length(self.len(self.pos.get(i))));
        let full = (0..self.letters.len()).all(|i| (to.get(i) - self.pos.get(i)).abs() < 1e-9);
        if collapsed && !full {
            return format!("G1{}{}", self.target(to), self.feed_word(feed));
        }
        let mut s = String::new();
        if plane != self.plane {
            self.plane = plane;
            s.push_str(match plane {
                Plane::Xy => "G17\n",
                Plane::Zx => "G18\n",
                Plane::Yz => "G19\n",
            });
        }
        s.push_str(if dir == ArcDir::Cw { "G2" } else { "G3" });
        s.push_str(&self.target(to));
        for (i, l) in self.letters.iter().enumerate() {
            let offset = match l {
                'X' => 'I',
                'Y' => 'J',
                'Z' => 'K',
                _ => continue,
            };
            let d = center.get(i) - self.pos.get(i);
            if d != 0.0 {
                s.push_str(&format!(" {offset}{}", length(self.len(d))));
            }
        }
        s.push_str(&self.feed_word(feed));
        s
    }

    /// The axes of this motion event if it goes to a machine point (after
    /// a `machine_move` marker of its block, which it consumes when it
    /// reaches the marker's point).
    fn machine_point_axes(&mut self, loc: &Loc, to: &Pos) -> Option<u8> {
        match &self.machine_move {
            Some((at, end, axes)) if at == loc && self.opts.coords == Coords::Work => {
                let axes = *axes;
                if end == to {
                    self.machine_move = None;
                }
                Some(axes)
            }
            Some(_) => {
                self.machine_move = None;
                None
            }
            None => None,
        }
    }

    /// A block of a move to a machine point: `G53` with the machine
    /// coordinates of the axes the program commanded.
    fn machine_block(&mut self, g: &str, to: &Pos, axes: u8, tail: &str) -> String {
        let mask = u32::from(axes);
        self.unplaced |= mask;
        let shown = self.shown;
        self.shown |= mask;
        let words = self.words(to, Pos::default(), mask);
        self.shown = shown | (self.shown & !mask);
        format!("G53 {g}{words}{tail}")
    }

    /// A work system or units change: a line in work coordinates (none
    /// before the header, which states what is in force at the first move).
    fn mode_change(&mut self, event: &Event) -> Option<String> {
        if self.opts.coords == Coords::Machine {
            return None;
        }
        let line = match event {
            Event::WorkSystem { system, .. } => {
                let s = system.unwrap_or(0);
                if s == self.system {
                    return None;
                }
                self.system = s;
                work_system_name(s)
            }
            Event::Units { inch, .. } => {
                if self.opts.units.is_some() || *inch == self.inch {
                    return None;
                }
                self.inch = *inch;
                // F is a number in the new units: written again.
                self.feed = None;
                (if *inch { "G20" } else { "G21" }).to_string()
            }
            _ => return None,
        };
        self.before.is_none().then_some(line)
    }

    fn block(&mut self, event: &Event) -> Option<String> {
        Some(match event {
            Event::Rapid {
                loc,
                to,
                exact_stop,
            } => match self.machine_point_axes(loc, to) {
                Some(axes) => self.machine_block("G0", to, axes, g09(*exact_stop)),
                None => format!("G0{}{}", self.target(to), g09(*exact_stop)),
            },
            Event::Feed {
                loc,
                to,
                feed,
                exact_stop,
            } => {
                let f = self.feed_word(*feed);
                match self.machine_point_axes(loc, to) {
                    Some(axes) => {
                        self.machine_block("G1", to, axes, &format!("{f}{}", g09(*exact_stop)))
                    }
                    None => format!("G1{}{f}{}", self.target(to), g09(*exact_stop)),
                }
            }
            Event::Arc {
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => self.arc(to, center, *plane, *dir, *feed),
            Event::Thread { to, lead_mm, .. } => {
                format!("G33{} K{}", self.target(to), fmt(self.len(*lead_mm)))
            }
            Event::Skip {
                to,
                feed,
                triggered,
                ..
            } => {
                format!(
                    "(G31 skip, signal {})\nG1{}{}",
                    if *triggered { "fired" } else { "not fired" },
                    self.target(to),
                    self.feed_word(*feed)
                )
            }
            Event::Dwell { seconds, .. } => format!("G4 P{}", fmt(*seconds)),
            Event::ToolChange { tool, .. } => format!("T{tool} M6"),
            Event::Spindle { dir, rpm, .. } => {
                self.rpm = *rpm;
                match dir {
                    SpindleDir::Cw => format!("M3 S{}", fmt(*rpm)),
                    SpindleDir::Ccw => format!("M4 S{}", fmt(*rpm)),
                    SpindleDir::Stop => "M5".into(),
                    SpindleDir::Orient => "M5 (M19 spindle orientation)".into(),
                }
            }
            Event::Coolant { on, .. } => (if *on { "M8" } else { "M9" }).into(),
            Event::PathMode { mode, .. } => {
                format!("(path mode {})", crate::jsonl::path_mode(*mode))
            }
            Event::Stop { code, .. } => (if *code == StopCode::M01 { "M1" } else { "M0" }).into(),
            Event::HighSpeed { on, p, .. } => {
                format!(
                    "(G05 P{p}: high-speed mode {})",
                    if *on { "on" } else { "off" }
                )
            }
            Event::End { code, .. } => (if *code == EndCode::M30 { "M30" } else { "M2" }).into(),
            // The cycle's moves follow as plain G0/G1: the hole is a comment.
            Event::Hole { cycle, at, .. } => {
                let off = self.offset();
                format!("({} hole at{})", cycle.as_str(), self.axes(at, off))
            }
            // M0 waits for cycle start on grbl and LinuxCNC alike.
            Event::Wait { reason, .. } => format!("M0 (wait: {})", reason.as_str()),
            Event::Junction { blend, .. } => {
                format!("(junction {})", if *blend { "blends" } else { "stops" })
            }
            Event::Smoothing {
                on, tolerance_mm, ..
            } => {
                if *on {
                    format!("(G05.1 path smoothing on, E{})", fmt(*tolerance_mm))
                } else {
                    "(G05.1 path smoothing off)".into()
                }
            }
            // grbl and LinuxCNC have no NURBS: chords within 1 µm of the curve.
            Event::Nurbs { curve, feed, .. } => {
                let mut out = format!("(G06.2 NURBS of order {}, as chords)", curve.order);
                let f = self.feed_word(*feed);
                for (i, p) in curve.flatten(NURBS_CHORD_MM).iter().enumerate() {
                    out.push_str(&format!(
                        "\nG1{}{}",
                        self.target(p),
                        if i == 0 { &f } else { "" }
                    ));
                }
                out
            }
            // Positions are resolved already: the frame is a comment.
            Event::Frame { frame, .. } => {
                format!(
                    "(program origin at machine{})",
                    self.axes(&frame.origin, Pos::default())
                )
            }
            Event::WorkSystem { .. } | Event::Units { .. } => return self.mode_change(event),
            Event::MachineMove { loc, to, axes } => {
                self.machine_move = Some((loc.clone(), *to, *axes));
                return None;
            }
            Event::Placed { axes, .. } => {
                self.unplaced &= !u32::from(*axes);
                return None;
            }
            // The machine builder's codes mean nothing to grbl or LinuxCNC.
            Event::Aux {
                code, description, ..
            } => format!("(M{code}: {})", comment_text(description)),
            // A macro's message: a stop waits for cycle start (M0).
            Event::Message { text, stop, .. } => {
                let text = comment_text(text);
                if *stop {
                    format!("M0 (message: {text})")
                } else {
                    format!("(message: {text})")
                }
            }
            Event::Warning(d) => format!(
                "(warning {} line {}: {})",
                d.code.as_str(),
                d.line,
                comment_text(&d.message)
            ),
            Event::Alarm(d) => format!(
                "(ALARM {} line {}: {})\nM2",
                d.code.as_str(),
                d.line,
                comment_text(&d.message)
            ),
            _ => return None,
        })
    }

    /// Writes `text` as a line, after the header once a move has come.
    fn write_line(&mut self, text: &str, moves: bool) {
        if let Some(before) = &mut self.before {
            if !moves {
                before.push_str(text);
                before.push('\n');
                return;
            }
            let before = std::mem::take(before);
            self.before = None;
            let head = self.header();
            self.error = self.out.write_all(head.as_bytes()).err();
            if self.error.is_none() {
                self.error = self.out.write_all(before.as_bytes()).err();
            }
        }
        if self.error.is_none() {
            self.error = writeln!(self.out, "{text}").err();
        }
    }
}

/// Text that can stand inside a `( )` comment on one line: no parentheses
/// (they would end or nest it) and no control characters (a newline would
/// make the rest a block).
fn comment_text(text: &str) -> String {
    text.chars()
        .filter(|c| !matches!(c, '(' | ')') && !c.is_control())
        .collect()
}

/// A comment for a G09 exact stop (plain G-code has no one-shot form).
fn g09(exact_stop: bool) -> &'static str {
    if exact_stop { " (G09 exact stop)" } else { "" }
}

/// A length: six decimals (a nanometre, so that a tiny arc keeps its
/// end apart from its start) without trailing zeros, always with a decimal
/// point (`5.`), so that a Fanuc-style reader, where `X5` is 5 µm, reads
/// the same millimetres as grbl and LinuxCNC.
fn length(v: f64) -> String {
    let s = decimals(v, 6);
    if s.contains('.') { s } else { s + "." }
}

/// Four decimals without trailing zeros (feeds, speeds, times): `5.5`,
/// `-0.0125`, `10`.
fn fmt(v: f64) -> String {
    decimals(v, 4)
}

fn decimals(v: f64, n: usize) -> String {
    let s = format!("{:.n$}", crate::num::round6(v));
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

impl<W: Write> Sink for GcodeSink<W> {
    fn event(&mut self, event: &Event) {
        if self.error.is_some() {
            return;
        }
        let end = event.motion_end();
        if let Some(text) = self.block(event) {
            self.write_line(&text, end.is_some());
        }
        if let Some(to) = end {
            self.pos = to;
        }
    }

    fn is_done(&self) -> bool {
        self.error.is_some()
    }

    fn finish(&mut self) -> io::Result<()> {
        // A program without a move still gets its header.
        if self.before.is_some() && self.error.is_none() {
            let before = self.before.take().unwrap_or_default();
            let head = self.header();
            self.error = self
                .out
                .write_all(head.as_bytes())
                .and_then(|()| self.out.write_all(before.as_bytes()))
                .err();
        }
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_core::{Loc, machine::DEFAULT_MILL_TOML};

    fn flatten(events: &[Event]) -> String {
        let machine = Machine::from_toml(DEFAULT_MILL_TOML).expect("built-in machine");
        let mut sink = GcodeSink::new(Vec::new(), &machine);
        for e in events {
            sink.event(e);
        }
        sink.finish().expect("written to memory");
        String::from_utf8(sink.into_inner()).expect("utf-8")
    }

    fn pos(x: f64, y: f64) -> Pos {
        let mut p = Pos::default();
        p.set(0, x);
        p.set(1, y);
        p
    }

    /// A rapid to (10, 0), then a ccw arc about the origin to (10, `y`).
    fn arc_from_10_0(y: f64) -> [Event; 2] {
        let start = Event::Rapid {
            loc: Loc::default(),
            to: pos(10.0, 0.0),
            exact_stop: false,
        };
        let arc = Event::Arc {
            loc: Loc::default(),
            to: pos(10.0, y),
            center: pos(0.0, 0.0),
            plane: Plane::Xy,
            dir: ArcDir::Ccw,
            feed: Feed::PerMin(100.0),
            exact_stop: false,
        };
        [start, arc]
    }

    #[test]
    fn an_arc_shorter_than_the_precision_is_a_line_not_a_full_circle() {
        // From (10, 0) 30 nm along a circle of radius 10: both ends write
        // as X10. Y0, which a reader would take for a full circle.
        let text = flatten(&arc_from_10_0(3e-8));
        let last = text.lines().last().unwrap_or_default();
        assert!(last.starts_with("G1 X10. Y0."), "{text}");
    }

    #[test]
    fn a_micron_arc_keeps_its_end_apart_from_its_start() {
        // 0.5 µm of arc: six decimals tell the ends apart (four would not).
        let text = flatten(&arc_from_10_0(5e-4));
        assert!(text.contains("G3 X10. Y0.0005"), "{text}");
    }

    #[test]
    fn comments_hold_no_parentheses_or_line_breaks() {
        assert_eq!(comment_text("pallet (A)\nclamp\tnow"), "pallet Aclampnow");
    }
}
