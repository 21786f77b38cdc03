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
use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
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

/// Writes `values` to `path` atomically: a reader (or the next run after a
/// crash or a full disk) sees the old file or the new one, never a part.
pub fn write(path: &Path, values: &BTreeMap<String, Value>) -> Result<(), String> {
    write_via(path, format(values).as_bytes(), |file, bytes| {
        file.write_all(bytes)
    })
    .map_err(|e| format!("cannot write variables file {}: {e}", path.display()))
}

/// Counts the temporary files of this process, so that two writes of one
/// process never share a name.
static TEMP_COUNT: AtomicU64 = AtomicU64::new(0);

/// The atomic write: `fill` writes `bytes` into a new temporary file in
/// `path`'s folder (a rename is atomic only within one file system), which
/// is flushed to the disk (fsync) and then renamed over `path`; the
/// folder is synced so that the rename survives a power cut too. On any
/// failure the temporary file is removed and `path` is left as it was.
///
/// ```text
///   vars.txt            (old, intact until the rename)
///   .vars.txt.4711-0.tmp ── write, fsync ──rename──▶ vars.txt
/// ```
fn write_via(
    path: &Path,
    bytes: &[u8],
    fill: impl FnOnce(&mut File, &[u8]) -> io::Result<()>,
) -> io::Result<()> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "the path names no file"))?;
    let n = TEMP_COUNT.fetch_add(1, Ordering::Relaxed);
    let mut temp_name = std::ffi::OsString::from(".");
    temp_name.push(name);
    temp_name.push(format!(".{}-{n}.tmp", std::process::id()));
    let temp = folder.join(temp_name);
    let written = (|| {
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)?;
        fill(&mut file, bytes)?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&temp, path)
    })();
    if let Err(e) = written {
        // Best effort: the temporary file may not exist.
        let _ = std::fs::remove_file(&temp);
        return Err(e);
    }
    // The rename is in the folder's entries: sync it where the system
    // lets a folder be opened (not on Windows).
    if let Ok(dir) = File::open(folder) {
        let _ = dir.sync_all();
    }
    Ok(())
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

    fn temp_folder(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("vcnc-vars-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// The folder's entries other than `keep`.
    fn others(dir: &Path, keep: &str) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != keep)
            .collect()
    }

    #[test]
    fn a_write_that_fails_halfway_leaves_the_old_file_intact() {
        let dir = temp_folder("halfway");
        let path = dir.join("vars.txt");
        let old = "// vcnc kept macro variables (--variables)\n#500 = 1.0\n";
        std::fs::write(&path, old).unwrap();
        let mut m = BTreeMap::new();
        m.insert("#500".to_string(), Value::Double(2.0));
        m.insert("#501".to_string(), Value::Double(3.0));
        let text = format(&m);
        // A writer that stops halfway, as on a full disk.
        let failed = write_via(&path, text.as_bytes(), |file, bytes| {
            file.write_all(&bytes[..bytes.len() / 2])?;
            Err(io::Error::other("no space left on device"))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), old);
        assert!(
            others(&dir, "vars.txt").is_empty(),
            "{:?}",
            others(&dir, "vars.txt")
        );
        // The ordinary write replaces it whole.
        write(&path, &m).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
        assert!(others(&dir, "vars.txt").is_empty());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_write_into_a_missing_folder_fails_and_creates_nothing() {
        let dir = temp_folder("missing");
        let path = dir.join("absent").join("vars.txt");
        assert!(write(&path, &BTreeMap::new()).is_err());
        assert!(!dir.join("absent").exists());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn bad_lines_are_reported() {
        assert!(parse("#500 12").is_err());
        assert!(parse("#500 = inf").is_err());
        assert!(parse("#500 = 1e400").is_err());
        assert!(parse("#500 = x").is_err());
    }
}
