//! `vcnc_syntax` turns the bytes of a word-address part program into blocks of
//! words with byte spans, and describes what is wrong with them as data.
//!
//! It is the first stage of the pipeline (`bytes → blocks → interpreter →
//! events`) and knows nothing of machines, modal state or dialect semantics:
//! only which characters form words, comments and block ends ([`LexRules`]).
//! The interpreter (`vcnc_interp`) pulls physical lines from a
//! [`LineReader`], which streams any [`TextSource`] in bounded memory and can
//! seek back to a remembered [`Cursor`] for jumps, and splits each line into
//! [`Block`]s with [`lex_block`]. Nothing here panics on any input.

mod block;
pub mod diagnostics;
mod lexer;
pub mod macros;
mod number;
mod reader;

pub use block::{Addr, Block, MAX_WORDS, Word};
pub use diagnostics::{Code, Diagnostic};
pub use lexer::{Extended, LexRules, MAX_BLOCK_BYTES, Semicolon, lex_block, next_block_start};
pub use number::parse_number;
pub use reader::{Cursor, Line, LineReader, MemSource, ReadError, TextSource};
pub use vcnc_core::{Span, clamp_u32, column_of};
