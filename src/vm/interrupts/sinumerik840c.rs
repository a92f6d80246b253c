//! The SINUMERIK 840C PLC (CPU 928B): normal and special mode.
//!
//! SINUMERIK 840C PLC manual, 5.3.1: in normal mode the cyclic program is interrupted only at
//! block changes, and "organization blocks OB 2 and OB 5 cannot be called up in normal mode";
//! even when they exist "they are nevertheless not processed". Special mode processes them.
//! The block-change interrupt points and the priorities are the generic engine's.

use super::{EngineConfig, Rules};

#[derive(Debug, Default)]
pub struct Sinumerik840c {
    special_mode: bool,
}

/// Why normal mode does not process OB 2 and OB 5.
pub const NORMAL_MODE: &str =
    "not processed in normal mode, even when it exists (SINUMERIK 840C PLC manual, 5.3.1)";

impl Sinumerik840c {
    pub fn new(config: &EngineConfig) -> Self {
        Sinumerik840c {
            special_mode: config.special_mode,
        }
    }
}

/// The OBs normal mode leaves out.
pub fn normal_mode_skips(ob: u8) -> bool {
    ob == 2 || ob == 5
}

impl Rules for Sinumerik840c {
    fn ignores(&self, ob: u8) -> Option<&'static str> {
        (!self.special_mode && normal_mode_skips(ob)).then_some(NORMAL_MODE)
    }
}
