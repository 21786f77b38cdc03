//! Semantic tokens: the editor colours codes, addresses, comments and
//! macro statements as the interpreter reads them (`scan`), in the
//! protocol's relative encoding (each token's line and start relative to
//! the previous one, lengths in UTF-16 units).
//!
//! | scan kind  | token type  |
//! |------------|-------------|
//! | Code       | `keyword`   |
//! | Address    | `parameter` |
//! | Comment    | `comment`   |
//! | Macro      | `macro`     |
//! | Variable   | `variable`  |
//! | Number     | `number`    |
//!
//! Columns are counted once per line, walking its characters, so a long
//! line costs its length and not its length times its tokens; at most
//! [`MAX_TOKENS`] tokens are sent.

use crate::scan::{self, Kind};
use crate::text::{Text, lines};
use lsp_types::{SemanticToken, SemanticTokenType, SemanticTokensLegend};
use vcnc_syntax::LexRules;

/// Tokens sent for one document at most.
pub const MAX_TOKENS: usize = 200_000;

/// The token types, in the legend's order.
pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: vec![
            SemanticTokenType::KEYWORD,
            SemanticTokenType::PARAMETER,
            SemanticTokenType::COMMENT,
            SemanticTokenType::MACRO,
            SemanticTokenType::VARIABLE,
            SemanticTokenType::NUMBER,
        ],
        token_modifiers: vec![],
    }
}

fn type_index(kind: Kind) -> u32 {
    match kind {
        Kind::Code => 0,
        Kind::Address => 1,
        Kind::Comment => 2,
        Kind::Macro => 3,
        Kind::Variable => 4,
        Kind::Number => 5,
    }
}

/// Every token of the document, encoded.
pub fn semantic_tokens(text: &Text, lex: &LexRules) -> Vec<SemanticToken> {
    let mut out = Vec::new();
    let (mut prev_line, mut prev_start) = (0u32, 0u32);
    for (start, line) in lines(text.as_str()) {
        let tokens = scan::tokens(line, lex);
        if tokens.is_empty() {
            continue;
        }
        let first = text.position(start);
        // (byte, protocol line, UTF-16 column) walked along the line; a
        // lone `\r` inside it starts a new protocol line.
        let mut at = (0usize, first.line, 0u32);
        for t in &tokens {
            let (Some(a), Some(b)) = (walk(line, &mut at, t.start), walk_len(line, at, t.end))
            else {
                continue;
            };
            if out.len() >= MAX_TOKENS {
                return out;
            }
            let delta_line = a.0 - prev_line;
            let delta_start = if delta_line == 0 {
                a.1 - prev_start
            } else {
                a.1
            };
            out.push(SemanticToken {
                delta_line,
                delta_start,
                length: b,
                token_type: type_index(t.kind),
                token_modifiers_bitset: 0,
            });
            (prev_line, prev_start) = a;
        }
    }
    out
}

/// Moves `at` to byte `to` of `line`; returns its (line, column).
fn walk(line: &str, at: &mut (usize, u32, u32), to: usize) -> Option<(u32, u32)> {
    let part = line.get(at.0..to)?;
    for c in part.chars() {
        if c == '\r' {
            at.1 += 1;
            at.2 = 0;
        } else {
            at.2 += u32::try_from(c.len_utf16()).ok()?;
        }
    }
    at.0 = to;
    Some((at.1, at.2))
}

/// The UTF-16 length from `at` to byte `to` (`None` across a line break).
fn walk_len(line: &str, at: (usize, u32, u32), to: usize) -> Option<u32> {
    let part = line.get(at.0..to)?;
    if part.contains('\r') {
        return None;
    }
    u32::try_from(part.chars().map(char::len_utf16).sum::<usize>()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use vcnc_interp::Dialect;

    fn tuples(text: &str, d: &Dialect) -> Vec<[u32; 4]> {
        semantic_tokens(&Text::new(text.to_string()), &d.lex)
            .iter()
            .map(|t| [t.delta_line, t.delta_start, t.length, t.token_type])
            .collect()
    }

    #[test]
    fn tokens_are_relative_and_counted_in_utf16() {
        // "(é)" is 3 characters; G01 after it starts at column 4.
        let got = tuples("(é) G01 X5.\n\n#1=2\n", &Dialect::fanuc());
        assert_eq!(
            got,
            vec![
                [0, 0, 3, 2],
                [0, 4, 3, 0],
                [0, 4, 3, 1],
                [2, 0, 2, 4],
                [0, 3, 1, 5],
            ]
        );
    }
}
