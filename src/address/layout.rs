//! Where the image areas lie in the VM's flat image memory.

use crate::mnemonics::Area;
use crate::profile::Sizes;

/// Where the areas lie in the VM's flat image memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    pub image_bytes: u16,
    pub flag_bytes: u16,
}

impl Layout {
    pub fn new(sizes: &Sizes) -> Self {
        Layout {
            image_bytes: sizes.image_bytes,
            flag_bytes: sizes.flag_bytes,
        }
    }

    pub fn input_base(self) -> u16 {
        0
    }

    pub fn output_base(self) -> u16 {
        self.image_bytes
    }

    pub fn flag_base(self) -> u16 {
        2 * self.image_bytes
    }

    /// The image byte of an address in I, Q or F (bit, byte, word or double word).
    pub fn image_byte(self, area: Area, index: u16) -> Option<u16> {
        let base = match area {
            Area::Input | Area::InputByte | Area::InputWord => self.input_base(),
            Area::Output | Area::OutputByte | Area::OutputWord => self.output_base(),
            Area::Flag | Area::FlagByte | Area::FlagWord | Area::FlagDouble => self.flag_base(),
            _ => return None,
        };
        Some(base + index)
    }
}
