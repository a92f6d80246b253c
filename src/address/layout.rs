//! Where the image areas lie in the VM's flat image memory.

use crate::mnemonics::Area;
use crate::profile::Sizes;

/// The image areas: the process images of the inputs and outputs, and the flags (STEP 7's M).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageArea {
    Input,
    Output,
    Flag,
}

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

    /// The image area an image byte lies in, and its byte number there.
    pub fn image_area_of(self, offset: u16) -> Option<(ImageArea, u16)> {
        if offset < self.output_base() {
            Some((ImageArea::Input, offset))
        } else if offset < self.flag_base() {
            Some((ImageArea::Output, offset - self.output_base()))
        } else {
            offset
                .checked_sub(self.flag_base())
                .filter(|byte| *byte < self.flag_bytes)
                .map(|byte| (ImageArea::Flag, byte))
        }
    }
}
