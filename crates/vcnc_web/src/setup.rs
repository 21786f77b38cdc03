//! The dialect, machine and tools of one call, chosen as the CLI chooses
//! them (`crates/vcnc/src/choose.rs`): a named dialect, or detection by
//! `vcnc_interp::detect` over the text's first 64 KiB and its file name,
//! with its evidence; the machine file's text (TOML, or a grbl `$$` dump)
//! or the dialect's built-in machine; a tool table's text (LinuxCNC `.tbl`
//! or CSV) written into the machine's registers in the dialect's tip
//! numbering, and with the CAM header comments the tools' shapes.

use serde::{Deserialize, Serialize};
use vcnc_core::tooling::{self, ToolLibrary};
use vcnc_interp::detect::{self, PREFIX_BYTES};
use vcnc_interp::{Dialect, Machine};

/// What the page passes with a program.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// A name of [`Dialect::NAMES`] (any case), or `None`/`"auto"`.
    pub dialect: Option<String>,
    /// The program's file name, when it came from a file (detection reads
    /// its extension).
    pub file_name: Option<String>,
    /// A machine file's text: TOML, or a grbl `$$` dump.
    pub machine: Option<String>,
    /// A tool table's text (LinuxCNC `.tbl` or CSV).
    pub tools: Option<String>,
    /// The tool table's file name (in messages; `.tbl` or `.csv` picks
    /// the reader).
    pub tools_name: Option<String>,
    /// Block delete (`/`) is on.
    pub block_delete: bool,
    /// Optional stop (M01) is on.
    pub optional_stop: bool,
}

/// The dialect a program runs in, and why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DialectChoice {
    /// Its name.
    pub name: &'static str,
    /// The page's picker named it (no detection).
    pub given: bool,
    /// Detection's evidence (`["--dialect"]` when given).
    pub evidence: Vec<String>,
    /// `high`, `low`, or `given`.
    pub confidence: &'static str,
    /// In words, as `vcnc check` says it: `haas (auto: G187, …)`.
    pub why: String,
}

/// One call's dialect, machine and tools.
#[derive(Debug)]
pub struct Setup {
    /// The dialect's tables.
    pub dialect: &'static Dialect,
    /// The machine, the tool table's offsets written in.
    pub machine: Machine,
    /// How the dialect was chosen.
    pub choice: DialectChoice,
    /// The tools' shapes: the table's, else the CAM comments'.
    pub tools: ToolLibrary,
    /// The interpreter's switches (keep-going is the caller's).
    pub options: vcnc_interp::Options,
}

/// The dialect names the picker offers besides auto.
pub fn dialects() -> Vec<&'static str> {
    Dialect::NAMES.to_vec()
}

/// What detection says of `text` (named `file_name`).
pub fn detect(text: &str, file_name: Option<&str>) -> DialectChoice {
    let head = text.as_bytes();
    let head = head.get(..PREFIX_BYTES).unwrap_or(head);
    let found = detect::detect(head, file_name);
    DialectChoice {
        name: found.dialect,
        given: false,
        evidence: found.evidence.clone(),
        confidence: found.confidence.as_str(),
        why: format!("{} ({})", found.dialect, found.describe()),
    }
}

/// How much of a program is read for the tool lists of CAM comments (as
/// the CLI's `TOOL_COMMENTS_BYTES`).
const TOOL_COMMENTS_BYTES: usize = 1 << 20;

impl Setup {
    /// Reads the settings: an unknown dialect, a machine file or a tool
    /// table that cannot be read is an error in words (the page shows it).
    pub fn new(text: &str, s: &Settings) -> Result<Setup, String> {
        let choice = match s.dialect.as_deref().map(str::trim) {
            None | Some("") => detect(text, s.file_name.as_deref()),
            Some(name) if name.eq_ignore_ascii_case("auto") => detect(text, s.file_name.as_deref()),
            Some(name) => {
                let d = Dialect::named(name).ok_or_else(|| {
                    format!(
                        "unknown dialect {name:?}: use auto or one of {}",
                        Dialect::NAMES.join(", ")
                    )
                })?;
                DialectChoice {
                    name: d.name,
                    given: true,
                    evidence: vec!["--dialect".to_string()],
                    confidence: "given",
                    why: format!("{} (chosen)", d.name),
                }
            }
        };
        let dialect = Dialect::named(choice.name)
            .ok_or_else(|| format!("detection chose {}, no dialect", choice.name))?;
        let mut machine = match s.machine.as_deref() {
            None => dialect.machine(),
            Some(m) if vcnc_core::grbl_settings::looks_like_settings(m) => {
                vcnc_core::grbl_settings::machine(m, "machine").map_err(|e| e.to_string())?
            }
            Some(m) => Machine::from_toml(m).map_err(|e| format!("machine file: {e}"))?,
        };
        let head = text.get(..TOOL_COMMENTS_BYTES).unwrap_or(text);
        let comments = tooling::from_comments(head);
        let tools = match s.tools.as_deref() {
            None => comments,
            Some(t) => {
                let name = s.tools_name.as_deref().unwrap_or("tools.tbl");
                let table = tooling::read_table(t, name).map_err(|e| e.to_string())?;
                table.fill_registers(&mut machine, dialect.tip_numbering);
                table.or_else(&comments)
            }
        };
        Ok(Setup {
            dialect,
            machine,
            choice,
            tools,
            options: vcnc_interp::Options {
                block_delete: s.block_delete,
                optional_stop: s.optional_stop,
                keep_going: false,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    #[test]
    fn a_haas_program_is_detected_with_its_evidence() {
        let s = Setup::new(
            "%\nO1000 (HAAS VF2)\nG187 P1\nM30\n%\n",
            &Settings::default(),
        )
        .unwrap();
        assert_eq!(s.choice.name, "haas");
        assert!(!s.choice.given);
        assert!(
            s.choice.evidence.iter().any(|e| e.contains("G187")),
            "{:?}",
            s.choice
        );
    }

    #[test]
    fn a_named_dialect_wins_and_an_unknown_one_is_an_error() {
        let named = Settings {
            dialect: Some("GRBL".into()),
            ..Settings::default()
        };
        let s = Setup::new("G187 P1\n", &named).unwrap();
        assert_eq!(s.choice.name, "grbl");
        assert_eq!(s.choice.confidence, "given");
        let bad = Settings {
            dialect: Some("okuma".into()),
            ..Settings::default()
        };
        let e = Setup::new("G0 X0\n", &bad).unwrap_err();
        assert!(e.contains("okuma") && e.contains("linuxcnc"), "{e}");
    }

    #[test]
    fn a_bad_machine_file_is_an_error_in_words() {
        let bad = Settings {
            machine: Some("[axes\nx = 1".into()),
            ..Settings::default()
        };
        assert!(
            Setup::new("G0 X0\n", &bad)
                .unwrap_err()
                .starts_with("machine file")
        );
    }
}
