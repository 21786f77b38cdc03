//! The `vcnc` Python module (docs/python.md): the virtual controller for
//! CAM and post-processor code — `check`, `events`, `flatten` and `time` —
//! over the same crates as the CLI.
//!
//! ```text
//!   Python args ─▶ Setup (dialect, machine, switches, program dir)   ValueError if bad
//!       GIL released ─▶ Interpreter::run ─▶ Summary + Planner ─▶ Result      check
//!                                        ─▶ write_event (jsonl) ─▶ thread ─▶ dicts  events (lazy)
//!                                        ─▶ GcodeSink ─▶ str                         flatten
//!                                        ─▶ Planner ─▶ Time                           time
//! ```
//!
//! Every run happens with the GIL released and under `catch_unwind`: a
//! bug in vcnc raises `vcnc.Error` and never takes the Python process
//! down. The dialect `"auto"` is the language server's choice
//! (`vcnc_lsp::dialect::choose`): the program's first-line comment
//! `(vcnc: --dialect haas)`, else the placeholder default until dialect
//! detection lands.

use crossbeam_channel::{Receiver, Sender, bounded};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList, PyString};
use std::collections::HashMap;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use vcnc_core::{Event, Sink};
use vcnc_interp::{Dialect, Interpreter, Machine, Options, Outcome, Pos};
use vcnc_lsp::analysis::Files;
use vcnc_output::{EventAxes, GcodeSink, Summary, write_event};
use vcnc_planner::{CycleTime, Planner};
use vcnc_syntax::MemSource;

create_exception!(
    vcnc,
    Error,
    PyException,
    "Something went wrong inside vcnc (a bug, reported with what happened)."
);
create_exception!(
    vcnc,
    ProgramAlarm,
    Error,
    "The program alarmed, so flatten() or time() has no whole answer; `.alarm` is the Diagnostic."
);

/// Runs `f`, turning a panic into `vcnc.Error`.
fn guarded<T>(f: impl FnOnce() -> T) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| {
        let what = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "a panic".into());
        Error::new_err(format!("internal error in vcnc (a bug): {what}"))
    })
}

/// An alarm or a warning.
#[pyclass(frozen, get_all, module = "vcnc")]
#[derive(Clone)]
struct Diagnostic {
    /// `"E303"`, `"W104"`.
    code: String,
    /// 1-based line.
    line: u64,
    /// 1-based column (characters).
    column: u32,
    /// What is wrong.
    message: String,
    /// How to fix it.
    help: String,
    /// The file, when not the main program.
    file: Option<String>,
    /// Whether it is a warning (else an alarm).
    is_warning: bool,
}

#[pymethods]
impl Diagnostic {
    fn __repr__(&self) -> String {
        format!(
            "<vcnc.Diagnostic {} at line {}, column {}: {}>",
            self.code, self.line, self.column, self.message
        )
    }
}

impl From<&vcnc_syntax::Diagnostic> for Diagnostic {
    fn from(d: &vcnc_syntax::Diagnostic) -> Diagnostic {
        Diagnostic {
            code: d.code.as_str().to_string(),
            line: d.line,
            column: d.column,
            message: d.message.clone(),
            help: d.help.clone(),
            file: d.file.clone(),
            is_warning: d.code.is_warning(),
        }
    }
}

/// What `check` found.
#[pyclass(frozen, get_all, module = "vcnc")]
struct Result {
    /// The program ran to its end (M02, M30 or its last block) without an alarm.
    ended: bool,
    /// How it ended (`"M30"`, `"M02"`, `"end of program"`), or None after an alarm.
    end: Option<String>,
    /// The first alarm, or None.
    alarm: Option<Diagnostic>,
    /// Every alarm (more than one only with keep_going=True).
    alarms: Vec<Diagnostic>,
    /// The warnings (the first 100).
    warnings: Vec<Diagnostic>,
    /// Warnings in all.
    warning_count: u64,
    /// Cycle time planned on the machine model, seconds.
    cycle_time_s: f64,
    /// Distance over feed, seconds (no acceleration).
    distance_feed_s: f64,
    /// Rapid travel, mm.
    rapid_mm: f64,
    /// Cutting travel, mm.
    cut_mm: f64,
    /// {"min": {"x": …}, "max": {…}} in machine mm, or None without motion.
    extents: Option<HashMap<String, HashMap<String, f64>>>,
    /// Tools changed to, in order of first use.
    tools: Vec<u32>,
    /// Holes drilled by canned cycles.
    holes: u64,
    /// (slowest, fastest) spindle speed commanded, rpm, or None.
    spindle_rpm: Option<(f64, f64)>,
    /// Times the program waits for the operator.
    waits: u64,
    /// The program ended in diameter programming (lathes).
    diameter_programming: bool,
    /// The dialect it was read in.
    dialect: String,
    /// The machine it ran on.
    machine: String,
}

#[pymethods]
impl Result {
    fn __repr__(&self) -> String {
        let how = match (&self.alarm, &self.end) {
            (Some(a), _) => format!("alarm {} at line {}", a.code, a.line),
            (None, Some(e)) => format!("ended by {e}"),
            (None, None) => "stopped".into(),
        };
        format!(
            "<vcnc.Result {how}, {:.1} s, {} warnings>",
            self.cycle_time_s, self.warning_count
        )
    }
}

/// What `time` planned.
#[pyclass(frozen, get_all, module = "vcnc")]
struct Time {
    /// Everything, seconds.
    total_s: f64,
    /// Cutting moves.
    cutting_s: f64,
    /// Rapids.
    rapid_s: f64,
    /// Dwells.
    dwell_s: f64,
    /// Tool changes.
    tool_change_s: f64,
    /// Spindle starts, reversals and stops.
    spindle_s: f64,
    /// Settling into position after exact stops.
    in_position_s: f64,
    /// Cutting path, mm.
    cutting_mm: f64,
    /// Rapid path, mm.
    rapid_mm: f64,
    /// Seconds per tool (None: before the first tool change).
    per_tool: HashMap<Option<u32>, f64>,
}

#[pymethods]
impl Time {
    fn __repr__(&self) -> String {
        format!("<vcnc.Time {:.1} s>", self.total_s)
    }
}

/// The machine, dialect and switches of one call.
struct Setup {
    dialect: Dialect,
    machine: Machine,
    options: Options,
    dir: Option<PathBuf>,
}

/// The program's bytes from a `str` or `bytes`.
fn program_bytes(text: &Bound<'_, PyAny>) -> PyResult<Vec<u8>> {
    if let Ok(s) = text.cast::<PyString>() {
        return Ok(s.to_str()?.as_bytes().to_vec());
    }
    if let Ok(b) = text.cast::<PyBytes>() {
        return Ok(b.as_bytes().to_vec());
    }
    Err(pyo3::exceptions::PyTypeError::new_err(
        "the program must be str or bytes",
    ))
}

/// A path argument (str or os.PathLike).
fn path_arg(arg: Option<&Bound<'_, PyAny>>) -> PyResult<Option<PathBuf>> {
    match arg {
        None => Ok(None),
        Some(a) if a.is_none() => Ok(None),
        Some(a) => a.extract::<PathBuf>().map(Some),
    }
}

#[allow(clippy::too_many_arguments)]
fn setup(
    text: &[u8],
    dialect: &str,
    machine: Option<&Bound<'_, PyAny>>,
    tools: Option<&Bound<'_, PyAny>>,
    program_dir: Option<&Bound<'_, PyAny>>,
    block_delete: bool,
    optional_stop: bool,
    keep_going: bool,
) -> PyResult<Setup> {
    let name = if dialect.eq_ignore_ascii_case("auto") {
        let lossy = String::from_utf8_lossy(text);
        vcnc_lsp::dialect::choose(&lossy, None, None)
            .map_err(PyValueError::new_err)?
            .name
    } else {
        let lower = dialect.to_ascii_lowercase();
        Dialect::NAMES
            .iter()
            .copied()
            .find(|n| *n == lower)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "unknown dialect {dialect:?}: use \"auto\" or one of {}",
                    Dialect::NAMES.join(", ")
                ))
            })?
    };
    let dialect = Dialect::by_name(name)
        .ok_or_else(|| Error::new_err(format!("dialect {name} has no tables")))?;
    let machine = match path_arg(machine)? {
        None => dialect.machine(),
        Some(path) => {
            let text = std::fs::read_to_string(&path).map_err(|e| {
                PyValueError::new_err(format!("cannot read machine file {}: {e}", path.display()))
            })?;
            Machine::from_toml(&text).map_err(|e| {
                PyValueError::new_err(format!("machine file {}: {e}", path.display()))
            })?
        }
    };
    let mut machine = machine;
    if let Some(path) = path_arg(tools)? {
        let text = std::fs::read_to_string(&path).map_err(|e| {
            PyValueError::new_err(format!("cannot read tool table {}: {e}", path.display()))
        })?;
        let table = vcnc_core::tooling::read_table(&text, &path.display().to_string())
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        table.fill_registers(&mut machine, dialect.tip_numbering);
    }
    Ok(Setup {
        dialect,
        machine,
        options: Options {
            block_delete,
            optional_stop,
            keep_going,
        },
        dir: path_arg(program_dir)?,
    })
}

impl Setup {
    /// Runs the program into `sink`; the outcome and whether it ended in
    /// diameter programming.
    fn run<S: Sink>(&self, text: Vec<u8>, sink: &mut S) -> (Outcome, bool) {
        self.run_marked(text, sink, false)
    }

    /// [`run`](Self::run), with the markers of program coordinates the
    /// flattened program is written from when `markers`.
    fn run_marked<S: Sink>(&self, text: Vec<u8>, sink: &mut S, markers: bool) -> (Outcome, bool) {
        let mut interp = Interpreter::new(&self.machine, &self.dialect, self.options);
        if markers {
            interp = interp.with_program_markers();
        }
        let mut store = Files {
            dir: self.dir.clone(),
        };
        let outcome = interp.run(Box::new(MemSource(text)), &mut store, sink);
        (outcome, interp.state().modal.diameter)
    }
}

/// Sends every event to two sinks.
struct Both<A, B>(A, B);

impl<A: Sink, B: Sink> Sink for Both<A, B> {
    fn event(&mut self, e: &Event) {
        self.0.event(e);
        self.1.event(e);
    }
}

fn end_name(o: &Outcome) -> Option<String> {
    match o {
        Outcome::Ended(code) => Some(code.as_str().to_string()),
        _ => None,
    }
}

fn pos_map(s: &Summary, p: &Pos) -> HashMap<String, f64> {
    s.axis_letters()
        .iter()
        .enumerate()
        .filter(|(i, _)| s.reports_axis(*i))
        .map(|(i, l)| (char::from(l.to_ascii_lowercase()).to_string(), p.get(i)))
        .collect()
}

/// Runs the program and reports what `vcnc check` reports: how it ended,
/// the alarm, the warnings, the planned cycle time and the summary.
#[pyfunction]
#[pyo3(signature = (text, dialect = "auto", machine = None, tools = None, program_dir = None, block_delete = false, optional_stop = false, keep_going = false))]
#[allow(clippy::too_many_arguments)]
fn check(
    py: Python<'_>,
    text: &Bound<'_, PyAny>,
    dialect: &str,
    machine: Option<&Bound<'_, PyAny>>,
    tools: Option<&Bound<'_, PyAny>>,
    program_dir: Option<&Bound<'_, PyAny>>,
    block_delete: bool,
    optional_stop: bool,
    keep_going: bool,
) -> PyResult<Result> {
    let bytes = program_bytes(text)?;
    let s = setup(
        &bytes,
        dialect,
        machine,
        tools,
        program_dir,
        block_delete,
        optional_stop,
        keep_going,
    )?;
    let (outcome, summary, planned, diameter) = py.detach(|| {
        guarded(|| {
            let mut summary = Summary::new(&s.machine);
            let mut plan = Planner::new(&s.machine, CycleTime::new());
            let (outcome, diameter) = s.run(bytes, &mut Both(&mut summary, &mut plan));
            (outcome, summary, plan.into_timeline(), diameter)
        })
    })?;
    let alarms: Vec<Diagnostic> = if summary.alarms.is_empty() {
        match &outcome {
            Outcome::Alarm(d) => vec![Diagnostic::from(d)],
            _ => Vec::new(),
        }
    } else {
        summary.alarms.iter().map(Diagnostic::from).collect()
    };
    let extents = summary.extents.map(|(lo, hi)| {
        HashMap::from([
            ("min".to_string(), pos_map(&summary, &lo)),
            ("max".to_string(), pos_map(&summary, &hi)),
        ])
    });
    Ok(Result {
        ended: matches!(outcome, Outcome::Ended(_)),
        end: end_name(&outcome),
        alarm: match &outcome {
            Outcome::Alarm(d) => Some(Diagnostic::from(d)),
            _ => None,
        },
        alarms,
        warnings: summary.warnings.iter().map(Diagnostic::from).collect(),
        warning_count: summary.warning_total(),
        cycle_time_s: planned.total_s,
        distance_feed_s: summary.cycle_time_s,
        rapid_mm: summary.rapid_mm,
        cut_mm: summary.cut_mm,
        extents,
        tools: summary.tools.clone(),
        holes: summary.holes.iter().map(|(_, n)| n).sum(),
        spindle_rpm: summary.spindle_rpm,
        waits: summary.waits,
        diameter_programming: diameter,
        dialect: s.dialect.name.to_string(),
        machine: s.machine.name.clone(),
    })
}

/// `vcnc.ProgramAlarm` for an alarmed run.
fn alarm_error(py: Python<'_>, d: &vcnc_syntax::Diagnostic) -> PyErr {
    let err = ProgramAlarm::new_err(format!(
        "alarm {} at line {}, column {}: {}",
        d.code.as_str(),
        d.line,
        d.column,
        d.message
    ));
    if let Ok(diag) = Py::new(py, Diagnostic::from(d)) {
        let _ = err.value(py).setattr("alarm", diag);
    }
    err
}

/// The flattened program `vcnc run --format gcode` writes: cycles,
/// compensation, subprograms and transforms expanded into plain moves.
/// Raises `vcnc.ProgramAlarm` when the program alarms.
#[pyfunction]
#[pyo3(signature = (text, dialect = "auto", machine = None, tools = None, program_dir = None, block_delete = false, optional_stop = false))]
#[allow(clippy::too_many_arguments)]
fn flatten(
    py: Python<'_>,
    text: &Bound<'_, PyAny>,
    dialect: &str,
    machine: Option<&Bound<'_, PyAny>>,
    tools: Option<&Bound<'_, PyAny>>,
    program_dir: Option<&Bound<'_, PyAny>>,
    block_delete: bool,
    optional_stop: bool,
) -> PyResult<String> {
    let bytes = program_bytes(text)?;
    let s = setup(
        &bytes,
        dialect,
        machine,
        tools,
        program_dir,
        block_delete,
        optional_stop,
        false,
    )?;
    let (outcome, out) = py.detach(|| {
        guarded(|| {
            // As `vcnc run --format gcode` writes it: the program's work
            // coordinates and units.
            let options = vcnc_output::GcodeOptions {
                coords: vcnc_output::Coords::Work,
                units: None,
            };
            let mut sink = GcodeSink::with_options(Vec::new(), &s.machine, options);
            let (outcome, _) = s.run_marked(bytes, &mut sink, true);
            let written = sink.finish();
            (outcome, written.map(|()| sink.into_inner()))
        })
    })?;
    if let Outcome::Alarm(d) = &outcome {
        return Err(alarm_error(py, d));
    }
    let out = out.map_err(|e| Error::new_err(format!("writing the program: {e}")))?;
    Ok(String::from_utf8_lossy(&out).into_owned())
}

/// The cycle time planned on the machine model and its split, as `vcnc
/// time` prints it. Raises `vcnc.ProgramAlarm` when the program alarms.
#[pyfunction]
#[pyo3(signature = (text, dialect = "auto", machine = None, tools = None, program_dir = None, block_delete = false, optional_stop = false))]
#[allow(clippy::too_many_arguments)]
fn time(
    py: Python<'_>,
    text: &Bound<'_, PyAny>,
    dialect: &str,
    machine: Option<&Bound<'_, PyAny>>,
    tools: Option<&Bound<'_, PyAny>>,
    program_dir: Option<&Bound<'_, PyAny>>,
    block_delete: bool,
    optional_stop: bool,
) -> PyResult<Time> {
    let bytes = program_bytes(text)?;
    let s = setup(
        &bytes,
        dialect,
        machine,
        tools,
        program_dir,
        block_delete,
        optional_stop,
        false,
    )?;
    let (outcome, t) = py.detach(|| {
        guarded(|| {
            let mut plan = Planner::new(&s.machine, CycleTime::new());
            let (outcome, _) = s.run(bytes, &mut plan);
            (outcome, plan.into_timeline())
        })
    })?;
    if let Outcome::Alarm(d) = &outcome {
        return Err(alarm_error(py, d));
    }
    Ok(Time {
        total_s: t.total_s,
        cutting_s: t.cutting_s,
        rapid_s: t.rapid_s,
        dwell_s: t.dwell_s,
        tool_change_s: t.tool_change_s,
        spindle_s: t.spindle_s,
        in_position_s: t.in_position_s,
        cutting_mm: t.cutting_mm,
        rapid_mm: t.rapid_mm,
        per_tool: t.per_tool.iter().copied().collect(),
    })
}

/// Events formatted as JSON lines, sent in chunks to the iterator.
type Chunk = std::result::Result<Vec<Vec<u8>>, String>;

/// Events per chunk sent from the run's thread.
const CHUNK: usize = 256;

/// The run's end of the channel: formats each event as `run --format
/// jsonl` does, and is done when the iterator is gone.
struct Feed {
    tx: Sender<Chunk>,
    axes: EventAxes,
    chunk: Vec<Vec<u8>>,
    gone: Arc<AtomicBool>,
}

impl Feed {
    fn flush(&mut self) {
        if self.chunk.is_empty() {
            return;
        }
        let chunk = std::mem::take(&mut self.chunk);
        if self.tx.send(Ok(chunk)).is_err() {
            self.gone.store(true, Ordering::Relaxed);
        }
    }
}

impl Sink for Feed {
    fn event(&mut self, e: &Event) {
        let mut line = Vec::with_capacity(128);
        write_event(&mut line, &mut self.axes, e);
        self.chunk.push(line);
        if self.chunk.len() >= CHUNK {
            self.flush();
        }
    }
    fn is_done(&self) -> bool {
        self.gone.load(Ordering::Relaxed)
    }
}

/// A lazy iterator over the run's events, each a dict in exactly the
/// shape of `vcnc run --format jsonl` (docs/events.md). The program runs
/// on its own thread a few hundred events ahead; dropping the iterator
/// stops it.
#[pyclass(module = "vcnc")]
struct Events {
    rx: Receiver<Chunk>,
    ready: Mutex<std::collections::VecDeque<Vec<u8>>>,
    gone: Arc<AtomicBool>,
}

impl Drop for Events {
    fn drop(&mut self) {
        self.gone.store(true, Ordering::Relaxed);
    }
}

#[pymethods]
impl Events {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        let poisoned = |_| Error::new_err("the event iterator was poisoned");
        // The lock is never held while the GIL is released: another
        // thread that holds the GIL and waits for it would deadlock.
        let mut line = self.ready.lock().map_err(poisoned)?.pop_front();
        if line.is_none() {
            // Waiting for the run's thread, with the GIL released.
            match py.detach(|| self.rx.recv()) {
                Ok(Ok(chunk)) => {
                    let mut ready = self.ready.lock().map_err(poisoned)?;
                    ready.extend(chunk);
                    line = ready.pop_front();
                }
                Ok(Err(e)) => return Err(Error::new_err(e)),
                Err(_) => return Ok(None),
            }
        }
        let Some(line) = line else {
            return Ok(None);
        };
        let value: serde_json::Value = serde_json::from_slice(&line)
            .map_err(|e| Error::new_err(format!("an event that is not JSON (a bug): {e}")))?;
        to_python(py, &value).map(Some)
    }
}

/// A JSON value as the Python object `json.loads` makes of it.
fn to_python(py: Python<'_>, v: &serde_json::Value) -> PyResult<Py<PyAny>> {
    use serde_json::Value as J;
    Ok(match v {
        J::Null => py.None(),
        J::Bool(b) => b.into_pyobject(py)?.to_owned().into_any().unbind(),
        J::Number(n) => match (n.as_i64(), n.as_u64(), n.as_f64()) {
            (Some(i), _, _) => i.into_pyobject(py)?.into_any().unbind(),
            (None, Some(u), _) => u.into_pyobject(py)?.into_any().unbind(),
            (None, None, f) => f.unwrap_or(f64::NAN).into_pyobject(py)?.into_any().unbind(),
        },
        J::String(s) => s.into_pyobject(py)?.into_any().unbind(),
        J::Array(a) => {
            let list = PyList::empty(py);
            for x in a {
                list.append(to_python(py, x)?)?;
            }
            list.into_any().unbind()
        }
        J::Object(o) => {
            let dict = PyDict::new(py);
            for (k, x) in o {
                dict.set_item(k, to_python(py, x)?)?;
            }
            dict.into_any().unbind()
        }
    })
}

/// The run's events, lazily: `for e in vcnc.events(text): …`.
#[pyfunction]
#[pyo3(signature = (text, dialect = "auto", machine = None, tools = None, program_dir = None, block_delete = false, optional_stop = false, keep_going = false))]
#[allow(clippy::too_many_arguments)]
fn events(
    text: &Bound<'_, PyAny>,
    dialect: &str,
    machine: Option<&Bound<'_, PyAny>>,
    tools: Option<&Bound<'_, PyAny>>,
    program_dir: Option<&Bound<'_, PyAny>>,
    block_delete: bool,
    optional_stop: bool,
    keep_going: bool,
) -> PyResult<Events> {
    let bytes = program_bytes(text)?;
    let s = setup(
        &bytes,
        dialect,
        machine,
        tools,
        program_dir,
        block_delete,
        optional_stop,
        keep_going,
    )?;
    let (tx, rx) = bounded::<Chunk>(4);
    let gone = Arc::new(AtomicBool::new(false));
    let feed_gone = Arc::clone(&gone);
    let started = std::thread::Builder::new()
        .name("vcnc-events".into())
        .stack_size(16 << 20)
        .spawn(move || {
            let errors = tx.clone();
            let ran = catch_unwind(AssertUnwindSafe(|| {
                let mut feed = Feed {
                    tx,
                    axes: EventAxes::new(&s.machine),
                    chunk: Vec::with_capacity(CHUNK),
                    gone: feed_gone,
                };
                let _ = s.run(bytes, &mut feed);
                feed.flush();
            }));
            if ran.is_err() {
                let _ = errors.send(Err(
                    "internal error in vcnc (a bug): the run panicked".into()
                ));
            }
        });
    if let Err(e) = started {
        return Err(Error::new_err(format!(
            "cannot start the run's thread: {e}"
        )));
    }
    Ok(Events {
        rx,
        ready: Mutex::new(std::collections::VecDeque::new()),
        gone,
    })
}

/// The dialect names `dialect=` accepts besides `"auto"`.
#[pyfunction]
fn dialects() -> Vec<&'static str> {
    Dialect::NAMES.to_vec()
}

/// The `vcnc` module.
#[pymodule]
fn vcnc(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("Error", m.py().get_type::<Error>())?;
    m.add("ProgramAlarm", m.py().get_type::<ProgramAlarm>())?;
    m.add_class::<Diagnostic>()?;
    m.add_class::<Result>()?;
    m.add_class::<Time>()?;
    m.add_class::<Events>()?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(events, m)?)?;
    m.add_function(wrap_pyfunction!(flatten, m)?)?;
    m.add_function(wrap_pyfunction!(time, m)?)?;
    m.add_function(wrap_pyfunction!(dialects, m)?)?;
    Ok(())
}
