//! `[[check]]`: operands verified during the run, at the first cycle end at or after a moment
//! of simulated time, and reported with the time they were verified.

use crate::vm::Cpu;

use super::expect::{Expectation, Expected, Mismatch, value_mismatch};

/// One `[[check]]` of a scenario, resolved against the program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TimedCheck {
    pub at_ns: u64,
    /// `at` as the file wrote it.
    pub at: String,
    pub expectations: Vec<Expectation>,
}

/// What became of a check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckOutcome {
    pub at: String,
    /// When it was verified and in which cycle; `None` when the run ended (or went to STOP)
    /// before a cycle end at or after `at`.
    pub verified: Option<(u64, u64)>,
    pub operands: usize,
    pub mismatches: Vec<Mismatch>,
}

impl CheckOutcome {
    pub fn passed(&self) -> bool {
        self.verified.is_some() && self.mismatches.is_empty()
    }
}

/// Verifies the checks at the cycle ends, in time order.
#[derive(Debug, Default)]
pub struct Checker {
    checks: Vec<TimedCheck>,
    outcomes: Vec<CheckOutcome>,
}

impl Checker {
    pub fn new(mut checks: Vec<TimedCheck>) -> Self {
        checks.sort_by_key(|check| std::cmp::Reverse(check.at_ns));
        Checker {
            checks,
            outcomes: Vec::new(),
        }
    }

    /// At a cycle end: verifies every check whose moment has come.
    /// Drops the checks due by `clock_ns`: they belong to the run before a snapshot taken then.
    pub fn skip_until(&mut self, clock_ns: u64) {
        self.checks.retain(|check| check.at_ns > clock_ns);
    }

    pub fn observe(&mut self, cpu: &Cpu) {
        while self
            .checks
            .last()
            .is_some_and(|check| check.at_ns <= cpu.clock)
        {
            let check = self.checks.pop().expect("looked at above");
            let mismatches = check
                .expectations
                .iter()
                .filter_map(|expectation| {
                    let Expected::Value {
                        target,
                        wanted,
                        written,
                    } = &expectation.expected
                    else {
                        return None;
                    };
                    let (expected, actual) = value_mismatch(cpu, *target, *wanted, written)?;
                    Some(Mismatch {
                        name: expectation.name.clone(),
                        expected,
                        actual,
                    })
                })
                .collect();
            self.outcomes.push(CheckOutcome {
                at: check.at,
                verified: Some((cpu.clock, cpu.cycle)),
                operands: check.expectations.len(),
                mismatches,
            });
        }
    }

    /// Every check, those the run did not reach last.
    pub fn finish(mut self) -> Vec<CheckOutcome> {
        while let Some(check) = self.checks.pop() {
            self.outcomes.push(CheckOutcome {
                at: check.at,
                verified: None,
                operands: check.expectations.len(),
                mismatches: Vec::new(),
            });
        }
        self.outcomes
    }
}
