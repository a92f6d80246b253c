//! The master control relay ("Statement List (STL) for S7-300 and S7-400 Programming",
//! Program Control Instructions, the MCR instructions): `MCR(` saves the RLO on the MCR stack
//! (8 entries deep), `)MCR` removes the last entry; the MCR is on while every entry is 1.
//! `MCRA` makes `=`, `S`, `R` on bits and `T` depend on it until `MCRD`: with the MCR off `=`
//! and `T` write 0, `S` and `R` leave their bit. More than 8 entries, or `)MCR` with none,
//! is the MCR stack fault (MCRF).
//!
//! The dependency belongs to the block that switched it on: a called block starts without
//! it, and the caller has its own back after the call. The MCR stack is the level's.
//!
//! Only a block with `MCRA` can have the dependency on, so only such a block is compiled
//! with the MCR-aware writes (and saves its dependency around its calls, and clears it at
//! its start); every other block runs as if there were no MCR.

/// The MCR stack's depth.
pub const DEPTH: u8 = 8;

/// The MCR of a processing level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Mcr {
    /// `MCRA` … `MCRD`: the writes depend on the MCR.
    pub active: bool,
    /// Entries on the MCR stack.
    pub depth: u8,
    /// The entries, the first in bit 0; bits at and above `depth` are 0.
    pub zones: u8,
    /// The dependency of each block with `MCRA` that is calling, the innermost in bit 0. The
    /// block stack holds at most the profile's nesting limit (16 per level on the S7 CPU),
    /// within these 32 bits.
    pub calls: u32,
}

/// What went wrong with the MCR stack.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StackFault {
    Overflow,
    Underflow,
}

impl Mcr {
    /// Whether a dependent write writes: the dependency is off, or every entry is 1.
    #[inline]
    pub fn writes(self) -> bool {
        !self.active || self.zones.count_ones() == u32::from(self.depth)
    }

    /// `MCR(` with the RLO `rlo`.
    pub fn open(&mut self, rlo: bool) -> Result<(), StackFault> {
        if self.depth == DEPTH {
            return Err(StackFault::Overflow);
        }
        self.zones |= u8::from(rlo) << self.depth;
        self.depth += 1;
        Ok(())
    }

    /// `)MCR`
    pub fn close(&mut self) -> Result<(), StackFault> {
        if self.depth == 0 {
            return Err(StackFault::Underflow);
        }
        self.depth -= 1;
        self.zones &= !(1 << self.depth);
        Ok(())
    }

    /// Before a call from a block with `MCRA`: its dependency saved, none in the callee.
    pub fn call(&mut self) {
        self.calls = self.calls << 1 | u32::from(self.active);
        self.active = false;
    }

    /// After that call: the caller's dependency back.
    pub fn called(&mut self) {
        self.active = self.calls & 1 != 0;
        self.calls >>= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mcr_is_on_while_every_entry_is_one() {
        let mut mcr = Mcr {
            active: true,
            ..Mcr::default()
        };
        assert!(mcr.writes(), "an empty stack: on");
        mcr.open(true).unwrap();
        assert!(mcr.writes());
        mcr.open(false).unwrap();
        assert!(!mcr.writes());
        mcr.open(true).unwrap();
        assert!(!mcr.writes(), "an inner 1 does not lift an outer 0");
        mcr.close().unwrap();
        mcr.close().unwrap();
        assert!(mcr.writes());
        mcr.active = false;
        mcr.open(false).unwrap();
        assert!(mcr.writes(), "without MCRA the writes do not depend on it");
    }

    #[test]
    fn eight_entries_and_no_more() {
        let mut mcr = Mcr::default();
        for _ in 0..DEPTH {
            mcr.open(true).unwrap();
        }
        assert_eq!(mcr.open(true), Err(StackFault::Overflow));
        for _ in 0..DEPTH {
            mcr.close().unwrap();
        }
        assert_eq!(mcr.close(), Err(StackFault::Underflow));
        assert_eq!(mcr, Mcr::default());
    }

    #[test]
    fn a_call_saves_the_dependency_and_clears_it() {
        let mut mcr = Mcr {
            active: true,
            ..Mcr::default()
        };
        mcr.call();
        assert!(!mcr.active);
        mcr.call();
        mcr.active = true;
        mcr.called();
        assert!(!mcr.active);
        mcr.called();
        assert!(mcr.active);
        assert_eq!(mcr.calls, 0);
    }
}
