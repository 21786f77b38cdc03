//! Number formatting shared by the writers: rounded to 1e-6, shortest form.

/// Rounds to 1e-6 and drops the sign of zero.
pub fn round6(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

/// Appends `v` (rounded) in its shortest round-trip form, e.g. `5.5`, `0.0`.
pub fn push_f64(out: &mut Vec<u8>, v: f64) {
    let mut buf = ryu::Buffer::new();
    out.extend_from_slice(buf.format(round6(v)).as_bytes());
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
            c if (c as u32) < 0x20 => out.extend_from_slice(format!("\\u{:04x}", c as u32).as_bytes()),
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
}
