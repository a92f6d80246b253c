//! The memory areas a network client reaches (`awl serve`'s S7comm and Modbus servers, and the
//! scenario's `[modbus]` map), in either dialect.

/// The memory areas a client reaches, in either dialect: STEP 5's F and STEP 7's M are both
/// [`Area::Flags`]; a STEP 5 data block is reached by byte offset, 2 × its data word number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MemoryArea {
    /// Read: the process image of the inputs (PII). Written: the input modules, which the
    /// program sees in the PII at the next cycle start.
    Inputs,
    /// Read: the process image of the outputs (PIQ), what the output modules were last sent.
    /// Written: the PIQ.
    Outputs,
    /// The flags (STEP 5's F, STEP 7's M).
    Flags,
    /// Data block n.
    DataBlock(u16),
    /// The timers: two bytes each, the time value in BCD with its time base (as `LC T`).
    /// `start` and `length` count timers, not bytes.
    Timers,
    /// The counters: two bytes each, the count in BCD (as `LC C`). `start` and `length` count
    /// counters, not bytes.
    Counters,
}
