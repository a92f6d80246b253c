//! Editor support for `awl lsp`: completion, semantic tokens, formatting, quick fixes and the TextMate grammar, in plain types the server converts.
pub mod complete;
pub mod fixes;
pub mod format;
pub mod text;
pub mod textmate;
pub mod tokens;
