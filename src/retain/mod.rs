//! Memory kept outside the process: retentive memory written crash-safe to a file and loaded at
//! the next start, as a CPU's battery or retentive flash keeps it through a power cycle, and
//! snapshots of the whole CPU to continue from.
//!
//! Both are JSON files in one envelope ([`file`]): a format name, a version, a checksum of the
//! body, and the body. What they hold is the VM's plain state ([`crate::vm::saved`]).

pub mod error;
pub mod file;
pub mod keeper;
pub mod memory;
pub mod snapshot;

pub use error::RetainError;
pub use keeper::{Keeper, RetainOptions};
pub use snapshot::Snapshot;
