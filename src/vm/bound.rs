//! The response bound a run shows: the longest stretch without an interrupt point anywhere in
//! the cycle, the operating system's work included. A request whose level could run is
//! serviced within it; one that waited for a reason the manuals give (a level of the same or a
//! higher priority, `IA`, the STARTUP) is counted apart.
//!
//! In normal mode (block points) a stretch ends at each block call and block end (SINUMERIK
//! 840C PLC manual, 5.3.2: "the maximum response time ... is therefore, in the worst case, the
//! processing time of the longest block"); with operation points it is the longest single
//! operation. Both add the parts of the operating system's work a request may land in: the
//! PII read, the PIQ write, the operating-system time, and an S5-95F OB 13's end with its
//! interrupt output data cycle.

use crate::profile::InterruptPoints;

use super::{Cpu, Stretch, StretchKind};

/// The bound and what sets it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bound {
    pub ns: u64,
    pub cause: BoundCause,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundCause {
    /// A stretch between block changes, or of the operating system's work.
    Stretch(StretchKind),
    /// The longest single operation of the program (operation points).
    Operation { block: u16, pc: usize },
}

impl Cpu {
    /// The program's longest single operation: (block, pc, ns).
    pub fn longest_operation(&self) -> Option<(u16, usize, u64)> {
        self.program
            .blocks
            .iter()
            .enumerate()
            .flat_map(|(index, block)| {
                (0..block.code.len()).map(move |pc| (index as u16, pc, block.cost(pc)))
            })
            .max_by_key(|(_, _, ns)| *ns)
    }

    /// The bound on the response to a request whose level could run, measured on the run so
    /// far (with operation points, the longest operation of the program).
    pub fn response_bound(&self) -> Bound {
        let system = stretch_bound(self.longest_system);
        let program = match self.engine.config.points {
            InterruptPoints::Block => stretch_bound(self.longest_block),
            InterruptPoints::Operation => match self.longest_operation() {
                Some((block, pc, ns)) => Bound {
                    ns,
                    cause: BoundCause::Operation { block, pc },
                },
                None => system,
            },
        };
        if system.ns > program.ns {
            system
        } else {
            program
        }
    }
}

fn stretch_bound(stretch: Stretch) -> Bound {
    Bound {
        ns: stretch.ns,
        cause: BoundCause::Stretch(stretch.kind),
    }
}
