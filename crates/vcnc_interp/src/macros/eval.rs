//! The expression evaluator: postfix ops over a reused value stack.
//!
//! Rules (Fanuc 0i where the Syntec manual is silent; `docs/macros.md`):
//!
//! ```text
//!   vacant (#0)   a bare reference keeps it (#2 = #1, X-#1 omits X); + − * / MOD,
//!                 AND OR XOR, functions and < > <= >= read it as 0; EQ / NE (=, <>)
//!                 tell it from 0: vacant EQ #0 is true, vacant EQ 0 is false
//!   Macro B       every number is real; / is real division; MOD, AND, OR, XOR
//!                 work on the integer portions (Haas's manual); results 1.0/0.0
//!   Syntec        Long op Long is Long (/ truncates toward zero, MOD and the
//!                 bit operators need Longs: E610), anything with a Double is Double
//!   errors        division by zero E608; a result that is not finite, a Long
//!                 overflow, SQRT/LN/ASIN/ACOS/POW out of their domain E609
//! ```
//!
//! What differs between the languages is data, [`Arith`], read through
//! [`arith`]: the evaluator never tests a language's name.
//!
//! Angles are degrees. Reads and writes of variables go through
//! [`Evaluator::read_var`] and [`Evaluator::write_var`], which know the
//! controller's variable table.

use super::Macros;
use super::vars::Slot;
use super::{UNSET_LIMIT, UnsetRead};
use crate::alarms;
use crate::config::Config;
use crate::flow::Flow;
use crate::interpreter::{Locator, Machining};
use crate::motion::stage::Stage;
use crate::state::{State, Tables};
use vcnc_syntax::macros::{Arg, BinOp, Expr, Func, Lang, OpCode, Value, VarKind};
use vcnc_syntax::{Diagnostic, Span};

/// What an operator does beyond `+ - * /` and the comparisons.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Operators {
    /// MOD, AND, OR, XOR on the integer portions of reals; EQ exact, a
    /// vacant operand told from 0 (Fanuc 0i, Haas's manual).
    IntegerPortions,
    /// Long op Long is Long; MOD and the bit operators need Longs (E610)
    /// (Syntec §3.4–3.5).
    Typed,
    /// rs274's: `**`, MOD in [0, |divisor|), AND OR XOR logical, EQ and NE
    /// within 0.0001, results unchecked until a word or setting takes them.
    Rs274,
}

/// Which functions a language's names stand for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Functions {
    /// Checked domains, exact at multiples of 90°, FIX/FUP toward and away
    /// from zero (Fanuc 0i, Syntec).
    Checked,
    /// rs274's: FIX/FUP floor and ceiling, `ATAN[y]/[x]` ±180°, results
    /// unchecked (`ngc.rs`).
    Rs274,
}

/// Where a `#n` lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Table {
    /// The controller's variable table (`vars.rs`, `system.rs`).
    Variables,
    /// LinuxCNC's parameters (#1–#5601, unset 0, and `#<name>`: `ngc.rs`).
    Parameters,
}

/// A language's arithmetic, as data: the evaluator asks these, never the
/// language's name (`docs/macros.md`, "Expressions").
#[derive(Debug)]
pub(crate) struct Arith {
    /// A number written without a point, a truth value and a whole-number
    /// function's result are Longs (Syntec); elsewhere every number is
    /// real.
    pub longs: bool,
    pub operators: Operators,
    pub functions: Functions,
    /// ASIN and the two-argument ATAN answer 0°…360° (Fanuc 0i with
    /// parameter NAT = 0) rather than ±.
    pub positive_angles: bool,
    /// POW of a negative base alarms even with a whole exponent (Syntec).
    pub negative_base_alarms: bool,
    pub table: Table,
    /// ROUND in an NC address rounds to the address's least input
    /// increment (Fanuc 0i).
    pub round_in_increments: bool,
    /// A GOTO into a DO–END range from outside it alarms E614 (Fanuc 0i;
    /// Syntec §4.8 only advises against it).
    pub goto_into_loop_alarms: bool,
}

const MACRO_B: Arith = Arith {
    longs: false,
    operators: Operators::IntegerPortions,
    functions: Functions::Checked,
    positive_angles: true,
    negative_base_alarms: false,
    table: Table::Variables,
    round_in_increments: true,
    goto_into_loop_alarms: true,
};

const SYNTEC: Arith = Arith {
    longs: true,
    operators: Operators::Typed,
    functions: Functions::Checked,
    positive_angles: false,
    negative_base_alarms: true,
    table: Table::Variables,
    round_in_increments: false,
    goto_into_loop_alarms: false,
};

const NGC: Arith = Arith {
    longs: false,
    operators: Operators::Rs274,
    functions: Functions::Rs274,
    positive_angles: false,
    negative_base_alarms: false,
    table: Table::Parameters,
    round_in_increments: false,
    goto_into_loop_alarms: false,
};

/// The arithmetic of `lang`: the one place a language's name is read.
#[inline]
pub(crate) fn arith(lang: Lang) -> &'static Arith {
    match lang {
        Lang::MacroB => &MACRO_B,
        Lang::Syntec => &SYNTEC,
        Lang::Ngc => &NGC,
    }
}

/// Values an i64 holds exactly enough for bit operations and Longs.
const I64_LIMIT: f64 = 9.2e18;

/// The integer portion of `x` as an i64 (Macro B's MOD and bit operators).
fn integer_part(x: f64, span: Span) -> Result<i64, Diagnostic> {
    let t = x.trunc();
    if t.abs() >= I64_LIMIT {
        return Err(alarms::macro_range(
            span,
            "the value is too large for an integer operation",
        ));
    }
    // Whole and within ±2^63: exact.
    #[allow(clippy::cast_possible_truncation)]
    Ok(t as i64)
}

/// A real number result, checked.
fn real(x: f64, span: Span) -> Result<Value, Diagnostic> {
    if x.is_finite() {
        Ok(Value::Double(x))
    } else {
        Err(alarms::macro_range(
            span,
            "the result is not a finite number",
        ))
    }
}

fn long(x: Option<i64>, span: Span) -> Result<Value, Diagnostic> {
    x.map(Value::Long)
        .ok_or_else(|| alarms::macro_range(span, "the result overflows a Long"))
}

fn truth(b: bool, rules: &Arith) -> Value {
    if rules.longs {
        Value::Long(i64::from(b))
    } else {
        Value::Double(f64::from(u8::from(b)))
    }
}

/// A vacant operand of an operation reads as 0.
fn operand(v: Value) -> Value {
    match v {
        Value::Null => Value::Long(0),
        v => v,
    }
}

fn num(v: Value) -> f64 {
    v.number().unwrap_or(0.0)
}

/// Sine and cosine of `deg` degrees, exact at multiples of 90°.
fn sin_cos_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (0.0, 1.0)
    } else if r == 90.0 {
        (1.0, 0.0)
    } else if r == 180.0 {
        (0.0, -1.0)
    } else if r == 270.0 {
        (-1.0, 0.0)
    } else {
        r.to_radians().sin_cos()
    }
}

/// Half away from zero.
fn round_half_away(x: f64) -> f64 {
    x.round()
}

/// `x` rounded half away from zero to a whole number of increments
/// (`per_unit` of them per unit). A value written in decimal that lands
/// within a millionth of an increment of a half counts as the half: 1.2345
/// is 1.235 at 0.001, as the control computes it in decimal.
fn round_to_increment(x: f64, per_unit: f64) -> f64 {
    let y = x * per_unit;
    let half = ((y - y.trunc()).abs() - 0.5).abs() < 1e-6;
    let n = if half {
        y.trunc() + y.signum()
    } else {
        round_half_away(y)
    };
    n / per_unit
}

/// Applies a binary operator.
pub(crate) fn binary(
    lang: Lang,
    op: BinOp,
    a: Value,
    b: Value,
    span: Span,
) -> Result<Value, Diagnostic> {
    let rules = arith(lang);
    if rules.operators == Operators::Rs274 {
        return super::ngc::ngc_binary(op, num(a), num(b), span);
    }
    fanuc_or_typed(rules, op, a, b, span)
}

/// [`binary`] under `IntegerPortions` or `Typed` operators (the
/// evaluator's loop has sent rs274's elsewhere).
#[inline]
fn fanuc_or_typed(
    rules: &Arith,
    op: BinOp,
    a: Value,
    b: Value,
    span: Span,
) -> Result<Value, Diagnostic> {
    match op {
        BinOp::Eq | BinOp::Ne => {
            let equal = match (a, b) {
                (Value::Null, Value::Null) => true,
                (Value::Null, _) | (_, Value::Null) => false,
                (x, y) => num(x) == num(y),
            };
            return Ok(truth(equal == (op == BinOp::Eq), rules));
        }
        BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
            let (x, y) = (num(a), num(b));
            let holds = match op {
                BinOp::Lt => x < y,
                BinOp::Le => x <= y,
                BinOp::Gt => x > y,
                _ => x >= y,
            };
            return Ok(truth(holds, rules));
        }
        _ => {}
    }
    let (a, b) = (operand(a), operand(b));
    match rules.operators {
        Operators::Typed => syntec_arith(op, a, b, span),
        Operators::IntegerPortions | Operators::Rs274 => macro_b_arith(op, num(a), num(b), span),
    }
}

fn macro_b_arith(op: BinOp, x: f64, y: f64, span: Span) -> Result<Value, Diagnostic> {
    match op {
        BinOp::Add => real(x + y, span),
        BinOp::Sub => real(x - y, span),
        BinOp::Mul => real(x * y, span),
        BinOp::Div if y == 0.0 => Err(alarms::division_by_zero(span)),
        BinOp::Div => real(x / y, span),
        BinOp::Mod | BinOp::And | BinOp::Or | BinOp::Xor => {
            let (i, j) = (integer_part(x, span)?, integer_part(y, span)?);
            let r = match op {
                BinOp::Mod if j == 0 => return Err(alarms::division_by_zero(span)),
                BinOp::Mod => i.wrapping_rem(j),
                BinOp::And => i & j,
                BinOp::Or => i | j,
                _ => i ^ j,
            };
            // |r| < 2^63 and these small integers are what programs use.
            #[allow(clippy::cast_precision_loss)]
            real(r as f64, span)
        }
        _ => Ok(Value::Null),
    }
}

fn syntec_arith(op: BinOp, a: Value, b: Value, span: Span) -> Result<Value, Diagnostic> {
    if let (Value::Long(i), Value::Long(j)) = (a, b) {
        return match op {
            BinOp::Add => long(i.checked_add(j), span),
            BinOp::Sub => long(i.checked_sub(j), span),
            BinOp::Mul => long(i.checked_mul(j), span),
            BinOp::Div | BinOp::Mod if j == 0 => Err(alarms::division_by_zero(span)),
            // Truncates toward zero (C, IEC 61131 DIV).
            BinOp::Div => long(i.checked_div(j), span),
            BinOp::Mod => long(i.checked_rem(j), span),
            BinOp::And => Ok(Value::Long(i & j)),
            BinOp::Or => Ok(Value::Long(i | j)),
            BinOp::Xor => Ok(Value::Long(i ^ j)),
            _ => Ok(Value::Null),
        };
    }
    let (x, y) = (num(a), num(b));
    match op {
        BinOp::Add => real(x + y, span),
        BinOp::Sub => real(x - y, span),
        BinOp::Mul => real(x * y, span),
        BinOp::Div if y == 0.0 => Err(alarms::division_by_zero(span)),
        BinOp::Div => real(x / y, span),
        BinOp::Mod | BinOp::And | BinOp::Or | BinOp::Xor => {
            Err(alarms::type_mismatch(span, op_name(op)))
        }
        _ => Ok(Value::Null),
    }
}

fn op_name(op: BinOp) -> &'static str {
    match op {
        BinOp::Mod => "MOD",
        BinOp::And => "AND",
        BinOp::Or => "OR",
        _ => "XOR",
    }
}

/// Unary minus: a vacant operand stays vacant (`X-#1` omits X).
pub(crate) fn negate(v: Value, span: Span) -> Result<Value, Diagnostic> {
    match v {
        Value::Null => Ok(Value::Null),
        Value::Long(i) => long(i.checked_neg(), span),
        Value::Double(x) => Ok(Value::Double(-x)),
    }
}

/// A number result of `lang`'s type for a whole-number function.
fn whole_result(x: f64, lang: Lang, span: Span) -> Result<Value, Diagnostic> {
    if !arith(lang).longs {
        real(x, span)
    } else if x.abs() < I64_LIMIT {
        // Whole (rounded above) and in range: exact.
        #[allow(clippy::cast_possible_truncation)]
        Ok(Value::Long(x as i64))
    } else {
        Err(alarms::macro_range(span, "the result overflows a Long"))
    }
}

/// A pure numeric function of one or two arguments.
pub(crate) fn function(
    lang: Lang,
    f: Func,
    args: &[Value],
    span: Span,
) -> Result<Value, Diagnostic> {
    let x = args.first().copied().map_or(0.0, num);
    let y = args.get(1).copied().map_or(0.0, num);
    let rules = arith(lang);
    if rules.functions == Functions::Rs274 {
        return super::ngc::ngc_function(f, x, y, span);
    }
    let domain = |what: &str| Err(alarms::macro_domain(span, what));
    match f {
        Func::Sin => real(sin_cos_deg(x).0, span),
        Func::Cos => real(sin_cos_deg(x).1, span),
        Func::Tan => {
            let (s, c) = sin_cos_deg(x);
            if c.abs() < 1e-12 {
                return domain("TAN of an odd multiple of 90°");
            }
            real(s / c, span)
        }
        Func::Asin | Func::Acos if !(-1.0..=1.0).contains(&x) => {
            domain("ASIN and ACOS take values from -1 to 1")
        }
        Func::Asin => {
            let d = x.asin().to_degrees();
            // Fanuc 0i (parameter NAT = 0) answers 270°…90°.
            real(
                if rules.positive_angles && d < 0.0 {
                    d + 360.0
                } else {
                    d
                },
                span,
            )
        }
        Func::Acos => real(x.acos().to_degrees(), span),
        Func::Atan | Func::Atan2 if args.len() == 2 => {
            if x == 0.0 && y == 0.0 {
                return domain("the arctangent of 0/0");
            }
            let d = x.atan2(y).to_degrees();
            // Fanuc 0i (NAT = 0): 0°…360°; Syntec ATAN2: ±180°.
            real(
                if rules.positive_angles && d < 0.0 {
                    d + 360.0
                } else {
                    d
                },
                span,
            )
        }
        Func::Atan | Func::Atan2 => real(x.atan().to_degrees(), span),
        Func::Sqrt if x < 0.0 => domain("SQRT of a negative number"),
        Func::Sqrt => real(x.sqrt(), span),
        Func::Abs => match args.first() {
            Some(Value::Long(i)) if rules.longs => long(i.checked_abs(), span),
            _ => real(x.abs(), span),
        },
        Func::Round => whole_result(round_half_away(x), lang, span),
        Func::Fix => whole_result(x.trunc(), lang, span),
        Func::Fup => whole_result(
            if x.fract() == 0.0 {
                x
            } else {
                x.trunc() + x.signum()
            },
            lang,
            span,
        ),
        Func::Ceil => whole_result(x.ceil(), lang, span),
        Func::Floor => whole_result(x.floor(), lang, span),
        Func::Sign => whole_result(
            if x > 0.0 {
                1.0
            } else if x < 0.0 {
                -1.0
            } else {
                0.0
            },
            lang,
            span,
        ),
        Func::Ln if x <= 0.0 => domain("LN of a number that is not positive"),
        Func::Ln => real(x.ln(), span),
        Func::Exp => real(x.exp(), span),
        Func::Pow if x < 0.0 && (rules.negative_base_alarms || y.fract() != 0.0) => {
            domain("POW of a negative base")
        }
        Func::Pow => real(x.powf(y), span),
        Func::Max | Func::Min => {
            let (a, b) = (
                operand(args.first().copied().unwrap_or_default()),
                operand(args.get(1).copied().unwrap_or_default()),
            );
            let pick_a = if f == Func::Max {
                num(a) >= num(b)
            } else {
                num(a) <= num(b)
            };
            match (a, b) {
                (Value::Long(_), Value::Long(_)) => Ok(if pick_a { a } else { b }),
                _ => real(if pick_a { num(a) } else { num(b) }, span),
            }
        }
        // Not pure: `Evaluator::call_function` answers them before.
        Func::Std
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

/// The macro evaluator's view of the interpreter: the variables it owns
/// (`Macros`); the modal state, the offset tables and the configuration
/// that system variables read and write; the stage a message goes to; the
/// program flow for the call level's locals and the block's location.
/// Borrowed from the [`Interpreter`] for one expression or assignment; the
/// run loop's counters and the program-point style stay out of its reach.
///
/// [`Interpreter`]: crate::interpreter::Interpreter
pub(crate) struct Evaluator<'r, 'a> {
    pub(crate) cfg: &'r Config<'a>,
    pub(crate) state: &'r mut State,
    pub(crate) tables: &'r mut Tables,
    pub(crate) stage: &'r mut Stage,
    pub(crate) macros: &'r mut Macros,
    pub(crate) flow: &'r mut Flow,
}

impl<'a> Evaluator<'_, 'a> {
    /// The machine's side, for a message the evaluator emits.
    pub(crate) fn machining(&mut self) -> Machining<'_, 'a> {
        Machining {
            cfg: self.cfg,
            state: self.state,
            tables: self.tables,
            stage: self.stage,
            at: Locator::new(self.flow, &self.macros.span_map),
        }
    }
}

/// A value stored in a Long-only variable (Syntec's PLC registers):
/// Doubles are truncated toward zero, as a C conversion does.
fn to_long(v: Value, span: Span) -> Result<Value, Diagnostic> {
    match v {
        Value::Double(x) => Ok(Value::Long(integer_part(x, span)?)),
        v => Ok(v),
    }
}

/// The name of `OpCode::Named(i)` in `e`.
fn text_name(e: &Expr, i: u16) -> &str {
    match e.texts.get(usize::from(i)).and_then(|t| t.first()) {
        Some(Arg::Name(name)) => name,
        _ => "",
    }
}

/// The text arguments of a call, joined.
fn text_arg(texts: &[Arg]) -> String {
    texts
        .iter()
        .filter_map(|a| match a {
            Arg::Str(s) => Some(s.to_string()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join(" ")
}

impl<'a> Evaluator<'_, 'a> {
    /// Evaluates `e` written in `lang`.
    pub(crate) fn eval(&mut self, e: &Expr, lang: Lang) -> Result<Value, Diagnostic> {
        let mut stack = std::mem::take(&mut self.macros.eval_stack);
        stack.clear();
        let result = self.eval_ops(e, lang, &mut stack);
        self.macros.eval_stack = stack;
        result
    }

    fn eval_ops(&mut self, e: &Expr, lang: Lang, st: &mut Vec<Value>) -> Result<Value, Diagnostic> {
        let rules = arith(lang);
        let rs274 = rules.operators == Operators::Rs274;
        let parameters = rules.table == Table::Parameters;
        for op in &e.ops {
            let span = op.span;
            match &op.code {
                OpCode::Num(v) => st.push(*v),
                OpCode::Var(kind, n) => {
                    let v = if parameters {
                        Value::Double(self.ngc_numbered(f64::from(*n), span)?)
                    } else {
                        self.read_var(*kind, *n, span)?
                    };
                    st.push(v);
                }
                OpCode::VarAt(kind) => {
                    let index = st.pop().unwrap_or_default();
                    let v = if parameters {
                        Value::Double(self.ngc_numbered(num(index), span)?)
                    } else {
                        let n = self.var_number(*kind, index, span)?;
                        self.read_var(*kind, n, span)?
                    };
                    st.push(v);
                }
                OpCode::Named(i) => {
                    let v = self.ngc_named(text_name(e, *i), span)?;
                    st.push(Value::Double(v));
                }
                OpCode::Neg => {
                    let v = negate(st.pop().unwrap_or_default(), span)?;
                    st.push(v);
                }
                OpCode::Pos => {}
                OpCode::Not => {
                    let v = match st.pop().unwrap_or_default() {
                        Value::Null => Value::Null,
                        Value::Long(i) => Value::Long(!i),
                        Value::Double(_) => return Err(alarms::type_mismatch(span, "NOT")),
                    };
                    st.push(v);
                }
                OpCode::Bin(b) => {
                    let y = st.pop().unwrap_or_default();
                    let x = st.pop().unwrap_or_default();
                    let v = if rs274 {
                        super::ngc::ngc_binary(*b, num(x), num(y), span)?
                    } else {
                        fanuc_or_typed(rules, *b, x, y, span)?
                    };
                    st.push(v);
                }
                OpCode::Call(f, argc) => {
                    let at = st.len().saturating_sub(usize::from(*argc));
                    let v = self.call_function(lang, *f, &st[at..], &[], span)?;
                    st.truncate(at);
                    st.push(v);
                }
                OpCode::CallText(f, argc, i) => {
                    let at = st.len().saturating_sub(usize::from(*argc));
                    let texts = e.texts.get(usize::from(*i)).map_or(&[][..], Vec::as_slice);
                    let v = self.call_function(lang, *f, &st[at..], texts, span)?;
                    st.truncate(at);
                    st.push(v);
                }
            }
        }
        Ok(st.pop().unwrap_or_default())
    }

    /// A variable number computed by `#[e]`: whole and not vacant.
    pub(crate) fn var_number(
        &self,
        kind: VarKind,
        v: Value,
        span: Span,
    ) -> Result<u32, Diagnostic> {
        let Some(x) = v.number() else {
            return Err(alarms::vacant_value(span, "a variable number"));
        };
        let r = round_half_away(x);
        if (x - r).abs() > 1e-9 || !(0.0..=f64::from(u32::MAX)).contains(&r) {
            return Err(alarms::no_such_variable(span, kind.sigil(), x));
        }
        // Whole and within u32, checked above.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        Ok(r as u32)
    }

    /// Functions with effects or interpreter state; pure ones go to
    /// [`function`].
    fn call_function(
        &mut self,
        lang: Lang,
        f: Func,
        args: &[Value],
        texts: &[Arg],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        match f {
            Func::Push => {
                if self.macros.stack.len() >= super::STACK_LIMIT {
                    return Err(alarms::macro_stack_full(span, super::STACK_LIMIT));
                }
                let v = args.first().copied().unwrap_or_default();
                self.macros.stack.push(v);
                Ok(v)
            }
            Func::Pop => Ok(self.macros.stack.pop().unwrap_or_default()),
            Func::StkTop => {
                let n = args
                    .first()
                    .copied()
                    .and_then(Value::number)
                    .unwrap_or(-1.0);
                let depth = self.macros.stack.len();
                // A whole index within the stack, else vacant.
                let i = (n >= 0.0 && n.fract() == 0.0 && n < depth as f64).then(|| {
                    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                    let k = n as usize;
                    depth - 1 - k
                });
                Ok(i.and_then(|i| self.macros.stack.get(i).copied())
                    .unwrap_or_default())
            }
            Func::Std | Func::StdAx => self.standardize(f, args, texts, span),
            Func::GetArg => Ok(self.get_arg(texts)),
            Func::Alarm => {
                let id = args.first().copied().and_then(Value::number).unwrap_or(0.0);
                Err(alarms::program_alarm(span, id, &text_arg(texts)))
            }
            Func::Msg => {
                let id = args.first().copied().and_then(Value::number);
                let mut text = text_arg(texts);
                if let Some(id) = id {
                    text = if text.is_empty() {
                        format!("{id}")
                    } else {
                        format!("{id}: {text}")
                    };
                }
                self.message(text, false);
                Ok(Value::Null)
            }
            Func::Wait | Func::Sleep | Func::Draw | Func::Param => Ok(Value::Null),
            // `EXISTS[#<name>]`; `EXISTS[#n]` is 1 for any parameter number.
            Func::Exists => match texts.first() {
                Some(Arg::Name(name)) => {
                    Ok(Value::Double(f64::from(u8::from(self.ngc_exists(name)))))
                }
                _ => {
                    let n = args.first().copied().map_or(0.0, num);
                    super::ngc::param_number(n, span)?;
                    Ok(Value::Double(1.0))
                }
            },
            Func::Round => match self.macros.round_per_unit {
                Some(per_unit) => {
                    let x = args.first().copied().map_or(0.0, num);
                    real(round_to_increment(x, per_unit), span)
                }
                None => function(lang, f, args, span),
            },
            _ => function(lang, f, args, span),
        }
    }

    /// STD(v), STDAX(v, axis): a Long in least increments becomes a Double
    /// in the program's units; a Double is already in them.
    fn standardize(
        &self,
        f: Func,
        args: &[Value],
        texts: &[Arg],
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let v = args.first().copied().unwrap_or_default();
        let Value::Long(i) = v else { return Ok(v) };
        let rotary = match (f, texts.get(1)) {
            (Func::StdAx, Some(Arg::Name(axis))) => {
                let letter = axis.as_bytes().first().copied().unwrap_or(b'?');
                if axis.len() != 1 || self.cfg.machine.axis_of(letter).is_none() {
                    return Err(alarms::macro_domain(
                        span,
                        &format!("STDAX: {axis} is not an axis of the machine"),
                    ));
                }
                matches!(letter, b'A' | b'B' | b'C')
            }
            _ => false,
        };
        let per_unit = if rotary || !self.state.modal.inch {
            1000.0
        } else {
            10_000.0
        };
        // Longs here come from program values: far below 2^53. A division
        // rounds once (100 / 1000 is the double nearest 0.1).
        #[allow(clippy::cast_precision_loss)]
        real(i as f64 / per_unit, span)
    }

    /// GETARG(letter): the argument the current macro call was given.
    fn get_arg(&self, texts: &[Arg]) -> Value {
        let Some(Arg::Name(name)) = texts.first() else {
            return Value::Null;
        };
        let level = self.flow.frames.last().map_or(0, |f| f.locals);
        match name.as_bytes() {
            [l] if l.is_ascii_uppercase() => self.macros.arg(level, *l),
            // Extended arguments (X1=…) are not passed: vacant.
            _ => Value::Null,
        }
    }

    /// Reads `kind n`.
    #[inline]
    pub(crate) fn read_var(
        &mut self,
        kind: VarKind,
        n: u32,
        span: Span,
    ) -> Result<Value, Diagnostic> {
        let (v, set) = match self.macros.vars.slot(kind, n) {
            Slot::Vacant => return Ok(Value::Null),
            Slot::Local(i) => {
                let level = self.flow.frames.last().map_or(0, |f| f.locals);
                self.macros.vars.local(level, i)
            }
            Slot::Common(i) => self.macros.vars.common(i),
            Slot::Modal(i) => self.macros.vars.modal(i),
            Slot::Global(g) => self.macros.vars.global(g),
            Slot::System(n) => return self.system_read(n, span),
            Slot::Missing => {
                return Err(alarms::no_such_variable(span, kind.sigil(), f64::from(n)));
            }
        };
        if !set {
            self.note_unset(kind, n);
        }
        Ok(v)
    }

    #[cold]
    fn note_unset(&mut self, kind: VarKind, n: u32) {
        let list = &mut self.macros.unset;
        if list.len() >= UNSET_LIMIT || list.iter().any(|u| u.kind == kind && u.n == n) {
            return;
        }
        list.push(UnsetRead {
            kind,
            n,
            line: self.flow.loc.line,
            file: self.flow.loc.file.clone(),
        });
    }

    /// Writes `kind n`; `comment` is the block's comment (the message of
    /// `#3000` and `#3006`).
    pub(crate) fn write_var(
        &mut self,
        kind: VarKind,
        n: u32,
        v: Value,
        span: Span,
        comment: Option<&str>,
    ) -> Result<(), Diagnostic> {
        self.macros.used = true;
        match self.macros.vars.slot(kind, n) {
            Slot::Vacant => Err(alarms::read_only_variable(span, kind.sigil(), n)),
            Slot::Local(i) => {
                let level = self.flow.frames.last().map_or(0, |f| f.locals);
                self.macros.vars.set_local(level, i, v);
                Ok(())
            }
            Slot::Common(i) => {
                self.macros.vars.set_common(i, v);
                Ok(())
            }
            Slot::Modal(i) => {
                self.macros.vars.set_modal(i, v);
                Ok(())
            }
            Slot::Global(g) => {
                let v = if self.macros.vars.long_only(kind, n) {
                    to_long(v, span)?
                } else {
                    v
                };
                self.macros.vars.set_global(g, v);
                Ok(())
            }
            Slot::System(n) => self.system_write(n, v, span, comment),
            Slot::Missing => Err(alarms::no_such_variable(span, kind.sigil(), f64::from(n))),
        }
    }
}
