//! Diagnostics as plain data: a stable [`Code`], a message that says what is
//! wrong, a hint that says how to fix it, and where.
//!
//! The catalogue of codes lives here so that both the syntax stage and the
//! interpreter share one numbering (documented in `docs/alarms.md`). Each
//! syntax diagnostic is built by one named constructor below; the
//! interpreter's constructors live in `vcnc_interp::alarms`. Rendering (source
//! line, caret) happens only in the CLI.

use crate::span::Span;

/// Stable alarm codes. The number never changes meaning.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // each code is documented in docs/alarms.md
pub enum Code {
    E101,
    E102,
    E103,
    E104,
    E105,
    E106,
    E107,
    E108,
    E109,
    E201,
    E202,
    E203,
    E204,
    E205,
    E206,
    E207,
    E208,
    E209,
    E301,
    E302,
    E303,
    E304,
    E305,
    E306,
    E307,
    E308,
    E309,
    E310,
    E311,
    E312,
    E313,
    E314,
    E401,
    E402,
    E403,
    E404,
    E405,
    E406,
    E408,
    E409,
    E501,
    E502,
    E503,
}

impl Code {
    /// The code as printed: `"E303"`.
    pub fn as_str(self) -> &'static str {
        use Code::*;
        match self {
            E101 => "E101",
            E102 => "E102",
            E103 => "E103",
            E104 => "E104",
            E105 => "E105",
            E106 => "E106",
            E107 => "E107",
            E108 => "E108",
            E109 => "E109",
            E201 => "E201",
            E202 => "E202",
            E203 => "E203",
            E204 => "E204",
            E205 => "E205",
            E206 => "E206",
            E207 => "E207",
            E208 => "E208",
            E209 => "E209",
            E301 => "E301",
            E302 => "E302",
            E303 => "E303",
            E304 => "E304",
            E305 => "E305",
            E306 => "E306",
            E307 => "E307",
            E308 => "E308",
            E309 => "E309",
            E310 => "E310",
            E311 => "E311",
            E312 => "E312",
            E313 => "E313",
            E314 => "E314",
            E401 => "E401",
            E402 => "E402",
            E403 => "E403",
            E404 => "E404",
            E405 => "E405",
            E406 => "E406",
            E408 => "E408",
            E409 => "E409",
            E501 => "E501",
            E502 => "E502",
            E503 => "E503",
        }
    }
}

/// One alarm: what, where, and how to fix it.
///
/// `span` is relative to the start of the line; the interpreter fills in
/// `line`, `column`, `line_offset` and `file` when it raises the alarm.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    /// Stable code.
    pub code: Code,
    /// What is wrong, in one sentence.
    pub message: String,
    /// How to fix it.
    pub help: String,
    /// The offending bytes within the line.
    pub span: Span,
    /// 1-based line number (0 when not yet located).
    pub line: u64,
    /// 1-based character column of `span.start`.
    pub column: u32,
    /// Byte offset of the line's first byte in its file.
    pub line_offset: u64,
    /// The file, when it is not the main program.
    pub file: Option<String>,
}

impl Diagnostic {
    /// A diagnostic not yet located in a file (line 0).
    pub fn new(code: Code, span: Span, message: String, help: &str) -> Diagnostic {
        Diagnostic {
            code,
            message,
            help: help.to_string(),
            span,
            line: 0,
            column: 0,
            line_offset: 0,
            file: None,
        }
    }
}

fn show(ch: char) -> String {
    if ch.is_control() || ch == ' ' {
        format!("{:?}", ch)
    } else {
        format!("'{ch}'")
    }
}

/// E101: a character that has no meaning in a program.
pub fn illegal_character(span: Span, ch: char) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        span,
        format!("illegal character {} (U+{:04X})", show(ch), ch as u32),
        "remove it, or put it inside a comment ( )",
    )
}

/// E102: the digits after an address do not form a number.
pub fn malformed_number(span: Span, letter: char) -> Diagnostic {
    Diagnostic::new(
        Code::E102,
        span,
        format!("the value of {letter} is not a number"),
        "write an optional sign, digits and at most one decimal point, e.g. X-12.5",
    )
}

/// E103: too many digits, or too large a value.
pub fn number_out_of_range(span: Span, letter: char) -> Diagnostic {
    Diagnostic::new(
        Code::E103,
        span,
        format!("the value of {letter} has too many digits"),
        "use at most 9 digits before the decimal point and 15 significant digits in all",
    )
}

/// E104: an address letter with no value after it.
pub fn missing_value(span: Span, letter: char) -> Diagnostic {
    Diagnostic::new(
        Code::E104,
        span,
        format!("address {letter} has no value"),
        "write a number right after the letter, e.g. G01 or X10.0",
    )
}

/// E203: an address that only another dialect has.
pub fn foreign_address(span: Span, text: &str, dialect: &str) -> Diagnostic {
    let mut d = Diagnostic::new(
        Code::E203,
        span,
        format!("{text} is not an address of this dialect"),
        "",
    );
    d.help = format!("{text} belongs to the {dialect} dialect: run with --dialect {dialect}");
    d
}

/// E105: a `(` comment that the line does not close.
pub fn unterminated_comment(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E105,
        span,
        "comment is not closed on this line".to_string(),
        "end the comment with ')' before the end of the line",
    )
}

/// E106: a block or line longer than the controller's buffer.
pub fn block_too_long(span: Span, max: usize) -> Diagnostic {
    Diagnostic::new(
        Code::E106,
        span,
        format!("block is longer than {max} bytes"),
        "split it into several blocks",
    )
}

/// E107: more words than a block can hold.
pub fn too_many_words(span: Span, max: usize) -> Diagnostic {
    Diagnostic::new(
        Code::E107,
        span,
        format!("block has more than {max} words"),
        "split it into several blocks",
    )
}
