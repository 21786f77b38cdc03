//! Numbers in the text files vcnc reads besides programs — tool tables,
//! CAM header comments, grbl's `$$` dump — checked before Rust's float
//! parser sees them.
//!
//! `str::parse::<f64>` accepts `inf`, `NaN` and `1e400` (which becomes
//! infinity); these files are written by people and other programs, so a
//! number here is only a plain decimal: an optional sign, digits with at
//! most one point, and an optional exponent, whose value is finite.
//! Programs themselves go through `vcnc_syntax::number`, which reads digit
//! by digit under a dialect's rules; this is the one reader for the rest.

/// The longest number text accepted (a table value never needs more).
const MAX_LEN: usize = 40;

/// A plain decimal (`6`, `-0.5`, `.25`, `6.`, `1e-3`), finite, or `None`.
pub(crate) fn parse(text: &str) -> Option<f64> {
    let t = text.trim();
    if t.is_empty() || t.len() > MAX_LEN || !is_plain(t.as_bytes()) {
        return None;
    }
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// Whether `b` is `[+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)?`.
fn is_plain(b: &[u8]) -> bool {
    let mut i = usize::from(matches!(b.first(), Some(b'+' | b'-')));
    let digits = |i: &mut usize| {
        let start = *i;
        while b.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i - start
    };
    let mut mantissa = digits(&mut i);
    if b.get(i) == Some(&b'.') {
        i += 1;
        mantissa += digits(&mut i);
    }
    if mantissa == 0 {
        return false;
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if digits(&mut i) == 0 {
            return false;
        }
    }
    i == b.len()
}

/// A whole number `0..=max` written as digits only (`12`, not `+12` or `12.0`).
pub(crate) fn whole(text: &str, max: u64) -> Option<u64> {
    let t = text.trim();
    if t.is_empty() || t.len() > 19 || !t.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse::<u64>().ok().filter(|v| *v <= max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_decimals_only() {
        assert_eq!(parse("6"), Some(6.0));
        assert_eq!(parse(" -0.5 "), Some(-0.5));
        assert_eq!(parse(".25"), Some(0.25));
        assert_eq!(parse("6."), Some(6.0));
        assert_eq!(parse("+1e-3"), Some(0.001));
        for bad in [
            "", ".", "-", "inf", "NaN", "1e400", "1e", "1.2.3", "0x10", "1_0", "--1", "e5",
        ] {
            assert_eq!(parse(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn whole_numbers_in_range() {
        assert_eq!(whole("12", 100), Some(12));
        assert_eq!(whole("101", 100), None);
        assert_eq!(whole("+1", 100), None);
        assert_eq!(whole("99999999999999999999999", u64::MAX), None);
    }
}
