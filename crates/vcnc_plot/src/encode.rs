//! The viewer page's compact encoding: columns of integers written as
//! LEB128 varints, deflated, then base64 — so that a 1,000,000-block
//! program's page stays small and decodes fast in the browser (which
//! inflates with its own `DecompressionStream("deflate-raw")`).
//!
//! ```text
//!   column   per item                         integer
//!   pos      Δx Δy Δz from the previous item  signed, quanta of 0.1 µm
//!   kind     one byte                         0 jump, 1 rapid, 2 cut
//!   tool     index into the plot's tools      unsigned
//!   line     Δ source line                    signed
//!   file     index into the files             unsigned (only with subprograms)
//!   time     Δ time                           signed, quanta of 0.1 ms
//!   feed     Δ feed                           signed, quanta of 0.001 mm/min
//! ```
//!
//! Coordinates are quantized to [`QUANTUM_MM`] (0.1 µm): a program's own
//! figures (0.001 mm, 0.0001 in = 2.54 µm) are whole multiples of it, so
//! the readout shows them exactly, and the drawing's finest merge step
//! (1/4096 of the model) is thousands of quanta. Deltas between
//! neighbouring vertices are small numbers of one to three bytes that
//! deflate compresses further (a surfacing program's path takes about
//! 5 bytes a vertex against 27 as raw typed arrays).

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use std::fmt::Write as _;

/// The grid of the page's coordinates, mm.
pub const QUANTUM_MM: f64 = 1e-4;
/// The grid of the page's times, s.
pub const QUANTUM_S: f64 = 1e-4;
/// The grid of the page's feeds, mm/min.
pub const QUANTUM_FEED: f64 = 1e-3;

/// The nearest whole number of `quantum`s in `v`, within ±2⁵² (exact in
/// the page's JavaScript numbers); 0 for a non-finite value.
pub fn quanta(v: f64, quantum: f64) -> i64 {
    let q = (v / quantum).round();
    if !q.is_finite() {
        return 0;
    }
    // Clamped to ±2^52 before the conversion.
    #[allow(clippy::cast_possible_truncation)]
    let k = q.clamp(-4.5e15, 4.5e15) as i64;
    k
}

/// Appends `v` as an unsigned LEB128 varint.
pub fn uvar(out: &mut Vec<u8>, mut v: u64) {
    loop {
        let low = u8::try_from(v & 0x7f).unwrap_or(0);
        v >>= 7;
        if v == 0 {
            out.push(low);
            return;
        }
        out.push(low | 0x80);
    }
}

/// Appends `v` zigzag-encoded (0, −1, 1, −2 … → 0, 1, 2, 3 …).
pub fn svar(out: &mut Vec<u8>, v: i64) {
    uvar(out, (v.wrapping_shl(1) ^ (v >> 63)).cast_unsigned());
}

/// Deflates `bytes` (raw deflate, no header) at `level` (1 fast … 9 small).
pub fn deflate(bytes: &[u8], level: u8) -> Vec<u8> {
    miniz_oxide::deflate::compress_to_vec(bytes, level)
}

/// Named columns of one table, written into one buffer.
#[derive(Debug, Default)]
pub struct Columns {
    buf: Vec<u8>,
    cols: Vec<(&'static str, usize)>,
}

impl Columns {
    /// Adds a column that `fill` writes.
    pub fn col(&mut self, name: &'static str, fill: impl FnOnce(&mut Vec<u8>)) {
        let start = self.buf.len();
        fill(&mut self.buf);
        self.cols.push((name, self.buf.len() - start));
    }

    /// Positions as deltas of quanta from the previous one (the first from
    /// zero), relative to `origin_q` (quanta).
    pub fn positions(&mut self, points: impl Iterator<Item = [f64; 3]>, origin_q: [i64; 3]) {
        self.col("pos", |out| {
            let mut last = [0i64; 3];
            for p in points {
                for k in 0..3 {
                    let q = quanta(p[k], QUANTUM_MM).saturating_sub(origin_q[k]);
                    svar(out, q.saturating_sub(last[k]));
                    last[k] = q;
                }
            }
        });
    }

    /// Writes the table as a JSON object `{"n":…,"z":"<base64>","cols":[["pos",bytes],…]}`.
    pub fn write_json(&self, out: &mut String, n: usize) {
        let _ = write!(out, "{{\"n\":{n},\"z\":\"");
        STANDARD.encode_string(deflate(&self.buf, 6), out);
        out.push_str("\",\"cols\":[");
        for (i, (name, len)) in self.cols.iter().enumerate() {
            let _ = write!(out, "{}[\"{name}\",{len}]", if i > 0 { "," } else { "" });
        }
        out.push_str("]}");
    }
}

/// Signed deltas of a sequence of integers.
pub fn deltas(out: &mut Vec<u8>, values: impl Iterator<Item = i64>) {
    let mut last = 0i64;
    for v in values {
        svar(out, v.saturating_sub(last));
        last = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varints_are_leb128_and_zigzag() {
        let mut out = Vec::new();
        uvar(&mut out, 0);
        uvar(&mut out, 127);
        uvar(&mut out, 128);
        uvar(&mut out, 300);
        assert_eq!(out, [0x00, 0x7f, 0x80, 0x01, 0xac, 0x02]);
        out.clear();
        for v in [0, -1, 1, -2, 2, i64::MIN] {
            svar(&mut out, v);
        }
        // i64::MIN zigzags to u64::MAX: ten bytes, the last 0x01.
        assert_eq!(&out[..5], [0, 1, 2, 3, 4]);
        assert_eq!(out.len(), 15);
        assert_eq!(out[14], 0x01);
    }

    #[test]
    fn program_figures_are_whole_quanta() {
        // 0.001 mm and 0.0001 in (2.54 µm) land on the grid exactly.
        assert_eq!(quanta(-99.5, QUANTUM_MM), -995_000);
        assert_eq!(quanta(1.2345 * 25.4, QUANTUM_MM), 313_563);
        assert_eq!(quanta(f64::NAN, QUANTUM_MM), 0);
        assert_eq!(quanta(1e300, QUANTUM_MM), 4_500_000_000_000_000);
    }

    #[test]
    fn deflate_round_trips() {
        let text = b"G1 X1 Y2\nG1 X1 Y2\nG1 X1 Y2\n".repeat(100);
        let z = deflate(&text, 1);
        assert!(z.len() < text.len() / 10);
        assert_eq!(miniz_oxide::inflate::decompress_to_vec(&z).unwrap(), text);
    }
}
