//! grbl's settings dump (`$$`) as a machine: what `--machine` reads when it
//! is given the text grbl prints, so a hobby machine is described by the
//! numbers its controller already holds.
//!
//! ```text
//!   $100=250.000  $101=250.000  $102=250.000     steps/mm        X Y Z
//!   $110=500.000  $111=500.000  $112=500.000     max rate mm/min  → rapid and max feed
//!   $120=10.000   $121=10.000   $122=10.000      accel mm/s²      → accel_mm_s2
//!   $130=200.000  $131=200.000  $132=200.000     max travel mm    → min_mm = -travel, max_mm = 0
//!   $11 junction deviation → motion.corner_tolerance_mm   $30 max spindle → max_spindle_rpm
//!   $20 soft limits: travel limits only when 1 (grbl checks them only then)
//! ```
//!
//! grbl's machine space is all negative (`limits.c`: "By default, Grbl
//! defines machine space as all negative"), so an axis of travel T runs
//! from −T to 0 in machine coordinates. grbl plans trapezoids (no jerk), so
//! the machine plans with the `trapezoid` profile. grblHAL's fourth to
//! sixth axes ($103–$105, $113–$115, …) become A, B and C. Steps per mm are
//! read and checked (positive) but the model has no use for them. Other
//! settings ($0–$32, grblHAL's $300s) are valid and not used; banner,
//! `ok`, `[…]` and `<…>` lines are skipped.
//!
//! The dump becomes a commented machine file ([`machine_toml`]), which
//! [`crate::Machine::from_toml`] validates like any other; `vcnc machine
//! --print --machine dump.txt` prints that file. A malformed dump is a
//! [`SettingsError`] naming the file, the line and what is wrong.

use crate::decimal;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// Why a settings dump was refused: where, what, how to fix it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SettingsError {
    /// The file's name as given.
    pub file: String,
    /// The 1-based line (0: the dump as a whole).
    pub line: u32,
    /// What is wrong.
    pub message: String,
}

impl std::fmt::Display for SettingsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "grbl settings {}:{}: {} (a `$$` dump is lines `$<number>=<value>`, as grbl prints them)",
            self.file, self.line, self.message
        )
    }
}

impl std::error::Error for SettingsError {}

/// Highest setting number read (grblHAL's go to the 700s).
const MAX_SETTING: u64 = 9_999;
/// Longest line read.
const MAX_LINE: usize = 256;
/// Most settings lines (grblHAL prints a few hundred).
const MAX_SETTINGS: usize = 2_000;
/// Largest rate, acceleration, travel or steps/mm accepted.
const MAX_VALUE: f64 = 1e7;

/// Axis letters by grbl's axis index (grblHAL: 3 A, 4 B, 5 C).
const AXES: [&str; 6] = ["x", "y", "z", "a", "b", "c"];

/// Whether `text` reads as a `$$` dump: its first line that holds anything
/// but grbl's messages (`[MSG:…]`, `<Idle…>`, `ok`) is a setting (`$0=10`)
/// or grbl's banner.
pub fn looks_like_settings(text: &str) -> bool {
    text.lines()
        .map(str::trim)
        .find(|l| {
            !(l.is_empty()
                || l.starts_with('[')
                || l.starts_with('<')
                || l.eq_ignore_ascii_case("ok"))
        })
        .is_some_and(|l| {
            l.starts_with("Grbl")
                || l.strip_prefix('$')
                    .is_some_and(|r| r.starts_with(|c: char| c.is_ascii_digit()))
        })
}

/// The settings of a dump, by number, with their lines.
fn settings(text: &str, file: &str) -> Result<BTreeMap<u64, (f64, u32)>, SettingsError> {
    let mut out: BTreeMap<u64, (f64, u32)> = BTreeMap::new();
    for (i, raw) in text.lines().enumerate() {
        let line = u32::try_from(i + 1).unwrap_or(u32::MAX);
        let err = |message: String| SettingsError {
            file: file.to_string(),
            line,
            message,
        };
        if raw.len() > MAX_LINE {
            return Err(err(format!("the line is {} bytes long", raw.len())));
        }
        let l = raw.trim();
        // grbl 0.9 printed a description after the value: `$100=250.000 (x, step/mm)`.
        let l = l.split_once(" (").map_or(l, |(s, _)| s).trim();
        if l.is_empty()
            || l.eq_ignore_ascii_case("ok")
            || l.starts_with('[')
            || l.starts_with('<')
            || l.starts_with("Grbl ")
            || l.starts_with("GrblHAL ")
        {
            continue;
        }
        let Some((key, value)) = l.strip_prefix('$').and_then(|r| r.split_once('=')) else {
            return Err(err(format!("`{l}` is not a setting")));
        };
        let n = decimal::whole(key, MAX_SETTING)
            .ok_or_else(|| err(format!("`${key}` is not a setting number")))?;
        let v = decimal::parse(value)
            .ok_or_else(|| err(format!("${n} = `{value}` is not a number")))?;
        if let Some((_, first)) = out.get(&n) {
            return Err(err(format!("${n} is set twice (first on line {first})")));
        }
        if out.len() >= MAX_SETTINGS {
            return Err(err(format!("more than {MAX_SETTINGS} settings")));
        }
        out.insert(n, (v, line));
    }
    Ok(out)
}

/// The machine a `$$` dump describes (through [`machine_toml`]).
pub fn machine(text: &str, file: &str) -> Result<crate::Machine, SettingsError> {
    let toml = machine_toml(text, file)?;
    crate::Machine::from_toml(&toml).map_err(|e| SettingsError {
        file: file.to_string(),
        line: 0,
        message: e.0,
    })
}

/// The machine file (TOML) a `$$` dump describes, commented with the
/// settings each value comes from. `file` names the dump in errors and
/// in the machine's name.
pub fn machine_toml(text: &str, file: &str) -> Result<String, SettingsError> {
    let s = settings(text, file)?;
    let err = |line: u32, message: String| SettingsError {
        file: file.to_string(),
        line,
        message,
    };
    let get = |n: u64| s.get(&n).copied();
    let positive = |n: u64, what: &str| -> Result<Option<f64>, SettingsError> {
        match get(n) {
            None => Ok(None),
            Some((v, _)) if v > 0.0 && v <= MAX_VALUE => Ok(Some(v)),
            Some((v, line)) => Err(err(
                line,
                format!("${n} ({what}) = {v}: it must be more than 0 and at most {MAX_VALUE}"),
            )),
        }
    };
    let soft_limits = get(20).is_some_and(|(v, _)| v != 0.0);
    let mut axes = String::new();
    for (i, letter) in (0u64..).zip(AXES) {
        let steps = positive(100 + i, "steps/mm")?;
        let rate = positive(110 + i, "max rate, mm/min")?;
        let accel = positive(120 + i, "acceleration, mm/s²")?;
        // Travel 0 is an axis without travel (a rotary axis on grblHAL).
        let travel = match get(130 + i) {
            Some((0.0, _)) => None,
            _ => positive(130 + i, "max travel, mm")?,
        };
        if i >= 3 && steps.is_none() && rate.is_none() && accel.is_none() && travel.is_none() {
            continue;
        }
        let (Some(rate), Some(accel)) = (rate, accel) else {
            let missing = if rate.is_none() { 110 + i } else { 120 + i };
            return Err(err(
                0,
                format!(
                    "the dump has no ${missing} for axis {}: copy all of grbl's `$$` output",
                    letter.to_uppercase()
                ),
            ));
        };
        let _ = writeln!(axes, "\n[[axes]]\nletter = \"{letter}\"");
        if let Some(steps) = steps {
            let _ = writeln!(
                axes,
                "# ${} = {steps} steps/mm (not used by the model)",
                100 + i
            );
        }
        match travel {
            Some(t) if soft_limits => {
                let _ = writeln!(
                    axes,
                    "min_mm = {:?}          # -${}: grbl's machine space is negative",
                    -t,
                    130 + i
                );
                let _ = writeln!(axes, "max_mm = 0.0");
            }
            Some(t) => {
                let _ = writeln!(
                    axes,
                    "# ${} = {t} mm of travel: no limits, as soft limits are off ($20 = 0)",
                    130 + i
                );
            }
            None => {}
        }
        let _ = writeln!(
            axes,
            "rapid_mm_per_min = {rate:?}   # ${} max rate",
            110 + i
        );
        let _ = writeln!(axes, "max_feed_mm_per_min = {rate:?}");
        let _ = writeln!(axes, "accel_mm_s2 = {accel:?}   # ${}", 120 + i);
    }
    let junction = positive(11, "junction deviation, mm")?;
    let spindle = get(30)
        .map(|(v, _)| v)
        .filter(|v| *v > 0.0 && *v <= MAX_VALUE);
    let name = format!("grbl machine from {file}").replace(['"', '\\', '\n'], "");
    let mut out = format!(
        "# A machine file made from grbl's settings (`$$`) in {file}\n# (docs/machine.md). Edit it, or give the dump itself with --machine.\nname = \"{name}\"\n\n# Power-on: grbl's machine position is 0 until homing.\nstart_mm = {{ x = 0.0, y = 0.0, z = 0.0 }}\n"
    );
    out.push_str(&axes);
    out.push_str("\n# grbl plans constant-acceleration ramps (no jerk limit).\n[motion]\nprofile = \"trapezoid\"\n");
    if let Some(j) = junction {
        let _ = writeln!(
            out,
            "corner_tolerance_mm = {j:?}   # $11 junction deviation"
        );
    }
    out.push_str("\n[parameters]\n# grbl reads integers as whole millimetres.\ndecimal_input = \"calculator\"\n");
    if let Some(rpm) = spindle {
        let _ = writeln!(out, "max_spindle_rpm = {rpm:?}   # $30");
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn banner_and_settings_are_recognised() {
        assert!(looks_like_settings("\n$0=10\n"));
        assert!(looks_like_settings("Grbl 1.1h ['$' for help]\n$0=10\n"));
        assert!(!looks_like_settings("name = \"mill\"\n"));
        assert!(!looks_like_settings("$HX\n"));
        assert!(looks_like_settings("[MSG:settings]\nok\n$0=10\n"));
        assert!(!looks_like_settings("[parameters]\ng00_mode = 0\n"));
    }
}
