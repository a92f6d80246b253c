//! STEP 7 STL: the second dialect. Its source form, operations and parameter passing differ from
//! STEP 5's; this module is where those differences live: [`ast`] is what the S7 front end
//! ([`lexer`], [`parser`]) produces, and what the compiler turns into the same VM's bytecode.

pub mod ast;
pub mod bytecode;
pub mod error;
pub mod layout;
pub mod lexer;
pub mod library;
pub mod literal;
pub mod mnemonics;
pub mod parser;
pub mod text;

pub use parser::{ParseOptions, Parsed, parse};
