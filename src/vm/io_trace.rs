//! Module changes in the trace: a scenario's input change reaching the input modules, and the
//! output modules changing (PIQ write, direct output, an interrupt PIQ). Bits of the process
//! image range are named as bits (`I 1.0`, `Q 4.0`), other bytes as peripheral bytes
//! (`PY 128`, `OY 2`).

use super::Cpu;
use crate::trace::Event;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Modules {
    Inputs,
    Outputs,
}

impl Cpu {
    fn modules(&self, which: Modules, extended: bool) -> &[u8] {
        match (which, extended) {
            (Modules::Inputs, false) => &self.inputs,
            (Modules::Inputs, true) => &self.extended_inputs,
            (Modules::Outputs, false) => &self.outputs,
            (Modules::Outputs, true) => &self.extended_outputs,
        }
    }

    /// A copy of the modules' bytes `at..at + count`, taken before a write when a trace is
    /// written (`None` otherwise: no copy, no allocation).
    pub(super) fn modules_before(
        &self,
        which: Modules,
        extended: bool,
        at: usize,
        count: usize,
    ) -> Option<Vec<u8>> {
        self.tracer
            .enabled
            .then(|| self.modules(which, extended)[at..at + count].to_vec())
    }

    /// Traces what changed in the modules since `before` was taken at `at`.
    #[cold]
    pub(super) fn trace_module_changes(
        &mut self,
        which: Modules,
        extended: bool,
        at: usize,
        before: &[u8],
    ) {
        let image_bytes = usize::from(self.program.layout.image_bytes);
        let mut events = Vec::new();
        let now = &self.modules(which, extended)[at..at + before.len()];
        for (offset, (&old, &new)) in before.iter().zip(now).enumerate() {
            let byte = at + offset;
            if old == new {
                continue;
            }
            if extended || byte >= image_bytes {
                let area = if extended { "OY" } else { "PY" };
                events.push((format!("{area} {byte}"), u32::from(new)));
                continue;
            }
            let area = match which {
                Modules::Inputs => "I",
                Modules::Outputs => "Q",
            };
            for bit in (0..8).filter(|bit| (old ^ new) >> bit & 1 != 0) {
                events.push((format!("{area} {byte}.{bit}"), u32::from(new >> bit & 1)));
            }
        }
        for (operand, value) in events {
            let event = match which {
                Modules::Inputs => Event::Input { operand, value },
                Modules::Outputs => Event::Output { operand, value },
            };
            self.tracer.emit(self.clock, event);
        }
    }
}
