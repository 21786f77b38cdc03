//! The lexer: one block out of one physical line.
//!
//! ```text
//!   line:  N10 G01 X5.5 (cut) Y-2 ; G04 P500   // note
//!          └───────── block 1 ──────┘ └ block 2 ┘└ comment ┘
//! ```
//!
//! A block ends at `;`, at the full-width `；` the Syntec manual prints, at a
//! `//` annotation (when the dialect's [`LexRules`] allow it) or at the end of
//! the line. `( )` comments are skipped, `%` alone is a tape mark, `/` at the
//! start marks a block-delete block, letters are case-insensitive and spaces
//! are ignored inside words. Multi-character addresses (`CR=`) come from the
//! rules table so that dialects differ by data, not by code.

use crate::block::{Addr, Block, MAX_WORDS, Word};
use crate::diagnostics::{self as diag, Diagnostic};
use crate::number::{NumberError, lex_number};
use vcnc_core::Span;

/// Longest block the lexer accepts (E106 beyond).
pub const MAX_BLOCK_BYTES: usize = 4096;

/// Dialect-dependent lexical rules.
#[derive(Debug, Clone, Copy)]
pub struct LexRules {
    /// What `;` means.
    pub semicolon: Semicolon,
    /// `//` starts a comment that runs to the end of the line (Syntec).
    pub slash_comments: bool,
    /// The full-width `；` (U+FF1B) ends a block like `;`.
    pub fullwidth_semicolon: bool,
    /// Multi-character addresses, tried before single letters, longest
    /// first, matched case-insensitively: (`"CR="`, its [`Addr`]).
    pub extended: Extended,
    /// Addresses of other dialects, with the dialect that has them, so that
    /// `CR=10` under the mill dialects says where `CR=` belongs.
    pub foreign: &'static [(&'static str, &'static str)],
    /// `:` is the address O (ISO code's program number, Fanuc): read where
    /// a word starts with it, so that it costs the words that start with
    /// letters nothing (as an extended address it was tried at each).
    pub colon_is_o: bool,
    /// Any `(` inside a `( )` comment is E101 (rs274: "Nested comment
    /// found"); otherwise only the `(A (B) C)` form, where a second `)`
    /// shows the programmer meant the comment to nest.
    pub paren_in_comment_alarms: bool,
}

/// A dialect's multi-character addresses (`CR=`, `,C`, `@`), and the
/// letters that start one: a word that starts with another letter is not
/// looked up among them, so that the Fanuc `,C`/`,R` cost the plain words
/// nothing and the lathe's `CR=` only the words of C.
#[derive(Debug, Clone, Copy)]
pub struct Extended {
    all: &'static [(&'static str, Addr)],
    /// Bit `k` for the letter `b'A' + k`.
    letters: u32,
}

impl Extended {
    /// No multi-character address.
    pub const NONE: Extended = Extended::new(&[]);

    /// The addresses, longest first where one starts another.
    pub const fn new(all: &'static [(&'static str, Addr)]) -> Self {
        let mut letters = 0;
        let mut k = 0;
        while k < all.len() {
            if let Some(&b) = all[k].0.as_bytes().first()
                && is_letter(b)
            {
                letters |= 1 << ((b & !0x20) - b'A');
            }
            k += 1;
        }
        Extended { all, letters }
    }

    /// Every address with its [`Addr`].
    pub fn all(&self) -> &'static [(&'static str, Addr)] {
        self.all
    }

    /// Whether an address may start with `letter` (an uppercase letter).
    #[inline(always)]
    fn may_start(&self, letter: u8) -> bool {
        self.letters & (1 << (letter.wrapping_sub(b'A') & 31)) != 0
    }
}

/// What `;` means in a dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Semicolon {
    /// It ends the block, like a line end (Fanuc's EOB, Syntec).
    EndOfBlock,
    /// It starts a comment that runs to the end of the line (grbl,
    /// LinuxCNC and the hobby CAM programs written for them).
    Comment,
}

const FULLWIDTH_SEMICOLON: &[u8] = "；".as_bytes();
const BOM: &[u8] = "\u{FEFF}".as_bytes();

/// Where the block after one the lexer rejected begins: past the `;` that
/// ends the block starting at `start` (comments and quoted text skipped),
/// or `line.len()`. A rejected block is often a macro statement
/// (`#1 = 1; N20 G00 X2.`), and the blocks after its `;` still hold labels.
pub fn next_block_start(line: &[u8], start: usize, rules: &LexRules) -> usize {
    if rules.semicolon == Semicolon::Comment {
        return line.len();
    }
    let mut i = start;
    while i < line.len() {
        let closing = match line[i] {
            b'(' => b')',
            b'"' => b'"',
            b';' => return i + 1,
            b'/' if rules.slash_comments && line.get(i + 1) == Some(&b'/') => return line.len(),
            0xEF if rules.fullwidth_semicolon && line[i..].starts_with(FULLWIDTH_SEMICOLON) => {
                return i + FULLWIDTH_SEMICOLON.len();
            }
            _ => {
                i += 1;
                continue;
            }
        };
        match memchr::memchr(closing, &line[i + 1..]) {
            Some(k) => i += k + 2,
            None => return line.len(),
        }
    }
    line.len()
}

/// Lexes the block that starts at `start` in `line` into `out`.
///
/// Returns the index where the next block starts (past the terminator), or
/// `line.len()` when the line is used up.
pub fn lex_block(
    line: &[u8],
    start: usize,
    rules: &LexRules,
    out: &mut Block,
) -> Result<usize, Diagnostic> {
    out.clear();
    // Most blocks are words up to the line's end (`lex_word` steps over the
    // blanks after each): they take this lean loop, and anything else hands
    // over to the general one, whose state and rare paths then cost them
    // nothing.
    let mut i = start;
    while let Some(&b) = line.get(i) {
        if !is_letter(b) {
            return lex_rest(line, start, i, rules, out);
        }
        i = lex_word(line, start, i, b & !0x20, rules, out)?;
    }
    finish(out, start, i, line.len())
}

/// Whether `b` is an ASCII letter: `b | 0x20` lowercases a letter, so one
/// compare finds both cases (and `b & !0x20` is then its uppercase).
#[inline(always)]
const fn is_letter(b: u8) -> bool {
    (b | 0x20).wrapping_sub(b'a') < 26
}

/// [`lex_block`] from `i` on, where its lean loop met something other than
/// a word: blanks, comments, block ends, block delete, tape marks, `,C`
/// and every error.
#[inline(never)]
fn lex_rest(
    line: &[u8],
    start: usize,
    mut i: usize,
    rules: &LexRules,
    out: &mut Block,
) -> Result<usize, Diagnostic> {
    // The lean loop reads only words, so none was read if it stopped at
    // the start.
    let mut first = i == start;
    loop {
        let Some(&b) = line.get(i) else {
            return finish(out, start, i, line.len());
        };
        // A word: a letter, or `,C`/`,R` (Fanuc chamfer and corner R) or
        // `@`/`^` (LinuxCNC polar words) when the dialect has them, or `:`
        // read as O.
        if is_letter(b) || (matches!(b, b',' | b'@' | b'^') && is_extended(line, i, rules)) {
            i = lex_word(line, start, i, b & !0x20, rules, out)?;
            first = false;
            continue;
        }
        if b == b':' && rules.colon_is_o {
            i = lex_word(line, start, i, b'O', rules, out)?;
            first = false;
            continue;
        }
        match b {
            b' ' | b'\t' | b'\r' | b'\n' | 0x0c => i += 1,
            b';' if rules.semicolon == Semicolon::Comment => {
                return finish(out, start, i, line.len());
            }
            b';' => return finish(out, start, i, i + 1),
            b'(' => i = skip_comment(line, i, rules.paren_in_comment_alarms)?,
            b'/' if rules.slash_comments && line.get(i + 1) == Some(&b'/') => {
                return finish(out, start, i, line.len());
            }
            b'/' if first => {
                i += 1;
                let level = match line.get(i) {
                    Some(d @ b'1'..=b'9') => {
                        i += 1;
                        d - b'0'
                    }
                    _ => 1,
                };
                out.deleted = Some(level);
            }
            b'%' if first && out.deleted.is_none() => {
                out.percent = true;
                return finish(out, start, i + 1, line.len());
            }
            0xEF if rules.fullwidth_semicolon && line[i..].starts_with(FULLWIDTH_SEMICOLON) => {
                return finish(out, start, i, i + FULLWIDTH_SEMICOLON.len());
            }
            // A byte-order mark (editors put one at the start of a file).
            0xEF if line[i..].starts_with(BOM) => i += BOM.len(),
            b'$' if first => return Err(system_command(line, i)),
            b')' => return Err(diag::stray_close_paren(Span::new(i, i + 1))),
            b'0'..=b'9' if first => return Err(digit_first(line, i)),
            _ => return Err(illegal_at(line, i)),
        }
        first = first && matches!(b, b' ' | b'\t' | b'\r' | b'(' | 0x0c);
        if i - start > MAX_BLOCK_BYTES {
            return Err(too_long(start));
        }
    }
}

/// E106 for the block that starts at `start`.
#[cold]
fn too_long(start: usize) -> Diagnostic {
    diag::block_too_long(Span::new(start, start + 1), MAX_BLOCK_BYTES)
}

/// E106 if the blanks skipped after a word (from `end` to `next`) took the
/// block beyond its length, as the main loop's check after each blank
/// would. Out of line, so that the common path is one compare.
#[cold]
fn blanks_too_long(start: usize, end: usize, next: usize) -> Result<(), Diagnostic> {
    if next > end {
        return Err(too_long(start));
    }
    Ok(())
}

fn finish(out: &mut Block, start: usize, end: usize, next: usize) -> Result<usize, Diagnostic> {
    out.span = Span::new(start, end);
    Ok(next)
}

fn skip_comment(line: &[u8], open: usize, strict: bool) -> Result<usize, Diagnostic> {
    match memchr::memchr(b')', &line[open + 1..]) {
        Some(k) => {
            let close = open + 1 + k;
            if let Some(inner) = memchr::memchr(b'(', &line[open + 1..close]) {
                if strict {
                    return Err(diag::paren_in_comment(Span::new(
                        open + 1 + inner,
                        open + 2 + inner,
                    )));
                }
                nested_comment(line, open + 1 + inner, close)?;
            }
            Ok(close + 1)
        }
        None => Err(diag::unterminated_comment(Span::new(open, open + 1))),
    }
}

/// E101 when a comment holds an `(` at `inner` and a `)` follows the one at
/// `close` with no `(` between (`(A (B) C)`): comments do not nest, so the
/// first `)` ended the comment and the rest would be read as words. Said
/// here, at the inner `(`, rather than as whatever the rest fails on.
#[cold]
fn nested_comment(line: &[u8], inner: usize, close: usize) -> Result<(), Diagnostic> {
    let rest = &line[close + 1..];
    let next_close = memchr::memchr(b')', rest);
    let next_open = memchr::memchr(b'(', rest);
    match (next_close, next_open) {
        (Some(c), Some(o)) if o < c => Ok(()),
        (Some(_), _) => Err(diag::nested_comment(Span::new(inner, inner + 1))),
        (None, _) => Ok(()),
    }
}

/// Lexes the word at `at` into `out` and returns where lexing goes on:
/// past the spaces and tabs after the word when the number parser has
/// looked at them, which the main loop would otherwise step over one by
/// one (counting them toward the block's length, as here).
#[inline(always)]
fn lex_word(
    line: &[u8],
    start: usize,
    at: usize,
    letter: u8,
    rules: &LexRules,
    out: &mut Block,
) -> Result<usize, Diagnostic> {
    let (addr, value_at) = address(line, at, letter, rules);
    let (n, next) = match lex_number(line, value_at) {
        Ok(n) => n,
        Err(e) => return Err(word_error(line, at, value_at, e, rules, out)),
    };
    let word = Word {
        addr,
        value: n.value,
        point: n.point,
        span: Span::new(at, n.end),
    };
    if !out.push(word) {
        return Err(diag::too_many_words(word.span, MAX_WORDS));
    }
    if next - start > MAX_BLOCK_BYTES {
        blanks_too_long(start, n.end, next)?;
    }
    Ok(next)
}

/// Why the word at `at`, whose value should start at `value_at`, has no
/// number: an address of another dialect, a lettered program name, or the
/// number's own error. Out of line, so that the word loop keeps neither
/// the rules' foreign addresses nor a diagnostic in its frame.
#[cold]
#[inline(never)]
fn word_error(
    line: &[u8],
    at: usize,
    value_at: usize,
    e: NumberError,
    rules: &LexRules,
    out: &Block,
) -> Diagnostic {
    foreign_address(line, at, rules)
        .or_else(|| o_word_flow(line, at, out))
        .or_else(|| variable_value(line, value_at))
        .or_else(|| lettered_program_name(line, at, out))
        .unwrap_or_else(|| number_error(line, at, value_at, e))
}

/// `X#1`, `X[#1+2]`: a variable or an expression as a word's value, in a
/// dialect without macros (a macro dialect's parser reads it first).
#[cold]
fn variable_value(line: &[u8], value_at: usize) -> Option<Diagnostic> {
    matches!(line.get(value_at), Some(b'#' | b'['))
        .then(|| diag::variable_without_macros(Span::new(value_at, value_at + 1)))
}

/// LinuxCNC's O-word statements after a block's O number (`o100 sub`).
const O_KEYWORDS: &[&str] = &[
    "sub",
    "endsub",
    "call",
    "return",
    "if",
    "elseif",
    "else",
    "endif",
    "while",
    "endwhile",
    "do",
    "repeat",
    "endrepeat",
    "break",
    "continue",
];

/// LinuxCNC's O-word flow control, which no vcnc dialect reads: `o<name>`
/// (an O without a number) or a keyword after a blank after the block's
/// O number (`o100 sub`, `N10 O101 while [#1 LT 3]`; glued, `O100IF` is a
/// lettered program name).
#[cold]
fn o_word_flow(line: &[u8], at: usize, out: &Block) -> Option<Diagnostic> {
    let word_end = |from: usize| {
        from + line[from..]
            .iter()
            .take_while(|c| c.is_ascii_alphanumeric() || matches!(c, b'<' | b'>' | b'_'))
            .count()
    };
    if line[at].eq_ignore_ascii_case(&b'O') && line.get(at + 1) == Some(&b'<') {
        return Some(diag::o_word_flow(Span::new(at, word_end(at + 1))));
    }
    let o = out.words().last()?;
    let o_end = o.span.end as usize;
    let blank = line
        .get(o_end..at)
        .is_some_and(|gap| !gap.is_empty() && gap.iter().all(|c| matches!(c, b' ' | b'\t')));
    if o.addr.as_letter() != Some(b'O') || !blank {
        return None;
    }
    let end = word_end(at);
    let keyword = &line[at..end];
    O_KEYWORDS
        .iter()
        .any(|k| keyword.eq_ignore_ascii_case(k.as_bytes()))
        .then(|| diag::o_word_flow(Span::new(o.span.start as usize, end)))
}

/// `O7997A`: a letter glued to the program number of an `O` word that
/// starts the block.
#[cold]
fn lettered_program_name(line: &[u8], at: usize, out: &Block) -> Option<Diagnostic> {
    let first = out.words().first()?;
    let glued = out.words().len() == 1
        && first.addr.as_letter() == Some(b'O')
        && first.span.end as usize == at;
    if !glued {
        return None;
    }
    let end = line[at..]
        .iter()
        .position(|b| !b.is_ascii_alphanumeric())
        .map_or(line.len(), |k| at + k);
    let name = String::from_utf8_lossy(&line[first.span.start as usize..end]).into_owned();
    Some(diag::lettered_program_name(
        Span::new(first.span.start as usize, end),
        &name,
    ))
}

/// An address of another dialect at `at`, as a diagnostic.
#[cold]
fn foreign_address(line: &[u8], at: usize, rules: &LexRules) -> Option<Diagnostic> {
    rules.foreign.iter().find_map(|(text, dialect)| {
        let t = text.as_bytes();
        let here = line.get(at..at + t.len())?;
        here.eq_ignore_ascii_case(t)
            .then(|| diag::foreign_address(Span::new(at, at + t.len()), text, dialect))
    })
}

#[cold]
fn number_error(line: &[u8], at: usize, value_at: usize, e: NumberError) -> Diagnostic {
    let letter = char::from(line[at].to_ascii_uppercase());
    let end = (value_at + 1).min(line.len()).max(at + 1);
    let span = Span::new(at, end);
    match e {
        NumberError::Missing => diag::missing_value(span, letter),
        NumberError::Malformed => diag::malformed_number(span, letter),
        NumberError::OutOfRange => diag::number_out_of_range(span, letter),
    }
}

/// The address at `at`, whose byte is `letter` in uppercase if it is a
/// letter (and not an address if not), and the index where its value
/// starts.
#[inline]
fn address(line: &[u8], at: usize, letter: u8, rules: &LexRules) -> (Addr, usize) {
    if is_letter(letter) && !rules.extended.may_start(letter) {
        return (Addr::letter(letter), at + 1);
    }
    for (text, addr) in rules.extended.all {
        let t = text.as_bytes();
        if line.len() >= at + t.len() && line[at..at + t.len()].eq_ignore_ascii_case(t) {
            return (*addr, at + t.len());
        }
    }
    (Addr::letter(letter), at + 1)
}

/// Whether one of the dialect's extended addresses starts at `at`.
fn is_extended(line: &[u8], at: usize, rules: &LexRules) -> bool {
    rules.extended.all.iter().any(|(text, _)| {
        line.get(at..at + text.len())
            .is_some_and(|here| here.eq_ignore_ascii_case(text.as_bytes()))
    })
}

/// A grbl system command (`$H`, `$X`, `$$`) in a program.
#[cold]
fn system_command(line: &[u8], i: usize) -> Diagnostic {
    let end = line[i..]
        .iter()
        .position(|b| b.is_ascii_whitespace() || *b == b';' || *b == b'(')
        .map_or(line.len(), |k| i + k);
    let text = String::from_utf8_lossy(&line[i..end]).into_owned();
    diag::system_command(Span::new(i, end), &text)
}

/// A block that starts with a digit: a line number without its N, or a
/// value without its address.
#[cold]
fn digit_first(line: &[u8], i: usize) -> Diagnostic {
    let end = line[i..]
        .iter()
        .position(|b| !(b.is_ascii_digit() || *b == b'.'))
        .map_or(line.len(), |k| i + k);
    let text = String::from_utf8_lossy(&line[i..end]).into_owned();
    diag::digit_first(Span::new(i, end), &text)
}

fn illegal_at(line: &[u8], i: usize) -> Diagnostic {
    if line[i] == b'#' {
        return diag::variable_without_macros(Span::new(i, i + 1));
    }
    let rest = &line[i..];
    let len = utf8_len(rest);
    let ch = std::str::from_utf8(&rest[..len])
        .ok()
        .and_then(|s| s.chars().next())
        .unwrap_or('\u{FFFD}');
    diag::illegal_character(Span::new(i, i + len), ch)
}

fn utf8_len(rest: &[u8]) -> usize {
    let want = match rest.first() {
        Some(b) if *b >= 0xF0 => 4,
        Some(b) if *b >= 0xE0 => 3,
        Some(b) if *b >= 0xC0 => 2,
        _ => 1,
    };
    if rest.len() >= want && std::str::from_utf8(&rest[..want]).is_ok() {
        want
    } else {
        1
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostics::Code;

    const SYNTEC: LexRules = LexRules {
        semicolon: Semicolon::EndOfBlock,
        slash_comments: true,
        fullwidth_semicolon: true,
        extended: Extended::NONE,
        foreign: &[("CR=", "lathe")],
        colon_is_o: false,
        paren_in_comment_alarms: false,
    };

    fn blocks(src: &str) -> Result<Vec<String>, Code> {
        let line = src.as_bytes();
        let mut out = Block::default();
        let mut res = Vec::new();
        let mut i = 0;
        while i < line.len() {
            i = lex_block(line, i, &SYNTEC, &mut out).map_err(|d| d.code)?;
            let words: Vec<String> = out
                .words()
                .iter()
                .map(|w| {
                    format!(
                        "{}{}{}",
                        char::from(w.addr.0),
                        w.value,
                        if w.point { "." } else { "" }
                    )
                })
                .collect();
            res.push(words.join(" "));
        }
        Ok(res)
    }

    #[test]
    fn splits_blocks_and_skips_comments() {
        assert_eq!(
            blocks("n10 g1 x5.5 (cut; here) y-2;G4 P500 // note").unwrap(),
            vec!["N10 G1 X5.5. Y-2", "G4 P500"]
        );
        assert_eq!(
            blocks("G90 G00 X5500 Y4000；//positioning").unwrap(),
            vec!["G90 G0 X5500 Y4000", ""]
        );
        assert_eq!(blocks("X 1 0 . 5").unwrap(), vec!["X10.5."]);
        assert_eq!(blocks("\u{FEFF}G0 X1").unwrap(), vec!["G0 X1"]);
    }

    #[test]
    fn a_comment_holding_a_parenthesis_says_comments_do_not_nest() {
        // Regression: `(A (B) C)` used to alarm E104 "address C has no value".
        let mut out = Block::default();
        let err = lex_block(b"G0 X0 (A (B) C)", 0, &SYNTEC, &mut out).unwrap_err();
        assert_eq!(err.code, Code::E101);
        assert_eq!((err.span.start, err.span.end), (9, 10));
        assert!(err.message.contains("do not nest"), "{}", err.message);
        // An `(` inside a comment alone is text, and so is one whose
        // follower opens a second comment.
        assert_eq!(blocks("G0 X1 (A ( B)").unwrap(), vec!["G0 X1"]);
        assert_eq!(blocks("G0 X1 (A ( B) (C)").unwrap(), vec!["G0 X1"]);
        // Where any `(` in a comment alarms (LinuxCNC), both do.
        let strict = LexRules {
            paren_in_comment_alarms: true,
            ..SYNTEC
        };
        for text in [&b"G0 X1 (A ( B)"[..], b"G0 X1 (A ( B) (C)"] {
            let err = lex_block(text, 0, &strict, &mut out).unwrap_err();
            assert_eq!((err.code, err.span.start), (Code::E101, 9));
        }
    }

    #[test]
    fn marks_block_delete_and_tape_marks() {
        let mut out = Block::default();
        lex_block(b"/2 G00 X1", 0, &SYNTEC, &mut out).unwrap();
        assert_eq!(out.deleted, Some(2));
        lex_block(b"%", 0, &SYNTEC, &mut out).unwrap();
        assert!(out.percent);
    }

    #[test]
    fn reports_bad_input_with_codes() {
        assert_eq!(blocks("G01 X1 #1"), Err(Code::E101));
        // A variable as a value: the lexer's alarm for dialects without
        // macros (a macro dialect's parser reads the block first).
        assert_eq!(blocks("G01 X#1"), Err(Code::E101));
        assert_eq!(blocks("G01 X[1+2]"), Err(Code::E101));
        assert_eq!(blocks("G01 X1.2.3"), Err(Code::E102));
        // An exponent is just another word for the interpreter to reject.
        assert_eq!(blocks("X1e400").unwrap(), vec!["X1 E400"]);
        assert_eq!(blocks("G X10"), Err(Code::E104));
        assert_eq!(blocks("G01 (open"), Err(Code::E105));
        assert_eq!(blocks("X12345678901234567890"), Err(Code::E103));
        assert_eq!(blocks("G01 X1 % "), Err(Code::E101));
        assert_eq!(blocks("G02 X1 CR=5"), Err(Code::E203));
    }

    #[test]
    fn reads_extended_addresses_only_where_they_start() {
        let rules = LexRules {
            extended: Extended::new(&[("CR=", Addr::CR), ("IX", Addr::IX), (",C", Addr::COMMA_C)]),
            ..SYNTEC
        };
        let mut out = Block::default();
        lex_block(b"cr=5 C6 ix2 I3 X1 ,c2", 0, &rules, &mut out).unwrap();
        let addrs: Vec<Addr> = out.words().iter().map(|w| w.addr).collect();
        assert_eq!(
            addrs,
            [
                Addr::CR,
                Addr::letter(b'C'),
                Addr::IX,
                Addr::letter(b'I'),
                Addr::letter(b'X'),
                Addr::COMMA_C
            ]
        );
        // Only C and I start one of these.
        assert!(rules.extended.may_start(b'C') && rules.extended.may_start(b'I'));
        assert!(!rules.extended.may_start(b'X') && !Extended::NONE.may_start(b'C'));
    }
}
