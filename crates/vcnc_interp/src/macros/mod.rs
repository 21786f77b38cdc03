//! Macros: variables, expressions and macro statements between the lexer
//! and the block's validation.
//!
//! ```text
//!   line ─▶ lex_block ──ok──▶ Block ─────────────────────────────▶ block(): validate, execute
//!              │ error (cold)                                        ▲
//!              ▼                                                     │ evaluated words
//!   parse_iso_block / Syntec statement reader ─▶ Compiled ─▶ run ──┬─┘ (X#1 → X12.5)
//!              (vcnc_syntax::macros)             cached by    assign, IF, WHILE, GOTO,
//!                                                cursor       calls (G65, G66, G200, M macros)
//! ```
//!
//! A block without macro syntax never comes here: the literal lexer
//! accepts it and the interpreter runs it as before. The first block the
//! lexer rejects is handed to the macro parser; if it holds macro syntax it
//! is compiled once, cached by where it starts (source, line, column) and
//! run; later passes of a loop run the cached statement without lexing.
//! Word blocks with expressions are evaluated into the same literal
//! [`Block`](vcnc_syntax::Block) the lexer would have made, so validation
//! and execution do not know macros exist. Syntec `%@MACRO` files are read
//! statement by statement (a statement may span lines) by `front.rs`.
//!
//! Files: `vars.rs` (variables and the controller's variable table),
//! `eval.rs` (the expression evaluator), `front.rs` (the statement cache,
//! the ISO hook and the `%@MACRO` reader), `exec.rs` (statements),
//! `structure.rs` (the loop and branch pairing found before a program's
//! statements run), `calls.rs` (G65, G66/G67, G200–G999, M-code macros).

mod calls;
mod eval;
mod exec;
mod front;
mod ngc;
mod structure;
mod system;
mod vars;

pub(crate) use calls::ModalCall;
pub(crate) use eval::Evaluator;
pub(crate) use front::Compiled;
pub(crate) use vars::Vars;

use crate::dialect::MacroRules;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::rc::Rc;
use vcnc_syntax::macros::Value;
use vcnc_syntax::{Cursor, Line};

/// A multiplicative hasher for the small integer keys of the caches (the
/// standard SipHash would cost more than the statement it finds).
#[derive(Default)]
pub(crate) struct KeyHasher(u64);

impl Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.write_u64(u64::from(*b));
        }
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn write_u32(&mut self, n: u32) {
        self.write_u64(u64::from(n));
    }
}

pub(crate) type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<KeyHasher>>;

/// Where a statement starts: (source id, line offset, column).
pub(crate) type Key = (u32, u64, u32);

pub(crate) fn key(id: u32, at: Cursor) -> Key {
    (id, at.offset, at.col)
}

/// Most statements kept compiled (beyond, statements are parsed each time
/// they run; memory stays bounded).
pub(crate) const CACHE_LIMIT: usize = 65_536;

/// Most values on the Syntec PUSH/POP stack (E613 beyond).
pub(crate) const STACK_LIMIT: usize = 4096;

/// Most distinct variables the unset-variable report keeps.
pub(crate) const UNSET_LIMIT: usize = 100;

/// One variable read while it had never been set.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct UnsetRead {
    pub kind: vcnc_syntax::macros::VarKind,
    pub n: u32,
    pub line: u64,
    pub file: Option<std::sync::Arc<str>>,
}

/// Everything the macro layer keeps for a run.
pub(crate) struct Macros {
    pub rules: MacroRules,
    pub vars: Vars,
    /// Compiled statements by where they start.
    pub cache: FastMap<Key, Rc<Compiled>>,
    /// The program has used variables, so an M99 in the main program may
    /// end its own loop (see `codes/calls.rs`).
    pub used: bool,
    /// Loop and branch links of the programs scanned.
    pub structure: structure::Structure,
    /// Which sources are `%@MACRO` files, by source id.
    pub macro_files: FastMap<u32, bool>,
    /// The last answer: (source index, `Flow::next_id` then, is a file).
    pub last_file: (usize, u32, bool),
    /// The G66 call in force (`State::modal.macro_call` says whether).
    pub modal: Option<ModalCall>,
    /// The FOR statement an END_FOR jumped back to (it steps instead of
    /// starting).
    pub for_resume: Option<Key>,
    /// The statement being run spans lines: alarms map their offsets back.
    pub span_map: Option<Rc<Compiled>>,
    /// The reader moved while a statement ran (a structure scan): the run
    /// loop must re-read from the next statement.
    pub moved_reader: bool,
    /// Syntec PUSH/POP.
    pub stack: Vec<Value>,
    /// The evaluator's value stack (reused).
    pub eval_stack: Vec<Value>,
    /// Variables read before ever being set, in the order first read.
    pub unset: Vec<UnsetRead>,
    /// Text of the statement being read (reused).
    pub text: Vec<u8>,
    /// The arguments of each call level (GETARG).
    pub args: Vec<[Value; 26]>,
    /// While a Macro B word of a length or angle address is evaluated:
    /// its least input increments per unit, to which ROUND rounds (Fanuc
    /// 0i); `None` elsewhere, where ROUND gives a whole number.
    pub round_per_unit: Option<f64>,
    /// LinuxCNC's parameters, once a line used one.
    pub ngc: Option<Box<ngc::Params>>,
    /// LinuxCNC's O-word flow (repeat counts, calls), once one ran.
    pub oword: Option<Box<structure::OFlow>>,
}

impl Macros {
    pub fn new(rules: MacroRules) -> Macros {
        Macros {
            rules,
            vars: Vars::new(rules),
            cache: FastMap::default(),
            used: false,
            structure: structure::Structure::default(),
            macro_files: FastMap::default(),
            last_file: (usize::MAX, 0, false),
            modal: None,
            for_resume: None,
            span_map: None,
            moved_reader: false,
            stack: Vec::new(),
            eval_stack: Vec::new(),
            ngc: None,
            oword: None,
            unset: Vec::new(),
            text: Vec::new(),
            args: Vec::new(),
            round_per_unit: None,
        }
    }

    /// The compiled statement starting at `k`, if cached.
    #[inline]
    pub fn cached(&self, k: Key) -> Option<Rc<Compiled>> {
        self.cache.get(&k).cloned()
    }

    /// Keeps a compiled statement (unless the cache is full).
    pub fn remember(&mut self, k: Key, c: &Rc<Compiled>) {
        if self.cache.len() < CACHE_LIMIT {
            self.cache.insert(k, Rc::clone(c));
        }
    }
}

/// `(virtual start, line)` of each line a statement's text was read from.
pub(crate) type LineMap = Box<[(u32, Line)]>;

impl crate::interpreter::Interpreter<'_> {
    /// The `unset_variables` event, once, when the program read variables
    /// nothing had set (a common or global set later in the run is not
    /// listed).
    pub(crate) fn unset_report(&mut self) -> Option<vcnc_core::events::Event> {
        let unset = std::mem::take(&mut self.macros.unset);
        let vars = &mut self.macros.vars;
        let variables: Vec<vcnc_core::events::UnsetVariable> = unset
            .into_iter()
            .filter(|u| match vars.slot(u.kind, u.n) {
                vars::Slot::Common(i) => !vars.common(i).1,
                vars::Slot::Modal(i) => !vars.modal(i).1,
                vars::Slot::Global(g) => !vars.global(g).1,
                _ => true,
            })
            .map(|u| vcnc_core::events::UnsetVariable {
                name: format!("{}{}", u.kind.sigil(), u.n).into(),
                line: u.line,
                file: u.file,
            })
            .collect();
        if variables.is_empty() {
            return None;
        }
        Some(vcnc_core::events::Event::UnsetVariables {
            loc: self.flow.loc.clone(),
            variables: variables.into(),
        })
    }

    /// The value of a variable after (or during) a run: a local of the
    /// main program's level (`#1`), a common (`#100`, `#500`) or a Syntec
    /// global (`@1`); `None` when vacant or not such a variable.
    pub fn variable(&mut self, name: &str) -> Option<f64> {
        let (kind, digits) = match name.as_bytes().first() {
            Some(b'#') => (vcnc_syntax::macros::VarKind::Hash, name.get(1..)?),
            Some(b'@') => (vcnc_syntax::macros::VarKind::At, name.get(1..)?),
            _ => return None,
        };
        let n: u32 = digits.parse().ok()?;
        let vars = &mut self.macros.vars;
        let v = match vars.slot(kind, n) {
            vars::Slot::Local(i) => vars.local(0, i).0,
            vars::Slot::Common(i) => vars.common(i).0,
            vars::Slot::Modal(i) => vars.modal(i).0,
            vars::Slot::Global(g) => vars.global(g).0,
            _ => return None,
        };
        v.number()
    }

    /// The variables kept between runs (Fanuc #500–#999; Syntec #401–#999,
    /// @656–@1999) that hold a number, by name.
    pub fn kept_variables(&self) -> std::collections::BTreeMap<String, Value> {
        self.macros.vars.kept()
    }

    /// Sets kept variables from an earlier run (before [`run`]); names a
    /// variable this controller does not keep in `Err`.
    ///
    /// [`run`]: crate::interpreter::Interpreter::run
    pub fn restore_variables(
        &mut self,
        values: &std::collections::BTreeMap<String, Value>,
    ) -> Result<(), String> {
        self.macros.vars.restore(values)
    }
}
