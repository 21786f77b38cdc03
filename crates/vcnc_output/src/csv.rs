//! CSV: one row per event with a fixed header, for spreadsheets and quick
//! plots. Columns that do not apply to an event are empty.
//!
//! A rotary axis' cells (A, B, C) stay empty until it has moved, as the
//! JSON events leave it out.
//!
//! Header: `type,line,file,<axes>,<center_axes>,plane,dir,feed,feed_per_rev,
//! lead_mm,seconds,tool,spindle,rpm,on,mode,code,column,message,triggered,
//! exact_stop,p,surface_m_per_min,help,linear,<tool_offset_axes>,tolerance_mm` (those
//! after `message` were added later: columns are only ever appended). A
//! `frame` row has its origin in the axis columns, its linear part as nine
//! space-separated numbers (rows x, y, z) in `linear` and the tool length
//! offset in `tool_offset_<axis>`. A `hole` row has its centre at the Z
//! point in the axis columns and its cycle (`G81`) in `code`; a `wait` row
//! its reason in `mode`; a `junction` row whether it blends in `on`; an
//! `aux` row its M code in `code` and its description in `message`; a
//! `warning` row is laid out like an `alarm` row; a `smoothing` row `on`
//! and its `tolerance_mm` (the last column, appended after the tool
//! offsets); a `nurbs` row its end point, feed and order in `p` (its
//! definition is in the JSON-lines output).

use crate::jsonl::{path_mode, spindle_dir};
use crate::num::push_f64;
use std::io::{self, Write};
use vcnc_core::{ArcDir, Event, Feed, Machine, Pos, Sink};

/// Columns appended after `message` (then one `tool_offset_<axis>` per axis).
const EXTRA: [&str; 6] = [
    "triggered",
    "exact_stop",
    "p",
    "surface_m_per_min",
    "help",
    "linear",
];

const TAIL: [&str; 13] = [
    "plane",
    "dir",
    "feed",
    "feed_per_rev",
    "lead_mm",
    "seconds",
    "tool",
    "spindle",
    "rpm",
    "on",
    "mode",
    "code",
    "column",
];

/// Writes events as CSV rows.
pub struct CsvSink<W: Write> {
    out: W,
    n_axes: usize,
    /// Bit i: axis i is written (linear axes always, a rotary one once it
    /// has moved; its cells stay empty before).
    shown: u32,
    row: Vec<String>,
    buf: Vec<u8>,
    error: Option<io::Error>,
}

impl<W: Write> CsvSink<W> {
    /// A sink writing the header and then one row per event.
    pub fn new(mut out: W, machine: &Machine) -> CsvSink<W> {
        let letters: Vec<char> = machine
            .axes
            .iter()
            .map(|a| char::from(a.letter.to_ascii_lowercase()))
            .collect();
        let mut header = vec!["type".to_string(), "line".into(), "file".into()];
        header.extend(letters.iter().map(|l| l.to_string()));
        header.extend(letters.iter().map(|l| format!("center_{l}")));
        header.extend(TAIL.iter().map(|s| s.to_string()));
        header.push("message".into());
        header.extend(EXTRA.iter().map(|s| s.to_string()));
        header.extend(letters.iter().map(|l| format!("tool_offset_{l}")));
        header.push("tolerance_mm".into());
        let error = writeln!(out, "{}", header.join(",")).err();
        let cols = header.len();
        let shown = letters
            .iter()
            .enumerate()
            .filter(|(_, l)| matches!(l, 'x' | 'y' | 'z'))
            .fold(0, |m, (i, _)| m | 1 << i);
        CsvSink {
            out,
            shown,
            n_axes: letters.len(),
            row: vec![String::new(); cols],
            buf: Vec::new(),
            error,
        }
    }

    /// The writer, after [`Sink::finish`].
    pub fn into_inner(self) -> W {
        self.out
    }

    fn set(&mut self, col: &str, v: String) {
        let base = 3 + 2 * self.n_axes;
        let i = match col {
            "type" => 0,
            "line" => 1,
            "file" => 2,
            "message" => base + TAIL.len(),
            "tolerance_mm" => self.row.len() - 1,
            _ if EXTRA.contains(&col) => {
                base + TAIL.len() + 1 + EXTRA.iter().position(|c| *c == col).unwrap_or(0)
            }
            _ => TAIL.iter().position(|c| *c == col).map_or(0, |k| base + k),
        };
        self.row[i] = v;
    }

    fn num(&mut self, v: f64) -> String {
        self.buf.clear();
        push_f64(&mut self.buf, v);
        String::from_utf8_lossy(&self.buf).into_owned()
    }

    fn pos(&mut self, p: &Pos, offset: usize) {
        for i in 0..self.n_axes {
            if p.get(i) != 0.0 {
                self.shown |= 1 << i;
            }
            if self.shown & (1 << i) != 0 {
                let v = self.num(p.get(i));
                self.row[3 + offset + i] = v;
            }
        }
    }

    fn feed(&mut self, f: Feed) {
        match f {
            Feed::PerMin(v) => {
                let s = self.num(v);
                self.set("feed", s);
            }
            Feed::PerRev(v) => {
                let s = self.num(v);
                self.set("feed_per_rev", s);
            }
        }
    }
}

fn quote(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

impl<W: Write> Sink for CsvSink<W> {
    fn event(&mut self, event: &Event) {
        if self.error.is_some() {
            return;
        }
        self.row.iter_mut().for_each(String::clear);
        let (kind, loc) = (event.kind(), event.loc());
        self.set("type", kind.to_string());
        if let Some(loc) = loc {
            self.set("line", loc.line.to_string());
            self.set("file", loc.file.as_deref().map(quote).unwrap_or_default());
        }
        match event {
            Event::Rapid {
                exact_stop: true, ..
            }
            | Event::Feed {
                exact_stop: true, ..
            }
            | Event::Arc {
                exact_stop: true, ..
            } => {
                self.set("exact_stop", "true".into());
            }
            Event::Skip { triggered, .. } => self.set("triggered", triggered.to_string()),
            Event::HighSpeed { p, .. } => self.set("p", p.to_string()),
            Event::Spindle {
                surface_m_per_min: Some(v),
                ..
            } => {
                let s = self.num(*v);
                self.set("surface_m_per_min", s);
            }
            _ => {}
        }
        match event {
            Event::Rapid { to, .. } => self.pos(to, 0),
            Event::Feed { to, feed, .. } | Event::Skip { to, feed, .. } => {
                self.pos(to, 0);
                self.feed(*feed);
            }
            Event::Arc {
                to,
                center,
                plane,
                dir,
                feed,
                ..
            } => {
                self.pos(to, 0);
                self.pos(center, self.n_axes);
                self.set("plane", plane.as_str().into());
                self.set("dir", if *dir == ArcDir::Cw { "cw" } else { "ccw" }.into());
                self.feed(*feed);
            }
            Event::Thread { to, lead_mm, .. } => {
                self.pos(to, 0);
                let s = self.num(*lead_mm);
                self.set("lead_mm", s);
            }
            Event::Dwell { seconds, .. } => {
                let s = self.num(*seconds);
                self.set("seconds", s);
            }
            Event::ToolChange { tool, .. } => self.set("tool", tool.to_string()),
            Event::Spindle { dir, rpm, .. } => {
                self.set("spindle", spindle_dir(*dir).into());
                let s = self.num(*rpm);
                self.set("rpm", s);
            }
            Event::Coolant { on, .. } => self.set("on", on.to_string()),
            Event::PathMode { mode, .. } => self.set("mode", path_mode(*mode).into()),
            Event::HighSpeed { on, .. } => self.set("on", on.to_string()),
            Event::Stop { code, .. } => self.set("code", code.as_str().into()),
            Event::End { code, .. } => self.set("code", code.as_str().into()),
            Event::Hole { cycle, at, .. } => {
                self.pos(at, 0);
                self.set("code", cycle.as_str().into());
            }
            Event::Wait { reason, .. } => self.set("mode", reason.as_str().into()),
            Event::Junction { blend, .. } => self.set("on", blend.to_string()),
            Event::Smoothing {
                on, tolerance_mm, ..
            } => {
                self.set("on", on.to_string());
                if *on {
                    let t = self.num(*tolerance_mm);
                    self.set("tolerance_mm", t);
                }
            }
            Event::Nurbs { curve, feed, .. } => {
                if let Some(end) = curve.points.last() {
                    self.pos(end, 0);
                }
                self.feed(*feed);
                self.set("p", curve.order.to_string());
            }
            Event::Contour { to, arc, .. } => {
                self.pos(to, 0);
                if let Some((center, plane, dir)) = arc {
                    self.pos(center, self.n_axes);
                    self.set("plane", plane.as_str().into());
                    self.set("dir", if *dir == ArcDir::Cw { "cw" } else { "ccw" }.into());
                }
            }
            Event::Frame { frame, .. } => {
                self.pos(&frame.origin, 0);
                if let Some(m) = &frame.linear {
                    let cells: Vec<String> = m.iter().flatten().map(|v| self.num(*v)).collect();
                    self.set("linear", cells.join(" "));
                }
                if frame.tool_offset != Pos::default() {
                    let offset = 3 + 2 * self.n_axes + TAIL.len() + 1 + EXTRA.len() - 3;
                    self.pos(&frame.tool_offset, offset);
                }
            }
            Event::Aux {
                code, description, ..
            } => {
                self.set("code", format!("M{code}"));
                self.set("message", quote(description));
            }
            Event::Message { text, stop, .. } => {
                self.set("on", stop.to_string());
                self.set("message", quote(text));
            }
            Event::UnsetVariables { variables, .. } => {
                let names: Vec<String> = variables
                    .iter()
                    .map(|v| format!("{}@{}", v.name, v.line))
                    .collect();
                self.set("message", quote(&names.join(" ")));
            }
            Event::Alarm(d) | Event::Warning(d) => {
                self.set("line", d.line.to_string());
                self.set("file", d.file.as_deref().map(quote).unwrap_or_default());
                self.set("code", d.code.as_str().into());
                self.set("column", d.column.to_string());
                self.set("message", quote(&d.message));
                self.set("help", quote(&d.help));
            }
            _ => {}
        }
        if let Err(e) = writeln!(self.out, "{}", self.row.join(",")) {
            self.error = Some(e);
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
