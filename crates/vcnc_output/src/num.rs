//! Number formatting shared by the writers: rounded to 1e-6, shortest form.

/// Rounds to 1e-6 and drops the sign of zero.
pub fn round6(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

/// Appends `v` (rounded) in its shortest round-trip form, e.g. `5.5`, `0.0`.
///
/// Below 1e8 the rounded value has at most 14 significant digits, so its
/// shortest round-trip form is its decimal with trailing zeros trimmed; that
/// is written with integer arithmetic (the hot path of `vcnc run`: four
/// numbers a move), and never in exponent notation (ryu would print 1e-6).
/// Larger values go through ryu.
///
/// The integer part and the six places of the fraction are each turned
/// into eight ASCII digits at once in a `u64` ([`digits8`]), the integer's
/// leading and the fraction's trailing zeros are cut by counting zero
/// bytes, and the text is put together in a small buffer and appended with
/// one copy of a known length:
///
/// ```text
///   -99.5:  n = -99_500_000 → int 99, frac 500000
///   int     "00000099" → "99"        frac "00500000" → "500000" → "5"
///   buffer  [ - | 9 | 9 | . | 5 | … ]
/// ```
pub fn push_f64(out: &mut Vec<u8>, v: f64) {
    Text::of(v).append_to(out);
}

/// The text of a number as [`push_f64`] writes it, kept to be written
/// again: a stream's next event often repeats a coordinate (a raster's
/// row, a feed), and copying its text costs a tenth of formatting it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Recent {
    bits: u64,
    text: Text,
}

impl Default for Recent {
    /// Holds 0.
    fn default() -> Recent {
        Recent {
            bits: 0f64.to_bits(),
            text: Text::of(0.0),
        }
    }
}

impl Recent {
    /// Appends `v` as [`push_f64`] does, formatting it only when it is
    /// not the number appended last (compared bit for bit, so that the
    /// text is always the one of `v`).
    #[inline]
    pub(crate) fn push(&mut self, out: &mut Vec<u8>, v: f64) {
        let bits = v.to_bits();
        if bits != self.bits {
            self.bits = bits;
            self.text = Text::of(v);
        }
        self.text.append_to(out);
    }
}

/// A number's text: at most 24 bytes (ryu's longest, e.g.
/// `-2.2250738585072014e-308`; the integer path's is 16), kept in three
/// words so that it is appended with three stores of a known length.
///
/// Words, not a byte array: a text is written and soon read back (the
/// next number that repeats it), and a 16-byte load of an array written
/// in 8-byte stores waits until they have reached the cache, some 15
/// cycles a number; a word is read back as it was written.
#[derive(Debug, Clone, Copy)]
struct Text {
    /// The bytes in order, the first in the low byte of the first word;
    /// those past `len` are anything.
    words: [u64; 3],
    len: usize,
}

/// The room of a [`Text`].
const TEXT: usize = 24;

impl Text {
    #[inline]
    fn of(v: f64) -> Text {
        match millionths(v) {
            Some(n) => Text::of_millionths(n),
            None => Text::of_ryu(v),
        }
    }

    #[cold]
    fn of_ryu(v: f64) -> Text {
        let mut buf = ryu::Buffer::new();
        let s = buf.format(round6(v)).as_bytes();
        let len = s.len().min(TEXT);
        let mut bytes = [0; TEXT];
        if let (Some(to), Some(from)) = (bytes.get_mut(..len), s.get(..len)) {
            to.copy_from_slice(from);
        }
        let mut words = [0; 3];
        for (w, b) in words.iter_mut().zip(bytes.chunks_exact(8)) {
            let mut le = [0; 8];
            le.copy_from_slice(b);
            *w = u64::from_le_bytes(le);
        }
        Text { words, len }
    }

    /// Appends the text: all `TEXT` bytes, then cut back to its end.
    #[inline]
    fn append_to(&self, out: &mut Vec<u8>) {
        let end = out.len() + self.len;
        out.reserve(TEXT);
        for w in self.words {
            out.extend_from_slice(&w.to_le_bytes());
        }
        out.truncate(end);
    }
}

/// `v` in millionths rounded half away from zero, when that is below
/// 1e14 in magnitude (else `None`: NaN, infinities and values of 1e8 or
/// more take ryu's path).
#[inline]
fn millionths(v: f64) -> Option<i64> {
    rounded(v * 1e6).filter(|n| n.unsigned_abs() < 100_000_000_000_000)
}

/// `x.round()` as an integer when |x| < 4.5e15 (else `None`, NaN too),
/// without a libm call: truncate, then step away from zero when the
/// dropped fraction is at least a half.
#[inline]
fn rounded(x: f64) -> Option<i64> {
    // Fails for NaN too. Below 2^52 the truncating cast is exact and in
    // range, and so is the fraction's subtraction.
    let in_range = x.abs() < 4.5e15;
    if !in_range {
        return None;
    }
    #[allow(clippy::cast_possible_truncation)]
    let t = x as i64;
    #[allow(clippy::cast_precision_loss)]
    let frac = x - t as f64;
    Some(if frac >= 0.5 {
        t + 1
    } else if frac <= -0.5 {
        t - 1
    } else {
        t
    })
}

/// The eight decimal digits of `v` < 1e8 as byte values 0–9 (not ASCII),
/// the most significant in the lowest byte, so that `to_le_bytes` reads
/// them in order: the halves of four digits, their pairs and their digits
/// are split in all lanes at once, a division by 100 or 10 being a
/// multiplication and a shift that is exact over a lane's range (a test
/// checks every value of each half).
#[inline]
fn digits8(v: u64) -> u64 {
    let halves = (v / 10_000) | ((v % 10_000) << 32);
    let hundreds = ((halves * 10_486) >> 20) & 0x0000_007F_0000_007F;
    let pairs = hundreds | (halves - hundreds * 100) << 16;
    let tens = ((pairs * 103) >> 10) & 0x000F_000F_000F_000F;
    tens | (pairs - tens * 10) << 8
}

/// ASCII '0' in each byte.
const ZEROS: u64 = u64::from_le_bytes([b'0'; 8]);

impl Text {
    /// The number of millionths `n`, |n| < 1e14.
    ///
    /// The text is put together in one 128-bit value: built byte by byte
    /// in a buffer, it was read back in a 16-byte load that waited for the
    /// narrower stores which wrote it, on every number.
    #[inline]
    fn of_millionths(n: i64) -> Text {
        let abs = n.unsigned_abs();
        let int = digits8(abs / 1_000_000);
        // Leading zero digits are the low zero bytes; the last digit stays.
        let skip = (int.trailing_zeros() / 8).min(7);
        // The fraction's six places are bytes 2..8 of its eight digits;
        // trailing zeros are its high zero bytes, and one place stays.
        let frac = digits8(abs % 1_000_000) >> 16;
        let places = 6 - (frac.leading_zeros() / 8 - 2).min(5);
        let int_len = 8 - skip;
        let int_bits = 8 * int_len;
        // The integer's digits, the point, then the six places (and two
        // '0's past them that the length leaves out; the last falls off
        // the top when there are eight integer digits and a sign).
        let int_text = u128::from((int >> (8 * skip)) + ZEROS) & ((1u128 << int_bits) - 1);
        let mut text = int_text
            | (u128::from(b'.') << int_bits)
            | (u128::from(frac + ZEROS) << (int_bits + 8));
        let negative = n < 0;
        if negative {
            text = (text << 8) | u128::from(b'-');
        }
        #[allow(clippy::cast_possible_truncation)]
        Text {
            words: [text as u64, (text >> 64) as u64, 0],
            len: (int_len + 1 + places + u32::from(negative)) as usize,
        }
    }
}

/// Appends an integer.
pub fn push_u64(out: &mut Vec<u8>, v: u64) {
    if v < 100_000_000 {
        let digits = digits8(v);
        let skip = (digits.trailing_zeros() / 8).min(7);
        let text = ((digits >> (8 * skip)) + ZEROS).to_le_bytes();
        let at_end = out.len() + (8 - skip) as usize;
        out.extend_from_slice(&text);
        out.truncate(at_end);
        return;
    }
    let mut buf = itoa::Buffer::new();
    out.extend_from_slice(buf.format(v).as_bytes());
}

/// Appends `s` as a JSON string literal.
pub fn push_json_str(out: &mut Vec<u8>, s: &str) {
    out.push(b'"');
    for c in s.chars() {
        match c {
            '"' => out.extend_from_slice(b"\\\""),
            '\\' => out.extend_from_slice(b"\\\\"),
            '\n' => out.extend_from_slice(b"\\n"),
            c if (c as u32) < 0x20 => {
                out.extend_from_slice(format!("\\u{:04x}", c as u32).as_bytes())
            }
            c => {
                let mut b = [0; 4];
                out.extend_from_slice(c.encode_utf8(&mut b).as_bytes());
            }
        }
    }
    out.push(b'"');
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounds_noise_away() {
        let mut out = Vec::new();
        push_f64(&mut out, 12.345 + 1e-12);
        out.push(b' ');
        push_f64(&mut out, -0.0000000001);
        out.push(b' ');
        push_f64(&mut out, 2000.0);
        assert_eq!(String::from_utf8(out).unwrap(), "12.345 0.0 2000.0");
    }

    #[test]
    fn writes_small_and_large_values_without_exponent() {
        let cases = [
            (0.000001, "0.000001"),
            (-0.00005, "-0.00005"),
            (0.1, "0.1"),
            (-100.0, "-100.0"),
            (123_456_789.5, "123456789.5"),
            (-999_999_999.999_999, "-999999999.999999"),
            (0.0000004, "0.0"),
            (-0.0000006, "-0.000001"),
        ];
        for (v, text) in cases {
            let mut out = Vec::new();
            push_f64(&mut out, v);
            assert_eq!(String::from_utf8(out).unwrap(), text, "value {v}");
        }
    }

    #[test]
    fn eight_digits_at_once_for_every_value_of_each_half() {
        for v in 0..10_000u64 {
            for n in [v, v * 10_000, v * 10_000 + (9_999 - v), 99_999_999 - v] {
                let digits = digits8(n).to_le_bytes().map(|d| b'0' + d);
                assert_eq!(digits, *format!("{n:08}").as_bytes(), "{n}");
            }
        }
    }

    #[test]
    fn integers_match_the_standard_library() {
        let mut out = Vec::new();
        let mut want = String::new();
        for v in (0..2_000u64).chain([9, 10, 99_999_999, 100_000_000, u64::MAX]) {
            for n in [v, v.wrapping_mul(997), v.wrapping_mul(1_000_003)] {
                push_u64(&mut out, n);
                out.push(b' ');
                want.push_str(&format!("{n} "));
            }
        }
        assert_eq!(String::from_utf8(out).unwrap(), want);
    }

    /// The text the integer path must give: the value rounded to six
    /// places by the standard library, trailing zeros dropped down to
    /// one place; from 1e8 on, ryu's.
    fn reference(v: f64) -> String {
        let r = round6(v);
        if r.is_nan() || r.abs() >= 1e8 {
            return ryu::Buffer::new().format(r).to_string();
        }
        let text = format!("{r:.6}");
        let trimmed = text.trim_end_matches('0');
        if trimmed.ends_with('.') {
            format!("{trimmed}0")
        } else {
            trimmed.to_string()
        }
    }

    /// Values of 0 to 7 places and so every count of trailing zeros,
    /// signs, zero, and the edge of the integer path (1e8).
    #[test]
    fn short_fractions_and_the_edges_match_the_reference() {
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        for places in 0..=7 {
            let scale = 10f64.powi(places);
            for _ in 0..5_000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                for v in [
                    (x % 2_000_000) as f64 / scale,
                    -((x % 3_000) as f64) / scale,
                ] {
                    let mut fast = Vec::new();
                    push_f64(&mut fast, v);
                    assert_eq!(String::from_utf8(fast).unwrap(), reference(v), "value {v}");
                }
            }
        }
        for v in [
            0.0,
            -0.0,
            99_999_999.999_999,
            99_999_999.999_999_6,
            -99_999_999.999_999,
            100_000_000.0,
            1e9,
            -4.5e9,
            f64::INFINITY,
            f64::NAN,
        ] {
            let mut fast = Vec::new();
            push_f64(&mut fast, v);
            assert_eq!(String::from_utf8(fast).unwrap(), reference(v), "value {v}");
        }
    }

    #[test]
    fn rounding_matches_the_standard_library() {
        for x in [
            0.5,
            -0.5,
            1.5,
            2.4999999999999996,
            -7.5,
            1e15,
            -3e16,
            0.49999999999999994,
            f64::NAN,
        ] {
            #[allow(clippy::cast_precision_loss)]
            let (a, b) = (rounded(x).map_or(x.round(), |n| n as f64), x.round());
            assert!(a == b || (a.is_nan() && b.is_nan()), "{x}: {a} vs {b}");
        }
    }

    #[test]
    fn integer_path_matches_ryu_on_rounded_values() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = ((x % 4_000_000_000_000) as f64 - 2e12) / 1e3 / 7.0;
            let mut fast = Vec::new();
            push_f64(&mut fast, v);
            let slow = ryu::Buffer::new().format(round6(v)).to_string();
            assert_eq!(String::from_utf8(fast).unwrap(), slow, "value {v}");
        }
    }
}
