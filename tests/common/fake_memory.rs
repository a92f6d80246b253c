//! The memory of a fake CPU that the server tests put behind `awl serve`'s protocols: plain
//! byte arrays per area answering the items of a request, as the station answers them from
//! the CPU. A timer or counter is two bytes.

use std::collections::HashMap;

use awl::serve::request::{Area, Item, ItemError, ItemResult, Range};

pub struct FakeMemory {
    areas: HashMap<Area, Vec<u8>>,
    read_only: bool,
}

impl FakeMemory {
    /// The areas it has; a data block it lacks is `NoSuchBlock`, any other area `NotSupported`.
    pub fn new(areas: impl IntoIterator<Item = (Area, Vec<u8>)>, read_only: bool) -> Self {
        FakeMemory {
            areas: areas.into_iter().collect(),
            read_only,
        }
    }

    /// An area's bytes, as the test looks at them.
    pub fn area(&self, area: Area) -> &[u8] {
        &self.areas[&area]
    }

    fn area_mut(&mut self, area: Area) -> Result<&mut Vec<u8>, ItemError> {
        self.areas.get_mut(&area).ok_or(match area {
            Area::DataBlock(_) => ItemError::NoSuchBlock,
            _ => ItemError::NotSupported,
        })
    }

    fn bytes(&mut self, range: Range) -> Result<&mut [u8], ItemError> {
        let scale = match range.area {
            Area::Timers | Area::Counters => 2,
            _ => 1,
        };
        let (start, length) = (range.start as usize * scale, range.length as usize * scale);
        self.area_mut(range.area)?
            .get_mut(start..start + length)
            .ok_or(ItemError::OutOfRange)
    }

    fn byte(&mut self, area: Area, byte: u32) -> Result<&mut u8, ItemError> {
        if matches!(area, Area::Timers | Area::Counters) {
            return Err(ItemError::NotSupported);
        }
        self.area_mut(area)?
            .get_mut(byte as usize)
            .ok_or(ItemError::OutOfRange)
    }

    /// One item of a request, refused for writing when the memory is read-only.
    pub fn serve(&mut self, item: Item) -> ItemResult {
        let writing = matches!(item, Item::Write { .. } | Item::WriteBit { .. });
        if writing && self.read_only {
            return Err(ItemError::ReadOnly);
        }
        match item {
            Item::Read(range) => Ok(self.bytes(range)?.to_vec()),
            Item::Write { range, bytes } => {
                self.bytes(range)?.copy_from_slice(&bytes);
                Ok(Vec::new())
            }
            Item::ReadBit { area, byte, bit } => Ok(vec![(*self.byte(area, byte)? >> bit) & 1]),
            Item::WriteBit {
                area,
                byte,
                bit,
                value,
            } => {
                let byte = self.byte(area, byte)?;
                *byte = (*byte & !(1 << bit)) | (u8::from(value) << bit);
                Ok(Vec::new())
            }
        }
    }
}
