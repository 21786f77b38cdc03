//! Statements: one ISO block of Custom Macro B, or one Syntec MACRO
//! statement (which may span lines).
//!
//! ```text
//!   Macro B block       [/n] [Nn] ( #i = e | IF [c] GOTO n | IF [c] THEN #i = e
//!                                 | WHILE [c] DO m | DO m | END m | GOTO n | words ) [;]
//!   word                letter ( number | [±]#n | [±]#[e] | [±][e] )
//!
//!   Syntec statement    [Nn] ( v := e; | IF c THEN | ELSEIF c THEN | ELSE | END_IF;
//!                            | CASE e OF | k, …: | END_CASE; | FOR v := a TO b [BY c] DO
//!                            | END_FOR; | WHILE c DO | END_WHILE; | REPEAT
//!                            | UNTIL c END_REPEAT; | EXIT; | GOTO n; | f(…); | words; )
//!   word                letter expression          (G01 X(#1+2.) Y30./2.)
//! ```
//!
//! A Syntec statement ends at its `;`, or right after the keyword that opens
//! a body (THEN, DO, OF, ELSE, REPEAT, a label's `:`); a line without `;`
//! joins the next one, as the controller reads it (its §4.13).
//! [`syntec_extent`] finds where a statement ends in text the caller
//! assembles line by line, so the statement reader needs no grammar of its
//! own.

use super::expr::{ExprParser, abbreviation, is_function};
use super::scan::Scan;
use super::{Expr, Lang, MAX_MACRO_WORDS, MValue, MWord, MacroSyntax, OpCode, Statement, StmtKind};
use super::{Target, Value, VarKind};
use crate::block::Addr;
use crate::diagnostics as diag;
use crate::number::{NumberError, parse_number};
use vcnc_core::{Diagnostic, Span};

const FULLWIDTH_SEMICOLON: &[u8] = "；".as_bytes();

/// Where one ISO block ends in `line`: (end of its text, start of the next).
fn iso_block_end(line: &[u8], start: usize, slash_comments: bool) -> (usize, usize) {
    let mut i = start;
    while i < line.len() {
        match line[i] {
            b'(' => match memchr::memchr(b')', &line[i..]) {
                Some(k) => i += k + 1,
                None => return (line.len(), line.len()),
            },
            b';' => return (i, i + 1),
            b'/' if slash_comments && line.get(i + 1) == Some(&b'/') => {
                return (i, line.len());
            }
            0xEF if line[i..].starts_with(FULLWIDTH_SEMICOLON) => {
                return (i, i + FULLWIDTH_SEMICOLON.len());
            }
            _ => i += 1,
        }
    }
    (line.len(), line.len())
}

/// Whether the block text (comments skipped) holds macro syntax: a `#`, a
/// `[`, or a statement keyword at its head.
fn has_macro_syntax(text: &[u8], start: usize, end: usize) -> bool {
    let mut i = start;
    let mut head = true;
    let mut word_start = true;
    while i < end {
        let b = text[i];
        match b {
            b'#' | b'[' => return true,
            b'(' => match memchr::memchr(b')', &text[i..end]) {
                Some(k) => {
                    i += k + 1;
                    continue;
                }
                None => return false,
            },
            b'a'..=b'z' | b'A'..=b'Z' if head && word_start => {
                let rest = &text[i..end];
                // With Macro B's abbreviations WH, EN, GO.
                let kw = ["IF", "WHILE", "DO", "END", "GOTO", "WH", "EN", "GO"]
                    .iter()
                    .any(|k| {
                        rest.len() >= k.len()
                            && rest[..k.len()].eq_ignore_ascii_case(k.as_bytes())
                            && !rest.get(k.len()).is_some_and(u8::is_ascii_alphabetic)
                    });
                if kw {
                    return true;
                }
                // Only `/`, `N` numbers and blanks may come before a keyword.
                head = matches!(b, b'N' | b'n');
            }
            b' ' | b'\t' | b'\r' | b'/' => {}
            b'0'..=b'9' | b'.' => {}
            _ => head = false,
        }
        word_start = !b.is_ascii_alphabetic();
        i += 1;
    }
    false
}

/// Parses the ISO (Custom Macro B) block that starts at `start` of `line`.
///
/// Returns `Ok(None)` when the block holds no macro syntax, so that the
/// literal lexer's diagnostic stands; otherwise the statement and where the
/// next block starts.
pub fn parse_iso_block(
    line: &[u8],
    start: usize,
    syn: &MacroSyntax,
) -> Result<Option<(Statement, usize)>, Diagnostic> {
    let (end, next) = iso_block_end(line, start, syn.slash_comments);
    if !has_macro_syntax(line, start, end) {
        return Ok(None);
    }
    let mut s = Scan::new(line, start, end, *syn);
    let mut st = Statement {
        kind: StmtKind::Words(Vec::new()),
        first: Span::new(start, start + 1),
        seq: None,
        deleted: None,
        comment: None,
    };
    if s.peek()? == b'/' {
        s.pos += 1;
        st.deleted = Some(match s.at(0) {
            d @ b'1'..=b'9' => {
                s.pos += 1;
                d - b'0'
            }
            _ => 1,
        });
    }
    let mut words = Vec::new();
    if matches!(s.peek()?, b'N' | b'n') && s.at(1).is_ascii_digit() {
        let w = iso_word(&mut s, false)?;
        if let MValue::Literal {
            value,
            point: false,
        } = w.value
        {
            st.seq = whole_u32(value);
        }
        words.push(w);
    }
    // The block's first word: its N label, else the statement's head.
    st.first = words.first().map_or_else(|| s.here(), |w| w.span);
    st.kind = iso_statement(&mut s, &mut words)?;
    s.trivia()?;
    st.comment = s.comment.take().map(String::into_boxed_str);
    Ok(Some((st, next)))
}

/// The statement of an ISO block after its optional `N` word.
fn iso_statement(s: &mut Scan<'_>, words: &mut Vec<MWord>) -> Result<StmtKind, Diagnostic> {
    let b = s.peek()?;
    if b == b'#' {
        return iso_assignment(s);
    }
    if b.is_ascii_alphabetic() {
        if s.at_prefix("IF")? {
            return iso_if(s);
        }
        if let Some(k) = macro_word(s, "WHILE")? {
            s.pos += k;
            let cond = bracketed(s, "WHILE")?;
            if !s.at_prefix("DO")? {
                return Err(expected(
                    s,
                    "DO m after the WHILE condition",
                    "WHILE [#1 LT 10] DO 1",
                ));
            }
            s.pos += 2;
            let m = loop_number(s, "DO")?;
            return finish(
                s,
                StmtKind::While {
                    cond: Some(cond),
                    m,
                },
            );
        }
        if s.at_prefix("DO")? {
            s.pos += 2;
            let m = loop_number(s, "DO")?;
            return finish(s, StmtKind::While { cond: None, m });
        }
        if let Some(k) = macro_word(s, "END")? {
            s.pos += k;
            let m = loop_number(s, "END")?;
            return finish(s, StmtKind::End(m));
        }
        if let Some(k) = macro_word(s, "GOTO")? {
            let word = Span::new(s.pos, s.pos + k);
            s.pos += k;
            let target = goto_target(s)?;
            return finish(s, StmtKind::Goto { word, target });
        }
    }
    loop {
        let b = s.peek()?;
        if s.pos >= s.end {
            break;
        }
        if !b.is_ascii_alphabetic() && comma_address(s).is_none() {
            return Err(stray(s));
        }
        if words.len() >= MAX_MACRO_WORDS {
            return Err(diag::too_many_words(s.here(), MAX_MACRO_WORDS));
        }
        let w = iso_word(s, true)?;
        words.push(w);
    }
    Ok(StmtKind::Words(std::mem::take(words)))
}

/// The length of custom macro word `full` (WHILE, END, GOTO) at the
/// scanner, glued to what follows (`END1`), or of its two-letter
/// abbreviation in the grammar (Macro B's `WH`, `EN`, `GO`: Fanuc's
/// abbreviations of custom macro words).
fn macro_word(s: &mut Scan<'_>, full: &str) -> Result<Option<usize>, Diagnostic> {
    if s.at_prefix(full)? {
        return Ok(Some(full.len()));
    }
    if let Some(short) = abbreviation(s.g(), full)
        && s.at_prefix(short)?
    {
        return Ok(Some(short.len()));
    }
    Ok(None)
}

/// After a statement: only blanks and comments may follow.
fn finish(s: &mut Scan<'_>, kind: StmtKind) -> Result<StmtKind, Diagnostic> {
    s.trivia()?;
    if s.pos < s.end {
        let what = s.show_next();
        return Err(diag::macro_syntax(
            s.here(),
            &format!("unexpected {what} after the statement"),
            "a macro statement stands alone in its block: put other words in a block of their own",
        ));
    }
    Ok(kind)
}

fn expected(s: &mut Scan<'_>, what: &str, example: &str) -> Diagnostic {
    let found = s.show_next();
    diag::macro_syntax(
        s.here(),
        &format!("expected {what}, found {found}"),
        &format!("write it like {example}"),
    )
}

/// A character that cannot start a word.
fn stray(s: &mut Scan<'_>) -> Diagnostic {
    let at = s.here();
    let rest = &s.text[at.start as usize..at.end as usize];
    let ch = std::str::from_utf8(rest)
        .ok()
        .and_then(|t| t.chars().next())
        .unwrap_or('\u{FFFD}');
    match ch {
        // In Syntec MACRO `[ ]` index variables: the advice differs.
        '+' | '-' | '*' | '/' | '=' | ']' if s.g().paren_groups => diag::macro_syntax(
            at,
            &format!("`{ch}` is not allowed here: a statement or a G-code block starts here"),
            "start a G-code block with its address letter, whose value may be an expression: X(#1 + 2.)",
        ),
        '+' | '-' | '*' | '/' | '=' | ']' => diag::macro_syntax(
            at,
            &format!(
                "`{ch}` is not allowed here: an address value is a number, a variable or [an expression]"
            ),
            "put the whole expression in brackets: X[#1+2.]",
        ),
        _ => diag::illegal_character(at, ch),
    }
}

/// `#i = e` or `#[e] = e`.
fn iso_assignment(s: &mut Scan<'_>) -> Result<StmtKind, Diagnostic> {
    let target = target(s)?;
    if !s.eat(b'=')? {
        // `/#2 G00 X1.` means a block delete switch from a variable, which
        // Custom Macro B does not have: say that rather than "expected =".
        let before = s.text[..target.span().start as usize]
            .iter()
            .rev()
            .find(|b| !matches!(b, b' ' | b'\t'));
        if before == Some(&b'/') {
            return Err(diag::block_delete_variable(target.span()));
        }
        return Err(expected(s, "`=` after the variable", "#1 = 2.5"));
    }
    let value = ExprParser::parse(s)?;
    if value.ops.is_empty() {
        return Err(expected(s, "a value after `=`", "#1 = 2.5"));
    }
    finish(s, StmtKind::Assign { target, value })
}

/// The variable at the head of an assignment (or a FOR).
fn target(s: &mut Scan<'_>) -> Result<Target, Diagnostic> {
    let b = s.peek()?;
    let kind = match b {
        b'#' => VarKind::Hash,
        b'@' if s.g().at_vars => VarKind::At,
        _ => return Err(expected(s, "a variable", "#1")),
    };
    let at = s.pos;
    if s.at(1) == b'[' {
        s.pos += 1;
        let open = s.pos;
        s.pos += 1;
        let mut p = ExprParser::new(s);
        p.expr()?;
        let index = std::mem::take(&mut p.out);
        if !s.eat(b']')? {
            let mut d = expected(s, "`]`", "#[#1+1]");
            if s.pos >= s.end {
                d.span = Span::new(open, open + 1);
            }
            return Err(d);
        }
        return Ok(Target::Indirect(kind, index, Span::new(at, s.pos)));
    }
    s.pos += 1;
    let mut p = ExprParser::new(s);
    let n = p.var_number(kind, at)?;
    Ok(Target::Fixed(kind, n, Span::new(at, s.pos)))
}

/// `IF [c] GOTO n` or `IF [c] THEN #i = e`.
fn iso_if(s: &mut Scan<'_>) -> Result<StmtKind, Diagnostic> {
    s.pos += 2;
    let cond = bracketed(s, "IF")?;
    if let Some(k) = macro_word(s, "GOTO")? {
        let word = Span::new(s.pos, s.pos + k);
        s.pos += k;
        let target = goto_target(s)?;
        return finish(s, StmtKind::IfGoto { cond, word, target });
    }
    let then = abbreviation(s.g(), "THEN");
    if s.keyword("THEN")? || (then.is_some_and(|t| t == "TH") && s.keyword("TH")?) {
        if s.peek()? != b'#' {
            return Err(expected(
                s,
                "an assignment after THEN",
                "IF [#1 EQ 0] THEN #2 = 5.",
            ));
        }
        let then = iso_assignment(s)?;
        return Ok(StmtKind::IfThen {
            cond,
            then: Box::new(then),
        });
    }
    Err(expected(
        s,
        "GOTO or THEN after the condition",
        "IF [#1 EQ 0] GOTO 100",
    ))
}

/// A condition in `[ ]` (Macro B requires the brackets).
fn bracketed(s: &mut Scan<'_>, keyword: &str) -> Result<Expr, Diagnostic> {
    if s.peek()? != b'[' {
        return Err(expected(
            s,
            &format!("a condition in [ ] after {keyword}"),
            &format!("{keyword} [#1 LT 10]"),
        ));
    }
    ExprParser::parse(s)
}

/// The target of a GOTO: a number, a variable or an expression.
fn goto_target(s: &mut Scan<'_>) -> Result<Expr, Diagnostic> {
    let e = ExprParser::parse(s)?;
    if e.ops.is_empty() {
        return Err(expected(s, "a sequence number after GOTO", "GOTO 100"));
    }
    Ok(e)
}

/// `m` of DO m / END m: 1, 2 or 3 written out.
fn loop_number(s: &mut Scan<'_>, keyword: &str) -> Result<u8, Diagnostic> {
    let Some(n) = s.number()? else {
        return Err(expected(
            s,
            &format!("a loop number 1, 2 or 3 after {keyword}"),
            &format!("{keyword} 1"),
        ));
    };
    match (n.point, n.value) {
        (false, 1.0) => Ok(1),
        (false, 2.0) => Ok(2),
        (false, 3.0) => Ok(3),
        _ => Err(diag::loop_number(n.span, keyword)),
    }
}

/// One word of an ISO block: a letter and a number, a variable or an
/// expression in brackets.
fn iso_word(s: &mut Scan<'_>, words_follow: bool) -> Result<MWord, Diagnostic> {
    s.trivia()?;
    let at = s.pos;
    let (addr, len) = comma_address(s).unwrap_or((Addr::letter(s.at(0).to_ascii_uppercase()), 1));
    // For messages: the letter of `,R` is R.
    let letter = s.at(len - 1).to_ascii_uppercase();
    s.pos += len;
    // Blanks may separate the letter from its value.
    s.trivia()?;
    let value_at = s.pos;
    let (sign, k) = match s.at(0) {
        b'-' => (Some(true), 1),
        b'+' => (Some(false), 1),
        _ => (None, 0),
    };
    let mut j = k;
    while matches!(s.at(j), b' ' | b'\t') {
        j += 1;
    }
    if matches!(s.at(j), b'#' | b'[') {
        // Fanuc 0i: "program numbers, sequence numbers ... cannot be
        // referenced using variables" (O#1, N#3 are its examples).
        if matches!(letter, b'N' | b'O') {
            return Err(diag::number_word_not_variable(
                Span::new(at, at + 1),
                char::from(letter),
            ));
        }
        s.pos = value_at + j;
        let mut p = ExprParser::new(s);
        p.primary()?;
        let mut e = std::mem::take(&mut p.out);
        if let Some(neg) = sign {
            let code = if neg { OpCode::Neg } else { OpCode::Pos };
            e.ops.push(super::Op {
                code,
                span: Span::new(value_at, value_at + 1),
            });
        }
        e.span = Span::new(value_at, s.pos);
        if words_follow {
            after_value(s)?;
        }
        return Ok(MWord {
            addr,
            value: MValue::Expr(e),
            span: Span::new(at, s.pos),
        });
    }
    // A plain number, read like the literal lexer reads it.
    match parse_number(&s.text[..s.end], value_at) {
        Ok(n) => {
            s.pos = n.end;
            if words_follow {
                after_value(s)?;
            }
            Ok(MWord {
                addr,
                value: MValue::Literal {
                    value: n.value,
                    point: n.point,
                },
                span: Span::new(at, n.end),
            })
        }
        Err(e) => {
            let end = (value_at + 1).min(s.end).max(at + 1);
            let span = Span::new(at, end);
            let l = char::from(letter);
            Err(match e {
                NumberError::Missing => diag::missing_value(span, l),
                NumberError::Malformed => diag::malformed_number(span, l),
                NumberError::OutOfRange => diag::number_out_of_range(span, l),
            })
        }
    }
}

/// After a word's value: another word, a comment or the end.
fn after_value(s: &mut Scan<'_>) -> Result<(), Diagnostic> {
    let b = s.peek()?;
    if s.pos >= s.end || b.is_ascii_alphabetic() || comma_address(s).is_some() {
        return Ok(());
    }
    Err(stray(s))
}

/// The dialect's `,C`/`,R` address at the scanner, and its length.
fn comma_address(s: &Scan<'_>) -> Option<(Addr, usize)> {
    if s.at(0) != b',' {
        return None;
    }
    s.syn.extended.iter().find_map(|(text, addr)| {
        let t = text.as_bytes();
        (t.first() == Some(&b',') && (0..t.len()).all(|k| s.at(k).eq_ignore_ascii_case(&t[k])))
            .then_some((*addr, t.len()))
    })
}

/// A whole number that fits a `u32`.
fn whole_u32(v: f64) -> Option<u32> {
    // In range and whole: exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    (v >= 0.0 && v <= f64::from(u32::MAX) && v.fract() == 0.0).then_some(v as u32)
}

/// Where a Syntec statement lies in the text assembled so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Extent {
    /// First byte of the statement (blanks and comments skipped).
    pub start: usize,
    /// One past its last byte (its `;` included).
    pub end: usize,
    /// The text ran out before the statement (or a comment) ended: read
    /// another line and ask again.
    pub incomplete: bool,
    /// Nothing but blanks and comments.
    pub empty: bool,
}

/// How a Syntec statement ends, from its first word.
#[derive(Clone, Copy, PartialEq)]
enum Ends {
    /// At `;`.
    Semicolon,
    /// Right after this keyword.
    After(&'static [&'static str]),
    /// After the keyword itself, and a `;` right after it.
    Keyword,
    /// After a label's `:`.
    Colon,
    /// At the end of the line (`%`).
    Line,
}

/// Finds the Syntec statement that starts at or after `start` in `text`.
pub fn syntec_extent(text: &[u8], start: usize) -> Extent {
    let mut i = start;
    // Blanks and comments.
    loop {
        match text.get(i) {
            Some(b' ' | b'\t' | b'\r' | b'\n' | 0x0c) => i += 1,
            Some(0xEF) if text[i..].starts_with("\u{FEFF}".as_bytes()) => i += 3,
            Some(b'/') if text.get(i + 1) == Some(&b'/') => {
                i = memchr::memchr(b'\n', &text[i..]).map_or(text.len(), |k| i + k);
            }
            Some(b'(') if text.get(i + 1) == Some(&b'*') => match find_close(text, i + 2) {
                Some(k) => i = k,
                None => return incomplete(start),
            },
            Some(_) => break,
            None => {
                return Extent {
                    start: i,
                    end: i,
                    incomplete: false,
                    empty: true,
                };
            }
        }
    }
    let first = i;
    let ends = match text[i] {
        b'%' => Ends::Line,
        b'0'..=b'9' => Ends::Colon,
        b if b.is_ascii_alphabetic() => {
            let word = ident_at(text, i);
            let upper = word.to_ascii_uppercase();
            let label_then = skip_label(text, i);
            match upper.as_slice() {
                b"IF" | b"ELSEIF" => Ends::After(&["THEN"]),
                b"WHILE" | b"FOR" => Ends::After(&["DO"]),
                b"CASE" => Ends::After(&["OF"]),
                b"UNTIL" => Ends::After(&["END_REPEAT", "ENDREPEAT"]),
                b"ELSE" | b"REPEAT" | b"END_IF" | b"ENDIF" | b"END_CASE" | b"ENDCASE"
                | b"END_FOR" | b"ENDFOR" | b"END_WHILE" | b"ENDWHILE" | b"EXIT" => Ends::Keyword,
                _ if label_then != i => return syntec_extent_labelled(text, start, first),
                _ => Ends::Semicolon,
            }
        }
        _ => Ends::Semicolon,
    };
    scan_to_end(text, start, first, ends)
}

/// `N10 IF …`: a label before a keyword statement ends like the keyword.
fn syntec_extent_labelled(text: &[u8], start: usize, first: usize) -> Extent {
    let after = skip_label(text, first);
    let mut e = syntec_extent(text, after);
    if e.empty {
        return scan_to_end(text, start, first, Ends::Semicolon);
    }
    e.start = first;
    e
}

/// After `N<digits>` and blanks at `i`, or `i` if there is no label.
fn skip_label(text: &[u8], i: usize) -> usize {
    if !matches!(text.get(i), Some(b'N' | b'n')) {
        return i;
    }
    let mut j = i + 1;
    if !text.get(j).is_some_and(u8::is_ascii_digit) {
        return i;
    }
    while text.get(j).is_some_and(u8::is_ascii_digit) {
        j += 1;
    }
    while matches!(text.get(j), Some(b' ' | b'\t')) {
        j += 1;
    }
    // Only a keyword statement after the label counts.
    let word = ident_at(text, j).to_ascii_uppercase();
    let keyword = matches!(
        word.as_slice(),
        b"IF" | b"WHILE" | b"FOR" | b"CASE" | b"REPEAT" | b"UNTIL" | b"ELSE" | b"ELSEIF"
    ) || word.starts_with(b"END");
    if keyword { j } else { i }
}

fn incomplete(start: usize) -> Extent {
    Extent {
        start,
        end: start,
        incomplete: true,
        empty: false,
    }
}

/// The index after the `*)` that closes a `(*` comment whose body starts
/// at `i`.
fn find_close(text: &[u8], mut i: usize) -> Option<usize> {
    while i + 1 < text.len() {
        if text[i] == b'*' && text[i + 1] == b')' {
            return Some(i + 2);
        }
        i += 1;
    }
    None
}

/// The identifier at `i` (letters, then letters, digits, `_`).
fn ident_at(text: &[u8], i: usize) -> &[u8] {
    let mut j = i;
    while let Some(b) = text.get(j) {
        let ok = b.is_ascii_alphabetic() || (j > i && (b.is_ascii_digit() || *b == b'_'));
        if !ok {
            break;
        }
        j += 1;
    }
    &text[i..j]
}

fn scan_to_end(text: &[u8], start: usize, first: usize, ends: Ends) -> Extent {
    let done = |end: usize| Extent {
        start: first,
        end,
        incomplete: false,
        empty: false,
    };
    let mut i = first;
    if ends == Ends::Line {
        let end = memchr::memchr(b'\n', &text[i..]).map_or(text.len(), |k| i + k);
        return done(end);
    }
    if ends == Ends::Keyword {
        i += ident_at(text, i).len();
        let mut j = i;
        while matches!(text.get(j), Some(b' ' | b'\t' | b'\r')) {
            j += 1;
        }
        return done(if text.get(j) == Some(&b';') { j + 1 } else { i });
    }
    while i < text.len() {
        let b = text[i];
        match b {
            b';' => return done(i + 1),
            b':' if ends == Ends::Colon && text.get(i + 1) != Some(&b'=') => return done(i + 1),
            b'"' => {
                i = memchr::memchr2(b'"', b'\n', &text[i + 1..])
                    .map_or(text.len(), |k| i + 1 + k + 1);
                continue;
            }
            b'/' if text.get(i + 1) == Some(&b'/') => {
                i = memchr::memchr(b'\n', &text[i..]).map_or(text.len(), |k| i + k);
                continue;
            }
            b'(' if text.get(i + 1) == Some(&b'*') => match find_close(text, i + 2) {
                Some(k) => {
                    i = k;
                    continue;
                }
                None => return incomplete(start),
            },
            b if b.is_ascii_alphabetic() && (i == 0 || !is_ident_byte(text[i - 1])) => {
                let word = ident_at(text, i);
                if let Ends::After(keywords) = ends
                    && i != first
                    && keywords
                        .iter()
                        .any(|k| word.eq_ignore_ascii_case(k.as_bytes()))
                {
                    let end = i + word.len();
                    // `UNTIL c END_REPEAT;`: the `;` belongs to it.
                    let mut j = end;
                    while matches!(text.get(j), Some(b' ' | b'\t' | b'\r')) {
                        j += 1;
                    }
                    let semi = keywords[0] == "END_REPEAT" && text.get(j) == Some(&b';');
                    return done(if semi { j + 1 } else { end });
                }
                i += word.len();
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    incomplete(start)
}

fn is_ident_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

/// Parses the Syntec statement in `text[start..end]` (an [`Extent`]).
pub fn parse_syntec_statement(
    text: &[u8],
    start: usize,
    end: usize,
    syn: &MacroSyntax,
) -> Result<Statement, Diagnostic> {
    let mut s = Scan::new(text, start, end, *syn);
    let mut st = Statement {
        kind: StmtKind::Percent,
        first: s.here(),
        seq: None,
        deleted: None,
        comment: None,
    };
    if s.eat(b'%')? {
        return Ok(st);
    }
    let mut words = Vec::new();
    if matches!(s.peek()?, b'N' | b'n') && s.at(1).is_ascii_digit() {
        let label_at = s.pos;
        s.pos += 1;
        let n = s.number()?;
        st.seq = n.and_then(|n| if n.point { None } else { whole_u32(n.value) });
        let span = Span::new(label_at, s.pos);
        let value = n.map_or(0.0, |n| n.value);
        words.push(MWord {
            addr: Addr::letter(b'N'),
            value: MValue::Literal {
                value,
                point: false,
            },
            span,
        });
    }
    st.first = s.here();
    let kind = syntec_kind(&mut s, &mut words)?;
    if let StmtKind::Words(w) = &kind
        && let Some(first) = w.first()
    {
        st.first = first.span;
    }
    st.kind = kind;
    // The statement's own `;`, then nothing.
    s.eat(b';')?;
    s.trivia()?;
    if s.pos < s.end {
        let what = s.show_next();
        return Err(diag::macro_syntax(
            s.here(),
            &format!("unexpected {what}"),
            "end the statement with `;` before the next one",
        ));
    }
    Ok(st)
}

fn syntec_kind(s: &mut Scan<'_>, words: &mut Vec<MWord>) -> Result<StmtKind, Diagnostic> {
    let b = s.peek()?;
    if s.pos >= s.end || b == b';' {
        return Ok(StmtKind::Words(std::mem::take(words)));
    }
    if matches!(b, b'#' | b'@') {
        let target = target(s)?;
        if !(s.eat2(b":=")? || s.eat(b'=')?) {
            return Err(expected(s, "`:=` after the variable", "#1 := 2.5;"));
        }
        if let Some((text, span)) = s.string()? {
            let value = string_value(&target, &text, span)?;
            return Ok(StmtKind::Assign { target, value });
        }
        let value = ExprParser::parse(s)?;
        if value.ops.is_empty() {
            return Err(expected(s, "a value after `:=`", "#1 := 2.5;"));
        }
        return Ok(StmtKind::Assign { target, value });
    }
    if b.is_ascii_digit() {
        return case_label(s);
    }
    if is_address(s) {
        return syntec_words(s, words);
    }
    let Some((name, span)) = s.peek_ident()? else {
        return Err(stray(s));
    };
    s.pos = span.end as usize;
    let kind = match name.as_str() {
        "IF" => StmtKind::If(condition(s, "THEN")?),
        "ELSEIF" => StmtKind::ElseIf(condition(s, "THEN")?),
        "ELSE" => StmtKind::Else,
        "END_IF" | "ENDIF" => StmtKind::EndIf,
        "CASE" => StmtKind::Case(condition(s, "OF")?),
        "END_CASE" | "ENDCASE" => StmtKind::EndCase,
        "WHILE" => StmtKind::WhileDo(condition(s, "DO")?),
        "END_WHILE" | "ENDWHILE" => StmtKind::EndWhile,
        "REPEAT" => StmtKind::Repeat,
        "UNTIL" => {
            let cond = ExprParser::parse(s)?;
            if !(s.keyword("END_REPEAT")? || s.keyword("ENDREPEAT")?) {
                return Err(expected(
                    s,
                    "END_REPEAT after the condition",
                    "UNTIL #1 > 5 END_REPEAT;",
                ));
            }
            StmtKind::Until(cond)
        }
        "FOR" => for_header(s)?,
        "END_FOR" | "ENDFOR" => StmtKind::EndFor,
        "EXIT" => StmtKind::Exit,
        "GOTO" => StmtKind::Goto {
            word: span,
            target: goto_target(s)?,
        },
        "ELSIF" => {
            return Err(diag::macro_syntax(
                span,
                "ELSIF is not a keyword of the Syntec MACRO language",
                "write ELSEIF",
            ));
        }
        "DEFAULT" => {
            return Err(diag::macro_syntax(
                span,
                "DEFAULT is not a keyword of the Syntec MACRO language",
                "write ELSE for the other cases of a CASE",
            ));
        }
        _ if is_function(Lang::Syntec, &name) => {
            s.pos = span.start as usize;
            StmtKind::Call(ExprParser::parse(s)?)
        }
        _ => return Err(diag::unknown_statement(span, &name)),
    };
    Ok(kind)
}

/// The value of `v := "text";` (Syntec §4.2): a local (`#`) holds the
/// number the text spells (`#10 := "12";` gives 12, a Long as `12` would
/// be; `"2.5"` a Double). A global (`@`) would hold the text's ASCII
/// codes, read back with SCANTEXT, which vcnc does not have.
fn string_value(target: &Target, text: &str, span: Span) -> Result<Expr, Diagnostic> {
    if matches!(
        target,
        Target::Fixed(VarKind::At, ..) | Target::Indirect(VarKind::At, ..)
    ) {
        return Err(diag::unavailable_string_store(span));
    }
    let bytes = text.trim().as_bytes();
    let number = parse_number(bytes, 0)
        .ok()
        .filter(|n| n.end == bytes.len() && !bytes.iter().any(|b| matches!(b, b' ' | b'\t')));
    let Some(n) = number else {
        return Err(diag::macro_syntax(
            span,
            &format!("the text \"{text}\" is not a number, and a # variable holds numbers"),
            "write the number in the quotes (#10 := \"12\";) or without them (#10 := 12;)",
        ));
    };
    let value = if n.point {
        Value::Double(n.value)
    } else {
        // Whole by construction: no point, and the number reader allows
        // at most 9 digits before it.
        #[allow(clippy::cast_possible_truncation)]
        Value::Long(n.value as i64)
    };
    Ok(Expr {
        ops: vec![super::Op {
            code: OpCode::Num(value),
            span,
        }],
        texts: Vec::new(),
        span,
    })
}

/// A condition followed by its keyword (THEN, DO, OF).
fn condition(s: &mut Scan<'_>, keyword: &str) -> Result<Expr, Diagnostic> {
    let cond = ExprParser::parse(s)?;
    if cond.ops.is_empty() {
        return Err(expected(s, "a condition", &format!("… #1 > 0 {keyword}")));
    }
    if !s.keyword(keyword)? {
        return Err(expected(
            s,
            &format!("{keyword} after the condition"),
            &format!("… #1 > 0 {keyword}"),
        ));
    }
    Ok(cond)
}

/// `FOR v := a TO b [BY c] DO`.
fn for_header(s: &mut Scan<'_>) -> Result<StmtKind, Diagnostic> {
    let var = target(s)?;
    if !s.eat2(b":=")? {
        return Err(expected(
            s,
            "`:=` after the FOR variable",
            "FOR #1 := 1 TO 10 BY 1 DO",
        ));
    }
    let from = ExprParser::parse(s)?;
    if !s.keyword("TO")? {
        return Err(expected(s, "TO", "FOR #1 := 1 TO 10 BY 1 DO"));
    }
    let to = ExprParser::parse(s)?;
    let by = if s.keyword("BY")? {
        Some(ExprParser::parse(s)?)
    } else {
        None
    };
    if !s.keyword("DO")? {
        return Err(expected(s, "DO", "FOR #1 := 1 TO 10 BY 1 DO"));
    }
    Ok(StmtKind::For { var, from, to, by })
}

/// `1:`, `3, 4, 5:`.
fn case_label(s: &mut Scan<'_>) -> Result<StmtKind, Diagnostic> {
    let mut values = Vec::new();
    loop {
        let Some(n) = s.number()? else {
            return Err(expected(s, "a case value", "1:"));
        };
        if n.point {
            return Err(diag::macro_syntax(
                n.span,
                "a CASE value is a whole number (a Long)",
                "write the value without a decimal point",
            ));
        }
        // Whole and at most 10 digits.
        #[allow(clippy::cast_possible_truncation)]
        values.push(n.value as i64);
        if values.len() > 512 {
            return Err(diag::macro_too_complex(n.span, 512));
        }
        if !s.eat(b',')? {
            break;
        }
    }
    if !s.eat(b':')? {
        return Err(expected(s, "`:` after the case values", "3, 4, 5:"));
    }
    Ok(StmtKind::CaseLabel(values))
}

/// A word block of a Syntec file: each letter takes an expression.
fn syntec_words(s: &mut Scan<'_>, words: &mut Vec<MWord>) -> Result<StmtKind, Diagnostic> {
    loop {
        let b = s.peek()?;
        if s.pos >= s.end || b == b';' {
            break;
        }
        if !is_address(s) {
            return match s.peek_ident()? {
                Some((name, span)) => Err(diag::unknown_statement(span, &name)),
                None => Err(stray(s)),
            };
        }
        let at = s.pos;
        let span = Span::new(at, at + 1);
        if words.len() >= MAX_MACRO_WORDS {
            return Err(diag::too_many_words(span, MAX_MACRO_WORDS));
        }
        let letter = s.at(0).to_ascii_uppercase();
        s.pos += 1;
        let mut k = 0;
        while s.at(k).is_ascii_digit() {
            k += 1;
        }
        if k > 0 && s.at(k) == b'=' {
            return Err(diag::macro_syntax(
                Span::new(at, s.pos + k + 1),
                "extended arguments such as X1= are not supported",
                "pass the value with a plain letter argument",
            ));
        }
        if s.peek()? == 0 || s.at(0) == b';' || is_address(s) {
            return Err(diag::missing_value(span, char::from(letter)));
        }
        let e = ExprParser::parse(s)?;
        if e.ops.is_empty() {
            return Err(diag::missing_value(
                Span::new(at, at + 1),
                char::from(letter),
            ));
        }
        let e_end = e.span.end;
        let value = match fold_literal(&e) {
            Some((value, point)) => MValue::Literal { value, point },
            None => MValue::Expr(e),
        };
        let end = match &value {
            MValue::Expr(e) => e.span.end,
            MValue::Literal { .. } => e_end,
        };
        words.push(MWord {
            addr: Addr::letter(letter),
            value,
            span: Span {
                start: vcnc_core::clamp_u32(at),
                end,
            },
        });
    }
    Ok(StmtKind::Words(std::mem::take(words)))
}

/// A literal (or a negated one) as a plain word value.
fn fold_literal(e: &Expr) -> Option<(f64, bool)> {
    let lit = |v: &Value| match *v {
        // Longs from literals have at most 10 digits: exact.
        #[allow(clippy::cast_precision_loss)]
        Value::Long(n) => Some((n as f64, false)),
        Value::Double(d) => Some((d, true)),
        Value::Null => None,
    };
    match e.ops.as_slice() {
        [a] => match &a.code {
            OpCode::Num(v) => lit(v),
            _ => None,
        },
        [a, b] => match (&a.code, &b.code) {
            (OpCode::Num(v), OpCode::Neg) => lit(v).map(|(x, p)| (-x, p)),
            (OpCode::Num(v), OpCode::Pos) => lit(v),
            _ => None,
        },
        _ => None,
    }
}

/// Whether a single-letter address comes next (a letter not followed by
/// another letter or `_`): `X10`, `G#1`, `Y(1.+2.)`.
fn is_address(s: &mut Scan<'_>) -> bool {
    let _ = s.trivia();
    s.at(0).is_ascii_alphabetic() && !(s.at(1).is_ascii_alphabetic() || s.at(1) == b'_')
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::macros::{BinOp, Func, OpCode};

    const B: MacroSyntax = MacroSyntax {
        lang: Lang::MacroB,
        max_nesting: 5,
        slash_comments: true,
        extended: &[(",C", Addr::COMMA_C), (",R", Addr::COMMA_R)],
    };
    const S: MacroSyntax = MacroSyntax {
        lang: Lang::Syntec,
        max_nesting: 32,
        slash_comments: true,
        extended: &[],
    };

    fn codes(e: &Expr) -> Vec<OpCode> {
        e.ops.iter().map(|o| o.code.clone()).collect()
    }

    fn iso(text: &str) -> Statement {
        parse_iso_block(text.as_bytes(), 0, &B).unwrap().unwrap().0
    }

    #[test]
    fn macro_b_compiles_to_postfix_in_precedence_order() {
        let st = iso("N20 #21 = 1 + 2 * #3");
        assert_eq!(st.seq, Some(20));
        let StmtKind::Assign { target, value } = st.kind else {
            panic!("{:?}", st.kind)
        };
        assert!(matches!(target, Target::Fixed(VarKind::Hash, 21, _)));
        assert_eq!(
            codes(&value),
            vec![
                OpCode::Num(Value::Double(1.0)),
                OpCode::Num(Value::Double(2.0)),
                OpCode::Var(VarKind::Hash, 3),
                OpCode::Bin(BinOp::Mul),
                OpCode::Bin(BinOp::Add),
            ]
        );
        // The * spans its own byte: an alarm at it points there.
        assert_eq!(value.ops[3].span, Span::new(16, 17));
    }

    #[test]
    fn macro_b_statements_and_words() {
        assert!(matches!(
            iso("WHILE [#1 LT 3] DO 2").kind,
            StmtKind::While { m: 2, .. }
        ));
        assert!(matches!(
            iso("DO1").kind,
            StmtKind::While { cond: None, m: 1 }
        ));
        assert!(matches!(iso("END 3").kind, StmtKind::End(3)));
        assert!(matches!(
            iso("IF [#1 EQ 0] GOTO10").kind,
            StmtKind::IfGoto { .. }
        ));
        assert!(matches!(
            iso("IF [#1 EQ 0] THEN #2 = 1").kind,
            StmtKind::IfThen { .. }
        ));
        let st = iso("/2 G01 X-#1 Y[#2] F100. (CUT)");
        assert_eq!(st.deleted, Some(2));
        assert_eq!(st.comment.as_deref(), Some("CUT"));
        let StmtKind::Words(w) = st.kind else {
            panic!()
        };
        assert_eq!(w.len(), 4);
        assert!(matches!(&w[1].value, MValue::Expr(e) if e.is_reference()));
        assert!(matches!(
            w[3].value,
            MValue::Literal {
                value: 100.0,
                point: true
            }
        ));
        // Nothing macro-like: the lexer's alarm stands.
        assert_eq!(parse_iso_block(b"G X10", 0, &B).unwrap(), None);
        // `;` ends the block: the next one starts after it.
        let (_, next) = parse_iso_block(b"#1 = 1; #2 = 2", 0, &B).unwrap().unwrap();
        assert_eq!(next, 7);
        assert_eq!(
            parse_iso_block(b"DO 4", 0, &B).unwrap_err().code,
            crate::Code::E611
        );
    }

    #[test]
    fn fanuc_two_argument_arctangent() {
        let StmtKind::Assign { value, .. } = iso("#1 = ATAN[#2]/[#3]").kind else {
            panic!()
        };
        assert_eq!(value.ops.last().unwrap().code, OpCode::Call(Func::Atan, 2));
    }

    #[test]
    fn syntec_statements_end_where_their_keywords_say() {
        let text = b"IF #1 > 0 THEN #2 := 1; END_IF;";
        let e = syntec_extent(text, 0);
        assert_eq!((e.start, e.end, e.incomplete), (0, 14, false));
        let e = syntec_extent(text, 14);
        assert_eq!((e.start, e.end), (15, 23));
        let e = syntec_extent(text, 23);
        assert_eq!((e.start, e.end), (24, 31));
        // No `;` yet: read another line.
        assert!(syntec_extent(b"#1 := 1 +", 0).incomplete);
        assert!(syntec_extent(b"(* open", 0).incomplete);
        assert!(syntec_extent(b"  // only a comment", 0).empty);
        let e = syntec_extent(b"3, 4: #1 := 2;", 0);
        assert_eq!(e.end, 5);
        let e = syntec_extent(b"UNTIL #1 > 3 END_REPEAT;", 0);
        assert_eq!(e.end, 24);
    }

    #[test]
    fn syntec_parses_longs_doubles_and_words() {
        let text = b"#1 := 7 / 2. MOD 3;";
        let st = parse_syntec_statement(text, 0, text.len(), &S).unwrap();
        let StmtKind::Assign { value, .. } = st.kind else {
            panic!()
        };
        assert_eq!(
            codes(&value),
            vec![
                OpCode::Num(Value::Long(7)),
                OpCode::Num(Value::Double(2.0)),
                OpCode::Bin(BinOp::Div),
                OpCode::Num(Value::Long(3)),
                OpCode::Bin(BinOp::Mod),
            ]
        );
        let text = b"G01 X(1. + #1) Y-5 F#9;";
        let st = parse_syntec_statement(text, 0, text.len(), &S).unwrap();
        let StmtKind::Words(w) = st.kind else {
            panic!()
        };
        assert!(matches!(w[1].value, MValue::Expr(_)));
        assert!(matches!(
            w[2].value,
            MValue::Literal {
                value: -5.0,
                point: false
            }
        ));
        let text = b"ELSIF 1 THEN";
        assert_eq!(
            parse_syntec_statement(text, 0, text.len(), &S)
                .unwrap_err()
                .code,
            crate::Code::E601
        );
    }
}
