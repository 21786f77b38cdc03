//! `vcnc_lsp`: the language server behind `vcnc lsp`, and the pieces the
//! Python module shares with it (the dialect choice).
pub mod analysis;
pub mod dialect;
pub mod hover;
pub mod scan;
pub mod text;
pub mod uri;
