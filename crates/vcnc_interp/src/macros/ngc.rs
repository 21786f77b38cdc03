//! LinuxCNC's parameters and expressions (`--dialect linuxcnc`): the
//! lines the lexer rejects for a `#` or a `[`, read and evaluated the way
//! its RS274/NGC interpreter does, then run as the plain block they stand
//! for.
//!
//! ```text
//!   #1 = 2   #<depth> = [#1 * 1.5]           (settings: after the line)
//!   G1 X[#1 + 10] Z-#<depth> F#<_rate>       (values: with the old ones)
//!        └─ G1 X12 Z-3 F… ──▶ the block pipeline
//! ```
//!
//! What differs from Custom Macro B, and why this is its own reader:
//! every parameter holds a number (an unset numbered one reads 0, an unset
//! named one alarms), settings on a line take effect after the whole line
//! is read, `ROUND` rounds half away from zero, `FIX`/`FUP` are floor and
//! ceiling, `AND`/`OR`/`XOR` are logical,
//! `**` is a power, `ATAN[y]/[x]` is the full-circle angle, EQ and NE
//! compare within 0.0001, MOD lands in [0, |divisor|), and the
//! precedence is `**` > `* / MOD` > `+ -` > comparisons > `AND OR XOR`.
//! Named parameters without a leading `_` are local to an O-word
//! subroutine (`oword.rs` saves them at its call, restores them at its
//! return); the others live for the whole program. System parameters
//! (#5061–#5428: probe results, offsets, the position) read what the
//! program wrote, 0 otherwise.

use crate::alarms;
use std::collections::HashMap;
use vcnc_syntax::{Addr, Diagnostic, Span, Word};

/// The highest numbered parameter (LinuxCNC's 5601).
const LAST: usize = 5601;

/// A word's value that the lexer would take (at most 9 digits before the
/// point): beyond, E103, as written literally.
const MAX_VALUE: f64 = 1e9;

/// rs274's tolerance of EQ and NE.
const EQUAL: f64 = 1e-4;

/// Parameters of one run.
#[derive(Debug, Clone)]
pub(crate) struct Params {
    numbered: Vec<f64>,
    named: HashMap<String, f64>,
}

impl Default for Params {
    fn default() -> Params {
        // The two a program may read before any call (rs274 predefines
        // them as 0).
        let named = [("_value", 0.0), ("_value_returned", 0.0)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        Params {
            numbered: vec![0.0; LAST + 1],
            named,
        }
    }
}

/// A parameter a line sets.
#[derive(Debug, Clone, PartialEq)]
enum Key {
    Numbered(usize),
    Named(String),
}

/// A line read: its words (values evaluated) and its settings.
#[derive(Debug, Default)]
pub(crate) struct Line {
    pub words: Vec<Word>,
    sets: Vec<(Key, f64)>,
    /// A `/` block delete at its start.
    pub deleted: bool,
}

impl Params {
    /// Applies a line's settings, in their order (the last of a
    /// parameter set twice wins).
    pub(crate) fn commit(&mut self, line: &Line) {
        for (k, v) in &line.sets {
            match k {
                Key::Numbered(n) => self.numbered[*n] = *v,
                Key::Named(name) => {
                    self.named.insert(name.clone(), *v);
                }
            }
        }
    }
}

/// rs274 2.9's predefined named parameters, which a program cannot set
/// ("Cannot assign to read-only parameter #<_x>", probed name by name
/// with `rs274 -g`: `_abs_u`…`_abs_w`, `_hal`, `_ini` and other `_` names
/// are ordinary globals). vcnc provides only `_value` and
/// `_value_returned`; the others read as unset names.
const READ_ONLY: &[&str] = &[
    "_vmajor",
    "_vminor",
    "_line",
    "_motion_mode",
    "_plane",
    "_ccomp",
    "_metric",
    "_imperial",
    "_absolute",
    "_incremental",
    "_inverse_time",
    "_units_per_minute",
    "_units_per_rev",
    "_coord_system",
    "_tool_offset",
    "_retract_r_plane",
    "_retract_old_z",
    "_spindle_rpm_mode",
    "_spindle_css_mode",
    "_ijk_absolute_mode",
    "_lathe_diameter_mode",
    "_lathe_radius_mode",
    "_spindle_on",
    "_spindle_cw",
    "_mist",
    "_flood",
    "_speed_override",
    "_feed_override",
    "_adaptive_feed",
    "_feed_hold",
    "_feed",
    "_rpm",
    "_x",
    "_y",
    "_z",
    "_a",
    "_b",
    "_c",
    "_u",
    "_v",
    "_w",
    "_abs_x",
    "_abs_y",
    "_abs_z",
    "_abs_a",
    "_abs_b",
    "_abs_c",
    "_current_tool",
    "_current_pocket",
    "_selected_tool",
    "_selected_pocket",
    "_value",
    "_value_returned",
    "_task",
    "_call_level",
    "_remap_level",
];

/// Reads `text[start..]`, one LinuxCNC line, with the parameters as they
/// were before it.
pub(crate) fn read_line(text: &[u8], start: usize, params: &Params) -> Result<Line, Diagnostic> {
    let mut r = Reader {
        s: text,
        i: start,
        params,
        depth: 0,
    };
    paren_in_comment(&text[start.min(text.len())..], start)?;
    let mut line = Line::default();
    r.blank();
    if r.peek() == b'/' {
        line.deleted = true;
        r.i += 1;
    }
    loop {
        r.blank();
        let at = r.i;
        match r.peek().to_ascii_uppercase() {
            0 => return Ok(line),
            b'#' => {
                let key = r.target()?;
                if let Key::Named(name) = &key
                    && READ_ONLY.contains(&name.as_str())
                {
                    return Err(alarms::read_only_named(Span::new(at, r.i), name));
                }
                r.blank();
                if r.peek() != b'=' {
                    return Err(syntax(Span::new(r.i, r.i + 1), "`=` after the parameter"));
                }
                r.i += 1;
                // A value, not a bare expression: `#1 = 2 G1 X3` sets 2.
                let v = r.value()?;
                if !v.is_finite() {
                    return Err(alarms::macro_range(
                        Span::new(at, r.i),
                        "the parameter's value",
                    ));
                }
                line.sets.push((key, v));
            }
            l @ b'A'..=b'Z' => {
                r.i += 1;
                let v = r.value()?;
                if !v.is_finite() {
                    return Err(alarms::macro_range(Span::new(at, r.i), "the word's value"));
                }
                if v.abs() >= MAX_VALUE {
                    return Err(vcnc_syntax::diagnostics::number_out_of_range(
                        Span::new(at, r.i),
                        char::from(l),
                    ));
                }
                // G and M codes may repeat (`G1 G91 Z-#1`); other letters
                // once, as the lexer wants.
                if !matches!(l, b'G' | b'M')
                    && line.words.iter().any(|w| w.addr.as_letter() == Some(l))
                {
                    return Err(syntax(Span::new(at, r.i), "one word per letter in a block"));
                }
                line.words.push(Word {
                    addr: Addr::letter(l),
                    value: v,
                    // Whole units either way; a fraction in an M or T
                    // word still alarms as written with a point.
                    point: v.fract() != 0.0,
                    span: Span::new(at, r.i),
                });
            }
            p @ (b'@' | b'^') => {
                // The polar words, with an expression for value (`@[#1]`).
                r.i += 1;
                let v = r.value()?;
                if !v.is_finite() || v.abs() >= MAX_VALUE {
                    return Err(alarms::macro_range(Span::new(at, r.i), "the word's value"));
                }
                let addr = if p == b'@' { Addr::AT } else { Addr::CARET };
                if line.words.iter().any(|w| w.addr == addr) {
                    return Err(syntax(Span::new(at, r.i), "one word per letter in a block"));
                }
                line.words.push(Word {
                    addr,
                    value: v,
                    point: v.fract() != 0.0,
                    span: Span::new(at, r.i),
                });
            }
            _ => {
                return Err(syntax(
                    Span::new(at, at + 1),
                    "a word, a parameter setting or a comment",
                ));
            }
        }
    }
}

/// E101 at a `(` inside a `( )` comment of `text` (which starts at byte
/// `start` of its line): rs274 stops with "Nested comment found".
fn paren_in_comment(text: &[u8], start: usize) -> Result<(), Diagnostic> {
    let mut open = None;
    for (k, c) in text.iter().enumerate() {
        match (c, open) {
            (b';', None) => return Ok(()),
            (b'(', None) => open = Some(k),
            (b'(', Some(_)) => {
                return Err(vcnc_syntax::diagnostics::paren_in_comment(Span::new(
                    start + k,
                    start + k + 1,
                )));
            }
            (b')', Some(_)) => open = None,
            _ => {}
        }
    }
    Ok(())
}

/// E601 in LinuxCNC's syntax.
fn syntax(span: Span, wanted: &str) -> Diagnostic {
    vcnc_syntax::diagnostics::macro_syntax(
        span,
        &format!("expected {wanted} here (LinuxCNC's parameters and expressions)"),
        "write e.g. #1 = [#2 * 3], #<depth> = 2, X[#1 + 5], or put text inside ( )",
    )
}

struct Reader<'a> {
    s: &'a [u8],
    i: usize,
    params: &'a Params,
    /// Values being read inside one another.
    depth: u8,
}

/// Most values inside one another (brackets, signs, `#`).
const MAX_DEPTH: u8 = 64;

/// Binary operators by precedence level, lowest first.
const LEVELS: &[&[&str]] = &[
    &["AND", "OR", "XOR"],
    &["EQ", "NE", "GT", "GE", "LT", "LE"],
    &["+", "-"],
    &["*", "/", "MOD"],
    &["**"],
];

impl Reader<'_> {
    fn peek(&self) -> u8 {
        self.s.get(self.i).copied().unwrap_or(0)
    }

    /// Skips blanks, `( )` comments and a `;` comment (to the end).
    fn blank(&mut self) {
        loop {
            match self.peek() {
                b' ' | b'\t' | b'\r' => self.i += 1,
                b'(' => match self.s[self.i..].iter().position(|c| *c == b')') {
                    Some(k) => self.i += k + 1,
                    None => self.i = self.s.len(),
                },
                b';' | b'\n' => self.i = self.s.len(),
                _ => return,
            }
        }
    }

    /// The keyword `k` (letters, any case) at the reader, consumed.
    fn keyword(&mut self, k: &str) -> bool {
        self.blank();
        let end = self.i + k.len();
        let here = self.s.get(self.i..end);
        let after = self.s.get(end).copied().unwrap_or(0);
        // `X` then `OR`: a letter word is no keyword's end.
        let word_end = !k.as_bytes()[0].is_ascii_alphabetic() || !after.is_ascii_alphabetic();
        if here.is_some_and(|h| h.eq_ignore_ascii_case(k.as_bytes())) && word_end {
            self.i = end;
            true
        } else {
            false
        }
    }

    /// A word's value: a number, a parameter, `[expr]`, a function or a
    /// signed one of these.
    fn value(&mut self) -> Result<f64, Diagnostic> {
        self.blank();
        let at = self.i;
        // Brackets, signs and `#` nest by recursion: bounded, so that a
        // line of 4,000 `[` alarms instead of overflowing the stack.
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(vcnc_syntax::diagnostics::macro_nesting(
                Span::new(at, at + 1),
                MAX_DEPTH,
            ));
        }
        let v = self.value_here(at);
        self.depth -= 1;
        v
    }

    fn value_here(&mut self, at: usize) -> Result<f64, Diagnostic> {
        match self.peek() {
            b'-' => {
                self.i += 1;
                Ok(-self.value()?)
            }
            b'+' => {
                self.i += 1;
                self.value()
            }
            b'[' => {
                self.i += 1;
                let v = self.expr()?;
                self.close(at)?;
                Ok(v)
            }
            b'#' => {
                let key = self.target()?;
                self.read(&key, Span::new(at, self.i))
            }
            b'0'..=b'9' | b'.' => self.number(),
            c if c.is_ascii_alphabetic() => self.function(at),
            _ => Err(syntax(Span::new(at, at + 1), "a value")),
        }
    }

    fn close(&mut self, open: usize) -> Result<(), Diagnostic> {
        self.blank();
        if self.peek() != b']' {
            return Err(syntax(Span::new(open, open + 1), "a `]` closing this `[`"));
        }
        self.i += 1;
        Ok(())
    }

    fn number(&mut self) -> Result<f64, Diagnostic> {
        let at = self.i;
        while matches!(self.peek(), b'0'..=b'9' | b'.') {
            self.i += 1;
        }
        std::str::from_utf8(&self.s[at..self.i])
            .ok()
            .and_then(|t| t.parse::<f64>().ok())
            .ok_or_else(|| syntax(Span::new(at, self.i), "a number"))
    }

    /// `#n`, `#[expr]`, `##n` or `#<name>`: which parameter.
    fn target(&mut self) -> Result<Key, Diagnostic> {
        let at = self.i;
        self.i += 1; // the `#`
        self.blank();
        if self.peek() == b'<' {
            let close = self.s[self.i..]
                .iter()
                .position(|c| *c == b'>')
                .ok_or_else(|| syntax(Span::new(at, self.i + 1), "a `>` closing the name"))?;
            let name: String = self.s[self.i + 1..self.i + close]
                .iter()
                .filter(|c| !c.is_ascii_whitespace())
                .map(|c| char::from(c.to_ascii_lowercase()))
                .collect();
            self.i += close + 1;
            if name.is_empty() {
                return Err(syntax(Span::new(at, self.i), "a parameter name"));
            }
            return Ok(Key::Named(name));
        }
        let n = self.value()?;
        let span = Span::new(at, self.i);
        if n.fract() != 0.0 || !(1.0..=LAST as f64).contains(&n) {
            return Err(alarms::no_such_variable(span, '#', n));
        }
        // 1..=LAST and whole: the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(Key::Numbered(n as usize))
    }

    fn read(&self, key: &Key, span: Span) -> Result<f64, Diagnostic> {
        match key {
            Key::Numbered(n) => Ok(self.params.numbered[*n]),
            Key::Named(name) => self
                .params
                .named
                .get(name)
                .copied()
                .ok_or_else(|| alarms::vacant_value(span, &format!("#<{name}>"))),
        }
    }

    /// A function call at `at`: `NAME[expr]`, `ATAN[y]/[x]`, `EXISTS[#<n>]`.
    fn function(&mut self, at: usize) -> Result<f64, Diagnostic> {
        let len = self.s[self.i..]
            .iter()
            .take_while(|c| c.is_ascii_alphabetic())
            .count();
        let name = String::from_utf8_lossy(&self.s[self.i..self.i + len]).to_ascii_uppercase();
        self.i += len;
        self.blank();
        if self.peek() != b'[' {
            return Err(syntax(
                Span::new(at, self.i),
                "a `[` after the function's name",
            ));
        }
        let open = self.i;
        self.i += 1;
        if name == "EXISTS" {
            self.blank();
            let key = self.target()?;
            self.close(open)?;
            return Ok(match key {
                Key::Named(n) => f64::from(u8::from(self.params.named.contains_key(&n))),
                Key::Numbered(_) => 1.0,
            });
        }
        let x = self.expr()?;
        self.close(open)?;
        let span = Span::new(at, self.i);
        let domain = |ok: bool, v: f64| {
            if ok {
                Ok(v)
            } else {
                Err(alarms::macro_domain(span, &format!("{name} of {x}")))
            }
        };
        match name.as_str() {
            "ABS" => Ok(x.abs()),
            "ACOS" => domain((-1.0..=1.0).contains(&x), x.acos().to_degrees()),
            "ASIN" => domain((-1.0..=1.0).contains(&x), x.asin().to_degrees()),
            "COS" => Ok(x.to_radians().cos()),
            "SIN" => Ok(x.to_radians().sin()),
            "TAN" => Ok(x.to_radians().tan()),
            "EXP" => Ok(x.exp()),
            "LN" => domain(x > 0.0, x.ln()),
            "SQRT" => domain(x >= 0.0, x.sqrt()),
            "FIX" => Ok(x.floor()),
            "FUP" => Ok(x.ceil()),
            // Half away from zero, as rs274.
            "ROUND" => Ok(x.round()),
            "ATAN" => {
                self.blank();
                if self.peek() != b'/' {
                    return Err(syntax(Span::new(at, self.i), "`/[x]` after ATAN[y]"));
                }
                self.i += 1;
                self.blank();
                if self.peek() != b'[' {
                    return Err(syntax(Span::new(self.i, self.i + 1), "`[x]`"));
                }
                let open = self.i;
                self.i += 1;
                let d = self.expr()?;
                self.close(open)?;
                Ok(x.atan2(d).to_degrees())
            }
            _ => Err(vcnc_syntax::diagnostics::unknown_function(
                Span::new(at, at + len),
                &name,
                false,
            )),
        }
    }

    /// An expression inside `[ ]`.
    fn expr(&mut self) -> Result<f64, Diagnostic> {
        self.level(0)
    }

    fn level(&mut self, n: usize) -> Result<f64, Diagnostic> {
        let Some(ops) = LEVELS.get(n) else {
            return self.value();
        };
        let mut left = self.level(n + 1)?;
        loop {
            let at = self.i;
            let Some(op) = ops.iter().copied().find(|op| {
                // `*` must not take the first half of `**`.
                let ok = self.keyword(op);
                if ok && *op == "*" && self.peek() == b'*' {
                    self.i -= 1;
                    return false;
                }
                ok
            }) else {
                return Ok(left);
            };
            let right = self.level(n + 1)?;
            left = apply(op, left, right, Span::new(at, self.i))?;
        }
    }
}

fn apply(op: &str, a: f64, b: f64, span: Span) -> Result<f64, Diagnostic> {
    let truth = |x: bool| f64::from(u8::from(x));
    Ok(match op {
        "**" => a.powf(b),
        "*" => a * b,
        "/" if b == 0.0 => return Err(alarms::division_by_zero(span)),
        "/" => a / b,
        "MOD" if b == 0.0 => return Err(alarms::division_by_zero(span)),
        // In [0, |b|), whatever the signs (rs274: -2 MOD 3 is 1, 2 MOD -3
        // is 2).
        "MOD" => a - b.abs() * (a / b.abs()).floor(),
        "+" => a + b,
        "-" => a - b,
        // rs274 compares for equality within 0.0001.
        "EQ" => truth((a - b).abs() < EQUAL),
        "NE" => truth((a - b).abs() >= EQUAL),
        "GT" => truth(a > b),
        "GE" => truth(a >= b),
        "LT" => truth(a < b),
        "LE" => truth(a <= b),
        "AND" => truth(a != 0.0 && b != 0.0),
        "OR" => truth(a != 0.0 || b != 0.0),
        _ => truth((a != 0.0) != (b != 0.0)),
    })
}

/// An O-word statement's keyword.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kw {
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
pub(crate) struct OStmt {
    pub label: String,
    pub kw: Kw,
    /// Byte index after the keyword.
    pub rest: usize,
}

/// The O-word statement of `text` (from `start`), if the line is one.
pub(crate) fn o_statement(text: &[u8], start: usize) -> Option<OStmt> {
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

/// The values in brackets after an O-word keyword (`[c]`, a call's
/// arguments `[1] [#2 * 3]`), read with `params`; no value: empty.
pub(crate) fn operands(text: &[u8], at: usize, params: &Params) -> Result<Vec<f64>, Diagnostic> {
    let mut r = Reader {
        s: text,
        i: at,
        params,
        depth: 0,
    };
    let mut out = Vec::new();
    loop {
        r.blank();
        match r.peek() {
            0 => return Ok(out),
            b'[' => {
                let open = r.i;
                r.i += 1;
                let v = r.expr()?;
                r.close(open)?;
                if !v.is_finite() {
                    return Err(alarms::macro_range(Span::new(open, r.i), "the value"));
                }
                out.push(v);
            }
            _ => return Err(syntax(Span::new(r.i, r.i + 1), "a value in [ ]")),
        }
    }
}

/// A subroutine's locals, kept while it runs: #1–#30 and the named
/// parameters without a leading `_`.
#[derive(Debug, Clone)]
pub(crate) struct Saved {
    numbered: [f64; 30],
    named: Vec<(String, f64)>,
}

impl Params {
    /// Enters a subroutine: its locals saved, #1… set to `args`, the rest
    /// of #1–#30 zero, no local named parameter.
    pub(crate) fn enter(&mut self, args: &[f64]) -> Saved {
        let mut numbered = [0.0; 30];
        numbered.copy_from_slice(&self.numbered[1..=30]);
        let named: Vec<(String, f64)> = self
            .named
            .iter()
            .filter(|(k, _)| !k.starts_with('_'))
            .map(|(k, v)| (k.clone(), *v))
            .collect();
        self.named.retain(|k, _| k.starts_with('_'));
        for (slot, v) in self.numbered[1..=30].iter_mut().enumerate() {
            *v = args.get(slot).copied().unwrap_or(0.0);
        }
        Saved { numbered, named }
    }

    /// Leaves a subroutine without a return: its locals restored and
    /// `#<_value>` untouched (a G7x profile's `o<Q> sub`, which the cycle
    /// reads rather than calls).
    pub(crate) fn restore(&mut self, saved: Saved) {
        self.numbered[1..=30].copy_from_slice(&saved.numbered);
        self.named.retain(|k, _| k.starts_with('_'));
        self.named.extend(saved.named);
    }

    /// Leaves a subroutine: its locals restored, the value it returned
    /// (if any) in `#<_value>`.
    pub(crate) fn leave(&mut self, saved: Saved, value: Option<f64>) {
        self.numbered[1..=30].copy_from_slice(&saved.numbered);
        self.named.retain(|k, _| k.starts_with('_'));
        self.named.extend(saved.named);
        self.named.insert(
            "_value_returned".into(),
            f64::from(u8::from(value.is_some())),
        );
        // A return without a value clears the last one (rs274).
        self.named.insert("_value".into(), value.unwrap_or(0.0));
    }
}
