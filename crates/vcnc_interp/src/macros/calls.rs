//! Macro calls: G65 (one call with arguments, Syntec manual 1.2.26), G66/G67
//! (a call after every move block until G67, 1.2.27), Syntec's extended
//! G-code macros G200–G999 (its MACRO manual §1.3, §5.3.1) and the M-code
//! macros a machine file registers (`[m_macros]`).
//!
//! ```text
//!   G65 P9010 L2 X10. Y5. ─▶ level n+1: #24 = 10, #25 = 5 ─▶ O9010 … M99 ─▶ level n
//!   letters: A#1 B#2 C#3 I#4 J#5 K#6 D#7 E#8 F#9 H#11 M#13 Q#17 R#18 S#19
//!            T#20 U#21 V#22 W#23 X#24 Y#25 Z#26   (Syntec G200/M macros: also
//!            L#12 P#16; G, N, O are never arguments)
//! ```
//!
//! A macro call opens a new level of locals (M98 shares its caller's); the
//! level goes when its program returns with M99. Under G66 a block that
//! names an axis (and no code that takes the axis words) moves, then calls
//! the macro with the G66 block's arguments; moves inside the called macro
//! do not call again. Syntec keeps one set of locals from G66 to G67.
//!
//! Argument values: Fanuc passes a length written without a decimal point
//! in least input increments (`X10` is 0.010 mm: its 0i manual's "the units
//! correspond to the least input increment of each address"); Syntec passes
//! the number as written, a Long or a Double, for the macro's STD to read.

use crate::alarms;
use crate::dialect::FlowOp;
use crate::dialect::{GDef, GOp, IntegerWords, ModalLocals, VarTable};
use crate::flow::{CallKind, Frame, ProgramStore};
use crate::interpreter::{Interpreter, Step};
use crate::words::At;
use std::io;
use vcnc_core::machine::DecimalInput;
use vcnc_syntax::macros::Value;
use vcnc_syntax::{Block, Cursor, Diagnostic, LineReader, Span, Word};

/// The local each argument letter sets (index: letter − 'A'; 0: none).
const FANUC_ARGS: [u8; 26] = [
    1, 2, 3, 7, 8, 9, 0, 11, 4, 5, 6, 0, 13, 0, 0, 0, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26,
];

/// Letters that pass a length or an angle (least increments without a
/// decimal point on Fanuc): the axes, the arc centre offsets I J K, R and
/// the peck depth Q. E is not among them: a Fanuc mill gives E no length
/// (programs pass codes through it, `G65 P9000 E41` for a `G#8`), so it
/// passes its number as written, like D, F, H, M, S, T.
const LENGTH_ARGS: &[u8] = b"ABCIJKQRUVWXYZ";

/// What a call runs.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Program {
    /// `O` number (G65 P, G66 P).
    Number(u32),
    /// A file name (`G0200`, `M0123`).
    Named(String),
}

/// The G66 call in force.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ModalCall {
    pub program: Program,
    pub repeats: u32,
    pub args: [Value; 26],
    /// Syntec: the locals shared from G66 to G67.
    pub shared: Option<Vec<Value>>,
    /// Where the G66 was written (alarms of its calls).
    pub span: Span,
}

/// A call's parameters read from its block.
struct Parsed {
    program: Option<(u32, Span)>,
    repeats: u32,
    args: [Value; 26],
}

impl Interpreter<'_> {
    /// A G65 or G66 block: its words are P, L and the arguments.
    pub(crate) fn macro_call_block(
        &mut self,
        block: &Block,
        code: At<GDef>,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let name = if code.def.op == GOp::Flow(FlowOp::MacroCall) {
            "G65"
        } else {
            "G66"
        };
        let p = self.call_words(block, code.span, name, true, b"GNO")?;
        let Some((number, p_span)) = p.program else {
            return Err(alarms::needs_word(
                code.span,
                name,
                "P (the program to call)",
            ));
        };
        if code.def.op == GOp::Flow(FlowOp::MacroModal) {
            self.macros.modal = Some(ModalCall {
                program: Program::Number(number),
                repeats: p.repeats,
                args: p.args,
                shared: None,
                span: p_span,
            });
            self.state.modal.macro_call = true;
            self.macros.used = true;
            return Ok(Step::Next);
        }
        if p.repeats == 0 {
            return Ok(Step::Next);
        }
        let locals = self.locals_from(&p.args);
        self.enter_macro(
            &Program::Number(number),
            p.repeats,
            &p.args,
            locals,
            CallKind::Macro,
            p_span,
            next,
            store,
        )
    }

    /// Reads P, L and the argument letters of a call block; `call` names
    /// the call in alarms. `own_pl`: P and L are the call's (G65, G66);
    /// else they are arguments too (Syntec's extended G and M macros: L
    /// repeats and sets #12, P sets #16).
    fn call_words(
        &self,
        block: &Block,
        code: Span,
        call: &str,
        own_pl: bool,
        not_args: &[u8],
    ) -> Result<Parsed, Diagnostic> {
        let mut p = Parsed {
            program: None,
            repeats: 1,
            args: [Value::Null; 26],
        };
        let syntec = self.macros.rules.variables == VarTable::Syntec;
        let mut seen = 0u32;
        for w in block.words() {
            if w.span == code {
                continue;
            }
            let Some(l) = w.addr.as_letter() else {
                return Err(alarms::extended_not_allowed(w.span, &w.addr.name()));
            };
            if l == b'N' {
                continue;
            }
            let bit = 1u32 << (l - b'A');
            if seen & bit != 0 {
                return Err(alarms::duplicate_argument(w.span, l));
            }
            seen |= bit;
            if not_args.contains(&l) {
                return Err(if l == b'G' || l == b'M' {
                    alarms::call_not_alone(w.span, call)
                } else {
                    alarms::word_not_allowed(w.span, l)
                });
            }
            match l {
                b'P' if own_pl => {
                    let n =
                        crate::words::whole(w, b'P', 0.0, 99_999_999.0, "P is a program number")?;
                    p.program = Some((n, w.span));
                }
                b'L' => {
                    p.repeats = crate::words::whole(w, b'L', 0.0, 9999.0, "L is a repeat count")?;
                    if syntec && !own_pl {
                        p.args[usize::from(b'L' - b'A')] = self.arg_value(w);
                    }
                }
                b'P' => p.args[usize::from(b'P' - b'A')] = self.arg_value(w),
                _ => p.args[usize::from(l - b'A')] = self.arg_value(w),
            }
        }
        Ok(p)
    }

    /// An argument word's value as its local receives it.
    fn arg_value(&self, w: &Word) -> Value {
        if self.macros.rules.variables == VarTable::Syntec {
            // Whole (no point) and within 9 digits.
            #[allow(clippy::cast_possible_truncation)]
            return if w.point {
                Value::Double(w.value)
            } else {
                Value::Long(w.value as i64)
            };
        }
        let whole_units = w.point
            || self.cfg.dialect.integers == IntegerWords::WholeUnits
            || self.cfg.machine.params.decimal_input == DecimalInput::Calculator;
        match self.increments_per_unit(w.addr.0) {
            Some(per_unit) if !whole_units => Value::Double(w.value / per_unit),
            _ => Value::Double(w.value),
        }
    }

    /// Least input increments per unit of a length or angle address
    /// (0.001 mm or degree, 0.0001 in); `None` for other letters.
    pub(crate) fn increments_per_unit(&self, letter: u8) -> Option<f64> {
        if !LENGTH_ARGS.contains(&letter) {
            return None;
        }
        let rotary = matches!(letter, b'A' | b'B' | b'C');
        Some(if rotary || !self.state.modal.inch {
            1000.0
        } else {
            10_000.0
        })
    }

    /// The locals a call starts with: each argument in its local.
    fn locals_from(&self, args: &[Value; 26]) -> Vec<(usize, Value)> {
        let syntec = self.macros.rules.variables == VarTable::Syntec;
        args.iter()
            .enumerate()
            .filter(|(_, v)| !matches!(v, Value::Null))
            .filter_map(|(i, v)| {
                let letter = b'A' + u8::try_from(i).unwrap_or(0);
                let local = match (letter, syntec) {
                    (b'L', true) => 12,
                    (b'P', true) => 16,
                    _ => FANUC_ARGS[i],
                };
                (local != 0).then(|| (usize::from(local) - 1, *v))
            })
            .collect()
    }

    /// Opens `program` as a new call level.
    #[allow(clippy::too_many_arguments)]
    fn enter_macro(
        &mut self,
        program: &Program,
        repeats: u32,
        args: &[Value; 26],
        locals: Vec<(usize, Value)>,
        kind: CallKind,
        span: Span,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let depth = self.flow.frames.len() as u64;
        if depth > u64::from(self.cfg.machine.limits.max_call_depth) {
            return Err(alarms::nesting_too_deep(
                span,
                self.cfg.machine.limits.max_call_depth,
            ));
        }
        let lex = self.cfg.dialect.lex;
        let (source, start) = match program {
            Program::Number(n) => match self.flow.find_program(*n, &lex, store) {
                Ok(Some(found)) => found,
                Ok(None) => return Err(alarms::program_not_found(span, *n)),
                Err(e) => return Err(alarms::program_unreadable(span, *n, &e)),
            },
            Program::Named(name) => match self.open_named(name, store) {
                Ok(Some(found)) => found,
                Ok(None) => return Err(alarms::macro_file_not_found(span, name)),
                Err(e) => return Err(alarms::program_unreadable(span, 0, &e)),
            },
        };
        // Every check has passed: only now do the flow and the locals change.
        self.count_jump(span)?;
        self.macros.used = true;
        let level = self.macros.vars.push_level();
        for (i, v) in locals {
            self.macros.vars.set_local(level, i, v);
        }
        self.macros.set_args(level, *args);
        self.flow.frames.push(Frame {
            source,
            start,
            program: start,
            last: None,
            ret: next,
            runs_left: repeats.max(1),
            started: false,
            returns_with: "M99",
            locals: level,
            call: kind,
            number: match program {
                Program::Number(n) => Some(*n),
                Program::Named(_) => None,
            },
        });
        Ok(Step::Jump(start))
    }

    /// A program opened by file name through the store (an open one is
    /// reused).
    fn open_named(
        &mut self,
        name: &str,
        store: &mut dyn ProgramStore,
    ) -> io::Result<Option<(usize, Cursor)>> {
        let open = self.flow.sources.iter().position(|s| {
            s.as_ref().is_some_and(|s| {
                s.number.is_none() && s.name.as_deref().is_some_and(|n| file_stem(n) == name)
            })
        });
        if let Some(i) = open {
            return Ok(Some((i, Cursor::default())));
        }
        match store.open_named(name) {
            None => Ok(None),
            Some(Err(e)) => Err(e),
            Some(Ok((mut text, shown))) => {
                text.read_at(0, &mut [0u8; 1])?;
                let src = crate::flow::Source {
                    reader: LineReader::new(text),
                    name: Some(shown.into()),
                    number: None,
                    id: 0,
                };
                Ok(Some((self.flow.install(src), Cursor::default())))
            }
        }
    }

    /// A level is left (M99, G24): its locals go; Syntec's G66 keeps them
    /// for its next call.
    pub(crate) fn leave_level(&mut self, left: Option<Frame>) {
        let Some(f) = left else { return };
        if f.call == CallKind::Sub {
            return;
        }
        if f.call == CallKind::Modal
            && self.macros.rules.modal_locals == ModalLocals::SharedUntilG67
            && let Some(m) = self.macros.modal.as_mut()
        {
            m.shared = Some(self.macros.vars.level_values(f.locals));
        }
        self.macros.vars.pop_to(f.locals);
        self.macros.drop_args(f.locals);
    }

    /// After a move block under G66: the modal call, unless the block is
    /// in a macro G66 called.
    pub(crate) fn modal_macro_call(
        &mut self,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        if self.flow.frames.iter().any(|f| f.call == CallKind::Modal) {
            return Ok(Step::Next);
        }
        let Some(m) = self.macros.modal.clone() else {
            return Ok(Step::Next);
        };
        // `G66 P L0` runs its program zero times, like `G65 P L0`.
        if m.repeats == 0 {
            return Ok(Step::Next);
        }
        let locals = match (&m.shared, self.macros.rules.modal_locals) {
            (Some(values), ModalLocals::SharedUntilG67) => values
                .iter()
                .enumerate()
                .filter(|(_, v)| !matches!(v, Value::Null))
                .map(|(i, v)| (i, *v))
                .collect(),
            _ => self.locals_from(&m.args),
        };
        self.enter_macro(
            &m.program,
            m.repeats,
            &m.args,
            locals,
            CallKind::Modal,
            m.span,
            next,
            store,
        )
    }

    /// A block the dialect rejected for an unknown G code: a Syntec
    /// extended G-code macro (G200–G999) if the program directory has its
    /// file; `None` leaves the alarm standing.
    #[cold]
    pub(crate) fn extended_g_call(
        &mut self,
        block: &Block,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Option<Step>, Diagnostic> {
        let Some(g) = block.words().iter().find(|w| {
            w.addr.as_letter() == Some(b'G')
                && (200.0..1000.0).contains(&w.value)
                && self.cfg.dialect.g(w.value).is_none()
        }) else {
            return Ok(None);
        };
        let Some(name) = extended_name(g.value) else {
            return Ok(None);
        };
        // Probe the store first: without the file the E201 stands.
        if self
            .open_named(&name, store)
            .map_err(|e| alarms::program_unreadable(g.span, 0, &e))?
            .is_none()
        {
            return Ok(None);
        }
        let p = self.call_words(block, g.span, "a G-code macro call", false, b"GO")?;
        if p.repeats == 0 {
            return Ok(Some(Step::Next));
        }
        let locals = self.locals_from(&p.args);
        self.enter_macro(
            &Program::Named(name),
            p.repeats,
            &p.args,
            locals,
            CallKind::Macro,
            g.span,
            next,
            store,
        )
        .map(Some)
    }

    /// A block with an M code the machine registers as a macro.
    #[cold]
    pub(crate) fn m_macro_call(
        &mut self,
        block: &Block,
        m: At<u32>,
        next: Cursor,
        store: &mut dyn ProgramStore,
    ) -> Result<Step, Diagnostic> {
        let name = self
            .cfg
            .machine
            .m_macros
            .get(&m.def)
            .map(|n| n.to_string())
            .unwrap_or_default();
        let p = self.call_words(block, m.span, "an M-code macro call", false, b"GMO")?;
        if p.repeats == 0 {
            return Ok(Step::Next);
        }
        let locals = self.locals_from(&p.args);
        self.enter_macro(
            &Program::Named(name),
            p.repeats,
            &p.args,
            locals,
            CallKind::Macro,
            m.span,
            next,
            store,
        )
    }
}

/// `G200` → `G0200`, `G200.1` → `G200001` (Syntec's file names); codes with
/// hundredths are not named.
fn extended_name(v: f64) -> Option<String> {
    let tenths = (v * 10.0).round();
    if (v * 10.0 - tenths).abs() > 1e-6 {
        return None;
    }
    // 2000..10000 tenths: exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let t = tenths as u32;
    Some(if t.is_multiple_of(10) {
        format!("G{:04}", t / 10)
    } else {
        format!("G{}{:03}", t / 10, t % 10)
    })
}

/// A file name without its directory and extension.
fn file_stem(path: &str) -> &str {
    let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
    name.split('.').next().unwrap_or(name)
}

impl super::Macros {
    /// The argument `letter` of call level `level`.
    pub fn arg(&self, level: u32, letter: u8) -> Value {
        let i = usize::try_from(level).unwrap_or(usize::MAX);
        self.args
            .get(i)
            .and_then(|a| a.get(usize::from(letter.wrapping_sub(b'A'))))
            .copied()
            .unwrap_or_default()
    }

    fn set_args(&mut self, level: u32, args: [Value; 26]) {
        let i = usize::try_from(level).unwrap_or(0);
        if self.args.len() <= i {
            self.args.resize(i + 1, [Value::Null; 26]);
        }
        self.args[i] = args;
    }

    fn drop_args(&mut self, level: u32) {
        self.args.truncate(usize::try_from(level).unwrap_or(0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extended_g_codes_name_their_files() {
        assert_eq!(extended_name(200.0).as_deref(), Some("G0200"));
        assert_eq!(extended_name(999.0).as_deref(), Some("G0999"));
        assert_eq!(extended_name(200.1).as_deref(), Some("G200001"));
        assert_eq!(extended_name(200.15), None);
        assert_eq!(file_stem("dir/sub/G0200.nc"), "G0200");
    }
}
