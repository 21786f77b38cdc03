//! A flattened plain program: what the controller did, as G0/G1/G2/G3/G4,
//! T/M6, S/M3–M5 and M8/M9 that grbl and LinuxCNC run as they are.
//!
//! Every offset, unit, subprogram and repeat is already resolved in the
//! events, so the output is one absolute, metric block per event, written in
//! the machine coordinates of the source machine (documented in the
//! program's header comment). Feed per revolution becomes feed per minute at
//! the spindle speed in force (grbl has no G95); G33 threads stay G33 with K
//! (LinuxCNC); path modes and the G31 skip become comments. An alarm ends
//! the program with a comment and M2, so the flattened program never does
//! more than the original.

use std::io::{self, Write};
use vcnc_core::{ArcDir, EndCode, Event, Feed, Machine, Plane, Pos, Sink, SpindleDir, StopCode};

/// Writes a flattened G-code program.
pub struct GcodeSink<W: Write> {
    out: W,
    letters: Vec<char>,
    /// Bit i: axis i is written (linear axes always, a rotary axis once it
    /// has moved: 3-axis programs stay 3-axis for grbl).
    shown: u32,
    pos: Pos,
    plane: Plane,
    feed: Option<f64>,
    per_rev: bool,
    rpm: f64,
    error: Option<io::Error>,
}

/// How far the flattened program's chords may pass from a NURBS curve, mm.
const NURBS_CHORD_MM: f64 = 0.001;

impl<W: Write> GcodeSink<W> {
    /// A sink writing the header and then one block per event.
    pub fn new(out: W, machine: &Machine) -> GcodeSink<W> {
        let name = comment_text(&machine.name);
        let mut sink = GcodeSink {
            out,
            letters: machine.axes.iter().map(|a| char::from(a.letter)).collect(),
            shown: machine
                .axes
                .iter()
                .enumerate()
                .filter(|(_, a)| matches!(a.letter, b'X' | b'Y' | b'Z'))
                .fold(0, |m, (i, _)| m | 1 << i),
            pos: machine.start,
            plane: Plane::Xy,
            feed: None,
            per_rev: false,
            rpm: 0.0,
            error: None,
        };
        // The program starts where the source machine starts, so the first
        // move (a cut, an arc) begins where the events say it does.
        let header = format!(
            "(flattened by vcnc for {name}: absolute machine coordinates, mm)\nG21 G90 G94 G17\nG0{} (power-on position)\n",
            sink.axes(&machine.start)
        );
        sink.error = sink.out.write_all(header.as_bytes()).err();
        sink
    }

    /// The writer, after [`Sink::finish`].
    pub fn into_inner(self) -> W {
        self.out
    }

    fn axes(&mut self, to: &Pos) -> String {
        let mut s = String::new();
        for (i, l) in self.letters.iter().enumerate() {
            if to.get(i) != 0.0 {
                self.shown |= 1 << i;
            }
            if self.shown & (1 << i) != 0 {
                s.push_str(&format!(" {l}{}", length(to.get(i))));
            }
        }
        s
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
        let collapsed =
            (0..self.letters.len()).all(|i| length(to.get(i)) == length(self.pos.get(i)));
        let full = (0..self.letters.len()).all(|i| (to.get(i) - self.pos.get(i)).abs() < 1e-9);
        if collapsed && !full {
            return format!("G1{}{}", self.axes(to), self.feed_word(feed));
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
        s.push_str(&self.axes(to));
        for (i, l) in self.letters.iter().enumerate() {
            let offset = match l {
                'X' => 'I',
                'Y' => 'J',
                'Z' => 'K',
                _ => continue,
            };
            let d = center.get(i) - self.pos.get(i);
            if d != 0.0 {
                s.push_str(&format!(" {offset}{}", length(d)));
            }
        }
        s.push_str(&self.feed_word(feed));
        s
    }

    fn block(&mut self, event: &Event) -> Option<String> {
        Some(match event {
            Event::Rapid { to, exact_stop, .. } => {
                format!("G0{}{}", self.axes(to), g09(*exact_stop))
            }
            Event::Feed {
                to,
                feed,
                exact_stop,
                ..
            } => {
                format!(
                    "G1{}{}{}",
                    self.axes(to),
                    self.feed_word(*feed),
                    g09(*exact_stop)
                )
            }
            Event::Arc {
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => self.arc(to, center, *plane, *dir, *feed),
            Event::Thread { to, lead_mm, .. } => format!("G33{} K{}", self.axes(to), fmt(*lead_mm)),
            Event::Skip {
                to,
                feed,
                triggered,
                ..
            } => {
                format!(
                    "(G31 skip, signal {})\nG1{}{}",
                    if *triggered { "fired" } else { "not fired" },
                    self.axes(to),
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
                format!("({} hole at{})", cycle.as_str(), self.axes(at))
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
                        self.axes(p),
                        if i == 0 { &f } else { "" }
                    ));
                }
                out
            }
            // Positions are machine coordinates already: the frame is a comment.
            Event::Frame { frame, .. } => {
                format!("(program origin at{})", self.axes(&frame.origin))
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
        if let Some(Err(e)) = self.block(event).map(|text| writeln!(self.out, "{text}")) {
            self.error = Some(e);
        }
        if let Some(to) = event.motion_end() {
            self.pos = to;
        }
    }

    fn is_done(&self) -> bool {
        self.error.is_some()
    }

    fn finish(&mut self) -> io::Result<()> {
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
