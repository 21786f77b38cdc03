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
use vcnc_interp::detect::{self, Confidence, Detection, PREFIX_BYTES};
use vcnc_interp::{Dialect, Machine};

/// What `--dialect` may name besides the dialects.
pub const AUTO: &str = "auto";

/// The choices the options make for every program.
pub(crate) struct Choice {
    /// `--dialect NAME`, when not auto.
    forced: Option<&'static Dialect>,
    /// `--machine FILE`.
    machine: Option<Machine>,
    /// The built-in machine of each dialect, in `Dialect::NAMES` order,
    /// parsed the first time a program needs it.
    defaults: Vec<OnceLock<Machine>>,
    options: vcnc_interp::Options,
}

/// One program's dialect and machine, and why.
pub(crate) struct Setup<'a> {
    pub machine: &'a Machine,
    pub dialect: &'static Dialect,
    pub options: vcnc_interp::Options,
    /// What detection found; `None` under `--dialect NAME`.
    pub detection: Option<Detection>,
}

impl Choice {
    /// Reads the options: an unknown dialect or an unreadable machine file
    /// is a usage error.
    pub fn new(c: &Options) -> Result<Choice, String> {
        let forced = match c.dialect.as_deref() {
            None => None,
            Some(name) if name.eq_ignore_ascii_case(AUTO) => None,
            Some(name) => Some(detect::dialect(name).ok_or_else(|| {
                format!(
                    "unknown dialect {name:?}: use auto or one of {}",
                    Dialect::NAMES.join(", ")
                )
            })?),
        };
        let machine = match &c.machine {
            Some(path) => {
                let text = std::fs::read_to_string(path)
                    .map_err(|e| format!("cannot read machine file {}: {e}", path.display()))?;
                Some(
                    Machine::from_toml(&text)
                        .map_err(|e| format!("machine file {}: {e}", path.display()))?,
                )
            }
            None => None,
        };
        Ok(Choice {
            forced,
            machine,
            defaults: Dialect::NAMES.iter().map(|_| OnceLock::new()).collect(),
            options: vcnc_interp::Options {
                block_delete: c.block_delete,
                optional_stop: c.optional_stop,
                keep_going: c.keep_going,
            },
        })
    }

    /// The dialect and machine of one program: detection reads its first
    /// [`PREFIX_BYTES`] unless `--dialect` named one.
    pub fn setup(&self, input: &Input) -> Result<Setup<'_>, String> {
        let (dialect, detection) = match self.forced {
            Some(d) => (d, None),
            None => {
                let found = detect::detect(&input.head(PREFIX_BYTES)?, input.file_name());
                let d = detect::dialect(found.dialect)
                    .ok_or_else(|| format!("detection chose {}, no dialect", found.dialect))?;
                (d, Some(found))
            }
        };
        let machine = match &self.machine {
            Some(m) => m,
            None => self.default_machine(dialect)?,
        };
        Ok(Setup {
            machine,
            dialect,
            options: self.options,
            detection,
        })
    }

    fn default_machine(&self, dialect: &'static Dialect) -> Result<&Machine, String> {
        let cell = Dialect::NAMES
            .iter()
            .position(|n| *n == dialect.name)
            .and_then(|i| self.defaults.get(i))
            .ok_or_else(|| format!("no built-in machine for dialect {}", dialect.name))?;
        Ok(cell.get_or_init(|| dialect.machine()))
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
