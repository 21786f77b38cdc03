//! `vcnc machine --print`: the machine a run uses, as a machine file to
//! start from.
//!
//! Without `--machine` it is the dialect's built-in machine: the embedded
//! file itself (`crates/vcnc_core/src/default_*.toml`), every key commented,
//! under a header that says how to use it. With `--machine` it is that file
//! as it is, or the commented TOML a grbl `$$` dump becomes. Whatever is
//! printed reads back to the machine the run would use (a test holds it).

use crate::cli::MachineArgs;
use crate::reported;
use std::io::Write;
use std::process::ExitCode;
use vcnc_core::grbl_settings;
use vcnc_interp::Dialect;

/// Runs `vcnc machine --print`.
pub fn print(args: &MachineArgs) -> Result<ExitCode, String> {
    let text = match &args.machine {
        Some(path) => {
            // Read through the same reader as a run, so that a file the run
            // would refuse is refused here too.
            crate::read_machine(path)?;
            let text = crate::read_text(path, "machine file")?;
            let file = path.display().to_string();
            if grbl_settings::looks_like_settings(&text) {
                grbl_settings::machine_toml(&text, &file).map_err(|e| e.to_string())?
            } else {
                text
            }
        }
        None => {
            let name = args.dialect.as_deref().unwrap_or("syntec");
            let dialect = Dialect::by_name(name).ok_or_else(|| {
                format!(
                    "unknown dialect {name:?}: use one of {}",
                    Dialect::NAMES.join(", ")
                )
            })?;
            format!(
                "# vcnc machine --print --dialect {name}: the built-in machine of the {name}\n\
                 # dialect. Save it, edit it (docs/machine.md) and give it with --machine FILE.\n\
                 #\n{}",
                dialect.default_machine
            )
        }
    };
    reported(std::io::stdout().write_all(text.as_bytes()))?;
    Ok(ExitCode::SUCCESS)
}
