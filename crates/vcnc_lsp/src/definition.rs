//! Go to definition: where a call, a jump or a variable leads.
//!
//! | under the cursor                  | leads to                                   |
//! |-----------------------------------|--------------------------------------------|
//! | `M98 P100`, `G65 P100` (the code or P) | `O100` in this file, else `O0100`, `O0100.nc` … in the program directory |
//! | `M98 H20`, `M97 P20`, `M99 P20`   | `N20` of this file                         |
//! | `GOTO 20` (GOTO or its number)    | `N20` of this file                         |
//! | `o<cut> call`, `o100 call`        | `o<cut> sub` in this file, else `cut.ngc` in the directory |
//! | `#<_depth>`, `#100`               | the first line that sets it (`#<_depth> = …`) |
//!
//! Which code calls and which jumps is the dialect table's operation of
//! the code (`MOp::Call`, `MOp::LocalCall`, `FlowOp::MacroCall` …), so a
//! dialect without M97 has no M97 to follow. Labels and headers are found
//! by reading the text (`scan`), not by
//! running it: a definition is where it is written, whichever way the
//! program would reach it. The program directory is searched with the
//! same names as the interpreter's runs (`analysis::program_files`).

use crate::analysis::{Job, program_files};
use crate::scan::{self, Kind, Token};
use crate::text::lines;
use lsp_types::{Location, Position, Range, Uri};
use std::path::Path;
use vcnc_interp::Dialect;
use vcnc_interp::dialect::{FlowOp, GOp, MOp};
use vcnc_syntax::LexRules;

/// What a reference names.
#[derive(Debug, Clone, PartialEq)]
enum Target {
    /// A program `O n`.
    Program(f64),
    /// A sequence number `N n`.
    Label(f64),
    /// An O-word subroutine (`o<name>` or `o100`, lowercase).
    Sub(String),
    /// A variable, as written (lowercase).
    Variable(String),
}

/// The definition of what is at `pos` in the job's document.
pub fn definition(job: &Job, uri: &Uri, pos: Position) -> Option<Location> {
    let text = job.text.as_str();
    let offset = job.text.offset(pos);
    let (start, line) = lines(text).find(|(s, l)| *s <= offset && offset <= s + l.len())?;
    let dialect = job.choice.dialect();
    let lex = dialect.lex;
    let tokens = scan::tokens(line, &lex);
    let i = tokens
        .iter()
        .position(|t| t.start <= offset - start && offset - start <= t.end)?;
    let target = target(&tokens, i, line, &dialect)?;
    if let Some((from, to)) = find(text, &lex, &target) {
        return Some(Location::new(uri.clone(), job.text.range(from, to)));
    }
    let dir = job.dir()?;
    in_directory(&dir, &lex, &target)
}

/// What the token `i` of a line refers to.
fn target(tokens: &[Token], i: usize, line: &str, dialect: &Dialect) -> Option<Target> {
    let t = tokens.get(i)?;
    let word = |letter: u8| {
        tokens
            .iter()
            .find(|t| t.kind == Kind::Address && t.letter == letter)
            .and_then(|t| t.value)
    };
    let word_text = t.text(line).to_ascii_lowercase();
    match t.kind {
        Kind::Variable => return Some(Target::Variable(word_text)),
        Kind::Macro if word_text == "goto" => {
            return next_number(tokens, i).map(Target::Label);
        }
        Kind::Number
            if i > 0
                && tokens
                    .get(i - 1)
                    .is_some_and(|p| p.text(line).eq_ignore_ascii_case("goto")) =>
        {
            return t.value.map(Target::Label);
        }
        _ => {}
    }
    // An O-word call: `o<name> call` / `o100 call`.
    let calls = tokens
        .iter()
        .any(|t| t.text(line).eq_ignore_ascii_case("call"));
    if calls {
        let o = tokens.first().filter(|o| o.letter == b'O')?;
        let name = o.text(line).to_ascii_lowercase();
        return Some(Target::Sub(name));
    }
    // The block's call or jump, as the dialect's tables define its codes.
    let call = tokens
        .iter()
        .filter(|t| t.kind == Kind::Code)
        .find_map(|t| call_of(dialect, t).map(|c| (t, c)));
    let (code, call) = call?;
    let on = |letter: u8| std::ptr::eq(t, code) || (t.kind == Kind::Address && t.letter == letter);
    match call {
        Call::Program if on(b'P') => word(b'P').map(Target::Program),
        Call::Program if on(b'H') => word(b'H').map(Target::Label),
        Call::Label if on(b'P') => word(b'P').map(Target::Label),
        _ => None,
    }
}

/// What a code of a block with P (and H) words calls.
enum Call {
    /// `M98 P`, `G65 P`, `G66 P`: a program (M98 H: a label of this one).
    Program,
    /// `M97 P`, `M99 P`: a label of this program.
    Label,
}

fn call_of(dialect: &Dialect, t: &Token) -> Option<Call> {
    let v = t.value?;
    match t.letter {
        b'M' => match dialect.m(v)?.op {
            MOp::Call => Some(Call::Program),
            MOp::LocalCall | MOp::Return => Some(Call::Label),
            _ => None,
        },
        b'G' => match dialect.g(v)?.op {
            GOp::Flow(FlowOp::MacroCall | FlowOp::MacroModal) => Some(Call::Program),
            _ => None,
        },
        _ => None,
    }
}

/// The value of the number after token `i` (`GOTO 20`, `GOTO20`).
fn next_number(tokens: &[Token], i: usize) -> Option<f64> {
    tokens
        .get(i + 1)
        .filter(|t| t.kind == Kind::Number)
        .and_then(|t| t.value)
}

/// Where `target` is defined in `text`: byte range of its header, label or
/// first assignment.
fn find(text: &str, lex: &LexRules, target: &Target) -> Option<(usize, usize)> {
    for (start, line) in lines(text) {
        let tokens = scan::tokens(line, lex);
        let Some(first) = tokens.iter().find(|t| t.kind != Kind::Comment) else {
            continue;
        };
        let span = |t: &Token| (start + t.start, start + t.end);
        let found = match target {
            Target::Program(n) => (first.kind == Kind::Address
                && first.letter == b'O'
                && first.value == Some(*n)
                && !is_oword(&tokens))
            .then(|| span(first)),
            Target::Label(n) => {
                // `N20` starts its block, possibly after an O header or `/`.
                tokens
                    .iter()
                    .take(2)
                    .find(|t| t.kind == Kind::Address && t.letter == b'N' && t.value == Some(*n))
                    .map(span)
            }
            Target::Sub(name) => (first.letter == b'O'
                && first.text(line).eq_ignore_ascii_case(name)
                && tokens
                    .get(1)
                    .is_some_and(|t| t.text(line).eq_ignore_ascii_case("sub")))
            .then(|| span(first)),
            Target::Variable(name) => assignment(&tokens, line, name).map(span),
        };
        if found.is_some() {
            return found;
        }
    }
    None
}

/// Whether the line is a LinuxCNC O-word statement (`o100 sub`, `o100 if`).
fn is_oword(tokens: &[Token]) -> bool {
    tokens.get(1).is_some_and(|t| t.kind == Kind::Macro)
}

/// The variable token of `line` that an `=` right after it sets.
fn assignment<'t>(tokens: &'t [Token], line: &str, name: &str) -> Option<&'t Token> {
    tokens.iter().find(|t| {
        t.kind == Kind::Variable
            && t.text(line).eq_ignore_ascii_case(name)
            && line
                .get(t.end..)
                .is_some_and(|rest| rest.trim_start().starts_with('='))
    })
}

/// A program or subroutine file in the program directory.
fn in_directory(dir: &Path, lex: &LexRules, target: &Target) -> Option<Location> {
    let (path, inner) = match target {
        Target::Program(n) if n.fract() == 0.0 && (0.0..1e8).contains(n) => {
            // Whole and below 10^8: the conversion is exact.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let number = *n as u32;
            let path = program_files(dir, number)
                .into_iter()
                .find(|p| p.is_file())?;
            (path, Some(target.clone()))
        }
        Target::Sub(name) => {
            let bare = name.trim_start_matches(['o', 'O']);
            let bare = bare.trim_start_matches('<').trim_end_matches('>');
            let path = dir.join(format!("{bare}.ngc"));
            (path.is_file().then_some(path)?, Some(target.clone()))
        }
        _ => return None,
    };
    let uri = crate::uri::from_path(&std::fs::canonicalize(&path).unwrap_or(path.clone()))?;
    let text = std::fs::read(&path).ok()?;
    let text = String::from_utf8_lossy(&text);
    let range = inner
        .and_then(|t| find(&text, lex, &t))
        .map(|(a, b)| crate::text::Text::new(text.to_string()).range(a, b))
        .unwrap_or_else(|| Range::new(Position::new(0, 0), Position::new(0, 0)));
    Some(Location::new(uri, range))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dialect::Choice;
    use std::str::FromStr;

    fn job(text: &str, dialect: &'static str, dir: Option<&Path>) -> Job {
        let choice = Choice {
            name: dialect,
            why: String::new(),
        };
        Job {
            program_dir: dir.map(Path::to_path_buf),
            ..Job::for_text(text, choice)
        }
    }

    fn uri() -> Uri {
        Uri::from_str("file:///tmp/main.nc").unwrap()
    }

    fn at(text: &str, dialect: &'static str, line: u32, character: u32) -> Option<Range> {
        definition(
            &job(text, dialect, None),
            &uri(),
            Position::new(line, character),
        )
        .map(|l| l.range)
    }

    fn range(line: u32, from: u32, to: u32) -> Option<Range> {
        Some(Range::new(
            Position::new(line, from),
            Position::new(line, to),
        ))
    }

    #[test]
    fn calls_lead_to_their_program_and_jumps_to_their_label() {
        let text = "O0001\nM98 P100 L2\nG65 P100 A1.\nM97 P20\nM30\nO100 (SUB)\nN20 G00 X0\nM99\n";
        // From P, from M98 itself, and from G65's P: the O100 header.
        assert_eq!(at(text, "fanuc", 1, 5), range(5, 0, 4));
        assert_eq!(at(text, "fanuc", 1, 1), range(5, 0, 4));
        assert_eq!(at(text, "fanuc", 2, 5), range(5, 0, 4));
        // Haas M97 P20: the label N20.
        assert_eq!(at(text, "haas", 3, 5), range(6, 0, 3));
        // The L word leads nowhere.
        assert_eq!(at(text, "fanuc", 1, 10), None);
    }

    #[test]
    fn goto_subroutines_and_variables() {
        let text = "#1 = 0\nN10 #1 = #1 + 1\nIF [#1 LT 3] GOTO 10\nM30\n";
        assert_eq!(at(text, "fanuc", 2, 14), range(1, 0, 3));
        assert_eq!(at(text, "fanuc", 2, 18), range(1, 0, 3));
        assert_eq!(at(text, "fanuc", 2, 5), range(0, 0, 2));
        let ngc =
            "#<_depth> = 2\no<cut> sub\nG01 Z-#<_depth> F100\no<cut> endsub\no<cut> call\nM2\n";
        assert_eq!(at(ngc, "linuxcnc", 4, 2), range(1, 0, 6));
        assert_eq!(at(ngc, "linuxcnc", 2, 9), range(0, 0, 9));
    }

    #[test]
    fn programs_of_the_directory_are_found_by_their_file_names() {
        let dir = std::env::temp_dir().join(format!("vcnc-lsp-def-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("O0200.nc"), "%\nO0200 (POCKET)\nG01 X1\nM99\n%\n").unwrap();
        let j = job("M98 P200\nM30\n", "fanuc", Some(&dir));
        let loc = definition(&j, &uri(), Position::new(0, 6)).unwrap();
        assert!(
            loc.uri.as_str().ends_with("/O0200.nc"),
            "{}",
            loc.uri.as_str()
        );
        assert_eq!(Some(loc.range), range(1, 0, 5));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
