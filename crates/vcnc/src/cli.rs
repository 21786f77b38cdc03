//! Command-line arguments (clap derive).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

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
    /// Run the whole program; print alarms and a summary (cycle time, distances, extents, tools, spindle).
    Check {
        /// Program and machine options.
        #[command(flatten)]
        common: Common,
    },
    /// Run the program and print its event stream.
    Run {
        /// Program and machine options.
        #[command(flatten)]
        common: Common,
        /// Output format: JSON lines (the event contract), CSV, or a flattened plain G-code program.
        #[arg(long, value_enum, default_value_t = Format::Jsonl)]
        format: Format,
    },
    /// Draw the program's path: an SVG or PNG back-plot, or an HTML page with a 3D viewer.
    Plot(crate::plot::PlotArgs),
}

/// Options every subcommand takes.
#[derive(Debug, Args)]
pub struct Common {
    /// The main program.
    pub file: PathBuf,
    /// Dialect: syntec (Syntec 900M mill), fanuc (Fanuc 0i mill) or lathe (the seed lathe controller).
    #[arg(long, default_value = "syntec")]
    pub dialect: String,
    /// Machine file (TOML); default: the built-in 3-axis mill, or the 2-axis lathe under --dialect lathe.
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
