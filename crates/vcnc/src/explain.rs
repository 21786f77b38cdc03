//! `vcnc explain CODE`: what a G or M code, or an address, means in each
//! dialect, printed from the interpreter's own tables
//! (`vcnc_interp::explain`); and `vcnc explain --matrix`, the dialect
//! matrix of docs/dialects.md, generated from the same tables.

use crate::cli::ExplainArgs;
use std::fmt::Write as _;
use std::process::ExitCode;
use vcnc_interp::Dialect;
use vcnc_interp::explain::{Explanation, Query, code_name, explain};

/// Runs `vcnc explain`.
pub fn run(args: &ExplainArgs) -> Result<ExitCode, String> {
    if args.matrix {
        print!("{}", matrix());
        return Ok(ExitCode::SUCCESS);
    }
    let Some(text) = args.code.as_deref() else {
        return Err("give a code (G87, M98), an address (X, D), or --matrix".into());
    };
    let query = Query::parse(text).ok_or_else(|| {
        format!("{text:?} is not a code or an address: write a G or M code (G87, G59.1, M98) or a letter (X, F, D)")
    })?;
    let dialects: Vec<Dialect> = match &args.dialect {
        Some(name) => vec![Dialect::by_name(&name.to_ascii_lowercase()).ok_or_else(|| {
            format!(
                "unknown dialect {name:?}: use one of {}",
                Dialect::NAMES.join(", ")
            )
        })?],
        None => Dialect::NAMES
            .iter()
            .filter_map(|n| Dialect::by_name(n))
            .collect(),
    };
    print!("{}", describe(query, &dialects));
    Ok(ExitCode::SUCCESS)
}

/// The answers for `dialects`, dialects with the same answer on one line.
pub fn describe(query: Query, dialects: &[Dialect]) -> String {
    let mut groups: Vec<(Explanation, Vec<&'static str>)> = Vec::new();
    for d in dialects {
        let e = explain(query, d);
        match groups.iter_mut().find(|(g, _)| *g == e) {
            Some((_, names)) => names.push(d.name),
            None => groups.push((e, vec![d.name])),
        }
    }
    let mut out = String::new();
    for (e, names) in &groups {
        let who = names.join(", ");
        let _ = match e {
            Explanation::Code {
                code,
                meaning,
                group,
                reads,
                axis_words,
            } => {
                let mut line = format!("{code} ({who}): {meaning}\n    group {group}");
                if !reads.is_empty() {
                    let _ = write!(line, "; reads {reads}");
                }
                if let Some(a) = axis_words {
                    let _ = write!(line, "; {a}");
                }
                writeln!(out, "{line}")
            }
            Explanation::Auxiliary { code, meaning } => {
                writeln!(out, "{code} ({who}): passed on to the machine: {meaning}")
            }
            Explanation::NotRun { code, reason } => {
                writeln!(
                    out,
                    "{code} ({who}): listed by the controller, not run by vcnc: {reason}"
                )
            }
            Explanation::Address {
                letter,
                meaning,
                read_by,
            } => {
                let mut line = format!("{letter} ({who}): {meaning}");
                if !read_by.is_empty() {
                    let _ = write!(line, "\n    read by {}", read_by.join(" "));
                }
                writeln!(out, "{line}")
            }
            Explanation::Unknown { code } => {
                writeln!(out, "{code} ({who}): not a code of this dialect")
            }
        };
    }
    out
}

/// The dialect matrix: every G and M code of any table, and what it is in
/// each dialect (a Markdown table; docs/dialects.md holds a copy that a
/// test keeps current).
pub fn matrix() -> String {
    let dialects: Vec<Dialect> = Dialect::NAMES
        .iter()
        .filter_map(|n| Dialect::by_name(n))
        .collect();
    let mut g_codes: Vec<u16> = dialects
        .iter()
        .flat_map(|d| d.g_rows().map(|(c, _)| c).collect::<Vec<_>>())
        .collect();
    g_codes.sort_unstable();
    g_codes.dedup();
    let mut m_codes: Vec<u16> = dialects
        .iter()
        .flat_map(|d| d.m_rows().map(|(c, _)| c).collect::<Vec<_>>())
        .collect();
    m_codes.sort_unstable();
    m_codes.dedup();
    let mut out = String::new();
    let header: Vec<&str> = dialects.iter().map(|d| d.name).collect();
    let _ = writeln!(out, "| code | {} |", header.join(" | "));
    let _ = writeln!(out, "|---|{}", "---|".repeat(header.len()));
    // A cell is a short name of the operation; the meaning is `vcnc explain`'s.
    let g_cell = |d: &Dialect, c: u16| {
        d.g_rows()
            .find(|(code, _)| *code == c)
            .map_or_else(|| "·".to_string(), |(_, def)| short(def.op.meaning()))
    };
    let m_cell = |d: &Dialect, c: u16| {
        d.m_rows()
            .find(|(code, _)| *code == c)
            .map_or_else(|| "·".to_string(), |(_, def)| short(def.op.meaning()))
    };
    for c in g_codes {
        let cells: Vec<String> = dialects.iter().map(|d| g_cell(d, c)).collect();
        let _ = writeln!(out, "| {} | {} |", code_name('G', c), cells.join(" | "));
    }
    for c in m_codes {
        let cells: Vec<String> = dialects.iter().map(|d| m_cell(d, c)).collect();
        let _ = writeln!(out, "| M{c} | {} |", cells.join(" | "));
    }
    out
}

/// The meaning up to its first `:` or `,` (the operation's name).
fn short(meaning: &str) -> String {
    let end = meaning.find([':', ',', '(']).unwrap_or(meaning.len());
    meaning[..end].trim().replace('|', "/")
}
