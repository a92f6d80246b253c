//! The engine's state between two cycles as plain data, for a snapshot: the requests pending,
//! the counts, and what each family's rules keep (their
//! timed OBs' next calls, held hardware events). Between two cycles no interrupt OB runs, so
//! the active levels are empty and not saved.

use serde::{Deserialize, Serialize};

use super::{Engine, FamilyRules, ObStats, Request};

#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct EngineState {
    pub pending: Vec<Request>,
    pub next_id: u64,
    pub run_started_at: Option<u64>,
    /// The OBs SFC 39 DIS_IRT has disabled.
    pub disabled: Vec<u8>,
    /// The counts of every OB requested so far.
    pub stats: Vec<(u8, ObStats)>,
    pub rules: RulesState,
}

/// What a family's rules keep besides the generic engine.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "family", rename_all = "snake_case")]
pub enum RulesState {
    /// Nothing beyond the generic engine (SINUMERIK 840C).
    Plain,
    /// The next call of each time-controlled OB.
    S5 { next_calls: Vec<(u8, u64)> },
    /// OB 13's next call and the interrupt process images.
    S595f {
        next_call: u64,
        completed_at: u64,
        interrupt_pii: Vec<u8>,
        interrupt_piq: Vec<u8>,
    },
    /// Modules busy between identification and acknowledgement, the events they hold, and
    /// OB 35's next request.
    Speed7 {
        busy: Vec<(u16, u16)>,
        held: Vec<(Request, u16)>,
        ob35_next: u64,
    },
}

impl Engine {
    /// The engine's state between two cycles.
    pub fn saved(&self) -> EngineState {
        EngineState {
            pending: self.pending.clone(),
            next_id: self.next_id,
            run_started_at: self.run_started_at,
            disabled: self.disabled.obs(),
            stats: self
                .requested_obs()
                .map(|(ob, stats)| (ob, *stats))
                .collect(),
            rules: self.rules.rules().saved(),
        }
    }

    /// Takes up `state`, saved at `clock_ns`: the schedule's events up to then are past (a
    /// cycle boundary is an interrupt point, where the engine takes in every event due). The
    /// collections keep the capacity they were made with, so the run allocates no more than
    /// one that never stopped.
    pub fn restore(&mut self, state: &EngineState, clock_ns: u64) -> Result<(), &'static str> {
        self.next = self.schedule.partition_point(|item| item.at_ns <= clock_ns);
        self.pending.clear();
        self.pending.extend_from_slice(&state.pending);
        self.next_id = state.next_id;
        self.run_started_at = state.run_started_at;
        self.disabled = super::control::Disabled::of(&state.disabled);
        for (ob, stats) in &state.stats {
            self.stats[usize::from(*ob)] = *stats;
        }
        match &mut self.rules {
            FamilyRules::Taken => Ok(()),
            rules => rules.rules_mut().restore(&state.rules),
        }
    }
}
