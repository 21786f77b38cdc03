//! Validation of one block: from the lexer's word list to a table the
//! executor reads by letter and by modal group.
//!
//! This is the "validate" phase: unknown codes, duplicate words, two codes of
//! one group, two codes wanting the axis words, and words nothing uses are
//! all rejected here, before anything is executed, so an alarm leaves the
//! machine untouched. Nothing is allocated: the table is a few fixed arrays.

use crate::alarms;
use crate::dialect::FlowOp;
use crate::dialect::{
    AxisWords, Dialect, GDef, GOp, Group, M_GROUPS, MDef, MGroup, MODAL_GROUPS, bit,
};
use vcnc_core::machine::{Machine, SameGroup};
use vcnc_syntax::{Addr, Block, Diagnostic, Span, Word};

/// Most one-shot (group 00) codes in one block.
const MAX_ONCE: usize = 4;

/// Most machine-builder (or unknown) M codes in one block besides the
/// dialect's own (Fanuc 0i allows three M codes a block).
pub(crate) const MAX_OTHER_M: usize = 3;

/// Most modal codes of different groups in one block (a safe-start line
/// such as `G00 G17 G21 G40 G49 G80 G90 G94 G98` has nine).
const MAX_MODAL: usize = 12;

/// A code with the span of the word that wrote it.
#[derive(Debug, Clone, Copy)]
pub struct At<T> {
    /// The definition.
    pub def: T,
    /// Where it was written.
    pub span: Span,
}

/// A block's G codes, set up by its first: a block of axis words alone
/// (most blocks of a CAM program) leaves them unwritten instead of
/// clearing sixteen slots (a tenth of the run loop's instructions).
#[derive(Debug, Clone, Copy)]
struct GCodes {
    /// Modal-group codes in the order written (one per group).
    modal: [Option<At<GDef>>; MAX_MODAL],
    /// Index + 1 into `modal` of each group's code, by [`Group::slot`].
    modal_slot: [u8; MODAL_GROUPS],
    once: [Option<At<GDef>>; MAX_ONCE],
}

impl GCodes {
    /// None yet. Built field by field in place (a constant is copied in
    /// with a call to `memcpy`, 60 instructions a lathe block).
    #[inline(always)]
    fn new() -> GCodes {
        GCodes {
            modal: [None; MAX_MODAL],
            modal_slot: [0; MODAL_GROUPS],
            once: [None; MAX_ONCE],
        }
    }
}

/// The validated words of one block; letters are indices into the block,
/// so building the table copies nothing.
#[derive(Debug)]
pub struct Words<'b> {
    block: &'b Block,
    /// Index + 1 of each extended address (`CR=`, `IX`, `IZ`, `,C`, `,R`),
    /// 0 when absent.
    ext: [u8; Addr::EXTENDED],
    /// Extended addresses present (bit = [`Addr::extended_index`]).
    pub ext_present: u8,
    /// The G codes, from the block's first one on (`None`: none written).
    g: Option<GCodes>,
    /// The group 00 code that takes the axis words, if any.
    pub axis_user: Option<At<GDef>>,
    /// M codes by group.
    pub m: [Option<At<MDef>>; M_GROUPS],
    /// M codes the dialect does not know: the machine file's auxiliary
    /// codes (`aux`) or unknown ones (a warning), by number.
    pub other_m: [Option<At<u32>>; MAX_OTHER_M],
    /// Letters the dialect's auxiliary M codes among `other_m` read
    /// (LinuxCNC's `M62 P1`).
    pub other_letters: u32,
    /// The block's first word span (for alarms about the whole block).
    pub first: Span,
    /// Whether any G code other than a motion code, or any M code, is written
    /// (lets the common "axis words only" block skip most steps).
    pub has_codes: bool,
    /// G65 or G66: the block is a macro call whose words are its P, L and
    /// arguments; validation stops there and `macros/calls.rs` takes over.
    pub macro_call: Option<At<GDef>>,
}

impl<'b> Words<'b> {
    /// An empty table for `block`; [`fill`](Self::fill) validates it in place
    /// (building in place spares copying the table out of a `Result`).
    #[inline]
    pub fn new(block: &'b Block) -> Words<'b> {
        Words {
            block,
            ext: [0; Addr::EXTENDED],
            ext_present: 0,
            g: None,
            axis_user: None,
            m: [None; M_GROUPS],
            other_m: [None; MAX_OTHER_M],
            other_letters: 0,
            first: block.first_span(),
            has_codes: false,
            macro_call: None,
        }
    }

    /// Collects and checks the block's words. The lexer has already
    /// indexed the letters; only codes, extended addresses and repeated
    /// letters need a pass over the words: a block of single letters
    /// other than G and M, most blocks, is done with one test here, in
    /// the caller.
    #[inline(always)]
    pub fn fill(
        &mut self,
        dialect: &Dialect,
        machine: &Machine,
        axis_mask: u32,
    ) -> Result<(), Diagnostic> {
        if self.block.is_plain() {
            return Ok(());
        }
        self.fill_codes(dialect, machine, axis_mask)
    }

    /// [`fill`](Self::fill) for a block with codes, extended addresses or
    /// a repeated letter.
    #[inline(never)]
    fn fill_codes(
        &mut self,
        dialect: &Dialect,
        machine: &Machine,
        axis_mask: u32,
    ) -> Result<(), Diagnostic> {
        let same_group = machine.params.same_group_in_block;
        let block = self.block;
        let mut seen = 0u32;
        for (k, word) in block.words().iter().enumerate() {
            match word.addr.as_letter() {
                Some(b'G') => {
                    self.add_g(word, dialect, same_group)?;
                    if self.macro_call.is_some() {
                        return Ok(());
                    }
                }
                Some(b'M') => self.add_m(word, dialect, machine)?,
                Some(l) => {
                    let bit = 1 << (l - b'A');
                    if seen & bit != 0 {
                        return Err(alarms::duplicate_word(word.span, l));
                    }
                    seen |= bit;
                }
                None => self.add_extended(k, word, dialect)?,
            }
        }
        if self.has_codes {
            self.check_alone(axis_mask)?;
        }
        Ok(())
    }

    fn add_extended(&mut self, k: usize, word: &Word, dialect: &Dialect) -> Result<(), Diagnostic> {
        let i = word
            .addr
            .extended_index()
            .ok_or_else(|| alarms::address_not_in_dialect(word.span, dialect.name))?;
        if self.ext_present & (1 << i) != 0 {
            return Err(alarms::duplicate_extended(word.span, &word.addr.name()));
        }
        self.ext_present |= 1 << i;
        self.ext[i] = u8::try_from(k + 1).unwrap_or(0);
        Ok(())
    }

    /// E209 when a code that must stand alone shares its block.
    fn check_alone(&self, axis_mask: u32) -> Result<(), Diagnostic> {
        let Some(code) = self
            .once_codes()
            .chain(self.modal_codes())
            .find(|a| a.def.alone)
        else {
            return Ok(());
        };
        let axes = if matches!(code.def.axes, AxisWords::Claim | AxisWords::ClaimAbsolute) {
            axis_mask
        } else {
            0
        };
        let own = code.def.letters | bit(b'N') | axes;
        let stray = self.block.words().iter().find(|word| {
            word.span != code.span && word.addr.as_letter().is_none_or(|l| own & bit(l) == 0)
        });
        match stray {
            Some(word) => Err(alarms::not_alone(word.span, code.span)),
            None => Ok(()),
        }
    }

    /// The word of an extended address, if present.
    pub fn get_ext(&self, addr: Addr) -> Option<Word> {
        let k = *self.ext.get(addr.extended_index()?)?;
        self.block
            .words()
            .get(usize::from(k).checked_sub(1)?)
            .copied()
    }

    fn add_g(
        &mut self,
        word: &Word,
        dialect: &Dialect,
        same_group: SameGroup,
    ) -> Result<(), Diagnostic> {
        let Some(def) = dialect.g(word.value) else {
            return Err(unknown_g(word, dialect));
        };
        let at = At {
            def,
            span: word.span,
        };
        // Most codes are group 01's: one test, then the rest.
        let motion = def.group == Group::Motion;
        if !motion && matches!(def.op, GOp::Flow(FlowOp::MacroCall | FlowOp::MacroModal)) {
            self.macro_call = Some(at);
            return Ok(());
        }
        self.has_codes |= !motion;
        if def.takes_axes() {
            // G28 X0, G92 X0, G51 X0 P2., G68 X0 R90.: the code's own arguments.
            if self.axis_user.is_some_and(|u| u.span != word.span) {
                return Err(alarms::axis_conflict(word.span));
            }
            self.axis_user = Some(at);
        }
        let codes = self.g.get_or_insert_with(GCodes::new);
        match def.group.slot() {
            Some(slot) => {
                let k = codes.modal_slot.get(slot).copied().unwrap_or(0);
                if let Some(prev) = usize::from(k).checked_sub(1).and_then(|i| codes.modal[i]) {
                    if same_group == SameGroup::Alarm {
                        return Err(alarms::same_group(word.span));
                    }
                    // Last wins: the replaced code no longer takes the axes.
                    if prev.def.takes_axes() && self.axis_user.is_some_and(|u| u.span == prev.span)
                    {
                        self.axis_user = def.takes_axes().then_some(at);
                    }
                    codes.modal[usize::from(k) - 1] = Some(at);
                } else {
                    let free = codes.modal.iter().position(Option::is_none);
                    let (Some(i), Some(slot_ref)) = (free, codes.modal_slot.get_mut(slot)) else {
                        return Err(alarms::same_group(word.span));
                    };
                    codes.modal[i] = Some(at);
                    *slot_ref = u8::try_from(i + 1).unwrap_or(0);
                }
            }
            None => {
                if codes.once.iter().flatten().any(|a| a.def.op == def.op) {
                    return Err(alarms::same_group(word.span));
                }
                match codes.once.iter_mut().find(|s| s.is_none()) {
                    Some(slot) => *slot = Some(at),
                    None => return Err(alarms::same_group(word.span)),
                }
            }
        }
        Ok(())
    }

    fn add_m(
        &mut self,
        word: &Word,
        dialect: &Dialect,
        machine: &Machine,
    ) -> Result<(), Diagnostic> {
        if word.point {
            return Err(alarms::no_decimal_point(
                word.span,
                b'M',
                "M codes are whole numbers",
            ));
        }
        let Some(def) = dialect.m(word.value) else {
            return self.add_other_m(word, dialect, machine);
        };
        let slot = &mut self.m[def.group as usize];
        if slot.is_some() {
            return Err(alarms::same_m_group(word.span));
        }
        *slot = Some(At {
            def,
            span: word.span,
        });
        self.has_codes = true;
        Ok(())
    }

    /// An M code the dialect does not know: the machine's auxiliary code,
    /// or an unknown one (an alarm on a strict machine, else kept for a
    /// warning).
    #[cold]
    fn add_other_m(
        &mut self,
        word: &Word,
        dialect: &Dialect,
        machine: &Machine,
    ) -> Result<(), Diagnostic> {
        let code = u32::try_from(whole_m(word.value)).ok();
        let aux = code.and_then(|c| dialect.aux_m(c));
        let known = aux.is_some()
            || code.is_some_and(|c| {
                machine.m_codes.contains_key(&c) || machine.m_macros.contains_key(&c)
            });
        if !known && machine.params.strict_m_codes {
            return Err(alarms::unknown_m(word.span, word.value, dialect.name));
        }
        let Some(code) = code else {
            return Err(alarms::unknown_m(word.span, word.value, dialect.name));
        };
        self.has_codes = true;
        self.other_letters |= aux.map_or(0, |a| a.letters);
        match self.other_m.iter_mut().find(|s| s.is_none()) {
            Some(slot) => {
                *slot = Some(At {
                    def: code,
                    span: word.span,
                });
                Ok(())
            }
            None => Err(alarms::same_m_group(word.span)),
        }
    }

    /// Rejects any letter outside `allowed` (bit mask), pointing at the first.
    pub fn check_used(&self, allowed: u32, allowed_ext: u8) -> Result<(), Diagnostic> {
        let stray_ext = self.ext_present & !allowed_ext;
        if stray_ext != 0 {
            let word = (0..Addr::EXTENDED)
                .filter(|i| stray_ext & (1 << i) != 0)
                .filter_map(|i| {
                    self.block
                        .words()
                        .get(usize::from(self.ext[i]).checked_sub(1)?)
                        .copied()
                })
                .min_by_key(|w| w.span.start)
                .unwrap_or_default();
            return Err(alarms::extended_not_allowed(word.span, &word.addr.name()));
        }
        let stray = self.block.present() & !allowed;
        if stray == 0 {
            return Ok(());
        }
        let first = (0u8..26)
            .filter(|i| stray & (1 << i) != 0)
            .filter_map(|i| self.get(b'A' + i))
            .min_by_key(|w| w.span.start)
            .unwrap_or_default();
        Err(alarms::word_not_allowed(first.span, first.addr.0))
    }

    /// The word of letter `l`, if present.
    #[inline]
    pub fn get(&self, l: u8) -> Option<Word> {
        self.block.letter(l)
    }

    /// Letters present (bit 0 = 'A').
    pub fn present(&self) -> u32 {
        self.block.present()
    }

    /// Letters whose word is not zero and has no decimal point.
    pub fn plain_values(&self) -> u32 {
        self.block.plain_values()
    }

    /// Letters whose word has a decimal point.
    pub fn pointed(&self) -> u32 {
        self.block.pointed()
    }

    /// Whether any letter of `mask` is present.
    pub fn any(&self, mask: u32) -> bool {
        self.block.present() & mask != 0
    }

    /// Whether the block names a point: an axis of `mask`, or LinuxCNC's
    /// polar `@`/`^` (only its lexer makes them).
    pub fn moves(&self, mask: u32) -> bool {
        const POLAR: u8 = ext_bit(Addr::AT) | ext_bit(Addr::CARET);
        self.any(mask) || self.ext_present & POLAR != 0
    }

    /// Whether the block holds `,C` or `,R` (a corner at a G01's end).
    pub fn corner_word(&self) -> bool {
        const CORNER: u8 = ext_bit(Addr::COMMA_C) | ext_bit(Addr::COMMA_R);
        self.ext_present & CORNER != 0
    }

    /// The one-shot code `op`, if written.
    pub fn once(&self, op: GOp) -> Option<At<GDef>> {
        self.once_codes().find(|a| a.def.op == op).copied()
    }

    /// The block's one-shot (group 00) codes.
    pub fn once_codes(&self) -> impl Iterator<Item = &At<GDef>> {
        self.g.iter().flat_map(|g| g.once.iter().flatten())
    }

    /// The code written for modal `group`, if any.
    #[inline]
    pub fn group(&self, group: Group) -> Option<At<GDef>> {
        let g = self.g.as_ref()?;
        let k = *g.modal_slot.get(group.slot()?)?;
        g.modal
            .get(usize::from(k).checked_sub(1)?)
            .copied()
            .flatten()
    }

    /// The modal codes of the block, in the order written.
    pub fn modal_codes(&self) -> impl Iterator<Item = &At<GDef>> {
        self.g.iter().flat_map(|g| g.modal.iter().flatten())
    }

    /// The M code written for `group`, if any.
    pub fn m_of(&self, group: MGroup) -> Option<At<MDef>> {
        self.m[group as usize]
    }

    /// Letters read by the one-shot and M codes of this block.
    pub fn code_letters(&self) -> u32 {
        // A cycle code beside a group-01 code is cancelled by it (Syntec
        // 1.2.31): its words are read by nothing.
        let cancelled = self.group(Group::Motion).is_some();
        let g = self
            .once_codes()
            .chain(self.modal_codes())
            .filter(|a| !(cancelled && a.def.group == Group::Cycle))
            .fold(0, |m, a| m | a.def.letters);
        self.m
            .iter()
            .flatten()
            .fold(g | self.other_letters, |m, a| m | a.def.letters)
    }
}

/// Letters every block may carry.
pub const ALWAYS: u32 = bit(b'N') | bit(b'F') | bit(b'S') | bit(b'T');

/// An M value as a whole number in 0..=9999, or -1 (the lexer already
/// rejected points; values beyond are not M codes of any machine).
fn whole_m(v: f64) -> i64 {
    if (0.0..=9999.0).contains(&v) && v.fract() == 0.0 {
        // In range and whole: the cast is exact.
        #[allow(clippy::cast_possible_truncation)]
        let n = v as i64;
        n
    } else {
        -1
    }
}

/// E201 (or the dialect's reason for a code it lists and does not run),
/// with the hint naming the dialects that know the code; out of line, so
/// that the hot path of a block's G codes stays small.
#[cold]
#[inline(never)]
fn unknown_g(word: &Word, dialect: &Dialect) -> Diagnostic {
    match dialect.unsupported_reason(word.value) {
        Some(why) => alarms::unsupported_g(word.span, why),
        None => alarms::unknown_g(
            word.span,
            word.value,
            dialect.name,
            crate::detect::g_hint(dialect, word.value),
        ),
    }
}

/// The bit of an extended address in [`Words::ext_present`].
const fn ext_bit(a: Addr) -> u8 {
    match a.0.checked_sub(128) {
        Some(i) if (i as usize) < Addr::EXTENDED => 1 << i,
        _ => 0,
    }
}

/// A dwell's word (G04 X or P, a cycle's P): E109 if it is negative.
pub(crate) fn dwell_not_negative(w: &Word) -> Result<(), Diagnostic> {
    if w.value < 0.0 {
        return Err(alarms::value_out_of_range(
            w.span,
            w.addr.0,
            w.value,
            "a dwell is not negative",
        ));
    }
    Ok(())
}

/// A whole number word in `min..=max`.
pub(crate) fn whole(
    w: &Word,
    letter: u8,
    min: f64,
    max: f64,
    why: &str,
) -> Result<u32, Diagnostic> {
    if w.point {
        return Err(alarms::no_decimal_point(w.span, letter, why));
    }
    if w.value < min || w.value > max {
        return Err(alarms::value_out_of_range(
            w.span,
            letter,
            w.value,
            &format!("{letter_c} is {min}..{max}", letter_c = char::from(letter)),
        ));
    }
    // In range and whole (no point), so the cast is exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok(w.value as u32)
}
