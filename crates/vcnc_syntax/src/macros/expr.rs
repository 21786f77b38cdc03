//! Expressions: precedence climbing into postfix ops.
//!
//! ```text
//!   Macro B (Fanuc 0i), loosest first     Syntec MACRO (its §3.1), loosest first
//!   1  EQ NE GT GE LT LE                   1 OR   2 XOR   3 AND &   4 <>   5 =
//!   2  + - OR XOR                          6 < > <= >=   7 + -   8 * / MOD
//!   3  * / AND MOD                         9 unary - NOT
//!   4  unary - +                           10 ( ) [ ], functions, variables
//!   5  [ ], functions, variables
//! ```
//!
//! Fanuc's AND binds like `*`, so `[#1 EQ 1 AND #2 EQ 2]` means
//! `#1 EQ [1 AND #2] EQ 2`, as on the control: write `[[#1 EQ 1] AND [#2 EQ 2]]`.
//! Operators of one level associate to the left. Brackets nest at most
//! `max_nesting` deep (Fanuc: five, function brackets included; E602), and
//! unary signs are collected in a loop, so recursion is bounded whatever the
//! input.

use super::scan::Scan;
use super::{Arg, BinOp, Expr, Func, Lang, MAX_OPS, Op, OpCode, Value, VarKind};
use crate::diagnostics as diag;
use vcnc_core::{Diagnostic, Span};

/// The expression parser: appends ops to `out`.
pub(super) struct ExprParser<'s, 'a> {
    pub s: &'s mut Scan<'a>,
    pub out: Expr,
    depth: u8,
}

/// How many argument slots a function takes, and of what kind.
#[derive(Clone, Copy)]
struct Sig {
    func: Func,
    min: u8,
    max: u8,
    /// Argument positions (bit i) that may be a bare name.
    names: u8,
    /// Argument positions that may be a string.
    strings: u8,
}

const fn sig(func: Func, min: u8, max: u8) -> Sig {
    Sig {
        func,
        min,
        max,
        names: 0,
        strings: 0,
    }
}

/// Fanuc 0i's functions (Custom Macro B), written `NAME[…]`.
const MACRO_B_FUNCS: &[(&str, Sig)] = &[
    ("SIN", sig(Func::Sin, 1, 1)),
    ("COS", sig(Func::Cos, 1, 1)),
    ("TAN", sig(Func::Tan, 1, 1)),
    ("ASIN", sig(Func::Asin, 1, 1)),
    ("ACOS", sig(Func::Acos, 1, 1)),
    ("ATAN", sig(Func::Atan, 1, 2)),
    ("SQRT", sig(Func::Sqrt, 1, 1)),
    ("SQR", sig(Func::Sqrt, 1, 1)),
    ("ABS", sig(Func::Abs, 1, 1)),
    ("ROUND", sig(Func::Round, 1, 1)),
    ("RND", sig(Func::Round, 1, 1)),
    ("FIX", sig(Func::Fix, 1, 1)),
    ("FUP", sig(Func::Fup, 1, 1)),
    ("LN", sig(Func::Ln, 1, 1)),
    ("EXP", sig(Func::Exp, 1, 1)),
    ("POW", sig(Func::Pow, 2, 2)),
];

/// The Syntec functions that make sense off-machine, written `NAME(…)`.
const SYNTEC_FUNCS: &[(&str, Sig)] = &[
    ("ABS", sig(Func::Abs, 1, 1)),
    ("SIN", sig(Func::Sin, 1, 1)),
    ("COS", sig(Func::Cos, 1, 1)),
    ("TAN", sig(Func::Tan, 1, 1)),
    ("ASIN", sig(Func::Asin, 1, 1)),
    ("ACOS", sig(Func::Acos, 1, 1)),
    ("ATAN", sig(Func::Atan, 1, 1)),
    ("ATAN2", sig(Func::Atan2, 2, 2)),
    ("SQRT", sig(Func::Sqrt, 1, 1)),
    ("POW", sig(Func::Pow, 2, 2)),
    ("EXP", sig(Func::Exp, 1, 1)),
    ("LN", sig(Func::Ln, 1, 1)),
    ("MAX", sig(Func::Max, 2, 2)),
    ("MIN", sig(Func::Min, 2, 2)),
    ("SIGN", sig(Func::Sign, 1, 1)),
    ("ROUND", sig(Func::Round, 1, 1)),
    ("CEIL", sig(Func::Ceil, 1, 1)),
    ("FLOOR", sig(Func::Floor, 1, 1)),
    ("STD", sig(Func::Std, 1, 2)),
    (
        "STDAX",
        Sig {
            names: 0b10,
            ..sig(Func::StdAx, 2, 2)
        },
    ),
    (
        "GETARG",
        Sig {
            names: 0b1,
            ..sig(Func::GetArg, 1, 1)
        },
    ),
    ("PUSH", sig(Func::Push, 1, 1)),
    ("POP", sig(Func::Pop, 0, 0)),
    (
        "ALARM",
        Sig {
            strings: 0b10,
            ..sig(Func::Alarm, 1, 2)
        },
    ),
    (
        "MSG",
        Sig {
            strings: 0b11,
            ..sig(Func::Msg, 1, 2)
        },
    ),
    ("WAIT", sig(Func::Wait, 0, 0)),
    ("SLEEP", sig(Func::Sleep, 0, 1)),
    ("PARAM", sig(Func::Param, 1, 2)),
    ("SETDRAW", sig(Func::Draw, 1, 3)),
    ("DRAWHOLE", sig(Func::Draw, 0, 0)),
];

/// Syntec functions that need the machine, files or the PLC: named so that
/// the alarm says why they do not run here.
const SYNTEC_UNAVAILABLE: &[&str] = &[
    "RANDOM",
    "GETTRAPARG",
    "SCANTEXT",
    "STR2INT",
    "AXID",
    "SYSVAR",
    "SYSDATA",
    "DRVDATA",
    "READDI",
    "READDO",
    "READABIT",
    "READRREGBIT",
    "SETDO",
    "SETABIT",
    "SETRREGBIT",
    "OPEN",
    "CLOSE",
    "PRINT",
    "DBOPEN",
    "DBNEW",
    "DBLOAD",
    "DBSAVE",
    "DBINSERT",
    "DBDELETE",
    "CHKMN",
    "CHKSN",
    "CHKMT",
    "CHKMI",
    "CHKINF",
];

/// Fanuc's abbreviations of custom macro words: "the first two characters
/// can be used as an abbreviation" (Fanuc 0i/16i operator's manuals,
/// custom macro, abbreviations of custom macro words), e.g. `WH[#1GT0]DO1`,
/// `#2=AT[#3]/[#4]`. The two letters of every word are distinct; the
/// operators EQ…LE, OR, DO, IF and LN are two letters already.
const MACRO_B_ABBREVIATIONS: &[(&str, &str)] = &[
    ("AB", "ABS"),
    ("AC", "ACOS"),
    ("AD", "ADP"),
    ("AN", "AND"),
    ("AS", "ASIN"),
    ("AT", "ATAN"),
    ("BC", "BCD"),
    ("BI", "BIN"),
    ("CO", "COS"),
    ("EN", "END"),
    ("EX", "EXP"),
    ("FI", "FIX"),
    ("FU", "FUP"),
    ("GO", "GOTO"),
    ("MO", "MOD"),
    ("PO", "POW"),
    ("RO", "ROUND"),
    ("SI", "SIN"),
    ("SQ", "SQRT"),
    ("TA", "TAN"),
    ("TH", "THEN"),
    ("WH", "WHILE"),
    ("XO", "XOR"),
];

/// The custom macro word `name` (upper case) stands for: the whole word
/// of a Macro B abbreviation, else `name` itself.
pub(super) fn macro_b_word(name: &str) -> &str {
    MACRO_B_ABBREVIATIONS
        .iter()
        .find(|(short, _)| *short == name)
        .map_or(name, |(_, full)| full)
}

/// Fanuc functions vcnc does not evaluate.
const MACRO_B_UNAVAILABLE: &[&str] = &["BIN", "BCD", "ADP"];

/// Whether `name` is a function of `lang` (known or unavailable).
pub(super) fn is_function(lang: Lang, name: &str) -> bool {
    match lang {
        Lang::MacroB => {
            let name = macro_b_word(name);
            MACRO_B_FUNCS.iter().any(|(n, _)| *n == name) || MACRO_B_UNAVAILABLE.contains(&name)
        }
        Lang::Syntec => {
            name == "STKTOP"
                || SYNTEC_FUNCS.iter().any(|(n, _)| *n == name)
                || SYNTEC_UNAVAILABLE.contains(&name)
        }
    }
}

impl<'s, 'a> ExprParser<'s, 'a> {
    pub fn new(s: &'s mut Scan<'a>) -> ExprParser<'s, 'a> {
        ExprParser {
            s,
            out: Expr::default(),
            depth: 0,
        }
    }

    /// Parses one whole expression into a fresh [`Expr`].
    pub fn parse(s: &'s mut Scan<'a>) -> Result<Expr, Diagnostic> {
        let mut p = ExprParser::new(s);
        p.s.trivia()?;
        let start = p.s.pos;
        p.expr()?;
        let mut out = std::mem::take(&mut p.out);
        // The blanks the parser looked past for an operator are not part
        // of it.
        let mut end = p.s.pos;
        while end > start && p.s.text[end - 1].is_ascii_whitespace() {
            end -= 1;
        }
        out.span = Span::new(start, end);
        Ok(out)
    }

    fn push(&mut self, code: OpCode, span: Span) -> Result<(), Diagnostic> {
        if self.out.ops.len() >= MAX_OPS {
            return Err(diag::macro_too_complex(span, MAX_OPS));
        }
        self.out.ops.push(Op { code, span });
        Ok(())
    }

    fn levels(&self) -> u8 {
        match self.s.syn.lang {
            Lang::MacroB => 3,
            Lang::Syntec => 8,
        }
    }

    pub fn expr(&mut self) -> Result<(), Diagnostic> {
        self.binary(1)
    }

    fn binary(&mut self, level: u8) -> Result<(), Diagnostic> {
        if level > self.levels() {
            return self.unary();
        }
        self.binary(level + 1)?;
        while let Some((op, span)) = self.operator(level)? {
            self.binary(level + 1)?;
            self.push(OpCode::Bin(op), span)?;
        }
        Ok(())
    }

    /// The binary operator of `level` that comes next, consumed.
    fn operator(&mut self, level: u8) -> Result<Option<(BinOp, Span)>, Diagnostic> {
        let b = self.s.peek()?;
        let at = self.s.pos;
        let sym = |len: usize, op: BinOp| Some((op, len));
        let found = match (self.s.syn.lang, level) {
            (Lang::MacroB, 2) => match b {
                b'+' => sym(1, BinOp::Add),
                b'-' => sym(1, BinOp::Sub),
                _ => self.word_op(&[("OR", BinOp::Or), ("XOR", BinOp::Xor)])?,
            },
            (Lang::MacroB, 3) => match b {
                b'*' => sym(1, BinOp::Mul),
                // `/[` after ATAN[…] is its second argument, handled there.
                b'/' => sym(1, BinOp::Div),
                _ => self.word_op(&[("AND", BinOp::And), ("MOD", BinOp::Mod)])?,
            },
            (Lang::MacroB, _) => self.word_op(&[
                ("EQ", BinOp::Eq),
                ("NE", BinOp::Ne),
                ("GT", BinOp::Gt),
                ("GE", BinOp::Ge),
                ("LT", BinOp::Lt),
                ("LE", BinOp::Le),
            ])?,
            (Lang::Syntec, 1) => self.word_op(&[("OR", BinOp::Or)])?,
            (Lang::Syntec, 2) => self.word_op(&[("XOR", BinOp::Xor)])?,
            (Lang::Syntec, 3) if b == b'&' => sym(1, BinOp::And),
            (Lang::Syntec, 3) => self.word_op(&[("AND", BinOp::And)])?,
            (Lang::Syntec, 4) if b == b'<' && self.s.at(1) == b'>' => sym(2, BinOp::Ne),
            (Lang::Syntec, 5) if b == b'=' && self.s.at(1) != b'=' => sym(1, BinOp::Eq),
            (Lang::Syntec, 6) => match (b, self.s.at(1)) {
                (b'<', b'=') => sym(2, BinOp::Le),
                (b'>', b'=') => sym(2, BinOp::Ge),
                (b'<', b'>') => None,
                (b'<', _) => sym(1, BinOp::Lt),
                (b'>', _) => sym(1, BinOp::Gt),
                _ => None,
            },
            (Lang::Syntec, 7) => match b {
                b'+' => sym(1, BinOp::Add),
                b'-' => sym(1, BinOp::Sub),
                _ => None,
            },
            (Lang::Syntec, 8) => match b {
                b'*' => sym(1, BinOp::Mul),
                b'/' if self.s.at(1) != b'/' => sym(1, BinOp::Div),
                _ => self.word_op(&[("MOD", BinOp::Mod)])?,
            },
            _ => None,
        };
        if let Some((BinOp::Eq, _)) = found
            && self.s.syn.lang == Lang::Syntec
            && b == b'='
            && self.s.at(1) == b'='
        {
            return Err(diag::macro_syntax(
                Span::new(at, at + 2),
                "`==` is not an operator of the Syntec MACRO language",
                "compare with a single `=`",
            ));
        }
        Ok(found.map(|(op, len)| {
            self.s.pos = at + len;
            (op, Span::new(at, at + len))
        }))
    }

    /// A keyword operator among `ops` if the next identifier is one
    /// (length in bytes).
    fn word_op(&mut self, ops: &[(&str, BinOp)]) -> Result<Option<(BinOp, usize)>, Diagnostic> {
        let Some((name, _)) = self.s.peek_ident()? else {
            return Ok(None);
        };
        let word = match self.s.syn.lang {
            Lang::MacroB => macro_b_word(&name),
            Lang::Syntec => &name,
        };
        Ok(ops
            .iter()
            .find(|(n, _)| *n == word)
            .map(|(_, op)| (*op, name.len())))
    }

    /// Unary signs (collected in a loop), then a primary.
    fn unary(&mut self) -> Result<(), Diagnostic> {
        let mut signs: Vec<(OpCode, Span)> = Vec::new();
        loop {
            let b = self.s.peek()?;
            let at = self.s.pos;
            if b == b'-' {
                self.s.pos += 1;
                signs.push((OpCode::Neg, Span::new(at, at + 1)));
            } else if b == b'+' {
                self.s.pos += 1;
                signs.push((OpCode::Pos, Span::new(at, at + 1)));
            } else if self.s.syn.lang == Lang::Syntec && self.s.keyword("NOT")? {
                signs.push((OpCode::Not, Span::new(at, at + 3)));
            } else {
                break;
            }
            if signs.len() > usize::from(u8::MAX) {
                return Err(diag::macro_too_complex(Span::new(at, at + 1), MAX_OPS));
            }
        }
        self.primary()?;
        for (code, span) in signs.into_iter().rev() {
            self.push(code, span)?;
        }
        Ok(())
    }

    fn enter(&mut self, span: Span) -> Result<(), Diagnostic> {
        self.depth += 1;
        if self.depth > self.s.syn.max_nesting {
            return Err(diag::macro_nesting(span, self.s.syn.max_nesting));
        }
        Ok(())
    }

    /// A bracketed sub-expression: `[e]` (or `(e)` in Syntec).
    fn group(&mut self, close: u8) -> Result<(), Diagnostic> {
        let open = Span::new(self.s.pos, self.s.pos + 1);
        self.s.pos += 1;
        self.enter(open)?;
        self.expr()?;
        self.close(close, open)?;
        self.depth -= 1;
        Ok(())
    }

    fn close(&mut self, close: u8, open: Span) -> Result<(), Diagnostic> {
        if self.s.eat(close)? {
            return Ok(());
        }
        let what = self.s.show_next();
        let mut d = diag::macro_syntax(
            self.s.here(),
            &format!(
                "expected `{}` to close the `{}`, found {what}",
                char::from(close),
                if close == b']' { '[' } else { '(' },
            ),
            "check the brackets of the expression",
        );
        // Point at the bracket left open when the text ran out.
        if self.s.pos >= self.s.end {
            d.span = open;
        }
        Err(d)
    }

    pub(super) fn primary(&mut self) -> Result<(), Diagnostic> {
        let b = self.s.peek()?;
        let lang = self.s.syn.lang;
        match b {
            b'[' => self.group(b']'),
            b'(' if lang == Lang::Syntec => self.group(b')'),
            b'#' => self.variable(VarKind::Hash),
            b'@' if lang == Lang::Syntec => self.variable(VarKind::At),
            b'0'..=b'9' | b'.' => {
                let Some(n) = self.s.number()? else {
                    return Err(self.expected_operand());
                };
                let v = match lang {
                    Lang::MacroB => Value::Double(n.value),
                    // Whole by construction (no point, at most 10 digits).
                    #[allow(clippy::cast_possible_truncation)]
                    Lang::Syntec if !n.point => Value::Long(n.value as i64),
                    Lang::Syntec => Value::Double(n.value),
                };
                self.push(OpCode::Num(v), n.span)
            }
            _ => match self.s.peek_ident()? {
                Some((name, span)) => self.call(name, span),
                None => Err(self.expected_operand()),
            },
        }
    }

    fn expected_operand(&mut self) -> Diagnostic {
        let what = self.s.show_next();
        let help = match self.s.syn.lang {
            Lang::MacroB => {
                "write a number, a variable (#1, #[#2+1]), [an expression] or a function (SIN[30])"
            }
            Lang::Syntec => {
                "write a number, a variable (#1, @2, #[#3+1]), (an expression) or a function (SIN(30))"
            }
        };
        diag::macro_syntax(
            self.s.here(),
            &format!("expected a value, found {what}"),
            help,
        )
    }

    /// `#n`, `#[e]`, `@n`, `@[e]`.
    fn variable(&mut self, kind: VarKind) -> Result<(), Diagnostic> {
        let at = self.s.pos;
        self.s.pos += 1;
        if self.s.at(0) == b'[' {
            self.group(b']')?;
            return self.push(OpCode::VarAt(kind), Span::new(at, self.s.pos));
        }
        let n = self.var_number(kind, at)?;
        self.push(OpCode::Var(kind, n), Span::new(at, self.s.pos))
    }

    /// The number after `#` or `@`: whole, unsigned, written right after it.
    pub fn var_number(&mut self, kind: VarKind, at: usize) -> Result<u32, Diagnostic> {
        let mut k = 0;
        let mut v: u64 = 0;
        while self.s.at(k).is_ascii_digit() {
            v = v * 10 + u64::from(self.s.at(k) - b'0');
            k += 1;
            if v > u64::from(u32::MAX) {
                return Err(diag::macro_syntax(
                    Span::new(at, self.s.pos + k),
                    "this variable number is too large",
                    "variable numbers have at most 9 digits",
                ));
            }
        }
        if k == 0 && self.s.at(0) == b'<' {
            let close = (0..)
                .take_while(|&j| !matches!(self.s.at(j), b'>' | 0))
                .count();
            let end = if self.s.at(close) == b'>' {
                close + 1
            } else {
                close
            };
            return Err(diag::macro_syntax(
                Span::new(at, self.s.pos + end),
                "named parameters (#<name>) are LinuxCNC's: vcnc reads numbered variables",
                "use a numbered variable instead (#1 … #33 locals, #100 … #199 and #500 … #999 commons)",
            ));
        }
        if k == 0 || self.s.at(k) == b'.' {
            let sigil = kind.sigil();
            let end = self.s.pos + k + usize::from(self.s.at(k) == b'.');
            return Err(diag::macro_syntax(
                Span::new(at, end.max(at + 1)),
                &format!(
                    "`{sigil}` must be followed by a whole variable number or [an expression]"
                ),
                &format!("write e.g. {sigil}1 or {sigil}[{sigil}2+1]"),
            ));
        }
        self.s.pos += k;
        // At most u32::MAX, checked above.
        #[allow(clippy::cast_possible_truncation)]
        Ok(v as u32)
    }

    /// A function call (the identifier is next, not yet consumed).
    fn call(&mut self, name: String, span: Span) -> Result<(), Diagnostic> {
        let lang = self.s.syn.lang;
        let name = match lang {
            Lang::MacroB => macro_b_word(&name).to_string(),
            Lang::Syntec => name,
        };
        if lang == Lang::Syntec && name == "STKTOP" {
            self.s.pos = span.end as usize;
            if self.s.peek()? != b'[' {
                return Err(diag::macro_syntax(
                    self.s.here(),
                    "STKTOP takes its index in [ ]",
                    "write STKTOP[0] for the top of the stack",
                ));
            }
            self.group(b']')?;
            return self.push(OpCode::Call(Func::StkTop, 1), span);
        }
        let table = match lang {
            Lang::MacroB => MACRO_B_FUNCS,
            Lang::Syntec => SYNTEC_FUNCS,
        };
        let Some(sig) = table.iter().find(|(n, _)| *n == name).map(|(_, s)| *s) else {
            let unavailable = match lang {
                Lang::MacroB => MACRO_B_UNAVAILABLE.contains(&name.as_str()),
                Lang::Syntec => SYNTEC_UNAVAILABLE.contains(&name.as_str()),
            };
            return Err(diag::unknown_function(span, &name, unavailable));
        };
        self.s.pos = span.end as usize;
        let (open, close) = match lang {
            Lang::MacroB => (b'[', b']'),
            Lang::Syntec => (b'(', b')'),
        };
        if !self.s.eat(open)? {
            let what = self.s.show_next();
            return Err(diag::macro_syntax(
                self.s.here(),
                &format!(
                    "{name} must be followed by `{}`, found {what}",
                    char::from(open)
                ),
                &format!("write {name}{}…{}", char::from(open), char::from(close)),
            ));
        }
        let open_span = Span::new(self.s.pos - 1, self.s.pos);
        self.enter(open_span)?;
        let mut texts: Vec<Arg> = Vec::new();
        let mut argc: u8 = 0;
        let mut slots: u8 = 0;
        if self.s.peek()? != close {
            loop {
                self.argument(sig, slots, &mut texts, &mut argc)?;
                slots += 1;
                if !self.s.eat(b',')? {
                    break;
                }
                if slots >= sig.max {
                    return Err(arity(span, &name, sig));
                }
            }
        }
        self.close(close, open_span)?;
        self.depth -= 1;
        // Fanuc's two-argument arctangent: ATAN[y]/[x].
        if lang == Lang::MacroB && sig.func == Func::Atan && slots == 1 && self.s.peek()? == b'/' {
            let save = self.s.pos;
            self.s.pos += 1;
            if self.s.peek()? == b'[' {
                self.group(b']')?;
                slots += 1;
                argc += 1;
            } else {
                self.s.pos = save;
            }
        }
        if slots < sig.min || slots > sig.max {
            return Err(arity(span, &name, sig));
        }
        if texts.iter().any(|a| !matches!(a, Arg::Num)) {
            let i = u16::try_from(self.out.texts.len()).unwrap_or(u16::MAX);
            self.out.texts.push(texts);
            self.push(OpCode::CallText(sig.func, argc, i), span)
        } else {
            self.push(OpCode::Call(sig.func, argc), span)
        }
    }

    /// One argument of a call: a string, a bare name or an expression.
    fn argument(
        &mut self,
        sig: Sig,
        slot: u8,
        texts: &mut Vec<Arg>,
        argc: &mut u8,
    ) -> Result<(), Diagnostic> {
        let bit = 1u8 << slot.min(7);
        if sig.strings & bit != 0
            && let Some((s, _)) = self.s.string()?
        {
            texts.push(Arg::Str(s));
            return Ok(());
        }
        if sig.names & bit != 0
            && let Some((name, span)) = self.s.peek_ident()?
            && !is_function(self.s.syn.lang, &name)
        {
            self.s.pos = span.end as usize;
            texts.push(Arg::Name(name.into_boxed_str()));
            return Ok(());
        }
        self.expr()?;
        texts.push(Arg::Num);
        *argc += 1;
        Ok(())
    }
}

fn arity(span: Span, name: &str, sig: Sig) -> Diagnostic {
    let wants = if sig.min == sig.max {
        format!("{}", sig.min)
    } else {
        format!("{} to {}", sig.min, sig.max)
    };
    diag::macro_syntax(
        span,
        &format!("{name} takes {wants} argument(s)"),
        "check the function's arguments",
    )
}
