//! Document symbols, the editor's outline: subprograms, the CAM's
//! operation comments, and tool changes with the tool's description.
//!
//! ```text
//!   O0100 (BRACKET)                 ── program      O0100  BRACKET
//!   (T1 D=6. - flat end mill)          (tool list: T1's description)
//!   N10 G90 G54                       
//!   (2D Contour1)                   ── operation    2D Contour1
//!   N25 T1 M6                       ──   tool change T1  D=6. - flat end mill
//!   …
//!   O0200 (SUB)                     ── program      O0200  SUB
//! ```
//!
//! - A program is a line that starts with an `O` number (`O0100`, `:100`)
//!   or an O-word `sub` (`o<cut> sub` … `o<cut> endsub`); it runs to the
//!   next one.
//! - An operation is a line that holds only comments, once the program has
//!   begun (comments before the first block are its title and notes, not
//!   operations), other than the tool list; it runs to the next operation.
//!   CAM systems write one before each operation (`(2D Contour1)`,
//!   `(OPERATION 3: DRILL)`).
//! - A tool change is a block with the dialect's tool-change M code (its
//!   table's `MOp::ToolChange`), or any T word where T indexes the turret
//!   (Fanuc lathes). Its description is the tool list's comment for that
//!   tool (`(T1 D=6. …)`, `(TOOL 4 = 1IN FACE MILL)`), else a comment on
//!   its line.

use crate::scan::{self, Kind, Token, comment_text};
use crate::text::{Text, lines};
use lsp_types::{DocumentSymbol, SymbolKind};
use std::collections::BTreeMap;
use vcnc_interp::Dialect;
use vcnc_interp::dialect::{MOp, ToolWords};

/// One entry of the outline before it is nested.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    /// What it is.
    pub kind: ItemKind,
    /// Its name.
    pub name: String,
    /// More about it (a comment, a tool's description).
    pub detail: Option<String>,
    /// Byte range of what names it.
    pub at: (usize, usize),
    /// Byte offset of its line's start.
    pub line_start: usize,
}

/// Kinds of outline entries, outermost first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum ItemKind {
    /// A program or subprogram.
    Program,
    /// An O-word subroutine's `endsub`: the end of the program before it.
    EndSub,
    /// A CAM operation comment.
    Operation,
    /// A tool change.
    ToolChange,
}

/// The outline's entries in text order.
pub fn items(text: &str, dialect: &Dialect) -> Vec<Item> {
    let tools = tool_list(text, dialect);
    let mut out = Vec::new();
    let mut begun = false;
    let mut selected: Option<u32> = None;
    for (start, line) in lines(text) {
        let tokens = scan::tokens(line, &dialect.lex);
        let Some(first) = tokens.first() else {
            continue;
        };
        let item = |kind, name: String, detail, t: &Token| Item {
            kind,
            name,
            detail,
            at: (start + t.start, start + t.end),
            line_start: start,
        };
        let words: Vec<&Token> = tokens.iter().filter(|t| t.kind != Kind::Comment).collect();
        let comment = tokens
            .iter()
            .find(|t| t.kind == Kind::Comment)
            .map(|t| comment_text(t.text(line)).to_string())
            .filter(|c| !c.is_empty());
        if words.is_empty() {
            let is_tool_list = comment.as_deref().and_then(tool_entry).is_some();
            if begun
                && !is_tool_list
                && let Some(c) = comment
            {
                out.push(item(ItemKind::Operation, c, None, first));
            }
            continue;
        }
        let head = words.first().copied().unwrap_or(first);
        if head.letter == b'O' {
            let keyword = words.get(1).map(|t| t.text(line).to_ascii_lowercase());
            match keyword.as_deref() {
                None | Some("sub") => {
                    out.push(item(
                        ItemKind::Program,
                        head.text(line).to_string(),
                        comment,
                        head,
                    ));
                    begun = false;
                    continue;
                }
                Some("endsub") => {
                    out.push(item(ItemKind::EndSub, String::new(), None, head));
                    continue;
                }
                _ => {}
            }
        }
        if words
            .iter()
            .any(|t| t.kind == Kind::Code || t.letter != b'N')
        {
            begun = true;
        }
        if let Some(t) = words
            .iter()
            .find(|t| t.letter == b'T')
            .and_then(|t| t.value)
            .and_then(tool_number)
        {
            selected = Some(t);
        }
        let turret = dialect.tool_words == ToolWords::TurretOffset;
        let change = words.iter().find(|t| {
            t.kind == Kind::Code
                && t.letter == b'M'
                && t.value
                    .and_then(|v| dialect.m(v))
                    .is_some_and(|m| m.op == MOp::ToolChange)
        });
        let change = change.or_else(|| words.iter().find(|t| turret && t.letter == b'T'));
        if let Some(at) = change {
            let tool = if turret {
                selected.map(|t| t / 100)
            } else {
                selected
            };
            let name = tool.map_or_else(|| "tool change".to_string(), |t| format!("T{t}"));
            let detail = tool.and_then(|t| tools.get(&t).cloned()).or(comment);
            out.push(item(ItemKind::ToolChange, name, detail, at));
        }
    }
    out
}

/// A T word's tool number.
fn tool_number(v: f64) -> Option<u32> {
    (v.fract() == 0.0 && (0.0..1e8).contains(&v)).then(|| {
        // Whole and below 10^8: the conversion is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = v as u32;
        n
    })
}

/// A tool-list comment's tool and description: `T1 D=6. - flat end
/// mill`, `TOOL 4 = 1IN FACE MILL`, `T12: DRILL 6.8`.
fn tool_entry(comment: &str) -> Option<(u32, String)> {
    let upper = comment.to_ascii_uppercase();
    let rest = upper
        .strip_prefix("TOOL")
        .or_else(|| upper.strip_prefix('T'))?
        .trim_start_matches([' ', '#']);
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    if digits == 0
        || rest
            .as_bytes()
            .get(digits)
            .is_some_and(u8::is_ascii_alphanumeric)
    {
        return None;
    }
    let n: u32 = rest.get(..digits)?.parse().ok()?;
    let skip = comment.len() - rest.len() + digits;
    let description = comment
        .get(skip..)?
        .trim_start_matches([' ', '=', ':', '-', '|'])
        .trim();
    (!description.is_empty()).then(|| (n, description.to_string()))
}

/// The tool list: every comment-only line that describes a tool.
fn tool_list(text: &str, dialect: &Dialect) -> BTreeMap<u32, String> {
    let mut out = BTreeMap::new();
    for (_, line) in lines(text) {
        if !line.trim_start().starts_with(['(', ';']) {
            continue;
        }
        for (a, b) in scan::comments(line.as_bytes(), &dialect.lex) {
            if let Some((n, d)) = line.get(a..b).map(comment_text).and_then(tool_entry) {
                out.entry(n).or_insert(d);
            }
        }
    }
    out
}

/// The outline, nested by containment: operations inside their program,
/// tool changes inside their operation. A program runs to the line before
/// the next program (or to its `endsub`), an operation to the line before
/// the next operation or program, a tool change over its line.
pub fn outline(text: &Text, dialect: &Dialect) -> Vec<DocumentSymbol> {
    let items = items(text.as_str(), dialect);
    let len = text.as_str().len();
    let line_end = |at: usize| {
        let rest = text.as_str().get(at..).unwrap_or_default();
        at + rest.find('\n').unwrap_or(rest.len())
    };
    // Where each entry ends, in bytes.
    let mut ranged: Vec<(&Item, usize)> = Vec::new();
    for (i, it) in items.iter().enumerate() {
        let rest = items.get(i + 1..).unwrap_or_default();
        let before = |n: &Item| n.line_start.saturating_sub(1).max(it.at.1);
        let end = match it.kind {
            ItemKind::EndSub => continue,
            ItemKind::Program => {
                rest.iter()
                    .find(|n| n.kind <= ItemKind::EndSub)
                    .map_or(len, |n| {
                        if n.kind == ItemKind::EndSub {
                            line_end(n.line_start)
                        } else {
                            before(n)
                        }
                    })
            }
            ItemKind::Operation => {
                rest.iter()
                    .find(|n| n.kind <= ItemKind::Operation)
                    .map_or(len, |n| {
                        if n.kind == ItemKind::EndSub {
                            line_end(n.line_start)
                        } else {
                            before(n)
                        }
                    })
            }
            ItemKind::ToolChange => line_end(it.line_start),
        };
        ranged.push((it, end));
    }
    let mut out: Vec<DocumentSymbol> = Vec::new();
    let mut open: Vec<(usize, DocumentSymbol)> = Vec::new();
    for (it, end) in ranged {
        while let Some((top_end, _)) = open.last() {
            if *top_end >= end {
                break;
            }
            if let Some((_, s)) = open.pop() {
                attach(&mut open, &mut out, s);
            }
        }
        open.push((end, symbol(it, text, end)));
    }
    while let Some((_, s)) = open.pop() {
        attach(&mut open, &mut out, s);
    }
    out
}

#[allow(deprecated)] // `deprecated` is a field every DocumentSymbol must fill
fn symbol(it: &Item, text: &Text, end: usize) -> DocumentSymbol {
    let kind = match it.kind {
        ItemKind::Program | ItemKind::EndSub => SymbolKind::FUNCTION,
        ItemKind::Operation => SymbolKind::NAMESPACE,
        ItemKind::ToolChange => SymbolKind::EVENT,
    };
    DocumentSymbol {
        name: if it.name.is_empty() {
            "?".into()
        } else {
            it.name.clone()
        },
        detail: it.detail.clone(),
        kind,
        tags: None,
        deprecated: None,
        range: text.range(it.line_start, end),
        selection_range: text.range(it.at.0, it.at.1),
        children: None,
    }
}

/// Puts a finished symbol under the one still open around it, or at the
/// top level.
fn attach(open: &mut [(usize, DocumentSymbol)], out: &mut Vec<DocumentSymbol>, s: DocumentSymbol) {
    match open.last_mut() {
        Some((_, parent)) => parent.children.get_or_insert_with(Vec::new).push(s),
        None => out.push(s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FUSION: &str = "%\nO01002 (BASE PLATE)\n(Using high feed G1 F5000. instead of G0.)\n(T1 D=6. CR=0. - flat end mill)\n(T2 D=8. - drill)\nN10 G90 G94 G17\n(2D Contour1)\nN25 T1 M6\nN30 S5000 M3\nN35 G1 X1. F100.\n(Drill1)\nN40 T2 M6 (DRILL)\nN45 G81 Z-5. R2. F80.\nN50 M30\n%\n";

    fn names(symbols: &[DocumentSymbol], depth: usize, out: &mut Vec<String>) {
        for s in symbols {
            out.push(format!(
                "{}{} [{}]",
                "  ".repeat(depth),
                s.name,
                s.detail.clone().unwrap_or_default()
            ));
            names(s.children.as_deref().unwrap_or_default(), depth + 1, out);
        }
    }

    #[test]
    fn programs_hold_operations_that_hold_tool_changes() {
        let text = Text::new(FUSION.to_string());
        let got = outline(&text, &Dialect::fanuc());
        let mut lines = Vec::new();
        names(&got, 0, &mut lines);
        assert_eq!(
            lines,
            vec![
                "O01002 [BASE PLATE]",
                "  2D Contour1 []",
                "    T1 [D=6. CR=0. - flat end mill]",
                "  Drill1 []",
                "    T2 [D=8. - drill]",
            ]
        );
        // The operation runs to the line before the next one.
        let op = &got[0].children.as_ref().unwrap()[0];
        assert_eq!((op.range.start.line, op.range.end.line), (6, 9));
    }

    #[test]
    fn turret_lathes_change_tools_with_t_alone() {
        let text = Text::new(
            "O0001\n(TOOL 1 = OD ROUGH)\nG50 S2000\nT0101\nG00 X50. Z2.\nT0202 (FINISH)\nM30\n"
                .to_string(),
        );
        let mut lines = Vec::new();
        names(&outline(&text, &Dialect::fanuc_lathe()), 0, &mut lines);
        assert_eq!(lines, vec!["O0001 []", "  T1 [OD ROUGH]", "  T2 [FINISH]"]);
    }

    #[test]
    fn oword_subroutines_end_at_endsub() {
        let text =
            Text::new("o<cut> sub\nG01 X1 F100\no<cut> endsub\nG00 X0\nT3 M6\nM2\n".to_string());
        let got = outline(&text, &Dialect::linuxcnc());
        assert_eq!(got[0].name, "o<cut>");
        assert_eq!(got[0].range.end.line, 2);
        assert_eq!(got[1].name, "T3");
    }
}
