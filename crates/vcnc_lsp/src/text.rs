//! A document's text and where its lines start, so that the byte offsets
//! the interpreter reports (a line's offset plus a span within it) and the
//! positions the client speaks (a line and a UTF-16 column) convert both
//! ways, and so that the client's incremental edits apply in place.
//!
//! ```text
//!   "G01 X1\r\nG02…"      starts = [0, 8, …]     Position { line: 1, character: 3 }
//!    ^0      ^8             byte 11  ◀──────────▶  (line 1 starts at byte 8; 3 UTF-16 units on)
//! ```
//!
//! Lines end where the protocol says they do (`\n`, `\r\n` or a lone
//! `\r`); the interpreter counts only `\n`, which is why everything here
//! goes through byte offsets rather than line numbers. A column past the
//! end of its line is the line's end, and a line past the last is the
//! text's end: a client that is a keystroke ahead gets the nearest place,
//! never a panic.

use lsp_types::{Position, Range};

/// A document's text with its line starts.
#[derive(Debug, Clone, Default)]
pub struct Text {
    text: String,
    /// Byte offset of each line's first byte; `starts[0] == 0`.
    starts: Vec<usize>,
}

impl Text {
    /// The text `text`, indexed.
    pub fn new(text: String) -> Text {
        let starts = line_starts(&text);
        Text { text, starts }
    }

    /// The whole text.
    pub fn as_str(&self) -> &str {
        &self.text
    }

    /// Lines in the protocol's sense.
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// The byte offset of `pos`, clamped into the text and onto a
    /// character boundary.
    pub fn offset(&self, pos: Position) -> usize {
        let Some(&start) = usize::try_from(pos.line)
            .ok()
            .and_then(|l| self.starts.get(l))
        else {
            return self.text.len();
        };
        let end = self.line_end(start);
        let line = self.text.get(start..end).unwrap_or_default();
        let mut units = 0u32;
        for (i, c) in line.char_indices() {
            if units >= pos.character {
                return start + i;
            }
            units = units.saturating_add(u32::try_from(c.len_utf16()).unwrap_or(2));
        }
        end
    }

    /// The position of byte `offset` (clamped into the text, and back to
    /// the start of the character it falls in).
    pub fn position(&self, offset: usize) -> Position {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self
            .starts
            .partition_point(|s| *s <= offset)
            .saturating_sub(1);
        let start = self.starts.get(line).copied().unwrap_or(0);
        let end = self.line_end(start);
        let upto = offset.min(end);
        let units: usize = self
            .text
            .get(start..upto)
            .map_or(0, |s| s.chars().map(char::len_utf16).sum());
        Position {
            line: u32::try_from(line).unwrap_or(u32::MAX),
            character: u32::try_from(units).unwrap_or(u32::MAX),
        }
    }

    /// The range of bytes `start..end`.
    pub fn range(&self, start: usize, end: usize) -> Range {
        Range {
            start: self.position(start),
            end: self.position(end.max(start)),
        }
    }

    /// Where the line that starts at byte `start` ends (before its line
    /// break).
    fn line_end(&self, start: usize) -> usize {
        let rest = self.text.get(start..).unwrap_or_default();
        start + rest.find(['\n', '\r']).unwrap_or(rest.len())
    }

    /// Replaces `range` (or everything, when `None`) with `new_text`: a
    /// `textDocument/didChange` content change.
    pub fn edit(&mut self, range: Option<Range>, new_text: &str) {
        match range {
            None => self.text = new_text.to_string(),
            Some(r) => {
                let start = self.offset(r.start);
                let end = self.offset(r.end).max(start);
                self.text.replace_range(start..end, new_text);
            }
        }
        self.starts = line_starts(&self.text);
    }
}

/// Byte offsets where lines start: after each `\n`, `\r\n` and lone `\r`.
fn line_starts(text: &str) -> Vec<usize> {
    let bytes = text.as_bytes();
    let mut starts = vec![0];
    let mut i = 0;
    while let Some(k) = bytes
        .get(i..)
        .and_then(|rest| rest.iter().position(|b| matches!(b, b'\n' | b'\r')))
    {
        let at = i + k;
        let next = if bytes.get(at) == Some(&b'\r') && bytes.get(at + 1) == Some(&b'\n') {
            at + 2
        } else {
            at + 1
        };
        starts.push(next);
        i = next;
    }
    starts
}

/// The 1-based line number the interpreter gives the byte at `offset`: it
/// counts `\n` only.
pub fn interp_line(text: &str, offset: usize) -> u64 {
    let upto = text.as_bytes().get(..offset).unwrap_or(text.as_bytes());
    let n = upto.iter().filter(|b| **b == b'\n').count();
    u64::try_from(n).unwrap_or(u64::MAX).saturating_add(1)
}

/// The physical lines as the interpreter reads them (split at `\n`, a
/// trailing `\r` dropped), each with its byte offset.
pub fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut offset = 0;
    text.split('\n').map(move |l| {
        let at = offset;
        offset += l.len() + 1;
        (at, l.strip_suffix('\r').unwrap_or(l))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pos(line: u32, character: u32) -> Position {
        Position { line, character }
    }

    #[test]
    fn offsets_and_positions_agree_across_line_ends_and_wide_characters() {
        // "é" is 2 bytes and 1 UTF-16 unit; "𝑥" is 4 bytes and 2 units.
        let t = Text::new("G01 X1\r\n(é𝑥) G02\rM30\n".to_string());
        assert_eq!(t.line_count(), 4);
        assert_eq!(t.offset(pos(1, 0)), 8);
        // After "(é𝑥)": 1 + 1 + 2 + 1 = 5 units, 1 + 2 + 4 + 1 = 8 bytes.
        assert_eq!(t.offset(pos(1, 5)), 16);
        assert_eq!(t.position(16), pos(1, 5));
        // Inside "𝑥" (bytes 11..15): its start.
        assert_eq!(t.position(13), pos(1, 2));
        // The lone \r ends line 1: M30 is line 2.
        assert_eq!(t.position(21), pos(2, 0));
        // Past the end of a line: its end; past the last line: the text's end.
        assert_eq!(t.offset(pos(0, 99)), 6);
        assert_eq!(t.offset(pos(9, 0)), t.as_str().len());
    }

    #[test]
    fn edits_replace_ranges_and_reindex() {
        let mut t = Text::new("G00 X0\nG01 X5 F100\nM30\n".to_string());
        t.edit(Some(Range::new(pos(1, 4), pos(1, 6))), "X7.5\nG01 Y2");
        assert_eq!(t.as_str(), "G00 X0\nG01 X7.5\nG01 Y2 F100\nM30\n");
        assert_eq!(t.line_count(), 5);
        t.edit(None, "M30");
        assert_eq!((t.as_str(), t.line_count()), ("M30", 1));
    }

    #[test]
    fn the_interpreter_counts_newlines_only() {
        let text = "A\r\nB\rC\nD";
        assert_eq!(interp_line(text, text.find('C').unwrap_or(0)), 2);
        assert_eq!(interp_line(text, text.len()), 3);
        let got: Vec<(usize, &str)> = lines(text).collect();
        assert_eq!(got, vec![(0, "A"), (3, "B\rC"), (7, "D")]);
    }
}
