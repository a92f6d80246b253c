//! Observers of single operations: program status (`awl status`) and the debugger. With a
//! probe set the CPU runs the stepping variant of the execution loop, which hands the probe
//! every operation before and after it runs; without one the loop is the plain one, so
//! observation costs nothing when it is off.

use crate::compiler::Op;

use super::Cpu;
use super::stop::Stop;

/// Whether the run goes on after a probe looked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    Go,
    /// End the run here; it reports as halted, not as a STOP.
    Halt,
}

pub trait Probe {
    /// Before the op at `cpu.level.pc` of `cpu.level.block` runs; the registers are in `cpu`.
    /// Simulated time stands still while this runs.
    fn before(&mut self, cpu: &mut Cpu) -> Flow;

    /// After op `pc` of `block` ran as `op` (a formal operand or a `DO` resolved). A block
    /// call is seen before the callee's frame is pushed and a block end before the caller's
    /// frame is popped, so `cpu.frames` is as it was while `block` ran.
    fn after(&mut self, cpu: &Cpu, block: u16, pc: u32, op: Op) -> Flow;

    /// The engine took in an interrupt request for `ob` that was made at `at_ns`.
    fn requested(&mut self, _cpu: &Cpu, _ob: u8, _at_ns: u64) {}

    /// The engine starts servicing `ob`: its first op comes next.
    fn serviced(&mut self, _cpu: &Cpu, _ob: u8) {}

    /// The CPU is about to go to STOP for `stop` (still in its mode, its registers and block
    /// stack as the fault left them): the debugger's `stop` exception filter pauses here.
    fn stopping(&mut self, _cpu: &mut Cpu, _stop: &Stop) {}

    /// The probe has seen what it looked for and leaves the CPU: the next stretch of the run
    /// takes the plain loop again (the online page's program status).
    fn done(&self) -> bool {
        false
    }
}

impl Cpu {
    /// Lends the probe the CPU (it is taken out meanwhile, so probes do not nest).
    pub(super) fn with_probe<T>(
        &mut self,
        idle: T,
        look: impl FnOnce(&mut dyn Probe, &mut Cpu) -> T,
    ) -> T {
        match self.probe.take() {
            Some(mut probe) => {
                let result = look(probe.as_mut(), self);
                if !probe.done() {
                    self.probe = Some(probe);
                }
                result
            }
            None => idle,
        }
    }
}
