//! `vcnc`, the command line: checks and runs part programs on a virtual
//! controller. This is the only crate that touches files, the terminal and
//! the process exit code; everything else is a library.
//!
//! Exit codes: 0 clean run, 1 the program raised an alarm, 2 usage error
//! (bad arguments, unreadable file, invalid machine file).

mod cli;
mod files;
mod plot;
mod render;

use clap::Parser;
use cli::{Cli, Command, Common, Format};
use std::io::{BufWriter, Write};
use std::process::ExitCode;
use vcnc_interp::{Dialect, Interpreter, Machine, Outcome, Sink};
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
        Command::Check { common } => check(&common),
        Command::Run { common, format } => run_events(&common, format),
        Command::Plot(args) => plot::plot(&args),
    }
}

/// Everything a run needs, resolved from the common options.
struct Setup {
    /// The main program, opened before any output is written so that a
    /// missing file is a usage error with nothing on stdout.
    main: Option<Box<dyn vcnc_syntax::TextSource>>,
    machine: Machine,
    dialect: Dialect,
    options: vcnc_interp::Options,
}

fn setup(c: &Common) -> Result<Setup, String> {
    let dialect = Dialect::by_name(&c.dialect).ok_or_else(|| {
        format!(
            "unknown dialect {:?}: use one of {}",
            c.dialect,
            Dialect::NAMES.join(", ")
        )
    })?;
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
    };
    Ok(Setup {
        main: Some(files::open_program(&c.file)?),
        machine,
        dialect,
        options,
    })
}

/// Runs the program of `c` into `sink`.
/// Returns how the run ended and whether it ended in diameter programming.
fn execute<S: Sink>(c: &Common, s: &mut Setup, sink: &mut S) -> Result<(Outcome, bool), String> {
    let main = s.main.take().ok_or("the program was already run")?;
    let dir = c
        .program_dir
        .clone()
        .unwrap_or_else(|| files::parent_dir(&c.file));
    let mut store = files::DirStore::new(dir);
    let mut interp = Interpreter::new(&s.machine, &s.dialect, s.options);
    let outcome = interp.run(main, &mut store, sink);
    Ok((outcome, interp.state().modal.diameter))
}

fn check(c: &Common) -> Result<ExitCode, String> {
    let mut s = setup(c)?;
    let mut summary = Summary::new(&s.machine);
    let (outcome, diameter) = execute(c, &mut s, &mut summary)?;
    if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, &c.file));
    }
    let mut out = std::io::stdout().lock();
    let diameter_axis = s.dialect.diameter.axis.filter(|_| diameter);
    render::summary(
        &mut out,
        c,
        &s.dialect,
        &s.machine,
        &summary,
        &outcome,
        diameter_axis,
    )
    .map_err(|e| e.to_string())?;
    Ok(exit_code(&outcome))
}

fn run_events(c: &Common, format: Format) -> Result<ExitCode, String> {
    let mut s = setup(c)?;
    // The JSON-lines sink buffers itself; the others go through a BufWriter.
    let out = std::io::stdout().lock();
    // One monomorphic run per format: the sink is on the hot path.
    let (outcome, written) = match format {
        Format::Jsonl => {
            let sink = JsonlSink::new(out, &s.machine);
            stream(c, &mut s, sink)?
        }
        Format::Csv => {
            let sink = CsvSink::new(BufWriter::with_capacity(1 << 16, out), &s.machine);
            stream(c, &mut s, sink)?
        }
        Format::Gcode => {
            let sink = GcodeSink::new(BufWriter::with_capacity(1 << 16, out), &s.machine);
            stream(c, &mut s, sink)?
        }
    };
    match written {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => return Err(format!("writing output: {e}")),
        Ok(()) => {}
    }
    if let Outcome::Alarm(d) = &outcome {
        eprint!("{}", render::diagnostic(d, &c.file));
    }
    let _ = std::io::stderr().flush();
    Ok(exit_code(&outcome))
}

/// Runs into `sink` and flushes it.
fn stream<S: Sink>(
    c: &Common,
    s: &mut Setup,
    mut sink: S,
) -> Result<(Outcome, std::io::Result<()>), String> {
    let (outcome, _) = execute(c, s, &mut sink)?;
    Ok((outcome, sink.finish()))
}

fn exit_code(o: &Outcome) -> ExitCode {
    match o {
        // Stopped: the reader of the output went away (`vcnc run | head`).
        Outcome::Ended(_) | Outcome::Stopped => ExitCode::SUCCESS,
        Outcome::Alarm(_) => ExitCode::from(1),
    }
}
