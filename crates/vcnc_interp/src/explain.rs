//! What a code or an address means in a dialect, read from the dialect's
//! own tables: `vcnc explain`, E201's help, the dialect matrix in
//! docs/dialects.md and the editor's hover all come from here.
//!
//! ```text
//!   "G87" ─▶ Query::G(87.0) ─▶ Dialect::g(87.0) ─▶ GDef { op, group, letters, axes }
//!                                                    └▶ op.meaning(), group, the letters it reads
//!   "D"   ─▶ Query::Address(b'D') ─▶ the dialect's policy for D, and the codes whose rows read D
//! ```
//!
//! Nothing here is a second list of codes: a code is explained only if a
//! table row says what it does, so what `explain` prints and what the
//! interpreter runs cannot drift apart.

use crate::dialect::{
    AxisWords, Dialect, FrameOp, GOp, Group, IntegerWords, MDef, OffsetDefault, ThreadLead,
    ToolWords, bit,
};

/// What the user asked about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Query {
    /// A G code (`G59.1` is 59.1).
    G(f64),
    /// An M code.
    M(u32),
    /// A letter (address) on its own: `X`, `F`, `D`.
    Address(u8),
}

impl Query {
    /// Reads `G87`, `g59.1`, `M98`, `G0`, `X` (any case; `G00` is G0).
    pub fn parse(text: &str) -> Option<Query> {
        let text = text.trim();
        let mut chars = text.chars();
        let letter = chars.next()?.to_ascii_uppercase();
        if !letter.is_ascii_uppercase() {
            return None;
        }
        let rest = chars.as_str();
        // A one-byte ASCII letter: the cast is exact.
        let byte = u8::try_from(letter).ok()?;
        if rest.is_empty() {
            return Some(Query::Address(byte));
        }
        if !rest.bytes().all(|b| b.is_ascii_digit() || b == b'.') || rest.len() > 8 {
            return None;
        }
        let value: f64 = rest.parse().ok()?;
        match byte {
            b'G' => Some(Query::G(value)),
            b'M' if value.fract() == 0.0 && (0.0..10_000.0).contains(&value) => {
                // Whole and below 10,000: the cast is exact.
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                Some(Query::M(value as u32))
            }
            _ => None,
        }
    }
}

/// The answer for one dialect.
#[derive(Debug, Clone, PartialEq)]
pub enum Explanation {
    /// A code of the dialect's tables.
    Code {
        /// `G87`, `M98`.
        code: String,
        /// What it does.
        meaning: &'static str,
        /// Its modal group (`"09 canned cycles"`, `"00 one-shot"`).
        group: String,
        /// The letters it reads besides the axes (`"R Q P K"`).
        reads: String,
        /// What it does with the block's axis words, if anything special.
        axis_words: Option<&'static str>,
    },
    /// A code the controller passes on to the machine (an auxiliary M
    /// code of the dialect or a machine's own).
    Auxiliary {
        /// `M62`.
        code: String,
        /// What the dialect says of it.
        meaning: &'static str,
    },
    /// A code the dialect's document lists and vcnc does not run.
    NotRun {
        /// `G7`.
        code: String,
        /// Why.
        reason: &'static str,
    },
    /// An address.
    Address {
        /// The letter.
        letter: char,
        /// What it is in this dialect.
        meaning: String,
        /// The codes whose rows read it besides the axis words (`G04 G10 …`).
        read_by: Vec<String>,
    },
    /// The dialect has no such code.
    Unknown {
        /// `G187`.
        code: String,
    },
}

/// How a code is written: `G59.1`, `G0`, `M98`.
pub fn code_name(letter: char, tenths: u16) -> String {
    if tenths.is_multiple_of(10) {
        format!("{letter}{}", tenths / 10)
    } else {
        format!("{letter}{}.{}", tenths / 10, tenths % 10)
    }
}

/// The modal group in words, with Fanuc's number.
pub fn group_name(group: Group) -> &'static str {
    match group {
        Group::NonModal => "00 one-shot",
        Group::Motion => "01 motion",
        Group::Plane => "02 plane",
        Group::Distance => "03 absolute/incremental",
        Group::FeedMode => "05 feed mode",
        Group::Units => "06 units",
        Group::CutterComp => "07 cutter compensation",
        Group::ToolLength => "08 tool length compensation",
        Group::Cycle => "09 canned cycles",
        Group::ReturnLevel => "10 cycle return level",
        Group::Scaling => "11 scaling",
        Group::MacroModal => "12 modal macro call",
        Group::SpindleMode => "13 constant surface speed",
        Group::Wcs => "14 work coordinate system",
        Group::Path => "15 path control",
        Group::Rotation => "16 coordinate rotation",
        Group::Polar => "17 polar coordinates",
        Group::Mirror => "22 mirror image",
        Group::DiameterMode => "diameter/radius programming",
        Group::ArcDistance => "arc centre mode",
    }
}

/// The letters of a mask, `"R Q P K"` style (in alphabetical order).
fn letters(mask: u32) -> String {
    (b'A'..=b'Z')
        .filter(|l| mask & bit(*l) != 0)
        .map(|l| char::from(l).to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

/// What `query` means in `dialect`.
pub fn explain(query: Query, dialect: &Dialect) -> Explanation {
    match query {
        Query::G(value) => explain_g(value, dialect),
        Query::M(value) => explain_m(value, dialect),
        Query::Address(letter) => explain_address(letter, dialect),
    }
}

fn g_name(value: f64) -> String {
    let tenths = (value * 10.0).round();
    if (0.0..65_535.0).contains(&tenths) {
        // In range and whole: the cast is exact.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        return code_name('G', tenths as u16);
    }
    format!("G{value}")
}

fn explain_g(value: f64, dialect: &Dialect) -> Explanation {
    let code = g_name(value);
    if let Some(def) = dialect.g(value) {
        let axis_words = match def.axes {
            AxisWords::Free => None,
            AxisWords::Claim => Some("the block's axis words are its arguments"),
            AxisWords::ClaimAbsolute => {
                Some("the block's axis words are absolute coordinates for it")
            }
            AxisWords::Refuse => Some("it takes the block: no axis words besides its own letters"),
        };
        return Explanation::Code {
            code,
            meaning: def.op.meaning(),
            group: group_name(def.group).to_string(),
            reads: letters(def.letters),
            axis_words,
        };
    }
    match dialect.unsupported_reason(value) {
        Some(reason) => Explanation::NotRun { code, reason },
        None => Explanation::Unknown { code },
    }
}

fn explain_m(value: u32, dialect: &Dialect) -> Explanation {
    let code = format!("M{value}");
    if let Some(MDef { op, letters: l, .. }) = dialect.m(f64::from(value)) {
        return Explanation::Code {
            code,
            meaning: op.meaning(),
            group: "M code".to_string(),
            reads: letters(l),
            axis_words: None,
        };
    }
    match dialect.aux_m(value) {
        Some(aux) => Explanation::Auxiliary {
            code,
            meaning: aux.what,
        },
        None => Explanation::Unknown { code },
    }
}

fn explain_address(letter: u8, dialect: &Dialect) -> Explanation {
    let read_by: Vec<String> = dialect
        .g_rows()
        .filter(|(_, def)| def.letters & bit(letter) != 0)
        .map(|(code, _)| code_name('G', code))
        .chain(
            dialect
                .m_rows()
                .filter(|(_, def)| def.letters & bit(letter) != 0)
                .map(|(code, _)| format!("M{code}")),
        )
        .collect();
    Explanation::Address {
        letter: char::from(letter),
        meaning: address_meaning(letter, dialect),
        read_by,
    }
}

/// What a letter is in a dialect, from its word rules.
fn address_meaning(letter: u8, d: &Dialect) -> String {
    let integers = match d.integers {
        IntegerWords::LeastIncrement => {
            "without a decimal point in least input increments (X100 is 0.1 mm)"
        }
        IntegerWords::WholeUnits => "without a decimal point in whole units (X100 is 100 mm)",
    };
    if let Some((_, axis)) = d.incremental_words.iter().find(|(w, _)| *w == letter) {
        return format!(
            "the incremental {} axis: a distance from where the tool is, {integers}",
            char::from(*axis)
        );
    }
    if d.diameter.axis == Some(letter) {
        return format!(
            "the {} axis, a diameter under diameter programming, {integers}",
            char::from(letter)
        );
    }
    let text: String = match letter {
        b'X' | b'Y' | b'Z' => format!("the {} axis, {integers}", char::from(letter)),
        b'A' | b'B' | b'C' => format!("the rotary {} axis, degrees", char::from(letter)),
        b'U' | b'V' | b'W' => format!("the {} axis where the machine has one", char::from(letter)),
        b'I' | b'J' | b'K' => {
            "the arc centre's offset along X, Y, Z (and a code's own data where it reads it)".into()
        }
        b'R' => "the arc radius, or the R level of a canned cycle, or a code's own data".into(),
        b'F' => match d.thread_lead {
            ThreadLead::F => {
                "the feed rate (per minute or per revolution), and a thread's lead".into()
            }
            ThreadLead::FHundredths => {
                "the feed rate (per minute or per revolution), and a thread's lead (0.01 mm without a decimal point)".into()
            }
            ThreadLead::K => "the feed rate (per minute or per revolution)".into(),
        },
        b'S' => "the spindle speed (rpm, or the cutting speed under constant surface speed)".into(),
        b'T' => match d.tool_words {
            ToolWords::Select => "selects a tool; M06 puts it in the spindle".into(),
            ToolWords::TurretOffset => {
                "T tt oo: indexes the turret to station tt and applies offset oo (00 cancels)"
                    .into()
            }
        },
        b'H' => match d.offset_default {
            _ if !d
                .g(43.0)
                .is_some_and(|g| g.op == GOp::Frame(FrameOp::ToolLengthPlus)) =>
            {
                "not a tool length offset here (no G43): a code's own data where a code reads it"
                    .into()
            }
            OffsetDefault::Modal => "the tool length offset register G43/G44 read".into(),
            OffsetDefault::ToolInSpindle => {
                "a tool number whose length G43 reads (none: the tool in the spindle)".into()
            }
        },
        b'D' => match d.offset_default {
            OffsetDefault::Modal if d.d_is_radius_offset() => {
                "the cutter radius offset register G41/G42 read (modal)".into()
            }
            OffsetDefault::Modal => {
                "not a radius offset here: a code's own data where a code reads it".into()
            }
            OffsetDefault::ToolInSpindle => {
                "a tool number whose diameter G41/G42 read (none: the tool in the spindle)".into()
            }
        },
        b'N' => "a sequence number (a label for jumps and calls)".into(),
        b'O' => "a program number".into(),
        b'G' => "a preparatory function: see `vcnc explain G<n>`".into(),
        b'M' => "a miscellaneous function: see `vcnc explain M<n>`".into(),
        b'P' => "a code's own data: a dwell, a program or sequence number, a count".into(),
        b'Q' => "a code's own data: a peck depth, a shift".into(),
        b'L' => "a code's own data: a repeat count, a G10 form".into(),
        _ => "a code's own data where a code reads it".into(),
    };
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_read_codes_and_letters() {
        assert_eq!(Query::parse("G87"), Some(Query::G(87.0)));
        assert_eq!(Query::parse("g59.1"), Some(Query::G(59.1)));
        assert_eq!(Query::parse("M98"), Some(Query::M(98)));
        assert_eq!(Query::parse("x"), Some(Query::Address(b'X')));
        assert_eq!(Query::parse("G1e5"), None);
        assert_eq!(Query::parse(""), None);
        assert_eq!(Query::parse("7"), None);
        assert_eq!(Query::parse("M1.5"), None);
    }

    #[test]
    fn g87_is_what_each_table_says() {
        let fanuc = explain(Query::G(87.0), &Dialect::fanuc());
        let eia = explain(Query::G(87.0), &Dialect::eia());
        match (fanuc, eia) {
            (
                Explanation::Code {
                    meaning: f, group, ..
                },
                Explanation::Code { meaning: e, .. },
            ) => {
                assert!(f.contains("back boring"), "{f}");
                assert!(e.contains("chip-breaking"), "{e}");
                assert_eq!(group, "09 canned cycles");
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            explain(Query::G(87.0), &Dialect::grbl()),
            Explanation::Unknown { .. }
        ));
    }

    #[test]
    fn addresses_follow_the_dialects_rules() {
        let Explanation::Address {
            meaning, read_by, ..
        } = explain(Query::Address(b'D'), &Dialect::linuxcnc())
        else {
            panic!()
        };
        assert!(meaning.contains("tool number"), "{meaning}");
        assert!(read_by.contains(&"G41".to_string()), "{read_by:?}");
        let Explanation::Address { meaning, .. } =
            explain(Query::Address(b'U'), &Dialect::fanuc_lathe())
        else {
            panic!()
        };
        assert!(meaning.contains("incremental X"), "{meaning}");
    }
}
