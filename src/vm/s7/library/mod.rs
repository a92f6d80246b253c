//! The library FCs a program calls without writing them ("System Software for S7-300/400
//! System and Standard Functions", IEC functions; the TI-S7 converting blocks FC 105 and
//! FC 106), run on the CPU's memory: the compiler checked every parameter and put their places
//! in the interface's order (see [`crate::step7::library`]). Each block gives whether it ran
//! without error, which becomes BR (the ENO of the manual's boxes).

mod date_time;
mod numbers;
mod strings;

use crate::step7::ast::AccessWidth;
use crate::step7::library::LibraryCall;
use crate::vm::Cpu;

use super::memory::{Fault, Located};

impl Cpu {
    /// `CALL` of library FC `call` of [`crate::step7::bytecode::S7Tables::library_calls`].
    pub(super) fn library_fc(&mut self, call: u16) -> Result<(), Fault> {
        let program = std::sync::Arc::clone(&self.program);
        let call = &program.s7.library_calls[usize::from(call)];
        for (place, bytes) in &call.constants {
            let (to, _) = self.locate_index(*place)?;
            self.write_bytes(to, bytes)?;
        }
        let db = self.db_at_call(call)?;
        let ok = match call.number {
            1 | 3 | 6..=9 | 12 | 14 | 18 | 23 | 28 | 33..=35 | 40 => self.date_time_fc(call)?,
            22 | 25 | 27 | 36 | 105 | 106 => self.number_fc(call)?,
            _ => self.string_fc(call)?,
        };
        // The block's end gives back the DB register it was called with, whatever the block
        // opened to reach its parameters.
        self.level.db = db;
        self.level.br = ok;
        Ok(())
    }

    /// The DB register as STEP 7's `CALL` leaves it for the block: an elementary actual of a
    /// data block (`DB2.DBW 0`) is passed as an area pointer with that DB opened, the last such
    /// one in the interface's order staying open; a STRING or DATE_AND_TIME actual carries its
    /// DB number in its DB pointer and opens nothing.
    fn db_at_call(&mut self, call: &LibraryCall) -> Result<u16, Fault> {
        let params = crate::step7::library::by_number(call.number).map_or(&[][..], |fc| fc.params);
        for (param, &place) in params.iter().zip(&call.params) {
            let before = self.level.db;
            self.locate_index(place)?;
            if param.ty.is_complex() {
                self.level.db = before;
            }
        }
        Ok(self.level.db)
    }

    /// Where parameter `index` of `call` is, and its width.
    fn arg(&mut self, call: &LibraryCall, index: usize) -> Result<(Located, AccessWidth), Fault> {
        self.locate_index(call.params[index])
    }

    /// The value of parameter `index`, as wide as its actual.
    fn read_arg(&mut self, call: &LibraryCall, index: usize) -> Result<u32, Fault> {
        let (at, width) = self.arg(call, index)?;
        self.fetch(at, width)
    }

    fn read_int(&mut self, call: &LibraryCall, index: usize) -> Result<i16, Fault> {
        Ok(self.read_arg(call, index)? as u16 as i16)
    }

    fn read_real(&mut self, call: &LibraryCall, index: usize) -> Result<f32, Fault> {
        Ok(f32::from_bits(self.read_arg(call, index)?))
    }

    /// Writes parameter `index` with `value`, as wide as its actual.
    fn write_arg(&mut self, call: &LibraryCall, index: usize, value: u32) -> Result<(), Fault> {
        let (at, width) = self.arg(call, index)?;
        self.store(at, width, value)
    }
}
