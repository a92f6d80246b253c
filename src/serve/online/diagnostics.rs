//! The diagnostic buffer, as a CPU keeps one for the PG ("Module Information", "Diagnostic
//! Buffer"): the last entries, newest first — STOPs with their cause, mode changes, interrupt
//! requests lost or serviced late, forces set and cleared, modifies.

use std::collections::VecDeque;

use crate::serve::request::DiagnosticEntry;
use crate::vm::Cpu;
use crate::vm::interrupts::{ObStats, Wait};

/// How many entries the buffer keeps.
pub const ENTRIES: usize = 100;

#[derive(Debug, Default)]
pub struct Diagnostics {
    /// Newest first.
    entries: VecDeque<DiagnosticEntry>,
    /// Each interrupt OB's counts when they were last looked at.
    seen: Vec<(u8, ObStats)>,
}

impl Diagnostics {
    /// Adds an entry at the CPU's time and cycle; the oldest goes when the buffer is full.
    pub fn record(&mut self, cpu: &Cpu, kind: &'static str, text: String) {
        if self.entries.len() == ENTRIES {
            self.entries.pop_back();
        }
        self.entries.push_front(DiagnosticEntry {
            time_ms: cpu.clock as f64 / 1e6,
            cycle: cpu.cycle,
            kind,
            text,
        });
    }

    /// The entries, newest first.
    pub fn entries(&self) -> Vec<DiagnosticEntry> {
        self.entries.iter().cloned().collect()
    }

    /// Enters the interrupt requests lost, or serviced late, since the last look: the engine
    /// counts them without a trace, so they are looked for now and then rather than as they
    /// happen.
    pub fn look_at_interrupts(&mut self, cpu: &Cpu) {
        for entry in cpu.profile.interrupt_obs {
            let now = cpu.engine.stats(entry.ob);
            let before = match self.seen.iter_mut().find(|(ob, _)| *ob == entry.ob) {
                Some((_, before)) => std::mem::replace(before, now),
                None => {
                    self.seen.push((entry.ob, now));
                    ObStats::default()
                }
            };
            let lost = now.lost - before.lost;
            if lost > 0 {
                let text = format!(
                    "OB {}: {} lost (the OB's last request was still pending or running)",
                    entry.ob,
                    crate::diagnostics::plural(lost, "request")
                );
                self.record(cpu, "interrupt_lost", text);
            }
            for (index, wait) in Wait::ALL.iter().enumerate() {
                let late = now.waited[index] - before.waited[index];
                if late > 0 {
                    let text = format!(
                        "OB {}: {} serviced late: {}",
                        entry.ob,
                        crate::diagnostics::plural(late, "request"),
                        wait.explanation()
                    );
                    self.record(cpu, "interrupt_late", text);
                }
            }
        }
    }
}
