//! The widths the program gives its addresses, read from its code: `T FW 0` makes flag bytes 0
//! and 1 one word, `T PW 4` output bytes 4 and 5, `T FD 4` bytes 4 to 7 one double word, `L IW 2` input bytes 2 and 3 one
//! word, `T DD 3` data words 3 and 4 one double word. `--state` shows each address in the width
//! the program used: the VM need not record anything while it runs. A STEP 7 program's data
//! blocks are byte-addressed: their widths come from its loads and transfers of DBW, DBD, DIW,
//! DID and from the parameters its FB calls copy into instance data blocks.

use std::collections::BTreeMap;

use crate::address::{ImageArea, Layout};
use crate::compiler::bytecode::DataPart;
use crate::compiler::{Op, Program};
use crate::step7::ast::AccessWidth;
use crate::step7::bytecode::{MemOp, Place, S7Code, Target as S7Target};

use super::flag_area;

/// The widths found, in bytes of the image and in words of the data blocks.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Widths {
    /// (area `"I"`, `"Q"` or `"F"`, byte) → bytes (2 or 4): the widest word or double word
    /// starting there.
    image: BTreeMap<(&'static str, u16), u16>,
    /// Data word number → words (2): the double words the program transfers (in any DB).
    data: BTreeMap<u16, u16>,
    /// STEP 7 data byte → bytes (2 or 4): the words and double words the program loads or
    /// transfers (in any DB).
    s7_data: BTreeMap<u16, u16>,
    /// The flag area's name, `F` or (STEP 7) `M`.
    flags: &'static str,
}

/// The ranges an area is shown in: (first address, width), in address order.
pub type Ranges = Vec<(u16, u16)>;

impl Widths {
    /// The widths of `program`: what it transfers to the outputs and flags, and what it loads
    /// from the inputs (a program reads its inputs and writes the rest).
    pub fn of(program: &Program) -> Widths {
        let layout = program.layout;
        let mut widths = Widths {
            flags: flag_area(program.s7.step7),
            ..Widths::default()
        };
        // The arena's plain code: every block's body and the FB bodies specialised for their
        // actual parameters (`T =OUT` with `OUT :FW 6` is a `T FW 6` there).
        for op in program.arena.plain.iter() {
            match *op {
                Op::TransferImageWord(at) => widths.image_width(layout, at, 2),
                Op::TransferImageDouble(at) => widths.image_width(layout, at, 4),
                // A transfer to an output module within the image's range updates the PIQ too.
                Op::TransferPeripheral {
                    width,
                    byte,
                    extended: false,
                } if width.bytes() > 1
                    && usize::from(byte) + width.bytes() <= usize::from(layout.image_bytes) =>
                {
                    widths.image_width(layout, layout.output_base() + byte, width.bytes() as u16)
                }
                Op::LoadImageWord(at) if at < layout.image_bytes => {
                    widths.image_width(layout, at, 2)
                }
                Op::LoadImageDouble(at) if at < layout.image_bytes => {
                    widths.image_width(layout, at, 4)
                }
                Op::TransferData(DataPart::Double, word) => {
                    widths.data.insert(word, 2);
                }
                Op::S7(S7Code::Mem {
                    op: MemOp::Load | MemOp::Transfer | MemOp::McrTransfer,
                    place,
                }) => widths.s7_place(program.s7.places[usize::from(place)], layout),
                _ => {}
            }
        }
        for call in &program.s7.fb_calls {
            // A multi-instance's data lie at its offset in the caller's (taken as one with an
            // instance DB of its own: nested ones' callers are known only at run time).
            let base = call.multi_instance.map_or(0, |offset| offset / 8);
            for copy in call.inputs.iter().chain(&call.outputs) {
                widths.s7_data_width(base + copy.byte, copy.width);
            }
        }
        widths
    }

    /// The width of a STEP 7 load or transfer: of the image, or of any data block.
    fn s7_place(&mut self, place: Place, layout: Layout) {
        match place.target {
            S7Target::Image { byte, .. } => match place.width {
                AccessWidth::Word => self.image_width(layout, byte, 2),
                AccessWidth::Double => self.image_width(layout, byte, 4),
                AccessWidth::Bit | AccessWidth::Byte => {}
            },
            // An FB's own variable: at its offset in an instance DB of its own (a
            // multi-instance's lies further on, see the FB calls below).
            S7Target::Data { byte, .. }
            | S7Target::NumberedData { byte, .. }
            | S7Target::Instance { byte, .. } => self.s7_data_width(byte, place.width),
            _ => {}
        }
    }

    fn s7_data_width(&mut self, byte: u32, width: AccessWidth) {
        let bytes = match width {
            AccessWidth::Word => 2,
            AccessWidth::Double => 4,
            AccessWidth::Bit | AccessWidth::Byte => return,
        };
        let Ok(byte) = u16::try_from(byte) else {
            return;
        };
        let widest = self.s7_data.entry(byte).or_insert(bytes);
        *widest = (*widest).max(bytes);
    }

    fn image_width(&mut self, layout: Layout, offset: u16, bytes: u16) {
        let Some(at) = area_byte(layout, offset, self.flags) else {
            return;
        };
        let widest = self.image.entry(at).or_insert(bytes);
        *widest = (*widest).max(bytes);
    }

    /// How to show the non-zero bytes `bytes` of `area` (`"I"`, `"Q"`, `"F"`, `"M"`): each in the
    /// word or double word the program used it in, else alone.
    pub fn image_ranges(&self, area: &'static str, bytes: impl Iterator<Item = u16>) -> Ranges {
        ranges(bytes, 4, |at| self.image.get(&(area, at)).copied())
    }

    /// How to show the non-zero data words `words`: double words where the program
    /// transferred one, else words.
    pub fn data_ranges(&self, words: impl Iterator<Item = u16>) -> Ranges {
        ranges(words, 2, |at| self.data.get(&at).copied())
    }

    /// How to show the non-zero bytes of a STEP 7 data block: words and double words where the
    /// program used them, else bytes.
    pub fn s7_data_ranges(&self, bytes: impl Iterator<Item = u16>) -> Ranges {
        ranges(bytes, 4, |at| self.s7_data.get(&at).copied())
    }
}

/// The area and byte number of an image offset; `flags` names the flag area.
fn area_byte(layout: Layout, offset: u16, flags: &'static str) -> Option<(&'static str, u16)> {
    let (area, byte) = layout.image_area_of(offset)?;
    let name = match area {
        ImageArea::Input => "I",
        ImageArea::Output => "Q",
        ImageArea::Flag => flags,
    };
    Some((name, byte))
}

/// Covers each address of `used` (ascending) once: with the earliest range that starts at most
/// `widest - 1` before it, reaches it and begins after what is already shown; else alone. A
/// range overlapping one already shown is not used (`T FW 0` and `T FW 1`: FW 0, then byte 2).
fn ranges(
    used: impl Iterator<Item = u16>,
    widest: u16,
    width_at: impl Fn(u16) -> Option<u16>,
) -> Ranges {
    let mut shown: Ranges = Vec::new();
    let mut next_free: u32 = 0;
    for at in used {
        if u32::from(at) < next_free {
            continue;
        }
        let earliest = at.saturating_sub(widest - 1).max(next_free as u16);
        let range = (earliest..=at)
            .find_map(|start| {
                let width = width_at(start)?;
                (u32::from(start) + u32::from(width) > u32::from(at)).then_some((start, width))
            })
            .unwrap_or((at, 1));
        next_free = u32::from(range.0) + u32::from(range.1);
        shown.push(range);
    }
    shown
}

#[cfg(test)]
mod tests {
    use super::*;

    fn widths(pairs: &[(u16, u16)]) -> impl Fn(u16) -> Option<u16> + '_ {
        |at| {
            pairs
                .iter()
                .find(|(start, _)| *start == at)
                .map(|(_, w)| *w)
        }
    }

    #[test]
    fn a_word_covers_both_bytes_even_when_its_high_byte_is_zero() {
        assert_eq!(
            ranges([1, 5].into_iter(), 4, widths(&[(0, 2)])),
            [(0, 2), (5, 1)]
        );
    }

    #[test]
    fn an_overlapping_word_gives_way_to_the_one_shown_first() {
        assert_eq!(
            ranges([0, 1, 2].into_iter(), 4, widths(&[(0, 2), (1, 2)])),
            [(0, 2), (2, 1)]
        );
    }

    #[test]
    fn a_double_word_covers_four_bytes() {
        assert_eq!(
            ranges([7, 9, 10].into_iter(), 4, widths(&[(6, 4)])),
            [(6, 4), (10, 1)]
        );
    }
}
