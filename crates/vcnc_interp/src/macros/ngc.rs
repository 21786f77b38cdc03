//! LinuxCNC's parameters (`--dialect linuxcnc`): the table a program's
//! `#1` and `#<name>` live in, and what a line with parameters does.
//! `vcnc_syntax::macros::parse_ngc_line` parses such a line into the
//! compiled form of every macro language; the one evaluator (`eval.rs`)
//! reads its values under LinuxCNC's arithmetic; here the line's words
//! and settings are checked and its settings applied.
//!
//! ```text
//!   #1 = 2   #<depth> = [#1 * 1.5]           (settings: after the line)
//!   G1 X[#1 + 10] Z-#<depth> F#<_rate>       (values: with the old ones)
//!        └─ G1 X12 Z-3 F… ──▶ the block pipeline
//! ```
//!
//! Every parameter holds a number (an unset numbered one reads 0, an
//! unset named one alarms). Named parameters without a leading `_` are
//! local to an O-word subroutine (`exec.rs` saves them at its call,
//! restores them at its return); the others live for the whole program.
//! System parameters (#5061–#5428: probe results, offsets, the position)
//! read what the program wrote, 0 otherwise.

use super::Evaluator;
use crate::alarms;
use std::collections::HashMap;
use vcnc_syntax::macros::{Expr, Lang, LineItem, MValue, Target, Value, ngc_expected};
use vcnc_syntax::{Addr, Diagnostic, Span, Word};

/// The highest numbered parameter (LinuxCNC's 5601).
const LAST: usize = 5601;

/// A word's value that the lexer would take (at most 9 digits before the
/// point): beyond, E103, as written literally.
const MAX_VALUE: f64 = 1e9;

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
pub(crate) enum Key {
    Numbered(usize),
    Named(String),
}

/// A line read: its words (values evaluated) and its settings.
#[derive(Debug, Default)]
pub(crate) struct Line {
    pub words: Vec<Word>,
    pub sets: Vec<(Key, f64)>,
}

impl Params {
    /// Numbered parameter `n` (1..=5601, checked by the caller).
    pub(crate) fn numbered(&self, n: usize) -> f64 {
        self.numbered.get(n).copied().unwrap_or(0.0)
    }

    /// Named parameter `name`, `None` when never set.
    pub(crate) fn named(&self, name: &str) -> Option<f64> {
        self.named.get(name).copied()
    }

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

/// The parameter number `n` names, checked: whole and 1..=5601.
pub(crate) fn param_number(n: f64, span: Span) -> Result<usize, Diagnostic> {
    if n.fract() != 0.0 || !(1.0..=LAST as f64).contains(&n) {
        return Err(alarms::no_such_variable(span, '#', n));
    }
    // 1..=LAST and whole: the cast is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok(n as usize)
}

/// A word of value `v` after `words`: a value the lexer would take (at
/// most 9 digits before the point), and G and M codes may repeat (`G1 G91
/// Z-#1`); other letters once, as the lexer wants.
fn ngc_word(words: &[Word], addr: Addr, v: f64, span: Span) -> Result<Word, Diagnostic> {
    let once = || ngc_expected(span, "one word per letter in a block");
    match addr.as_letter() {
        Some(l) => {
            if !v.is_finite() {
                return Err(alarms::macro_range(span, "the word's value"));
            }
            if v.abs() >= MAX_VALUE {
                return Err(vcnc_syntax::diagnostics::number_out_of_range(
                    span,
                    char::from(l),
                ));
            }
            if !matches!(l, b'G' | b'M') && words.iter().any(|w| w.addr.as_letter() == Some(l)) {
                return Err(once());
            }
        }
        // The polar words `@` and `^`.
        None => {
            if !v.is_finite() || v.abs() >= MAX_VALUE {
                return Err(alarms::macro_range(span, "the word's value"));
            }
            if words.iter().any(|w| w.addr == addr) {
                return Err(once());
            }
        }
    }
    Ok(Word {
        addr,
        value: v,
        // Whole units either way; a fraction in an M or T word still
        // alarms as written with a point.
        point: v.fract() != 0.0,
        span,
    })
}

/// A value of LinuxCNC's arithmetic (`eval.rs` asks): rs274's rules.
#[inline(never)]
pub(crate) fn ngc_binary(
    op: vcnc_syntax::macros::BinOp,
    a: f64,
    b: f64,
    span: Span,
) -> Result<Value, Diagnostic> {
    use vcnc_syntax::macros::BinOp;
    let truth = |x: bool| f64::from(u8::from(x));
    Ok(Value::Double(match op {
        BinOp::Pow => a.powf(b),
        BinOp::Mul => a * b,
        BinOp::Div | BinOp::Mod if b == 0.0 => return Err(alarms::division_by_zero(span)),
        BinOp::Div => a / b,
        // In [0, |b|), whatever the signs (rs274: -2 MOD 3 is 1, 2 MOD -3
        // is 2).
        BinOp::Mod => a - b.abs() * (a / b.abs()).floor(),
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        // rs274 compares for equality within 0.0001.
        BinOp::Eq => truth((a - b).abs() < EQUAL),
        BinOp::Ne => truth((a - b).abs() >= EQUAL),
        BinOp::Gt => truth(a > b),
        BinOp::Ge => truth(a >= b),
        BinOp::Lt => truth(a < b),
        BinOp::Le => truth(a <= b),
        // Logical, not bitwise.
        BinOp::And => truth(a != 0.0 && b != 0.0),
        BinOp::Or => truth(a != 0.0 || b != 0.0),
        BinOp::Xor => truth((a != 0.0) != (b != 0.0)),
    }))
}

/// rs274's tolerance of EQ and NE.
const EQUAL: f64 = 1e-4;

/// rs274's functions: angles in degrees, FIX and FUP floor and ceiling,
/// ROUND half away from zero, `ATAN[y]/[x]` the full-circle angle (±180°);
/// results are not checked here (a word or a setting that gets an
/// infinite value alarms).
#[inline(never)]
pub(crate) fn ngc_function(
    f: vcnc_syntax::macros::Func,
    x: f64,
    y: f64,
    span: Span,
) -> Result<Value, Diagnostic> {
    use vcnc_syntax::macros::Func;
    let domain = |ok: bool, name: &str, v: f64| {
        if ok {
            Ok(Value::Double(v))
        } else {
            Err(alarms::macro_domain(span, &format!("{name} of {x}")))
        }
    };
    match f {
        Func::Abs => domain(true, "ABS", x.abs()),
        Func::Acos => domain((-1.0..=1.0).contains(&x), "ACOS", x.acos().to_degrees()),
        Func::Asin => domain((-1.0..=1.0).contains(&x), "ASIN", x.asin().to_degrees()),
        Func::Cos => domain(true, "COS", x.to_radians().cos()),
        Func::Sin => domain(true, "SIN", x.to_radians().sin()),
        Func::Tan => domain(true, "TAN", x.to_radians().tan()),
        Func::Exp => domain(true, "EXP", x.exp()),
        Func::Ln => domain(x > 0.0, "LN", x.ln()),
        Func::Sqrt => domain(x >= 0.0, "SQRT", x.sqrt()),
        Func::Fix => domain(true, "FIX", x.floor()),
        Func::Fup => domain(true, "FUP", x.ceil()),
        Func::Round => domain(true, "ROUND", x.round()),
        Func::Atan => domain(true, "ATAN", x.atan2(y).to_degrees()),
        // The parser gives LinuxCNC no other function (`NGC_FUNCS`), and
        // `Evaluator::call_function` answers EXISTS before.
        Func::Atan2
        | Func::Pow
        | Func::Max
        | Func::Min
        | Func::Sign
        | Func::Ceil
        | Func::Floor
        | Func::Std
        | Func::StdAx
        | Func::GetArg
        | Func::Push
        | Func::Pop
        | Func::StkTop
        | Func::Alarm
        | Func::Msg
        | Func::Wait
        | Func::Sleep
        | Func::Param
        | Func::Draw
        | Func::Exists => Ok(Value::Null),
    }
}

impl<'a> Evaluator<'_, 'a> {
    fn ngc_params(&mut self) -> &mut Params {
        self.macros.ngc.get_or_insert_with(Box::default)
    }

    /// `#n` read under LinuxCNC's table.
    pub(crate) fn ngc_numbered(&mut self, n: f64, span: Span) -> Result<f64, Diagnostic> {
        let n = param_number(n, span)?;
        Ok(self.ngc_params().numbered(n))
    }

    /// `#<name>` read: an unset name alarms.
    pub(crate) fn ngc_named(&mut self, name: &str, span: Span) -> Result<f64, Diagnostic> {
        self.ngc_params()
            .named(name)
            .ok_or_else(|| alarms::vacant_value(span, &format!("#<{name}>")))
    }

    /// Whether `#<name>` is set (EXISTS).
    pub(crate) fn ngc_exists(&mut self, name: &str) -> bool {
        self.ngc_params().named(name).is_some()
    }

    /// A value of LinuxCNC's expressions (every one is a number).
    fn ngc_eval(&mut self, e: &Expr) -> Result<f64, Diagnostic> {
        Ok(self.eval(e, Lang::Ngc)?.number().unwrap_or(0.0))
    }

    /// Evaluates a parsed line's items in their order with the parameters
    /// as they were before it: its words, checked as the lexer would
    /// check them, and its settings (applied later by `Params::commit`).
    pub(crate) fn ngc_line(&mut self, items: &[LineItem]) -> Result<Line, Diagnostic> {
        let mut line = Line::default();
        for item in items {
            match item {
                LineItem::Set {
                    target,
                    value,
                    span,
                } => {
                    let key = self.ngc_key(target)?;
                    let v = self.ngc_eval(value)?;
                    if !v.is_finite() {
                        return Err(alarms::macro_range(*span, "the parameter's value"));
                    }
                    line.sets.push((key, v));
                }
                LineItem::Word(w) => {
                    let v = match &w.value {
                        MValue::Literal { value, .. } => *value,
                        MValue::Expr(e) => self.ngc_eval(e)?,
                    };
                    line.words.push(ngc_word(&line.words, w.addr, v, w.span)?);
                }
            }
        }
        Ok(line)
    }

    /// The parameter a setting writes.
    fn ngc_key(&mut self, target: &Target) -> Result<Key, Diagnostic> {
        match target {
            Target::Named(name, span) => {
                if READ_ONLY.contains(&&**name) {
                    return Err(alarms::read_only_named(*span, name));
                }
                Ok(Key::Named(name.to_string()))
            }
            Target::Fixed(_, n, span) => Ok(Key::Numbered(param_number(f64::from(*n), *span)?)),
            Target::Indirect(_, e, span) => {
                let n = self.ngc_eval(e)?;
                Ok(Key::Numbered(param_number(n, *span)?))
            }
        }
    }

    /// The values of an O-word statement's operands (`[c]`, a call's
    /// arguments `[1] [#2 * 3]`), in order; each must be finite.
    pub(crate) fn ngc_values(&mut self, operands: &[Expr]) -> Result<Vec<f64>, Diagnostic> {
        let mut out = Vec::with_capacity(operands.len());
        for e in operands {
            let v = self.ngc_eval(e)?;
            if !v.is_finite() {
                return Err(alarms::macro_range(e.span, "the value"));
            }
            out.push(v);
        }
        Ok(out)
    }
}
