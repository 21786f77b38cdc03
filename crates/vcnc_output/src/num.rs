//! Number formatting shared by the writers: rounded to 1e-6, shortest form.

/// Rounds to 1e-6 and drops the sign of zero.
pub fn round6(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

/// Appends `v` (rounded) in its shortest round-trip form, e.g. `5.5`, `0.0`.
///
/// Below 1e9 the rounded value has at most 15 significant digits, so its
/// shortest round-trip form is its decimal with trailing zeros trimmed; that
/// is written with integer arithmetic (the hot path of `vcnc run`: four
/// numbers a move), and never in exponent notation (ryu would print 1e-6).
/// Larger values go through ryu.
///
/// The digits are written backwards, two at a time, into a small buffer,
/// then appended at once:
///
/// ```text
///   -99.5:  scaled = -99_500_000 → int 99, frac 500000
///   buffer  [ … | - | 9 | 9 | . | 5 | 0 0 0 0 0 ]
///                 └ at               └ end: the fraction's zeros dropped
/// ```
pub fn push_f64(out: &mut Vec<u8>, v: f64) {
    let scaled = round_half_away(v * 1e6);
    if scaled.abs() < 1e15 {
        // |scaled| < 1e15 fits an i64 exactly.
        #[allow(clippy::cast_possible_truncation)]
        let n = scaled as i64;
        out.extend_from_slice(Digits::of(n).text());
        return;
    }
    let mut buf = ryu::Buffer::new();
    out.extend_from_slice(buf.format(round6(v)).as_bytes());
}

/// The text of a number of millionths, |n| < 1e15: at most a sign, nine
/// integer digits, the point and six fraction digits.
struct Digits {
    buf: [u8; 24],
    /// Where the text starts.
    at: usize,
    /// Where it ends (before the fraction's trailing zeros).
    end: usize,
}

/// "00", "01", … "99": two digits for one division by 100.
const PAIRS: &[u8; 200] = b"\
    0001020304050607080910111213141516171819\
    2021222324252627282930313233343536373839\
    4041424344454647484950515253545556575859\
    6061626364656667686970717273747576777879\
    8081828384858687888990919293949596979899";

impl Digits {
    fn of(n: i64) -> Digits {
        let mut d = Digits {
            buf: [0; 24],
            at: 24,
            end: 24,
        };
        let abs = n.unsigned_abs();
        let frac = abs % 1_000_000;
        if frac == 0 {
            d.push(b'0');
        } else {
            // All six places, then the trailing zeros dropped.
            d.push_pair(frac % 100);
            d.push_pair(frac / 100 % 100);
            d.push_pair(frac / 10_000);
            while d.buf.get(d.end - 1) == Some(&b'0') {
                d.end -= 1;
            }
        }
        d.push(b'.');
        let mut int = abs / 1_000_000;
        while int >= 100 {
            d.push_pair(int % 100);
            int /= 100;
        }
        if int >= 10 {
            d.push_pair(int);
        } else {
            d.push(b'0' + u8::try_from(int).unwrap_or(0));
        }
        if n < 0 {
            d.push(b'-');
        }
        d
    }

    /// Puts `b` before the text so far. The buffer holds the longest text
    /// (17 bytes), so `at` never reaches zero.
    #[inline]
    fn push(&mut self, b: u8) {
        self.at -= 1;
        if let Some(slot) = self.buf.get_mut(self.at) {
            *slot = b;
        }
    }

    /// Puts the two digits of `v` < 100 before the text so far.
    #[inline]
    fn push_pair(&mut self, v: u64) {
        // `v` < 100: the cast is exact.
        #[allow(clippy::cast_possible_truncation)]
        let i = 2 * v as usize;
        if let Some(&[tens, ones]) = PAIRS.get(i..i + 2) {
            self.push(ones);
            self.push(tens);
        }
    }

    fn text(&self) -> &[u8] {
        self.buf.get(self.at..self.end).unwrap_or_default()
    }
}

/// `x.round()` without a libm call on the hot path: truncate, then step
/// away from zero when the dropped fraction is at least a half.
#[inline]
fn round_half_away(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= 4.5e15 {
        return x.round();
    }
    // |x| < 2^52: the truncating cast is exact and in range.
    #[allow(clippy::cast_possible_truncation, clippy::cast_precision_loss)]
    let t = x as i64 as f64;
    let frac = x - t;
    if frac >= 0.5 {
        t + 1.0
    } else if frac <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// Appends an integer.
pub fn push_u64(out: &mut Vec<u8>, v: u64) {
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
            let (a, b) = (round_half_away(x), x.round());
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
