//! The kept-variables file of `--variables FILE`: the macro variables a
//! controller keeps across power-off (Fanuc #500–#999; Syntec #401–#999,
//! @656–@1999), read before a run and written after it, so that a counter
//! or a probed offset survives from one run to the next as on the machine.
//!
//! ```text
//!   // vcnc kept macro variables      comments: lines starting with //
//!   #500 = 12.5                       a real number (Macro B, Syntec Double)
//!   @700 = 3                          a Syntec Long: no decimal point
//! ```
//!
//! The interpreter never touches files: it takes and gives the values as a
//! map (`Interpreter::restore_variables`, `kept_variables`).

use std::collections::BTreeMap;
use std::path::Path;
use vcnc_syntax::macros::Value;

/// Reads `path`; a missing file is an empty set (the first run).
pub fn read(path: &Path) -> Result<BTreeMap<String, Value>, String> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(e) => {
            return Err(format!(
                "cannot read variables file {}: {e}",
                path.display()
            ));
        }
    };
    parse(&text).map_err(|e| format!("variables file {}: {e}", path.display()))
}

/// Parses the file's text.
pub fn parse(text: &str) -> Result<BTreeMap<String, Value>, String> {
    let mut out = BTreeMap::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with("//") {
            continue;
        }
        let bad = || format!("line {}: expected `#500 = 1.5`, found {line:?}", k + 1);
        let (name, value) = line.split_once('=').ok_or_else(bad)?;
        let (name, value) = (name.trim(), value.trim());
        let long = !value.contains(['.', 'e', 'E']);
        let value = if long {
            Value::Long(value.parse().map_err(|_| bad())?)
        } else {
            // Rust's parser reads inf and NaN: only finite numbers pass.
            let x: f64 = value.parse().map_err(|_| bad())?;
            if !x.is_finite() {
                return Err(bad());
            }
            Value::Double(x)
        };
        out.insert(name.to_string(), value);
    }
    Ok(out)
}

/// The file's text for `values`.
pub fn format(values: &BTreeMap<String, Value>) -> String {
    let mut s = String::from("// vcnc kept macro variables (--variables)\n");
    for (name, v) in values {
        match v {
            Value::Long(i) => s.push_str(&format!("{name} = {i}\n")),
            // Debug prints the shortest text that reads back exactly, with a point.
            Value::Double(x) => s.push_str(&format!("{name} = {x:?}\n")),
            Value::Null => {}
        }
    }
    s
}

/// Writes `values` to `path`.
pub fn write(path: &Path, values: &BTreeMap<String, Value>) -> Result<(), String> {
    std::fs::write(path, format(values))
        .map_err(|e| format!("cannot write variables file {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_read_back_as_written() {
        let mut m = BTreeMap::new();
        m.insert("#500".to_string(), Value::Double(0.1));
        m.insert("#501".to_string(), Value::Double(5.0));
        m.insert("@700".to_string(), Value::Long(-3));
        let text = format(&m);
        assert!(
            text.contains("#501 = 5.0\n") && text.contains("@700 = -3\n"),
            "{text}"
        );
        assert_eq!(parse(&text).unwrap(), m);
    }

    #[test]
    fn bad_lines_are_reported() {
        assert!(parse("#500 12").is_err());
        assert!(parse("#500 = inf").is_err());
        assert!(parse("#500 = 1e400").is_err());
        assert!(parse("#500 = x").is_err());
    }
}
