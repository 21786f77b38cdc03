//! Variable storage and the controller's variable table.
//!
//! ```text
//!   Fanuc 0i                         Syntec
//!   #0        vacant (read-only)     #0 / @0     vacant (read-only)
//!   #1–#33    locals, per level      #1–#400     locals, per level
//!   #100–#199 common                 #401–#999   kept between runs
//!   #500–#999 common, kept           #2001–#3100 modal variables
//!   #1000…    system (eval.rs)       #1000…      system (a few, eval.rs)
//!                                    @1–@1999    globals (@656–@1999 kept)
//!                                    @10000–@14095, @100000–@165535  Long (PLC R)
//! ```
//!
//! Locals live in one flat vector, a fixed-size slice per call level; a
//! level is pushed by a macro call and popped by its return (M98 shares its
//! caller's level). Each storage keeps a bit per variable saying whether it
//! was ever set, for the `check` report of variables read but never set.
//! "Kept" variables survive between runs only when the caller asks
//! (`vcnc --variables FILE`): the interpreter never touches files.

use super::FastMap;
use crate::dialect::{MacroRules, VarTable};
use std::collections::BTreeMap;
use vcnc_syntax::macros::{Value, VarKind};

/// Where a variable number lives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Slot {
    /// `#0`, `@0`: always vacant.
    Vacant,
    /// A local of the current level.
    Local(usize),
    /// `#100…#999` (Fanuc), `#401…#999` (Syntec).
    Common(usize),
    /// Syntec `#2001–#3100`.
    Modal(usize),
    /// Syntec `@n`.
    Global(u32),
    /// A system variable (read and written by `eval.rs`).
    System(u32),
    /// Not a variable of this controller.
    Missing,
}

/// Syntec's modal variables.
const MODAL_FIRST: u32 = 2001;
const MODAL_LAST: u32 = 3100;
/// Syntec globals held densely.
const DENSE_GLOBALS: u32 = 2000;

/// The variables of one run.
pub(crate) struct Vars {
    table: VarTable,
    size: usize,
    words: usize,
    locals: Vec<Value>,
    local_set: Vec<u64>,
    commons: Vec<Value>,
    common_set: Vec<u64>,
    modal: Vec<Value>,
    modal_set: Vec<u64>,
    globals: Vec<Value>,
    global_set: Vec<u64>,
    globals_hi: FastMap<u32, Value>,
    /// Fanuc #3001 (ms) and #3002 (h): the clock does not run off-machine.
    pub clock: [f64; 2],
    /// Fanuc #3003, #3004 (single block, feed hold control): kept, no effect.
    pub control: [f64; 2],
    /// Fanuc #3901, #3902: parts machined and parts required.
    pub parts: [f64; 2],
    /// Haas #5401–#6000 written by the program (the rest read 0).
    pub tool_life: FastMap<u32, f64>,
}

fn bit(set: &[u64], i: usize) -> bool {
    set.get(i / 64).is_some_and(|w| w & (1 << (i % 64)) != 0)
}

fn set_bit(set: &mut [u64], i: usize) {
    if let Some(w) = set.get_mut(i / 64) {
        *w |= 1 << (i % 64);
    }
}

impl Vars {
    pub fn new(rules: MacroRules) -> Vars {
        let size = usize::from(rules.locals);
        Vars {
            table: rules.variables,
            size,
            words: size.div_ceil(64),
            locals: Vec::new(),
            local_set: Vec::new(),
            commons: Vec::new(),
            common_set: Vec::new(),
            modal: Vec::new(),
            modal_set: Vec::new(),
            globals: Vec::new(),
            global_set: Vec::new(),
            globals_hi: FastMap::default(),
            clock: [0.0; 2],
            control: [0.0; 2],
            parts: [0.0; 2],
            tool_life: FastMap::default(),
        }
    }

    /// Where `kind n` lives.
    #[inline]
    pub fn slot(&self, kind: VarKind, n: u32) -> Slot {
        let local = usize::try_from(n).unwrap_or(usize::MAX);
        match (self.table, kind) {
            (_, VarKind::Hash) if n == 0 => Slot::Vacant,
            (_, VarKind::Hash) if local <= self.size => Slot::Local(local - 1),
            (VarTable::Fanuc, VarKind::Hash) => match n {
                100..=199 | 500..=999 => Slot::Common(local),
                1000.. => Slot::System(n),
                _ => Slot::Missing,
            },
            (VarTable::Syntec, VarKind::Hash) => match n {
                401..=999 => Slot::Common(local),
                MODAL_FIRST..=MODAL_LAST => Slot::Modal(local - MODAL_FIRST as usize),
                1000.. => Slot::System(n),
                _ => Slot::Missing,
            },
            (VarTable::Fanuc, VarKind::At) => Slot::Missing,
            (VarTable::Syntec, VarKind::At) => match n {
                0 => Slot::Vacant,
                1..=1999 | 10_000..=14_095 | 100_000..=165_535 => Slot::Global(n),
                _ => Slot::Missing,
            },
        }
    }

    /// Syntec globals that mirror PLC R registers hold Longs.
    pub fn long_only(&self, kind: VarKind, n: u32) -> bool {
        self.table == VarTable::Syntec
            && kind == VarKind::At
            && matches!(n, 401..=655 | 10_000..=14_095 | 100_000..=165_535)
    }

    /// Adds a call level with every local vacant; returns its number.
    pub fn push_level(&mut self) -> u32 {
        if self.locals.is_empty() {
            // Level 0, the main program's, is made on first use.
            self.locals.resize(self.size, Value::Null);
            self.local_set.resize(self.words, 0);
        }
        let level = self.locals.len() / self.size.max(1);
        self.locals
            .resize(self.locals.len() + self.size, Value::Null);
        self.local_set.resize(self.local_set.len() + self.words, 0);
        u32::try_from(level).unwrap_or(u32::MAX)
    }

    /// Drops every level from `level` up.
    pub fn pop_to(&mut self, level: u32) {
        let level = usize::try_from(level).unwrap_or(usize::MAX);
        self.locals.truncate(level.max(1) * self.size);
        self.local_set.truncate(level.max(1) * self.words);
    }

    /// The locals of `level` (for a G66 call that shares them).
    pub fn level_values(&self, level: u32) -> Vec<Value> {
        let start = usize::try_from(level).unwrap_or(0) * self.size;
        self.locals
            .get(start..start + self.size)
            .map(<[Value]>::to_vec)
            .unwrap_or_default()
    }

    /// Makes the main program's level on first use.
    #[cold]
    fn first_level(&mut self) {
        if self.locals.is_empty() {
            self.locals.resize(self.size, Value::Null);
            self.local_set.resize(self.words, 0);
        }
    }

    /// Reads a local: its value and whether it was ever set.
    #[inline]
    pub fn local(&mut self, level: u32, i: usize) -> (Value, bool) {
        let level = level as usize;
        let at = level * self.size + i;
        if at >= self.locals.len() {
            self.first_level();
            if at >= self.locals.len() {
                return (Value::Null, false);
            }
        }
        (
            self.locals[at],
            bit(&self.local_set, level * self.words * 64 + i),
        )
    }

    /// Writes a local.
    #[inline]
    pub fn set_local(&mut self, level: u32, i: usize, v: Value) {
        let level = level as usize;
        let at = level * self.size + i;
        if at >= self.locals.len() {
            self.first_level();
            if at >= self.locals.len() {
                return;
            }
        }
        self.locals[at] = v;
        set_bit(&mut self.local_set, level * self.words * 64 + i);
    }

    fn ensure_commons(&mut self) {
        if self.commons.is_empty() {
            self.commons.resize(1000, Value::Null);
            self.common_set.resize(1000usize.div_ceil(64), 0);
        }
    }

    pub fn common(&mut self, i: usize) -> (Value, bool) {
        self.ensure_commons();
        (
            self.commons.get(i).copied().unwrap_or_default(),
            bit(&self.common_set, i),
        )
    }

    pub fn set_common(&mut self, i: usize, v: Value) {
        self.ensure_commons();
        if let Some(slot) = self.commons.get_mut(i) {
            *slot = v;
            set_bit(&mut self.common_set, i);
        }
    }

    pub fn modal(&mut self, i: usize) -> (Value, bool) {
        (
            self.modal.get(i).copied().unwrap_or_default(),
            bit(&self.modal_set, i),
        )
    }

    pub fn set_modal(&mut self, i: usize, v: Value) {
        if self.modal.is_empty() {
            let n = (MODAL_LAST - MODAL_FIRST + 1) as usize;
            self.modal.resize(n, Value::Null);
            self.modal_set.resize(n.div_ceil(64), 0);
        }
        if let Some(slot) = self.modal.get_mut(i) {
            *slot = v;
            set_bit(&mut self.modal_set, i);
        }
    }

    pub fn global(&self, n: u32) -> (Value, bool) {
        if n < DENSE_GLOBALS {
            let i = n as usize;
            return (
                self.globals.get(i).copied().unwrap_or_default(),
                bit(&self.global_set, i),
            );
        }
        match self.globals_hi.get(&n) {
            Some(v) => (*v, true),
            None => (Value::Null, false),
        }
    }

    pub fn set_global(&mut self, n: u32, v: Value) {
        if n < DENSE_GLOBALS {
            if self.globals.is_empty() {
                self.globals.resize(DENSE_GLOBALS as usize, Value::Null);
                self.global_set
                    .resize((DENSE_GLOBALS as usize).div_ceil(64), 0);
            }
            let i = n as usize;
            if let Some(slot) = self.globals.get_mut(i) {
                *slot = v;
                set_bit(&mut self.global_set, i);
            }
            return;
        }
        // At most 69,632 numbers exist above the dense range: bounded.
        self.globals_hi.insert(n, v);
    }

    /// Whether `kind n` is kept between runs.
    pub fn retained(&self, kind: VarKind, n: u32) -> bool {
        match (self.table, kind) {
            (VarTable::Fanuc, VarKind::Hash) => (500..=999).contains(&n),
            (VarTable::Syntec, VarKind::Hash) => (401..=999).contains(&n),
            (VarTable::Syntec, VarKind::At) => (656..=1999).contains(&n),
            (VarTable::Fanuc, VarKind::At) => false,
        }
    }

    /// The kept variables that hold a number, by name (`#500`, `@700`).
    pub fn kept(&self) -> BTreeMap<String, Value> {
        let mut out = BTreeMap::new();
        for (i, v) in self.commons.iter().enumerate() {
            let n = u32::try_from(i).unwrap_or(0);
            if self.retained(VarKind::Hash, n) && *v != Value::Null {
                out.insert(format!("#{n}"), *v);
            }
        }
        for (i, v) in self.globals.iter().enumerate() {
            let n = u32::try_from(i).unwrap_or(0);
            if self.retained(VarKind::At, n) && *v != Value::Null {
                out.insert(format!("@{n}"), *v);
            }
        }
        out
    }

    /// Sets kept variables from a previous run; `Err` names one that is
    /// not kept on this controller.
    pub fn restore(&mut self, values: &BTreeMap<String, Value>) -> Result<(), String> {
        for (name, v) in values {
            let (kind, digits) = match name.as_bytes().first() {
                Some(b'#') => (VarKind::Hash, &name[1..]),
                Some(b'@') => (VarKind::At, &name[1..]),
                _ => return Err(format!("{name} is not a variable name (#500, @700)")),
            };
            let n: u32 = digits
                .parse()
                .map_err(|_| format!("{name} is not a variable name (#500, @700)"))?;
            if !self.retained(kind, n) {
                return Err(format!(
                    "{name} is not a variable this controller keeps between runs"
                ));
            }
            let value = match *v {
                Value::Double(x) if !x.is_finite() => {
                    return Err(format!("{name}: {x} is not a number"));
                }
                // Macro B has no Longs.
                Value::Long(i) if self.table == VarTable::Fanuc => {
                    // Kept values are program values: far below 2^53.
                    #[allow(clippy::cast_precision_loss)]
                    Value::Double(i as f64)
                }
                v => v,
            };
            match self.slot(kind, n) {
                Slot::Common(i) => self.set_common(i, value),
                Slot::Global(g) => self.set_global(g, value),
                _ => return Err(format!("{name} cannot be restored")),
            }
        }
        Ok(())
    }
}
