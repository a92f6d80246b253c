//! The front-end toolkit both dialects' parsers are built on: the token with its span, the
//! lexer core over a dialect's logos token kind and the split into lines ([`token`]); the
//! token-slice input for nom, the failure a dialect's grammar reports and the primitive parsers
//! ([`input`]); and the tally that decides a file's mnemonic set ([`votes`]). Each dialect keeps
//! only its token kinds, its error variants and its grammar.

pub mod input;
pub mod token;
pub mod votes;

pub use input::{Failure, Grammar, Parsed, Tokens};
pub use token::{Kind, Token};
