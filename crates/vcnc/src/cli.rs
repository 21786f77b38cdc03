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
    /// Plan the motion on the machine model and print the cycle time and its split.
    Time(TimeArgs),
    /// Draw the program's path: an SVG or PNG back-plot, or an HTML page with a 3D viewer.
    Plot(crate::plot::PlotArgs),
    /// What a G or M code, or an address, means in each dialect (from the interpreter's own tables).
    Explain(ExplainArgs),
    /// List the tools a program uses: their shapes and sizes, their offset registers, and where each figure came from.
    Tools(ToolsArgs),
    /// Print the machine a run uses as a machine file to start from (TOML).
    Machine(MachineArgs),
    /// Simulate material removal: the volume removed, collisions (rapid into stock, holder, table), the finished part as STL, PNG or a replay page.
    Sim(crate::sim::SimArgs),
    /// A language server for editors over standard input and output (docs/editor.md).
    Lsp,
}

/// `vcnc explain`.
#[derive(Debug, Args)]
pub struct ExplainArgs {
    /// A G or M code (`G87`, `G59.1`, `M98`) or an address (`X`, `D`).
    pub code: Option<String>,
    /// Only this dialect (default: every dialect, those that agree on one line).
    #[arg(long)]
    pub dialect: Option<String>,
    /// Print the dialect matrix: every code of every table (Markdown).
    #[arg(long, conflicts_with = "code")]
    pub matrix: bool,
}

/// `vcnc tools FILE`.
#[derive(Debug, Args)]
pub struct ToolsArgs {
    /// The program (`-`: standard input).
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output: text for people, or one JSON document.
    #[arg(long, value_enum, default_value_t = TimeFormat::Text)]
    pub format: TimeFormat,
}

/// `vcnc machine --print`.
#[derive(Debug, Args)]
pub struct MachineArgs {
    /// Print the machine file: the built-in machine of --dialect (default syntec), or the one --machine reads (a TOML file as it is, a grbl `$$` dump as the TOML it makes).
    #[arg(long, required = true)]
    pub print: bool,
    /// Dialect whose built-in machine is printed (see `vcnc check --help`).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Dialect::NAMES.iter().copied()))]
    pub dialect: Option<String>,
    /// Machine file (TOML) or grbl `$$` dump to print instead.
    #[arg(long)]
    pub machine: Option<PathBuf>,
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
    /// Also simulate material removal from this stock (as `vcnc sim --stock`): the volume removed and the collisions join the report.
    #[arg(long)]
    pub stock: Option<String>,
}

/// `vcnc run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The main program (`-`: standard input).
    pub file: PathBuf,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output format: JSON lines (the event contract), CSV, a flattened plain G-code program, or the planned trajectory sampled every --period seconds.
    #[arg(long, value_enum, default_value_t = Format::Jsonl)]
    pub format: Format,
    /// Warnings fail the run (exit 1), as alarms do.
    #[arg(long)]
    pub deny_warnings: bool,
    /// Coordinates of --format gcode: work (the program's first work coordinate system, written out; a machine with the same work offsets moves as the original did) or machine (absolute machine coordinates under G53's frame, with the power-on position first, for comparisons).
    #[arg(long, value_enum, default_value_t = Coords::Work)]
    pub coords: Coords,
    /// Sampling period of --format trace, seconds.
    #[arg(long, default_value_t = 0.001)]
    pub period: f64,
    /// Speed profile of --format trace (default: the machine file's).
    #[arg(long, value_enum)]
    pub profile: Option<ProfileArg>,
}

/// `vcnc time PATH…`.
#[derive(Debug, Args)]
pub struct TimeArgs {
    /// Programs, or directories searched recursively as `check` does; `-` reads a program from standard input.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Program and machine options.
    #[command(flatten)]
    pub opts: Options,
    /// Output: text for people, or one JSON object per program.
    #[arg(long, value_enum, default_value_t = TimeFormat::Text)]
    pub format: TimeFormat,
    /// Speed profile (default: the machine file's).
    #[arg(long, value_enum)]
    pub profile: Option<ProfileArg>,
}

/// Length units a person or a flattened program reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum UnitsArg {
    /// Millimetres.
    Mm,
    /// Inches.
    In,
}

impl From<UnitsArg> for vcnc_core::display::DisplayUnits {
    fn from(u: UnitsArg) -> Self {
        match u {
            UnitsArg::Mm => vcnc_core::display::DisplayUnits::Mm,
            UnitsArg::In => vcnc_core::display::DisplayUnits::In,
        }
    }
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
    /// Jerk-limited S-curve ramps in every block.
    Jerk,
    /// Trapezoid ramps through a moving-average filter (acceleration and
    /// deceleration after interpolation).
    Filter,
}

impl From<ProfileArg> for vcnc_planner::ProfileShape {
    fn from(p: ProfileArg) -> Self {
        match p {
            ProfileArg::Trapezoid => vcnc_planner::ProfileShape::Trapezoid,
            ProfileArg::Jerk => vcnc_planner::ProfileShape::Jerk,
            ProfileArg::Filter => vcnc_planner::ProfileShape::Filter,
        }
    }
}

/// Options every subcommand takes.
#[derive(Debug, Clone, Args)]
pub struct Options {
    /// Dialect: auto (the default: chosen per file from its own evidence, and said), syntec (Syntec 900M mill), fanuc (Fanuc 0i mill), lathe (the seed lathe controller), eia (EIA-274-D), grbl (grbl 1.1 and hobby CAM output), haas (Haas mills), fanuc-lathe (Fanuc 0i-TF lathes), haas-lathe (Haas lathes), linuxcnc (LinuxCNC 2.9 RS274NGC mills) linuxcnc-lathe (the same in lathe mode: G7/G8, XZ plane) or mach3 (Mach3: RS274/NGC with O-number M98/M99 subprograms and M-code macros); any case.
    #[arg(long, ignore_case = true, value_parser = dialect_names())]
    pub dialect: Option<String>,
    /// Machine file (TOML) or grbl's `$$` settings dump; default: the built-in mill (X Y Z A B C, no travel limits, empty offset memory), or a 2-axis lathe under --dialect lathe, fanuc-lathe, haas-lathe and linuxcnc-lathe.
    #[arg(long)]
    pub machine: Option<PathBuf>,
    /// Tool table: LinuxCNC `.tbl` (T P D Z …, D a diameter, in mm) or CSV with the header `tool,diameter,corner_radius,length,flute_length,holder_diameter[,shank_diameter,stickout,units]`. It fills the H (length) and D (radius) registers of its tools and gives their shapes; without it, shapes come from the program's CAM header comments, which never fill registers.
    #[arg(long, value_name = "FILE")]
    pub tools: Option<PathBuf>,
    /// Units of lengths: those people read (the summaries of check and time, vcnc tools, plot legends and the page; default mm) and those `run --format gcode` writes (default: the program's own).
    #[arg(long, value_enum)]
    pub units: Option<UnitsArg>,
    /// Where called programs (M98 P10 → O0010 or O0010.nc) are looked up; default: the program's directory.
    #[arg(long)]
    pub program_dir: Option<PathBuf>,
    /// Block delete switch on: skip blocks that start with `/`.
    #[arg(long)]
    pub block_delete: bool,
    /// Optional stop switch on: stop at M01.
    #[arg(long)]
    pub optional_stop: bool,
    /// After an alarm, go on with the next block (the state as it was before the alarmed one) and report every alarm; the exit code is still 1.
    #[arg(long)]
    pub keep_going: bool,
    /// Keep the macro variables a controller keeps across power-off (Fanuc #500-#999; Syntec #401-#999, @656-@1999) in FILE: read before the run when it exists, written after it. One program at a time.
    #[arg(long, value_name = "FILE")]
    pub variables: Option<PathBuf>,
}

/// `auto` and every dialect name, matched in any case.
fn dialect_names() -> clap::builder::PossibleValuesParser {
    let names = std::iter::once(crate::choose::AUTO).chain(Dialect::NAMES.iter().copied());
    clap::builder::PossibleValuesParser::new(names)
}

/// The coordinates `run --format gcode` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Coords {
    /// The program's first work coordinate system (G54 if none), written out.
    Work,
    /// Absolute machine coordinates, from the power-on position.
    Machine,
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
