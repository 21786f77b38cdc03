//! Macro syntax: the statements and expressions of Fanuc Custom Macro B and
//! of the Syntec MACRO language, parsed into a compiled form the interpreter
//! evaluates.
//!
//! ```text
//!   ISO block  "N20 #21 = 360 / #2"       Syntec statement  "IF #1 > 0 THEN"
//!        │ parse_iso_block                      │ syntec_extent + parse_syntec_statement
//!        ▼                                      ▼
//!   Statement { kind: Assign { target: #21, value: [360, #2, /] }, … }
//! ```
//!
//! The literal lexer (`lexer.rs`) stays the hot path: a block without macro
//! syntax never comes here. Expressions compile to postfix [`Op`]s so the
//! interpreter evaluates them with a small value stack and no allocation;
//! every op keeps the span of the text it came from, so an alarm raised while
//! evaluating (a division by zero) points at the operator. Spans are byte
//! offsets in the statement's text: for an ISO block that text is its line;
//! for a Syntec statement that spans lines, the caller joins the lines into
//! one buffer and maps offsets back to `(line, column)` pairs.
//!
//! The three languages differ in grammar and arithmetic, which [`Lang`]
//! selects and `expr.rs` describes as data (a [`Lang`]'s operator levels,
//! function table, brackets, sigils): Macro B writes expressions in `[ ]`,
//! comments in `( )`, `=` assigns, and every number is real; Syntec MACRO
//! groups with `( )`, comments with `//` and `(* *)`, assigns with `:=`, and
//! types numbers Long (no decimal point) or Double; LinuxCNC's RS274/NGC
//! (`ngc.rs`) writes `[ ]` like Macro B, adds named parameters `#<name>`,
//! `**` and `EXISTS`, and ranks its operators its own way. Which variable
//! numbers exist is the interpreter's business.

mod expr;
mod ngc;
mod scan;
mod stmt;

pub use ngc::{
    Kw, OStmt, ngc_expected, ngc_operands, o_statement, o_word_statement, parse_ngc_line,
};
pub use stmt::{Extent, parse_iso_block, parse_syntec_statement, syntec_extent};

use crate::block::Addr;
use vcnc_core::Span;

/// Which macro language a text is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lang {
    /// Fanuc Custom Macro B (also Haas, and ISO-format Syntec programs).
    MacroB,
    /// The Syntec MACRO language of files whose first line is `%@MACRO`.
    Syntec,
    /// LinuxCNC's RS274/NGC parameters and expressions.
    Ngc,
}

/// What the parser needs to know about the dialect.
#[derive(Debug, Clone, Copy)]
pub struct MacroSyntax {
    /// The language.
    pub lang: Lang,
    /// Most nested brackets (`[ ]`, `( )`, function brackets) in one
    /// expression: Fanuc allows five.
    pub max_nesting: u8,
    /// `//` starts a comment to the end of the line.
    pub slash_comments: bool,
    /// The dialect's addresses written with more than a letter (the
    /// lexer's `LexRules::extended`); those that start with `,` (`,C`,
    /// `,R`) are words of a macro block too, so that they take a variable
    /// or an expression as any address does (`,R#1`).
    pub extended: &'static [(&'static str, Addr)],
}

/// Most ops one expression compiles to (E602 beyond).
pub const MAX_OPS: usize = 512;
/// Most words of one macro word block (the literal block's limit).
pub const MAX_MACRO_WORDS: usize = crate::block::MAX_WORDS;

/// A macro value. `Null` is Fanuc's `#0` "vacant" (Syntec's VACANT).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Value {
    /// No value: never assigned, or assigned `#0`.
    #[default]
    Null,
    /// A Syntec Long (an integer literal written without a decimal point).
    Long(i64),
    /// A real number (every number of Macro B, Syntec's Double).
    Double(f64),
}

impl Value {
    /// The number, `None` when vacant.
    pub fn number(self) -> Option<f64> {
        match self {
            Value::Null => None,
            // Longs come from literals and whole arithmetic within ±2^53
            // checks; the conversion is the language's own.
            #[allow(clippy::cast_precision_loss)]
            Value::Long(v) => Some(v as f64),
            Value::Double(v) => Some(v),
        }
    }
}

/// `#` (local and system variables) or `@` (Syntec global variables).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum VarKind {
    /// `#n`.
    Hash,
    /// `@n` (Syntec).
    At,
}

impl VarKind {
    /// The sigil.
    pub fn sigil(self) -> char {
        match self {
            VarKind::Hash => '#',
            VarKind::At => '@',
        }
    }
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)] // named after what they compute
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    /// LinuxCNC `**`.
    Pow,
}

/// Functions of both languages; which ones a language has is decided by
/// the parser's name table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(missing_docs)] // named after the function
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    /// One argument, or two (`ATAN[y]/[x]`, `ATAN[y,x]`).
    Atan,
    Atan2,
    Sqrt,
    Abs,
    Round,
    Fix,
    Fup,
    Ln,
    Exp,
    Pow,
    Max,
    Min,
    Sign,
    Ceil,
    Floor,
    /// Syntec `STD(value[, unit])`: a Long in least increments to a Double.
    Std,
    /// Syntec `STDAX(value, axis)`.
    StdAx,
    /// Syntec `GETARG(letter)`.
    GetArg,
    Push,
    Pop,
    /// Syntec `STKTOP[n]` (written with brackets).
    StkTop,
    Alarm,
    Msg,
    /// Syntec `WAIT()`: a no-op off-machine.
    Wait,
    /// Syntec `SLEEP()`: a no-op off-machine.
    Sleep,
    /// Syntec `PARAM(n)`: no parameter file, so vacant.
    Param,
    /// Syntec `SETDRAW(…)`/`DRAWHOLE()`: graphics settings, no-ops.
    Draw,
    /// LinuxCNC `EXISTS[#<name>]`: 1 when the named parameter is set (the
    /// name is the call's text); `EXISTS[#n]` checks the number and is 1.
    Exists,
}

/// An argument of a call that takes names or strings.
#[derive(Debug, Clone, PartialEq)]
pub enum Arg {
    /// A number: the next value popped, in argument order.
    Num,
    /// A string (`MSG("text")`).
    Str(Box<str>),
    /// A bare name (`GETARG(X)`, `STDAX(#1, X)`).
    Name(Box<str>),
}

/// One postfix operation.
#[derive(Debug, Clone, PartialEq)]
pub enum OpCode {
    /// A literal.
    Num(Value),
    /// `#n` or `@n`.
    Var(VarKind, u32),
    /// `#[e]`, `@[e]`: pops the number.
    VarAt(VarKind),
    /// Unary minus.
    Neg,
    /// Unary plus.
    Pos,
    /// Syntec `NOT`: −(x+1) on a Long.
    Not,
    /// Pops two, pushes one.
    Bin(BinOp),
    /// Pops `argc` values (the numeric arguments), pushes the result.
    Call(Func, u8),
    /// A call whose arguments include names or strings: `Expr::texts[i]`
    /// holds them, numeric arguments are popped (`argc`).
    CallText(Func, u8, u16),
    /// LinuxCNC `#<name>`: the name (lower case, blanks removed) is the
    /// only `Arg::Name` of `Expr::texts[i]`.
    Named(u16),
}

/// One op and the text it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Op {
    /// What to do.
    pub code: OpCode,
    /// Where it is written (statement text offsets).
    pub span: Span,
}

/// A compiled expression (postfix).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Expr {
    /// The operations, operands first.
    pub ops: Vec<Op>,
    /// Non-numeric arguments of calls (`CallText`), in order.
    pub texts: Vec<Vec<Arg>>,
    /// The whole expression's text.
    pub span: Span,
}

impl Expr {
    /// Whether the expression is a plain (possibly signed) variable
    /// reference, whose vacant value omits a word (`X#1`, `X-#1`).
    pub fn is_reference(&self) -> bool {
        match self.ops.as_slice() {
            [op] => matches!(op.code, OpCode::Var(..)),
            [a, b] => {
                matches!(a.code, OpCode::Var(..)) && matches!(b.code, OpCode::Neg | OpCode::Pos)
            }
            _ => false,
        }
    }
}

/// The variable an assignment (or a FOR) writes.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// `#n`, `@n`.
    Fixed(VarKind, u32, Span),
    /// `#[e]`, `@[e]`.
    Indirect(VarKind, Expr, Span),
    /// LinuxCNC `#<name>` (lower case, blanks removed).
    Named(Box<str>, Span),
}

impl Target {
    /// Where the variable is written.
    pub fn span(&self) -> Span {
        match self {
            Target::Fixed(_, _, s) | Target::Indirect(_, _, s) | Target::Named(_, s) => *s,
        }
    }
}

/// One item of a LinuxCNC line, in the order written.
#[derive(Debug, Clone, PartialEq)]
pub enum LineItem {
    /// `#1 = e`, `#<name> = e`: takes effect after the whole line.
    Set {
        /// The parameter.
        target: Target,
        /// Its value.
        value: Expr,
        /// The whole setting (alarms about its value).
        span: Span,
    },
    /// A word whose value is a number or an expression.
    Word(MWord),
}

/// The value of a word in a macro word block.
#[derive(Debug, Clone, PartialEq)]
pub enum MValue {
    /// A number written out.
    Literal {
        /// Its value.
        value: f64,
        /// Written with a decimal point.
        point: bool,
    },
    /// An expression (`X#1`, `X[#1+2]`, Syntec `X(#1+2)`).
    Expr(Expr),
}

/// A word of a macro word block.
#[derive(Debug, Clone, PartialEq)]
pub struct MWord {
    /// The address letter.
    pub addr: Addr,
    /// Its value.
    pub value: MValue,
    /// The whole word.
    pub span: Span,
}

/// What a statement does.
#[derive(Debug, Clone, PartialEq)]
pub enum StmtKind {
    /// `#i = e` (Macro B), `#i := e` (Syntec).
    Assign {
        /// The variable written.
        target: Target,
        /// The value.
        value: Expr,
    },
    /// A word-address block whose words may hold expressions.
    Words(Vec<MWord>),
    /// A `%` tape mark (Syntec files).
    Percent,
    /// `GOTO n`.
    Goto {
        /// The GOTO keyword (alarms about where it jumps).
        word: Span,
        /// Sequence number.
        target: Expr,
    },
    /// Macro B `IF [c] GOTO n`.
    IfGoto {
        /// Condition.
        cond: Expr,
        /// The GOTO keyword.
        word: Span,
        /// Sequence number.
        target: Expr,
    },
    /// Macro B `IF [c] THEN statement`.
    IfThen {
        /// Condition.
        cond: Expr,
        /// The statement run when it holds.
        then: Box<StmtKind>,
    },
    /// Macro B `WHILE [c] DO m`, or `DO m` alone (`cond` none: for ever).
    While {
        /// Condition.
        cond: Option<Expr>,
        /// Loop number 1–3.
        m: u8,
    },
    /// Macro B `END m`.
    End(u8),
    /// Syntec `IF c THEN`.
    If(Expr),
    /// Syntec `ELSEIF c THEN`.
    ElseIf(Expr),
    /// Syntec `ELSE` (of an IF or a CASE).
    Else,
    /// Syntec `END_IF`.
    EndIf,
    /// Syntec `CASE e OF`.
    Case(Expr),
    /// Syntec `1:`, `3, 4, 5:`.
    CaseLabel(Vec<i64>),
    /// Syntec `END_CASE`.
    EndCase,
    /// Syntec `FOR v := a TO b BY c DO`.
    For {
        /// The counter.
        var: Target,
        /// Start value.
        from: Expr,
        /// Last value.
        to: Expr,
        /// Step (1 when not written).
        by: Option<Expr>,
    },
    /// Syntec `END_FOR`.
    EndFor,
    /// Syntec `WHILE c DO`.
    WhileDo(Expr),
    /// Syntec `END_WHILE`.
    EndWhile,
    /// Syntec `REPEAT`.
    Repeat,
    /// Syntec `UNTIL c END_REPEAT`.
    Until(Expr),
    /// Syntec `EXIT`.
    Exit,
    /// A call statement (`MSG("x");`, `PUSH(5);`, `WAIT();`).
    Call(Expr),
    /// A LinuxCNC line: its words, evaluated with the parameters as they
    /// were before it, and its settings, applied after it.
    Line(Vec<LineItem>),
    /// A LinuxCNC O-word statement (`o100 while [#1 LT 3]`, `o<probe>
    /// call [1] [2]`): it pairs by label, not by nesting.
    OWord {
        /// The keyword.
        kw: Kw,
        /// `100` for `o100`, a name in lower case.
        label: String,
        /// The values in brackets after the keyword (a condition, a
        /// count, a call's arguments, a return value).
        operands: Vec<Expr>,
    },
}

impl StmtKind {
    /// Whether the statement opens, continues or closes a loop or branch
    /// structure (what the structure scan records).
    pub fn is_structure(&self) -> bool {
        !matches!(
            self,
            StmtKind::Assign { .. }
                | StmtKind::Words(_)
                | StmtKind::Percent
                | StmtKind::Goto { .. }
                | StmtKind::IfGoto { .. }
                | StmtKind::IfThen { .. }
                | StmtKind::Call(_)
                | StmtKind::Line(_)
        )
    }
}

/// One parsed statement (an ISO block or a Syntec statement).
#[derive(Debug, Clone, PartialEq)]
pub struct Statement {
    /// What it does.
    pub kind: StmtKind,
    /// Its first word or keyword (alarms about the whole statement).
    pub first: Span,
    /// The leading `N` number, when written.
    pub seq: Option<u32>,
    /// `/` or `/n` block delete.
    pub deleted: Option<u8>,
    /// The text of its `( )` comments (Macro B messages of `#3000`,
    /// `#3006`).
    pub comment: Option<Box<str>>,
}
