//! The syntax stage's diagnostics, one named constructor each.
//!
//! The catalogue of codes (and the [`Diagnostic`] type) lives in
//! `vcnc_core::diagnostic`, so the syntax stage and the interpreter share one
//! numbering (documented in `docs/alarms.md`); the interpreter's
//! constructors live in `vcnc_interp::alarms`. Rendering (source line,
//! caret) happens only in the CLI.

use vcnc_core::Span;
pub use vcnc_core::{Code, Diagnostic};

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

/// E101: a `#` variable or parameter in a dialect without macros (a macro
/// dialect's parser reads it before this is reported).
pub fn variable_without_macros(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        span,
        "a `#` variable or a `[ ]` expression, which this dialect does not read".to_string(),
        "run macro programs (Custom Macro B) under --dialect fanuc, haas or syntec, and LinuxCNC's parameters under --dialect linuxcnc",
    )
}

/// E101: a `$` line in a program: a grbl system command, a multi-path
/// header (`$1`) or a file header.
pub fn system_command(span: Span, text: &str) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        span,
        format!(
            "{text} is not G-code: a `$` line is a grbl system command ($H homing, $X unlock, $$ settings), a multi-path header ($1, $2) or a file header"
        ),
        "remove the line; send system commands to the controller from its console; a program of one path of a multi-path lathe is checked on its own",
    )
}

/// E604: LinuxCNC's O-word flow control (`o100 sub`, `o<name> call`).
pub fn o_word_flow(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E604,
        span,
        "LinuxCNC's O-word statements (o100 sub, call, if, while …) are read under --dialect linuxcnc only"
            .to_string(),
        "run a LinuxCNC program with --dialect linuxcnc (or linuxcnc-lathe); a Fanuc-style control writes subroutines and loops as M98/M99 subprograms and Custom Macro B IF, WHILE, GOTO",
    )
}

/// E101: a `)` outside a comment (usually an inner `( )` that closed the
/// comment early).
pub fn stray_close_paren(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        span,
        "`)` without an open `(`: comments do not nest, so an inner `)` closed the comment before it".to_string(),
        "write the inner parentheses of a comment as [ ], or remove them",
    )
}

/// E101: a comment that holds a parenthesis, `(A (B) C)`: the first `)`
/// closed it, and a later `)` shows the programmer meant it to nest.
pub fn nested_comment(inner_open: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        inner_open,
        "`(` inside a comment: comments do not nest, so the first `)` ends the comment and the text after it is read as G-code".to_string(),
        "write the inner parentheses of a comment as [ ], or remove them",
    )
}

/// E101: a `(` inside a comment, in a dialect whose comments may hold
/// none (LinuxCNC: rs274 stops with "Nested comment found").
pub fn paren_in_comment(inner_open: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        inner_open,
        "`(` inside a comment: LinuxCNC refuses a comment holding a parenthesis (\"Nested comment found\")".to_string(),
        "write the inner parentheses of a comment as [ ], or remove them",
    )
}

/// E101: a block that starts with a digit.
pub fn digit_first(span: Span, text: &str) -> Diagnostic {
    Diagnostic::new(
        Code::E101,
        span,
        format!("the block starts with the number {text}, which has no address letter"),
        &format!(
            "write a sequence number as N{text}, or put the letter the value belongs to before it"
        ),
    )
}

/// E104: a program name with a letter in it (`O7997A`).
pub fn lettered_program_name(span: Span, name: &str) -> Diagnostic {
    Diagnostic::new(
        Code::E104,
        span,
        format!("{name} is not a program number: O takes digits only"),
        "name the program with digits (O7997) and put any text in a comment: O7997 (A)",
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

/// E104: a Syntec `@` variable as a word's value in an ISO program
/// (`Y@1`): `@` variables exist only in `%@MACRO` files.
pub fn at_variable_in_iso(span: Span, letter: char) -> Diagnostic {
    Diagnostic::new(
        Code::E104,
        span,
        format!(
            "address {letter} has no value: `@` variables exist only in Syntec MACRO files, whose first line is %@MACRO"
        ),
        "start the file with a %@MACRO line to use @ variables, or use a # variable in this ISO program",
    )
}

/// E601: a variable right after `/` (`/#2 G00 X1.`): the block-delete
/// (optional block skip) switch is a digit, never a variable (Fanuc 0i).
pub fn block_delete_variable(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E601,
        span,
        "a block delete switch cannot be a variable: after `/` comes a digit 1-9 or nothing"
            .to_string(),
        "write the switch as a digit (/2 G00 X1.); a variable after `/` starts an assignment (/#2 = 5)",
    )
}

/// E604: text stored in a Syntec global (`@10 := "12";`), which the
/// controller keeps as ASCII codes for SCANTEXT to read back.
pub fn unavailable_string_store(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E604,
        span,
        "text in a global (@) variable is kept as ASCII codes for SCANTEXT, which needs the real controller".to_string(),
        "store numbers in @ variables; a # variable takes a number written as text (#10 := \"12\";)",
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

// Macro statements (Custom Macro B, Syntec MACRO): E1xx reading errors
// shared with the lexer, and the E6xx range.

/// E105: a Syntec `(*` comment that the file does not close.
pub fn unterminated_block_comment(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E105,
        span,
        "`(*` comment is not closed".to_string(),
        "end the comment with `*)`",
    )
}

/// E103: a number in a macro expression with too many digits.
pub fn macro_number_out_of_range(span: Span) -> Diagnostic {
    Diagnostic::new(
        Code::E103,
        span,
        "this number has too many digits".to_string(),
        "use at most 9 digits before the decimal point and 15 significant digits in all",
    )
}

/// E601: a macro statement or expression that does not parse; `what` says
/// what was expected and found.
pub fn macro_syntax(span: Span, what: &str, help: &str) -> Diagnostic {
    Diagnostic::new(Code::E601, span, what.to_string(), help)
}

/// E601: a sequence or program number written as a variable or an
/// expression (`N#1`, `O[#2]`), which Custom Macro B forbids.
pub fn number_word_not_variable(span: Span, letter: char) -> Diagnostic {
    let what = if letter == 'N' {
        "a sequence number"
    } else {
        "a program number"
    };
    Diagnostic::new(
        Code::E601,
        span,
        format!("{letter} cannot take a variable or an expression: {what} is written as digits"),
        "write the number itself (N100, O0010); to jump to a computed label use GOTO #1",
    )
}

/// E602: an expression of more than `max` operations.
pub fn macro_too_complex(span: Span, max: usize) -> Diagnostic {
    Diagnostic::new(
        Code::E602,
        span,
        format!("this expression is too complex (more than {max} operations or values)"),
        "split it into several assignments",
    )
}

/// E602: brackets nested deeper than the control allows.
pub fn macro_nesting(span: Span, max: u8) -> Diagnostic {
    Diagnostic::new(
        Code::E602,
        span,
        format!("brackets are nested more than {max} deep (function brackets count)"),
        "compute part of the expression into a variable first",
    )
}

/// E604: a function the language does not have, or one that needs the
/// machine (I/O, files, the PLC).
pub fn unknown_function(span: Span, name: &str, unavailable: bool) -> Diagnostic {
    if unavailable {
        return Diagnostic::new(
            Code::E604,
            span,
            format!(
                "{name} needs the real machine (its I/O, files, parameters or PLC): vcnc cannot evaluate it"
            ),
            "run this part of the program on the machine, or give the value as a number",
        );
    }
    Diagnostic::new(
        Code::E604,
        span,
        format!("{name} is not a function or operator of this macro language"),
        "check the spelling against the function list (docs/macros.md)",
    )
}

/// E604: a Syntec statement word that is neither a keyword, a function nor
/// an address (robot commands such as MOVL).
pub fn unknown_statement(span: Span, name: &str) -> Diagnostic {
    Diagnostic::new(
        Code::E604,
        span,
        format!(
            "{name} is not a statement vcnc runs (robot and coordinate-system commands are not supported)"
        ),
        "check the spelling; addresses are single letters (G01 X10.)",
    )
}

/// E611: a DO/END loop number other than 1, 2 or 3.
pub fn loop_number(span: Span, keyword: &str) -> Diagnostic {
    Diagnostic::new(
        Code::E611,
        span,
        format!("{keyword} takes a loop number 1, 2 or 3"),
        "number nested loops 1 to 3 (DO 1 … END 1)",
    )
}
