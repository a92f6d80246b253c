//! Interrupts raised by input changes (a scenario's `[[interrupt_input]]`): an input bit tied to
//! an interrupt raises it on its configured edge, whatever changed the input (a scenario's `set`,
//! a network client's write to the inputs).
//!
//! - S5 CPUs: the interrupt inputs request their process interrupt OB on an edge (S5-115U
//!   Manual, 9.3 Interrupt processing with the 434-7 digital input module: each input enabled
//!   for a rising or a falling edge; S5-100U Manual, 10 Interrupt Processing: OB 2 from the
//!   interrupt-capable bus unit's input modules; S5-95F Manual, 12.2 and 12.3: OB 2 on a falling
//!   edge at I 59.0 to I 59.3, OB 3 on a falling, a rising or either edge; CPU 928B Programming
//!   Guide, 4, process interrupts edge-triggered).
//! - VIPA SPEED7: a digital input module's channel raises a hardware interrupt on its edge, and
//!   the event stays active while the input keeps the edge's level (VIPA SPEED7 operation list,
//!   "OB 40, OB 41 - HW_INTx - Hardware Interrupt"), so it ends when the input changes back.
//!
//! The check runs only when inputs change, against the table the run was set up with: the VM's
//! loop never sees it.

use super::super::stop::Stop;
use super::{Cpu, HardwareSource, InputChange, InputTarget};

/// Which change of an input raises its interrupt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edge {
    /// 0 → 1.
    Rising,
    /// 1 → 0.
    Falling,
    /// Either.
    Both,
}

impl Edge {
    /// Whether a change to `level` is this edge.
    fn raises_on(self, level: bool) -> bool {
        match self {
            Edge::Rising => level,
            Edge::Falling => !level,
            Edge::Both => true,
        }
    }
}

/// What an input's edge raises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Raises {
    /// S5: an interrupt request for the OB.
    Ob(u8),
    /// SPEED7: a hardware interrupt of a module's channel.
    Hardware { module: u16, channel: u16 },
}

/// An input bit of the process input modules tied to an interrupt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InterruptInput {
    pub byte: u16,
    pub bit: u8,
    pub edge: Edge,
    pub raises: Raises,
}

impl InterruptInput {
    /// Whether `change` writes this input's byte.
    pub fn touched_by(&self, change: &InputChange) -> bool {
        let first = change.byte;
        let count = u16::from(change.bytes.max(1));
        change.target == InputTarget::Process
            && (first..first.saturating_add(count)).contains(&self.byte)
    }

    /// A hardware interrupt's event: active until the input changes again.
    fn raises_hardware(&self) -> bool {
        matches!(self.raises, Raises::Hardware { .. })
    }
}

/// The end of a hardware event an input raised: not known when it comes, it is the moment the
/// input changes back.
pub const WHILE_INPUT_HOLDS: u64 = u64::MAX;

/// How many hardware events the input changes of `changes` can raise at most, to give the
/// engine room for them before the run.
pub fn hardware_events<'a>(
    inputs: &[InterruptInput],
    changes: impl Iterator<Item = &'a InputChange>,
) -> usize {
    changes
        .map(|change| {
            inputs
                .iter()
                .filter(|input| input.raises_hardware() && input.touched_by(change))
                .count()
        })
        .sum()
}

/// The bytes `change` writes, as they were before it: at most 4.
#[derive(Debug, Clone, Copy)]
pub(super) struct Before {
    bytes: [u8; 4],
}

impl Cpu {
    /// The input bytes `change` will write, kept to compare after it (a copy on the stack).
    pub(super) fn inputs_before(&self, change: &InputChange) -> Before {
        let mut bytes = [0; 4];
        if change.target == InputTarget::Process {
            let at = usize::from(change.byte);
            let count = usize::from(change.bytes.max(1)).min(4);
            if let Some(old) = self.inputs.get(at..at + count) {
                bytes[..count].copy_from_slice(old);
            }
        }
        Before { bytes }
    }

    /// Raises what the changed interrupt inputs raise at `at`: `before` holds the bytes
    /// `change` wrote as they were.
    pub(super) fn raise_on_edges(
        &mut self,
        change: &InputChange,
        before: Before,
        at: u64,
    ) -> Result<(), Stop> {
        for index in 0..self.engine.config.interrupt_inputs.len() {
            let input = self.engine.config.interrupt_inputs[index];
            if !input.touched_by(change) {
                continue;
            }
            let offset = usize::from(input.byte - change.byte);
            let old = before.bytes[offset] >> input.bit & 1 != 0;
            let level = self.inputs[usize::from(input.byte)] >> input.bit & 1 != 0;
            if old == level {
                continue;
            }
            let raise = input.edge.raises_on(level);
            match input.raises {
                Raises::Ob(ob) if raise => {
                    self.request(ob, at, None);
                }
                Raises::Ob(_) => {}
                Raises::Hardware { module, channel } => {
                    // The input left the level of its last event: that event is over.
                    self.with_rules(|rules, cpu| rules.hardware_ended(cpu, module, channel, at));
                    if raise {
                        let source = HardwareSource {
                            module,
                            channel,
                            active_until: WHILE_INPUT_HOLDS,
                        };
                        self.with_rules(|rules, cpu| rules.hardware_event(cpu, at, source))?;
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn change(byte: u16, bytes: u8) -> InputChange {
        InputChange {
            target: InputTarget::Process,
            byte,
            bit: 0,
            bytes,
            value: 0,
        }
    }

    #[test]
    fn a_change_touches_the_inputs_of_the_bytes_it_writes() {
        let input = InterruptInput {
            byte: 9,
            bit: 3,
            edge: Edge::Rising,
            raises: Raises::Ob(2),
        };
        assert!(input.touched_by(&change(9, 0)));
        assert!(input.touched_by(&change(8, 2)));
        assert!(!input.touched_by(&change(8, 1)));
        assert!(!input.touched_by(&change(10, 4)));
        let extended = InputChange {
            target: InputTarget::Extended,
            ..change(9, 1)
        };
        assert!(!input.touched_by(&extended));
    }

    #[test]
    fn each_edge_raises_on_its_level() {
        assert!(Edge::Rising.raises_on(true) && !Edge::Rising.raises_on(false));
        assert!(Edge::Falling.raises_on(false) && !Edge::Falling.raises_on(true));
        assert!(Edge::Both.raises_on(true) && Edge::Both.raises_on(false));
    }
}
