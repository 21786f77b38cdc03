//! Decimal numbers parsed digit by digit, never by Rust's float parser.
//!
//! A program number is an optional sign, digits and at most one decimal
//! point. The digits accumulate into an integer mantissa (at most 15
//! significant digits, so it is exact in an `f64`) and the value is
//! `mantissa / 10^fraction_digits`, one correctly rounded division: `5.5`,
//! `5500 / 1000` and `0.1` come out as the nearest doubles, with no `inf`,
//! `NaN` or exponent possible. Spaces between the characters of a number are
//! ignored, as on a tape reader.

/// Most digits before the decimal point.
const MAX_INT_DIGITS: u32 = 9;
/// Most significant digits in all.
const MAX_SIG_DIGITS: u32 = 15;

const POW10: [f64; 16] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
];

/// Why a number could not be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NumberError {
    /// Nothing that starts a number.
    Missing,
    /// A sign or point without digits, or a second point or sign.
    Malformed,
    /// Too many digits.
    OutOfRange,
}

/// A parsed number and where it ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number {
    /// The value as written.
    pub value: f64,
    /// Whether a decimal point was written.
    pub point: bool,
    /// Byte index just past the number (trailing spaces not included).
    pub end: usize,
}

/// Parses a number starting at `bytes[start]`, skipping spaces and tabs.
///
/// ```
/// let n = vcnc_syntax::parse_number(b"-12.50 Y", 0).unwrap();
/// assert_eq!((n.value, n.point, n.end), (-12.5, true, 6));
/// ```
// Inlined into the macro parser's hot paths, as it was when the lexer
// called it too.
#[inline(always)]
pub fn parse_number(bytes: &[u8], start: usize) -> Result<Number, NumberError> {
    lex_number(bytes, start).map(|(n, _)| n)
}

/// [`parse_number`] for the lexer: the number, and where the lexer goes on,
/// which is past the spaces and tabs after the number when the fast path
/// has looked at them (it must, to know that the number ended there) and
/// at its end otherwise.
#[inline(always)]
pub(crate) fn lex_number(bytes: &[u8], start: usize) -> Result<(Number, usize), NumberError> {
    fast_number(bytes, start).map_or_else(|| slow_number(bytes, start).map(|n| (n, n.end)), Ok)
}

/// The common case in two tight loops: `[-+]digits[.digits]` with no
/// spaces inside, at most 9 digits before the point and 15 in all (the
/// fraction's length is where its loop ended, so no digit is counted). `None` sends
/// anything else to the careful path, which gives the same answer for these
/// forms. Returns the number and the index past the blanks after it.
#[inline(always)]
fn fast_number(bytes: &[u8], start: usize) -> Option<(Number, usize)> {
    let mut i = start;
    let negative = match bytes.get(i) {
        Some(b'-') => {
            i += 1;
            true
        }
        Some(b'+') => {
            i += 1;
            false
        }
        _ => false,
    };
    let digits_start = i;
    let mut mantissa: u64 = 0;
    digits(bytes, &mut i, &mut mantissa);
    let int_digits = i - digits_start;
    let point = bytes.get(i) == Some(&b'.');
    let mut frac = 0;
    if point {
        i += 1;
        let frac_start = i;
        digits(bytes, &mut i, &mut mantissa);
        frac = i - frac_start;
    }
    // Leading zeros count here, so `0000000001` takes the careful path.
    if int_digits + frac == 0
        || int_digits > MAX_INT_DIGITS as usize
        || int_digits + frac > MAX_SIG_DIGITS as usize
    {
        return None;
    }
    // A space ends the number only if no digit, point or sign follows it;
    // right after the digits a point or sign (a second point, a sign inside
    // the number) is malformed.
    let mut next = i;
    while let Some(b' ' | b'\t') = bytes.get(next) {
        next += 1;
    }
    if let Some(b'0'..=b'9' | b'.' | b'+' | b'-') = bytes.get(next) {
        return None;
    }
    // At most 15 digits: the mantissa is below 2^63, where the signed
    // conversion (one instruction, the unsigned one takes six) is exact.
    let magnitude = (mantissa as i64) as f64 / POW10[frac];
    let number = Number {
        value: if negative { -magnitude } else { magnitude },
        point,
        end: i,
    };
    Some((number, next))
}

/// Appends the digits at `bytes[*i..]` to `mantissa` and moves `i` past
/// them. An indexed loop: an iterator costs more per digit.
#[inline(always)]
fn digits(bytes: &[u8], i: &mut usize, mantissa: &mut u64) {
    while let Some(&c) = bytes.get(*i) {
        // Widened before the subtraction, so the digit is added as it is.
        let d = u64::from(c).wrapping_sub(u64::from(b'0'));
        if d > 9 {
            break;
        }
        // Wrapping: more than 15 digits go to the careful path.
        *mantissa = mantissa.wrapping_mul(10).wrapping_add(d);
        *i += 1;
    }
}

/// Spaces inside the number, leading zeros beyond 15 digits, and all errors.
fn slow_number(bytes: &[u8], start: usize) -> Result<Number, NumberError> {
    let mut i = skip_blanks(bytes, start);
    let mut negative = false;
    let mut signed = false;
    if let Some(&s @ (b'+' | b'-')) = bytes.get(i) {
        negative = s == b'-';
        signed = true;
        i = skip_blanks(bytes, i + 1);
    }
    let mut acc = Digits::default();
    let mut end = i;
    while let Some(&b) = bytes.get(i) {
        match b {
            b'0'..=b'9' => acc.digit(b - b'0')?,
            b'.' if !acc.point => acc.point = true,
            b'.' | b'+' | b'-' => return Err(NumberError::Malformed),
            b' ' | b'\t' => {
                i += 1;
                continue;
            }
            _ => break,
        }
        i += 1;
        end = i;
    }
    if acc.digits == 0 {
        return Err(if signed || acc.point {
            NumberError::Malformed
        } else {
            NumberError::Missing
        });
    }
    // Fraction digits beyond the 15th significant one were dropped: round.
    let mantissa = acc.mantissa + u64::from(acc.first_dropped.is_some_and(|d| d >= 5));
    let magnitude = mantissa as f64 / POW10[acc.frac as usize];
    let value = if negative { -magnitude } else { magnitude };
    Ok(Number {
        value,
        point: acc.point,
        end,
    })
}

fn skip_blanks(bytes: &[u8], mut i: usize) -> usize {
    while matches!(bytes.get(i), Some(b' ' | b'\t')) {
        i += 1;
    }
    i
}

#[derive(Default)]
struct Digits {
    mantissa: u64,
    digits: u32,
    significant: u32,
    int_digits: u32,
    frac: u32,
    point: bool,
    /// The first fraction digit beyond the precision kept, if any.
    first_dropped: Option<u8>,
}

impl Digits {
    fn digit(&mut self, d: u8) -> Result<(), NumberError> {
        self.digits += 1;
        if self.point && (self.significant >= MAX_SIG_DIGITS || self.frac >= MAX_SIG_DIGITS) {
            // CAM output prints doubles in full (0.2949604031677465): a
            // fraction digit beyond 15 significant ones is below any
            // resolution, so it is dropped, not an error.
            self.first_dropped.get_or_insert(d);
            return Ok(());
        }
        if self.significant == 0 && d == 0 {
            // Leading zeros cost nothing, but fraction zeros still scale.
            if self.point {
                self.frac += 1;
                if self.frac > MAX_SIG_DIGITS {
                    return Err(NumberError::OutOfRange);
                }
            }
            return Ok(());
        }
        self.significant += 1;
        if self.point {
            self.frac += 1;
        } else {
            self.int_digits += 1;
        }
        if self.significant > MAX_SIG_DIGITS
            || self.int_digits > MAX_INT_DIGITS
            || self.frac > MAX_SIG_DIGITS
        {
            return Err(NumberError::OutOfRange);
        }
        self.mantissa = self.mantissa * 10 + u64::from(d);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn val(s: &str) -> Result<(f64, bool), NumberError> {
        parse_number(s.as_bytes(), 0).map(|n| (n.value, n.point))
    }

    #[test]
    fn reads_the_forms_programs_use() {
        assert_eq!(val("5500"), Ok((5500.0, false)));
        assert_eq!(val("5.5"), Ok((5.5, true)));
        assert_eq!(val("-.5"), Ok((-0.5, true)));
        assert_eq!(val("5."), Ok((5.0, true)));
        assert_eq!(val("+ 1 2.5"), Ok((12.5, true)));
        assert_eq!(val("0.1"), Ok((0.1, true)));
        assert_eq!(val("0.000000000000001"), Ok((1e-15, true)));
    }

    #[test]
    fn rejects_what_is_not_a_number() {
        assert_eq!(val(""), Err(NumberError::Missing));
        assert_eq!(val("Y"), Err(NumberError::Missing));
        assert_eq!(val("-"), Err(NumberError::Malformed));
        assert_eq!(val("."), Err(NumberError::Malformed));
        assert_eq!(val("1.2.3"), Err(NumberError::Malformed));
        assert_eq!(val("1-2"), Err(NumberError::Malformed));
        assert_eq!(val("1234567890"), Err(NumberError::OutOfRange));
        // Fraction digits beyond 15 significant ones are rounded away.
        assert_eq!(val("0.1234567890123456"), Ok((0.123456789012346, true)));
        assert_eq!(val("0.2949604031677465"), Ok((0.294960403167747, true)));
        assert_eq!(val("12345678901234567.5"), Err(NumberError::OutOfRange));
        assert_eq!(val("0000000000000000000000001"), Ok((1.0, false)));
    }
}

#[cfg(test)]
mod equivalence {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The fast path agrees with the careful one wherever it answers.
        #[test]
        fn fast_path_agrees_with_slow_path(s in "[-+ 0-9.]{0,20}[ XY;]{0,2}") {
            let b = s.as_bytes();
            if let Some((fast, next)) = fast_number(b, 0) {
                prop_assert_eq!(Ok(fast), slow_number(b, 0));
                // The lexer goes on past the blanks after the number.
                prop_assert!(b[fast.end..next].iter().all(|c| matches!(c, b' ' | b'\t')));
                prop_assert!(!matches!(b.get(next), Some(b' ' | b'\t')));
            }
        }
    }
}
