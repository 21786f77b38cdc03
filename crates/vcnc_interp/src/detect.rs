//! `--dialect auto`: which dialect a program is written for, worked out from
//! its own text, with the evidence that decided it.
//!
//! A pure function over the program's first [`PREFIX_BYTES`] and its file
//! name; it never runs the program, so it is deterministic and costs one
//! pass over the prefix (the rest of the file is never read):
//!
//! ```text
//!   prefix ─▶ scan: block shapes (G/M codes, letters, modal motion),
//!                   comments, `;` and `//`, macro syntax, `$` lines,
//!                   lathe signs, how lengths are written
//!          ─▶ each dialect: codes that would alarm there (from its own
//!             tables: Dialect::g, m, its lexical and macro rules) ─ penalty
//!                           + evidence for it (header names, extension,
//!                             lathe or mill signs, integer style, …)
//!          ─▶ best score; confidence from the margin over the best dialect
//!             that would run the program differently
//! ```
//!
//! Which dialects know a code is asked of the dialect tables, never listed
//! here; what is listed here are the signs no table holds: names in header
//! comments, file extensions, the lathe's T0101, the two G71 forms, how
//! integers are written. `docs/dialects.md` ("Choosing the dialect") lists
//! every rule and its evidence string. The same tables give E201's hint
//! ([`g_hint`]): the dialects that know a code, and how each reads an
//! integer, so that a hint never changes a program's units unsaid.

mod board;
mod scan;

use crate::dialect::{Dialect, IntegerWords};
use board::{Board, is_lathe};
use scan::Scan;

/// How much of a program detection reads.
pub const PREFIX_BYTES: usize = 64 * 1024;

/// How sure detection is of its choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Confidence {
    /// The evidence separates the choice from every dialect that would run
    /// the program differently.
    High,
    /// A guess: another dialect that would run it differently fits nearly
    /// as well.
    Low,
}

impl Confidence {
    /// `high` or `low`.
    pub fn as_str(self) -> &'static str {
        match self {
            Confidence::High => "high",
            Confidence::Low => "low",
        }
    }
}

/// The dialect detection chose, and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Detection {
    /// The chosen dialect's `--dialect` name.
    pub dialect: &'static str,
    /// What decided it, strongest first: `G187`, `"(HAAS VF2)" header`,
    /// `.ngc file`, `whole-unit integers (X20)` …
    pub evidence: Vec<String>,
    /// How sure it is.
    pub confidence: Confidence,
    /// With low confidence: the dialect that came closest among those that
    /// would run the program differently.
    pub runner_up: Option<&'static str>,
    /// Close dialects that would run it the same as far as the prefix
    /// shows (the choice among them does not matter), at most three.
    pub alike: Vec<&'static str>,
}

impl Detection {
    /// `auto: G187, "(HAAS VF2)" header`, or with low confidence `auto,
    /// low confidence: …; next: fanuc`.
    pub fn describe(&self) -> String {
        let mut why = if self.evidence.is_empty() {
            "no distinguishing evidence".to_string()
        } else {
            self.evidence.join(", ")
        };
        if !self.alike.is_empty() {
            why.push_str(&format!("; {} read it alike", self.alike.join(", ")));
        }
        match (self.confidence, self.runner_up) {
            (Confidence::High, _) => format!("auto: {why}"),
            (Confidence::Low, Some(next)) => {
                format!("auto, low confidence: {why}; next: {next}")
            }
            (Confidence::Low, None) => format!("auto, low confidence: {why}"),
        }
    }
}

/// Chooses the dialect of a program from its text and file name.
pub fn detect(bytes: &[u8], file_name: Option<&str>) -> Detection {
    let (mut board, scan) = weigh(bytes, file_name);
    board.decide(Dialect::all(), &scan)
}

/// Detection's scores per dialect and the evidence behind them, as text:
/// for tuning the rules and for tests that explain a choice.
pub fn explain(bytes: &[u8], file_name: Option<&str>) -> String {
    let (mut board, scan) = weigh(bytes, file_name);
    let chosen = board.decide(Dialect::all(), &scan);
    format!("{}\n{}", chosen.describe(), board.explain(Dialect::all()))
}

/// The scan of the prefix and every rule's evidence on it.
fn weigh(bytes: &[u8], file_name: Option<&str>) -> (Board, Scan) {
    let scan = Scan::of(bounded(bytes));
    let all = Dialect::all();
    let mut board = Board::new(all.len());
    board.codes(all, &scan);
    board.syntax(all, &scan);
    board.header(all, &scan);
    board.extension(all, file_name);
    board.kind(all, &scan);
    board.integers(all, &scan);
    (board, scan)
}

/// The bytes detection reads: at most [`PREFIX_BYTES`], cut after the
/// last whole line.
fn bounded(bytes: &[u8]) -> &[u8] {
    if bytes.len() <= PREFIX_BYTES {
        return bytes;
    }
    let head = bytes.get(..PREFIX_BYTES).unwrap_or(bytes);
    match head.iter().rposition(|b| *b == b'\n') {
        Some(end) => head.get(..end).unwrap_or(head),
        None => head,
    }
}

/// E201's help when another G-code system of `current` (a Fanuc lathe's
/// A, B or C, docs/machine.md) has G `value`: the machine file chooses the
/// system, not `--dialect`, so the help names the key to set.
fn system_hint(current: &Dialect, code: &str, value: f64) -> Option<String> {
    use vcnc_core::machine::GcodeSystem;
    let base = Dialect::named(current.name)?;
    let systems: Vec<&str> = [GcodeSystem::A, GcodeSystem::B, GcodeSystem::C]
        .into_iter()
        .filter(|s| {
            let d = base.for_system(*s);
            !std::ptr::eq(d, current) && d.g(value).is_some() && d.g_rows().ne(current.g_rows())
        })
        .map(|s| s.letter())
        .collect();
    let (first, rest) = systems.split_first()?;
    let others: String = rest.iter().map(|s| format!(" (or \"{s}\")")).collect();
    Some(format!(
        "{code} is a code of {}'s G-code system {}: write gcode_system = \"{first}\"{others} \
         in the machine file (--machine FILE, docs/machine.md) if the program is written for it",
        current.name,
        systems.join(" and "),
    ))
}

/// E201's help when dialect `current` does not know G `value`: the
/// dialects that do (for a lathe, the lathes that read `;` as it does; for
/// a mill, the mills when any mill knows it), and — whenever one of them
/// reads an integer otherwise than
/// `current` — how each reads `X20`, so that following the hint never
/// changes the program's units unsaid.
pub fn g_hint(current: &Dialect, value: f64) -> String {
    let code = format!("G{value}");
    if let Some(hint) = system_hint(current, &code, value) {
        return hint;
    }
    let knows: Vec<&Dialect> = Dialect::all()
        .iter()
        .filter(|d| d.name != current.name && d.g(value).is_some())
        .collect();
    // A lathe program goes to lathes of its own `;` family only: a Fanuc
    // lathe's G43 is not LinuxCNC's.
    let same_kind: Vec<&Dialect> = knows
        .iter()
        .copied()
        .filter(|d| is_lathe(d) == is_lathe(current))
        .filter(|d| !is_lathe(d) || d.lex.semicolon == current.lex.semicolon)
        .collect();
    // A lathe program is never sent to a mill: its X is a diameter.
    let named: Vec<&Dialect> = if !same_kind.is_empty() || is_lathe(current) {
        same_kind
    } else {
        knows
    };
    if named.is_empty() {
        return "check the code against the controller's G-code list".to_string();
    }
    let auto = "or leave --dialect out and vcnc chooses from the program";
    let list = |ds: &[&Dialect]| ds.iter().map(|d| d.name).collect::<Vec<_>>().join(", ");
    let (same, other): (Vec<&Dialect>, Vec<&Dialect>) =
        named.iter().partition(|d| d.integers == current.integers);
    let reading = |i: IntegerWords| match i {
        IntegerWords::WholeUnits => "X20 as 20 mm",
        IntegerWords::LeastIncrement => "X20 as 0.020 mm",
    };
    match (same.first(), other.is_empty()) {
        (Some(first), true) => format!(
            "{code} is a code of {}: run with --dialect {}, {auto}",
            list(&same),
            first.name
        ),
        (Some(_), false) => format!(
            "{code} is a code of {} (which read {}, as {} does) and of {} (which read {}): \
             choose by how the program writes lengths, {auto}",
            list(&same),
            reading(current.integers),
            current.name,
            list(&other),
            reading(other.first().map_or(current.integers, |d| d.integers)),
        ),
        (None, _) => format!(
            "{code} is a code of {}, which read{} {} where {} reads {}: \
             run with --dialect {} if the program means that, {auto}",
            list(&other),
            if other.len() == 1 { "s" } else { "" },
            reading(other.first().map_or(current.integers, |d| d.integers)),
            current.name,
            reading(current.integers),
            other.first().map_or("", |d| d.name),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_core::machine::GcodeSystem;

    #[test]
    fn e201s_help_names_the_gcode_system_that_knows_the_code() {
        let a = Dialect::named("fanuc-lathe").unwrap();
        // Under system A it names the key that brings G95 and G91.
        for v in [95.0, 91.0, 77.0] {
            let help = g_hint(a, v);
            assert!(help.contains("gcode_system = \"B\""), "{help}");
        }
        // And under B, system A's G50.
        let help = g_hint(a.for_system(GcodeSystem::B), 50.0);
        assert!(help.contains("gcode_system = \"A\""), "{help}");
        // A code of no system keeps the ordinary help.
        assert!(!g_hint(a, 17.1).contains("gcode_system"));
    }
}
