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

/// Fanuc functions vcnc does not evaluate.
const MACRO_B_UNAVAILABLE: &[&str] = &["BIN", "BCD", "ADP"];

/// LinuxCNC's functions (rs274 2.9), written `NAME[…]`; ATAN is always
/// `ATAN[y]/[x]` and EXISTS takes a parameter, both read by
/// [`ExprParser::ngc_call`].
const NGC_FUNCS: &[(&str, Sig)] = &[
    ("ABS", sig(Func::Abs, 1, 1)),
    ("ACOS", sig(Func::Acos, 1, 1)),
    ("ASIN", sig(Func::Asin, 1, 1)),
    ("COS", sig(Func::Cos, 1, 1)),
    ("SIN", sig(Func::Sin, 1, 1)),
    ("TAN", sig(Func::Tan, 1, 1)),
    ("EXP", sig(Func::Exp, 1, 1)),
    ("LN", sig(Func::Ln, 1, 1)),
    ("SQRT", sig(Func::Sqrt, 1, 1)),
    ("FIX", sig(Func::Fix, 1, 1)),
    ("FUP", sig(Func::Fup, 1, 1)),
    ("ROUND", sig(Func::Round, 1, 1)),
    ("ATAN", sig(Func::Atan, 2, 2)),
];

/// One binary operator as written: a symbol, or a word (letters).
type OpRow = (&'static str, BinOp);

/// What the expression parser needs to know about a language: data, so
/// that the one parser reads all three.
pub(super) struct Grammar {
    /// What is a comment between tokens.
    pub comments: Comments,
    /// Digits and `_` continue an identifier (Syntec's `END_IF`,
    /// `ATAN2`); elsewhere keywords are letters only (`#1EQ2`, `GOTO10`).
    pub ident_tail: bool,
    /// `0x1F` hexadecimal numbers (Syntec).
    pub hex_numbers: bool,
    /// Binary operators by level, loosest first; operators of one level
    /// associate to the left.
    levels: &'static [&'static [OpRow]],
    /// Texts that begin like a symbol operator but are none (Syntec's `==`
    /// and `//`): the longest symbol written wins, so `<>` is never `<`.
    not_ops: &'static [&'static str],
    /// Functions, and those that need the machine (E604).
    funcs: &'static [(&'static str, Sig)],
    unavailable: &'static [&'static str],
    /// Two-letter abbreviations of words (Fanuc's).
    pub abbreviations: &'static [(&'static str, &'static str)],
    /// `( )` groups as well as `[ ]` (Syntec).
    pub paren_groups: bool,
    /// The brackets of a function's arguments.
    call: (u8, u8),
    /// `@n` variables (Syntec globals).
    pub at_vars: bool,
    /// `NOT` is a unary operator (Syntec).
    not: bool,
    /// A number written without a point is a Long (Syntec).
    longs: bool,
    /// Fanuc's `ATAN[y]/[x]` may follow a one-argument ATAN.
    atan_slash: bool,
    /// STKTOP[n] (Syntec).
    stktop: bool,
    /// LinuxCNC's reading: a value is a signed number, parameter,
    /// `[expression]` or function, nested at most 64 deep by any of these
    /// (rs274's recursion); `#` takes any value (`##1`, `#<name>`); an
    /// operator's span runs to the end of its right operand; messages say
    /// what was expected.
    pub ngc_values: bool,
    /// The help of "expected a value".
    operand_help: &'static str,
}

/// Comments between tokens.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Comments {
    /// `( )`, whose text is kept (Macro B's #3000 messages); an unclosed
    /// one alarms.
    ParenMessages,
    /// `(* *)` and, with `MacroSyntax::slash_comments`, `//` (Syntec).
    StarParen,
    /// `( )` (unclosed: to the end) and `;` to the end (rs274).
    ParenSemicolon,
}

const MACRO_B: Grammar = Grammar {
    comments: Comments::ParenMessages,
    ident_tail: false,
    hex_numbers: false,
    levels: &[
        &[
            ("EQ", BinOp::Eq),
            ("NE", BinOp::Ne),
            ("GT", BinOp::Gt),
            ("GE", BinOp::Ge),
            ("LT", BinOp::Lt),
            ("LE", BinOp::Le),
        ],
        &[
            ("+", BinOp::Add),
            ("-", BinOp::Sub),
            ("OR", BinOp::Or),
            ("XOR", BinOp::Xor),
        ],
        &[
            ("*", BinOp::Mul),
            // `/[` after ATAN[…] is its second argument, handled there.
            ("/", BinOp::Div),
            ("AND", BinOp::And),
            ("MOD", BinOp::Mod),
        ],
    ],
    not_ops: &[],
    funcs: MACRO_B_FUNCS,
    unavailable: MACRO_B_UNAVAILABLE,
    abbreviations: MACRO_B_ABBREVIATIONS,
    paren_groups: false,
    call: (b'[', b']'),
    at_vars: false,
    not: false,
    longs: false,
    atan_slash: true,
    stktop: false,
    ngc_values: false,
    operand_help: "write a number, a variable (#1, #[#2+1]), [an expression] or a function (SIN[30])",
};

const SYNTEC: Grammar = Grammar {
    comments: Comments::StarParen,
    ident_tail: true,
    hex_numbers: true,
    levels: &[
        &[("OR", BinOp::Or)],
        &[("XOR", BinOp::Xor)],
        &[("&", BinOp::And), ("AND", BinOp::And)],
        &[("<>", BinOp::Ne)],
        &[("=", BinOp::Eq)],
        &[
            ("<=", BinOp::Le),
            (">=", BinOp::Ge),
            ("<", BinOp::Lt),
            (">", BinOp::Gt),
        ],
        &[("+", BinOp::Add), ("-", BinOp::Sub)],
        &[("*", BinOp::Mul), ("/", BinOp::Div), ("MOD", BinOp::Mod)],
    ],
    not_ops: &["==", "//"],
    funcs: SYNTEC_FUNCS,
    unavailable: SYNTEC_UNAVAILABLE,
    abbreviations: &[],
    paren_groups: true,
    call: (b'(', b')'),
    at_vars: true,
    not: true,
    longs: true,
    atan_slash: false,
    stktop: true,
    ngc_values: false,
    operand_help: "write a number, a variable (#1, @2, #[#3+1]), (an expression) or a function (SIN(30))",
};

/// rs274's precedence (`interp_read.cc`'s levels): `**` binds tightest,
/// then `* / MOD`, `+ -`, the comparisons, and `AND OR XOR` loosest.
const NGC: Grammar = Grammar {
    comments: Comments::ParenSemicolon,
    ident_tail: false,
    hex_numbers: false,
    levels: &[
        &[("AND", BinOp::And), ("OR", BinOp::Or), ("XOR", BinOp::Xor)],
        &[
            ("EQ", BinOp::Eq),
            ("NE", BinOp::Ne),
            ("GT", BinOp::Gt),
            ("GE", BinOp::Ge),
            ("LT", BinOp::Lt),
            ("LE", BinOp::Le),
        ],
        &[("+", BinOp::Add), ("-", BinOp::Sub)],
        &[("*", BinOp::Mul), ("/", BinOp::Div), ("MOD", BinOp::Mod)],
        &[("**", BinOp::Pow)],
    ],
    not_ops: &[],
    funcs: NGC_FUNCS,
    unavailable: &[],
    abbreviations: &[],
    paren_groups: false,
    call: (b'[', b']'),
    at_vars: false,
    not: false,
    longs: false,
    atan_slash: false,
    stktop: false,
    ngc_values: true,
    operand_help: "",
};

/// Most values inside one another in a LinuxCNC expression (brackets,
/// signs, `#`, functions).
pub(super) const NGC_MAX_DEPTH: u8 = 64;

/// The grammar of `lang`.
pub(super) fn grammar(lang: Lang) -> &'static Grammar {
    match lang {
        Lang::MacroB => &MACRO_B,
        Lang::Syntec => &SYNTEC,
        Lang::Ngc => &NGC,
    }
}

/// The word `name` (upper case) stands for in `g`: the whole word of an
/// abbreviation, else `name` itself.
pub(super) fn full_word<'n>(g: &Grammar, name: &'n str) -> &'n str {
    g.abbreviations
        .iter()
        .find(|(short, _)| *short == name)
        .map_or(name, |(_, full)| full)
}

/// The abbreviation of word `full` in `g`, if it has one.
pub(super) fn abbreviation(g: &Grammar, full: &str) -> Option<&'static str> {
    g.abbreviations
        .iter()
        .find(|(_, f)| *f == full)
        .map(|(short, _)| *short)
}

/// Whether `name` is a function of `lang` (known or unavailable).
pub(super) fn is_function(lang: Lang, name: &str) -> bool {
    let g = grammar(lang);
    let name = full_word(g, name);
    (g.stktop && name == "STKTOP")
        || g.funcs.iter().any(|(n, _)| *n == name)
        || g.unavailable.contains(&name)
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

    fn g(&self) -> &'static Grammar {
        grammar(self.s.syn.lang)
    }

    pub fn expr(&mut self) -> Result<(), Diagnostic> {
        self.binary(1)
    }

    fn binary(&mut self, level: u8) -> Result<(), Diagnostic> {
        let g = self.g();
        if usize::from(level) > g.levels.len() {
            return if g.ngc_values {
                self.ngc_value()
            } else {
                self.unary()
            };
        }
        self.binary(level + 1)?;
        while let Some((op, span)) = self.operator(level)? {
            self.binary(level + 1)?;
            // rs274 reports an operator's error over its right operand.
            let span = if g.ngc_values {
                Span::new(span.start as usize, self.s.pos)
            } else {
                span
            };
            self.push(OpCode::Bin(op), span)?;
        }
        Ok(())
    }

    /// The binary operator of `level` that comes next, consumed.
    fn operator(&mut self, level: u8) -> Result<Option<(BinOp, Span)>, Diagnostic> {
        let g = self.g();
        let Some(row) = g.levels.get(usize::from(level) - 1) else {
            return Ok(None);
        };
        let b = self.s.peek()?;
        let at = self.s.pos;
        let found = if b.is_ascii_alphabetic() {
            self.word_op(row)?
        } else {
            self.symbol_op(row)
        };
        Ok(found.map(|(op, len)| {
            self.s.pos = at + len;
            (op, Span::new(at, at + len))
        }))
    }

    /// The symbol operator of `row` written next: the longest symbol of
    /// the grammar that starts here must be one of `row`'s.
    fn symbol_op(&self, row: &[OpRow]) -> Option<(BinOp, usize)> {
        let g = self.g();
        let here = |t: &str| t.bytes().enumerate().all(|(k, c)| self.s.at(k) == c);
        let symbols = g
            .levels
            .iter()
            .flat_map(|l| l.iter().map(|(t, _)| *t))
            .chain(g.not_ops.iter().copied())
            .filter(|t| !t.as_bytes()[0].is_ascii_alphabetic());
        let mut longest: Option<&str> = None;
        for t in symbols {
            if here(t) && longest.is_none_or(|l| t.len() > l.len()) {
                longest = Some(t);
            }
        }
        let t = longest?;
        row.iter()
            .find(|(r, _)| *r == t)
            .map(|(_, op)| (*op, t.len()))
    }

    /// A keyword operator of `row` if the next identifier is one (length
    /// in bytes).
    fn word_op(&mut self, row: &[OpRow]) -> Result<Option<(BinOp, usize)>, Diagnostic> {
        let Some((name, _)) = self.s.peek_ident()? else {
            return Ok(None);
        };
        let word = full_word(self.g(), &name);
        Ok(row
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
            } else if self.g().not && self.s.keyword("NOT")? {
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
        let g = self.g();
        match b {
            b'[' => self.group(b']'),
            b'(' if g.paren_groups => self.group(b')'),
            b'#' => self.variable(VarKind::Hash),
            b'@' if g.at_vars => self.variable(VarKind::At),
            b'0'..=b'9' | b'.' => {
                let Some(n) = self.s.number()? else {
                    return Err(self.expected_operand());
                };
                let v = if g.longs && !n.point {
                    // Whole by construction (no point, at most 10 digits).
                    #[allow(clippy::cast_possible_truncation)]
                    Value::Long(n.value as i64)
                } else {
                    Value::Double(n.value)
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
        diag::macro_syntax(
            self.s.here(),
            &format!("expected a value, found {what}"),
            self.g().operand_help,
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
        let g = self.g();
        let name = full_word(g, &name).to_string();
        if g.stktop && name == "STKTOP" {
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
        let Some(sig) = g.funcs.iter().find(|(n, _)| *n == name).map(|(_, s)| *s) else {
            let unavailable = g.unavailable.contains(&name.as_str());
            return Err(diag::unknown_function(span, &name, unavailable));
        };
        self.s.pos = span.end as usize;
        let (open, close) = g.call;
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
        if g.atan_slash && sig.func == Func::Atan && slots == 1 && self.s.peek()? == b'/' {
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

    /// A LinuxCNC value: a signed value, `[expression]`, a parameter, a
    /// number or a function. Each one inside another counts toward
    /// [`NGC_MAX_DEPTH`], as rs274's recursion does, so that 4,000 `[`
    /// alarm instead of overflowing the stack.
    pub(super) fn ngc_value(&mut self) -> Result<(), Diagnostic> {
        self.s.trivia()?;
        let at = self.s.pos;
        self.depth += 1;
        if self.depth > NGC_MAX_DEPTH {
            return Err(diag::macro_nesting(Span::new(at, at + 1), NGC_MAX_DEPTH));
        }
        self.ngc_value_here(at)?;
        self.depth -= 1;
        Ok(())
    }

    fn ngc_value_here(&mut self, at: usize) -> Result<(), Diagnostic> {
        match self.s.at(0) {
            b'-' => {
                self.s.pos += 1;
                self.ngc_value()?;
                self.push(OpCode::Neg, Span::new(at, at + 1))
            }
            b'+' => {
                self.s.pos += 1;
                self.ngc_value()
            }
            b'[' => {
                self.s.pos += 1;
                self.expr()?;
                self.ngc_close(at)
            }
            b'#' => self.ngc_parameter(at),
            b'0'..=b'9' | b'.' => {
                let Some(n) = self.s.number()? else {
                    return Err(super::ngc::ngc_expected(Span::new(at, at + 1), "a value"));
                };
                self.push(OpCode::Num(Value::Double(n.value)), n.span)
            }
            c if c.is_ascii_alphabetic() => self.ngc_call(at),
            _ => Err(super::ngc::ngc_expected(Span::new(at, at + 1), "a value")),
        }
    }

    fn ngc_close(&mut self, open: usize) -> Result<(), Diagnostic> {
        self.s.trivia()?;
        if self.s.at(0) != b']' {
            return Err(super::ngc::ngc_expected(
                Span::new(open, open + 1),
                "a `]` closing this `[`",
            ));
        }
        self.s.pos += 1;
        Ok(())
    }

    /// `#<name>`: the name in lower case, blanks removed; `Ok(None)` when
    /// no `<` follows the `#` at `at` (the scanner is past the `#` and
    /// its blanks).
    pub(super) fn ngc_name(&mut self, at: usize) -> Result<Option<Box<str>>, Diagnostic> {
        if self.s.at(0) != b'<' {
            return Ok(None);
        }
        let rest = &self.s.text[self.s.pos..self.s.end];
        let Some(close) = memchr::memchr(b'>', rest) else {
            return Err(super::ngc::ngc_expected(
                Span::new(at, self.s.pos + 1),
                "a `>` closing the name",
            ));
        };
        let name: String = rest[1..close]
            .iter()
            .filter(|c| !c.is_ascii_whitespace())
            .map(|c| char::from(c.to_ascii_lowercase()))
            .collect();
        self.s.pos += close + 1;
        if name.is_empty() {
            return Err(super::ngc::ngc_expected(
                Span::new(at, self.s.pos),
                "a parameter name",
            ));
        }
        Ok(Some(name.into_boxed_str()))
    }

    /// The parameter `#` at `at` names: a name, or a number that is any
    /// value (`#1`, `#[#2 + 1]`, `##3`), whose range the evaluator checks.
    /// Returns the name, or pushes the number's ops and returns `None`.
    pub(super) fn ngc_target(&mut self, at: usize) -> Result<Option<Box<str>>, Diagnostic> {
        self.s.pos += 1;
        self.s.trivia()?;
        if let Some(name) = self.ngc_name(at)? {
            return Ok(Some(name));
        }
        self.ngc_value()?;
        Ok(None)
    }

    /// A parameter read: `Var` for a whole number written out, `VarAt`
    /// over a computed one, `Named` for a name.
    fn ngc_parameter(&mut self, at: usize) -> Result<(), Diagnostic> {
        let before = self.out.ops.len();
        if let Some(name) = self.ngc_target(at)? {
            return self.push_named(name, Span::new(at, self.s.pos));
        }
        let span = Span::new(at, self.s.pos);
        if let [op] = &self.out.ops[before..]
            && let OpCode::Num(Value::Double(v)) = op.code
            && v.fract() == 0.0
            && (0.0..=f64::from(u32::MAX)).contains(&v)
        {
            self.out.ops.truncate(before);
            // Whole and within u32, checked above.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            return self.push(OpCode::Var(VarKind::Hash, v as u32), span);
        }
        self.push(OpCode::VarAt(VarKind::Hash), span)
    }

    fn push_named(&mut self, name: Box<str>, span: Span) -> Result<(), Diagnostic> {
        let i = u16::try_from(self.out.texts.len())
            .map_err(|_| diag::macro_too_complex(span, MAX_OPS))?;
        self.out.texts.push(vec![Arg::Name(name)]);
        self.push(OpCode::Named(i), span)
    }

    /// A LinuxCNC function at `at`: `NAME[e]`, `ATAN[y]/[x]`,
    /// `EXISTS[#<name>]`.
    fn ngc_call(&mut self, at: usize) -> Result<(), Diagnostic> {
        let mut len = 0;
        while self.s.at(len).is_ascii_alphabetic() {
            len += 1;
        }
        let name = String::from_utf8_lossy(&self.s.text[at..at + len]).to_ascii_uppercase();
        self.s.pos += len;
        self.s.trivia()?;
        if self.s.at(0) != b'[' {
            return Err(super::ngc::ngc_expected(
                Span::new(at, self.s.pos),
                "a `[` after the function's name",
            ));
        }
        let open = self.s.pos;
        self.s.pos += 1;
        if name == "EXISTS" {
            self.s.trivia()?;
            let hash = self.s.pos;
            let name = self.ngc_target(hash)?;
            let span = Span::new(hash, self.s.pos);
            self.ngc_close(open)?;
            return match name {
                Some(name) => {
                    let i = u16::try_from(self.out.texts.len())
                        .map_err(|_| diag::macro_too_complex(span, MAX_OPS))?;
                    self.out.texts.push(vec![Arg::Name(name)]);
                    self.push(OpCode::CallText(Func::Exists, 0, i), span)
                }
                None => self.push(OpCode::Call(Func::Exists, 1), span),
            };
        }
        self.expr()?;
        self.ngc_close(open)?;
        let span = Span::new(at, self.s.pos);
        let Some(sig) = NGC_FUNCS.iter().find(|(n, _)| *n == name).map(|(_, s)| *s) else {
            return Err(diag::unknown_function(
                Span::new(at, at + len),
                &name,
                false,
            ));
        };
        if sig.func == Func::Atan {
            self.s.trivia()?;
            if self.s.at(0) != b'/' {
                return Err(super::ngc::ngc_expected(
                    Span::new(at, self.s.pos),
                    "`/[x]` after ATAN[y]",
                ));
            }
            self.s.pos += 1;
            self.s.trivia()?;
            if self.s.at(0) != b'[' {
                return Err(super::ngc::ngc_expected(
                    Span::new(self.s.pos, self.s.pos + 1),
                    "`[x]`",
                ));
            }
            let open = self.s.pos;
            self.s.pos += 1;
            self.expr()?;
            self.ngc_close(open)?;
            return self.push(OpCode::Call(Func::Atan, 2), span);
        }
        self.push(OpCode::Call(sig.func, 1), span)
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
