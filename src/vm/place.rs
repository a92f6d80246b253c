//! Where the CPU was at a moment of the stretch that has just ended: the block and source line
//! (or the operating system's work) a request came in, for the trace. A request is noticed at
//! the first interrupt point after it, so it always lies in the last stretch.

use super::{Cpu, StretchKind};

/// The block and line, or the operating system's work, at a moment.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Place {
    pub block: Option<String>,
    pub line: Option<u32>,
    /// The PG listing's segment of the line, in a listing.
    pub segment: Option<u16>,
    pub during: Option<&'static str>,
}

impl Cpu {
    /// Where the CPU was at `at`, a moment of the last stretch.
    pub fn place_of(&self, at: u64) -> Place {
        let stretch = self.last_stretch;
        if at < stretch.start_ns || at > stretch.end_ns {
            return Place::default();
        }
        let block = |index: u16| Some(self.block_id(index).to_string());
        match stretch.kind {
            StretchKind::Block { block: index, .. } if index == super::IDLE => Place::default(),
            StretchKind::Block {
                block: index,
                end_pc,
            } => {
                let pc = self.pc_at(index, end_pc, stretch.start_ns, stretch.end_ns, at);
                Place {
                    block: block(index),
                    line: pc.map(|pc| self.line_of(index, pc)),
                    segment: pc.and_then(|pc| self.segment_of(index, pc)),
                    during: None,
                }
            }
            StretchKind::InterruptEnd { block: index } => Place {
                block: block(index),
                ..Place::default()
            },
            StretchKind::ProcessImageRead => during("process image read (PII)"),
            StretchKind::ProcessImageWrite => during("process image write (PIQ)"),
            StretchKind::OsTime => during("operating-system time"),
            StretchKind::MinCycleWait => during("wait for the minimum cycle time"),
        }
    }

    /// The op that ran at `at`, walking back over the op times from op `end_pc` (which ended
    /// at `end_ns`) towards `start_ns`. Known when the stretch ran straight through the block:
    /// the walk must not pass `start_ns` between two ops.
    fn pc_at(&self, block: u16, end_pc: u32, start_ns: u64, end_ns: u64, at: u64) -> Option<u32> {
        let code = self.program.blocks.get(usize::from(block))?;
        let mut t = end_ns;
        let mut found = None;
        for pc in (0..=end_pc as usize).rev() {
            if t <= start_ns || pc >= code.code.len() {
                break;
            }
            let begin = t
                .checked_sub(code.cost(pc))
                .filter(|begin| *begin >= start_ns)?;
            if found.is_none() && begin <= at {
                found = Some(pc);
            }
            t = begin;
        }
        found.map(|pc| pc as u32)
    }
}

fn during(what: &'static str) -> Place {
    Place {
        during: Some(what),
        ..Place::default()
    }
}
