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
        /// Output format: JSON lines (the event contract), CSV, a flattened plain G-code program, or the planned trajectory sampled every --period seconds.
        #[arg(long, value_enum, default_value_t = Format::Jsonl)]
        format: Format,
        /// Sampling period of --format trace, seconds.
        #[arg(long, default_value_t = 0.001)]
        period: f64,
        /// Speed profile of --format trace (default: the machine file's).
        #[arg(long, value_enum)]
        profile: Option<ProfileArg>,
    },
    /// Plan the motion on the machine model and print the cycle time and its split.
    Time(TimeArgs),
}

/// `vcnc time FILE…`.
#[derive(Debug, Args)]
pub struct TimeArgs {
    /// The programs.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Dialect: syntec (Syntec 900M mill), fanuc (Fanuc 0i mill) or lathe (the seed lathe controller).
    #[arg(long, default_value = "syntec")]
    pub dialect: String,
    /// Machine file (TOML); default: the built-in machine of the dialect.
    #[arg(long)]
    pub machine: Option<PathBuf>,
    /// Where called programs are looked up; default: each program's directory.
    #[arg(long)]
    pub program_dir: Option<PathBuf>,
    /// Block delete switch on.
    #[arg(long)]
    pub block_delete: bool,
    /// Optional stop switch on.
    #[arg(long)]
    pub optional_stop: bool,
    /// Output: text for people, or one JSON object per program.
    #[arg(long, value_enum, default_value_t = TimeFormat::Text)]
    pub format: TimeFormat,
    /// Speed profile (default: the machine file's).
    #[arg(long, value_enum)]
    pub profile: Option<ProfileArg>,
}

/// Output formats of `vcnc time`.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum TimeFormat {
    /// For people.
    Text,
    /// One JSON object per program.
    Json,
}

/// Speed profile shapes.
#[derive(Debug, Clone, Copy, ValueEnum)]
pub enum ProfileArg {
    /// Constant acceleration ramps.
    Trapezoid,
    /// Jerk-limited S-curve ramps.
    Jerk,
}

impl From<ProfileArg> for vcnc_planner::ProfileShape {
    fn from(p: ProfileArg) -> Self {
        match p {
            ProfileArg::Trapezoid => vcnc_planner::ProfileShape::Trapezoid,
            ProfileArg::Jerk => vcnc_planner::ProfileShape::Jerk,
        }
    }
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
    /// The planned trajectory as CSV samples (docs/planner.md).
    Trace,
}
