//! The machine's rules, one home for both dialects and both sides of the bytecode: the status
//! bits and how operations combine into the RLO ([`status`]), fixed-point arithmetic,
//! comparisons and word logic with their condition codes ([`arith`]), STEP 7's jump and status
//! conditions ([`jump`]), REAL arithmetic ([`real`]) and the BCD digits ([`bcd`]). The VM executes them; the compiler and
//! the STEP 7 front end name and fold with them. They sit below all three so that none of them
//! reaches up into another.

pub mod arith;
pub mod bcd;
pub mod effects;
pub mod jump;
pub mod real;
pub mod status;
