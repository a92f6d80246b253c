//! awl — a STEP 5 STL (AWL) interpreter with interrupt-aware execution.
//!
//! The stages, each in its own module: [`lexer`] → [`parser`] (AST in [`ast`]) → [`compiler`]
//! (bytecode) → [`vm`] (executes) with the interrupt engine in [`vm::interrupts`] → [`trace`] and
//! [`report`].

// No unsafe code anywhere: the fuzz targets run without AddressSanitizer on that ground.
#![forbid(unsafe_code)]

pub mod address;
pub mod analyze;
pub mod ast;
#[cfg(not(target_arch = "wasm32"))]
pub mod cli;
pub mod compiler;
#[cfg(not(target_arch = "wasm32"))]
pub mod conformance;
#[cfg(not(target_arch = "wasm32"))]
pub mod dap;
pub mod debug;
pub mod diagnostics;
pub mod dialect;
pub mod docs;
pub mod dump;
pub mod fragment;
pub mod frontend;
pub mod lexer;
#[cfg(not(target_arch = "wasm32"))]
pub mod lsp;
pub mod mnemonics;
pub mod parser;
pub mod playground;
pub mod profile;
pub mod program_files;
pub mod program_status;
pub mod project;
pub mod report;
pub mod retain;
pub mod rules;
pub mod runner;
pub mod s5_float;
pub mod scenario;
#[cfg(not(target_arch = "wasm32"))]
pub mod serve;
pub mod source;
pub mod state;
pub mod step7;
pub mod suggest;
pub mod symbols;
pub mod syntax;
pub mod timeline;
pub mod trace;
pub mod vm;
