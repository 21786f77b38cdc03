//! Byte spans inside one physical line, and the column a person counts.
//!
//! Spans are `u32` offsets relative to the start of the line that holds the
//! block (a line longer than 4 GiB cannot be read anyway); the line itself is
//! located by its byte offset and 1-based number, kept by the reader. Columns
//! are counted in characters, so a full-width `；` counts as one.

/// A half-open byte range `start..end` within one line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Span {
    /// First byte of the range.
    pub start: u32,
    /// One past the last byte of the range.
    pub end: u32,
}

impl Span {
    /// A span from `start` to `end` (byte offsets within the line).
    pub fn new(start: usize, end: usize) -> Span {
        Span {
            start: clamp_u32(start),
            end: clamp_u32(end),
        }
    }
}

/// `v` as `u32`, saturating (offsets within one line never get that far).
pub fn clamp_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}

/// The 1-based character column of byte offset `byte` in `line`.
///
/// Bytes that are not UTF-8 (a GBK or Latin-1 comment) count as the
/// replacement characters a lossy decoding shows, so the column matches
/// what the CLI prints.
pub fn column_of(line: &[u8], byte: u32) -> u32 {
    let end = (byte as usize).min(line.len());
    let chars = String::from_utf8_lossy(&line[..end]).chars().count();
    clamp_u32(chars).saturating_add(1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_count_characters_not_bytes() {
        let line = "G01；X1".as_bytes();
        assert_eq!(column_of(line, 0), 1);
        // `；` is three bytes: X starts at byte 6 but column 5.
        assert_eq!(column_of(line, 6), 5);
    }
}
