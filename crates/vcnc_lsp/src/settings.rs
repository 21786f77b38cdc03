//! The client's settings (`vcnc.*` in VS Code; `settings.vcnc` in any
//! client's `workspace/didChangeConfiguration`, or `initializationOptions`
//! at start), and the machine file they name, read once per change.
//!
//! | setting            | meaning                                                  |
//! |--------------------|----------------------------------------------------------|
//! | `dialect`          | a dialect name, or `auto` (the default)                  |
//! | `machine`          | a machine file (TOML, docs/machine.md); relative to the workspace |
//! | `tools`            | a tool table (LinuxCNC `.tbl` or CSV): its offsets fill the machine's H and D registers (`--tools` of the command line) |
//! | `programDir`       | where `M98 P10` finds `O0010` (default: the program's folder) |
//! | `blockDelete`      | skip blocks that start with `/`                          |
//! | `optionalStop`     | stop at M01                                              |
//! | `inlayHints`       | show each operation's planned time (off by default)      |

use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vcnc_interp::Machine;

/// What the client set.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", default)]
pub struct Settings {
    /// A dialect name, or `auto`.
    pub dialect: Option<String>,
    /// A machine file.
    pub machine: Option<String>,
    /// A tool table (not read yet: the tool-table reader is on its way).
    pub tools: Option<String>,
    /// The directory of called programs.
    pub program_dir: Option<String>,
    /// The block delete switch.
    pub block_delete: bool,
    /// The optional stop switch.
    pub optional_stop: bool,
    /// Planned time per operation as inlay hints.
    pub inlay_hints: bool,
}

impl Settings {
    /// The settings in `value`: `{ "vcnc": { … } }` or `{ … }` itself; what
    /// cannot be read is left at its default.
    pub fn from_json(value: &serde_json::Value) -> Settings {
        let inner = value.get("vcnc").unwrap_or(value);
        serde_json::from_value(inner.clone()).unwrap_or_default()
    }

    /// The machine file, read and checked (`None`: the dialect's own).
    pub fn load_machine(&self, root: Option<&Path>) -> Result<Option<Arc<Machine>>, String> {
        let Some(name) = self.machine.as_deref().filter(|m| !m.trim().is_empty()) else {
            return Ok(None);
        };
        let path = resolve(name, root);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read machine file {}: {e}", path.display()))?;
        Machine::from_toml(&text)
            .map(|m| Some(Arc::new(m)))
            .map_err(|e| format!("machine file {}: {e}", path.display()))
    }

    /// The tool table (LinuxCNC `.tbl` or CSV), read and checked (`None`:
    /// none set); its offsets are written into the machine's registers of
    /// each run (`Job::machine`).
    pub fn load_tools(
        &self,
        root: Option<&Path>,
    ) -> Result<Option<Arc<vcnc_core::ToolLibrary>>, String> {
        let Some(name) = self.tools.as_deref().filter(|t| !t.trim().is_empty()) else {
            return Ok(None);
        };
        let path = resolve(name, root);
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("cannot read tool table {}: {e}", path.display()))?;
        vcnc_core::tooling::read_table(&text, &path.display().to_string())
            .map(|t| Some(Arc::new(t)))
            .map_err(|e| e.to_string())
    }

    /// The program directory, if set.
    pub fn program_dir(&self, root: Option<&Path>) -> Option<PathBuf> {
        self.program_dir
            .as_deref()
            .filter(|d| !d.trim().is_empty())
            .map(|d| resolve(d, root))
    }
}

/// A path as the user wrote it: absolute, or relative to the workspace.
fn resolve(name: &str, root: Option<&Path>) -> PathBuf {
    let p = PathBuf::from(name);
    match root {
        Some(r) if p.is_relative() => r.join(p),
        _ => p,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn settings_are_read_with_or_without_their_section() {
        let a = Settings::from_json(&json!({"vcnc": {"dialect": "haas", "inlayHints": true}}));
        let b = Settings::from_json(&json!({"dialect": "haas", "inlayHints": true}));
        assert_eq!(a, b);
        assert_eq!(a.dialect.as_deref(), Some("haas"));
        assert!(a.inlay_hints);
        // Junk leaves the defaults.
        assert_eq!(
            Settings::from_json(&json!({"vcnc": 7})),
            Settings::default()
        );
    }

    #[test]
    fn a_missing_or_bad_machine_file_is_a_message() {
        let s = Settings {
            machine: Some("no/such/machine.toml".into()),
            ..Settings::default()
        };
        let e = s.load_machine(Some(Path::new("/nowhere"))).unwrap_err();
        assert!(e.contains("/nowhere/no/such/machine.toml"), "{e}");
    }
}
