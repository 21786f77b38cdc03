//! Command-line arguments (clap derive).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use vcnc_interp::Dialect;

/// vcnc, a virtual CNC controller: runs a part program as a Syntec/Fanuc
/// controller would and reports what the machine does.
#[derive(Debug, Parser)]
#[command(name = "vcnc", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run whole programs; print alarms, warnings and a summary (one file: cycle time, distances, extents, tools, spindle; several: one line each and a total).
    Check(CheckArgs),
    /// Run the program and print its event stream.
    Run(RunArgs),
}

/// `vcnc check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Programs, or directories searched recursively for .nc .ngc .tap .cnc .gcode .mpf .txt files and extension-less O-number files; `-` reads a program from standard input.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Report format: text for people, one JSON document, or SARIF 2.1.0 for CI annotations.
    #[arg(long, value_enum, default_value_t = CheckFormat::Text)]
    pub format: CheckFormat,
    /// Warnings fail the check (exit 1), as alarms do.
    #[arg(long)]
    pub deny_warnings: bool,
    /// Programs checked at once (default: one per core).
    #[arg(long)]
    pub jobs: Option<usize>,
}

/// `vcnc run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The main program (`-`: standard input).
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output format: JSON lines (the event contract), CSV, or a flattened plain G-code program.
    #[arg(long, value_enum, default_value_t = Format::Jsonl)]
    pub format: Format,
    /// Warnings fail the run (exit 1), as alarms do.
    #[arg(long)]
    pub deny_warnings: bool,
}

/// Options every subcommand takes.
#[derive(Debug, Clone, Args)]
pub struct Options {
    /// Dialect: syntec (Syntec 900M mill), fanuc (Fanuc 0i mill), lathe (the seed lathe controller), eia (EIA-274-D), grbl (grbl 1.1 and hobby CAM output), haas (Haas mills) or fanuc-lathe (Fanuc 0i-TF and Haas lathes).
    #[arg(long, default_value = "syntec", value_parser = clap::builder::PossibleValuesParser::new(Dialect::NAMES.iter().copied()))]
    pub dialect: String,
    /// Machine file (TOML); default: the built-in mill (X Y Z A B C, no travel limits), or a 2-axis lathe under --dialect lathe and fanuc-lathe.
    #[arg(long)]
    pub machine: Option<PathBuf>,
    /// Where called programs (M98 P10 → O0010 or O0010.nc) are looked up; default: the program's directory.
    #[arg(long)]
    pub program_dir: Option<PathBuf>,
    /// Block delete switch on: skip blocks that start with `/`.
    #[arg(long)]
    pub block_delete: bool,
    /// Optional stop switch on: stop at M01.
    #[arg(long)]
    pub optional_stop: bool,
}

/// Output formats of `vcnc run`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum Format {
    /// One JSON object per event (docs/events.md).
    Jsonl,
    /// One CSV row per event.
    Csv,
    /// A flattened plain program for grbl or LinuxCNC.
    Gcode,
}

/// Report formats of `vcnc check`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum CheckFormat {
    /// Lines for people.
    Text,
    /// One JSON document (docs/cli.md).
    Json,
    /// SARIF 2.1.0.
    Sarif,
}
