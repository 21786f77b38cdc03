//! The scan of `--dialect auto`: one pass over a program's prefix that
//! keeps what tells dialects apart — each distinct block shape (its G and M
//! codes × 10, its letters, the motion code in force before it, so that a
//! dialect's tables can say whether it would run it), comments (header
//! names, LinuxCNC's active comments), what `;` and `//` do, macro syntax
//! (`#`, `#<name>`, `o<name> sub`, IF/WHILE/GOTO, `:=`), `$` lines, how
//! lengths are written (points, `X2.`, plain integers and their size) and
//! the signs of a lathe or a mill. It reads words the way the lexer does
//! (letters in any case, spaces inside numbers) but keeps no text beyond a
//! few evidence strings: memory is bounded by the distinct shapes.

use crate::dialect::{Dialect, bit};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

/// Comments kept from the header.
const HEADER_COMMENTS: usize = 40;

/// Lines at the start whose comments count as the program's header.
const HEADER_LINES: u32 = 60;

/// No code in a shape slot.
pub(super) const NONE: u16 = u16::MAX;

/// Axis letters (a G28 without them sends every axis home, or alarms).
pub(super) const AXIS_LETTERS: u32 = bit(b'X')
    | bit(b'Y')
    | bit(b'Z')
    | bit(b'A')
    | bit(b'B')
    | bit(b'C')
    | bit(b'U')
    | bit(b'V')
    | bit(b'W');

/// A block reduced to what decides whether a dialect runs it: its G codes
/// (× 10), M codes, letters, and the motion code in force before it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) struct Shape {
    pub(super) g: [u16; 6],
    pub(super) m: [u16; 4],
    pub(super) letters: u32,
    pub(super) modal: u16,
}

/// One word of a block: its letter and value, and how it was written.
#[derive(Debug, Clone, Copy)]
pub(super) struct Word {
    letter: u8,
    value: f64,
    point: bool,
    /// `X2.`: a point and no digit after it (the Fanuc posts' style).
    trailing_point: bool,
    /// Digits before the point (`T0101`: 4).
    int_digits: u8,
}

/// How the program writes lengths.
#[derive(Debug, Default)]
pub(super) struct Lengths {
    /// Non-zero lengths with a decimal point.
    pub(super) pointed: u32,
    /// … of which written `X2.`.
    pub(super) trailing: u32,
    /// Feeds written with a point, and those written `F1000.`.
    pub(super) f_pointed: u32,
    pub(super) f_trailing: u32,
    /// The first word written `X2.`, as written.
    pub(super) first_trailing: Option<String>,
    /// Non-zero lengths without one, their magnitudes (the first 512).
    pub(super) plain: Vec<f64>,
    /// How many there were in all.
    pub(super) plain_count: u32,
    /// The first plain one, as written (`X20`).
    pub(super) first_plain: Option<String>,
}

/// Signs of a lathe or a mill.
#[derive(Debug, Default)]
pub(super) struct Kind {
    pub(super) x: u32,
    pub(super) y: u32,
    pub(super) z: u32,
    /// Distinct values of A on moves, up to [`ROTARY_VALUES`]: an A axis
    /// turning through many angles is a mill's fourth (rotary) axis, which
    /// no lathe dialect has (a lathe's rotary axis is C); a few values are
    /// the angles of a contour (Philips' `A0 B90`, Fanuc's direct drawing
    /// input `X30. A150`).
    pub(super) a_values: Vec<f64>,
    /// A move of A alone (`G0 A180.`): a rotary axis indexing, which no
    /// contour angle is.
    pub(super) a_index: bool,
    pub(super) uw: u32,
    pub(super) turret: Option<String>,
    pub(super) g96: bool,
    pub(super) g50_s: Option<String>,
    /// A single turning cycle of Fanuc's G-code system B (`G77`, `G78`,
    /// `G79` with an axis word), as written.
    pub(super) system_b_cycle: Option<String>,
    pub(super) plane_header: Option<u16>,
    pub(super) two_block_g71: bool,
    pub(super) one_block_g71_d: bool,
    /// `G76 X Z K D` (Haas) against `G76 P Q R` then `G76 X Z P Q`.
    pub(super) one_block_g76: bool,
    pub(super) two_block_g76: bool,
    pub(super) laser_m4: bool,
    pub(super) s_on_moves: u32,
}

/// Distinct A values that make an A axis a rotary one.
const ROTARY_VALUES: usize = 8;

impl Kind {
    /// A turns as a mill's rotary axis: it indexes alone, or takes many
    /// angles.
    pub(super) fn rotary(&self) -> bool {
        self.a_index || self.a_values.len() >= ROTARY_VALUES
    }
}

impl Lengths {
    /// `self` with `other`'s words added after its own.
    fn absorb(&mut self, other: Lengths) {
        self.pointed += other.pointed;
        self.trailing += other.trailing;
        self.first_trailing = self.first_trailing.take().or(other.first_trailing);
        self.plain_count += other.plain_count;
        let room = 512usize.saturating_sub(self.plain.len());
        self.plain.extend(other.plain.into_iter().take(room));
        self.first_plain = self.first_plain.take().or(other.first_plain);
    }
}

/// What the prefix shows.
#[derive(Debug, Default)]
pub(super) struct Scan {
    /// Distinct block shapes and the first line each was seen on.
    pub(super) shapes: BTreeMap<Shape, u32>,
    /// `%@MACRO` on the first line.
    pub(super) macro_file: bool,
    /// `:=` statements (Syntec MACRO).
    pub(super) syntec_statements: bool,
    /// Custom Macro B flow (`IF [`, `WHILE [`, `GOTO`): the keyword.
    pub(super) macro_b: Option<&'static str>,
    /// `#1 = …`, `X#1`: numbered variables.
    pub(super) numbered_vars: bool,
    /// `#<_name>`: LinuxCNC's named parameters, as written.
    pub(super) named_params: Option<String>,
    /// `o<name> sub`, `o100 while`: LinuxCNC's O-word flow, as written.
    pub(super) o_words: Option<String>,
    /// LinuxCNC comments (`(MSG,`, `(DEBUG,`, `(PRINT,`).
    pub(super) ngc_comment: Option<String>,
    /// LinuxCNC polar words (`^`).
    pub(super) polar: bool,
    /// `O1234` alone: a program number.
    pub(super) program_number: bool,
    /// A `%` line before the first block (tape format).
    pub(super) percent_start: bool,
    /// `:1234`: ISO's program number.
    pub(super) colon_number: bool,
    /// `; text`.
    pub(super) semicolon_comments: bool,
    /// `;` ending blocks.
    pub(super) semicolon_ends: u32,
    /// `;` with another block after it on the same line (`G0 X1; G1 X2`),
    /// which a dialect where `;` starts a comment would skip.
    pub(super) semicolon_blocks: u32,
    /// `//` comments.
    pub(super) slash_comments: bool,
    /// `$H`, `$X`, `$$`, `$32=1`: grbl system commands, as written.
    pub(super) grbl_dollar: Option<String>,
    /// `$08684 (…)`, `$1`: a file or path header (Okuma, Citizen).
    pub(super) dollar_header: Option<String>,
    /// Extended addresses written (`CR=`, `,C`).
    pub(super) extended: BTreeSet<&'static str>,
    /// Header comments, as written (with their delimiters).
    pub(super) comments: Vec<String>,
    /// G and M codes seen (for "would it run the same").
    pub(super) g_seen: BTreeSet<u16>,
    pub(super) m_seen: BTreeSet<u16>,
    pub(super) letters_seen: u32,
    /// A G28 without axis words (every axis home, or an alarm).
    pub(super) bare_g28: bool,
    /// A G04 P with a decimal point (seconds, or an alarm).
    pub(super) dwell_p_point: bool,
    pub(super) lengths: Lengths,
    /// A's words, which count among the lengths once A shows itself a
    /// rotary axis (`A2` is 0.002° to a control counting least
    /// increments); a contour's angles do not.
    a_lengths: Lengths,
    pub(super) kind: Kind,
    pub(super) blocks: u32,
}

/// Every extended address some dialect reads, longest first.
fn extended_addresses() -> &'static [&'static str] {
    static ALL: OnceLock<Vec<&'static str>> = OnceLock::new();
    ALL.get_or_init(|| {
        let mut v: Vec<&'static str> = Dialect::all()
            .iter()
            .flat_map(|d| d.lex.extended.all().iter().map(|(t, _)| *t))
            .collect();
        v.sort_by(|a, b| b.len().cmp(&a.len()).then(a.cmp(b)));
        v.dedup();
        v
    })
}

/// LinuxCNC's O-word keywords.
const O_KEYWORDS: &[&str] = &[
    "SUB",
    "ENDSUB",
    "CALL",
    "DO",
    "WHILE",
    "ENDWHILE",
    "IF",
    "ELSEIF",
    "ELSE",
    "ENDIF",
    "REPEAT",
    "ENDREPEAT",
    "BREAK",
    "CONTINUE",
    "RETURN",
];

/// Custom Macro B's flow keywords.
const MACRO_B_KEYWORDS: &[&str] = &["IF", "WHILE", "GOTO", "THEN", "DO", "END"];

/// One block being read.
#[derive(Default)]
struct Block {
    words: Vec<Word>,
    /// Macro syntax (`#`, `[`, `=`, keywords): not a plain block.
    statement: bool,
    /// The multi-letter keywords of the block (upper case).
    keywords: Vec<String>,
    /// `o<name>` (LinuxCNC).
    o_name: bool,
}

impl Scan {
    pub(super) fn of(text: &[u8]) -> Scan {
        let mut scan = Scan::default();
        let mut modal = NONE;
        for (index, raw) in text.split(|b| *b == b'\n').enumerate() {
            let line_no = u32::try_from(index).unwrap_or(u32::MAX).saturating_add(1);
            let line = raw.strip_suffix(b"\r").unwrap_or(raw);
            if line_no == 1 && starts_with_ignore_case(trim(line), b"%@MACRO") {
                scan.macro_file = true;
                continue;
            }
            scan.line(line, line_no, &mut modal);
        }
        if scan.kind.rotary() {
            let a = std::mem::take(&mut scan.a_lengths);
            scan.lengths.absorb(a);
        }
        scan
    }

    /// One line: its comments and blocks.
    fn line(&mut self, line: &[u8], line_no: u32, modal: &mut u16) {
        let mut rest = trim(line);
        // Block delete: `/`, `/1`.
        if let Some(r) = rest.strip_prefix(b"/")
            && !r.starts_with(b"/")
        {
            let digit = r.first().is_some_and(u8::is_ascii_digit);
            rest = trim(if digit {
                r.get(1..).unwrap_or_default()
            } else {
                r
            });
        }
        match rest.first() {
            None => return,
            Some(b'%') => {
                self.percent_start |= self.blocks == 0;
                return;
            }
            Some(b'$') => {
                self.dollar(rest);
                return;
            }
            _ => {}
        }
        if contains(rest, b":=") {
            self.syntec_statements = true;
        }
        let mut block = Block::default();
        let mut i = 0;
        while let Some(&c) = rest.get(i) {
            match c {
                b'(' => {
                    let end = rest
                        .get(i..)
                        .and_then(|r| r.iter().position(|b| *b == b')'))
                        .map_or(rest.len(), |e| i + e + 1);
                    self.comment(rest.get(i..end).unwrap_or_default(), line_no);
                    i = end;
                }
                b';' => {
                    let after = trim(rest.get(i + 1..).unwrap_or_default());
                    if after.starts_with(b"//") {
                        // `G03 X1500; //absolute command`: Syntec's block
                        // end and comment.
                        self.semicolon_ends += 1;
                        self.slash_comments = true;
                        break;
                    }
                    if after.is_empty() || after.starts_with(b"(") {
                        self.semicolon_ends += u32::from(after.is_empty());
                        self.end_block(&mut block, line_no, modal);
                        if after.is_empty() {
                            return;
                        }
                        i += 1;
                    } else if is_prose(after) {
                        self.semicolon_comments = true;
                        self.comment(rest.get(i..).unwrap_or_default(), line_no);
                        break;
                    } else {
                        // Fanuc: another block on the same line.
                        self.semicolon_ends += 1;
                        self.semicolon_blocks += 1;
                        self.end_block(&mut block, line_no, modal);
                        i += 1;
                    }
                }
                b'/' if rest.get(i + 1) == Some(&b'/') => {
                    self.slash_comments = true;
                    break;
                }
                b'#' => {
                    block.statement = true;
                    if rest.get(i + 1) == Some(&b'<') {
                        let end = rest
                            .get(i..)
                            .and_then(|r| r.iter().position(|b| *b == b'>'))
                            .map_or(rest.len(), |e| i + e + 1);
                        if self.named_params.is_none() {
                            let t = rest.get(i..end).unwrap_or_default();
                            self.named_params = Some(shown(t, 24));
                        }
                        i = end;
                    } else {
                        self.numbered_vars |= rest.get(i + 1).is_some_and(u8::is_ascii_digit);
                        i += 1;
                    }
                }
                b'[' | b']' | b'=' => {
                    block.statement = true;
                    i += 1;
                }
                b'^' => {
                    self.polar = true;
                    i += 1;
                }
                b'*' => break,
                b':' if rest.get(i + 1).is_some_and(u8::is_ascii_digit) => {
                    self.colon_number = true;
                    let (_, n) = number(rest, i + 1);
                    i = n;
                    block.words.push(Word {
                        letter: b'O',
                        value: 0.0,
                        point: false,
                        trailing_point: false,
                        int_digits: 0,
                    });
                }
                c if c.is_ascii_alphabetic() || c == b',' => {
                    i = self.letters(rest, i, &mut block);
                }
                _ => i += 1,
            }
        }
        self.end_block(&mut block, line_no, modal);
    }

    /// A `$` line: a grbl system command, or a file or path header.
    fn dollar(&mut self, rest: &[u8]) {
        let word: Vec<u8> = rest
            .iter()
            .take_while(|b| !b.is_ascii_whitespace() && **b != b'(')
            .copied()
            .collect();
        let after = word.get(1..).unwrap_or_default();
        let grbl = match after.first() {
            Some(c) if c.is_ascii_alphabetic() || *c == b'$' || *c == b'#' => true,
            Some(c) if c.is_ascii_digit() => after.contains(&b'='),
            _ => false,
        };
        let slot = if grbl {
            &mut self.grbl_dollar
        } else {
            &mut self.dollar_header
        };
        if slot.is_none() {
            *slot = Some(shown(&word, 16));
        }
    }

    /// A comment (`(…)` or `; …`): header names, LinuxCNC's active
    /// comments.
    fn comment(&mut self, text: &[u8], line_no: u32) {
        let upper = text.to_ascii_uppercase();
        for active in [
            &b"(MSG,"[..],
            b"(DEBUG,",
            b"(PRINT,",
            b"(PROBEOPEN",
            b"(LOGOPEN",
        ] {
            if upper.starts_with(active) && self.ngc_comment.is_none() {
                self.ngc_comment = Some(shown(text.get(..active.len()).unwrap_or(text), 12));
            }
        }
        if line_no <= HEADER_LINES && self.comments.len() < HEADER_COMMENTS {
            self.comments.push(shown(text, 200));
        }
    }

    /// Letters at `i`: a word (`X12.5`), a keyword (`IF`, `SUB`), an
    /// extended address (`CR=`, `,C`). Returns where reading goes on.
    fn letters(&mut self, rest: &[u8], i: usize, block: &mut Block) -> usize {
        let tail = rest.get(i..).unwrap_or_default();
        for ext in extended_addresses() {
            if starts_with_ignore_case(tail, ext.as_bytes()) {
                let after = tail.get(ext.len()..).unwrap_or_default();
                let numeric = trim(after)
                    .first()
                    .is_some_and(|b| b.is_ascii_digit() || b"+-.".contains(b));
                if numeric {
                    self.extended.insert(ext);
                    return i + ext.len();
                }
            }
        }
        if tail.first() == Some(&b',') {
            return i + 1;
        }
        let run = tail.iter().take_while(|b| b.is_ascii_alphabetic()).count();
        if run >= 2 {
            let word =
                String::from_utf8_lossy(tail.get(..run).unwrap_or_default()).to_ascii_uppercase();
            block.statement = true;
            block.keywords.push(word);
            return i + run;
        }
        let letter = tail.first().map_or(b' ', u8::to_ascii_uppercase);
        // `o<name>`: a LinuxCNC O word by name.
        if letter == b'O' && tail.get(1) == Some(&b'<') {
            block.o_name = true;
            let end = tail
                .iter()
                .position(|b| *b == b'>')
                .map_or(tail.len(), |e| e + 1);
            return i + end;
        }
        let (word, next) = number(rest, i + 1);
        if let Some((value, point, trailing_point, int_digits)) = word {
            block.words.push(Word {
                letter,
                value,
                point,
                trailing_point,
                int_digits,
            });
        } else if rest.get(next).is_some_and(|b| *b == b'#' || *b == b'[') {
            // A macro value: the word is there, its value is not known.
            block.statement = true;
        }
        next
    }

    /// The block read so far ends: record its shape and its signs.
    fn end_block(&mut self, block: &mut Block, line_no: u32, modal: &mut u16) {
        let b = std::mem::take(block);
        if b.words.is_empty() && b.keywords.is_empty() && !b.o_name {
            return;
        }
        self.blocks += 1;
        let o_word = b.o_name || b.words.first().is_some_and(|w| w.letter == b'O');
        if o_word {
            if let Some(k) = b.keywords.iter().find(|k| O_KEYWORDS.contains(&k.as_str())) {
                if self.o_words.is_none() {
                    let o = if b.o_name { "o<name>" } else { "o100" };
                    self.o_words = Some(format!("{o} {}", k.to_ascii_lowercase()));
                }
                return;
            }
            if b.o_name {
                self.o_words.get_or_insert_with(|| "o<name>".to_string());
                return;
            }
            if b.words.len() == 1 && b.keywords.is_empty() {
                self.program_number = true;
                return;
            }
        }
        if let Some(k) = b
            .keywords
            .iter()
            .find_map(|k| MACRO_B_KEYWORDS.iter().find(|m| **m == k.as_str()))
            && (b.statement || *k == "GOTO")
        {
            self.macro_b.get_or_insert(k);
        }
        if b.statement || !b.keywords.is_empty() {
            return;
        }
        self.words(&b.words, line_no, modal);
    }

    /// A plain block's words.
    fn words(&mut self, words: &[Word], line_no: u32, modal: &mut u16) {
        let mut shape = Shape {
            g: [NONE; 6],
            m: [NONE; 4],
            letters: 0,
            modal: *modal,
        };
        let (mut ng, mut nm) = (0, 0);
        for w in words {
            match w.letter {
                b'G' => {
                    if let Some(code) = tenths(w.value)
                        && let Some(slot) = shape.g.get_mut(ng)
                    {
                        *slot = code;
                        ng += 1;
                        self.g_seen.insert(code);
                    }
                }
                b'M' => {
                    if let Some(code) = whole(w.value)
                        && let Some(slot) = shape.m.get_mut(nm)
                    {
                        *slot = code;
                        nm += 1;
                        self.m_seen.insert(code);
                    }
                }
                b'N' | b'O' => {}
                l => shape.letters |= bit(l),
            }
        }
        shape.g.sort_unstable();
        shape.m.sort_unstable();
        self.letters_seen |= shape.letters;
        let has = |code: u16| shape.g.contains(&code);
        // The motion code in force for the next block (the same numbers
        // are motion in every dialect that has them).
        for &code in shape.g.iter().take(ng) {
            if matches!(code, 0 | 10 | 20 | 30 | 330 | 730..=890) {
                *modal = if code == 800 { NONE } else { code };
            }
        }
        if has(800) {
            *modal = NONE;
        }
        self.shapes.entry(shape).or_insert(line_no);
        self.bare_g28 |= has(280) && shape.letters & AXIS_LETTERS == 0;
        self.dwell_p_point |= has(40) && words.iter().any(|w| w.letter == b'P' && w.point);
        self.kind_signs(words, &shape);
        // Lengths: not those of G04 (a time), G10 (offsets) or G65 (its
        // arguments).
        if !(has(40) || has(100) || has(650) || has(660)) {
            for w in words {
                self.length(w);
            }
        }
        for f in words.iter().filter(|w| w.letter == b'F' && w.point) {
            let l = &mut self.lengths;
            l.f_pointed += 1;
            l.f_trailing += u32::from(f.trailing_point);
            if f.trailing_point && l.first_trailing.is_none() {
                l.first_trailing = Some(format!("F{}.", f.value));
            }
        }
    }

    fn length(&mut self, w: &Word) {
        if !matches!(
            w.letter,
            b'X' | b'Y' | b'Z' | b'U' | b'W' | b'I' | b'J' | b'K' | b'R' | b'A'
        ) || w.value == 0.0
        {
            return;
        }
        let l = if w.letter == b'A' {
            &mut self.a_lengths
        } else {
            &mut self.lengths
        };
        if w.point {
            l.pointed += 1;
            l.trailing += u32::from(w.trailing_point);
            if w.trailing_point && l.first_trailing.is_none() {
                l.first_trailing = Some(format!("{}{}.", char::from(w.letter), w.value));
            }
        } else {
            l.plain_count += 1;
            if l.plain.len() < 512 {
                l.plain.push(w.value.abs());
            }
            if l.first_plain.is_none() {
                l.first_plain = Some(format!("{}{}", char::from(w.letter), w.value));
            }
        }
    }

    /// Lathe and mill signs of one block.
    fn kind_signs(&mut self, words: &[Word], shape: &Shape) {
        let k = &mut self.kind;
        let has = |code: u16| shape.g.contains(&code);
        let get = |l: u8| words.iter().find(|w| w.letter == l);
        let moving = shape.modal != NONE || shape.g.iter().any(|g| matches!(g, 0..=30));
        if moving {
            k.x += u32::from(get(b'X').is_some());
            k.y += u32::from(get(b'Y').is_some());
            k.z += u32::from(get(b'Z').is_some());
            if let Some(a) = get(b'A') {
                if k.a_values.len() < ROTARY_VALUES && !k.a_values.contains(&a.value) {
                    k.a_values.push(a.value);
                }
                k.a_index |= [b'X', b'Y', b'Z'].iter().all(|l| get(*l).is_none());
            }
        }
        k.uw += u32::from(get(b'U').is_some() || get(b'W').is_some());
        let m6 = shape.m.contains(&6);
        if let Some(t) = get(b'T')
            && !m6
            && !t.point
            && t.value >= 101.0
            && t.value < 10_000.0
        {
            // `T0101`, `T0202`, `T101`: station and offset.
            let (station, offset) = ((t.value / 100.0).floor(), t.value % 100.0);
            if k.turret.is_none() && station >= 1.0 && offset >= 1.0 && t.int_digits >= 3 {
                k.turret = Some(format!("T{:0w$}", t.value, w = usize::from(t.int_digits)));
            }
        }
        k.g96 |= has(960) && get(b'S').is_some();
        if has(500)
            && let Some(s) = get(b'S')
        {
            k.g50_s.get_or_insert_with(|| format!("G50 S{}", s.value));
        }
        let planes = shape
            .g
            .iter()
            .filter(|g| matches!(g, 170 | 180 | 190))
            .count();
        if planes == 1 && shape.g.iter().filter(|g| **g != NONE).count() >= 3 {
            let plane = shape
                .g
                .iter()
                .copied()
                .find(|g| matches!(g, 170 | 180 | 190));
            if k.plane_header.is_none() && k.x + k.z == 0 {
                k.plane_header = plane;
            }
        }
        if let Some(code) = shape.g.iter().find(|g| matches!(g, 770 | 780 | 790))
            && (get(b'X').is_some() || get(b'Z').is_some() || get(b'U').is_some())
        {
            k.system_b_cycle
                .get_or_insert_with(|| format!("G{}", code / 10));
        }
        if has(710) || has(720) {
            let (p, q) = (get(b'P').is_some(), get(b'Q').is_some());
            k.two_block_g71 |= get(b'U').is_some() && get(b'R').is_some() && !p;
            k.one_block_g71_d |= p && q && get(b'D').is_some();
        }
        if has(760) {
            let (p, q) = (get(b'P').is_some(), get(b'Q').is_some());
            k.one_block_g76 |= get(b'K').is_some() && get(b'D').is_some() && !p && !q;
            k.two_block_g76 |= p && q && get(b'X').is_none() && get(b'Z').is_none();
        }
        k.laser_m4 |= shape.m.contains(&4);
        let feed = has(10) || (shape.modal == 10 && !shape.g.iter().any(|g| matches!(g, 0..=30)));
        k.s_on_moves += u32::from(feed && get(b'S').is_some());
    }
}

/// A number after a letter: value, point, `2.`, integer digits; and where
/// it ends. Spaces inside are skipped, as the lexer does.
#[allow(clippy::type_complexity)]
fn number(text: &[u8], mut i: usize) -> (Option<(f64, bool, bool, u8)>, usize) {
    while text.get(i).is_some_and(|b| *b == b' ' || *b == b'\t') {
        i += 1;
    }
    let mut sign = 1.0;
    if let Some(&c) = text.get(i)
        && (c == b'+' || c == b'-')
    {
        sign = if c == b'-' { -1.0 } else { 1.0 };
        i += 1;
    }
    let (mut int, mut frac, mut scale) = (0.0f64, 0.0f64, 1.0f64);
    let (mut digits, mut int_digits, mut point, mut frac_digits) = (0u32, 0u8, false, 0u32);
    while let Some(&c) = text.get(i) {
        match c {
            b'0'..=b'9' if !point => {
                int = int * 10.0 + f64::from(c - b'0');
                int_digits = int_digits.saturating_add(1);
                digits += 1;
            }
            b'0'..=b'9' => {
                scale /= 10.0;
                frac += f64::from(c - b'0') * scale;
                frac_digits += 1;
                digits += 1;
            }
            b'.' if !point => point = true,
            b' ' | b'\t'
                if text
                    .get(i + 1)
                    .is_some_and(|b| b.is_ascii_digit() || *b == b'.') => {}
            _ => break,
        }
        i += 1;
        if digits > 15 {
            // Far past any real word: read on without adding.
            while text.get(i).is_some_and(u8::is_ascii_digit) {
                i += 1;
            }
            break;
        }
    }
    if digits == 0 {
        return (None, i);
    }
    let value = sign * (int + frac);
    (
        Some((value, point, point && frac_digits == 0, int_digits)),
        i,
    )
}

/// A G code's value × 10 (`59.1` → 591), if it has at most one decimal.
fn tenths(v: f64) -> Option<u16> {
    let t = (v * 10.0).round();
    if (v * 10.0 - t).abs() > 1e-6 || !(0.0..10_000.0).contains(&t) {
        return None;
    }
    // In 0..10000 and whole.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Some(t as u16)
}

/// An M code's value, if whole and below 1000.
fn whole(v: f64) -> Option<u16> {
    if v.fract() != 0.0 || !(0.0..1000.0).contains(&v) {
        return None;
    }
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Some(v as u16)
}

fn trim(s: &[u8]) -> &[u8] {
    let start = s
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(s.len());
    let end = s
        .iter()
        .rposition(|b| !b.is_ascii_whitespace())
        .map_or(start, |e| e + 1);
    s.get(start..end).unwrap_or_default()
}

fn starts_with_ignore_case(s: &[u8], prefix: &[u8]) -> bool {
    s.get(..prefix.len())
        .is_some_and(|h| h.eq_ignore_ascii_case(prefix))
}

fn contains(s: &[u8], needle: &[u8]) -> bool {
    s.windows(needle.len()).any(|w| w == needle)
}

/// Text after a `;` that is not G-code: two letters in a row outside a
/// comment (`; Set units`, `;svg#path`), or characters no block has.
fn is_prose(after: &[u8]) -> bool {
    let mut in_comment = false;
    let mut prev_alpha = false;
    for &c in after {
        match c {
            b'(' => in_comment = true,
            b')' => in_comment = false,
            _ if in_comment => {}
            c if c.is_ascii_alphabetic() => {
                if prev_alpha {
                    return true;
                }
                prev_alpha = true;
                continue;
            }
            c if c.is_ascii_digit() || b" \t.+-;".contains(&c) => {}
            _ => return true,
        }
        prev_alpha = false;
    }
    false
}

/// Bytes as text for an evidence string, at most `max` characters.
pub(super) fn shown(text: &[u8], max: usize) -> String {
    let s = String::from_utf8_lossy(text);
    let s = s.trim();
    if s.chars().count() <= max {
        return s.to_string();
    }
    let mut out: String = s.chars().take(max).collect();
    out.push('…');
    out
}
