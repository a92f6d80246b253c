//! The STEP 7 (S7-300/S7-400) operations on the accumulators and the status word, as small
//! pure functions the execution loop calls ("Statement List (STL) for S7-300 and S7-400
//! Programming" is the reference; `grammar/README.md`, "STEP 7 operations", lists the
//! choices where it leaves one).
//!
//! - [`bit_logic`]: `O` alone, `SET CLR NOT SAVE`, the end of a string by `= S R`, `FP FN`;
//!   the scans `A AN O ON X XN` and the nesting stack are in [`super::status`].
//! - [`integer`]: `+I -I *I /I +D -D *D /D MOD NEGI NEGD INVI INVD`, `+ constant`.
//! - [`real`]: `+R -R *R /R`, `SQR SQRT EXP LN SIN COS TAN ASIN ACOS ATAN`, `ABS NEGR`, and
//!   the status of a REAL result.
//! - [`compare`]: `==I … <=I`, `==D … <=D`, `==R … <=R`.
//! - [`convert`]: `ITD ITB BTI BTD DTB DTR RND RND+ RND- TRUNC CAW CAD`.
//! - [`word_logic`]: `AW OW XOW AD OD XOD`.
//! - [`shift`]: `SSI SSD SLW SRW SLD SRD RLD RRD RLDA RRDA`.
//! - [`accu`]: `TAK PUSH POP ENT LEAVE INC DEC`, and the move of ACCU 3/4 after arithmetic.
//! - [`jump`]: whether each conditional jump jumps and what it does to the status; `LOOP`; the
//!   status conditions `==0 <>0 >0 <0 >=0 <=0 UO OV OS BR` as bit operands.
//! - [`mcr`]: the master control relay, `MCRA MCRD MCR( )MCR`.
//! - `complex`: parameters of ARRAY, STRUCT, UDT, STRING and DATE_AND_TIME types (copies,
//!   DB pointers).
//! - [`memory`]: where an operand is (L stack, DB/DI, parameters, indirect addresses);
//!   [`exec`]: the out-of-line executor the loop calls for [`crate::step7::bytecode::S7Code`].
//!
//! The status word itself (`L STW`/`T STW` as [`Status::to_word`] and [`Status::from_word`],
//! `__STWRST` as `Status::default()`) is [`super::status::Status`]; BR is beside it,
//! [`super::LevelState::br`].
//!
//! [`Status::to_word`]: super::status::Status::to_word
//! [`Status::from_word`]: super::status::Status::from_word

pub mod accu;
pub mod bit_logic;
mod block_move;
mod bridge;
mod clock_sfcs;
pub mod compare;
mod complex;
pub mod convert;
pub mod exec;
pub mod integer;
mod library;
pub mod mcr;
pub mod memory;
pub mod shift;
mod system_blocks;
pub mod word_logic;

pub use crate::rules::{jump, real};

use crate::compiler::Program;
use crate::vm::Cpu;

/// The STEP 7 data blocks at the start, by slot (see [`S7Tables::db_numbers`]): `None` for a
/// data block the program names but does not define.
///
/// [`S7Tables::db_numbers`]: crate::step7::bytecode::S7Tables::db_numbers
pub fn initial_data(program: &Program) -> Vec<Option<Vec<u8>>> {
    let defined: std::collections::HashMap<u16, &Vec<u8>> = program
        .s7
        .data_blocks
        .iter()
        .map(|(number, bytes)| (*number, bytes))
        .collect();
    program
        .s7
        .db_numbers
        .iter()
        .map(|number| defined.get(number).map(|bytes| (*bytes).clone()))
        .collect()
}

impl Cpu {
    /// STEP 7 data block `number`'s bytes, when the program has it.
    pub fn s7_db(&self, number: u16) -> Option<&[u8]> {
        let slot = self.program.s7.db_slot(number)?;
        self.s7_data.get(usize::from(slot))?.as_deref()
    }

    /// STEP 7 data block `number`'s bytes to write, when the program has it.
    pub fn s7_db_mut(&mut self, number: u16) -> Option<&mut [u8]> {
        let slot = self.program.s7.db_slot(number)?;
        self.s7_data.get_mut(usize::from(slot))?.as_deref_mut()
    }
}
