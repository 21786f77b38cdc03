//! Blocks and words: what the lexer produces and the interpreter consumes.
//!
//! A [`Block`] is a fixed-capacity buffer reused for every block of a program,
//! so lexing allocates nothing. A [`Word`] keeps its value as written (sign,
//! digits, whether it had a decimal point) and its span; what the value means
//! (millimetres, least input increments, a count) is decided by the
//! interpreter, which knows the word's role.

use vcnc_core::Span;

/// Most words one block may hold (E107 beyond).
pub const MAX_WORDS: usize = 48;

/// A word address: an uppercase ASCII letter, or a dialect's multi-character
/// address (`CR=`, `IX`) numbered from 128 by the dialect's [`LexRules`].
///
/// [`LexRules`]: crate::LexRules
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Addr(pub u8);

impl Addr {
    /// `CR=`: arc radius (lathe dialect).
    pub const CR: Addr = Addr(128);
    /// `IX`: X of an arc's middle point (lathe G05).
    pub const IX: Addr = Addr(129);
    /// `IZ`: Z of an arc's middle point (lathe G05).
    pub const IZ: Addr = Addr(130);
    /// `,C`: chamfer at the end of a G01 (Fanuc lathe).
    pub const COMMA_C: Addr = Addr(131);
    /// `,R`: corner rounding at the end of a G01 (Fanuc lathe).
    pub const COMMA_R: Addr = Addr(132);
    /// `@`: polar distance from the XY origin (LinuxCNC).
    pub const AT: Addr = Addr(133);
    /// `^`: polar angle in degrees, counter-clockwise from +X (LinuxCNC).
    pub const CARET: Addr = Addr(134);

    /// Most extended addresses (their indices are 0..EXTENDED).
    pub const EXTENDED: usize = 8;

    /// Index 0..[`EXTENDED`](Self::EXTENDED) of an extended address, for
    /// per-block tables.
    pub fn extended_index(self) -> Option<usize> {
        self.0
            .checked_sub(128)
            .map(usize::from)
            .filter(|i| *i < Self::EXTENDED)
    }

    /// How the address is written, for messages.
    pub fn name(self) -> String {
        match self {
            Addr::CR => "CR=".into(),
            Addr::IX => "IX".into(),
            Addr::IZ => "IZ".into(),
            Addr::COMMA_C => ",C".into(),
            Addr::COMMA_R => ",R".into(),
            Addr::AT => "@".into(),
            Addr::CARET => "^".into(),
            Addr(l) => char::from(l).to_string(),
        }
    }

    /// The address of an uppercase letter.
    pub const fn letter(l: u8) -> Addr {
        Addr(l)
    }
    /// The letter if this is a single-letter address.
    pub fn as_letter(self) -> Option<u8> {
        self.0.is_ascii_uppercase().then_some(self.0)
    }
    /// Index 0..26 for letters, `None` for extended addresses.
    pub fn letter_index(self) -> Option<usize> {
        self.as_letter().map(|l| usize::from(l - b'A'))
    }
}

/// One word: address, value and span.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Word {
    /// The address.
    pub addr: Addr,
    /// The value exactly as written (`X5500` → 5500.0, `X5.5` → 5.5).
    pub value: f64,
    /// Whether the value was written with a decimal point.
    pub point: bool,
    /// Bytes of the whole word (letter and value) within the line.
    pub span: Span,
}

/// One block: the words between two block ends.
#[derive(Debug, Clone)]
pub struct Block {
    words: [Word; MAX_WORDS],
    len: usize,
    /// Index + 1 of the first word of each letter other than G and M.
    letters: [u8; 26],
    /// Letters present, other than G and M (bit 0 = 'A').
    present: u32,
    /// Letters whose word has no decimal point and is not zero (the
    /// least-increment trap, warning W101, is looked for only there).
    plain_values: u32,
    /// Letters whose word has a decimal point.
    pointed: u32,
    /// G, M and extended-address words, and repeated letters, counted: a
    /// block without any is plain axis words the interpreter need not sort.
    special: u8,
    /// Bytes of the block within its line (without the terminator).
    pub span: Span,
    /// The block began with `/` (block delete); the digit after it, 1 if none.
    pub deleted: Option<u8>,
    /// The block is a `%` tape mark.
    pub percent: bool,
}

impl Default for Block {
    fn default() -> Block {
        Block {
            words: [Word::default(); MAX_WORDS],
            len: 0,
            letters: [0; 26],
            present: 0,
            plain_values: 0,
            pointed: 0,
            special: 0,
            span: Span::default(),
            deleted: None,
            percent: false,
        }
    }
}

impl Block {
    /// The words in the order written.
    pub fn words(&self) -> &[Word] {
        &self.words[..self.len]
    }
    /// Whether the block holds no words (a comment or an empty line).
    pub fn is_empty(&self) -> bool {
        self.len == 0 && !self.percent
    }
    /// Empties the block for reuse (the lexer's first step; the macro
    /// front end fills a block with evaluated words the same way).
    pub fn clear(&mut self) {
        self.len = 0;
        self.letters = [0; 26];
        self.present = 0;
        self.plain_values = 0;
        self.pointed = 0;
        self.special = 0;
        self.deleted = None;
        self.percent = false;
    }
    /// Appends a word; `false` when the block is full.
    pub fn push(&mut self, w: Word) -> bool {
        let Some(slot) = self.words.get_mut(self.len) else {
            return false;
        };
        *slot = w;
        self.len += 1;
        match w.addr.letter_index() {
            Some(i) if w.addr.0 != b'G' && w.addr.0 != b'M' && self.present & (1 << i) == 0 => {
                self.present |= 1 << i;
                if w.point {
                    self.pointed |= 1 << i;
                } else if w.value != 0.0 {
                    self.plain_values |= 1 << i;
                }
                // len ≤ MAX_WORDS (48), so it fits a u8.
                self.letters[i] = u8::try_from(self.len).unwrap_or(0);
            }
            _ => self.special = self.special.saturating_add(1),
        }
        true
    }

    /// The first word of `letter` (not G or M), if any.
    #[inline]
    pub fn letter(&self, letter: u8) -> Option<Word> {
        let k = *self.letters.get(usize::from(letter.wrapping_sub(b'A')))?;
        self.words().get(usize::from(k).checked_sub(1)?).copied()
    }

    /// Letters present other than G and M (bit 0 = 'A').
    pub fn present(&self) -> u32 {
        self.present
    }

    /// Letters (not G or M) whose word is not zero and has no decimal point.
    pub fn plain_values(&self) -> u32 {
        self.plain_values
    }

    /// Letters (not G or M) whose word has a decimal point.
    pub fn pointed(&self) -> u32 {
        self.pointed
    }

    /// Whether the block holds only single letters other than G and M (no
    /// code, no extended address, no letter twice).
    pub fn is_plain(&self) -> bool {
        self.special == 0
    }
    /// The first word's span, or the block's start when it has none.
    #[inline]
    pub fn first_span(&self) -> Span {
        self.words().first().map_or(
            Span::new(self.span.start as usize, self.span.start as usize + 1),
            |w| w.span,
        )
    }
}
