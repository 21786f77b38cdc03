//! Which dialect a document is read in, decided in one function
//! ([`choose`]) for the language server and the Python module alike.
//!
//! In order: a first-line comment `(vcnc: --dialect haas)` (or `; vcnc:
//! --dialect grbl`), which travels with the program; then the client's
//! `vcnc.dialect` setting; then the document itself, by the detector the
//! command line uses for `--dialect auto` (`vcnc_interp::detect`: the
//! extension, header comments, codes only one family knows, lathe signs,
//! how integers are written), with its evidence as the reason.

use std::path::Path;
use vcnc_interp::Dialect;

/// The dialect chosen for a document, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Choice {
    /// A name of [`Dialect::NAMES`].
    pub name: &'static str,
    /// Why, in words (shown in the hover).
    pub why: String,
}

impl Choice {
    /// The dialect's tables.
    pub fn dialect(&self) -> Dialect {
        // `name` is one of `Dialect::NAMES`, so `by_name` finds it.
        Dialect::by_name(self.name).unwrap_or_else(Dialect::fanuc)
    }
}

/// The dialect of the program `text` at `path` (none: an unsaved buffer or
/// a Python string), given the client's `setting` (`None` or `"auto"`:
/// none). An unknown name in the first line or the setting is an error
/// that names the dialects there are.
pub fn choose(text: &str, path: Option<&Path>, setting: Option<&str>) -> Result<Choice, String> {
    if let Some(name) = first_line_dialect(text) {
        return Ok(Choice {
            name: known(&name).ok_or_else(|| unknown("the first-line comment", &name))?,
            why: "from the first-line comment".into(),
        });
    }
    match setting.map(str::trim) {
        None | Some("" | "auto") => {}
        Some(name) => {
            return Ok(Choice {
                name: known(name).ok_or_else(|| unknown("the setting vcnc.dialect", name))?,
                why: "from the client's settings".into(),
            });
        }
    }
    let file_name = path.and_then(Path::file_name).and_then(|n| n.to_str());
    let found = vcnc_interp::detect::detect(text.as_bytes(), file_name);
    Ok(Choice {
        name: found.dialect,
        why: found.describe(),
    })
}

/// The name after `--dialect` in a `vcnc:` comment on the first line.
fn first_line_dialect(text: &str) -> Option<String> {
    let first = text.lines().next()?;
    let at = first.to_ascii_lowercase().find("vcnc:")?;
    let rest = first.get(at + 5..)?;
    let mut words = rest.split(|c: char| c.is_whitespace() || c == ')' || c == '=');
    while let Some(w) = words.next() {
        if w == "--dialect" {
            return words.find(|w| !w.is_empty()).map(str::to_ascii_lowercase);
        }
    }
    None
}

fn known(name: &str) -> Option<&'static str> {
    let lower = name.to_ascii_lowercase();
    Dialect::NAMES.iter().copied().find(|n| *n == lower)
}

fn unknown(place: &str, name: &str) -> String {
    format!(
        "unknown dialect {name:?} in {place}: use one of {}",
        Dialect::NAMES.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_line_wins_then_the_setting_then_the_extension() {
        let text = "(vcnc: --dialect haas)\nG00 X0\n";
        let c = choose(text, Some(Path::new("a.ngc")), Some("grbl")).unwrap();
        assert_eq!(c.name, "haas");
        let c = choose("; vcnc: --dialect=GRBL\n", None, None).unwrap();
        assert_eq!(c.name, "grbl");
        let c = choose("G00 X0\n", Some(Path::new("a.ngc")), Some("syntec")).unwrap();
        assert_eq!(c.name, "syntec");
        let c = choose("G00 X0\n", Some(Path::new("a.NGC")), Some("auto")).unwrap();
        assert_eq!(c.name, "linuxcnc");
        assert!(c.why.starts_with("auto"), "{}", c.why);
        // Haas's own code and header: detected, with the evidence as why.
        let c = choose(
            "%\nO1000 (HAAS VF2)\nG187 P1\nM30\n%\n",
            Some(Path::new("a.nc")),
            None,
        )
        .unwrap();
        assert_eq!(c.name, "haas");
        assert!(c.why.contains("G187"), "{}", c.why);
    }

    #[test]
    fn unknown_names_are_errors_that_list_the_dialects() {
        let e = choose("(vcnc: --dialect okuma)\n", None, None).unwrap_err();
        assert!(e.contains("\"okuma\"") && e.contains("linuxcnc"), "{e}");
        assert!(choose("G00\n", None, Some("heidenhain")).is_err());
    }
}
