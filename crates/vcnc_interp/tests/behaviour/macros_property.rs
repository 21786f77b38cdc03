//! Property test: random expressions, printed with the fewest brackets the
//! precedence rules allow, evaluate in the interpreter exactly as a
//! reference evaluator written here says — operator by operator, with the
//! vacant-value (null) rules, Macro B's integer portions for MOD and the
//! bit operators, Syntec's Long/Double typing and truncating division, and
//! the alarms for division by zero, type mismatches and nesting too deep.
//!
//! The reference is a plain tree walk, independent of the interpreter's
//! postfix compiler, parser and value stack.

#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic in a test is a failure report

use proptest::prelude::*;
use std::sync::LazyLock;
use vcnc_interp::{Dialect, Interpreter, Machine, Options, Outcome, VecSink};
use vcnc_syntax::Code;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Op {
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
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Fun {
    Abs,
    Round,
    Fix,
    Fup,
    Ceil,
    Floor,
}

#[derive(Debug, Clone)]
enum E {
    /// `n/4` written with a point when `point` (Syntec: a Double).
    Num(i64, bool),
    /// #1..#4 (#3 is vacant).
    Var(u8),
    Vacant,
    Neg(Box<E>),
    Not(Box<E>),
    Bin(Op, Box<E>, Box<E>),
    Fun(Fun, Box<E>),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum V {
    Null,
    L(i64),
    D(f64),
}

impl V {
    fn num(self) -> f64 {
        match self {
            V::Null => 0.0,
            V::L(i) => i as f64,
            V::D(d) => d,
        }
    }
    fn or_zero(self) -> V {
        if self == V::Null { V::L(0) } else { self }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Lang {
    B,
    S,
}

/// The prelude's variables: #1 = 3, #2 = -2.5, #3 vacant, #4 = 7.
fn var(n: u8) -> V {
    match n {
        1 => V::L(3),
        2 => V::D(-2.5),
        4 => V::L(7),
        _ => V::Null,
    }
}

/// Precedence of an operator in `lang` (bigger binds tighter).
fn prec(lang: Lang, op: Op) -> u8 {
    match (lang, op) {
        (Lang::B, Op::Eq | Op::Ne | Op::Lt | Op::Le | Op::Gt | Op::Ge) => 1,
        (Lang::B, Op::Add | Op::Sub | Op::Or | Op::Xor) => 2,
        (Lang::B, _) => 3,
        (Lang::S, Op::Or) => 1,
        (Lang::S, Op::Xor) => 2,
        (Lang::S, Op::And) => 3,
        (Lang::S, Op::Ne) => 4,
        (Lang::S, Op::Eq) => 5,
        (Lang::S, Op::Lt | Op::Le | Op::Gt | Op::Ge) => 6,
        (Lang::S, Op::Add | Op::Sub) => 7,
        (Lang::S, _) => 8,
    }
}

fn op_text(lang: Lang, op: Op) -> &'static str {
    match (lang, op) {
        (_, Op::Add) => "+",
        (_, Op::Sub) => "-",
        (_, Op::Mul) => "*",
        (_, Op::Div) => "/",
        (_, Op::Mod) => " MOD ",
        (_, Op::And) => " AND ",
        (_, Op::Or) => " OR ",
        (_, Op::Xor) => " XOR ",
        (Lang::B, Op::Eq) => " EQ ",
        (Lang::B, Op::Ne) => " NE ",
        (Lang::B, Op::Lt) => " LT ",
        (Lang::B, Op::Le) => " LE ",
        (Lang::B, Op::Gt) => " GT ",
        (Lang::B, Op::Ge) => " GE ",
        (Lang::S, Op::Eq) => "=",
        (Lang::S, Op::Ne) => "<>",
        (Lang::S, Op::Lt) => "<",
        (Lang::S, Op::Le) => "<=",
        (Lang::S, Op::Gt) => ">",
        (Lang::S, Op::Ge) => ">=",
    }
}

fn group(lang: Lang, s: String) -> String {
    match lang {
        Lang::B => format!("[{s}]"),
        Lang::S => format!("({s})"),
    }
}

/// Prints `e`; brackets only where precedence needs them.
fn print(lang: Lang, e: &E) -> String {
    match e {
        E::Num(n, point) => {
            let v = *n as f64 / 4.0;
            if *point || v.fract() != 0.0 {
                let s = format!("{v}");
                if s.contains('.') { s } else { format!("{s}.") }
            } else {
                format!("{v}")
            }
        }
        E::Var(n) => format!("#{n}"),
        E::Vacant => "#0".into(),
        E::Neg(x) => format!("-{}", operand(lang, x)),
        E::Not(x) => format!("NOT {}", operand(lang, x)),
        E::Bin(op, a, b) => {
            let p = prec(lang, *op);
            let side = |x: &E, right: bool| {
                let s = print(lang, x);
                match x {
                    E::Bin(o, ..) if prec(lang, *o) < p || (right && prec(lang, *o) == p) => {
                        group(lang, s)
                    }
                    _ => s,
                }
            };
            format!("{}{}{}", side(a, false), op_text(lang, *op), side(b, true))
        }
        E::Fun(f, x) => {
            let name = match f {
                Fun::Abs => "ABS",
                Fun::Round => "ROUND",
                Fun::Fix => "FIX",
                Fun::Fup => "FUP",
                Fun::Ceil => "CEIL",
                Fun::Floor => "FLOOR",
            };
            let inner = print(lang, x);
            match lang {
                Lang::B => format!("{name}[{inner}]"),
                Lang::S => format!("{name}({inner})"),
            }
        }
    }
}

/// A unary operator's operand: bracketed unless it is a primary.
fn operand(lang: Lang, x: &E) -> String {
    let s = print(lang, x);
    match x {
        E::Bin(..) => group(lang, s),
        _ => s,
    }
}

/// Deepest bracket nesting of a printed expression.
fn nesting(s: &str) -> usize {
    let (mut d, mut max) = (0usize, 0usize);
    for c in s.chars() {
        match c {
            '[' | '(' => {
                d += 1;
                max = max.max(d);
            }
            ']' | ')' => d = d.saturating_sub(1),
            _ => {}
        }
    }
    max
}

fn int_part(x: f64) -> i64 {
    // The generated values are small: the integer portion fits.
    #[allow(clippy::cast_possible_truncation)]
    let i = x.trunc() as i64;
    i
}

/// The reference evaluator.
fn eval(lang: Lang, e: &E) -> Result<V, Code> {
    Ok(match e {
        E::Num(n, point) => {
            let v = *n as f64 / 4.0;
            match lang {
                Lang::S if !*point && v.fract() == 0.0 => V::L(int_part(v)),
                _ => V::D(v),
            }
        }
        E::Var(n) => match (lang, var(*n)) {
            // Macro B has no Longs: every number is real.
            (Lang::B, V::L(i)) => V::D(i as f64),
            (_, v) => v,
        },
        E::Vacant => V::Null,
        E::Neg(x) => match eval(lang, x)? {
            V::Null => V::Null,
            V::L(i) => V::L(-i),
            V::D(d) => V::D(-d),
        },
        E::Not(x) => match eval(lang, x)? {
            V::Null => V::Null,
            V::L(i) => V::L(!i),
            V::D(_) => return Err(Code::E610),
        },
        E::Fun(f, x) => {
            let v = eval(lang, x)?.num();
            let r = match f {
                Fun::Abs => v.abs(),
                Fun::Round => v.round(),
                Fun::Fix => v.trunc(),
                Fun::Fup => {
                    if v.fract() == 0.0 {
                        v
                    } else {
                        v.trunc() + v.signum()
                    }
                }
                Fun::Ceil => v.ceil(),
                Fun::Floor => v.floor(),
            };
            match (lang, f) {
                (Lang::S, Fun::Abs) => match eval(lang, x)? {
                    V::L(i) => V::L(i.abs()),
                    _ => V::D(r),
                },
                (Lang::S, _) => V::L(int_part(r)),
                _ => V::D(r),
            }
        }
        E::Bin(op, a, b) => binary(lang, *op, eval(lang, a)?, eval(lang, b)?)?,
    })
}

fn truth(lang: Lang, b: bool) -> V {
    match lang {
        Lang::B => V::D(f64::from(u8::from(b))),
        Lang::S => V::L(i64::from(b)),
    }
}

fn binary(lang: Lang, op: Op, a: V, b: V) -> Result<V, Code> {
    match op {
        Op::Eq | Op::Ne => {
            let eq = match (a, b) {
                (V::Null, V::Null) => true,
                (V::Null, _) | (_, V::Null) => false,
                _ => a.num() == b.num(),
            };
            return Ok(truth(lang, eq == (op == Op::Eq)));
        }
        Op::Lt => return Ok(truth(lang, a.num() < b.num())),
        Op::Le => return Ok(truth(lang, a.num() <= b.num())),
        Op::Gt => return Ok(truth(lang, a.num() > b.num())),
        Op::Ge => return Ok(truth(lang, a.num() >= b.num())),
        _ => {}
    }
    let (a, b) = (a.or_zero(), b.or_zero());
    if lang == Lang::S
        && let (V::L(i), V::L(j)) = (a, b)
    {
        return match op {
            Op::Add => Ok(V::L(i + j)),
            Op::Sub => Ok(V::L(i - j)),
            Op::Mul => Ok(V::L(i * j)),
            Op::Div | Op::Mod if j == 0 => Err(Code::E608),
            Op::Div => Ok(V::L(i / j)),
            Op::Mod => Ok(V::L(i % j)),
            Op::And => Ok(V::L(i & j)),
            Op::Or => Ok(V::L(i | j)),
            _ => Ok(V::L(i ^ j)),
        };
    }
    let (x, y) = (a.num(), b.num());
    match op {
        Op::Add => Ok(V::D(x + y)),
        Op::Sub => Ok(V::D(x - y)),
        Op::Mul => Ok(V::D(x * y)),
        Op::Div if y == 0.0 => Err(Code::E608),
        Op::Div => Ok(V::D(x / y)),
        _ if lang == Lang::S => Err(Code::E610),
        _ => {
            let (i, j) = (int_part(x), int_part(y));
            Ok(V::D(match op {
                Op::Mod if j == 0 => return Err(Code::E608),
                Op::Mod => (i % j) as f64,
                Op::And => (i & j) as f64,
                Op::Or => (i | j) as f64,
                _ => (i ^ j) as f64,
            }))
        }
    }
}

fn expr(lang: Lang) -> impl Strategy<Value = E> {
    let leaf = prop_oneof![
        4 => (-12i64..40, any::<bool>()).prop_map(|(n, p)| E::Num(n.max(0), p)),
        2 => (1u8..=4).prop_map(E::Var),
        1 => Just(E::Vacant),
    ];
    let ops = [
        Op::Add,
        Op::Sub,
        Op::Mul,
        Op::Div,
        Op::Mod,
        Op::And,
        Op::Or,
        Op::Xor,
        Op::Eq,
        Op::Ne,
        Op::Lt,
        Op::Le,
        Op::Gt,
        Op::Ge,
    ];
    leaf.prop_recursive(4, 24, 2, move |inner| {
        prop_oneof![
            6 => (proptest::sample::select(ops.to_vec()), inner.clone(), inner.clone())
                .prop_map(|(op, a, b)| E::Bin(op, Box::new(a), Box::new(b))),
            1 => inner.clone().prop_map(|x| E::Neg(Box::new(x))),
            1 => inner.clone().prop_map(move |x| if lang == Lang::S { E::Not(Box::new(x)) } else { E::Neg(Box::new(x)) }),
            1 => (proptest::sample::select(if lang == Lang::B {
                    vec![Fun::Abs, Fun::Round, Fun::Fix, Fun::Fup]
                } else {
                    vec![Fun::Abs, Fun::Round, Fun::Ceil, Fun::Floor]
                }), inner)
                .prop_map(|(f, x)| E::Fun(f, Box::new(x))),
        ]
    })
}

static MACHINE: LazyLock<Machine> = LazyLock::new(Machine::default_mill);

/// What the interpreter gives: a value (`None` vacant) or an alarm code.
fn interpret(lang: Lang, text: &str) -> Result<Option<f64>, Code> {
    let (dialect, program, name) = match lang {
        Lang::B => (
            Dialect::fanuc(),
            format!("#1 = 3\n#2 = -2.5\n#4 = 7\n#100 = {text}\nM30\n"),
            "#100",
        ),
        Lang::S => (
            Dialect::syntec(),
            format!("%@MACRO\n#1 := 3;\n#2 := -2.5;\n#4 := 7;\n@1 := {text};\nM30;\n"),
            "@1",
        ),
    };
    let mut interp = Interpreter::new(&MACHINE, &dialect, Options::default());
    match interp.run_str(&program, &mut VecSink::default()) {
        Outcome::Alarm(d) => Err(d.code),
        _ => Ok(interp.variable(name)),
    }
}

fn check(lang: Lang, e: &E) -> Result<(), TestCaseError> {
    let text = print(lang, e);
    let limit = if lang == Lang::B { 5 } else { 32 };
    let want = if nesting(&text) > limit {
        Err(Code::E602)
    } else {
        eval(lang, e).map(|v| match v {
            V::Null => None,
            v => Some(v.num()),
        })
    };
    let got = interpret(lang, &text);
    match (want, got) {
        (Ok(Some(a)), Ok(Some(b))) => {
            prop_assert!(
                (a - b).abs() <= 1e-9 * a.abs().max(1.0),
                "{text}: want {a}, got {b}"
            )
        }
        (w, g) => prop_assert_eq!(w, g, "{}", text),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn macro_b_expressions_evaluate_like_the_reference(e in expr(Lang::B)) {
        check(Lang::B, &e)?;
    }

    #[test]
    fn syntec_expressions_evaluate_like_the_reference(e in expr(Lang::S)) {
        check(Lang::S, &e)?;
    }
}

#[test]
fn the_printer_and_the_reference_agree_on_known_cases() {
    // The reference itself, checked by hand: 3 - 2 - 1 prints without
    // brackets and is 0; 3 - (2 - 1) needs them and is 2.
    let n = |v: i64| Box::new(E::Num(v * 4, false));
    let left = E::Bin(Op::Sub, Box::new(E::Bin(Op::Sub, n(3), n(2))), n(1));
    let right = E::Bin(Op::Sub, n(3), Box::new(E::Bin(Op::Sub, n(2), n(1))));
    assert_eq!(print(Lang::B, &left), "3-2-1");
    assert_eq!(print(Lang::B, &right), "3-[2-1]");
    assert_eq!(eval(Lang::B, &left), Ok(V::D(0.0)));
    assert_eq!(eval(Lang::B, &right), Ok(V::D(2.0)));
    // Syntec: 7 / 2 is the Long 3.
    assert_eq!(eval(Lang::S, &E::Bin(Op::Div, n(7), n(2))), Ok(V::L(3)));
}
