//! Diagnostics as plain data: a stable [`Code`], a message that says what is
//! wrong, a hint that says how to fix it, and where.
//!
//! Every alarm code is declared exactly once, in the [`codes!`] table below,
//! with a short title; `docs/alarms.md` documents each one and a test checks
//! that it lists every code of [`Code::ALL`]. The constructors that build
//! each diagnostic live beside the code that raises it (`vcnc_syntax`'s
//! `diagnostics.rs`, `vcnc_interp`'s `alarms.rs`); rendering (source line,
//! caret) happens only in the CLI.

use crate::span::Span;

/// Declares the alarm catalogue: one line per code, `CODE => "title"`.
macro_rules! codes {
    ($($code:ident => $title:literal,)*) => {
        /// Stable alarm codes. A number never changes meaning; new codes are
        /// added at the end of their range.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Code {
            $(#[doc = $title] $code,)*
        }

        impl Code {
            /// Every code, in order.
            pub const ALL: &'static [Code] = &[$(Code::$code,)*];

            /// The code as printed: `"E303"`.
            pub fn as_str(self) -> &'static str {
                match self {
                    $(Code::$code => stringify!($code),)*
                }
            }

            /// Whether this is a warning (`W…`): reported, the run goes on.
            pub fn is_warning(self) -> bool {
                self.as_str().starts_with('W')
            }

            /// A short title (the first column of `docs/alarms.md`).
            pub fn title(self) -> &'static str {
                match self {
                    $(Code::$code => $title,)*
                }
            }
        }
    };
}

codes! {
    E101 => "illegal character",
    E102 => "malformed number",
    E103 => "number out of range",
    E104 => "address without a value",
    E105 => "unterminated comment",
    E106 => "block or line too long",
    E107 => "too many words in a block",
    E108 => "decimal point not allowed",
    E109 => "value out of range for this word",
    E201 => "unknown or unsupported G code",
    E202 => "unknown M code",
    E203 => "word not used in this block",
    E204 => "address written twice",
    E205 => "two G codes of one group",
    E206 => "two M codes of one group",
    E207 => "two codes want the axis words",
    E208 => "G92 with axis words and S",
    E209 => "code must stand alone",
    E210 => "code not allowed in this mode",
    E301 => "zero feed",
    E302 => "arc radius too small",
    E303 => "arc end point off the circle",
    E304 => "arc of zero radius",
    E305 => "arc without centre or radius",
    E306 => "R arc with end equal to start",
    E307 => "G29 without G28/G30",
    E308 => "G53 in incremental mode",
    E309 => "M06 without a tool",
    E310 => "surface speed without a tool diameter",
    E311 => "thread without a lead",
    E312 => "required word missing",
    E313 => "three points on a line",
    E314 => "cycle parameters contradict each other",
    E315 => "arc cannot be transformed",
    E316 => "transform parameter out of range",
    E317 => "arc in a compensation start-up or cancel block",
    E318 => "cutter compensation over-cut",
    E319 => "too many blocks without motion in the compensation plane",
    E320 => "code not allowed while compensating",
    E321 => "tapping without the spindle turning the right way",
    E322 => "hole pattern without a canned cycle",
    E323 => "hole bottom on the wrong side of the R level",
    E324 => "plane change in a canned cycle",
    E325 => "pocket smaller than the tool",
    E326 => "one block expands to too many moves",
    E327 => "path smoothing started under exact stop or tapping mode",
    E328 => "NURBS outside high-speed high-precision mode",
    E329 => "NURBS definition is invalid",
    E340 => "probe did not trip",
    E341 => "spindle too fast for the thread's lead",
    E342 => "feed per revolution with the spindle stopped",
    E343 => "profile of a turning cycle cannot be cut",
    E344 => "code or word not allowed in a profile block",
    E345 => "profile end not found",
    E346 => "zero depth of cut, step or pass count",
    E347 => "chamfer or corner R cannot be made",
    E348 => "G96 at the spindle axis without a speed clamp",
    E349 => "cycle not allowed in the modes in force",
    E401 => "program number not found",
    E402 => "sequence number not found",
    E403 => "subprogram nesting too deep",
    E404 => "too many blocks executed",
    E405 => "too many jumps",
    E406 => "subprogram ended without M99",
    E407 => "reserved",
    E408 => "called program unreadable",
    E409 => "return without a call",
    E501 => "soft over-travel",
    E502 => "reference point not defined",
    E503 => "offset number out of range",
    E601 => "macro syntax error",
    E602 => "macro expression nested too deeply or too complex",
    E603 => "macro statement too long",
    E604 => "unknown or unavailable macro function or statement",
    E605 => "no such variable",
    E606 => "variable is read-only",
    E607 => "vacant value where a number is required",
    E608 => "division by zero",
    E609 => "math domain or range error",
    E610 => "operand type mismatch",
    E611 => "loop or branch structure does not pair",
    E612 => "alarm raised by the program",
    E613 => "macro stack full",
    E614 => "GOTO into a loop from outside it",
    W101 => "length without a decimal point in a program that writes points",
    W102 => "feed above the machine's maximum",
    W103 => "spindle speed above the machine's maximum",
    W104 => "cutting with the spindle stopped",
    W105 => "M code the controller does not know",
    W106 => "program ends without M02 or M30",
    W107 => "M99 repeats the main program",
    W108 => "tool compensation with an empty offset register",
    W109 => "no decimal points and a part under 1 mm: probably whole units",
    W110 => "G53 ignored in incremental mode",
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

    /// Whether the interpreter has already placed it in a file.
    pub fn is_located(&self) -> bool {
        self.line != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_print_their_names_and_ranges_are_ordered() {
        assert_eq!(Code::E303.as_str(), "E303");
        assert_eq!(Code::E101.title(), "illegal character");
        let names: Vec<&str> = Code::ALL.iter().map(|c| c.as_str()).collect();
        let mut sorted = names.clone();
        sorted.sort_unstable();
        assert_eq!(names, sorted, "declare codes in numeric order");
    }
}

#[cfg(test)]
mod catalogue_tests {
    use super::Code;

    /// Every code has a row in `docs/alarms.md`, and the page has no row for
    /// a code that does not exist.
    #[test]
    fn docs_alarms_lists_every_code() {
        let doc = include_str!("../../../docs/alarms.md");
        let rows: Vec<&str> = doc
            .lines()
            .filter_map(|l| l.strip_prefix("| "))
            .filter(|l| l.starts_with(['E', 'W']))
            .filter_map(|l| l.split_whitespace().next())
            .collect();
        for code in Code::ALL {
            assert!(
                rows.contains(&code.as_str()),
                "docs/alarms.md has no row for {}",
                code.as_str()
            );
        }
        for row in rows {
            assert!(
                Code::ALL.iter().any(|c| c.as_str() == row),
                "docs/alarms.md documents {row}, which the catalogue does not declare"
            );
        }
    }
}
