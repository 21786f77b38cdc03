//! Streaming a program line by line in bounded memory, with seeks.
//!
//! ```text
//!   TextSource (file, memory, …)
//!        │ read_at(offset)
//!        ▼
//!   ┌──────────── buffer (64 KiB, fixed) ────────────┐
//!   │ …consumed… │ line │ line │ line │ partial line │ ← refilled on demand
//!   └────────────────────────────────────────────────┘
//! ```
//!
//! The reader never holds more than its fixed buffer, so a 500 MB program
//! runs in the same memory as a 5 kB one. Jumps (M99 P, M98 H, later GOTO and
//! WHILE) seek to a [`Cursor`] remembered or found by a forward search; a seek
//! inside the buffer costs nothing. The source is a trait so that the
//! interpreter stays free of file I/O and embeddable.

use std::io;

/// Random-access bytes of one program text.
pub trait TextSource {
    /// Fills `buf` with the bytes at `offset`; returns how many (0 at the end).
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> io::Result<usize>;
}

/// A program held in memory.
#[derive(Debug, Clone)]
pub struct MemSource<T>(pub T);

impl<T: AsRef<[u8]>> TextSource for MemSource<T> {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> io::Result<usize> {
        let data = self.0.as_ref();
        let start = usize::try_from(offset)
            .unwrap_or(usize::MAX)
            .min(data.len());
        let n = buf.len().min(data.len() - start);
        buf[..n].copy_from_slice(&data[start..start + n]);
        Ok(n)
    }
}

impl<S: TextSource + ?Sized> TextSource for Box<S> {
    fn read_at(&mut self, offset: u64, buf: &mut [u8]) -> io::Result<usize> {
        (**self).read_at(offset, buf)
    }
}

/// A position in a program: the start of a line, and a byte within it where
/// a block begins. The default is the start of the text (line 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cursor {
    /// Byte offset of the line's first byte.
    pub offset: u64,
    /// 1-based line number.
    pub line: u64,
    /// Byte index within the line where the block starts.
    pub col: u32,
}

impl Default for Cursor {
    fn default() -> Cursor {
        Cursor {
            offset: 0,
            line: 1,
            col: 0,
        }
    }
}

/// One physical line handed out by [`LineReader::next_line`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Line {
    /// Byte offset of its first byte in the source.
    pub offset: u64,
    /// 1-based line number.
    pub number: u64,
    start: usize,
    end: usize,
}

/// Why the next line could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// The source failed.
    Io(io::Error),
    /// A line longer than the buffer; the line is skipped.
    TooLong {
        /// Offset of the line's start.
        offset: u64,
        /// Its number.
        line: u64,
    },
}

/// Buffer size: the longest line that can be read (64 KiB) and its newline.
pub const BUFFER_BYTES: usize = 64 * 1024 + 1;

/// What [`LineReader::refill_for_line`] found.
enum Refilled {
    /// More text in the buffer: look for a line again.
    More,
    /// The text ends in a line of this many bytes without a `\n`.
    Last(usize),
    /// The text is over.
    End,
}

/// Reads lines from a [`TextSource`] through one fixed buffer.
pub struct LineReader<S> {
    src: S,
    buf: Box<[u8]>,
    filled: usize,
    buf_offset: u64,
    pos: usize,
    next_line_no: u64,
    eof: bool,
}

impl<S: TextSource> LineReader<S> {
    /// A reader at the start of `src`.
    pub fn new(src: S) -> LineReader<S> {
        LineReader {
            src,
            buf: vec![0; BUFFER_BYTES].into_boxed_slice(),
            filled: 0,
            buf_offset: 0,
            pos: 0,
            next_line_no: 1,
            eof: false,
        }
    }

    /// The bytes of a line just returned by [`next_line`](Self::next_line).
    pub fn bytes(&self, line: &Line) -> &[u8] {
        self.buf.get(line.start..line.end).unwrap_or(&[])
    }

    /// The next physical line without its `\n`, or `None` at the end.
    ///
    /// Every line is taken here, in the caller's code, so that it comes
    /// back in registers: when the refilling path returned the line, the
    /// two paths met in memory, and the caller read the line back in
    /// 16-byte loads that waited for the 8-byte stores which wrote it, on
    /// every line. The refilling path only says what it found.
    #[inline(always)]
    pub fn next_line(&mut self) -> Result<Option<Line>, ReadError> {
        loop {
            let window = self.buf.get(self.pos..self.filled).unwrap_or(&[]);
            // One `take` for both ends of a line, so that the caller does
            // not merge two lines (in memory) either.
            let (len, consumed) = match memchr::memchr(b'\n', window) {
                Some(k) => (k, k + 1),
                None => match self.refill_for_line()? {
                    Refilled::More => continue,
                    Refilled::Last(rest) => (rest, rest),
                    Refilled::End => return Ok(None),
                },
            };
            return Ok(Some(self.take(len, consumed)));
        }
    }

    /// What [`next_line`](Self::next_line) does when the buffer holds no
    /// whole line: refills it, or hands out the last line (without a
    /// `\n`), or skips one too long.
    #[inline(never)]
    fn refill_for_line(&mut self) -> Result<Refilled, ReadError> {
        if self.eof {
            let rest = self.filled.saturating_sub(self.pos);
            return Ok(if rest > 0 {
                Refilled::Last(rest)
            } else {
                Refilled::End
            });
        }
        if self.pos == 0 && self.filled == self.buf.len() {
            return Err(self.skip_long_line());
        }
        self.refill().map_err(ReadError::Io)?;
        Ok(Refilled::More)
    }

    /// Where the next line starts.
    pub fn position(&self) -> Cursor {
        Cursor {
            offset: self.buf_offset + self.pos as u64,
            line: self.next_line_no,
            col: 0,
        }
    }

    /// Continues reading at `to` (its `col` is the caller's business).
    pub fn seek(&mut self, to: Cursor) {
        let end = self.buf_offset + self.filled as u64;
        if to.offset >= self.buf_offset && to.offset <= end {
            self.pos = usize::try_from(to.offset - self.buf_offset).unwrap_or(self.filled);
        } else {
            self.buf_offset = to.offset;
            self.filled = 0;
            self.pos = 0;
            self.eof = false;
        }
        self.next_line_no = to.line;
    }

    /// The bytes of `line` again, for an alarm raised after the buffer may
    /// have moved (a search or a later line): re-read from the source when
    /// the buffer no longer holds it. Cold path; leaves the reader at the
    /// line after `line`.
    pub fn reread(&mut self, line: &Line) -> Vec<u8> {
        let still_here =
            self.buf_offset + line.start as u64 == line.offset && line.end <= self.filled;
        if still_here {
            return self.bytes(line).to_vec();
        }
        self.seek(Cursor {
            offset: line.offset,
            line: line.number,
            col: 0,
        });
        match self.next_line() {
            Ok(Some(l)) => self.bytes(&l).to_vec(),
            _ => Vec::new(),
        }
    }

    fn take(&mut self, len: usize, consumed: usize) -> Line {
        let line = Line {
            offset: self.buf_offset + self.pos as u64,
            number: self.next_line_no,
            start: self.pos,
            end: self.pos + len,
        };
        self.pos += consumed;
        self.next_line_no += 1;
        line
    }

    /// Moves the unread tail to the front and reads more after it.
    fn refill(&mut self) -> io::Result<()> {
        self.buf.copy_within(self.pos..self.filled, 0);
        self.filled -= self.pos;
        self.buf_offset += self.pos as u64;
        self.pos = 0;
        let at = self.buf_offset + self.filled as u64;
        let n = self.src.read_at(at, &mut self.buf[self.filled..])?;
        self.filled += n;
        self.eof = n == 0;
        Ok(())
    }

    /// Reports a line that does not fit and moves past it.
    fn skip_long_line(&mut self) -> ReadError {
        let err = ReadError::TooLong {
            offset: self.buf_offset,
            line: self.next_line_no,
        };
        loop {
            self.pos = self.filled;
            if self.refill().is_err() || self.eof {
                break;
            }
            if let Some(k) = memchr::memchr(b'\n', &self.buf[..self.filled]) {
                self.pos = k + 1;
                break;
            }
        }
        self.next_line_no += 1;
        err
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(src: &[u8]) -> Vec<(u64, u64, Vec<u8>)> {
        let mut r = LineReader::new(MemSource(src.to_vec()));
        let mut out = Vec::new();
        while let Some(l) = r.next_line().unwrap() {
            out.push((l.offset, l.number, r.bytes(&l).to_vec()));
        }
        out
    }

    #[test]
    fn numbers_lines_and_keeps_offsets() {
        let got = lines(b"G0\nG1 X1\n\nM30");
        assert_eq!(
            got,
            vec![
                (0, 1, b"G0".to_vec()),
                (3, 2, b"G1 X1".to_vec()),
                (9, 3, b"".to_vec()),
                (10, 4, b"M30".to_vec())
            ]
        );
    }

    #[test]
    fn streams_across_buffer_refills_and_seeks_back() {
        let mut text = Vec::new();
        for i in 0..20_000 {
            text.extend_from_slice(format!("N{i} G01 X{i}\n").as_bytes());
        }
        let mut r = LineReader::new(MemSource(text));
        let mut mark = None;
        let mut count = 0;
        while let Some(l) = r.next_line().unwrap() {
            if l.number == 5 {
                mark = Some(Cursor {
                    offset: l.offset,
                    line: l.number,
                    col: 0,
                });
            }
            count += 1;
        }
        assert_eq!(count, 20_000);
        r.seek(mark.unwrap());
        let l = r.next_line().unwrap().unwrap();
        assert_eq!((l.number, r.bytes(&l)), (5, &b"N4 G01 X4"[..]));
    }

    #[test]
    fn a_line_longer_than_the_buffer_is_reported_and_skipped() {
        let mut text = vec![b'X'; BUFFER_BYTES + 10];
        text.extend_from_slice(b"\nM30\n");
        let mut r = LineReader::new(MemSource(text));
        assert!(matches!(
            r.next_line(),
            Err(ReadError::TooLong { line: 1, .. })
        ));
        let l = r.next_line().unwrap().unwrap();
        assert_eq!((l.number, r.bytes(&l)), (2, &b"M30"[..]));
    }
}
