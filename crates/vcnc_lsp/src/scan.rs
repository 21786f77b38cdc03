//! What each piece of a line is, for the editor: codes, addresses,
//! comments and macro statements, with their byte ranges. Hover,
//! definitions, symbols and semantic tokens all read lines through here.
//!
//! ```text
//!   N20 G83 Z-12. R2. Q3. F80 (PECK)     #1 = [#2 + 3] (SUM)
//!   ─── ─── ───── ─── ─── ─── ──────     ── ─ ── ─ ─── ─────
//!   adr code adr  adr adr adr comment    var   var   num comment
//!                                        (macro: keyword-like runs, o<name>)
//! ```
//!
//! Word blocks are read by the interpreter's own lexer
//! (`vcnc_syntax::lex_block` under the dialect's `LexRules`), so a word is
//! what the interpreter sees. A block the lexer rejects is usually a macro
//! statement (`#1 = 2`, `IF [..] GOTO 10`, `o<cut> call`): it is split by
//! the shapes of its pieces only (runs of letters, `#` variables,
//! numbers), which is all an editor needs to colour it and find its
//! labels, and nothing here evaluates it. Lines are cut off at
//! [`MAX_SCANNED`] bytes so that a 10 MB line costs the editor nothing.

use vcnc_syntax::{Block, LexRules, Semicolon, lex_block, next_block_start};

/// Bytes of one line looked at; the rest of a longer line is left plain.
pub const MAX_SCANNED: usize = 4096;

/// What a piece of a line is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A G or M code: `G83`, `M98`.
    Code,
    /// Any other word: `X10.`, `P100`, `N20`.
    Address,
    /// A comment, with its delimiters.
    Comment,
    /// A keyword of a macro statement (`IF`, `GOTO`, `WHILE`, `sub`,
    /// `o<name>`).
    Macro,
    /// A macro variable: `#1`, `#<_depth>`.
    Variable,
    /// A number inside a macro statement.
    Number,
}

/// One piece of a line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Token {
    /// Byte range within the line.
    pub start: usize,
    /// One past its last byte.
    pub end: usize,
    /// What it is.
    pub kind: Kind,
    /// The address letter of a word (uppercase), 0 otherwise.
    pub letter: u8,
    /// The value of a word or a number (`None` when it is an expression).
    pub value: Option<f64>,
}

impl Token {
    /// The token's text in `line`.
    pub fn text<'l>(&self, line: &'l str) -> &'l str {
        line.get(self.start..self.end).unwrap_or_default()
    }
}

/// The pieces of `line`, in order.
pub fn tokens(line: &str, rules: &LexRules) -> Vec<Token> {
    let line = cut(line);
    let bytes = line.as_bytes();
    let comments = comments(bytes, rules);
    let mut out: Vec<Token> = Vec::new();
    let mut block = Block::default();
    let mut i = 0;
    while i < bytes.len() {
        match lex_block(bytes, i, rules, &mut block) {
            Ok(next) => {
                out.extend(block.words().iter().map(|w| word(w, bytes)));
                i = next.max(i + 1);
            }
            Err(_) => {
                let end = next_block_start(bytes, i, rules).max(i + 1);
                statement(bytes, i, end.min(bytes.len()), &comments, &mut out);
                i = end;
            }
        }
    }
    out.extend(comments.iter().map(|&(start, end)| Token {
        start,
        end,
        kind: Kind::Comment,
        letter: 0,
        value: None,
    }));
    out.sort_by_key(|t| t.start);
    out
}

/// The first [`MAX_SCANNED`] bytes of `line`, on a character boundary.
fn cut(line: &str) -> &str {
    if line.len() <= MAX_SCANNED {
        return line;
    }
    let mut end = MAX_SCANNED;
    while !line.is_char_boundary(end) {
        end -= 1;
    }
    &line[..end]
}

fn word(w: &vcnc_syntax::Word, bytes: &[u8]) -> Token {
    let start = w.span.start as usize;
    let end = (w.span.end as usize).min(bytes.len());
    let letter = w.addr.as_letter().unwrap_or(0);
    Token {
        start,
        end,
        kind: if matches!(letter, b'G' | b'M') {
            Kind::Code
        } else {
            Kind::Address
        },
        letter,
        value: Some(w.value),
    }
}

/// Byte ranges of the comments of a line: `( … )`, and to the line's end
/// after `;` where the dialect says so or after `//` (Syntec).
pub fn comments(bytes: &[u8], rules: &LexRules) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(&b) = bytes.get(i) {
        let to_end = (b == b';' && rules.semicolon == Semicolon::Comment)
            || (b == b'/' && rules.slash_comments && bytes.get(i + 1) == Some(&b'/'));
        if to_end {
            out.push((i, bytes.len()));
            break;
        }
        if b == b'(' {
            let end = bytes
                .get(i + 1..)
                .and_then(|rest| rest.iter().position(|c| *c == b')'))
                .map_or(bytes.len(), |k| i + 1 + k + 1);
            out.push((i, end));
            i = end;
            continue;
        }
        i += 1;
    }
    out
}

/// The pieces of a statement the lexer rejected, `start..end` of `bytes`,
/// comments left out.
fn statement(
    bytes: &[u8],
    start: usize,
    end: usize,
    comments: &[(usize, usize)],
    out: &mut Vec<Token>,
) {
    let mut i = start;
    while i < end {
        if let Some(&(_, e)) = comments.iter().find(|(s, e)| *s <= i && i < *e) {
            i = e;
            continue;
        }
        let b = bytes[i];
        let (len, kind, letter) = match b {
            b'#' => (variable_len(&bytes[i..end]), Kind::Variable, 0),
            b'0'..=b'9' | b'.' => (number_len(&bytes[i..end]), Kind::Number, 0),
            b'o' | b'O' if bytes.get(i + 1) == Some(&b'<') => {
                (angle_len(&bytes[i + 1..end]) + 1, Kind::Macro, b'O')
            }
            _ if b.is_ascii_alphabetic() => {
                let run = bytes[i..end]
                    .iter()
                    .take_while(|c| c.is_ascii_alphabetic() || **c == b'_')
                    .count();
                if run == 1 {
                    let up = b.to_ascii_uppercase();
                    let code = matches!(up, b'G' | b'M')
                        && bytes.get(i + 1).is_some_and(u8::is_ascii_digit);
                    (1, if code { Kind::Code } else { Kind::Address }, up)
                } else {
                    (run, Kind::Macro, 0)
                }
            }
            _ => {
                i += 1;
                continue;
            }
        };
        let len = len.max(1);
        let mut t = Token {
            start: i,
            end: (i + len).min(end),
            kind,
            letter,
            value: None,
        };
        // A code or a word followed by a plain number takes it as its value.
        if matches!(kind, Kind::Code | Kind::Address) {
            let n = number_len(&bytes[t.end..end]);
            if n > 0 {
                t.value = std::str::from_utf8(&bytes[t.end..t.end + n])
                    .ok()
                    .and_then(|s| s.parse().ok());
                t.end += n;
            }
        }
        if kind == Kind::Number {
            t.value = std::str::from_utf8(&bytes[t.start..t.end])
                .ok()
                .and_then(|s| s.parse().ok());
        }
        out.push(t);
        i = t.end;
    }
}

/// `#12`, `#<_name>`, or a lone `#` (before a bracket).
fn variable_len(b: &[u8]) -> usize {
    match b.get(1) {
        Some(b'<') => 1 + angle_len(&b[1..]),
        _ => 1 + b[1..].iter().take_while(|c| c.is_ascii_digit()).count(),
    }
}

/// `<name>` up to and with its `>` (or the end).
fn angle_len(b: &[u8]) -> usize {
    b.iter().position(|c| *c == b'>').map_or(b.len(), |k| k + 1)
}

/// Digits and at most one point.
fn number_len(b: &[u8]) -> usize {
    let mut point = false;
    b.iter()
        .take_while(|c| match c {
            b'0'..=b'9' => true,
            b'.' if !point => {
                point = true;
                true
            }
            _ => false,
        })
        .count()
}

/// The token of `tokens` at byte `at` (a cursor just after a word's last
/// byte still hovers it).
pub fn at(tokens: &[Token], at: usize) -> Option<&Token> {
    tokens
        .iter()
        .find(|t| t.start <= at && at < t.end)
        .or_else(|| {
            tokens
                .iter()
                .find(|t| t.end == at && t.kind != Kind::Comment)
        })
}

/// The text inside a comment token, without its delimiters.
pub fn comment_text(text: &str) -> &str {
    let t = text.trim();
    let t = t
        .strip_prefix('(')
        .map(|t| t.strip_suffix(')').unwrap_or(t))
        .or_else(|| t.strip_prefix("//"))
        .or_else(|| t.strip_prefix(';'))
        .unwrap_or(t);
    t.trim()
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_interp::Dialect;

    fn kinds<'l>(line: &'l str, dialect: &Dialect) -> Vec<(Kind, &'l str)> {
        tokens(line, &dialect.lex)
            .iter()
            .map(|t| (t.kind, &line[t.start..t.end]))
            .collect()
    }

    #[test]
    fn word_blocks_read_as_the_lexer_reads_them() {
        let got = kinds("N20 G83 Z-12. Q3. (PECK) M08", &Dialect::fanuc());
        assert_eq!(
            got,
            vec![
                (Kind::Address, "N20"),
                (Kind::Code, "G83"),
                (Kind::Address, "Z-12."),
                (Kind::Address, "Q3."),
                (Kind::Comment, "(PECK)"),
                (Kind::Code, "M08"),
            ]
        );
    }

    #[test]
    fn macro_statements_split_into_keywords_variables_and_numbers() {
        let got = kinds("IF [#1 GT 3] GOTO 10", &Dialect::fanuc());
        assert_eq!(
            got,
            vec![
                (Kind::Macro, "IF"),
                (Kind::Variable, "#1"),
                (Kind::Macro, "GT"),
                (Kind::Number, "3"),
                (Kind::Macro, "GOTO"),
                (Kind::Number, "10"),
            ]
        );
        let got = kinds("o<cut> call [2] ; depth", &Dialect::linuxcnc());
        assert_eq!(
            got,
            vec![
                (Kind::Macro, "o<cut>"),
                (Kind::Macro, "call"),
                (Kind::Number, "2"),
                (Kind::Comment, "; depth"),
            ]
        );
        let got = kinds("#<_depth> = 2.5", &Dialect::linuxcnc());
        assert_eq!(
            got,
            vec![(Kind::Variable, "#<_depth>"), (Kind::Number, "2.5")]
        );
    }

    #[test]
    fn long_lines_and_junk_are_cut_not_fatal() {
        let long = "G01 X1 ".repeat(10_000);
        let t = tokens(&long, &Dialect::fanuc().lex);
        assert!(t.iter().all(|t| t.end <= MAX_SCANNED));
        let junk = "\u{1}\u{7f}é(((;;;#<<[[]]%%";
        let _ = tokens(junk, &Dialect::fanuc().lex);
        let _ = tokens(junk, &Dialect::linuxcnc().lex);
    }
}
