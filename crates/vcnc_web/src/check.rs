//! The runs the page asks for, each one pass of the interpreter over the
//! program text into the CLI's own sinks.
//!
//! [`check`] is what the page does on every edit: a keep-going run (the
//! editor's: every alarm, the run going on with the state as before the
//! block) into the plot sink, the `check` summary and the planner at once,
//! so one run gives the diagnostics, the summary panel, the planned time
//! and the viewer's data (`vcnc_plot::page_data`: the data of the page
//! `vcnc plot` writes, retimed on the planner's seconds as `vcnc plot`
//! retimes it, without the program text, which the page already has), for
//! the viewer the page loads once (`viewer`, `vcnc_plot::write_viewer`).
//! Diagnostics carry their line and the UTF-16 columns of their span
//! within the line, which is what the editor (CodeMirror) counts in.

use crate::setup::{DialectChoice, Settings, Setup};
use serde::Serialize;
use std::collections::BTreeMap;
use vcnc_core::display::{DisplayUnits, duration};
use vcnc_interp::{Event, Interpreter, NoPrograms, Outcome, Pos, Sink};
use vcnc_planner::{Blocks, CycleTime, Numbered, Planner, Stamps};
use vcnc_plot::{
    Clock, ColorBy, FitTo, Legend, Page, PlotOptions, PlotSink, Source, Space, Theme, View,
};
use vcnc_syntax::MemSource;

/// Most vertices the page keeps (as `vcnc plot`'s page).
const PAGE_BUDGET: usize = 1 << 19;
/// Most hole and tool-change marks kept.
const MAX_MARKS: usize = 100_000;
/// Merge units across the model (as `vcnc plot`'s page).
const PAGE_RESOLUTION: f64 = 2048.0;
/// Most events [`events`] returns (about 200 MB of JS objects past this).
pub const MAX_EVENTS: usize = 1_000_000;

/// An alarm or a warning, placed for the editor.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Diag {
    /// `"E303"`, `"W104"`.
    pub code: &'static str,
    /// `"error"` (an alarm) or `"warning"`.
    pub severity: &'static str,
    /// What is wrong.
    pub message: String,
    /// How to fix it.
    pub help: String,
    /// 1-based line (0: not in a line, e.g. a setup error).
    pub line: u64,
    /// 1-based character column, as the CLI prints it.
    pub column: u32,
    /// UTF-16 offsets of the span within its line, `from < to` (a word or
    /// at least one character) unless the line is empty.
    pub from: u32,
    /// End of the span (UTF-16 units from the line's start).
    pub to: u32,
    /// The file, when not the main program.
    pub file: Option<String>,
    /// An earlier alarm came before it (the run went on with the state as
    /// it was before that block).
    pub after_alarm: bool,
}

/// Extents in machine mm, per reported axis (lowercase letter).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Extents {
    /// Least value of each axis.
    pub min: BTreeMap<String, f64>,
    /// Greatest value of each axis.
    pub max: BTreeMap<String, f64>,
}

/// A tool of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolRow {
    /// Its number.
    pub number: u32,
    /// Its diameter, when its shape is known (table or CAM comments).
    pub diameter_mm: Option<f64>,
}

/// The summary panel: what `vcnc check` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// `ended by M30`, `alarm E301 at line 2`, `stopped`.
    pub result: String,
    /// The program ran to its end without an alarm.
    pub ended: bool,
    /// Cycle time planned on the machine model, s (`vcnc time`'s total).
    pub planned_s: f64,
    /// The planned time as the CLI writes it (`1m 02.3s`).
    pub planned: String,
    /// Distance over feed, s (no acceleration).
    pub dist_feed_s: f64,
    /// Rapid travel, mm.
    pub rapid_mm: f64,
    /// Cutting travel, mm.
    pub cut_mm: f64,
    /// Machine extents, or none without motion.
    pub extents: Option<Extents>,
    /// Tools changed to, in order of first use.
    pub tools: Vec<ToolRow>,
    /// Holes drilled by canned cycles.
    pub holes: u64,
    /// Alarms in all (keep-going).
    pub alarms: u64,
    /// Warnings in all.
    pub warnings: u64,
    /// Events in all.
    pub events: u64,
    /// The machine's name.
    pub machine: String,
}

/// What [`check`] returns.
#[derive(Debug, Clone, Serialize)]
pub struct Checked {
    /// The dialect and why.
    pub dialect: DialectChoice,
    /// Every alarm and warning, in the order of the run.
    pub diagnostics: Vec<Diag>,
    /// The summary panel.
    pub summary: Summary,
    /// The viewer's data (`vcnc_plot::page_data`'s JSON), when
    /// `with_view`.
    pub view: Option<String>,
}

/// The planned time and its split (`vcnc time`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TimeSplit {
    /// The dialect and why.
    pub dialect: DialectChoice,
    /// The alarm that stopped the run, if any (the times are up to it).
    pub alarm: Option<Diag>,
    /// Everything, s.
    pub total_s: f64,
    /// Cutting moves, s.
    pub cutting_s: f64,
    /// Rapids, s.
    pub rapid_s: f64,
    /// Dwells, s.
    pub dwell_s: f64,
    /// Tool changes, s.
    pub tool_change_s: f64,
    /// Spindle starts and stops, s.
    pub spindle_s: f64,
    /// Settling into position, s.
    pub in_position_s: f64,
    /// Cutting path, mm.
    pub cutting_mm: f64,
    /// Rapid path, mm.
    pub rapid_mm: f64,
}

/// The flattened program (`vcnc run --format gcode`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Flattened {
    /// The dialect and why.
    pub dialect: DialectChoice,
    /// The plain program, up to the alarm if there is one.
    pub gcode: String,
    /// The alarm that stopped the run: the program is not whole.
    pub alarm: Option<Diag>,
}

/// The event stream (`vcnc run --format jsonl`), as objects.
#[derive(Debug, Clone, Serialize)]
pub struct Events {
    /// The dialect and why.
    pub dialect: DialectChoice,
    /// The events, each in exactly the shape of docs/events.md.
    pub events: Vec<serde_json::Value>,
    /// More than [`MAX_EVENTS`]: the run was stopped there.
    pub truncated: bool,
}

/// Sends every event to two sinks.
struct Tee<A, B>(A, B);

impl<A: Sink, B: Sink> Sink for Tee<A, B> {
    fn event(&mut self, e: &Event) {
        self.0.event(e);
        self.1.event(e);
    }
    fn is_done(&self) -> bool {
        self.0.is_done() || self.1.is_done()
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.0.finish()?;
        self.1.finish()
    }
}

/// The plot's clock: the `check` summary and the block number as stamp
/// (as `vcnc plot`'s).
struct BlockClock {
    summary: vcnc_output::Summary,
    blocks: Blocks,
}

impl Sink for BlockClock {
    fn event(&mut self, e: &Event) {
        self.summary.event(e);
        self.blocks.see(e);
    }
}

impl Clock for BlockClock {
    fn now(&self) -> f64 {
        // Block counts are far below 2^53: exact.
        #[allow(clippy::cast_precision_loss)]
        let n = self.blocks.count() as f64;
        n
    }
}

/// One run of `text` into `sink`.
pub(crate) fn run<S: Sink>(
    text: &str,
    s: &Setup,
    keep_going: bool,
    markers: bool,
    sink: &mut S,
) -> Outcome {
    let options = vcnc_interp::Options {
        keep_going,
        ..s.options
    };
    let mut interp = Interpreter::new(&s.machine, s.dialect, options);
    if markers {
        interp = interp.with_program_markers();
    }
    let main = Box::new(MemSource(text.as_bytes().to_vec()));
    interp.run(main, &mut NoPrograms, sink)
}

/// Checks `text`: every alarm and warning (keep-going), the summary with
/// the planned time, and (`with_view`) the viewer's data.
pub fn check(text: &str, settings: &Settings, with_view: bool) -> Result<Checked, String> {
    let s = Setup::new(text, settings)?;
    let lathe = s.dialect.diameter.lathe;
    let options = PlotOptions {
        space: Space::Volume {
            resolution: PAGE_RESOLUTION,
        },
        color: ColorBy::Tool,
        max_vertices: PAGE_BUDGET,
        max_marks: MAX_MARKS,
        fit: FitTo::Cuts,
    };
    let clock = BlockClock {
        summary: vcnc_output::Summary::new(&s.machine),
        blocks: Blocks::default(),
    };
    let plot = PlotSink::with_clock(&s.machine, options, clock);
    let plan = Planner::with_profile(&s.machine, s.machine.motion.profile, Stamps::default());
    let numbered = Numbered {
        inner: plan,
        blocks: Blocks::default(),
    };
    let mut both = Tee(plot, numbered);
    let outcome = run(text, &s, true, false, &mut both);
    let Tee(plot, numbered) = both;
    let stamps = numbered.inner.into_timeline();
    let planned_s = stamps.sum.total_s;
    let (mut plot, clock) = plot.into_parts();
    plot.retime(planned_s, |stamp| stamps.time_of(stamp));
    let summary = &clock.summary;
    let mut alarms: Vec<&vcnc_core::Diagnostic> = summary.alarms.iter().collect();
    if alarms.is_empty()
        && let Outcome::Alarm(d) = &outcome
    {
        alarms.push(d);
    }
    let diagnostics = diagnostics(text, &alarms, &summary.warnings);
    let sum = summary_of(summary, &outcome, planned_s, &s);
    let view = with_view.then(|| {
        let legend = legend(&sum, &s);
        // The name only: the page has the text.
        let sources = [Source::new("program".into(), Vec::new())];
        let page = Page {
            theme: Theme::Light,
            // One colour per tool says little about a one-tool program.
            color: if plot.tools.len() >= 2 {
                ColorBy::Tool
            } else {
                ColorBy::Depth
            },
            lathe,
            view: if lathe { View::Xz } else { View::Iso },
            fit: FitTo::Cuts,
            rapids: true,
            units: DisplayUnits::Mm,
            legend: &legend,
            time_label: "planned",
            sources: &sources,
            tools: Some(&s.tools),
            meshes: &[],
        };
        vcnc_plot::page_data(&plot, None, &page)
    });
    Ok(Checked {
        dialect: s.choice.clone(),
        diagnostics,
        summary: sum,
        view,
    })
}

/// The alarms and warnings in the order of their lines, placed.
fn diagnostics(
    text: &str,
    alarms: &[&vcnc_core::Diagnostic],
    warnings: &[vcnc_core::Diagnostic],
) -> Vec<Diag> {
    let first_alarm = alarms.first().map(|d| (d.line, d.column));
    let mut out: Vec<Diag> = alarms
        .iter()
        .enumerate()
        .map(|(i, d)| place(text, d, i > 0))
        .chain(warnings.iter().map(|d| {
            let after = first_alarm.is_some_and(|a| (d.line, d.column) > a);
            place(text, d, after)
        }))
        .collect();
    out.sort_by_key(|d| (d.line, d.from));
    out
}

/// Where a diagnostic points in its line: its span, or (an empty span)
/// the word that starts there, or one character; in UTF-16 units.
fn place(text: &str, d: &vcnc_core::Diagnostic, after_alarm: bool) -> Diag {
    let (mut from, mut to) = (0, 0);
    if d.file.is_none() && d.line > 0 {
        let start = usize::try_from(d.line_offset).unwrap_or(usize::MAX);
        let line = text.get(start..).unwrap_or_default();
        let line = line.split('\n').next().unwrap_or_default();
        let line = line.strip_suffix('\r').unwrap_or(line);
        let a = floor_char(line, d.span.start as usize);
        let mut b = floor_char(line, d.span.end as usize).max(a);
        if b == a {
            let rest = line.get(a..).unwrap_or_default();
            let word = rest
                .find(|c: char| c.is_whitespace() || c == '(' || c == ';')
                .unwrap_or(rest.len());
            b = a + word.max(rest.chars().next().map_or(0, char::len_utf8));
        }
        from = utf16_len(line.get(..a).unwrap_or_default());
        to = from + utf16_len(line.get(a..b).unwrap_or_default());
    }
    Diag {
        code: d.code.as_str(),
        severity: if d.code.is_warning() {
            "warning"
        } else {
            "error"
        },
        message: d.message.clone(),
        help: d.help.clone(),
        line: d.line,
        column: d.column,
        from,
        to,
        file: d.file.clone(),
        after_alarm,
    }
}

/// `at`, or the start of the character it falls inside, within `s`.
fn floor_char(s: &str, at: usize) -> usize {
    let mut i = at.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn utf16_len(s: &str) -> u32 {
    let n: usize = s.chars().map(char::len_utf16).sum();
    u32::try_from(n).unwrap_or(u32::MAX)
}

fn result_text(o: &Outcome, alarms: usize) -> String {
    match o {
        Outcome::Ended(code) if alarms > 0 => {
            format!("{alarms} alarm(s); the run went on to {}", code.as_str())
        }
        Outcome::Ended(code) => format!("ended by {}", code.as_str()),
        Outcome::Stopped => "stopped".into(),
        Outcome::Alarm(d) => format!("alarm {} at line {}", d.code.as_str(), d.line),
    }
}

fn axis_map(s: &vcnc_output::Summary, p: &Pos) -> BTreeMap<String, f64> {
    s.axis_letters()
        .iter()
        .enumerate()
        .filter(|(i, _)| s.reports_axis(*i))
        .map(|(i, l)| (char::from(l.to_ascii_lowercase()).to_string(), p.get(i)))
        .collect()
}

fn summary_of(s: &vcnc_output::Summary, o: &Outcome, planned_s: f64, setup: &Setup) -> Summary {
    let alarms = s
        .alarms
        .len()
        .max(usize::from(matches!(o, Outcome::Alarm(_))));
    Summary {
        result: result_text(o, alarms),
        ended: matches!(o, Outcome::Ended(_)) && alarms == 0,
        planned_s,
        planned: duration(planned_s),
        dist_feed_s: s.cycle_time_s,
        rapid_mm: s.rapid_mm,
        cut_mm: s.cut_mm,
        extents: s.extents.map(|(lo, hi)| Extents {
            min: axis_map(s, &lo),
            max: axis_map(s, &hi),
        }),
        tools: s
            .tools
            .iter()
            .map(|t| ToolRow {
                number: *t,
                diameter_mm: setup.tools.get(*t).map(|shape| shape.diameter_mm),
            })
            .collect(),
        holes: s.holes.iter().map(|(_, n)| n).sum(),
        alarms: alarms as u64,
        warnings: s.warning_total(),
        events: s.events,
        machine: setup.machine.name.clone(),
    }
}

/// The viewer's legend rows: the summary, shortened.
fn legend(sum: &Summary, s: &Setup) -> Legend {
    let mut rows = vec![
        ("result".to_string(), sum.result.clone()),
        (
            "cycle time".to_string(),
            format!(
                "{} planned ({} dist/feed)",
                sum.planned,
                duration(sum.dist_feed_s)
            ),
        ),
        (
            "distance".to_string(),
            format!("rapid {:.3} mm, cutting {:.3} mm", sum.rapid_mm, sum.cut_mm),
        ),
    ];
    if !sum.tools.is_empty() {
        let tools: Vec<String> = sum.tools.iter().map(|t| format!("T{}", t.number)).collect();
        rows.push(("tools".to_string(), tools.join(" ")));
    }
    Legend {
        title: format!("program ({})", s.dialect.name),
        rows,
        compare: None,
    }
}

/// The planned time and its split, as `vcnc time` plans it.
pub fn time(text: &str, settings: &Settings) -> Result<TimeSplit, String> {
    let s = Setup::new(text, settings)?;
    let mut plan = Planner::with_profile(&s.machine, s.machine.motion.profile, CycleTime::new());
    let outcome = run(text, &s, false, false, &mut plan);
    let t = plan.into_timeline();
    Ok(TimeSplit {
        dialect: s.choice.clone(),
        alarm: alarm_of(text, &outcome),
        total_s: t.total_s,
        cutting_s: t.cutting_s,
        rapid_s: t.rapid_s,
        dwell_s: t.dwell_s,
        tool_change_s: t.tool_change_s,
        spindle_s: t.spindle_s,
        in_position_s: t.in_position_s,
        cutting_mm: t.cutting_mm,
        rapid_mm: t.rapid_mm,
    })
}

fn alarm_of(text: &str, o: &Outcome) -> Option<Diag> {
    match o {
        Outcome::Alarm(d) => Some(place(text, d, false)),
        _ => None,
    }
}

/// The flattened program, as `vcnc run --format gcode` writes it: in the
/// program's work coordinates and units.
pub fn flatten(text: &str, settings: &Settings) -> Result<Flattened, String> {
    let s = Setup::new(text, settings)?;
    let options = vcnc_output::GcodeOptions {
        coords: vcnc_output::Coords::Work,
        units: None,
    };
    let mut sink = vcnc_output::GcodeSink::with_options(Vec::new(), &s.machine, options);
    let outcome = run(text, &s, false, true, &mut sink);
    sink.finish()
        .map_err(|e| format!("writing the program: {e}"))?;
    Ok(Flattened {
        dialect: s.choice.clone(),
        gcode: String::from_utf8_lossy(&sink.into_inner()).into_owned(),
        alarm: alarm_of(text, &outcome),
    })
}

/// Formats each event as `run --format jsonl` does and keeps it as a
/// value, up to [`MAX_EVENTS`].
struct Collect {
    axes: vcnc_output::EventAxes,
    line: Vec<u8>,
    events: Vec<serde_json::Value>,
    truncated: bool,
}

impl Sink for Collect {
    fn event(&mut self, e: &Event) {
        if self.events.len() >= MAX_EVENTS {
            self.truncated = true;
            return;
        }
        self.line.clear();
        vcnc_output::write_event(&mut self.line, &mut self.axes, e);
        // write_event writes JSON; a line that is not would be a bug there,
        // kept visible as a string rather than dropped.
        let v = serde_json::from_slice(&self.line).unwrap_or_else(|_| {
            serde_json::Value::String(String::from_utf8_lossy(&self.line).into_owned())
        });
        self.events.push(v);
    }
    fn is_done(&self) -> bool {
        self.truncated
    }
}

/// The run's events (`vcnc run --format jsonl`), as objects.
pub fn events(text: &str, settings: &Settings) -> Result<Events, String> {
    let s = Setup::new(text, settings)?;
    let mut sink = Collect {
        axes: vcnc_output::EventAxes::new(&s.machine),
        line: Vec::with_capacity(256),
        events: Vec::new(),
        truncated: false,
    };
    let _ = run(text, &s, false, false, &mut sink);
    Ok(Events {
        dialect: s.choice.clone(),
        events: sink.events,
        truncated: sink.truncated,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn fanuc() -> Settings {
        Settings {
            dialect: Some("fanuc".into()),
            ..Settings::default()
        }
    }

    #[test]
    fn every_alarm_is_placed_at_its_word_and_later_ones_are_marked() {
        // Line 2: a cut with no feed rate (E301); line 4: an arc from X20
        // about X23 (radius 3) that ends 7 mm from its centre (E303).
        let text =
            "S1000 M03 G90 G17 G54 G00 X0 Y0\nG01 X10.\nG01 X20. F100.\nG02 X30. Y0 I3. J0.\nM30\n";
        let c = check(text, &fanuc(), false).unwrap();
        let codes: Vec<_> = c.diagnostics.iter().map(|d| (d.code, d.line)).collect();
        assert_eq!(
            codes,
            vec![("E301", 2), ("E303", 4)],
            "{:#?}",
            c.diagnostics
        );
        for d in &c.diagnostics {
            // ASCII lines: the UTF-16 start is the CLI's column less one.
            assert_eq!(d.from + 1, d.column, "{d:?}");
            assert!(d.to > d.from);
            assert_eq!(d.severity, "error");
        }
        assert!(!c.diagnostics[0].after_alarm);
        assert!(c.diagnostics[1].after_alarm);
        assert_eq!(c.summary.alarms, 2);
        assert!(!c.summary.ended);
        assert!(c.view.is_none());
    }

    #[test]
    fn a_fixed_program_has_no_diagnostics_and_its_planned_time_is_vcnc_times() {
        let text = "S1000 M03 G90 G17 G54 G00 X0 Y0\nG01 X10. F300.\nG01 X20. Y5.\nG02 X30. Y5. I5. J0.\nG00 Z50.\nM30\n";
        let c = check(text, &fanuc(), true).unwrap();
        assert!(c.diagnostics.is_empty(), "{:#?}", c.diagnostics);
        assert!(c.summary.ended);
        assert_eq!(c.summary.result, "ended by M30");
        let t = time(text, &fanuc()).unwrap();
        assert!(t.alarm.is_none());
        assert!(t.total_s > 0.0);
        // The page's planner is fed block numbers for lines; the time is
        // the same plan.
        assert_eq!(c.summary.planned_s, t.total_s);
        // Cut: 10 + √(100 + 25) + π·5 mm.
        let cut = 10.0 + 125f64.sqrt() + std::f64::consts::PI * 5.0;
        assert!(
            (c.summary.cut_mm - cut).abs() < 1e-9,
            "{}",
            c.summary.cut_mm
        );
        let ext = c.summary.extents.as_ref().unwrap();
        assert_eq!(ext.max["x"], 30.0);
        // The viewer's data: the path from X0 to X30, no program text.
        let view: serde_json::Value = serde_json::from_str(&c.view.unwrap()).unwrap();
        assert_eq!(view["files"], serde_json::json!(["program"]));
        assert_eq!(view["center"][0], 15.0);
        assert!(view["path"]["n"].as_u64().unwrap() >= 4, "{}", view["path"]);
    }

    #[test]
    fn a_column_after_wide_characters_counts_utf16_units() {
        // "(ü😀)" is 4 characters, 5 UTF-16 units, 8 bytes.
        let text = "(\u{fc}\u{1F600}) G01 X10.\nM30\n";
        let c = check(text, &fanuc(), false).unwrap();
        let d = &c.diagnostics[0];
        assert_eq!(d.code, "E301");
        assert_eq!(d.column, 6);
        assert_eq!(d.from, 6);
    }

    #[test]
    fn binary_input_and_endless_loops_end_in_located_alarms() {
        let mut bin = String::from("G00 X0\n");
        bin.extend((0u8..=255).map(char::from));
        bin.push('\n');
        let c = check(&bin, &fanuc(), false).unwrap();
        assert!(
            c.diagnostics
                .iter()
                .any(|d| d.line == 2 && d.severity == "error"),
            "{:#?}",
            c.diagnostics
        );
        let endless = "#1=0\nWHILE [#1 LT 1] DO1\nG00 X1.\nEND1\nM30\n";
        let c = check(endless, &fanuc(), false).unwrap();
        let d = c
            .diagnostics
            .iter()
            .find(|d| d.severity == "error")
            .unwrap();
        assert!(d.line >= 2, "{d:?}");
        let long = format!("G00 X{}\nM30\n", "1".repeat(10 << 20));
        let c = check(&long, &fanuc(), false).unwrap();
        assert_eq!(
            c.diagnostics.first().map(|d| d.line),
            Some(1),
            "{:#?}",
            c.diagnostics
        );
    }

    #[test]
    fn flatten_and_events_are_the_clis_outputs() {
        let text = "G90 G00 X1. Y2.\nG01 X3. F200.\nM30\n";
        let f = flatten(text, &fanuc()).unwrap();
        assert!(f.alarm.is_none());
        assert!(f.gcode.contains("X3"), "{}", f.gcode);
        let e = events(text, &fanuc()).unwrap();
        assert_eq!(e.events[0]["type"], "rapid");
        assert_eq!(e.events[0]["to"]["x"], 1.0);
        let feed = e.events.iter().find(|v| v["type"] == "feed").unwrap();
        assert_eq!(feed["to"]["x"], 3.0);
        assert_eq!(feed["feed"], 200.0);
        assert!(!e.truncated);
        let bad = flatten("G01 X1.\nM30\n", &fanuc()).unwrap();
        assert_eq!(bad.alarm.map(|a| a.code), Some("E301"));
    }

    #[test]
    fn a_tool_table_gives_shapes_and_registers() {
        let s = Settings {
            dialect: Some("linuxcnc".into()),
            tools: Some("T1 P1 D6.0 Z25.0 ;end mill\n".into()),
            tools_name: Some("t.tbl".into()),
            ..Settings::default()
        };
        let c = check("T1 M06\nG43 H1 G00 Z0\nM30\n", &s, false).unwrap();
        assert!(c.diagnostics.is_empty(), "{:#?}", c.diagnostics);
        assert_eq!(
            c.summary.tools,
            vec![ToolRow {
                number: 1,
                diameter_mm: Some(6.0)
            }]
        );
        // Z0 of the gauge line plus 25 mm of tool length.
        assert_eq!(c.summary.extents.unwrap().max["z"], 25.0);
    }
}
