//! `vcnc`, the command line: checks and runs part programs on a virtual
//! controller. This is the only crate that touches files, the terminal and
//! the process exit code; everything else is a library.
//!
//! Exit codes (docs/cli.md): 0 clean run, 1 an alarm (or a warning under
//! `--deny-warnings`), 2 usage error (bad arguments, unreadable file,
//! invalid machine file).

mod check;
mod cli;
mod explain;
mod files;
mod offload;
mod plot;
mod render;
mod timing;
mod trace;
mod variables;

use clap::Parser;
use cli::{Cli, Command, Format, Options, RunArgs};
use files::Input;
use std::io::{BufWriter, Write};
use std::process::ExitCode;
use vcnc_interp::{Dialect, Event, Interpreter, Machine, Outcome, Sink};
use vcnc_output::{CsvSink, GcodeSink, JsonlSink, Summary};

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(message) => {
            eprintln!("error: {message}");
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

/// The dialect named `name` (any case), or a usage error naming them all.
pub(crate) fn dialect_by_name(name: &str) -> Result<Dialect, String> {
    Dialect::by_name(&name.to_ascii_lowercase()).ok_or_else(|| {
        format!(
            "unknown dialect {name:?}: use one of {}",
            Dialect::NAMES.join(", ")
        )
    })
}

/// The machine and dialect the options ask for.
pub(crate) struct Setup {
    pub machine: Machine,
    pub dialect: Dialect,
    pub options: vcnc_interp::Options,
}

/// The options' machine and dialect for the programs at `paths`. Without
/// `--dialect`: syntec, or linuxcnc when every path is a `.ngc` file
/// (LinuxCNC's own extension, which no Syntec or Fanuc program carries).
pub(crate) fn setup(c: &Options, paths: &[&std::path::Path]) -> Result<Setup, String> {
    let ngc = |p: &&std::path::Path| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ngc"));
    let name = match &c.dialect {
        Some(name) => name.as_str(),
        None if !paths.is_empty() && paths.iter().all(ngc) => "linuxcnc",
        None => "syntec",
    };
    let dialect = dialect_by_name(name)?;
    let machine = match &c.machine {
        Some(path) => {
            let text = std::fs::read_to_string(path)
                .map_err(|e| format!("cannot read machine file {}: {e}", path.display()))?;
            Machine::from_toml(&text)
                .map_err(|e| format!("machine file {}: {e}", path.display()))?
        }
        None => dialect.machine(),
    };
    let options = vcnc_interp::Options {
        block_delete: c.block_delete,
        optional_stop: c.optional_stop,
        keep_going: c.keep_going,
    };
    Ok(Setup {
        machine,
        dialect,
        options,
    })
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
    let mut interp = Interpreter::new(&s.machine, &s.dialect, s.options);
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
    let s = setup(&args.opts, &[args.file.as_path()])?;
    // Opened before any output is written, so that a missing file is a
    // usage error with nothing on stdout.
    let input = Input::from_arg(&args.file)?;
    drop(input.open()?);
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
        Format::Gcode => stream(args, &s, &input, || {
            GcodeSink::new(
                BufWriter::with_capacity(1 << 16, std::io::stdout()),
                machine,
            )
        })?,
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
        warnings: Summary::new(&s.machine),
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
