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
/// is written with integer arithmetic (the hot path of `vcnc run`), and
/// never in exponent notation (ryu would print 1e-6). Larger values go
/// through ryu.
pub fn push_f64(out: &mut Vec<u8>, v: f64) {
    let scaled = round_half_away(v * 1e6);
    if scaled.abs() < 1e15 {
        // |scaled| < 1e15 fits an i64 exactly.
        #[allow(clippy::cast_possible_truncation)]
        let n = scaled as i64;
        if n < 0 {
            out.push(b'-');
        }
        let n = n.unsigned_abs();
        push_u64(out, n / 1_000_000);
        out.push(b'.');
        let frac = n % 1_000_000;
        if frac == 0 {
            out.push(b'0');
            return;
        }
        let mut digits = *b"000000";
        let mut f = frac;
        for d in digits.iter_mut().rev() {
            *d = b'0' + (f % 10) as u8;
            f /= 10;
        }
        let keep = 6 - frac.trailing_zeros_decimal();
        out.extend_from_slice(&digits[..keep]);
        return;
    }
    let mut buf = ryu::Buffer::new();
    out.extend_from_slice(buf.format(round6(v)).as_bytes());
}

trait TrailingZerosDecimal {
    fn trailing_zeros_decimal(self) -> usize;
}

impl TrailingZerosDecimal for u64 {
    fn trailing_zeros_decimal(mut self) -> usize {
        let mut n = 0;
        while self != 0 && self.is_multiple_of(10) {
            self /= 10;
            n += 1;
        }
        n
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
