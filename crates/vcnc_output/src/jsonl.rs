//! The JSON-lines event format: the public contract of `vcnc run --format
//! jsonl`, documented in `docs/events.md`.
//!
//! Hand-written rather than serde-derived because the field order, the
//! rounding and the omission of default fields (`exact_stop`, `file`) are
//! part of the contract, and because this is the hot path of `vcnc run`
//! (millions of events per second): one reused buffer, no allocation per
//! event.

use crate::num::{Recent, push_f64, push_json_str, push_u64};
use std::io::{self, Write};
use vcnc_core::events::MAX_AXES;
use vcnc_core::{ArcDir, Event, Feed, FrameInfo, Loc, Machine, PathMode, Pos, Sink, SpindleDir};

/// Writes one JSON object per event.
pub struct JsonlSink<W: Write> {
    out: W,
    axes: EventAxes,
    buf: Vec<u8>,
    error: Option<io::Error>,
}

/// The axes an event lists: the linear axes always, a rotary axis (A, B,
/// C) from the first position where it is away from 0 on, so that a 3-axis
/// program reads the same on a machine that also has rotary axes. It also
/// keeps the text of each axis's last coordinate and of the last feed,
/// which the next event often repeats.
#[derive(Debug, Clone)]
pub struct EventAxes {
    letters: Vec<u8>,
    /// Bit i: axis i is listed.
    shown: u32,
    all: u32,
    /// The last coordinate written of axis i.
    recent: [Recent; MAX_AXES],
    /// The last feed written (per minute or per revolution).
    feed: Recent,
}

impl EventAxes {
    /// The axes of `machine`, before any event.
    pub fn new(machine: &Machine) -> EventAxes {
        let letters: Vec<u8> = machine
            .axes
            .iter()
            .map(|a| a.letter.to_ascii_lowercase())
            .collect();
        let shown = letters
            .iter()
            .enumerate()
            .filter(|(_, l)| matches!(l, b'x' | b'y' | b'z'))
            .fold(0, |m, (i, _)| m | 1 << i);
        let all = (1u32 << letters.len()) - 1;
        EventAxes {
            letters,
            shown,
            all,
            recent: [Recent::default(); MAX_AXES],
            feed: Recent::default(),
        }
    }

    /// Lists from now on every rotary axis `p` has away from 0.
    #[inline]
    fn note(&mut self, p: &Pos) {
        if self.shown == self.all {
            return;
        }
        for i in 0..self.letters.len() {
            if p.get(i) != 0.0 {
                self.shown |= 1 << i;
            }
        }
    }

    /// Whether axis `i` is listed.
    pub fn shows(&self, i: usize) -> bool {
        self.shown & (1 << i) != 0
    }
}

impl<W: Write> JsonlSink<W> {
    /// A sink writing to `out` for a machine's axes.
    pub fn new(out: W, machine: &Machine) -> JsonlSink<W> {
        JsonlSink {
            out,
            axes: EventAxes::new(machine),
            buf: Vec::with_capacity(FLUSH_BYTES + 1024),
            error: None,
        }
    }

    /// The writer, after [`Sink::finish`].
    pub fn into_inner(self) -> W {
        self.out
    }
}

/// Events are formatted straight into one buffer that goes to the writer
/// when it holds this much: no second copy through a `BufWriter`.
const FLUSH_BYTES: usize = 64 * 1024;

impl<W: Write> Sink for JsonlSink<W> {
    fn event(&mut self, event: &Event) {
        if self.error.is_some() {
            return;
        }
        write_event(&mut self.buf, &mut self.axes, event);
        self.buf.push(b'\n');
        if self.buf.len() >= FLUSH_BYTES {
            if let Err(e) = self.out.write_all(&self.buf) {
                self.error = Some(e);
            }
            self.buf.clear();
        }
    }

    /// A write failed (the reader went away): the run can stop.
    fn is_done(&self) -> bool {
        self.error.is_some()
    }

    /// Flushes, or returns the first write error.
    fn finish(&mut self) -> io::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.out.write_all(&self.buf)?;
        self.buf.clear();
        self.out.flush()
    }
}

/// Appends the JSON object of `event` (no newline) with the axes `axes`
/// lists (and notes the rotary axes it moves).
pub fn write_event(out: &mut Vec<u8>, axes: &mut EventAxes, event: &Event) {
    let mut j = Obj { out, axes };
    match event {
        Event::Rapid {
            loc,
            to,
            exact_stop,
        } => {
            j.head("rapid", loc);
            j.pos("to", to);
            j.flag("exact_stop", *exact_stop);
        }
        Event::Feed {
            loc,
            to,
            feed,
            exact_stop,
        } => {
            j.head("feed", loc);
            j.pos("to", to);
            j.feed(*feed);
            j.flag("exact_stop", *exact_stop);
        }
        Event::Arc {
            loc,
            to,
            center,
            plane,
            dir,
            feed,
            exact_stop,
        } => {
            j.head("arc", loc);
            j.pos("to", to);
            j.pos("center", center);
            j.str("plane", plane.as_str());
            j.str("dir", if *dir == ArcDir::Cw { "cw" } else { "ccw" });
            j.feed(*feed);
            j.flag("exact_stop", *exact_stop);
        }
        Event::Thread { loc, to, lead_mm } => {
            j.head("thread", loc);
            j.pos("to", to);
            j.num("lead_mm", *lead_mm);
        }
        Event::Skip {
            loc,
            to,
            feed,
            triggered,
        } => {
            j.head("skip", loc);
            j.pos("to", to);
            j.feed(*feed);
            j.boolean("triggered", *triggered);
        }
        Event::Dwell { loc, seconds } => {
            j.head("dwell", loc);
            j.num("seconds", *seconds);
        }
        Event::ToolChange { loc, tool } => {
            j.head("tool_change", loc);
            j.int("tool", u64::from(*tool));
        }
        Event::Spindle {
            loc,
            dir,
            rpm,
            surface_m_per_min,
        } => {
            j.head("spindle", loc);
            j.str("dir", spindle_dir(*dir));
            j.num("rpm", *rpm);
            if let Some(s) = surface_m_per_min {
                j.num("surface_m_per_min", *s);
            }
        }
        Event::Coolant { loc, on } => {
            j.head("coolant", loc);
            j.boolean("on", *on);
        }
        Event::PathMode { loc, mode } => {
            j.head("path_mode", loc);
            j.str("mode", path_mode(*mode));
        }
        Event::HighSpeed { loc, on, p } => {
            j.head("high_speed", loc);
            j.boolean("on", *on);
            j.int("p", u64::from(*p));
        }
        Event::Stop { loc, code } => {
            j.head("stop", loc);
            j.str("code", code.as_str());
        }
        Event::End { loc, code } => {
            j.head("end", loc);
            j.str("code", code.as_str());
        }
        Event::Frame { loc, frame } => {
            j.head("frame", loc);
            j.frame(frame);
        }
        Event::Hole { loc, cycle, at } => {
            j.head("hole", loc);
            j.str("cycle", cycle.as_str());
            j.pos("at", at);
        }
        Event::Wait { loc, reason } => {
            j.head("wait", loc);
            j.str("reason", reason.as_str());
        }
        Event::Junction { loc, blend } => {
            j.head("junction", loc);
            j.boolean("blend", *blend);
        }
        Event::Smoothing {
            loc,
            on,
            tolerance_mm,
        } => {
            j.head("smoothing", loc);
            j.boolean("on", *on);
            if *on {
                j.num("tolerance_mm", *tolerance_mm);
            }
        }
        Event::Nurbs { loc, curve, feed } => {
            j.head("nurbs", loc);
            j.int("order", u64::from(curve.order));
            j.nums("knots", &curve.knots);
            j.key("points");
            j.out.push(b'[');
            for (i, p) in curve.points.iter().enumerate() {
                if i > 0 {
                    j.out.push(b',');
                }
                j.point(p);
            }
            j.out.push(b']');
            j.nums("weights", &curve.weights);
            j.feed(*feed);
        }
        Event::Contour { loc, from, to, arc } => {
            j.head("contour", loc);
            j.pos("from", from);
            j.pos("to", to);
            if let Some((center, plane, dir)) = arc {
                j.pos("center", center);
                j.str("plane", plane.as_str());
                j.str("dir", if *dir == ArcDir::Cw { "cw" } else { "ccw" });
            }
        }
        Event::Aux {
            loc,
            code,
            description,
        } => {
            j.head("aux", loc);
            j.int("code", u64::from(*code));
            j.str("description", description);
        }
        Event::Message { loc, text, stop } => {
            j.head("message", loc);
            j.str("text", text);
            j.boolean("stop", *stop);
        }
        Event::UnsetVariables { loc, variables } => {
            j.head("unset_variables", loc);
            j.key("variables");
            j.out.push(b'[');
            for (k, v) in variables.iter().enumerate() {
                if k > 0 {
                    j.out.push(b',');
                }
                j.out.extend_from_slice(b"{\"name\":");
                push_json_str(j.out, &v.name);
                j.int("line", v.line);
                if let Some(f) = &v.file {
                    j.str("file", f);
                }
                j.out.push(b'}');
            }
            j.out.push(b']');
        }
        Event::WorkSystem { loc, system } => {
            j.head("work_system", loc);
            match system {
                Some(n) => j.str("system", &vcnc_core::events::work_system_name(*n)),
                None => {
                    j.key("system");
                    j.out.extend_from_slice(b"null");
                }
            }
        }
        Event::Units { loc, inch } => {
            j.head("units", loc);
            j.str("units", if *inch { "in" } else { "mm" });
        }
        Event::MachineMove { loc, to, axes } => {
            j.head("machine_move", loc);
            j.key("to");
            j.axes_of(to, u32::from(*axes));
        }
        Event::Placed { loc, axes } => {
            j.head("placed", loc);
            let letters: String = (j.axes.letters.iter().enumerate())
                .filter(|(i, _)| axes & (1 << i) != 0)
                .map(|(_, l)| char::from(*l))
                .collect();
            j.str("axes", &letters);
        }
        Event::Warning(d) => j.diagnostic("warning", d),
        Event::Alarm(d) => j.diagnostic("alarm", d),
        // The contract is additive: an event type this writer does not know
        // yet still leaves as a valid object with its type and line.
        other => j.head(other.kind(), other.loc().unwrap_or(&Loc::default())),
    }
    j.out.push(b'}');
}

/// `"cw"`, `"ccw"`, `"stop"`, `"orient"`.
pub(crate) fn spindle_dir(d: SpindleDir) -> &'static str {
    match d {
        SpindleDir::Cw => "cw",
        SpindleDir::Ccw => "ccw",
        SpindleDir::Stop => "stop",
        SpindleDir::Orient => "orient",
    }
}

/// The `path_mode` names.
pub(crate) fn path_mode(m: PathMode) -> &'static str {
    match m {
        PathMode::ExactStop => "exact_stop",
        PathMode::Surface => "surface",
        PathMode::Tapping => "tapping",
        PathMode::Cutting => "cutting",
    }
}

struct Obj<'a> {
    out: &'a mut Vec<u8>,
    axes: &'a mut EventAxes,
}

// The small writers below are inlined so that the key and type names,
// string literals at every call, are copied with their lengths known
// (a few stores rather than a call to `memcpy` each): the hot path of
// `vcnc run --format jsonl`.
impl Obj<'_> {
    /// An alarm or a warning: where, code, message, help.
    fn diagnostic(&mut self, kind: &str, d: &vcnc_core::Diagnostic) {
        self.head(
            kind,
            &Loc {
                line: d.line,
                file: d.file.as_deref().map(Into::into),
            },
        );
        self.int("column", u64::from(d.column));
        self.str("code", d.code.as_str());
        self.key("message");
        push_json_str(self.out, &d.message);
        self.key("help");
        push_json_str(self.out, &d.help);
    }

    #[inline(always)]
    fn head(&mut self, kind: &str, loc: &Loc) {
        self.out.extend_from_slice(b"{\"type\":\"");
        self.out.extend_from_slice(kind.as_bytes());
        self.out.extend_from_slice(b"\",\"line\":");
        push_u64(self.out, loc.line);
        if let Some(f) = &loc.file {
            self.key("file");
            push_json_str(self.out, f);
        }
    }
    #[inline(always)]
    fn key(&mut self, k: &str) {
        self.out.extend_from_slice(b",\"");
        self.out.extend_from_slice(k.as_bytes());
        self.out.extend_from_slice(b"\":");
    }
    fn nums(&mut self, k: &str, v: &[f64]) {
        self.key(k);
        self.out.push(b'[');
        for (i, x) in v.iter().enumerate() {
            if i > 0 {
                self.out.push(b',');
            }
            push_f64(self.out, *x);
        }
        self.out.push(b']');
    }
    #[inline]
    fn pos(&mut self, k: &str, p: &Pos) {
        self.key(k);
        self.point(p);
    }
    fn point(&mut self, p: &Pos) {
        self.axes.note(p);
        self.axes_of(p, self.axes.shown);
    }
    /// The axes of `mask` (bit i: axis i) of `p`.
    fn axes_of(&mut self, p: &Pos, mask: u32) {
        self.out.push(b'{');
        let mut first = true;
        let axes = &mut *self.axes;
        for ((i, letter), recent) in axes.letters.iter().enumerate().zip(&mut axes.recent) {
            if mask & (1 << i) == 0 {
                continue;
            }
            if !first {
                self.out.push(b',');
            }
            first = false;
            self.out.extend_from_slice(&[b'"', *letter, b'"', b':']);
            recent.push(self.out, p.get(i));
        }
        self.out.push(b'}');
    }
    #[inline]
    fn num(&mut self, k: &str, v: f64) {
        self.key(k);
        push_f64(self.out, v);
    }
    fn int(&mut self, k: &str, v: u64) {
        self.key(k);
        push_u64(self.out, v);
    }
    fn str(&mut self, k: &str, v: &str) {
        self.key(k);
        push_json_str(self.out, v);
    }
    fn boolean(&mut self, k: &str, v: bool) {
        self.key(k);
        self.out
            .extend_from_slice(if v { b"true" } else { b"false" });
    }
    fn flag(&mut self, k: &str, v: bool) {
        if v {
            self.boolean(k, true);
        }
    }
    fn frame(&mut self, f: &FrameInfo) {
        self.pos("origin", &f.origin);
        if let Some(m) = &f.linear {
            self.key("linear");
            self.out.push(b'[');
            for (r, row) in m.iter().enumerate() {
                if r > 0 {
                    self.out.push(b',');
                }
                self.out.push(b'[');
                for (c, v) in row.iter().enumerate() {
                    if c > 0 {
                        self.out.push(b',');
                    }
                    push_f64(self.out, *v);
                }
                self.out.push(b']');
            }
            self.out.push(b']');
        }
        if f.tool_offset != Pos::default() {
            self.pos("tool_offset", &f.tool_offset);
        }
    }
    fn feed(&mut self, f: Feed) {
        let v = match f {
            Feed::PerMin(v) => {
                self.key("feed");
                v
            }
            Feed::PerRev(v) => {
                self.key("feed_per_rev");
                v
            }
        };
        self.axes.feed.push(self.out, v);
    }
}
