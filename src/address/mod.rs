//! The address model of both dialects: where the image areas lie ([`Layout`]), the CPU's
//! ranges ([`range`]), and the operands a scenario, the debugger or a watch names — STEP 5's
//! word-addressed data blocks (`DB 10 DW 3`) and STEP 7's byte-addressed ones (`DB5.DBW 4`),
//! in either mnemonic set ([`operand`]) — and how each dialect writes the values they hold
//! ([`notation`]).

pub mod declared;
mod layout;
mod memory_area;
pub mod modbus_map;
pub mod notation;
pub mod operand;
pub mod range;

pub use layout::{ImageArea, Layout};
pub use memory_area::MemoryArea;
pub use operand::{Places, Refusal, Target};
