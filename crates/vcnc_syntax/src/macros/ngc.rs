//! LinuxCNC's lines with parameters and expressions (`--dialect
//! linuxcnc`), parsed into the compiled form of the other macro languages:
//! one [`StmtKind::Line`] of words and settings, whose values are
//! postfix [`Expr`]s of the shared parser under [`Lang::Ngc`]'s grammar.
//!
//! ```text
//!   #1 = 2   #<depth> = [#1 * 1.5]           (settings: after the line)
//!   G1 X[#1 + 10] Z-#<depth> F#<_rate>       (values: with the old ones)
//!        └─ Line [Set #1 ← 2, Set #<depth> ← …, Word G 1, Word X …, …]
//! ```
//!
//! A value here is what rs274 reads after a letter or an `=`: a signed
//! number, parameter, `[expression]` or function, never a bare
//! expression (`#1 = 2 G1 X3` sets 2). The interpreter evaluates the
//! items in order with the parameters as they were before the line, then
//! applies the settings. An O-word statement's label and keyword are read
//! by [`o_statement`] and its operands (`[c]`, a call's `[1] [#2 * 3]`)
//! by [`ngc_operands`], and compiled into one [`StmtKind::OWord`] by
//! [`o_word_statement`]; the interpreter pairs them by label
//! (`macros/structure.rs`) and runs them (`macros/exec.rs`).

use super::expr::ExprParser;
use super::scan::Scan;
use super::{Expr, Lang, LineItem, MValue, MWord, MacroSyntax, OpCode, Statement, StmtKind};
use super::{Target, Value, VarKind};
use crate::block::Addr;
use crate::diagnostics as diag;
use vcnc_core::{Diagnostic, Span};

/// The scanner's settings for LinuxCNC's text.
const SYNTAX: MacroSyntax = MacroSyntax {
    lang: Lang::Ngc,
    max_nesting: super::expr::NGC_MAX_DEPTH,
    slash_comments: false,
    extended: &[],
};

/// E601 in LinuxCNC's syntax: what was expected at `span`.
#[cold]
pub fn ngc_expected(span: Span, wanted: &str) -> Diagnostic {
    diag::macro_syntax(
        span,
        &format!("expected {wanted} here (LinuxCNC's parameters and expressions)"),
        "write e.g. #1 = [#2 * 3], #<depth> = 2, X[#1 + 5], or put text inside ( )",
    )
}

/// E101 at a `(` inside a `( )` comment of `text[start..]`: rs274 stops
/// with "Nested comment found".
fn paren_in_comment(text: &[u8], start: usize) -> Result<(), Diagnostic> {
    let mut open = None;
    for (k, c) in text.iter().enumerate().skip(start) {
        match (c, open) {
            (b';', None) => return Ok(()),
            (b'(', None) => open = Some(k),
            (b'(', Some(_)) => return Err(diag::paren_in_comment(Span::new(k, k + 1))),
            (b')', Some(_)) => open = None,
            _ => {}
        }
    }
    Ok(())
}

/// One value (see the module's text) as an expression.
fn value(s: &mut Scan<'_>) -> Result<Expr, Diagnostic> {
    s.trivia()?;
    let start = s.pos;
    let mut p = ExprParser::new(s);
    p.ngc_value()?;
    let mut e = std::mem::take(&mut p.out);
    e.span = Span::new(start, s.pos);
    Ok(e)
}

/// Parses the LinuxCNC line `text[start..]` (its words, settings and
/// comments; a `/` block delete at its start).
pub fn parse_ngc_line(text: &[u8], start: usize) -> Result<Statement, Diagnostic> {
    paren_in_comment(text, start.min(text.len()))?;
    let mut s = Scan::new(text, start, text.len(), SYNTAX);
    let mut st = Statement {
        kind: StmtKind::Line(Vec::new()),
        first: Span::new(start, start + 1),
        seq: None,
        deleted: None,
        comment: None,
    };
    s.trivia()?;
    if s.at(0) == b'/' {
        st.deleted = Some(1);
        s.pos += 1;
    }
    let mut items = Vec::new();
    loop {
        s.trivia()?;
        let at = s.pos;
        match s.at(0).to_ascii_uppercase() {
            0 => break,
            b'#' => items.push(setting(&mut s, at)?),
            l @ b'A'..=b'Z' => items.push(word(&mut s, at, Addr::letter(l))?),
            b'@' => items.push(word(&mut s, at, Addr::AT)?),
            b'^' => items.push(word(&mut s, at, Addr::CARET)?),
            _ => {
                return Err(ngc_expected(
                    Span::new(at, at + 1),
                    "a word, a parameter setting or a comment",
                ));
            }
        }
    }
    st.kind = StmtKind::Line(items);
    Ok(st)
}

/// `#n = value`, `#[e] = value`, `#<name> = value` at `at`.
fn setting(s: &mut Scan<'_>, at: usize) -> Result<LineItem, Diagnostic> {
    let mut p = ExprParser::new(s);
    let name = p.ngc_target(at)?;
    let index = std::mem::take(&mut p.out);
    let span = Span::new(at, s.pos);
    let target = match name {
        Some(name) => Target::Named(name, span),
        None => match literal(&index) {
            Some(v) if v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v) => {
                // Whole and within u32, checked above.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                Target::Fixed(VarKind::Hash, v as u32, span)
            }
            _ => Target::Indirect(VarKind::Hash, index, span),
        },
    };
    s.trivia()?;
    if s.at(0) != b'=' {
        return Err(ngc_expected(
            Span::new(s.pos, s.pos + 1),
            "`=` after the parameter",
        ));
    }
    s.pos += 1;
    let value = value(s)?;
    Ok(LineItem::Set {
        target,
        value,
        span: Span::new(at, s.pos),
    })
}

/// A word at `at`: its address, then a value.
fn word(s: &mut Scan<'_>, at: usize, addr: Addr) -> Result<LineItem, Diagnostic> {
    s.pos += 1;
    let e = value(s)?;
    let value = match literal(&e) {
        Some(value) => MValue::Literal {
            value,
            point: value.fract() != 0.0,
        },
        None => MValue::Expr(e),
    };
    Ok(LineItem::Word(MWord {
        addr,
        value,
        span: Span::new(at, s.pos),
    }))
}

/// The number an expression of one literal stands for.
fn literal(e: &Expr) -> Option<f64> {
    match e.ops.as_slice() {
        [op] => match op.code {
            OpCode::Num(Value::Double(v)) => Some(v),
            _ => None,
        },
        _ => None,
    }
}

/// The values in brackets after an O-word keyword (`[c]`, a call's
/// arguments `[1] [#2 * 3]`) from `at`; none: empty.
pub fn ngc_operands(text: &[u8], at: usize) -> Result<Vec<Expr>, Diagnostic> {
    let mut s = Scan::new(text, at, text.len(), SYNTAX);
    let mut out = Vec::new();
    loop {
        s.trivia()?;
        match s.at(0) {
            0 => return Ok(out),
            b'[' => {
                let open = s.pos;
                s.pos += 1;
                let mut p = ExprParser::new(&mut s);
                p.expr()?;
                let mut e = std::mem::take(&mut p.out);
                s.trivia()?;
                if s.at(0) != b']' {
                    return Err(ngc_expected(
                        Span::new(open, open + 1),
                        "a `]` closing this `[`",
                    ));
                }
                s.pos += 1;
                e.span = Span::new(open, s.pos);
                out.push(e);
            }
            _ => return Err(ngc_expected(Span::new(s.pos, s.pos + 1), "a value in [ ]")),
        }
    }
}

/// The O-word statement `o` read from `text[start..]` (by
/// [`o_statement`]) compiled: its operands parsed, the statement spanning
/// the rest of the line.
pub fn o_word_statement(text: &[u8], start: usize, o: OStmt) -> Result<Statement, Diagnostic> {
    let operands = ngc_operands(text, o.rest)?;
    Ok(Statement {
        kind: StmtKind::OWord {
            kw: o.kw,
            label: o.label,
            operands,
        },
        first: Span::new(start, text.len()),
        seq: None,
        deleted: None,
        comment: None,
    })
}

/// An O-word statement's keyword.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)] // named after the keyword
pub enum Kw {
    Sub,
    EndSub,
    Call,
    Return,
    If,
    ElseIf,
    Else,
    EndIf,
    While,
    EndWhile,
    Do,
    Repeat,
    EndRepeat,
    Break,
    Continue,
}

const KEYWORDS: &[(&str, Kw)] = &[
    ("endsub", Kw::EndSub),
    ("sub", Kw::Sub),
    ("call", Kw::Call),
    ("return", Kw::Return),
    ("elseif", Kw::ElseIf),
    ("else", Kw::Else),
    ("endif", Kw::EndIf),
    ("if", Kw::If),
    ("endwhile", Kw::EndWhile),
    ("while", Kw::While),
    ("do", Kw::Do),
    ("endrepeat", Kw::EndRepeat),
    ("repeat", Kw::Repeat),
    ("break", Kw::Break),
    ("continue", Kw::Continue),
];

/// `[N…] o<label> keyword …`: the label (`100`, or a name in lower case),
/// the keyword and where its operands start.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OStmt {
    /// `100` for `o100` (leading zeros dropped), a name in lower case.
    pub label: String,
    /// The keyword.
    pub kw: Kw,
    /// Byte index after the keyword.
    pub rest: usize,
}

/// The O-word statement of `text` (from `start`), if the line is one.
pub fn o_statement(text: &[u8], start: usize) -> Option<OStmt> {
    let mut i = start;
    let skip = |i: &mut usize| {
        while matches!(text.get(*i), Some(b' ' | b'\t' | b'\r')) {
            *i += 1;
        }
    };
    skip(&mut i);
    // Block delete, then a sequence number before it.
    if text.get(i) == Some(&b'/') {
        i += 1;
        skip(&mut i);
    }
    if matches!(text.get(i), Some(b'N' | b'n')) {
        i += 1;
        while matches!(text.get(i), Some(b'0'..=b'9' | b' ' | b'\t')) {
            i += 1;
        }
    }
    if !matches!(text.get(i), Some(b'O' | b'o')) {
        return None;
    }
    i += 1;
    skip(&mut i);
    let label = if text.get(i) == Some(&b'<') {
        let close = text[i..].iter().position(|c| *c == b'>')?;
        let name: String = text[i + 1..i + close]
            .iter()
            .filter(|c| !c.is_ascii_whitespace())
            .map(|c| char::from(c.to_ascii_lowercase()))
            .collect();
        i += close + 1;
        name
    } else {
        let digits = text[i..].iter().take_while(|c| c.is_ascii_digit()).count();
        if digits == 0 {
            return None;
        }
        // `o0100` is `o100`.
        let label = String::from_utf8_lossy(&text[i..i + digits])
            .trim_start_matches('0')
            .to_string();
        i += digits;
        label
    };
    skip(&mut i);
    let len = text[i..]
        .iter()
        .take_while(|c| c.is_ascii_alphabetic())
        .count();
    let word = &text[i..i + len];
    let kw = KEYWORDS
        .iter()
        .find(|(k, _)| word.eq_ignore_ascii_case(k.as_bytes()))?
        .1;
    Some(OStmt {
        label,
        kw,
        rest: i + len,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::macros::{Arg, BinOp, Func};

    fn codes(e: &Expr) -> Vec<OpCode> {
        e.ops.iter().map(|o| o.code.clone()).collect()
    }

    fn items(text: &str) -> Vec<LineItem> {
        match parse_ngc_line(text.as_bytes(), 0).map(|s| s.kind) {
            Ok(StmtKind::Line(items)) => items,
            other => panic!("{text}: {other:?}"),
        }
    }

    fn word_expr(text: &str) -> Expr {
        match items(text).as_slice() {
            [
                LineItem::Word(MWord {
                    value: MValue::Expr(e),
                    ..
                }),
            ] => e.clone(),
            other => panic!("{text}: {other:?}"),
        }
    }

    fn num(v: f64) -> OpCode {
        OpCode::Num(Value::Double(v))
    }

    #[test]
    fn rs274_precedence_power_first_logic_last() {
        // 1 + 2 * 3 ** 2 EQ 19 AND 1  →  ((1 + (2 * (3 ** 2))) EQ 19) AND 1
        let e = word_expr("X[1 + 2 * 3 ** 2 EQ 19 AND 1]");
        assert_eq!(
            codes(&e),
            vec![
                num(1.0),
                num(2.0),
                num(3.0),
                num(2.0),
                OpCode::Bin(BinOp::Pow),
                OpCode::Bin(BinOp::Mul),
                OpCode::Bin(BinOp::Add),
                num(19.0),
                OpCode::Bin(BinOp::Eq),
                num(1.0),
                OpCode::Bin(BinOp::And),
            ]
        );
        // `**` associates to the left, as rs274 reads it: (2 ** 3) ** 2.
        let e = word_expr("X[2**3**2]");
        assert_eq!(
            codes(&e),
            vec![
                num(2.0),
                num(3.0),
                OpCode::Bin(BinOp::Pow),
                num(2.0),
                OpCode::Bin(BinOp::Pow),
            ]
        );
    }

    #[test]
    fn parameters_numbered_computed_and_named() {
        assert_eq!(
            codes(&word_expr("X#12")),
            vec![OpCode::Var(VarKind::Hash, 12)]
        );
        // `##1`: the parameter whose number #1 holds.
        assert_eq!(
            codes(&word_expr("X##1")),
            vec![OpCode::Var(VarKind::Hash, 1), OpCode::VarAt(VarKind::Hash)]
        );
        // A name is read in lower case without its blanks.
        let e = word_expr("Z-#<Cut Depth>");
        assert_eq!(codes(&e), vec![OpCode::Named(0), OpCode::Neg]);
        assert_eq!(e.texts, vec![vec![Arg::Name("cutdepth".into())]]);
        let e = word_expr("X[EXISTS[#<_a>]]");
        assert_eq!(codes(&e), vec![OpCode::CallText(Func::Exists, 0, 0)]);
        let e = word_expr("X[ATAN[1]/[2]]");
        assert_eq!(
            codes(&e),
            vec![num(1.0), num(2.0), OpCode::Call(Func::Atan, 2)]
        );
    }

    #[test]
    fn settings_and_words_keep_their_order() {
        let items = items("#1 = 2 #<d> = [#1 * 1.5] G1 X[#1 + 10] (c) ; rest");
        let kinds: Vec<&str> = items
            .iter()
            .map(|i| match i {
                LineItem::Set {
                    target: Target::Fixed(..),
                    ..
                } => "set#",
                LineItem::Set {
                    target: Target::Named(..),
                    ..
                } => "set<>",
                LineItem::Set { .. } => "set[]",
                LineItem::Word(w) if matches!(w.value, MValue::Literal { .. }) => "literal",
                LineItem::Word(_) => "expr",
            })
            .collect();
        assert_eq!(kinds, ["set#", "set<>", "literal", "expr"]);
    }

    #[test]
    fn syntax_errors_say_what_was_expected() {
        let err = |t: &str| parse_ngc_line(t.as_bytes(), 0).unwrap_err();
        let e = err("G1 X[1 + 2");
        assert!(e.message.contains("a `]` closing this `[`"), "{e:?}");
        assert_eq!((e.span.start, e.span.end), (4, 5));
        assert!(err("#1 2").message.contains("`=` after the parameter"));
        assert!(err("X[ATAN[1]]").message.contains("`/[x]` after ATAN[y]"));
        assert!(err("X[FOO[1]]").message.contains("FOO"));
        assert!(err("X#<abc").message.contains("a `>` closing the name"));
        assert_eq!(err("(a (b))").code, crate::Code::E101);
        // Nesting is bounded: 4,000 `[` alarm instead of overflowing.
        let deep = format!("X{}1{}", "[".repeat(4000), "]".repeat(4000));
        assert_eq!(err(&deep).code, crate::Code::E602);
    }

    #[test]
    fn operands_of_o_words() {
        let ops = ngc_operands(b"o100 call [1] [#2 * 3]", 9).unwrap();
        assert_eq!(ops.len(), 2);
        assert_eq!(codes(&ops[0]), vec![num(1.0)]);
        assert!(ngc_operands(b"o1 if 1", 5).is_err());
    }

    #[test]
    fn o_word_statements_compile_with_their_operands() {
        let text = b"N10 o<Probe> call [1] [#2 * 3] (c)";
        let o = o_statement(text, 0).unwrap();
        let st = o_word_statement(text, 0, o).unwrap();
        let StmtKind::OWord {
            kw,
            label,
            operands,
        } = &st.kind
        else {
            panic!("{st:?}");
        };
        assert_eq!(
            (*kw, label.as_str(), operands.len()),
            (Kw::Call, "probe", 2)
        );
        assert_eq!(codes(&operands[1])[0], OpCode::Var(VarKind::Hash, 2));
        // The statement spans the rest of its line (where E611 points).
        assert_eq!(st.first, Span::new(0, text.len()));
        // An operand that does not parse is the statement's error.
        let text = b"o1 if [1 +";
        let o = o_statement(text, 0).unwrap();
        assert!(o_word_statement(text, 0, o).is_err());
    }
}
