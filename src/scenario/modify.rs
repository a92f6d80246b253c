//! `[[event]] set` on a STEP 7 data block operand: the write a PG's "modify variable" makes.
//! Like the PG's modify at the cycle control point, it happens between two cycles — at the first
//! cycle boundary at or after the event's moment — never inside one, so the program sees the new
//! value from the start of a cycle on. Input changes, by contrast, reach the input modules at
//! their exact moment (the process does not wait for the cycle).

use crate::vm::Cpu;

use super::operand::Target;

/// One data block write of a scenario.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DataWrite {
    pub at_ns: u64,
    pub target: Target,
    pub raw: u32,
}

/// Makes the data block writes of a run at the cycle boundaries.
#[derive(Debug, Default)]
pub struct Modifier {
    /// Latest first, so the next one is popped from the end.
    writes: Vec<DataWrite>,
}

impl Modifier {
    pub fn new(mut writes: Vec<DataWrite>) -> Self {
        writes.sort_by_key(|write| std::cmp::Reverse(write.at_ns));
        Modifier { writes }
    }

    /// Drops the writes due by `clock_ns`: a run continued from a snapshot taken then has made
    /// them.
    pub fn skip_until(&mut self, clock_ns: u64) {
        self.writes.retain(|write| write.at_ns > clock_ns);
    }

    /// At a cycle boundary: makes every write whose moment has come, in time order. A write to
    /// a data block the program no longer has (deleted at run time) is skipped.
    pub fn observe(&mut self, cpu: &mut Cpu) {
        while self
            .writes
            .last()
            .is_some_and(|write| write.at_ns <= cpu.clock)
        {
            let write = self.writes.pop().expect("looked at above");
            let _skipped_when_gone = write_s7_data(cpu, write.target, write.raw);
        }
    }
}

/// Writes `raw` into a STEP 7 data block operand (a bit: 0 or 1), or says why it cannot.
pub fn write_s7_data(cpu: &mut Cpu, target: Target, raw: u32) -> Result<(), String> {
    let Target::S7Data {
        db,
        byte,
        bit,
        bytes,
    } = target
    else {
        return Err("not a data block operand".into());
    };
    let data = cpu
        .s7_db_mut(db)
        .ok_or_else(|| format!("DB {db} is not loaded"))?;
    let start = usize::try_from(byte).unwrap_or(usize::MAX);
    let count = usize::from(bytes.max(1));
    let length = data.len();
    let slot = data
        .get_mut(start..start.saturating_add(count))
        .ok_or_else(|| format!("DB {db} has {length} bytes"))?;
    if bytes == 0 {
        let mask = 1u8 << bit;
        slot[0] = if raw & 1 != 0 {
            slot[0] | mask
        } else {
            slot[0] & !mask
        };
    } else {
        slot.copy_from_slice(&raw.to_be_bytes()[4 - count..]);
    }
    Ok(())
}
