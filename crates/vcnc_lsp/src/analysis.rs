//! Runs of the interpreter for the editor, each on a snapshot of a
//! document that owns everything it needs ([`Job`]), so that it runs on a
//! worker thread and the server's loop never waits for it.
//!
//! ```text
//!   Job (text, dialect, machine, program dir) ─┬─▶ diagnose   keep-going run ─▶ alarms + warnings
//!                                              ├─▶ state_after run until a line ─▶ State (hover)
//!                                              └─▶ line_times run + planner ─▶ seconds per line
//! ```
//!
//! Every run is cancellable: its sink says it is done as soon as the
//! server sets the job's flag (the next edit), and the interpreter asks
//! after every block, so a cancelled run ends within one block. A program
//! that loops forever ends at the machine's usual runaway limits.

use crate::dialect::Choice;
use crate::text::Text;
use lsp_types::{
    Diagnostic, DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use vcnc_interp::{Event, Interpreter, Machine, Options, Outcome, ProgramStore, Sink, State};
use vcnc_planner::{AxesMove, Pause, Profile, Segment, Timeline};
use vcnc_syntax::{MemSource, TextSource};

/// Warnings reported per document at most (alarms are at most
/// `vcnc_interp::MAX_ALARMS`).
pub const MAX_WARNINGS: usize = 500;

/// Largest called program read from disk.
const MAX_PROGRAM_BYTES: u64 = 64 << 20;

/// One document as a run sees it.
#[derive(Debug, Clone)]
pub struct Job {
    /// Its text at one version.
    pub text: Arc<Text>,
    /// Where it is saved (none: an unsaved buffer).
    pub path: Option<PathBuf>,
    /// Its dialect.
    pub choice: Choice,
    /// The machine of the settings (none: the dialect's built-in one).
    pub machine: Option<Arc<Machine>>,
    /// The tool table of the settings, written into the machine's
    /// registers (none: the machine's registers as they are).
    pub tools: Option<Arc<vcnc_core::ToolLibrary>>,
    /// Where `M98 P10` looks for `O0010` (none: the document's directory).
    pub program_dir: Option<PathBuf>,
    /// Operator switches (keep-going is always on).
    pub options: Options,
    /// What is wrong with the settings, shown on the first line.
    pub setup_errors: Vec<String>,
    /// The dialect named in the first line or the settings that does not
    /// exist: shown on the first line, and the program is not run.
    pub dialect_error: Option<String>,
}

impl Job {
    /// A job for `text` alone in the dialect `choice`: no file, the
    /// dialect's built-in machine, the switches off (tests, benchmarks,
    /// embedding).
    pub fn for_text(text: &str, choice: Choice) -> Job {
        Job {
            text: Arc::new(Text::new(text.to_string())),
            path: None,
            choice,
            machine: None,
            tools: None,
            program_dir: None,
            options: Options::default(),
            setup_errors: Vec::new(),
            dialect_error: None,
        }
    }

    /// The directory of called programs.
    pub fn dir(&self) -> Option<PathBuf> {
        self.program_dir.clone().or_else(|| {
            self.path
                .as_deref()
                .and_then(Path::parent)
                .map(Path::to_path_buf)
        })
    }

    /// Runs the document into `sink`; returns the outcome and the state at
    /// the end (or where the sink stopped the run).
    fn run<S: Sink>(&self, sink: &mut S) -> (Outcome, State) {
        let dialect = self.choice.dialect();
        let built_in;
        let machine = match &self.machine {
            Some(m) => m.as_ref(),
            None => {
                built_in = dialect.machine();
                &built_in
            }
        };
        let options = Options {
            keep_going: true,
            ..self.options
        };
        let mut interp = Interpreter::new(machine, &dialect, options);
        let main = Box::new(MemSource(self.text.as_str().as_bytes().to_vec()));
        let mut store = Files { dir: self.dir() };
        let outcome = interp.run(main, &mut store, sink);
        (outcome, *interp.state())
    }

    /// The machine a run uses.
    pub fn machine(&self) -> Machine {
        let dialect = self.choice.dialect();
        let mut machine = match &self.machine {
            Some(m) => Machine::clone(m),
            None => dialect.machine(),
        };
        if let Some(tools) = &self.tools {
            tools.fill_registers(&mut machine, dialect.tip_numbering);
        }
        machine
    }
}

/// The files a call may name in `dir` for program `number`, in the order
/// a controller's directory is searched (`O0010`, `O0010.nc`, …).
pub fn program_files(dir: &Path, number: u32) -> Vec<PathBuf> {
    [
        format!("O{number:04}"),
        format!("O{number:04}.nc"),
        format!("O{number:04}.NC"),
        format!("O{number}"),
        format!("O{number}.nc"),
    ]
    .iter()
    .map(|n| dir.join(n))
    .collect()
}

/// Called programs from the program directory, read whole (the language
/// server's runs and the Python module's).
#[derive(Debug, Clone, Default)]
pub struct Files {
    /// The directory (none: no called programs but the document's own).
    pub dir: Option<PathBuf>,
}

impl Files {
    fn read(path: &Path) -> Option<std::io::Result<(Box<dyn TextSource>, String)>> {
        if !path.is_file() {
            return None;
        }
        let read = || -> std::io::Result<(Box<dyn TextSource>, String)> {
            let len = std::fs::metadata(path)?.len();
            if len > MAX_PROGRAM_BYTES {
                return Err(std::io::Error::other(format!(
                    "larger than {} MB",
                    MAX_PROGRAM_BYTES >> 20
                )));
            }
            let bytes = std::fs::read(path)?;
            Ok((Box::new(MemSource(bytes)), path.display().to_string()))
        };
        Some(read())
    }
}

impl ProgramStore for Files {
    fn open(&mut self, number: u32) -> Option<std::io::Result<(Box<dyn TextSource>, String)>> {
        let dir = self.dir.as_deref()?;
        program_files(dir, number)
            .iter()
            .find_map(|p| Files::read(p))
    }

    fn open_named(&mut self, name: &str) -> Option<std::io::Result<(Box<dyn TextSource>, String)>> {
        let dir = self.dir.as_deref()?;
        [name.to_string(), format!("{name}.nc"), format!("{name}.NC")]
            .iter()
            .find_map(|n| Files::read(&dir.join(n)))
    }
}

/// One alarm or warning of a run, and whether an alarm came before it.
struct Found {
    d: vcnc_syntax::Diagnostic,
    after_alarm: bool,
}

/// Keeps the alarms and warnings; done when the job is cancelled.
struct Collect<'c> {
    cancel: &'c AtomicBool,
    found: Vec<Found>,
    /// Index in `found` of the first alarm.
    first_alarm: Option<usize>,
    warnings: usize,
}

impl Sink for Collect<'_> {
    fn event(&mut self, e: &Event) {
        let after_alarm = self.first_alarm.is_some();
        match e {
            Event::Alarm(d) => {
                if self.first_alarm.is_none() {
                    self.first_alarm = Some(self.found.len());
                }
                self.found.push(Found {
                    d: d.clone(),
                    after_alarm,
                });
            }
            Event::Warning(d) if self.warnings < MAX_WARNINGS => {
                self.warnings += 1;
                self.found.push(Found {
                    d: d.clone(),
                    after_alarm,
                });
            }
            _ => {}
        }
    }

    fn is_done(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The diagnostics of the document: every alarm (the run goes on after
/// each with the state as before it) and warning, each after the first
/// alarm marked so. `None` when the job was cancelled.
pub fn diagnose(job: &Job, uri: &lsp_types::Uri, cancel: &AtomicBool) -> Option<Vec<Diagnostic>> {
    if let Some(e) = &job.dialect_error {
        return Some(vec![setup_diagnostic(e)]);
    }
    let mut out: Vec<Diagnostic> = job
        .setup_errors
        .iter()
        .map(|e| setup_diagnostic(e))
        .collect();
    let mut sink = Collect {
        cancel,
        found: Vec::new(),
        first_alarm: None,
        warnings: 0,
    };
    let _ = job.run(&mut sink);
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    let first = sink
        .first_alarm
        .and_then(|i| sink.found.get(i))
        .map(|f| (f.d.clone(), place(&job.text, &f.d)));
    for f in &sink.found {
        out.push(to_lsp(
            &job.text,
            &f.d,
            f.after_alarm.then_some(()).and(first.as_ref()),
            uri,
        ));
    }
    Some(out)
}

/// A problem with the settings or the first-line comment, on line 1.
fn setup_diagnostic(message: &str) -> Diagnostic {
    Diagnostic {
        range: lsp_types::Range::default(),
        severity: Some(DiagnosticSeverity::ERROR),
        source: Some("vcnc".into()),
        message: message.to_string(),
        ..Diagnostic::default()
    }
}

/// Where a diagnostic of the main program points: its span (a word, or at
/// least one character), as a range of the document.
fn place(text: &Text, d: &vcnc_syntax::Diagnostic) -> lsp_types::Range {
    if d.file.is_some() || d.line == 0 {
        return lsp_types::Range::default();
    }
    let base = usize::try_from(d.line_offset).unwrap_or(usize::MAX);
    let start = base.saturating_add(d.span.start as usize);
    let mut end = base.saturating_add(d.span.end as usize);
    if end <= start {
        // An empty span: the word that starts there, or one character.
        let rest = text.as_str().get(start..).unwrap_or_default();
        let word = rest
            .find(|c: char| c.is_whitespace() || c == '(' || c == ';')
            .unwrap_or(rest.len());
        end = start + word.max(rest.chars().next().map_or(0, char::len_utf8));
    }
    text.range(start, end)
}

fn to_lsp(
    text: &Text,
    d: &vcnc_syntax::Diagnostic,
    first: Option<&(vcnc_syntax::Diagnostic, lsp_types::Range)>,
    uri: &lsp_types::Uri,
) -> Diagnostic {
    let mut message = d.message.clone();
    if let Some(file) = &d.file {
        message = format!("in {file}, line {}: {message}", d.line);
    }
    if !d.help.is_empty() {
        message.push_str("\nhelp: ");
        message.push_str(&d.help);
    }
    let mut related = Vec::new();
    if let Some((a, range)) = first {
        message.push_str(&format!(
            "\n(after the alarm {} at line {}: the run went on with the state as it was before that block)",
            a.code.as_str(),
            a.line
        ));
        related.push(DiagnosticRelatedInformation {
            location: Location::new(uri.clone(), *range),
            message: format!("the earlier alarm {}: {}", a.code.as_str(), a.message),
        });
    }
    Diagnostic {
        range: place(text, d),
        severity: Some(if d.code.is_warning() {
            DiagnosticSeverity::WARNING
        } else {
            DiagnosticSeverity::ERROR
        }),
        code: Some(NumberOrString::String(d.code.as_str().to_string())),
        source: Some("vcnc".into()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        ..Diagnostic::default()
    }
}

/// Stops the run after a line and remembers that it did.
struct StopAt<'c> {
    line: u64,
    reached: bool,
    cancel: &'c AtomicBool,
}

impl Sink for StopAt<'_> {
    fn event(&mut self, _: &Event) {}
    fn is_done(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
    fn stop_after_line(&mut self, line: u64) -> bool {
        self.reached |= line == self.line;
        line == self.line
    }
}

/// The state at the end of the first run of the main program's `line`
/// (the interpreter's numbering: 1-based, `\n` only). `None` when the line
/// never runs (the program ends or alarms fatally before it, or it holds
/// no block) or the job was cancelled.
pub fn state_after(job: &Job, line: u64, cancel: &AtomicBool) -> Option<State> {
    let mut sink = StopAt {
        line,
        reached: false,
        cancel,
    };
    let (_, state) = job.run(&mut sink);
    (sink.reached && !cancel.load(Ordering::Relaxed)).then_some(state)
}

/// Planned seconds per line of the main program (index: the line number).
#[derive(Debug, Default)]
pub struct LineTimes(pub Vec<f64>);

impl LineTimes {
    fn add(&mut self, attr: &vcnc_planner::Attr, seconds: f64) {
        if attr.file.is_some() {
            return;
        }
        let Ok(i) = usize::try_from(attr.line) else {
            return;
        };
        if let Some(slot) = self.0.get_mut(i) {
            *slot += seconds;
        }
    }
}

impl Timeline for LineTimes {
    fn segment(&mut self, seg: &Segment, profile: &Profile) {
        self.add(&seg.attr, profile.duration());
    }
    fn axes(&mut self, mv: &AxesMove) {
        self.add(&mv.attr, mv.duration_s);
    }
    fn pause(&mut self, pause: &Pause) {
        self.add(&pause.attr, pause.seconds);
    }
}

/// A sink that is done when its job is cancelled.
struct Cancellable<'c, S> {
    inner: S,
    cancel: &'c AtomicBool,
}

impl<S: Sink> Sink for Cancellable<'_, S> {
    fn event(&mut self, e: &Event) {
        self.inner.event(e);
    }
    fn take_events(&mut self, events: &mut Vec<Event>) {
        self.inner.take_events(events);
    }
    fn is_done(&self) -> bool {
        self.cancel.load(Ordering::Relaxed) || self.inner.is_done()
    }
}

/// The planned time of each line of the main program (`None`: cancelled).
pub fn line_times(job: &Job, cancel: &AtomicBool) -> Option<LineTimes> {
    let machine = job.machine();
    let lines = job.text.as_str().bytes().filter(|b| *b == b'\n').count() + 2;
    let planner = vcnc_planner::Planner::new(&machine, LineTimes(vec![0.0; lines]));
    let mut sink = Cancellable {
        inner: planner,
        cancel,
    };
    let _ = job.run(&mut sink);
    if cancel.load(Ordering::Relaxed) {
        return None;
    }
    Some(sink.inner.into_timeline())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::str::FromStr;

    fn job(text: &str, dialect: &'static str) -> Job {
        Job::for_text(
            text,
            Choice {
                name: dialect,
                why: String::new(),
            },
        )
    }

    fn uri() -> lsp_types::Uri {
        lsp_types::Uri::from_str("file:///tmp/t.nc").unwrap()
    }

    #[test]
    fn every_alarm_is_reported_and_later_ones_are_marked() {
        // Line 2: a cut with no feed rate (E301); line 4: an arc from
        // X20 about X23 (radius 3) that ends 7 mm from its centre (E303).
        let text =
            "S1000 M03 G90 G17 G54 G00 X0 Y0\nG01 X10.\nG01 X20. F100.\nG02 X30. Y0 I3. J0.\nM30\n";
        let d = diagnose(&job(text, "fanuc"), &uri(), &AtomicBool::new(false)).unwrap();
        assert_eq!(d.len(), 2, "{d:#?}");
        assert_eq!(d[0].code, Some(NumberOrString::String("E301".into())));
        assert_eq!(d[0].range.start.line, 1);
        assert!(d[0].related_information.is_none());
        assert_eq!(d[1].code, Some(NumberOrString::String("E303".into())));
        assert_eq!(d[1].range.start.line, 3);
        assert!(d[1].message.contains("after the alarm"), "{}", d[1].message);
        let related = d[1].related_information.as_ref().unwrap();
        assert_eq!(related[0].location.range, d[0].range);
    }

    #[test]
    fn a_cancelled_run_reports_nothing() {
        let text = "G01 X10. F100.\nM30\n";
        assert!(diagnose(&job(text, "fanuc"), &uri(), &AtomicBool::new(true)).is_none());
    }

    #[test]
    fn the_state_is_read_after_the_asked_line_only() {
        let text = "G90 G00 X1. Y2.\nG91 G01 X3. F200.\nG90 X9.\nM30\n";
        let j = job(text, "fanuc");
        let s = state_after(&j, 2, &AtomicBool::new(false)).unwrap();
        assert!(s.modal.incremental);
        assert_eq!(s.program_pos().0[0], 4.0);
        assert_eq!(s.program_pos().0[1], 2.0);
        assert_eq!(s.feed, 200.0);
        // Line 5 is empty: it never runs a block.
        assert!(state_after(&j, 5, &AtomicBool::new(false)).is_none());
    }
}
