//! The byte scanner under both macro grammars: blanks and comments,
//! identifiers, numbers and punctuation, with the span of each.
//!
//! The parser asks for what it expects (`ident`, `number`, `eat(b'[')`), so
//! that context decides what a letter is: an address in a word block
//! (`X10`), a keyword or a function in an expression (`SIN`, `END_IF`).

use super::MacroSyntax;
use super::expr::{Comments, Grammar, grammar};
use crate::diagnostics as diag;
use crate::number::parse_number;
use vcnc_core::{Diagnostic, Span};

/// A scanner over `text[pos..end]`.
pub(super) struct Scan<'a> {
    pub text: &'a [u8],
    pub pos: usize,
    pub end: usize,
    pub syn: MacroSyntax,
    /// Text of the `( )` comments passed (Macro B messages).
    pub comment: Option<String>,
}

/// A number as written.
#[derive(Debug, Clone, Copy)]
pub(super) struct Num {
    pub value: f64,
    pub point: bool,
    pub span: Span,
}

impl<'a> Scan<'a> {
    pub fn new(text: &'a [u8], pos: usize, end: usize, syn: MacroSyntax) -> Scan<'a> {
        Scan {
            text,
            pos,
            end: end.min(text.len()),
            syn,
            comment: None,
        }
    }

    /// The byte at `pos + k` (0 past the end).
    pub fn at(&self, k: usize) -> u8 {
        let i = self.pos + k;
        if i < self.end { self.text[i] } else { 0 }
    }

    /// Skips blanks and comments; `Err` for a comment left open.
    /// The grammar of the text's language.
    pub fn g(&self) -> &'static Grammar {
        grammar(self.syn.lang)
    }

    pub fn trivia(&mut self) -> Result<(), Diagnostic> {
        let comments = self.g().comments;
        if comments == Comments::ParenSemicolon {
            self.ngc_trivia();
            return Ok(());
        }
        loop {
            match self.at(0) {
                b' ' | b'\t' | b'\r' | b'\n' | 0x0c => self.pos += 1,
                // A byte-order mark.
                0xEF if self.at(1) == 0xBB && self.at(2) == 0xBF => self.pos += 3,
                b'/' if self.at(1) == b'/' && self.syn.slash_comments => {
                    while self.pos < self.end && self.text[self.pos] != b'\n' {
                        self.pos += 1;
                    }
                }
                b'(' if comments == Comments::StarParen && self.at(1) == b'*' => {
                    let open = self.pos;
                    self.pos += 2;
                    loop {
                        if self.pos + 1 >= self.end {
                            // Stay before the comment: a caller that ignores
                            // this error (`here`) must not skip the text.
                            self.pos = open;
                            return Err(diag::unterminated_block_comment(Span::new(
                                open,
                                open + 2,
                            )));
                        }
                        if self.text[self.pos] == b'*' && self.text[self.pos + 1] == b')' {
                            self.pos += 2;
                            break;
                        }
                        self.pos += 1;
                    }
                }
                b'(' if comments == Comments::ParenMessages => {
                    let open = self.pos;
                    let rest = &self.text[self.pos + 1..self.end];
                    let Some(k) = memchr::memchr(b')', rest) else {
                        return Err(diag::unterminated_comment(Span::new(open, open + 1)));
                    };
                    let inner = String::from_utf8_lossy(&rest[..k]);
                    let c = self.comment.get_or_insert_with(String::new);
                    if !c.is_empty() {
                        c.push(' ');
                    }
                    c.push_str(inner.trim());
                    self.pos = open + 1 + k + 1;
                }
                _ => return Ok(()),
            }
        }
    }

    /// LinuxCNC's blanks: spaces, tabs, `( )` comments (one left open
    /// runs to the end) and a `;` comment to the end of the line.
    fn ngc_trivia(&mut self) {
        loop {
            match self.at(0) {
                b' ' | b'\t' | b'\r' => self.pos += 1,
                b'(' => match memchr::memchr(b')', &self.text[self.pos..self.end]) {
                    Some(k) => self.pos += k + 1,
                    None => self.pos = self.end,
                },
                b';' | b'\n' => self.pos = self.end,
                _ => return,
            }
        }
    }

    /// The next byte after blanks and comments (0 at the end).
    pub fn peek(&mut self) -> Result<u8, Diagnostic> {
        self.trivia()?;
        Ok(self.at(0))
    }

    /// Consumes `b` if it comes next.
    pub fn eat(&mut self, b: u8) -> Result<bool, Diagnostic> {
        if self.peek()? == b {
            self.pos += 1;
            return Ok(true);
        }
        Ok(false)
    }

    /// Consumes the two bytes `s` if they come next.
    pub fn eat2(&mut self, s: &[u8; 2]) -> Result<bool, Diagnostic> {
        if self.peek()? == s[0] && self.at(1) == s[1] {
            self.pos += 2;
            return Ok(true);
        }
        Ok(false)
    }

    /// Whether byte `b` continues an identifier.
    fn ident_byte(&self, b: u8, first: bool) -> bool {
        b.is_ascii_alphabetic()
            || (self.g().ident_tail && !first && (b.is_ascii_digit() || b == b'_'))
    }

    /// Length of the identifier at `pos` (after blanks), 0 if none.
    pub fn ident_len(&mut self) -> Result<usize, Diagnostic> {
        self.trivia()?;
        let mut k = 0;
        while self.ident_byte(self.at(k), k == 0) {
            k += 1;
        }
        Ok(k)
    }

    /// The identifier at `pos`, uppercase, with its span (not consumed).
    pub fn peek_ident(&mut self) -> Result<Option<(String, Span)>, Diagnostic> {
        let k = self.ident_len()?;
        if k == 0 {
            return Ok(None);
        }
        let word = &self.text[self.pos..self.pos + k];
        let s = String::from_utf8_lossy(word).to_ascii_uppercase();
        Ok(Some((s, Span::new(self.pos, self.pos + k))))
    }

    /// Consumes keyword `kw` if it is the next identifier.
    pub fn keyword(&mut self, kw: &str) -> Result<bool, Diagnostic> {
        let k = self.ident_len()?;
        if k == kw.len() && self.text[self.pos..self.pos + k].eq_ignore_ascii_case(kw.as_bytes()) {
            self.pos += k;
            return Ok(true);
        }
        Ok(false)
    }

    /// Whether the text at `pos` starts with `kw` as a prefix (Macro B
    /// writes `GOTO10`, `DO1`, `END1` glued to their numbers).
    pub fn at_prefix(&mut self, kw: &str) -> Result<bool, Diagnostic> {
        self.trivia()?;
        let k = kw.len();
        let word_ends = !self.at(k).is_ascii_alphabetic();
        Ok(self.pos + k <= self.end
            && self.text[self.pos..self.pos + k].eq_ignore_ascii_case(kw.as_bytes())
            && word_ends)
    }

    /// An unsigned number (digits and at most one point; Syntec also
    /// `0x` hexadecimal), digit by digit.
    pub fn number(&mut self) -> Result<Option<Num>, Diagnostic> {
        self.trivia()?;
        let start = self.pos;
        if self.g().hex_numbers
            && self.at(0) == b'0'
            && matches!(self.at(1), b'x' | b'X')
            && self.at(2).is_ascii_hexdigit()
        {
            return self.hex(start).map(Some);
        }
        let mut k = 0;
        while self.at(k).is_ascii_digit() || self.at(k) == b'.' {
            k += 1;
        }
        if k == 0 {
            return Ok(None);
        }
        let span = Span::new(start, start + k);
        if self.g().ngc_values {
            return self.ngc_number(span).map(Some);
        }
        let n = parse_number(&self.text[..start + k], start).map_err(|e| {
            use crate::number::NumberError;
            match e {
                NumberError::OutOfRange => diag::macro_number_out_of_range(span),
                _ => diag::macro_syntax(
                    span,
                    "this is not a number",
                    "write digits with at most one decimal point",
                ),
            }
        })?;
        self.pos = start + k;
        Ok(Some(Num {
            value: n.value,
            point: n.point,
            span,
        }))
    }

    /// LinuxCNC reads any run of digits and points as one number; the
    /// text holds nothing but digits and points, so the float parser can
    /// only fail (`1.2.3`, `.`) or give a large finite value (or infinity
    /// for 309 digits, which the word's and the setting's range checks
    /// stop).
    fn ngc_number(&mut self, span: Span) -> Result<Num, Diagnostic> {
        let digits = &self.text[span.start as usize..span.end as usize];
        let value = std::str::from_utf8(digits)
            .ok()
            .and_then(|t| t.parse::<f64>().ok())
            .ok_or_else(|| super::ngc::ngc_expected(span, "a number"))?;
        self.pos = span.end as usize;
        Ok(Num {
            value,
            point: false,
            span,
        })
    }

    fn hex(&mut self, start: usize) -> Result<Num, Diagnostic> {
        let mut k = 2;
        let mut v: u64 = 0;
        while self.at(k).is_ascii_hexdigit() {
            let d = char::from(self.at(k)).to_digit(16).unwrap_or(0);
            v = v
                .checked_mul(16)
                .and_then(|v| v.checked_add(u64::from(d)))
                .filter(|v| *v <= u64::from(u32::MAX))
                .ok_or_else(|| diag::macro_number_out_of_range(Span::new(start, start + k + 1)))?;
            k += 1;
        }
        self.pos = start + k;
        // At most 32 bits: exact in an f64.
        #[allow(clippy::cast_precision_loss)]
        let value = v as f64;
        Ok(Num {
            value,
            point: false,
            span: Span::new(start, start + k),
        })
    }

    /// A `"string"` (Syntec), its contents as text.
    pub fn string(&mut self) -> Result<Option<(Box<str>, Span)>, Diagnostic> {
        if self.peek()? != b'"' {
            return Ok(None);
        }
        let open = self.pos;
        let rest = &self.text[open + 1..self.end];
        let k = rest
            .iter()
            .position(|b| *b == b'"' || *b == b'\n')
            .filter(|k| rest[*k] == b'"')
            .ok_or_else(|| {
                diag::macro_syntax(
                    Span::new(open, open + 1),
                    "this string is not closed",
                    "end it with \" on the same line",
                )
            })?;
        let s = String::from_utf8_lossy(&rest[..k]).into_owned();
        self.pos = open + 1 + k + 1;
        Ok(Some((s.into_boxed_str(), Span::new(open, self.pos))))
    }

    /// Span of the next token (for "unexpected …" messages).
    pub fn here(&mut self) -> Span {
        let _ = self.trivia();
        let len = char_len(&self.text[self.pos.min(self.end)..self.end]).max(1);
        Span::new(self.pos, self.pos + len)
    }

    /// What the next token looks like, for messages.
    pub fn show_next(&mut self) -> String {
        let _ = self.trivia();
        if self.pos >= self.end {
            return "the end of the statement".into();
        }
        let k = self.ident_len().unwrap_or(0).max(1);
        let k = k.min(self.end - self.pos);
        format!(
            "`{}`",
            String::from_utf8_lossy(&self.text[self.pos..self.pos + k])
        )
    }
}

/// Bytes of the UTF-8 character that starts `rest` (1 for a stray byte).
fn char_len(rest: &[u8]) -> usize {
    let want = match rest.first() {
        Some(b) if *b >= 0xF0 => 4,
        Some(b) if *b >= 0xE0 => 3,
        Some(b) if *b >= 0xC0 => 2,
        Some(_) => 1,
        None => 0,
    };
    if want > 1 && rest.len() >= want && std::str::from_utf8(&rest[..want]).is_ok() {
        want
    } else {
        want.min(1)
    }
}
