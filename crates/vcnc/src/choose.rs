//! Which dialect and machine each program runs on: `--dialect NAME` (any
//! case) for every program, or `--dialect auto` (the default) chosen per
//! file by `vcnc_interp::detect` from the file's first 64 KiB and its name;
//! `--machine FILE` for every program, or the built-in machine of each
//! program's dialect, each read once.
//!
//! ```text
//!   Options ─▶ Choice (the forced dialect, the machine file, a cache of
//!              built-in machines) ─▶ per Input: Setup (dialect, machine,
//!              and the Detection that chose them)
//! ```

use crate::cli::Options;
use crate::files::Input;
use std::sync::OnceLock;
use vcnc_core::tooling::{self, ToolKind, ToolLibrary, ToolShape, ToolSource};
use vcnc_interp::detect::{self, Confidence, Detection, PREFIX_BYTES};
use vcnc_interp::{Dialect, Machine};

/// What `--dialect` may name besides the dialects.
pub const AUTO: &str = "auto";

/// The choices the options make for every program.
pub(crate) struct Choice {
    /// `--dialect NAME`, when not auto.
    forced: Option<&'static Dialect>,
    /// `--machine FILE` (a TOML file or a grbl `$$` dump), and where the
    /// machine came from.
    machine: Option<Machine>,
    machine_from: MachineFrom,
    /// `--tools FILE`: the table and its file name; its offsets are
    /// written into each dialect's machine.
    table: Option<(ToolLibrary, String)>,
    /// The machine of each dialect (`--machine`'s or the dialect's
    /// built-in one, with `--tools`' registers written in the dialect's
    /// tip numbering), in `Dialect::NAMES` order, made the first time a
    /// program needs it.
    machines: Vec<OnceLock<Machine>>,
    options: vcnc_interp::Options,
    /// Runs emit the markers of program coordinates (the flattened
    /// program's: `Interpreter::with_program_markers`).
    markers: bool,
}

/// Where a run's machine came from (`vcnc tools` says where offsets come
/// from).
pub(crate) enum MachineFrom {
    /// The dialect's built-in machine.
    BuiltIn,
    /// A machine file (TOML).
    File(String),
    /// A grbl `$$` dump.
    GrblSettings(String),
}

/// One program's dialect and machine, and why.
pub(crate) struct Setup<'a> {
    pub machine: &'a Machine,
    pub dialect: &'static Dialect,
    pub options: vcnc_interp::Options,
    /// What detection found; `None` under `--dialect NAME`.
    pub detection: Option<Detection>,
    /// Where the machine came from.
    pub machine_from: &'a MachineFrom,
    /// The tool table of `--tools` and its file name, already written
    /// into `machine`'s registers.
    pub table: Option<&'a (ToolLibrary, String)>,
    /// Runs emit the markers of program coordinates.
    pub markers: bool,
}

impl Choice {
    /// Reads the options: an unknown dialect or an unreadable machine file
    /// is a usage error.
    pub fn new(c: &Options) -> Result<Choice, String> {
        let forced = match c.dialect.as_deref() {
            None => None,
            Some(name) if name.eq_ignore_ascii_case(AUTO) => None,
            Some(name) => Some(Dialect::named(name).ok_or_else(|| {
                format!(
                    "unknown dialect {name:?}: use auto or one of {}",
                    Dialect::NAMES.join(", ")
                )
            })?),
        };
        let (machine, machine_from) = match &c.machine {
            Some(path) => {
                let (m, from) = crate::read_machine(path)?;
                (Some(m), from)
            }
            None => (None, MachineFrom::BuiltIn),
        };
        let table = match &c.tools {
            Some(path) => {
                let file = path.display().to_string();
                let text = crate::read_text(path, "tool table")?;
                let lib = tooling::read_table(&text, &file).map_err(|e| e.to_string())?;
                Some((lib, file))
            }
            None => None,
        };
        Ok(Choice {
            forced,
            machine,
            machine_from,
            table,
            machines: Dialect::NAMES.iter().map(|_| OnceLock::new()).collect(),
            options: vcnc_interp::Options {
                block_delete: c.block_delete,
                optional_stop: c.optional_stop,
                keep_going: c.keep_going,
            },
            markers: false,
        })
    }

    /// Runs emit the markers of program coordinates (for `run --format
    /// gcode`).
    pub fn with_markers(mut self, markers: bool) -> Choice {
        self.markers = markers;
        self
    }

    /// The dialect and machine of one program: detection reads its first
    /// [`PREFIX_BYTES`] unless `--dialect` named one.
    pub fn setup(&self, input: &Input) -> Result<Setup<'_>, String> {
        let (dialect, detection) = match self.forced {
            Some(d) => (d, None),
            None => {
                let found = detect::detect(&input.head(PREFIX_BYTES)?, input.file_name());
                let d = Dialect::named(found.dialect)
                    .ok_or_else(|| format!("detection chose {}, no dialect", found.dialect))?;
                (d, Some(found))
            }
        };
        let machine = self.machine_of(dialect)?;
        // The machine's G-code system renumbers a Fanuc lathe's codes.
        let dialect = dialect.for_system(machine.gcode_system);
        Ok(Setup {
            machine,
            dialect,
            options: self.options,
            detection,
            machine_from: &self.machine_from,
            table: self.table.as_ref(),
            markers: self.markers,
        })
    }

    /// The machine a program of `dialect` runs on: `--machine`'s or the
    /// dialect's built-in one, with `--tools`' offsets in its registers.
    fn machine_of(&self, dialect: &'static Dialect) -> Result<&Machine, String> {
        let cell = Dialect::NAMES
            .iter()
            .position(|n| *n == dialect.name)
            .and_then(|i| self.machines.get(i))
            .ok_or_else(|| format!("no built-in machine for dialect {}", dialect.name))?;
        Ok(cell.get_or_init(|| {
            let mut m = self.machine.clone().unwrap_or_else(|| dialect.machine());
            if let Some((lib, _)) = &self.table {
                lib.fill_registers(&mut m, dialect.tip_numbering);
            }
            m
        }))
    }

    /// The name of `--machine`'s machine, if one was given.
    pub fn machine_name(&self) -> Option<&str> {
        self.machine.as_ref().map(|m| m.name.as_str())
    }

    /// Whether `--dialect` named a dialect (then reports need not say it
    /// per program).
    pub fn is_forced(&self) -> bool {
        self.forced.is_some()
    }
}

impl Setup<'_> {
    /// `haas (auto: G187, "(HAAS VF2)" header)`, or `fanuc (--dialect)`.
    pub fn dialect_text(&self) -> String {
        match &self.detection {
            Some(d) => format!("{} ({})", self.dialect.name, d.describe()),
            None => format!("{} (--dialect)", self.dialect.name),
        }
    }

    /// The evidence list for JSON and SARIF (`["--dialect"]` when given).
    pub fn evidence(&self) -> Vec<String> {
        match &self.detection {
            Some(d) => d.evidence.clone(),
            None => vec!["--dialect".to_string()],
        }
    }

    /// `high`, `low`, or `given` under `--dialect`.
    pub fn confidence(&self) -> &'static str {
        match &self.detection {
            Some(d) => d.confidence.as_str(),
            None => "given",
        }
    }

    /// Whether detection was unsure.
    pub fn doubtful(&self) -> bool {
        self.detection
            .as_ref()
            .is_some_and(|d| d.confidence == Confidence::Low)
    }
}

/// How much of a program's text is read for the tool lists CAM posts write
/// in their header comments.
pub const TOOL_COMMENTS_BYTES: usize = 1 << 20;

impl Setup<'_> {
    /// The shapes of the run's tools, for plots and the simulation: the
    /// `--tools` table's, else the tool lists of the program's header
    /// comments (`head`: its first bytes), else what the offset registers
    /// say (a mill's D radius as a flat end mill, a lathe's nose radius and
    /// tip). Comments never fill registers; registers never override a
    /// table or a comment.
    pub fn tool_library(&self, head: &str) -> ToolLibrary {
        let comments = tooling::from_comments(head);
        let registers = registers_library(self.machine, self.dialect.diameter.lathe);
        let described = match self.table {
            Some((table, _)) => table.clone().or_else(&comments),
            None => comments,
        };
        described.or_else(&registers)
    }
}

/// The tools the machine's offset registers describe: a lathe's inserts by
/// their nose radius and tip, a mill's cutters as flat end mills of twice
/// their D radius (geometry + wear; a register of 0 describes nothing).
fn registers_library(machine: &Machine, lathe: bool) -> ToolLibrary {
    let mut lib = ToolLibrary::default();
    for (n, t) in &machine.tools {
        let shape = if lathe {
            let nose = t.nose_radius_mm + t.nose_radius_wear_mm;
            ToolShape {
                kind: ToolKind::Turning {
                    nose_radius_mm: nose,
                    tip: t.tip,
                },
                diameter_mm: 2.0 * nose,
                source: ToolSource::Registers,
                ..ToolShape::assumed(*n)
            }
        } else {
            let radius = t.d_mm + t.d_wear_mm;
            if radius <= 0.0 {
                continue;
            }
            ToolShape {
                diameter_mm: 2.0 * radius,
                source: ToolSource::Registers,
                ..ToolShape::assumed(*n)
            }
        };
        lib.insert(shape);
    }
    lib
}
