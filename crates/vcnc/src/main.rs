//! `vcnc`, the command line: checks and runs part programs on a virtual
//! controller. This is the only crate that touches files, the terminal and
//! the process exit code; everything else is a library.
//!
//! Exit codes (docs/cli.md): 0 clean run, 1 an alarm (or a warning under
//! `--deny-warnings`), 2 usage error (bad arguments, unreadable file,
//! invalid machine file).

mod check;
mod choose;
mod cli;
mod explain;
mod files;
mod machine_print;
mod offload;
mod plot;
mod render;
mod sim;
mod timing;
mod tools;
mod trace;
mod variables;

use clap::Parser;
use cli::{Cli, Command, Format, Options, RunArgs};
use files::Input;
use std::io::{BufWriter, Write};
use std::process::ExitCode;
use vcnc_core::grbl_settings;
use vcnc_interp::{Event, Interpreter, Machine, Outcome, Sink};
use vcnc_output::{CsvSink, GcodeOptions, GcodeSink, JsonlSink, Summary};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(message) => {
            // Tool tables and machine files are quoted in these messages:
            // their control characters are shown, not obeyed.
            eprintln!("error: {}", render::visible(&message));
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode, String> {
    match cli.command {
        Command::Check(args) => check::check(&args),
        Command::Run(args) => run_events(&args),
        Command::Time(args) => timing::time(&args),
        Command::Plot(args) => plot::plot(&args),
        Command::Explain(args) => explain::run(&args),
        Command::Tools(args) => tools::tools(&args),
        Command::Machine(args) => machine_print::print(&args),
        Command::Sim(args) => sim::sim(&args),
        Command::Lsp => vcnc_lsp::serve_stdio().map(|()| ExitCode::SUCCESS),
    }
}

/// Output written to standard output (`run`'s events, `check`'s report):
/// a reader that closed the pipe (`vcnc check big.nc | head -3`) has what
/// it wanted; any other error is the output's.
pub(crate) fn reported(r: std::io::Result<()>) -> Result<(), String> {
    match r {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => r.map_err(|e| format!("writing output: {e}")),
    }
}

pub(crate) use choose::{MachineFrom, Setup};

/// Largest machine file, tool table or `$$` dump read: each is a page of
/// text, so a larger file is the wrong one (and is not read into memory).
const MAX_SETTINGS_FILE: u64 = 16 << 20;

/// A text file the user names (a machine file, a tool table), read whole
/// (lossily: a comment in another encoding must not refuse a table) up to
/// [`MAX_SETTINGS_FILE`].
pub(crate) fn read_text(path: &std::path::Path, what: &str) -> Result<String, String> {
    let text = read_prefix(path, what, MAX_SETTINGS_FILE + 1)?;
    if text.len() as u64 > MAX_SETTINGS_FILE {
        return Err(format!(
            "{what} {} is larger than {} MiB: is it the right file?",
            path.display(),
            MAX_SETTINGS_FILE >> 20
        ));
    }
    Ok(text)
}

/// At most the first `limit` bytes of a file, as text (lossily).
pub(crate) fn read_prefix(
    path: &std::path::Path,
    what: &str,
    limit: u64,
) -> Result<String, String> {
    use std::io::Read;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read {what} {}: {e}", path.display()))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// `--machine FILE`: a machine file (TOML) or grbl's `$$` dump.
pub(crate) fn read_machine(path: &std::path::Path) -> Result<(Machine, MachineFrom), String> {
    let text = read_text(path, "machine file")?;
    let file = path.display().to_string();
    if grbl_settings::looks_like_settings(&text) {
        let m = grbl_settings::machine(&text, &file).map_err(|e| e.to_string())?;
        return Ok((m, MachineFrom::GrblSettings(file)));
    }
    let m = Machine::from_toml(&text).map_err(|e| format!("machine file {file}: {e}"))?;
    Ok((m, MachineFrom::File(file)))
}

/// Runs the program `input` into `sink`. Returns how the run ended and
/// whether it ended in diameter programming.
pub(crate) fn execute<S: Sink>(
    c: &Options,
    s: &Setup,
    input: &Input,
    sink: &mut S,
) -> Result<(Outcome, bool), String> {
    let main = input.open()?;
    let dir = c.program_dir.clone().unwrap_or_else(|| input.dir());
    let mut store = files::DirStore::new(dir);
    let mut interp = Interpreter::new(s.machine, s.dialect, s.options);
    if s.markers {
        interp = interp.with_program_markers();
    }
    if let Some(path) = &c.variables {
        let kept = variables::read(path)?;
        interp
            .restore_variables(&kept)
            .map_err(|e| format!("variables file {}: {e}", path.display()))?;
    }
    let outcome = interp.run(main, &mut store, sink);
    if let Some(path) = &c.variables {
        variables::write(path, &interp.kept_variables())?;
    }
    Ok((outcome, interp.state().modal.diameter))
}

fn run_events(args: &RunArgs) -> Result<ExitCode, String> {
    let choice =
        choose::Choice::new(&args.opts)?.with_markers(matches!(args.format, Format::Gcode));
    // Opened before any output is written, so that a missing file is a
    // usage error with nothing on stdout.
    let input = Input::from_arg(&args.file)?;
    drop(input.open()?);
    let s = choice.setup(&input)?;
    if s.doubtful() {
        eprintln!(
            "note: dialect {}; give --dialect to be sure",
            s.dialect_text()
        );
    }
    // The sink formats and writes on the second core (`offload`); the
    // JSON-lines sink buffers itself, the others go through a BufWriter.
    let machine = &s.machine;
    let (outcome, warnings, written) = match args.format {
        Format::Jsonl => stream(args, &s, &input, || {
            JsonlSink::new(std::io::stdout(), machine)
        })?,
        Format::Csv => stream(args, &s, &input, || {
            CsvSink::new(
                BufWriter::with_capacity(1 << 16, std::io::stdout()),
                machine,
            )
        })?,
        Format::Gcode => {
            let opts = GcodeOptions {
                coords: match args.coords {
                    cli::Coords::Work => vcnc_output::Coords::Work,
                    cli::Coords::Machine => vcnc_output::Coords::Machine,
                },
                units: args.opts.units.map(|u| match u {
                    cli::UnitsArg::Mm => vcnc_output::Units::Mm,
                    cli::UnitsArg::In => vcnc_output::Units::Inch,
                }),
            };
            stream(args, &s, &input, || {
                GcodeSink::with_options(
                    BufWriter::with_capacity(1 << 16, std::io::stdout()),
                    machine,
                    opts,
                )
            })?
        }
        Format::Trace => {
            let profile = args.profile.map(Into::into);
            trace::check_period(machine, args.period, profile)?;
            stream(args, &s, &input, || {
                trace::TraceSink::new(std::io::stdout(), machine, args.period, profile)
            })?
        }
    };
    reported(written)?;
    eprint!("{}", render::warnings(&warnings, &input));
    if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, &input));
    }
    let _ = std::io::stderr().flush();
    let denied = args.deny_warnings && warnings.warning_total() > 0;
    Ok(exit_code(&outcome, denied))
}

/// A sink that passes events on and keeps the warnings (in a summary) for
/// the terminal.
struct Tap<S> {
    inner: S,
    warnings: Summary,
}

impl<S: Sink> Sink for Tap<S> {
    fn event(&mut self, e: &Event) {
        if matches!(e, Event::Warning(_)) {
            self.warnings.event(e);
        }
        self.inner.event(e);
    }
    fn take_events(&mut self, events: &mut Vec<Event>) {
        for e in events.iter().filter(|e| matches!(e, Event::Warning(_))) {
            self.warnings.event(e);
        }
        self.inner.take_events(events);
    }
    fn is_done(&self) -> bool {
        self.inner.is_done()
    }
}

type Streamed = (Outcome, Summary, std::io::Result<()>);

/// Runs into the sink `make` builds (on the second core when there is one)
/// and flushes it.
fn stream<S: Sink + Send + 'static>(
    args: &RunArgs,
    s: &Setup,
    input: &Input,
    make: impl Fn() -> S,
) -> Result<Streamed, String> {
    let mut tap = Tap {
        inner: offload::Offload::start(make),
        warnings: Summary::new(s.machine),
    };
    let ran = execute(&args.opts, s, input, &mut tap);
    // The sink is taken back also when the run failed (the variables file
    // could not be written), and then dropped unfinished as it was when it
    // ran in line: the events still in its chunk reach it and its buffer
    // is flushed before the error is reported.
    let sink = tap.inner.join();
    let (outcome, _) = ran?;
    let written = sink?.finish();
    Ok((outcome, tap.warnings, written))
}

/// 1 for an alarm, or for warnings when they are denied.
pub(crate) fn exit_code(o: &Outcome, denied_warnings: bool) -> ExitCode {
    match o {
        Outcome::Alarm(_) => ExitCode::from(1),
        _ if denied_warnings => ExitCode::from(1),
        // Stopped: the reader of the output went away (`vcnc run | head`).
        Outcome::Ended(_) | Outcome::Stopped => ExitCode::SUCCESS,
    }
}
